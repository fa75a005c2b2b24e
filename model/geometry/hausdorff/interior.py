"""Case 3 of the maximum: the points of int A equidistant from three features of ∂B, found by boxes.

A first stage covers A with float boxes, decided in batches by the vectorized float filters of
:mod:`mrm.geometry.hausdorff.spatial`; boxes with few edges of ∂B nearby, or below float resolution, go to
an exact stage (:func:`_exact_boxes`) whose leaves solve the triples of features that can be nearest in
the box (:mod:`mrm.geometry.hausdorff.equidistant`), after the interval shadow of that solver
(:func:`_may_improve`) has discarded the triples that certainly cannot win.
"""

from __future__ import annotations

import heapq
import itertools
import math
from fractions import Fraction
from typing import Any

import numpy as np

from mrm.geometry.hausdorff.branch_and_bound import _MAX_DEPTH, _Run
from mrm.geometry.hausdorff.equidistant import _could_be_nearest, _equidistant, _line
from mrm.geometry.hausdorff.exact_numbers import _cmp, _rat, _sign
from mrm.geometry.hausdorff.intervals import _INF, _IV_TOWER, Rat, _iv, _Undecided
from mrm.geometry.hausdorff.shapes import Box, _corners, _dseg2, _pt_box2, _pt_box_max2, _seg_box2
from mrm.geometry.hausdorff.spatial import (
    _box_orig,
    _contains,
    _fl_count_near,
    _fl_inside,
    _fl_misses,
    _fl_nearest_up,
    _meets_boundary,
    _near,
    _query,
    _radius_orig,
    _vup,
)


def _interior(run: _Run) -> None:
    """Branch-and-bound over boxes for the points of int A equidistant from three features of ∂B.

    A first stage works on batches of float boxes (dyadic, so exact) with vectorized float tests whose
    rounding is bounded: a box is dropped when ``f(c) + r ≤ best`` (Lipschitz, with an upper bound of
    ``d(c, ∂B)``), or when it certainly misses ∂A with its centre certainly outside A, or certainly misses ∂B
    with its centre certainly inside B; whatever the floats cannot settle is kept. Boxes with few edges of ∂B
    nearby, or below float resolution, go to the exact stage (:func:`_exact_boxes`).
    """
    a, b, k = run.a, run.b, run.k
    if not a.edges or b.tree is None:
        return
    x0, y0 = float(a.fe[:, [0, 2]].min()), float(a.fe[:, [1, 3]].min())
    x1, y1 = float(a.fe[:, [0, 2]].max()), float(a.fe[:, [1, 3]].max())
    # A root square whose corner is on a power-of-two grid and whose side is a power of two: every sub-box
    # then has float corners and an exact centre.
    grid = math.ldexp(1.0, math.frexp(max(x1 - x0, y1 - y0, 1e-300))[1] - 1)
    rx, ry = math.floor(x0 / grid) * grid, math.floor(y0 / grid) * grid
    side = math.ldexp(1.0, math.frexp(max(x1 - rx, y1 - ry))[1])
    # Rounding allowance of the float distance bounds: a few ulps of the largest coordinate in play, the
    # boxes' included (see _fl_nearest_up).
    mag = max(a.mag, b.mag, abs(rx) + side, abs(ry) + side)
    slack = math.ldexp(mag + 1.0, -44)
    counter = itertools.count()
    heap: list[tuple[float, int, float, float, float, int]] = [(0.0, next(counter), rx, ry, side, 0)]
    while heap:
        batch = [heapq.heappop(heap) for _ in range(min(len(heap), _BATCH))]
        run.tick()
        bx0 = np.array([t[2] for t in batch])
        by0 = np.array([t[3] for t in batch])
        sz = np.array([t[4] for t in batch])
        depth = np.array([t[5] for t in batch])
        bx1, by1 = bx0 + sz, by0 + sz
        cx, cy = bx0 + sz / 2, by0 + sz / 2
        r = _vup(_vup(_vup(np.hypot(sz, sz)) / 2) + slack)
        fup = _fl_nearest_up(b, cx, cy, slack)
        upper = _vup(fup + r)
        llo = run.l_lo()
        live = upper > llo  # else f ≤ f(c) + r ≤ best on the box
        # Outside A: misses ∂A and the centre is outside. Inside B: misses ∂B and the centre is inside.
        idx = np.flatnonzero(live)
        if idx.size:
            misses_a = _fl_misses(a, bx0[idx], by0[idx], bx1[idx], by1[idx])
            if misses_a.any():
                j = idx[misses_a]
                ins, sure = _fl_inside(a, cx[j], cy[j])
                live[j[sure & ~ins]] = False
            idx = np.flatnonzero(live)
            misses_b = _fl_misses(b, bx0[idx], by0[idx], bx1[idx], by1[idx])
            if misses_b.any():
                j = idx[misses_b]
                ins, sure = _fl_inside(b, cx[j], cy[j])
                live[j[sure & ins]] = False
        idx = np.flatnonzero(live)
        if not idx.size:
            continue
        # Below ~2⁻³² of the coordinates floats no longer tell features apart: exact arithmetic decides; it
        # also takes over where few edges of ∂B are near (its bounds are sharper there).
        tiny = r[idx] <= 4096 * slack
        split = ~tiny
        ask = np.flatnonzero(split)
        if ask.size:
            j = idx[ask]
            split[ask] = _fl_count_near(b, bx0[j], by0[j], bx1[j], by1[j], upper[j]) > _LEAF_EDGES
        for i, sp in zip(idx.tolist(), split.tolist(), strict=True):
            if sp:
                h = float(sz[i]) / 2
                for ox, oy in ((0.0, 0.0), (h, 0.0), (0.0, h), (h, h)):
                    item = (
                        -float(upper[i]),
                        next(counter),
                        float(bx0[i]) + ox,
                        float(by0[i]) + oy,
                        h,
                        int(depth[i]) + 1,
                    )
                    heapq.heappush(heap, item)
            else:
                scale = 1 << k
                q = (
                    Fraction(float(bx0[i])) * scale,
                    Fraction(float(by0[i])) * scale,
                    Fraction(float(bx1[i])) * scale,
                    Fraction(float(by1[i])) * scale,
                )
                _exact_boxes(run, q, int(depth[i]))


#: A box of the exact stage becomes a leaf when at most this many features can be nearest in it.
_LEAF_FEATURES = 6
#: How many float boxes the first stage handles at once.
_BATCH = 256
#: A box goes to the exact stage when at most this many edges of ∂B lie within its float upper bound.
_LEAF_EDGES = 4


def _exact_boxes(run: _Run, root: Box, depth0: int) -> None:
    """The exact stage: exact tests, exact bounds, subdivision in rationals, leaves solved exactly."""
    a, b, k = run.a, run.b, run.k
    counter = itertools.count()
    heap: list[tuple[float, int, Box, int]] = [(0.0, next(counter), root, depth0)]
    while heap:
        _, _, q, depth = heapq.heappop(heap)
        run.tick()
        box_f = _box_orig(q, k)
        cx, cy = (q[0] + q[2]) / 2, (q[1] + q[3]) / 2
        a_edges = [e for e in _query(a, *box_f) if _seg_box2(a, e, q) == 0]
        if not a_edges and not _contains(a, k, cx, cy):
            continue  # the box misses ∂A and its centre is outside A: it is outside A
        if not _meets_boundary(b, q, box_f) and _contains(b, k, cx, cy):
            continue  # inside B: d(·, B) = 0 on the box
        nr = _near(b, k, cx, cy)
        if not nr.inside and _contains(a, k, cx, cy):
            run.offer(nr.f2, cx, cy, "interior")  # any point of A gives a lower bound
        # f ≤ d(·, e) for the edge e nearest to the centre; d(·, e) is convex, so its maximum over the polygon
        # Q ∩ A is at one of that polygon's vertices.
        u2 = max(_rat(_dseg2(b, nr.edge, x, y)[0]) for x, y in _clip_vertices(run, q, a_edges))
        if _cmp(u2, run.best.f2) <= 0:
            continue
        verts, edges = _features_near_box(run, q, u2)
        if len(verts) + len(edges) > _LEAF_FEATURES and depth < _MAX_DEPTH:
            key = -math.ldexp(math.sqrt(float(u2)), -k)
            for child in (
                (q[0], q[1], cx, cy),
                (cx, q[1], q[2], cy),
                (q[0], cy, cx, q[3]),
                (cx, cy, q[2], q[3]),
            ):
                heapq.heappush(heap, (key, next(counter), child, depth + 1))
            continue
        _leaf(run, q, u2, verts, edges)


def _clip_vertices(run: _Run, q: Box, a_edges: list[int]) -> list[tuple[Rat, Rat]]:
    """A superset of the vertices of the polygon Q ∩ A, all rational.

    Q's corners in A, A's vertices in Q, and the points where the edges of A meeting Q cross Q's sides.
    """
    a, k = run.a, run.k
    if not a_edges:
        return list(_corners(q))
    pts: list[tuple[Rat, Rat]] = [c for c in _corners(q) if _contains(a, k, c[0], c[1])]
    x0, y0, x1, y1 = q
    for e in a_edges:
        ux, uy, wx, wy = a.edges[e]
        for vx, vy in ((ux, uy), (wx, wy)):
            if x0 <= vx <= x1 and y0 <= vy <= y1:
                pts.append((vx, vy))
        if ux != wx:
            for x in (x0, x1):
                if (ux - x) * (wx - x) <= 0:
                    y = uy + (x - ux) * (wy - uy) / Fraction(wx - ux)
                    if y0 <= y <= y1:
                        pts.append((x, y))
        if uy != wy:
            for y in (y0, y1):
                if (uy - y) * (wy - y) <= 0:
                    x = ux + (y - uy) * (wx - ux) / Fraction(wy - uy)
                    if x0 <= x <= x1:
                        pts.append((x, y))
    return pts or list(_corners(q))


def _features_near_box(run: _Run, q: Box, u2: Rat) -> tuple[list[tuple[int, int]], list[int]]:
    b, k = run.b, run.k
    r = _radius_orig(u2, k)
    edges = []
    verts: set[tuple[int, int]] = set()
    for e in _query(b, *_box_orig(q, k, r)):
        if _seg_box2(b, e, q) > u2:
            continue
        ux, uy, wx, wy = b.edges[e]
        for vv in ((ux, uy), (wx, wy)):
            if vv not in verts and _pt_box2(vv[0], vv[1], q) <= u2 and not b.reflex[vv]:
                verts.add(vv)
        # A point outside B has its nearest edge on the outer side (ℓ < 0): an edge whose line leaves the
        # whole box on the inner side is never the nearest feature of a point that counts.
        mx, my = wx - ux, wy - uy
        if any(mx * (cy - uy) - my * (cx - ux) < 0 for cx, cy in _corners(q)):
            edges.append(e)
    return sorted(verts), edges


def _leaf(run: _Run, q: Box, u2: Rat, verts: list[tuple[int, int]], edges: list[int]) -> None:
    """Points of the box equidistant from three features that can be nearest in it."""
    b = run.b
    feats: list[tuple[str, Any, Rat, Rat]] = []
    for v in verts:
        feats.append(("v", v, _pt_box2(v[0], v[1], q), _pt_box_max2(v[0], v[1], q)))
    for e in edges:
        ux, uy, wx, wy = b.edges[e]
        mx, my = wx - ux, wy - uy
        top = max(Fraction((mx * (cy - uy) - my * (cx - ux)) ** 2, b.norms[e]) for cx, cy in _corners(q))
        feats.append(("e", e, _seg_box2(b, e, q), top))
    for f1, f2, f3 in itertools.combinations(feats, 3):
        lo = max(f1[2], f2[2], f3[2])
        hi = min(f1[3], f2[3], f3[3], u2)
        if lo > hi or _cmp(hi, run.best.f2) <= 0:
            continue  # the three distances cannot meet above the best value inside the box
        run.tick()
        trio = (f1, f2, f3)
        if not _may_improve(run, q, trio):
            continue
        for x, y in _equidistant(run, trio, run.t):
            if not (_cmp(x, q[0]) >= 0 and _cmp(x, q[2]) <= 0 and _cmp(y, q[1]) >= 0 and _cmp(y, q[3]) <= 0):
                continue
            if not _could_be_nearest(b, trio, x, y):
                continue
            if not _contains(run.a, run.k, x, y):
                continue
            nr = _near(b, run.k, x, y)
            if not nr.inside:
                run.offer(nr.f2, x, y, "interior")


def _may_improve(run: _Run, q: Box, trio: tuple[tuple[str, Any, Rat, Rat], ...]) -> bool:
    """Interval shadow of :func:`_equidistant`: False only when no solution can beat the best in the box."""
    try:
        pts = _equidistant(run, trio, _IV_TOWER)
    except (_Undecided, ZeroDivisionError):
        return True
    best_lo = _iv(run.best.f2)[0] if _sign(run.best.f2) > 0 else -_INF
    f = trio[0]
    for x, y in pts:
        xl, xh = _iv(x)
        yl, yh = _iv(y)
        if xh < q[0] or xl > q[2] or yh < q[1] or yl > q[3]:
            continue
        try:
            if not _could_be_nearest(run.b, trio, x, y):
                continue
        except _Undecided:
            pass
        if f[0] == "v":
            d2 = (x - f[1][0]) * (x - f[1][0]) + (y - f[1][1]) * (y - f[1][1])
        else:
            la, lb, lc, n = _line(run.b, f[1])
            ell = la * x + lb * y + lc
            d2 = ell * ell * Fraction(1, n)
        if _iv(d2)[1] <= best_lo:
            continue
        return True
    return False
