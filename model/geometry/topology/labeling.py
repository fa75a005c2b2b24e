"""Connected-component labelling of a binary mask by runs, with the (4, 8) digital topology.

Reference: docs/design.md §4.

The object (True pixels) is labelled with 4-connectivity and the complement with 8-connectivity — or the
other way round — in one raster pass over *runs* (maximal horizontal segments of equal pixels) with a
union-find forest, so the cost is one byte scan plus work proportional to the number of runs, not pixels.

The complement is taken in the whole plane: the mask is surrounded by a virtual border of background, so
every background run that touches the border of the array belongs to the one unbounded background
component. The bounded background components of an object labelled with 4-connectivity are its holes.

Labels are canonical: object components are numbered 1, 2, … in raster order of their first pixel, i.e.
by (row, col) of their lowest-leftmost pixel (row 0 is the lowest y). Background components are numbered
0 (the unbounded one), 1, 2, … in the same order.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import leaf_njit, njit

Int32Array = npt.NDArray[np.int32]
Int64Array = npt.NDArray[np.int64]


class Runs(NamedTuple):
    """Runs of a mask and their component labels, as computed by :func:`label_runs`.

    Object run ``k`` lies in row ``r`` with ``ptr[r] <= k < ptr[r + 1]`` and covers columns
    ``start[k] .. end[k]`` (inclusive). Row ``r`` also has ``ptr[r+1] - ptr[r] + 1`` background runs, the
    gaps before, between and after its object runs (columns −1 and ``width`` belong to the virtual border);
    gap ``t`` of row ``r`` has the index ``ptr[r] + r + t`` in ``bg_label``.
    """

    start: Int32Array
    end: Int32Array
    ptr: Int64Array
    label: Int32Array
    n_labels: int
    counts: Int64Array
    bg_label: Int32Array
    n_bg: int
    bg_counts: Int64Array


@njit(cache=True)
def _find_runs(m: npt.NDArray[np.uint8]) -> tuple[Int32Array, Int32Array, Int64Array]:  # pragma: no cover
    # The runs of non-zero bytes of each row of a C-contiguous mask. The mask's memory is also read as 8-byte
    # words: a word of eight background bytes, or of eight 1s inside a run, is passed at once, four words at
    # a time where they can be (large smooth masks: this scan is most of R's time at 8192²). Words are
    # counted over the whole buffer (rows need not start on a word boundary), so the kernel has one type.
    h, w = m.shape
    nb = h * w
    words = m.reshape(nb)[: 8 * (nb // 8)].view(np.uint64)
    zero = np.uint64(0)
    ones = np.uint64(0x0101010101010101)
    cap = max(1, h * ((w + 1) // 2))
    rs = np.empty(cap, np.int32)
    re = np.empty(cap, np.int32)
    ptr = np.empty(h + 1, np.int64)
    n = 0
    for r in range(h):
        ptr[r] = n
        row = m[r]
        b0 = r * w  # the row's first byte in the buffer
        kend = (b0 + w) >> 3  # words wholly before the row's end
        c = 0
        while c < w:
            if ((b0 + c) & 7) == 0:
                k = (b0 + c) >> 3
                while k + 4 <= kend and (words[k] | words[k + 1] | words[k + 2] | words[k + 3]) == zero:
                    k += 4
                while k < kend and words[k] == zero:
                    k += 1
                c = (k << 3) - b0
                if c >= w:
                    break
            if row[c]:
                s = c
                c += 1
                while c < w and row[c]:
                    if ((b0 + c) & 7) == 0:
                        k = (b0 + c) >> 3
                        while (
                            k + 4 <= kend
                            and (
                                (words[k] ^ ones)
                                | (words[k + 1] ^ ones)
                                | (words[k + 2] ^ ones)
                                | (words[k + 3] ^ ones)
                            )
                            == zero
                        ):
                            k += 4
                        while k < kend and words[k] == ones:
                            k += 1
                        c = (k << 3) - b0
                        if c >= w or not row[c]:
                            break
                    c += 1
                rs[n] = s
                re[n] = c - 1
                n += 1
            else:
                c += 1
    ptr[h] = n
    return rs[:n], re[:n], ptr


@njit(cache=True)
def _gap_labels(bparent: Int64Array, n: int) -> tuple[npt.NDArray[np.int32], int]:  # pragma: no cover
    """Number the background components of gaps 0..n − 1 (union-find ``bparent``; index ``n`` is the outside).

    The component holding the outside gets 0, the others 1, 2, … in the order of their first gap; returns the
    labels and one more than the largest. Shared by the 2D and 3D labelings.
    """
    bg_label = np.empty(n, np.int32)
    out_root = _find(bparent, n)
    nbg = 1
    for g in range(n):
        root = _find(bparent, g)
        if root == out_root:
            bg_label[g] = 0
        elif root == g:
            bg_label[g] = nbg
            nbg += 1
        else:
            bg_label[g] = bg_label[root]
    return bg_label, nbg


# Leaf kernels (no reference counting): they allocate nothing, and the 3D safety net calls them for every
# overlap of runs.
@leaf_njit(cache=True)
def _find(parent: Int64Array, x: int) -> int:  # pragma: no cover
    while parent[x] != x:
        parent[x] = parent[parent[x]]
        x = parent[x]
    return x


@leaf_njit(cache=True)
def _union(parent: Int64Array, a: int, b: int) -> None:  # pragma: no cover
    # The smaller index stays the root, so a component's root is its first run in raster order.
    a = _find(parent, a)
    b = _find(parent, b)
    if a < b:
        parent[b] = a
    elif b < a:
        parent[a] = b


@njit(cache=True)
def _label_runs(
    rs: Int32Array, re: Int32Array, ptr: Int64Array, w: int, obj_diag: int
) -> tuple[Int32Array, int, Int64Array, Int32Array, int, Int64Array]:  # pragma: no cover
    h = ptr.size - 1
    n = rs.size
    bg_diag = 1 - obj_diag
    # ---- object runs: link with the overlapping runs of the row below (diagonals if obj_diag).
    parent = np.arange(n, dtype=np.int64)
    for r in range(1, h):
        i, i1 = ptr[r - 1], ptr[r]
        j, j1 = ptr[r], ptr[r + 1]
        while i < i1 and j < j1:
            if re[i] + obj_diag < rs[j]:
                i += 1
            elif re[j] + obj_diag < rs[i]:
                j += 1
            else:
                _union(parent, i, j)
                if re[i] < re[j]:
                    i += 1
                else:
                    j += 1
    label = np.empty(n, np.int32)
    nlab = 0
    for k in range(n):
        root = _find(parent, k)
        if root == k:
            nlab += 1
            label[k] = nlab
        else:
            label[k] = label[root]
    counts = np.zeros(nlab + 1, np.int64)
    for k in range(n):
        counts[label[k]] += re[k] - rs[k] + 1

    # ---- background runs (gaps), with a virtual border; node nb stands for the outside of the array.
    # Gap t of row r spans [s, e]: s = end of object run t-1 plus 1 (or -1, the border column), e = start of
    # object run t minus 1 (or w, the border column).
    nb = n + h
    bparent = np.arange(nb + 1, dtype=np.int64)
    for r in range(h):
        g0 = ptr[r] + r
        k = ptr[r + 1] - ptr[r]
        # The first and last gaps contain border columns; every gap of rows 0 and h-1 touches a border row.
        _union(bparent, g0, nb)
        _union(bparent, g0 + k, nb)
        if r == 0 or r == h - 1:
            for t in range(1, k):
                _union(bparent, g0 + t, nb)
        if r == 0:
            continue
        q0 = ptr[r]
        p0 = ptr[r - 1]
        kp = q0 - p0
        gp0 = p0 + r - 1
        a = 0
        b = 0
        while a <= kp and b <= k:
            sa = re[p0 + a - 1] + 1 if a > 0 else -1
            ea = rs[p0 + a] - 1 if a < kp else w
            sb = re[q0 + b - 1] + 1 if b > 0 else -1
            eb = rs[q0 + b] - 1 if b < k else w
            if ea + bg_diag < sb:
                a += 1
            elif eb + bg_diag < sa:
                b += 1
            else:
                _union(bparent, gp0 + a, g0 + b)
                if ea < eb:
                    a += 1
                else:
                    b += 1
    bg_label, nbg = _gap_labels(bparent, nb)
    bg_counts = np.zeros(nbg, np.int64)
    for r in range(h):
        k = ptr[r + 1] - ptr[r]
        g0 = ptr[r] + r
        for t in range(k + 1):
            s = re[ptr[r] + t - 1] + 1 if t > 0 else 0
            e = rs[ptr[r] + t] - 1 if t < k else w - 1
            if e >= s:
                bg_counts[bg_label[g0 + t]] += e - s + 1
    return label, nlab, counts, bg_label, nbg, bg_counts


@njit(cache=True)
def _paint(
    rs: Int32Array, re: Int32Array, ptr: Int64Array, label: Int32Array, w: int
) -> Int32Array:  # pragma: no cover
    h = ptr.size - 1
    out = np.zeros((h, w), np.int32)
    for r in range(h):
        row = out[r]
        for k in range(ptr[r], ptr[r + 1]):
            v = label[k]
            for c in range(rs[k], re[k] + 1):
                row[c] = v
    return out


def as_u8(mask: npt.ArrayLike) -> npt.NDArray[np.uint8]:
    """Return a read-only C-contiguous 2-D uint8 view (or copy) of a mask; non-zero entries are the object.

    Always read-only, so that the numba kernels are compiled for one array type only.
    """
    m = np.asarray(mask)
    if m.ndim != 2:
        raise ValueError(f"a mask must be 2-D, got shape {m.shape}")
    if m.dtype == np.bool_:
        m = m.view(np.uint8)
    elif m.dtype != np.uint8:
        m = (m != 0).view(np.uint8)
    m = np.ascontiguousarray(m).view()
    m.flags.writeable = False
    return m


def label_runs(mask: npt.ArrayLike, connectivity: int = 4) -> Runs:
    """Label the runs of a mask: object with ``connectivity``, complement (in the whole plane) with the other.

    Parameters
    ----------
    mask : array_like, shape (rows, cols)
        Non-zero entries are the object; row 0 is the lowest y.
    connectivity : {4, 8}
        Adjacency of object pixels; the complement gets the dual one (8 or 4).

    Returns
    -------
    Runs
        The runs, their canonical labels and the pixel counts of every object and background component.
    """
    if connectivity not in (4, 8):
        raise ValueError(f"connectivity must be 4 or 8, got {connectivity}")
    m = as_u8(mask)
    rs, re, ptr = _find_runs(m)
    label, nlab, counts, bg_label, nbg, bg_counts = _label_runs(
        rs, re, ptr, m.shape[1], int(connectivity == 8)
    )
    return Runs(rs, re, ptr, label, int(nlab), counts, bg_label, int(nbg), bg_counts)


def paint(runs: Runs, width: int) -> Int32Array:
    """Return the (rows, width) int32 image of the object labels of ``runs`` (0 on the background)."""
    return _paint(runs.start, runs.end, runs.ptr, runs.label, int(width))


def label(mask: npt.ArrayLike, connectivity: int = 4) -> tuple[Int32Array, int]:
    """Label the connected components of the non-zero pixels of a mask.

    Parameters
    ----------
    mask : array_like, shape (rows, cols)
        Non-zero entries are the pixels to label.
    connectivity : {4, 8}
        4: pixels sharing an edge are adjacent; 8: pixels sharing a corner too.

    Returns
    -------
    labels : ndarray of int32, shape (rows, cols)
        0 off the mask, 1..n on it, numbered in raster order of each component's first pixel.
    n : int
        The number of components.
    """
    m = as_u8(mask)
    runs = label_runs(m, connectivity)
    return paint(runs, m.shape[1]), runs.n_labels


@njit(cache=True)
def _group_by_label(flat: Int32Array, vmax: int) -> tuple[Int64Array, Int64Array]:  # pragma: no cover
    # Counting sort of the pixel indices by label: pixels of label v are order[start[v]:start[v+1]].
    start = np.zeros(vmax + 2, np.int64)
    for k in range(flat.size):
        start[flat[k] + 1] += 1
    for v in range(vmax + 1):
        start[v + 1] += start[v]
    fill = start[:-1].copy()
    order = np.empty(flat.size, np.int64)
    for k in range(flat.size):
        v = flat[k]
        order[fill[v]] = k
        fill[v] += 1
    return start, order


def group_by_label(labels: npt.NDArray[np.int32]) -> tuple[list[int], list[Int64Array]]:
    """Group the flat indices of the pixels of a label image by label.

    Returns
    -------
    values : list of int
        The distinct labels present, increasing (0 included if present).
    indices : list of ndarray of int64
        For each label, the increasing flat (row-major) indices of its pixels.
    """
    flat = np.ascontiguousarray(labels, dtype=np.int32).ravel()
    if flat.size == 0:
        return [], []
    vmax = int(flat.max())
    if vmax <= 4 * flat.size + 1024:
        start, order = _group_by_label(flat, vmax)
        counts = np.diff(start)
        values = np.flatnonzero(counts)
        return values.tolist(), [order[start[v] : start[v + 1]] for v in values.tolist()]
    # Sparse huge label values: sort instead (stable, so indices stay increasing).
    order = np.argsort(flat, kind="stable")
    vals, first = np.unique(flat[order], return_index=True)
    bounds = np.append(first, flat.size)
    return vals.tolist(), [order[bounds[i] : bounds[i + 1]] for i in range(vals.size)]


class LabelRegions(NamedTuple):
    """The regions of a label image: 4-connected components of equal non-zero labels (:func:`label_regions`).

    Regions are numbered in raster order of their first pixel (lowest row, then lowest column; row 0 is the
    lowest y). ``first_row`` / ``first_col`` give that pixel, ``label`` the region's label and ``pixels``
    its number of pixels.
    """

    label: Int64Array
    pixels: Int64Array
    first_row: Int64Array
    first_col: Int64Array


@njit(cache=True)
def _label_regions(
    lab: Int32Array,
) -> tuple[Int64Array, Int64Array, Int64Array, Int64Array]:  # pragma: no cover
    # Union-find over the pixels, 4-adjacency between equal labels; the smaller index stays the root, so a
    # region's root is its first pixel in raster order.
    h, w = lab.shape
    parent = np.empty(h * w, np.int64)
    for k in range(h * w):
        parent[k] = k
    for r in range(h):
        for c in range(w):
            v = lab[r, c]
            if v == 0:
                continue
            k = r * w + c
            if c > 0 and lab[r, c - 1] == v:
                _union(parent, k - 1, k)
            if r > 0 and lab[r - 1, c] == v:
                _union(parent, k - w, k)
    index = np.full(h * w, -1, np.int64)
    n = 0
    for k in range(h * w):
        if lab[k // w, k % w] != 0 and _find(parent, k) == k:
            index[k] = n
            n += 1
    label = np.empty(n, np.int64)
    pixels = np.zeros(n, np.int64)
    first_row = np.empty(n, np.int64)
    first_col = np.empty(n, np.int64)
    for k in range(h * w):
        if lab[k // w, k % w] == 0:
            continue
        i = index[_find(parent, k)]
        if pixels[i] == 0:
            label[i] = lab[k // w, k % w]
            first_row[i] = k // w
            first_col[i] = k % w
        pixels[i] += 1
    return label, pixels, first_row, first_col


def label_regions(labels: npt.ArrayLike) -> LabelRegions:
    """Return the regions (4-connected components of equal non-zero labels) of a label image.

    Parameters
    ----------
    labels : array_like of int, shape (rows, cols)
        The label image; 0 is the background; row 0 is the lowest y.

    Returns
    -------
    LabelRegions
        One entry per region, in raster order of the regions' first pixels.
    """
    lab = np.ascontiguousarray(labels, dtype=np.int32)
    if lab.ndim != 2:
        raise ValueError(f"a label image must be 2-D, got shape {lab.shape}")
    return LabelRegions(*_label_regions(lab))


# ---------------------------------------------------------------------------------------------- pooling
# Level-of-detail images of big masks and label images, f × f max-pooled in one pass: no padded copy and no
# full-size temporaries. At 10⁸ pixels each full-size temporary is hundreds of megabytes of fresh memory,
# whose first touch (page faults) cost more than the arithmetic, on the core the window shares.


@njit(cache=True)
def _max_pool(src: npt.NDArray[np.uint8], f: int) -> npt.NDArray[np.uint8]:  # pragma: no cover
    h, w = src.shape
    out = np.zeros(((h + f - 1) // f, (w + f - 1) // f), np.uint8)
    for r in range(h):
        row = src[r]
        orow = out[r // f]
        for oc in range(orow.size):
            m = orow[oc]
            for c in range(oc * f, min(w, oc * f + f)):
                if row[c] > m:
                    m = row[c]
            orow[oc] = m
    return out


@njit(cache=True)
def _pool_labels(labels: Int32Array, f: int) -> npt.NDArray[np.uint8]:  # pragma: no cover
    h, w = labels.shape
    out = np.zeros(((h + f - 1) // f, (w + f - 1) // f), np.uint8)
    for r in range(h):
        row = labels[r]
        orow = out[r // f]
        for oc in range(orow.size):
            m = orow[oc]
            for c in range(oc * f, min(w, oc * f + f)):
                v = row[c]
                if v > 0:
                    u = (v - 1) % 255 + 1
                    if u > m:
                        m = u
            orow[oc] = m
    return out


@njit(cache=True)
def _pool_holes(
    rs: Int32Array, re: Int32Array, ptr: Int64Array, bg_label: Int32Array, w: int, f: int
) -> npt.NDArray[np.uint8]:  # pragma: no cover
    h = ptr.size - 1
    out = np.zeros(((h + f - 1) // f, (w + f - 1) // f), np.uint8)
    for r in range(h):
        k = ptr[r + 1] - ptr[r]
        g0 = ptr[r] + r
        orow = out[r // f]
        for t in range(k + 1):
            if bg_label[g0 + t] == 0:
                continue  # the unbounded background
            s = re[ptr[r] + t - 1] + 1 if t > 0 else 0
            e = rs[ptr[r] + t] - 1 if t < k else w - 1
            if e >= s:
                for oc in range(s // f, e // f + 1):
                    orow[oc] = 1
    return out


def _read_only(a: npt.NDArray[Any]) -> npt.NDArray[Any]:
    """A read-only view: numba compiles a kernel once per writeable flag, so the pools see one kind."""
    v = a.view()
    v.flags.writeable = False
    return v


def max_pool(mask: npt.ArrayLike, f: int) -> npt.NDArray[np.uint8]:
    """The f × f max-pooled image of a bool or uint8 image (beyond its edges: 0), as uint8 (any thread)."""
    m = np.asarray(mask)
    src = m.view(np.uint8) if m.dtype == np.bool_ else m
    if src.dtype != np.uint8 or src.ndim != 2:
        raise ValueError(f"max_pool takes a 2-D bool or uint8 image, got {src.dtype} {src.shape}")
    if f == 1:
        return src
    return _max_pool(_read_only(src), int(f))  # a strided crop is read in place (a specialisation of its own)


def pooled_labels(labels: npt.ArrayLike, f: int = 1) -> npt.NDArray[np.uint8]:
    """The label image as uint8 (labels beyond 255 cycle through 1 … 255), f × f max-pooled (any thread).

    For drawing: each component gets one of 255 colours. Equal to max-pooling ``(labels − 1) % 255 + 1``
    (0 off the set), without its three full-size int32 temporaries.
    """
    lab = np.ascontiguousarray(labels, dtype=np.int32)
    if lab.ndim != 2:
        raise ValueError(f"a label image must be 2-D, got shape {lab.shape}")
    return _pool_labels(_read_only(lab), max(1, int(f)))


def pooled_holes(mask: npt.ArrayLike, f: int = 1) -> npt.NDArray[np.uint8]:
    """1 on the holes of a mask (bounded 8-components of its complement), f × f max-pooled (any thread).

    From the runs of the mask (:func:`label_runs`): no label image of the complement is painted.
    """
    m = as_u8(mask)
    runs = label_runs(m, 4)
    return _pool_holes(runs.start, runs.end, runs.ptr, runs.bg_label, m.shape[1], max(1, int(f)))


@njit(cache=True)
def _lookup(
    table: npt.NDArray[np.uint32], img: npt.NDArray[np.uint8]
) -> npt.NDArray[np.uint32]:  # pragma: no cover
    h, w = img.shape
    out = np.empty((h, w), np.uint32)
    for r in range(h):
        row = img[r]
        orow = out[r]
        for c in range(w):
            orow[c] = table[row[c]]
    return out


def lookup(table: npt.ArrayLike, img: npt.ArrayLike) -> npt.NDArray[np.uint32]:
    """``table[img]`` for a uint8 image and a 256-entry uint32 table (any thread).

    numpy's take or fancy index first casts the uint8 indices to a full-size int64 array (32 MB per
    4 M-pixel picture) of fresh memory.
    """
    t = np.ascontiguousarray(table, dtype=np.uint32)
    if t.shape != (256,):
        raise ValueError(f"a lookup table has 256 entries, got shape {t.shape}")
    m = np.asarray(img)
    if m.dtype != np.uint8 or m.ndim != 2:
        raise ValueError(f"lookup takes a 2-D uint8 image, got {m.dtype} {m.shape}")
    return _lookup(_read_only(t), _read_only(m))
