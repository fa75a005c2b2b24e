"""Phase 3 of R: the V4 greedy choice of lines and vertices around each ring."""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit
from mrm.geometry.reconstruct._base import _BIG, _EPS, SRC_LINES, SRC_PATCH
from mrm.geometry.reconstruct._reach import dss_reach, general_reach
from mrm.geometry.reconstruct._sliding import sliding_reach

# ============================================================================================ V4 greedy

#: Windows (gates) per start above which a ring's preimages are computed in one sliding pass.
_SLIDE_RATIO = 14


@njit(cache=True)
def ring_reach(
    e0: int,
    e1: int,
    ec: np.ndarray,
    er: np.ndarray,
    cnt: np.ndarray,
    full: bool,
    pel: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    reach: np.ndarray,
    lines: np.ndarray,
) -> None:  # pragma: no cover
    """Reach table and central lines of a ring's pieces.

    Windows of full squares (pixels under the cover models, dual squares of pointels under gauss) use the
    O(n) standard DSS reach (stabbing full gates in order is exactly being a standard DSS); windows that
    meet a split square use the exact dual-polygon preimage (sub-gates only restrict, so the DSS window
    bounds it): one window at a time (:func:`general_reach`, the sum of the windows' lengths), or, where
    the windows are long (one-pixel-wide lines, where that sum is quadratic), all in one sliding pass
    (:func:`sliding_reach`, linear, dearer per window). Both give the same reaches and lines.
    """
    n = gdir.size
    if full:
        dss_reach(e0, ec, er, n, reach, lines)
        return
    todo = np.ones(n, np.bool_)
    ne = e1 - e0
    rd = np.empty(ne, np.int64)
    ld = np.empty((ne, 4), np.float64)
    dss_reach(e0, ec, er, ne, rd, ld)
    # split elements, prefix counts over two laps
    pre = np.zeros(2 * ne + 1, np.int32)  # counts < 2 × linels (int32, INT32_LINELS)
    for k in range(2 * ne):
        kk = k % ne
        pre[k + 1] = pre[k] + (1 if cnt[e0 + kk] >= 2 else 0)
    work = 0  # what general_reach would cost (window lengths) …
    starts = 0  # … and the starts both compute
    for i in range(n):
        k = pel[i]
        if pre[k + rd[k] + 1] - pre[k] == 0:
            todo[i] = False
            reach[i] = rd[k]
            for u in range(4):
                lines[i, u] = ld[k, u]
        else:
            work += rd[k]
            starts += 1
    # measured break-even: windows of about 17 gates on average when both passes counted references
    # (camera's largest ring, at 38, took 4.6 ms one way against 10.8 the other); without the counting
    # (leaf_njit) the sliding pass gained more, and text's largest ring (about 17) is 1 ms faster sliding
    if work > _SLIDE_RATIO * starts and sliding_reach(gp, gq, gdir, todo, reach, lines):
        return
    general_reach(gp, gq, gdir, todo, reach, lines)


@leaf_njit(cache=True)
def _gate_param(line: np.ndarray, gp: np.ndarray, gq: np.ndarray, k: int) -> float:  # pragma: no cover
    # Parameter (Q-units along the unit direction) where the line meets the gate's supporting line.
    if gp[k, 0] == gq[k, 0]:
        if line[2] == 0.0:
            return _BIG
        return float((gp[k, 0] - line[0]) / line[2])
    if line[3] == 0.0:
        return _BIG
    return float((gp[k, 1] - line[1]) / line[3])


@leaf_njit(cache=True)
def _inside_rect(rect: np.ndarray, k: int, x: float, y: float, eps: float) -> bool:  # pragma: no cover
    return bool(rect[k, 0] + eps < x < rect[k, 1] - eps and rect[k, 2] + eps < y < rect[k, 3] - eps)


@leaf_njit(cache=True)
def _locate(
    lines: np.ndarray,
    s: int,
    e: int,
    x: float,
    y: float,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    n: int,
) -> tuple[int, float, bool]:  # pragma: no cover
    # The piece t in [s, e] (unwrapped) that the point (x, y) of line s lies in, its parameter on line s,
    # and whether it is safely inside (away from the gates by the construction margin).
    ln = lines[s % n]
    lam = (x - ln[0]) * ln[2] + (y - ln[1]) * ln[3]
    lo = s + 1
    hi = e + 1  # first k in [s+1, e] with param >= lam; e+1 if none
    while lo < hi:
        mid = (lo + hi) // 2
        if _gate_param(ln, gp, gq, mid % n) >= lam:
            hi = mid
        else:
            lo = mid + 1
    t = lo - 1
    ok = True
    if t > s and lam - _gate_param(ln, gp, gq, t % n) <= _EPS:
        ok = False
    if t < e and _gate_param(ln, gp, gq, (t + 1) % n) - lam <= _EPS:
        ok = False
    if ok and not _inside_rect(rect, t % n, x, y, _EPS):
        ok = False
    return t, lam, ok


@leaf_njit(cache=True)
def _meet(l1: np.ndarray, l2: np.ndarray) -> tuple[float, float, bool]:  # pragma: no cover
    den = l1[2] * l2[3] - l1[3] * l2[2]
    if abs(den) < 1e-12:
        return 0.0, 0.0, False
    wx = l2[0] - l1[0]
    wy = l2[1] - l1[1]
    lam = (wx * l2[3] - wy * l2[2]) / den
    return l1[0] + lam * l1[2], l1[1] + lam * l1[3], True


@leaf_njit(cache=True)
def _chord_point(
    ln: np.ndarray, rect: np.ndarray, k: int, lam_min: float, lam_max: float
) -> tuple[float, float, bool]:  # pragma: no cover
    # The midpoint of the part of the line inside the (open) rectangle k, with lam_min < param < lam_max.
    t0 = lam_min
    t1 = lam_max
    for ax in range(2):
        o = ln[ax]
        d = ln[2 + ax]
        a = float(rect[k, 2 * ax])
        b = float(rect[k, 2 * ax + 1])
        if d == 0.0:
            if not (a + _EPS < o < b - _EPS):
                return 0.0, 0.0, False
        else:
            ta = (a - o) / d
            tb = (b - o) / d
            if ta > tb:
                ta, tb = tb, ta
            t0 = max(t0, ta)
            t1 = min(t1, tb)
    if t1 - t0 <= 4.0 * _EPS:
        return 0.0, 0.0, False
    t = 0.5 * (t0 + t1)
    return ln[0] + t * ln[2], ln[1] + t * ln[3], True


@njit(cache=True)
def _v4_periodic(
    reach: np.ndarray, lines: np.ndarray, rect: np.ndarray, gp: np.ndarray, gq: np.ndarray, s0: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, bool]:  # pragma: no cover
    n = reach.size
    cap = 16 * n + 32
    vx = np.empty(cap, np.float64)
    vy = np.empty(cap, np.float64)
    vt = np.empty(cap, np.int64)
    vs = np.empty(cap, np.int64)
    vl = np.empty(cap, np.int64)
    seen = np.full(n, -1, np.int64)  # last vertex index whose outgoing line is ≡ s (mod n)
    nv = 0
    s = s0
    t_prev = s0
    lam_prev = -_BIG
    while nv + 2 < cap:
        e = s + reach[s % n]
        ls = lines[s % n]
        found = False
        for s2 in range(e, s, -1):
            l2 = lines[s2 % n]
            x, y, okm = _meet(ls, l2)
            if not okm:
                continue
            t, lam, ok = _locate(lines, s, e, x, y, rect, gp, gq, n)
            if not ok or t < s2 or t > e:
                continue
            if t < t_prev or (t == t_prev and lam <= lam_prev + _EPS):
                continue
            vx[nv] = x
            vy[nv] = y
            vt[nv] = t
            vs[nv] = SRC_LINES
            vl[nv] = s2
            nv += 1
            s = s2
            t_prev = t
            lam_prev = (x - l2[0]) * l2[2] + (y - l2[1]) * l2[3]
            found = True
            break
        if not found:
            lmin = lam_prev if e == t_prev else -_BIG
            ax, ay, oka = _chord_point(ls, rect, e % n, lmin, _BIG)
            le = lines[e % n]
            bx, by, okb = _chord_point(le, rect, e % n, -_BIG, _BIG)
            if not (oka and okb):
                break
            vx[nv] = ax
            vy[nv] = ay
            vt[nv] = e
            vs[nv] = SRC_PATCH
            vl[nv] = -1 - s  # the patch edge; keeps the state distinct from a line vertex
            nv += 1
            vx[nv] = bx
            vy[nv] = by
            vt[nv] = e
            vs[nv] = SRC_PATCH
            vl[nv] = e
            nv += 1
            s = e
            t_prev = e
            lam_prev = (bx - le[0]) * le[2] + (by - le[1]) * le[3]
        # the state after the last vertex is (its position, the current line): a repeat one lap later closes
        last = nv - 1
        k = s % n
        j = seen[k]
        if j >= 0 and vl[j] == s - n and vx[j] == vx[last] and vy[j] == vy[last] and vt[last] - vt[j] == n:
            m = last - j
            out = np.empty((m, 2), np.float64)
            ot = np.empty(m, np.int64)
            os_ = np.empty(m, np.int64)
            ol = np.empty(m, np.int64)
            for q in range(m):
                out[q, 0] = vx[j + 1 + q]
                out[q, 1] = vy[j + 1 + q]
                ot[q] = vt[j + 1 + q] - n * ((vt[j + 1] - (vt[j + 1] % n)) // n)
                os_[q] = vs[j + 1 + q]
                ol[q] = vl[j + 1 + q] % n if vl[j + 1 + q] >= 0 else -1
            return out, ot, os_, ol, True
        seen[k] = last
        if vt[last] > s0 + 5 * n:
            break
    return np.empty((0, 2), np.float64), vt[:0], vs[:0], vl[:0], False


@njit(cache=True)
def v4_greedy(
    reach: np.ndarray,
    lines: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    periodic: bool,
    start: int = -1,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, bool]:  # pragma: no cover
    """Choose lines and vertices around the ring (docs/algorithms.md §3.5, V4).

    From the longest window, take as next line the farthest one that meets the current line inside a piece
    of their overlap (after the previous vertex); if none does, a patch (two vertices in the last piece of
    the current window). ``periodic=False`` closes the ring on the first line after one lap;
    ``periodic=True`` walks on until a vertex repeats one lap later and keeps that period.

    Returns float vertices (k, 2) in Q-units, their pieces (unwrapped, increasing by at most one lap), their
    sources, the line of the edge *leaving* each vertex, and whether it succeeded.
    """
    n = reach.size
    s0 = 0
    for i in range(n):
        if reach[i] > reach[s0]:
            s0 = i
    if start >= 0:
        s0 = start
    if periodic:
        return _v4_periodic(reach, lines, rect, gp, gq, s0)
    cap = 4 * n + 16
    vx = np.empty(cap, np.float64)
    vy = np.empty(cap, np.float64)
    vt = np.empty(cap, np.int64)
    vs = np.empty(cap, np.int64)
    vl = np.empty(cap, np.int64)
    nv = 0
    s = s0
    t_prev = s0
    lam_prev = -_BIG
    first_t = -1
    first_lam = 0.0
    guard = 0
    l0 = lines[s0]
    while True:
        guard += 1
        if guard > 3 * n + 10 or nv + 2 >= cap:
            return np.empty((0, 2), np.float64), vt[:0], vs[:0], vl[:0], False
        e = s + reach[s % n]
        closing = nv > 0 and e >= s0 + n
        hi = s0 + n if closing else e
        ls = lines[s % n]
        found = False
        for s2 in range(hi, s, -1):
            l2 = lines[s2 % n]
            x, y, okm = _meet(ls, l2)
            if not okm:
                continue
            t, lam, ok = _locate(lines, s, e, x, y, rect, gp, gq, n)
            if not ok or t < s2 or t > e:
                continue
            if t < t_prev or (t == t_prev and lam <= lam_prev + _EPS):
                continue
            if nv > 0:
                if t > first_t + n:
                    continue
                if s2 == s0 + n:
                    lam0 = (x - l0[0]) * l0[2] + (y - l0[1]) * l0[3]
                    if t == first_t + n and lam0 >= first_lam - _EPS:
                        continue
                elif t >= first_t + n:
                    continue
            vx[nv] = x
            vy[nv] = y
            vt[nv] = t
            vs[nv] = SRC_LINES
            vl[nv] = s2 % n
            nv += 1
            if nv == 1:
                first_t = t
                first_lam = (x - l0[0]) * l0[2] + (y - l0[1]) * l0[3]
            if s2 == s0 + n:
                out = np.empty((nv, 2), np.float64)
                for q in range(nv):
                    out[q, 0] = vx[q]
                    out[q, 1] = vy[q]
                return out, vt[:nv], vs[:nv], vl[:nv], True
            s = s2
            t_prev = t
            l2n = lines[s % n]
            lam_prev = (x - l2n[0]) * l2n[2] + (y - l2n[1]) * l2n[3]
            found = True
            break
        if found:
            continue
        if closing:
            # close with a patch in the first possible piece: a on line s, then b on line s0
            tc = max(s0 + n, t_prev)
            if tc > e or tc > first_t + n:
                return np.empty((0, 2), np.float64), vt[:0], vs[:0], vl[:0], False
            lmin = lam_prev if tc == t_prev else -_BIG
            ax, ay, oka = _chord_point(ls, rect, tc % n, lmin, _BIG)
            lmax = first_lam if tc == first_t + n else _BIG
            bx, by, okb = _chord_point(l0, rect, tc % n, -_BIG, lmax)
            if not (oka and okb):
                return np.empty((0, 2), np.float64), vt[:0], vs[:0], vl[:0], False
            vx[nv] = ax
            vy[nv] = ay
            vt[nv] = tc
            vs[nv] = SRC_PATCH
            vl[nv] = -1
            nv += 1
            vx[nv] = bx
            vy[nv] = by
            vt[nv] = tc
            vs[nv] = SRC_PATCH
            vl[nv] = s0
            nv += 1
            out = np.empty((nv, 2), np.float64)
            for q in range(nv):
                out[q, 0] = vx[q]
                out[q, 1] = vy[q]
            return out, vt[:nv], vs[:nv], vl[:nv], True
        # patch in piece e: a on line s, b on line e
        lmin = lam_prev if e == t_prev else -_BIG
        ax, ay, oka = _chord_point(ls, rect, e % n, lmin, _BIG)
        le = lines[e % n]
        bx, by, okb = _chord_point(le, rect, e % n, -_BIG, _BIG)
        if not (oka and okb):
            return np.empty((0, 2), np.float64), vt[:0], vs[:0], vl[:0], False
        vx[nv] = ax
        vy[nv] = ay
        vt[nv] = e
        vs[nv] = SRC_PATCH
        vl[nv] = -1
        nv += 1
        if nv == 1:
            first_t = e
            first_lam = (ax - l0[0]) * l0[2] + (ay - l0[1]) * l0[3]
        vx[nv] = bx
        vy[nv] = by
        vt[nv] = e
        vs[nv] = SRC_PATCH
        vl[nv] = e % n
        nv += 1
        s = e
        t_prev = e
        lam_prev = (bx - le[0]) * le[2] + (by - le[1]) * le[3]
