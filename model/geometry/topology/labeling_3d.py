"""Connected components of a voxel mask by runs, with the (6, 26) topology, and its Euler characteristic.

Reference: docs/design.md §11 (region representation); the 2D counterpart is :mod:`.labeling`.

The mask is read as runs (maximal segments of object voxels along x, one row per (z, y)), found by the 2D
run scanner over the (nz·ny, nx) view of the array. The object is labelled with 6-connectivity and the
complement with 26-connectivity (or the other way round) by a union-find forest over the runs and over the
*gaps* between them, so the cost is one byte scan plus work proportional to the number of runs.

The complement is taken in the whole space: the array is surrounded by a virtual border of background, and
every gap touching the border of the array belongs to the one unbounded background component. The bounded
background components of an object labelled with 6-connectivity are its **cavities**.

The Euler characteristic χ of the object (6-connectivity) is summed from a table over the 2×2×2 windows of
the padded volume (each window's share of the cubical complex whose vertices are the voxels, edges join
6-adjacent voxels, squares fill planar 2×2 blocks and cubes 2×2×2 blocks). A window whose rows are constant
along x over its two columns contributes nothing, so only the windows at run ends are visited: the cost is
again proportional to the number of runs. Tunnels follow from χ = components − tunnels + cavities.

Labels are canonical: components are numbered 1, 2, … in raster order of their first voxel, i.e. by
(z, y, x) of their lexicographically smallest voxel (z first); cavities 1, 2, … the same way, 0 being the
unbounded background.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import njit
from mrm.geometry.topology.labeling import _find, _find_runs, _gap_labels, _union

Int32Array = npt.NDArray[np.int32]
Int64Array = npt.NDArray[np.int64]
UInt8Array = npt.NDArray[np.uint8]


class Runs3D(NamedTuple):
    """Runs of a voxel mask and their component labels, as computed by :func:`label_runs_3d`.

    Row ``r = k * ny + j`` holds the voxels (x0 + i, y0 + j, z0 + k). Object run ``n`` lies in row ``r`` with
    ``ptr[r] <= n < ptr[r + 1]`` and covers columns ``start[n] .. end[n]`` (inclusive). Row ``r`` also has
    ``ptr[r + 1] - ptr[r] + 1`` gaps (before, between and after its runs; columns −1 and ``nx`` are the
    virtual border); gap ``t`` of row ``r`` has the index ``ptr[r] + r + t`` in ``bg_label``.

    Attributes
    ----------
    label : int32 per run, 1..n_labels.
    counts : int64 (n_labels + 1,), voxels per component (entry 0 unused).
    box : int64 (n_labels + 1, 6), (imin, jmin, kmin, imax, jmax, kmax) per component, array indices.
    bg_label : int32 per gap, 0 = the unbounded background, 1..n_bg − 1 the bounded components.
    bg_counts : int64 (n_bg,), voxels per background component (entry 0: inside the array only).
    bg_box : int64 (n_bg, 6), as ``box`` (entry 0 meaningless).
    encloser : int64 (n_bg,), the component enclosing each bounded background component (entry 0: 0).
    """

    shape: tuple[int, int, int]
    start: Int32Array
    end: Int32Array
    ptr: Int64Array
    label: Int32Array
    n_labels: int
    counts: Int64Array
    box: Int64Array
    bg_label: Int32Array
    n_bg: int
    bg_counts: Int64Array
    bg_box: Int64Array
    encloser: Int64Array


@njit(cache=True)
def _link_rows(
    parent: Int64Array, s: Int32Array, e: Int32Array, a: int, a1: int, b: int, b1: int, diag: int
) -> None:  # pragma: no cover
    # Union the spans a..a1-1 and b..b1-1 (two rows, each sorted) that overlap, or touch within diag columns.
    while a < a1 and b < b1:
        if e[a] + diag < s[b]:
            a += 1
        elif e[b] + diag < s[a]:
            b += 1
        else:
            _union(parent, a, b)
            if e[a] < e[b]:
                a += 1
            else:
                b += 1


@njit(cache=True)
def _label_runs_3d(
    rs: Int32Array, re: Int32Array, ptr: Int64Array, nx: int, ny: int, nz: int, obj26: int
) -> tuple[
    Int32Array, int, Int64Array, Int64Array, Int32Array, int, Int64Array, Int64Array, Int64Array
]:  # pragma: no cover
    nrows = ny * nz
    n = rs.size
    # ---- object runs
    parent = np.arange(n, dtype=np.int64)
    for k in range(nz):
        for j in range(ny):
            r = k * ny + j
            if obj26 == 0:
                if j > 0:
                    _link_rows(parent, rs, re, ptr[r - 1], ptr[r], ptr[r], ptr[r + 1], 0)
                if k > 0:
                    _link_rows(parent, rs, re, ptr[r - ny], ptr[r - ny + 1], ptr[r], ptr[r + 1], 0)
            else:
                if j > 0:
                    _link_rows(parent, rs, re, ptr[r - 1], ptr[r], ptr[r], ptr[r + 1], 1)
                if k > 0:
                    for dj in range(-1, 2):
                        jj = j + dj
                        if 0 <= jj < ny:
                            q = r - ny + dj
                            _link_rows(parent, rs, re, ptr[q], ptr[q + 1], ptr[r], ptr[r + 1], 1)
    label = np.empty(n, np.int32)
    nlab = 0
    for t in range(n):
        root = _find(parent, t)
        if root == t:
            nlab += 1
            label[t] = nlab
        else:
            label[t] = label[root]
    counts = np.zeros(nlab + 1, np.int64)
    box = np.empty((nlab + 1, 6), np.int64)
    for c in range(nlab + 1):
        box[c, 0] = box[c, 1] = box[c, 2] = 1 << 62
        box[c, 3] = box[c, 4] = box[c, 5] = -(1 << 62)
    for r in range(nrows):
        k = r // ny
        j = r - k * ny
        for t in range(ptr[r], ptr[r + 1]):
            c = label[t]
            counts[c] += re[t] - rs[t] + 1
            box[c, 0] = min(box[c, 0], rs[t])
            box[c, 3] = max(box[c, 3], re[t])
            box[c, 1] = min(box[c, 1], j)
            box[c, 4] = max(box[c, 4], j)
            box[c, 2] = min(box[c, 2], k)
            box[c, 5] = max(box[c, 5], k)

    # ---- gaps, with a virtual border; node ng stands for the outside of the array.
    ng = n + nrows
    gs = np.empty(ng, np.int32)
    ge = np.empty(ng, np.int32)
    for r in range(nrows):
        g0 = ptr[r] + r
        m = ptr[r + 1] - ptr[r]
        for t in range(m + 1):
            gs[g0 + t] = re[ptr[r] + t - 1] + 1 if t > 0 else -1
            ge[g0 + t] = rs[ptr[r] + t] - 1 if t < m else nx
    bparent = np.arange(ng + 1, dtype=np.int64)
    for k in range(nz):
        for j in range(ny):
            r = k * ny + j
            g0 = ptr[r] + r
            g1 = ptr[r + 1] + r + 1
            _union(bparent, g0, ng)
            _union(bparent, g1 - 1, ng)
            if k == 0 or k == nz - 1 or j == 0 or j == ny - 1:
                for g in range(g0 + 1, g1 - 1):
                    _union(bparent, g, ng)
            if obj26 == 0:
                # The complement is 26-connected: the previous row and the three rows below, diagonals too.
                if j > 0:
                    _link_rows(bparent, gs, ge, ptr[r - 1] + r - 1, ptr[r] + r, g0, g1, 1)
                if k > 0:
                    for dj in range(-1, 2):
                        jj = j + dj
                        if 0 <= jj < ny:
                            q = r - ny + dj
                            _link_rows(bparent, gs, ge, ptr[q] + q, ptr[q + 1] + q + 1, g0, g1, 1)
            else:
                if j > 0:
                    _link_rows(bparent, gs, ge, ptr[r - 1] + r - 1, ptr[r] + r, g0, g1, 0)
                if k > 0:
                    q = r - ny
                    _link_rows(bparent, gs, ge, ptr[q] + q, ptr[q + 1] + q + 1, g0, g1, 0)
    bg_label, nbg = _gap_labels(bparent, ng)
    bg_counts = np.zeros(nbg, np.int64)
    bg_box = np.empty((nbg, 6), np.int64)
    for c in range(nbg):
        bg_box[c, 0] = bg_box[c, 1] = bg_box[c, 2] = 1 << 62
        bg_box[c, 3] = bg_box[c, 4] = bg_box[c, 5] = -(1 << 62)
    encloser = np.zeros(nbg, np.int64)
    for r in range(nrows):
        k = r // ny
        j = r - k * ny
        g0 = ptr[r] + r
        m = ptr[r + 1] - ptr[r]
        for t in range(m + 1):
            c = bg_label[g0 + t]
            s = max(gs[g0 + t], 0)
            e = min(ge[g0 + t], nx - 1)
            if e < s:
                continue
            if c > 0 and bg_counts[c] == 0:
                # The first voxel v of a cavity in raster order: v − e_x is an object voxel (the gap is not at
                # the row's ends), and its component encloses the cavity: a component nested in the cavity
                # would have, below its own lowest voxel, a voxel of the cavity coming before v.
                encloser[c] = label[ptr[r] + t - 1]
            bg_counts[c] += e - s + 1
            bg_box[c, 0] = min(bg_box[c, 0], s)
            bg_box[c, 3] = max(bg_box[c, 3], e)
            bg_box[c, 1] = min(bg_box[c, 1], j)
            bg_box[c, 4] = max(bg_box[c, 4], j)
            bg_box[c, 2] = min(bg_box[c, 2], k)
            bg_box[c, 5] = max(bg_box[c, 5], k)
    return label, nlab, counts, box, bg_label, nbg, bg_counts, bg_box, encloser


def _euler_table() -> Int64Array:
    """8·(the share of χ) of each 2×2×2 configuration; bit di + 2·dj + 4·dk is voxel (i+di, j+dj, k+dk).

    Each voxel lies in 8 windows, each edge between 6-adjacent voxels in 4, each planar 2×2 square in 2 and
    each 2×2×2 cube in 1, so the window's share is V/8 − E/4 + F/2 − C.
    """
    edges = [(a, a | bit) for bit in (1, 2, 4) for a in range(8) if not a & bit]
    faces = []
    for fixed in (1, 2, 4):
        for val in (0, fixed):
            faces.append([a for a in range(8) if a & fixed == val])
    table = np.zeros(256, np.int64)
    for cfg in range(256):
        on = [bool(cfg >> b & 1) for b in range(8)]
        v = sum(on)
        e = sum(on[a] and on[b] for a, b in edges)
        f = sum(all(on[a] for a in face) for face in faces)
        c = int(all(on))
        table[cfg] = v - 2 * e + 4 * f - 8 * c
    return table


EULER_TABLE_6 = _euler_table()
EULER_TABLE_6.flags.writeable = False


@njit(cache=True)
def _pair_seq(
    rs: Int32Array,
    re: Int32Array,
    label: Int32Array,
    a: int,
    a1: int,
    b: int,
    b1: int,
    pos: Int64Array,
    code: Int64Array,
    lab0: Int64Array,
    lab1: Int64Array,
    n: int,
) -> int:  # pragma: no cover
    # The columns where the pair of rows a..a1-1 (bit 1) and b..b1-1 (bit 2) changes, appended at n: from
    # column pos[t] on, the pair's code is code[t] (labels lab0 / lab1 where a bit is set). Returns the new n.
    ca = 0
    cb = 0
    la = 0
    lb = 0
    while a < a1 or b < b1:
        # the next change of each row: the start of its next run, or the column after its current run
        xa = 1 << 62
        if a < a1:
            xa = re[a] + 1 if ca else rs[a]
        xb = 1 << 62
        if b < b1:
            xb = re[b] + 1 if cb else rs[b]
        x = min(xa, xb)
        if xa == x:
            if ca:
                ca = 0
                a += 1
            else:
                ca = 1
                la = label[a]
        if xb == x:
            if cb:
                cb = 0
                b += 1
            else:
                cb = 1
                lb = label[b]
        pos[n] = x
        code[n] = ca | (cb << 1)
        lab0[n] = la
        lab1[n] = lb
        n += 1
    return n


@njit(cache=True)
def _euler8(
    rs: Int32Array,
    re: Int32Array,
    ptr: Int64Array,
    label: Int32Array,
    nlab: int,
    ny: int,
    nz: int,
    table: Int64Array,
) -> Int64Array:  # pragma: no cover
    # Sum of the table over the windows (k, j, i) of rows (k, j), (k, j+1), (k+1, j), (k+1, j+1), columns i
    # and i + 1, for k in −1..nz−1, j in −1..ny−1. A window whose four rows do not change between its two
    # columns adds nothing, so only the columns where one of them changes are visited: for each layer pair
    # (k, k+1), the change columns of each row pair (k, j), (k+1, j) are listed once, then each window row
    # merges two such lists. Per component: a window's cells (voxels, edges, squares, cubes of 6-adjacent
    # voxels) each lie in one component, so its share is the table summed over the window restricted to each
    # component.
    total = np.zeros(nlab + 1, np.int64)
    most = 0
    for k in range(nz):
        most = max(most, ptr[(k + 1) * ny] - ptr[k * ny])
    cap = 4 * most + 4
    pos = np.empty(cap, np.int64)
    code = np.empty(cap, np.int64)
    lab0 = np.empty(cap, np.int64)
    lab1 = np.empty(cap, np.int64)
    start = np.empty(ny + 1, np.int64)
    bl = np.empty(8, np.int64)  # the label of each set bit of a window
    for k in range(-1, nz):
        n = 0
        for j in range(ny):
            start[j] = n
            a = a1 = b = b1 = 0
            if k >= 0:
                a = ptr[k * ny + j]
                a1 = ptr[k * ny + j + 1]
            if k + 1 < nz:
                b = ptr[(k + 1) * ny + j]
                b1 = ptr[(k + 1) * ny + j + 1]
            n = _pair_seq(rs, re, label, a, a1, b, b1, pos, code, lab0, lab1, n)
        start[ny] = n
        for j in range(-1, ny):
            # list A: row pair j (bits dy = 0), list B: row pair j + 1 (dy = 1)
            p = start[j] if j >= 0 else 0
            p1 = start[j + 1] if j >= 0 else 0
            q = start[j + 1] if j + 1 < ny else 0
            q1 = start[j + 2] if j + 1 < ny else 0
            if p == p1 and q == q1:
                continue
            ca = 0
            cb = 0
            a0 = 0
            a1_ = 0
            b0 = 0
            b1_ = 0
            while p < p1 or q < q1:
                xa = pos[p] if p < p1 else 1 << 62
                xb = pos[q] if q < q1 else 1 << 62
                x = min(xa, xb)
                # the column x − 1 (before the change) and x (after)
                na, nb_ = ca, cb
                na0, na1, nb0, nb1 = a0, a1_, b0, b1_
                if xa == x:
                    na = code[p]
                    na0 = lab0[p]
                    na1 = lab1[p]
                    p += 1
                if xb == x:
                    nb_ = code[q]
                    nb0 = lab0[q]
                    nb1 = lab1[q]
                    q += 1
                # bit dx + 2 dy + 4 dz: dx = 0 is column x − 1, dx = 1 column x
                cfg = 0
                for dx in range(2):
                    sa = ca if dx == 0 else na
                    sb = cb if dx == 0 else nb_
                    if sa & 1:
                        cfg |= 1 << dx
                        bl[dx] = a0 if dx == 0 else na0
                    if sa & 2:
                        cfg |= 1 << (dx + 4)
                        bl[dx + 4] = a1_ if dx == 0 else na1
                    if sb & 1:
                        cfg |= 1 << (dx + 2)
                        bl[dx + 2] = b0 if dx == 0 else nb0
                    if sb & 2:
                        cfg |= 1 << (dx + 6)
                        bl[dx + 6] = b1_ if dx == 0 else nb1
                for u in range(8):
                    if not (cfg >> u) & 1:
                        continue
                    first = True
                    for w in range(u):
                        if (cfg >> w) & 1 and bl[w] == bl[u]:
                            first = False
                            break
                    if not first:
                        continue
                    sub = 0
                    for w in range(u, 8):
                        if (cfg >> w) & 1 and bl[w] == bl[u]:
                            sub |= 1 << w
                    total[bl[u]] += table[sub]
                ca, cb = na, nb_
                a0, a1_, b0, b1_ = na0, na1, nb0, nb1
    return total


@njit(cache=True)
def _overlap(rs: Int32Array, re: Int32Array, a: int, a1: int, b: int, b1: int) -> int:  # pragma: no cover
    # The number of columns covered by both row a..a1-1 and row b..b1-1.
    total = 0
    while a < a1 and b < b1:
        lo = max(rs[a], rs[b])
        hi = min(re[a], re[b])
        if hi >= lo:
            total += hi - lo + 1
        if re[a] < re[b]:
            a += 1
        else:
            b += 1
    return total


@njit(cache=True)
def _surfel_count(
    rs: Int32Array, re: Int32Array, ptr: Int64Array, ny: int, nz: int
) -> int:  # pragma: no cover
    # 6 per voxel minus 2 per pair of 6-adjacent voxels.
    total = 0
    for r in range(ny * nz):
        k = r // ny
        j = r - k * ny
        for t in range(ptr[r], ptr[r + 1]):
            total += 4 * (re[t] - rs[t] + 1) + 2
        if j > 0:
            total -= 2 * _overlap(rs, re, ptr[r - 1], ptr[r], ptr[r], ptr[r + 1])
        if k > 0:
            total -= 2 * _overlap(rs, re, ptr[r - ny], ptr[r - ny + 1], ptr[r], ptr[r + 1])
    return total


def surfel_count(runs: Runs3D) -> int:
    """The number of surfels of the object of ``runs`` (voxel faces between the object and the outside)."""
    nz, ny, _nx = runs.shape
    return int(_surfel_count(runs.start, runs.end, runs.ptr, ny, nz))


@njit(cache=True)
def _paint_3d(
    rs: Int32Array, re: Int32Array, ptr: Int64Array, label: Int32Array, nx: int, ny: int, nz: int
) -> Int32Array:  # pragma: no cover
    out = np.zeros((nz, ny, nx), np.int32)
    flat = out.reshape(nz * ny, nx)
    for r in range(nz * ny):
        row = flat[r]
        for t in range(ptr[r], ptr[r + 1]):
            v = label[t]
            for c in range(rs[t], re[t] + 1):
                row[c] = v
    return out


@njit(cache=True)
def _paint_gaps_3d(
    rs: Int32Array, re: Int32Array, ptr: Int64Array, bg_label: Int32Array, nx: int, ny: int, nz: int
) -> Int32Array:  # pragma: no cover
    out = np.zeros((nz, ny, nx), np.int32)
    flat = out.reshape(nz * ny, nx)
    for r in range(nz * ny):
        row = flat[r]
        m = ptr[r + 1] - ptr[r]
        g0 = ptr[r] + r
        for t in range(m + 1):
            v = bg_label[g0 + t]
            if v == 0:
                continue
            s = re[ptr[r] + t - 1] + 1 if t > 0 else 0
            e = rs[ptr[r] + t] - 1 if t < m else nx - 1
            for c in range(s, e + 1):
                row[c] = v
    return out


def as_u8_3d(mask: npt.ArrayLike) -> UInt8Array:
    """Return a read-only C-contiguous 3-D uint8 view (or copy) of a mask; non-zero entries are the object."""
    m = np.asarray(mask)
    if m.ndim != 3:
        raise ValueError(f"a voxel mask must be 3-D, got shape {m.shape}")
    if m.dtype == np.bool_:
        m = m.view(np.uint8)
    elif m.dtype != np.uint8:
        m = (m != 0).view(np.uint8)
    m = np.ascontiguousarray(m).view()
    m.flags.writeable = False
    return m


def find_runs_3d(mask: npt.ArrayLike) -> tuple[Int32Array, Int32Array, Int64Array, tuple[int, int, int]]:
    """The runs of a voxel mask along x: (start, end, ptr, shape), rows r = k·ny + j (see :class:`Runs3D`)."""
    m = as_u8_3d(mask)
    nz, ny, nx = m.shape
    if m.size == 0:
        return np.zeros(0, np.int32), np.zeros(0, np.int32), np.zeros(nz * ny + 1, np.int64), (nz, ny, nx)
    flat = m.reshape(nz * ny, nx)
    rs, re, ptr = _find_runs(flat)
    return rs, re, ptr, (nz, ny, nx)


def label_runs_3d(mask: npt.ArrayLike, connectivity: int = 6) -> Runs3D:
    """Label the runs of a voxel mask: object with ``connectivity``, complement (whole space) with the dual.

    Parameters
    ----------
    mask : array_like, shape (nz, ny, nx)
        Non-zero entries are the object; ``mask[k, j, i]`` is voxel (i, j, k) relative to the origin.
    connectivity : {6, 26}
        Adjacency of object voxels; the complement gets the other one.

    Returns
    -------
    Runs3D
        The runs, their canonical labels, voxel counts and boxes of every object and background component,
        and the component enclosing each bounded background component.
    """
    if connectivity not in (6, 26):
        raise ValueError(f"connectivity must be 6 or 26, got {connectivity}")
    rs, re, ptr, shape = find_runs_3d(mask)
    nz, ny, nx = shape
    label, nlab, counts, box, bg_label, nbg, bg_counts, bg_box, encloser = _label_runs_3d(
        rs, re, ptr, nx, ny, nz, int(connectivity == 26)
    )
    return Runs3D(
        shape, rs, re, ptr, label, int(nlab), counts, box, bg_label, int(nbg), bg_counts, bg_box, encloser
    )


def paint_3d(runs: Runs3D) -> Int32Array:
    """The (nz, ny, nx) int32 volume of the component labels of ``runs`` (0 off the object)."""
    nz, ny, nx = runs.shape
    return _paint_3d(runs.start, runs.end, runs.ptr, runs.label, nx, ny, nz)


def paint_background_3d(runs: Runs3D) -> Int32Array:
    """The (nz, ny, nx) int32 volume of the bounded background labels (cavities 1..; 0 elsewhere)."""
    nz, ny, nx = runs.shape
    return _paint_gaps_3d(runs.start, runs.end, runs.ptr, runs.bg_label, nx, ny, nz)


def label_3d(mask: npt.ArrayLike, connectivity: int = 6) -> tuple[Int32Array, int]:
    """Label the connected components of the non-zero voxels of a mask.

    Parameters
    ----------
    mask : array_like, shape (nz, ny, nx)
    connectivity : {6, 26}
        6: voxels sharing a face are adjacent; 26: sharing an edge or a corner too.

    Returns
    -------
    labels : ndarray of int32, shape (nz, ny, nx)
        0 off the mask, 1..n on it, in raster order (z, y, x) of each component's first voxel.
    n : int
    """
    runs = label_runs_3d(mask, connectivity)
    return paint_3d(runs), runs.n_labels


def euler_per_label(runs: Runs3D) -> Int64Array:
    """The Euler characteristic of each 6-component of labelled runs: entry c for component c (entry 0: 0).

    χ(X) = 1 − tunnels(X) + cavities(X) for each component X (see :func:`euler_3d`).
    """
    nz, ny, _nx = runs.shape
    return _euler_from(runs.start, runs.end, runs.ptr, runs.label, runs.n_labels, ny, nz)


def _euler_from(
    rs: Int32Array, re: Int32Array, ptr: Int64Array, label: Int32Array, nlab: int, ny: int, nz: int
) -> Int64Array:
    if rs.size == 0:
        return np.zeros(nlab + 1, np.int64)
    e8 = _euler8(rs, re, ptr, label, nlab, ny, nz, EULER_TABLE_6)
    if np.any(e8 % 8):
        raise AssertionError("the Euler table summed to a value that is not a multiple of 8")
    return e8 // 8


def euler_3d(mask: npt.ArrayLike) -> int:
    """The Euler characteristic χ = b0 − b1 + b2 of a voxel set with the (6, 26) topology.

    χ = components − tunnels + cavities; it is that of V(A) eroded by ¼ (voxels touching only along an edge
    or at a corner kept apart).
    """
    rs, re, ptr, (nz, ny, _nx) = find_runs_3d(mask)
    # Every run labelled 1: one total.
    return int(_euler_from(rs, re, ptr, np.ones(rs.size, np.int32), 1, ny, nz).sum())
