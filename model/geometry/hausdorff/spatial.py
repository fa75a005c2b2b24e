"""Searching the edges of a shape through its STRtree: exact nearest distance and containment, float filters.

The index (GEOS STRtree, in original float coordinates) only ever selects a *superset* of the edges that
matter: query boxes are rounded outward, and every answer is then decided exactly on the integer edges
(:func:`_near`, :func:`_contains`, :func:`_meets_boundary`). The vectorized float tests (``_fl_*``) decide
whole batches of boxes at once for the first stage of :func:`mrm.geometry.hausdorff.interior._interior`;
each float inequality carries a proven rounding allowance, and what it cannot settle is kept.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import shapely

from mrm.geometry.hausdorff.exact_numbers import Num, _cmp, _sign
from mrm.geometry.hausdorff.intervals import _INF, _down, _iv, _up
from mrm.geometry.hausdorff.shapes import Box, _dseg2, _in_wedges, _seg_box2, _Shape


def _to_orig_iv(x: Num, k: int) -> tuple[float, float]:
    lo, hi = _iv(x)
    return _down(math.ldexp(lo, -k)), _up(math.ldexp(hi, -k))


def _radius_orig(d2: Num, k: int) -> float:
    """A float ≥ √d2 in original units."""
    hi = _iv(d2)[1]
    if hi == _INF:
        return _INF
    return _up(math.ldexp(_up(math.sqrt(max(hi, 0.0))), -k))


def _query(s: _Shape, xlo: float, ylo: float, xhi: float, yhi: float) -> list[int]:
    if s.tree is None:
        return []
    if not all(math.isfinite(v) for v in (xlo, ylo, xhi, yhi)):
        return list(range(len(s.edges)))
    return [int(i) for i in s.tree.query(shapely.box(xlo, ylo, xhi, yhi))]


@dataclass
class _Near:
    f2: Num  # squared distance to the set (0 inside)
    edge: int  # an edge of the boundary at minimum distance
    inside: bool


def _near(s: _Shape, k: int, px: Num, py: Num) -> _Near:
    """Exact squared distance from p to the filled set s (and whether p is inside)."""
    xlo, xhi = _to_orig_iv(px, k)
    ylo, yhi = _to_orig_iv(py, k)
    assert s.tree is not None
    xm = 0.5 * (xlo + xhi) if math.isfinite(xlo + xhi) else 0.0
    ym = 0.5 * (ylo + yhi) if math.isfinite(ylo + yhi) else 0.0
    first = int(s.tree.query_nearest(shapely.Point(xm, ym))[0])
    d0, _, _ = _dseg2(s, first, px, py)
    if _sign(d0) == 0:
        return _Near(0, first, True)
    r = _radius_orig(d0, k)
    cands = _query(s, _down(xlo - r), _down(ylo - r), _up(xhi + r), _up(yhi + r))
    best: Num = d0
    best_edges: list[tuple[int, int, Num]] = []
    for e in cands:
        d2, kind, cross = _dseg2(s, e, px, py)
        c = _cmp(d2, best)
        if c < 0:
            best, best_edges = d2, [(e, kind, cross)]
        elif c == 0:
            best_edges.append((e, kind, cross))
    if not best_edges:  # the first edge is always a candidate; keep the code total anyway
        d2, kind, cross = _dseg2(s, first, px, py)
        best_edges = [(first, kind, cross)]
    if _sign(best) == 0:
        return _Near(0, best_edges[0][0], True)
    # The side of p: from an edge whose nearest point is inside it, else from the wedges at the vertex.
    for e, kind, cross in best_edges:
        if kind == 0:
            return _Near(best, e, _sign(cross) > 0)
    e, kind, _ = best_edges[0]
    ux, uy, wx, wy = s.edges[e]
    v = (ux, uy) if kind == 1 else (wx, wy)
    inside = _in_wedges(s, v, px - v[0], py - v[1])
    return _Near(best, e, inside)


def _contains(s: _Shape, k: int, px: Num, py: Num) -> bool:
    """Is p in the closed set s? (exact crossing number, boundary included)."""
    xlo, _ = _to_orig_iv(px, k)
    ylo, yhi = _to_orig_iv(py, k)
    cands = _query(s, xlo, ylo, _up(max(s.xmax_orig, xlo) + 1.0), yhi)
    inside = False
    for e in cands:
        ax, ay, bx, by = s.edges[e]
        cross = (bx - ax) * (py - ay) - (by - ay) * (px - ax)
        sc = _sign(cross)
        # On the supporting line and between the endpoints: on the edge.
        if (
            sc == 0
            and _cmp(px, min(ax, bx)) >= 0
            and _cmp(px, max(ax, bx)) <= 0
            and _cmp(py, min(ay, by)) >= 0
            and _cmp(py, max(ay, by)) <= 0
        ):
            return True
        a_above = _cmp(py, ay) < 0  # ay > py
        b_above = _cmp(py, by) < 0
        if a_above != b_above and ((by > ay and sc > 0) or (by < ay and sc < 0)):
            inside = not inside
    return inside


def _box_orig(q: Box, k: int, pad: float = 0.0) -> tuple[float, float, float, float]:
    xlo, _ = _to_orig_iv(q[0], k)
    ylo, _ = _to_orig_iv(q[1], k)
    _, xhi = _to_orig_iv(q[2], k)
    _, yhi = _to_orig_iv(q[3], k)
    if pad:
        return _down(xlo - pad), _down(ylo - pad), _up(xhi + pad), _up(yhi + pad)
    return xlo, ylo, xhi, yhi


def _meets_boundary(s: _Shape, q: Box, box_f: tuple[float, float, float, float]) -> bool:
    """Tell exactly whether some edge of s meets the closed box q."""
    return any(_seg_box2(s, e, q) == 0 for e in _query(s, *box_f))


F64 = npt.NDArray[np.float64]
Bools = npt.NDArray[np.bool_]


def _vup(x: F64) -> F64:
    return np.nextafter(x, np.inf)


def _fl_nearest_up(s: _Shape, px: F64, py: F64, slack: float) -> F64:
    """Floats ≥ the distance from each point to ∂s, through one nearby edge.

    The clamped projection ``q = u + t·(w − u)`` (t ∈ [0, 1] exactly) is a point of the segment up to the
    rounding of three operations on numbers of magnitude ≤ 2M (M the largest coordinate), and ``hypot`` is
    within one ulp, so the computed distance is off by less than ``2⁻⁴⁷·M``: ``slack = 2⁻⁴⁴·(M + 1)`` covers
    it, with the result rounded up.
    """
    pairs = s.tree.query_nearest(shapely.points(px, py))
    _, first = np.unique(pairs[0], return_index=True)
    e = s.fe[pairs[1][first]]
    ux, uy, wx, wy = e[:, 0], e[:, 1], e[:, 2], e[:, 3]
    mx, my = wx - ux, wy - uy
    nn = mx * mx + my * my
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(nn > 0, ((px - ux) * mx + (py - uy) * my) / np.where(nn > 0, nn, 1.0), 0.0)
    t = np.clip(t, 0.0, 1.0)
    d = np.hypot(px - (ux + t * mx), py - (uy + t * my))
    return _vup(_vup(d) + slack)


def _fl_pairs(s: _Shape, x0: F64, y0: F64, x1: F64, y1: F64) -> tuple[npt.NDArray[np.intp], F64]:
    """(box index, edge coordinates) for every edge whose envelope meets each box."""
    pairs = s.tree.query(shapely.box(x0, y0, x1, y1))
    return pairs[0], s.fe[pairs[1]]


def _fl_sides(e: F64, cx: F64, cy: F64) -> tuple[F64, F64]:
    """Orientation of (cx, cy) to each edge's line, with a bound on its rounding error."""
    ux, uy, wx, wy = e[:, 0], e[:, 1], e[:, 2], e[:, 3]
    p1 = (wx - ux) * (cy - uy)
    p2 = (wy - uy) * (cx - ux)
    # Each product has a relative error below 3u (u = 2⁻⁵³), the difference adds u: 2⁻⁵⁰ covers it.
    return p1 - p2, np.ldexp(np.abs(p1) + np.abs(p2), -50)


def _fl_misses(s: _Shape, x0: F64, y0: F64, x1: F64, y1: F64) -> Bools:
    """Boxes that certainly miss every edge (separated along an axis or by the edge's line)."""
    n = x0.size
    i, e = _fl_pairs(s, x0, y0, x1, y1)
    if not i.size:
        return np.ones(n, dtype=bool)
    bx0, by0, bx1, by1 = x0[i], y0[i], x1[i], y1[i]
    ux, uy, wx, wy = e[:, 0], e[:, 1], e[:, 2], e[:, 3]
    apart = (np.maximum(ux, wx) < bx0) | (np.minimum(ux, wx) > bx1)
    apart |= (np.maximum(uy, wy) < by0) | (np.minimum(uy, wy) > by1)
    pos = np.ones(i.size, dtype=bool)
    neg = np.ones(i.size, dtype=bool)
    for cx, cy in ((bx0, by0), (bx1, by0), (bx1, by1), (bx0, by1)):
        v, err = _fl_sides(e, cx, cy)
        pos &= v > err
        neg &= v < -err
    meets = ~(apart | pos | neg)
    misses: Bools = np.bincount(i[meets], minlength=n) == 0
    return misses


def _fl_inside(s: _Shape, px: F64, py: F64) -> tuple[Bools, Bools]:
    """Crossing-number point-in-set test in floats: (inside, certain) for each point."""
    n = px.size
    i, e = _fl_pairs(s, px, py, np.full(n, s.xmax_orig + 1.0), py)
    inside = np.zeros(n, dtype=bool)
    sure = np.ones(n, dtype=bool)
    if i.size:
        x, y = px[i], py[i]
        ay, by = e[:, 1], e[:, 3]
        straddle = (ay > y) != (by > y)
        v, err = _fl_sides(e, x, y)
        unsure = straddle & (np.abs(v) <= err)
        cross = straddle & (((by > ay) & (v > 0)) | ((by < ay) & (v < 0)))
        inside = np.bincount(i[cross], minlength=n) % 2 == 1
        sure = np.bincount(i[unsure], minlength=n) == 0
    return inside, sure


def _fl_count_near(s: _Shape, x0: F64, y0: F64, x1: F64, y1: F64, radius: F64) -> npt.NDArray[np.intp]:
    """About how many edges lie within ``radius`` of each box (decides splitting only, never a result)."""
    n = x0.size
    i, e = _fl_pairs(s, x0 - radius, y0 - radius, x1 + radius, y1 + radius)
    if not i.size:
        return np.zeros(n, dtype=np.intp)
    bx0, by0, bx1, by1, rad = x0[i], y0[i], x1[i], y1[i], radius[i]
    ux, uy, wx, wy = e[:, 0], e[:, 1], e[:, 2], e[:, 3]
    mx, my = wx - ux, wy - uy
    nn = np.maximum(mx * mx + my * my, 1e-300)
    best = np.full(i.size, np.inf)
    corners = ((bx0, by0), (bx1, by0), (bx1, by1), (bx0, by1))
    for cx, cy in corners:
        t = np.clip(((cx - ux) * mx + (cy - uy) * my) / nn, 0.0, 1.0)
        best = np.minimum(best, np.hypot(cx - ux - t * mx, cy - uy - t * my))
    for px, py in ((ux, uy), (wx, wy)):
        dx = np.maximum(np.maximum(bx0 - px, 0.0), px - bx1)
        dy = np.maximum(np.maximum(by0 - py, 0.0), py - by1)
        best = np.minimum(best, np.hypot(dx, dy))
    sides = np.stack([mx * (cy - uy) - my * (cx - ux) for cx, cy in corners])
    crossing = ~(np.all(sides > 0, axis=0) | np.all(sides < 0, axis=0))
    crossing &= (np.maximum(ux, wx) >= bx0) & (np.minimum(ux, wx) <= bx1)
    crossing &= (np.maximum(uy, wy) >= by0) & (np.minimum(uy, wy) <= by1)
    best[crossing] = 0.0
    return np.bincount(i[best <= rad * (1 + 1e-9)], minlength=n)
