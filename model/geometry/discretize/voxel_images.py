"""The exact voxelization D(T(P)) of the image of a polyhedron P under a rational affine map T.

Reference: docs/design.md §11 (D in 3D) and §8 (DSS_α = D∘Sc_α∘R, dR = D∘rot∘R); ADRs 0058, 0062.

:func:`~mrm.geometry.discretize.voxels.voxelize_solid` is exact for float64 vertices. ``T(v) = M·v + t`` with
rational M and t (Sc_α for α = p/q about a rational centre, a quarter turn) maps P's float64 vertices to
rationals that are not float64 values when q has an odd factor (α = 1/5, 4/5, 2/3). Rounding them could move
a vertex across a voxel side. Instead the image is scaled by an odd N, where it is float64, and voxelized on
the grid of step N, whose voxel c is the cube of side N centred on N·c:

* every float64 vertex coordinate is X·2^-k (X an integer, k one exponent for the whole solid), so
  T(v)_i = Y_i / (D_i·2^k) with Y_i an integer combination of the X (int64 arithmetic where it cannot
  overflow, else Python integers in object arrays; never a Fraction per vertex);
* N is the odd part of the common denominator of all these values (the least odd N making N·T(P) dyadic),
  and Q = N·T(P) has dyadic coordinates; when they are float64 values in the exact kernels' range (checked
  exactly; a ParameterError otherwise) the kernels compute D(T(P)) = D(Q / N) on the grid of step N.
  N = 1 (a dyadic α such as 1.25 or 2, a quarter turn) is the unit grid.

Why this is exact. Scaling by N is a bijection, so c ∈ D(T(P)) ⟺ Q meets N·K(c): the point N·c + N·τ
(gauss), the closed cube N·V(c) (supercover), the open cube int(N·V(c)) + N·τ (standard) — the kernels of
the grid of step N. Its planes N·(k ± ½) are half-integers (N odd) and its centres integers, exact floats,
so every comparison and determinant the kernels make on them is exact as on the unit grid. The shift N·τ =
(Nε, Nε², Nε³) decides as τ does: Q is a finite union of convex polytopes; that one meets a box
lo + σ < x < hi + σ (or holds a point u + σ) is a linear feasibility problem in x, which Fourier–Motzkin
elimination turns into finitely many conditions a + b·σ < 0 or ≤ 0 with rational a, b (the elimination takes
positive combinations of the constraints, in which σ enters linearly). For every small ε the sign of a + b·σ
is that of the first non-zero term of (a, b_x, b_y, b_z), for σ = τ and σ = N·τ alike (N > 0 scales b).

The cost is that of D of an image of the result's size: no finer grid. The result's box is computed from
Q's exact extremes and refused beyond ``limit`` before any grid is made.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from fractions import Fraction
from functools import reduce
from numbers import Rational
from typing import Any

import numpy as np
import numpy.typing as npt

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.grids import VoxelSet
from mrm.core.limits import DEFAULT_VOXEL_LIMIT, check_pixels
from mrm.core.models import Model
from mrm.core.progress import ProgressLike
from mrm.geometry.discretize._kernels3d import least_exponent
from mrm.geometry.discretize.exact import MAX_ABS_COORD
from mrm.geometry.discretize.voxels import MAX_GRID_STEP, MIN_ABS_COORD_3D, voxelize_solid

__all__ = ["integer_vertices", "voxelize_image"]

log = logging.getLogger(__name__)

Floats = npt.NDArray[np.float64]
Matrix = Sequence[Sequence[Any]]

#: Integers up to this magnitude are summed in int64 without overflow (three products and a constant).
_INT64_SAFE = 1 << 62
#: Largest integer below which every integer is a float64 value.
_FLOAT_INTEGERS = 1 << 53
#: Beyond the exponent of the least subnormal (2^-1074): no float64 needs more fractional bits.
_MAX_EXPONENT = 1100
#: Numerators read first when reducing the odd denominator (most images are reduced to 1 by a few).
_GCD_PREFIX = 64


def voxelize_image(
    solid: Any,
    linear: Matrix,
    offset: Sequence[Any],
    model: str = "standard",
    *,
    limit: int | None = DEFAULT_VOXEL_LIMIT,
    progress: ProgressLike | None = None,
    what: str = "the voxelization",
) -> VoxelSet:
    """D(T(P)) exactly, for T(v) = linear·v + offset with rational entries (see the module docstring).

    Parameters
    ----------
    solid : Polyhedron
        A validated solid P (:class:`mrm.geometry.polyhedra.Polyhedron`), e.g. R(A) of a voxel set.
    linear : 3 × 3 rationals
        The linear part of T (``fractions.Fraction``, int, or float taken exactly), with a positive
        determinant (an invertible map keeping orientation).
    offset : three rationals
        The translation of T.
    model : {"standard", "supercover", "gauss"}
        The kernel (docs/design.md §11).
    limit : int or None
        Largest number of voxels in the bounding box of the result, checked before any grid is made. None
        for no limit.
    progress : object with ``update(fraction, message)``, optional
        Told when the voxelization starts and ends; the ``Cancelled`` it raises propagates.
    what : str
        How a size refusal names the work ("DSS 0.2").

    Returns
    -------
    VoxelSet
        The voxels p whose kernel K(p) meets T(P).

    Raises
    ------
    ParameterError
        A map that is not 3 × 3 rationals and three rationals, or whose determinant is not positive; an
        unknown model; an image whose coordinates scaled by N are not float64 values in the range of the
        exact kernels (53-bit mantissas, |x| ≤ 2⁵¹, 0 or ≥ 2⁻²⁵⁰), or N beyond 2⁴⁹.
    InvalidGeometryError
        ``solid`` is not a Polyhedron.
    SizeLimitError
        The result would exceed ``limit`` voxels.

    Examples
    --------
    >>> from fractions import Fraction as F
    >>> import mrm
    >>> from mrm.geometry.reconstruct import reconstruct
    >>> a = mrm.VoxelSet.box(0, 0, 0, 9, 9, 9)  # a 10³ cube; DSS_1/5 about the corner (-½, -½, -½)
    >>> fifth = [[F(1, 5), 0, 0], [0, F(1, 5), 0], [0, 0, F(1, 5)]]
    >>> len(voxelize_image(reconstruct(a, "standard"), fifth, [F(-2, 5)] * 3, "standard"))
    8
    """
    from mrm.geometry.polyhedra import Polyhedron  # the value's module builds on the voxel predicates

    if not isinstance(solid, Polyhedron):
        raise InvalidGeometryError(f"voxelize_image takes a Polyhedron, got {type(solid).__name__}")
    m, t = _exact_map(linear, offset)
    parsed = Model.parse(model)
    if solid.is_empty:
        return VoxelSet.empty()
    fast = _dyadic_image(solid.vertices, m, t)
    if fast is not None:  # T(P)'s coordinates computed in float64 without rounding (checked): N = 1
        q, n = fast, 1
        lo = [Fraction(float(q[:, i].min())) for i in range(3)]
        hi = [Fraction(float(q[:, i].max())) for i in range(3)]
    else:
        z, exps, n = _scaled_image(solid.vertices, m, t)
        lo = [Fraction(int(z[:, i].min()), 1 << exps[i]) for i in range(3)]
        hi = [Fraction(int(z[:, i].max()), 1 << exps[i]) for i in range(3)]
    box = _grid_box(lo, hi, parsed, n)
    check_pixels(_volume(box), limit, what, unit="voxels")
    if box is None:
        return VoxelSet.empty()
    if fast is None:
        q = _as_floats(z, exps, n)
    if progress is not None:
        progress.update(0.0, "voxelizing")
    mask, origin = voxelize_solid(q, solid.triangles, parsed.value, limit=None, step=n)
    if progress is not None:
        progress.update(1.0, None)
    log.debug("voxelize_image: %s on the grid of step %d, %d voxels", parsed.value, n, mask.size)
    return VoxelSet.taking_over(mask, origin)


# ---------------------------------------------------------------------------------------------- the map
def _rational(value: Any, what: str) -> Fraction:
    try:
        if isinstance(value, bool):
            raise TypeError
        if isinstance(value, float | np.floating):
            return Fraction(float(value))  # a finite float is the rational it holds
        if isinstance(value, np.integer):
            return Fraction(int(value))
        if isinstance(value, Rational):
            return Fraction(value)
    except (ValueError, OverflowError):
        raise ParameterError(f"{what} must be a finite number, got {value!r}") from None
    except TypeError:
        pass
    raise ParameterError(f"{what} must be a rational number, got {value!r}")


def _exact_map(linear: Matrix, offset: Sequence[Any]) -> tuple[list[list[Fraction]], list[Fraction]]:
    """The map as Fractions; refuses a shape other than 3 × 3 and 3, and a determinant ≤ 0."""
    try:
        rows = [list(r) for r in linear]
        off = list(offset)
    except TypeError:
        raise ParameterError("an affine map is a 3 × 3 matrix and three numbers") from None
    if len(rows) != 3 or any(len(r) != 3 for r in rows) or len(off) != 3:
        raise ParameterError("an affine map is a 3 × 3 matrix and three numbers")
    m = [[_rational(v, "a matrix entry") for v in r] for r in rows]
    t = [_rational(v, "an offset") for v in off]
    det = (
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )
    if det <= 0:
        raise ParameterError(
            f"the map's determinant is {det}: an exact image needs an invertible map that keeps orientation"
        )
    return m, t


# ---------------------------------------------------------------------------------- the scaled image
def _power_of_two(q: Fraction) -> bool:
    n, d = abs(q.numerator), q.denominator
    return n != 0 and n & (n - 1) == 0 and d & (d - 1) == 0


def _dyadic_image(v: Floats, m: list[list[Fraction]], t: list[Fraction]) -> Floats | None:
    """T(v) in float64 when no operation rounds, else None (then the integer path computes it).

    For a map whose rows each take one coordinate times ±2^k (dyadic α about a dyadic centre, a quarter
    turn): a product by a power of two is exact unless it leaves the normal range (checked); the sum with
    the offset is checked exact by Knuth's error-free TwoSum (the rounding error of ``s = a + b`` is
    ``(a − (s − b′)) + (b − b′)`` with ``b′ = s − a``, exactly, for finite values). This skips the integer
    reading of every vertex, which costs more than the voxelization of a gauss image (1 ms of 4 at 128³).
    """
    cols = []
    for i in range(3):
        nonzero = [j for j in range(3) if m[i][j] != 0]
        if len(nonzero) != 1 or not _power_of_two(m[i][nonzero[0]]) or float(t[i]) != t[i]:
            return None
        cols.append(nonzero[0])
    if sorted(cols) != [0, 1, 2]:
        return None
    q = np.empty_like(v)
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        for i, j in enumerate(cols):
            a = v[:, j] * float(m[i][j])
            tiny = (a != 0) & (np.abs(a) < np.finfo(np.float64).tiny)
            if tiny.any() or ((a == 0) != (v[:, j] == 0)).any() or not np.isfinite(a).all():
                return None
            b = float(t[i])
            s = a + b
            bb = s - a
            if not np.isfinite(s).all() or ((a - (s - bb)) + (b - bb) != 0).any():
                return None
            q[:, i] = s
    return q


def integer_vertices(v: Floats) -> tuple[npt.NDArray[Any], int]:
    """(X, k) with v = X·2^-k exactly, X integers (int64 when they fit, else Python ints), k ≥ 0 least."""
    if v.size == 0:
        return np.zeros(v.shape, dtype=np.int64), 0
    vmax = float(np.abs(v).max())
    k = least_exponent(np.ascontiguousarray(v, dtype=np.float64).reshape(-1), _MAX_EXPONENT)
    # |v|·2^k < 2^62, compared without forming 2^k (k reaches 1074 for a subnormal)
    if k >= 0 and vmax < math.ldexp(1.0, 62 - k):
        return np.ldexp(v, k).astype(np.int64), k  # exact: a power-of-two scale of integers below 2^62
    mant, e = np.frexp(v)  # v = mant·2^e, 0.5 ≤ |mant| < 1
    big = np.ldexp(mant, 53).astype(np.int64)  # v = big·2^(e − 53), exactly
    nz = big != 0
    if not nz.any():
        return np.zeros(v.shape, dtype=np.int64), 0
    low = big[nz]
    tz = np.log2((low & -low).astype(np.float64)).astype(np.int64)  # trailing zero bits (powers of two)
    k = max(0, -int((e[nz] - 53 + tz).min()))
    if vmax < math.ldexp(1.0, 62 - k):
        return np.ldexp(v, k).astype(np.int64), k
    # Coordinates spanning more than 62 bits together: Python integers (rare; still no Fraction).
    # big has its trailing zero bits, so a right shift (k ≥ −(e − 53 + tz)) drops zeros only.
    shifts = np.where(nz, e - 53 + k, 0).reshape(-1).tolist()
    ints = [b << s if s >= 0 else b >> -s for b, s in zip(big.reshape(-1).tolist(), shifts, strict=True)]
    out = np.empty(len(ints), dtype=object)
    out[:] = ints
    return out.reshape(v.shape), k


def _scaled_image(
    v: Floats, m: list[list[Fraction]], t: list[Fraction]
) -> tuple[npt.NDArray[Any], list[int], int]:
    """(Z, e, N): N·T(v)_i = Z[:, i]·2^-e[i] exactly, N the odd part of the image's common denominator."""
    x, k = integer_vertices(v)
    xmax = [int(np.abs(x[:, j]).max()) for j in range(3)]
    rows = []
    for i in range(3):
        den = reduce(math.lcm, [m[i][j].denominator for j in range(3)] + [t[i].denominator], 1)
        a = [int(m[i][j] * den) for j in range(3)]
        b = int(t[i] * den) << k
        bound = sum(abs(a[j]) * xmax[j] for j in range(3)) + abs(b)
        xs = x if bound < _INT64_SAFE and x.dtype == np.int64 else x.astype(object)
        y = _combination(xs, a, b)  # T(v)_i = y / (den·2^k)
        two = (den & -den).bit_length() - 1
        odd = den >> two
        g = _gcd_with(y, odd)
        rows.append((y, g, odd // g, two + k, bound // g))
    n = reduce(math.lcm, [r[2] for r in rows], 1)
    z_cols = []
    exps = []
    for y, g, n_i, e_i, bound in rows:
        f = n // n_i
        if y.dtype == np.int64 and bound * f < _INT64_SAFE:
            z_cols.append((y // g) * f if (g, f) != (1, 1) else y)
        else:
            z_cols.append((y.astype(object) // g) * f)
        exps.append(e_i)
    obj = any(c.dtype == object for c in z_cols)
    z = np.stack([c.astype(object) if obj else c for c in z_cols], axis=1)
    return z, exps, n


def _combination(x: npt.NDArray[Any], a: list[int], b: int) -> npt.NDArray[Any]:
    """x[:, 0]·a[0] + x[:, 1]·a[1] + x[:, 2]·a[2] + b, skipping zero terms (a scaling's row has one)."""
    y: npt.NDArray[Any] | None = None
    for j in range(3):
        if a[j] != 0:
            term = x[:, j] * a[j]
            y = term if y is None else y + term
    if y is None:  # pragma: no cover - a row of an invertible matrix is not zero
        y = np.zeros(x.shape[0], dtype=x.dtype)
    return y + b if b != 0 else y


def _gcd_with(y: npt.NDArray[Any], odd: int) -> int:
    """gcd(odd, every y): the part of the denominator ``odd`` that every value's numerator cancels."""
    if odd == 1:
        return 1
    if y.dtype == np.int64 and odd < _INT64_SAFE:
        # gcd(odd, y) = gcd(odd, y mod odd): the remainders are small, so Euclid's loop per element is short.
        # A few values usually bring the gcd to 1 already (then the rest need not be read).
        g = math.gcd(odd, int(np.gcd.reduce(y[:_GCD_PREFIX] % odd)))
        if g == 1 or y.shape[0] <= _GCD_PREFIX:
            return g
        return math.gcd(g, int(np.gcd.reduce(y[_GCD_PREFIX:] % g)))
    g = odd
    for value in y.tolist():
        g = math.gcd(g, value)
        if g == 1:
            break
    return g


def _as_floats(z: npt.NDArray[Any], exps: list[int], n: int) -> Floats:
    """Q = Z·2^-e as float64, refused (ParameterError) unless exact and in the range of the exact kernels."""
    if z.dtype == np.int64:
        mag = np.abs(z)
        exact = bool((mag <= _FLOAT_INTEGERS).all())
        if not exact:
            wide = z[mag > _FLOAT_INTEGERS]
            back = wide.astype(np.float64)
            exact = bool(((np.abs(back) < 2.0**63) & (back.astype(np.int64) == wide)).all())
    else:
        try:
            exact = all(float(u) == u for u in z.reshape(-1).tolist())
        except OverflowError:
            exact = False
    q = np.empty(z.shape, dtype=np.float64)
    if exact:
        for i in range(3):
            q[:, i] = np.ldexp(z[:, i].astype(np.float64), -exps[i])
        a = np.abs(q)
        exact = bool(((a <= MAX_ABS_COORD) & ((a >= MIN_ABS_COORD_3D) | (z == 0))).all())
    if not exact or n > MAX_GRID_STEP:
        raise ParameterError(
            f"the exact image's coordinates times {n}, which makes them dyadic, are not all float64 numbers "
            "within the exact voxelization's range (53-bit mantissas, |x| ≤ 2^51, 0 or ≥ 2^-250, a factor "
            "≤ 2^49); choose a simpler ratio or centre"
        )
    return q


# -------------------------------------------------------------------------------------------- boxes
Box3 = tuple[int, int, int, int, int, int]


def _grid_box(lo: list[Fraction], hi: list[Fraction], model: Model, n: int) -> Box3 | None:
    """The voxels of the grid of step n (centres n·c) that hold D of a solid with this extent.

    As voxels.voxelization_box, exactly on the extent's Fractions.
    """
    if model is Model.GAUSS:  # lo ≤ n·c < hi
        c_lo = [math.ceil(u / n) for u in lo]
        c_hi = [math.ceil(u / n) - 1 for u in hi]
        if any(c_hi[d] < c_lo[d] for d in range(3)):
            return None
    else:  # the cells (n·c − n/2, n·c + n/2] of the extremes; closed cubes add the next one on a plane
        half = Fraction(1, 2)
        c_lo = [math.ceil(u / n - half) for u in lo]
        c_hi = [math.ceil(u / n - half) for u in hi]
        if model is Model.SUPERCOVER:
            c_hi = [c + (u / n == c + half) for c, u in zip(c_hi, hi, strict=True)]
    return (c_lo[0], c_lo[1], c_lo[2], c_hi[0], c_hi[1], c_hi[2])


def _volume(box: Box3 | None) -> int:
    if box is None:
        return 0
    return (box[3] - box[0] + 1) * (box[4] - box[1] + 1) * (box[5] - box[2] + 1)
