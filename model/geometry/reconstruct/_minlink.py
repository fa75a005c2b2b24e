"""Phase 4 of R on rings above their window bound: a minimum-link ring through the corridor (ADR 0031).

The V4 greedy (:mod:`._greedy`) takes the *central* line of each window, and where two consecutive central
lines do not meet inside a common piece it spends two vertices (a patch). A ring of fewest vertices is a
minimum-link closed path through the corridor: a polygonal path in the sleeve of pieces that crosses the
gates in order and winds once. For a path from a fixed point s this is Suri's window partition: the points
reachable from s with k links are bounded by a *window* W_k, a chord of the sleeve, and the points reachable
with k + 1 links are those weakly visible from W_k (seen from some point of it). So:

* W_1 is the chord along the tightest ray of the cone of rays from s through the gates, from the gate end
  that bounds it to where it leaves the last piece the cone reaches;
* the lines of link k + 1 cross W_k from its reachable side and then the gates in order. Cut W_k into its
  parts σ_t in the pieces t it runs through; for each, the lines crossing σ_t and gates t+1 … J form a
  convex polygon in line space (every constraint is "this point strictly left / right of the line", linear
  in the slope and offset of the line in a frame where all those lines point forward). The farthest J any
  part reaches, and the line of that polygon nearest to passing the next gate, give W_{k+1}: that line
  from its last contact with the inside of the turn to where it leaves piece J;
* once a window sees s one lap later, the ring is built backwards: the vertex on W_k is taken in the middle
  of the part of W_k that sees the next vertex (an interval, from the linear conditions of the backward
  cone), pushed slightly into the reachable side.

Everything here is floating point and only *proposes* a ring: the caller snaps it to the dyadic grid and
verifies it exactly (:func:`._check.snap_ring`, :func:`._check.verify_ring`), and keeps it only when it
verifies and has fewer vertices than the ring it would replace. Gates are shrunk by a small margin at both
ends while searching and vertices are pushed off their windows, so a proposal rarely sits on a constraint.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from mrm.geometry._jit import leaf_njit, njit
from mrm.geometry.reconstruct._base import SRC_LINES, _grow1
from mrm.geometry.reconstruct._check import snap_ring, verify_ring


class Windows(NamedTuple):
    """The windows W_1, W_2, … of one search (row k is W_k; row 0 unused).

    Window k runs from the point (cx, cy) along the unit direction (dx, dy), its reachable side on the
    left when side[k] = +1 (right: −1); its parts are off[k] … off[k+1]−1, each a piece t and a parameter
    interval l0 … l1 along the window.
    """

    cx: np.ndarray
    cy: np.ndarray
    dx: np.ndarray
    dy: np.ndarray
    side: np.ndarray
    off: np.ndarray
    t: np.ndarray
    l0: np.ndarray
    l1: np.ndarray


_GATE_EPS = 1.0 / 32.0  # Q-units each gate is shrunk by at both ends while searching
# A window's line must be free to move sideways by _ROOM Q-units among the lines of its step, or the step
# is taken again with the gates shrunk by _ROOMY_EXTRA more: a window resting on a sliver of lines (slopes
# within 1 % of each other through a one-pixel arm, thinner than the snapping grid) promises a ring the
# backward pass cannot place. When the backward pass fails all the same, the search runs once more with
# _ROOM_AGAIN. Measured on the benchmark images and noisy stars: _ROOM = 1/512 from the start costs the
# images 1-4 vertices each; 1/16384, then 1/512, costs camera one and gains the stars 3-7 % (ADR 0038).
_ROOMY_EXTRA = 1.0 / 32.0
_ROOM = 1.0 / 16384.0
_ROOM_AGAIN = 1.0 / 512.0
_PUSH = 1.0 / 32.0  # Q-units a vertex is pushed off its window into the reachable side (at most)
_MARGIN = 1.0 / 512.0  # Q-units a vertex keeps from the sides of its piece (room for snapping)
_PCAP = 96  # vertices of a line-space polygon (a preimage has a handful; more aborts the search)
_BOX_A = 64.0  # |slope| bound of the initial line-space box (the frame keeps real slopes small)
_INSET = 0.3  # how far a window's line moves from the extreme line towards the polygon's centroid
_STARTS = 3  # starts tried (vertices 0, m/3, 2m/3) while the windows promise fewer vertices
_MANY_STARTS_PIECES = 1024  # … on corridors of at most this many pieces; larger ones try vertex 0 only


@njit(cache=True)
def shrunk_gates(gp: np.ndarray, gq: np.ndarray) -> np.ndarray:  # pragma: no cover
    """Gate ends moved towards each other by :data:`_GATE_EPS` (or a quarter of the gate): (n, 4) floats."""
    n = gp.shape[0]
    out = np.empty((n, 4), np.float64)
    for g in range(n):
        px = float(gp[g, 0])
        py = float(gp[g, 1])
        qx = float(gq[g, 0])
        qy = float(gq[g, 1])
        ln = abs(qx - px) + abs(qy - py)  # gates are axis-parallel
        e = min(_GATE_EPS, 0.25 * ln)
        ux = (qx - px) / ln
        uy = (qy - py) / ln
        out[g, 0] = px + e * ux
        out[g, 1] = py + e * uy
        out[g, 2] = qx - e * ux
        out[g, 3] = qy - e * uy
    return out


@leaf_njit(cache=True)
def _cone(
    ox: float, oy: float, t0: int, tmax: int, sg: np.ndarray
) -> tuple[int, float, float, int, int]:  # pragma: no cover
    # Follow the cone of rays from o (in piece t0) through the shrunk gates t0+1, … while it stays open, up
    # to piece tmax. Returns the last piece J it reaches, the window ray (a vector from o to the gate end
    # that bounds it), how the cone closes at gate J+1 (0: it does not; 1: the corridor turns right and the
    # window runs along the right ray; 2: it turns left, along the left ray) and the gate of that end.
    n = sg.shape[0]
    lx = 0.0
    ly = 0.0
    rx = 0.0
    ry = 0.0
    gl = -1
    gr = -1
    for k in range(t0 + 1, tmax + 1):
        g = k % n
        px = sg[g, 0] - ox
        py = sg[g, 1] - oy
        qx = sg[g, 2] - ox
        qy = sg[g, 3] - oy
        if k == t0 + 1:
            lx, ly, rx, ry = px, py, qx, qy
            gl = k
            gr = k
            continue
        if rx * py - ry * px <= 0.0:  # the whole gate clockwise of the right ray: a right turn
            return k - 1, rx, ry, 1, gr
        if lx * qy - ly * qx >= 0.0:  # counter-clockwise of the left ray: a left turn
            return k - 1, lx, ly, 2, gl
        if lx * py - ly * px < 0.0:
            lx, ly = px, py
            gl = k
        if rx * qy - ry * qx > 0.0:
            rx, ry = qx, qy
            gr = k
    return tmax, 0.0, 0.0, 0, -1


@leaf_njit(cache=True)
def _sees(
    ax: float, ay: float, ta: int, bx: float, by: float, tb: int, sg: np.ndarray
) -> bool:  # pragma: no cover
    # Whether b (in piece tb >= ta) lies strictly inside the cone from a through the shrunk gates ta+1 … tb.
    n = sg.shape[0]
    dx = bx - ax
    dy = by - ay
    for k in range(ta + 1, tb + 1):
        g = k % n
        px = sg[g, 0] - ax
        py = sg[g, 1] - ay
        qx = sg[g, 2] - ax
        qy = sg[g, 3] - ay
        if dx * py - dy * px <= 0.0 or dx * qy - dy * qx >= 0.0:  # P strictly left of a→b, Q right
            return False
    return True


@leaf_njit(cache=True)
def _span(
    ox: float, oy: float, dx: float, dy: float, rect: np.ndarray, t: int
) -> tuple[float, float]:  # pragma: no cover
    # The parameter interval in which the line o + λd is in the closed rectangle t (empty: lo > hi).
    lo = -1e300
    hi = 1e300
    for ax in range(2):
        o = ox if ax == 0 else oy
        d = dx if ax == 0 else dy
        a0 = float(rect[t, 2 * ax])
        a1 = float(rect[t, 2 * ax + 1])
        if d == 0.0:
            if not (a0 <= o <= a1):
                return 1.0, -1.0
        else:
            a = (a0 - o) / d
            b = (a1 - o) / d
            if a > b:
                a, b = b, a
            lo = max(lo, a)
            hi = min(hi, b)
    return lo, hi


@leaf_njit(cache=True)
def _inside(rect: np.ndarray, t: int, x: float, y: float, m: float) -> bool:  # pragma: no cover
    return bool(rect[t, 0] + m < x < rect[t, 1] - m and rect[t, 2] + m < y < rect[t, 3] - m)


@leaf_njit(cache=True)
def _halfplane(
    pa: np.ndarray, pb: np.ndarray, m: int, ca: float, cb: float, cc: float, oa: np.ndarray, ob: np.ndarray
) -> int:  # pragma: no cover
    # Clip the convex polygon (pa, pb)[:m] in line space to ca·a + cb·b + cc > 0, into (oa, ob). Returns the
    # new size (0: empty; −1: too many vertices).
    k = 0
    for i in range(m):
        j = i + 1 if i + 1 < m else 0
        fi = ca * pa[i] + cb * pb[i] + cc
        fj = ca * pa[j] + cb * pb[j] + cc
        if fi > 0.0:
            if k >= oa.size:
                return -1
            oa[k] = pa[i]
            ob[k] = pb[i]
            k += 1
        if (fi > 0.0) != (fj > 0.0):
            if k >= oa.size:
                return -1
            t = fi / (fi - fj)
            oa[k] = pa[i] + t * (pa[j] - pa[i])
            ob[k] = pb[i] + t * (pb[j] - pb[i])
            k += 1
    return k if k >= 3 else 0


@leaf_njit(cache=True)
def _frame(t: int, tmax: int, reach: np.ndarray, gdir: np.ndarray) -> tuple[float, float]:  # pragma: no cover
    # A unit direction u that every line crossing gates t+1 … (its window) in order points along (u · d > 0):
    # the gates' common crossing direction, or the diagonal between the two perpendicular ones. Slopes
    # measured in the frame of u then stay small.
    n = gdir.size
    e = min(tmax, t + reach[t % n])
    seen = 0
    for k in range(t + 1, e + 1):
        seen |= 1 << gdir[k % n]
    ux = 0.0
    uy = 0.0
    for d in range(4):
        if seen & (1 << d):
            ux += 1.0 if d == 0 else (-1.0 if d == 2 else 0.0)
            uy += 1.0 if d == 1 else (-1.0 if d == 3 else 0.0)
    ln = np.hypot(ux, uy)
    if ln == 0.0:
        d = gdir[(t + 1) % n]
        ux = 1.0 if d == 0 else (-1.0 if d == 2 else 0.0)
        uy = 1.0 if d == 1 else (-1.0 if d == 3 else 0.0)
        ln = 1.0
    return ux / ln, uy / ln


@leaf_njit(cache=True)
def _gate(sg: np.ndarray, g: int, extra: float) -> tuple[float, float, float, float]:  # pragma: no cover
    # Gate g's ends P, Q, shrunk by ``extra`` more Q-units (or a quarter of what is left) at both ends.
    px = sg[g, 0]
    py = sg[g, 1]
    qx = sg[g, 2]
    qy = sg[g, 3]
    if extra > 0.0:
        ln = abs(qx - px) + abs(qy - py)  # gates are axis-parallel
        e = min(extra, 0.25 * ln) / ln
        ux = (qx - px) * e
        uy = (qy - py) * e
        px += ux
        py += uy
        qx -= ux
        qy -= uy
    return px, py, qx, qy


@leaf_njit(cache=True)
def _room(pa: np.ndarray, pb: np.ndarray, m: int, a: float, b: float) -> float:  # pragma: no cover
    # How far the line (a, b) of line space is from the boundary of the convex polygon (pa, pb)[:m] along
    # the offset axis: the smaller of b − (lowest b of the polygon at slope a) and (highest b) − b.
    lo = 1e300
    hi = -1e300
    for i in range(m):
        j = i + 1 if i + 1 < m else 0
        a0 = pa[i]
        a1 = pa[j]
        if (a0 - a) * (a1 - a) > 0.0:
            continue  # this edge does not span slope a
        if a1 == a0:
            c0 = min(pb[i], pb[j])
            c1 = max(pb[i], pb[j])
        else:
            c0 = pb[i] + (a - a0) / (a1 - a0) * (pb[j] - pb[i])
            c1 = c0
        lo = min(lo, c0)
        hi = max(hi, c1)
    if hi < lo:
        return 0.0
    return max(0.0, min(b - lo, hi - b))


@leaf_njit(cache=True)
def _pre_reach(
    lx: float,
    ly: float,
    rx: float,
    ry: float,
    t: int,
    tmax: int,
    sg: np.ndarray,
    extra: float,
    reach: np.ndarray,
    gdir: np.ndarray,
    bufa: np.ndarray,
    bufb: np.ndarray,
) -> tuple[
    int, int, float, float, float, float, float, float, float, float, float, float
]:  # pragma: no cover
    # Lines that have l strictly on their left and r on their right (the oriented crossing of a part of a
    # window, in piece t) and then cross the shrunk gates t+1, … in order: follow their polygon in line
    # space (frame u from :func:`_frame`, origin o the midpoint of l and r; a line is y' = a·x' + b) while
    # it is non-empty, up to piece tmax. Returns the last piece J, how the gate J+1 is missed (0: not, up
    # to tmax; 1: a right turn; 2: a left turn; −1: failure), the extreme line towards that gate (a world
    # point and unit direction), how far it misses the gate's end (smaller is nearer to turning the
    # corner), and the line the next window runs on: the extreme line moved by _INSET towards the polygon's
    # centroid (at tmax, both lines are the centroid's), and that line's room: how far it can move
    # sideways before it leaves the polygon (Q-units; 1e300 at tmax). bufa / bufb: (3, _PCAP) scratch.
    n = sg.shape[0]
    ux, uy = _frame(t, tmax, reach, gdir)
    vx = -uy  # left normal
    vy = ux
    ox = 0.5 * (lx + rx)
    oy = 0.5 * (ly + ry)
    ext = 8.0 * (tmax - t + 2) + 8.0
    pa = bufa[0]
    pb = bufb[0]
    qa = bufa[1]
    qb = bufb[1]
    pa[0] = -_BOX_A
    pb[0] = -_BOX_A * ext
    pa[1] = _BOX_A
    pb[1] = -_BOX_A * ext
    pa[2] = _BOX_A
    pb[2] = _BOX_A * ext
    pa[3] = -_BOX_A
    pb[3] = _BOX_A * ext
    m = 4
    # l left: y' − a·x' − b > 0; r right: a·x' + b − y' > 0
    xl = (lx - ox) * ux + (ly - oy) * uy
    yl = (lx - ox) * vx + (ly - oy) * vy
    m = _halfplane(pa, pb, m, -xl, -1.0, yl, qa, qb)
    if m <= 0:
        return t, -1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    xr = (rx - ox) * ux + (ry - oy) * uy
    yr = (rx - ox) * vx + (ry - oy) * vy
    m = _halfplane(qa, qb, m, xr, 1.0, -yr, pa, pb)
    if m <= 0:
        return t, -1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    ja = t
    for k in range(t + 1, tmax + 1):
        g = k % n
        gpx, gpy, gqx, gqy = _gate(sg, g, extra)
        xp = (gpx - ox) * ux + (gpy - oy) * uy
        yp = (gpx - ox) * vx + (gpy - oy) * vy
        xq = (gqx - ox) * ux + (gqy - oy) * uy
        yq = (gqx - ox) * vx + (gqy - oy) * vy
        m1 = _halfplane(pa, pb, m, -xp, -1.0, yp, qa, qb)
        m2 = 0
        if m1 > 0:
            m2 = _halfplane(qa, qb, m1, xq, 1.0, -yq, bufa[2], bufb[2])
        if m1 < 0 or m2 < 0:
            return ja, -1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
        if m2 == 0:
            # missed: the gate lies right of every line (P never left: a right turn) or left of all
            vpmax = -1e300
            vqmax = -1e300
            ip = 0
            iq = 0
            for i in range(m):
                vp = yp - pa[i] * xp - pb[i]
                vq = pa[i] * xq + pb[i] - yq
                if vp > vpmax:
                    vpmax = vp
                    ip = i
                if vq > vqmax:
                    vqmax = vq
                    iq = i
            if vpmax <= 0.0 and (vqmax > 0.0 or vpmax >= vqmax):
                side = 1
                i = ip
                miss = -vpmax
            else:
                side = 2
                i = iq
                miss = -vqmax
            a = pa[i]
            b = pb[i]
            dl = np.hypot(1.0, a)
            # the window line itself: a little inside the polygon, towards its centroid, so that its points
            # are reachable with room to spare (the extreme line is only a limit of reachable lines)
            ca = 0.0
            cb = 0.0
            for i2 in range(m):
                ca += pa[i2]
                cb += pb[i2]
            a2 = a + _INSET * (ca / m - a)
            b2 = b + _INSET * (cb / m - b)
            dl2 = np.hypot(1.0, a2)
            return (
                ja,
                side,
                ox + b * vx,
                oy + b * vy,
                (ux + a * vx) / dl,
                (uy + a * vy) / dl,
                miss / dl,
                ox + b2 * vx,
                oy + b2 * vy,
                (ux + a2 * vx) / dl2,
                (uy + a2 * vy) / dl2,
                _room(pa, pb, m, a2, b2) / dl2,
            )
        for i in range(m2):
            pa[i] = bufa[2, i]
            pb[i] = bufb[2, i]
        m = m2
        ja = k
    # reached tmax: the centroid line (for a last vertex that must see a given point)
    ca = 0.0
    cb = 0.0
    for i in range(m):
        ca += pa[i]
        cb += pb[i]
    ca /= m
    cb /= m
    dl = np.hypot(1.0, ca)
    x = ox + cb * vx
    y = oy + cb * vy
    dx = (ux + ca * vx) / dl
    dy = (uy + ca * vy) / dl
    return ja, 0, x, y, dx, dy, 0.0, x, y, dx, dy, 1e300


@leaf_njit(cache=True)
def _contact(
    wx: float,
    wy: float,
    dx: float,
    dy: float,
    side: int,
    lx: float,
    ly: float,
    rx: float,
    ry: float,
    t: int,
    j: int,
    sg: np.ndarray,
    extra: float,
) -> float:  # pragma: no cover
    # Where the extreme line w + λd last touches the inside of the turn (the right-hand points — the part's
    # r end and the gates' Q ends — for a right turn, the left-hand ones for a left turn): the largest λ of
    # a point within a small distance of the line, which is where the next window starts.
    n = sg.shape[0]
    best = -1e300
    tol = 1e-6
    for k in range(t, j + 1):
        if k == t:
            x = rx if side == 1 else lx
            y = ry if side == 1 else ly
        else:
            g = k % n
            gpx, gpy, gqx, gqy = _gate(sg, g, extra)
            x = gqx if side == 1 else gpx
            y = gqy if side == 1 else gpy
        off = (x - wx) * dy - (y - wy) * dx
        if abs(off) < tol * (1.0 + abs(x - wx) + abs(y - wy)):
            lam = (x - wx) * dx + (y - wy) * dy
            if lam > best:
                best = lam
    return best


@leaf_njit(cache=True)
def _window_parts(
    cx: float,
    cy: float,
    dx: float,
    dy: float,
    j: int,
    tmin: int,
    rect: np.ndarray,
    wt: np.ndarray,
    w0: np.ndarray,
    w1: np.ndarray,
    at: int,
) -> int:  # pragma: no cover
    # Cut the window c + λd (λ ≥ 0, up to where it leaves piece j) into its parts in the pieces j, j−1, …
    # (not below tmin): piece and parameter interval of each, written from ``at``. Returns the new end.
    n = rect.shape[0]
    lo, hi = _span(cx, cy, dx, dy, rect, j % n)
    if hi <= 1e-9:
        return at
    k = at
    for t in range(j, tmin - 1, -1):
        if k >= wt.size:
            break
        lo, hi = _span(cx, cy, dx, dy, rect, t % n)
        lo = max(lo, 0.0)
        if hi - lo > 1e-6:
            wt[k] = t
            w0[k] = lo
            w1[k] = hi
            k += 1
        if lo <= 1e-9 and hi > 1e-9:
            break
    return k


@leaf_njit(cache=True)
def _back_interval(
    xx: float,
    xy: float,
    tx: int,
    cx: float,
    cy: float,
    dx: float,
    dy: float,
    t: int,
    l0: float,
    l1: float,
    sg: np.ndarray,
) -> tuple[float, float]:  # pragma: no cover
    # The parameters λ in (l0, l1) of the window part c + λd (in piece t < tx) whose points see x (in
    # piece tx) through the shrunk gates t+1 … tx. The conditions "P_g left of y→x, Q_g right" are linear
    # in λ, so this is an interval (empty: lo >= hi).
    n = sg.shape[0]
    lo = l0
    hi = l1
    bx = cx - xx  # the window's base relative to x
    by = cy - xy
    for k in range(t + 1, tx + 1):
        g = k % n
        for e in range(2):
            ex = sg[g, 2 * e] - xx
            ey = sg[g, 2 * e + 1] - xy
            # y = b + λd (relative to x); cross(x − y, e − y) = cross(−y, e − y) = −cross(y, e), wanted
            # > 0 for P (e = 0), < 0 for Q
            c0 = bx * ey - by * ex
            c1 = dx * ey - dy * ex
            if e == 0:
                c0 = -c0
                c1 = -c1
            if c1 > 0.0:
                lo = max(lo, -c0 / c1)
            elif c1 < 0.0:
                hi = min(hi, -c0 / c1)
            elif c0 <= 0.0:
                return 1.0, 0.0
        if hi <= lo:
            return 1.0, 0.0
    return lo, hi


@leaf_njit(cache=True)
def _seen_from(
    xx: float,
    xy: float,
    tx: int,
    k: int,
    w: Windows,
    sg: np.ndarray,
    reach: np.ndarray,
) -> bool:  # pragma: no cover
    # Whether some part of window k has a stretch (not just a point) that sees x.
    n = sg.shape[0]
    for p in range(w.off[k], w.off[k + 1]):
        t = w.t[p]
        if t >= tx or t + reach[t % n] < tx:
            continue
        lo, hi = _back_interval(xx, xy, tx, w.cx[k], w.cy[k], w.dx[k], w.dy[k], t, w.l0[p], w.l1[p], sg)
        if hi - lo > 1e-7 * (1.0 + abs(hi)):
            return True
    return False


_BACK_F = np.array([0.5, 0.3, 0.7, 0.15, 0.85, 0.05, 0.95], np.float64)
_NPUSH = 3  # pushes tried per position: the largest, then a quarter, then a sixteenth of it
_NCAND = _BACK_F.size * _NPUSH  # candidates per window part


@leaf_njit(cache=True)
def _back_onto(
    xx: float,
    xy: float,
    tx: int,
    k: int,
    c0: int,
    sx: float,
    sy: float,
    t0: int,
    w: Windows,
    sg: np.ndarray,
    rect: np.ndarray,
    reach: np.ndarray,
) -> tuple[float, float, int, int]:  # pragma: no cover
    # The first candidate vertex, from number c0 on, on window k that sees x (in piece tx) and is itself seen
    # from window k − 1 (from s when k = 1). Candidates are points of the interval of
    # :func:`_back_interval` on each part (deepest part first), from the middle outwards, pushed off the
    # window to its reachable side by decreasing amounts; one step of look-ahead keeps the backward pass
    # from painting itself into a corner, and the caller backtracks from c + 1 when a later step fails.
    # Returns the point, its piece and its candidate number (−1: none).
    n = rect.shape[0]
    dx = w.dx[k]
    dy = w.dy[k]
    nx = -dy * w.side[k]
    ny = dx * w.side[k]
    np_ = w.off[k + 1] - w.off[k]
    for pi in range(c0 // _NCAND, np_):
        p = w.off[k] + pi
        t = w.t[p]
        if t >= tx or t + reach[t % n] < tx:
            continue
        lo, hi = _back_interval(xx, xy, tx, w.cx[k], w.cy[k], dx, dy, t, w.l0[p], w.l1[p], sg)
        if hi <= lo:
            continue
        push0 = min(_PUSH, 0.25 * (hi - lo))
        cstart = c0 - pi * _NCAND if pi == c0 // _NCAND else 0
        for c in range(cstart, _NCAND):
            lam = lo + _BACK_F[c // _NPUSH] * (hi - lo)
            push = push0 / float(1 << (2 * (c % _NPUSH)))
            x = w.cx[k] + lam * dx + push * nx
            y = w.cy[k] + lam * dy + push * ny
            if not (_inside(rect, t % n, x, y, _MARGIN) and _sees(x, y, t, xx, xy, tx, sg)):
                continue
            if k == 1:
                if _sees(sx, sy, t0, x, y, t, sg):
                    return x, y, t, pi * _NCAND + c
            elif _seen_from(x, y, t, k - 1, w, sg, reach):
                return x, y, t, pi * _NCAND + c
    return 0.0, 0.0, 0, -1


@leaf_njit(cache=True)
def _crossing(w: Windows, k: int, p: int) -> tuple[float, float, float, float]:  # pragma: no cover
    # The ends l, r of part p of window k, ordered as lines crossing it from its reachable side see them:
    # l on their left (for a window with the reachable side on its left, the far end).
    c0x = w.cx[k] + w.l0[p] * w.dx[k]
    c0y = w.cy[k] + w.l0[p] * w.dy[k]
    c1x = w.cx[k] + w.l1[p] * w.dx[k]
    c1y = w.cy[k] + w.l1[p] * w.dy[k]
    if w.side[k] > 0.0:
        return c1x, c1y, c0x, c0y
    return c0x, c0y, c1x, c1y


@leaf_njit(cache=True)
def _best_part(
    k: int,
    w: Windows,
    tend: int,
    sg: np.ndarray,
    extra: float,
    reach: np.ndarray,
    gdir: np.ndarray,
    bufa: np.ndarray,
    bufb: np.ndarray,
) -> tuple[int, float, float, float, float, int, int, float, float, float, float, float]:  # pragma: no cover
    # The part of window k whose lines reach farthest (ties: the one that misses the next gate by least),
    # with what :func:`_pre_reach` says of it (gates shrunk by ``extra`` more): the last piece (−1: none),
    # the extreme line, the side, the part, the next window's line and its room.
    n = sg.shape[0]
    jbest = -1
    bmiss = 1e300
    best = (0.0, 0.0, 0.0, 0.0, 0, -1, 0.0, 0.0, 0.0, 0.0, 0.0)
    for p in range(w.off[k], w.off[k + 1]):
        t = w.t[p]
        if t + reach[t % n] < jbest:
            continue  # no line from piece t gets as far (the reach table is exact)
        lx, ly, rx_, ry_ = _crossing(w, k, p)
        jj, sd, ex, ey, edx, edy, miss, ix_, iy_, idx_, idy_, room = _pre_reach(
            lx, ly, rx_, ry_, t, tend, sg, extra, reach, gdir, bufa, bufb
        )
        if sd < 0:
            continue
        if jj > jbest or (jj == jbest and miss < bmiss):
            jbest = jj
            bmiss = miss
            best = (ex, ey, edx, edy, sd, p, ix_, iy_, idx_, idy_, room)
    ex, ey, edx, edy, sd, p, ix_, iy_, idx_, idy_, room = best
    return jbest, ex, ey, edx, edy, sd, p, ix_, iy_, idx_, idy_, room


@njit(cache=True)
def _forward(
    sx: float,
    sy: float,
    t0: int,
    rect: np.ndarray,
    sg: np.ndarray,
    room: float,
    reach: np.ndarray,
    gdir: np.ndarray,
    limit: int,
) -> tuple[int, float, float, int, Windows]:  # pragma: no cover
    # The windows W_1, W_2, … from s (in piece t0) until one sees s one lap later (or needs one more
    # vertex, returned as last_x, last_y, last_t with last_t >= 0). Returns kend (−1: failed), that extra
    # vertex, and the windows (:class:`Windows`). sg: the shrunk gates; a step whose next window's line
    # could not move sideways by ``room`` among its lines is taken again with the gates shrunk by
    # _ROOMY_EXTRA more.
    n = rect.shape[0]
    tend = t0 + n
    # windows: start point, unit direction, reachable side, and their parts (piece, λ interval)
    wcap = limit + 2
    pcap = max(16 * wcap, tend - t0) + 64  # parts; grown below when a window runs through more pieces
    w = Windows(
        np.empty(wcap, np.float64),
        np.empty(wcap, np.float64),
        np.empty(wcap, np.float64),
        np.empty(wcap, np.float64),
        np.empty(wcap, np.float64),
        np.zeros(wcap + 1, np.int64),
        np.empty(pcap, np.int64),
        np.empty(pcap, np.float64),
        np.empty(pcap, np.float64),
    )
    bufa = np.empty((3, _PCAP), np.float64)
    bufb = np.empty((3, _PCAP), np.float64)
    # W_1, from the cone of s
    j, rx, ry, side, gc = _cone(sx, sy, t0, tend, sg)
    if side == 0:
        return -1, 0.0, 0.0, -1, w
    dl = np.hypot(rx, ry)
    w.cx[1] = sx + rx
    w.cy[1] = sy + ry
    w.dx[1] = rx / dl
    w.dy[1] = ry / dl
    w.side[1] = 1.0 if side == 1 else -1.0
    w.off[1] = 0
    w.off[2] = _window_parts(w.cx[1], w.cy[1], w.dx[1], w.dy[1], j, gc - 1, rect, w.t, w.l0, w.l1, 0)
    if w.off[2] == 0:
        return -1, 0.0, 0.0, -1, w
    # jumps[t - t0]: the fewest windows from piece t to the end piece (greedy longest jumps, exact for the
    # reach table): links still needed from a window whose parts lie in pieces up to t, at least
    jumps = np.zeros(n + 1, np.int64)
    for t in range(tend - 1, t0 - 1, -1):
        e = t + reach[t % n]
        jumps[t - t0] = 1 + (jumps[e - t0] if e < tend else 0)
    last_x = 0.0
    last_y = 0.0
    last_t = -1
    kend = -1
    for k in range(1, limit - 1):
        # a ring through s has k + 1 vertices up to W_k (in pieces up to its first part's) and needs at
        # least jumps more links, the last of them ending on s: give up when that is no gain
        jw = w.t[w.off[k]]
        if jw < tend and k + jumps[jw - t0] >= limit:
            break
        # link k + 1 from the parts of W_k; when its lines are a sliver (the next window's line could not
        # move sideways by ``room`` without leaving them), again with the roomier gates
        jbest, bx_, by_, bdx, bdy, bside, bpart, bix, biy, bidx, bidy, broom = _best_part(
            k, w, tend, sg, 0.0, reach, gdir, bufa, bufb
        )
        extra = 0.0
        if bside > 0 and broom < room:
            alt = _best_part(k, w, tend, sg, _ROOMY_EXTRA, reach, gdir, bufa, bufb)
            if alt[0] >= 0:
                jbest, bx_, by_, bdx, bdy, bside, bpart, bix, biy, bidx, bidy, broom = alt
                extra = _ROOMY_EXTRA
        if jbest < 0:
            break
        if jbest >= tend:
            # s one lap later is weakly visible from W_k, or one more vertex is needed
            kend = k
            _x, _y, _t, cdir = _back_onto(sx, sy, tend, k, 0, sx, sy, t0, w, sg, rect, reach)
            direct = cdir >= 0
            if not direct and bside == 0:
                # a point on the central line of the best part's lines, in one of the last pieces, that
                # sees s: the ring then has one more vertex
                for t in range(tend - 1, max(w.t[bpart], tend - 8), -1):
                    lo, hi = _span(bx_, by_, bdx, bdy, rect, t % n)
                    if hi - lo <= 1e-6:
                        continue
                    lam = 0.5 * (lo + hi)
                    x = bx_ + lam * bdx
                    y = by_ + lam * bdy
                    if _inside(rect, t % n, x, y, _MARGIN) and _sees(x, y, t, sx, sy, tend, sg):
                        last_x = x
                        last_y = y
                        last_t = t
                        break
            break
        # W_{k+1}: the extreme line from its last contact with the inside of the turn
        t = w.t[bpart]
        lx, ly, rx_, ry_ = _crossing(w, k, bpart)
        lam = _contact(bx_, by_, bdx, bdy, bside, lx, ly, rx_, ry_, t, jbest, sg, extra)
        if lam < -1e299:
            break
        # the window runs on the inset line, from the point nearest the contact
        cx_ = bx_ + lam * bdx
        cy_ = by_ + lam * bdy
        lam2 = (cx_ - bix) * bidx + (cy_ - biy) * bidy
        w.cx[k + 1] = bix + lam2 * bidx
        w.cy[k + 1] = biy + lam2 * bidy
        w.dx[k + 1] = bidx
        w.dy[k + 1] = bidy
        bdx = bidx
        bdy = bidy
        w.side[k + 1] = 1.0 if bside == 1 else -1.0
        e = w.off[k + 1]
        need = e + jbest - t + 2  # at most one part per piece the window runs through
        if need > w.t.size:
            cap = max(2 * w.t.size, need + 64)
            w = Windows(
                w.cx,
                w.cy,
                w.dx,
                w.dy,
                w.side,
                w.off,
                _grow1(w.t, e, cap),
                _grow1(w.l0, e, cap),
                _grow1(w.l1, e, cap),
            )
        w.off[k + 2] = _window_parts(w.cx[k + 1], w.cy[k + 1], bdx, bdy, jbest, t, rect, w.t, w.l0, w.l1, e)
        if w.off[k + 2] == e:
            break
    return kend, last_x, last_y, last_t, w


@njit(cache=True)
def minlink_from(
    sx: float,
    sy: float,
    t0: int,
    rect: np.ndarray,
    sg: np.ndarray,
    room: float,
    reach: np.ndarray,
    gdir: np.ndarray,
    limit: int,
) -> tuple[np.ndarray, np.ndarray, int]:  # pragma: no cover
    """A ring of fewest vertices through s (Q-units, in piece t0), by Suri's windows (module docstring).

    ``sg`` are the gates shrunk by :data:`_GATE_EPS` (:func:`shrunk_gates`). The forward pass takes a step
    again with the gates shrunk by :data:`_ROOMY_EXTRA` more when the next window's line could not move
    sideways by ``room`` Q-units among the lines of its step (0: never), so that the backward pass finds
    room on every window.

    Returns the vertices (m, 2), their pieces (unwrapped from t0, increasing) and a status: 0 found, 1 the
    windows need ``limit`` vertices or more (or a float step of the forward pass failed), 2 the windows
    promise fewer but the backward pass found no vertices (another start may succeed).
    """
    n = rect.shape[0]
    tend = t0 + n
    kend, last_x, last_y, last_t, w = _forward(sx, sy, t0, rect, sg, room, reach, gdir, limit)
    if kend < 0:
        return np.empty((0, 2), np.float64), np.empty(0, np.int64), 1
    # backwards: the target, then a vertex on each window W_kend … W_1 that sees the one after it
    extra = 1 if last_t >= 0 else 0
    m = kend + 1 + extra
    if m >= limit:
        return np.empty((0, 2), np.float64), np.empty(0, np.int64), 1
    ox = np.empty((m, 2), np.float64)
    ot = np.empty(m, np.int64)
    ox[0, 0] = sx
    ox[0, 1] = sy
    ot[0] = t0
    xx = sx
    xy = sy
    tx = tend
    if extra == 1:
        ox[m - 1, 0] = last_x
        ox[m - 1, 1] = last_y
        ot[m - 1] = last_t
        xx = last_x
        xy = last_y
        tx = last_t
    # depth first from W_kend down to W_1, backtracking to the next candidate of the step before when a
    # step finds none (within a budget of candidate searches)
    cand = np.zeros(kend + 2, np.int64)
    k = kend
    budget = kend + kend // 4 + 8
    while k >= 1:
        if k < kend:
            xx = ox[k + 1, 0]
            xy = ox[k + 1, 1]
            tx = ot[k + 1]
        elif extra == 1:
            xx = last_x
            xy = last_y
            tx = last_t
        else:
            xx = sx
            xy = sy
            tx = tend
        budget -= 1
        fx, fy, ft, c = _back_onto(xx, xy, tx, k, cand[k], sx, sy, t0, w, sg, rect, reach)
        if c < 0:
            if k == kend or budget <= 0:
                return np.empty((0, 2), np.float64), np.empty(0, np.int64), 2
            k += 1
            cand[k] += 1
            continue
        cand[k] = c
        ox[k, 0] = fx
        ox[k, 1] = fy
        ot[k] = ft
        k -= 1
        if k >= 1:
            cand[k] = 0
    xx = ox[1, 0]
    xy = ox[1, 1]
    tx = ot[1]
    if not _sees(sx, sy, t0, xx, xy, tx, sg):
        return np.empty((0, 2), np.float64), np.empty(0, np.int64), 2
    return ox, ot, 0


@njit(cache=True)
def minlink_ring(
    ix: np.ndarray,
    iy: np.ndarray,
    vt: np.ndarray,
    vs: np.ndarray,
    vl: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    reach: np.ndarray,
    kmax: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """A ring of the corridor with fewer vertices than the given verified ring, or the given ring itself.

    Parameters
    ----------
    ix, iy, vt, vs, vl : ndarray of int64
        The ring: vertices in integer coordinates scaled by 2^kmax (Q-units), their pieces (unwrapped,
        non-decreasing, within one lap), sources and edge windows (as in :func:`._merge.merge_ring`).
    rect, gp, gq, gdir, reach : ndarray
        The corridor: pieces, gate ends and directions, and the reach table of its windows.
    kmax : int
        The ring's snapping depth.

    Returns
    -------
    tuple of ndarray
        The ring of :func:`minlink_from` through vertex 0 of the input (then through vertices m/3 and 2m/3
        while the windows promise fewer vertices but the backward pass finds none), snapped
        (:func:`._check.snap_ring`) and verified exactly (:func:`._check.verify_ring`), with sources
        ``SRC_LINES`` and no edge windows; the input arrays themselves when no such ring snaps, verifies
        and has fewer vertices. Exactness never depends on this search.
    """
    n = gdir.size
    m = ix.size
    sc = 1 << kmax
    fsc = float(sc)
    sg = shrunk_gates(gp, gq)
    # other starts: only on rings small enough for them to be cheap (on the benchmark images every vertex
    # but one was gained from the first start, and on the 1024² blob three failing starts cost 14 ms)
    starts = _STARTS if n <= _MANY_STARTS_PIECES else 1
    for si in range(starts):
        i0 = (si * m) // starts
        sx = ix[i0] / fsc
        sy = iy[i0] / fsc
        fv, ft, status = minlink_from(sx, sy, vt[i0] % n, rect, sg, _ROOM, reach, gdir, m)
        if status == 2:
            # the windows promised more than the backward pass could place: again, with more room
            fv, ft, status = minlink_from(sx, sy, vt[i0] % n, rect, sg, _ROOM_AGAIN, reach, gdir, m)
        if status == 1:
            break  # the windows promise nothing from here: other starts rarely do better
        if status != 0 or ft.size < 3:
            continue
        mm = ft.size
        fx = np.empty(mm, np.float64)
        fy = np.empty(mm, np.float64)
        for i in range(mm):
            fx[i] = fv[i, 0]
            fy[i] = fv[i, 1]
        ox = np.empty(mm, np.int64)
        oy = np.empty(mm, np.int64)
        bad = np.zeros(mm, np.bool_)
        snap_ring(fx, fy, ft, rect, gp, gq, gdir, kmax, ox, oy, bad)
        good = True
        for i in range(mm):
            if bad[i]:
                good = False
        if good and verify_ring(ox, oy, ft, rect, gp, gq, gdir, sc, bad):
            return ox, oy, ft.copy(), np.full(mm, SRC_LINES, np.int64), np.full(mm, -1, np.int64)
    return ix, iy, vt, vs, vl
