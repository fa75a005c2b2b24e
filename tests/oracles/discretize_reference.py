"""Reference discretization: the definitions of docs/design.md §2, evaluated with fractions.Fraction.

D(E) = { p ∈ Z² : E ∩ K(p) ≠ ∅ } with τ = (ε, ε²), ε → 0⁺, and

    open        K(p) = int V(p)                 (only for the sandwich property; not a product model)
    standard    K(p) = int V(p) + τ
    supercover  K(p) = V(p)
    gauss       K(p) = { p + τ }

Quantities that depend on ε are *triples* (v0, v1, v2) meaning v0 + v1·ε + v2·ε²; Python compares tuples
lexicographically, which is exactly "for every sufficiently small ε > 0". Every kernel is an axis-aligned box
lo ⋖ z ⋖ hi (⋖ being < for open boxes and ≤ for closed ones) whose bounds are triples, so one Liang–Barsky
routine tests segments against all four kernels. A polygon meets the connected K(p) iff one of its edges
does, or a point of K(p) lies inside it; when no edge meets K(p) every point of K(p) (and p + τ, and p
itself for the open and closed squares) has the same status, decided by a ray test from p + τ, whose
horizontal line y = p_y + ε² never passes through a vertex.

Nothing here is shared with mrm.geometry: no float filter, no walk, no scanline.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable
from fractions import Fraction
from typing import Any

import shapely

Q = Fraction
Triple = tuple[Fraction, Fraction, Fraction]
Pt = tuple[Fraction, Fraction]

REFERENCE_MODELS = ("open", "standard", "supercover", "gauss")
HALF = Q(1, 2)
ZERO, ONE = Q(0), Q(1)


def _t(v0: Fraction, v1: Fraction | int = 0, v2: Fraction | int = 0) -> Triple:
    return (Q(v0), Q(v1), Q(v2))


def kernel_box(p: tuple[int, int], model: str) -> tuple[Triple, Triple, Triple, Triple, bool]:
    """(lo_x, hi_x, lo_y, hi_y, strict) describing K(p) for ``model``."""
    x, y = Q(p[0]), Q(p[1])
    if model == "open":
        return _t(x - HALF), _t(x + HALF), _t(y - HALF), _t(y + HALF), True
    if model == "standard":
        return _t(x - HALF, 1), _t(x + HALF, 1), _t(y - HALF, 0, 1), _t(y + HALF, 0, 1), True
    if model == "supercover":
        return _t(x - HALF), _t(x + HALF), _t(y - HALF), _t(y + HALF), False
    if model == "gauss":
        return _t(x, 1), _t(x, 1), _t(y, 0, 1), _t(y, 0, 1), False
    raise ValueError(model)


def _below(lo: Triple, hi: Triple, strict: bool) -> bool:
    return lo < hi if strict else lo <= hi


def point_meets(z: Pt, box: tuple[Triple, Triple, Triple, Triple, bool]) -> bool:
    lox, hix, loy, hiy, strict = box
    zx, zy = _t(z[0]), _t(z[1])
    return (
        _below(lox, zx, strict)
        and _below(zx, hix, strict)
        and _below(loy, zy, strict)
        and _below(zy, hiy, strict)
    )


def segment_meets(a: Pt, b: Pt, box: tuple[Triple, Triple, Triple, Triple, bool]) -> bool:
    """Liang–Barsky: is there t ∈ [0, 1] with a + t(b − a) in the box (for all small ε)?"""
    lox, hix, loy, hiy, strict = box
    lowers: list[tuple[Triple, bool]] = [(_t(ZERO), False)]
    uppers: list[tuple[Triple, bool]] = [(_t(ONE), False)]
    for lo, hi, a0, d in ((lox, hix, a[0], b[0] - a[0]), (loy, hiy, a[1], b[1] - a[1])):
        if d == 0:
            if not (_below(lo, _t(a0), strict) and _below(_t(a0), hi, strict)):
                return False
            continue
        t_lo = tuple((v - (a0 if k == 0 else 0)) / d for k, v in enumerate(lo))
        t_hi = tuple((v - (a0 if k == 0 else 0)) / d for k, v in enumerate(hi))
        if d < 0:
            t_lo, t_hi = t_hi, t_lo
        lowers.append((t_lo, strict))  # type: ignore[arg-type]
        uppers.append((t_hi, strict))  # type: ignore[arg-type]
    return all(_below(lo, hi, s1 or s2) for lo, s1 in lowers for hi, s2 in uppers)


def inside_tau(p: tuple[int, int], rings: list[list[Pt]]) -> bool:
    """Is p + τ inside the polygon bounded by ``rings`` (even-odd)? Ray from p + τ towards +x."""
    zx, zy = _t(Q(p[0]), 1), _t(Q(p[1]), 0, 1)
    count = 0
    for ring in rings:
        for a, b in itertools.pairwise(ring):
            if a[1] == b[1]:
                continue
            lo, hi = min(a[1], b[1]), max(a[1], b[1])
            if not (_t(lo) < zy < _t(hi)):
                continue
            slope = (b[0] - a[0]) / (b[1] - a[1])
            cross = _t(a[0] + (zy[0] - a[1]) * slope, 0, slope)  # x on the edge at y = p_y + ε²
            assert cross != zx
            if zx < cross:
                count += 1
    return count % 2 == 1


# ----------------------------------------------------------------------------------------- geometry
def _ring(coords: Iterable[Any]) -> list[Pt]:
    return [(Q(float(x)), Q(float(y))) for x, y, *_ in coords]


def pieces(geom: Any) -> tuple[list[list[list[Pt]]], list[tuple[Pt, Pt]], list[Pt]]:
    """(polygons as lists of closed rings, segments, points) of a shapely geometry, exactly."""
    polys: list[list[list[Pt]]] = []
    segs: list[tuple[Pt, Pt]] = []
    pts: list[Pt] = []

    def visit(g: Any) -> None:
        if g.is_empty:
            return
        kind = g.geom_type
        if kind == "Polygon":
            polys.append([_ring(g.exterior.coords)] + [_ring(r.coords) for r in g.interiors])
        elif kind in ("LineString", "LinearRing"):
            c = _ring(g.coords)
            segs.extend(itertools.pairwise(c))
        elif kind == "Point":
            pts.append((Q(float(g.x)), Q(float(g.y))))
        elif kind in ("MultiPolygon", "MultiLineString", "MultiPoint", "GeometryCollection"):
            for part in g.geoms:
                visit(part)
        else:
            raise ValueError(kind)

    visit(geom)
    return polys, segs, pts


def _closed_range(lo: Fraction, hi: Fraction) -> range:
    """Integers k whose closed interval [k − ½, k + ½] meets [lo, hi]."""
    return range(math.ceil(lo - HALF), math.floor(hi + HALF) + 1)


def reference_discretize(geom: Any, model: str) -> set[tuple[int, int]]:
    """D(geom) = { p : geom ∩ K(p) ≠ ∅ } for a shapely geometry, by the definitions."""
    polys, segs, pts = pieces(geom)
    out: set[tuple[int, int]] = set()

    def meets_candidates(xs: list[Fraction], ys: list[Fraction]) -> Iterable[tuple[int, int]]:
        for i in _closed_range(min(xs), max(xs)):
            for j in _closed_range(min(ys), max(ys)):
                yield (i, j)

    for z in pts:
        for p in meets_candidates([z[0]], [z[1]]):
            if point_meets(z, kernel_box(p, model)):
                out.add(p)
    edges = list(segs)
    for rings in polys:
        for ring in rings:
            edges.extend(itertools.pairwise(ring))
    for a, b in edges:
        dx, dy = b[0] - a[0], b[1] - a[1]
        half_w = (abs(dx) + abs(dy)) / 2
        for p in meets_candidates([a[0], b[0]], [a[1], b[1]]):
            # Pruning only: every kernel lies in the closed square, which the line a-b misses when
            # |f(p)| > ω/2 (docs/algorithms.md §1.1); the decision itself is segment_meets.
            if abs(dy * (p[0] - a[0]) - dx * (p[1] - a[1])) > half_w:
                continue
            if p not in out and segment_meets(a, b, kernel_box(p, model)):
                out.add(p)
    for rings in polys:
        xs = [v[0] for r in rings for v in r]
        ys = [v[1] for r in rings for v in r]
        for p in meets_candidates(xs, ys):
            if p not in out and inside_tau(p, rings):
                out.add(p)
    return out


def reference_segment(a: tuple[float, float], b: tuple[float, float], model: str) -> set[tuple[int, int]]:
    """D([a, b]) by the definitions."""
    return (
        reference_discretize(shapely.LineString([a, b]), model)
        if a != b
        else reference_discretize(shapely.Point(a), model)
    )


def standard_line_inequality(
    a: Fraction, b: Fraction, c: Fraction, window: tuple[int, int, int, int]
) -> set[tuple[int, int]]:
    """Andres' standard line −ω/2 ≤ a·x + b·y + c < ω/2 (normal made canonical: a > 0, or a = 0 < b)."""
    if a < 0 or (a == 0 and b < 0):
        a, b, c = -a, -b, -c
    w = abs(a) + abs(b)
    x0, y0, x1, y1 = window
    return {
        (x, y) for x in range(x0, x1 + 1) for y in range(y0, y1 + 1) if -w / 2 <= a * x + b * y + c < w / 2
    }
