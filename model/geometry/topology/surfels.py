"""Surfels of a voxel set grouped into closed surfaces, with the (6, 26) topology.

Reference: docs/design.md §11 (region representation); the 2D counterpart is :mod:`.cracks`.

A **surfel** is the oriented unit square between a voxel p of A and its 6-neighbour p + n outside A; it is
written (p, d) with d the index of the outward normal n in :data:`DIRS` (+x, −x, +y, −y, +z, −z).

Each of the four edges of a surfel (p, n), on its side t (a unit vector orthogonal to n), is shared with
exactly one other surfel, chosen by the (6, 26) rule:

- p + t ∈ A and p + t + n ∈ A: the surface turns inward, to (p + t + n, −t);
- p + t ∈ A and p + t + n ∉ A: it goes on flat, to (p + t, n);
- p + t ∉ A: it turns outward around p, to (p, t) — even when p + t + n ∈ A, so that two voxels of A meeting
  only along an edge keep their surfaces apart.

The rule is symmetric and keeps both the voxel of A (6-adjacent steps) and the voxel outside (26-adjacent
steps) in their components. A **surface** is the set of surfels between one 6-component X of A and one
26-component C of the complement: one outer surface per component and one per cavity. Every edge of a
surface's surfels is shared by exactly two of its surfels, so each surface is closed. It is connected when
surfels meeting at a single pointel are allowed too: two voxels of C meeting only at a corner (26-adjacent)
join their surfels there, which edge steps alone do not (the surfels of a cavity voxel 26-adjacent to the
outside only through a corner are an edge-closed patch of the outer surface). For the same reason a surface's
genus is not read from its surfels' vertices; the tunnels come from the Euler characteristic
(:mod:`.labeling_3d`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import njit, py_func
from mrm.geometry.topology.labeling_3d import Runs3D, as_u8_3d

Int32Array = npt.NDArray[np.int32]
Int64Array = npt.NDArray[np.int64]
UInt8Array = npt.NDArray[np.uint8]

#: The outward normals of the six surfel directions, as (dx, dy, dz).
DIRS = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=np.int64)
DIRS.flags.writeable = False


class Surfels(NamedTuple):
    """The surfels of a voxel mask and their surfaces (:func:`surfels_of`).

    Surfels are in raster order of their voxel (z, y, x), then by direction. Surfaces are numbered 0, 1, …
    in the order of their first surfel.

    Attributes
    ----------
    voxel : int64 (n, 3), the (i, j, k) array indices of the voxel of A each surfel belongs to.
    direction : uint8 (n,), the index in :data:`DIRS` of its outward normal.
    neighbour : int64 (n, 4), the surfels across its four edges (sides in the order of :func:`edge_sides`).
    surface : int32 (n,), its surface.
    component : int64 (n_surfaces,), the component (label of :class:`Runs3D`) on the inside of each surface.
    outside : int64 (n_surfaces,), the background component on its outside (0: unbounded; else a cavity id).
    """

    voxel: Int64Array
    direction: UInt8Array
    neighbour: Int64Array
    surface: Int32Array
    component: Int64Array
    outside: Int64Array

    @property
    def n_surfaces(self) -> int:
        """The number of surfaces."""
        return int(self.component.size)


@njit(cache=True)
def _sides(d: int) -> tuple[int, int, int, int]:  # pragma: no cover
    # The four sides t of a surfel with normal d: the directions of the two other axes, + then −.
    a = d >> 1
    b = (a + 1) % 3
    c = (a + 2) % 3
    return 2 * b, 2 * b + 1, 2 * c, 2 * c + 1


@njit(cache=True)
def _lookup(keys: Int64Array, lo: int, hi: int, key: int) -> int:  # pragma: no cover
    while lo < hi:
        mid = (lo + hi) >> 1
        if keys[mid] < key:
            lo = mid + 1
        else:
            hi = mid
    return lo


@njit(cache=True)
def _surfels(
    m: UInt8Array,
) -> tuple[Int64Array, UInt8Array, Int64Array]:  # pragma: no cover
    nz, ny, nx = m.shape
    NX, NY, NZ = nx + 2, ny + 2, nz + 2
    pad = np.zeros((NZ, NY, NX), np.uint8)
    pad[1:-1, 1:-1, 1:-1] = m
    flat = pad.reshape(NX * NY * NZ)
    off = np.empty(6, np.int64)
    off[0], off[1], off[2], off[3], off[4], off[5] = 1, -1, NX, -NX, NX * NY, -NX * NY
    # rows of the padded array: row R = k·NY + j holds the voxels (·, j, k); surfel key within a row: i·6 + d.
    rowptr = np.zeros(NZ * NY + 1, np.int64)
    for R in range(NZ * NY):
        cnt = 0
        base = R * NX
        for i in range(1, NX - 1):
            v = base + i
            if flat[v]:
                for d in range(6):
                    if not flat[v + off[d]]:
                        cnt += 1
        rowptr[R + 1] = rowptr[R] + cnt
    n = rowptr[-1]
    keys = np.empty(n, np.int64)
    voxel = np.empty((n, 3), np.int64)
    direction = np.empty(n, np.uint8)
    t = 0
    for R in range(NZ * NY):
        base = R * NX
        k = R // NY
        j = R - k * NY
        for i in range(1, NX - 1):
            v = base + i
            if flat[v]:
                for d in range(6):
                    if not flat[v + off[d]]:
                        keys[t] = i * 6 + d
                        voxel[t, 0] = i - 1
                        voxel[t, 1] = j - 1
                        voxel[t, 2] = k - 1
                        direction[t] = d
                        t += 1
    # ---- neighbours across the four edges, by the (6, 26) rule
    neighbour = np.empty((n, 4), np.int64)
    for s in range(n):
        i = voxel[s, 0] + 1
        j = voxel[s, 1] + 1
        k = voxel[s, 2] + 1
        v = (k * NY + j) * NX + i
        d = direction[s]
        sides = _sides(d)
        for e in range(4):
            tt = sides[e]
            if flat[v + off[tt]]:
                if flat[v + off[tt] + off[d]]:
                    q = v + off[tt] + off[d]
                    qd = tt ^ 1
                else:
                    q = v + off[tt]
                    qd = d
            else:
                q = v
                qd = tt
            R = q // NX
            lo = rowptr[R]
            hi = rowptr[R + 1]
            key = (q - R * NX) * 6 + qd
            idx = _lookup(keys, lo, hi, key)
            neighbour[s, e] = idx
    return voxel, direction, neighbour


@njit(cache=True)
def _pairs(
    voxel: Int64Array,
    direction: UInt8Array,
    rs: npt.NDArray[np.int32],
    re: npt.NDArray[np.int32],
    ptr: Int64Array,
    label: npt.NDArray[np.int32],
    bg_label: npt.NDArray[np.int32],
    nx: int,
    ny: int,
    nz: int,
    n_bg: int,
) -> Int64Array:  # pragma: no cover
    # For each surfel: (its voxel's component) · n_bg + (the background component of the voxel outside),
    # read from the runs by binary search in the voxel's row.
    n = direction.size
    out = np.empty(n, np.int64)
    for s in range(n):
        i, j, k = voxel[s, 0], voxel[s, 1], voxel[s, 2]
        r = k * ny + j
        lo = ptr[r]
        hi = ptr[r + 1]
        while lo < hi:  # the first run ending at or after i
            mid = (lo + hi) >> 1
            if re[mid] < i:
                lo = mid + 1
            else:
                hi = mid
        c = label[lo]
        d = direction[s]
        i2 = i + DIRS_X[d]
        j2 = j + DIRS_Y[d]
        k2 = k + DIRS_Z[d]
        b = 0
        if 0 <= i2 < nx and 0 <= j2 < ny and 0 <= k2 < nz:
            r2 = k2 * ny + j2
            lo = ptr[r2]
            hi = ptr[r2 + 1]
            while lo < hi:  # the runs starting before i2: the gap holding i2 comes after them
                mid = (lo + hi) >> 1
                if rs[mid] < i2:
                    lo = mid + 1
                else:
                    hi = mid
            b = bg_label[lo + r2]
        out[s] = c * n_bg + b
    return out


DIRS_X = np.ascontiguousarray(DIRS[:, 0])
DIRS_Y = np.ascontiguousarray(DIRS[:, 1])
DIRS_Z = np.ascontiguousarray(DIRS[:, 2])


def edge_sides(direction: int) -> tuple[int, int, int, int]:
    """The four sides of a surfel with outward normal ``DIRS[direction]``, as indices into :data:`DIRS`.

    Column e of :attr:`Surfels.neighbour` is the surfel across the edge on side ``edge_sides(d)[e]``.
    """
    a, b, c, d = py_func(_sides)(int(direction))
    return int(a), int(b), int(c), int(d)


def surfels_of(mask: npt.ArrayLike, runs: Runs3D) -> Surfels:
    """The surfels of a voxel mask, linked by the (6, 26) rule and grouped into closed surfaces.

    Parameters
    ----------
    mask : array_like, shape (nz, ny, nx)
        Non-zero entries are the object.
    runs : Runs3D
        The mask's runs labelled with 6-connectivity (:func:`~.labeling_3d.label_runs_3d`).

    Returns
    -------
    Surfels
        See the module docstring; voxel coordinates are array indices (i, j, k).
    """
    m = as_u8_3d(mask)
    if m.shape != runs.shape:
        raise ValueError(f"the runs are of a {runs.shape} mask, not {m.shape}")
    if m.size == 0 or runs.n_labels == 0:
        z = np.zeros(0, np.int64)
        return Surfels(
            np.zeros((0, 3), np.int64),
            np.zeros(0, np.uint8),
            np.zeros((0, 4), np.int64),
            np.zeros(0, np.int32),
            z,
            z,
        )
    voxel, direction, neighbour = _surfels(m)
    nz, ny, nx = m.shape
    key = _pairs(
        voxel, direction, runs.start, runs.end, runs.ptr, runs.label, runs.bg_label, nx, ny, nz, runs.n_bg
    )
    uniq, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")  # surfaces numbered by their first surfel
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    surface = rank[inverse.ravel()].astype(np.int32)
    keys = uniq[order]
    return Surfels(voxel, direction, neighbour, surface, keys // runs.n_bg, keys % runs.n_bg)
