"""Numba kernels for arithmetic DSS recognition and the segmentations built on it.

These are the hot paths behind :mod:`mrm.geometry.dss.segmentation`; :mod:`mrm.geometry.dss` holds the
readable pure-Python recognizer they mirror step for step (and that the tests compare them with). The
algorithm is Debled-Rennesson & Reveillès' incremental recognition with Lachaud, de Vieilleville &
Feschet's O(1) retraction, in the DGtal ``ArithmeticalDSS`` convention (docs/algorithms.md §2.1-2.2):
remainder r = a·x − b·y, direction (b, a), lo = μ ≤ r ≤ hi = μ + ω − 1.

A DSS state is one int64 array of ``STATE_SIZE`` entries (layout below), so that kernels can pass it
around cheaply; ``FI`` / ``LI`` are the indices in the chain of its back (first) and front (last) points.
Indices are *unwrapped*: on a closed chain of m points, index k means point ``k mod m``.

Coordinates are int64; remainders are products of a coordinate and a slope component, so coordinates up
to about 2³⁰ and segments up to 2³⁰ points are safe from overflow.
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit

A, B, LO, HI = 0, 1, 2, 3
FX, FY, LX, LY = 4, 5, 6, 7
UFX, UFY, ULX, ULY = 8, 9, 10, 11
LFX, LFY, LLX, LLY = 12, 13, 14, 15
S1X, S1Y, S2X, S2Y = 16, 17, 18, 19
SHX, SHY = 20, 21
FI, LI = 22, 23
STATE_SIZE = 24

#: Columns of a segment table row: first, last, a, b, mu, omega, Uf, Ul, Lf, Ll (x, y each).
SEG_COLS = 14


@njit(cache=True, inline="always")
def _norm(dx: int, dy: int, adj: int) -> int:
    if adj == 4:
        return abs(dx) + abs(dy)
    return max(abs(dx), abs(dy))


@njit(cache=True, inline="always")
def _background_norm(dx: int, dy: int, adj: int) -> int:
    # The background of a 4-connected line is 8-connected and vice versa.
    if adj == 4:
        return max(abs(dx), abs(dy))
    return abs(dx) + abs(dy)


@njit(cache=True)
def steps_of(a: int, b: int, adj: int) -> tuple[int, int, int, int]:
    """The two elementary steps (s1, s2) of the DSLs of slope (a, b) (DGtal ``ArithmeticalDSLKernel``)."""
    if adj == 4:
        if b == 0:
            if a == 0:
                return 0, 0, 0, 0
            if a > 0:
                return 0, 1, 0, 0
            return 0, -1, 0, 0
        if b > 0:
            if a == 0:
                return 1, 0, 0, 0
            if a > 0:
                return 1, 0, 0, 1
            return 0, -1, 1, 0
        if a == 0:
            return -1, 0, 0, 0
        if a > 0:
            return 0, 1, -1, 0
        return -1, 0, 0, -1
    # adjacency 8: octants
    if b == 0:
        if a == 0:
            return 0, 0, 0, 0
        if a > 0:
            return 0, 1, 0, 0
        return 0, -1, 0, 0
    if b > 0:
        if a == 0:
            return 1, 0, 0, 0
        if a > 0:
            if b == a:
                return 1, 1, 0, 0
            if b > a:
                return 1, 0, 1, 1
            return 1, 1, 0, 1
        if b == -a:
            return 1, -1, 0, 0
        if b > -a:
            return 1, -1, 1, 0
        return 0, -1, 1, -1
    if a == 0:
        return -1, 0, 0, 0
    if a > 0:
        if -b == a:
            return -1, 1, 0, 0
        if -b > a:
            return -1, 1, -1, 0
        return 0, 1, -1, 1
    if b == a:
        return -1, -1, 0, 0
    if -b > -a:
        return -1, 0, -1, -1
    return -1, -1, 0, -1


@njit(cache=True)
def shift_of(a: int, b: int, adj: int) -> tuple[int, int]:
    """The shift vector (taking remainder r to r + ω) of the DSLs of slope (a, b)."""
    if adj == 4:
        if b == 0:
            if a == 0:
                return 0, 0
            if a > 0:
                return 1, 1
            return -1, -1
        if b > 0:
            if a >= 0:
                return 1, -1
            return -1, -1
        if a > 0:
            return 1, 1
        return -1, 1
    if b == 0:
        if a == 0:
            return 0, 0
        if a > 0:
            return 1, 0
        return -1, 0
    if b > 0:
        if a == 0:
            return 0, -1
        if a > 0:
            if b > a:
                return 0, -1
            return 1, 0
        if b >= -a:
            return 0, -1
        return -1, 0
    if a == 0:
        return 0, 1
    if a > 0:
        if -b >= a:
            return 0, 1
        return 1, 0
    if -b > -a:
        return 0, 1
    return -1, 0


@leaf_njit(cache=True)
def init_state(st: np.ndarray, x: int, y: int, idx: int) -> None:
    """Make ``st`` the one-point DSS {(x, y)} at chain index ``idx``."""
    for k in range(STATE_SIZE):
        st[k] = 0
    for k in range(FX, LLY + 1, 2):
        st[k] = x
        st[k + 1] = y
    st[FI] = idx
    st[LI] = idx


@leaf_njit(cache=True)
def _rem(st: np.ndarray, x: int, y: int) -> int:
    return int(st[A] * x - st[B] * y)


@leaf_njit(cache=True)
def is_extendable_front(st: np.ndarray, qx: int, qy: int, adj: int) -> int:
    """DGtal's case code for adding (qx, qy) at the front: 0 = rejected, 1-9 = how to update."""
    dx = qx - st[LX]
    dy = qy - st[LY]
    dev = _norm(dx, dy, adj)
    if dev == 0:
        return 9
    if dev > 1:
        return 0
    if st[S1X] == 0 and st[S1Y] == 0:
        return 1
    if st[S2X] == 0 and st[S2Y] == 0:
        if dx == st[S1X] and dy == st[S1Y]:
            return 2
        if _background_norm(dx - st[S1X], dy - st[S1Y], adj) == 1:
            r = _rem(st, qx, qy)
            if r == st[LO] - 1:
                return 3
            return 4
        return 0
    if (dx == st[S1X] and dy == st[S1Y]) or (dx == st[S2X] and dy == st[S2Y]):
        r = _rem(st, qx, qy)
        lo = st[LO]
        hi = st[HI]
        if r < lo - 1 or r > hi + 1:
            return 0
        if r == lo:
            return 5
        if r == hi:
            return 6
        if r == lo - 1:
            return 7
        if r == hi + 1:
            return 8
        return 9
    return 0


@leaf_njit(cache=True)
def _set_steps_shift(st: np.ndarray, adj: int) -> None:
    s1x, s1y, s2x, s2y = steps_of(st[A], st[B], adj)
    st[S1X] = s1x
    st[S1Y] = s1y
    st[S2X] = s2x
    st[S2Y] = s2y


@leaf_njit(cache=True)
def extend_front(st: np.ndarray, qx: int, qy: int, qi: int, adj: int) -> bool:
    """Add (qx, qy), chain index ``qi``, at the front if the result is still a DSS; return whether it was."""
    c = is_extendable_front(st, qx, qy, adj)
    if c == 0:
        return False
    apply_front(st, c, qx, qy, qi, adj)
    return True


@leaf_njit(cache=True)
def apply_front(st: np.ndarray, c: int, qx: int, qy: int, qi: int, adj: int) -> None:
    """Add (qx, qy) at the front given its non-zero case code ``c`` from :func:`is_extendable_front`."""
    # The frequent cases (the slope does not change) stay here, small enough to be inlined by LLVM;
    # the slope changes go to a separate function.
    if c == 5:
        st[ULX] = qx
        st[ULY] = qy
    elif c == 6:
        st[LLX] = qx
        st[LLY] = qy
    elif c == 2:
        st[ULX] = qx
        st[ULY] = qy
        st[LLX] = qx
        st[LLY] = qy
    elif c != 9:
        _apply_slope_change(st, c, qx, qy, adj)
    st[LX] = qx
    st[LY] = qy
    st[LI] = qi


@leaf_njit(cache=True)
def _apply_slope_change(st: np.ndarray, c: int, qx: int, qy: int, adj: int) -> None:
    # cases 1, 3, 4, 7, 8 of DGtal's extendFront (the front point L is updated by the caller)
    if c == 1:
        st[S1X] = qx - st[LX]
        st[S1Y] = qy - st[LY]
        st[A] = st[S1Y]
        st[B] = st[S1X]
        st[LO] = _rem(st, st[UFX], st[UFY])
        st[HI] = _rem(st, st[LFX], st[LFY])
        st[ULX] = qx
        st[ULY] = qy
        st[LLX] = qx
        st[LLY] = qy
        sx, sy = shift_of(st[A], st[B], adj)
        st[SHX] = sx
        st[SHY] = sy
    elif c == 3:
        st[A] = (st[ULY] - st[UFY]) + (qy - st[LY])
        st[B] = (st[ULX] - st[UFX]) + (qx - st[LX])
        st[LO] = _rem(st, st[UFX], st[UFY])
        st[HI] = _rem(st, st[LLX], st[LLY])
        st[ULX] = qx
        st[ULY] = qy
        st[LFX] = st[LLX]
        st[LFY] = st[LLY]
        _set_steps_shift(st, adj)
        st[SHX] = st[S1X] - st[S2X]
        st[SHY] = st[S1Y] - st[S2Y]
    elif c == 4:
        st[A] = (st[LLY] - st[LFY]) + (qy - st[LY])
        st[B] = (st[LLX] - st[LFX]) + (qx - st[LX])
        st[LO] = _rem(st, st[ULX], st[ULY])
        st[HI] = _rem(st, st[LFX], st[LFY])
        st[LLX] = qx
        st[LLY] = qy
        st[UFX] = st[ULX]
        st[UFY] = st[ULY]
        _set_steps_shift(st, adj)
        st[SHX] = st[S1X] - st[S2X]
        st[SHY] = st[S1Y] - st[S2Y]
    elif c == 7:
        st[A] = qy - st[UFY]
        st[B] = qx - st[UFX]
        st[LO] = _rem(st, st[UFX], st[UFY])
        st[HI] = _rem(st, st[LLX], st[LLY])
        st[ULX] = qx
        st[ULY] = qy
        st[LFX] = st[LLX]
        st[LFY] = st[LLY]
    elif c == 8:
        st[A] = qy - st[LFY]
        st[B] = qx - st[LFX]
        st[LO] = _rem(st, st[ULX], st[ULY])
        st[HI] = _rem(st, st[LFX], st[LFY])
        st[LLX] = qx
        st[LLY] = qy
        st[UFX] = st[ULX]
        st[UFY] = st[ULY]


@leaf_njit(cache=True)
def negate(st: np.ndarray) -> None:
    """Reverse the orientation of the DSS in place (DGtal ``negate``): back and front swap."""
    a = st[A]
    st[A] = -a
    st[B] = -st[B]
    lo = st[LO]
    st[LO] = -st[HI]
    st[HI] = -lo
    for k0, k1 in ((FX, LX), (UFX, LLX), (ULX, LFX)):
        tx = st[k0]
        ty = st[k0 + 1]
        st[k0] = st[k1]
        st[k0 + 1] = st[k1 + 1]
        st[k1] = tx
        st[k1 + 1] = ty
    for k in range(S1X, SHY + 1):
        st[k] = -st[k]
    t = st[FI]
    st[FI] = st[LI]
    st[LI] = t


@leaf_njit(cache=True)
def extend_back(st: np.ndarray, qx: int, qy: int, qi: int, adj: int) -> bool:
    """Add (qx, qy), chain index ``qi``, at the back if the result is still a DSS."""
    negate(st)
    ok = extend_front(st, qx, qy, qi, adj)
    negate(st)
    return ok


@leaf_njit(cache=True)
def _retract_update_params(st: np.ndarray, ndx: int, ndy: int, adj: int) -> None:
    st[A] = ndy
    st[B] = ndx
    st[LO] = _rem(st, st[UFX], st[UFY])
    st[HI] = _rem(st, st[LFX], st[LFY])
    if st[UFX] == st[LFX] and st[UFY] == st[LFY]:
        _set_steps_shift(st, adj)
        sx, sy = shift_of(st[A], st[B], adj)
        st[SHX] = sx
        st[SHY] = sy


@leaf_njit(cache=True)
def _retract_upper_turn(st: np.ndarray, nx: int, ny: int, adj: int) -> None:
    # The back is the only upper leaning point Uf and the lower side has a single leaning point too:
    # the new slope is the vector from the Bezout point Uf + shift to Lf.
    bx = st[UFX] + st[SHX]
    by = st[UFY] + st[SHY]
    ndx = st[LFX] - bx
    ndy = st[LFY] - by
    nn = _norm(ndx, ndy, adj)
    k = _norm(st[ULX] - nx, st[ULY] - ny, adj) // nn
    st[UFX] = st[ULX] - ndx * k
    st[UFY] = st[ULY] - ndy * k
    k = _norm(st[LX] - st[LFX], st[LY] - st[LFY], adj) // nn
    st[LLX] = st[LFX] + ndx * k
    st[LLY] = st[LFY] + ndy * k
    _retract_update_params(st, ndx, ndy, adj)


@leaf_njit(cache=True)
def _retract_lower_turn(st: np.ndarray, nx: int, ny: int, adj: int) -> None:
    # The mirror case: the back is Lf, alone on its side; the slope turns to Uf − (Lf − shift).
    bx = st[LFX] - st[SHX]
    by = st[LFY] - st[SHY]
    ndx = st[UFX] - bx
    ndy = st[UFY] - by
    nn = _norm(ndx, ndy, adj)
    k = _norm(st[LLX] - nx, st[LLY] - ny, adj) // nn
    st[LFX] = st[LLX] - ndx * k
    st[LFY] = st[LLY] - ndy * k
    k = _norm(st[LX] - st[UFX], st[LY] - st[UFY], adj) // nn
    st[ULX] = st[UFX] + ndx * k
    st[ULY] = st[UFY] + ndy * k
    _retract_update_params(st, ndx, ndy, adj)


@leaf_njit(cache=True)
def retract_back(st: np.ndarray, nx: int, ny: int, ni: int, adj: int) -> bool:
    """Remove the back point; (nx, ny), chain index ``ni``, is the point that follows it in the DSS.

    Lachaud, de Vieilleville & Feschet (2007), Th. 5, as in DGtal ``retractBack``: if the removed point
    was the only leaning point on its side, the slope turns to the vector from the Bezout point to the
    opposite leaning point and the leaning points are recomputed; otherwise the first leaning point on
    the removal side moves one period along the direction.
    """
    if st[FX] == st[LX] and st[FY] == st[LY]:
        return False
    if nx == st[LX] and ny == st[LY]:
        li = st[LI]
        init_state(st, nx, ny, ni)
        st[LI] = li
        return True
    if st[FX] == st[UFX] and st[FY] == st[UFY]:
        if st[LFX] == st[LLX] and st[LFY] == st[LLY]:
            _retract_upper_turn(st, nx, ny, adj)
        else:
            st[UFX] += st[B]
            st[UFY] += st[A]
    if st[FX] == st[LFX] and st[FY] == st[LFY]:
        if st[UFX] == st[ULX] and st[UFY] == st[ULY]:
            _retract_lower_turn(st, nx, ny, adj)
        else:
            # the direction read here is the one left by the block above (DGtal does the same)
            st[LFX] += st[B]
            st[LFY] += st[A]
    st[FX] = nx
    st[FY] = ny
    st[FI] = ni
    return True


@njit(cache=True, inline="always")
def _wrap(k: int, m: int) -> int:
    # k mod m without a division: indices stay within a few periods of [0, m)
    while k >= m:
        k -= m
    while k < 0:
        k += m
    return k


@leaf_njit(cache=True)
def check_chain(pts: np.ndarray, closed: bool, adj: int) -> int:
    """Return the first index k whose step to the next point is not one elementary step, or −1."""
    n = pts.shape[0]
    last = n if closed and n > 1 else n - 1
    for k in range(last):
        k1 = k + 1 if k + 1 < n else 0
        if _norm(pts[k1, 0] - pts[k, 0], pts[k1, 1] - pts[k, 1], adj) != 1:
            return k
    return -1


@leaf_njit(cache=True)
def _write_segment(out: np.ndarray, k: int, st: np.ndarray) -> None:
    out[k, 0] = st[FI]
    out[k, 1] = st[LI]
    out[k, 2] = st[A]
    out[k, 3] = st[B]
    out[k, 4] = st[LO]
    out[k, 5] = st[HI] - st[LO] + 1
    for j in range(8):
        out[k, 6 + j] = st[UFX + j]


@njit(cache=True)
def greedy_kernel(pts: np.ndarray, m: int, last_index: int, adj: int) -> np.ndarray:
    """Greedy segmentation of the points 0 … ``last_index`` (index k is ``pts[k mod m]``).

    From point 0, extend the front while the points form a DSS; the next segment starts at the last point
    of the previous one (DGtal ``GreedySegmentation``, whose segments intersect when the chain is
    connected). Returns a (k, SEG_COLS) table.
    """
    out = np.empty((max(last_index, 1), SEG_COLS), dtype=np.int64)
    st = np.empty(STATE_SIZE, dtype=np.int64)
    k = 0
    s = 0
    while True:
        p = _wrap(s, m)
        init_state(st, pts[p, 0], pts[p, 1], s)
        e = s
        while e < last_index:
            q = _wrap(e + 1, m)
            if not extend_front(st, pts[q, 0], pts[q, 1], e + 1, adj):
                break
            e += 1
        _write_segment(out, k, st)
        k += 1
        if e >= last_index:
            break
        s = e
    return out[:k]


@leaf_njit(cache=True)
def _extend_front_max(st: np.ndarray, pts: np.ndarray, m: int, limit: int, adj: int) -> None:
    # Extend while the next point keeps a DSS, never beyond index ``limit``.
    e = st[LI]
    while e < limit:
        q = _wrap(e + 1, m)
        if not extend_front(st, pts[q, 0], pts[q, 1], e + 1, adj):
            break
        e += 1


@leaf_njit(cache=True)
def _retract_once(st: np.ndarray, pts: np.ndarray, m: int, adj: int) -> None:
    ni = st[FI] + 1
    q = _wrap(ni, m)
    if not retract_back(st, pts[q, 0], pts[q, 1], ni, adj):
        init_state(st, pts[q, 0], pts[q, 1], ni)


@njit(cache=True)
def maximal_kernel(pts: np.ndarray, closed: bool, adj: int) -> np.ndarray:
    """All maximal segments (the tangential cover), in the order of the sweep.

    Open chain of n points: windows [i, j] ⊂ [0, n−1], ordered by i. Closed chain of m points: cyclic
    windows of at most m points, reported with 0 ≤ first < m and first ≤ last ≤ first + m − 1 (indices
    taken mod m), starting with the one through point 0 found first. Extend / retract as in Lachaud,
    de Vieilleville & Feschet (2007): O(n) in total.
    """
    n = pts.shape[0]
    m = n
    out = np.empty((max(n, 1), SEG_COLS), dtype=np.int64)
    st = np.empty(STATE_SIZE, dtype=np.int64)
    init_state(st, pts[0, 0], pts[0, 1], 0)
    _extend_front_max(st, pts, m, m - 1, adj)
    i0 = 0
    if closed:
        # extend backwards from point 0 too (a window holds at most m points): a maximal segment
        while st[LI] - st[FI] < m - 1:
            pi = st[FI] - 1
            q = _wrap(pi, m)
            if not extend_back(st, pts[q, 0], pts[q, 1], pi, adj):
                break
        if st[FI] < 0:
            st[FI] += m
            st[LI] += m
        i0 = st[FI]
    k = 0
    _write_segment(out, k, st)
    k += 1
    max_len = m if closed else n
    # The sweep (written out in one loop: calls per segment would cost as much as the work): from a
    # segment that cannot grow at the front, retract the back until the next point can be added (keeping
    # at most max_len points), add it, extend as far as possible: that is the next maximal segment.
    while closed or st[LI] < n - 1:
        e = st[LI]
        q = _wrap(e + 1, m)
        qx = pts[q, 0]
        qy = pts[q, 1]
        c = 0
        while True:
            if e + 1 - st[FI] < max_len:
                c = is_extendable_front(st, qx, qy, adj)
                if c != 0:
                    break
            _retract_once(st, pts, m, adj)
        if closed and st[FI] >= i0 + m:
            break
        apply_front(st, c, qx, qy, e + 1, adj)
        limit = st[FI] + m - 1 if closed else m - 1
        e += 1
        while e < limit:
            q = _wrap(e + 1, m)
            if not extend_front(st, pts[q, 0], pts[q, 1], e + 1, adj):
                break
            e += 1
        _write_segment(out, k, st)
        if out[k, 0] >= m:
            out[k, 0] -= m
            out[k, 1] -= m
        k += 1
    return out[:k]


@njit(cache=True)
def reach_kernel(pts: np.ndarray, closed: bool, adj: int) -> np.ndarray:
    """For each start i, the largest j such that points i … j form a DSS, with its (a, b, mu, omega).

    Returns an (m, 5) table [j, a, b, mu, omega]. On a closed chain j ≤ i + m − 1 (indices mod m).
    A sliding window: retract the back, extend the front; O(m) in total.
    """
    m = pts.shape[0]
    out = np.empty((m, 5), dtype=np.int64)
    st = np.empty(STATE_SIZE, dtype=np.int64)
    init_state(st, pts[0, 0], pts[0, 1], 0)
    for i in range(m):
        if i > 0:
            if st[LI] < i:
                init_state(st, pts[i, 0], pts[i, 1], i)
            else:
                _retract_once(st, pts, m, adj)
        limit = i + m - 1 if closed else m - 1
        # the extension loop is written out here: a call per start costs as much as the loop itself
        e = st[LI]
        while e < limit:
            q = _wrap(e + 1, m)
            if not extend_front(st, pts[q, 0], pts[q, 1], e + 1, adj):
                break
            e += 1
        out[i, 0] = st[LI]
        out[i, 1] = st[A]
        out[i, 2] = st[B]
        out[i, 3] = st[LO]
        out[i, 4] = st[HI] - st[LO] + 1
    return out


@njit(cache=True)
def window_kernel(pts: np.ndarray, i: int, j: int, adj: int) -> np.ndarray:
    """Recognize the window i … j, 0 ≤ i < m, j < i + m (indices mod m): its segment row or an empty table."""
    m = pts.shape[0]
    out = np.empty((1, SEG_COLS), dtype=np.int64)
    st = np.empty(STATE_SIZE, dtype=np.int64)
    init_state(st, pts[i, 0], pts[i, 1], i)
    for k in range(i + 1, j + 1):
        q = _wrap(k, m)
        if not extend_front(st, pts[q, 0], pts[q, 1], k, adj):
            return out[:0]
    _write_segment(out, 0, st)
    return out


@njit(cache=True)
def segment_chains_kernel(
    pts: np.ndarray, offsets: np.ndarray, maximal: bool, wrap: bool, adj: int
) -> tuple[np.ndarray, np.ndarray]:
    """Segment many closed chains at once: chain c is ``pts[offsets[c]:offsets[c + 1]]`` (m ≥ 1, cyclic).

    Greedy (``maximal`` False; ``wrap``: the last segment ends back on point m) or maximal segments (sorted by
    first index). Returns the concatenated (k, SEG_COLS) table, indices local to each chain, and the (C + 1,)
    row offsets of each chain's segments.
    """
    nch = offsets.shape[0] - 1
    total = offsets[nch] - offsets[0]
    out = np.empty((total + nch, SEG_COLS), dtype=np.int64)
    ptr = np.empty(nch + 1, dtype=np.int64)
    ptr[0] = 0
    k = 0
    for c in range(nch):
        p = pts[offsets[c] : offsets[c + 1]].copy()  # C layout: one compiled variant of the kernels
        m = p.shape[0]
        if m == 1:
            t = window_kernel(p, 0, 0, adj)
        elif maximal:
            t = maximal_kernel(p, True, adj)
            t = t[np.argsort(t[:, 0], kind="mergesort")]
        else:
            t = greedy_kernel(p, m, m if wrap else m - 1, adj)
        for r in range(t.shape[0]):
            for q in range(SEG_COLS):
                out[k, q] = t[r, q]
            k += 1
        ptr[c + 1] = k
    return out[:k], ptr
