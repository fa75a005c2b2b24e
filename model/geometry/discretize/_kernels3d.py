"""Numba kernels of the exact voxelization (used by :mod:`mrm.geometry.discretize.voxels`).

Every decision reduces to one of three exact questions about float64 data:

* the cell of a coordinate (comparisons with grid half-integers, exact: :func:`_cell_step`);
* the sign of a 2×2 determinant ``(p1 − p2)(q1 − q2) − (r1 − r2)(s1 − s2)`` (the 2D kernels' filtered
  :func:`._kernels._det_filter` / :func:`._kernels._det_sign_exact`);
* the sign of a 3×3 determinant det[a − d; b − d; c − d] (here: Shewchuk's orient3d filter, and an exact
  floating-point expansion when the filter cannot decide).

The expansion arithmetic is exact as long as no product underflows or overflows: the caller limits the
coordinates to 2^-250 ≤ |v| ≤ 2^51 (or v = 0) and the grid step to w ≤ 2^49, so that grid numbers within two
voxels of the data stay below 2^52, exact half-integers. Every input and grid number is a multiple of 2^-302,
every product of three of them (and every rounding error of such a product) a multiple of 2^-906, far above
the subnormal range. When the caller has proved plain float arithmetic exact for the whole mesh
(``exact=True``, :func:`mrm.geometry.discretize.exact.float_predicates_are_exact` with ``EXACT_UNITS_3D`` and
the step) the float determinants are used as they are, zero included.

Voxel p = (i, j, k) is centred on p; τ = (ε, ε², ε³). The kernels also run on the grid of step w (a
positive integer; ``w = 1.0`` is the unit grid): voxel p is then the cube of side w centred on w·p, its kernel
is w·K(p) (shift w·τ), and the result is D(P / w) without dividing P (ADR 0062). Grid numbers w·p and
w·p ± w/2 are integers or half-integers, exact floats in the supported range, and every tie is decided by the
sign of a linear form a·τ, the same for w·τ. The docstrings below are written for w = 1.

The models (docs/design.md §11):

* gauss — p + τ inside the solid: a parity scanline along +x (:func:`fill_parity`);
* supercover — V(p) meets a triangle: the separating-axis test with strict separation;
* standard — int V(p) + τ meets a triangle: the separating-axis test with weak separation, ties broken by
  the sign of a·τ (:func:`mark_triangles`).

For a closed solid P, D(P) = gauss(P) ∪ D(∂P) in both covers: a kernel K(p) that meets P but no triangle lies
in the interior of P, and so does p + τ ∈ K(p).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import njit
from mrm.geometry.discretize._kernels import (
    _grow,
    _two_diff,
    _two_prod,
    det_sign,
)

BoolMask = npt.NDArray[np.bool_]
Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

_EPS = 2.0**-53
#: Shewchuk's orient3d error bound relative to the permanent ("o3derrboundA").
_O3D_BOUND = (7.0 + 56.0 * _EPS) * _EPS
#: Scratch size for one exact 3×3 sign: 6 products × 8 partial products × 4 components, with room.
SCRATCH3_SIZE = 256


# ----------------------------------------------------------------------------------- exact 3×3 signs
@njit(cache=True)
def _add3(e: Floats, m: int, x: float, xl: float, y: float, yl: float, z: float, zl: float, sg: float) -> int:
    """Add sg·(x + xl)(y + yl)(z + zl) exactly to the expansion e[:m]; return its new length."""
    for xi in (x, xl):
        if xi == 0.0:
            continue
        for yi in (y, yl):
            if yi == 0.0:
                continue
            p, pe = _two_prod(xi, yi)
            for zi in (z, zl):
                if zi == 0.0:
                    continue
                h, hl = _two_prod(p, zi)
                m = _grow(e, m, sg * hl)
                m = _grow(e, m, sg * h)
                if pe != 0.0:
                    h, hl = _two_prod(pe, zi)
                    m = _grow(e, m, sg * hl)
                    m = _grow(e, m, sg * h)
    return m


@njit(cache=True)
def _det3_exact(
    ax: float,
    ay: float,
    az: float,
    bx: float,
    by: float,
    bz: float,
    cx: float,
    cy: float,
    cz: float,
    dx: float,
    dy: float,
    dz: float,
    e: Floats,
) -> int:
    """Exact sign of det[a − d; b − d; c − d] with floating-point expansions (Shewchuk 1997)."""
    adx, adxl = _two_diff(ax, dx)
    ady, adyl = _two_diff(ay, dy)
    adz, adzl = _two_diff(az, dz)
    bdx, bdxl = _two_diff(bx, dx)
    bdy, bdyl = _two_diff(by, dy)
    bdz, bdzl = _two_diff(bz, dz)
    cdx, cdxl = _two_diff(cx, dx)
    cdy, cdyl = _two_diff(cy, dy)
    cdz, cdzl = _two_diff(cz, dz)
    m = 0
    m = _add3(e, m, adz, adzl, bdx, bdxl, cdy, cdyl, 1.0)
    m = _add3(e, m, adz, adzl, bdy, bdyl, cdx, cdxl, -1.0)
    m = _add3(e, m, bdz, bdzl, cdx, cdxl, ady, adyl, 1.0)
    m = _add3(e, m, bdz, bdzl, adx, adxl, cdy, cdyl, -1.0)
    m = _add3(e, m, cdz, cdzl, adx, adxl, bdy, bdyl, 1.0)
    m = _add3(e, m, cdz, cdzl, ady, adyl, bdx, bdxl, -1.0)
    if m == 0:
        return 0
    return 1 if e[m - 1] > 0.0 else -1


@njit(cache=True)
def det3_sign(
    ax: float,
    ay: float,
    az: float,
    bx: float,
    by: float,
    bz: float,
    cx: float,
    cy: float,
    cz: float,
    dx: float,
    dy: float,
    dz: float,
    exact: bool,
    e: Floats,
) -> int:
    """Return the exact sign of det[a − d; b − d; c − d] = ((b − a) × (c − a)) · (a − d).

    Float filter first (Shewchuk's orient3d bound); :func:`_det3_exact` when it cannot decide.
    """
    adx = ax - dx
    ady = ay - dy
    adz = az - dz
    bdx = bx - dx
    bdy = by - dy
    bdz = bz - dz
    cdx = cx - dx
    cdy = cy - dy
    cdz = cz - dz
    bdxcdy = bdx * cdy
    cdxbdy = cdx * bdy
    cdxady = cdx * ady
    adxcdy = adx * cdy
    adxbdy = adx * bdy
    bdxady = bdx * ady
    det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady)
    if exact:
        return 1 if det > 0.0 else (-1 if det < 0.0 else 0)
    perm = (
        (abs(bdxcdy) + abs(cdxbdy)) * abs(adz)
        + (abs(cdxady) + abs(adxcdy)) * abs(bdz)
        + (abs(adxbdy) + abs(bdxady)) * abs(cdz)
    )
    bound = _O3D_BOUND * perm
    if det > bound:
        return 1
    if -det > bound:
        return -1
    if perm == 0.0:
        # Every float product is 0, so in every term a factor is a difference of equal floats (no product
        # of non-zero numbers underflows in the supported range): the determinant is exactly 0.
        return 0
    return _det3_exact(ax, ay, az, bx, by, bz, cx, cy, cz, dx, dy, dz, e)


@njit(cache=True)
def _sgn(u: float) -> int:
    return 1 if u > 0.0 else (-1 if u < 0.0 else 0)


# ------------------------------------------------------------------------------------- the grid step
@njit(cache=True)
def _ceil_step(u: float, w: float) -> int:
    """Return the least k with k·w ≥ u: ⌈u / w⌉ exactly (k·w is an integer below 2^53, an exact float)."""
    k = math.ceil(u / w)  # off by at most one: the quotient is rounded once
    if k * w < u:
        k += 1
    elif (k - 1) * w >= u:
        k -= 1
    return k


@njit(cache=True)
def _cell_step(u: float, w: float, half: float) -> int:
    """Return k with u ∈ (k·w − half, k·w + half], half = w / 2 (exact: k·w ± half are floats)."""
    k = np.floor((u + half) / w)
    while u > k * w + half:
        k += 1.0
    while u <= k * w - half:
        k -= 1.0
    return int(k)


# ------------------------------------------------------------------------------------------ gauss
@njit(cache=True)
def _edge_side(ay: float, az: float, by: float, bz: float, j: float, k: float, exact: bool, e: Floats) -> int:
    """Sign of orient((a, b, q)) in the (y, z) plane for q = (j + ε², k + ε³), never 0 for a ≠ b.

    orient = f0 + (a_z − b_z)·ε² + (b_y − a_y)·ε³ with f0 = (b_y − a_y)(k − a_z) − (b_z − a_z)(j − a_y).
    """
    s = det_sign(by, ay, k, az, bz, az, j, ay, exact, e)
    if s != 0:
        return s
    if az != bz:
        return 1 if az > bz else -1
    return 1 if by > ay else -1


@njit(cache=True)
def _crossing_ceil(
    ax: float,
    ay: float,
    az: float,
    bx: float,
    by: float,
    bz: float,
    cx: float,
    cy: float,
    cz: float,
    s: int,
    j: float,
    k: float,
    lo: int,
    hi: int,
    w: float,
    exact: bool,
    e: Floats,
) -> int:
    """Return min(max(⌈X / w⌉, lo), hi), X the abscissa where the line (·, j, k) meets the plane of abc.

    X ≤ n·w ⟺ s · det[a − q; b − q; c − q] ≤ 0 for q = (n·w, j, k), s the sign of the normal's x component
    (w the grid step). The float estimate of X / w gives the first candidate; a binary search corrects it
    (needed only where the estimate is off by more than a unit, i.e. almost never).
    """
    nx = (by - ay) * (cz - az) - (bz - az) * (cy - ay)
    ny = (bz - az) * (cx - ax) - (bx - ax) * (cz - az)
    nz = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    xe = (ax + (ny * (ay - j) + nz * (az - k)) / nx) / w
    if xe != xe:  # NaN: take the middle of the range
        c = (lo + hi) // 2
    elif xe <= lo:
        c = lo
    elif xe >= hi:
        c = hi
    else:
        c = math.ceil(xe)
    if c < hi and s * det3_sign(ax, ay, az, bx, by, bz, cx, cy, cz, c * w, j, k, exact, e) > 0:
        lo2 = c + 1
        hi2 = hi
    else:
        if c == lo or s * det3_sign(ax, ay, az, bx, by, bz, cx, cy, cz, (c - 1) * w, j, k, exact, e) > 0:
            return c
        lo2 = lo
        hi2 = c - 1
    # The answer lies in [lo2, hi2] and X ≤ hi2 holds (or hi2 == hi, the clamp).
    while lo2 < hi2:
        mid = (lo2 + hi2) // 2
        if s * det3_sign(ax, ay, az, bx, by, bz, cx, cy, cz, mid * w, j, k, exact, e) <= 0:
            hi2 = mid
        else:
            lo2 = mid + 1
    return lo2


@njit(cache=True)
def fill_parity(
    mask: BoolMask,
    x0: int,
    y0: int,
    z0: int,
    vx: Floats,
    vy: Floats,
    vz: Floats,
    tris: Ints,
    exact: bool,
    scratch: Floats,
    ext: Ints,
    w: float,
) -> int:
    """Set the voxels p with p + τ inside the closed surface ``tris`` (even-odd rule); return #misses.

    On the grid of step w (a positive integer as a float) the point is w·p + w·τ, below written for w = 1:
    the argument is the same with j, k, i replaced by w·j, w·k, w·i, and ⌈X⌉ by ⌈X / w⌉.

    The ray from p + τ towards +x, {(i + ε + t, j + ε², k + ε³)}, passes through no vertex and no edge: it
    crosses a triangle exactly when (j + ε², k + ε³) lies inside the triangle's projection on the (y, z) plane
    (signs of :func:`_edge_side`, all equal to the projection's orientation; a triangle whose projection has
    no area is never crossed), at X, and the crossing counts for p when i < X, i.e. i < ⌈X⌉. Each crossing
    toggles mask[k, j, ⌈X⌉]; a prefix parity along each row then gives the inside voxels (the number of
    crossings of a row is even, so "odd number of ⌈X⌉ > i" = "odd number of ⌈X⌉ ≤ i"). ``mask`` must be all
    False on entry; ``ext`` (xmin, ymin, zmin, xmax, ymax, zmax) is widened to hold every voxel set.
    """
    nzs, nys, nxs = mask.shape
    active = np.zeros((nzs, nys), np.bool_)
    bad = 0
    for t in range(tris.shape[0]):
        a = tris[t, 0]
        b = tris[t, 1]
        c = tris[t, 2]
        ax, ay, az = vx[a], vy[a], vz[a]
        bx, by, bz = vx[b], vy[b], vz[b]
        cx, cy, cz = vx[c], vy[c], vz[c]
        s = det_sign(by, ay, cz, az, bz, az, cy, ay, exact, scratch)
        if s == 0:
            continue  # seen edge-on along x: never crossed
        jlo = _ceil_step(min(ay, by, cy), w)
        jhi = _ceil_step(max(ay, by, cy), w) - 1
        klo = _ceil_step(min(az, bz, cz), w)
        khi = _ceil_step(max(az, bz, cz), w) - 1
        for k in range(klo, khi + 1):
            fk = k * w
            for j in range(jlo, jhi + 1):
                fj = j * w
                if _edge_side(ay, az, by, bz, fj, fk, exact, scratch) != s:
                    continue
                if _edge_side(by, bz, cy, cz, fj, fk, exact, scratch) != s:
                    continue
                if _edge_side(cy, cz, ay, az, fj, fk, exact, scratch) != s:
                    continue
                ci = _crossing_ceil(
                    ax, ay, az, bx, by, bz, cx, cy, cz, s, fj, fk, x0, x0 + nxs, w, exact, scratch
                )
                kk = k - z0
                jj = j - y0
                if kk < 0 or jj < 0 or kk >= nzs or jj >= nys:
                    bad += 1
                    continue
                active[kk, jj] = True
                if ci < x0 + nxs:
                    mask[kk, jj, ci - x0] = not mask[kk, jj, ci - x0]
    for kk in range(nzs):
        for jj in range(nys):
            if not active[kk, jj]:
                continue
            par = False
            first = -1
            last = -1
            for ii in range(nxs):
                if mask[kk, jj, ii]:
                    par = not par
                mask[kk, jj, ii] = par
                if par:
                    if first < 0:
                        first = ii
                    last = ii
            if first >= 0:
                ext[0] = min(ext[0], x0 + first)
                ext[3] = max(ext[3], x0 + last)
                ext[1] = min(ext[1], y0 + jj)
                ext[4] = max(ext[4], y0 + jj)
                ext[2] = min(ext[2], z0 + kk)
                ext[5] = max(ext[5], z0 + kk)
    return bad


# ------------------------------------------------------------------------------------- covers (SAT)
@njit(cache=True)
def _cross_axis_separates(
    vs: float,
    vt: float,
    ws: float,
    wt: float,
    os_: float,
    ot: float,
    cs: float,
    ct: float,
    t_first: bool,
    supercover: bool,
    side: float,
    exact: bool,
    e: Floats,
) -> bool:
    """Tell whether the axis a = (w − v) × u (u a coordinate axis) separates the triangle from the kernel.

    (s, t) are the two other coordinates, in cyclic order, so that a = (e_t, −e_s) in that plane, e = w − v.
    The triangle projects on a to {a·v = a·w, a·o}; the kernel's cube (centre c, side ``side``, the grid
    step) to [a·c_min, a·c_max].
    supercover: separated when both values lie strictly below a·c_min or strictly above a·c_max.
    standard (open cube shifted by τ): below when a·(x − c_min) ≤ a·τ, an equality counting when a·τ > 0,
    i.e. when the first non-zero component of a in (x, y, z) order is positive (``t_first``: t comes first).
    """
    a_s = _sgn(wt - vt)
    a_t = -_sgn(ws - vs)
    if a_s == 0 and a_t == 0:
        return False
    # Float filter: the projections' centre-relative values and the cube's radius, each off by less than
    # ``bound`` (four roundings at most per term, counted with a factor 4 of slack).
    es = ws - vs
    et = wt - vt
    pvs = vs - cs
    pvt = vt - ct
    pos = os_ - cs
    pot = ot - ct
    pv = et * pvs - es * pvt
    po = et * pos - es * pot
    half = 0.5 * side
    r = half * (abs(et) + abs(es))
    bound = 16.0 * _EPS * (abs(et) * (abs(pvs) + abs(pos) + side) + abs(es) * (abs(pvt) + abs(pot) + side))
    hi_v = max(pv, po)
    lo_v = min(pv, po)
    if hi_v + r > bound and lo_v - r < -bound:
        return False  # the intervals overlap with room: not separated, whatever the tie rule
    if hi_v + r < -bound or lo_v - r > bound:
        return True  # strictly apart
    first, second = (a_t, a_s) if t_first else (a_s, a_t)
    lex = first if first != 0 else second
    ms = cs - half if a_s > 0 else cs + half
    mt = ct - half if a_t > 0 else ct + half
    # a·(x − m) = e_t (x_s − m_s) − e_s (x_t − m_t)
    d1 = det_sign(wt, vt, vs, ms, ws, vs, vt, mt, exact, e)
    if d1 < 0 or (d1 == 0 and not supercover and lex > 0):
        d2 = det_sign(wt, vt, os_, ms, ws, vs, ot, mt, exact, e)
        if d2 < 0 or (d2 == 0 and not supercover and lex > 0):
            return True
    xs = 2.0 * cs - ms
    xt = 2.0 * ct - mt
    d1 = det_sign(wt, vt, vs, xs, ws, vs, vt, xt, exact, e)
    if d1 > 0 or (d1 == 0 and not supercover and lex < 0):
        d2 = det_sign(wt, vt, os_, xs, ws, vs, ot, xt, exact, e)
        if d2 > 0 or (d2 == 0 and not supercover and lex < 0):
            return True
    return False


@njit(cache=True)
def _plane_cross_separates(
    ax: float,
    ay: float,
    az: float,
    bx: float,
    by: float,
    bz: float,
    cx: float,
    cy: float,
    cz: float,
    fs: float,
    ft: float,
    plane: int,
    supercover: bool,
    side: float,
    exact: bool,
    e: Floats,
) -> bool:
    """Tell whether an axis edge × u separates the triangle from the cube centred at (fs, ft) in ``plane``.

    plane 0: u = x, (s, t) = (y, z); 1: u = y, (s, t) = (z, x); 2: u = z, (s, t) = (x, y).
    """
    if plane == 0:
        a_s, a_t, b_s, b_t, c_s, c_t = ay, az, by, bz, cy, cz
    elif plane == 1:
        a_s, a_t, b_s, b_t, c_s, c_t = az, ax, bz, bx, cz, cx
    else:
        a_s, a_t, b_s, b_t, c_s, c_t = ax, ay, bx, by, cx, cy
    tf = plane == 1
    if _cross_axis_separates(a_s, a_t, b_s, b_t, c_s, c_t, fs, ft, tf, supercover, side, exact, e):
        return True
    if _cross_axis_separates(b_s, b_t, c_s, c_t, a_s, a_t, fs, ft, tf, supercover, side, exact, e):
        return True
    return _cross_axis_separates(c_s, c_t, a_s, a_t, b_s, b_t, fs, ft, tf, supercover, side, exact, e)


@njit(cache=True)
def _range(lo: float, hi: float, supercover: bool, w: float) -> tuple[int, int]:
    """Voxel indices whose kernel's extent on one axis meets [lo, hi] (closed cells, or the cell rule).

    On the grid of step w the kernel of index i spans w·i ± w/2 on the axis (shifted by w·ε in standard).
    """
    half = 0.5 * w
    i0 = _cell_step(lo, w, half)
    i1 = _cell_step(hi, w, half)
    if supercover and hi == i1 * w + half:
        i1 += 1
    return i0, i1


@njit(cache=True)
def _normal_separates(
    ax: float,
    ay: float,
    az: float,
    bx: float,
    by: float,
    bz: float,
    cx: float,
    cy: float,
    cz: float,
    fi: float,
    fj: float,
    fk: float,
    snx: int,
    sny: int,
    snz: int,
    lexn: int,
    supercover: bool,
    half: float,
    exact: bool,
    e: Floats,
) -> bool:
    """Tell whether the triangle's normal n separates it from the cube of half-side ``half`` at (fi, fj, fk).

    n·(a − m) = det[a − m; b − m; c − m] for the cube's corner m minimizing n·x: below when < 0 (or = 0 with
    n·τ > 0 under the tie rule); the same with the maximizing corner, above.
    """
    if lexn == 0:
        return False
    mx = fi - half if snx > 0 else fi + half
    my = fj - half if sny > 0 else fj + half
    mz = fk - half if snz > 0 else fk + half
    d = det3_sign(ax, ay, az, bx, by, bz, cx, cy, cz, mx, my, mz, exact, e)
    if d < 0 or (d == 0 and not supercover and lexn > 0):
        return True
    d = det3_sign(ax, ay, az, bx, by, bz, cx, cy, cz, 2.0 * fi - mx, 2.0 * fj - my, 2.0 * fk - mz, exact, e)
    return d > 0 or (d == 0 and not supercover and lexn < 0)


#: Narrow a column to the voxels near the triangle's plane only when the float normal is this accurate.
_NARROW_REL = 2.0**-30
#: ... and the triangle spans at most this many voxels (bounds the error of the float estimate, see below).
_NARROW_SPAN = 2.0**20


@njit(cache=True)
def mark_triangles(
    mask: BoolMask,
    x0: int,
    y0: int,
    z0: int,
    vx: Floats,
    vy: Floats,
    vz: Floats,
    tris: Ints,
    supercover: bool,
    exact: bool,
    scratch: Floats,
    w: float,
) -> int:
    """Set the voxels whose kernel meets a closed triangle of ``tris`` (standard or supercover); #misses.

    Voxel p's cube has side w (the grid step, a positive integer as a float) and centre w·p; below, w = 1.

    Separating-axis theorem (the 13 candidate axes of a box and a triangle: the 3 coordinate axes, the
    triangle's normal and the 9 products edge × axis; zero axes of degenerate triangles are skipped, and the
    candidates stay complete for segments and points). The coordinate axes are the loops' ranges.

    The voxels are visited in columns along the axis D where the float normal is largest: the three axes
    edge × D depend on the column only and are tested once per column, and along the column only the voxels
    whose cube can meet the triangle's plane are tested — |n_D (d − a_D) + G| ≤ h with G = n_P (p − a_P) +
    n_Q (q − a_Q), h = ½ Σ|n|, at most 1 + Σ|n| / |n_D| ≤ 4 voxels. That range comes from float arithmetic
    and only narrows the candidates (every decision is still exact); it is widened by a margin that bounds
    its error, and not used at all when the float normal is not accurate enough.
    """
    nzs, nys, nxs = mask.shape
    bad = 0
    half = 0.5 * w
    lo = np.empty(3, np.int64)
    hi = np.empty(3, np.int64)
    f = np.empty(3)  # the voxel's centre w·p
    ix = np.empty(3, np.int64)  # p
    for t in range(tris.shape[0]):
        a = tris[t, 0]
        b = tris[t, 1]
        c = tris[t, 2]
        ax, ay, az = vx[a], vy[a], vz[a]
        bx, by, bz = vx[b], vy[b], vz[b]
        cx, cy, cz = vx[c], vy[c], vz[c]
        snx = det_sign(by, ay, cz, az, bz, az, cy, ay, exact, scratch)
        sny = det_sign(bz, az, cx, ax, bx, ax, cz, az, exact, scratch)
        snz = det_sign(bx, ax, cy, ay, by, ay, cx, ax, exact, scratch)
        lexn = snx if snx != 0 else (sny if sny != 0 else snz)
        lo[0], hi[0] = _range(min(ax, bx, cx), max(ax, bx, cx), supercover, w)
        lo[1], hi[1] = _range(min(ay, by, cy), max(ay, by, cy), supercover, w)
        lo[2], hi[2] = _range(min(az, bz, cz), max(az, bz, cz), supercover, w)
        # The float normal and a bound of its error: each component has two products of rounded
        # differences and one subtraction, below 4u(1 + 4u)(|p1| + |p2|) off; 8u leaves room.
        p1 = (by - ay) * (cz - az)
        p2 = (bz - az) * (cy - ay)
        q1 = (bz - az) * (cx - ax)
        q2 = (bx - ax) * (cz - az)
        r1 = (bx - ax) * (cy - ay)
        r2 = (by - ay) * (cx - ax)
        n0 = p1 - p2
        n1 = q1 - q2
        n2 = r1 - r2
        err = 8.0 * _EPS * max(abs(p1) + abs(p2), abs(q1) + abs(q2), abs(r1) + abs(r2))
        dd = 0
        if abs(n1) > abs(n0):
            dd = 1
        if abs(n2) > max(abs(n0), abs(n1)):
            dd = 2
        nd = n0 if dd == 0 else (n1 if dd == 1 else n2)
        span = max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) + 2.0
        narrow = nd != 0.0 and err <= _NARROW_REL * abs(nd) and span <= _NARROW_SPAN
        pp = (dd + 1) % 3
        qq = (dd + 2) % 3
        av = (ax, ay, az)
        nv = (n0, n1, n2)
        # Error of the float range (see the docstring), in units of w: relative error of n below 2^-30,
        # |n_D| ≥ Σ|n| / 3, |p − a_P| / w, |q − a_Q| / w below the span, so the quotients are off by far less
        # than 2^-6; the roundings of a_D − quotient and of the division by w are below
        # 2^-51 |a_D| / w + 2^-49 · span.
        margin = 1.0 + (abs(av[dd]) / w + span) * 2.0**-40
        h = half * (abs(n0) + abs(n1) + abs(n2))
        for q in range(lo[qq], hi[qq] + 1):
            for p in range(lo[pp], hi[pp] + 1):
                f[pp] = p * w
                f[qq] = q * w
                ix[pp] = p
                ix[qq] = q
                if dd == 0:
                    sep = _plane_cross_separates(
                        ax, ay, az, bx, by, bz, cx, cy, cz, f[1], f[2], 0, supercover, w, exact, scratch
                    )
                elif dd == 1:
                    sep = _plane_cross_separates(
                        ax, ay, az, bx, by, bz, cx, cy, cz, f[2], f[0], 1, supercover, w, exact, scratch
                    )
                else:
                    sep = _plane_cross_separates(
                        ax, ay, az, bx, by, bz, cx, cy, cz, f[0], f[1], 2, supercover, w, exact, scratch
                    )
                if sep:
                    continue
                d0 = lo[dd]
                d1 = hi[dd]
                if narrow:
                    g = nv[pp] * (f[pp] - av[pp]) + nv[qq] * (f[qq] - av[qq])
                    u1 = (av[dd] - (g + h) / nd) / w
                    u2 = (av[dd] - (g - h) / nd) / w
                    if u1 > u2:
                        u1, u2 = u2, u1
                    d0 = max(d0, math.ceil(u1 - margin))
                    d1 = min(d1, math.floor(u2 + margin))
                for d in range(d0, d1 + 1):
                    f[dd] = d * w
                    ix[dd] = d
                    fi = f[0]
                    fj = f[1]
                    fk = f[2]
                    kk = ix[2] - z0
                    jj = ix[1] - y0
                    ii = ix[0] - x0
                    if kk < 0 or jj < 0 or ii < 0 or kk >= nzs or jj >= nys or ii >= nxs:
                        bad += 1
                        continue
                    if mask[kk, jj, ii]:
                        continue  # already in (inside the solid, or met by another triangle)
                    # Float filter on the plane: g = n·(centre − a) against the cube's radius h on n.
                    ui = fi - ax
                    uj = fj - ay
                    uk = fk - az
                    g = n0 * ui + n1 * uj + n2 * uk
                    gb = err * (abs(ui) + abs(uj) + abs(uk) + 3.0 * half) + 16.0 * _EPS * (
                        abs(n0 * ui) + abs(n1 * uj) + abs(n2 * uk) + h
                    )
                    if abs(g) > h + gb:
                        continue  # the plane misses the closed cube: separated
                    if abs(g) >= h - gb and _normal_separates(
                        ax,
                        ay,
                        az,
                        bx,
                        by,
                        bz,
                        cx,
                        cy,
                        cz,
                        fi,
                        fj,
                        fk,
                        snx,
                        sny,
                        snz,
                        lexn,
                        supercover,
                        half,
                        exact,
                        scratch,
                    ):
                        continue
                    if dd != 0 and _plane_cross_separates(
                        ax, ay, az, bx, by, bz, cx, cy, cz, fj, fk, 0, supercover, w, exact, scratch
                    ):
                        continue
                    if dd != 1 and _plane_cross_separates(
                        ax, ay, az, bx, by, bz, cx, cy, cz, fk, fi, 1, supercover, w, exact, scratch
                    ):
                        continue
                    if dd != 2 and _plane_cross_separates(
                        ax, ay, az, bx, by, bz, cx, cy, cz, fi, fj, 2, supercover, w, exact, scratch
                    ):
                        continue
                    mask[kk, jj, ii] = True
    return bad


@njit(cache=True)
def least_exponent(v: Floats, kmax: int) -> int:
    """Return the least k ≥ 0 with v·2^k an integer for every value of the 1-D array v; −1 beyond kmax.

    v·2^k is exact (k ≥ 0: no underflow; an overflow to ±inf only for values that are integers already),
    and an integer stays one as k grows, so k only rises: one pass. The product by the float 2^k is the
    fast way; beyond 2^1000 (subnormal input only) 2^k is no float and ldexp takes over.
    """
    k = 0
    scale = 1.0
    for i in range(v.shape[0]):
        u = v[i] * scale if k <= 1000 else math.ldexp(v[i], k)
        while u != math.floor(u):
            if k >= kmax:
                return -1
            k += 1
            scale *= 2.0  # 2^k; inf beyond 2^1023, where it is not used
            u = v[i] * scale if k <= 1000 else math.ldexp(v[i], k)
    return k


@njit(cache=True)
def crop_in_place(mask: BoolMask, i0: int, j0: int, k0: int, nx: int, ny: int, nz: int) -> None:
    """Move mask[k0:k0+nz, j0:j0+ny, i0:i0+nx] to the front of the buffer, as a C-ordered (nz, ny, nx) array.

    Every element moves to a flat index no larger than its own, so an ascending copy never overwrites an
    element not yet read. The caller then shrinks the buffer (``ndarray.resize``).
    """
    flat = mask.reshape(-1)
    sy = mask.shape[2]
    sz = mask.shape[1] * sy
    d = 0
    for k in range(nz):
        for j in range(ny):
            src = (k0 + k) * sz + (j0 + j) * sy + i0
            for i in range(nx):
                flat[d] = flat[src + i]
                d += 1
