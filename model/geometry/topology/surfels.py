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
from mrm.geometry.topology.labeling_3d import Runs3D

Int32Array = npt.NDArray[np.int32]
Int64Array = npt.NDArray[np.int64]
UInt8Array = npt.NDArray[np.uint8]

#: The outward normals of the six surfel directions, as (dx, dy, dz).
DIRS = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=np.int64)
DIRS.flags.writeable = False
DIRS_X = np.ascontiguousarray(DIRS[:, 0])
DIRS_Y = np.ascontiguousarray(DIRS[:, 1])
DIRS_Z = np.ascontiguousarray(DIRS[:, 2])


class Surfels(NamedTuple):
    """The surfels of a voxel mask and their surfaces (:func:`surfels_of`).

    Surfels are in raster order of their voxel (z, y, x), then by direction. Surfaces are numbered 0, 1, …
    by component, each component's outer surface first, then one per cavity.

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
    rs: npt.NDArray[np.int32], re: npt.NDArray[np.int32], ptr: Int64Array, nx: int, ny: int, nz: int
) -> tuple[Int64Array, UInt8Array, Int64Array]:  # pragma: no cover
    # The surfels of the voxels of the runs, in raster order then by direction, and their neighbours. Only the
    # voxels of A are visited; membership is read from a padded byte copy of the mask built from the runs.
    NX, NY, NZ = nx + 2, ny + 2, nz + 2
    flat = np.zeros(NX * NY * NZ, np.uint8)
    nrows = ny * nz
    for r in range(nrows):
        k = r // ny
        j = r - k * ny
        base = ((k + 1) * NY + j + 1) * NX + 1
        for t in range(ptr[r], ptr[r + 1]):
            for i in range(rs[t], re[t] + 1):
                flat[base + i] = 1
    off = np.empty(6, np.int64)
    off[0], off[1], off[2], off[3], off[4], off[5] = 1, -1, NX, -NX, NX * NY, -NX * NY
    # surfel key within a row (k, j): i·6 + d; rowptr over the rows of the unpadded mask.
    rowptr = np.zeros(nrows + 1, np.int64)
    for r in range(nrows):
        k = r // ny
        j = r - k * ny
        base = ((k + 1) * NY + j + 1) * NX + 1
        cnt = 0
        for t in range(ptr[r], ptr[r + 1]):
            cnt += 2  # ±x at the run's ends
            for i in range(rs[t], re[t] + 1):
                v = base + i
                for d in range(2, 6):
                    if not flat[v + off[d]]:
                        cnt += 1
        rowptr[r + 1] = rowptr[r] + cnt
    n = rowptr[-1]
    keys = np.empty(n, np.int64)
    voxel = np.empty((n, 3), np.int64)
    direction = np.empty(n, np.uint8)
    s = 0
    for r in range(nrows):
        k = r // ny
        j = r - k * ny
        base = ((k + 1) * NY + j + 1) * NX + 1
        for t in range(ptr[r], ptr[r + 1]):
            for i in range(rs[t], re[t] + 1):
                v = base + i
                for d in range(6):
                    if not flat[v + off[d]]:
                        keys[s] = i * 6 + d
                        voxel[s, 0] = i
                        voxel[s, 1] = j
                        voxel[s, 2] = k
                        direction[s] = d
                        s += 1
    # ---- neighbours across the four edges, by the (6, 26) rule
    neighbour = np.empty((n, 4), np.int64)
    for s in range(n):
        i = voxel[s, 0]
        j = voxel[s, 1]
        k = voxel[s, 2]
        v = ((k + 1) * NY + j + 1) * NX + i + 1
        d = direction[s]
        sides = _sides(d)
        for e in range(4):
            tt = sides[e]
            qi, qj, qk = i, j, k
            if flat[v + off[tt]]:
                qi += DIRS_X[tt]
                qj += DIRS_Y[tt]
                qk += DIRS_Z[tt]
                if flat[v + off[tt] + off[d]]:
                    qi += DIRS_X[d]
                    qj += DIRS_Y[d]
                    qk += DIRS_Z[d]
                    qd = tt ^ 1
                else:
                    qd = d
            else:
                qd = tt
            r = qk * ny + qj
            neighbour[s, e] = _lookup(keys, rowptr[r], rowptr[r + 1], qi * 6 + qd)
    return voxel, direction, neighbour


@njit(cache=True)
def _surface_ids(
    voxel: Int64Array,
    direction: UInt8Array,
    rs: npt.NDArray[np.int32],
    re: npt.NDArray[np.int32],
    ptr: Int64Array,
    label: npt.NDArray[np.int32],
    bg_label: npt.NDArray[np.int32],
    exterior: Int64Array,
    first_surface: Int64Array,
    cavity_slot: Int64Array,
    nx: int,
    ny: int,
    nz: int,
) -> Int32Array:  # pragma: no cover
    # Each surfel's surface: its voxel's component c (binary search in the voxel's row) and the background
    # component b of the voxel outside (the gap holding it); first_surface[c] if b is c's exterior, else
    # first_surface[c] + cavity_slot[b].
    n = direction.size
    out = np.empty(n, np.int32)
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
        out[s] = first_surface[c] if b == exterior[c] else first_surface[c] + cavity_slot[b]
    return out


@njit(cache=True)
def _exterior(
    rs: npt.NDArray[np.int32],
    ptr: Int64Array,
    label: npt.NDArray[np.int32],
    bg_label: npt.NDArray[np.int32],
    nlab: int,
    ny: int,
) -> Int64Array:  # pragma: no cover
    # The background component outside each component: the one holding the voxel below its first voxel (the
    # column below the lowest voxel of a component meets none of it, so that voxel is in its exterior).
    ext = np.full(nlab + 1, -1, np.int64)
    for r in range(ptr.size - 1):
        k = r // ny
        for t in range(ptr[r], ptr[r + 1]):
            c = label[t]
            if ext[c] >= 0:
                continue
            if k == 0:
                ext[c] = 0
                continue
            r2 = r - ny
            i = rs[t]
            lo = ptr[r2]
            hi = ptr[r2 + 1]
            while lo < hi:
                mid = (lo + hi) >> 1
                if rs[mid] < i:
                    lo = mid + 1
                else:
                    hi = mid
            ext[c] = bg_label[lo + r2]
    return ext


def edge_sides(direction: int) -> tuple[int, int, int, int]:
    """The four sides of a surfel with outward normal ``DIRS[direction]``, as indices into :data:`DIRS`.

    Column e of :attr:`Surfels.neighbour` is the surfel across the edge on side ``edge_sides(d)[e]``.
    """
    a, b, c, d = py_func(_sides)(int(direction))
    return int(a), int(b), int(c), int(d)


def surfels_of(runs: Runs3D) -> Surfels:
    """The surfels of a voxel mask, linked by the (6, 26) rule and grouped into closed surfaces.

    Parameters
    ----------
    runs : Runs3D
        The mask's runs labelled with 6-connectivity (:func:`~.labeling_3d.label_runs_3d`).

    Returns
    -------
    Surfels
        See the module docstring; voxel coordinates are array indices (i, j, k). Surfaces are numbered by
        component, each component's outer surface first, then one per cavity in the order of their labels.
    """
    nz, ny, nx = runs.shape
    if runs.n_labels == 0:
        z = np.zeros(0, np.int64)
        return Surfels(
            np.zeros((0, 3), np.int64),
            np.zeros(0, np.uint8),
            np.zeros((0, 4), np.int64),
            np.zeros(0, np.int32),
            z,
            z,
        )
    voxel, direction, neighbour = _surfels(runs.start, runs.end, runs.ptr, nx, ny, nz)
    exterior = _exterior(runs.start, runs.ptr, runs.label, runs.bg_label, runs.n_labels, ny)
    # surfaces: component c's outer one, then its cavities (background ids b with encloser[b] == c, in order)
    n_cav = np.bincount(runs.encloser[1:], minlength=runs.n_labels + 1)
    first_surface = np.zeros(runs.n_labels + 1, np.int64)
    first_surface[1:] = np.cumsum(1 + n_cav[1:]) - (1 + n_cav[1:])
    cavity_slot = np.zeros(runs.n_bg, np.int64)
    component = np.repeat(np.arange(1, runs.n_labels + 1), 1 + n_cav[1:])
    outside = np.empty(component.size, np.int64)
    outside[first_surface[1:]] = exterior[1:]
    seen = np.zeros(runs.n_labels + 1, np.int64)
    for b in range(1, runs.n_bg):  # few: one per cavity
        c = int(runs.encloser[b])
        seen[c] += 1
        cavity_slot[b] = seen[c]
        outside[first_surface[c] + seen[c]] = b
    surface = _surface_ids(
        voxel,
        direction,
        runs.start,
        runs.end,
        runs.ptr,
        runs.label,
        runs.bg_label,
        exterior,
        first_surface,
        cavity_slot,
        nx,
        ny,
        nz,
    )
    return Surfels(voxel, direction, neighbour, surface, component, outside)
