"""What an operation hands back besides its result, the guards every one runs first, and the D∘T∘R core.

Each operation is ``D∘T∘R`` (discrete → discrete), ``T⁻¹∘R∘D∘T`` (Euclidean → Euclidean) or a Boolean
combination of discretizations. To replay a chain and measure its error (docs/design.md §8) the chain runner
needs, for every step, the Euclidean similarity ``T`` it applies and the Euclidean object just before its
final discretization (or its exact Euclidean result): :class:`StepOutcome` carries them, exactly.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from fractions import Fraction
from functools import partial
from typing import Any

import numpy as np
import numpy.typing as npt

from mrm.core.grids import PixelSet, VoxelSet
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
    discrete: PixelSet
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
    if progress is not None:
        progress.update(0.0, "continuing R(A)")
    image = ExactSolid(reconstruct(vs, model), Similarity3.identity()).map(sim)
    if progress is not None:
        progress.update(0.3, "discretizing the exact image")
    result = image.discretize(str(model), limit=limit, progress=sub_progress(progress, 0.3, 1.0))
    return StepOutcome(result, sim, image, result)


def mapped_image(geom: Any, sim: Similarity) -> ExactShape:
    """T(E), exact, for a float64 polygon E: a step's Euclidean object, made when the account asks for it."""
    return ExactShape.from_geometry(geom).map(sim)


def continued_image(ps: PixelSet, sim: Similarity, model: Any) -> ExactShape:
    """T(R(A)), exact: the Euclidean object of a step that never needed R(A) to make its result."""
    return mapped_image(reconstruct(ps, model), sim)


#: Largest block side k pooled by k slice ORs on A padded to whole blocks; beyond it, ufunc.reduceat on A.
_POOL_SLICES_MAX_K = 32


def scaling_by_pixels(ps: PixelSet, sim: Similarity, model: str) -> PixelSet | None:
    """DSS_1/k(A) = D(Sc_1/k(R(A))) from A's pixels alone, when the grid of the result is aligned to A's.

    Applies when ``sim`` is ``Sc_α`` with α = 1/k (k a positive integer) about a centre C, and
    ``Sc_1/α = v ↦ k·v + c`` (c = (1 − k)·C) maps pixel centres to pixel centres (gauss: c ∈ Z²) or the
    kernel of every result pixel onto a k × k block of A's voxels (covers: c − (k − 1)/2 ∈ Z²); otherwise
    returns None. Proof, from R's contract (docs/design.md §3; :mod:`mrm.geometry.reconstruct`, items 1–3):

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
    # q holds the pixels b with k·q + s ≤ b ≤ k·q + s + k − 1: OR the rows, then the columns, of each block.
    qx0, qy0 = (x0 - sx) // k, (y0 - sy) // k
    left, bottom = (x0 - sx) - k * qx0, (y0 - sy) - k * qy0
    h, w = mask.shape
    if k > _POOL_SLICES_MAX_K:
        # Cut the blocks where they start in A: padding A to whole k × k blocks would take up to k² times the
        # result's size (α = 10⁻⁶ on one pixel: a 10⁶ × 10⁶ array), and k slice ORs k Python steps.
        rows_or = np.logical_or.reduceat(mask, _block_starts(h, bottom, k), axis=0)
        pooled = np.logical_or.reduceat(rows_or, _block_starts(w, left, k), axis=1)
        return PixelSet(pooled, (qx0, qy0))
    rows = -(-(h + bottom) // k)
    cols = -(-(w + left) // k)
    if (bottom, left, h, w) == (0, 0, rows * k, cols * k):
        padded = mask
    else:  # at most k − 1 more rows and columns
        padded = np.zeros((rows * k, cols * k), dtype=bool)
        padded[bottom : bottom + h, left : left + w] = mask
    # OR of the k rows, then of the k columns of each block (k slice ORs: ten times faster than .any(axis),
    # and than ufunc.reduceat for small k).
    strips = padded.reshape(rows, k, cols * k)
    rows_or = strips[:, 0].copy()
    for i in range(1, k):
        rows_or |= strips[:, i]
    blocks = rows_or.reshape(rows, cols, k)
    pooled = blocks[..., 0].copy()
    for i in range(1, k):
        pooled |= blocks[..., i]
    return PixelSet(pooled, (qx0, qy0))


def _block_starts(n: int, offset: int, k: int) -> npt.NDArray[np.intp]:
    """Where the blocks of ``k`` cells start in ``range(n)`` when the first has ``offset`` cells before 0.

    0, then k − offset, 2k − offset, … below n (0 ≤ offset < k): ⌈(n + offset)/k⌉ blocks.
    """
    return np.concatenate(([0], np.arange(k - offset, n, k))).astype(np.intp)


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
