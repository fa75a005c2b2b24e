"""Discrete-based simplification Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))).

Reference: the paper's Definition 14, docs/design.md §8.

``Sc_α(E)`` is computed exactly with rationals and discretized exactly
(:mod:`mrm.geometry.discretize.rational`);
R gives float64 vertices; ``Sc_1/α`` maps them back exactly, and the result is rounded once to float64 (a
Euclidean object is a shapely polygon). For α a power of two — or any α with ``v/α`` a float64 for every
vertex v — nothing is rounded at all.

Idempotence: ``Sp_α ∘ Sp_α = Sp_α`` because ``D(Sc_α(Sp_α(E))) = D(R(D(Sc_α(E)))) = D(Sc_α(E))``. When the
final rounding is exact this holds exactly. When it is not, each vertex moves by at most half a float64
spacing, and R keeps its boundary strictly away from every tie of the model (docs/design.md §3.6), so the
discretization at scale α — and therefore the result — does not change; the tests check it for non-dyadic
factors.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.grids import box_area, dimension_of
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, check_pixels
from mrm.core.models import Model
from mrm.core.numbers import Point, spell
from mrm.core.params import Parameters
from mrm.core.progress import ProgressLike, sub_progress
from mrm.geometry.discretize.exact_shape import ExactShape, Similarity, pixel_box
from mrm.geometry.discretize.exact_solid import ExactSolid, identity_map, scaling_map
from mrm.geometry.discretize.rational import discretize_exact
from mrm.geometry.hausdorff.bounds import BoundStep, simplification_step
from mrm.geometry.reconstruct import reconstruct
from mrm.ops.declare import alpha_param, center_param, model_param
from mrm.ops.estimate import estimated_pixels
from mrm.ops.outcome import StepOutcome
from mrm.ops.registry import OperationResult, OperationSpec, input_dimension, register
from mrm.ops.representations import euclidean_of


@dataclass(frozen=True)
class SimplifyParams(Parameters):
    """Parameters of Sp_α: α (read exactly), the centre of both scalings, the model."""

    alpha: Fraction = alpha_param(
        0.5, "The grid spacing is 1/α; details below it are simplified away (error ≤ √2/α)."
    )
    center: Point | None = center_param("Centre of the scalings (default: origin).")
    model: Model = model_param()


def _scaling(params: SimplifyParams) -> Similarity:
    """Sc_α about the centre."""
    return Similarity.scaling(params.alpha, params.center)


def simplification(
    source: Any,
    alpha: object,
    center: object = None,
    model: Model | str = Model.STANDARD,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
) -> StepOutcome:
    """Return Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))).

    Parameters
    ----------
    source : shapely Polygon / MultiPolygon, ExactShape, or PixelSet
        The Euclidean object E (for a pixel set A, its Euclidean representation R(A)).
    alpha : number
        α > 0: the voxel size of the simplification is 1/α.
    center : pair of numbers, optional
        The centre of both scalings (the origin by default; it changes where the grid falls).
    model : Model or str
    limit : int or None
        Largest discretization D(Sc_α(E)) (pixels of its bounding box), checked before it is computed.
    progress : object with ``update(fraction, message)``, optional

    Returns
    -------
    StepOutcome
        ``result`` (the polygon, float64), ``euclidean`` (the exact result before rounding), ``discrete``
        (D(Sc_α(E)), on the scaled grid), ``transform`` (the identity: Sc_1/α ∘ Sc_α).

    Raises
    ------
    ParameterError, SizeLimitError, InvalidGeometryError
    """
    params = SimplifyParams.read(alpha=alpha, center=center, model=model)
    model = params.model
    geom = euclidean_of(source, model)
    if dimension_of(geom) == 3:  # a polyhedron or an exact solid
        return _simplification_3d(ExactSolid.of(geom), params, limit=limit, progress=progress)
    sc = _scaling(params)
    a = sc.ratio
    shape = ExactShape.from_geometry(geom).map(sc)
    what = f"Sp with α = {spell(a)} (the discretization at scale α)"
    check_pixels(box_area(pixel_box(shape.bounds(), model)), limit, what)
    scaled = discretize_exact(shape, model, limit=limit, progress=sub_progress(progress, 0.0, 0.4), what=what)
    if progress is not None:
        progress.update(0.4, "continuing")
    back = sc.inverse()
    exact = ExactShape.from_geometry(reconstruct(scaled, model)).map(back)
    if progress is not None:
        progress.update(0.9, "scaling back")
    result = exact.to_geometry()
    if not exact.is_float_exact() and _rounding_may_matter(result, a):
        # Far from the origin the final rounding is no longer provably below R's margin: check the fixed
        # point exactly (one more discretization) and refuse rather than return a result that is not one.
        again = discretize_exact(ExactShape.from_geometry(result).map(sc), model, limit=limit, what=what)
        if again != scaled:
            raise ParameterError(
                f"{what}: the result cannot be written in float64 this far from the origin without changing "
                "its discretization (Sp_α would not be idempotent); move the object or the centre nearer "
                "the origin, or use an α whose inverse is a power of two"
            )
    if progress is not None:
        progress.update(1.0, "done")
    return StepOutcome(result, Similarity.identity(), exact, scaled, {"scaled_pixels": scaled})


def _simplification_3d(
    solid: ExactSolid, params: SimplifyParams, *, limit: int | None, progress: ProgressLike | None
) -> StepOutcome:
    """Sp_α of a solid (docs/design.md §11): D(Sc_α(E)) exactly, R of it, Sc_1/α back, rounded once.

    The exact result is Sc_1/α(R(D(Sc_α(E)))), an :class:`ExactSolid`; the polyhedron returned is its vertices
    rounded to float64 (exact when 1/α·v is a float64, e.g. α = 1/2, 1/3, 2/3 on R's quarter-grid vertices).
    When rounding happened, the fixed point is checked exactly — D(Sc_α(result)) must be the same voxels, so
    that Sp_α ∘ Sp_α = Sp_α — and a result that fails it, or is no longer a valid solid, is refused.
    """
    from mrm.geometry.polyhedra import Polyhedron  # 3D only: the plane work never loads the polyhedra

    model = str(params.model)
    sc = scaling_map(params.alpha, params.center, 3)
    what = f"Sp with α = {spell(params.alpha)} (the discretization at scale α)"
    scaled = solid.map(sc).discretize(model, limit=limit, progress=sub_progress(progress, 0.0, 0.4))
    if progress is not None:
        progress.update(0.4, "continuing")
    exact = ExactSolid(reconstruct(scaled, model)).map(sc.inverse())
    if progress is not None:
        progress.update(0.9, "scaling back")
    vertices, error = exact.float_vertices()
    try:
        result = exact.base if exact.transform.is_identity else Polyhedron(vertices, exact.base.triangles)
    except InvalidGeometryError as e:
        raise ParameterError(f"{what}: the result is no valid solid once written in float64 ({e})") from None
    if error:
        refusal = ParameterError(
            f"{what}: the result cannot be written in float64 keeping its discretization (Sp_α would not "
            "be idempotent); use an α whose numerator is a power of two (1/3, 2/3, 1/2…)"
        )
        try:
            again = ExactSolid(result).map(sc).discretize(model, limit=limit)
        except ParameterError:  # the rounded vertices have more bits than the exact voxelization takes
            raise refusal from None
        if again != scaled:
            raise refusal
    if progress is not None:
        progress.update(1.0, "done")
    return StepOutcome(result, identity_map(3), exact, scaled, {"scaled_pixels": scaled})


#: R keeps its boundary at least 2⁻²⁴ / L pixels from every tie of the model (its vertices lie on the grid
#: 2⁻¹² with the pixel corners and centres, so a nonzero cross product is at least 2⁻²⁴; L is the longest
#: edge). Rounding Sc_1/α's output to float64 moves a vertex by at most 2⁻⁵³·|v| per coordinate, i.e.
#: 2⁻⁵³·α·|v|·√2 pixels at scale α. Below this bound on α·|v|·L that is less than half the margin, so the
#: discretization at scale α, and hence Sp_α ∘ Sp_α = Sp_α, cannot change.
_PROVEN_PRODUCT = 2.0**27


def _rounding_may_matter(result: Any, alpha: Any) -> bool:
    # α·max|v|·L against the proven bound (L ≤ the diagonal of the result's box, at scale α).
    if result.is_empty:
        return False
    x0, y0, x1, y1 = result.bounds
    vmax = max(abs(x0), abs(y0), abs(x1), abs(y1))
    diag = float(alpha) * ((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5 + 1.0
    return bool(float(alpha) * vmax * diag >= _PROVEN_PRODUCT)


# ---------------------------------------------------------------------------------------------- the spec
def estimate(inputs: Sequence[Any], params: SimplifyParams) -> int:
    """The size of the discretization D(Sc_α(E)) from the input's bounding box alone."""
    n = input_dimension(inputs[:1])
    return estimated_pixels(inputs[:1], scaling_map(params.alpha, params.center, n), params.model)


def step(
    source: Any,
    params: SimplifyParams,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
    estimated: bool = False,
) -> StepOutcome:
    """Sp_α as a chain step (its own size check is of D(Sc_α(E)), made again: it costs a box)."""
    return simplification(source, params.alpha, params.center, params.model, limit=limit, progress=progress)


def run(
    inputs: Sequence[Any], params: SimplifyParams, progress: ProgressLike | None = None
) -> OperationResult:
    """Run Sp_α on one object (a pixel set A is read as its Euclidean representation R(A))."""
    out = step(inputs[0], params, progress=progress)
    return OperationResult(outputs=[(f"Sp {spell(params.alpha)}", out.result)])


def bound(params: SimplifyParams, part: str, n: int = 2) -> BoundStep:
    """Sp_α in the bound rule: a round trip at scale α."""
    return simplification_step(SPEC.label(params), scaling_map(params.alpha, params.center, n))


NAME = "simplify"
#: Sp_α, declared once: the panel, the CLI, the chain, the bound rule and the account read this spec.
SPEC = register(
    OperationSpec(
        name=NAME,
        title="Discrete-based simplification Sp_α",
        arity=1,
        params=SimplifyParams,
        run=run,
        reads="any",
        produces="euclidean",
        help="Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))): simplify on a grid of spacing 1/α (paper, Def. 14).",
        estimate=estimate,
        bound=bound,
        # Sp_α applies Sc_α and Sc_1/α around its round trip: as a whole, the identity.
        similarity=lambda params, n=2: identity_map(n),
        step=step,
        symbol="SP",
        aliases=("simplification",),
        grid="same",
        command="simplify",
    )
)
