"""What an operation hands back besides its result, the guards every one runs first, and the D∘T∘R core.

Each operation is ``D∘T∘R`` (discrete → discrete), ``T⁻¹∘R∘D∘T`` (Euclidean → Euclidean) or a Boolean
combination of discretizations. To replay a chain and measure its error (docs/design.md §8) the chain runner
needs, for every step, the Euclidean similarity ``T`` it applies and the Euclidean object just before its
final discretization (or its exact Euclidean result): :class:`StepOutcome` carries them, exactly.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import partial
from typing import Any, TypeVar

from mrm.core.blocks import or_pool, sample
from mrm.core.grids import GridSet, PixelSet, VoxelSet
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, check_pixels
from mrm.core.models import Model
from mrm.core.progress import ProgressLike, sub_progress
from mrm.geometry.discretize.exact_shape import ExactShape, Similarity
from mrm.geometry.discretize.exact_solid import ExactSolid, Similarity3
from mrm.geometry.discretize.rational import discretize_exact, discretize_image
from mrm.geometry.hausdorff.bounds import BoundStep, discrete_similarity_step
from mrm.geometry.reconstruct import reconstruct
from mrm.ops.estimate import estimated_pixels
from mrm.ops.registry import OperationResult, OperationSpec, input_dimension, register
from mrm.ops.representations import discrete_of

_G = TypeVar("_G", bound="GridSet[Any, Any]")


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
    transform: Any
    # An ExactShape, or a picklable function making it on first use (it costs Fraction arithmetic): a module
    # function bound with functools.partial, never a closure, so that an outcome can cross to a worker
    # process.
    exact_image: Any
    discrete: Any
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def euclidean(self) -> Any:
        """The exact Euclidean object (computed on first use when the operation did not need it).

        An :class:`ExactShape` in the plane, an :class:`~mrm.geometry.discretize.exact_solid.ExactSolid`
        in space.
        """
        value = self.exact_image
        if not isinstance(value, ExactShape | ExactSolid):
            value = value()
            object.__setattr__(self, "exact_image", value)
        return value


def discrete_similarity(
    ps: PixelSet | VoxelSet,
    sim: Any,
    model: Model | str,
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
    if not estimated:
        check_pixels(estimated_pixels([ps], sim, model, reads="discrete"), limit, what)
    if isinstance(ps, VoxelSet):
        return _discrete_similarity_3d(ps, sim, model, limit=limit, progress=progress)
    pooled = scaling_by_pixels(ps, sim, model)
    if pooled is not None:
        # The pixels of A decide every result pixel (see scaling_by_pixels); R(A) and T(R(A)) are still the
        # chain's Euclidean object, made on first use only.
        if progress is not None:
            progress.update(1.0, "done")
        return StepOutcome(pooled, sim, partial(continued_image, ps, sim, model), pooled)
    if progress is not None:
        progress.update(0.0, "continuing R(A)")
    euclid = reconstruct(ps, model)
    if progress is not None:
        progress.update(0.3, "applying the similarity")
    image = partial(mapped_image, euclid, sim)
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


def _discrete_similarity_3d(
    vs: VoxelSet, sim: Similarity3, model: Model | str, *, limit: int | None, progress: ProgressLike | None
) -> StepOutcome:
    """``D(T(R(A)))`` for a voxel set A: R(A) a polyhedron, T(R(A)) its exact image (docs/design.md §11)."""
    m = sim.linear
    alpha = m[0][0]
    if all(m[i][j] == (alpha if i == j else 0) for i in range(3) for j in range(3)):
        pooled = scaling_by_pixels(vs, (alpha, sim.offset), str(model))
        if pooled is not None:  # DSS_1/k on an aligned grid: A's voxels decide (scaling_by_pixels)
            if progress is not None:
                progress.update(1.0, "done")
            return StepOutcome(pooled, sim, partial(solid_image, vs, sim, model), pooled)
    if progress is not None:
        progress.update(0.0, "continuing R(A)")
    image = solid_image(vs, sim, model)
    if progress is not None:
        progress.update(0.3, "discretizing the exact image")
    result = image.discretize(str(model), limit=limit, progress=sub_progress(progress, 0.3, 1.0))
    return StepOutcome(result, sim, image, result)


def solid_image(vs: VoxelSet, sim: Similarity3, model: Any) -> ExactSolid:
    """T(R(A)) of a voxel set A, exact: the Euclidean object of a 3D step (made on first use when pooled)."""
    return ExactSolid(reconstruct(vs, model)).map(sim)


def mapped_image(geom: Any, sim: Similarity) -> ExactShape:
    """T(E), exact, for a float64 polygon E: a step's Euclidean object, made when the account asks for it."""
    return ExactShape.from_geometry(geom).map(sim)


def continued_image(ps: PixelSet, sim: Similarity, model: Any) -> ExactShape:
    """T(R(A)), exact: the Euclidean object of a step that never needed R(A) to make its result."""
    return mapped_image(reconstruct(ps, model), sim)


def scaling_by_pixels(gs: _G, sim: Similarity | tuple[Fraction, Sequence[Fraction]], model: str) -> _G | None:
    """DSS_1/k(A) = D(Sc_1/k(R(A))) from A's cells (pixels, voxels) alone, when the grids are aligned.

    ``gs`` is A, a :class:`~mrm.core.grids.PixelSet` or a :class:`~mrm.core.grids.VoxelSet` (any dimension
    n); ``sim`` is the similarity T, a 2D :class:`Similarity` or, in any dimension, a pair ``(α, t)`` for
    T(v) = α·v + t (Sc_α about C has t = (1 − α)·C).

    Applies when T is ``Sc_α`` with α = 1/k (k a positive integer), and ``T⁻¹ = v ↦ k·v + c`` (c = −k·t)
    maps cell centres to cell centres (gauss: c ∈ Zⁿ) or the kernel of every result cell onto a k^n block of
    A's cells (covers: c − (k − 1)/2 ∈ Zⁿ); otherwise returns None. Proof, from R's contract (docs/design.md
    §3, and §11 for n = 3, items 1–3; :mod:`mrm.geometry.reconstruct`):

    * ``gauss``: q ∈ D(Sc_α(R(A))) ⟺ z + kτ ∈ R(A) with z = k·q + c, a cell centre. No centre lies on
      ∂R(A), so that is z ∈ R(A), and since D(R(A)) = A it is z ∈ A: the result is A sampled every k
      cells, ``{q : k·q + c ∈ A}``.
    * ``standard`` / ``supercover``: the kernel of q maps to the open block B(q) + kτ (standard) or the
      closed block B̄(q) (supercover) made of the closed cells (pixels, voxels) of the k^n cells b with
      b − (k·q + s) ∈ [0, k − 1]ⁿ, s = c − (k − 1)/2. If one of them is in A, R(A) meets int V(b)
      (condition C2: its centre is in R(A) or ∂R(A) crosses its open cell), an open subset of B(q), so
      both kernels meet R(A). If none is, R(A) misses every V(b) (the same R(A) has D_supercover = A, so it
      misses the closed cell of every point outside A), so it misses the compact B̄(q) at a positive
      distance and both kernels. The result is ``{q : A meets the block of q}``, a k^n OR-pooling.

    (k = 1 gives DSS_1(A) = A.) tests/model/test_ops_scaling.py (2D) and tests/model/test_voxel_images.py
    (3D) compare it with D(Sc_α(R(A))) computed.
    """
    t: tuple[Fraction, ...]
    if isinstance(sim, Similarity):
        if sim.b != 0:
            return None
        alpha, t = sim.a, (sim.tx, sim.ty)
    else:
        alpha, t = Fraction(sim[0]), tuple(Fraction(v) for v in sim[1])
    if alpha <= 0 or alpha.numerator != 1 or gs.is_empty() or len(t) != len(gs.origin):
        return None
    k = alpha.denominator
    c = [-k * v for v in t]
    if model == "gauss":
        if any(v.denominator != 1 for v in c):
            return None
        # q holds the one cell b = k·q + c: the cells of A congruent to c modulo k.
        return sample(gs, k, [int(v) for v in c])
    half = Fraction(k - 1, 2)
    if any((v - half).denominator != 1 for v in c):
        return None
    # q holds the cells b with k·q + s ≤ b ≤ k·q + s + k − 1.
    return or_pool(gs, k, [int(v - half) for v in c])


def register_discrete_similarity(
    *,
    name: str,
    title: str,
    params: type,
    similarity: Callable[..., Any],
    symbol: str,
    result_name: Callable[[Any], str],
    what: Callable[[Any], str],
    help: str,
    aliases: tuple[str, ...],
    grid: Any,
    command: str,
) -> OperationSpec:
    """Register a ``D∘T∘R`` operation (DSS_α, dR_θ,C) from its declarations alone.

    ``params`` is its parameters dataclass (with ``center`` and ``model``), ``similarity(params)`` its exact
    T. ``result_name(params)`` names the result (``DSS 0.2``) and ``what(params)`` the operation in a refusal.
    The size estimate, the step, the run and the bound are the same for every such operation, so they are
    written here once; the module's public function is the step.
    """

    def estimate(inputs: Any, p: Any) -> int:
        n = input_dimension(inputs[:1])
        return estimated_pixels(inputs[:1], similarity(p, n), p.model, reads="discrete")

    def step(
        source: Any,
        p: Any,
        *,
        limit: int | None = DEFAULT_PIXEL_LIMIT,
        progress: ProgressLike | None = None,
        estimated: bool = False,
    ) -> StepOutcome:
        ps = discrete_of(source, p.model, limit=limit)
        sim = similarity(p, input_dimension([ps]))
        return discrete_similarity(
            ps, sim, p.model, limit=limit, progress=progress, what=what(p), estimated=estimated
        )

    def run(inputs: Any, p: Any, progress: ProgressLike | None = None) -> OperationResult:
        # run_operation read the parameters, checked the size (estimate above) and stamps provenance
        # and bound: the estimate is not made a second time.
        out = step(inputs[0], p, progress=progress, estimated=True)
        return OperationResult(outputs=[(result_name(p), out.result)])

    def bound(p: Any, part: str, n: int = 2) -> BoundStep:
        return discrete_similarity_step(spec.label(p), similarity(p, n))

    spec = OperationSpec(
        name=name,
        title=title,
        arity=1,
        params=params,
        run=run,
        reads="any",
        produces="discrete",
        help=help,
        estimate=estimate,
        bound=bound,
        similarity=similarity,
        step=step,
        symbol=symbol,
        aliases=aliases,
        grid=grid,
        command=command,
    )
    return register(spec)
