"""Exact orientation predicates on float64 points: a float filter, an exact expansion stage, Fractions last.

Every float64 is a rational, so the sign of a determinant of float64 coordinates is a well-defined exact
quantity; these predicates return it, never a rounded guess (docs/design.md §11: validity is decided exactly).

``orient3d(a, b, c, d)`` is the sign of det[b − a, c − a, d − a]: positive when d lies on the side of the
plane (a, b, c) towards which the normal (b − a) × (c − a) points, i.e. above a triangle a, b, c seen
counter-clockwise. ``orient2d(p, q, r, i, j)`` is the sign of (q − p)ᵢ(r − p)ⱼ − (q − p)ⱼ(r − p)ᵢ, the
orientation of the projections on the coordinate axes i, j: ``orient2d(a, b, c, 1, 2)``,
``orient2d(a, b, c, 2, 0)`` and ``orient2d(a, b, c, 0, 1)`` are the signs of the x, y and z components of
(b − a) × (c − a).

Three stages, in the compiled kernels:

1. **Filter.** The determinant evaluated in float64 from the coordinate differences, with Shewchuk's static
   bound on its error (*Adaptive precision floating-point arithmetic and fast robust geometric predicates*,
   1997, "errbound A"): |error| ≤ (7 + 56ε)ε · permanent for orient3d and (3 + 16ε)ε · permanent for
   orient2d, ε = 2⁻⁵³, where the permanent is the same expression with every product in absolute value. The
   bound accounts for the rounding of the differences themselves. When |det| exceeds it the sign is certain.
2. **Exact expansion.** Otherwise the determinant is expanded over the raw coordinates (the 4×4 determinant
   with a column of ones: 24 products of three coordinates for orient3d, 6 products of two for orient2d);
   each product is split exactly into 4 (or 2) doubles by Dekker's two-product, and the exact sum of those
   doubles is accumulated as a non-overlapping expansion (Shewchuk's grow-expansion with zero elimination),
   whose largest component has the sign of the sum.
3. **Out of range.** Both stages assume no overflow or underflow: they are used only when every coordinate
   is 0 or of magnitude in [2⁻²⁰⁰, 2²⁰⁰] (then every difference is 0 or ≥ 2⁻²⁵², every product of three
   stays far inside the normal range, and Dekker's split cannot overflow). Anything else returns
   :data:`UNKNOWN`, and the caller decides with :func:`orient3d_exact` / :func:`orient2d_exact`
   (Python Fractions, exact for any finite float64).

Out-of-range coordinates are the only case the Fraction path ever sees; real meshes stay on the fast path.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np
import numpy.typing as npt
from numba.extending import overload

from mrm.geometry._jit import njit

Floats = npt.NDArray[np.float64]

#: Returned by the compiled predicates when a coordinate is outside the range where they are exact.
UNKNOWN = 2

_EPS = 2.0**-53
_O3_BOUND = (7.0 + 56.0 * _EPS) * _EPS
_O2_BOUND = (3.0 + 16.0 * _EPS) * _EPS
_SPLITTER = 134217729.0  # 2**27 + 1, Dekker's splitter for float64
#: Coordinates must be 0 or within [_LOW, _HIGH] in magnitude for the compiled stages to be exact.
_LOW = 2.0**-200
_HIGH = 2.0**200


# ---------------------------------------------------------------------------------------------- error-free
@njit(cache=True, inline="always")
def _two_sum(a: float, b: float) -> tuple[float, float]:
    """X + y = a + b exactly, x = fl(a + b) (Knuth's branch-free two-sum)."""
    x = a + b
    bv = x - a
    av = x - bv
    return x, (a - av) + (b - bv)


@njit(cache=True, inline="always")
def _two_product(a: float, b: float) -> tuple[float, float]:
    """X + y = a·b exactly, x = fl(a·b) (Dekker's product; no overflow or underflow in range)."""
    x = a * b
    c = _SPLITTER * a
    ahi = c - (c - a)
    alo = a - ahi
    c = _SPLITTER * b
    bhi = c - (c - b)
    blo = b - bhi
    err = x - ahi * bhi
    err -= alo * bhi
    err -= ahi * blo
    return x, alo * blo - err


@njit(cache=True, inline="always")
def _in_range(v: float) -> bool:
    a = abs(v)
    return a == 0.0 or (_LOW <= a <= _HIGH)


@njit(cache=True)
def _sign_of_sum(terms: Floats, n: int) -> int:
    """The exact sign of ``terms[0] + … + terms[n-1]``; ``terms`` is overwritten with the expansion."""
    hlen = 0
    for i in range(n):
        q = terms[i]
        if q == 0.0:
            continue
        k = 0
        # Grow the expansion terms[:hlen] by q in place: component k is written only after component
        # k (≥ the write index) has been read, so reading and writing the same buffer is safe.
        for j in range(hlen):
            q, hh = _two_sum(q, terms[j])
            if hh != 0.0:
                terms[k] = hh
                k += 1
        if q != 0.0 or k == 0:
            terms[k] = q
            k += 1
        hlen = k
    if hlen == 0:
        return 0
    top = terms[hlen - 1]
    return 1 if top > 0.0 else (-1 if top < 0.0 else 0)


@njit(cache=True, inline="always")
def _push_triple(buf: Floats, n: int, s: float, a: float, b: float, c: float) -> int:
    """Append the 4 doubles whose sum is s·a·b·c exactly (s = ±1) to ``buf`` at ``n``; return the new n."""
    x, y = _two_product(a, b)
    p1, p2 = _two_product(x, c)
    p3, p4 = _two_product(y, c)
    buf[n] = s * p1
    buf[n + 1] = s * p2
    buf[n + 2] = s * p3
    buf[n + 3] = s * p4
    return n + 4


@njit(cache=True, inline="always")
def _push_det3(buf: Floats, n: int, s: float, p: Floats, q: Floats, r: Floats) -> int:
    """Append s·det[p; q; r] = s·p·(q × r) as 24 exact doubles."""
    n = _push_triple(buf, n, s, p[0], q[1], r[2])
    n = _push_triple(buf, n, -s, p[0], q[2], r[1])
    n = _push_triple(buf, n, -s, p[1], q[0], r[2])
    n = _push_triple(buf, n, s, p[1], q[2], r[0])
    n = _push_triple(buf, n, s, p[2], q[0], r[1])
    return _push_triple(buf, n, -s, p[2], q[1], r[0])


@njit(cache=True, inline="always")
def _exact_difference(p: Floats, q: Floats) -> bool:
    """True when fl(p − q) = p − q exactly in all three coordinates (two-sum's error term is zero)."""
    for k in range(3):
        x = p[k] - q[k]
        bv = p[k] - x
        av = x + bv
        if (p[k] - av) + (bv - q[k]) != 0.0:
            return False
    return True


@njit(cache=True, inline="always")
def _sign_if_unrounded(
    ux: float, uy: float, uz: float, vx: float, vy: float, vz: float, wx: float, wy: float, wz: float
) -> int:
    """Sign of det[u; v; w] when its float evaluation is exact (every error term zero), else UNKNOWN.

    Short coordinates (integers, halves, quarters … of moderate size) make every product and sum exact;
    checking the error terms costs far less than an expansion and allocates nothing.
    """
    p1, e1 = _two_product(vy, wz)
    p2, e2 = _two_product(vz, wy)
    m1, f1 = _two_sum(p1, -p2)
    p3, e3 = _two_product(vz, wx)
    p4, e4 = _two_product(vx, wz)
    m2, f2 = _two_sum(p3, -p4)
    p5, e5 = _two_product(vx, wy)
    p6, e6 = _two_product(vy, wx)
    m3, f3 = _two_sum(p5, -p6)
    t1, g1 = _two_product(ux, m1)
    t2, g2 = _two_product(uy, m2)
    t3, g3 = _two_product(uz, m3)
    s1, h1 = _two_sum(t1, t2)
    s2, h2 = _two_sum(s1, t3)
    if (
        e1 != 0.0
        or e2 != 0.0
        or e3 != 0.0
        or e4 != 0.0
        or e5 != 0.0
        or e6 != 0.0
        or f1 != 0.0
        or f2 != 0.0
        or f3 != 0.0
        or g1 != 0.0
        or g2 != 0.0
        or g3 != 0.0
        or h1 != 0.0
        or h2 != 0.0
    ):
        return UNKNOWN
    return 1 if s2 > 0.0 else (-1 if s2 < 0.0 else 0)


# ---------------------------------------------------------------------------------------------- orient3d
@njit(cache=True)
def _orient3d_expansion(a: Floats, b: Floats, c: Floats, d: Floats) -> int:
    # det[b − a; c − a; d − a] = det3(b,c,d) − det3(a,c,d) + det3(a,b,d) − det3(a,b,c): the 4×4
    # determinant with a column of ones, expanded along it, so no rounded difference enters.
    buf = np.empty(96)
    n = _push_det3(buf, 0, 1.0, b, c, d)
    n = _push_det3(buf, n, -1.0, a, c, d)
    n = _push_det3(buf, n, 1.0, a, b, d)
    n = _push_det3(buf, n, -1.0, a, b, c)
    return _sign_of_sum(buf, n)


@njit(cache=True)
def orient3d(a: Floats, b: Floats, c: Floats, d: Floats) -> int:
    """Sign of det[b − a, c − a, d − a] (−1, 0, 1), or :data:`UNKNOWN` outside the exact range."""
    for k in range(3):
        if not (_in_range(a[k]) and _in_range(b[k]) and _in_range(c[k]) and _in_range(d[k])):
            return UNKNOWN
    ux, uy, uz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
    vx, vy, vz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
    wx, wy, wz = d[0] - a[0], d[1] - a[1], d[2] - a[2]
    vywz, vzwy = vy * wz, vz * wy
    vzwx, vxwz = vz * wx, vx * wz
    vxwy, vywx = vx * wy, vy * wx
    det = ux * (vywz - vzwy) + uy * (vzwx - vxwz) + uz * (vxwy - vywx)
    perm = (
        abs(ux) * (abs(vywz) + abs(vzwy))
        + abs(uy) * (abs(vzwx) + abs(vxwz))
        + abs(uz) * (abs(vxwy) + abs(vywx))
    )
    bound = _O3_BOUND * perm
    if det > bound:
        return 1
    if det < -bound:
        return -1
    if _exact_difference(b, a) and _exact_difference(c, a) and _exact_difference(d, a):
        # The common near-tie (exactly coplanar points with short coordinates): the differences are
        # exact. If no product or sum of the float evaluation rounded either, its sign is exact;
        # otherwise the 3×3 determinant of the differences is expanded, 24 doubles instead of 96.
        sign = _sign_if_unrounded(ux, uy, uz, vx, vy, vz, wx, wy, wz)
        if sign != UNKNOWN:
            return sign
        buf = np.empty(24)
        u = np.array((ux, uy, uz))
        v = np.array((vx, vy, vz))
        w = np.array((wx, wy, wz))
        return _sign_of_sum(buf, _push_det3(buf, 0, 1.0, u, v, w))
    return _orient3d_expansion(a, b, c, d)


# ---------------------------------------------------------------------------------------------- orient2d
@njit(cache=True)
def _orient2d_expansion(p: Floats, q: Floats, r: Floats, i: int, j: int) -> int:
    # (q_i r_j − q_j r_i) − (p_i r_j − p_j r_i) + (p_i q_j − p_j q_i): the 3×3 determinant with ones.
    buf = np.empty(12)
    terms = (
        (1.0, q[i], r[j]),
        (-1.0, q[j], r[i]),
        (-1.0, p[i], r[j]),
        (1.0, p[j], r[i]),
        (1.0, p[i], q[j]),
        (-1.0, p[j], q[i]),
    )
    n = 0
    for s, x, y in terms:
        hi, lo = _two_product(x, y)
        buf[n] = s * hi
        buf[n + 1] = s * lo
        n += 2
    return _sign_of_sum(buf, n)


@njit(cache=True)
def orient2d(p: Floats, q: Floats, r: Floats, i: int, j: int) -> int:
    """Sign of (q − p)ᵢ(r − p)ⱼ − (q − p)ⱼ(r − p)ᵢ (−1, 0, 1), or :data:`UNKNOWN` outside the exact range."""
    for k in (i, j):
        if not (_in_range(p[k]) and _in_range(q[k]) and _in_range(r[k])):
            return UNKNOWN
    dqi, eqi = _two_sum(q[i], -p[i])
    drj, erj = _two_sum(r[j], -p[j])
    dqj, eqj = _two_sum(q[j], -p[j])
    dri, eri = _two_sum(r[i], -p[i])
    left, el = _two_product(dqi, drj)
    right, er = _two_product(dqj, dri)
    det, ed = _two_sum(left, -right)
    bound = _O2_BOUND * (abs(left) + abs(right))
    if det > bound:
        return 1
    if det < -bound:
        return -1
    if eqi == 0.0 and erj == 0.0 and eqj == 0.0 and eri == 0.0 and el == 0.0 and er == 0.0 and ed == 0.0:
        # Nothing rounded (short coordinates: collinear points on a grid): the float value is exact.
        return 1 if det > 0.0 else (-1 if det < 0.0 else 0)
    return _orient2d_expansion(p, q, r, i, j)


# ---------------------------------------------------------------------------------------------- Fractions
def _sign(v: Fraction) -> int:
    return (v > 0) - (v < 0)


def orient3d_exact(a: Floats, b: Floats, c: Floats, d: Floats) -> int:
    """:func:`orient3d` with Python Fractions: exact for every finite float64, never :data:`UNKNOWN`."""
    fa, fb, fc, fd = ([Fraction(float(x)) for x in p] for p in (a, b, c, d))
    u = [fb[k] - fa[k] for k in range(3)]
    v = [fc[k] - fa[k] for k in range(3)]
    w = [fd[k] - fa[k] for k in range(3)]
    det = (
        u[0] * (v[1] * w[2] - v[2] * w[1])
        + u[1] * (v[2] * w[0] - v[0] * w[2])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
    )
    return _sign(det)


def orient2d_exact(p: Floats, q: Floats, r: Floats, i: int, j: int) -> int:
    """:func:`orient2d` with Python Fractions: exact for every finite float64, never :data:`UNKNOWN`."""
    pi, pj, qi, qj, ri, rj = (Fraction(float(x)) for x in (p[i], p[j], q[i], q[j], r[i], r[j]))
    return _sign((qi - pi) * (rj - pj) - (qj - pj) * (ri - pi))


def orient3d_sign(a: Floats, b: Floats, c: Floats, d: Floats) -> int:
    """The exact sign of det[b − a, c − a, d − a] for any finite float64 points (compiled when in range)."""
    s = int(orient3d(a, b, c, d))
    return s if s != UNKNOWN else orient3d_exact(a, b, c, d)


def orient2d_sign(p: Floats, q: Floats, r: Floats, i: int, j: int) -> int:
    """The exact sign of the orientation of p, q, r projected on the axes i, j, for any finite float64."""
    s = int(orient2d(p, q, r, i, j))
    return s if s != UNKNOWN else orient2d_exact(p, q, r, i, j)


# ---------------------------------------------------------------------------------------------- by index
def o3(v: Floats, i: int, j: int, k: int, m: int) -> int:
    """``orient3d`` of the vertices i, j, k, m of ``v``: exact in Python, compiled inside kernels.

    Called from Python it never returns :data:`UNKNOWN` (Fractions decide what the compiled stages
    cannot); inside a numba kernel it is the compiled :func:`orient3d` and may. The geometric tests of this
    package are written once on top of it (``register_jitable``): compiled for speed, and run as plain
    Python for the rare cases a kernel left undecided.
    """
    return orient3d_sign(v[i], v[j], v[k], v[m])


def o2(v: Floats, i: int, j: int, k: int, a1: int, a2: int) -> int:
    """``orient2d`` of the vertices i, j, k of ``v`` on the axes a1, a2 (see :func:`o3`)."""
    return orient2d_sign(v[i], v[j], v[k], a1, a2)


@njit(cache=True)
def _o3_indexed(v: Floats, i: int, j: int, k: int, m: int) -> int:
    """The filter of :func:`orient3d` on scalars read from ``v`` (no array view per call: the hot path)."""
    ax, ay, az = v[i, 0], v[i, 1], v[i, 2]
    ux, uy, uz = v[j, 0] - ax, v[j, 1] - ay, v[j, 2] - az
    vx, vy, vz = v[k, 0] - ax, v[k, 1] - ay, v[k, 2] - az
    wx, wy, wz = v[m, 0] - ax, v[m, 1] - ay, v[m, 2] - az
    vywz, vzwy = vy * wz, vz * wy
    vzwx, vxwz = vz * wx, vx * wz
    vxwy, vywx = vx * wy, vy * wx
    det = ux * (vywz - vzwy) + uy * (vzwx - vxwz) + uz * (vxwy - vywx)
    perm = (
        abs(ux) * (abs(vywz) + abs(vzwy))
        + abs(uy) * (abs(vzwx) + abs(vxwz))
        + abs(uz) * (abs(vxwy) + abs(vywx))
    )
    big = max(abs(ux), abs(uy), abs(uz), abs(vx), abs(vy), abs(vz), abs(wx), abs(wy), abs(wz))
    # With differences ≤ 2³⁰⁰ nothing overflows, and an underflow (absolute error ≤ 2⁻¹⁰⁷⁴, times a
    # difference ≤ 2³⁰⁰, a few times over) stays far below the added 2⁻⁷⁰⁰: Shewchuk's bound plus that is
    # sound for any input. Otherwise, or near a tie, the full predicate checks its range and decides.
    if big <= 2.0**300:
        bound = _O3_BOUND * perm + 2.0**-700
        if det > bound:
            return 1
        if det < -bound:
            return -1
        # A near-tie, most often exact coplanarity on short coordinates: if the differences were exact
        # and no operation rounded, the float value is the exact one (no view, no allocation).
        small = 2.0**300
        exact = True
        for p, q in (
            (v[j, 0], ax), (v[j, 1], ay), (v[j, 2], az),
            (v[k, 0], ax), (v[k, 1], ay), (v[k, 2], az),
            (v[m, 0], ax), (v[m, 1], ay), (v[m, 2], az),
        ):  # fmt: skip
            x, e = _two_sum(p, -q)
            if e != 0.0:
                exact = False
            if x != 0.0:
                small = min(small, abs(x))
        if exact and small >= 2.0**-300:
            sign = _sign_if_unrounded(ux, uy, uz, vx, vy, vz, wx, wy, wz)
            if sign != UNKNOWN:
                return sign
    return orient3d(v[i], v[j], v[k], v[m])


@njit(cache=True)
def _o2_indexed(v: Floats, i: int, j: int, k: int, a1: int, a2: int) -> int:
    left = (v[j, a1] - v[i, a1]) * (v[k, a2] - v[i, a2])
    right = (v[j, a2] - v[i, a2]) * (v[k, a1] - v[i, a1])
    det = left - right
    perm = abs(left) + abs(right)
    big = max(
        abs(v[j, a1] - v[i, a1]), abs(v[k, a2] - v[i, a2]), abs(v[j, a2] - v[i, a2]), abs(v[k, a1] - v[i, a1])
    )
    if big <= 2.0**500:  # as in _o3_indexed: no overflow, underflow far below the added 2⁻¹⁰⁰⁰
        bound = _O2_BOUND * perm + 2.0**-1000
        if det > bound:
            return 1
        if det < -bound:
            return -1
    return orient2d(v[i], v[j], v[k], a1, a2)


#: Options of the compiled forms (typed Any: numba's stubs do not list ``cache``).
_JIT_OPTIONS: Any = {"cache": True, "nogil": True}


@overload(o3, inline="always", jit_options=_JIT_OPTIONS)
def _o3_compiled(v: Any, i: Any, j: Any, k: Any, m: Any) -> Any:
    def impl(v: Any, i: Any, j: Any, k: Any, m: Any) -> Any:  # pragma: no cover - compiled
        return _o3_indexed(v, i, j, k, m)

    return impl


@overload(o2, inline="always", jit_options=_JIT_OPTIONS)
def _o2_compiled(v: Any, i: Any, j: Any, k: Any, a1: Any, a2: Any) -> Any:
    def impl(v: Any, i: Any, j: Any, k: Any, a1: Any, a2: Any) -> Any:  # pragma: no cover - compiled
        return _o2_indexed(v, i, j, k, a1, a2)

    return impl


__all__ = [
    "UNKNOWN",
    "o2",
    "o3",
    "orient2d",
    "orient2d_exact",
    "orient2d_sign",
    "orient3d",
    "orient3d_exact",
    "orient3d_sign",
]
