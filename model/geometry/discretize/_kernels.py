"""Numba kernels of the exact discretization (used by :mod:`mrm.geometry.discretize`).

Every decision reduces to one of two exact questions about float64 data:

* the sign of an orientation-like determinant ``(p1 − p2)(q1 − q2) − (r1 − r2)(s1 − s2)``, where the
  operands are input coordinates and grid numbers (integers, half-integers);
* the standard cell of a coordinate, decided by comparing floats with half-integers (always exact).

Signs are computed with a floating-point filter (Shewchuk's orient2d error bound) and, when the filter
cannot decide, exactly with floating-point expansions (two-sum / two-product, Shewchuk 1997). When the
caller has proved that plain float arithmetic is exact for the whole geometry (``exact=True``, see
:func:`mrm.geometry.discretize.exact.float_predicates_are_exact`), the float result is used as is, including
zero.

The expansion arithmetic is exact as long as no product underflows or overflows; the caller guarantees
this by limiting coordinates to 2^-400 ≤ |v| ≤ 2^51 (or v = 0). Then every input and grid number is a
multiple of 2^-452, so are the two parts of each difference, and every product, product rounding error and
partial sum is a multiple of 2^-904: far above the subnormal range, hence computed without loss.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import njit

BoolMask = npt.NDArray[np.bool_]
Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

_EPS = 2.0**-53
_SPLITTER = 134217729.0  # 2^27 + 1, Dekker's splitter
#: Shewchuk's bound for |det − fl(det)| relative to |fl(l)| + |fl(r)| (orient2d, "ccwerrboundA").
_ORIENT_BOUND = (3.0 + 16.0 * _EPS) * _EPS
#: Bound, relative to |q| + |x|, of the error of x = lx + (j − ly)·slope (six roundings, with slack).
_CROSS_BOUND = 8.0 * _EPS
#: Size of the scratch buffer an exact sign needs (16 products' worth of components, with room to spare).
SCRATCH_SIZE = 40


# -------------------------------------------------------------------------------------- exact signs
@njit(cache=True)
def _two_sum(a: float, b: float) -> tuple[float, float]:
    x = a + b
    bv = x - a
    av = x - bv
    return x, (a - av) + (b - bv)


@njit(cache=True)
def _two_diff(a: float, b: float) -> tuple[float, float]:
    x = a - b
    bv = a - x
    av = x + bv
    return x, (a - av) + (bv - b)


@njit(cache=True)
def _split(a: float) -> tuple[float, float]:
    c = _SPLITTER * a
    hi = c - (c - a)
    return hi, a - hi


@njit(cache=True)
def _two_prod(a: float, b: float) -> tuple[float, float]:
    x = a * b
    ahi, alo = _split(a)
    bhi, blo = _split(b)
    err = x - ahi * bhi
    err -= alo * bhi
    err -= ahi * blo
    return x, alo * blo - err


@njit(cache=True)
def _grow(e: Floats, m: int, b: float) -> int:
    """Add ``b`` to the expansion e[:m] in place (Shewchuk's grow-expansion with zero elimination).

    The expansion stays non-overlapping with components of increasing magnitude, so the sign of its
    value is the sign of its last component.
    """
    q = b
    k = 0
    for i in range(m):
        q, h = _two_sum(q, e[i])
        if h != 0.0:
            e[k] = h
            k += 1
    if q != 0.0:
        e[k] = q
        k += 1
    return k


@njit(cache=True)
def _add_product(e: Floats, m: int, x: float, y: float, sign: float) -> int:
    """Add sign·x·y (exactly) to the expansion e[:m]; return its new length."""
    if x == 0.0 or y == 0.0:
        return m
    p, err = _two_prod(x, y)
    m = _grow(e, m, sign * err)
    return _grow(e, m, sign * p)


@njit(cache=True)
def _det_sign_exact(
    p1: float, p2: float, q1: float, q2: float, r1: float, r2: float, s1: float, s2: float, e: Floats
) -> int:
    a, al = _two_diff(p1, p2)
    b, bl = _two_diff(q1, q2)
    c, cl = _two_diff(r1, r2)
    d, dl = _two_diff(s1, s2)
    m = 0
    m = _add_product(e, m, a, b, 1.0)
    m = _add_product(e, m, a, bl, 1.0)
    m = _add_product(e, m, al, b, 1.0)
    m = _add_product(e, m, al, bl, 1.0)
    m = _add_product(e, m, c, d, -1.0)
    m = _add_product(e, m, c, dl, -1.0)
    m = _add_product(e, m, cl, d, -1.0)
    m = _add_product(e, m, cl, dl, -1.0)
    if m == 0:
        return 0
    return 1 if e[m - 1] > 0.0 else -1


#: Returned by :func:`_det_filter` when the float filter cannot decide.
UNDECIDED = 2


@njit(cache=True)
def _det_filter(
    p1: float, p2: float, q1: float, q2: float, r1: float, r2: float, s1: float, s2: float, exact: bool
) -> int:
    """Sign of (p1 − p2)(q1 − q2) − (r1 − r2)(s1 − s2) when floats can tell, else :data:`UNDECIDED`.

    Scalars only, so that numba inlines it into the hot loops (an array argument would cost a reference
    count round trip per call); the rare undecided cases go to :func:`_det_sign_exact`.
    """
    left = (p1 - p2) * (q1 - q2)
    right = (r1 - r2) * (s1 - s2)
    det = left - right
    if exact:
        return 1 if det > 0.0 else (-1 if det < 0.0 else 0)
    bound = _ORIENT_BOUND * (abs(left) + abs(right))
    if det > bound:
        return 1
    if -det > bound:
        return -1
    if bound == 0.0:
        # Both float products are 0, so a factor of each is a difference of equal floats: exactly 0.
        return 0
    return UNDECIDED


@njit(cache=True)
def det_sign(
    p1: float,
    p2: float,
    q1: float,
    q2: float,
    r1: float,
    r2: float,
    s1: float,
    s2: float,
    exact: bool,
    scratch: Floats,
) -> int:
    """Return the exact sign of (p1 − p2)(q1 − q2) − (r1 − r2)(s1 − s2)."""
    s = _det_filter(p1, p2, q1, q2, r1, r2, s1, s2, exact)
    if s == UNDECIDED:
        s = _det_sign_exact(p1, p2, q1, q2, r1, r2, s1, s2, scratch)
    return s


# -------------------------------------------------------------------------------------------- cells
@njit(cache=True)
def cell(u: float) -> int:
    """Return k with u ∈ (k − ½, k + ½] (exact: k ± ½ are floats, comparisons never round)."""
    k = np.floor(u + 0.5)
    while u > k + 0.5:
        k += 1.0
    while u <= k - 0.5:
        k -= 1.0
    return int(k)


@njit(cache=True)
def _put(mask: BoolMask, x0: int, y0: int, i: int, j: int) -> int:
    """Set pixel (i, j); return 1 if it falls outside the array (a bug upstream), else 0."""
    r = j - y0
    c = i - x0
    # Plain ``and`` chains: numba compiles chained comparisons (0 <= r < n) into much slower code.
    if r >= 0 and c >= 0 and r < mask.shape[0] and c < mask.shape[1]:
        mask[r, c] = True
        return 0
    return 1


@njit(cache=True)
def _put_closed_cells(mask: BoolMask, x0: int, y0: int, u: float, v: float) -> int:
    """Set every pixel whose closed square holds the point (u, v): one, two or four of them."""
    i = cell(u)
    j = cell(v)
    i2 = i + 1 if u == i + 0.5 else i
    j2 = j + 1 if v == j + 0.5 else j
    bad = 0
    for ii in range(i, i2 + 1):
        for jj in range(j, j2 + 1):
            bad += _put(mask, x0, y0, ii, jj)
    return bad


# ----------------------------------------------------------------------------------------- segments
@njit(cache=True)
def _walk(
    mask: BoolMask,
    x0: int,
    y0: int,
    ax: float,
    ay: float,
    bx: float,
    by: float,
    supercover: bool,
    exact: bool,
    scratch: Floats,
) -> int:
    """Discretize the segment a→b into ``mask``: standard model, or supercover if asked.

    Standard: the segment shifted by −τ = (−ε, −ε²) never meets a grid corner and never runs along a grid
    line, so it visits a 4-connected chain of open squares from the cell of a to the cell of b. At pixel
    (i, j), with steps left in both directions, it leaves through the vertical side x = cx when it reaches
    that line first, i.e. when sx·sy·g(c) < 0 with c = (cx, cy) the corner ahead and
    g(c) = f(c) + dy·ε − dx·ε², f(c) = dy·(cx − ax) − dx·(cy − ay). The sign of g is the sign of f(c), or
    of dy when f(c) = 0 (dy ≠ 0 there).

    Supercover adds what the closed squares see beyond the standard chain: the fourth pixel at a corner the
    segment passes through (f(c) = 0), all closed cells of the two end points, and the row or column on
    the other side of a grid line the segment runs along.
    """
    bad = 0
    i = cell(ax)
    j = cell(ay)
    i1 = cell(bx)
    j1 = cell(by)
    sx = 1 if i1 >= i else -1
    sy = 1 if j1 >= j else -1
    nx = abs(i1 - i)
    ny = abs(j1 - j)
    mirror_row = False
    mirror_col = False
    if supercover:
        bad += _put_closed_cells(mask, x0, y0, ax, ay)
        bad += _put_closed_cells(mask, x0, y0, bx, by)
        mirror_row = ay == by and ay == j + 0.5
        mirror_col = ax == bx and ax == i + 0.5
    bad += _put(mask, x0, y0, i, j)
    if mirror_row:
        bad += _put(mask, x0, y0, i, j + 1)
    if mirror_col:
        bad += _put(mask, x0, y0, i + 1, j)
    while nx > 0 and ny > 0:
        cx = i + 0.5 * sx
        cy = j + 0.5 * sy
        s = _det_filter(by, ay, cx, ax, bx, ax, cy, ay, exact)
        if s == UNDECIDED:
            s = _det_sign_exact(by, ay, cx, ax, bx, ax, cy, ay, scratch)
        if s == 0:
            if supercover:
                bad += _put(mask, x0, y0, i + sx, j)
                bad += _put(mask, x0, y0, i, j + sy)
            s = sy
        if sx * sy * s < 0:
            i += sx
            nx -= 1
        else:
            j += sy
            ny -= 1
        bad += _put(mask, x0, y0, i, j)
    while nx > 0:
        i += sx
        nx -= 1
        bad += _put(mask, x0, y0, i, j)
        if mirror_row:
            bad += _put(mask, x0, y0, i, j + 1)
    while ny > 0:
        j += sy
        ny -= 1
        bad += _put(mask, x0, y0, i, j)
        if mirror_col:
            bad += _put(mask, x0, y0, i + 1, j)
    return bad


@njit(cache=True)
def walk_segments(
    mask: BoolMask,
    x0: int,
    y0: int,
    ax: Floats,
    ay: Floats,
    bx: Floats,
    by: Floats,
    supercover: bool,
    exact: bool,
    scratch: Floats,
) -> int:
    """Discretize every segment (ax[k], ay[k]) → (bx[k], by[k]) into ``mask`` (union); return #misses."""
    bad = 0
    for k in range(ax.shape[0]):
        bad += _walk(mask, x0, y0, ax[k], ay[k], bx[k], by[k], supercover, exact, scratch)
    return bad


@njit(cache=True)
def mark_points(mask: BoolMask, x0: int, y0: int, px: Floats, py: Floats, supercover: bool) -> int:
    """Discretize isolated points: their standard cell, or all closed cells holding them (supercover)."""
    bad = 0
    for k in range(px.shape[0]):
        if supercover:
            bad += _put_closed_cells(mask, x0, y0, px[k], py[k])
        else:
            bad += _put(mask, x0, y0, cell(px[k]), cell(py[k]))
    return bad


# --------------------------------------------------------------------------------------- gauss fill
@njit(cache=True)
def _crossing_bounds(lx: float, ly: float, slope: float, j: int) -> tuple[float, float]:
    """Integers lo ≤ ⌈X⌉ ≤ hi for X the abscissa where the edge from (lx, ly) with slope dx/dy meets y = j.

    The float estimate x = lx + (j − ly)·slope has |x − X| ≤ 8u(|q| + |x|) (u = 2^-53): six roundings
    of relative size u, with slack for the rounding of x ± d itself. Scalars only (inlined, see _det_filter).
    """
    q = (float(j) - ly) * slope
    x = lx + q
    d = _CROSS_BOUND * (abs(q) + abs(x))
    return np.ceil(x - d), np.ceil(x + d)


@njit(cache=True)
def _crossing_exact(
    lx: float, ly: float, hx: float, hy: float, j: int, lo: float, hi: float, exact: bool, scratch: Floats
) -> int:
    """Return ⌈X⌉ among the candidates lo … hi (see :func:`_crossing_bounds`).

    Decided by the exact sign of X − n = [(lx − n)(hy − ly) − (ly − j)(hx − lx)] / (hy − ly), with hy > ly.
    """
    fj = float(j)
    n = lo
    while n < hi:
        s = _det_filter(lx, n, hy, ly, ly, fj, hx, lx, exact)
        if s == UNDECIDED:
            s = _det_sign_exact(lx, n, hy, ly, ly, fj, hx, lx, scratch)
        if s <= 0:
            return int(n)
        n += 1.0
    return int(hi)


@njit(cache=True)
def _fill_group(
    mask: BoolMask,
    x0: int,
    y0: int,
    ax: Floats,
    ay: Floats,
    bx: Floats,
    by: Floats,
    exact: bool,
    scratch: Floats,
    ext: Ints,
) -> int:
    """Set the pixels p with p + τ inside the closed rings given as edges (even-odd rule).

    Scanline with an active-edge table. On row y = j an edge counts when min_y ≤ j < max_y, and it
    crosses at X; p = (i, j) is inside when an odd number of crossings have i < X, i.e. i < ⌈X⌉. With the
    ceilings C sorted, the inside pixels of the row are [C0, C1) ∪ [C2, C3) ∪ …  The active list is kept in
    crossing order from row to row, so the insertion sort costs about one pass per row.
    ``ext`` (xmin, ymin, xmax, ymax) is widened to hold every pixel set. The edges must come sorted by
    ⌈min(ay, by)⌉, their first row (numba's argsort would cost seconds of compile time).
    """
    n = ax.shape[0]
    lx = np.empty(n)
    ly = np.empty(n)
    hx = np.empty(n)
    hy = np.empty(n)
    slope = np.empty(n)
    r0 = np.empty(n, np.int64)
    r1 = np.empty(n, np.int64)
    m = 0
    for e in range(n):
        if ay[e] == by[e]:
            continue  # horizontal edges never count
        if ay[e] < by[e]:
            xa, ya, xb, yb = ax[e], ay[e], bx[e], by[e]
        else:
            xa, ya, xb, yb = bx[e], by[e], ax[e], ay[e]
        first = np.int64(math.ceil(ya))
        last = np.int64(math.ceil(yb)) - 1
        if first > last:
            continue
        lx[m] = xa
        ly[m] = ya
        hx[m] = xb
        hy[m] = yb
        slope[m] = (xb - xa) / (yb - ya)
        r0[m] = first
        r1[m] = last
        m += 1
    if m == 0:
        return 0
    # The caller sorted the edges by ⌈min y⌉ within each group, so r0[:m] is non-decreasing.
    act = np.empty(m, np.int64)
    cross = np.empty(m, np.int64)
    height = mask.shape[0]
    width = mask.shape[1]
    bad = 0
    nact = 0
    k = 0
    row = r0[0]
    while k < m or nact > 0:
        if nact == 0 and r0[k] > row:
            row = r0[k]
        while k < m and r0[k] == row:
            act[nact] = k
            nact += 1
            k += 1
        for t in range(nact):
            e = act[t]
            lo, hi = _crossing_bounds(lx[e], ly[e], slope[e], row)
            if lo == hi:
                cross[t] = np.int64(lo)
            else:
                cross[t] = _crossing_exact(lx[e], ly[e], hx[e], hy[e], row, lo, hi, exact, scratch)
        for t in range(1, nact):
            c = cross[t]
            a = act[t]
            u = t - 1
            while u >= 0 and cross[u] > c:
                cross[u + 1] = cross[u]
                act[u + 1] = act[u]
                u -= 1
            cross[u + 1] = c
            act[u + 1] = a
        rr = row - y0
        for t in range(0, nact - 1, 2):
            s = cross[t]
            f = cross[t + 1]
            if s >= f:
                continue
            if rr < 0 or rr >= height or s < x0 or f - x0 > width:
                bad += 1
                continue
            mask[rr, s - x0 : f - x0] = True
            if s < ext[0]:
                ext[0] = s
            if f - 1 > ext[2]:
                ext[2] = f - 1
            if row < ext[1]:
                ext[1] = row
            if row > ext[3]:
                ext[3] = row
        row += 1
        u = 0
        for t in range(nact):
            if r1[act[t]] >= row:
                act[u] = act[t]
                cross[u] = cross[t]
                u += 1
        nact = u
    return bad


@njit(cache=True)
def fill_groups(
    mask: BoolMask,
    x0: int,
    y0: int,
    ax: Floats,
    ay: Floats,
    bx: Floats,
    by: Floats,
    starts: Ints,
    exact: bool,
    scratch: Floats,
    ext: Ints,
) -> int:
    """Run the even-odd fill on each group of edges and OR the results into ``mask``; return #misses.

    Group g is ``starts[g]:starts[g + 1]``: a polygon or a valid multipolygon (pieces with disjoint
    interiors, so that the even-odd rule over all their rings holds).
    """
    bad = 0
    for g in range(starts.shape[0] - 1):
        a = starts[g]
        b = starts[g + 1]
        bad += _fill_group(mask, x0, y0, ax[a:b], ay[a:b], bx[a:b], by[a:b], exact, scratch, ext)
    return bad


# ---------------------------------------------------------------------------------- ring simplicity
@njit(cache=True)
def _turn(ax: float, ay: float, bx: float, by: float, cx: float, cy: float) -> int:
    """Exact sign of the turn a → b → c (> 0: c on the left of a→b). Scalars only: a cheap call."""
    s = _det_filter(bx, ax, cy, ay, by, ay, cx, ax, False)
    if s == UNDECIDED:
        s = _det_sign_exact(bx, ax, cy, ay, by, ay, cx, ax, np.empty(SCRATCH_SIZE))
    return s


@njit(cache=True)
def _orient(xs: Floats, ys: Floats, a: int, b: int, c: int) -> int:
    """Exact sign of the turn through vertices a → b → c of a ring."""
    return _turn(xs[a], ys[a], xs[b], ys[b], xs[c], ys[c])


@njit(cache=True)
def _within(ax: float, ay: float, bx: float, by: float, px: float, py: float) -> bool:
    """Tell whether p, collinear with a and b, lies within the closed segment [a, b]."""
    return min(ax, bx) <= px and px <= max(ax, bx) and min(ay, by) <= py and py <= max(ay, by)


@njit(cache=True)
def _segments_meet(
    ax: float, ay: float, bx: float, by: float, cx: float, cy: float, dx: float, dy: float
) -> bool:
    """Tell whether the closed segments [a, b] and [c, d] have a point in common (exact)."""
    d1 = _turn(ax, ay, bx, by, cx, cy)
    d2 = _turn(ax, ay, bx, by, dx, dy)
    d3 = _turn(cx, cy, dx, dy, ax, ay)
    d4 = _turn(cx, cy, dx, dy, bx, by)
    if d1 * d2 < 0 and d3 * d4 < 0:
        return True
    return (
        (d1 == 0 and _within(ax, ay, bx, by, cx, cy))
        or (d2 == 0 and _within(ax, ay, bx, by, dx, dy))
        or (d3 == 0 and _within(cx, cy, dx, dy, ax, ay))
        or (d4 == 0 and _within(cx, cy, dx, dy, bx, by))
    )


@njit(cache=True)
def _edges_meet(xs: Floats, ys: Floats, n: int, e: int, f: int) -> bool:
    """True when ring edges e and f meet anywhere they should not (conservative: True when unsure)."""
    a1, a2 = e, (e + 1) % n
    b1, b2 = f, (f + 1) % n
    if a2 == b1 or b2 == a1:  # neighbours on the ring share one vertex; only a collinear fold is wrong
        shared = a2 if a2 == b1 else a1
        u = a1 if shared == a2 else a2
        w = b2 if shared == b1 else b1
        return _orient(xs, ys, shared, u, w) == 0
    return _segments_meet(xs[a1], ys[a1], xs[a2], ys[a2], xs[b1], ys[b1], xs[b2], ys[b2])


@njit(cache=True)
def ring_is_simple(xs: Floats, ys: Floats, order: Ints) -> bool:
    """Prove that the closed ring through xs, ys (no closing repeat, no equal consecutive vertices) is simple.

    Shamos–Hoey sweep in lexicographic (x, y) order with exact orientations: edges that are neighbours in
    the sweep status are tested when they become neighbours, which finds an intersection if there is one.
    Returns True only when the ring is certainly simple (then a polygon with this ring as its only ring is
    valid); False means "not proved" — a crossing, a touching vertex, a repeated vertex or a collinear fold,
    and the caller asks GEOS. ``order`` lists the vertex indices sorted by (x, y): np.lexsort((ys, xs)).
    """
    n = xs.shape[0]
    if n < 3:
        return False
    rank = np.empty(n, np.int64)
    for k in range(n):
        rank[order[k]] = k
        if k > 0 and xs[order[k]] == xs[order[k - 1]] and ys[order[k]] == ys[order[k - 1]]:
            return False  # a vertex visited twice: the ring touches itself
    status = np.empty(n, np.int64)
    pos = np.full(n, -1, np.int64)
    ends = np.empty(2, np.int64)
    m = 0
    for k in range(n):
        v = order[k]
        e_prev = (v - 1 + n) % n
        e_next = v
        ending = 0
        for e in (e_prev, e_next):
            other = e if e == e_prev else (v + 1) % n
            if rank[other] < rank[v]:
                ends[ending] = e
                ending += 1
        # ---- remove the edges ending at v
        if ending > 0:
            i1 = pos[ends[0]]
            lo = i1
            hi = i1
            if ending == 2:
                i2 = pos[ends[1]]
                if abs(i1 - i2) != 1:
                    return False  # something between the two edges that meet at v
                lo = min(i1, i2)
                hi = max(i1, i2)
            width = hi - lo + 1
            for t in range(lo, m - width):
                status[t] = status[t + width]
                pos[status[t]] = t
            for t in range(ending):
                pos[ends[t]] = -1
            m -= width
            if lo > 0 and _orient(xs, ys, status[lo - 1], (status[lo - 1] + 1) % n, v) == 0:
                return False
            if lo < m and _orient(xs, ys, status[lo], (status[lo] + 1) % n, v) == 0:
                return False
            if 0 < lo < m and _edges_meet(xs, ys, n, status[lo - 1], status[lo]):
                return False
        if ending == 2:
            continue
        # ---- insert the edges starting at v (2 - ending of them)
        lo = 0
        hi = m
        while lo < hi:
            mid = (lo + hi) // 2
            t = status[mid]
            s = _orient(xs, ys, t, (t + 1) % n, v)
            a = t if rank[t] < rank[(t + 1) % n] else (t + 1) % n
            if a != t:  # orient relative to the edge's left → right direction
                s = -s
            if s == 0:
                return False  # v lies on another edge
            if s > 0:
                lo = mid + 1
            else:
                hi = mid
        for t in (lo - 1, lo):
            if 0 <= t < m and _orient(xs, ys, status[t], (status[t] + 1) % n, v) == 0:
                return False
        count = 2 - ending
        first = e_next
        second = e_prev
        if count == 1:
            first = e_prev if ending == 1 and ends[0] == e_next else e_next
        else:
            # Both edges leave v to the right: the one turning clockwise from the other goes below.
            turn = _orient(xs, ys, v, (v + 1) % n, (v - 1 + n) % n)
            if turn == 0:
                return False
            if turn < 0:  # v-1 is below the line v → v+1
                first = e_prev
                second = e_next
        for t in range(m - 1, lo - 1, -1):
            status[t + count] = status[t]
            pos[status[t + count]] = t + count
        status[lo] = first
        pos[first] = lo
        if count == 2:
            status[lo + 1] = second
            pos[second] = lo + 1
        m += count
        top = lo + count - 1
        if lo > 0 and _edges_meet(xs, ys, n, status[lo - 1], status[lo]):
            return False
        if top + 1 < m and _edges_meet(xs, ys, n, status[top], status[top + 1]):
            return False
    return True
