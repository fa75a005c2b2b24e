"""Crack (inter-pixel) boundary tracing into Freeman chains, and the fill back.

Reference: docs/design.md §4, docs/algorithms.md §2.5.

Coordinates here are *array* coordinates: pixel (c, r) is ``mask[r, c]`` and pointel (c, r) is its lower-left
corner (row 0 is the lowest y). :mod:`mrm.reps.region` adds the origin.

Freeman codes: 0 = E (+1, 0), 1 = N (0, +1), 2 = W (−1, 0), 3 = S (0, −1). The pixel on the left of code ``d``
leaving pointel (i, j) is (i + LX[d], j + LY[d]) and the one on its right (i + RX[d], j + RY[d]).

Binary masks are traced with the (4, 8) rule: walk each linel with the object on the left and look at the two
pixels ahead, front-left FL and front-right FR: if FL is not in the object turn left; else if FR is in the
object turn right; else go straight. Each traced ring separates one 4-component of the object (on its left)
from one 8-component of the complement (on its right); outer rings run counter-clockwise, hole rings
clockwise, and every ring is rotated to its canonical start, the pointel with the smallest (y, x).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import njit
from mrm.geometry.topology.labeling import Runs, as_u8, label_runs

U8Array = npt.NDArray[np.uint8]
I32Array = npt.NDArray[np.int32]
I64Array = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]

DX = np.array([1, 0, -1, 0], dtype=np.int64)
DY = np.array([0, 1, 0, -1], dtype=np.int64)
LX = np.array([0, -1, -1, 0], dtype=np.int64)
LY = np.array([0, 0, -1, -1], dtype=np.int64)
RX = np.array([0, 0, -1, -1], dtype=np.int64)
RY = np.array([-1, 0, 0, -1], dtype=np.int64)


class Rings(NamedTuple):
    """All crack rings of a mask, in array coordinates (see the module docstring).

    Ring ``k`` has the codes ``codes[off[k]:off[k+1]]`` (values 0..3) from its canonical start pointel
    ``(sx[k], sy[k])``; ``comp[k]`` is the label of the object component on its left (``runs.label``),
    ``bg[k]`` the label of the background component on its right (``runs.bg_label``, 0 = unbounded);
    ``area2[k]`` is twice its signed area (> 0 for outer rings, < 0 for holes); ``box[k]`` is
    (xmin, ymin, xmax, ymax) of its pointels. Rings come in raster order of their first bottom-edge linel.
    """

    codes: U8Array
    off: I64Array
    sx: I64Array
    sy: I64Array
    comp: I32Array
    bg: I32Array
    area2: I64Array
    box: I64Array
    runs: Runs


@njit(cache=True)
def _count_linels(rs: I32Array, re: I32Array, ptr: I64Array) -> int:  # pragma: no cover
    # Vertical linels: two per run. Horizontal ones between rows r-1 and r: |row r xor row r-1|.
    h = ptr.size - 1
    total = 2 * rs.size
    for r in range(h + 1):
        la = 0
        lb = 0
        ov = 0
        if r > 0:
            for k in range(ptr[r - 1], ptr[r]):
                la += re[k] - rs[k] + 1
        if r < h:
            for k in range(ptr[r], ptr[r + 1]):
                lb += re[k] - rs[k] + 1
        if 0 < r < h:
            i, i1 = ptr[r - 1], ptr[r]
            j, j1 = ptr[r], ptr[r + 1]
            while i < i1 and j < j1:
                lo = max(rs[i], rs[j])
                hi = min(re[i], re[j])
                if hi >= lo:
                    ov += hi - lo + 1
                if re[i] < re[j]:
                    i += 1
                else:
                    j += 1
        total += la + lb - 2 * ov
    return total


@njit(cache=True)
def _inside(m: U8Array, x: int, y: int) -> bool:  # pragma: no cover
    return 0 <= y < m.shape[0] and 0 <= x < m.shape[1] and bool(m[y, x] != 0)


@njit(cache=True)
def _reverse(a: U8Array, i: int, j: int) -> None:  # pragma: no cover
    # Reverse a[i:j] in place.
    j -= 1
    while i < j:
        t = a[i]
        a[i] = a[j]
        a[j] = t
        i += 1
        j -= 1


@njit(cache=True)
def _gap(rs: I32Array, ptr: I64Array, c: int, r: int) -> int:  # pragma: no cover
    # Index of the background run (gap) holding the background pixel (c, r) of row r (0 <= r < h).
    lo = ptr[r]
    hi = ptr[r + 1]
    while lo < hi:  # first run starting after c
        mid = (lo + hi) // 2
        if rs[mid] <= c:
            lo = mid + 1
        else:
            hi = mid
    return int(lo + r)


@njit(cache=True)
def _bottom_edges(
    rs: I32Array, re: I32Array, ptr: I64Array
) -> tuple[I64Array, I64Array, I64Array, I64Array, I64Array]:  # pragma: no cover
    # The maximal column intervals [bs, be] of each row r whose pixels are in the object and whose lower
    # neighbours are not (the bottom boundary linels, walked East), rows at bptr[r] … bptr[r+1]−1, the
    # object run holding each (brun), and the index of each interval's first linel in a flat numbering of
    # them all (bidx; the total last).
    h = ptr.size - 1
    cap = 2 * rs.size + 1
    bs = np.empty(cap, np.int64)
    be = np.empty(cap, np.int64)
    brun = np.empty(cap, np.int64)
    bidx = np.zeros(cap + 1, np.int64)
    bptr = np.zeros(h + 1, np.int64)
    nb = 0
    for r in range(h):
        i = ptr[r - 1] if r > 0 else 0
        i1 = ptr[r] if r > 0 else 0
        for j in range(ptr[r], ptr[r + 1]):
            c = rs[j]
            while c <= re[j]:
                # skip the columns covered by a run of the row below
                while i < i1 and re[i] < c:
                    i += 1
                if i < i1 and rs[i] <= c:
                    c = re[i] + 1
                    continue
                e = re[j] if i >= i1 else min(re[j], rs[i] - 1)
                bs[nb] = c
                be[nb] = e
                brun[nb] = j
                bidx[nb + 1] = bidx[nb] + e - c + 1
                nb += 1
                c = e + 1
        bptr[r + 1] = nb
    return bs[:nb], be[:nb], brun[:nb], bidx[: nb + 1], bptr


@njit(cache=True)
def _bottom_edge(bs: I64Array, bidx: I64Array, bptr: I64Array, x: int, y: int) -> int:  # pragma: no cover
    # The flat index of the bottom boundary linel of pixel (x, y) (one of :func:`_bottom_edges`).
    lo = bptr[y]
    hi = bptr[y + 1]
    while hi - lo > 1:  # the last interval starting at or before x
        mid = (lo + hi) // 2
        if bs[mid] <= x:
            lo = mid
        else:
            hi = mid
    return int(bidx[lo] + x - bs[lo])


@njit(cache=True)
def _trace_mask(
    m: U8Array,
    rs: I32Array,
    re: I32Array,
    ptr: I64Array,
    label: I32Array,
    bg_label: I32Array,
    n_rings: int,
) -> tuple[U8Array, I64Array, I64Array, I64Array, I32Array, I32Array, I64Array, I64Array]:  # pragma: no cover
    h, w = m.shape
    dx = np.array([1, 0, -1, 0], dtype=np.int64)
    dy = np.array([0, 1, 0, -1], dtype=np.int64)
    lx = np.array([0, -1, -1, 0], dtype=np.int64)
    ly = np.array([0, 0, -1, -1], dtype=np.int64)
    rx = np.array([0, 0, -1, -1], dtype=np.int64)
    ry = np.array([-1, 0, 0, -1], dtype=np.int64)
    codes = np.empty(_count_linels(rs, re, ptr), np.uint8)
    off = np.zeros(n_rings + 1, np.int64)
    sx = np.empty(n_rings, np.int64)
    sy = np.empty(n_rings, np.int64)
    comp = np.empty(n_rings, np.int32)
    bg = np.empty(n_rings, np.int32)
    area2 = np.empty(n_rings, np.int64)
    box = np.empty((n_rings, 4), np.int64)
    # visited[k]: bottom boundary linel k (walked East, code 0) belongs to a traced ring. Only those linels
    # are numbered (a whole (h, w) array cost 28 ms of page faults at 8192², for a few thousand linels).
    bs, be, brun, bidx, bptr = _bottom_edges(rs, re, ptr)
    visited = np.zeros(bidx[-1], np.uint8)
    pos = 0
    nr = 0
    for r in range(h):
        for b in range(bptr[r], bptr[r + 1]):
            j = brun[b]
            c = bs[b]
            e = be[b]
            for cc in range(c, e + 1):
                if visited[bidx[b] + cc - c]:
                    continue
                # ---- trace the ring through the bottom edge of pixel (cc, r), walked East.
                start = pos
                x0 = cc
                y0 = r
                x = x0
                y = y0
                d = 0
                a2 = 0
                mx = x0
                my = y0
                mi = 0
                bx0 = x0
                bx1 = x0
                by1 = y0
                while True:
                    codes[pos] = d
                    pos += 1
                    if d == 0:
                        visited[_bottom_edge(bs, bidx, bptr, x, y)] = 1
                    a2 += x * dy[d] - y * dx[d]
                    x += dx[d]
                    y += dy[d]
                    if not _inside(m, x + lx[d], y + ly[d]):
                        d = (d + 1) & 3
                    elif _inside(m, x + rx[d], y + ry[d]):
                        d = (d + 3) & 3
                    if x == x0 and y == y0 and d == 0:
                        break
                    if y < my or (y == my and x < mx):
                        # A new lowest-leftmost pointel; that one is passed only once (3 of its 4
                        # pixels are on the same side), so the rotation below is well defined.
                        my = y
                        mx = x
                        mi = pos - start
                    if x < bx0:
                        bx0 = x
                    elif x > bx1:
                        bx1 = x
                    if y > by1:
                        by1 = y
                # ---- rotate to the canonical start (the lowest-leftmost pointel).
                if mi != 0:
                    _reverse(codes, start, start + mi)
                    _reverse(codes, start + mi, pos)
                    _reverse(codes, start, pos)
                sx[nr] = mx
                sy[nr] = my
                comp[nr] = label[j]
                d = codes[start]
                px = mx + rx[d]
                py = my + ry[d]
                if 0 <= py < h and 0 <= px < w:
                    bg[nr] = bg_label[_gap(rs, ptr, px, py)]
                else:
                    bg[nr] = 0
                area2[nr] = a2
                box[nr, 0] = bx0
                box[nr, 1] = my
                box[nr, 2] = bx1
                box[nr, 3] = by1
                nr += 1
                off[nr] = pos
    return codes[:pos], off[: nr + 1], sx[:nr], sy[:nr], comp[:nr], bg[:nr], area2[:nr], box[:nr]


def trace_mask(mask: npt.ArrayLike) -> Rings:
    """Trace every crack ring of a binary mask (object 4-connected, complement 8-connected).

    Parameters
    ----------
    mask : array_like, shape (rows, cols)
        Non-zero entries are the object; row 0 is the lowest y.

    Returns
    -------
    Rings
        The rings, each rotated to its canonical start, with the labels of the components on each side.
    """
    m = as_u8(mask)
    runs = label_runs(m, 4)
    n_rings = runs.n_labels + runs.n_bg - 1
    codes, off, sx, sy, comp, bg, area2, box = _trace_mask(
        m, runs.start, runs.end, runs.ptr, runs.label, runs.bg_label, n_rings
    )
    return Rings(codes, off, sx, sy, comp, bg, area2, box, runs)


# ---------------------------------------------------------------------------------------------- fill


@njit(cache=True)
def _ring_extent(
    codes: U8Array, off: I64Array, sx: I64Array, sy: I64Array
) -> tuple[int, int, int, int, bool]:  # pragma: no cover
    # Pointel bounding box of the rings, and whether each ring comes back to its start.
    xmin = sx[0]
    xmax = sx[0]
    ymin = sy[0]
    ymax = sy[0]
    closed = True
    for k in range(off.size - 1):
        x = sx[k]
        y = sy[k]
        for p in range(off[k], off[k + 1]):
            d = codes[p]
            if d == 0:
                x += 1
                if x > xmax:
                    xmax = x
            elif d == 1:
                y += 1
                if y > ymax:
                    ymax = y
            elif d == 2:
                x -= 1
                if x < xmin:
                    xmin = x
            else:
                y -= 1
                if y < ymin:
                    ymin = y
        if x != sx[k] or y != sy[k] or off[k + 1] == off[k]:
            closed = False
        xmin = min(xmin, sx[k])
        xmax = max(xmax, sx[k])
        ymin = min(ymin, sy[k])
        ymax = max(ymax, sy[k])
    return xmin, ymin, xmax, ymax, closed


@njit(cache=True)
def _winding_diff(
    codes: U8Array, off: I64Array, sx: I64Array, sy: I64Array, wt: I32Array, x0: int, y0: int, w: int, h: int
) -> I32Array:  # pragma: no cover
    # The x-difference of the (weighted) winding number is carried by the vertical linels: going East across
    # a linel whose left side is West the winding number of its ring drops by 1, else it rises by 1. The
    # difference at column w (the right edge of the box) is never summed into a pixel, so it is dropped.
    diff = np.zeros((h, w), np.int32)
    for k in range(off.size - 1):
        x = sx[k] - x0
        y = sy[k] - y0
        v = wt[k]
        for p in range(off[k], off[k + 1]):
            d = codes[p]
            if d == 0:
                x += 1
            elif d == 1:
                if x < w:
                    diff[y, x] -= v
                y += 1
            elif d == 2:
                x -= 1
            else:
                y -= 1
                if x < w:
                    diff[y, x] += v
    return diff


@njit(cache=True)
def _fill(
    codes: U8Array, off: I64Array, sx: I64Array, sy: I64Array, x0: int, y0: int, w: int, h: int
) -> tuple[BoolArray, bool]:  # pragma: no cover
    diff = _winding_diff(codes, off, sx, sy, np.ones(off.size - 1, np.int32), x0, y0, w, h)
    out = np.empty((h, w), np.bool_)
    ok = True
    for r in range(h):
        acc = 0
        for c in range(w):
            acc += diff[r, c]
            if acc != 0 and acc != 1:
                ok = False
            out[r, c] = acc == 1
    return out, ok


@njit(cache=True)
def _paint_rings(
    codes: U8Array, off: I64Array, sx: I64Array, sy: I64Array, wt: I32Array, x0: int, y0: int, w: int, h: int
) -> I32Array:  # pragma: no cover
    out = _winding_diff(codes, off, sx, sy, wt, x0, y0, w, h)
    for r in range(h):
        acc = 0
        for c in range(w):
            acc += out[r, c]
            out[r, c] = acc
    return out


def ring_extent(codes: U8Array, off: I64Array, sx: I64Array, sy: I64Array) -> tuple[int, int, int, int, bool]:
    """Pointel bounding box (xmin, ymin, xmax, ymax) of at least one ring, and whether all are closed."""
    xmin, ymin, xmax, ymax, closed = _ring_extent(codes, off, sx, sy)
    return int(xmin), int(ymin), int(xmax), int(ymax), bool(closed)


def fill_rings(codes: U8Array, off: I64Array, sx: I64Array, sy: I64Array) -> tuple[BoolArray, int, int, str]:
    """Rasterise closed crack rings by their winding number.

    Parameters
    ----------
    codes, off, sx, sy
        Concatenated codes (0..3), ring offsets (n+1) and start pointels of the rings; outer rings run
        counter-clockwise and holes clockwise, so that the winding number is 1 inside and 0 outside.

    Returns
    -------
    mask : ndarray of bool
        The pixels of winding number 1, over the pointel bounding box of the rings.
    x0, y0 : int
        The pixel of ``mask[0, 0]``.
    problem : str
        Empty when all is well; otherwise why the rings do not bound a pixel set (a ring is not closed, or
        some winding number is neither 0 nor 1: overlapping or wrongly oriented rings).
    """
    if off.size <= 1:
        return np.zeros((0, 0), bool), 0, 0, ""
    xmin, ymin, xmax, ymax, closed = ring_extent(codes, off, sx, sy)
    if not closed:
        return np.zeros((0, 0), bool), 0, 0, "a crack chain is empty or does not come back to its start"
    mask, ok = _fill(codes, off, sx, sy, xmin, ymin, xmax - xmin, ymax - ymin)
    if not ok:
        return mask, xmin, ymin, "the chains overlap or are wrongly oriented (winding number not 0 or 1)"
    return mask, xmin, ymin, ""


def paint_rings(
    codes: U8Array,
    off: I64Array,
    sx: I64Array,
    sy: I64Array,
    weights: I32Array,
    box: tuple[int, int, int, int],
) -> I32Array:
    """Sum ``weights[k]`` × (winding number of ring k) over the pixels of a box.

    With every ring of a region weighted by the label of its component, this is the component label image:
    an island inside a hole of C gets C's label + (−C's label) + its own.

    Parameters
    ----------
    codes, off, sx, sy
        Closed rings as for :func:`fill_rings`.
    weights : ndarray of int32
        One weight per ring.
    box : tuple of int
        (xmin, ymin, xmax, ymax) of the pixels to paint, bounds included; it must hold every ring.
    """
    xmin, ymin, xmax, ymax = box
    return _paint_rings(codes, off, sx, sy, weights, xmin, ymin, xmax - xmin + 1, ymax - ymin + 1)


# ---------------------------------------------------------------------------------------------- label maps


class CellChains(NamedTuple):
    """The 0-cells and 1-cells of a label image, in array coordinates (see :func:`trace_cells`).

    0-cell ``k`` is the pointel ``(zx[k], zy[k])``. 1-cell ``k`` has the codes ``codes[off[k]:off[k+1]]``
    from the pointel ``(sx[k], sy[k])``, the label ``left[k]`` on its left and ``right[k] < left[k]`` on its
    right; it ends at a 0-cell (open) or comes back to its start (closed, no 0-cell on it).
    """

    zx: I64Array
    zy: I64Array
    codes: U8Array
    off: I64Array
    sx: I64Array
    sy: I64Array
    left: I32Array
    right: I32Array


@njit(cache=True)
def _trace_cells(
    lab: I32Array,
) -> tuple[I64Array, I64Array, U8Array, I64Array, I64Array, I64Array, I32Array, I32Array]:  # pragma: no cover
    # ``lab`` is padded with a ring of 0; pointel (i, j) is the lower-left corner of pixel lab[j, i].
    h2, w2 = lab.shape
    dx = np.array([1, 0, -1, 0], dtype=np.int64)
    dy = np.array([0, 1, 0, -1], dtype=np.int64)
    lx = np.array([0, -1, -1, 0], dtype=np.int64)
    ly = np.array([0, 0, -1, -1], dtype=np.int64)
    rx = np.array([0, 0, -1, -1], dtype=np.int64)
    ry = np.array([-1, 0, 0, -1], dtype=np.int64)
    # Degree of a pointel = number of boundary linels at it; 0-cells are the pointels of degree >= 3.
    deg = np.zeros((h2, w2), np.uint8)
    n_linels = 0
    n_zero = 0
    for j in range(1, h2):
        for i in range(1, w2):
            tr = lab[j, i]
            tl = lab[j, i - 1]
            br = lab[j - 1, i]
            bl = lab[j - 1, i - 1]
            # int(): without the JIT (NUMBA_DISABLE_JIT=1), numpy bools add as a logical or.
            e = int(tr != br)
            n = int(tl != tr)
            deg[j, i] = e + n + int(tl != bl) + int(bl != br)
            n_linels += e + n
            if deg[j, i] >= 3:
                n_zero += 1
    zx = np.empty(n_zero, np.int64)
    zy = np.empty(n_zero, np.int64)
    k = 0
    for j in range(1, h2):
        for i in range(1, w2):
            if deg[j, i] >= 3:
                zx[k] = i
                zy[k] = j
                k += 1
    codes = np.empty(n_linels, np.uint8)
    cap = n_linels
    off = np.zeros(cap + 1, np.int64)
    sx = np.empty(cap, np.int64)
    sy = np.empty(cap, np.int64)
    left = np.empty(cap, np.int32)
    right = np.empty(cap, np.int32)
    # hv[j, i]: linel (i, j)-(i+1, j) walked; vv[j, i]: linel (i, j)-(i, j+1) walked.
    hv = np.zeros((h2, w2), np.uint8)
    vv = np.zeros((h2, w2), np.uint8)
    pos = 0
    nc = 0
    # Pass 1 starts at the 0-cells (open 1-cells), pass 2 at the lowest-leftmost pointel of closed loops.
    for phase in range(2):
        for j in range(1, h2):
            for i in range(1, w2):
                if phase == 0:
                    if deg[j, i] < 3:
                        continue
                    dirs = (0, 1, 2, 3)
                else:
                    if lab[j, i] == lab[j - 1, i] or hv[j, i]:
                        continue
                    dirs = (0, 0, 0, 0) if lab[j, i] > lab[j - 1, i] else (1, 1, 1, 1)
                for d0 in dirs:
                    a = lab[j + ly[d0], i + lx[d0]]
                    b = lab[j + ry[d0], i + rx[d0]]
                    if a <= b:
                        continue
                    if d0 == 0:
                        seen = hv[j, i]
                    elif d0 == 1:
                        seen = vv[j, i]
                    elif d0 == 2:
                        seen = hv[j, i - 1]
                    else:
                        seen = vv[j - 1, i]
                    if seen:
                        continue
                    x = i
                    y = j
                    d = d0
                    while True:
                        codes[pos] = d
                        pos += 1
                        if d == 0:
                            hv[y, x] = 1
                        elif d == 1:
                            vv[y, x] = 1
                        elif d == 2:
                            hv[y, x - 1] = 1
                        else:
                            vv[y - 1, x] = 1
                        x += dx[d]
                        y += dy[d]
                        if deg[y, x] >= 3 or (x == i and y == j):
                            break
                        # A pointel of degree 2: exactly one other boundary linel, not the one behind.
                        for nd in ((d + 1) & 3, d, (d + 3) & 3):
                            if lab[y + ly[nd], x + lx[nd]] != lab[y + ry[nd], x + rx[nd]]:
                                d = nd
                                break
                    sx[nc] = i
                    sy[nc] = j
                    left[nc] = a
                    right[nc] = b
                    nc += 1
                    off[nc] = pos
                    if phase == 1:
                        break
    return zx, zy, codes[:pos], off[: nc + 1], sx[:nc], sy[:nc], left[:nc], right[:nc]


def trace_cells(labels: npt.ArrayLike) -> CellChains:
    """Split the boundaries of a label image into 0-cells and maximal 1-cells.

    Parameters
    ----------
    labels : array_like of int, shape (rows, cols)
        Non-negative labels; outside the array the label is 0 (background), which counts as a label.

    Returns
    -------
    CellChains
        0-cells (pointels where at least three boundary linels meet: three or more labels, or two labels
        meeting diagonally) and 1-cells (maximal chains of boundary linels between two labels, oriented with
        the larger label on the left), in array coordinates.
    """
    lab = np.pad(np.asarray(labels, dtype=np.int32), 1)
    zx, zy, codes, off, sx, sy, left, right = _trace_cells(lab)
    return CellChains(zx - 1, zy - 1, codes, off, sx - 1, sy - 1, left, right)
