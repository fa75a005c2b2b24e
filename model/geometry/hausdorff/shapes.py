"""The polygonal sets on a common integer grid, and exact distances to their edges.

Coordinates (float64, so dyadic rationals) of both sets are scaled by one power of two ``2^k`` to integers
(:func:`_setup`); a :class:`_Shape` holds the edges with the interior on their left, the wedges at each
vertex, an STRtree over the edges in original coordinates (for :mod:`mrm.geometry.hausdorff.spatial`) and
their float copy. The distances here are exact: points may be rationals or tower elements.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
import numpy.typing as npt
import shapely
from shapely.geometry import MultiPolygon, Polygon
from shapely.geometry.base import BaseGeometry
from shapely.geometry.polygon import orient

from mrm.core.errors import InvalidGeometryError
from mrm.geometry.hausdorff.exact_numbers import Num, _cmp, _div, _sign
from mrm.geometry.hausdorff.intervals import _INF, Rat


@dataclass
class _Shape:
    """A polygonal set on the common integer grid: edges with the interior on their left."""

    edges: list[tuple[int, int, int, int]]
    norms: list[int]
    wedges: dict[tuple[int, int], list[tuple[int, int, int, int]]]
    vertices: list[tuple[int, int]]
    tree: Any
    xmax_orig: float
    reflex: dict[tuple[int, int], bool]
    fe: npt.NDArray[np.float64]  # the edges in original coordinates, (m, 4): ux, uy, wx, wy
    mag: float  # the largest coordinate magnitude


def _polygons(geom: BaseGeometry, what: str) -> list[Polygon]:
    if geom is None:
        raise InvalidGeometryError(f"{what}: no geometry")
    if geom.is_empty:
        return []
    if isinstance(geom, Polygon):
        polys = [geom]
    elif isinstance(geom, MultiPolygon):
        polys = list(geom.geoms)
    else:
        raise InvalidGeometryError(f"{what}: expected a Polygon or MultiPolygon, got a {geom.geom_type}")
    for p in polys:
        coords = shapely.get_coordinates(p)
        if not all(math.isfinite(v) for v in coords.ravel()):
            raise InvalidGeometryError(f"{what}: non-finite coordinates")
    if not geom.is_valid:
        raise InvalidGeometryError(f"{what}: invalid geometry ({shapely.is_valid_reason(geom)})")
    return [p for p in polys if not p.is_empty]


def _rings(polys: list[Polygon]) -> list[list[tuple[float, float]]]:
    rings: list[list[tuple[float, float]]] = []
    for p in polys:
        p = orient(p, 1.0)  # exterior counter-clockwise, holes clockwise: the interior is on the left
        for ring in [p.exterior, *p.interiors]:
            pts: list[tuple[float, float]] = []
            for x, y in list(ring.coords)[:-1]:
                q = (float(x), float(y))
                if not pts or pts[-1] != q:
                    pts.append(q)
            while len(pts) > 1 and pts[0] == pts[-1]:
                pts.pop()
            if len(pts) >= 3:
                rings.append(pts)
    return rings


def _scale_exponent(rings: list[list[tuple[float, float]]]) -> int:
    k = 0
    for ring in rings:
        for x, y in ring:
            for v in (x, y):
                d = v.as_integer_ratio()[1]
                k = max(k, d.bit_length() - 1)
    return k


def _prepare(rings: list[list[tuple[float, float]]], k: int) -> _Shape:
    def scaled(v: float) -> int:
        n, d = v.as_integer_ratio()
        return n * ((1 << k) // d)

    edges: list[tuple[int, int, int, int]] = []
    lines = []
    wedges: dict[tuple[int, int], list[tuple[int, int, int, int]]] = {}
    xmax = -_INF
    for ring in rings:
        pts = [(scaled(x), scaled(y)) for x, y in ring]
        m = len(pts)
        for i in range(m):
            u, w = pts[i], pts[(i + 1) % m]
            edges.append((u[0], u[1], w[0], w[1]))
            lines.append(((ring[i][0], ring[i][1]), (ring[(i + 1) % m][0], ring[(i + 1) % m][1])))
            prev = pts[i - 1]
            wedges.setdefault(u, []).append((u[0] - prev[0], u[1] - prev[1], w[0] - u[0], w[1] - u[1]))
            xmax = max(xmax, ring[i][0])
    norms = [(wx - ux) ** 2 + (wy - uy) ** 2 for ux, uy, wx, wy in edges]
    tree = shapely.STRtree(shapely.linestrings(lines)) if lines else None
    # A strictly reflex vertex (every wedge turns right) is never the nearest point of an outside point.
    reflex = {v: all(ix * oy - iy * ox < 0 for ix, iy, ox, oy in ws) for v, ws in wedges.items()}
    fe = np.array([[p[0][0], p[0][1], p[1][0], p[1][1]] for p in lines], dtype=np.float64).reshape(-1, 4)
    mag = float(np.abs(fe).max()) if fe.size else 0.0
    return _Shape(edges, norms, wedges, list(wedges), tree, xmax, reflex, fe, mag)


def _setup(a: BaseGeometry, b: BaseGeometry) -> tuple[_Shape, _Shape, int]:
    ra = _rings(_polygons(a, "first geometry"))
    rb = _rings(_polygons(b, "second geometry"))
    k = max(_scale_exponent(ra), _scale_exponent(rb))
    return _prepare(ra, k), _prepare(rb, k), k


def _dseg2(s: _Shape, e: int, px: Num, py: Num) -> tuple[Num, int, Num]:
    """Squared distance from p to edge e, the kind of nearest point and the cross product.

    Kind 0: the nearest point is inside the edge, 1: it is u, 2: it is w. The cross product is positive when
    p is on the interior side of the edge's line.
    """
    ux, uy, wx, wy = s.edges[e]
    mx, my = wx - ux, wy - uy
    dx, dy = px - ux, py - uy
    cross = mx * dy - my * dx
    proj = dx * mx + dy * my
    if _sign(proj) <= 0:
        return dx * dx + dy * dy, 1, cross
    n = s.norms[e]
    if _cmp(proj, n) >= 0:
        ex, ey = px - wx, py - wy
        return ex * ex + ey * ey, 2, cross
    return _div(cross * cross, n), 0, cross


def _in_wedges(s: _Shape, v: tuple[int, int], dx: Num, dy: Num) -> bool:
    """Tell whether the direction (dx, dy) from vertex v points into the interior."""
    for ix, iy, ox, oy in s.wedges[v]:
        left_in = _sign(ix * dy - iy * dx) > 0
        left_out = _sign(ox * dy - oy * dx) > 0
        turn = ix * oy - iy * ox
        if turn > 0:
            inside = left_in and left_out
        elif turn < 0:
            inside = left_in or left_out
        else:
            inside = left_in
        if inside:
            return True
    return False


def _seg_seg_dist2(p: tuple[Rat, Rat], q: tuple[Rat, Rat], s: _Shape, e: int) -> Rat:
    ux, uy, wx, wy = s.edges[e]

    def orient2(ax: Rat, ay: Rat, bx: Rat, by: Rat, cx: Rat, cy: Rat) -> int:
        v = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
        return (v > 0) - (v < 0)

    o1 = orient2(p[0], p[1], q[0], q[1], ux, uy)
    o2 = orient2(p[0], p[1], q[0], q[1], wx, wy)
    o3 = orient2(ux, uy, wx, wy, p[0], p[1])
    o4 = orient2(ux, uy, wx, wy, q[0], q[1])
    if o1 * o2 < 0 and o3 * o4 < 0:
        return 0
    cands = [
        _pt_seg2(ux, uy, p, q),
        _pt_seg2(wx, wy, p, q),
        _pt_seg2(p[0], p[1], (ux, uy), (wx, wy)),
        _pt_seg2(q[0], q[1], (ux, uy), (wx, wy)),
    ]
    return min(cands)


def _pt_seg2(px: Rat, py: Rat, a: tuple[Rat, Rat], b: tuple[Rat, Rat]) -> Rat:
    mx, my = b[0] - a[0], b[1] - a[1]
    dx, dy = px - a[0], py - a[1]
    proj = dx * mx + dy * my
    if proj <= 0:
        return dx * dx + dy * dy
    n = mx * mx + my * my
    if proj >= n:
        ex, ey = px - b[0], py - b[1]
        return ex * ex + ey * ey
    cross = mx * dy - my * dx
    return Fraction(cross * cross, 1) / n


Box = tuple[Fraction, Fraction, Fraction, Fraction]


def _pt_box2(px: Rat, py: Rat, q: Box) -> Rat:
    dx: Rat = q[0] - px if px < q[0] else (px - q[2] if px > q[2] else 0)
    dy: Rat = q[1] - py if py < q[1] else (py - q[3] if py > q[3] else 0)
    return dx * dx + dy * dy


def _pt_box_max2(px: Rat, py: Rat, q: Box) -> Rat:
    dx = max(abs(px - q[0]), abs(px - q[2]))
    dy = max(abs(py - q[1]), abs(py - q[3]))
    return dx * dx + dy * dy


def _corners(q: Box) -> list[tuple[Fraction, Fraction]]:
    return [(q[0], q[1]), (q[2], q[1]), (q[2], q[3]), (q[0], q[3])]


def _seg_box2(s: _Shape, e: int, q: Box) -> Rat:
    ux, uy, wx, wy = s.edges[e]
    if (q[0] <= ux <= q[2] and q[1] <= uy <= q[3]) or (q[0] <= wx <= q[2] and q[1] <= wy <= q[3]):
        return 0
    cs = _corners(q)
    # does the segment cross the box? (it has no endpoint inside, so it crosses two sides)
    sides = [0, 0, 0, 0]
    for i, (cx, cy) in enumerate(cs):
        v = (wx - ux) * (cy - uy) - (wy - uy) * (cx - ux)
        sides[i] = (v > 0) - (v < 0)
    # Separating axes: the box's two axes and the segment's normal.
    straddles = not (all(x > 0 for x in sides) or all(x < 0 for x in sides))
    overlaps = max(ux, wx) >= q[0] and min(ux, wx) <= q[2] and max(uy, wy) >= q[1] and min(uy, wy) <= q[3]
    if straddles and overlaps:
        return 0
    best = min(_pt_box2(ux, uy, q), _pt_box2(wx, wy, q))
    for cx, cy in cs:
        best = min(best, _pt_seg2(cx, cy, (ux, uy), (wx, wy)))
    return best
