"""Phase 2 of R on long windows: every reach of a ring in one sliding pass (amortized O(n) preimages).

:func:`._reach.general_reach` builds the preimage of each start's window from scratch, gate by gate, so a
ring costs the sum of its reaches: quadratic on a one-pixel-wide line under the cover models (every pixel
is visited twice, so no window is a plain DSS, and every window runs to the far end: 4.4 s for a 3,000-pixel
line). Here the windows slide instead. The preimage of a window is the intersection of one convex polygon
per gate end (in the dual plane of oriented lines), an associative operation, so the classic two-stack queue
applies: for the starts i of a block [s, m) the suffix preimages B_i (gates i+1 … m) are built once,
backwards, and kept; the front F (gates m+1 … j) grows one gate at a time; window [i, j] admits a line iff
B_i ∩ F is not empty. Each gate enters one suffix and one front, so a ring costs O(n) clippings plus one
intersection test per step of j or i.

Lines are parametrized in four fixed quadrants of directions d(t) = (sgx (1 − t), sgy t), t ∈ [0, 1] (the
cells of :mod:`._reach`, whose polygons and clipping this module reuses); a polygon is its four quadrant
polygons, most of them empty. Constraint ids are global: 2k for the left end of unwrapped gate k, 2k + 1 for
its right end. The central line of each window is the one :func:`._reach._best_line` picks on the window's
polygon, in the order of quadrants :func:`._reach.general_reach` uses; it can differ from that function's
line only where the max-margin choice ties between constraints listed in a different order (the reach,
a property of the window, never differs, and every line R uses is verified exactly later).
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit
from mrm.geometry.reconstruct._base import _BIG, _grow1, _grow2
from mrm.geometry.reconstruct._reach import _QUAD_X, _QUAD_Y, _best_line, _clip, _vline

#: Most vertices a polygon of the sliding pass may have; a ring that needs more is left to
#: :func:`._reach.general_reach` (the polygons seen have 3 to 8).
CAP = 48

# The four fixed quadrants (sgx, sgy).
_FQX = np.array([1, -1, -1, 1], dtype=np.int64)
_FQY = np.array([1, 1, -1, -1], dtype=np.int64)


@njit(cache=True, inline="always")
def _quadrant(sgx: int, sgy: int) -> int:  # pragma: no cover
    if sgx > 0:
        return 0 if sgy > 0 else 3
    return 1 if sgy > 0 else 2


@leaf_njit(cache=True)
def _init_gate(
    buf: np.ndarray, vb: np.ndarray, q: int, w: int, pid: int, ptx: np.ndarray, pty: np.ndarray
) -> int:  # pragma: no cover
    # Into buf[q, w]: the dual polygon of the lines of quadrant q crossing the gate whose ends are pid (left)
    # and pid + 1 (right), with its vertex lines; 0 when no line of the quadrant crosses it forward.
    sgx = _FQX[q]
    sgy = _FQY[q]
    ex = ptx[pid] - ptx[pid + 1]
    ey = pty[pid] - pty[pid + 1]
    h0 = sgx * ey
    h1 = -sgy * ex
    if h0 <= 0 and h1 <= 0:
        return 0
    if h0 > 0 and h1 > 0:
        buf[q, w, 0] = pid
        buf[q, w, 1] = -2
        buf[q, w, 2] = pid + 1
        buf[q, w, 3] = -1
        sz = 4
    elif h0 > 0:
        buf[q, w, 0] = pid
        buf[q, w, 1] = pid + 1
        buf[q, w, 2] = -1
        sz = 3
    else:
        buf[q, w, 0] = pid
        buf[q, w, 1] = -2
        buf[q, w, 2] = pid + 1
        sz = 3
    for v in range(sz):
        _vline(buf[q, w, v - 1 if v > 0 else sz - 1], buf[q, w, v], sgx, sgy, ptx, pty, vb, q, w, v)
    return sz


@leaf_njit(cache=True)
def _clip_in(
    buf: np.ndarray,
    vb: np.ndarray,
    cur: np.ndarray,
    size: np.ndarray,
    q: int,
    newid: int,
    ptx: np.ndarray,
    pty: np.ndarray,
    sg: np.ndarray,
) -> bool:  # pragma: no cover
    # Clip quadrant q of the polygon (buf, vb, cur, size) by one constraint; False if it no longer fits CAP.
    if size[q] == 0:
        return True
    if size[q] + 1 > buf.shape[2]:
        return False
    r = _clip(buf, vb, q, cur[q], size[q], newid, _FQX[q], _FQY[q], ptx, pty, sg)
    if r == 0:
        size[q] = 0
    elif r > 0:
        size[q] = r
        cur[q] = 1 - cur[q]
    return True


@njit(cache=True)
def _pack_poly(
    buf: np.ndarray,
    vb: np.ndarray,
    cur: np.ndarray,
    size: np.ndarray,
    pid: np.ndarray,
    pvb: np.ndarray,
    pos: int,
    poff: np.ndarray,
    psize: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, int]:  # pragma: no cover
    # A working polygon's live buffers appended to the packed store (pid, pvb) from pos, quadrant q at
    # poff[q] with psize[q] vertices; the store grows when full. Returns it and the new end.
    need = pos + size[0] + size[1] + size[2] + size[3]
    if need > pid.size:
        ncap = max(2 * pid.size, need)
        pid = _grow1(pid, pos, ncap)
        pvb = _grow2(pvb, pos, ncap)
    return pid, pvb, _write_packed(buf, vb, cur, size, pid, pvb, pos, poff, psize)


@leaf_njit(cache=True)
def _write_packed(
    buf: np.ndarray,
    vb: np.ndarray,
    cur: np.ndarray,
    size: np.ndarray,
    pid: np.ndarray,
    pvb: np.ndarray,
    pos: int,
    poff: np.ndarray,
    psize: np.ndarray,
) -> int:  # pragma: no cover
    # A working polygon's live buffers written at pos of a packed store with room for them (quadrant q at
    # poff[q], psize[q] vertices); returns the new end. Also the snapshot of W (a store of one polygon).
    for q in range(4):
        sz = size[q]
        poff[q] = pos
        psize[q] = sz
        c = cur[q]
        for v in range(sz):
            pid[pos + v] = buf[q, c, v]
            for u in range(4):
                pvb[pos + v, u] = vb[q, c, v, u]
        pos += sz
    return pos


@njit(cache=True)
def _unpack_poly(
    pid: np.ndarray,
    pvb: np.ndarray,
    poff: np.ndarray,
    psize: np.ndarray,
    dbuf: np.ndarray,
    dvb: np.ndarray,
    dcur: np.ndarray,
    dsize: np.ndarray,
) -> None:  # pragma: no cover
    # A polygon of the packed store into buffer 0 of a working one.
    for q in range(4):
        sz = psize[q]
        o = poff[q]
        dsize[q] = sz
        dcur[q] = 0
        for v in range(sz):
            dbuf[q, 0, v] = pid[o + v]
            for u in range(4):
                dvb[q, 0, v, u] = pvb[o + v, u]


@leaf_njit(cache=True)
def _meet_front(
    wbuf: np.ndarray,
    wvb: np.ndarray,
    wcur: np.ndarray,
    wsize: np.ndarray,
    fbuf: np.ndarray,
    fcur: np.ndarray,
    fsize: np.ndarray,
    ptx: np.ndarray,
    pty: np.ndarray,
    sg: np.ndarray,
) -> int:  # pragma: no cover
    # The working polygon (a copy of a suffix B) clipped by the constraints on the boundary of the front F,
    # quadrant by quadrant (F's own boundary is all of F that matters inside its quadrant). Returns how many
    # quadrants stay non-empty, or −1 if a polygon outgrew CAP.
    alive = 0
    for q in range(4):
        if fsize[q] == 0:
            wsize[q] = 0
            continue
        c = fcur[q]
        for v in range(fsize[q]):
            cid = fbuf[q, c, v]
            if cid >= 0:
                if not _clip_in(wbuf, wvb, wcur, wsize, q, cid, ptx, pty, sg):
                    return -1
                if wsize[q] == 0:
                    break
        if wsize[q] > 0:
            alive += 1
    return alive


@njit(cache=True)
def sliding_reach(
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    todo: np.ndarray,
    reach: np.ndarray,
    lines: np.ndarray,
    cap: int = CAP,
) -> bool:  # pragma: no cover
    """Reach and central lines of the starts with ``todo[i]``, by one sliding pass over the ring.

    Same reach and lines as :func:`._reach.general_reach` (see the module docstring). Returns False,
    leaving ``reach`` and ``lines`` partly written, if some preimage polygon outgrew ``cap`` vertices; the
    caller then uses :func:`._reach.general_reach`.
    """
    n = gdir.size
    cap = max(cap, 2)  # a gate's own polygon has up to four vertices
    # gate ends over two laps: the windows of the starts 0 … n−1 end before gate 2n
    ptx = np.empty(4 * n + 4, np.int32)  # int32 as gp, gq: half the scratch of the largest ring
    pty = np.empty(4 * n + 4, np.int32)
    for k in range(2 * n + 2):
        g = k % n
        ptx[2 * k] = gp[g, 0]
        pty[2 * k] = gp[g, 1]
        ptx[2 * k + 1] = gq[g, 0]
        pty[2 * k + 1] = gq[g, 1]
    sg = np.empty(cap + 2, np.int64)
    # working polygons: W (a suffix met with the front) and F (the front), double-buffered for _clip
    wbuf = np.empty((4, 2, cap + 2), np.int64)
    wvb = np.empty((4, 2, cap + 2, 4), np.int64)
    wcur = np.zeros(4, np.int64)
    wsize = np.zeros(4, np.int64)
    fbuf = np.empty((4, 2, cap + 2), np.int64)
    fvb = np.empty((4, 2, cap + 2, 4), np.int64)
    fcur = np.zeros(4, np.int64)
    fsize = np.zeros(4, np.int64)
    sid = np.empty(4 * (cap + 2), np.int64)  # a snapshot of W, packed like the suffixes
    svb = np.empty((4 * (cap + 2), 4), np.int64)
    soff = np.zeros(4, np.int64)
    ssize = np.zeros(4, np.int64)
    ffull = True  # F has no gate yet (the whole plane)
    # the suffixes B_x, x in [base, m): gates x+1 … m, packed one after the other (quadrant q of B_x is
    # bsize[x − base, q] vertices from boff[x − base, q] in bid, bvb): they have 3 to 8 vertices, so a
    # slot of cap vertices per quadrant each would take ~25 times the memory (2.8 MB on the camera image)
    blen = 16
    bsize = np.zeros((blen, 4), np.int64)
    boff = np.zeros((blen, 4), np.int64)
    bid = np.empty(16 * blen, np.int64)
    bvb = np.empty((16 * blen, 4), np.int64)
    bpos = 0
    base = 0
    m = 0  # no block yet
    j = 0
    line = np.empty(4, np.float64)
    best = np.empty(4, np.float64)
    ida = np.empty(cap + 2, np.int64)
    cand = np.empty(256, np.float64)
    last = -1
    for i in range(n):
        if todo[i]:
            last = i
    for i in range(last + 1):
        if not todo[i]:
            # nothing to compute: window [i', j] still admits a line for the next start i' wanted (a
            # window with fewer gates), and its suffix B_i' is stored or built then
            continue
        # ---- the window [i, j] admits a line and B_i is stored (or i == m: B is the whole plane)
        if j < i + 1 or i >= m:
            # rebuild the block: suffixes of gates up to m = max(j, i + 1), built backwards
            m = max(j, i + 1)
            j = m
            if m - i > blen:
                blen = 2 * (m - i)
                bsize = np.zeros((blen, 4), np.int64)
                boff = np.zeros((blen, 4), np.int64)
            base = i
            bpos = 0
            for q in range(4):
                wcur[q] = 0
                wsize[q] = _init_gate(wbuf, wvb, q, 0, 2 * m, ptx, pty)
            bid, bvb, bpos = _pack_poly(
                wbuf, wvb, wcur, wsize, bid, bvb, bpos, boff[m - 1 - base], bsize[m - 1 - base]
            )
            for x in range(m - 2, i - 1, -1):
                for pt in range(2):
                    for q in range(4):
                        if not _clip_in(wbuf, wvb, wcur, wsize, q, 2 * (x + 1) + pt, ptx, pty, sg):
                            return False
                bid, bvb, bpos = _pack_poly(
                    wbuf, wvb, wcur, wsize, bid, bvb, bpos, boff[x - base], bsize[x - base]
                )
            ffull = True
        # ---- W = B_i ∩ F, then extend j while W ∩ (gate j+1) is not empty; F grows with j
        _unpack_poly(bid, bvb, boff[i - base], bsize[i - base], wbuf, wvb, wcur, wsize)
        if not ffull and _meet_front(wbuf, wvb, wcur, wsize, fbuf, fcur, fsize, ptx, pty, sg) < 0:
            return False
        spoiled = False  # W lost to a failed clip (its buffers are reused): back from the snapshot
        while j < i + n - 1:
            g = j + 1
            # the line needs W as it was before the gate that is one too many
            _write_packed(wbuf, wvb, wcur, wsize, sid, svb, 0, soff, ssize)
            alive = 0
            for q in range(4):
                for pt in range(2):
                    if not _clip_in(wbuf, wvb, wcur, wsize, q, 2 * g + pt, ptx, pty, sg):
                        return False
                if wsize[q] > 0:
                    alive += 1
            if alive == 0:
                spoiled = True
                break
            if ffull:
                for q in range(4):
                    fcur[q] = 0
                    fsize[q] = _init_gate(fbuf, fvb, q, 0, 2 * g, ptx, pty)
                ffull = False
            else:
                for q in range(4):
                    for pt in range(2):
                        if not _clip_in(fbuf, fvb, fcur, fsize, q, 2 * g + pt, ptx, pty, sg):
                            return False
            j = g
        reach[i] = j - i
        # the window's polygon W = B_i ∩ F, and its central line in general_reach's order of quadrants
        if spoiled:
            _unpack_poly(sid, svb, soff, ssize, wbuf, wvb, wcur, wsize)
        d0 = gdir[(i + 1) % n]
        bm = -_BIG
        for k in range(2):
            sgx = _QUAD_X[d0, k]
            sgy = _QUAD_Y[d0, k]
            q = _quadrant(sgx, sgy)
            if wsize[q] > 0:
                mm = _best_line(wbuf, q, wcur[q], wsize[q], sgx, sgy, ptx, pty, line, ida, cand, 2 * (i + 1))
                if mm > bm:
                    bm = mm
                    for u in range(4):
                        best[u] = line[u]
        for u in range(4):
            lines[i, u] = best[u]
    return True
