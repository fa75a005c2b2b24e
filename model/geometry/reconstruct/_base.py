"""Shared constants and array helpers of R's kernels (:mod:`._kernels`)."""

from __future__ import annotations

import numpy as np

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
_RELINK_MAX = 48  # relink_ring verifies the whole ring per candidate (quadratic): only rings this small
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
