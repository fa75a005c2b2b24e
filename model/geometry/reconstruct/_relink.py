"""Phase 4 of R: relinking, four consecutive vertices replaced by three (:func:`relink_ring`, ADR 0022).

It undoes what merging (:mod:`._merge`) cannot: two vertices close together that one vertex would replace
only if both neighbours moved as well. :func:`._kernels.finish_all` relinks verified rings of 6 …
``_RELINK_MAX`` vertices that are still above their window bound (:func:`._small_search.window_bound`). The
middle vertex is placed by the merge search (:func:`._merge._merge_cones`, on cones computed once per
candidate, ADR 0023); :func:`_sees_piece` (that search's first clips alone) rules out the pairs of
candidates whose cones share no piece.
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit
from mrm.geometry.reconstruct._base import SRC_LINES
from mrm.geometry.reconstruct._check import _in_piece, edge_ok, gate_rays, rays_admit, verify_ring
from mrm.geometry.reconstruct._merge import _clip_poly, _cone_bwd, _cone_fwd, _merge_cones


@leaf_njit(cache=True)
def _unwrap6(t: np.ndarray, i: int, n: int, jj: np.ndarray, tt: np.ndarray) -> None:  # pragma: no cover
    # Indices of vertices i-2 … i+3 (cyclic) and their pieces unwrapped from the first.
    m = t.size
    for d in range(6):
        j = (i - 2 + d) % m
        jj[d] = j
        tt[d] = t[j]
        if d > 0:
            while tt[d] < tt[d - 1]:
                tt[d] += n


@leaf_njit(cache=True)
def _sees_piece(
    rect: np.ndarray,
    r: int,
    ox: float,
    oy: float,
    cone: np.ndarray,
    row: int,
    k: int,
    fwd: bool,
    poly: np.ndarray,
) -> bool:  # pragma: no cover
    # Whether piece r meets the cone cone[row, :, k] from (ox, oy) (Q-units): the first clips of
    # :func:`._merge._merge_cones`, alone. Used to skip pairs of candidates whose own sides already leave
    # nothing.
    if k == 0:
        return True
    pxs = poly[0]
    pys = poly[1]
    qxs = poly[2]
    qys = poly[3]
    pxs[0] = rect[r, 0]
    pys[0] = rect[r, 2]
    pxs[1] = rect[r, 1]
    pys[1] = rect[r, 2]
    pxs[2] = rect[r, 1]
    pys[2] = rect[r, 3]
    pxs[3] = rect[r, 0]
    pys[3] = rect[r, 3]
    sg = -1.0 if fwd else 1.0
    nv = _clip_poly(pxs, pys, 4, ox, oy, ox + cone[row, 0, k], oy + cone[row, 1, k], sg, qxs, qys)
    if nv >= 3:
        nv = _clip_poly(qxs, qys, nv, ox, oy, ox + cone[row, 2, k], oy + cone[row, 3, k], -sg, pxs, pys)
    return nv >= 3


@njit(cache=True)
def relink_ring(
    ix: np.ndarray,
    iy: np.ndarray,
    vt: np.ndarray,
    vs: np.ndarray,
    vl: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    reach: np.ndarray,
    kmax: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """Replace four consecutive vertices by three where the two outer neighbours allow it.

    For vertices a, c1, v, v', c3, b: c1 is moved among its own position and nine points of its piece that
    a sees, c3 likewise towards b, and one point w replacing v, v' is placed by
    :func:`._merge._merge_pair`. This undoes what :func:`._merge.merge_ring` cannot (two vertices close
    together that one vertex would replace only if both neighbours moved); ``reach`` (the ring's reach table)
    rules out most positions at once. Every change is verified exactly on the whole ring, so the ring stays
    valid; the scan stops after a lap without change.
    """
    n = gdir.size
    sc = 1 << kmax
    fsc = float(sc)
    m = ix.size
    if m < 6:
        return ix, iy, vt, vs, vl
    x = ix.copy()
    y = iy.copy()
    t = vt.copy()
    s = vs.copy()
    ln = vl.copy()
    # the cones of the (at most ten) candidates of each side, computed once per position
    ccap = 16
    cone_a = np.empty((10, 4, ccap), np.float64)
    ok_a = np.zeros((10, ccap), np.bool_)
    cone_b = np.empty((10, 4, ccap), np.float64)
    ok_b = np.zeros((10, ccap), np.bool_)
    live_a = np.zeros(10, np.bool_)
    mask_a = np.zeros(10, np.int64)
    mask_b = np.zeros(10, np.int64)
    poly = np.empty((4, 16), np.float64)
    jj = np.empty(6, np.int64)
    tt = np.empty(6, np.int64)
    c1x = np.empty(10, np.int64)
    c1y = np.empty(10, np.int64)
    c3x = np.empty(10, np.int64)
    c3y = np.empty(10, np.int64)
    nx = np.empty(m, np.int64)
    ny = np.empty(m, np.int64)
    nt = np.empty(m, np.int64)
    ns = np.empty(m, np.int64)
    nl = np.empty(m, np.int64)
    bad = np.zeros(m, np.bool_)
    i = 0
    fails = 0
    steps = 0
    while m >= 6 and fails < m and steps < 4 * ix.size:
        steps += 1
        _unwrap6(t[:m], i, n, jj, tt)
        ok = False
        # The reach table first (exact, and far cheaper than the candidates): c1 stays in piece tt[1], c3
        # in tt[4], w goes to a piece of tt[2] … tt[3], and an edge from piece u ends at most at
        # u + reach[u], which never decreases with u; so w's farthest allowed piece is the one to test.
        wfar = min(tt[3], tt[1] + reach[tt[1] % n])
        if tt[5] - tt[0] < n and wfar >= tt[2] and wfar + reach[wfar % n] >= tt[4]:
            ax = x[jj[0]]
            ay = y[jj[0]]
            bx = x[jj[5]]
            by = y[jj[5]]
            # candidates for c1 (seen from a) and c3 (seeing b): the current point first, then a 3 x 3 grid
            n1 = 0
            n3 = 0
            alx, aly, arx, ary, fa = gate_rays(ax, ay, tt[0], tt[1], True, gp, gq, sc)
            blx, bly, brx, bry, fb = gate_rays(bx, by, tt[4], tt[5], False, gp, gq, sc)
            for side in range(2):
                d = 1 if side == 0 else 4
                r = tt[d] % n
                for k in range(10):
                    if k == 0:
                        px = x[jj[d]]
                        py = y[jj[d]]
                    else:
                        a_ = (k - 1) // 3
                        b_ = (k - 1) % 3
                        px = rect[r, 0] * sc + (rect[r, 1] - rect[r, 0]) * sc * (2 * a_ + 1) // 6
                        py = rect[r, 2] * sc + (rect[r, 3] - rect[r, 2]) * sc * (2 * b_ + 1) // 6
                        if not _in_piece(rect, r, px, py, sc):
                            continue
                    if side == 0:
                        if fa and not rays_admit(ax, ay, alx, aly, arx, ary, True, px, py):
                            continue
                        if edge_ok(ax, ay, tt[0], px, py, tt[1], gp, gq, gdir, sc):
                            c1x[n1] = px
                            c1y[n1] = py
                            n1 += 1
                    elif (not fb or rays_admit(bx, by, blx, bly, brx, bry, False, px, py)) and edge_ok(
                        px, py, tt[4], bx, by, tt[5], gp, gq, gdir, sc
                    ):
                        c3x[n3] = px
                        c3y[n3] = py
                        n3 += 1
            span = tt[4] - tt[1]
            if span + 1 > ccap:
                ccap = 2 * (span + 1)
                cone_a = np.empty((10, 4, ccap), np.float64)
                ok_a = np.zeros((10, ccap), np.bool_)
                cone_b = np.empty((10, 4, ccap), np.float64)
                ok_b = np.zeros((10, ccap), np.bool_)
            any_a = False
            for u in range(n1):
                _cone_fwd(c1x[u], c1y[u], tt[1], tt[3] - tt[1], gp, gq, fsc, cone_a, ok_a, u)
                # w needs a piece tt[2] … tt[3] that c1 sees (the cone is open up to it): else skip c1
                live_a[u] = tt[2] == tt[1] or ok_a[u, tt[2] - tt[1]]
                any_a = any_a or live_a[u]
            if any_a:
                for v in range(n3):
                    _cone_bwd(c3x[v], c3y[v], tt[4], tt[4] - tt[2], gp, gq, fsc, cone_b, ok_b, v)
            # which pieces tt[2] … tt[3] each candidate's cone meets (bit per piece): a pair can only work
            # in a piece both meet
            nt_ = tt[3] - tt[2] + 1
            for u in range(n1):
                mask_a[u] = -1
                if live_a[u] and nt_ <= 62:
                    mask_a[u] = 0
                    for e in range(nt_):
                        te = tt[2] + e
                        ka = te - tt[1]
                        if (ka == 0 or ok_a[u, ka]) and _sees_piece(
                            rect, te % n, c1x[u] / fsc, c1y[u] / fsc, cone_a, u, ka, True, poly
                        ):
                            mask_a[u] |= 1 << e
            for v in range(n3):
                mask_b[v] = -1
                if any_a and nt_ <= 62:
                    mask_b[v] = 0
                    for e in range(nt_):
                        te = tt[2] + e
                        kb = tt[4] - te
                        if (kb == 0 or ok_b[v, kb]) and _sees_piece(
                            rect, te % n, c3x[v] / fsc, c3y[v] / fsc, cone_b, v, kb, False, poly
                        ):
                            mask_b[v] |= 1 << e
            for u in range(n1):
                if ok:
                    break
                if not live_a[u]:
                    continue
                for v in range(n3):
                    if tt[4] > tt[3] and not ok_b[v, tt[4] - tt[3]]:
                        continue  # c3 sees no piece tt[2] … tt[3]
                    if (mask_a[u] & mask_b[v]) == 0:
                        continue
                    wx, wy, tw, okw = _merge_cones(
                        c1x[u],
                        c1y[u],
                        tt[1],
                        c3x[v],
                        c3y[v],
                        tt[4],
                        tt[2],
                        tt[3],
                        rect,
                        gp,
                        gq,
                        gdir,
                        kmax,
                        cone_a,
                        ok_a,
                        u,
                        cone_b,
                        ok_b,
                        v,
                        poly,
                    )
                    if not okw:
                        continue
                    # the new ring from b round to a, then c1, w, c3 (pieces unwrapped from b's)
                    q = 0
                    j = jj[5]
                    base = tt[5]
                    prev = tt[5]
                    while True:
                        pj = t[j]
                        while pj < prev:
                            pj += n
                        nx[q] = x[j]
                        ny[q] = y[j]
                        nt[q] = pj
                        ns[q] = s[j]
                        nl[q] = ln[j]
                        prev = pj
                        q += 1
                        if j == jj[0]:
                            break
                        j = (j + 1) % m
                    lap = prev - tt[0]  # a one lap later, relative to its position in tt
                    nx[q] = c1x[u]
                    ny[q] = c1y[u]
                    nt[q] = tt[1] + lap
                    nx[q + 1] = wx
                    ny[q + 1] = wy
                    nt[q + 1] = tw + lap
                    nx[q + 2] = c3x[v]
                    ny[q + 2] = c3y[v]
                    nt[q + 2] = tt[4] + lap
                    for e in range(3):
                        ns[q + e] = SRC_LINES
                        nl[q + e] = -1
                    q += 3
                    off = (base // n) * n
                    for e in range(q):
                        nt[e] -= off
                    if verify_ring(nx[:q], ny[:q], nt[:q], rect, gp, gq, gdir, sc, bad[:q]):
                        for e in range(q):
                            x[e] = nx[e]
                            y[e] = ny[e]
                            t[e] = nt[e]
                            s[e] = ns[e]
                            ln[e] = nl[e]
                        m = q
                        ok = True
                        break
        if ok:
            fails = 0
            i = 0
        else:
            fails += 1
            i = (i + 1) % m
    if m == ix.size:
        return ix, iy, vt, vs, vl
    return x[:m].copy(), y[:m].copy(), t[:m].copy(), s[:m].copy(), ln[:m].copy()
