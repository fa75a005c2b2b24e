"""Numba kernels of the reversible continuation R (see :mod:`mrm.geometry.reconstruct`).

Everything here works in *array* coordinates (pixel (c, r) is ``mask[r, c]``) and in **Q-units**, a
quarter of a pixel: the centre of pixel (c, r) is (4c, 4r) and pointel (i, j), the lower-left corner of pixel
(i, j), is (4i − 2, 4j − 2). Every corner, side midpoint, centre and safety-net vertex is then an integer.

The pipeline for one crack ring (object on the left):

1. *elements* — the 4-connected border path: one element per maximal run of linels with the same inner
   pixel, plus an *elbow* element at every right turn (ALGORITHMS §2.5);
2. *pieces* — open axis-parallel rectangles the ring may pass through, in path order, and the *gates* (open
   segments) between consecutive pieces. Cover models: a pixel visited once is one full-square piece; a
   pixel visited several times (one-pixel-wide parts) gets one part per visit, the part on the outer side
   of the centre polyline. ``gauss`` uses those outer parts everywhere (the ring must keep every centre of
   A strictly inside and stay in V(A));
3. *reach* — for each start piece i, the farthest piece j such that one line crosses gates i+1 … j in
   order: arithmetic standard-DSS recognition when every piece is a full pixel, an exact incremental
   preimage (dual polygon, integer orientation tests) otherwise; and a central line of that preimage;
4. *V4 greedy* — consecutive chosen lines meet inside a piece of their overlap, otherwise a patch (two
   vertices in one piece);
5. *snap* — each vertex to the coarsest dyadic grid that keeps every constraint (exact integer checks);
5b. *straighten* — each edge moved onto the simplest line (least |dx| + |dy|, offset centred) that crosses
   the gates of the pieces it covers, where the moved vertices still verify (same vertex count);
6. *verify* — exact: every vertex strictly inside its piece, every edge crossing its gates strictly inside
   and in order, no fold, no crossing between edges meeting in a piece. Pieces of different visits are
   disjoint, so a verified ring is simple and disjoint from the other rings;
7. *repair* — local: the failing stretch is replaced by the safety net R0 (the crack ring offset inward by
   ¼ pixel, which is always a valid ring of the same corridor) spliced in with two vertices at each end;
   the whole ring becomes R0 only if that does not verify.

Integer checks use coordinates scaled by 2^K with K chosen per ring so that every product of two
coordinate differences stays below 2⁶² (no overflow, no rounding).
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._dss_kernels import reach_kernel
from mrm.geometry._jit import njit

# Freeman directions 0 = E, 1 = N, 2 = W, 3 = S.
_DX = np.array([1, 0, -1, 0], dtype=np.int64)
_DY = np.array([0, 1, 0, -1], dtype=np.int64)
# Pixel on the left of a code leaving pointel (i, j): (i + _LXD[d], j + _LYD[d]).
_LXD = np.array([0, -1, -1, 0], dtype=np.int64)
_LYD = np.array([0, 0, -1, -1], dtype=np.int64)

#: Vertex sources (``reconstruct_detailed``).
SRC_LINES = 0  # where two chosen lines meet
SRC_PATCH = 1  # a patch vertex (two per patch, on one line each)
SRC_SPLICE = 2  # a splice vertex joining the V4 ring to the safety net
SRC_NET = 3  # a safety-net (R0) vertex
SRC_SINGLE = 4  # the triangle of an isolated pixel

#: Ring status flags.
RING_V4 = 0
RING_PARTIAL = 1  # some stretches replaced by the safety net
RING_NET = 2  # the whole ring is the safety net
RING_SINGLE = 3  # isolated pixel

_SMALL = 12  # corridors up to this many pieces also get an exhaustive search for a triangle
_SMALL_POLY = 24  # verified rings of corridors up to this many pieces: search for 3 or 4 vertices
_EPS = 1e-4  # float margin (Q-units) used only while *constructing*; every result is checked exactly
_BIG = 1e300


# Explicit copy loops: numpy slice assignment and fancy indexing cost seconds of compile time each.
@njit(cache=True)
def _cp1(dst: np.ndarray, at: int, src: np.ndarray) -> None:  # pragma: no cover
    for i in range(src.shape[0]):
        dst[at + i] = src[i]


@njit(cache=True)
def _cp2(dst: np.ndarray, at: int, src: np.ndarray) -> None:  # pragma: no cover
    for i in range(src.shape[0]):
        for j in range(src.shape[1]):
            dst[at + i, j] = src[i, j]


@njit(cache=True)
def _grow1(a: np.ndarray, n: int, cap: int) -> np.ndarray:  # pragma: no cover
    b = np.empty(cap, a.dtype)
    for i in range(n):
        b[i] = a[i]
    return b


@njit(cache=True)
def _grow2(a: np.ndarray, n: int, cap: int) -> np.ndarray:  # pragma: no cover
    b = np.empty((cap, a.shape[1]), a.dtype)
    for i in range(n):
        for j in range(a.shape[1]):
            b[i, j] = a[i, j]
    return b


# ============================================================================================ elements


@njit(cache=True)
def build_elements(
    codes: np.ndarray, off: np.ndarray, sx: np.ndarray, sy: np.ndarray
) -> tuple[
    np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray
]:  # pragma: no cover
    """Border-path elements and safety-net vertices of every ring.

    Returns ``eoff`` (ring offsets into the element arrays), ``ec, er`` (pixel), ``edin, edout``
    (incoming / outgoing step), ``enl`` (0 = elbow, else the number of linels of the run: 1 straight,
    2 convex corner, 3 tip, 4 isolated pixel), ``r0off`` (ring offsets into the R0 arrays), ``r0`` (R0
    vertices, Q-units, (n, 2)) and ``r0e`` (the element of each R0 vertex, global index).
    """
    nr = off.size - 1
    lt = codes.size
    cap = 2 * lt + nr + 1
    ec = np.empty(cap, np.int64)
    er = np.empty(cap, np.int64)
    edin = np.empty(cap, np.int64)
    edout = np.empty(cap, np.int64)
    enl = np.empty(cap, np.int64)
    eoff = np.zeros(nr + 1, np.int64)
    r0 = np.empty((lt + 1, 2), np.int64)
    r0e = np.empty(lt + 1, np.int64)
    r0off = np.zeros(nr + 1, np.int64)
    ne = 0
    nv = 0
    for k in range(nr):
        o0 = off[k]
        n = off[k + 1] - o0
        px = np.empty(n, np.int64)
        py = np.empty(n, np.int64)
        x = sx[k]
        y = sy[k]
        for i in range(n):
            px[i] = x
            py[i] = y
            d = codes[o0 + i]
            x += _DX[d]
            y += _DY[d]
        first = -1
        for i in range(n):
            if ((codes[o0 + i] - codes[o0 + (i - 1) % n]) & 3) != 1:
                first = i
                break
        if first < 0:
            # an isolated pixel: four left turns
            d0 = codes[o0]
            ec[ne] = px[0] + _LXD[d0]
            er[ne] = py[0] + _LYD[d0]
            edin[ne] = d0
            edout[ne] = codes[o0 + n - 1]
            enl[ne] = n
            for i in range(n):
                dp = codes[o0 + (i - 1) % n]
                d = codes[o0 + i]
                r0[nv, 0] = 4 * px[i] - 2 + _DX[(dp + 1) & 3] + _DX[(d + 1) & 3]
                r0[nv, 1] = 4 * py[i] - 2 + _DY[(dp + 1) & 3] + _DY[(d + 1) & 3]
                r0e[nv] = ne
                nv += 1
            ne += 1
        else:
            i = first
            while i < first + n:
                ii = i % n
                dp = codes[o0 + (ii - 1) % n]
                d = codes[o0 + ii]
                if ((d - dp) & 3) == 3:
                    # right turn at pointel ii: the elbow FL, then the run
                    ec[ne] = px[ii] + _LXD[dp]
                    er[ne] = py[ii] + _LYD[dp]
                    edin[ne] = dp
                    edout[ne] = d
                    enl[ne] = 0
                    r0[nv, 0] = 4 * px[ii] - 2 + _DX[(dp + 1) & 3] + _DX[(d + 1) & 3]
                    r0[nv, 1] = 4 * py[ii] - 2 + _DY[(dp + 1) & 3] + _DY[(d + 1) & 3]
                    r0e[nv] = ne
                    nv += 1
                    ne += 1
                j = i + 1
                while j < first + n and ((codes[o0 + j % n] - codes[o0 + (j - 1) % n]) & 3) == 1:
                    j += 1
                ec[ne] = px[ii] + _LXD[d]
                er[ne] = py[ii] + _LYD[d]
                edin[ne] = d
                edout[ne] = codes[o0 + (j - 1) % n]
                enl[ne] = j - i
                for m in range(i + 1, j):
                    mm = m % n
                    a = codes[o0 + (mm - 1) % n]
                    b = codes[o0 + mm]
                    r0[nv, 0] = 4 * px[mm] - 2 + _DX[(a + 1) & 3] + _DX[(b + 1) & 3]
                    r0[nv, 1] = 4 * py[mm] - 2 + _DY[(a + 1) & 3] + _DY[(b + 1) & 3]
                    r0e[nv] = ne
                    nv += 1
                ne += 1
                i = j
        eoff[k + 1] = ne
        r0off[k + 1] = nv
    return eoff, ec[:ne], er[:ne], edin[:ne], edout[:ne], enl[:ne], r0off, r0[:nv], r0e[:nv]


@njit(cache=True)
def count_visits(h: int, w: int, ec: np.ndarray, er: np.ndarray) -> np.ndarray:  # pragma: no cover
    """How many border-path elements (over all rings) sit on each pixel, saturated at 2."""
    cnt = np.zeros((h, w), np.uint8)
    for k in range(ec.size):
        if cnt[er[k], ec[k]] < 2:
            cnt[er[k], ec[k]] += 1
    return cnt


# ============================================================================================ pieces


@njit(cache=True)
def _rect_of(c: int, r: int, hx: int, hy: int, out: np.ndarray, k: int) -> None:  # pragma: no cover
    # The part of pixel (c, r) on side (hx, hy) (0 = both halves) as [x0, x1] x [y0, y1], Q-units.
    cx = 4 * c
    cy = 4 * r
    out[k, 0] = cx if hx > 0 else cx - 2
    out[k, 1] = cx if hx < 0 else cx + 2
    out[k, 2] = cy if hy > 0 else cy - 2
    out[k, 3] = cy if hy < 0 else cy + 2


@njit(cache=True)
def build_pieces(
    e0: int,
    e1: int,
    ec: np.ndarray,
    er: np.ndarray,
    edin: np.ndarray,
    edout: np.ndarray,
    enl: np.ndarray,
    cnt: np.ndarray,
    gauss: bool,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """Pieces and gates of the ring whose elements are e0 … e1−1.

    Returns ``rect`` (n, 4) [x0, x1, y0, y1], ``pel`` (element of each piece, local index), ``gp``, ``gq``
    (n, 2) the left and right end of gate k (between piece k−1 and k, looking in the crossing direction),
    ``gdir`` (n) the crossing direction and ``full`` (1 if every piece is a full pixel).
    """
    ne = e1 - e0
    cap = 2 * ne + 2
    rect = np.empty((cap, 4), np.int64)
    pel = np.empty(cap, np.int64)
    internal = np.zeros(cap, np.int64)  # 1: the gate before this piece is inside its pixel
    n = 0
    full = 1
    for k in range(ne):
        e = e0 + k
        c = ec[e]
        r = er[e]
        din = edin[e]
        dout = edout[e]
        nl = enl[e]
        if (not gauss) and cnt[r, c] < 2:
            _rect_of(c, r, 0, 0, rect, n)
            pel[n] = k
            n += 1
            continue
        full = 0
        rx = _DX[(din + 3) & 3]  # right of din
        ry = _DY[(din + 3) & 3]
        if nl == 0:
            # elbow (right turn): the quadrant right of both steps
            _rect_of(c, r, rx + _DX[(dout + 3) & 3], ry + _DY[(dout + 3) & 3], rect, n)
            pel[n] = k
            n += 1
        elif nl == 1:
            _rect_of(c, r, rx, ry, rect, n)
            pel[n] = k
            n += 1
        elif nl == 2:
            # convex corner: the half right of din, then the quadrant ahead of din and dout
            _rect_of(c, r, rx, ry, rect, n)
            pel[n] = k
            n += 1
            _rect_of(c, r, _DX[din] + _DX[dout], _DY[din] + _DY[dout], rect, n)
            pel[n] = k
            internal[n] = 1
            n += 1
        else:
            # tip (U-turn): the half right of din, then the half left of din
            _rect_of(c, r, rx, ry, rect, n)
            pel[n] = k
            n += 1
            _rect_of(c, r, -rx, -ry, rect, n)
            pel[n] = k
            internal[n] = 1
            n += 1
    gp = np.empty((n, 2), np.int64)
    gq = np.empty((n, 2), np.int64)
    gdir = np.empty(n, np.int64)
    for k in range(n):
        a = (k - 1) % n
        if internal[k] == 1:
            e = e0 + pel[k]
            din = edin[e]
            cx = 4 * ec[e]
            cy = 4 * er[e]
            gp[k, 0] = cx
            gp[k, 1] = cy
            gq[k, 0] = cx + 2 * _DX[din]
            gq[k, 1] = cy + 2 * _DY[din]
            gdir[k] = (din + 1) & 3
            continue
        ix0 = max(rect[a, 0], rect[k, 0])
        ix1 = min(rect[a, 1], rect[k, 1])
        iy0 = max(rect[a, 2], rect[k, 2])
        iy1 = min(rect[a, 3], rect[k, 3])
        if ix0 == ix1:
            if rect[a, 1] == ix0:  # crossing East
                gdir[k] = 0
                gp[k, 0] = ix0
                gp[k, 1] = iy1
                gq[k, 0] = ix0
                gq[k, 1] = iy0
            else:
                gdir[k] = 2
                gp[k, 0] = ix0
                gp[k, 1] = iy0
                gq[k, 0] = ix0
                gq[k, 1] = iy1
        else:
            if rect[a, 3] == iy0:  # crossing North
                gdir[k] = 1
                gp[k, 0] = ix0
                gp[k, 1] = iy0
                gq[k, 0] = ix1
                gq[k, 1] = iy0
            else:
                gdir[k] = 3
                gp[k, 0] = ix1
                gp[k, 1] = iy0
                gq[k, 0] = ix0
                gq[k, 1] = iy0
    return rect[:n], pel[:n], gp, gq, gdir, np.array([full], np.int64)


@njit(cache=True)
def net_pieces(
    r0: np.ndarray, r0e_local: np.ndarray, rect: np.ndarray, pel: np.ndarray
) -> np.ndarray:  # pragma: no cover
    """The piece holding each R0 vertex (pieces of its own element; −1 if none, which is a bug)."""
    n = rect.shape[0]
    first = np.full(pel[n - 1] + 2, -1, np.int64)
    for k in range(n - 1, -1, -1):
        first[pel[k]] = k
    out = np.full(r0.shape[0], -1, np.int64)
    for v in range(r0.shape[0]):
        k = first[r0e_local[v]]
        while 0 <= k < n and pel[k] == r0e_local[v]:
            if rect[k, 0] < r0[v, 0] < rect[k, 1] and rect[k, 2] < r0[v, 1] < rect[k, 3]:
                out[v] = k
                break
            k += 1
    return out


# ============================================================================================ preimage


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
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


@njit(cache=True)
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
) -> float:  # pragma: no cover
    # Max-margin line over the point constraints on the dual polygon's boundary: lines
    # f(X) = n(t).X + c, n = (-sgy t, sgx (1-t)), P: f >= m, Q: f <= -m; margin m is L1-normalised.
    # g_X(t) = n(t).X = a_X + t b_X. m(t) = (min_P g - max_Q g) / 2. Returns the margin (Q-units).
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
    fx = 0.5 * (ptx[0] + ptx[1])
    fy = 0.5 * (pty[0] + pty[1])
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
    ptx = np.empty(2 * n + 2, np.int64)
    pty = np.empty(2 * n + 2, np.int64)
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
def cell_reach(
    rect: np.ndarray, gp: np.ndarray, gq: np.ndarray, reach: np.ndarray, lines: np.ndarray
) -> bool:  # pragma: no cover
    """Reach and median lines when every piece is a quarter or a half of a pixel, in O(n).

    This is the case under ``gauss`` (and for split pixels only). In the lattice of half-pixel *cells* each
    piece is one or two cells and each gate one cell side, so the corridor is a 4-connected path of cells and
    a line crosses its gates in order exactly when the cell centres form a standard DSS (the side between the
    two cells of a half is crossed by any line entering and leaving that convex half through its gates). O(n).
    Returns False if some piece is a whole pixel (then the caller falls back).
    """
    n = rect.shape[0]
    cu = np.empty(2 * n, np.int64)
    cv = np.empty(2 * n, np.int64)
    first = np.empty(n + 1, np.int64)  # first cell of each piece
    m = 0
    for k in range(n):
        x0 = rect[k, 0]
        x1 = rect[k, 1]
        y0 = rect[k, 2]
        y1 = rect[k, 3]
        first[k] = m
        # the gate into this piece: its midpoint picks the first cell of a half
        mx = gp[k, 0] + gq[k, 0]  # twice the midpoint
        my = gp[k, 1] + gq[k, 1]
        if x1 - x0 == 2 and y1 - y0 == 2:
            cu[m] = x0 // 2
            cv[m] = y0 // 2
            m += 1
        elif x1 - x0 == 4 and y1 - y0 == 2:
            a = x0 // 2
            if mx > 2 * (x0 + 2):  # entered on the right half
                cu[m] = a + 1
                cu[m + 1] = a
            else:
                cu[m] = a
                cu[m + 1] = a + 1
            cv[m] = y0 // 2
            cv[m + 1] = y0 // 2
            m += 2
        elif x1 - x0 == 2 and y1 - y0 == 4:
            b = y0 // 2
            if my > 2 * (y0 + 2):
                cv[m] = b + 1
                cv[m + 1] = b
            else:
                cv[m] = b
                cv[m + 1] = b + 1
            cu[m] = x0 // 2
            cu[m + 1] = x0 // 2
            m += 2
        else:
            return False
    first[n] = m
    pts = np.empty((m, 2), np.int64)
    for k in range(m):
        pts[k, 0] = cu[k]
        pts[k, 1] = cv[k]
    t = reach_kernel(pts, True, 4)
    j = 0  # unwrapped piece index, non-decreasing with i
    for i in range(n):
        last = first[i + 1] - 1
        cr = t[last, 0]  # farthest cell (unwrapped)
        if j < i + 1:
            j = i + 1
        # largest piece j < i + n whose first cell (unwrapped) is <= cr
        while j + 1 < i + n and first[(j + 1) % n] + m * ((j + 1) // n) <= cr:
            j += 1
        reach[i] = j - i
        a = t[last, 1]
        b = t[last, 2]
        mu = t[last, 3]
        om = t[last, 4]
        # median line a u - b v = mu + (om - 1) / 2 in cells;
        # Q-units X = 2u + 1: a X - b Y = 2 mu + om - 1 + a - b
        cst = 2.0 * mu + (om - 1) + a - b
        x0 = 2.0 * pts[last, 0] + 1.0
        y0 = 2.0 * pts[last, 1] + 1.0
        nn = float(a * a + b * b)
        f = (a * x0 - b * y0 - cst) / nn
        lines[i, 0] = x0 - f * a
        lines[i, 1] = y0 + f * b
        dx = float(b)
        dy = float(a)
        cc = cr % m
        if dx * (pts[cc, 0] - pts[last, 0]) + dy * (pts[cc, 1] - pts[last, 1]) < 0:
            dx = -dx
            dy = -dy
        dl = np.sqrt(dx * dx + dy * dy)
        lines[i, 2] = dx / dl
        lines[i, 3] = dy / dl
    return True


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


# ============================================================================================ V4 greedy


@njit(cache=True)
def ring_reach(
    e0: int,
    e1: int,
    ec: np.ndarray,
    er: np.ndarray,
    cnt: np.ndarray,
    gauss: bool,
    full: bool,
    pel: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    reach: np.ndarray,
    lines: np.ndarray,
) -> None:  # pragma: no cover
    """Reach table and central lines of a ring's pieces.

    Windows of full pixels use the O(n) standard DSS
    reach (stabbing full gates in order is exactly being a standard DSS); windows that meet a split pixel,
    and every window under gauss, use the exact dual-polygon preimage (sub-gates only restrict, so the DSS
    window bounds it).
    """
    n = gdir.size
    if full:
        dss_reach(e0, ec, er, n, reach, lines)
        return
    if gauss and cell_reach(rect, gp, gq, reach, lines):
        return
    todo = np.ones(n, np.bool_)
    if not gauss:
        ne = e1 - e0
        rd = np.empty(ne, np.int64)
        ld = np.empty((ne, 4), np.float64)
        dss_reach(e0, ec, er, ne, rd, ld)
        # split elements, prefix counts over two laps
        pre = np.zeros(2 * ne + 1, np.int64)
        for k in range(2 * ne):
            kk = k % ne
            pre[k + 1] = pre[k] + (1 if cnt[er[e0 + kk], ec[e0 + kk]] >= 2 else 0)
        for i in range(n):
            k = pel[i]
            if pre[k + rd[k] + 1] - pre[k] == 0:
                todo[i] = False
                reach[i] = rd[k]
                for u in range(4):
                    lines[i, u] = ld[k, u]
    general_reach(gp, gq, gdir, todo, reach, lines)


@njit(cache=True)
def _gate_param(line: np.ndarray, gp: np.ndarray, gq: np.ndarray, k: int) -> float:  # pragma: no cover
    # Parameter (Q-units along the unit direction) where the line meets the gate's supporting line.
    if gp[k, 0] == gq[k, 0]:
        if line[2] == 0.0:
            return _BIG
        return float((gp[k, 0] - line[0]) / line[2])
    if line[3] == 0.0:
        return _BIG
    return float((gp[k, 1] - line[1]) / line[3])


@njit(cache=True)
def _inside_rect(rect: np.ndarray, k: int, x: float, y: float, eps: float) -> bool:  # pragma: no cover
    return bool(rect[k, 0] + eps < x < rect[k, 1] - eps and rect[k, 2] + eps < y < rect[k, 3] - eps)


@njit(cache=True)
def _locate(
    lines: np.ndarray,
    s: int,
    e: int,
    x: float,
    y: float,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    n: int,
) -> tuple[int, float, bool]:  # pragma: no cover
    # The piece t in [s, e] (unwrapped) that the point (x, y) of line s lies in, its parameter on line s,
    # and whether it is safely inside (away from the gates by the construction margin).
    ln = lines[s % n]
    lam = (x - ln[0]) * ln[2] + (y - ln[1]) * ln[3]
    lo = s + 1
    hi = e + 1  # first k in [s+1, e] with param >= lam; e+1 if none
    while lo < hi:
        mid = (lo + hi) // 2
        if _gate_param(ln, gp, gq, mid % n) >= lam:
            hi = mid
        else:
            lo = mid + 1
    t = lo - 1
    ok = True
    if t > s and lam - _gate_param(ln, gp, gq, t % n) <= _EPS:
        ok = False
    if t < e and _gate_param(ln, gp, gq, (t + 1) % n) - lam <= _EPS:
        ok = False
    if ok and not _inside_rect(rect, t % n, x, y, _EPS):
        ok = False
    return t, lam, ok


@njit(cache=True)
def _meet(l1: np.ndarray, l2: np.ndarray) -> tuple[float, float, bool]:  # pragma: no cover
    den = l1[2] * l2[3] - l1[3] * l2[2]
    if abs(den) < 1e-12:
        return 0.0, 0.0, False
    wx = l2[0] - l1[0]
    wy = l2[1] - l1[1]
    lam = (wx * l2[3] - wy * l2[2]) / den
    return l1[0] + lam * l1[2], l1[1] + lam * l1[3], True


@njit(cache=True)
def _chord_point(
    ln: np.ndarray, rect: np.ndarray, k: int, lam_min: float, lam_max: float
) -> tuple[float, float, bool]:  # pragma: no cover
    # The midpoint of the part of the line inside the (open) rectangle k, with lam_min < param < lam_max.
    t0 = lam_min
    t1 = lam_max
    for ax in range(2):
        o = ln[ax]
        d = ln[2 + ax]
        a = float(rect[k, 2 * ax])
        b = float(rect[k, 2 * ax + 1])
        if d == 0.0:
            if not (a + _EPS < o < b - _EPS):
                return 0.0, 0.0, False
        else:
            ta = (a - o) / d
            tb = (b - o) / d
            if ta > tb:
                ta, tb = tb, ta
            t0 = max(t0, ta)
            t1 = min(t1, tb)
    if t1 - t0 <= 4.0 * _EPS:
        return 0.0, 0.0, False
    t = 0.5 * (t0 + t1)
    return ln[0] + t * ln[2], ln[1] + t * ln[3], True


@njit(cache=True)
def _v4_periodic(
    reach: np.ndarray, lines: np.ndarray, rect: np.ndarray, gp: np.ndarray, gq: np.ndarray, s0: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, bool]:  # pragma: no cover
    n = reach.size
    cap = 16 * n + 32
    vx = np.empty(cap, np.float64)
    vy = np.empty(cap, np.float64)
    vt = np.empty(cap, np.int64)
    vs = np.empty(cap, np.int64)
    vl = np.empty(cap, np.int64)
    seen = np.full(n, -1, np.int64)  # last vertex index whose outgoing line is ≡ s (mod n)
    nv = 0
    s = s0
    t_prev = s0
    lam_prev = -_BIG
    while nv + 2 < cap:
        e = s + reach[s % n]
        ls = lines[s % n]
        found = False
        for s2 in range(e, s, -1):
            l2 = lines[s2 % n]
            x, y, okm = _meet(ls, l2)
            if not okm:
                continue
            t, lam, ok = _locate(lines, s, e, x, y, rect, gp, gq, n)
            if not ok or t < s2 or t > e:
                continue
            if t < t_prev or (t == t_prev and lam <= lam_prev + _EPS):
                continue
            vx[nv] = x
            vy[nv] = y
            vt[nv] = t
            vs[nv] = SRC_LINES
            vl[nv] = s2
            nv += 1
            s = s2
            t_prev = t
            lam_prev = (x - l2[0]) * l2[2] + (y - l2[1]) * l2[3]
            found = True
            break
        if not found:
            lmin = lam_prev if e == t_prev else -_BIG
            ax, ay, oka = _chord_point(ls, rect, e % n, lmin, _BIG)
            le = lines[e % n]
            bx, by, okb = _chord_point(le, rect, e % n, -_BIG, _BIG)
            if not (oka and okb):
                break
            vx[nv] = ax
            vy[nv] = ay
            vt[nv] = e
            vs[nv] = SRC_PATCH
            vl[nv] = -1 - s  # the patch edge; keeps the state distinct from a line vertex
            nv += 1
            vx[nv] = bx
            vy[nv] = by
            vt[nv] = e
            vs[nv] = SRC_PATCH
            vl[nv] = e
            nv += 1
            s = e
            t_prev = e
            lam_prev = (bx - le[0]) * le[2] + (by - le[1]) * le[3]
        # the state after the last vertex is (its position, the current line): a repeat one lap later closes
        last = nv - 1
        k = s % n
        j = seen[k]
        if j >= 0 and vl[j] == s - n and vx[j] == vx[last] and vy[j] == vy[last] and vt[last] - vt[j] == n:
            m = last - j
            out = np.empty((m, 2), np.float64)
            ot = np.empty(m, np.int64)
            os_ = np.empty(m, np.int64)
            ol = np.empty(m, np.int64)
            for q in range(m):
                out[q, 0] = vx[j + 1 + q]
                out[q, 1] = vy[j + 1 + q]
                ot[q] = vt[j + 1 + q] - n * ((vt[j + 1] - (vt[j + 1] % n)) // n)
                os_[q] = vs[j + 1 + q]
                ol[q] = vl[j + 1 + q] % n if vl[j + 1 + q] >= 0 else -1
            return out, ot, os_, ol, True
        seen[k] = last
        if vt[last] > s0 + 5 * n:
            break
    return np.empty((0, 2), np.float64), vt[:0], vs[:0], vl[:0], False


@njit(cache=True)
def v4_greedy(
    reach: np.ndarray,
    lines: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    periodic: bool,
    start: int = -1,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, bool]:  # pragma: no cover
    """Choose lines and vertices around the ring (ALGORITHMS §3.5, V4).

    From the longest window, take as next line the farthest one that meets the current line inside a piece
    of their overlap (after the previous vertex); if none does, a patch (two vertices in the last piece of
    the current window). ``periodic=False`` closes the ring on the first line after one lap;
    ``periodic=True`` walks on until a vertex repeats one lap later and keeps that period.

    Returns float vertices (k, 2) in Q-units, their pieces (unwrapped, increasing by at most one lap), their
    sources, the line of the edge *leaving* each vertex, and whether it succeeded.
    """
    n = reach.size
    s0 = 0
    for i in range(n):
        if reach[i] > reach[s0]:
            s0 = i
    if start >= 0:
        s0 = start
    if periodic:
        return _v4_periodic(reach, lines, rect, gp, gq, s0)
    cap = 4 * n + 16
    vx = np.empty(cap, np.float64)
    vy = np.empty(cap, np.float64)
    vt = np.empty(cap, np.int64)
    vs = np.empty(cap, np.int64)
    vl = np.empty(cap, np.int64)
    nv = 0
    s = s0
    t_prev = s0
    lam_prev = -_BIG
    first_t = -1
    first_lam = 0.0
    guard = 0
    l0 = lines[s0]
    while True:
        guard += 1
        if guard > 3 * n + 10 or nv + 2 >= cap:
            return np.empty((0, 2), np.float64), vt[:0], vs[:0], vl[:0], False
        e = s + reach[s % n]
        closing = nv > 0 and e >= s0 + n
        hi = s0 + n if closing else e
        ls = lines[s % n]
        found = False
        for s2 in range(hi, s, -1):
            l2 = lines[s2 % n]
            x, y, okm = _meet(ls, l2)
            if not okm:
                continue
            t, lam, ok = _locate(lines, s, e, x, y, rect, gp, gq, n)
            if not ok or t < s2 or t > e:
                continue
            if t < t_prev or (t == t_prev and lam <= lam_prev + _EPS):
                continue
            if nv > 0:
                if t > first_t + n:
                    continue
                if s2 == s0 + n:
                    lam0 = (x - l0[0]) * l0[2] + (y - l0[1]) * l0[3]
                    if t == first_t + n and lam0 >= first_lam - _EPS:
                        continue
                elif t >= first_t + n:
                    continue
            vx[nv] = x
            vy[nv] = y
            vt[nv] = t
            vs[nv] = SRC_LINES
            vl[nv] = s2 % n
            nv += 1
            if nv == 1:
                first_t = t
                first_lam = (x - l0[0]) * l0[2] + (y - l0[1]) * l0[3]
            if s2 == s0 + n:
                out = np.empty((nv, 2), np.float64)
                for q in range(nv):
                    out[q, 0] = vx[q]
                    out[q, 1] = vy[q]
                return out, vt[:nv], vs[:nv], vl[:nv], True
            s = s2
            t_prev = t
            l2n = lines[s % n]
            lam_prev = (x - l2n[0]) * l2n[2] + (y - l2n[1]) * l2n[3]
            found = True
            break
        if found:
            continue
        if closing:
            # close with a patch in the first possible piece: a on line s, then b on line s0
            tc = max(s0 + n, t_prev)
            if tc > e or tc > first_t + n:
                return np.empty((0, 2), np.float64), vt[:0], vs[:0], vl[:0], False
            lmin = lam_prev if tc == t_prev else -_BIG
            ax, ay, oka = _chord_point(ls, rect, tc % n, lmin, _BIG)
            lmax = first_lam if tc == first_t + n else _BIG
            bx, by, okb = _chord_point(l0, rect, tc % n, -_BIG, lmax)
            if not (oka and okb):
                return np.empty((0, 2), np.float64), vt[:0], vs[:0], vl[:0], False
            vx[nv] = ax
            vy[nv] = ay
            vt[nv] = tc
            vs[nv] = SRC_PATCH
            vl[nv] = -1
            nv += 1
            vx[nv] = bx
            vy[nv] = by
            vt[nv] = tc
            vs[nv] = SRC_PATCH
            vl[nv] = s0
            nv += 1
            out = np.empty((nv, 2), np.float64)
            for q in range(nv):
                out[q, 0] = vx[q]
                out[q, 1] = vy[q]
            return out, vt[:nv], vs[:nv], vl[:nv], True
        # patch in piece e: a on line s, b on line e
        lmin = lam_prev if e == t_prev else -_BIG
        ax, ay, oka = _chord_point(ls, rect, e % n, lmin, _BIG)
        le = lines[e % n]
        bx, by, okb = _chord_point(le, rect, e % n, -_BIG, _BIG)
        if not (oka and okb):
            return np.empty((0, 2), np.float64), vt[:0], vs[:0], vl[:0], False
        vx[nv] = ax
        vy[nv] = ay
        vt[nv] = e
        vs[nv] = SRC_PATCH
        vl[nv] = -1
        nv += 1
        if nv == 1:
            first_t = e
            first_lam = (ax - l0[0]) * l0[2] + (ay - l0[1]) * l0[3]
        vx[nv] = bx
        vy[nv] = by
        vt[nv] = e
        vs[nv] = SRC_PATCH
        vl[nv] = e % n
        nv += 1
        s = e
        t_prev = e
        lam_prev = (bx - le[0]) * le[2] + (by - le[1]) * le[3]


# ============================================================================================ exact checks


@njit(cache=True)
def _sgn(v: int) -> int:  # pragma: no cover
    return 1 if v > 0 else (-1 if v < 0 else 0)


@njit(cache=True)
def _orient(ax: int, ay: int, bx: int, by: int, cx: int, cy: int) -> int:  # pragma: no cover
    return _sgn((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))


@njit(cache=True)
def _on_seg(ax: int, ay: int, bx: int, by: int, px: int, py: int) -> bool:  # pragma: no cover
    # p collinear with [a, b]: is it on the closed segment?
    return min(ax, bx) <= px <= max(ax, bx) and min(ay, by) <= py <= max(ay, by)


@njit(cache=True)
def segments_meet(
    ax: int, ay: int, bx: int, by: int, cx: int, cy: int, dx: int, dy: int
) -> bool:  # pragma: no cover
    """Whether the closed segments [a, b] and [c, d] share a point (exact)."""
    o1 = _orient(ax, ay, bx, by, cx, cy)
    o2 = _orient(ax, ay, bx, by, dx, dy)
    o3 = _orient(cx, cy, dx, dy, ax, ay)
    o4 = _orient(cx, cy, dx, dy, bx, by)
    if o1 * o2 < 0 and o3 * o4 < 0:
        return True
    if o1 == 0 and _on_seg(ax, ay, bx, by, cx, cy):
        return True
    if o2 == 0 and _on_seg(ax, ay, bx, by, dx, dy):
        return True
    if o3 == 0 and _on_seg(cx, cy, dx, dy, ax, ay):
        return True
    return o4 == 0 and _on_seg(cx, cy, dx, dy, bx, by)


@njit(cache=True)
def edge_ok(
    ux: int,
    uy: int,
    tu: int,
    wx: int,
    wy: int,
    tw: int,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    sc: int,
) -> bool:  # pragma: no cover
    """Whether the segment u → w crosses gates tu+1 … tw in order, each strictly inside.

    u is in piece tu and w in piece tw ≥ tu (unwrapped). Coordinates are scaled by ``sc``; gates are in
    Q-units.
    """
    n = gdir.size
    if tw - tu >= n:
        return False
    pa = 0  # previous crossing parameter pa / pb (0 at u), pb > 0
    pb = 1
    for k in range(tu + 1, tw + 1):
        g = k % n
        d = gdir[g]
        if d == 0 or d == 2:
            gx = gp[g, 0] * sc
            lo = min(gp[g, 1], gq[g, 1]) * sc
            hi = max(gp[g, 1], gq[g, 1]) * sc
            den = wx - ux
            num = gx - ux
            if d == 0 and not (ux < gx < wx):
                return False
            if d == 2 and not (ux > gx > wx):
                return False
            cross = num * (wy - uy)  # (y - uy) * den
            if den < 0:
                den = -den
                num = -num
                cross = -cross
            if not ((lo - uy) * den < cross < (hi - uy) * den):
                return False
        else:
            gy = gp[g, 1] * sc
            lo = min(gp[g, 0], gq[g, 0]) * sc
            hi = max(gp[g, 0], gq[g, 0]) * sc
            den = wy - uy
            num = gy - uy
            if d == 1 and not (uy < gy < wy):
                return False
            if d == 3 and not (uy > gy > wy):
                return False
            cross = num * (wx - ux)
            if den < 0:
                den = -den
                num = -num
                cross = -cross
            if not ((lo - ux) * den < cross < (hi - ux) * den):
                return False
        # crossing parameter num / den must increase strictly
        if k > tu + 1 and not (pa * den < num * pb):
            return False
        pa = num
        pb = den
    return True


@njit(cache=True)
def _in_piece(rect: np.ndarray, t: int, x: int, y: int, sc: int) -> bool:  # pragma: no cover
    return bool(rect[t, 0] * sc < x < rect[t, 1] * sc and rect[t, 2] * sc < y < rect[t, 3] * sc)


@njit(cache=True)
def verify_ring(
    vx: np.ndarray,
    vy: np.ndarray,
    vt: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    sc: int,
    bad: np.ndarray,
) -> bool:  # pragma: no cover
    """Exact check of a ring of the corridor (see the module docstring).

    Marks ``bad[i]`` for failing vertices (a failing edge i → i+1 marks both). Vertices: integer coordinates
    scaled by ``sc``, pieces unwrapped and non-decreasing, within one lap of the first.
    """
    n = gdir.size
    m = vx.size
    ok = True
    for i in range(m):
        bad[i] = False
    if m < 3:
        for i in range(m):
            bad[i] = True
        return False
    for i in range(m):
        j = (i + 1) % m
        tj = vt[j] + (n if j == 0 else 0)
        if tj < vt[i] or (j == 0 and vt[i] < vt[0]):
            bad[i] = True
            bad[j] = True
            ok = False
            continue
        if not _in_piece(rect, vt[i] % n, vx[i], vy[i], sc):
            bad[i] = True
            ok = False
        if not edge_ok(vx[i], vy[i], vt[i], vx[j], vy[j], tj, gp, gq, gdir, sc):
            bad[i] = True
            bad[j] = True
            ok = False
    if vt[m - 1] > vt[0] + n:
        bad[m - 1] = True
        ok = False
    if not ok:
        return False
    # folds: consecutive edges going back along themselves
    for i in range(m):
        a = (i - 1) % m
        b = (i + 1) % m
        o = _orient(vx[a], vy[a], vx[i], vy[i], vx[b], vy[b])
        if o == 0 and (vx[i] - vx[a]) * (vx[b] - vx[i]) + (vy[i] - vy[a]) * (vy[b] - vy[i]) <= 0:
            bad[i] = True
            ok = False
    if not ok:
        return False
    # edges meeting in a piece that holds two or more vertices (the run of vertex 0 may continue from the
    # end of the ring, one lap later)
    jb = m
    while jb - 1 > 0 and vt[jb - 1] == vt[0] + n:
        jb -= 1
    i = 0
    while i < jb:
        j = i
        while j + 1 < jb and vt[j + 1] == vt[i]:
            j += 1
        extra = (m - jb) if i == 0 else 0
        cnt = (j - i + 1) + extra
        if cnt >= 2:
            k0 = (jb - 1) if extra > 0 else (i - 1) % m
            nedge = cnt + 1
            for p in range(nedge):
                pa = (k0 + p) % m
                pb = (pa + 1) % m
                for q in range(p + 2, nedge):
                    qa = (k0 + q) % m
                    qb = (qa + 1) % m
                    if qb == pa:
                        continue
                    if segments_meet(vx[pa], vy[pa], vx[pb], vy[pb], vx[qa], vy[qa], vx[qb], vy[qb]):
                        bad[pb] = True
                        bad[qa] = True
                        ok = False
        i = j + 1
    return ok


# ============================================================================================ snapping


@njit(cache=True)
def snap_ring(
    fx: np.ndarray,
    fy: np.ndarray,
    vt: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: int,
    ix: np.ndarray,
    iy: np.ndarray,
    bad: np.ndarray,
) -> None:  # pragma: no cover
    """Snap float vertices (Q-units) to the coarsest dyadic grids that keep every constraint.

    The grid 2^-k (k ≤ kmax) must keep the vertex in its piece and the edges to its neighbours valid; integer
    results at scale 2^kmax. Vertices for which no grid works are marked bad (rounded at 2^-kmax).
    """
    n = gdir.size
    m = fx.size
    sc = 1 << kmax
    for i in range(m):
        bad[i] = False
    for i in range(m):
        t = vt[i]
        nxt = (i + 1) % m
        tn = vt[nxt] + (n if nxt == 0 else 0)
        # the next vertex as it would be at the finest grid (for i < m-1)
        nx = int(np.round(fx[nxt] * sc))
        ny = int(np.round(fy[nxt] * sc))
        if nxt == 0:
            nx = ix[0]
            ny = iy[0]
        done = False
        for k in range(kmax + 1):
            f = float(1 << k)
            mul = 1 << (kmax - k)
            x = int(np.round(fx[i] * f)) * mul
            y = int(np.round(fy[i] * f)) * mul
            if not _in_piece(rect, t % n, x, y, sc):
                continue
            if i > 0 and not edge_ok(ix[i - 1], iy[i - 1], vt[i - 1], x, y, t, gp, gq, gdir, sc):
                continue
            if m > 1 and not edge_ok(x, y, t, nx, ny, tn, gp, gq, gdir, sc):
                continue
            ix[i] = x
            iy[i] = y
            done = True
            break
        if not done:
            ix[i] = int(np.round(fx[i] * sc))
            iy[i] = int(np.round(fy[i] * sc))
            bad[i] = True


# ============================================================================================ repair


@njit(cache=True)
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


@njit(cache=True)
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


@njit(cache=True)
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


@njit(cache=True)
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
    # sweep; the piece cut by the four rays gives a centre, snapped and checked exactly.
    n = gdir.size
    sc = float(1 << kmax)
    isc = 1 << kmax
    fax = ax / sc
    fay = ay / sc
    fbx = bx / sc
    fby = by / sc
    span = tb - ta
    # scratch (span + 1 rows): cone from a after gates ta+1 .. ta+k in cone[0], from b in cone[1]
    alx = cone[0, 0]
    aly = cone[0, 1]
    arx = cone[0, 2]
    ary = cone[0, 3]
    aok = okc[0]
    blx = cone[1, 0]
    bly = cone[1, 1]
    brx = cone[1, 2]
    bry = cone[1, 3]
    bok = okc[1]
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
        alx[k] = lx
        aly[k] = ly
        arx[k] = rx
        ary[k] = ry
        aok[k] = ok
    # cone from b before gates tb-k+1 .. tb (k = 0 .. span), looking back
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
        blx[k] = lx
        bly[k] = ly
        brx[k] = rx
        bry[k] = ry
        bok[k] = ok
    pxs = poly[0]
    pys = poly[1]
    qxs = poly[2]
    qys = poly[3]
    for t in range(t0, t1 + 1):
        ka = t - ta
        kb = tb - t
        if (ka > 0 and not aok[ka]) or (kb > 0 and not bok[kb]):
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
            nv = _clip_poly(pxs, pys, nv, fax, fay, fax + alx[ka], fay + aly[ka], -1.0, qxs, qys)
            if nv >= 3:
                nv = _clip_poly(qxs, qys, nv, fax, fay, fax + arx[ka], fay + ary[ka], 1.0, pxs, pys)
        if nv >= 3 and kb > 0:
            nv = _clip_poly(pxs, pys, nv, fbx, fby, fbx + blx[kb], fby + bly[kb], 1.0, qxs, qys)
            if nv >= 3:
                nv = _clip_poly(qxs, qys, nv, fbx, fby, fbx + brx[kb], fby + bry[kb], -1.0, pxs, pys)
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
    for rnd in range(2):
        i = 0
        while i < m - 1 and m > 3:
            # vertices i and i+1 (never across the end of the arrays: the second round runs on the ring
            # rotated by half a turn); unwrapped pieces of the neighbours
            ta = t[i - 1] if i > 0 else t[m - 1] - n
            tb = t[i + 2] if i + 2 < m else t[0] + n
            xa = x[i - 1] if i > 0 else x[m - 1]
            ya = y[i - 1] if i > 0 else y[m - 1]
            xb = x[i + 2] if i + 2 < m else x[0]
            yb = y[i + 2] if i + 2 < m else y[0]
            merged = False
            if tb - ta < n:
                wx, wy, tt, ok = _merge_pair(
                    xa, ya, ta, xb, yb, tb, t[i], t[i + 1], rect, gp, gq, gdir, kmax, cone, okc, poly
                )
                if ok:
                    x[i] = wx
                    y[i] = wy
                    t[i] = tt
                    s[i] = SRC_LINES
                    ln[i] = -1
                    for q in range(i + 1, m - 1):
                        x[q] = x[q + 1]
                        y[q] = y[q + 1]
                        t[q] = t[q + 1]
                        s[q] = s[q + 1]
                        ln[q] = ln[q + 1]
                    m -= 1
                    merged = True
            if not merged:
                i += 1
        if rnd == 0 and m > 3:
            # rotate by half a turn, keeping the pieces non-decreasing from vertex 0
            h = m // 2
            rx = np.empty(m, np.int64)
            ry = np.empty(m, np.int64)
            rt = np.empty(m, np.int64)
            rs = np.empty(m, np.int64)
            rl = np.empty(m, np.int64)
            for q in range(m):
                src = (h + q) % m
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


@njit(cache=True)
def window_bound(reach: np.ndarray) -> int:  # pragma: no cover
    """A lower bound on the vertices of any ring of the corridor: the fewest windows covering one lap.

    An edge leaving a vertex in piece t ends in a piece at most t + reach[t] (reach is exact), and the
    pieces of consecutive vertices advance by one lap in total, so a ring of m vertices is a cyclic chain of
    m windows, each starting where the last one ends. Starts are tried across the longest window (every
    chain has a vertex there); the greedy longest jump is optimal for a fixed start.
    """
    n = reach.size
    s0 = 0
    for i in range(n):
        if reach[i] > reach[s0]:
            s0 = i
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
def small_polygon(
    rect: np.ndarray, gp: np.ndarray, gq: np.ndarray, gdir: np.ndarray, reach: np.ndarray, kmax: int, nv: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:  # pragma: no cover
    """For a small corridor, look for a ring of ``nv`` = 3 or 4 vertices (the fewest the windows allow).

    Vertex 0 lies in the shortest window (every ring has a vertex in each window, since i + reach[i] never
    decreases). Vertices 0 and 2 are taken among nine points per piece (a 3 × 3 grid at 1/6, 1/2, 5/6 of
    the piece);
    each vertex between them is placed by :func:`_merge_pair` (the centre of the region both neighbours
    see, searched in every piece between them), so only two of the vertices are enumerated. For a triangle
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
    cone = np.empty((2, 4, n + 1), np.float64)
    okc = np.zeros((2, n + 1), np.bool_)
    poly = np.empty((4, 16), np.float64)
    tx = np.empty(nv, np.int64)
    ty = np.empty(nv, np.int64)
    tt = np.empty(nv, np.int64)
    bad = np.zeros(nv, np.bool_)
    # every window chain has a vertex in every window (i + reach[i] never decreases): start in the shortest
    smin = 0
    for i in range(n):
        if reach[i] < reach[smin]:
            smin = i
    for ta0 in range(smin, smin + reach[smin] + 1):
        ta = ta0 % n
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
            for i in range(per * ta, per * ta + per):
                for c in range(per * (tc % n), per * (tc % n) + per):
                    if nv == 3 and not edge_ok(cx[c], cy[c], tc, cx[i], cy[i], ta + n, gp, gq, gdir, sc):
                        continue
                    wx, wy, tw, ok = _merge_pair(
                        cx[i], cy[i], ta, cx[c], cy[c], tc, ta, tc, rect, gp, gq, gdir, kmax, cone, okc, poly
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
                        ux, uy, tu, oku = _merge_pair(
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
                            cone,
                            okc,
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


@njit(cache=True)
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
    kmax: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """Replace four consecutive vertices by three where the two outer neighbours allow it.

    For vertices a, c1, v, v', c3, b: c1 is moved among its own position and nine points of its piece that
    a sees, c3 likewise towards b, and one point w replacing v, v' is placed by :func:`_merge_pair`. This
    undoes what :func:`merge_ring` cannot (two vertices close together that one vertex would replace only if
    both neighbours moved). Every change is verified exactly on the whole ring, so the ring stays valid; the
    scan stops after a lap without change.
    """
    n = gdir.size
    sc = 1 << kmax
    m = ix.size
    if m < 6:
        return ix, iy, vt, vs, vl
    x = ix.copy()
    y = iy.copy()
    t = vt.copy()
    s = vs.copy()
    ln = vl.copy()
    cone = np.empty((2, 4, n + 1), np.float64)
    okc = np.zeros((2, n + 1), np.bool_)
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
        if tt[5] - tt[0] < n:
            ax = x[jj[0]]
            ay = y[jj[0]]
            bx = x[jj[5]]
            by = y[jj[5]]
            # candidates for c1 (seen from a) and c3 (seeing b): the current point first, then a 3 x 3 grid
            n1 = 0
            n3 = 0
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
                        if edge_ok(ax, ay, tt[0], px, py, tt[1], gp, gq, gdir, sc):
                            c1x[n1] = px
                            c1y[n1] = py
                            n1 += 1
                    elif edge_ok(px, py, tt[4], bx, by, tt[5], gp, gq, gdir, sc):
                        c3x[n3] = px
                        c3y[n3] = py
                        n3 += 1
            for u in range(n1):
                if ok:
                    break
                for v in range(n3):
                    wx, wy, tw, okw = _merge_pair(
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
                        cone,
                        okc,
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


# ============================================================================================ straightening


@njit(cache=True)
def _window_fit(
    dx: int, dy: int, gp: np.ndarray, gq: np.ndarray, g0: int, g1: int, n: int
) -> tuple[int, int, int, int]:  # pragma: no cover
    # Lines dx·Y − dy·X = C (Q-units) crossing gates g0 … g1 (unwrapped) strictly inside and in order: every
    # gate's left end strictly left, its right end strictly right (order then follows, the pieces between
    # the gates being convex), i.e. lo < C < hi. Returns lo, hi and the gates that set them (it stops at the
    # first gate that leaves no offset: those two gates already show it).
    lo = -(1 << 62)
    hi = 1 << 62
    glo = g0
    ghi = g0
    for k in range(g0, g1 + 1):
        g = k % n
        cq = dx * gq[g, 1] - dy * gq[g, 0]
        cp = dx * gp[g, 1] - dy * gp[g, 0]
        if cq > lo:
            lo = cq
            glo = g
        if cp < hi:
            hi = cp
            ghi = g
        if lo >= hi:
            break
    return lo, hi, glo, ghi


@njit(cache=True)
def simplest_line(
    gp: np.ndarray, gq: np.ndarray, g0: int, g1: int, n: int, ex: int, ey: int, depth: int
) -> tuple[bool, int, int, int]:  # pragma: no cover
    """The simplest line crossing gates g0 … g1 (unwrapped) strictly inside and in order.

    Simplest: its primitive direction (dx, dy) has the least |dx| + |dy| (axis-parallel when allowed, then
    45°, …: the Stern–Brocot search of the open interval of slopes, exact), with the offset centred in the
    open interval of offsets. (ex, ey) is a direction known to be allowed (the current edge's): among
    allowed axis directions the one nearest it is taken; otherwise the quadrant of (ex, ey) holds every
    allowed direction. Returns (found, dx, dy, c2) for the line dx·Y − dy·X = c2 / 2 in Q-units; not found
    beyond ``depth`` Stern–Brocot steps.
    """
    # axis directions E, N, W, S
    best = -1
    bdot = 0
    for a in range(4):
        lo, hi, _gl, _gh = _window_fit(_DX[a], _DY[a], gp, gq, g0, g1, n)
        if lo < hi:
            dot = _DX[a] * ex + _DY[a] * ey
            if best < 0 or dot > bdot:
                best = a
                bdot = dot
    if best >= 0:
        lo, hi, _gl, _gh = _window_fit(_DX[best], _DY[best], gp, gq, g0, g1, n)
        return True, _DX[best], _DY[best], lo + hi
    if ex == 0 or ey == 0:
        return False, 0, 0, 0
    sx = 1 if ex > 0 else -1
    sy = 1 if ey > 0 else -1
    # d = u (sx, 0) + w (0, sy); Stern–Brocot on w / u between 0/1 (E1) and 1/0 (E2)
    lu = 1
    lw = 0
    ru = 0
    rw = 1
    for _ in range(depth):
        u = lu + ru
        w = lw + rw
        dx = u * sx
        dy = w * sy
        lo, hi, glo, ghi = _window_fit(dx, dy, gp, gq, g0, g1, n)
        if lo < hi:
            return True, dx, dy, lo + hi
        # infeasible: cross(d, v) >= 0 for v = q[glo] − p[ghi], and every allowed d' has cross(d', v) < 0,
        # a sign that changes at most once along the quadrant: go towards the end where it is negative
        vy = gq[glo, 1] - gp[ghi, 1]
        if sx * vy < 0:  # cross((sx, 0), v) < 0: towards E1 (smaller w / u)
            ru = u
            rw = w
        else:
            lu = u
            lw = w
    return False, 0, 0, 0


@njit(cache=True)
def _vget(
    x: np.ndarray, y: np.ndarray, t: np.ndarray, m: int, n: int, j: int
) -> tuple[int, int, int]:  # pragma: no cover
    # Vertex j of the ring, any integer j: its coordinates and its piece unwrapped by whole laps.
    b = j % m
    return x[b], y[b], t[b] + n * ((j - b) // m)


@njit(cache=True)
def _edge_line(
    x: np.ndarray,
    y: np.ndarray,
    t: np.ndarray,
    isnew: np.ndarray,
    nl: np.ndarray,
    m: int,
    n: int,
    j: int,
) -> tuple[int, int, int]:  # pragma: no cover
    # The line dx·Y − dy·X = C (scaled units) of edge j: its new line, or the line through its vertices.
    b = j % m
    if isnew[b]:
        return nl[b, 0], nl[b, 1], nl[b, 2]
    ax, ay, _ta = _vget(x, y, t, m, n, j)
    bx, by, _tb = _vget(x, y, t, m, n, j + 1)
    dx = bx - ax
    dy = by - ay
    return dx, dy, dx * ay - dy * ax


@njit(cache=True)
def _meet_int(
    d1x: int, d1y: int, c1: int, d2x: int, d2y: int, c2: int
) -> tuple[float, float, bool]:  # pragma: no cover
    # Intersection of dkx·Y − dky·X = ck (k = 1, 2), in floats (exact when both lines are simple).
    den = float(d1x * d2y - d1y * d2x)
    if den == 0.0:
        return 0.0, 0.0, False
    fc1 = float(c1)
    fc2 = float(c2)
    return (fc1 * d2x - d1x * fc2) / den, (fc1 * d2y - d1y * fc2) / den, True


@njit(cache=True)
def _place(
    fx: float,
    fy: float,
    tlo: int,
    thi: int,
    ax: int,
    ay: int,
    ta: int,
    check_prev: bool,
    check_next: bool,
    bx: int,
    by: int,
    tb: int,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: int,
) -> tuple[int, int, int, bool]:  # pragma: no cover
    # A vertex near (fx, fy) (scaled units): the point itself when it is on the grid (an exact meeting
    # point stays exact), else the coarsest dyadic grid point; inside a piece of tlo … thi, the edge from
    # (ax, ay) valid and, with check_next, the edge to (bx, by) too.
    n = gdir.size
    sc = 1 << kmax
    if abs(fx) > 4.0e9 or abs(fy) > 4.0e9:
        return 0, 0, 0, False
    # the piece of the point itself (float test: only a shortcut, the grid points are checked exactly)
    t = tlo
    while t <= thi:
        r = t % n
        if rect[r, 0] * sc < fx < rect[r, 1] * sc and rect[r, 2] * sc < fy < rect[r, 3] * sc:
            break
        t += 1
    if t > thi:
        return 0, 0, 0, False
    for k in range(-1, kmax + 1):
        if k < 0:
            if fx != np.floor(fx) or fy != np.floor(fy):
                continue
            x = int(fx)
            y = int(fy)
        else:
            mul = 1 << (kmax - k)
            x = int(np.round(fx / mul)) * mul
            y = int(np.round(fy / mul)) * mul
        if not _in_piece(rect, t % n, x, y, sc):
            continue
        if check_prev and not edge_ok(ax, ay, ta, x, y, t, gp, gq, gdir, sc):
            continue
        if check_next and not edge_ok(x, y, t, bx, by, tb, gp, gq, gdir, sc):
            continue
        return x, y, t, True
    return 0, 0, 0, False


@njit(cache=True)
def _local_ok(
    x: np.ndarray, y: np.ndarray, t: np.ndarray, m: int, n: int, i: int
) -> bool:  # pragma: no cover
    # After vertices i and i+1 moved: no fold at vertices i−1 … i+2, and (as verify_ring) no two edges
    # meeting around a piece that holds two or more of the vertices i−1 … i+2.
    for j in range(i - 1, i + 3):
        ax, ay, _ta = _vget(x, y, t, m, n, j - 1)
        bx, by, _tb = _vget(x, y, t, m, n, j)
        cx, cy, _tc = _vget(x, y, t, m, n, j + 1)
        if _orient(ax, ay, bx, by, cx, cy) == 0 and (bx - ax) * (cx - bx) + (by - ay) * (cy - by) <= 0:
            return False
    for j in range(i - 1, i + 3):
        _x, _y, tj = _vget(x, y, t, m, n, j)
        lo = j
        while lo > j - m + 1 and _vget(x, y, t, m, n, lo - 1)[2] == tj:
            lo -= 1
        hi = j
        while hi < lo + m - 1 and _vget(x, y, t, m, n, hi + 1)[2] == tj:
            hi += 1
        if hi == lo:
            continue
        # edges lo−1 … hi (edge e joins vertices e and e+1)
        for p in range(lo - 1, hi + 1):
            pax, pay, _a = _vget(x, y, t, m, n, p)
            pbx, pby, _b = _vget(x, y, t, m, n, p + 1)
            for q in range(p + 2, hi + 1):
                if (q + 1 - p) % m == 0:
                    continue
                qax, qay, _c = _vget(x, y, t, m, n, q)
                qbx, qby, _d = _vget(x, y, t, m, n, q + 1)
                if segments_meet(pax, pay, pbx, pby, qax, qay, qbx, qby):
                    return False
    return True


@njit(cache=True)
def _ring_lines(
    x: np.ndarray,
    y: np.ndarray,
    t: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    n: int,
    sc: int,
    vmin: int,
    isnew: np.ndarray,
    nl: np.ndarray,
) -> None:  # pragma: no cover
    # The simplest line of every edge of the ring (windows as in straighten_ring, from variant vmin on).
    m = x.size
    for i in range(m):
        xb, yb, tb = _vget(x, y, t, m, n, i)
        xc, yc, tc = _vget(x, y, t, m, n, i + 1)
        isnew[i] = False
        for variant in range(vmin, 4):
            g0 = tb + (2 if variant <= 1 else 1)
            g1 = tc - (1 if variant % 2 == 0 else 0)
            if g1 < g0:
                continue
            okl, dx, dy, c2 = simplest_line(gp, gq, g0, g1, n, xc - xb, yc - yb, 4 * (g1 - g0) + 64)
            if okl:
                isnew[i] = True
                nl[i, 0] = dx
                nl[i, 1] = dy
                nl[i, 2] = c2 * (sc // 2)
                break


@njit(cache=True)
def _ring_attempt(
    x: np.ndarray,
    y: np.ndarray,
    t: np.ndarray,
    isnew: np.ndarray,
    nl: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:  # pragma: no cover
    # Every vertex where the lines of its two edges meet (new lines where isnew, else the current edges),
    # placed between the pieces of its neighbours; the ring verified exactly.
    n = gdir.size
    m = x.size
    ox = np.empty(m, np.int64)
    oy = np.empty(m, np.int64)
    ot = np.empty(m, np.int64)
    for i in range(m):
        pdx, pdy, pc = _edge_line(x, y, t, isnew, nl, m, n, i - 1)
        qdx, qdy, qc = _edge_line(x, y, t, isnew, nl, m, n, i)
        fx, fy, okm = _meet_int(pdx, pdy, pc, qdx, qdy, qc)
        if not okm:
            return ox, oy, ot, False
        _xa, _ya, ta = _vget(x, y, t, m, n, i - 1)
        _xc, _yc, tc = _vget(x, y, t, m, n, i + 1)
        if i == 0:
            nx, ny, nt, ok = _place(fx, fy, ta, tc, 0, 0, 0, False, False, 0, 0, 0, rect, gp, gq, gdir, kmax)
        elif i < m - 1:
            nx, ny, nt, ok = _place(
                fx,
                fy,
                ot[i - 1],
                tc,
                ox[i - 1],
                oy[i - 1],
                ot[i - 1],
                True,
                False,
                0,
                0,
                0,
                rect,
                gp,
                gq,
                gdir,
                kmax,
            )
        else:
            nx, ny, nt, ok = _place(
                fx,
                fy,
                ot[i - 1],
                min(tc, ot[0] + n),
                ox[i - 1],
                oy[i - 1],
                ot[i - 1],
                True,
                True,
                ox[0],
                oy[0],
                ot[0] + n,
                rect,
                gp,
                gq,
                gdir,
                kmax,
            )
        if not ok:
            return ox, oy, ot, False
        ox[i] = nx
        oy[i] = ny
        ot[i] = nt
    base = (ot[0] // n) * n
    for i in range(m):
        ot[i] -= base
    bad = np.zeros(m, np.bool_)
    return ox, oy, ot, verify_ring(ox, oy, ot, rect, gp, gq, gdir, 1 << kmax, bad)


@njit(cache=True)
def straighten_ring(
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
    """Put each edge of a verified ring on the simplest line its pieces allow; same vertex count.

    Edge by edge: the window of pieces the edge crosses (without its end pieces first, where the vertices
    may move, then with them) gives the simplest line (:func:`simplest_line`); the edge's two vertices move
    to where that line meets its neighbours' lines, exact when on the grid, else snapped to the coarsest
    dyadic grid that keeps the constraints; the move is kept when both vertices lie in pieces of the
    corridor, in order, and every edge they touch crosses its gates (exact checks). The ring is returned
    unchanged if the result fails :func:`verify_ring`.
    """
    n = gdir.size
    m = ix.size
    if m < 3 or n < 2:
        return ix, iy, vt, vs, vl
    sc = 1 << kmax
    x = ix.copy()
    y = iy.copy()
    t = vt.copy()
    ln = vl.copy()
    isnew = np.zeros(m, np.bool_)
    nl = np.zeros((m, 3), np.int64)
    changed = False
    # the whole ring at once first (neighbouring edges often have to change together, e.g. at a corner)
    for vmin in (0, 3):
        _ring_lines(x, y, t, gp, gq, n, sc, vmin, isnew, nl)
        rx, ry, rt, okr = _ring_attempt(x, y, t, isnew, nl, rect, gp, gq, gdir, kmax)
        if okr:
            x = rx
            y = ry
            t = rt
            for i in range(m):
                if isnew[i]:
                    ln[i] = -1
            changed = True
            break
    if not changed:
        for i in range(m):
            isnew[i] = False
    # then edge by edge, twice round (an edge may move once its neighbours have)
    for it in range(2 * m):
        i = it % m
        if isnew[i]:
            continue
        xa, ya, ta = _vget(x, y, t, m, n, i - 1)
        xb, yb, tb = _vget(x, y, t, m, n, i)
        xc, yc, tc = _vget(x, y, t, m, n, i + 1)
        xd, yd, td = _vget(x, y, t, m, n, i + 2)
        span = tc - tb
        if span < 1:
            continue
        pdx, pdy, pc = _edge_line(x, y, t, isnew, nl, m, n, i - 1)
        qdx, qdy, qc = _edge_line(x, y, t, isnew, nl, m, n, i + 1)
        dx = 0
        dy = 0
        c2 = 0
        okl = False
        for trial in range(12):
            # gates of the window: end pieces left out (0), only the first (1), only the last (2), none (3);
            # the offset at the middle of the allowed interval, then at its quarters (when two centred
            # lines meet on a pixel side)
            variant = trial // 3
            frac = trial % 3
            g0 = tb + (2 if variant <= 1 else 1)
            g1 = tc - (1 if variant % 2 == 0 else 0)
            if g1 < g0:
                continue
            if frac == 0:
                okl, dx, dy, c2 = simplest_line(gp, gq, g0, g1, n, xc - xb, yc - yb, 4 * (g1 - g0) + 64)
            if not okl:
                continue
            if frac == 0:
                cc = c2 * (sc // 2)
            else:
                lo, hi, _gl, _gh = _window_fit(dx, dy, gp, gq, g0, g1, n)
                cc = (3 * lo + hi if frac == 1 else lo + 3 * hi) * (sc // 4)
            f1x, f1y, ok1 = _meet_int(pdx, pdy, pc, dx, dy, cc)
            f2x, f2y, ok2 = _meet_int(dx, dy, cc, qdx, qdy, qc)
            if not (ok1 and ok2):
                continue
            nbx, nby, nbt, okb = _place(
                f1x, f1y, ta, tc, xa, ya, ta, True, False, 0, 0, 0, rect, gp, gq, gdir, kmax
            )
            if not okb:
                continue
            ncx, ncy, nct, okc = _place(
                f2x, f2y, nbt, td, nbx, nby, nbt, True, True, xd, yd, td, rect, gp, gq, gdir, kmax
            )
            if not okc:
                continue
            ob = i % m
            oc = (i + 1) % m
            sbx, sby, sbt = x[ob], y[ob], t[ob]
            scx, scy, sct = x[oc], y[oc], t[oc]
            x[ob] = nbx
            y[ob] = nby
            t[ob] = nbt - n * ((i - ob) // m)
            x[oc] = ncx
            y[oc] = ncy
            t[oc] = nct - n * ((i + 1 - oc) // m)
            if _local_ok(x, y, t, m, n, i):
                isnew[ob] = True
                nl[ob, 0] = dx
                nl[ob, 1] = dy
                nl[ob, 2] = cc
                ln[ob] = -1
                changed = True
                break
            x[ob], y[ob], t[ob] = sbx, sby, sbt
            x[oc], y[oc], t[oc] = scx, scy, sct
    if not changed:
        return ix, iy, vt, vs, vl
    base = (t[0] // n) * n
    for i in range(m):
        t[i] -= base
    bad = np.zeros(m, np.bool_)
    if verify_ring(x, y, t, rect, gp, gq, gdir, sc, bad):
        return x, y, t, vs, ln
    return ix, iy, vt, vs, vl


# ============================================================================================ driver


@njit(cache=True)
def _domino(
    c0: int, r0_: int, c1: int, r1: int, sc: int
) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover
    # Cover models, two 4-adjacent pixels visited once each: a counter-clockwise triangle with its vertices
    # inside the open squares, crossing the common side twice (scale sc Q-units). (Under gauss the two
    # pixels are split like every element and the greedy handles them.)
    ux = c1 - c0
    uy = r1 - r0_  # from the first pixel to the second
    vx_ = -uy
    vy_ = ux  # to the left of u
    cx = 4 * c0
    cy = 4 * r0_
    # (a, b) in 1/16 pixel along u and v from the first centre
    pa = np.array([-4, 16 + 4, 12], np.int64)
    pb = np.array([-4, -4, 4], np.int64)
    x = np.empty(3, np.int64)
    y = np.empty(3, np.int64)
    for i in range(3):
        x[i] = cx * sc + (pa[i] * ux + pb[i] * vx_) * sc // 4
        y[i] = cy * sc + (pa[i] * uy + pb[i] * vy_) * sc // 4
    return x, y


@njit(cache=True)
def _kmax_for(rect: np.ndarray) -> int:  # pragma: no cover
    xmin = rect[0, 0]
    xmax = rect[0, 1]
    ymin = rect[0, 2]
    ymax = rect[0, 3]
    for i in range(rect.shape[0]):
        xmin = min(xmin, rect[i, 0])
        xmax = max(xmax, rect[i, 1])
        ymin = min(ymin, rect[i, 2])
        ymax = max(ymax, rect[i, 3])
    ext = max(xmax - xmin, ymax - ymin) + 1
    bits = 0
    while (1 << bits) < ext:
        bits += 1
    k = 30 - bits
    if k > 20:
        k = 20
    if k < 2:
        k = 2
    return k


@njit(cache=True)
def _net_ring(
    r0: np.ndarray, r0t: np.ndarray, kmax: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    sc = 1 << kmax
    m = r0t.size
    ox = np.empty(m, np.int64)
    oy = np.empty(m, np.int64)
    ot = np.empty(m, np.int64)
    osrc = np.full(m, SRC_NET, np.int64)
    for i in range(m):
        ox[i] = r0[i, 0] * sc
        oy[i] = r0[i, 1] * sc
        ot[i] = r0t[i]
    return ox, oy, ot, osrc


# The driver runs in four phases, each over all rings at once and each called from Python: numba
# re-optimises a caller together with everything it calls, so one deep driver compiles the whole call tree
# several times over; flat phases compile each part once.


@njit(cache=True)
def corridors_all(
    codes: np.ndarray, off: np.ndarray, sx: np.ndarray, sy: np.ndarray, h: int, w: int, gauss: bool, kcap: int
) -> tuple[
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
    np.ndarray,
]:  # pragma: no cover
    """Phase 1: border-path elements, visit counts, pieces, gates and net vertices of every ring.

    Returns (eoff, ec, er, edin, edout, enl, cnt, r0off, r0, r0t, poff, rect, pel, gp, gq, gdir, kmax,
    special, full). Ring k has pieces poff[k] … poff[k+1]−1 (``pel`` local element indices) and net
    vertices r0off[k] … with ``r0t`` their local piece; ``special`` is 1 for an isolated pixel (no pieces),
    2 for two pixels visited once each (cover models), else 0.
    """
    eoff, ec, er, edin, edout, enl, r0off, r0, r0e = build_elements(codes, off, sx, sy)
    cnt = count_visits(h, w, ec, er)
    nr = off.size - 1
    cap = 2 * ec.size + 2 * nr + 2
    rect = np.empty((cap, 4), np.int64)
    pel = np.empty(cap, np.int64)
    gp = np.empty((cap, 2), np.int64)
    gq = np.empty((cap, 2), np.int64)
    gdir = np.empty(cap, np.int64)
    poff = np.zeros(nr + 1, np.int64)
    kmax = np.zeros(nr, np.int64)
    special = np.zeros(nr, np.int64)
    full = np.zeros(nr, np.int64)
    r0t = np.full(r0.shape[0], -1, np.int64)
    pos = 0
    for k in range(nr):
        e0 = eoff[k]
        e1 = eoff[k + 1]
        if e1 - e0 == 1 and enl[e0] == 4:
            special[k] = 1
            kmax[k] = 2
            poff[k + 1] = pos
            continue
        rc, pl, p, q, g, fl = build_pieces(e0, e1, ec, er, edin, edout, enl, cnt, gauss)
        n = g.size
        _cp2(rect, pos, rc)
        _cp1(pel, pos, pl)
        _cp2(gp, pos, p)
        _cp2(gq, pos, q)
        _cp1(gdir, pos, g)
        full[k] = fl[0]
        if e1 - e0 == 2 and fl[0] == 1:
            special[k] = 2
        kmax[k] = min(_kmax_for(rc), kcap)
        r0l = np.empty(r0off[k + 1] - r0off[k], np.int64)
        for i in range(r0l.size):
            r0l[i] = r0e[r0off[k] + i] - e0
        _cp1(r0t, r0off[k], net_pieces(r0[r0off[k] : r0off[k + 1]], r0l, rc, pl))
        pos += n
        poff[k + 1] = pos
    return (
        eoff,
        ec,
        er,
        edin,
        edout,
        enl,
        cnt,
        r0off,
        r0,
        r0t,
        poff,
        rect[:pos],
        pel[:pos],
        gp[:pos],
        gq[:pos],
        gdir[:pos],
        kmax,
        special,
        full,
    )


@njit(cache=True)
def reach_all(
    eoff: np.ndarray,
    ec: np.ndarray,
    er: np.ndarray,
    cnt: np.ndarray,
    gauss: bool,
    poff: np.ndarray,
    pel: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    special: np.ndarray,
    full: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover
    """Phase 2: the reach table and the central lines of every ring's pieces."""
    npc = gdir.size
    reach = np.zeros(npc, np.int64)
    lines = np.zeros((npc, 4), np.float64)
    for k in range(eoff.size - 1):
        a = poff[k]
        b = poff[k + 1]
        if special[k] == 1 or b == a:
            continue
        ring_reach(
            eoff[k],
            eoff[k + 1],
            ec,
            er,
            cnt,
            gauss,
            full[k] == 1,
            pel[a:b],
            rect[a:b],
            gp[a:b],
            gq[a:b],
            gdir[a:b],
            reach[a:b],
            lines[a:b],
        )
    return reach, lines


@njit(cache=True)
def greedy_all(
    poff: np.ndarray,
    reach: np.ndarray,
    lines: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    special: np.ndarray,
    periodic: bool,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """Phase 3: the V4 greedy on every ring (one closing rule).

    Returns the float vertices, their pieces,
    sources and edge windows (concatenated), the ring offsets and a success flag per ring.
    """
    nr = poff.size - 1
    cap = 16
    fv = np.empty((cap, 2), np.float64)
    vt = np.empty(cap, np.int64)
    vs = np.empty(cap, np.int64)
    vl = np.empty(cap, np.int64)
    voff = np.zeros(nr + 1, np.int64)
    ok = np.zeros(nr, np.bool_)
    pos = 0
    for k in range(nr):
        a = poff[k]
        b = poff[k + 1]
        if special[k] == 0 and b > a:
            f, t, sr, ln, good = v4_greedy(reach[a:b], lines[a:b], rect[a:b], gp[a:b], gq[a:b], periodic)
            m = t.size
            if good and m >= 3:
                if pos + m > cap:
                    ncap = 2 * cap + m
                    fv = _grow2(fv, pos, ncap)
                    vt = _grow1(vt, pos, ncap)
                    vs = _grow1(vs, pos, ncap)
                    vl = _grow1(vl, pos, ncap)
                    cap = ncap
                _cp2(fv, pos, f)
                _cp1(vt, pos, t)
                _cp1(vs, pos, sr)
                _cp1(vl, pos, ln)
                pos += m
                ok[k] = True
        voff[k + 1] = pos
    return fv[:pos], vt[:pos], vs[:pos], vl[:pos], voff, ok


@njit(cache=True)
def _push(
    xy: np.ndarray,
    src: np.ndarray,
    win: np.ndarray,
    pos: int,
    x: np.ndarray,
    y: np.ndarray,
    s: np.ndarray,
    ln: np.ndarray,
    kk: int,
    x0: int,
    y0: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:  # pragma: no cover
    # Append one closed ring (plane coordinates) to the output buffers, growing them when needed.
    m = x.size
    if pos + m + 1 > xy.shape[0]:
        ncap = 2 * xy.shape[0] + m + 1
        xy = _grow2(xy, pos, ncap)
        src = _grow1(src, pos, ncap)
        win = _grow1(win, pos, ncap)
    f = 1.0 / float(1 << (kk + 2))
    for i in range(m):
        xy[pos + i, 0] = x0 + x[i] * f
        xy[pos + i, 1] = y0 + y[i] * f
        src[pos + i] = s[i]
        win[pos + i] = ln[i]
    xy[pos + m, 0] = xy[pos, 0]
    xy[pos + m, 1] = xy[pos, 1]
    src[pos + m] = -1
    win[pos + m] = -1
    return xy, src, win, pos + m + 1


@njit(cache=True)
def finish_all(
    eoff: np.ndarray,
    ec: np.ndarray,
    er: np.ndarray,
    reach: np.ndarray,
    poff: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: np.ndarray,
    special: np.ndarray,
    r0off: np.ndarray,
    r0: np.ndarray,
    r0t: np.ndarray,
    fa: np.ndarray,
    ta: np.ndarray,
    sa: np.ndarray,
    la: np.ndarray,
    oa: np.ndarray,
    ka: np.ndarray,
    fb: np.ndarray,
    tb: np.ndarray,
    sb: np.ndarray,
    lb: np.ndarray,
    ob: np.ndarray,
    kb: np.ndarray,
    x0: int,
    y0: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """Phase 4: snap, verify, prune and (locally) repair every ring; emit closed rings in plane coordinates.

    Two greedy results per ring (a: periodic closing, b: closing on the first line): the one with fewer
    vertices is tried first, then the other; if neither verifies, the better one is repaired with the safety
    net. Returns ``xy`` (closed rings), ``roff`` (ring offsets into xy), ``status`` per ring, ``src`` and
    ``win`` per vertex (−1 on the closing repeats).
    """
    nr = eoff.size - 1
    cap = 4 * r0.shape[0] + 8 * nr + 16
    xy = np.empty((cap, 2), np.float64)
    src = np.empty(cap, np.int64)
    win = np.empty(cap, np.int64)
    roff = np.zeros(nr + 1, np.int64)
    status = np.zeros(nr, np.int64)
    pos = 0
    for k in range(nr):
        e0 = eoff[k]
        a = poff[k]
        b = poff[k + 1]
        kk = kmax[k]
        sc = 1 << kk
        if special[k] == 1:
            cx = 4 * ec[e0]
            cy = 4 * er[e0]
            x = np.empty(3, np.int64)
            y = np.empty(3, np.int64)
            x[0] = (cx - 1) * sc
            x[1] = (cx + 1) * sc
            x[2] = cx * sc
            y[0] = (cy - 1) * sc
            y[1] = (cy - 1) * sc
            y[2] = (cy + 1) * sc
            s3 = np.full(3, SRC_SINGLE, np.int64)
            xy, src, win, pos = _push(xy, src, win, pos, x, y, s3, np.full(3, -1, np.int64), kk, x0, y0)
            status[k] = RING_SINGLE
            roff[k + 1] = pos
            continue
        if special[k] == 2:
            x, y = _domino(ec[e0], er[e0], ec[e0 + 1], er[e0 + 1], sc)
            s3 = np.full(3, SRC_SINGLE, np.int64)
            xy, src, win, pos = _push(xy, src, win, pos, x, y, s3, np.full(3, -1, np.int64), kk, x0, y0)
            status[k] = RING_SINGLE
            roff[k + 1] = pos
            continue
        rc = rect[a:b]
        p = gp[a:b]
        q = gq[a:b]
        g = gdir[a:b]
        rv = r0[r0off[k] : r0off[k + 1]]
        rt = r0t[r0off[k] : r0off[k + 1]]
        done = False
        # candidates in order of vertex count
        na_ = oa[k + 1] - oa[k] if ka[k] else 1 << 60
        nb_ = ob[k + 1] - ob[k] if kb[k] else 1 << 60
        first_b = nb_ < na_
        best_x = np.zeros(0, np.int64)
        best_y = np.zeros(0, np.int64)
        best_t = np.zeros(0, np.int64)
        best_s = np.zeros(0, np.int64)
        best_bad = np.zeros(0, np.bool_)
        for attempt in range(2):
            use_b = first_b if attempt == 0 else not first_b
            if use_b:
                if not kb[k]:
                    continue
                fv = fb[ob[k] : ob[k + 1]]
                vt = tb[ob[k] : ob[k + 1]]
                vs = sb[ob[k] : ob[k + 1]]
                vl = lb[ob[k] : ob[k + 1]]
            else:
                if not ka[k]:
                    continue
                fv = fa[oa[k] : oa[k + 1]]
                vt = ta[oa[k] : oa[k + 1]]
                vs = sa[oa[k] : oa[k + 1]]
                vl = la[oa[k] : oa[k + 1]]
            m = vt.size
            ix = np.empty(m, np.int64)
            iy = np.empty(m, np.int64)
            bad = np.zeros(m, np.bool_)
            fx = np.empty(m, np.float64)
            fy = np.empty(m, np.float64)
            for i in range(m):
                fx[i] = fv[i, 0]
                fy[i] = fv[i, 1]
            snap_ring(fx, fy, vt, rc, p, q, g, kk, ix, iy, bad)
            bad2 = np.zeros(m, np.bool_)
            good = verify_ring(ix, iy, vt, rc, p, q, g, sc, bad2)
            for i in range(m):
                if bad[i]:
                    good = False
                    bad2[i] = True
            if not good:
                # a redundant vertex may be the culprit (three in one piece crossing): prune and re-check
                jx, jy, jt, js, jl = prune_ring(ix, iy, vt, vs, vl, rc, p, q, g, sc, False)
                if jt.size >= 3 and jt.size < m:
                    jbad = np.zeros(jt.size, np.bool_)
                    if verify_ring(jx, jy, jt, rc, p, q, g, sc, jbad):
                        ix, iy, vt, vs, vl = jx, jy, jt, js, jl
                        good = True
            if good:
                px, py, pt, ps, pl = prune_ring(ix, iy, vt, vs, vl, rc, p, q, g, sc)
                px, py, pt, ps, pl = merge_ring(px, py, pt, ps, pl, rc, p, q, g, kk)
                if px.size >= 6 and px.size > window_bound(reach[a:b]):
                    px, py, pt, ps, pl = relink_ring(px, py, pt, ps, pl, rc, p, q, g, kk)
                if px.size > 3 and b - a <= _SMALL_POLY:
                    # a small corridor: search for the fewest vertices its windows allow (3 or 4)
                    lbv = max(3, window_bound(reach[a:b]))
                    for nvv in range(lbv, min(px.size - 1, 4) + 1):
                        tx, ty, tt, okt = small_polygon(rc, p, q, g, reach[a:b], kk, nvv)
                        if okt:
                            px = tx
                            py = ty
                            pt = tt
                            ps = np.full(nvv, SRC_LINES, np.int64)
                            pl = np.full(nvv, -1, np.int64)
                            break
                px, py, pt, ps, pl = straighten_ring(px, py, pt, ps, pl, rc, p, q, g, kk)
                xy, src, win, pos = _push(xy, src, win, pos, px, py, ps, pl, kk, x0, y0)
                status[k] = RING_V4
                done = True
                break
            if best_t.size == 0:
                best_x = ix
                best_y = iy
                best_t = vt.copy()
                best_s = vs.copy()
                best_bad = bad2
        if not done and b - a <= _SMALL:
            # no greedy ring verified: a small corridor may still hold a triangle (a 1 x 3 bar under gauss)
            tx, ty, tt, okt = small_triangle(rc, p, q, g, reach[a:b], kk)
            if okt:
                tbad = np.zeros(3, np.bool_)
                if verify_ring(tx, ty, tt, rc, p, q, g, sc, tbad):
                    s3 = np.full(3, SRC_LINES, np.int64)
                    xy, src, win, pos = _push(
                        xy, src, win, pos, tx, ty, s3, np.full(3, -1, np.int64), kk, x0, y0
                    )
                    status[k] = RING_V4
                    done = True
        if not done and best_t.size >= 3:
            # local repair: widen the removed runs until the spliced ring verifies
            m = best_t.size
            remove = best_bad.copy()
            for _attempt in range(6):
                nrm = 0
                for i in range(m):
                    if remove[i]:
                        nrm += 1
                if nrm >= m - 1:
                    break
                sx_, sy_, st_, ss_, oks = splice_ring(
                    best_x, best_y, best_t, best_s, remove, rv, rt, rc, p, g, kk
                )
                if oks and st_.size >= 3:
                    bad3 = np.zeros(st_.size, np.bool_)
                    if verify_ring(sx_, sy_, st_, rc, p, q, g, sc, bad3):
                        sl_ = np.full(st_.size, -1, np.int64)
                        px, py, pt, ps, pl = prune_ring(sx_, sy_, st_, ss_, sl_, rc, p, q, g, sc)
                        px, py, pt, ps, pl = merge_ring(px, py, pt, ps, pl, rc, p, q, g, kk)
                        xy, src, win, pos = _push(xy, src, win, pos, px, py, ps, pl, kk, x0, y0)
                        status[k] = RING_PARTIAL
                        done = True
                        break
                grown = remove.copy()
                for i in range(m):
                    if remove[i]:
                        grown[(i - 1) % m] = True
                        grown[(i + 1) % m] = True
                remove = grown
        if not done:
            ox, oy, ot, osrc = _net_ring(rv, rt, kk)
            xy, src, win, pos = _push(
                xy, src, win, pos, ox, oy, osrc, np.full(ot.size, -1, np.int64), kk, x0, y0
            )
            status[k] = RING_NET
        roff[k + 1] = pos
    return xy[:pos], roff, status, src[:pos], win[:pos]


@njit(cache=True)
def check_nets(
    poff: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: np.ndarray,
    special: np.ndarray,
    r0off: np.ndarray,
    r0: np.ndarray,
    r0t: np.ndarray,
) -> np.ndarray:  # pragma: no cover
    """Whether each ring's safety net passes the exact corridor check (it always should; tests assert it)."""
    nr = poff.size - 1
    out = np.ones(nr, np.bool_)
    for k in range(nr):
        a = poff[k]
        b = poff[k + 1]
        if special[k] == 1:
            continue
        rt = r0t[r0off[k] : r0off[k + 1]]
        for i in range(rt.size):
            if rt[i] < 0:
                out[k] = False
        if not out[k]:
            continue
        ox, oy, ot, _s = _net_ring(r0[r0off[k] : r0off[k + 1]], rt, kmax[k])
        bad = np.zeros(ot.size, np.bool_)
        out[k] = verify_ring(ox, oy, ot, rect[a:b], gp[a:b], gq[a:b], gdir[a:b], 1 << kmax[k], bad)
    return out
