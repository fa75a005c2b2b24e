"""Phase 2 of R: the reach table and a central line per window (exact preimage, DSS recognition)."""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit
from mrm.geometry.dss._kernels import reach_kernel
from mrm.geometry.reconstruct._base import _BIG

# ============================================================================================ preimage


@leaf_njit(cache=True)
def _vline(
    a: int,
    b: int,
    sgx: int,
    sgy: int,
    ptx: np.ndarray,
    pty: np.ndarray,
    vb: np.ndarray,
    q: int,
    w: int,
    k: int,
) -> None:  # pragma: no cover
    # The oriented line (base point, direction) of the dual polygon's vertex between constraint edges a and b
    # (ids >= 0: gate ends; -1: t = 0, i.e. direction (sgx, 0); -2: t = 1, direction (0, sgy)), stored in
    # vb[q, w, k]. (Indices rather than array views: views cost reference counting in the hot loop.)
    if a >= 0 and b >= 0:
        bx = ptx[a]
        by = pty[a]
        dx = ptx[b] - bx
        dy = pty[b] - by
        if sgx * dx < 0 or sgy * dy < 0:
            dx = -dx
            dy = -dy
    else:
        p = a if a >= 0 else b
        t = b if a >= 0 else a
        bx = ptx[p]
        by = pty[p]
        if t == -1:
            dx = sgx
            dy = 0
        else:
            dx = 0
            dy = sgy
    vb[q, w, k, 0] = bx
    vb[q, w, k, 1] = by
    vb[q, w, k, 2] = dx
    vb[q, w, k, 3] = dy


@leaf_njit(cache=True)
def _clip(
    buf: np.ndarray,
    vb: np.ndarray,
    q: int,
    ws: int,
    size: int,
    newid: int,
    sgx: int,
    sgy: int,
    ptx: np.ndarray,
    pty: np.ndarray,
    sg: np.ndarray,
) -> int:  # pragma: no cover
    # Clip the dual polygon buf[q, ws] (cyclic list of constraint ids; vb[q, ws, v] the line of the vertex
    # between edges v-1 and v) by a new point constraint into buf[q, 1 - ws]. Returns the new size, 0 when
    # the open preimage becomes empty, or −size when the constraint is redundant (nothing written).
    wd = 1 - ws
    x = ptx[newid]
    y = pty[newid]
    neg = (newid & 1) == 1
    npos = 0
    nneg = 0
    for v in range(size):
        w = vb[q, ws, v, 2] * (y - vb[q, ws, v, 1]) - vb[q, ws, v, 3] * (x - vb[q, ws, v, 0])
        if neg:
            w = -w
        s = 1 if w > 0 else (-1 if w < 0 else 0)
        sg[v] = s
        if s > 0:
            npos += 1
        elif s < 0:
            nneg += 1
    if npos == 0:
        return 0
    if nneg == 0:
        return -size
    # exit: sg[i] > 0 >= sg[i+1]; entry: sg[j] <= 0 < sg[j+1]
    i = -1
    j = -1
    for v in range(size):
        v1 = v + 1 if v + 1 < size else 0
        if sg[v] > 0 and sg[v1] <= 0:
            i = v
        if sg[v] <= 0 and sg[v1] > 0:
            j = v
    cnt = i - j + 1 if i >= j else i - j + 1 + size
    for r in range(cnt):
        v = j + r
        if v >= size:
            v -= size
        buf[q, wd, r] = buf[q, ws, v]
        if r > 0:
            for u in range(4):
                vb[q, wd, r, u] = vb[q, ws, v, u]
    buf[q, wd, cnt] = newid
    # vertices: 0 = (new, first), 1 .. cnt-1 copied above, cnt = (last, new)
    _vline(newid, buf[q, wd, 0], sgx, sgy, ptx, pty, vb, q, wd, 0)
    _vline(buf[q, wd, cnt - 1], newid, sgx, sgy, ptx, pty, vb, q, wd, cnt)
    return cnt + 1


@leaf_njit(cache=True)
def _init_poly(
    buf: np.ndarray, q: int, sgx: int, sgy: int, ptx: np.ndarray, pty: np.ndarray
) -> int:  # pragma: no cover
    # Into buf[q, 0]: the dual polygon of the lines (direction in quadrant (sgx, sgy)) crossing the first
    # gate, points 0 (P) and 1 (Q). Lines: direction d(t) = (sgx (1-t), sgy t), t in [0, 1].
    ex = ptx[0] - ptx[1]
    ey = pty[0] - pty[1]
    h0 = sgx * ey  # cross((sgx, 0), P - Q)
    h1 = -sgy * ex  # cross((0, sgy), P - Q)
    if h0 <= 0 and h1 <= 0:
        return 0
    if h0 > 0 and h1 > 0:
        buf[q, 0, 0] = 0
        buf[q, 0, 1] = -2
        buf[q, 0, 2] = 1
        buf[q, 0, 3] = -1
        return 4
    if h0 > 0:
        buf[q, 0, 0] = 0
        buf[q, 0, 1] = 1
        buf[q, 0, 2] = -1
        return 3
    buf[q, 0, 0] = 0
    buf[q, 0, 1] = -2
    buf[q, 0, 2] = 1
    return 3


@leaf_njit(cache=True)
def _best_line(
    buf: np.ndarray,
    q0: int,
    w0: int,
    size: int,
    sgx: int,
    sgy: int,
    ptx: np.ndarray,
    pty: np.ndarray,
    line: np.ndarray,
    ida: np.ndarray,
    cand: np.ndarray,
    first: int = 0,
) -> float:  # pragma: no cover
    # Max-margin line over the point constraints on the dual polygon's boundary: lines
    # f(X) = n(t).X + c, n = (-sgy t, sgx (1-t)), P: f >= m, Q: f <= -m; margin m is L1-normalised.
    # g_X(t) = n(t).X = a_X + t b_X. m(t) = (min_P g - max_Q g) / 2. Returns the margin (Q-units). The
    # line's point is the one nearest the middle of the window's first gate (ids first, first + 1).
    na = 0
    for q in range(size):
        if buf[q0, w0, q] >= 0:
            ida[na] = buf[q0, w0, q]
            na += 1
    nc = 0
    cand[nc] = 0.0
    nc += 1
    cand[nc] = 1.0
    nc += 1
    for u in range(na):
        iu = ida[u]
        au = sgx * pty[iu]
        bu = -sgy * ptx[iu] - sgx * pty[iu]
        for v in range(u + 1, na):
            iv = ida[v]
            if (iu & 1) != (iv & 1):
                continue
            av = sgx * pty[iv]
            bv = -sgy * ptx[iv] - sgx * pty[iv]
            if bu != bv:
                t = (av - au) / (bu - bv)
                if 0.0 < t < 1.0 and nc < cand.size:
                    cand[nc] = t
                    nc += 1
    best = -_BIG
    bt = 0.0
    bc = 0.0
    for q in range(nc):
        t = cand[q]
        mp = _BIG
        mq = -_BIG
        for u in range(na):
            iu = ida[u]
            g = sgx * pty[iu] + t * (-sgy * ptx[iu] - sgx * pty[iu])
            if (iu & 1) == 0:
                if g < mp:
                    mp = g
            elif g > mq:
                mq = g
        m = 0.5 * (mp - mq)
        if m > best:
            best = m
            bt = t
            bc = -0.5 * (mp + mq)
    dx = sgx * (1.0 - bt)
    dy = sgy * bt
    nx = -dy
    ny = dx
    nn = nx * nx + ny * ny
    # a point of the line n.X + c = 0 near the first gate
    fx = 0.5 * (ptx[first] + ptx[first + 1])
    fy = 0.5 * (pty[first] + pty[first + 1])
    f = nx * fx + ny * fy + bc
    line[0] = fx - f * nx / nn
    line[1] = fy - f * ny / nn
    dl = np.sqrt(dx * dx + dy * dy)
    line[2] = dx / dl
    line[3] = dy / dl
    return best


_QUAD_X = np.array([[1, 1], [1, -1], [-1, -1], [1, -1]], dtype=np.int64)
_QUAD_Y = np.array([[1, -1], [1, 1], [1, -1], [-1, -1]], dtype=np.int64)


@njit(cache=True)
def general_reach(
    gp: np.ndarray, gq: np.ndarray, gdir: np.ndarray, todo: np.ndarray, reach: np.ndarray, lines: np.ndarray
) -> None:  # pragma: no cover
    """Reach and central lines by the exact dual-polygon preimage, for the starts with ``todo[i]``.

    For each such start piece i: the farthest j (stored as j − i) such that a line crosses gates i+1 … j in
    order, and a central (max-margin) line of that preimage. Exact: the preimage is a dual
    polygon per direction quadrant whose vertices are lines through two gate ends, clipped with integer
    orientation tests.
    """
    n = gdir.size
    ptx = np.empty(2 * n + 2, np.int32)  # int32 as gp, gq: half the scratch of the largest ring
    pty = np.empty(2 * n + 2, np.int32)
    cap = 2 * n + 8
    buf = np.empty((2, 2, cap), np.int64)  # [quadrant, buffer, edge]
    vbuf = np.empty((2, 2, cap, 4), np.int64)  # vertex lines
    cur = np.zeros(2, np.int64)
    size = np.zeros(2, np.int64)
    sgx = np.empty(2, np.int64)
    sgy = np.empty(2, np.int64)
    sg = np.empty(cap, np.int64)
    line = np.empty(4, np.float64)
    best = np.empty(4, np.float64)
    ida = np.empty(cap, np.int64)
    cand = np.empty(256, np.float64)
    for i in range(n):
        if not todo[i]:
            continue
        g = (i + 1) % n
        d0 = gdir[g]
        ptx[0] = gp[g, 0]
        pty[0] = gp[g, 1]
        ptx[1] = gq[g, 0]
        pty[1] = gq[g, 1]
        for q in range(2):
            sgx[q] = _QUAD_X[d0, q]
            sgy[q] = _QUAD_Y[d0, q]
            cur[q] = 0
            sz = _init_poly(buf, q, sgx[q], sgy[q], ptx, pty)
            size[q] = sz
            for v in range(sz):
                _vline(
                    buf[q, 0, v - 1 if v > 0 else sz - 1],
                    buf[q, 0, v],
                    sgx[q],
                    sgy[q],
                    ptx,
                    pty,
                    vbuf,
                    q,
                    0,
                    v,
                )
        j = i + 1
        while j < i + n - 1:
            g = (j + 1) % n
            w = j - i  # gates already in the window
            ptx[2 * w] = gp[g, 0]
            pty[2 * w] = gp[g, 1]
            ptx[2 * w + 1] = gq[g, 0]
            pty[2 * w + 1] = gq[g, 1]
            # clip each live quadrant into its other buffer; commit only if some quadrant survives
            alive = 0
            nsz0 = 0
            nsz1 = 0
            where0 = 0
            where1 = 0
            for q in range(2):
                if size[q] == 0:
                    continue
                c = cur[q]
                sz = size[q]
                wh = c
                for pt in range(2):
                    r = _clip(buf, vbuf, q, wh, sz, 2 * w + pt, sgx[q], sgy[q], ptx, pty, sg)
                    if r == 0:
                        sz = 0
                        break
                    if r > 0:
                        sz = r
                        wh = 1 - wh
                if sz > 0:
                    alive += 1
                if q == 0:
                    nsz0 = sz
                    where0 = wh
                else:
                    nsz1 = sz
                    where1 = wh
            if alive == 0:
                break
            if size[0] > 0:
                size[0] = nsz0
                cur[0] = where0
            if size[1] > 0:
                size[1] = nsz1
                cur[1] = where1
            j += 1
        reach[i] = j - i
        bm = -_BIG
        for q in range(2):
            if size[q] > 0:
                m = _best_line(buf, q, cur[q], size[q], sgx[q], sgy[q], ptx, pty, line, ida, cand)
                if m > bm:
                    bm = m
                    for u in range(4):
                        best[u] = line[u]
        for u in range(4):
            lines[i, u] = best[u]


@njit(cache=True)
def dss_reach(
    e0: int, ec: np.ndarray, er: np.ndarray, n: int, reach: np.ndarray, lines: np.ndarray
) -> None:  # pragma: no cover
    """Reach and median lines when every piece is a full pixel: standard DSS of the pixel centres."""
    pts = np.empty((n, 2), np.int64)
    for k in range(n):
        pts[k, 0] = ec[e0 + k]
        pts[k, 1] = er[e0 + k]
    t = reach_kernel(pts, True, 4)
    for i in range(n):
        j = t[i, 0]
        a = t[i, 1]
        b = t[i, 2]
        mu = t[i, 3]
        om = t[i, 4]
        if j > i + n - 1:
            j = i + n - 1
        reach[i] = j - i
        # median line a x - b y = mu + (om - 1) / 2 in pixels; Q-units: a X - b Y = 4 mu + 2 (om - 1)
        cst = 4.0 * mu + 2.0 * (om - 1)
        x0 = 4.0 * pts[i, 0]
        y0 = 4.0 * pts[i, 1]
        nn = float(a * a + b * b)
        f = (a * x0 - b * y0 - cst) / nn
        lines[i, 0] = x0 - f * a
        lines[i, 1] = y0 + f * b
        dx = float(b)
        dy = float(a)
        jj = j % n
        if dx * (pts[jj, 0] - pts[i, 0]) + dy * (pts[jj, 1] - pts[i, 1]) < 0:
            dx = -dx
            dy = -dy
        dl = np.sqrt(dx * dx + dy * dy)
        lines[i, 2] = dx / dl
        lines[i, 3] = dy / dl
