"""Shared constants and array helpers of R's kernels (:mod:`._kernels`)."""

from __future__ import annotations

from typing import NamedTuple

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


# ============================================================================================ stage records
# The arrays one phase hands to the next, grouped (numba compiles and caches NamedTuples of arrays): the
# *_all drivers take and return these instead of a dozen positional arrays each.


class Corridors(NamedTuple):
    """Phase 1's output for every ring (:func:`._kernels.corridors_all`, :func:`._dual.dual_corridors_all`).

    Ring k has elements ``eoff[k] … eoff[k+1]−1`` (``ec``, ``er`` their pixel or pointel in array
    coordinates, ``edin`` / ``edout`` the codes into and out of it, ``enl`` its linels, ``cnt`` how many
    elements share its pixel, saturated at 2), pieces ``poff[k] … poff[k+1]−1`` (``rect`` [x0, x1, y0, y1]
    in Q-units, ``pel`` each piece's element (local index), ``gp`` / ``gq`` the left / right end of the
    gate into it, ``gdir`` the crossing direction) and safety-net vertices ``r0off[k] …`` (``r0``, ``r0t``
    their local piece); ``kmax`` its snapping depth, ``special`` 1 for an isolated pixel (no pieces), 2 for
    two pixels visited once each (cover models), else 0, and ``full`` 1 when every piece is a whole square.

    The per-element, per-piece and per-net-vertex arrays are int32 (coordinates, indices) and int8 (codes,
    linel counts, directions), not int64: they are most of what R holds (half its peak memory on the
    camera image with int64). Numba widens them to int64 in every expression, so no product overflows;
    :func:`mrm.geometry.reconstruct._run` refuses arrays whose Q-units or element counts would not fit.
    """

    eoff: np.ndarray
    ec: np.ndarray
    er: np.ndarray
    edin: np.ndarray
    edout: np.ndarray
    enl: np.ndarray
    cnt: np.ndarray
    r0off: np.ndarray
    r0: np.ndarray
    r0t: np.ndarray
    poff: np.ndarray
    rect: np.ndarray
    pel: np.ndarray
    gp: np.ndarray
    gq: np.ndarray
    gdir: np.ndarray
    kmax: np.ndarray
    special: np.ndarray
    full: np.ndarray


class Greedy(NamedTuple):
    """Phase 3's output (:func:`._kernels.greedy_all`): the V4 greedy rings, concatenated.

    ``xy`` the float vertices (Q-units), ``piece`` their (unwrapped) pieces, ``source`` and ``line`` the
    vertex source and the window of the edge leaving each vertex; ring k is ``off[k] … off[k+1]−1``, and
    ``ok[k]`` says whether its greedy succeeded.
    """

    xy: np.ndarray
    piece: np.ndarray
    source: np.ndarray
    line: np.ndarray
    off: np.ndarray
    ok: np.ndarray


class Rings(NamedTuple):
    """Phase 4's output (:func:`._kernels.finish_all`): closed rings in plane coordinates.

    ``xy`` the vertices (each ring closed by a repeat of its first), ring k is ``roff[k] … roff[k+1]−1``;
    ``status`` per ring (``RING_*``), ``src`` and ``win`` per vertex (−1 on the closing repeats).
    """

    xy: np.ndarray
    roff: np.ndarray
    status: np.ndarray
    src: np.ndarray
    win: np.ndarray
