"""Cells of a label volume's boundaries: boundary squares, their patches and the linels where labels meet.

Reference: docs/design.md §11 (region representation, label volumes); the 2D counterpart is
:func:`.cracks.trace_cells`. The space outside the array carries label 0, like the background.

Indices are those of the array padded by one voxel of 0 on every side. A **square** (n, v) is the unit
square between voxel v and v + e_n (n = 0, 1, 2 for x, y, z); it is a boundary square when their labels
differ. A **linel** (b, p) is the unit edge along axis b shared by voxels p, p + e_c, p + e_c + e_d and
p + e_d ((b, c, d) a cyclic order of the axes); its ends are the **pointels** p − e_b and p, pointel q
being the corner q + (½, ½, ½). Around a linel lie four squares; it is a **junction** linel when three or
four of them are boundary squares (three or more labels meet there, or two labels meet diagonally, the 3D
form of the 2D pinch), and a boundary patch passes through it when exactly two are.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import njit
from mrm.geometry.topology.labeling import _find, _union

Int32Array = npt.NDArray[np.int32]
Int64Array = npt.NDArray[np.int64]


class BoundaryCells(NamedTuple):
    """The boundary squares grouped into patches, and the junction linels (:func:`boundary_cells`).

    Attributes
    ----------
    squares : int64 (n, 4), (normal axis, i, j, k) of each boundary square (padded indices), in raster order
        of (k, j, i) then axis.
    patch : int64 (n,), its patch (2-cell), numbered by first square.
    n_patches : int
    linels : int64 (m, 4), (axis, i, j, k) of each junction linel (padded indices), in raster order.
    linel_labels : int64 (m, 4), the labels of its four voxels (p, p + e_c, p + e_c + e_d, p + e_d).
    """

    squares: Int64Array
    patch: Int64Array
    n_patches: int
    linels: Int64Array
    linel_labels: Int64Array


@njit(cache=True)
def _boundary_cells(
    lab: Int32Array,
) -> tuple[Int64Array, Int64Array, int, Int64Array, Int64Array]:  # pragma: no cover
    NZ, NY, NX = lab.shape
    nvox = NZ * NY * NX
    step = np.array([1, NX, NX * NY], np.int64)
    flat = lab.reshape(nvox)
    parent = np.arange(3 * nvox, dtype=np.int64)
    is_b = np.zeros(3 * nvox, np.uint8)
    for k in range(NZ):
        for j in range(NY):
            for i in range(NX):
                v = (k * NY + j) * NX + i
                coords = (i, j, k)
                dims = (NX, NY, NZ)
                for n in range(3):
                    if coords[n] + 1 < dims[n] and flat[v] != flat[v + step[n]]:
                        is_b[n * nvox + v] = 1
    jl = np.empty((64, 4), np.int64)
    jlab = np.empty((64, 4), np.int64)
    nj = 0
    sq = np.empty(4, np.int64)
    vx = np.empty(4, np.int64)
    for k in range(NZ - 1):
        for j in range(NY - 1):
            for i in range(NX - 1):
                p = (k * NY + j) * NX + i
                for b in range(3):
                    c = (b + 1) % 3
                    d = (b + 2) % 3
                    vx[0] = p
                    vx[1] = p + step[c]
                    vx[2] = p + step[c] + step[d]
                    vx[3] = p + step[d]
                    sq[0] = c * nvox + p
                    sq[1] = d * nvox + p + step[c]
                    sq[2] = c * nvox + p + step[d]
                    sq[3] = d * nvox + p
                    nb = 0
                    for t in range(4):
                        nb += is_b[sq[t]]
                    if nb == 2:
                        first = -1
                        for t in range(4):
                            if is_b[sq[t]]:
                                if first < 0:
                                    first = sq[t]
                                else:
                                    _union(parent, first, sq[t])
                    elif nb >= 3:
                        if nj == jl.shape[0]:
                            j2 = np.empty((2 * nj, 4), np.int64)
                            j2[:nj] = jl
                            jl = j2
                            l2 = np.empty((2 * nj, 4), np.int64)
                            l2[:nj] = jlab
                            jlab = l2
                        jl[nj, 0] = b
                        jl[nj, 1] = i
                        jl[nj, 2] = j
                        jl[nj, 3] = k
                        for t in range(4):
                            jlab[nj, t] = flat[vx[t]]
                        nj += 1
    # Linels with p on the last layer of any axis are skipped: along c or d a voxel would be beyond the padded
    # array, along b the four voxels are padding (all 0), so none of them is a boundary or junction linel.
    nsq = 0
    for s in range(3 * nvox):
        nsq += is_b[s]
    squares = np.empty((nsq, 4), np.int64)
    patch = np.empty(nsq, np.int64)
    pid = np.full(3 * nvox, -1, np.int64)
    npatch = 0
    t = 0
    for v in range(nvox):
        for n in range(3):
            s = n * nvox + v
            if not is_b[s]:
                continue
            root = _find(parent, s)
            if pid[root] < 0:
                pid[root] = npatch
                npatch += 1
            k = v // (NX * NY)
            j = (v // NX) % NY
            i = v % NX
            squares[t, 0] = n
            squares[t, 1] = i
            squares[t, 2] = j
            squares[t, 3] = k
            patch[t] = pid[root]
            t += 1
    return squares, patch, npatch, jl[:nj], jlab[:nj]


def boundary_cells(labels: npt.ArrayLike) -> BoundaryCells:
    """Group the boundary squares of a label volume into patches and list its junction linels.

    Parameters
    ----------
    labels : array_like of int, shape (nz, ny, nx)
        The label volume; 0 and everything outside the array is the background.

    Returns
    -------
    BoundaryCells
        In the indices of the array padded by one voxel on every side.
    """
    lab = np.asarray(labels)
    if lab.ndim != 3:
        raise ValueError(f"a label volume must be 3-D, got shape {lab.shape}")
    padded = np.pad(np.ascontiguousarray(lab, dtype=np.int32), 1)
    return BoundaryCells(*_boundary_cells(padded))


@njit(cache=True)
def _label_regions_3d(
    lab: Int32Array,
) -> tuple[Int32Array, Int64Array, Int64Array, Int64Array]:  # pragma: no cover - compiled
    # Union-find over the voxels, 6-adjacency between equal non-zero labels; the smaller index stays the root,
    # so a region's root is its first voxel in raster order. Returns every voxel's region (1, 2, …; 0: the
    # background) and, per region, its label, its number of voxels and its first voxel.
    nz, ny, nx = lab.shape
    n = nz * ny * nx
    flat = lab.reshape(n)
    parent = np.arange(n, dtype=np.int64)
    for v in range(n):
        a = flat[v]
        if a == 0:
            continue
        i = v % nx
        j = (v // nx) % ny
        k = v // (nx * ny)
        if i > 0 and flat[v - 1] == a:
            _union(parent, v - 1, v)
        if j > 0 and flat[v - nx] == a:
            _union(parent, v - nx, v)
        if k > 0 and flat[v - nx * ny] == a:
            _union(parent, v - nx * ny, v)
    region = np.zeros(n, np.int32)
    m = 0
    for v in range(n):
        if flat[v] != 0 and _find(parent, v) == v:
            m += 1
            region[v] = m
    label = np.empty(m, np.int64)
    voxels = np.zeros(m, np.int64)
    first = np.empty(m, np.int64)
    for v in range(n):
        if flat[v] == 0:
            continue
        region[v] = region[_find(parent, v)]  # the root comes first: its number is set
        r = region[v] - 1
        if voxels[r] == 0:
            label[r] = flat[v]
            first[r] = v
        voxels[r] += 1
    return region.reshape(lab.shape), label, voxels, first


def label_regions_3d(labels: npt.ArrayLike) -> tuple[Int64Array, Int64Array, Int64Array]:
    """The regions (6-connected components of equal non-zero labels) of a label volume.

    Returns
    -------
    label, voxels, first : ndarray of int64
        For each region in raster order (z, y, x) of its first voxel: its label, its number of voxels and the
        flat index of its first voxel in the (nz, ny, nx) array.
    """
    return region_map_3d(labels)[1:]


def region_map_3d(labels: npt.ArrayLike) -> tuple[Int32Array, Int64Array, Int64Array, Int64Array]:
    """The regions of a label volume (:func:`label_regions_3d`) and the region of every voxel.

    Returns
    -------
    region : ndarray of int32, the volume's shape
        Every voxel's region, numbered 1, 2, … as :func:`label_regions_3d` lists them; 0 for the background.
    label, voxels, first : ndarray of int64
        As :func:`label_regions_3d`.
    """
    lab = np.ascontiguousarray(labels, dtype=np.int32)
    if lab.ndim != 3:
        raise ValueError(f"a label volume must be 3-D, got shape {lab.shape}")
    return _label_regions_3d(lab)
