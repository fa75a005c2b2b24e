"""Phase 4 of R, local repair: a failing stretch of a ring replaced by the safety net (:func:`splice_ring`).

When neither greedy ring of a corridor verifies (and a small corridor holds no triangle either,
:mod:`._small_search`), :func:`._kernels.finish_all` removes the vertices the exact check flagged and
replaces each run of them by the stretch of the safety net R0 (the crack ring offset inward by ¼ pixel, always
a valid ring of the same corridor) between the pieces of its kept neighbours, joined with two splice vertices
at each end (``SRC_SPLICE``; the net's own vertices are ``SRC_NET``). The runs are widened until the spliced
ring verifies (status ``partial``); only a ring that cannot be spliced becomes R0 whole. This is what keeps
a failure local. It places points on the net and on kept edges, and shares nothing with the steps that
take vertices out of a valid ring (:mod:`._prune`, :mod:`._merge`).
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit
from mrm.geometry.reconstruct._base import _DX, _DY, SRC_NET, SRC_SPLICE


@leaf_njit(cache=True)
def _seg_point_in_rect(
    ax: float, ay: float, bx: float, by: float, rect: np.ndarray, k: int, frac: float
) -> tuple[float, float, bool]:  # pragma: no cover
    # A point of the segment [a, b] inside the open rectangle k, at fraction ``frac`` of the chord.
    t0 = 0.0
    t1 = 1.0
    for ax_ in range(2):
        o = ax if ax_ == 0 else ay
        d = (bx - ax) if ax_ == 0 else (by - ay)
        lo = float(rect[k, 2 * ax_])
        hi = float(rect[k, 2 * ax_ + 1])
        if d == 0.0:
            if not (lo < o < hi):
                return 0.0, 0.0, False
        else:
            ta = (lo - o) / d
            tb = (hi - o) / d
            if ta > tb:
                ta, tb = tb, ta
            t0 = max(t0, ta)
            t1 = min(t1, tb)
    if t1 <= t0:
        return 0.0, 0.0, False
    t = t0 + frac * (t1 - t0)
    return ax + t * (bx - ax), ay + t * (by - ay), True


@leaf_njit(cache=True)
def _net_crossing(
    r0: np.ndarray, r0t: np.ndarray, k: int, n: int, gp: np.ndarray, gdir: np.ndarray
) -> tuple[int, int, int]:  # pragma: no cover
    # Where the safety net crosses gate k (0 <= k < n; Q-units), and the index of the net vertex after it.
    m = r0t.size
    # first net vertex whose piece >= k (pieces of the net are 0 … n-1, non-decreasing)
    j = 0
    while j < m and r0t[j] < k:
        j += 1
    jp = (j - 1) % m
    jn = j % m
    g = k % n
    d = gdir[g]
    if d == 0 or d == 2:
        cx = gp[g, 0]
        cy = r0[jp, 1]
    else:
        cx = r0[jp, 0]
        cy = gp[g, 1]
    return cx, cy, jn


@njit(cache=True)
def splice_ring(
    ix: np.ndarray,
    iy: np.ndarray,
    vt: np.ndarray,
    vs: np.ndarray,
    remove: np.ndarray,
    r0: np.ndarray,
    r0t: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gdir: np.ndarray,
    kmax: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, bool]:  # pragma: no cover
    """Replace each maximal run of removed vertices by the safety net.

    The net is joined with two splice vertices at each end (one on the kept edge, one on the net, both in the
    same piece). Returns the new ring or False when a run cannot be spliced (too short a gap, everything
    removed).
    """
    n = gdir.size
    m = ix.size
    sc = 1 << kmax
    nr = r0t.size
    cap = m + 4 * m + nr * 2 + 8
    ox = np.empty(cap, np.int64)
    oy = np.empty(cap, np.int64)
    ot = np.empty(cap, np.int64)
    osrc = np.empty(cap, np.int64)
    # start at a kept vertex that follows a removed one (or just any kept one)
    start = -1
    for i in range(m):
        if not remove[i] and remove[(i - 1) % m]:
            start = i
            break
    if start < 0:
        return ox[:0], oy[:0], ot[:0], osrc[:0], False
    no = 0
    i = start
    cnt = 0
    while cnt < m:
        ii = i % m
        if not remove[ii]:
            t = vt[ii] + (n if ii < start else 0)
            ox[no] = ix[ii]
            oy[no] = iy[ii]
            ot[no] = t
            osrc[no] = vs[ii]
            no += 1
            i += 1
            cnt += 1
            continue
        # a run of removed vertices ii .. jj
        jj = i
        while remove[jj % m] and jj - i < m:
            jj += 1
        # kept u before, kept w after
        u = (i - 1) % m
        w = jj % m
        tu = ot[no - 1]
        r1 = ii
        r2 = (jj - 1) % m
        a = vt[r1] + (n if r1 < start else 0)
        b = vt[r2] + (n if r2 < start else 0)
        tw = vt[w] + (n if w < start else 0)
        if w == start:
            tw = vt[w] + n
        if b < a + 1:
            b = a + 1
        if not (tu < a and b < tw):
            return ox[:0], oy[:0], ot[:0], osrc[:0], False
        # Z1 on the kept edge u -> removed r1, inside piece a
        z1x, z1y, ok1 = _seg_point_in_rect(
            ix[u] / sc, iy[u] / sc, ix[r1] / sc, iy[r1] / sc, rect, a % n, 0.25
        )
        # Z4 on the kept edge removed r2 -> w, inside piece b
        z4x, z4y, ok4 = _seg_point_in_rect(
            ix[r2] / sc, iy[r2] / sc, ix[w] / sc, iy[w] / sc, rect, b % n, 0.75
        )
        if not (ok1 and ok4):
            return ox[:0], oy[:0], ot[:0], osrc[:0], False
        # Z2: the net's crossing of gate a+1, one eighth of a pixel back; Z3: crossing of gate b, 1/8 on
        c2x, c2y, j2 = _net_crossing(r0, r0t, (a + 1) % n, n, gp, gdir)
        c3x, c3y, j3 = _net_crossing(r0, r0t, b % n, n, gp, gdir)
        d2 = gdir[(a + 1) % n]
        d3 = gdir[b % n]
        half = sc // 2  # 1/8 pixel = 1/2 Q-unit
        z2x = c2x * sc - _DX[d2] * half
        z2y = c2y * sc - _DY[d2] * half
        z3x = c3x * sc + _DX[d3] * half
        z3y = c3y * sc + _DY[d3] * half
        ox[no] = int(np.round(z1x * sc))
        oy[no] = int(np.round(z1y * sc))
        ot[no] = a
        osrc[no] = SRC_SPLICE
        no += 1
        ox[no] = z2x
        oy[no] = z2y
        ot[no] = a
        osrc[no] = SRC_SPLICE
        no += 1
        # net vertices strictly between pieces a and b
        q = j2
        steps = 0
        while steps < nr:
            tq = r0t[q]
            # unwrap tq into (a, b)
            tu_ = tq
            while tu_ <= a:
                tu_ += n
            if tu_ >= b:
                break
            ox[no] = r0[q, 0] * sc
            oy[no] = r0[q, 1] * sc
            ot[no] = tu_
            osrc[no] = SRC_NET
            no += 1
            q = (q + 1) % nr
            steps += 1
        ox[no] = z3x
        oy[no] = z3y
        ot[no] = b
        osrc[no] = SRC_SPLICE
        no += 1
        ox[no] = int(np.round(z4x * sc))
        oy[no] = int(np.round(z4y * sc))
        ot[no] = b
        osrc[no] = SRC_SPLICE
        no += 1
        _ = j3
        cnt += jj - i
        i = jj
    return ox[:no], oy[:no], ot[:no], osrc[:no], True
