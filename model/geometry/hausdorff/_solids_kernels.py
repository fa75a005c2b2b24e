"""Numba kernels of the certified Hausdorff interval between two solids (:mod:`.solids`).

Every function returns either an exact decision or a float enclosure whose error allowance is stated where
it is computed. Conventions:

* a mesh is ``(V, T)``: float64 (n, 3) vertices, int64 (m, 3) outward counter-clockwise triangles;
* a 3D bin grid ``(o, g, n, start, items)`` lists, for each bin, the triangles whose bounding box meets it
  (CSR); a 2D grid over (y, z) does the same for the parity rays along +x;
* a bin index is ``clamp(floor((x − o) / g), 0, n − 1)``, a monotone (non-decreasing) function of x in
  floats: every rounding step (subtraction, division, floor, clamp) is monotone. So if ``lo ≤ y ≤ hi``
  coordinate-wise then ``index(lo) ≤ index(y) ≤ index(hi)``: a triangle that contains a point y is listed
  in y's bin, and a search over the index box of ``[lo, hi]`` sees every triangle with a point in
  ``[lo, hi]`` — no rounding allowance is needed for the grids.

Exactness of the predicates: the parity test and the side tests use
:func:`mrm.geometry.discretize._kernels3d.det3_sign` and :func:`mrm.geometry.discretize._kernels.det_sign`,
exact for coordinates that are 0 or of magnitude in [2⁻²⁵⁰, 2⁵¹] (the caller checks the data and the
query points).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import njit
from mrm.geometry.discretize._kernels import det_sign
from mrm.geometry.discretize._kernels3d import SCRATCH3_SIZE, _edge_side, det3_sign

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

#: Relative allowance on a computed distance (2⁻⁴⁸ = 32 units in the last place).
REL = 2.0**-48
#: Absolute allowance on a point–triangle distance, per unit of the largest coordinate magnitude M.
ABS = 2.0**-44
#: Relative allowance on the sign of the "projection inside the triangle" determinants, per L⁴.
_SIDE = 2.0**-44
#: Cells keep at most this many listed triangles for the exact containment certificate.
KMAX = 48
#: How many (x, y, z) grid bins a dimension may have at most.
MAX_BINS = 256
_TINY = 2.0**-1000


class Mesh(NamedTuple):
    """A mesh with its bin grids (numba passes it to the kernels as a tuple)."""

    V: Floats
    T: Ints
    o: Floats
    g: float
    n: Ints
    s3: Ints
    i3: Ints
    s2: Ints
    i2: Ints


# --------------------------------------------------------------------------------------------- grids
@njit(cache=True)
def _idx(x: float, o: float, g: float, n: int) -> int:
    u = math.floor((x - o) / g)
    if u != u or u < 0.0:
        return 0
    if u > n - 1:
        return n - 1
    return int(u)


@njit(cache=True)
def build_grid3(V: Floats, T: Ints, o: Floats, g: float, n: Ints) -> tuple[Ints, Ints]:
    """CSR lists of the triangles whose bounding box meets each bin (bin id = (k·ny + j)·nx + i)."""
    nb = n[0] * n[1] * n[2]
    counts = np.zeros(nb + 1, np.int64)
    m = T.shape[0]
    rng = np.empty((m, 6), np.int64)
    for t in range(m):
        for ax in range(3):
            lo = min(V[T[t, 0], ax], V[T[t, 1], ax], V[T[t, 2], ax])
            hi = max(V[T[t, 0], ax], V[T[t, 1], ax], V[T[t, 2], ax])
            rng[t, ax] = _idx(lo, o[ax], g, n[ax])
            rng[t, 3 + ax] = _idx(hi, o[ax], g, n[ax])
        for k in range(rng[t, 2], rng[t, 5] + 1):
            for j in range(rng[t, 1], rng[t, 4] + 1):
                for i in range(rng[t, 0], rng[t, 3] + 1):
                    counts[(k * n[1] + j) * n[0] + i + 1] += 1
    start = np.cumsum(counts)
    fill = start[:-1].copy()
    items = np.empty(start[-1], np.int64)
    for t in range(m):
        for k in range(rng[t, 2], rng[t, 5] + 1):
            for j in range(rng[t, 1], rng[t, 4] + 1):
                for i in range(rng[t, 0], rng[t, 3] + 1):
                    b = (k * n[1] + j) * n[0] + i
                    items[fill[b]] = t
                    fill[b] += 1
    return start, items


@njit(cache=True)
def build_grid2(V: Floats, T: Ints, o: Floats, g: float, n: Ints) -> tuple[Ints, Ints]:
    """CSR lists of the triangles whose (y, z) bounding box meets each (y, z) bin (id = k·ny + j)."""
    nb = n[1] * n[2]
    counts = np.zeros(nb + 1, np.int64)
    m = T.shape[0]
    rng = np.empty((m, 4), np.int64)
    for t in range(m):
        for q in range(2):
            ax = q + 1
            lo = min(V[T[t, 0], ax], V[T[t, 1], ax], V[T[t, 2], ax])
            hi = max(V[T[t, 0], ax], V[T[t, 1], ax], V[T[t, 2], ax])
            rng[t, q] = _idx(lo, o[ax], g, n[ax])
            rng[t, 2 + q] = _idx(hi, o[ax], g, n[ax])
        for k in range(rng[t, 1], rng[t, 3] + 1):
            for j in range(rng[t, 0], rng[t, 2] + 1):
                counts[k * n[1] + j + 1] += 1
    start = np.cumsum(counts)
    fill = start[:-1].copy()
    items = np.empty(start[-1], np.int64)
    for t in range(m):
        for k in range(rng[t, 1], rng[t, 3] + 1):
            for j in range(rng[t, 0], rng[t, 2] + 1):
                b = k * n[1] + j
                items[fill[b]] = t
                fill[b] += 1
    return start, items


# ------------------------------------------------------------------------------------------- parity
@njit(cache=True)
def inside(qx: float, qy: float, qz: float, m: Mesh, e: Floats) -> bool:
    """Whether q + τ, τ = (ε, ε², ε³) infinitesimal, lies inside the closed mesh (exact; even-odd rule).

    The ray {q + τ + (s, 0, 0), s > 0} meets no vertex and no edge. A triangle whose (y, z) projection is
    flat is never crossed; otherwise it is crossed when (q_y + ε², q_z + ε³) is inside its projection (the
    three edge signs equal its orientation) and its plane is met beyond q_x + ε, i.e. the crossing
    abscissa X satisfies X > q_x (a tie X = q_x loses against the ε). If q + τ is inside, q belongs to the
    closed solid; if q + τ is outside but q belongs to the solid, q lies on the surface.
    """
    V, T, o, g, n, start, items = m.V, m.T, m.o, m.g, m.n, m.s2, m.i2
    if T.shape[0] == 0:
        return False
    j = _idx(qy, o[1], g, n[1])
    k = _idx(qz, o[2], g, n[2])
    b = k * n[1] + j
    par = False
    for p in range(start[b], start[b + 1]):
        t = items[p]
        a0 = T[t, 0]
        a1 = T[t, 1]
        a2 = T[t, 2]
        ay, az = V[a0, 1], V[a0, 2]
        by, bz = V[a1, 1], V[a1, 2]
        cy, cz = V[a2, 1], V[a2, 2]
        if qy < min(ay, by, cy) or qy > max(ay, by, cy) or qz < min(az, bz, cz) or qz > max(az, bz, cz):
            continue
        s = det_sign(by, ay, cz, az, bz, az, cy, ay, False, e)
        if s == 0:
            continue
        if _edge_side(ay, az, by, bz, qy, qz, False, e) != s:
            continue
        if _edge_side(by, bz, cy, cz, qy, qz, False, e) != s:
            continue
        if _edge_side(cy, cz, ay, az, qy, qz, False, e) != s:
            continue
        d = det3_sign(V[a0, 0], ay, az, V[a1, 0], by, bz, V[a2, 0], cy, cz, qx, qy, qz, False, e)
        if s * d > 0:
            par = not par
    return par


# -------------------------------------------------------------------------------- point–triangle distance
@njit(cache=True)
def _seg(ax: float, ay: float, az: float, bx: float, by: float, bz: float) -> float:
    # Distance from the origin to the segment [a, b] (floats; see tri_dist for the allowance).
    ex = bx - ax
    ey = by - ay
    ez = bz - az
    ee = ex * ex + ey * ey + ez * ez
    t = 0.0
    if ee > 0.0:
        t = -(ax * ex + ay * ey + az * ez) / ee
        if t < 0.0:
            t = 0.0
        elif t > 1.0:
            t = 1.0
    wx = ax + t * ex
    wy = ay + t * ey
    wz = az + t * ez
    return math.sqrt(wx * wx + wy * wy + wz * wz)


@njit(cache=True)
def tri_dist(
    qx: float, qy: float, qz: float, V: Floats, T: Ints, t: int, alpha: float
) -> tuple[float, float]:
    """An enclosure [lo, hi] of the exact distance from q to triangle t (see the allowance below).

    Allowance (u = 2⁻⁵³, M ≥ every |coordinate| of q and of the triangle, ``alpha = ABS·M = 512·u·M``):

    * translating the vertices to q (p_k = fl(v_k − q)) moves each by at most u·|v_k − q| ≤ 2u·M per
      coordinate, 2√3·u·M ≈ 3.5u·M in length; the triangle T' of the rounded p_k is within that Hausdorff
      distance of T − q, so d(q, T) = d(0, T') ± 3.5u·M. The rest bounds d(0, T').
    * a segment [p, p'] (|p|, |p'| ≤ 2√3·M): the computed parameter t differs from the exact clamped one by
      at most (γ₃|p||e| + γ₅|p||e|)/|e|² (the dot product's absolute error, the division's relative error,
      clamping is 1-Lipschitz), which moves the point by ≤ 9u·|p| ≤ 31u·M; e = fl(p' − p) is off by
      ≤ u|p' − p| ≤ 7u·M; evaluating p + t·e costs ≤ 2u(|p_i| + |e_i|) per coordinate, ≤ 21u·M in length;
      and the norm's sqrt of a sum of squares has relative error ≤ 3u. Total: ≤ 63u·M + 3u·relative.
    * the plane: the computed normal n' = fl(e₁ × e₂) differs from the exact one by |Δn| ≤ 8u·L² (L the sum
      of the 1-norms of p₀, p₁, p₂), so |p₀·n'|/|n'| is within β = 2⁻⁴⁵·|p₀|₁·L²/|n'| (≥ 2(|p₀||Δn| +
      3u|p₀||n'|)/|n'|) of |p₀·n|/|n| while |n'| ≥ 2⁻⁴⁰·L² (below that the plane is not used). The three
      signs "the projection is inside" (n'·(p_i × p_j)) have errors ≤ 15u·L⁴ < 2⁻⁴⁴·L⁴: a sign is trusted
      only beyond that margin. The plane distance is always ≤ the distance (a lower bound whenever the
      projection may be inside); it is used as an upper bound only when the projection is certainly
      inside; the minimum over the three edges is always an upper bound; and ``min edge − inradius`` is
      always a lower bound (inradius = |n|/perimeter, taken with a 2⁻⁴⁰ relative margin).

    So lo = (1 − 2⁻⁴⁸)·lo' − alpha and hi = (1 + 2⁻⁴⁸)·hi' + alpha enclose the exact distance, with
    alpha = 512u·M ≥ 8 × the 66u·M above and 2⁻⁴⁸ = 32u ≥ 8 × the relative 4u of a float norm.
    """
    a = T[t, 0]
    b = T[t, 1]
    c = T[t, 2]
    p0x = V[a, 0] - qx
    p0y = V[a, 1] - qy
    p0z = V[a, 2] - qz
    p1x = V[b, 0] - qx
    p1y = V[b, 1] - qy
    p1z = V[b, 2] - qz
    p2x = V[c, 0] - qx
    p2y = V[c, 1] - qy
    p2z = V[c, 2] - qz
    d01 = _seg(p0x, p0y, p0z, p1x, p1y, p1z)
    d12 = _seg(p1x, p1y, p1z, p2x, p2y, p2z)
    d20 = _seg(p2x, p2y, p2z, p0x, p0y, p0z)
    segmin = min(d01, d12, d20)
    lo_raw = segmin
    hi_raw = segmin
    e1x = p1x - p0x
    e1y = p1y - p0y
    e1z = p1z - p0z
    e2x = p2x - p0x
    e2y = p2y - p0y
    e2z = p2z - p0z
    nx = e1y * e2z - e1z * e2y
    ny = e1z * e2x - e1x * e2z
    nz = e1x * e2y - e1y * e2x
    nl = math.sqrt(nx * nx + ny * ny + nz * nz)
    n0 = abs(p0x) + abs(p0y) + abs(p0z)
    L = n0 + abs(p1x) + abs(p1y) + abs(p1z) + abs(p2x) + abs(p2y) + abs(p2z)
    perim = (
        math.sqrt(e1x * e1x + e1y * e1y + e1z * e1z)
        + math.sqrt(e2x * e2x + e2y * e2y + e2z * e2z)
        + math.sqrt((p2x - p1x) ** 2 + (p2y - p1y) ** 2 + (p2z - p1z) ** 2)
    )
    if perim > 0.0:  # (0 only when the three rounded vertices are equal: T' is that point)
        inr = (nl + 2.0**-45 * L * L) / perim * (1.0 + 2.0**-40)
        may_inside = True  # a flat float normal (nl = 0) cannot tell: T' may still have a tiny area
        surely_inside = False
        if nl > 0.0:
            # Three signs n'·(p_i × p_j): all ≥ 0 when the projection of the origin is inside (closed).
            s0 = nx * (p0y * p1z - p0z * p1y) + ny * (p0z * p1x - p0x * p1z) + nz * (p0x * p1y - p0y * p1x)
            s1 = nx * (p1y * p2z - p1z * p2y) + ny * (p1z * p2x - p1x * p2z) + nz * (p1x * p2y - p1y * p2x)
            s2 = nx * (p2y * p0z - p2z * p0y) + ny * (p2z * p0x - p2x * p0z) + nz * (p2x * p0y - p2y * p0x)
            sig = _SIDE * (L * L) * (L * L)
            may_inside = s0 >= -sig and s1 >= -sig and s2 >= -sig
            surely_inside = s0 > sig and s1 > sig and s2 > sig
        if may_inside:
            lo_raw = segmin - inr
            if nl > 2.0**-40 * L * L:
                dp = abs(p0x * nx + p0y * ny + p0z * nz) / nl
                beta = 2.0**-45 * n0 * L * L / nl
                lo_raw = max(lo_raw, dp - beta)
                if surely_inside:
                    hi_raw = min(hi_raw, dp + beta)
    lo = lo_raw * (1.0 - REL) - alpha
    if lo < 0.0:
        lo = 0.0
    hi = hi_raw * (1.0 + REL) + alpha
    return lo, hi


# ---------------------------------------------------------------------------------- nearest triangle
@njit(cache=True)
def _reach(x: float, d: float, sign: float) -> float:
    # A float y with y ≤ x − d (sign −1) or y ≥ x + d (sign +1) exactly: the slack 2⁻⁵¹(|x| + d) exceeds
    # the rounding of the sum and of the slack itself.
    slack = d + 2.0**-50 * (abs(x) + d) + _TINY
    return x + sign * slack


@njit(cache=True)
def nearest(
    qx: float, qy: float, qz: float, m: Mesh, stamp: Ints, qid: int, alpha: float
) -> tuple[float, float, int]:
    """[lo, hi] of the distance from q to the nearest triangle, and that triangle (−1 when none).

    Bins are visited in growing index boxes around q's bin until the box holds the index box of
    [q − D, q + D] for D the best upper bound so far: the nearest triangle has a point within D of q, so it
    is listed in a visited bin (monotone indices), and the minimum of the visited lower bounds is a lower
    bound of the true minimum.
    """
    V, T, o, g, n, start, items = m.V, m.T, m.o, m.g, m.n, m.s3, m.i3
    if T.shape[0] == 0:
        return math.inf, math.inf, -1
    i0 = _idx(qx, o[0], g, n[0])
    j0 = _idx(qy, o[1], g, n[1])
    k0 = _idx(qz, o[2], g, n[2])
    bx0, bx1, by0, by1, bz0, bz1 = i0, i0, j0, j0, k0, k0
    px0, px1, py0, py1, pz0, pz1 = i0, i0 - 1, j0, j0, k0, k0  # previous box (empty at first)
    best_lo = math.inf
    best_hi = math.inf
    best_t = -1
    while True:
        for k in range(bz0, bz1 + 1):
            for j in range(by0, by1 + 1):
                for i in range(bx0, bx1 + 1):
                    if px0 <= i <= px1 and py0 <= j <= py1 and pz0 <= k <= pz1:
                        continue
                    b = (k * n[1] + j) * n[0] + i
                    for p in range(start[b], start[b + 1]):
                        t = items[p]
                        if stamp[t] == qid:
                            continue
                        stamp[t] = qid
                        lo, hi = tri_dist(qx, qy, qz, V, T, t, alpha)
                        if lo < best_lo:
                            best_lo = lo
                        if hi < best_hi:
                            best_hi = hi
                            best_t = t
        if best_hi < math.inf:
            rx0 = _idx(_reach(qx, best_hi, -1.0), o[0], g, n[0])
            rx1 = _idx(_reach(qx, best_hi, 1.0), o[0], g, n[0])
            ry0 = _idx(_reach(qy, best_hi, -1.0), o[1], g, n[1])
            ry1 = _idx(_reach(qy, best_hi, 1.0), o[1], g, n[1])
            rz0 = _idx(_reach(qz, best_hi, -1.0), o[2], g, n[2])
            rz1 = _idx(_reach(qz, best_hi, 1.0), o[2], g, n[2])
        else:
            rx0, rx1, ry0, ry1, rz0, rz1 = 0, n[0] - 1, 0, n[1] - 1, 0, n[2] - 1
        if bx0 <= rx0 and bx1 >= rx1 and by0 <= ry0 and by1 >= ry1 and bz0 <= rz0 and bz1 >= rz1:
            break
        px0, px1, py0, py1, pz0, pz1 = bx0, bx1, by0, by1, bz0, bz1
        if bx0 > rx0:
            bx0 -= 1
        if bx1 < rx1:
            bx1 += 1
        if by0 > ry0:
            by0 -= 1
        if by1 < ry1:
            by1 += 1
        if bz0 > rz0:
            bz0 -= 1
        if bz1 < rz1:
            bz1 += 1
    return best_lo, best_hi, best_t


# ------------------------------------------------------------------------------- box–triangle test
@njit(cache=True)
def may_meet(V: Floats, T: Ints, t: int, cx: float, cy: float, cz: float, h: float) -> bool:
    """False only when triangle t certainly misses the closed cube of centre c and half-side h.

    The bounding boxes are compared exactly (c ± h are exact: the cells are dyadic). The plane test
    |n'·(c − a)| > h·|n'|₁ + σ separates for certain with σ = 2⁻⁴⁴·L_e²·(|c − a|₁ + 3h), L_e the sum of the
    1-norms of the two edge vectors: the computed normal is within 8u·L_e² of the exact one and the
    remaining roundings are relative (≤ 5u) to terms bounded by L_e²·(|c − a|₁ + 3h).
    """
    a = T[t, 0]
    b = T[t, 1]
    c = T[t, 2]
    for ax in range(3):
        lo = min(V[a, ax], V[b, ax], V[c, ax])
        hi = max(V[a, ax], V[b, ax], V[c, ax])
        ce = cx if ax == 0 else (cy if ax == 1 else cz)
        if hi < ce - h or lo > ce + h:
            return False
    e1x = V[b, 0] - V[a, 0]
    e1y = V[b, 1] - V[a, 1]
    e1z = V[b, 2] - V[a, 2]
    e2x = V[c, 0] - V[a, 0]
    e2y = V[c, 1] - V[a, 1]
    e2z = V[c, 2] - V[a, 2]
    nx = e1y * e2z - e1z * e2y
    ny = e1z * e2x - e1x * e2z
    nz = e1x * e2y - e1y * e2x
    dx = cx - V[a, 0]
    dy = cy - V[a, 1]
    dz = cz - V[a, 2]
    dist = abs(nx * dx + ny * dy + nz * dz)
    rad = h * (abs(nx) + abs(ny) + abs(nz))
    le = abs(e1x) + abs(e1y) + abs(e1z) + abs(e2x) + abs(e2y) + abs(e2z)
    sig = 2.0**-44 * le * le * (abs(dx) + abs(dy) + abs(dz) + 3.0 * h)
    return not (dist > rad + sig)


@njit(cache=True)
def tris_in_cube(m: Mesh, stamp: Ints, qid: int, cx: float, cy: float, cz: float, h: float, out: Ints) -> int:
    """The triangles that may meet the cube (at most ``out.size`` listed); return their count (may exceed)."""
    V, T, o, g, n, start, items = m.V, m.T, m.o, m.g, m.n, m.s3, m.i3
    if T.shape[0] == 0:
        return 0
    i0 = _idx(cx - h, o[0], g, n[0])
    i1 = _idx(cx + h, o[0], g, n[0])
    j0 = _idx(cy - h, o[1], g, n[1])
    j1 = _idx(cy + h, o[1], g, n[1])
    k0 = _idx(cz - h, o[2], g, n[2])
    k1 = _idx(cz + h, o[2], g, n[2])
    cnt = 0
    for k in range(k0, k1 + 1):
        for j in range(j0, j1 + 1):
            for i in range(i0, i1 + 1):
                b = (k * n[1] + j) * n[0] + i
                for p in range(start[b], start[b + 1]):
                    t = items[p]
                    if stamp[t] == qid:
                        continue
                    stamp[t] = qid
                    if may_meet(V, T, t, cx, cy, cz, h):
                        if cnt < out.size:
                            out[cnt] = t
                        cnt += 1
    return cnt


# ------------------------------------------------------------------------------------- the searches
@njit(cache=True)
def _inner(V: Floats, T: Ints, t: int, x: float, y: float, z: float, e: Floats) -> int:
    # Sign of ((b − a) × (c − a))·(a − x): > 0 strictly on the inner side of triangle t's plane.
    a = T[t, 0]
    b = T[t, 1]
    c = T[t, 2]
    return det3_sign(
        V[a, 0], V[a, 1], V[a, 2], V[b, 0], V[b, 1], V[b, 2], V[c, 0], V[c, 1], V[c, 2], x, y, z, False, e
    )


@njit(cache=True)
def vertex_lows(P: Floats, mb: Mesh, alpha: float) -> Floats:
    """Lower bounds of d(p, B) for each row p of P (0 when p + τ is inside B)."""
    out = np.empty(P.shape[0])
    e = np.empty(SCRATCH3_SIZE)
    stamp = np.full(mb.T.shape[0], -1, np.int64)
    for r in range(P.shape[0]):
        x, y, z = P[r, 0], P[r, 1], P[r, 2]
        if inside(x, y, z, mb, e):
            out[r] = 0.0
        else:
            out[r] = nearest(x, y, z, mb, stamp, r, alpha)[0]
    return out


@njit(cache=True)
def _certify_inside_b(
    cx: float,
    cy: float,
    cz: float,
    h: float,
    hq: float,
    lb: Ints,
    nb: int,
    la: Ints,
    na: int,
    ma: Mesh,
    mb: Mesh,
    e: Floats,
) -> bool:
    """Whether C ∩ A ⊆ B is proved exactly (see :mod:`.solids`, "containment").

    ``lb`` lists the triangles of B that may meet the cube Q ⊇ C of half-side ``hq`` (h or 2h), ``la``
    those of A that may meet C (all of them: ``na`` ≤ their room).
    """
    VA, TA, VB, TB = ma.V, ma.T, mb.V, mb.T
    # 1. The listed B triangles are all on the boundary of K = ∩ inner half-spaces (a convex configuration).
    for p in range(nb):
        for q in range(nb):
            if p == q:
                continue
            for w in range(3):
                v = TB[lb[q], w]
                if _inner(VB, TB, lb[p], VB[v, 0], VB[v, 1], VB[v, 2], e) < 0:
                    return False
    # 2. A point z + τ of int K ∩ int Q inside B: then int K ∩ int Q ⊆ B (connected, misses ∂B). The
    # candidates: the centre and the points c ± s·h/2 for s = 1 (and 3 when Q is the doubled cube).
    found = False
    for w in range(17 if hq > h else 9):
        if w == 0:
            zx, zy, zz = cx, cy, cz
        else:
            f = 0.5 * h if w < 9 else 1.5 * h
            zx = cx + (f if (w - 1) & 1 else -f)
            zy = cy + (f if (w - 1) & 2 else -f)
            zz = cz + (f if (w - 1) & 4 else -f)
        ok = True
        for p in range(nb):
            if _inner(VB, TB, lb[p], zx, zy, zz, e) <= 0:
                ok = False
                break
        if ok and inside(zx, zy, zz, mb, e):
            found = True
            break
    if not found:
        return False
    # 3. Every listed A triangle lies in K (its vertices do), and so does every corner of C that is in A.
    for p in range(na):
        for w in range(3):
            v = TA[la[p], w]
            for q in range(nb):
                if _inner(VB, TB, lb[q], VA[v, 0], VA[v, 1], VA[v, 2], e) < 0:
                    return False
    for w in range(8):
        zx = cx + (h if w & 1 else -h)
        zy = cy + (h if w & 2 else -h)
        zz = cz + (h if w & 4 else -h)
        ok = True
        for q in range(nb):
            if _inner(VB, TB, lb[q], zx, zy, zz, e) < 0:
                ok = False
                break
        if not ok and inside(zx, zy, zz, ma, e):
            return False
    return True


@njit(cache=True)
def _same_triangles(la: Ints, na: int, VA: Floats, TA: Ints, lb: Ints, nb: int, VB: Floats, TB: Ints) -> bool:
    """Whether the listed triangles of A and of B are the same oriented triangles (equal coordinates)."""
    if na != nb:
        return False
    for p in range(na):
        ta = la[p]
        found = False
        for q in range(nb):
            tb = lb[q]
            for rot in range(3):
                same = True
                for w in range(3):
                    va = TA[ta, w]
                    vb = TB[tb, (w + rot) % 3]
                    if VA[va, 0] != VB[vb, 0] or VA[va, 1] != VB[vb, 1] or VA[va, 2] != VB[vb, 2]:
                        same = False
                        break
                if same:
                    found = True
                    break
            if found:
                break
        if not found:
            return False
    return True


@njit(cache=True)
def _phi(x: float, y: float, z: float, VB: Floats, TB: Ints, t: int, alpha: float, kind: int) -> float:
    # An upper bound of the convex φ at x: kind 0, the distance to triangle t; kind 1, max(0, signed
    # distance to t's plane, positive outward) with the allowance of :func:`_flat_under`.
    if kind == 0:
        return tri_dist(x, y, z, VB, TB, t, alpha)[1]
    a = TB[t, 0]
    b = TB[t, 1]
    c = TB[t, 2]
    e1x = VB[b, 0] - VB[a, 0]
    e1y = VB[b, 1] - VB[a, 1]
    e1z = VB[b, 2] - VB[a, 2]
    e2x = VB[c, 0] - VB[a, 0]
    e2y = VB[c, 1] - VB[a, 1]
    e2z = VB[c, 2] - VB[a, 2]
    nx = e1y * e2z - e1z * e2y
    ny = e1z * e2x - e1x * e2z
    nz = e1x * e2y - e1y * e2x
    nl = math.sqrt(nx * nx + ny * ny + nz * nz)
    dx = x - VB[a, 0]
    dy = y - VB[a, 1]
    dz = z - VB[a, 2]
    le = abs(e1x) + abs(e1y) + abs(e1z) + abs(e2x) + abs(e2y) + abs(e2z)
    s = (nx * dx + ny * dy + nz * dz) / nl
    err = 2.0**-44 * (abs(dx) + abs(dy) + abs(dz)) * le * le / nl + alpha
    v = s * (1.0 + REL) + err if s > 0.0 else s * (1.0 - REL) + err
    return float(max(v, 0.0))


@njit(cache=True)
def _piece_points(
    V: Floats, T: Ints, t: int, cx: float, cy: float, cz: float, h: float, ecap: float, out: Floats
) -> int:
    """Points within ``ecap`` of every vertex of the piece T ∩ C (T = triangle t); −1 when not certain.

    A vertex of the convex polygon T ∩ C meets two of its boundary lines: (a) a vertex of T inside C
    (exact comparisons), (b) an edge of T crossing a face plane of C (the crossing's own coordinate is the
    plane's exactly; the two others are interpolated with an error ≤ 30u·M ≪ ecap = 2⁻³⁶·M), or (c) an edge
    line of C crossing T's plane (solved with an error estimate; −1 when the estimate exceeds ecap/2, a
    near-parallel edge). Every candidate that may be such a vertex is returned (the tests are widened by the
    errors), so each true vertex has a returned point within ecap: the piece lies within ecap of their
    convex hull, and a 1-Lipschitz convex φ is at most their maximum + ecap on it.
    """
    lo0, lo1, lo2 = cx - h, cy - h, cz - h
    hi0, hi1, hi2 = cx + h, cy + h, cz + h
    m = 2.0 * ecap
    cnt = 0
    # (a) the vertices of T in C.
    for w in range(3):
        v = T[t, w]
        if lo0 <= V[v, 0] <= hi0 and lo1 <= V[v, 1] <= hi1 and lo2 <= V[v, 2] <= hi2:
            out[cnt, 0] = V[v, 0]
            out[cnt, 1] = V[v, 1]
            out[cnt, 2] = V[v, 2]
            cnt += 1
    # (b) the edges of T across the face planes of C.
    for w in range(3):
        p = T[t, w]
        q = T[t, (w + 1) % 3]
        for ax in range(3):
            pa = V[p, ax]
            qa = V[q, ax]
            if pa == qa:
                continue
            for side in range(2):
                if ax == 0:
                    x = lo0 if side == 0 else hi0
                elif ax == 1:
                    x = lo1 if side == 0 else hi1
                else:
                    x = lo2 if side == 0 else hi2
                if x < min(pa, qa) or x > max(pa, qa):
                    continue
                f = (x - pa) / (qa - pa)
                ok = True
                for k in range(3):
                    if k == ax:
                        out[cnt, k] = x
                        continue
                    y = V[p, k] + f * (V[q, k] - V[p, k])
                    out[cnt, k] = y
                    lo = lo0 if k == 0 else (lo1 if k == 1 else lo2)
                    hi = hi0 if k == 0 else (hi1 if k == 1 else hi2)
                    if y < lo - m or y > hi + m:
                        ok = False
                if ok:
                    cnt += 1
    # (c) the edges of C across the plane of T.
    a = T[t, 0]
    b = T[t, 1]
    c = T[t, 2]
    e1x = V[b, 0] - V[a, 0]
    e1y = V[b, 1] - V[a, 1]
    e1z = V[b, 2] - V[a, 2]
    e2x = V[c, 0] - V[a, 0]
    e2y = V[c, 1] - V[a, 1]
    e2z = V[c, 2] - V[a, 2]
    nx = e1y * e2z - e1z * e2y
    ny = e1z * e2x - e1x * e2z
    nz = e1x * e2y - e1y * e2x
    le = abs(e1x) + abs(e1y) + abs(e1z) + abs(e2x) + abs(e2y) + abs(e2z)
    dn = 2.0**-46 * le * le  # ≥ 8u·L_e², the error of each component of n'
    n1 = abs(nx) + abs(ny) + abs(nz)
    for ax in range(3):
        na = nx if ax == 0 else (ny if ax == 1 else nz)
        if abs(na) <= dn:
            continue  # (nearly) parallel to T's plane: such an edge meets it nowhere or all along
        j = (ax + 1) % 3
        k = (ax + 2) % 3
        nj = nx if j == 0 else (ny if j == 1 else nz)
        nk = nx if k == 0 else (ny if k == 1 else nz)
        lo_a = lo0 if ax == 0 else (lo1 if ax == 1 else lo2)
        hi_a = hi0 if ax == 0 else (hi1 if ax == 1 else hi2)
        for corner in range(4):
            yj = (
                (lo0 if j == 0 else (lo1 if j == 1 else lo2))
                if corner & 1 == 0
                else (hi0 if j == 0 else (hi1 if j == 1 else hi2))
            )
            yk = (
                (lo0 if k == 0 else (lo1 if k == 1 else lo2))
                if corner & 2 == 0
                else (hi0 if k == 0 else (hi1 if k == 1 else hi2))
            )
            num = nx * V[a, 0] + ny * V[a, 1] + nz * V[a, 2] - nj * yj - nk * yk
            sval = num / na
            # |Δnum| ≤ dn·(|a|₁ + |yj| + |yk|) + 5u·(Σ|n_i a_i| + |nj yj| + |nk yk|); dividing by
            # |na| − dn bounds the error of sval, plus |sval|·dn/(|na| − dn) for the error of na itself.
            an = abs(V[a, 0]) + abs(V[a, 1]) + abs(V[a, 2]) + abs(yj) + abs(yk)
            snum = abs(nx * V[a, 0]) + abs(ny * V[a, 1]) + abs(nz * V[a, 2]) + abs(nj * yj) + abs(nk * yk)
            err = (dn * an + 2.0**-50 * snum + abs(sval) * dn) / (abs(na) - dn) + 2.0**-50 * abs(sval)
            if sval < lo_a - m - err or sval > hi_a + m + err:
                continue
            out[cnt, ax] = sval
            out[cnt, j] = yj
            out[cnt, k] = yk
            # Inside T (closed): the three signs n'·((p_{k+1} − p_k) × (x − p_k)) ≥ −margin, the margin
            # covering the point's error (≤ ρ = max(err, ecap)) and the roundings
            # (2⁻⁴⁴·L_e²·|e_k|₁·(|x − p_k|₁ + ρ)). A point certainly outside T is no vertex; one that may be
            # inside but is known only to err > ecap/2 makes the piece uncertain.
            rho = max(err, ecap)
            inside_t = True
            for w in range(3):
                p = T[t, w]
                q = T[t, (w + 1) % 3]
                ex = V[q, 0] - V[p, 0]
                ey = V[q, 1] - V[p, 1]
                ez = V[q, 2] - V[p, 2]
                dx = out[cnt, 0] - V[p, 0]
                dy = out[cnt, 1] - V[p, 1]
                dz = out[cnt, 2] - V[p, 2]
                sg = nx * (ey * dz - ez * dy) + ny * (ez * dx - ex * dz) + nz * (ex * dy - ey * dx)
                e1 = abs(ex) + abs(ey) + abs(ez)
                d1 = abs(dx) + abs(dy) + abs(dz)
                if sg < -(n1 * e1 * 2.0 * rho + 2.0**-44 * le * le * e1 * (d1 + rho)):
                    inside_t = False
                    break
            if inside_t:
                if err > 0.5 * ecap:
                    return -1
                cnt += 1
    return cnt


@njit(cache=True)
def _restricted_bound(
    cx: float,
    cy: float,
    cz: float,
    h: float,
    corner_in_a: npt.NDArray[np.bool_],
    la: Ints,
    na: int,
    ma: Mesh,
    mb: Mesh,
    t: int,
    alpha: float,
    kind: int,
    ecap: float,
    pts: Floats,
) -> float:
    """An upper bound of the convex, 1-Lipschitz φ over C ∩ A (see :func:`process_cells`).

    C ∩ A lies in the convex hull of C's corners in A and of the pieces T_A ∩ C; on a piece, φ is at most
    the smaller of its maxima over T_A's vertices, over C's corners, and over the piece's points (+ ecap).
    """
    VA, TA, VB, TB = ma.V, ma.T, mb.V, mb.T
    mc = 0.0
    best = 0.0
    for w in range(8):
        zx = cx + (h if w & 1 else -h)
        zy = cy + (h if w & 2 else -h)
        zz = cz + (h if w & 4 else -h)
        v = _phi(zx, zy, zz, VB, TB, t, alpha, kind)
        mc = max(mc, v)
        if corner_in_a[w]:
            best = max(best, v)
    for p in range(na):
        pv = 0.0
        for w in range(3):
            q = TA[la[p], w]
            pv = max(pv, _phi(VA[q, 0], VA[q, 1], VA[q, 2], VB, TB, t, alpha, kind))
        piece = min(pv, mc)
        if piece > best:
            cnt = _piece_points(VA, TA, la[p], cx, cy, cz, h, ecap, pts)
            if cnt >= 0:
                g = 0.0
                for w in range(cnt):
                    g = max(g, _phi(pts[w, 0], pts[w, 1], pts[w, 2], VB, TB, t, alpha, kind))
                g = g + ecap
                g = g + g * 2.0**-51
                piece = min(piece, g)
        best = max(best, piece)
    return best


@njit(cache=True)
def _exact_range(v: float) -> bool:
    # The exact predicates' range for a query coordinate: 0 or 2⁻²⁴⁰ ≤ |v| ≤ 2⁵⁰ (the solids' own check).
    a = abs(v)
    return a == 0.0 or (2.0**-240 <= a <= 2.0**50)


@njit(cache=True)
def _flat_under(
    cx: float, cy: float, cz: float, h: float, t: int, mb: Mesh, stamp: Ints, qid: int, big: float, e: Floats
) -> bool:
    """Whether d(x, B) ≤ max(0, s(x)) on C, s the signed distance to the plane H of B's triangle t.

    Z is a box holding C, the projections of C's corners on H and those pushed h further in (computed in
    floats, widened by more than their error, see below). When every triangle of B that may meet Z lies in
    H (exact signs) and a point of Z strictly on the inner side of H is inside B (exact parity), the inner
    side of H in Z (convex, missing ∂B) lies in B with its closure, which holds the projection
    π(x) ∈ H ∩ Z of every
    x ∈ C: then d(x, B) ≤ |x − π(x)| = s(x) outside, and d(x, B) = 0 on the inner side. ``_phi`` with kind 1
    bounds max(0, s): s is computed with n' = fl(e₁ × e₂) (within 8u·L_e² of the exact normal) and a few
    relative roundings, covered by 2⁻⁴⁴·|x − a|₁·L_e²/|n'| plus the usual alpha, while |n'| ≥ 2⁻⁴⁰·L_e².
    """
    VB, TB, o3, g3, n3, s3, i3 = mb.V, mb.T, mb.o, mb.g, mb.n, mb.s3, mb.i3
    a = TB[t, 0]
    b = TB[t, 1]
    c = TB[t, 2]
    e1x = VB[b, 0] - VB[a, 0]
    e1y = VB[b, 1] - VB[a, 1]
    e1z = VB[b, 2] - VB[a, 2]
    e2x = VB[c, 0] - VB[a, 0]
    e2y = VB[c, 1] - VB[a, 1]
    e2z = VB[c, 2] - VB[a, 2]
    nx = e1y * e2z - e1z * e2y
    ny = e1z * e2x - e1x * e2z
    nz = e1x * e2y - e1y * e2x
    nl = math.sqrt(nx * nx + ny * ny + nz * nz)
    le = abs(e1x) + abs(e1y) + abs(e1z) + abs(e2x) + abs(e2y) + abs(e2z)
    if not nl > 2.0**-40 * le * le:
        return False
    ux, uy, uz = nx / nl, ny / nl, nz / nl
    lox, loy, loz = cx - h, cy - h, cz - h
    hix, hiy, hiz = cx + h, cy + h, cz + h
    smax = 0.0
    for w in range(8):
        zx = cx + (h if w & 1 else -h)
        zy = cy + (h if w & 2 else -h)
        zz = cz + (h if w & 4 else -h)
        s = ux * (zx - VB[a, 0]) + uy * (zy - VB[a, 1]) + uz * (zz - VB[a, 2])
        # The projection, and the projection pushed h further to the inner side (room for a test point).
        for depth in (s, s + h):
            px, py, pz = zx - depth * ux, zy - depth * uy, zz - depth * uz
            lox, loy, loz = min(lox, px), min(loy, py), min(loz, pz)
            hix, hiy, hiz = max(hix, px), max(hiy, py), max(hiz, pz)
        smax = max(smax, abs(s))
    # The projections' error: roundings (≪ 2⁻⁴⁰·(big + |s|)) and the direction of n', off by at most
    # 2√3·|Δn|/|n| with |Δn| ≤ √3·2⁻⁴⁶·L_e² per the normal's allowance.
    m = 2.0**-40 * (big + smax) + 8.0 * smax * 2.0**-46 * le * le / nl
    lox, loy, loz = lox - m, loy - m, loz - m
    hix, hiy, hiz = hix + m, hiy + m, hiz + m
    # The triangles of B that may meet Z (bounding boxes, exact comparisons): all must lie in H.
    i0 = _idx(lox, o3[0], g3, n3[0])
    i1 = _idx(hix, o3[0], g3, n3[0])
    j0 = _idx(loy, o3[1], g3, n3[1])
    j1 = _idx(hiy, o3[1], g3, n3[1])
    k0 = _idx(loz, o3[2], g3, n3[2])
    k1 = _idx(hiz, o3[2], g3, n3[2])
    if (i1 - i0 + 1) * (j1 - j0 + 1) * (k1 - k0 + 1) > 125:
        return False
    cnt = 0
    for k in range(k0, k1 + 1):
        for j in range(j0, j1 + 1):
            for i in range(i0, i1 + 1):
                bb = (k * n3[1] + j) * n3[0] + i
                for p in range(s3[bb], s3[bb + 1]):
                    q = i3[p]
                    if stamp[q] == qid:
                        continue
                    stamp[q] = qid
                    out = False
                    for ax in range(3):
                        lo = min(VB[TB[q, 0], ax], VB[TB[q, 1], ax], VB[TB[q, 2], ax])
                        hi = max(VB[TB[q, 0], ax], VB[TB[q, 1], ax], VB[TB[q, 2], ax])
                        zl = lox if ax == 0 else (loy if ax == 1 else loz)
                        zh = hix if ax == 0 else (hiy if ax == 1 else hiz)
                        if hi < zl or lo > zh:
                            out = True
                    if out:
                        continue
                    cnt += 1
                    if cnt > 4 * KMAX:
                        return False
                    for w in range(3):
                        v = TB[q, w]
                        if _inner(VB, TB, t, VB[v, 0], VB[v, 1], VB[v, 2], e) != 0:
                            return False
    # A point strictly inside Z, strictly on the inner side, inside B: the centre's projection pushed h/2
    # inwards, or points a quarter of Z's extent from its centre.
    sc = ux * (cx - VB[a, 0]) + uy * (cy - VB[a, 1]) + uz * (cz - VB[a, 2]) + 0.5 * h
    for w in range(9):
        if w == 8:
            zx, zy, zz = cx - sc * ux, cy - sc * uy, cz - sc * uz
        else:
            zx = 0.5 * (lox + hix) + (0.25 if w & 1 else -0.25) * (hix - lox)
            zy = 0.5 * (loy + hiy) + (0.25 if w & 2 else -0.25) * (hiy - loy)
            zz = 0.5 * (loz + hiz) + (0.25 if w & 4 else -0.25) * (hiz - loz)
        if not (lox < zx < hix and loy < zy < hiy and loz < zz < hiz):
            continue
        if not (_exact_range(zx) and _exact_range(zy) and _exact_range(zz)):
            continue  # a computed point outside the predicates' exact range
        if _inner(VB, TB, t, zx, zy, zz, e) > 0 and inside(zx, zy, zz, mb, e):
            return True
    return False


@njit(cache=True)
def _add_planes(
    lst: Ints, cnt: int, m: Mesh, cx: float, cy: float, cz: float, hq: float, vals: Floats, nv: Ints
) -> bool:
    # Record the axis-aligned plane of each listed triangle that cuts int Q; False for a slanted triangle.
    V, T = m.V, m.T
    for p in range(cnt):
        t = lst[p]
        found = False
        for ax in range(3):
            x = V[T[t, 0], ax]
            if V[T[t, 1], ax] != x or V[T[t, 2], ax] != x:
                continue
            found = True
            c = cx if ax == 0 else (cy if ax == 1 else cz)
            if not (c - hq < x < c + hq):
                break  # on Q's boundary or beyond: it does not cut int Q
            seen = False
            for u in range(nv[ax]):
                if vals[ax, u] == x:
                    seen = True
            if not seen:
                vals[ax, nv[ax]] = x
                nv[ax] += 1
            break
        if not found:
            return False
    return True


@njit(cache=True)
def _axis_cells_inside(
    cx: float,
    cy: float,
    cz: float,
    hq: float,
    la: Ints,
    na: int,
    lb: Ints,
    nb: int,
    ma: Mesh,
    mb: Mesh,
    vals: Floats,
    e: Floats,
) -> bool:
    """Whether A ∩ int Q ⊆ B is proved when every triangle of A and B that may meet Q is axis-aligned.

    The planes of those triangles cut int Q into open boxes; each misses both surfaces, so it lies inside
    or outside each solid as a whole, as its midpoint + τ does (exact parity). If every box inside A is
    inside B, then A ∩ int Q — the closure of A's interior, whose points off the planes lie in those boxes —
    is in the closure of B's boxes, in B. (Voxel reconstructions are axis-aligned: shared faces, edges and
    corners, convex or not and however triangulated, are settled here.)
    """
    nv = np.zeros(3, np.int64)
    if not _add_planes(la, na, ma, cx, cy, cz, hq, vals, nv):
        return False
    if not _add_planes(lb, nb, mb, cx, cy, cz, hq, vals, nv):
        return False
    if (nv[0] + 1) * (nv[1] + 1) * (nv[2] + 1) > 512:
        return False
    for ax in range(3):
        vals[ax, : nv[ax]] = np.sort(vals[ax, : nv[ax]])
    for i in range(nv[0] + 1):
        x0 = cx - hq if i == 0 else vals[0, i - 1]
        x1 = cx + hq if i == nv[0] else vals[0, i]
        zx = 0.5 * x0 + 0.5 * x1
        for j in range(nv[1] + 1):
            y0 = cy - hq if j == 0 else vals[1, j - 1]
            y1 = cy + hq if j == nv[1] else vals[1, j]
            zy = 0.5 * y0 + 0.5 * y1
            for k in range(nv[2] + 1):
                z0 = cz - hq if k == 0 else vals[2, k - 1]
                z1 = cz + hq if k == nv[2] else vals[2, k]
                zz = 0.5 * z0 + 0.5 * z1
                if not (x0 < zx < x1 and y0 < zy < y1 and z0 < zz < z1):
                    return False  # no float strictly inside: cannot sample this box
                if not (_exact_range(zx) and _exact_range(zy) and _exact_range(zz)):
                    return False
                if inside(zx, zy, zz, ma, e) and not inside(zx, zy, zz, mb, e):
                    return False
    return True


@njit(cache=True)
def process_cells(
    C: Floats, h: float, r_up: float, ma: Mesh, mb: Mesh, alpha: float, big: float, settle: float
) -> tuple[Floats, Floats]:
    """Upper bounds of max d(·, B) over C ∩ A, and lower bounds from the centre, for cubes C (centres C).

    hi = −inf marks a cell that certainly misses A; lo = −inf a centre not proved to be in A. The costlier
    bounds are skipped once hi ≤ ``settle`` (the current lower bound plus the tolerance). ``big`` ≥ every
    coordinate magnitude.
    """
    m = C.shape[0]
    his = np.empty(m)
    los = np.full(m, -math.inf)
    e = np.empty(SCRATCH3_SIZE)
    stamp_a = np.full(ma.T.shape[0], -1, np.int64)
    stamp_b = np.full(mb.T.shape[0], -1, np.int64)
    la = np.empty(KMAX, np.int64)
    lb = np.empty(KMAX, np.int64)
    lq = np.empty(KMAX, np.int64)
    vals = np.empty((3, 2 * KMAX + 2))
    corner_in_a = np.zeros(8, np.bool_)
    pts = np.empty((40, 3))
    cand = np.empty(9, np.int64)
    ecap = 2.0**-36 * big
    qid = 0
    for r in range(m):
        cx, cy, cz = C[r, 0], C[r, 1], C[r, 2]
        qid += 1
        na = tris_in_cube(ma, stamp_a, qid, cx, cy, cz, h, la)
        c_in_a = inside(cx, cy, cz, ma, e)
        if na == 0 and not c_in_a:
            his[r] = -math.inf  # C ∩ ∂A = ∅ and the centre is outside: C misses A
            continue
        c_in_b = inside(cx, cy, cz, mb, e)
        tbest = -1
        if c_in_b:
            flo = 0.0
            fhi = 0.0
        else:
            flo, fhi, tbest = nearest(cx, cy, cz, mb, stamp_b, qid, alpha)
        if c_in_a:
            los[r] = flo
        hi = fhi + r_up
        hi = hi + hi * 2.0**-51  # outward rounding of the sum
        qid += 2
        nb = tris_in_cube(mb, stamp_b, qid, cx, cy, cz, h, lb)
        if nb == 0:
            if c_in_b:
                hi = 0.0  # C ∩ ∂B = ∅ and the centre is inside: C ⊆ B
        elif nb <= KMAX and na <= KMAX and _certify_inside_b(cx, cy, cz, h, h, lb, nb, la, na, ma, mb, e):
            hi = 0.0
        if hi > 0.0 and 0 < nb <= KMAX and na <= KMAX:
            # A cube touching B only on its boundary has no interior point in B: try the doubled cube.
            qid += 1
            nq = tris_in_cube(mb, stamp_b, qid, cx, cy, cz, 2.0 * h, lb)
            if 0 < nq <= KMAX and _certify_inside_b(cx, cy, cz, h, 2.0 * h, lb, nq, la, na, ma, mb, e):
                hi = 0.0
            elif 0 < nq <= KMAX and c_in_a == c_in_b:
                # The same boundary in Q (the same oriented triangles may meet Q): every component of
                # int Q minus the surface is on the same side of it for both solids, so A ∩ int Q = B ∩ int Q
                # and C ∩ A ⊆ B (C lies in int Q). When no listed triangle really meets int Q, int Q is on
                # one side of both, the side of the centre: hence the centre's test.
                qid += 1
                nqa = tris_in_cube(ma, stamp_a, qid, cx, cy, cz, 2.0 * h, lq)
                if nqa <= KMAX and (
                    _same_triangles(lq, nqa, ma.V, ma.T, lb, nq, mb.V, mb.T)
                    or _axis_cells_inside(cx, cy, cz, 2.0 * h, lq, nqa, lb, nq, ma, mb, vals, e)
                ):
                    hi = 0.0
        if hi > 0.0 and hi > settle and tbest >= 0:
            if na <= KMAX:
                # Bounds restricted to C ∩ A, which lies in the convex hull of C's corners in A and of the
                # pieces T_A ∩ C of A's triangles; for a convex φ the maximum over a piece is at most the
                # smaller of its maxima over T_A's vertices and over C's corners.
                for w in range(8):
                    zx = cx + (h if w & 1 else -h)
                    zy = cy + (h if w & 2 else -h)
                    zz = cz + (h if w & 4 else -h)
                    corner_in_a[w] = inside(zx, zy, zz, ma, e)
                # Candidates T: the triangles nearest the centre and the corners (each bound is valid alone).
                ncand = 0
                cand[ncand] = tbest
                ncand += 1
                for w in range(8):
                    if hi <= settle:
                        break
                    if w > 0:
                        zx = cx + (h if w & 1 else -h)
                        zy = cy + (h if w & 2 else -h)
                        zz = cz + (h if w & 4 else -h)
                        qid += 1
                        tc = nearest(zx, zy, zz, mb, stamp_b, qid, alpha)[2]
                        seen = tc < 0
                        for u in range(ncand):
                            if cand[u] == tc:
                                seen = True
                        if seen:
                            continue
                        cand[ncand] = tc
                        ncand += 1
                    tc = cand[ncand - 1]
                    g = _restricted_bound(cx, cy, cz, h, corner_in_a, la, na, ma, mb, tc, alpha, 0, ecap, pts)
                    if g < hi:
                        hi = g
                    qid += 1
                    if hi > settle and _flat_under(cx, cy, cz, h, tc, mb, stamp_b, qid, big, e):
                        g = _restricted_bound(
                            cx, cy, cz, h, corner_in_a, la, na, ma, mb, tc, alpha, 1, ecap, pts
                        )
                        if g < hi:
                            hi = g
            else:
                # d(·, B) ≤ d(·, T) for the triangle T nearest the centre, convex: its maximum over C is at a
                # corner.
                g = 0.0
                for w in range(8):
                    zx = cx + (h if w & 1 else -h)
                    zy = cy + (h if w & 2 else -h)
                    zz = cz + (h if w & 4 else -h)
                    g = max(g, tri_dist(zx, zy, zz, mb.V, mb.T, tbest, alpha)[1])
                if g < hi:
                    hi = g
        his[r] = hi
    return his, los
