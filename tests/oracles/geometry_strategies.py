"""Hypothesis strategies for adversarial Euclidean geometry on the pixel grid.

Coordinates are snapped to a *lattice* chosen per example, because ties are what break discretizers:

    integer   vertices on pixel centres
    half      pixel sides and corners (edges along sides, diagonals through corners)
    quarter   a 2^-2 grid
    dyadic    a 2^-10 grid
    float     raw floats with full mantissas (the float filter path)
    near_tie  half-integers nudged by ±2^-30 or ±2^-44 (ties and near-ties, exact fallback path)
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import shapely
from hypothesis import assume
from hypothesis import strategies as st


def floats(lo: float, hi: float) -> Any:
    """Floats in [lo, hi] without the sub-2^-300 magnitudes that discretize refuses (they become 0)."""
    return st.floats(lo, hi).map(lambda v: v if abs(v) >= 2.0**-300 else 0.0)


LATTICES = ("integer", "half", "quarter", "dyadic", "float", "near_tie")
_NUDGES = (0.0, 0.0, 2.0**-30, -(2.0**-30), 2.0**-44, -(2.0**-44))


@st.composite
def snapper(draw: Any) -> Any:
    """A function v ↦ v snapped to a lattice drawn for this example."""
    lattice = draw(st.sampled_from(LATTICES))
    nudges = draw(st.lists(st.sampled_from(_NUDGES), min_size=16, max_size=16))
    counter = [0]

    def snap(v: float) -> float:
        if lattice == "integer":
            return float(round(v))
        if lattice == "half":
            return round(2 * v) / 2
        if lattice == "quarter":
            return round(4 * v) / 4
        if lattice == "dyadic":
            return round(v * 1024) / 1024
        if lattice == "float":
            # Below 2^-400 coordinates are refused (see mrm.geometry.discretize.exact.MIN_ABS_COORD).
            return v if abs(v) >= 2.0**-300 else 0.0
        counter[0] += 1
        return round(2 * v) / 2 + nudges[counter[0] % len(nudges)]

    return snap


def _star(
    snap: Any, cx: float, cy: float, angles: list[float], radii: list[float]
) -> list[tuple[float, float]]:
    return [
        (snap(cx + r * math.cos(a)), snap(cy + r * math.sin(a))) for a, r in zip(angles, radii, strict=True)
    ]


_angle = st.floats(0.0, 2 * math.pi, exclude_max=True, allow_nan=False)


@st.composite
def star_polygons(draw: Any, max_vertices: int = 8, max_radius: float = 6.0, holes: bool = True) -> Any:
    """A valid star-shaped polygon (sometimes with a star-shaped hole) on a random lattice."""
    snap = draw(snapper())
    n = draw(st.integers(3, max_vertices))
    cx = draw(floats(-3.0, 3.0))
    cy = draw(floats(-3.0, 3.0))
    scale = draw(floats(0.3, max_radius))
    angles = sorted(draw(st.lists(_angle, min_size=n, max_size=n, unique=True)))
    radii = [scale * r for r in draw(st.lists(st.floats(0.25, 1.0), min_size=n, max_size=n))]
    shell = _star(snap, cx, cy, angles, radii)
    interiors = []
    if holes and draw(st.booleans()) and draw(st.booleans()):
        m = draw(st.integers(3, 5))
        h_angles = sorted(draw(st.lists(_angle, min_size=m, max_size=m, unique=True)))
        h_radii = [0.2 * min(radii) * r for r in draw(st.lists(st.floats(0.3, 1.0), min_size=m, max_size=m))]
        interiors.append(_star(snap, cx, cy, h_angles, h_radii))
    poly = shapely.Polygon(shell, interiors)
    assume(poly.is_valid and poly.area > 0)
    return poly


@st.composite
def rectilinear_shapes(draw: Any, size: int = 10) -> Any:
    """A union of boxes with half-integer or integer corners: edges along pixel sides, often holes and
    several pieces (Polygon or MultiPolygon), exact because no new coordinate is constructed."""
    k = draw(st.integers(1, 5))
    step = draw(st.sampled_from([0.5, 1.0]))
    boxes = []
    for _ in range(k):
        x0 = draw(st.integers(-size, size)) * step
        y0 = draw(st.integers(-size, size)) * step
        w = draw(st.integers(1, 8)) * step
        h = draw(st.integers(1, 8)) * step
        boxes.append(shapely.box(x0, y0, x0 + w, y0 + h))
    shape = shapely.unary_union(boxes)
    assume(shape.is_valid and not shape.is_empty)
    return shape


@st.composite
def slivers(draw: Any) -> Any:
    """A triangle much thinner than a pixel, often through pixel corners or along a pixel side."""
    snap = draw(snapper())
    ax, ay = snap(draw(floats(-5, 5))), snap(draw(floats(-5, 5)))
    bx, by = snap(draw(floats(-5, 5))), snap(draw(floats(-5, 5)))
    assume((ax, ay) != (bx, by))
    t = draw(st.sampled_from([0.5, 0.25, 0.75]))
    width = draw(st.sampled_from([2.0**-3, 2.0**-12, 2.0**-30, 1e-9]))
    # The apex: a point of the segment pushed sideways by `width` along a grid direction.
    cx, cy = ax + t * (bx - ax), ay + t * (by - ay)
    dx, dy = draw(st.sampled_from([(width, 0.0), (0.0, width), (-width, 0.0), (0.0, -width), (width, width)]))
    poly = shapely.Polygon([(ax, ay), (bx, by), (cx + dx, cy + dy)])
    assume(poly.is_valid and poly.area > 0)
    return poly


@st.composite
def grazing_polygons(draw: Any) -> Any:
    """A triangle with full-mantissa float vertices whose edges pass within rounding error of pixel centres
    or corners (or exactly through them): float evaluation gets these wrong, exact evaluation must not."""
    half = draw(st.sampled_from([0.0, 0.5]))

    def grid_point() -> tuple[float, float]:
        return draw(st.integers(-6, 6)) + half, draw(st.integers(-6, 6)) + half

    ax, ay = draw(floats(-7, 7)), draw(floats(-7, 7))
    vertices = [(ax, ay)]
    for _ in range(2):
        px, py = vertices[-1]
        gx, gy = grid_point()
        t = draw(floats(1.0, 2.0))
        vertices.append((px + t * (gx - px), py + t * (gy - py)))
    poly = shapely.Polygon(vertices)
    assume(poly.is_valid and poly.area > 0)
    return poly


@st.composite
def moved(draw: Any, shapes: Any) -> Any:
    """A shape from ``shapes`` moved far away (huge coordinates) or shrunk to a speck near a grid corner."""
    g = draw(shapes)
    how = draw(st.sampled_from(["none", "far", "speck"]))
    if how == "far":
        off = draw(st.sampled_from([2.0**20, -(2.0**33), 2.0**40 + 0.5]))
        g = shapely.transform(g, lambda c: c + off)
    elif how == "speck":
        # 2^-20 keeps snapped coordinates exact after adding a corner anchor; 2^-60 only around 0.
        f, anchor = draw(st.sampled_from([(2.0**-20, 0.5), (2.0**-20, -0.5), (2.0**-60, 0.0)]))
        g = shapely.transform(g, lambda c: c * f + anchor)
    assume(g.is_valid and not g.is_empty)
    return g


def segments(lattice_points: bool = False) -> Any:
    """((ax, ay), (bx, by)) on a random lattice (or pixel centres when ``lattice_points``)."""

    @st.composite
    def build(draw: Any) -> Any:
        if lattice_points:
            a = (float(draw(st.integers(-8, 8))), float(draw(st.integers(-8, 8))))
            b = (float(draw(st.integers(-8, 8))), float(draw(st.integers(-8, 8))))
            return a, b
        snap = draw(snapper())
        c = [snap(draw(floats(-6, 6))) for _ in range(4)]
        if draw(st.booleans()):  # axis-aligned, often on a pixel side
            if draw(st.booleans()):
                c[3] = c[1]
            else:
                c[2] = c[0]
        return (c[0], c[1]), (c[2], c[3])

    return build()


@st.composite
def polylines(draw: Any) -> Any:
    snap = draw(snapper())
    n = draw(st.integers(2, 6))
    pts = [(snap(draw(floats(-6, 6))), snap(draw(floats(-6, 6)))) for _ in range(n)]
    return shapely.LineString(pts)


@st.composite
def point_sets(draw: Any) -> Any:
    snap = draw(snapper())
    n = draw(st.integers(1, 6))
    return shapely.MultiPoint([(snap(draw(floats(-4, 4))), snap(draw(floats(-4, 4)))) for _ in range(n)])


def polygonal() -> Any:
    """Any of the polygonal strategies above."""
    return st.one_of(
        star_polygons(),
        rectilinear_shapes(),
        slivers(),
        grazing_polygons(),
        moved(star_polygons(max_radius=4.0)),
    )


def noisy_star(n: int, radius: float, seed: int, centre: tuple[float, float] = (0.0, 0.0)) -> Any:
    """A star-shaped polygon with n vertices: a smooth random radius plus ±2 % noise per vertex.

    Discretized, its boundary has long straight stretches broken by one-pixel arms and notches (the
    benchmarks' 1024² blob is one; the minimum-link tests use smaller ones).
    """
    rng = np.random.default_rng(seed)
    ang = np.sort(rng.uniform(0.0, 2 * np.pi, n))
    smooth = sum(rng.uniform(0.02, 0.08) * np.sin(k * ang + rng.uniform(0, 6.3)) for k in (2, 3, 5, 7))
    r = radius * (0.8 + smooth + rng.uniform(-0.02, 0.02, n))
    poly = shapely.Polygon(np.c_[centre[0] + r * np.cos(ang), centre[1] + r * np.sin(ang)])
    assert poly.is_valid
    return poly
