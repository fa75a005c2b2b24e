"""Segmentations of chains of points into digital straight segments.

Reference: docs/design.md §5, docs/algorithms.md §2.3.

A *chain* is a sequence of integer points in which consecutive points are 4-adjacent (``adjacency=4``,
standard segments) or 8-adjacent (``adjacency=8``, naive segments). It is read as open unless
``closed=True``; a closed chain of m points is cyclic (point m−1 is followed by point 0) and, when its last
point repeats the first (as :func:`chain_points` of a closed Freeman chain does), that repeated point is
dropped, so that index m and index 0 name the same point.

* :func:`greedy_segmentation` — DGtal's ``GreedySegmentation`` over ``ArithmeticalDSSComputer``: from
  point 0, extend the segment while the points form a DSS; the next segment starts at the last point of
  the previous one (consecutive segments share their end point).
* :func:`maximal_segments` — DGtal's ``SaturatedSegmentation``: all maximal segments (the tangential cover).
* :func:`standard_dss_reach` / :func:`standard_dss_reach_table` — for each start, how far a standard DSS
  reaches, and its characteristics.
* :func:`dss_of_window` — the minimal DSS of any window of a chain.

Every function is O(n) (extend plus retract, Lachaud, de Vieilleville & Feschet 2007) and runs in numba.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Literal

import numpy as np
import numpy.typing as npt

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.geometry.dss import Segment
from mrm.geometry.dss import _kernels as K

IntArray = npt.NDArray[np.int64]

_CODE_STEPS = np.array([[1, 0], [0, 1], [-1, 0], [0, -1]], dtype=np.int64)


def chain_points(start: Sequence[int], codes: str | Sequence[int]) -> IntArray:
    """Return the points of a Freeman chain: point 0 is ``start``, point i follows code i−1.

    Parameters
    ----------
    start : (int, int)
        The first point.
    codes : str or sequence of int
        Freeman codes 0 = E (+1, 0), 1 = N (0, +1), 2 = W (−1, 0), 3 = S (0, −1), as a string such as
        ``"0011"`` or a sequence of ints.

    Returns
    -------
    ndarray of int64, shape (n + 1, 2)
        The n + 1 points of a chain of n codes. For a closed chain the last point equals the first.

    Raises
    ------
    InvalidGeometryError
        If a code is not one of 0, 1, 2, 3.
    """
    if isinstance(codes, str):
        raw = np.frombuffer(codes.encode("ascii", errors="replace"), dtype=np.uint8).astype(np.int64) - 48
    else:
        raw = np.asarray(list(codes), dtype=np.int64).reshape(-1)
    bad = np.flatnonzero((raw < 0) | (raw > 3))
    if bad.size:
        k = int(bad[0])
        shown = codes[k] if isinstance(codes, str) else raw[k]
        raise InvalidGeometryError(f"Freeman code {shown!r} at position {k} is not one of 0, 1, 2, 3")
    x0, y0 = (int(start[0]), int(start[1]))
    out = np.empty((raw.size + 1, 2), dtype=np.int64)
    out[0] = (x0, y0)
    if raw.size:
        np.cumsum(_CODE_STEPS[raw], axis=0, out=out[1:])
        out[1:] += out[0]
    return out


def _as_chain(points: npt.ArrayLike, closed: bool, adjacency: int) -> IntArray:
    """Validate a chain; return it as a C-contiguous (m, 2) int64 array (closing repeat dropped)."""
    if adjacency not in (4, 8):
        raise ParameterError(f"adjacency must be 4 or 8, not {adjacency!r}")
    arr = np.asarray(points)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise InvalidGeometryError(f"a chain must be an (n, 2) array of points, not shape {arr.shape}")
    if arr.shape[0] == 0:
        raise InvalidGeometryError("a chain needs at least one point")
    if not np.issubdtype(arr.dtype, np.integer):
        if not np.issubdtype(arr.dtype, np.floating) or not np.all(arr == np.round(arr)):
            raise InvalidGeometryError("chain points must have integer coordinates")
        if np.abs(arr).max() >= 2**53:
            raise InvalidGeometryError("chain coordinates are too large")
    pts = np.ascontiguousarray(arr, dtype=np.int64)
    if max(-int(pts.min()), int(pts.max())) >= 2**40:
        # remainders a·x − b·y must fit in int64 (|a|, |b| ≤ chain length)
        raise InvalidGeometryError("chain coordinates must stay below 2**40 in absolute value")
    if closed and pts.shape[0] > 1 and pts[0, 0] == pts[-1, 0] and pts[0, 1] == pts[-1, 1]:
        pts = pts[:-1]
    k = int(K.check_chain(pts, closed, adjacency))
    if k >= 0:
        k1 = (k + 1) % pts.shape[0]
        what = "4-adjacent" if adjacency == 4 else "8-adjacent (and distinct)"
        raise InvalidGeometryError(
            f"chain points {k} {tuple(pts[k].tolist())} and {k1} {tuple(pts[k1].tolist())} are not {what}"
        )
    return pts


def _segments_of(table: IntArray) -> list[Segment]:
    return [
        Segment(
            int(r[0]),
            int(r[1]),
            int(r[2]),
            int(r[3]),
            int(r[4]),
            int(r[5]),
            (int(r[6]), int(r[7])),
            (int(r[8]), int(r[9])),
            (int(r[10]), int(r[11])),
            (int(r[12]), int(r[13])),
        )
        for r in table.tolist()
    ]


ClosedEnd = Literal["wrap", "truncate"]


def greedy_table(
    points: npt.ArrayLike, *, closed: bool = False, adjacency: int = 4, closed_end: ClosedEnd = "wrap"
) -> IntArray:
    """Like :func:`greedy_segmentation`, as a (k, 14) int64 table (no Python objects; for large inputs).

    Columns: first, last, a, b, mu, omega, Uf x, Uf y, Ul x, Ul y, Lf x, Lf y, Ll x, Ll y.
    """
    pts = _as_chain(points, closed, adjacency)
    m = pts.shape[0]
    if not closed:
        last = m - 1
    elif closed_end == "wrap":
        last = m if m > 1 else 0
    elif closed_end == "truncate":
        last = m - 1
    else:
        raise ParameterError(f"closed_end must be 'wrap' or 'truncate', not {closed_end!r}")
    table: IntArray = K.greedy_kernel(pts, m, last, adjacency)
    return table


def greedy_segmentation(
    points: npt.ArrayLike, *, closed: bool = False, adjacency: int = 4, closed_end: ClosedEnd = "wrap"
) -> list[Segment]:
    """Greedy segmentation into DSS, exactly DGtal's ``GreedySegmentation`` over ``ArithmeticalDSSComputer``.

    Parameters
    ----------
    points : array_like of int, shape (n, 2)
        The chain (see the module docstring); e.g. :func:`chain_points` of a Freeman chain.
    closed : bool
        Read the chain as cyclic.
    adjacency : {4, 8}
        4: standard DSS on a 4-connected chain (DGtal ``StandardDSS4Computer``); 8: naive DSS on an
        8-connected chain (``NaiveDSS8Computer``).
    closed_end : {"wrap", "truncate"}
        Only for closed chains of m points. Segments start at point 0 and run around the cycle, each
        starting at the last point of the previous one, until they are back at point 0. With ``"wrap"``
        (the default) the last segment ends *on* point 0 again (``last == m``), so the segments cover
        every step of the cycle. With ``"truncate"`` the last segment stops at point m − 1, as DGtal's
        greedy segmentation does on a circulator in its default "Truncate" mode (the closing step
        m−1 → 0 then belongs to no segment). The two differ in count only when the step back to point 0
        cannot extend the last segment, which then adds the one-step segment [m−1, m].

    Returns
    -------
    list of Segment
        In chain order; ``segments[k].last == segments[k + 1].first``. For an open chain the first segment
        starts at 0 and the last ends at n − 1.

    Raises
    ------
    InvalidGeometryError
        If the points are not a chain for this adjacency (non-integer, repeated or non-adjacent points).
    """
    return _segments_of(greedy_table(points, closed=closed, adjacency=adjacency, closed_end=closed_end))


def maximal_table(points: npt.ArrayLike, *, closed: bool = False, adjacency: int = 4) -> IntArray:
    """Like :func:`maximal_segments`, as a (k, 14) int64 table (columns as in :func:`greedy_table`)."""
    pts = _as_chain(points, closed, adjacency)
    if pts.shape[0] == 1:
        single: IntArray = K.window_kernel(pts, 0, 0, adjacency)
        return single
    table: IntArray = K.maximal_kernel(pts, closed, adjacency)
    if closed:
        # the sweep runs once around from the maximal segment through point 0; list them by first index
        table = table[np.argsort(table[:, 0], kind="stable")]
    return table


def maximal_segments(points: npt.ArrayLike, *, closed: bool = False, adjacency: int = 4) -> list[Segment]:
    """All maximal segments of a chain (the tangential cover; DGtal ``SaturatedSegmentation``).

    A maximal segment is a window of consecutive points that is a DSS and that stays a DSS neither with
    the point before it nor with the point after it added.

    Parameters
    ----------
    points : array_like of int, shape (n, 2)
        The chain.
    closed : bool
        Read the chain as cyclic (m points): windows may wrap around and hold at most m points; they are
        reported with ``0 <= first < m`` and ``first <= last <= first + m - 1`` (point k is
        ``points[k mod m]``).
    adjacency : {4, 8}
        Standard (4) or naive (8) segments.

    Returns
    -------
    list of Segment
        Ordered by ``first`` (both ``first`` and ``last`` strictly increase); together they cover the chain
        and consecutive ones overlap or touch.
    """
    return _segments_of(maximal_table(points, closed=closed, adjacency=adjacency))


def standard_dss_reach_table(points: npt.ArrayLike, closed: bool = False) -> tuple[IntArray, IntArray]:
    """For each start index, how far a standard DSS reaches, and that DSS's characteristics.

    Parameters
    ----------
    points : array_like of int, shape (m, 2)
        A 4-connected chain (for example the pixel centres of a 4-connected border path).
    closed : bool
        Cyclic chain: windows wrap around and hold at most m points.

    Returns
    -------
    reach : ndarray of int64, shape (m,)
        ``reach[i]`` is the largest j such that points i … j form a standard DSS (j ≤ m − 1 on an open
        chain; i ≤ j ≤ i + m − 1 on a closed one, where point k is ``points[k mod m]``).
    params : ndarray of int64, shape (m, 4)
        (a, b, mu, omega) of that DSS (DGtal convention; its median line is
        a·x − b·y = mu + (omega − 1) / 2).
    """
    pts = _as_chain(points, closed, 4)
    t = K.reach_kernel(pts, closed, 4)
    return np.ascontiguousarray(t[:, 0]), np.ascontiguousarray(t[:, 1:])


def standard_dss_reach(points: npt.ArrayLike, closed: bool = False) -> IntArray:
    """Return ``reach`` of :func:`standard_dss_reach_table`: for each i, the largest j with i … j a DSS."""
    return standard_dss_reach_table(points, closed)[0]


def dss_of_window(
    points: npt.ArrayLike, i: int, j: int, adjacency: int = 4, *, closed: bool = False
) -> Segment:
    """Return the minimal DSS of the window of points i … j (both included).

    Parameters
    ----------
    points : array_like of int, shape (m, 2)
        The chain.
    i, j : int
        The window, ``i <= j``. On an open chain 0 <= i <= j < m. On a closed chain indices are taken mod m,
        so a window may wrap around (``j`` up to ``i + m - 1``); the returned indices are ``i`` and ``j``
        as given.
    adjacency : {4, 8}
        Standard (4) or naive (8).
    closed : bool
        Read the chain as cyclic.

    Raises
    ------
    ValueError
        If the window is out of range or is not a DSS.
    """
    pts = _as_chain(points, closed, adjacency)
    m = pts.shape[0]
    i, j = int(i), int(j)
    if j < i or (not closed and (i < 0 or j >= m)) or (closed and j - i >= m):
        raise ValueError(
            f"window [{i}, {j}] is not a window of a {'closed' if closed else 'open'} chain of {m}"
        )
    t = K.window_kernel(pts, i % m, i % m + (j - i), adjacency)
    if t.shape[0] == 0:
        raise ValueError(f"points {i} … {j} do not form a DSS")
    t[0, :2] = (i, j)
    return _segments_of(t)[0]
