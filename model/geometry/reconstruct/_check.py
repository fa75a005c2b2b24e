"""Exact checks of R's rings and the dyadic snapping of their vertices (integer arithmetic only)."""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit

# ============================================================================================ exact checks


@njit(cache=True)
def _sgn(v: int) -> int:  # pragma: no cover
    return 1 if v > 0 else (-1 if v < 0 else 0)


@njit(cache=True)
def _orient(ax: int, ay: int, bx: int, by: int, cx: int, cy: int) -> int:  # pragma: no cover
    return _sgn((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))


@njit(cache=True)
def _on_seg(ax: int, ay: int, bx: int, by: int, px: int, py: int) -> bool:  # pragma: no cover
    # p collinear with [a, b]: is it on the closed segment?
    return min(ax, bx) <= px <= max(ax, bx) and min(ay, by) <= py <= max(ay, by)


@njit(cache=True)
def segments_meet(
    ax: int, ay: int, bx: int, by: int, cx: int, cy: int, dx: int, dy: int
) -> bool:  # pragma: no cover
    """Whether the closed segments [a, b] and [c, d] share a point (exact)."""
    o1 = _orient(ax, ay, bx, by, cx, cy)
    o2 = _orient(ax, ay, bx, by, dx, dy)
    o3 = _orient(cx, cy, dx, dy, ax, ay)
    o4 = _orient(cx, cy, dx, dy, bx, by)
    if o1 * o2 < 0 and o3 * o4 < 0:
        return True
    if o1 == 0 and _on_seg(ax, ay, bx, by, cx, cy):
        return True
    if o2 == 0 and _on_seg(ax, ay, bx, by, dx, dy):
        return True
    if o3 == 0 and _on_seg(cx, cy, dx, dy, ax, ay):
        return True
    return o4 == 0 and _on_seg(cx, cy, dx, dy, bx, by)


@leaf_njit(cache=True)
def edge_ok(
    ux: int,
    uy: int,
    tu: int,
    wx: int,
    wy: int,
    tw: int,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    sc: int,
) -> bool:  # pragma: no cover
    """Whether the segment u → w crosses gates tu+1 … tw in order, each strictly inside.

    u is in piece tu and w in piece tw ≥ tu (unwrapped). Coordinates are scaled by ``sc``; gates are in
    Q-units.
    """
    n = gdir.size
    if tw - tu >= n:
        return False
    pa = 0  # previous crossing parameter pa / pb (0 at u), pb > 0
    pb = 1
    for k in range(tu + 1, tw + 1):
        g = k % n
        d = gdir[g]
        if d == 0 or d == 2:
            gx = gp[g, 0] * sc
            lo = min(gp[g, 1], gq[g, 1]) * sc
            hi = max(gp[g, 1], gq[g, 1]) * sc
            den = wx - ux
            num = gx - ux
            if d == 0 and not (ux < gx < wx):
                return False
            if d == 2 and not (ux > gx > wx):
                return False
            cross = num * (wy - uy)  # (y - uy) * den
            if den < 0:
                den = -den
                num = -num
                cross = -cross
            if not ((lo - uy) * den < cross < (hi - uy) * den):
                return False
        else:
            gy = gp[g, 1] * sc
            lo = min(gp[g, 0], gq[g, 0]) * sc
            hi = max(gp[g, 0], gq[g, 0]) * sc
            den = wy - uy
            num = gy - uy
            if d == 1 and not (uy < gy < wy):
                return False
            if d == 3 and not (uy > gy > wy):
                return False
            cross = num * (wx - ux)
            if den < 0:
                den = -den
                num = -num
                cross = -cross
            if not ((lo - ux) * den < cross < (hi - ux) * den):
                return False
        # crossing parameter num / den must increase strictly
        if k > tu + 1 and not (pa * den < num * pb):
            return False
        pa = num
        pb = den
    return True


@leaf_njit(cache=True)
def gate_rays(
    ox: int, oy: int, t0: int, t1: int, fwd: bool, gp: np.ndarray, gq: np.ndarray, sc: int
) -> tuple[int, int, int, int, bool]:  # pragma: no cover
    """The two tightest rays from o through the gates t0+1 … t1 (unwrapped), for a quick edge pre-test.

    Forward (o in piece t0, the edge leaving o): an edge o → x that crosses those gates strictly inside has
    x − o strictly clockwise of every o→P and counter-clockwise of every o→Q, so of the most clockwise P ray
    and the most counter-clockwise Q ray returned. Backward (o in piece t1, the edge x → o): x − o strictly
    counter-clockwise of every o→P and clockwise of every o→Q. Exact integers (coordinates scaled by ``sc``);
    the last value is False when there are no gates (or a lap or more: then :func:`edge_ok` decides alone).
    See :func:`rays_admit`.
    """
    n = gp.shape[0]
    if not (t0 < t1 < t0 + n):
        return 0, 0, 0, 0, False
    lx = 0
    ly = 0
    rx = 0
    ry = 0
    for k in range(t0 + 1, t1 + 1):
        g = (k if fwd else t0 + 1 + t1 - k) % n
        px_ = gp[g, 0] * sc - ox
        py_ = gp[g, 1] * sc - oy
        qx_ = gq[g, 0] * sc - ox
        qy_ = gq[g, 1] * sc - oy
        first = k == t0 + 1
        if fwd:
            if first or lx * py_ - ly * px_ < 0:
                lx = px_
                ly = py_
            if first or rx * qy_ - ry * qx_ > 0:
                rx = qx_
                ry = qy_
        else:
            if first or lx * py_ - ly * px_ > 0:
                lx = px_
                ly = py_
            if first or rx * qy_ - ry * qx_ < 0:
                rx = qx_
                ry = qy_
    return lx, ly, rx, ry, True


@njit(cache=True, inline="always")
def rays_admit(
    ox: int, oy: int, lx: int, ly: int, rx: int, ry: int, fwd: bool, x: int, y: int
) -> bool:  # pragma: no cover
    """Whether x is strictly between the rays of :func:`gate_rays` (a necessary condition of the edge)."""
    cl = lx * (y - oy) - ly * (x - ox)
    cr = rx * (y - oy) - ry * (x - ox)
    if fwd:
        return cl < 0 < cr
    return cr < 0 < cl


@leaf_njit(cache=True)
def _in_piece(rect: np.ndarray, t: int, x: int, y: int, sc: int) -> bool:  # pragma: no cover
    return bool(rect[t, 0] * sc < x < rect[t, 1] * sc and rect[t, 2] * sc < y < rect[t, 3] * sc)


@leaf_njit(cache=True)
def verify_ring(
    vx: np.ndarray,
    vy: np.ndarray,
    vt: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    sc: int,
    bad: np.ndarray,
) -> bool:  # pragma: no cover
    """Exact check of a ring of the corridor (see the module docstring).

    Marks ``bad[i]`` for failing vertices (a failing edge i → i+1 marks both). Vertices: integer coordinates
    scaled by ``sc``, pieces unwrapped and non-decreasing, within one lap of the first.
    """
    n = gdir.size
    m = vx.size
    ok = True
    for i in range(m):
        bad[i] = False
    if m < 3:
        for i in range(m):
            bad[i] = True
        return False
    for i in range(m):
        j = (i + 1) % m
        tj = vt[j] + (n if j == 0 else 0)
        if tj < vt[i] or (j == 0 and vt[i] < vt[0]):
            bad[i] = True
            bad[j] = True
            ok = False
            continue
        if not _in_piece(rect, vt[i] % n, vx[i], vy[i], sc):
            bad[i] = True
            ok = False
        if not edge_ok(vx[i], vy[i], vt[i], vx[j], vy[j], tj, gp, gq, gdir, sc):
            bad[i] = True
            bad[j] = True
            ok = False
    if vt[m - 1] > vt[0] + n:
        bad[m - 1] = True
        ok = False
    if not ok:
        return False
    # folds: consecutive edges going back along themselves
    for i in range(m):
        a = (i - 1) % m
        b = (i + 1) % m
        o = _orient(vx[a], vy[a], vx[i], vy[i], vx[b], vy[b])
        if o == 0 and (vx[i] - vx[a]) * (vx[b] - vx[i]) + (vy[i] - vy[a]) * (vy[b] - vy[i]) <= 0:
            bad[i] = True
            ok = False
    if not ok:
        return False
    # edges meeting in a piece that holds two or more vertices (the run of vertex 0 may continue from the
    # end of the ring, one lap later)
    jb = m
    while jb - 1 > 0 and vt[jb - 1] == vt[0] + n:
        jb -= 1
    i = 0
    while i < jb:
        j = i
        while j + 1 < jb and vt[j + 1] == vt[i]:
            j += 1
        extra = (m - jb) if i == 0 else 0
        cnt = (j - i + 1) + extra
        if cnt >= 2:
            k0 = (jb - 1) if extra > 0 else (i - 1) % m
            nedge = cnt + 1
            for p in range(nedge):
                pa = (k0 + p) % m
                pb = (pa + 1) % m
                for q in range(p + 2, nedge):
                    qa = (k0 + q) % m
                    qb = (qa + 1) % m
                    if qb == pa:
                        continue
                    if segments_meet(vx[pa], vy[pa], vx[pb], vy[pb], vx[qa], vy[qa], vx[qb], vy[qb]):
                        bad[pb] = True
                        bad[qa] = True
                        ok = False
        i = j + 1
    return ok


# ============================================================================================ snapping


@leaf_njit(cache=True)
def snap_ring(
    fx: np.ndarray,
    fy: np.ndarray,
    vt: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: int,
    ix: np.ndarray,
    iy: np.ndarray,
    bad: np.ndarray,
) -> None:  # pragma: no cover
    """Snap float vertices (Q-units) to the coarsest dyadic grids that keep every constraint.

    The grid 2^-k (k ≤ kmax) must keep the vertex in its piece and the edges to its neighbours valid; integer
    results at scale 2^kmax. Vertices for which no grid works are marked bad (rounded at 2^-kmax).
    """
    n = gdir.size
    m = fx.size
    sc = 1 << kmax
    for i in range(m):
        bad[i] = False
    for i in range(m):
        t = vt[i]
        nxt = (i + 1) % m
        tn = vt[nxt] + (n if nxt == 0 else 0)
        # the next vertex as it would be at the finest grid (for i < m-1)
        nx = int(np.round(fx[nxt] * sc))
        ny = int(np.round(fy[nxt] * sc))
        if nxt == 0:
            nx = ix[0]
            ny = iy[0]
        done = False
        for k in range(kmax + 1):
            f = float(1 << k)
            mul = 1 << (kmax - k)
            x = int(np.round(fx[i] * f)) * mul
            y = int(np.round(fy[i] * f)) * mul
            if not _in_piece(rect, t % n, x, y, sc):
                continue
            if i > 0 and not edge_ok(ix[i - 1], iy[i - 1], vt[i - 1], x, y, t, gp, gq, gdir, sc):
                continue
            if m > 1 and not edge_ok(x, y, t, nx, ny, tn, gp, gq, gdir, sc):
                continue
            ix[i] = x
            iy[i] = y
            done = True
            break
        if not done:
            ix[i] = int(np.round(fx[i] * sc))
            iy[i] = int(np.round(fy[i] * sc))
            bad[i] = True
