"""Exact Euclidean geometry for the operations: rational numbers, polygons and similarities.

Reference: docs/design.md §8.

The paper's operations apply a Euclidean similarity (a scaling ``Sc_α`` about a centre, a rotation
``rot_θ,C``) between a continuation and a discretization. Applied to float64 vertices in floating point, a
similarity rounds, and a rounded vertex may land on the other side of a pixel side than the true one. Here
every similarity is applied **exactly**: coordinates are :class:`fractions.Fraction` (every float64 is a
dyadic rational), and the image is discretized exactly (:mod:`mrm.geometry.discretize.rational`).

Numbers
-------
Every number here is a :class:`fractions.Fraction`, read once by :func:`mrm.core.numbers.read_number` where a
user gave it (a float is the decimal it prints as: ``0.2`` means 1/5, so ``DSS 5`` followed by ``DSS 0.2``
scales by exactly 1).

Rotations
---------
``cos θ`` and ``sin θ`` are irrational for almost every angle. A rotation by θ is applied as the exact
rational rotation with ``c = (1 − t²)/(1 + t²)``, ``s = 2t/(1 + t²)``, where θ is first reduced to
(−45°, 45°] by exact quarter turns and ``t`` is the float64 value of ``tan(θ/2)`` taken as an exact rational.
It is an exact isometry (``c² + s² = 1``) whose angle differs from θ by about one float64 rounding (less than
10⁻¹⁵ radian); multiples of 90° are exact (``t = 0`` and quarter turns), so a rotation by 90° about a pixel
centre maps pixel corners to pixel corners exactly.

Polygons
--------
:class:`ExactShape` holds polygons with holes as rings of rational points. It converts from shapely without
loss and back to shapely by rounding each coordinate once to the nearest float64 (exact whenever the
coordinate is a float64, e.g. for dyadic scale factors).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import shapely
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import InvalidGeometryError
from mrm.core.numbers import Point, is_float

Ring = tuple[Point, ...]
PolygonRings = tuple[Ring, ...]

_ZERO = Fraction(0)
_ONE = Fraction(1)
_HALF = Fraction(1, 2)


# ---------------------------------------------------------------------------------------------- similarities
@dataclass(frozen=True)
class Similarity:
    """An exact direct similarity ``v ↦ M·v + t`` with ``M = [[a, −b], [b, a]]`` (rational).

    Attributes
    ----------
    a, b : Fraction
        The matrix entries; ``a² + b² = ratio²``.
    tx, ty : Fraction
        The translation.
    ratio : Fraction
        The ratio of the similarity (how it multiplies distances).
    """

    a: Fraction = _ONE
    b: Fraction = _ZERO
    tx: Fraction = _ZERO
    ty: Fraction = _ZERO
    ratio: Fraction = _ONE

    @classmethod
    def identity(cls) -> Similarity:
        """The identity."""
        return cls()

    @classmethod
    def scaling(cls, alpha: Fraction, center: Point | None = None) -> Similarity:
        """``Sc_α`` about ``center`` (the origin by default): ``v ↦ C + α·(v − C)``."""
        cx, cy = center if center is not None else (_ZERO, _ZERO)
        return cls(alpha, _ZERO, (1 - alpha) * cx, (1 - alpha) * cy, alpha)

    @classmethod
    def translation(cls, dx: Fraction, dy: Fraction) -> Similarity:
        """``v ↦ v + (dx, dy)``."""
        return cls(_ONE, _ZERO, dx, dy, _ONE)

    @classmethod
    def rotation(cls, degrees: Fraction, center: Point | None = None) -> Similarity:
        """The exact rational rotation by ``degrees`` about ``center`` (module docstring)."""
        c, s = rotation_cos_sin(degrees)
        cx, cy = center if center is not None else (_ZERO, _ZERO)
        return cls(c, s, cx - (c * cx - s * cy), cy - (s * cx + c * cy), _ONE)

    def __call__(self, p: Point) -> Point:
        """The image of the point ``p``, exact."""
        x, y = p
        return self.a * x - self.b * y + self.tx, self.b * x + self.a * y + self.ty

    def then(self, other: Similarity) -> Similarity:
        """The composite ``other ∘ self`` (self first)."""
        a = other.a * self.a - other.b * self.b
        b = other.a * self.b + other.b * self.a
        tx, ty = other((self.tx, self.ty))
        return Similarity(a, b, tx, ty, self.ratio * other.ratio)

    def inverse(self) -> Similarity:
        """The inverse similarity."""
        n = self.a * self.a + self.b * self.b
        a, b = self.a / n, -self.b / n
        tx = -(a * self.tx - b * self.ty)
        ty = -(b * self.tx + a * self.ty)
        return Similarity(a, b, tx, ty, 1 / self.ratio)

    @property
    def is_identity(self) -> bool:
        """True for the identity map."""
        return self.a == 1 and self.b == 0 and self.tx == 0 and self.ty == 0


def rotation_cos_sin(degrees: Fraction) -> tuple[Fraction, Fraction]:
    """Exact rational (cos, sin) of the rotation applied for an angle of ``degrees`` (module docstring)."""
    theta = degrees % 360  # in [0, 360), exact
    quarter = int(theta // 90)
    rest = theta - 90 * quarter  # in [0, 90)
    if rest > 45:  # reduce to (−45°, 45°] so that |tan(θ/2)| < 1 stays well conditioned
        quarter += 1
        rest -= 90
    qc, qs = ((_ONE, _ZERO), (_ZERO, _ONE), (-_ONE, _ZERO), (_ZERO, -_ONE))[quarter % 4]
    if rest == 0:
        return qc, qs
    t = Fraction(math.tan(math.radians(float(rest)) / 2))
    den = 1 + t * t
    c, s = (1 - t * t) / den, 2 * t / den
    # (qc + i·qs)·(c + i·s): a quarter turn composed with the small rotation, still exact.
    return qc * c - qs * s, qc * s + qs * c


# ---------------------------------------------------------------------------------------------- shapes
@dataclass(frozen=True)
class ExactShape:
    """Polygons with holes whose vertices are exact rational points.

    Attributes
    ----------
    polygons : tuple
        One entry per polygon: its rings (exterior first, then holes), each a tuple of vertices without the
        closing repeat.
    """

    polygons: tuple[PolygonRings, ...] = ()

    @classmethod
    def from_geometry(cls, geom: Any) -> ExactShape:
        """Read a shapely Polygon / MultiPolygon (or an empty geometry) exactly; an ExactShape is kept."""
        if isinstance(geom, ExactShape):
            return geom
        if geom is None or geom.is_empty:
            return cls(())
        if not isinstance(geom, Polygon | MultiPolygon):
            raise InvalidGeometryError(f"expected a polygon, got a {geom.geom_type}")
        polys = []
        for part in shapely.get_parts(geom):
            if part.is_empty:
                continue
            rings = []
            for ring in (part.exterior, *part.interiors):
                coords = ring.coords[:-1]
                rings.append(tuple((Fraction(float(x)), Fraction(float(y))) for x, y, *_ in coords))
            polys.append(tuple(rings))
        return cls(tuple(polys))

    def is_empty(self) -> bool:
        """True when there is no polygon."""
        return not self.polygons

    def coordinates(self) -> list[Fraction]:
        """Every coordinate (x and y values)."""
        return [c for poly in self.polygons for ring in poly for p in ring for c in p]

    def n_vertices(self) -> int:
        """The number of vertices."""
        return sum(len(ring) for poly in self.polygons for ring in poly)

    def bounds(self) -> tuple[Fraction, Fraction, Fraction, Fraction] | None:
        """(xmin, ymin, xmax, ymax), exact, or None when empty."""
        xs = [p[0] for poly in self.polygons for ring in poly for p in ring]
        ys = [p[1] for poly in self.polygons for ring in poly for p in ring]
        if not xs:
            return None
        return min(xs), min(ys), max(xs), max(ys)

    def map(self, sim: Similarity) -> ExactShape:
        """The exact image under a similarity (a direct similarity keeps ring orientations and validity)."""
        if sim.is_identity:
            return self
        return ExactShape(
            tuple(tuple(tuple(sim(p) for p in ring) for ring in poly) for poly in self.polygons)
        )

    def is_float_exact(self) -> bool:
        """True when every coordinate is a float64: :meth:`to_geometry` is then exact."""
        return all(is_float(c) for c in self.coordinates())

    def to_geometry(self) -> Polygon | MultiPolygon:
        """The shapely geometry, each coordinate rounded once to the nearest float64 (exact when it is one).

        Raises
        ------
        InvalidGeometryError
            When rounding made the polygon invalid (vertices closer than the float64 spacing), or a
            coordinate does not fit a float64.
        """
        if not self.polygons:
            return Polygon()
        try:
            polys = [
                Polygon(
                    [(float(x), float(y)) for x, y in poly[0]],
                    [[(float(x), float(y)) for x, y in ring] for ring in poly[1:]],
                )
                for poly in self.polygons
            ]
        except OverflowError:
            raise InvalidGeometryError("a coordinate of the result does not fit a float64") from None
        geom: Polygon | MultiPolygon = polys[0] if len(polys) == 1 else MultiPolygon(polys)
        if not self.is_float_exact() and not shapely.is_valid(geom):
            raise InvalidGeometryError(
                "the result's vertices are too close together for float64 coordinates "
                f"({shapely.is_valid_reason(geom)}); use a simpler scale factor"
            )
        return geom


# ---------------------------------------------------------------------------------------------- pixel boxes
def cell_range(lo: Fraction, hi: Fraction, model: str) -> tuple[int, int]:
    """Pixel indices k whose kernel can meet [lo, hi] along one axis, for ``model``.

    ``supercover``: the closed intervals [k − ½, k + ½] meeting [lo, hi]; ``standard`` and ``gauss``: from the
    cell (k − ½, k + ½] of ``lo`` to that of ``hi`` (tight for ``standard``, a superset for ``gauss``).
    """
    if model == "supercover":
        return math.ceil(lo - _HALF), math.floor(hi + _HALF)
    return math.ceil(lo - _HALF), math.ceil(hi - _HALF)


def pixel_box(bounds: Any, model: str) -> Any:
    """The pixel (or voxel) box holding D of any set with these Euclidean bounds (None for no bounds).

    ``bounds`` is ``(mins..., maxs...)`` in any dimension: (xmin, ymin, xmax, ymax) in the plane,
    (xmin, ymin, zmin, xmax, ymax, zmax) in space; the box has the same form.
    """
    if bounds is None:
        return None
    n = len(bounds) // 2
    ranges = [cell_range(bounds[d], bounds[n + d], model) for d in range(n)]
    return (*(r[0] for r in ranges), *(r[1] for r in ranges))


def voxel_bounds(box: Any) -> Any:
    """The Euclidean bounds of the voxels of a pixel (or voxel) box: each side widened by ½."""
    if box is None:
        return None
    n = len(box) // 2
    return (*(box[d] - _HALF for d in range(n)), *(box[n + d] + _HALF for d in range(n)))


def mapped_bounds(bounds: Any, sim: Any) -> Any:
    """Exact bounds of the image of a box under an affine map (the box of its mapped corners), any n."""
    if bounds is None:
        return None
    n = len(bounds) // 2
    corners = [
        tuple(bounds[d + n * ((k >> d) & 1)] for d in range(n)) for k in range(2**n)
    ]  # every choice of min or max per axis
    pts = [sim(p) for p in corners]
    return (*(min(p[d] for p in pts) for d in range(n)), *(max(p[d] for p in pts) for d in range(n)))
