"""Phase 4 of R, last step: every edge onto the simplest line its pieces allow (same vertex count)."""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import leaf_njit, njit
from mrm.geometry.reconstruct._base import _DX, _DY
from mrm.geometry.reconstruct._check import (
    _in_piece,
    _orient,
    edge_ok,
    gate_rays,
    rays_admit,
    segments_meet,
    verify_ring,
)

# ============================================================================================ straightening


@leaf_njit(cache=True)
def _window_fit(
    dx: int, dy: int, gp: np.ndarray, gq: np.ndarray, g0: int, g1: int, n: int
) -> tuple[int, int, int, int]:  # pragma: no cover
    # Lines dx·Y − dy·X = C (Q-units) crossing gates g0 … g1 (unwrapped) strictly inside and in order: every
    # gate's left end strictly left, its right end strictly right (order then follows, the pieces between
    # the gates being convex), i.e. lo < C < hi. Returns lo, hi and the gates that set them (it stops at the
    # first gate that leaves no offset: those two gates already show it).
    lo = -(1 << 62)
    hi = 1 << 62
    glo = g0
    ghi = g0
    for k in range(g0, g1 + 1):
        g = k % n
        cq = dx * gq[g, 1] - dy * gq[g, 0]
        cp = dx * gp[g, 1] - dy * gp[g, 0]
        if cq > lo:
            lo = cq
            glo = g
        if cp < hi:
            hi = cp
            ghi = g
        if lo >= hi:
            break
    return lo, hi, glo, ghi


@leaf_njit(cache=True)
def simplest_line(
    gp: np.ndarray, gq: np.ndarray, g0: int, g1: int, n: int, ex: int, ey: int, depth: int
) -> tuple[bool, int, int, int]:  # pragma: no cover
    """The simplest line crossing gates g0 … g1 (unwrapped) strictly inside and in order.

    Simplest: its primitive direction (dx, dy) has the least |dx| + |dy| (axis-parallel when allowed, then
    45°, …: the Stern–Brocot search of the open interval of slopes, exact), with the offset centred in the
    open interval of offsets. (ex, ey) is a direction known to be allowed (the current edge's): among
    allowed axis directions the one nearest it is taken; otherwise the quadrant of (ex, ey) holds every
    allowed direction. Returns (found, dx, dy, c2) for the line dx·Y − dy·X = c2 / 2 in Q-units; not found
    beyond ``depth`` Stern–Brocot steps.
    """
    # axis directions E, N, W, S: their offset intervals (as _window_fit's) from one pass over the gates
    pxmin = pymin = qxmin = qymin = 1 << 62
    pxmax = pymax = qxmax = qymax = -(1 << 62)
    for k in range(g0, g1 + 1):
        g = k % n
        pxmin = min(pxmin, gp[g, 0])
        pxmax = max(pxmax, gp[g, 0])
        pymin = min(pymin, gp[g, 1])
        pymax = max(pymax, gp[g, 1])
        qxmin = min(qxmin, gq[g, 0])
        qxmax = max(qxmax, gq[g, 0])
        qymin = min(qymin, gq[g, 1])
        qymax = max(qymax, gq[g, 1])
    best = -1
    bdot = 0
    blo = 0
    bhi = 0
    for a in range(4):
        # the line dx·Y − dy·X = C of direction a: C = Y (E), −X (N), −Y (W), X (S)
        if a == 0:
            lo, hi = qymax, pymin
        elif a == 1:
            lo, hi = -qxmin, -pxmax
        elif a == 2:
            lo, hi = -qymin, -pymax
        else:
            lo, hi = qxmax, pxmin
        if lo < hi:
            dot = _DX[a] * ex + _DY[a] * ey
            if best < 0 or dot > bdot:
                best = a
                bdot = dot
                blo = lo
                bhi = hi
    if best >= 0:
        return True, _DX[best], _DY[best], blo + bhi
    if ex == 0 or ey == 0:
        return False, 0, 0, 0
    sx = 1 if ex > 0 else -1
    sy = 1 if ey > 0 else -1
    # d = u (sx, 0) + w (0, sy); Stern–Brocot on w / u between 0/1 (E1) and 1/0 (E2)
    lu = 1
    lw = 0
    ru = 0
    rw = 1
    for _ in range(depth):
        u = lu + ru
        w = lw + rw
        dx = u * sx
        dy = w * sy
        lo, hi, glo, ghi = _window_fit(dx, dy, gp, gq, g0, g1, n)
        if lo < hi:
            return True, dx, dy, lo + hi
        # infeasible: cross(d, v) >= 0 for v = q[glo] − p[ghi], and every allowed d' has cross(d', v) < 0,
        # a sign that changes at most once along the quadrant: go towards the end where it is negative
        vy = gq[glo, 1] - gp[ghi, 1]
        if sx * vy < 0:  # cross((sx, 0), v) < 0: towards E1 (smaller w / u)
            ru = u
            rw = w
        else:
            lu = u
            lw = w
    return False, 0, 0, 0


@leaf_njit(cache=True)
def _vget(
    x: np.ndarray, y: np.ndarray, t: np.ndarray, m: int, n: int, j: int
) -> tuple[int, int, int]:  # pragma: no cover
    # Vertex j of the ring, any integer j: its coordinates and its piece unwrapped by whole laps.
    b = j % m
    return x[b], y[b], t[b] + n * ((j - b) // m)


@leaf_njit(cache=True)
def _edge_line(
    x: np.ndarray,
    y: np.ndarray,
    t: np.ndarray,
    isnew: np.ndarray,
    nl: np.ndarray,
    m: int,
    n: int,
    j: int,
) -> tuple[int, int, int]:  # pragma: no cover
    # The line dx·Y − dy·X = C (scaled units) of edge j: its new line, or the line through its vertices.
    b = j % m
    if isnew[b]:
        return nl[b, 0], nl[b, 1], nl[b, 2]
    ax, ay, _ta = _vget(x, y, t, m, n, j)
    bx, by, _tb = _vget(x, y, t, m, n, j + 1)
    dx = bx - ax
    dy = by - ay
    return dx, dy, dx * ay - dy * ax


@njit(cache=True)
def _meet_int(
    d1x: int, d1y: int, c1: int, d2x: int, d2y: int, c2: int
) -> tuple[float, float, bool]:  # pragma: no cover
    # Intersection of dkx·Y − dky·X = ck (k = 1, 2), in floats (exact when both lines are simple).
    den = float(d1x * d2y - d1y * d2x)
    if den == 0.0:
        return 0.0, 0.0, False
    fc1 = float(c1)
    fc2 = float(c2)
    return (fc1 * d2x - d1x * fc2) / den, (fc1 * d2y - d1y * fc2) / den, True


@leaf_njit(cache=True)
def _piece_of(
    fx: float, fy: float, tlo: int, thi: int, hint: int, rect: np.ndarray, n: int, sc: int
) -> int:  # pragma: no cover
    # The first piece of tlo … thi holding (fx, fy) (scaled units), thi + 1 if none (nor for far points).
    # A float test: only a shortcut, the grid points :func:`_place` takes are checked exactly.
    if abs(fx) > 4.0e9 or abs(fy) > 4.0e9:
        return thi + 1
    if thi - tlo < n:
        # Within one lap the pieces are disjoint open rectangles, so at most one holds the point: searched
        # outwards from hint (the piece of the vertex the point replaces, where it nearly always lies), it
        # is found in a few steps instead of a scan over the pieces of two or three edges from tlo.
        h = min(max(hint, tlo), thi)
        for d in range(thi - tlo + 1):
            up = h + d
            dn = h - 1 - d
            if up > thi and dn < tlo:
                break
            if up <= thi:
                r = up % n
                if rect[r, 0] * sc < fx < rect[r, 1] * sc and rect[r, 2] * sc < fy < rect[r, 3] * sc:
                    return up
            if dn >= tlo:
                r = dn % n
                if rect[r, 0] * sc < fx < rect[r, 1] * sc and rect[r, 2] * sc < fy < rect[r, 3] * sc:
                    return dn
        return thi + 1
    t = tlo
    while t <= thi:
        r = t % n
        if rect[r, 0] * sc < fx < rect[r, 1] * sc and rect[r, 2] * sc < fy < rect[r, 3] * sc:
            break
        t += 1
    return t


@leaf_njit(cache=True)
def _place(
    fx: float,
    fy: float,
    tlo: int,
    thi: int,
    hint: int,
    ax: int,
    ay: int,
    ta: int,
    check_prev: bool,
    check_next: bool,
    bx: int,
    by: int,
    tb: int,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: int,
) -> tuple[int, int, int, bool]:  # pragma: no cover
    # A vertex near (fx, fy) (scaled units): the point itself when it is on the grid (an exact meeting
    # point stays exact), else the coarsest dyadic grid point; inside a piece of tlo … thi (hint: the piece
    # of the vertex it replaces, where :func:`_piece_of` looks first), the edge from (ax, ay) valid and, with
    # check_next, the edge to (bx, by) too.
    n = gdir.size
    sc = 1 << kmax
    t = _piece_of(fx, fy, tlo, thi, hint, rect, n, sc)
    if t > thi:
        return 0, 0, 0, False
    # A quick necessary test before the exact edge checks (which cost the length of the edge each): the
    # edge a → x crosses every gate ta+1 … t strictly inside, so x − a lies strictly clockwise of every
    # a→P and counter-clockwise of every a→Q, hence of the tightest two (exact integers); likewise x seen
    # from b through the gates t+1 … tb. When the exact check would pass these tests pass, so the result is
    # the one of the exact checks alone.
    alx, aly, arx, ary, fa = gate_rays(ax, ay, ta, t if check_prev else ta, True, gp, gq, sc)
    blx, bly, brx, bry, fb = gate_rays(bx, by, t, tb if check_next else t, False, gp, gq, sc)
    for k in range(-1, kmax + 1):
        if k < 0:
            if fx != np.floor(fx) or fy != np.floor(fy):
                continue
            x = int(fx)
            y = int(fy)
        else:
            mul = 1 << (kmax - k)
            x = int(np.round(fx / mul)) * mul
            y = int(np.round(fy / mul)) * mul
        if not _in_piece(rect, t % n, x, y, sc):
            continue
        if fa and not rays_admit(ax, ay, alx, aly, arx, ary, True, x, y):
            continue
        if fb and not rays_admit(bx, by, blx, bly, brx, bry, False, x, y):
            continue
        if check_prev and not edge_ok(ax, ay, ta, x, y, t, gp, gq, gdir, sc):
            continue
        if check_next and not edge_ok(x, y, t, bx, by, tb, gp, gq, gdir, sc):
            continue
        return x, y, t, True
    return 0, 0, 0, False


@leaf_njit(cache=True)
def _local_ok(
    x: np.ndarray, y: np.ndarray, t: np.ndarray, m: int, n: int, i: int
) -> bool:  # pragma: no cover
    # After vertices i and i+1 moved: no fold at vertices i−1 … i+2, and (as verify_ring) no two edges
    # meeting around a piece that holds two or more of the vertices i−1 … i+2.
    for j in range(i - 1, i + 3):
        ax, ay, _ta = _vget(x, y, t, m, n, j - 1)
        bx, by, _tb = _vget(x, y, t, m, n, j)
        cx, cy, _tc = _vget(x, y, t, m, n, j + 1)
        if _orient(ax, ay, bx, by, cx, cy) == 0 and (bx - ax) * (cx - bx) + (by - ay) * (cy - by) <= 0:
            return False
    for j in range(i - 1, i + 3):
        _x, _y, tj = _vget(x, y, t, m, n, j)
        lo = j
        while lo > j - m + 1 and _vget(x, y, t, m, n, lo - 1)[2] == tj:
            lo -= 1
        hi = j
        while hi < lo + m - 1 and _vget(x, y, t, m, n, hi + 1)[2] == tj:
            hi += 1
        if hi == lo:
            continue
        # edges lo−1 … hi (edge e joins vertices e and e+1)
        for p in range(lo - 1, hi + 1):
            pax, pay, _a = _vget(x, y, t, m, n, p)
            pbx, pby, _b = _vget(x, y, t, m, n, p + 1)
            for q in range(p + 2, hi + 1):
                if (q + 1 - p) % m == 0:
                    continue
                qax, qay, _c = _vget(x, y, t, m, n, q)
                qbx, qby, _d = _vget(x, y, t, m, n, q + 1)
                if segments_meet(pax, pay, pbx, pby, qax, qay, qbx, qby):
                    return False
    return True


@leaf_njit(cache=True)
def _simplest_edge_line(
    x: np.ndarray,
    y: np.ndarray,
    t: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    n: int,
    sc: int,
    vmin: int,
    isnew: np.ndarray,
    nl: np.ndarray,
    i: int,
) -> None:  # pragma: no cover
    # The simplest line of edge i of the ring (windows as in straighten_ring, from variant vmin on), in
    # nl[i] with isnew[i] set; isnew[i] cleared when no window has one.
    m = x.size
    xb, yb, tb = _vget(x, y, t, m, n, i)
    xc, yc, tc = _vget(x, y, t, m, n, i + 1)
    isnew[i] = False
    for variant in range(vmin, 4):
        g0 = tb + (2 if variant <= 1 else 1)
        g1 = tc - (1 if variant % 2 == 0 else 0)
        if g1 < g0:
            continue
        okl, dx, dy, c2 = simplest_line(gp, gq, g0, g1, n, xc - xb, yc - yb, 4 * (g1 - g0) + 64)
        if okl:
            isnew[i] = True
            nl[i, 0] = dx
            nl[i, 1] = dy
            nl[i, 2] = c2 * (sc // 2)
            break


@njit(cache=True)
def _ring_attempt(
    x: np.ndarray,
    y: np.ndarray,
    t: np.ndarray,
    vmin: int,
    isnew: np.ndarray,
    nl: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, bool]:  # pragma: no cover
    # Every edge on its simplest line (variants from vmin on, :func:`_simplest_edge_line`; the current edge
    # where there is none) and every vertex where the lines of its two edges meet, placed between the
    # pieces of its neighbours; the ring verified exactly. Lines are found as the vertices need them, so a
    # failing attempt (most of them) stops early; isnew / nl then hold only the edges seen so far.
    n = gdir.size
    m = x.size
    sc = 1 << kmax
    ox = np.empty(m, np.int64)
    oy = np.empty(m, np.int64)
    ot = np.empty(m, np.int64)
    _simplest_edge_line(x, y, t, gp, gq, n, sc, vmin, isnew, nl, m - 1)
    for i in range(m):
        if i < m - 1:
            _simplest_edge_line(x, y, t, gp, gq, n, sc, vmin, isnew, nl, i)
        pdx, pdy, pc = _edge_line(x, y, t, isnew, nl, m, n, i - 1)
        qdx, qdy, qc = _edge_line(x, y, t, isnew, nl, m, n, i)
        fx, fy, okm = _meet_int(pdx, pdy, pc, qdx, qdy, qc)
        if not okm:
            return ox, oy, ot, False
        _xa, _ya, ta = _vget(x, y, t, m, n, i - 1)
        _xb, _yb, tb = _vget(x, y, t, m, n, i)
        _xc, _yc, tc = _vget(x, y, t, m, n, i + 1)
        if i == 0:
            nx, ny, nt, ok = _place(
                fx, fy, ta, tc, tb, 0, 0, 0, False, False, 0, 0, 0, rect, gp, gq, gdir, kmax
            )
        elif i < m - 1:
            nx, ny, nt, ok = _place(
                fx,
                fy,
                ot[i - 1],
                tc,
                tb,
                ox[i - 1],
                oy[i - 1],
                ot[i - 1],
                True,
                False,
                0,
                0,
                0,
                rect,
                gp,
                gq,
                gdir,
                kmax,
            )
        else:
            nx, ny, nt, ok = _place(
                fx,
                fy,
                ot[i - 1],
                min(tc, ot[0] + n),
                tb,
                ox[i - 1],
                oy[i - 1],
                ot[i - 1],
                True,
                True,
                ox[0],
                oy[0],
                ot[0] + n,
                rect,
                gp,
                gq,
                gdir,
                kmax,
            )
        if not ok:
            return ox, oy, ot, False
        ox[i] = nx
        oy[i] = ny
        ot[i] = nt
    base = (ot[0] // n) * n
    for i in range(m):
        ot[i] -= base
    bad = np.zeros(m, np.bool_)
    return ox, oy, ot, verify_ring(ox, oy, ot, rect, gp, gq, gdir, 1 << kmax, bad)


@njit(cache=True)
def straighten_ring(
    ix: np.ndarray,
    iy: np.ndarray,
    vt: np.ndarray,
    vs: np.ndarray,
    vl: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    kmax: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """Put each edge of a verified ring on the simplest line its pieces allow; same vertex count.

    Edge by edge: the window of pieces the edge crosses (without its end pieces first, where the vertices
    may move, then with them) gives the simplest line (:func:`simplest_line`); the edge's two vertices move
    to where that line meets its neighbours' lines, exact when on the grid, else snapped to the coarsest
    dyadic grid that keeps the constraints; the move is kept when both vertices lie in pieces of the
    corridor, in order, and every edge they touch crosses its gates (exact checks). The ring is returned
    unchanged if the result fails :func:`verify_ring`.
    """
    n = gdir.size
    m = ix.size
    if m < 3 or n < 2:
        return ix, iy, vt, vs, vl
    sc = 1 << kmax
    x = ix.copy()
    y = iy.copy()
    t = vt.copy()
    ln = vl.copy()
    isnew = np.zeros(m, np.bool_)
    nl = np.zeros((m, 3), np.int64)
    changed = False
    # the whole ring at once first (neighbouring edges often have to change together, e.g. at a corner)
    for vmin in (0, 3):
        rx, ry, rt, okr = _ring_attempt(x, y, t, vmin, isnew, nl, rect, gp, gq, gdir, kmax)
        if okr:
            x = rx
            y = ry
            t = rt
            for i in range(m):
                if isnew[i]:
                    ln[i] = -1
            changed = True
            break
    if not changed:
        for i in range(m):
            isnew[i] = False
    # then edge by edge, twice round (an edge may move once its neighbours have). A try depends only on
    # vertices i−1 … i+2 and the lines of edges i−1, i+1, which change only with those vertices: an edge
    # that failed is tried again only if one of them moved since (the same inputs would fail the same way).
    moved = np.zeros(m, np.int64)  # times each vertex moved
    tried = np.full(m, -1, np.int64)  # moves around edge i when it last failed
    # the lines (dx, dy, offset) already tried for the current edge: a try depends on nothing else, so a
    # line a second window gives again fails again (on the 1024² blob 38 % of the tries were such repeats)
    seen = np.empty((12, 3), np.int64)
    for it in range(2 * m):
        i = it % m
        if isnew[i]:
            continue
        around = moved[(i - 1) % m] + moved[i] + moved[(i + 1) % m] + moved[(i + 2) % m]
        if tried[i] == around:
            continue
        xa, ya, ta = _vget(x, y, t, m, n, i - 1)
        xb, yb, tb = _vget(x, y, t, m, n, i)
        xc, yc, tc = _vget(x, y, t, m, n, i + 1)
        xd, yd, td = _vget(x, y, t, m, n, i + 2)
        span = tc - tb
        if span < 1:
            continue
        pdx, pdy, pc = _edge_line(x, y, t, isnew, nl, m, n, i - 1)
        qdx, qdy, qc = _edge_line(x, y, t, isnew, nl, m, n, i + 1)
        dx = 0
        dy = 0
        c2 = 0
        okl = False
        nseen = 0
        for trial in range(12):
            # gates of the window: end pieces left out (0), only the first (1), only the last (2), none (3);
            # the offset at the middle of the allowed interval, then at its quarters (when two centred
            # lines meet on a pixel side)
            variant = trial // 3
            frac = trial % 3
            g0 = tb + (2 if variant <= 1 else 1)
            g1 = tc - (1 if variant % 2 == 0 else 0)
            if g1 < g0:
                continue
            if frac == 0:
                okl, dx, dy, c2 = simplest_line(gp, gq, g0, g1, n, xc - xb, yc - yb, 4 * (g1 - g0) + 64)
            if not okl:
                continue
            if frac == 0:
                cc = c2 * (sc // 2)
            else:
                lo, hi, _gl, _gh = _window_fit(dx, dy, gp, gq, g0, g1, n)
                cc = (3 * lo + hi if frac == 1 else lo + 3 * hi) * (sc // 4)
            again = False
            for j in range(nseen):
                if seen[j, 0] == dx and seen[j, 1] == dy and seen[j, 2] == cc:
                    again = True
                    break
            if again:
                continue
            seen[nseen, 0] = dx
            seen[nseen, 1] = dy
            seen[nseen, 2] = cc
            nseen += 1
            f1x, f1y, ok1 = _meet_int(pdx, pdy, pc, dx, dy, cc)
            f2x, f2y, ok2 = _meet_int(dx, dy, cc, qdx, qdy, qc)
            if not (ok1 and ok2):
                continue
            # the second vertex is placed in a piece of (first's piece ≥ ta) … td: none there, no try
            if _piece_of(f2x, f2y, ta, td, tc, rect, n, sc) > td:
                continue
            nbx, nby, nbt, okb = _place(
                f1x, f1y, ta, tc, tb, xa, ya, ta, True, False, 0, 0, 0, rect, gp, gq, gdir, kmax
            )
            if not okb:
                continue
            ncx, ncy, nct, okc = _place(
                f2x, f2y, nbt, td, tc, nbx, nby, nbt, True, True, xd, yd, td, rect, gp, gq, gdir, kmax
            )
            if not okc:
                continue
            ob = i % m
            oc = (i + 1) % m
            sbx, sby, sbt = x[ob], y[ob], t[ob]
            scx, scy, sct = x[oc], y[oc], t[oc]
            x[ob] = nbx
            y[ob] = nby
            t[ob] = nbt - n * ((i - ob) // m)
            x[oc] = ncx
            y[oc] = ncy
            t[oc] = nct - n * ((i + 1 - oc) // m)
            if _local_ok(x, y, t, m, n, i):
                isnew[ob] = True
                nl[ob, 0] = dx
                nl[ob, 1] = dy
                nl[ob, 2] = cc
                ln[ob] = -1
                moved[ob] += 1
                moved[oc] += 1
                changed = True
                break
            x[ob], y[ob], t[ob] = sbx, sby, sbt
            x[oc], y[oc], t[oc] = scx, scy, sct
        if not isnew[i]:
            tried[i] = around
    if not changed:
        return ix, iy, vt, vs, vl
    base = (t[0] // n) * n
    for i in range(m):
        t[i] -= base
    bad = np.zeros(m, np.bool_)
    if verify_ring(x, y, t, rect, gp, gq, gdir, sc, bad):
        return x, y, t, vs, ln
    return ix, iy, vt, vs, vl
