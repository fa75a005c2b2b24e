"""Exact maps of 3-D space and the exact images of polyhedra under them (docs/design.md §8, §11).

The 3-D counterpart of :mod:`mrm.geometry.discretize.exact_shape`: the paper's operations apply a map ``T``
between a continuation and a discretization, DSS_α(A) = D(Sc_α(R(A))), dR(A) = D(rot(R(A))). Here ``T`` is a
:class:`Similarity3` with rational entries, and the image ``T(P)`` of a polyhedron is kept as the pair
(P, T) — an :class:`ExactSolid` — and discretized exactly
(:func:`mrm.geometry.discretize.voxel_images.voxelize_image`), never rounded first.

Which maps (docs/adr/0060)
--------------------------
* ``Sc_α`` about a centre C: ``v ↦ C + α·(v − C)``, α and C exact rationals (0.2 is 1/5).
* Quarter turns about a coordinate axis (the axis ±x, ±y or ±z and θ a multiple of 90°): exact signed
  permutations, a true isometry.
* Any other rotation (axis, θ): the matrix of the axis-angle formula with each entry rounded to a multiple of
  2⁻³⁰. A rational rotation that is exactly orthogonal has non-dyadic entries whose denominators would make
  the exact discretization sample a grid 10⁹ times finer; a dyadic matrix keeps the image of R(A)'s vertices
  (multiples of ¼) float64 values, so the compiled exact kernels take it as it is. The map applied is then
  not exactly an isometry: its stretch lies within 2⁻²⁸ of 1, and :attr:`Similarity3.stretch` holds exact
  rational bounds of its singular values, which the bound rule uses (an error vector is multiplied by at
  most ``stretch[1]``), so every bound stays a bound for the map actually applied. The angle applied differs
  from θ by less than 10⁻⁸ radian.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np

from mrm.core.errors import ParameterError
from mrm.geometry.discretize.exact_shape import Similarity

Vec3 = tuple[Fraction, Fraction, Fraction]
Mat3 = tuple[Vec3, Vec3, Vec3]

_ZERO = Fraction(0)
_ONE = Fraction(1)
_IDENTITY: Mat3 = ((_ONE, _ZERO, _ZERO), (_ZERO, _ONE, _ZERO), (_ZERO, _ZERO, _ONE))

#: The entries of a rotation matrix that is no quarter turn are multiples of 2^-ROTATION_BITS (module
#: docstring): fine enough for an angle within 10⁻⁸ radian, coarse enough that the image of R(A)'s vertices
#: (multiples of ¼, below 2¹⁹ in magnitude) is a float64 value.
ROTATION_BITS = 30

__all__ = [
    "ROTATION_BITS",
    "ExactSolid",
    "Similarity3",
    "identity_map",
    "rotation_map",
    "rotation_matrix",
    "scaling_map",
]


def _mul(m: Mat3, n: Mat3) -> Mat3:
    return tuple(  # type: ignore[return-value]
        tuple(sum((m[i][k] * n[k][j] for k in range(3)), _ZERO) for j in range(3)) for i in range(3)
    )


def _apply(m: Mat3, v: Vec3) -> Vec3:
    return (
        m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
        m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
        m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
    )


def _det(m: Mat3) -> Fraction:
    return (
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )


def _inverse(m: Mat3) -> Mat3:
    d = _det(m)
    if d == 0:
        raise ParameterError("the map flattens space (its determinant is 0)")
    c = [[_ZERO] * 3 for _ in range(3)]
    for i in range(3):
        for j in range(3):
            r = [k for k in range(3) if k != j]
            s = [k for k in range(3) if k != i]
            minor = m[r[0]][s[0]] * m[r[1]][s[1]] - m[r[0]][s[1]] * m[r[1]][s[0]]
            c[i][j] = (-1) ** (i + j) * minor / d
    return tuple(tuple(row) for row in c)  # type: ignore[return-value]


def _sqrt_up(q: Fraction) -> Fraction:
    """A rational r ≥ √q with ten decimals (a bound a reader can read: 1.0000000001), at most 10⁻¹⁰ above."""
    scale = 10**10
    r = Fraction(math.ceil(math.sqrt(float(q)) * scale), scale)
    while r * r < q:
        r += Fraction(1, scale)
    return r


def _sqrt_down(q: Fraction) -> Fraction:
    """A rational r ≤ √q (0 for q ≤ 0)."""
    if q <= 0:
        return _ZERO
    r = Fraction(math.sqrt(float(q)))
    while r * r > q:
        r = Fraction(math.nextafter(float(r), 0.0))
    return r


def _stretch(m: Mat3) -> tuple[Fraction, Fraction]:
    """Exact bounds (lo, hi) of the singular values of ``m``.

    With G = mᵀm = I + E: every eigenvalue of G lies within ‖E‖_∞ (the largest absolute row sum, an induced
    norm bounds the spectral radius) of 1, and the singular values are the square roots of those eigenvalues.
    A scaled isometry (G = s²·I) gives lo = hi = s exactly.
    """
    g = _mul(tuple(zip(*m, strict=True)), m)  # type: ignore[arg-type]
    s2 = g[0][0]
    if all(g[i][j] == (s2 if i == j else 0) for i in range(3) for j in range(3)):
        s = _sqrt_down(s2)
        if s * s == s2:
            return s, s
    e = max(sum(abs(g[i][j] - (s2 if i == j else 0)) for j in range(3)) for i in range(3))
    return _sqrt_down(s2 - e), _sqrt_up(s2 + e)


def rotation_matrix(degrees: Fraction, axis: Any = None) -> Mat3:
    """The matrix applied for a rotation by ``degrees`` about ``axis`` (module docstring; exact values).

    ``axis`` is three numbers (not all zero; the z axis when None), counter-clockwise seen from its tip.
    """
    ax = (_ZERO, _ZERO, _ONE) if axis is None else tuple(Fraction(c) for c in axis)
    if len(ax) != 3 or all(c == 0 for c in ax):
        raise ParameterError("the axis of a 3D rotation is three numbers, not all zero")
    theta = Fraction(degrees) % 360
    nonzero = [i for i in range(3) if ax[i] != 0]
    if len(nonzero) == 1 and theta % 90 == 0:
        i = nonzero[0]
        quarter = int(theta // 90) * (1 if ax[i] > 0 else -1) % 4
        c, s = ((1, 0), (0, 1), (-1, 0), (0, -1))[quarter]
        a, b = ((1, 2), (2, 0), (0, 1))[i]  # the plane turned, counter-clockwise seen from +axis
        m = [list(row) for row in _IDENTITY]
        m[a][a], m[a][b], m[b][a], m[b][b] = Fraction(c), Fraction(-s), Fraction(s), Fraction(c)
        return tuple(tuple(row) for row in m)  # type: ignore[return-value]
    u = np.array([float(c) for c in ax])
    u = u / np.linalg.norm(u)
    t = math.radians(float(theta))
    k = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    r = np.eye(3) + math.sin(t) * k + (1.0 - math.cos(t)) * (k @ k)
    scale = 2**ROTATION_BITS
    return tuple(  # type: ignore[return-value]
        tuple(Fraction(round(float(r[i, j]) * scale), scale) for j in range(3)) for i in range(3)
    )


@dataclass(frozen=True)
class Similarity3:
    """An exact map ``v ↦ M·v + t`` of 3-D space with rational entries (a similarity, up to 2⁻²⁸).

    Attributes
    ----------
    linear : 3 × 3 tuple of Fraction
        M, row by row.
    offset : three Fractions
        t.
    stretch : (Fraction, Fraction)
        Exact bounds of M's singular values: equal for a similarity (its ratio), within 2⁻²⁸ of each other
        for a rounded rotation (module docstring).
    """

    linear: Mat3 = _IDENTITY
    offset: Vec3 = (_ZERO, _ZERO, _ZERO)
    stretch: tuple[Fraction, Fraction] = (_ONE, _ONE)

    n = 3

    @classmethod
    def identity(cls) -> Similarity3:
        """The identity."""
        return cls()

    @classmethod
    def of(cls, linear: Mat3, offset: Vec3 = (_ZERO, _ZERO, _ZERO)) -> Similarity3:
        """The map ``v ↦ linear·v + offset`` (its stretch computed exactly)."""
        if _det(linear) <= 0:
            raise ParameterError("a 3D similarity keeps orientation (its determinant must be positive)")
        return cls(linear, offset, _stretch(linear))

    @classmethod
    def scaling(cls, alpha: Fraction, center: Any = None) -> Similarity3:
        """``Sc_α`` about ``center`` (the origin by default): ``v ↦ C + α·(v − C)``."""
        a = Fraction(alpha)
        c = _center(center)
        lin = ((a, _ZERO, _ZERO), (_ZERO, a, _ZERO), (_ZERO, _ZERO, a))
        return cls(lin, tuple((1 - a) * x for x in c), (a, a))  # type: ignore[arg-type]

    @classmethod
    def translation(cls, *d: Fraction) -> Similarity3:
        """``v ↦ v + d``."""
        return cls(_IDENTITY, tuple(Fraction(x) for x in d))  # type: ignore[arg-type]

    @classmethod
    def rotation(cls, degrees: Fraction, center: Any = None, axis: Any = None) -> Similarity3:
        """The rotation by ``degrees`` about ``axis`` through ``center`` (:func:`rotation_matrix`)."""
        m = rotation_matrix(degrees, axis)
        c = _center(center)
        mc = _apply(m, c)
        return cls.of(m, (c[0] - mc[0], c[1] - mc[1], c[2] - mc[2]))

    @property
    def ratio(self) -> Fraction:
        """How much the map can stretch a distance at most (the ratio of a similarity)."""
        return self.stretch[1]

    @property
    def is_identity(self) -> bool:
        """True for the identity map."""
        return self.linear == _IDENTITY and not any(self.offset)

    def __call__(self, p: Any) -> Vec3:
        """The image of the point ``p``, exact."""
        v = _apply(self.linear, (Fraction(p[0]), Fraction(p[1]), Fraction(p[2])))
        return v[0] + self.offset[0], v[1] + self.offset[1], v[2] + self.offset[2]

    def then(self, other: Similarity3) -> Similarity3:
        """The composite ``other ∘ self`` (self first)."""
        lin = _mul(other.linear, self.linear)
        lo, hi = self.stretch[0] * other.stretch[0], self.stretch[1] * other.stretch[1]
        return Similarity3(lin, other(self.offset), (lo, hi))

    def inverse(self) -> Similarity3:
        """The inverse map."""
        inv = _inverse(self.linear)
        t = _apply(inv, self.offset)
        lo, hi = self.stretch
        return Similarity3(inv, (-t[0], -t[1], -t[2]), (1 / hi, 1 / lo))


def _center(center: Any) -> Vec3:
    if center is None:
        return (_ZERO, _ZERO, _ZERO)
    if len(center) != 3:
        raise ParameterError(
            f"the centre (parameter 'center') of a 3D object must be 3 numbers (x, y, z), got {len(center)}"
        )
    return (Fraction(center[0]), Fraction(center[1]), Fraction(center[2]))


@dataclass(frozen=True, eq=False)
class ExactSolid:
    """The exact image T(P) of a polyhedron P under an exact map T, kept as the pair (P, T).

    Attributes
    ----------
    base : Polyhedron
        P (float64 vertices).
    transform : Similarity3
        T.
    """

    base: Any
    transform: Similarity3 = Similarity3()

    #: A solid of space (``mrm.core.grids.dimension_of`` reads it).
    ndim = 3

    @classmethod
    def of(cls, solid: Any) -> ExactSolid:
        """A polyhedron as an exact solid (an ExactSolid is kept)."""
        return solid if isinstance(solid, ExactSolid) else cls(solid)

    def map(self, sim: Similarity3) -> ExactSolid:
        """The exact image under ``sim``."""
        return self if sim.is_identity else ExactSolid(self.base, self.transform.then(sim))

    def is_empty(self) -> bool:
        """True for the empty solid."""
        return bool(self.base.is_empty)

    def __eq__(self, other: object) -> bool:
        # The same polyhedron under the same map: a sufficient test of equal solids (a single DSS's A_last is
        # T(A_first) in exactly this form).
        if not isinstance(other, ExactSolid):
            return NotImplemented
        return self.transform == other.transform and self.base == other.base

    def __hash__(self) -> int:
        return hash((self.transform, self.base))

    def bounds(self) -> tuple[Fraction, ...] | None:
        """The exact bounds (xmin, ymin, zmin, xmax, ymax, zmax) of the image, or None when empty."""
        if self.is_empty():
            return None
        lo, hi = self.base.bbox
        corners = [
            self.transform((x, y, z)) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])
        ]
        # The image of the box's corners bounds the image of the box, so of P (an affine map).
        return (
            *(min(p[d] for p in corners) for d in range(3)),
            *(max(p[d] for p in corners) for d in range(3)),
        )

    def float_vertices(self) -> tuple[np.ndarray, float]:
        """The image's vertices rounded to float64, and a bound of the rounding error of any coordinate.

        Computed with Python integers: the base's coordinates are ``X·2⁻ᵏ`` (dyadic, read by the exact
        voxelization's :func:`~mrm.geometry.discretize.voxel_images.integer_vertices`), so every image
        coordinate is one integer over one common denominator, and the division rounds once.
        """
        from mrm.geometry.discretize.voxel_images import integer_vertices

        v = np.asarray(self.base.vertices, dtype=np.float64)
        if self.transform.is_identity or v.size == 0:
            return v.copy(), 0.0
        m = self.transform.linear
        t = self.transform.offset
        den = math.lcm(*(x.denominator for row in m for x in row), *(x.denominator for x in t))
        mi = np.array([[int(x * den) for x in row] for row in m], dtype=object)
        ti = np.array([int(x * den) for x in t], dtype=object)
        x, k = integer_vertices(v)  # v = x·2^-k exactly
        xi = x.astype(object)  # Python integers: the products below may pass int64
        num = xi.dot(mi.T) + ti * 2**k  # image = num / (den · 2^k)
        scale = den * 2**k
        out = np.array([[c / scale for c in row] for row in num.tolist()], dtype=np.float64)
        # int / int in Python rounds correctly: the error is at most half an ulp of the result.
        err = float(np.max(np.spacing(np.abs(out)))) if out.size else 0.0
        return out, err

    def discretize(self, model: str, *, limit: int | None, progress: Any = None) -> Any:
        """D(T(P)), exact (:func:`mrm.geometry.discretize.voxel_images.voxelize_image`)."""
        from mrm.geometry.discretize.voxel_images import voxelize_image

        t = self.transform
        return voxelize_image(self.base, t.linear, t.offset, model, limit=limit, progress=progress)


# ------------------------------------------------------------------------------------- one per dimension
def _planar_center(center: Any) -> Any:
    if center is not None and len(center) != 2:
        raise ParameterError(
            f"the centre (parameter 'center') of a 2D object must be 2 numbers (x, y), got {len(center)}"
        )
    return center


def identity_map(n: int = 2) -> Any:
    """The identity of the plane (n = 2, a :class:`~.exact_shape.Similarity`) or of space (n = 3)."""
    return Similarity3.identity() if n == 3 else Similarity.identity()


def scaling_map(alpha: Fraction, center: Any = None, n: int = 2) -> Any:
    """``Sc_α`` about ``center`` in dimension ``n`` (the one declaration DSS_α, Sp_α and EDco_α read)."""
    if n == 3:
        return Similarity3.scaling(alpha, center)
    return Similarity.scaling(alpha, _planar_center(center))


def rotation_map(degrees: Fraction, center: Any = None, axis: Any = None, n: int = 2) -> Any:
    """The rotation applied for ``degrees`` about ``axis`` through ``center`` in dimension ``n``.

    In the plane the axis is z (the exact rational rotation of :mod:`.exact_shape`); in space
    :meth:`Similarity3.rotation` (module docstring).
    """
    if n == 3:
        return Similarity3.rotation(degrees, center, axis)
    if axis is not None and (axis[0] != 0 or axis[1] != 0 or axis[2] <= 0):
        raise ParameterError("a 2D object turns about the z axis: give no axis, or 0,0,1")
    return Similarity.rotation(degrees, _planar_center(center))
