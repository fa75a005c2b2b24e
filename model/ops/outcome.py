"""What an operation hands back besides its result, the guards every one runs first, and the D∘T∘R core.

Each operation is ``D∘T∘R`` (discrete → discrete), ``T⁻¹∘R∘D∘T`` (Euclidean → Euclidean) or a Boolean
combination of discretizations. To replay a chain and measure its error (DESIGN §8) the chain runner needs,
for every step, the Euclidean similarity ``T`` it applies and the Euclidean object just before its final
discretization (or its exact Euclidean result): :class:`StepOutcome` carries them, exactly.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass, field
from fractions import Fraction
from functools import partial
from typing import Any, TypeVar

import numpy as np

from mrm.errors import DEFAULT_PIXEL_LIMIT, ParameterError, SizeLimitError
from mrm.geometry.discretize.exact_shape import (
    ExactShape,
    Point,
    Similarity,
    box_area,
    exact_number,
    exact_point,
    mapped_bounds,
    number_to_json,
    pixel_box,
    positive_number,
    voxel_bounds,
)
from mrm.geometry.discretize.rational import discretize_exact, discretize_image
from mrm.geometry.hausdorff.bounds import ChainStep
from mrm.ops.base import OperationSpec, param
from mrm.progress import ProgressLike, sub_progress
from mrm.reps.pixels import Box, PixelSet

T = TypeVar("T")

#: The discretization models an operation accepts.
MODELS = ("standard", "supercover", "gauss")


def model_param() -> Any:
    """The ``model`` field every operation's parameters carry: the discretization model of D and R."""
    return param("standard", choices=MODELS, label="model", help="Discretization model of D and R.")


#: The range of every scale and precision factor α (DSS_α, Sp_α, EDco_α), declared once: beyond it a result
#: is either below one pixel or beyond any pixel limit, and the exact arithmetic would only spend time.
ALPHA_MIN, ALPHA_MAX = 1e-6, 1e6
#: The range of every rotation angle, in degrees (ten turns either way).
ANGLE_LIMIT = 3600.0


def alpha_param(default: float | None, help: str, *, optional: bool = False) -> Any:
    """A factor α with its declared range [ALPHA_MIN, ALPHA_MAX], read exactly (0.2 is 1/5)."""
    return param(
        default,
        kind="float",
        label="α",
        unit="×",
        minimum=ALPHA_MIN,
        maximum=ALPHA_MAX,
        optional=optional,
        help=help,
    )


def angle_param(default: float, help: str) -> Any:
    """A rotation angle in degrees with its declared range [−ANGLE_LIMIT, ANGLE_LIMIT]."""
    return param(default, label="θ", unit="°", minimum=-ANGLE_LIMIT, maximum=ANGLE_LIMIT, help=help)


def center_param(help: str) -> Any:
    """An optional centre (a point; None means the origin), as DSS_α, dR_θ,C and Sp_α take."""
    return param(None, kind="point", optional=True, label="centre", unit="px", help=help)


@dataclass(frozen=True)
class StepOutcome:
    """The result of one operation, with what a chain needs to bound and measure it.

    Attributes
    ----------
    result : PixelSet or shapely Polygon / MultiPolygon
        What the operation produces (a pixel set for DSS and dR, a polygon for Sp, EDu).
    transform : Similarity
        The Euclidean similarity the operation applies (identity for Sp, EDu, EDco).
    euclidean : ExactShape
        The exact Euclidean object just before the final discretization (DSS, dR: ``T(R(A))``), or the exact
        Euclidean result (Sp: ``Sc_1/α(R(D(Sc_α(E))))`` before rounding to float64; EDu: ``R(·)``).
    discrete : PixelSet
        The discrete result (DSS, dR), or the pixel set the Euclidean result was continued from (on the
        scaled grid for Sp and EDco_α).
    extra : dict
        Operation-specific values (e.g. the parts of a co-refinement).
    """

    result: Any
    transform: Similarity
    # An ExactShape, or a function making it on first use (it costs Fraction arithmetic); a module-level one
    # or a partial of one, so that the outcome pickles (the window's worker processes send it back).
    exact_image: Any
    discrete: PixelSet
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def euclidean(self) -> ExactShape:
        """The exact Euclidean object (computed on first use when the operation did not need it)."""
        value = self.exact_image
        if not isinstance(value, ExactShape):
            value = value()
            object.__setattr__(self, "exact_image", value)
        assert isinstance(value, ExactShape)
        return value


def check_model(model: str) -> str:
    """Return ``model`` if it is a discretization model, else raise ParameterError."""
    if model not in MODELS:
        raise ParameterError(f"unknown discretization model {model!r}; choose one of {', '.join(MODELS)}")
    return model


def check_limit(limit: int | None) -> None:
    """Refuse a pixel limit that is not a non-negative integer (None = no limit)."""
    if limit is not None and (isinstance(limit, bool) or not isinstance(limit, int) or limit < 0):
        raise ParameterError(f"the pixel limit must be a non-negative integer or None, got {limit!r}")


def check_size(estimated: int, limit: int | None, what: str) -> None:
    """Raise SizeLimitError when ``estimated`` pixels exceed ``limit`` (before anything is computed)."""
    if limit is not None and estimated > limit:
        raise SizeLimitError(estimated, int(limit), what)


def estimated_pixels(source: Any, sim: Similarity, model: str) -> int:
    """An upper bound of the pixels of D(T(R(A))), A an object's discrete representation (nothing computed).

    A pixel set is A itself; for a polygon E, A = D(E) lies in the closed cells of E's bounding box (the
    supercover box). Under the covers R(A) ⊂ V(A) ⊂ V(bbox(A)); under gauss ∂R(A) stays within the voxels
    of the border pixels on either side (DESIGN §3.2), so R(A) lies in V(bbox(A)) grown by one pixel.
    T(R(A)) lies in the box of T's image of that rectangle. The one estimate of DSS_α and dR_θ,C: the
    registry's guard (run_operation) and the direct calls both use it.
    """
    if source is None:
        return 0
    if isinstance(source, PixelSet):
        box = source.bbox
    elif source.is_empty:
        return 0
    else:
        x0, y0, x1, y1 = (Fraction(float(v)) for v in source.bounds)
        box = pixel_box((x0, y0, x1, y1), "supercover")
    if box is not None and model == "gauss":
        box = (box[0] - 1, box[1] - 1, box[2] + 1, box[3] + 1)
    return box_area(pixel_box(mapped_bounds(voxel_bounds(box), sim), model))


def discrete_similarity(
    ps: PixelSet,
    sim: Similarity,
    model: str,
    *,
    limit: int | None,
    progress: ProgressLike | None,
    what: str,
    estimated: bool = False,
) -> StepOutcome:
    """``D(T(R(A)))`` with ``T`` applied exactly: the core of DSS_α and dR_θ,C.

    The size of the result is estimated from A's bounding box first (:func:`estimated_pixels`) and refused
    beyond ``limit``, unless the caller did so already (``estimated``: run_operation's guard).
    """
    check_model(model)
    check_limit(limit)
    if not estimated:
        check_size(estimated_pixels(ps, sim, model), limit, what)
    from mrm.geometry.reconstruct import reconstruct

    pooled = scaling_by_pixels(ps, sim, model)
    if pooled is not None:
        # The pixels of A decide every result pixel (see scaling_by_pixels); R(A) and T(R(A)) are still the
        # chain's Euclidean object, made on first use only.
        if progress is not None:
            progress.update(1.0, "done")
        return StepOutcome(pooled, sim, partial(_reconstructed_image, ps, sim, model), pooled)
    if progress is not None:
        progress.update(0.0, "continuing R(A)")
    euclid = reconstruct(ps, model)
    if progress is not None:
        progress.update(0.3, "applying the similarity")

    image = partial(_mapped_image, euclid, sim)
    # Scalings and translations of float64 vertices: integer arithmetic and compiled kernels, no Fraction.
    result = discretize_image(euclid, sim, model, limit=limit, what=what, valid=True)  # R's output is valid
    if result is None:
        exact = image()
        result = discretize_exact(
            exact, model, limit=limit, progress=sub_progress(progress, 0.3, 1.0), what=what
        )
        return StepOutcome(result, sim, exact, result)
    if progress is not None:
        progress.update(1.0, "done")
    return StepOutcome(result, sim, image, result)


def _mapped_image(geom: Any, sim: Similarity) -> ExactShape:
    """``sim(geom)`` exactly: the Euclidean object of a step, made when first asked for.

    A module-level function (bound with :func:`functools.partial`), never a closure: a :class:`StepOutcome`
    holding it is pickled to and from the window's worker processes.
    """
    return ExactShape.from_geometry(geom).map(sim)


def _reconstructed_image(ps: PixelSet, sim: Similarity, model: str) -> ExactShape:
    """``sim(R(ps))`` exactly (see :func:`_mapped_image`)."""
    from mrm.geometry.reconstruct import reconstruct

    return _mapped_image(reconstruct(ps, model), sim)


def scaling_by_pixels(ps: PixelSet, sim: Similarity, model: str) -> PixelSet | None:
    """DSS_1/k(A) = D(Sc_1/k(R(A))) from A's pixels alone, when the grid of the result is aligned to A's.

    Applies when ``sim`` is ``Sc_α`` with α = 1/k (k a positive integer) about a centre C, and
    ``Sc_1/α = v ↦ k·v + c`` (c = (1 − k)·C) maps pixel centres to pixel centres (gauss: c ∈ Z²) or the
    kernel of every result pixel onto a k × k block of A's voxels (covers: c − (k − 1)/2 ∈ Z²); otherwise
    returns None. Proof, from R's contract (DESIGN §3; :mod:`mrm.geometry.reconstruct`, items 1–3):

    * ``gauss``: q ∈ D(Sc_α(R(A))) ⟺ z + kτ ∈ R(A) with z = k·q + c, a pixel centre. No centre lies on
      ∂R(A), so that is z ∈ R(A), and since D(R(A)) = A it is z ∈ A: the result is A sampled every k
      pixels, ``{q : k·q + c ∈ A}``.
    * ``standard`` / ``supercover``: the kernel of q maps to the open block B(q) + kτ (standard) or the
      closed block B̄(q) (supercover) made of the voxels of the k × k pixels b with
      b − (k·q + s) ∈ [0, k − 1]², s = c − (k − 1)/2. If one of them is in A, R(A) meets int V(b)
      (condition C2: its centre is in R(A) or ∂R(A) crosses its open square), an open subset of B(q), so
      both kernels meet R(A). If none is, R(A) misses every V(b) (the same R(A) has D_supercover = A, so it
      misses the closed voxel of every pixel outside A), so it misses the compact B̄(q) at a positive
      distance and both kernels. The result is ``{q : A meets the block of q}``, a k × k OR-pooling.

    (k = 1 gives DSS_1(A) = A.) tests/model/test_ops_scaling.py compares it with D(Sc_α(R(A))) computed.
    """
    if sim.b != 0 or sim.a <= 0 or sim.a.numerator != 1 or ps.is_empty():
        return None
    inv = sim.inverse()
    k = int(inv.a)
    cx, cy = inv.tx, inv.ty
    if model == "gauss":
        if cx.denominator != 1 or cy.denominator != 1:
            return None
        sx, sy = int(cx), int(cy)
    else:
        half = Fraction(k - 1, 2)
        if (cx - half).denominator != 1 or (cy - half).denominator != 1:
            return None
        sx, sy = int(cx - half), int(cy - half)
    x0, y0 = ps.origin
    mask = ps.mask
    if model == "gauss":
        # q holds the one pixel b = k·q + s: the rows and columns of A congruent to s modulo k.
        r0, c0 = (sy - y0) % k, (sx - x0) % k
        sub = np.ascontiguousarray(mask[r0::k, c0::k])
        return PixelSet(sub, ((x0 + c0 - sx) // k, (y0 + r0 - sy) // k))
    # q holds the pixels b with k·q + s ≤ b ≤ k·q + s + k − 1: pad A to whole blocks, then OR each block.
    qx0, qy0 = (x0 - sx) // k, (y0 - sy) // k
    left, bottom = (x0 - sx) - k * qx0, (y0 - sy) - k * qy0
    h, w = mask.shape
    rows = -(-(h + bottom) // k)
    cols = -(-(w + left) // k)
    if (bottom, left, h, w) == (0, 0, rows * k, cols * k):
        padded = mask
    else:
        padded = np.zeros((rows * k, cols * k), dtype=bool)
        padded[bottom : bottom + h, left : left + w] = mask
    # OR of the k rows, then of the k columns of each block (k slice ORs: ten times faster than .any(axis)).
    strips = padded.reshape(rows, k, cols * k)
    rows_or = strips[:, 0].copy()
    for i in range(1, k):
        rows_or |= strips[:, i]
    blocks = rows_or.reshape(rows, cols, k)
    pooled = blocks[..., 0].copy()
    for i in range(1, k):
        pooled |= blocks[..., i]
    return PixelSet(pooled, (qx0, qy0))


def factor_params(name: str, doc: str, factor: str, declared: Any, centre: str, module: str) -> type:
    """The parameters dataclass of a one-factor similarity operation: ``factor``, ``center``, ``model``.

    DSS_α, dR_θ,C and Sp_α take their number (declared with :func:`alpha_param` or :func:`angle_param`), an
    optional centre (help text ``centre``) and the model, in that order; the class is frozen, named ``name``
    in ``module`` (so that it pickles to a worker process), and read by :func:`mrm.ops.base.param_specs`.
    """
    fields = [
        (factor, float, declared),
        ("center", tuple[float, float] | None, center_param(centre)),
        ("model", str, model_param()),
    ]
    cls = dataclasses.make_dataclass(name, fields, frozen=True, namespace={"__doc__": doc})
    cls.__module__ = module
    return cls


def factor_map(
    factor: str, make: Callable[[Fraction, Point | None], T], *, signed: bool = False
) -> Callable[[Any], T]:
    """``params ↦ make(q, C)``: an operation's number ``factor`` and its ``center``, read exactly.

    The one reading of a similarity's parameters (DESIGN §8): a float is the decimal it prints as (0.4 is
    2/5), a ``signed`` number (an angle) may be any finite value, any other must be positive. DSS_α, dR_θ,C,
    Sp_α and the Euclidean scale and rotate make their exact similarity and their bound step through it, so
    the registry's run, the chain, the bound rule and the account read the same numbers, with the same
    messages.
    """
    read = exact_number if signed else positive_number

    def of(params: Any) -> T:
        return make(read(getattr(params, factor), factor), exact_point(params.center, "center"))

    return of


def register_discrete_similarity(
    *,
    name: str,
    title: str,
    params: type,
    factor: str,
    similarity: Callable[[Fraction, Point | None], Similarity],
    bound: Callable[[Fraction, Point | None], ChainStep],
    label: str,
    what: str,
    help: str,
    aliases: tuple[str, ...],
    signed: bool = False,
) -> OperationSpec:
    """Register a ``D∘T∘R`` operation (DSS_α, dR_θ,C) from its declarations alone.

    ``params`` carries the number ``factor`` (and ``center``, ``model``); ``similarity(q, C)`` makes the exact
    T and ``bound(q, C)`` its step in the bound rule, both read by :func:`factor_map`. ``label`` names the
    result and ``what`` the operation in a refusal, each with ``{}`` for the number (``"DSS {}"`` gives
    ``DSS 0.2``). The size estimate, the step and the run are the same for every such operation, so they are
    written here once; the module's public function is the step.
    """
    from mrm.ops.base import OperationResult, register

    sim_of = factor_map(factor, similarity, signed=signed)
    read = exact_number if signed else positive_number

    def number(p: Any) -> Any:
        return number_to_json(read(getattr(p, factor), factor))

    def estimate(inputs: Any, p: Any) -> int:
        return estimated_pixels(inputs[0], sim_of(p), p.model)

    def step(
        source: Any,
        p: Any,
        *,
        limit: int | None = DEFAULT_PIXEL_LIMIT,
        progress: ProgressLike | None = None,
        estimated: bool = False,
    ) -> StepOutcome:
        sim = sim_of(p)
        ps = discrete_of(source, p.model, limit)
        return discrete_similarity(
            ps, sim, p.model, limit=limit, progress=progress, what=what.format(number(p)), estimated=estimated
        )

    def run(inputs: Any, p: Any, progress: ProgressLike | None = None) -> Any:
        # run_operation validated the parameters, checked the size (estimate above) and stamps provenance
        # and bound: the estimate is not made a second time.
        out = step(inputs[0], p, progress=progress, estimated=True)
        return OperationResult(outputs=[(label.format(number(p)), out.result)])

    return register(
        OperationSpec(
            name=name,
            title=title,
            arity=1,
            params=params,
            run=run,
            input_kind="any",
            output_kind="discrete",
            help=help,
            estimate=estimate,
            chain_step=factor_map(factor, bound, signed=signed),
            similarity=sim_of,
            aliases=aliases,
            step=step,
        )
    )


def discrete_of(source: Any, model: str, limit: int | None) -> PixelSet:
    """The discrete representation of an object's source: A itself, or D(E) for a polygon E."""
    if isinstance(source, PixelSet):
        return source
    from mrm.geometry.discretize import discretize

    return discretize(source, model, limit=limit)


def params_json(params: Any) -> dict[str, Any]:
    """A parameter dataclass (or mapping) as JSON data: tuples become lists, Fractions exact numbers."""
    raw = (
        {k: getattr(params, k) for k in params.__dataclass_fields__}
        if hasattr(params, "__dataclass_fields__")
        else dict(params)
    )

    def conv(v: Any) -> Any:
        if isinstance(v, Fraction):
            return number_to_json(v)
        if isinstance(v, tuple | list):
            return [conv(x) for x in v]
        return v

    return {k: conv(v) for k, v in raw.items()}


def provenance(operation: str, params: Any, inputs: tuple[int, ...] = ()) -> dict[str, Any]:
    """``{"operation", "params", "inputs"}`` as :meth:`mrm.document.Provenance.from_json` reads it."""
    return {"operation": operation, "params": params_json(params), "inputs": list(inputs)}


def source_box(source: Any, sim: Similarity, model: str) -> Box | None:
    """A pixel box holding D(T(X)) for an object X (a pixel set: from its voxels; a polygon: its bounds)."""
    if isinstance(source, PixelSet):
        return pixel_box(mapped_bounds(voxel_bounds(source.bbox), sim), model)
    if source is None or source.is_empty:
        return None
    x0, y0, x1, y1 = (Fraction(float(v)) for v in source.bounds)
    return pixel_box(mapped_bounds((x0, y0, x1, y1), sim), model)


def estimate_source(source: Any, sim: Similarity, model: str) -> int:
    """An upper bound of the pixels of D(T(X)) for an object X, before anything is computed."""
    return box_area(source_box(source, sim, model))


def joint_box(boxes: list[Box | None]) -> Box | None:
    """The smallest box holding every given box (None when there is none)."""
    real = [b for b in boxes if b is not None]
    if not real:
        return None
    return min(b[0] for b in real), min(b[1] for b in real), max(b[2] for b in real), max(b[3] for b in real)
