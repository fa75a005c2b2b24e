"""References for the operations' tests: exact similarities and D of rational polygons, by the definitions.

Nothing here uses mrm.ops: the rings of a shapely polygon are read into Fractions, scaled or rotated with
plain Fraction arithmetic, and discretized with the kernels of tests/oracles/discretize_reference.py
(D(E) = { p : E ∩ K(p) ≠ ∅ }, Liang–Barsky with (v0, v1, v2) triples, a ray test from p + τ).
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction
from typing import Any

import numpy as np
import shapely
from hypothesis import strategies as st

from mrm.core.grids import PixelSet
from mrm.core.models import Model
from mrm.geometry.discretize import discretize
from tests.oracles.discretize_reference import inside_tau, kernel_box, segment_meets
from tests.oracles.geometry_strategies import star_polygons

MODELS = Model.names()
COVERS = ("standard", "supercover")

Q = Fraction
Pt = tuple[Fraction, Fraction]
Rings = list[list[Pt]]  # one polygon: its closed rings (first point repeated at the end)


def polygons_of(geom: Any) -> list[Rings]:
    """The polygons of a shapely Polygon / MultiPolygon as closed rings of exact Fractions."""
    out: list[Rings] = []
    for part in shapely.get_parts(geom):
        if part.is_empty:
            continue
        rings = [part.exterior, *part.interiors]
        out.append([[(Q(float(x)), Q(float(y))) for x, y in r.coords] for r in rings])
    return out


def scaled(polys: list[Rings], alpha: Fraction, center: Pt | None = None) -> list[Rings]:
    """Sc_α about ``center`` (the origin by default): v ↦ C + α (v − C), exactly."""
    cx, cy = center if center is not None else (Q(0), Q(0))
    return [[[(cx + alpha * (x - cx), cy + alpha * (y - cy)) for x, y in r] for r in p] for p in polys]


def rotated(polys: list[Rings], c: Fraction, s: Fraction, center: Pt) -> list[Rings]:
    """The linear map [[c, −s], [s, c]] about ``center``, exactly."""
    cx, cy = center
    return [
        [[(cx + c * (x - cx) - s * (y - cy), cy + s * (x - cx) + c * (y - cy)) for x, y in r] for r in p]
        for p in polys
    ]


def _closed_range(lo: Fraction, hi: Fraction) -> range:
    return range(math.ceil(lo - Q(1, 2)), math.floor(hi + Q(1, 2)) + 1)


def reference_discretize_rings(polys: list[Rings], model: str) -> PixelSet:
    """D(∪ polys) by the definitions of docs/design.md §2 (valid polygons with Fraction vertices)."""
    out: set[tuple[int, int]] = set()
    if not polys:
        return PixelSet.empty()
    for rings in polys:
        pxs = [v[0] for r in rings for v in r]
        pys = [v[1] for r in rings for v in r]
        cands = [(i, j) for i in _closed_range(min(pxs), max(pxs)) for j in _closed_range(min(pys), max(pys))]
        for a, b in (e for r in rings for e in itertools.pairwise(r)):
            if a == b or model == "gauss":
                continue
            for p in cands:
                if p in out:
                    continue
                # every kernel lies in the closed square, which the segment misses outside its box
                if not (
                    min(a[0], b[0]) - 1 <= p[0] <= max(a[0], b[0]) + 1
                    and min(a[1], b[1]) - 1 <= p[1] <= max(a[1], b[1]) + 1
                ):
                    continue
                if segment_meets(a, b, kernel_box(p, model)):
                    out.add(p)
        for p in cands:
            if p not in out and inside_tau(p, rings):
                out.add(p)
    return PixelSet.from_points(sorted(out)) if out else PixelSet.empty()


def as_mask_set(ps: PixelSet) -> set[tuple[int, int]]:
    """The pixels of a set as Python tuples."""
    return {(int(x), int(y)) for x, y in np.asarray(ps.points())}


# ---------------------------------------------------------------------------------------------- strategies
@st.composite
def pixel_sets(draw, max_side: int = 6) -> PixelSet:
    w = draw(st.integers(1, max_side))
    h = draw(st.integers(1, max_side))
    bits = draw(st.lists(st.booleans(), min_size=w * h, max_size=w * h))
    x0 = draw(st.integers(-4, 4))
    y0 = draw(st.integers(-4, 4))
    ps = PixelSet(np.array(bits, dtype=bool).reshape(h, w), (x0, y0))
    if ps.is_empty():
        ps = PixelSet.from_points([(x0, y0)])
    return ps


@st.composite
def objects(draw) -> PixelSet:
    """Small random pixel sets, or digitized random polygons (holes, slivers, ties included)."""
    if draw(st.booleans()):
        return draw(pixel_sets())
    poly = draw(star_polygons(max_vertices=6, max_radius=4.0))
    ps = discretize(poly, draw(st.sampled_from(MODELS)))
    return ps if not ps.is_empty() else PixelSet.from_points([(0, 0)])
