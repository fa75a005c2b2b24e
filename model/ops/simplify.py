"""Discrete-based simplification Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))) (the paper's Definition 14, DESIGN §8).

``Sc_α(E)`` is computed exactly with rationals and discretized exactly
(:mod:`mrm.geometry.discretize.rational`);
R gives float64 vertices; ``Sc_1/α`` maps them back exactly, and the result is rounded once to float64 (a
Euclidean object is a shapely polygon). For α a power of two — or any α with ``v/α`` a float64 for every
vertex v — nothing is rounded at all.

Idempotence: ``Sp_α ∘ Sp_α = Sp_α`` because ``D(Sc_α(Sp_α(E))) = D(R(D(Sc_α(E)))) = D(Sc_α(E))``. When the
final rounding is exact this holds exactly. When it is not, each vertex moves by at most half a float64
spacing, and R keeps its boundary strictly away from every tie of the model (DESIGN §3.6), so the
discretization at scale α — and therefore the result — does not change; the tests check it for non-dyadic
factors.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from mrm.core.errors import DEFAULT_PIXEL_LIMIT, ParameterError
from mrm.core.grids import PixelSet
from mrm.core.progress import ProgressLike, sub_progress
from mrm.geometry.discretize.exact_shape import (
    ExactShape,
    Similarity,
    box_area,
    number_to_json,
    pixel_box,
)
from mrm.geometry.discretize.rational import discretize_exact
from mrm.geometry.hausdorff import bounds
from mrm.ops.base import OperationResult, OperationSpec, register
from mrm.ops.outcome import (
    StepOutcome,
    alpha_param,
    check_limit,
    check_model,
    check_size,
    estimate_source,
    factor_map,
    factor_params,
)


def euclidean_input(source: Any, model: str) -> Any:
    """The Euclidean representation of an object's source: E itself, or R(A) for a pixel set A.

    E may be a shapely polygon or an exact :class:`~mrm.geometry.discretize.exact_shape.ExactShape` (kept as
    it is).
    """
    if isinstance(source, PixelSet):
        from mrm.geometry.reconstruct import reconstruct

        return reconstruct(source, model)
    return source


def simplification(
    source: Any,
    alpha: object,
    center: object = None,
    model: str = "standard",
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
    model : {"standard", "supercover", "gauss"}
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
    check_model(model)
    check_limit(limit)
    sc = _scaling(SPEC.params(alpha, center, model))
    a = sc.ratio
    geom = euclidean_input(source, model)
    shape = ExactShape.from_geometry(geom).map(sc)
    what = f"Sp with α = {number_to_json(a)} (the discretization at scale α)"
    check_size(box_area(pixel_box(shape.bounds(), model)), limit, what)
    scaled = discretize_exact(shape, model, limit=limit, progress=sub_progress(progress, 0.0, 0.4), what=what)
    if progress is not None:
        progress.update(0.4, "continuing")
    from mrm.geometry.reconstruct import reconstruct

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
#: α (read exactly), the centre of both scalings, the model.
SimplifyParams = factor_params(
    "SimplifyParams",
    "Parameters of Sp_α.",
    "alpha",
    alpha_param(0.5, "The grid spacing is 1/α; details below it are simplified away (error ≤ √2/α)."),
    "Centre of the scalings (default: origin).",
    __name__,
)


#: Sc_α about the centre, read as every path reads it (:func:`mrm.ops.outcome.factor_map`).
_scaling = factor_map("alpha", Similarity.scaling)


def estimate(inputs: Sequence[Any], params: Any) -> int:
    """The size of the discretization D(Sc_α(E)) from the input's bounding box alone."""
    return estimate_source(inputs[0], _scaling(params), params.model)


def step(
    source: Any,
    params: Any,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
    estimated: bool = False,
) -> StepOutcome:
    """Sp_α as a chain step (its own size check is of D(Sc_α(E)), made again: it costs a box)."""
    return simplification(source, params.alpha, params.center, params.model, limit=limit, progress=progress)


def run(inputs: Sequence[Any], params: Any, progress: ProgressLike | None = None) -> OperationResult:
    """Run Sp_α on one object (a pixel set A is read as its Euclidean representation R(A))."""
    out = step(inputs[0], params, progress=progress)
    return OperationResult(outputs=[(f"Sp {number_to_json(_scaling(params).ratio)}", out.result)])


NAME = "simplify"
#: Sp_α, declared once: the panel, the CLI, the chain, the bound rule and the account read this spec.
SPEC = register(
    OperationSpec(
        name=NAME,
        title="Discrete-based simplification Sp_α",
        arity=1,
        params=SimplifyParams,
        run=run,
        input_kind="any",
        output_kind="euclidean",
        help="Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))): simplify on a grid of spacing 1/α (paper, Def. 14).",
        estimate=estimate,
        chain_step=factor_map("alpha", bounds.sp),
        # Sp_α applies Sc_α and Sc_1/α around its round trip: as a whole, the identity.
        similarity=lambda params: Similarity.identity(),
        aliases=("SP", "simplification"),
        step=step,
    )
)
