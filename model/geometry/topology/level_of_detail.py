"""Coarser levels of a voxel set for drawing: f × f × f blocks max-pooled into one voxel.

A voxel set of 10⁷–10⁸ voxels has millions of surfels: more than a view can draw at an interactive rate. A
coarser level replaces each block of f × f × f voxels by one voxel of side f, set when any voxel of the
block is set (max pooling), so the coarse set covers the fine one and its surface has about 1/f² of the
surfels. :func:`coarse_level` picks the smallest f whose surface fits a budget. The coarse set is for
drawing only: its topology can differ from the fine set's (thin gaps close, small cavities fill).

Everything here is numpy on masks (its loops release the GIL), run on a worker by the views.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

BoolArray = npt.NDArray[np.bool_]
Int64Array = npt.NDArray[np.int64]
UInt8Array = npt.NDArray[np.uint8]


def pool_voxels(mask: npt.ArrayLike, factor: int) -> BoolArray:
    """Max-pool a voxel mask by blocks of ``factor`` voxels along each axis.

    Parameters
    ----------
    mask : array_like of bool, shape (nz, ny, nx)
        The voxel set; ``mask[k, j, i]`` is voxel (x0 + i, y0 + j, z0 + k).
    factor : int
        The side f ≥ 1 of the blocks.

    Returns
    -------
    ndarray of bool, shape (⌈nz/f⌉, ⌈ny/f⌉, ⌈nx/f⌉)
        Voxel (I, J, K) is set when any voxel of the block f·(I, J, K) + [0, f)³ is; the last block of an axis
        may be cut by the mask's end.
    """
    f = int(factor)
    if f < 1:
        raise ValueError(f"a pooling factor must be at least 1, got {factor}")
    m = np.asarray(mask, dtype=bool)
    if m.ndim != 3:
        raise ValueError(f"a voxel mask must be 3-D, got shape {m.shape}")
    if f == 1 or m.size == 0:
        return m.copy()
    for axis in range(3):
        m = np.logical_or.reduceat(m, np.arange(0, m.shape[axis], f), axis=axis)
    return m


def boundary_surfels(mask: npt.ArrayLike) -> tuple[Int64Array, UInt8Array]:
    """The surfels of a voxel mask: each face between a voxel of the set and a 6-neighbour outside it.

    Parameters
    ----------
    mask : array_like of bool, shape (nz, ny, nx)

    Returns
    -------
    voxels : int64 (n, 3)
        The (i, j, k) array indices (x first) of the voxel each surfel belongs to.
    directions : uint8 (n,)
        The index of its outward normal in :data:`mrm.geometry.topology.surfels.DIRS`
        (+x, −x, +y, −y, +z, −z); surfels come by direction, then in raster order.
    """
    m = np.asarray(mask, dtype=bool)
    if m.ndim != 3:
        raise ValueError(f"a voxel mask must be 3-D, got shape {m.shape}")
    p = np.pad(m, 1)
    inner = p[1:-1, 1:-1, 1:-1]
    # the neighbour across each direction, as a view of the padded mask (axes are z, y, x)
    neighbour = (
        p[1:-1, 1:-1, 2:],
        p[1:-1, 1:-1, :-2],
        p[1:-1, 2:, 1:-1],
        p[1:-1, :-2, 1:-1],
        p[2:, 1:-1, 1:-1],
        p[:-2, 1:-1, 1:-1],
    )
    voxels = []
    directions = []
    for d, other in enumerate(neighbour):
        k, j, i = np.nonzero(inner & ~other)
        voxels.append(np.stack([i, j, k], axis=1).astype(np.int64))
        directions.append(np.full(i.size, d, np.uint8))
    return np.concatenate(voxels), np.concatenate(directions)


def surfel_total(mask: npt.ArrayLike) -> int:
    """The number of surfels of a voxel mask (faces between the set and the outside)."""
    m = np.asarray(mask, dtype=bool)
    p = np.pad(m, 1)
    return sum(int(np.count_nonzero(np.diff(p, axis=a))) for a in range(3))


def coarse_level(mask: npt.ArrayLike, budget: int, n_surfels: int | None = None) -> tuple[int, BoolArray]:
    """The finest max-pooled level of a voxel mask whose surfels number at most ``budget``.

    Parameters
    ----------
    mask : array_like of bool, shape (nz, ny, nx)
    budget : int
        The most surfels the level may have (≥ 1).
    n_surfels : int, optional
        The mask's own surfel count when known (saves counting it).

    Returns
    -------
    factor : int
        The block side f (1: the mask itself, within the budget).
    pooled : ndarray of bool
        :func:`pool_voxels` ``(mask, f)``.
    """
    if budget < 1:
        raise ValueError(f"a surfel budget must be positive, got {budget}")
    m = np.asarray(mask, dtype=bool)
    n = surfel_total(m) if n_surfels is None else int(n_surfels)
    if n <= budget:
        return 1, m
    # The surface of a pooled set shrinks about as 1/f²: start there and go coarser until it fits.
    f = max(2, math.ceil(math.sqrt(n / budget)))
    while True:
        pooled = pool_voxels(m, f)
        if surfel_total(pooled) <= budget or max(pooled.shape) <= 1:
            return f, pooled
        f += max(1, f // 4)


def cluster_vertices(
    vertices: npt.ArrayLike, triangles: npt.ArrayLike, cell: float
) -> tuple[npt.NDArray[np.float64], Int64Array, Int64Array]:
    """A coarser triangle mesh by vertex clustering: the vertices in one cube of side ``cell`` become one.

    Each cluster's vertex is the mean of its vertices; a triangle two of whose corners fall in one cluster
    vanishes, and of triangles with the same three clusters one is kept. For drawing only: the result need
    not be a closed or manifold surface.

    Parameters
    ----------
    vertices : float (n, 3)
    triangles : int (m, 3)
    cell : float
        The side of the clustering cubes (> 0), cubes aligned on the origin.

    Returns
    -------
    vertices : float64 (n', 3)
    triangles : int64 (m', 3)
    kept : int64 (m',)
        The index in ``triangles`` of each triangle kept (to carry per-triangle data, e.g. its face).
    """
    if not cell > 0:
        raise ValueError(f"a clustering cell must be positive, got {cell}")
    v = np.asarray(vertices, np.float64).reshape(-1, 3)
    t = np.asarray(triangles, np.int64).reshape(-1, 3)
    if t.size == 0:
        return np.zeros((0, 3)), np.zeros((0, 3), np.int64), np.zeros(0, np.int64)
    cells = np.floor(v / cell).astype(np.int64)
    cluster, counts = _unique_rows(cells)
    sums = np.zeros((counts.size, 3))
    np.add.at(sums, cluster, v)
    centres = sums / counts[:, None]
    ct = cluster[t]
    proper = (ct[:, 0] != ct[:, 1]) & (ct[:, 1] != ct[:, 2]) & (ct[:, 0] != ct[:, 2])
    index = np.flatnonzero(proper)
    ct = ct[proper]
    # one triangle per set of three clusters (turned so that its smallest cluster comes first, keeping its
    # orientation: a triangle and its reverse are different faces)
    first = np.argmin(ct, axis=1)
    rolled = np.stack([ct[np.arange(len(ct)), (first + k) % 3] for k in range(3)], axis=1)
    which, _counts = _unique_rows(rolled)
    unique_at = np.full(int(which.max()) + 1 if which.size else 0, len(which), np.int64)
    np.minimum.at(unique_at, which, np.arange(len(which)))
    unique_at.sort()
    return centres, rolled[unique_at], index[unique_at]


def _unique_rows(rows: Int64Array) -> tuple[Int64Array, Int64Array]:
    """The index of each row's class of equal rows (classes in sorted order) and each class's size.

    Rows are packed into one int64 key when their ranges allow it, so that numpy sorts integers (without
    holding the GIL, which a worker must not hold for long: the GUI thread waits for it) rather than rows.
    """
    lo = rows.min(axis=0)
    span = rows.max(axis=0) - lo + 1
    if float(np.prod(span.astype(np.float64))) < 2.0**62:
        shifted = rows - lo
        key = shifted[:, 0]
        for k in range(1, rows.shape[1]):
            key = key * span[k] + shifted[:, k]
        _u, inverse, counts = np.unique(key, return_inverse=True, return_counts=True)
    else:
        _r, inverse, counts = np.unique(rows, axis=0, return_inverse=True, return_counts=True)
    return inverse.reshape(-1).astype(np.int64), counts.astype(np.int64)


def coarse_mesh(
    vertices: npt.ArrayLike, triangles: npt.ArrayLike, budget: int
) -> tuple[float, npt.NDArray[np.float64], Int64Array, Int64Array]:
    """The finest vertex clustering (:func:`cluster_vertices`) of a mesh within ``budget`` triangles.

    Returns
    -------
    cell : float
        The side of the clustering cubes (0: the mesh itself, within the budget).
    vertices, triangles, kept :
        As :func:`cluster_vertices` (the mesh itself, and every index, at cell 0).
    """
    if budget < 1:
        raise ValueError(f"a triangle budget must be positive, got {budget}")
    v = np.asarray(vertices, np.float64).reshape(-1, 3)
    t = np.asarray(triangles, np.int64).reshape(-1, 3)
    if len(t) <= budget:
        return 0.0, v, t, np.arange(len(t), dtype=np.int64)
    # the mean edge length sets the start: triangles shrink in number about as 1/cell²
    edge = float(np.mean(np.linalg.norm(v[t[:, 1]] - v[t[:, 0]], axis=1))) or 1.0
    cell = edge * max(1.0, math.sqrt(len(t) / budget))
    while True:
        cv, ct, kept = cluster_vertices(v, t, cell)
        if len(ct) <= budget:
            return cell, cv, ct, kept
        cell *= 1.3
