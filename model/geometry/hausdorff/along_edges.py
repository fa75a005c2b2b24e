"""Case 2 of the maximum: the points of the edges of A, by a branch-and-bound over pieces of each edge.

Along a piece of an edge of A each feature's squared distance is a quadratic in the edge's parameter, so
the maximum of ``d(·, B)`` on the piece is at a crossing of two features (a root in ``Q(√D)``) or at an end
of a line feature's slab (:func:`_edge_leaf`). A piece is dropped when it lies inside B, when the convex
bound of one edge of ∂B at its ends cannot beat the best value, or by the Lipschitz test.
"""

from __future__ import annotations

from fractions import Fraction

from mrm.geometry.hausdorff.branch_and_bound import _MAX_DEPTH, _lipschitz_prunes, _Run
from mrm.geometry.hausdorff.exact_numbers import Num, _cmp, _rat, _solve_quadratic
from mrm.geometry.hausdorff.intervals import Rat, _down, _up
from mrm.geometry.hausdorff.shapes import _dseg2, _pt_seg2, _seg_seg_dist2
from mrm.geometry.hausdorff.spatial import _near, _query, _radius_orig, _to_orig_iv


def _features_near_segment(
    run: _Run, p: tuple[Rat, Rat], q: tuple[Rat, Rat], u2: Rat
) -> tuple[list[int], list[tuple[int, int]]]:
    """Features of ∂B that can be nearest to an outside point of segment pq at distance ≤ √u2."""
    b, k = run.b, run.k
    r = _radius_orig(u2, k)
    xlo, _ = _to_orig_iv(min(p[0], q[0]), k)
    ylo, _ = _to_orig_iv(min(p[1], q[1]), k)
    _, xhi = _to_orig_iv(max(p[0], q[0]), k)
    _, yhi = _to_orig_iv(max(p[1], q[1]), k)
    edges = []
    verts: set[tuple[int, int]] = set()
    for e in _query(b, _down(xlo - r), _down(ylo - r), _up(xhi + r), _up(yhi + r)):
        if _seg_seg_dist2(p, q, b, e) > u2:
            continue
        ux, uy, wx, wy = b.edges[e]
        for vv in ((ux, uy), (wx, wy)):
            if vv not in verts and not b.reflex[vv] and _pt_seg2(vv[0], vv[1], p, q) <= u2:
                verts.add(vv)
        mx, my = wx - ux, wy - uy
        if any(mx * (cy - uy) - my * (cx - ux) < 0 for cx, cy in (p, q)):
            edges.append(e)
    return edges, sorted(verts)


#: A piece of an edge of A becomes a leaf when at most this many features can be nearest on it.
_LEAF_FEATURES_1D = 6


def _edge(run: _Run, i: int, u2: Rat) -> None:
    """Offer the maximum of d(·, B) along edge i of A.

    A branch-and-bound over pieces [t0, t1] of the edge; its leaves examine the exact candidates (feature
    crossings and slab ends).
    """
    a, b, k = run.a, run.b, run.k
    px, py, qx, qy = a.edges[i]
    dx, dy = qx - px, qy - py
    length2 = dx * dx + dy * dy
    stack: list[tuple[Fraction, Fraction, int]] = [(Fraction(0), Fraction(1), 0)]
    while stack:
        t0, t1, depth = stack.pop()
        run.tick()
        p0 = (px + t0 * dx, py + t0 * dy)
        p1 = (px + t1 * dx, py + t1 * dy)
        tm = (t0 + t1) / 2
        cx, cy = px + tm * dx, py + tm * dy
        nr = _near(b, k, cx, cy)
        if nr.inside and not _segment_meets_boundary(run, p0, p1):
            continue  # the piece lies inside B
        piece_u2 = max(_rat(_dseg2(b, nr.edge, p0[0], p0[1])[0]), _rat(_dseg2(b, nr.edge, p1[0], p1[1])[0]))
        if depth == 0:
            piece_u2 = min(piece_u2, u2)
        if _cmp(piece_u2, run.best.f2) <= 0:
            continue
        if _lipschitz_prunes(run, (t1 - t0) ** 2 * length2 / 4, nr.f2):
            continue
        edges, verts = _features_near_segment(run, p0, p1, piece_u2)
        if len(edges) + len(verts) > _LEAF_FEATURES_1D and depth < _MAX_DEPTH:
            stack.append((t0, tm, depth + 1))
            stack.append((tm, t1, depth + 1))
            continue
        _edge_leaf(run, (px, py), (dx, dy), t0, t1, edges, verts)


def _segment_meets_boundary(run: _Run, p: tuple[Rat, Rat], q: tuple[Rat, Rat]) -> bool:
    b, k = run.b, run.k
    xlo, _ = _to_orig_iv(min(p[0], q[0]), k)
    ylo, _ = _to_orig_iv(min(p[1], q[1]), k)
    _, xhi = _to_orig_iv(max(p[0], q[0]), k)
    _, yhi = _to_orig_iv(max(p[1], q[1]), k)
    return any(_seg_seg_dist2(p, q, b, e) == 0 for e in _query(b, xlo, ylo, xhi, yhi))


_Quad = tuple[Rat, Rat, Rat, Rat | None, Rat | None]


def _edge_leaf(
    run: _Run,
    p: tuple[int, int],
    d: tuple[int, int],
    t0: Fraction,
    t1: Fraction,
    edges: list[int],
    verts: list[tuple[int, int]],
) -> None:
    b = run.b
    (px, py), (dx, dy) = p, d
    # Each feature's squared distance along the edge: c2·t² + c1·t + c0, valid for lo ≤ t ≤ hi.
    feats: list[_Quad] = []
    for vx, vy in verts:
        wx, wy = px - vx, py - vy
        feats.append((dx * dx + dy * dy, 2 * (dx * wx + dy * wy), wx * wx + wy * wy, None, None))
    ends: list[Rat] = []
    for e in edges:
        ux, uy, ex, ey = b.edges[e]
        mx, my = ex - ux, ey - uy
        n = b.norms[e]
        l0 = mx * (py - uy) - my * (px - ux)
        l1 = mx * dy - my * dx
        pi0 = (px - ux) * mx + (py - uy) * my
        pi1 = dx * mx + dy * my
        lo: Rat | None = None
        hi: Rat | None = None
        if pi1 == 0:
            if not 0 <= pi0 <= n:
                continue
        else:
            ta, tb = Fraction(-pi0, pi1), Fraction(n - pi0, pi1)
            lo, hi = min(ta, tb), max(ta, tb)
            if hi < t0 or lo > t1:
                continue
            ends.extend(t for t in (lo, hi) if t0 <= t <= t1)
        feats.append((Fraction(l1 * l1, n), Fraction(2 * l0 * l1, n), Fraction(l0 * l0, n), lo, hi))

    def valid(f: _Quad, t: Num) -> bool:
        return (f[3] is None or _cmp(t, f[3]) >= 0) and (f[4] is None or _cmp(t, f[4]) <= 0)

    def value(f: _Quad, t: Num) -> Num:
        return (f[0] * t + f[1]) * t + f[2]

    cands: list[tuple[Num, int]] = [(t, -1) for t in ends]
    for j1 in range(len(feats)):
        for j2 in range(j1 + 1, len(feats)):
            f, g = feats[j1], feats[j2]
            roots = _solve_quadratic(run.t, f[0] - g[0], f[1] - g[1], f[2] - g[2])
            for t in roots or ():
                if _cmp(t, t0) >= 0 and _cmp(t, t1) <= 0 and valid(f, t) and valid(g, t):
                    cands.append((t, j1))
    for t, j in cands:
        if j >= 0 and _cmp(value(feats[j], t), run.best.f2) <= 0:
            continue  # f(t) ≤ this feature's distance ≤ the best so far
        if any(valid(f, t) and _cmp(value(f, t), run.best.f2) <= 0 for f in feats):
            continue
        x, y = px + t * dx, py + t * dy
        nr = _near(b, run.k, x, y)
        if not nr.inside:
            run.offer(nr.f2, x, y, "edge")
