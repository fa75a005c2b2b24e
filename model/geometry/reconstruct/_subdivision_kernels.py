"""Numba kernels for :mod:`mrm.geometry.reconstruct.subdivision`: the polylines of many 1-cells in one call.

:func:`polylines_kernel` is :func:`mrm.geometry.reconstruct._cell_polylines._polyline` (staircase, greedy
construction, merge pass, closing of a ring, exact verification) written for int64, applied to every chain of
a batch. The Python functions stay the definition and the tests compare the two chain by chain.

Exactness: every product and shift goes through :func:`_mul` / :func:`_shl`, which refuse (set the overflow
flag ``st[0]``) any result above ``st[1]`` in absolute value (2⁶⁰ in use, so sums of a few such terms stay
inside int64). A chain whose computation would leave that range gets status :data:`FALLBACK` and is done by
the Python functions on Python integers, which give the same answer; so the kernel either returns exactly what
the Python code returns or nothing. Floor division and ``abs`` follow Python's semantics in numba.
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import njit
from mrm.geometry.dss._kernels import reach_kernel

#: Status of a chain: its polyline, its staircase (the construction gave nothing better), or left to the
#: Python functions (int64 would overflow, or a case that "cannot happen" was met).
POLYLINE, STAIRCASE, FALLBACK = 0, 1, 2

LIMIT = 1 << 60
_MAX_SNAP_BITS = 60
_CANDIDATE_BUDGET = 400
_SMALL = 1 << 30


@njit(cache=True)
def _mul(a: int, b: int, st: np.ndarray) -> int:
    """a·b, or 0 with the overflow flag set when |a·b| would exceed st[1]."""
    if a == 0 or b == 0:
        return 0
    aa = -a if a < 0 else a
    bb = -b if b < 0 else b
    if aa < _SMALL and bb < _SMALL:
        return a * b
    if aa > st[1] // bb:
        st[0] = 1
        return 0
    return a * b


@njit(cache=True)
def _shl(a: int, e: int, st: np.ndarray) -> int:
    """a·2^e (e ≥ 0) under the same limit."""
    if a == 0:
        return 0
    if e >= 62:
        st[0] = 1
        return 0
    return _mul(a, 1 << e, st)


@njit(cache=True)
def _cross(ax: int, ay: int, bx: int, by: int, st: np.ndarray) -> int:
    return _mul(ax, by, st) - _mul(ay, bx, st)


@njit(cache=True)
def _cone_holds(lox: int, loy: int, hix: int, hiy: int, dx: int, dy: int, st: np.ndarray) -> bool:
    return _cross(lox, loy, dx, dy, st) > 0 and _cross(dx, dy, hix, hiy, st) > 0


@njit(cache=True)
def _in_piece(
    loc: np.ndarray, n: int, closed: bool, vx: int, vy: int, e: int, k: int, st: np.ndarray
) -> bool:
    kk = k % n if closed else k
    h = _shl(1, e, st)
    dx = vx - _shl(loc[kk, 0], e + 1, st)
    dy = vy - _shl(loc[kk, 1], e + 1, st)
    return abs(dx) < h and abs(dy) < h


@njit(cache=True)
def _gate_from(
    gl: np.ndarray, gr: np.ndarray, n: int, k: int, e: int, px: int, py: int, st: np.ndarray
) -> tuple[int, int, int, int]:
    """The left and right centres of gate k (cyclic) at scale 2^e, minus the point (px, py)."""
    i = (k - 1) % n
    return (
        _shl(gl[i, 0], e, st) - px,
        _shl(gl[i, 1], e, st) - py,
        _shl(gr[i, 0], e, st) - px,
        _shl(gr[i, 1], e, st) - py,
    )


@njit(cache=True)
def _edge_ok(
    gl: np.ndarray,
    gr: np.ndarray,
    n: int,
    ax0: int,
    ay0: int,
    ae: int,
    ia: int,
    bx0: int,
    by0: int,
    be: int,
    ib: int,
    st: np.ndarray,
) -> bool:
    e = max(ae, be)
    ax, ay = _shl(ax0, e - ae, st), _shl(ay0, e - ae, st)
    dx, dy = _shl(bx0, e - be, st) - ax, _shl(by0, e - be, st) - ay
    for k in range(ia + 1, ib + 1):
        lx_, ly_, rx_, ry_ = _gate_from(gl, gr, n, k, e, ax, ay, st)
        if (
            _cross(rx_, ry_, lx_, ly_, st) <= 0
            or _cross(dx, dy, lx_, ly_, st) <= 0
            or _cross(dx, dy, rx_, ry_, st) >= 0
        ):
            return False
        if st[0]:
            return False
    return True


@njit(cache=True)
def _cones(
    gl: np.ndarray,
    gr: np.ndarray,
    n: int,
    px: int,
    py: int,
    e: int,
    ip: int,
    last: int,
    cl: np.ndarray,
    st: np.ndarray,
) -> int:
    """Fill cl[j] = (lox, loy, hix, hiy), the cone through gates ip+1 … ip+1+j; return how many."""
    cnt = 0
    lox = loy = hix = hiy = 0
    for k in range(ip + 1, last + 1):
        lx_, ly_, rx_, ry_ = _gate_from(gl, gr, n, k, e, px, py, st)
        if _cross(rx_, ry_, lx_, ly_, st) <= 0:
            break
        if cnt == 0:
            lox, loy, hix, hiy = rx_, ry_, lx_, ly_
        else:
            if _cross(lox, loy, rx_, ry_, st) > 0:
                nlx, nly = rx_, ry_
            else:
                nlx, nly = lox, loy
            if _cross(lx_, ly_, hix, hiy, st) > 0:
                nhx, nhy = lx_, ly_
            else:
                nhx, nhy = hix, hiy
            if _cross(nlx, nly, nhx, nhy, st) <= 0:
                break
            mx, my = nlx + nhx, nly + nhy
            if not (
                _cross(lox, loy, mx, my, st) > 0
                and _cross(mx, my, hix, hiy, st) > 0
                and _cross(rx_, ry_, mx, my, st) > 0
                and _cross(mx, my, lx_, ly_, st) > 0
            ):
                break
            lox, loy, hix, hiy = nlx, nly, nhx, nhy
        if st[0]:
            return cnt
        cl[cnt, 0], cl[cnt, 1], cl[cnt, 2], cl[cnt, 3] = lox, loy, hix, hiy
        cnt += 1
    return cnt


@njit(cache=True)
def _on_line(a: int, b: int, c: int, cons: np.ndarray, m: int, out: np.ndarray, st: np.ndarray) -> bool:
    """_cell_polylines._on_line with the constraints cons[:m]; the point goes to out = (X·D, Y·D, D)."""
    has_lo = False
    has_hi = False
    lo0 = lo1 = hi0 = hi1 = 0
    n2 = _mul(a, a, st) + _mul(b, b, st)
    for t in range(m):
        ax, ay, a0 = cons[t, 0], cons[t, 1], cons[t, 2]
        g = _mul(ax, b, st) + _mul(ay, a, st)
        if g == 0:
            if a != 0:
                f = _mul(_mul(ax, c, st) + _mul(a0, a, st), a, st)
            else:
                f = _mul(-_mul(ay, c, st) + _mul(a0, b, st), b, st)
            if f <= 0:
                return False
            continue
        num = _mul(c, _mul(b, ay, st) - _mul(a, ax, st), st) - _mul(a0, n2, st)
        den = g
        if den > 0:
            if not has_lo or _mul(num, lo1, st) > _mul(lo0, den, st):
                lo0, lo1, has_lo = num, den, True
        else:
            num, den = -num, -den
            if not has_hi or _mul(num, hi1, st) < _mul(hi0, den, st):
                hi0, hi1, has_hi = num, den, True
        if st[0]:
            return False
    if not has_lo or not has_hi or _mul(lo0, hi1, st) >= _mul(hi0, lo1, st):
        return False
    sn = _mul(lo0, hi1, st) + _mul(hi0, lo1, st)
    sd = _mul(2 * lo1, hi1, st)
    d = _mul(sd, n2, st)
    out[0] = _mul(_mul(a, c, st), sd, st) + _mul(b, sn, st)
    out[1] = _mul(a, sn, st) - _mul(_mul(b, c, st), sd, st)
    out[2] = d
    return not st[0]


@njit(cache=True)
def _square(loc: np.ndarray, q: int, e: int, cons: np.ndarray, st: np.ndarray) -> None:
    """The open piece of pointel q as constraints cons[0:4] (_cell_polylines._square)."""
    vx, vy, h = _shl(loc[q, 0], e + 1, st), _shl(loc[q, 1], e + 1, st), _shl(1, e, st)
    cons[0, 0], cons[0, 1], cons[0, 2] = 1, 0, h - vx
    cons[1, 0], cons[1, 1], cons[1, 2] = -1, 0, vx + h
    cons[2, 0], cons[2, 1], cons[2, 2] = 0, 1, h - vy
    cons[3, 0], cons[3, 1], cons[3, 2] = 0, -1, vy + h


@njit(cache=True)
def _snapped(
    loc: np.ndarray,
    n: int,
    closed: bool,
    xn: int,
    yn: int,
    d: int,
    q: int,
    px: int,
    py: int,
    e: int,
    cone: np.ndarray,
    has_strip: bool,
    sa: int,
    sb: int,
    sc: int,
    out: np.ndarray,
    st: np.ndarray,
) -> bool:
    """_cell_polylines._snapped; the vertex (x, y, e) in lowest terms goes to out."""
    den = _shl(2 * d, e, st)
    de = _shl(d, e, st)
    for k in range(_MAX_SNAP_BITS + 1):
        s = 1 << k
        yx = (_mul(2 * xn, s, st) + de) // den
        yy = (_mul(2 * yn, s, st) + de) // den
        if st[0]:
            return False
        if not _in_piece(loc, n, closed, yx, yy, k, q, st):
            continue
        mm = max(k, e)
        dx = _shl(yx, mm - k, st) - _shl(px, mm - e, st)
        dy = _shl(yy, mm - k, st) - _shl(py, mm - e, st)
        if not _cone_holds(cone[0], cone[1], cone[2], cone[3], dx, dy, st):
            continue
        if has_strip:
            r = _mul(sa, yx, st) - _mul(sb, yy, st) - _mul(sc, s, st)
            if abs(r) >= s:
                continue
        if st[0]:
            return False
        while k > 0 and not (yx & 1) and not (yy & 1):
            yx, yy, k = yx >> 1, yy >> 1, k - 1
        out[0], out[1], out[2] = yx, yy, k
        return True
    return False


@njit(cache=True)
def _greedy(
    loc: np.ndarray,
    n: int,
    closed: bool,
    gl: np.ndarray,
    gr: np.ndarray,
    table: np.ndarray,
    vx: np.ndarray,
    vk: np.ndarray,
    st: np.ndarray,
) -> int:
    """_cell_polylines._greedy: vertices (x, y, e) in vx and pieces in vk; their number, 0 when stuck."""
    cl = np.empty((n + 1, 4), dtype=np.int64)
    cons = np.empty((6, 3), dtype=np.int64)
    pt = np.empty(3, dtype=np.int64)
    y = np.empty(3, dtype=np.int64)
    endx, endy = 2 * loc[n, 0], 2 * loc[n, 1]
    px, py, pe, ip = 2 * loc[0, 0], 2 * loc[0, 1], 0, 0
    vx[0, 0], vx[0, 1], vx[0, 2], vk[0] = px, py, pe, 0
    cnt = 1
    while True:
        nc = _cones(gl, gr, n, px, py, pe, ip, n, cl, st)
        if st[0] or nc == 0:
            return 0
        far = ip + nc
        if far >= n:
            c = cl[n - ip - 1]
            if _cone_holds(c[0], c[1], c[2], c[3], _shl(endx, pe, st) - px, _shl(endy, pe, st) - py, st):
                if st[0]:
                    return 0
                vx[cnt, 0], vx[cnt, 1], vx[cnt, 2], vk[cnt] = endx, endy, 0, n
                return cnt + 1
        found = False
        bq = 0
        sa = sb = sc = 0
        budget = _CANDIDATE_BUDGET
        top = min(far, n - 1)
        for i2 in range(top, -1, -1):
            if table[i2, 0] <= ip + 1 or budget <= 0:
                break
            a, b, mu, om = table[i2, 1], table[i2, 2], table[i2, 3], table[i2, 4]
            for q in range(max(i2, ip + 1), min(top, table[i2, 0]) + 1):
                budget -= 1
                if a == 0 and b == 0:
                    continue
                _square(loc, q, pe, cons, st)
                c = cl[q - ip - 1]
                # _in_cone: cross(lo, X − p) > 0 and cross(X − p, hi) > 0
                cons[4, 0], cons[4, 1], cons[4, 2] = -c[1], c[0], _mul(c[1], px, st) - _mul(c[0], py, st)
                cons[5, 0], cons[5, 1], cons[5, 2] = c[3], -c[2], _mul(py, c[2], st) - _mul(px, c[3], st)
                if _on_line(a, b, _shl(2 * mu + om - 1, pe, st), cons, 6, pt, st):
                    found = True
                    bq = q
                    sa, sb, sc = a, b, 2 * mu + om - 1
                    break
                if st[0]:
                    return 0
            if found:
                break
        got = False
        if found:
            got = _snapped(
                loc, n, closed, pt[0], pt[1], pt[2], bq, px, py, pe, cl[bq - ip - 1], True, sa, sb, sc, y, st
            )
            q = bq
            if st[0]:
                return 0
        if not got:
            q = top
            if q < ip + 1:
                return 0
            c = cl[q - ip - 1]
            dx, dy = c[0] + c[2], c[1] + c[3]
            _square(loc, q, pe, cons, st)
            if not _on_line(dy, dx, _mul(dy, px, st) - _mul(dx, py, st), cons, 4, pt, st):
                st[0] = 2  # "the central ray misses its piece": the Python code raises
                return 0
            got = _snapped(loc, n, closed, pt[0], pt[1], pt[2], q, px, py, pe, c, False, 0, 0, 0, y, st)
            if st[0] or not got:
                return 0
        vx[cnt, 0], vx[cnt, 1], vx[cnt, 2], vk[cnt] = y[0], y[1], y[2], q
        cnt += 1
        px, py, pe, ip = y[0], y[1], y[2], q


@njit(cache=True)
def _chain_polyline(loc: np.ndarray, closed: bool, out: np.ndarray, st: np.ndarray) -> tuple[int, int]:
    """_cell_polylines._polyline for one chain (pointels relative to the first): (status, vertex count)."""
    n = loc.shape[0] - 1
    # the staircase
    ns = 0
    for k in range(n + 1):
        if not closed and (k == 0 or k == n):
            out[ns, 0], out[ns, 1], out[ns, 2] = 2 * loc[k, 0], 2 * loc[k, 1], 0
            ns += 1
            continue
        if k == n:
            continue
        km = k - 1 if k > 0 else n - 1
        if (loc[k, 0] - loc[km, 0] != loc[k + 1, 0] - loc[k, 0]) or (
            loc[k, 1] - loc[km, 1] != loc[k + 1, 1] - loc[k, 1]
        ):
            out[ns, 0], out[ns, 1], out[ns, 2] = 2 * loc[k, 0], 2 * loc[k, 1], 0
            ns += 1
    if n <= 2 or ns <= 2:
        return STAIRCASE, ns
    gl = np.empty((n, 2), dtype=np.int64)
    gr = np.empty((n, 2), dtype=np.int64)
    for k in range(n):
        dx, dy = loc[k + 1, 0] - loc[k, 0], loc[k + 1, 1] - loc[k, 1]
        mx, my = 2 * loc[k, 0] + dx, 2 * loc[k, 1] + dy
        gl[k, 0], gl[k, 1] = mx - dy, my + dx
        gr[k, 0], gr[k, 1] = mx + dy, my - dx
    table = reach_kernel(loc, False, 4)
    vx = np.empty((n + 2, 3), dtype=np.int64)
    vk = np.empty(n + 2, dtype=np.int64)
    cnt = _greedy(loc, n, closed, gl, gr, table, vx, vk, st)
    if st[0]:
        return FALLBACK, 0
    if cnt == 0:
        return STAIRCASE, ns
    # the merge pass
    keep = np.empty(cnt, dtype=np.int64)
    keep[0] = 0
    m = 1
    for k in range(1, cnt - 1):
        a = keep[m - 1]
        b = k + 1
        if not _edge_ok(
            gl, gr, n, vx[a, 0], vx[a, 1], vx[a, 2], vk[a], vx[b, 0], vx[b, 1], vx[b, 2], vk[b], st
        ):
            keep[m] = k
            m += 1
        if st[0]:
            return FALLBACK, 0
    keep[m] = cnt - 1
    m += 1
    first = 0
    if closed:
        m -= 1  # drop the closing repeat of the start
        if m > 3:
            a, b = keep[m - 1], keep[1]
            if _edge_ok(
                gl, gr, n, vx[a, 0], vx[a, 1], vx[a, 2], vk[a], vx[b, 0], vx[b, 1], vx[b, 2], vk[b] + n, st
            ):
                first = 1
            if st[0]:
                return FALLBACK, 0
    nv = m - first
    if nv >= ns:
        return STAIRCASE, ns
    # exact verification (_cell_polylines._verify_chain), the pieces being the construction's own
    ok = True
    if closed:
        ok = nv >= 3
    else:
        a, b = keep[first], keep[m - 1]
        ok = (
            nv >= 2
            and vx[a, 0] == 0
            and vx[a, 1] == 0
            and vx[a, 2] == 0
            and vx[b, 0] == 2 * loc[n, 0]
            and vx[b, 1] == 2 * loc[n, 1]
            and vx[b, 2] == 0
        )
    lo_k = 0 if closed else 1
    hi_k = n - 1
    prev = -1
    for t in range(first, m):
        j = keep[t]
        k = vk[j]
        inner = t != first and t != m - 1
        if closed or inner:
            if (
                k < lo_k
                or k > hi_k
                or k <= prev
                or not _in_piece(loc, n, closed, vx[j, 0], vx[j, 1], vx[j, 2], k, st)
            ):
                ok = False
        elif k <= prev:
            ok = False
        prev = k
        if t > first:
            i = keep[t - 1]
            if not _edge_ok(
                gl, gr, n, vx[i, 0], vx[i, 1], vx[i, 2], vk[i], vx[j, 0], vx[j, 1], vx[j, 2], k, st
            ):
                ok = False
        if not ok:
            break
    if ok and closed:
        i, j = keep[m - 1], keep[first]
        if not _edge_ok(
            gl, gr, n, vx[i, 0], vx[i, 1], vx[i, 2], vk[i], vx[j, 0], vx[j, 1], vx[j, 2], vk[j] + n, st
        ):
            ok = False
    if st[0]:
        return FALLBACK, 0
    if not ok:
        return STAIRCASE, ns
    for t in range(nv):
        j = keep[first + t]
        out[t, 0], out[t, 1], out[t, 2] = vx[j, 0], vx[j, 1], vx[j, 2]
    return POLYLINE, nv


@njit(cache=True)
def polylines_kernel(
    loc: np.ndarray, off: np.ndarray, closed: np.ndarray, limit: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The polylines of a batch of chains.

    Parameters
    ----------
    loc : (N, 2) int64
        The pointels of every chain, each relative to its own first pointel, chain i in rows
        off[i] … off[i+1] − 1 (a ring with its closing repeat).
    off : (m + 1,) int64
    closed : (m,) bool
    limit : int
        Largest |value| of a product (:data:`LIMIT`; smaller in tests, to exercise the fallback).

    Returns
    -------
    status : (m,) int8
        :data:`POLYLINE`, :data:`STAIRCASE` or :data:`FALLBACK`.
    count : (m,) int64
        The number of vertices of chain i, in rows off[i] … off[i] + count[i] − 1 of ``verts``.
    verts : (N, 3) int64
        Vertices (x, y, e): the dyadic point (x / 2^e, y / 2^e) in doubled coordinates relative to the
        chain's first pointel (the ``Vertex`` of :mod:`mrm.geometry.reconstruct._cell_polylines`).
    """
    m = closed.shape[0]
    status = np.empty(m, dtype=np.int8)
    count = np.zeros(m, dtype=np.int64)
    verts = np.zeros((loc.shape[0], 3), dtype=np.int64)
    st = np.zeros(2, dtype=np.int64)
    for i in range(m):
        st[0] = 0
        st[1] = limit
        s, c = _chain_polyline(loc[off[i] : off[i + 1]], closed[i], verts[off[i] : off[i + 1]], st)
        status[i] = s
        count[i] = c
    return status, count, verts


@njit(cache=True)
def label_boxes(lab: np.ndarray, vmax: int) -> np.ndarray:
    """For every label 0 … vmax: [pixel count, first row, last row, first column, last column] in one pass."""
    out = np.zeros((vmax + 1, 5), dtype=np.int64)
    out[:, 1] = lab.shape[0]
    out[:, 3] = lab.shape[1]
    out[:, 2] = -1
    out[:, 4] = -1
    for r in range(lab.shape[0]):
        for c in range(lab.shape[1]):
            v = lab[r, c]
            out[v, 0] += 1
            if r < out[v, 1]:
                out[v, 1] = r
            out[v, 2] = r
            if c < out[v, 3]:
                out[v, 3] = c
            if c > out[v, 4]:
                out[v, 4] = c
    return out
