"""Phase 4 of R on verified rings: net splices, pruning, merging, relinking, small-corridor searches."""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit
from mrm.geometry.reconstruct._base import _DX, _DY, SRC_LINES, SRC_NET, SRC_SPLICE
from mrm.geometry.reconstruct._check import _in_piece, edge_ok, gate_rays, rays_admit, verify_ring

# ============================================================================================ repair


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


# ============================================================================================ pruning


@njit(cache=True)
def prune_ring(
    ix: np.ndarray,
    iy: np.ndarray,
    vt: np.ndarray,
    vs: np.ndarray,
    vl: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    sc: int,
    check: bool = True,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """Drop every vertex whose two neighbours can be joined by a valid edge (exact), in one sweep.

    With ``check``, the original ring is kept if the result does not verify; without, the pruned ring is
    returned as it is (used to repair a ring that failed: the caller verifies).
    """
    n = gdir.size
    m = ix.size
    keep = np.ones(m, np.bool_)
    left = m
    for i in range(m):
        if left <= 3:
            break
        p = (i - 1) % m
        while not keep[p]:
            p = (p - 1) % m
        q = (i + 1) % m
        while not keep[q]:
            q = (q + 1) % m
        tp = vt[p]
        tq = vt[q]
        if p > i:
            tp -= n  # p is in the previous lap
        if q < i:
            tq += n  # q is in the next lap
        if tq - tp >= n:
            continue
        if edge_ok(ix[p], iy[p], tp, ix[q], iy[q], tq, gp, gq, gdir, sc):
            keep[i] = False
            left -= 1
    if left == m:
        return ix, iy, vt, vs, vl
    ox = np.empty(left, np.int64)
    oy = np.empty(left, np.int64)
    ot = np.empty(left, np.int64)
    os_ = np.empty(left, np.int64)
    ol = np.empty(left, np.int64)
    j = 0
    for i in range(m):
        if keep[i]:
            ox[j] = ix[i]
            oy[j] = iy[i]
            ot[j] = vt[i]
            os_[j] = vs[i]
            ol[j] = vl[i]
            j += 1
    if not check:
        return ox, oy, ot, os_, ol
    bad = np.zeros(left, np.bool_)
    if verify_ring(ox, oy, ot, rect, gp, gq, gdir, sc, bad):
        return ox, oy, ot, os_, ol
    return ix, iy, vt, vs, vl


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
    # :func:`_merge_cones`, alone. Used to skip pairs of candidates whose own sides already leave nothing.
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
    the piece);
    each vertex between them is placed as by :func:`_merge_pair` (the centre of the region both neighbours
    see, searched in every piece between them; each candidate's cone of rays is computed once per piece or
    piece pair, :func:`_merge_cones`), so only two of the vertices are enumerated. For a triangle
    the edge 2 → 0 is checked directly. Piece pairs are pruned by the reach table; the result is verified
    exactly (:func:`verify_ring`).
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
    a sees, c3 likewise towards b, and one point w replacing v, v' is placed by :func:`_merge_pair`. This
    undoes what :func:`merge_ring` cannot (two vertices close together that one vertex would replace only if
    both neighbours moved); ``reach`` (the ring's reach table) rules out most positions at once. Every
    change is verified exactly on the whole ring, so the ring stays valid; the scan stops after a lap
    without change.
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
