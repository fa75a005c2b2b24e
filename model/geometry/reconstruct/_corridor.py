"""Phase 1 of R: border-path elements, pieces and gates of every ring (:mod:`._kernels`)."""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import njit
from mrm.geometry.reconstruct._base import _DX, _DY, _LXD, _LYD

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
    ec = np.empty(cap, np.int32)
    er = np.empty(cap, np.int32)
    edin = np.empty(cap, np.int8)
    edout = np.empty(cap, np.int8)
    enl = np.empty(cap, np.int8)
    eoff = np.zeros(nr + 1, np.int64)
    r0 = np.empty((lt + 1, 2), np.int32)
    r0e = np.empty(lt + 1, np.int32)
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
def element_visits(ec: np.ndarray, er: np.ndarray, h: int, w: int) -> np.ndarray:  # pragma: no cover
    """For each element, how many elements (over all rings) sit on its pixel (c, r), saturated at 2.

    0 ≤ r < h and 0 ≤ c < w. Time and memory O(elements + h + w): the elements are bucketed by row and
    counted in one row of scratch at a time, so a large sparse image costs nothing per pixel (a whole
    (h, w) counter cost 63 ms at 8192², in page faults).
    """
    ne = ec.size
    start = np.zeros(h + 1, np.int64)
    for k in range(ne):
        start[er[k] + 1] += 1
    for r in range(h):
        start[r + 1] += start[r]
    fill = start[:-1].copy()
    order = np.empty(ne, np.int32)
    for k in range(ne):
        order[fill[er[k]]] = k
        fill[er[k]] += 1
    row = np.zeros(w, np.uint8)
    out = np.empty(ne, np.uint8)
    for r in range(h):
        a = start[r]
        b = start[r + 1]
        for i in range(a, b):
            c = ec[order[i]]
            if row[c] < 2:
                row[c] += 1
        for i in range(a, b):
            out[order[i]] = row[ec[order[i]]]
        for i in range(a, b):
            row[ec[order[i]]] = 0
    return out


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


@njit(cache=True, inline="always")
def side_gate(
    rect: np.ndarray, a: int, k: int, gp: np.ndarray, gq: np.ndarray, gdir: np.ndarray
) -> None:  # pragma: no cover
    # Gate k between pieces a and k (used by both corridors): their common side, oriented so that gp[k] is
    # its left end and gq[k] its right end when crossing in direction gdir[k].
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
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """Pieces and gates of the ring whose elements are e0 … e1−1.

    Returns ``rect`` (n, 4) [x0, x1, y0, y1], ``pel`` (element of each piece, local index), ``gp``, ``gq``
    (n, 2) the left and right end of gate k (between piece k−1 and k, looking in the crossing direction),
    ``gdir`` (n) the crossing direction and ``full`` (1 if every piece is a full pixel). ``cnt`` is
    :func:`element_visits` (an element's pixel visited twice or more is split between its visits).
    """
    ne = e1 - e0
    cap = 2 * ne + 2
    rect = np.empty((cap, 4), np.int32)
    pel = np.empty(cap, np.int32)
    internal = np.zeros(cap, np.int8)  # 1: the gate before this piece is inside its pixel
    n = 0
    full = 1
    for k in range(ne):
        e = e0 + k
        c = ec[e]
        r = er[e]
        din = edin[e]
        dout = edout[e]
        nl = enl[e]
        if cnt[e] < 2:
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
    gp = np.empty((n, 2), np.int32)
    gq = np.empty((n, 2), np.int32)
    gdir = np.empty(n, np.int8)
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
        side_gate(rect, a, k, gp, gq, gdir)
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
    out = np.full(r0.shape[0], -1, np.int32)
    for v in range(r0.shape[0]):
        k = first[r0e_local[v]]
        while 0 <= k < n and pel[k] == r0e_local[v]:
            if rect[k, 0] < r0[v, 0] < rect[k, 1] and rect[k, 2] < r0[v, 1] < rect[k, 3]:
                out[v] = k
                break
            k += 1
    return out
