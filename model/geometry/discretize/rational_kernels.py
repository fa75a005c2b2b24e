"""Exact discretization of polygons with integer vertices on a grid of spacing G (docs/design.md §2, §8).

The image of a float64 polygon under an exact rational similarity (``Sc_1/5``, ``Sc_5/4`` about a centre,
a rotation) has rational vertices. Written over one common denominator ``D``, every vertex is ``X/D`` with
an integer ``X``; scaling by 2 makes the pixel centres multiples of ``G = 2D`` and the pixel sides odd
multiples of ``D``, so D of the polygon is decided by integer arithmetic alone: the scanline fill of
``{p : p + τ ∈ P}`` (:func:`crossings_kernel`, :func:`_fill_spans`) and, for the cover models, the pixels
whose kernel meets an edge, tested by an exact Liang–Barsky on ``v₀ + v₁ε + v₂ε²`` triples
(:func:`walks_kernel`).

These definitions are written once and run two ways (:func:`discretize_integer_edges`): compiled by numba
on int64 when no intermediate quantity can overflow (:func:`fits_int64`: every product is at most
``8·M² + 4·G·M`` for vertex magnitudes ``M``), and otherwise as plain Python on Python integers (the
kernels' ``py_func``, their helpers ``register_jitable``), so nothing is ever rounded.

The float-filtered kernels at the end decide almost every pixel of a similarity image from float64 data
with a proven error bound and leave only the near-ties to these integer definitions.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt
from numba.extending import register_jitable

from mrm.geometry._jit import njit, py_func

Ints = npt.NDArray[np.int64]
Floats = npt.NDArray[np.float64]

#: Largest magnitude the kernels accept for ``8·M² + 4·G·M`` (every intermediate product stays below it).
_INT64_SAFE = 2**62


def fits_int64(max_coordinate: int, g: int) -> bool:
    """True when the kernels are exact for integer vertices up to ``max_coordinate`` and spacing ``g``."""
    m = int(max_coordinate) + 2 * int(g)  # pixel-centre offsets reach a little beyond the vertices
    return 8 * m * m + 4 * int(g) * m < _INT64_SAFE


@register_jitable
def _ceil_div(a: int, b: int) -> int:
    return -((-a) // b)


@register_jitable
def _count_crossings(edges: Ints, g: int) -> int:
    total = 0
    for k in range(edges.shape[0]):
        ay, by = edges[k, 1], edges[k, 3]
        if ay == by:
            continue
        lo, hi = (ay, by) if by > ay else (by, ay)
        j0 = _ceil_div(lo, g)
        j1 = _ceil_div(hi, g) - 1
        if j1 >= j0:
            total += j1 - j0 + 1
    return total


@njit(cache=True)
def crossings_kernel(edges: Ints, g: int, x0: int, x1: int) -> tuple[Ints, Ints]:
    """The fill crossings ``(row j, m)`` of every edge, ``m = ⌈X⌉ − 1`` clipped to ``[x0 − 1, x1]``.

    An edge counts on row j when a_y ≤ G·j < b_y or b_y ≤ G·j < a_y (the row y = G·j + ε² never meets a
    horizontal edge); pixel i of the row counts when it lies strictly left of the crossing X: i ≤ ⌈X⌉ − 1.
    """
    n = _count_crossings(edges, g)
    rows = np.empty(n, np.int64)
    xs = np.empty(n, np.int64)
    t = 0
    for k in range(edges.shape[0]):
        ax, ay, bx, by = edges[k, 0], edges[k, 1], edges[k, 2], edges[k, 3]
        if ay == by:
            continue
        dx, dy = bx - ax, by - ay
        lo, hi = (ay, by) if dy > 0 else (by, ay)
        den = g * dy
        sign = 1 if den > 0 else -1
        den *= sign
        base = sign * (ax * dy - ay * dx)
        step = sign * g * dx
        j0 = _ceil_div(lo, g)
        j1 = _ceil_div(hi, g) - 1
        num = base + step * j0
        for j in range(j0, j1 + 1):
            # The crossing is X = num / den (pixel units).
            xi = _ceil_div(num, den) - 1
            xs[t] = min(max(xi, x0 - 1), x1)  # clipping keeps the fill: spans are clipped to the box
            rows[t] = j
            t += 1
            num += step
    return rows, xs


@njit(cache=True)
def _fill_spans(mask: npt.NDArray[np.bool_], rows: Ints, xs: Ints, x0: int, y0: int) -> None:
    """Fill row by row from the crossings ``(rows, xs)``, ``xs`` clipped to ``[x0 − 1, x1]``.

    Pixel ``i`` of row ``j`` is inside when an odd number of the row's crossings ``m`` (the last pixel left
    of a crossing) have ``i ≤ m``.
    """
    h, w = mask.shape
    x1 = x0 + w - 1
    n = rows.shape[0]
    order = np.argsort(rows * (w + 2) + (xs - x0 + 1), kind="mergesort")
    start = 0
    while start < n:
        j = rows[order[start]]
        stop = start
        while stop < n and rows[order[stop]] == j:
            stop += 1
        r = j - y0
        if 0 <= r < h:
            for q in range(start, stop - 1, 2):
                lo_i = max(xs[order[q]] + 1, x0)
                hi_i = min(xs[order[q + 1]], x1)
                for i in range(lo_i, hi_i + 1):
                    mask[r, i - x0] = True
        start = stop


@register_jitable
def _less(a0: int, a1: int, a2: int, da: int, b0: int, b1: int, b2: int, db: int, strict: bool) -> bool:
    """Lexicographic (a0, a1, a2)/da < (b0, b1, b2)/db (or ≤), for positive denominators."""
    l0, l1, l2 = a0 * db, a1 * db, a2 * db
    r0, r1, r2 = b0 * da, b1 * da, b2 * da
    if l0 != r0:
        return l0 < r0
    if l1 != r1:
        return l1 < r1
    if l2 != r2:
        return l2 < r2
    return not strict


@register_jitable
def _axis_bounds(
    a0: int, d: int, c: int, h: int, u1: int, u2: int
) -> tuple[bool, bool, int, int, int, int, int, int, int]:
    """The bounds on t of c − h + ε·(u1, u2) < a0 + t·d < c + h + ε·(u1, u2) along one axis.

    Returns (feasible, bounded, lo₀, lo₁, lo₂, up₀, up₁, up₂, den): t > lo/den and t < up/den (strict)
    when ``bounded``; for d = 0 the axis only says whether a0 lies in (c − h, c + h].
    """
    if d == 0:
        return c - h < a0 <= c + h, False, 0, 0, 0, 0, 0, 0, 1
    if d > 0:
        return True, True, c - h - a0, u1, u2, c + h - a0, u1, u2, d
    return True, True, -(c + h - a0), -u1, -u2, -(c - h - a0), -u1, -u2, -d


@register_jitable
def _meets_standard(ax: int, ay: int, dx: int, dy: int, i: int, j: int, g: int, h: int) -> bool:
    """Does the segment a + t·d, t ∈ [0, 1], meet int V(p) + τ for p = (i, j)? (exact Liang–Barsky).

    Every lower bound on t (0, and each axis') must lie below every upper bound (1, and each axis'),
    strictly unless both are the segment's own 0 and 1.
    """
    okx, hx, lx0, lx1, lx2, ux0, ux1, ux2, dxn = _axis_bounds(ax, dx, g * i, h, 1, 0)
    if not okx:
        return False
    oky, hy, ly0, ly1, ly2, uy0, uy1, uy2, dyn = _axis_bounds(ay, dy, g * j, h, 0, 1)
    if not oky:
        return False
    if hx and not (
        _less(0, 0, 0, 1, ux0, ux1, ux2, dxn, True)
        and _less(lx0, lx1, lx2, dxn, 1, 0, 0, 1, True)
        and _less(lx0, lx1, lx2, dxn, ux0, ux1, ux2, dxn, True)
    ):
        return False
    if hy and not (
        _less(0, 0, 0, 1, uy0, uy1, uy2, dyn, True)
        and _less(ly0, ly1, ly2, dyn, 1, 0, 0, 1, True)
        and _less(ly0, ly1, ly2, dyn, uy0, uy1, uy2, dyn, True)
    ):
        return False
    if hx and hy:
        return _less(lx0, lx1, lx2, dxn, uy0, uy1, uy2, dyn, True) and _less(
            ly0, ly1, ly2, dyn, ux0, ux1, ux2, dxn, True
        )
    return True


@njit(cache=True)
def walks_kernel(mask: npt.NDArray[np.bool_], edges: Ints, g: int, x0: int, y0: int, standard: bool) -> None:
    """Mark the pixels whose kernel meets an edge (closed square; open square + τ for ``standard``)."""
    h = g // 2
    hh, ww = mask.shape
    for k in range(edges.shape[0]):
        ax, ay, bx, by = edges[k, 0], edges[k, 1], edges[k, 2], edges[k, 3]
        if ax > bx:
            ax, ay, bx, by = bx, by, ax, ay
        dx, dy = bx - ax, by - ay
        for i in range(_ceil_div(ax - h, g), (bx + h) // g + 1):
            if dx == 0:
                ylo, yhi = min(ay, by), max(ay, by)
                j0, j1 = _ceil_div(ylo - h, g), (yhi + h) // g
            else:
                xl, xr = max(ax, g * i - h), min(bx, g * i + h)
                n1 = ay * dx + (xl - ax) * dy
                n2 = ay * dx + (xr - ax) * dy
                nlo, nhi = min(n1, n2), max(n1, n2)
                j0, j1 = _ceil_div(nlo - h * dx, g * dx), (nhi + h * dx) // (g * dx)
            for j in range(j0, j1 + 1):
                r, c = j - y0, i - x0
                if (
                    0 <= r < hh
                    and 0 <= c < ww
                    and not mask[r, c]
                    and (not standard or _meets_standard(ax, ay, dx, dy, i, j, g, h))
                ):
                    mask[r, c] = True


def _object_edges(edges: Any) -> Any:
    """Edges as an (n, 4) array of Python integers (numpy's ``object`` dtype: no overflow)."""
    rows = [tuple(int(v) for v in edge) for edge in edges]
    e = np.empty((len(rows), 4), dtype=object)
    if rows:
        e[:] = rows
    return e


def integer_crossings(edges: Any, g: int, x0: int, x1: int) -> tuple[Ints, Ints]:
    """:func:`crossings_kernel` compiled on int64 when it cannot overflow, else on Python integers."""
    e = _object_edges(edges)
    m = max((abs(int(v)) for v in e.ravel()), default=0)
    if fits_int64(m, g):
        return crossings_kernel(e.astype(np.int64), int(g), int(x0), int(x1))
    rows, xs = py_func(crossings_kernel)(e, int(g), int(x0), int(x1))
    return rows, xs


def discretize_integer_edges(
    edges: Any, g: int, box: tuple[int, int, int, int], model: str, *, compiled: bool = True
) -> npt.NDArray[np.bool_]:
    """The mask of D over ``box`` for integer edges ``(ax, ay, bx, by)`` on the grid of spacing ``g``.

    ``edges`` is an int64 array or any sequence of Python integers; the compiled kernels run when
    :func:`fits_int64` proves them exact (and ``compiled``), the same definitions on Python integers
    otherwise. ``box`` holds every pixel D can contain.
    """
    x0, y0, x1, y1 = (int(v) for v in box)
    mask = np.zeros((y1 - y0 + 1, x1 - x0 + 1), dtype=np.bool_)
    e: Any
    if isinstance(edges, np.ndarray) and edges.dtype == np.int64:
        e = edges.reshape(-1, 4)
        m = int(np.abs(e).max(initial=0))
    else:
        e = _object_edges(edges)
        m = max((abs(int(v)) for v in e.ravel()), default=0)
    if not e.shape[0]:
        return mask
    if compiled and fits_int64(m, g):
        ints = np.ascontiguousarray(e, dtype=np.int64)
        rows, xs = crossings_kernel(ints, int(g), x0, x1)
        _fill_spans(mask, rows, xs, x0, y0)
        if model != "gauss":
            walks_kernel(mask, ints, int(g), x0, y0, model == "standard")
        return mask
    big = e.astype(object)
    rows, xs = py_func(crossings_kernel)(big, int(g), x0, x1)
    _fill_spans(mask, rows, xs, x0, y0)
    if model != "gauss":
        py_func(walks_kernel)(mask, big, int(g), x0, y0, model == "standard")
    return mask


def integer_walks(mask: npt.NDArray[np.bool_], edges: Any, g: int, x0: int, y0: int, standard: bool) -> None:
    """:func:`walks_kernel` compiled on int64 when it cannot overflow, else on Python integers."""
    e = _object_edges(edges)
    m = max((abs(int(v)) for v in e.ravel()), default=0)
    if fits_int64(m, g):
        walks_kernel(mask, e.astype(np.int64), int(g), int(x0), int(y0), standard)
    else:
        py_func(walks_kernel)(mask, e, int(g), int(x0), int(y0), standard)


# ------------------------------------------------------------------------------ float-filtered kernels
# The exact image of a float64 polygon under a rational similarity (a rotation by the exact rational angle)
# has coordinates with ~110-bit denominators: the integer kernels above would overflow int64 and Python
# integers cost 10× the float discretization. Here the image is computed in float64 with a proven error
# bound ``delta`` per coordinate (|X − X'| ≤ delta for every vertex, exact X, float X'), and every decision
# of the integer kernels is taken from the float data when it is the same for every polygon within
# ``delta``; an edge with one decision that is not is flagged (``ok[k] = False``) and left to the exact
# integer path, which decides it from the exact vertices (mrm.geometry.discretize.rational). So the pixels are
# those of the integer path, bit for bit, and the exact arithmetic runs only on the near-ties.
#
# Both kernels rest on one fact: the exact edge S = [a, b] and its float image S' = [a', b'] with
# |a − a'|∞, |b − b'|∞ ≤ delta are within delta of each other point by point (a + t(b − a) vs
# a' + t(b' − a'), same t). ``delta`` carries a factor ≥ 2 of slack over the vertex rounding it bounds,
# which absorbs the relative roundings (a few units of 2⁻⁵³) of the bounds computed from it here.

_U = 2.0**-53
_TINY = 2.0**-1000


@njit(cache=True, inline="always")
def _sure_ceil(v: float, e: float) -> tuple[bool, int]:
    """(True, ⌈V⌉) when ⌈V⌉ is one integer for every real V with |V − v| ≤ e; else (False, 0).

    The widening by 8u·e + 4u·|v| covers the rounding of ``v ± w`` (u = 2⁻⁵³), so the two computed ends
    enclose [v − e, v + e]; NaN or infinite input is never sure.
    """
    w = e * (1.0 + 8.0 * _U) + 4.0 * _U * abs(v) + _TINY
    lo = np.ceil(v - w)
    hi = np.ceil(v + w)
    if lo != hi or not (abs(lo) < 2.0**62):  # NaN compares unequal
        return False, 0
    return True, int(lo)


@njit(cache=True)
def filtered_crossings(
    ax: Floats, ay: Floats, bx: Floats, by: Floats, delta: float, x0: int, x1: int
) -> tuple[Ints, Ints, npt.NDArray[np.bool_]]:
    """The fill crossings ``(row j, ⌈X⌉ − 1)`` of the edges the float data decide, and the flags ``ok``.

    As :func:`crossings_kernel`: an edge counts on row j when min(a_y, b_y) ≤ j < max(a_y, b_y) (exact
    vertices), at the crossing X of the row. The rows follow from ⌈a_y⌉ and ⌈b_y⌉ (sure within delta).
    The exact crossing X of S and the crossing X'' of the line of S' differ by at most
    delta·(1 + |dx'/dy'|): the point of S' at S's parameter of (X, j) is within delta of it, and sliding
    along S' back to height j moves x by |dy|·|dx'/dy'| ≤ delta·|dx'/dy'|. X' = a'_x + (j − a'_y)·slope in
    float64 is within 8u(|a'_x| + |(j − a'_y)·slope|) of X'' (five roundings, u = 2⁻⁵³). An edge with a
    doubtful decision records no crossing and gets ``ok[k] = False``.
    """
    n_e = ax.shape[0]
    bound = 0
    for k in range(n_e):
        lo = min(ay[k], by[k])
        hi = max(ay[k], by[k])
        bound += int(np.ceil(hi + delta + 1.0) - np.floor(lo - delta - 1.0)) + 1
    rows = np.empty(bound, np.int64)
    xs = np.empty(bound, np.int64)
    ok = np.ones(n_e, np.bool_)
    t = 0
    for k in range(n_e):
        sa, ca = _sure_ceil(ay[k], delta)
        sb, cb = _sure_ceil(by[k], delta)
        if not (sa and sb):
            ok[k] = False
            continue
        if ca == cb:
            continue  # no integer j with min ≤ j < max: the edge crosses no row
        # ⌈a_y⌉ ≠ ⌈b_y⌉ for every exact edge within delta, so a'_y ≠ b'_y and the slope is finite or inf.
        slope = (bx[k] - ax[k]) / (by[k] - ay[k])
        grow = delta * (1.0 + abs(slope) * (1.0 + 8.0 * _U))
        start = t
        for j in range(min(ca, cb), max(ca, cb)):
            p = (j - ay[k]) * slope
            x = ax[k] + p
            sx, cx = _sure_ceil(x, grow + 8.0 * _U * (abs(ax[k]) + abs(p)))
            if not sx:
                t = start
                ok[k] = False
                break
            xs[t] = min(max(cx - 1, x0 - 1), x1)  # pixel i counts when i < X, i.e. i ≤ ⌈X⌉ − 1
            rows[t] = j
            t += 1
    return rows[:t].copy(), xs[:t].copy(), ok


@njit(cache=True)
def filtered_spans(mask: npt.NDArray[np.bool_], rows: Ints, xs: Ints, x0: int, y0: int) -> None:
    """Fill ``mask`` from crossings (:func:`filtered_crossings` plus the exact ones of flagged edges)."""
    _fill_spans(mask, rows, xs, x0, y0)


@njit(cache=True, inline="always")
def _walk_major(
    mask: npt.NDArray[np.bool_],
    ua: float,
    va: float,
    ub: float,
    vb: float,
    m: float,
    e: float,
    x0: int,
    y0: int,
    swapped: bool,
) -> bool:
    """Mark the pixels the exact edge surely meets in their open square; False if one is doubtful.

    (u, v) is (x, y), or (y, x) when ``swapped``, chosen so that |v'_b − v'_a| ≤ |u'_b − u'_a|: the slope
    is at most 1 and each v(u) on S' is computed within e/2 (e = 32u·(M + 4) for magnitudes ≤ M).
    Column i: *outer* rows are those whose closed square grown by delta S' may meet (every pixel whose
    closed square S meets is one); *inner* rows those whose square shrunk by delta S' surely meets (S then
    meets the open square). The margins m = delta + e and e cover the roundings of the bounds themselves.
    Inner pixels are in D under both cover models (an edge through the open square meets int V(p) + τ);
    a pixel that is outer but not inner is a near-tie, and the edge goes to the exact path.
    """
    if ua > ub:
        ua, va, ub, vb = ub, vb, ua, va
    du = ub - ua
    slope = (vb - va) / du if du > 0.0 else 0.0
    hh, ww = mask.shape
    sure = True
    i_lo = int(np.ceil(ua - 0.5 - m))
    i_hi = int(np.floor(ub + 0.5 + m))
    for i in range(i_lo, i_hi + 1):
        ul = max(ua, i - 0.5 - m)
        ur = min(ub, i + 0.5 + m)
        if ul > ur:
            continue
        vl = va + (ul - ua) * slope
        vr = va + (ur - ua) * slope
        jo0 = int(np.ceil(min(vl, vr) - 0.5 - m - e))
        jo1 = int(np.floor(max(vl, vr) + 0.5 + m + e))
        ul = max(ua, i - 0.5 + m)
        ur = min(ub, i + 0.5 - m)
        if ul > ur:
            if jo0 <= jo1:
                sure = False
            continue
        vl = va + (ul - ua) * slope
        vr = va + (ur - ua) * slope
        ji0 = int(np.ceil(min(vl, vr) + e + m - 0.5))
        ji1 = int(np.floor(max(vl, vr) - e - m + 0.5))
        if ji0 > jo0 or ji1 < jo1:
            sure = False
        for j in range(ji0, ji1 + 1):
            if swapped:
                r, c = i - y0, j - x0
            else:
                r, c = j - y0, i - x0
            if 0 <= r < hh and 0 <= c < ww:
                mask[r, c] = True
    return sure


@njit(cache=True)
def filtered_walks(
    mask: npt.NDArray[np.bool_],
    ax: Floats,
    ay: Floats,
    bx: Floats,
    by: Floats,
    ok: npt.NDArray[np.bool_],
    delta: float,
    magnitude: float,
    x0: int,
    y0: int,
) -> None:
    """Mark the edge pixels of the cover models for the edges still ``ok``; flag those with a near-tie.

    ``magnitude`` bounds every |coordinate| of the float images. The pixels marked for a flagged edge are
    all in D; the exact path adds the rest.
    """
    e = 32.0 * _U * (magnitude + 4.0)
    m = delta + e
    for k in range(ax.shape[0]):
        if not ok[k]:
            continue
        if abs(bx[k] - ax[k]) >= abs(by[k] - ay[k]):
            sure = _walk_major(mask, ax[k], ay[k], bx[k], by[k], m, e, x0, y0, False)
        else:
            sure = _walk_major(mask, ay[k], ax[k], by[k], bx[k], m, e, x0, y0, True)
        if not sure:
            ok[k] = False
