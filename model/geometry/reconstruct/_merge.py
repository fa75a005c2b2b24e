"""Phase 4 of R: merging, two consecutive vertices replaced by one both neighbours see (:func:`merge_ring`).

The new vertex w of a pair between a (in piece ta) and b (in piece tb) is searched in the pieces of the pair.
From a, w must lie in the cone of rays through the gates after ta up to w's piece; from b, in the cone back
through the gates up to tb. Each cone is kept as its two tightest rays and whether it is still open
(:func:`_cone_fwd`, :func:`_cone_bwd`); a piece clipped by the four rays (:func:`_clip_poly`) gives a centre,
snapped to the coarsest dyadic grid where both edges pass the exact checks (:func:`_merge_cones`).
:func:`_merge_pair` computes both cones and places w. :func:`._kernels.finish_all` merges every pruned ring
(:mod:`._prune`).

This placement of one vertex between two fixed neighbours is also what relinking (:mod:`._relink`) and the
small-corridor search (:mod:`._small_search`) build on: they compute each candidate's cones once and call
:func:`_merge_cones` (ADR 0023).
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit
from mrm.geometry.reconstruct._base import SRC_LINES
from mrm.geometry.reconstruct._check import _in_piece, edge_ok, verify_ring


@leaf_njit(cache=True)
def _clip_poly(
    px: np.ndarray,
    py: np.ndarray,
    n: int,
    ax: float,
    ay: float,
    bx: float,
    by: float,
    sign: float,
    ox: np.ndarray,
    oy: np.ndarray,
) -> int:  # pragma: no cover
    # Keep the part of polygon (px, py)[:n] where sign * orient(a, b, w) > 0 (float; a margin is enforced
    # later by the exact checks). Returns the new vertex count, written to (ox, oy).
    m = 0
    for i in range(n):
        j = i + 1 if i + 1 < n else 0
        fi = sign * ((bx - ax) * (py[i] - ay) - (by - ay) * (px[i] - ax))
        fj = sign * ((bx - ax) * (py[j] - ay) - (by - ay) * (px[j] - ax))
        if fi > 0:
            ox[m] = px[i]
            oy[m] = py[i]
            m += 1
        if (fi > 0) != (fj > 0) and fi != fj:
            t = fi / (fi - fj)
            ox[m] = px[i] + t * (px[j] - px[i])
            oy[m] = py[i] + t * (py[j] - py[i])
            m += 1
    return m


@leaf_njit(cache=True)
def _cone_fwd(
    ax: int,
    ay: int,
    ta: int,
    span: int,
    gp: np.ndarray,
    gq: np.ndarray,
    sc: float,
    cone: np.ndarray,
    okc: np.ndarray,
    row: int,
) -> None:  # pragma: no cover
    # The cone of rays from a (in piece ta, scaled units) through the gates ta+1 … ta+k, for k = 1 … span:
    # its two tightest rays in cone[row, :, k] (left x, y, right x, y; Q-units relative to a) and in
    # okc[row, k] whether it is still open (a prefix property: once closed it stays closed).
    n = gp.shape[0]
    fax = ax / sc
    fay = ay / sc
    lx = 0.0
    ly = 0.0
    rx = 0.0
    ry = 0.0
    ok = True
    for k in range(1, span + 1):
        g = (ta + k) % n
        px_ = gp[g, 0] - fax
        py_ = gp[g, 1] - fay
        qx_ = gq[g, 0] - fax
        qy_ = gq[g, 1] - fay
        if k == 1:
            lx, ly, rx, ry = px_, py_, qx_, qy_
        else:
            if lx * py_ - ly * px_ < 0:  # P ray clockwise of the left ray: tighter
                lx, ly = px_, py_
            if rx * qy_ - ry * qx_ > 0:  # Q ray counter-clockwise of the right ray: tighter
                rx, ry = qx_, qy_
        if ok and rx * ly - ry * lx <= 0:  # the left ray must stay counter-clockwise of the right ray
            ok = False
        cone[row, 0, k] = lx
        cone[row, 1, k] = ly
        cone[row, 2, k] = rx
        cone[row, 3, k] = ry
        okc[row, k] = ok


@leaf_njit(cache=True)
def _cone_bwd(
    bx: int,
    by: int,
    tb: int,
    span: int,
    gp: np.ndarray,
    gq: np.ndarray,
    sc: float,
    cone: np.ndarray,
    okc: np.ndarray,
    row: int,
) -> None:  # pragma: no cover
    # The cone of rays from b (in piece tb) looking back through the gates tb−k+1 … tb, k = 1 … span: a
    # point w there sees b through those gates when it is left of every b→P and right of every b→Q.
    n = gp.shape[0]
    fbx = bx / sc
    fby = by / sc
    lx = 0.0
    ly = 0.0
    rx = 0.0
    ry = 0.0
    ok = True
    for k in range(1, span + 1):
        g = (tb - k + 1) % n
        px_ = gp[g, 0] - fbx
        py_ = gp[g, 1] - fby
        qx_ = gq[g, 0] - fbx
        qy_ = gq[g, 1] - fby
        if k == 1:
            lx, ly, rx, ry = px_, py_, qx_, qy_
        else:
            if lx * py_ - ly * px_ > 0:  # w left of every b→P: the most counter-clockwise P ray binds
                lx, ly = px_, py_
            if rx * qy_ - ry * qx_ < 0:
                rx, ry = qx_, qy_
        if ok and lx * ry - ly * rx <= 0:
            ok = False
        cone[row, 0, k] = lx
        cone[row, 1, k] = ly
        cone[row, 2, k] = rx
        cone[row, 3, k] = ry
        okc[row, k] = ok


@leaf_njit(cache=True)
def _merge_cones(
    ax: int,
    ay: int,
    ta: int,
    bx: int,
    by: int,
    tb: int,
    t0: int,
    t1: int,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: int,
    ca: np.ndarray,
    oka: np.ndarray,
    ra: int,
    cb: np.ndarray,
    okb: np.ndarray,
    rb: int,
    poly: np.ndarray,
) -> tuple[int, int, int, bool]:  # pragma: no cover
    # :func:`_merge_pair` with the two cones already computed (rows ra of ca / oka from a, at least up to
    # k = t1 − ta; rows rb of cb / okb from b, at least up to k = tb − t0).
    n = gdir.size
    sc = float(1 << kmax)
    isc = 1 << kmax
    fax = ax / sc
    fay = ay / sc
    fbx = bx / sc
    fby = by / sc
    pxs = poly[0]
    pys = poly[1]
    qxs = poly[2]
    qys = poly[3]
    for t in range(t0, t1 + 1):
        ka = t - ta
        kb = tb - t
        if (ka > 0 and not oka[ra, ka]) or (kb > 0 and not okb[rb, kb]):
            continue
        r = t % n
        pxs[0] = rect[r, 0]
        pys[0] = rect[r, 2]
        pxs[1] = rect[r, 1]
        pys[1] = rect[r, 2]
        pxs[2] = rect[r, 1]
        pys[2] = rect[r, 3]
        pxs[3] = rect[r, 0]
        pys[3] = rect[r, 3]
        nv = 4
        if ka > 0:
            nv = _clip_poly(pxs, pys, nv, fax, fay, fax + ca[ra, 0, ka], fay + ca[ra, 1, ka], -1.0, qxs, qys)
            if nv >= 3:
                nv = _clip_poly(
                    qxs, qys, nv, fax, fay, fax + ca[ra, 2, ka], fay + ca[ra, 3, ka], 1.0, pxs, pys
                )
        if nv >= 3 and kb > 0:
            nv = _clip_poly(pxs, pys, nv, fbx, fby, fbx + cb[rb, 0, kb], fby + cb[rb, 1, kb], 1.0, qxs, qys)
            if nv >= 3:
                nv = _clip_poly(
                    qxs, qys, nv, fbx, fby, fbx + cb[rb, 2, kb], fby + cb[rb, 3, kb], -1.0, pxs, pys
                )
        if nv < 3:
            continue
        cx = 0.0
        cy = 0.0
        for i in range(nv):
            cx += pxs[i]
            cy += pys[i]
        cx /= nv
        cy /= nv
        # start at a grid four times finer than the region's extent: coarser ones would miss it
        ext = 0.0
        for i in range(nv):
            ext = max(ext, abs(pxs[i] - cx), abs(pys[i] - cy))
        k0 = 0
        while k0 < kmax and float(1 << k0) * ext < 4.0:
            k0 += 1
        for k in range(k0, kmax + 1):
            f = float(1 << k)
            mul = 1 << (kmax - k)
            x = int(np.round(cx * f)) * mul
            y = int(np.round(cy * f)) * mul
            if not _in_piece(rect, r, x, y, isc):
                continue
            if not edge_ok(ax, ay, ta, x, y, t, gp, gq, gdir, isc):
                continue
            if not edge_ok(x, y, t, bx, by, tb, gp, gq, gdir, isc):
                continue
            return x, y, t, True
    return 0, 0, 0, False


@leaf_njit(cache=True)
def _merge_pair(
    ax: int,
    ay: int,
    ta: int,
    bx: int,
    by: int,
    tb: int,
    t0: int,
    t1: int,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: int,
    cone: np.ndarray,
    okc: np.ndarray,
    poly: np.ndarray,
) -> tuple[int, int, int, bool]:  # pragma: no cover
    # A dyadic point w in a piece t0 <= t <= t1 such that a -> w and w -> b are valid edges (a in piece ta,
    # b in piece tb). From a, w must lie in the cone of rays through the gates ta+1 … t (right of every
    # a→P, left of every a→Q); from b, in the cone through the gates t+1 … tb (left of every b→P, right of
    # every b→Q). Both cones are kept as their two tightest rays, so each piece costs O(1) on top of one
    # sweep; the piece cut by the four rays gives a centre, snapped and checked exactly. ``cone`` (2, 4, ≥
    # span + 1), ``okc`` (2, ≥ span + 1) and ``poly`` (4, 16) are scratch.
    sc = float(1 << kmax)
    _cone_fwd(ax, ay, ta, t1 - ta, gp, gq, sc, cone, okc, 0)
    _cone_bwd(bx, by, tb, tb - t0, gp, gq, sc, cone, okc, 1)
    return _merge_cones(
        ax, ay, ta, bx, by, tb, t0, t1, rect, gp, gq, gdir, kmax, cone, okc, 0, cone, okc, 1, poly
    )


@njit(cache=True)
def merge_ring(
    ix: np.ndarray,
    iy: np.ndarray,
    vt: np.ndarray,
    vs: np.ndarray,
    vl: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """Replace pairs of consecutive vertices by one wherever both neighbours can reach a common point.

    The point is searched in the pieces of the pair (exact checks), until no pair merges; the input is kept
    if the result fails to verify.
    """
    n = gdir.size
    m = ix.size
    x = ix.copy()
    y = iy.copy()
    t = vt.copy()
    s = vs.copy()
    ln = vl.copy()
    cone = np.empty((2, 4, n + 1), np.float64)
    okc = np.zeros((2, n + 1), np.bool_)
    poly = np.empty((4, 16), np.float64)
    # Which vertex each slot holds (a merged vertex is a new one), and for each vertex v the pair tried
    # in the first round that failed: (v's predecessor, v's successor, the one after). The second round
    # meets most pairs again with the same four vertices, only a lap further round (pieces shifted by n),
    # which _merge_pair does not see: it fails again, so it is not tried (85 % of the second round's pairs
    # on the 1024² blob).
    vid = np.arange(m)
    nid = m
    failed = np.full((2 * m, 3), -1, np.int64)
    for rnd in range(2):
        # The ring's vertices are x[0 … i] (looked at) followed by x[j … last] (not yet): a merge drops
        # x[j] instead of shifting the rest down, so a round costs O(m), not O(merges · m).
        last = m - 1
        i = 0
        j = 1
        while i < m - 1 and m > 3:
            # vertices i and i+1 = x[j] (never across the end of the arrays: the second round runs on the
            # ring rotated by half a turn); unwrapped pieces of the neighbours, vertex m−1 being x[last]
            ta = t[i - 1] if i > 0 else t[last] - n
            tb = t[j + 1] if j < last else t[0] + n
            xa = x[i - 1] if i > 0 else x[last]
            ya = y[i - 1] if i > 0 else y[last]
            xb = x[j + 1] if j < last else x[0]
            yb = y[j + 1] if j < last else y[0]
            merged = False
            va = vid[i - 1] if i > 0 else vid[last]
            vb = vid[j + 1] if j < last else vid[0]
            again = failed[vid[i], 0] == va and failed[vid[i], 1] == vid[j] and failed[vid[i], 2] == vb
            if tb - ta < n and not again:
                wx, wy, tt, ok = _merge_pair(
                    xa, ya, ta, xb, yb, tb, t[i], t[j], rect, gp, gq, gdir, kmax, cone, okc, poly
                )
                if ok:
                    x[i] = wx
                    y[i] = wy
                    t[i] = tt
                    s[i] = SRC_LINES
                    ln[i] = -1
                    vid[i] = nid
                    nid += 1
                    j += 1
                    m -= 1
                    merged = True
                elif rnd == 0:
                    failed[vid[i], 0] = va
                    failed[vid[i], 1] = vid[j]
                    failed[vid[i], 2] = vb
            if not merged:
                i += 1
                x[i] = x[j]
                y[i] = y[j]
                t[i] = t[j]
                s[i] = s[j]
                ln[i] = ln[j]
                vid[i] = vid[j]
                j += 1
        # the vertices not looked at (when m reached 3) follow vertex i again
        for q in range(j, last + 1):
            x[i + 1 + q - j] = x[q]
            y[i + 1 + q - j] = y[q]
            t[i + 1 + q - j] = t[q]
            s[i + 1 + q - j] = s[q]
            ln[i + 1 + q - j] = ln[q]
            vid[i + 1 + q - j] = vid[q]
        if rnd == 0 and m > 3:
            # rotate by half a turn, keeping the pieces non-decreasing from vertex 0
            h = m // 2
            rx = np.empty(m, np.int64)
            ry = np.empty(m, np.int64)
            rt = np.empty(m, np.int64)
            rs = np.empty(m, np.int64)
            rl = np.empty(m, np.int64)
            rv = np.empty(m, np.int64)
            for q in range(m):
                src = (h + q) % m
                rv[q] = vid[src]
                rx[q] = x[src]
                ry[q] = y[src]
                rt[q] = t[src] + (n if src < h else 0)
                rs[q] = s[src]
                rl[q] = ln[src]
            base = (rt[0] // n) * n
            for q in range(m):
                x[q] = rx[q]
                y[q] = ry[q]
                t[q] = rt[q] - base
                s[q] = rs[q]
                ln[q] = rl[q]
                vid[q] = rv[q]
    if m == ix.size:
        return ix, iy, vt, vs, vl
    ox = x[:m].copy()
    oy = y[:m].copy()
    ot = t[:m].copy()
    os_ = s[:m].copy()
    ol = ln[:m].copy()
    bad = np.zeros(m, np.bool_)
    if verify_ring(ox, oy, ot, rect, gp, gq, gdir, 1 << kmax, bad):
        return ox, oy, ot, os_, ol
    return ix, iy, vt, vs, vl
