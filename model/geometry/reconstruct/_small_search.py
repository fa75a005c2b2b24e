"""Phase 4 of R: the window bound, and the searches of small corridors for a ring of three or four vertices.

* :func:`window_bound`: the fewest windows (runs of gates one line crosses, from the reach table) covering one
  lap of the corridor, a lower bound on the vertices of any of its rings (ADR 0022).
  :func:`._kernels.finish_all` computes it once per verified ring and tries relinking (:mod:`._relink`), the
  search below and the minimum-link ring (:mod:`._minlink`) only on rings still above it.
* :func:`small_polygon`: on a verified ring of a corridor of at most ``_SMALL_POLY`` pieces, a ring of 3 or 4
  vertices (the fewest its windows allow), the vertices between the two enumerated ones placed as merging
  places them (:mod:`._merge`).
* :func:`small_triangle`: where no greedy ring verified, on a corridor of at most ``_SMALL`` pieces, a search
  for a triangle among nine candidate points per piece (a 1 × 3 bar under ``gauss``), tried before the net
  splice (:mod:`._splice`).
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit
from mrm.geometry.reconstruct._check import edge_ok, gate_rays, rays_admit, verify_ring
from mrm.geometry.reconstruct._merge import _cone_bwd, _cone_fwd, _merge_cones


@njit(cache=True)
def small_triangle(
    rect: np.ndarray, gp: np.ndarray, gq: np.ndarray, gdir: np.ndarray, reach: np.ndarray, kmax: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:  # pragma: no cover
    """For a small corridor, look for a triangle among a few candidate points per piece.

    Candidates are each piece's centre, side midpoints and corners, inset by 1/16 pixel; the search is
    pruned by the reach table; exact checks throughout.
    """
    n = gdir.size
    sc = 1 << kmax
    q = sc // 4  # 1/16 pixel = 1/4 Q-unit
    nc = 9 * n
    cx = np.empty(nc, np.int64)
    cy = np.empty(nc, np.int64)
    ct = np.empty(nc, np.int64)
    k = 0
    for t in range(n):
        x0 = rect[t, 0] * sc + q
        x1 = rect[t, 1] * sc - q
        y0 = rect[t, 2] * sc + q
        y1 = rect[t, 3] * sc - q
        xm = (rect[t, 0] + rect[t, 1]) * sc // 2
        ym = (rect[t, 2] + rect[t, 3]) * sc // 2
        for a in range(3):
            xa = x0 if a == 0 else (xm if a == 1 else x1)
            for b in range(3):
                cx[k] = xa
                cy[k] = y0 if b == 0 else (ym if b == 1 else y1)
                ct[k] = t
                k += 1
    valid = np.full((nc, nc), -1, np.int8)  # edge i -> j with j's piece unwrapped after i's (memo)
    tx = np.empty(3, np.int64)
    ty = np.empty(3, np.int64)
    tt = np.empty(3, np.int64)
    bad = np.zeros(3, np.bool_)
    # piece triples first: three windows must cover the ring (reach), else no candidate can work
    for ta in range(n):
        for tb in range(ta + 1, min(ta + reach[ta], ta + n - 1) + 1):
            if tb >= n + ta:
                break
            for tc in range(tb + 1, min(tb + reach[tb % n], ta + n - 1) + 1):
                if tc + reach[tc % n] < ta + n:
                    continue
                for i in range(9 * ta, 9 * ta + 9):
                    for j in range(9 * (tb % n), 9 * (tb % n) + 9):
                        if valid[i, j] < 0:
                            valid[i, j] = (
                                1 if edge_ok(cx[i], cy[i], ta, cx[j], cy[j], tb, gp, gq, gdir, sc) else 0
                            )
                        if valid[i, j] == 0:
                            continue
                        for c in range(9 * (tc % n), 9 * (tc % n) + 9):
                            if valid[j, c] < 0:
                                valid[j, c] = (
                                    1 if edge_ok(cx[j], cy[j], tb, cx[c], cy[c], tc, gp, gq, gdir, sc) else 0
                                )
                            if valid[j, c] == 0:
                                continue
                            if not edge_ok(cx[c], cy[c], tc, cx[i], cy[i], ta + n, gp, gq, gdir, sc):
                                continue
                            tx[0] = cx[i]
                            ty[0] = cy[i]
                            tt[0] = ta
                            tx[1] = cx[j]
                            ty[1] = cy[j]
                            tt[1] = tb
                            tx[2] = cx[c]
                            ty[2] = cy[c]
                            tt[2] = tc
                            if verify_ring(tx, ty, tt, rect, gp, gq, gdir, sc, bad):
                                return tx, ty, tt, True
    return tx, ty, tt, False


@leaf_njit(cache=True)
def _window_bound_walk(reach: np.ndarray, s0: int) -> int:  # pragma: no cover
    # window_bound by walking the greedy chain from every start of the window s0 … s0 + reach[s0].
    n = reach.size
    best = 1 << 30
    for s in range(s0, s0 + reach[s0] + 1):
        t = s
        c = 0
        while t < s + n and c < best:
            step = reach[t % n]
            if step <= 0:
                c = 1 << 30
                break
            t += step
            c += 1
        if c < best:
            best = c
    return best


@njit(cache=True)
def window_bound(reach: np.ndarray) -> int:  # pragma: no cover
    """A lower bound on the vertices of any ring of the corridor: the fewest windows covering one lap.

    An edge leaving a vertex in piece t ends in a piece at most t + reach[t] (reach is exact), and the
    pieces of consecutive vertices advance by one lap in total, so a ring of m vertices is a cyclic chain of
    m windows, each starting where the last one ends. Starts are tried across the longest window (every
    chain has a vertex there); the greedy longest jump is optimal for a fixed start.

    The chains of the starts soon land on a piece the chain of the first start visits, and from there follow
    it: that chain is walked once (far enough for every start's lap) with each piece's index on it, and a
    later chain stops at the first piece it shares, its remaining count read by bisection on the first
    one's pieces. Same value as walking every chain to its end (:func:`_window_bound_walk`, kept for small
    corridors), which on a large ring with a long window cost (longest window) × (bound) steps: 194,000 on
    camera's outer ring, now about 5,000.
    """
    n = reach.size
    s0 = 0
    for i in range(n):
        if reach[i] > reach[s0]:
            s0 = i
    r0 = reach[s0]
    if r0 <= 0 or n <= 64:
        return _window_bound_walk(reach, s0)
    lim = s0 + r0 + n  # the last start's lap ends here
    idx = np.full(r0 + 2 * n + 1, -1, np.int64)  # piece − s0 → its index on the first chain, −1: off it
    pos = np.empty(r0 + n + 2, np.int64)
    t = s0
    last = 0
    while True:
        pos[last] = t
        idx[t - s0] = last
        if t >= lim:
            break
        step = reach[t % n]
        if step <= 0:
            break  # a dead end: no chain through it reaches its lap
        t += step
        last += 1
    best = 1 << 30
    for s in range(s0, s0 + r0 + 1):
        tgt = s + n
        t = s
        c = 0
        while t < tgt and c < best:
            i = idx[t - s0]
            if i >= 0:
                # from here on the first chain: its first piece at or past tgt
                lo = i
                hi = last + 1
                while lo < hi:
                    mid = (lo + hi) // 2
                    if pos[mid] >= tgt:
                        hi = mid
                    else:
                        lo = mid + 1
                c = 1 << 30 if lo > last else c + lo - i
                break
            step = reach[t % n]
            if step <= 0:
                c = 1 << 30
                break
            t += step
            c += 1
        if c < best:
            best = c
    return best


@njit(cache=True)
def small_polygon(
    rect: np.ndarray, gp: np.ndarray, gq: np.ndarray, gdir: np.ndarray, reach: np.ndarray, kmax: int, nv: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:  # pragma: no cover
    """For a small corridor, look for a ring of ``nv`` = 3 or 4 vertices (the fewest the windows allow).

    Vertex 0 lies in the shortest window (every ring has a vertex in each window, since i + reach[i] never
    decreases). Vertices 0 and 2 are taken among nine points per piece (a 3 × 3 grid at 1/6, 1/2, 5/6 of
    the piece); each vertex between them is placed as by :func:`._merge._merge_pair` (the centre of the
    region both neighbours see, searched in every piece between them; each candidate's cone of rays is
    computed once per piece or piece pair, :func:`._merge._merge_cones`), so only two of the vertices are
    enumerated. For a triangle the edge 2 → 0 is checked directly. Piece pairs are pruned by the reach table;
    the result is verified exactly (:func:`verify_ring`).
    """
    n = gdir.size
    sc = 1 << kmax
    per = 9
    cx = np.empty(per * n, np.int64)
    cy = np.empty(per * n, np.int64)
    k = 0
    for t in range(n):
        x0 = rect[t, 0] * sc
        x1 = rect[t, 1] * sc
        y0 = rect[t, 2] * sc
        y1 = rect[t, 3] * sc
        for a in range(3):
            for b in range(3):
                cx[k] = x0 + (x1 - x0) * (2 * a + 1) // 6
                cy[k] = y0 + (y1 - y0) * (2 * b + 1) // 6
                k += 1
    # cones of the candidates (rows): from vertex 0 forward (ai) and, one lap later, back (bi), computed
    # once per piece of vertex 0; from vertex 2 back (bc) and forward (ac), once per piece pair
    ai = np.empty((per, 4, n + 1), np.float64)
    oai = np.zeros((per, n + 1), np.bool_)
    bi = np.empty((per, 4, n + 1), np.float64)
    obi = np.zeros((per, n + 1), np.bool_)
    ac = np.empty((per, 4, n + 1), np.float64)
    oac = np.zeros((per, n + 1), np.bool_)
    bc = np.empty((per, 4, n + 1), np.float64)
    obc = np.zeros((per, n + 1), np.bool_)
    fsc = float(sc)
    poly = np.empty((4, 16), np.float64)
    tx = np.empty(nv, np.int64)
    ty = np.empty(nv, np.int64)
    tt = np.empty(nv, np.int64)
    bad = np.zeros(nv, np.bool_)
    rays = np.empty((per, 4), np.int64)
    raysok = np.zeros(per, np.bool_)
    # every window chain has a vertex in every window (i + reach[i] never decreases): start in the shortest
    smin = 0
    for i in range(n):
        if reach[i] < reach[smin]:
            smin = i
    for ta0 in range(smin, smin + reach[smin] + 1):
        ta = ta0 % n
        # nv windows from ta must close the lap (the greedy longest jumps go farthest): else no ring
        # starts here, and the cones of its candidates are not worth computing
        far = ta
        for _j in range(nv):
            far += max(reach[far % n], 0)
        if far < ta + n:
            continue
        for u in range(per):
            _cone_fwd(cx[per * ta + u], cy[per * ta + u], ta, n - 1, gp, gq, fsc, ai, oai, u)
            if nv == 4:
                _cone_bwd(cx[per * ta + u], cy[per * ta + u], ta + n, n, gp, gq, fsc, bi, obi, u)
        for tc in range(ta, ta + n):
            # a window chain ta -> tb -> tc, then tc -> ta + n directly (triangle) or through td (quad)
            okb = False
            for tb in range(ta, min(tc, ta + reach[ta]) + 1):
                if tb + reach[tb % n] >= tc:
                    okb = True
                    break
            if not okb:
                continue
            if nv == 3:
                if tc + reach[tc % n] < ta + n:
                    continue
            else:
                okd = False
                for td in range(tc, min(ta + n, tc + reach[tc % n]) + 1):
                    if td + reach[td % n] >= ta + n:
                        okd = True
                        break
                if not okd:
                    continue
            for v in range(per):
                c = per * (tc % n) + v
                _cone_bwd(cx[c], cy[c], tc, tc - ta, gp, gq, fsc, bc, obc, v)
                if nv == 4:
                    _cone_fwd(cx[c], cy[c], tc, ta + n - tc, gp, gq, fsc, ac, oac, v)
            if nv == 3:
                # the tightest rays from each candidate through the gates of the closing edge: a quick
                # necessary test before its exact check (gate_rays, as _place does)
                for v in range(per):
                    c = per * (tc % n) + v
                    r0x, r0y, r1x, r1y, rok = gate_rays(cx[c], cy[c], tc, ta + n, True, gp, gq, sc)
                    rays[v, 0] = r0x
                    rays[v, 1] = r0y
                    rays[v, 2] = r1x
                    rays[v, 3] = r1y
                    raysok[v] = rok
            for i in range(per * ta, per * ta + per):
                for c in range(per * (tc % n), per * (tc % n) + per):
                    if nv == 3:
                        v = c - per * (tc % n)
                        if raysok[v] and not rays_admit(
                            cx[c], cy[c], rays[v, 0], rays[v, 1], rays[v, 2], rays[v, 3], True, cx[i], cy[i]
                        ):
                            continue
                        if not edge_ok(cx[c], cy[c], tc, cx[i], cy[i], ta + n, gp, gq, gdir, sc):
                            continue
                    wx, wy, tw, ok = _merge_cones(
                        cx[i],
                        cy[i],
                        ta,
                        cx[c],
                        cy[c],
                        tc,
                        ta,
                        tc,
                        rect,
                        gp,
                        gq,
                        gdir,
                        kmax,
                        ai,
                        oai,
                        i - per * ta,
                        bc,
                        obc,
                        c - per * (tc % n),
                        poly,
                    )
                    if not ok:
                        continue
                    tx[0] = cx[i]
                    ty[0] = cy[i]
                    tt[0] = ta
                    tx[1] = wx
                    ty[1] = wy
                    tt[1] = tw
                    tx[2] = cx[c]
                    ty[2] = cy[c]
                    tt[2] = tc
                    if nv == 4:
                        ux, uy, tu, oku = _merge_cones(
                            cx[c],
                            cy[c],
                            tc,
                            cx[i],
                            cy[i],
                            ta + n,
                            tc,
                            ta + n,
                            rect,
                            gp,
                            gq,
                            gdir,
                            kmax,
                            ac,
                            oac,
                            c - per * (tc % n),
                            bi,
                            obi,
                            i - per * ta,
                            poly,
                        )
                        if not oku:
                            continue
                        tx[3] = ux
                        ty[3] = uy
                        tt[3] = tu
                    if verify_ring(tx, ty, tt, rect, gp, gq, gdir, sc, bad):
                        return tx, ty, tt, True
    return tx, ty, tt, False
