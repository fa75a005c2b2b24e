"""Euclidean similarities of shapely geometries: translation, scaling about a centre, rotation about a centre.

These are the exact Euclidean maps the paper's operations are built from (``Sc_α``, ``rot_θ,C``). Floats
cannot hold every image exactly, so the guarantee is the best one floats allow:

- translations, scalings and rotations by a multiple of 90° are *correctly rounded*: every output coordinate
  is the float nearest to the exact image of the input coordinate (in particular it is exact whenever the
  exact image is a float — a rotation by 90° about a pixel centre of a polygon with dyadic coordinates is
  exact, as docs/design.md §3.6 needs). The fast path computes in floats and proves, with error-free
  transformations (TwoSum, Dekker's TwoProduct), that its only rounding is the last one; the few coordinates
  where it cannot are recomputed with :class:`fractions.Fraction`;
- other rotations use ``cos θ`` and ``sin θ`` rounded to floats, so images are within a few ulps
  (``shapely.affinity`` would also round ``cos 90°`` to ``6e-17``; here 90° multiples never touch cos/sin).

The registered operations ``scale``, ``rotate`` and ``translate`` do not use these float functions: they read
their parameters as every other path does (a float is the decimal it prints as, so 0.4 is 2/5; a rotation is
the exact rational rotation of :mod:`mrm.geometry.discretize.exact_shape`), apply the map exactly and round
each coordinate
once — the same numbers as the chain steps of the same names.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
import numpy.typing as npt
import shapely
from shapely.geometry import MultiPolygon, Polygon
from shapely.geometry.base import BaseGeometry

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.grids import PixelSet
from mrm.core.numbers import Point
from mrm.core.params import Parameters, param
from mrm.core.progress import ProgressLike
from mrm.geometry.discretize.exact_shape import ExactShape, Similarity
from mrm.geometry.hausdorff.bounds import BoundStep, euclidean_similarity_step
from mrm.ops.declare import alpha_param, angle_param, center_param
from mrm.ops.outcome import StepOutcome
from mrm.ops.registry import OperationResult, OperationSpec, Output, register

F64 = npt.NDArray[np.float64]

__all__ = [
    "ROTATE",
    "SCALE",
    "TRANSLATE",
    "RotateParams",
    "ScaleParams",
    "TranslateParams",
    "rotate_geometry",
    "scale_geometry",
    "translate_geometry",
]

_SPLITTER = 134217729.0  # 2**27 + 1, Veltkamp's constant for float64


def _two_sum_err(a: F64, b: F64, s: F64) -> F64:
    """The rounding error of ``s = fl(a + b)`` (Knuth's TwoSum; exact barring overflow)."""
    bb = s - a
    return (a - (s - bb)) + (b - bb)


def _split(a: F64) -> tuple[F64, F64]:
    c = _SPLITTER * a
    hi = c - (c - a)
    return hi, a - hi


def _two_prod_err(a: F64, b: float, p: F64) -> F64:
    """The rounding error of ``p = fl(a·b)`` (Dekker's TwoProduct; exact barring overflow/underflow)."""
    ah, al = _split(a)
    bh, bl = _split(np.full_like(a, b))
    return ((ah * bh - p) + ah * bl + al * bh) + al * bl


def _affine(u: F64, c_in: float, s: float, c_out: float) -> F64:
    """Correctly rounded ``c_out + s·(u − c_in)`` for every entry of ``u``."""
    with np.errstate(all="ignore"):
        d = u - c_in
        ok = _two_sum_err(u, np.full_like(u, -c_in), d) == 0
        p = d * s
        ok &= _two_prod_err(d, s, p) == 0
        r = p + c_out
        # Dekker's product is exact only away from overflow and underflow: check the ranges.
        ok &= np.isfinite(r) & (np.abs(u) < 2.0**900) & (abs(s) < 2.0**900)
        ok &= ((p == 0) & (d == 0)) | (np.abs(p) > 2.0**-900)
    if not ok.all():
        fs, fi, fo = Fraction(s), Fraction(c_in), Fraction(c_out)
        for i in np.flatnonzero(~ok):
            try:
                r[i] = float(fo + fs * (Fraction(float(u[i])) - fi))
            except OverflowError:
                raise InvalidGeometryError("the transformed coordinates overflow float64") from None
    return r


def _finite(v: float, what: str) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float, Fraction)) or not math.isfinite(float(v)):
        raise ParameterError(f"{what} must be a finite number, got {v!r}")
    return float(v)


def _checked(out: BaseGeometry, src: BaseGeometry) -> BaseGeometry:
    coords = shapely.get_coordinates(out)
    if coords.size and not np.isfinite(coords).all():
        raise InvalidGeometryError("the transformed coordinates overflow float64")
    if src.is_valid and not out.is_valid:
        raise InvalidGeometryError(
            f"the transformed geometry is invalid after rounding to floats ({shapely.is_valid_reason(out)})"
        )
    return out


def translate_geometry(geom: BaseGeometry, dx: float, dy: float) -> BaseGeometry:
    """``geom + (dx, dy)``, every coordinate correctly rounded."""
    dx, dy = _finite(dx, "dx"), _finite(dy, "dy")

    def fn(xy: F64) -> F64:
        out = np.empty_like(xy)
        out[:, 0] = _affine(xy[:, 0], 0.0, 1.0, dx)
        out[:, 1] = _affine(xy[:, 1], 0.0, 1.0, dy)
        return out

    return _checked(shapely.transform(geom, fn), geom)


def scale_geometry(geom: BaseGeometry, factor: float, center: Sequence[float] = (0.0, 0.0)) -> BaseGeometry:
    """``center + factor·(x − center)``, every coordinate correctly rounded (``factor`` > 0)."""
    s = _finite(factor, "scale factor")
    if s <= 0:
        raise ParameterError(f"the scale factor must be positive, got {factor!r}")
    cx, cy = _finite(center[0], "centre x"), _finite(center[1], "centre y")

    def fn(xy: F64) -> F64:
        out = np.empty_like(xy)
        out[:, 0] = _affine(xy[:, 0], cx, s, cx)
        out[:, 1] = _affine(xy[:, 1], cy, s, cy)
        return out

    return _checked(shapely.transform(geom, fn), geom)


def rotate_geometry(
    geom: BaseGeometry, angle_deg: float, center: Sequence[float] = (0.0, 0.0)
) -> BaseGeometry:
    """Rotate by ``angle_deg`` degrees (counter-clockwise, y up) about ``center``.

    Multiples of 90° are exact maps (correctly rounded coordinates, no cosine involved); other angles round
    ``cos``/``sin`` to floats.
    """
    a = _finite(angle_deg, "angle")
    cx, cy = _finite(center[0], "centre x"), _finite(center[1], "centre y")
    if a % 90 == 0:
        k = int(a // 90) % 4

        def fn(xy: F64) -> F64:
            x, y = xy[:, 0], xy[:, 1]
            out = np.empty_like(xy)
            if k == 0:
                out[:] = xy
            elif k == 1:  # (x, y) ↦ (cx − (y − cy), cy + (x − cx))
                out[:, 0] = _affine(y, cy, -1.0, cx)
                out[:, 1] = _affine(x, cx, 1.0, cy)
            elif k == 2:
                out[:, 0] = _affine(x, cx, -1.0, cx)
                out[:, 1] = _affine(y, cy, -1.0, cy)
            else:
                out[:, 0] = _affine(y, cy, 1.0, cx)
                out[:, 1] = _affine(x, cx, -1.0, cy)
            return out

    else:
        t = math.radians(a)
        c, s = math.cos(t), math.sin(t)

        def fn(xy: F64) -> F64:
            dx, dy = xy[:, 0] - cx, xy[:, 1] - cy
            out = np.empty_like(xy)
            out[:, 0] = cx + (c * dx - s * dy)
            out[:, 1] = cy + (s * dx + c * dy)
            return out

    return _checked(shapely.transform(geom, fn), geom)


# ============================================================================================================
# As operations
# ============================================================================================================


@dataclass(frozen=True)
class TranslateParams(Parameters):
    """Parameters of a Euclidean translation: the offset (written ``TRANSLATE dx,dy`` in a chain's text)."""

    dx: Fraction = param(
        0,
        kind="number",
        label="dx",
        unit="px",
        positional=True,
        help="Horizontal offset (x grows to the right).",
    )
    dy: Fraction = param(
        0, kind="number", label="dy", unit="px", positional=True, help="Vertical offset (y grows upwards)."
    )


@dataclass(frozen=True)
class ScaleParams(Parameters):
    """Parameters of a Euclidean scaling."""

    factor: Fraction = alpha_param(2, "Scale factor (> 0).", label="factor")
    center: Point = center_param("The fixed point.", default=(0, 0))


@dataclass(frozen=True)
class RotateParams(Parameters):
    """Parameters of a Euclidean rotation."""

    angle: Fraction = angle_param(0, "Counter-clockwise angle in degrees.")
    center: Point = center_param("The centre of rotation.", default=(0, 0))


# One arithmetic for every path (docs/design.md §8): the registry's similarities read their parameters as the
# chain's steps do — a float as the decimal it prints as (0.4 is 2/5), the exact rational rotation — apply
# them exactly and round each coordinate once.


def _exact_map(geom: BaseGeometry, sim: Similarity) -> BaseGeometry:
    """The exact image of a polygonal geometry, each coordinate rounded once to float64."""
    if not isinstance(geom, Polygon | MultiPolygon):
        raise InvalidGeometryError(f"expected a polygon, got a {geom.geom_type}")
    return _checked(ExactShape.from_geometry(geom).map(sim).to_geometry(), geom)


def euclidean_step(source: Any, sim: Similarity) -> StepOutcome:
    """A Euclidean similarity as a chain step: the exact image (kept for the next step), rounded once."""
    exact = ExactShape.from_geometry(source).map(sim)
    return StepOutcome(exact.to_geometry(), sim, exact, PixelSet.empty())


def _similarity_operation(
    name: str, params: type, similarity: Callable[[Any], Similarity], output: str, **declared: Any
) -> OperationSpec:
    """Register a Euclidean similarity: ``similarity(params)`` is its exact map, ``output`` names the result.

    ``declared`` is the rest of its :class:`OperationSpec` (title, help, symbol, aliases).
    """

    def run(inputs: Sequence[Output], p: Any, progress: ProgressLike) -> OperationResult:
        return OperationResult(outputs=[(output, _exact_map(inputs[0], similarity(p)))])

    def step(source: Any, p: Any, **_: Any) -> StepOutcome:
        return euclidean_step(source, similarity(p))

    def bound(p: Any, part: str, n: int = 2) -> BoundStep:
        return euclidean_similarity_step(spec.label(p), in_plane(p, n))

    def in_plane(p: Any, n: int = 2) -> Similarity:
        # the exact Euclidean maps are planar so far (the registry refuses them 3D inputs)
        if n != 2:
            raise ParameterError(f"{declared.get('title', name)} does not take 3D objects yet")
        return similarity(p)

    spec = OperationSpec(
        name=name,
        arity=1,
        params=params,
        run=run,
        reads="euclidean",
        produces="euclidean",
        similarity=in_plane,
        step=step,
        bound=bound,
        **declared,
    )
    return register(spec)


TRANSLATE = _similarity_operation(
    "translate",
    TranslateParams,
    lambda p: Similarity.translation(p.dx, p.dy),
    "translated",
    title="Translate",
    help="Move a Euclidean object by (dx, dy), exactly, each coordinate rounded once.",
    symbol="TRANSLATE",
    aliases=("tr", "move"),
)
SCALE = _similarity_operation(
    "scale",
    ScaleParams,
    lambda p: Similarity.scaling(p.factor, p.center),
    "scaled",
    title="Scale (Euclidean)",
    help="Scale a Euclidean object about a centre, exactly (0.4 is 2/5), each coordinate rounded once.",
    symbol="SCALE",
    aliases=("sc",),
)
ROTATE = _similarity_operation(
    "rotate",
    RotateParams,
    lambda p: Similarity.rotation(p.angle, p.center),
    "rotated",
    title="Rotate (Euclidean)",
    help="Rotate a Euclidean object about a centre by the exact rational rotation, rounded once.",
    symbol="EROT",
    aliases=("erotate",),
)
