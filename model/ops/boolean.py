"""Euclidean-discrete union and co-refinement (the paper's Definitions 17–19, DESIGN §8).

* ``EDu(E, E′) = R(D(E) ∪ D(E′))``;
* ``EDco(E, E′) = { R(D(E) ∖ D(E′)), R(D(E) ∩ D(E′)), R(D(E′) ∖ D(E)) }``, given as three polygons and as
  one label map of the three discrete parts (1 = E ∖ E′, 2 = E ∩ E′, 3 = E′ ∖ E; 0 = neither);
* ``EDco_α``: the same on ``Sc_α(E)`` and ``Sc_α(E′)`` (exact rationals, discretized exactly), each part
  mapped back by ``Sc_1/α`` exactly and rounded once to float64. Its label map lives on the scaled grid.

An input may be a polygon E or a pixel set A; for a pixel set, D(E) is A itself (an object's discrete
representation is always D of its Euclidean one) and, for EDco_α, E is R(A).

The discrete parts partition D(E) ∪ D(E′). Under the cover models each R(part) lies in V(part), so the three
polygons have disjoint interiors. Under ``gauss`` the joint reconstruction of the label map
(``mrm.geometry.reconstruct.subdivision.reconstruct_label_map``), when it is available, makes them a
watertight
subdivision: neighbouring parts share their boundaries exactly.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import partial
from typing import Any

import numpy as np

from mrm.errors import DEFAULT_PIXEL_LIMIT
from mrm.geometry.discretize.exact_shape import (
    ExactShape,
    Similarity,
    box_area,
    number_to_json,
    positive_number,
)
from mrm.geometry.discretize.rational import discretize_exact, discretize_image
from mrm.geometry.hausdorff import bounds
from mrm.geometry.hausdorff.bounds import ChainStep, CorefinePart
from mrm.ops.base import OperationResult, OperationSpec, register
from mrm.ops.outcome import (
    StepOutcome,
    alpha_param,
    check_limit,
    check_model,
    check_size,
    joint_box,
    model_param,
    source_box,
)
from mrm.ops.simplify import euclidean_input
from mrm.progress import ProgressLike, sub_progress
from mrm.reps.pixels import LabelMap, PixelSet
from mrm.summary import optional_function

#: The parts of a co-refinement, in label order (label = index + 1), as files and properties name them.
PARTS = ("a_minus_b", "a_and_b", "b_minus_a")
#: The part of each in :mod:`mrm.geometry.hausdorff.bounds` terms.
BOUND_PART: dict[str, CorefinePart] = {"a_minus_b": "first", "a_and_b": "common", "b_minus_a": "second"}
#: What each part is.
PART_TITLES = {"a_minus_b": "A ∖ B", "a_and_b": "A ∩ B", "b_minus_a": "B ∖ A"}


def discrete_input(
    source: Any, model: str, sim: Similarity | None, limit: int | None, progress: ProgressLike | None
) -> PixelSet:
    """D(T(E)) for a polygon E, or A itself for a pixel set A when T is the identity (None)."""
    if isinstance(source, PixelSet) and sim is None:
        return source
    geom = euclidean_input(source, model)
    if sim is None and not isinstance(geom, ExactShape):
        from mrm.geometry.discretize import discretize

        return discretize(geom, model, limit=limit)  # float64 input: the compiled exact discretization
    if sim is not None and not isinstance(geom, ExactShape):
        fast = discretize_image(geom, sim, model, limit=limit, what="the discretization of an input")
        if fast is not None:  # int64 kernels, no Fraction (the same pixels)
            return fast
    shape = ExactShape.from_geometry(geom)
    if sim is not None:
        shape = shape.map(sim)
    return discretize_exact(
        shape, model, limit=limit, progress=progress, what="the discretization of an input"
    )


def parts_label_map(a: PixelSet, b: PixelSet) -> LabelMap:
    """The label map of the three parts of D(E) and D(E′): 1 = a ∖ b, 2 = a ∩ b, 3 = b ∖ a.

    The same labels as ``LabelMap.from_pixel_sets([a - b, a & b, b - a])``, read from one table lookup of
    ``a + 2·b`` over the joint box (a sixth of the time on a 800² co-refinement).
    """
    box = joint_box([a.bbox, b.bbox])
    if box is None:
        return LabelMap(np.zeros((0, 0), dtype=np.int32))
    ua, ub = a.to_array(box).view(np.uint8), b.to_array(box).view(np.uint8)  # bools are bytes 0/1
    # the Gray code of a + 2·b: 0 neither, 1 only a, 2 both, 3 only b
    labels = ((ua ^ ub) | (ub << 1)).astype(np.int32)
    # a and b are cropped and the box is their joint box: the support touches its four sides
    return LabelMap._canonical(labels, (box[0], box[1]))


def euclidean_discrete_union(
    first: Any,
    second: Any,
    model: str = "standard",
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
) -> StepOutcome:
    """Return EDu(E, E′) = R(D(E) ∪ D(E′)).

    Parameters
    ----------
    first, second : shapely Polygon / MultiPolygon, or PixelSet
        E and E′ (a pixel set stands for itself as D(E)).
    model : {"standard", "supercover", "gauss"}
    limit : int or None
        Largest discretization of an input and largest union (pixels of their bounding boxes).
    progress : object with ``update(fraction, message)``, optional

    Returns
    -------
    StepOutcome
        ``result`` (the polygon), ``discrete`` (D(E) ∪ D(E′)), ``euclidean`` (the result, exact).
    """
    check_model(model)
    check_limit(limit)
    a = discrete_input(first, model, None, limit, sub_progress(progress, 0.0, 0.2))
    b = discrete_input(second, model, None, limit, sub_progress(progress, 0.2, 0.4))
    check_size(box_area(joint_box([a.bbox, b.bbox])), limit, "the union")
    union = a | b
    if progress is not None:
        progress.update(0.5, "continuing the union")
    from mrm.geometry.reconstruct import reconstruct

    geom = reconstruct(union, model)
    if progress is not None:
        progress.update(1.0, "done")
    return StepOutcome(geom, Similarity.identity(), partial(ExactShape.from_geometry, geom), union)


def euclidean_discrete_corefinement(
    first: Any,
    second: Any,
    model: str = "standard",
    alpha: object = None,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
    estimated: bool = False,
) -> StepOutcome:
    """Return EDco(E, E′), or EDco_α(E, E′) when ``alpha`` is given.

    Parameters
    ----------
    first, second : shapely Polygon / MultiPolygon, or PixelSet
        E and E′.
    model : {"standard", "supercover", "gauss"}
    alpha : number, optional
        The precision factor α > 0 of the precise co-refinement (None: plain EDco, α = 1).
    limit : int or None
        Largest discretization (pixels of its bounding box), at scale α; checked before it is computed.
    progress : object with ``update(fraction, message)``, optional
    estimated : bool
        The caller checked the size estimate (:func:`estimate_corefine`) against ``limit`` already
        (run_operation's guard): it is not made twice.

    Returns
    -------
    StepOutcome
        ``result``: a dict part name → polygon (float64), in :data:`PARTS` order; ``discrete``: the support
        D(E) ∪ D(E′) (at scale α); ``extra``: ``label_map`` (LabelMap, label i+1 = ``PARTS[i]``),
        ``pixels`` (part → PixelSet), ``exact`` (part → ExactShape before rounding), ``alpha`` and
        ``watertight`` (whether the joint gauss reconstruction was used).
    """
    check_model(model)
    check_limit(limit)
    sim = None
    if alpha is not None:
        a_q = positive_number(alpha, "alpha")
        sim = Similarity.scaling(a_q)
        what = f"the discretization at scale α = {number_to_json(a_q)}"
        if not estimated:  # from the bounding boxes, before anything is discretized or continued
            check_size(_estimate_pair([first, second], sim, model), limit, what)
    a = discrete_input(first, model, sim, limit, sub_progress(progress, 0.0, 0.2))
    b = discrete_input(second, model, sim, limit, sub_progress(progress, 0.2, 0.4))
    check_size(box_area(joint_box([a.bbox, b.bbox])), limit, "the co-refinement")
    pixels = {"a_minus_b": a - b, "a_and_b": a & b, "b_minus_a": b - a}
    label_map = parts_label_map(a, b)
    if progress is not None:
        progress.update(0.45, "continuing the parts")
    geoms, watertight = _reconstruct_parts(pixels, label_map, model, progress)
    back = sim.inverse() if sim is not None else Similarity.identity()
    exact: Mapping[str, ExactShape]
    if _is_dyadic_scaling(back):
        # Scaling back by a power of two is exact in float64: the parts need no Fraction; their exact form
        # is made only when asked for (the account measures it).
        from shapely import affinity

        r = float(back.ratio)
        result = {p: geoms[p] if r == 1 else affinity.scale(geoms[p], r, r, origin=(0, 0)) for p in PARTS}
        exact = _LazyExact(result)
    else:
        exact = {p: ExactShape.from_geometry(g).map(back) for p, g in geoms.items()}
        result = {p: exact[p].to_geometry() for p in PARTS}
    if progress is not None:
        progress.update(1.0, "done")
    extra = {
        "label_map": label_map,
        "pixels": pixels,
        "exact": exact,
        "alpha": None if sim is None else sim.ratio,
        "watertight": watertight,
    }
    return StepOutcome(result, Similarity.identity(), partial(_joined_parts, exact), a | b, extra)


def _joined_parts(exact: Mapping[str, ExactShape]) -> ExactShape:
    """The parts of a co-refinement as one exact shape (EDco's Euclidean object, made on first use).

    Module-level, not a closure: the outcome is pickled to and from the window's worker processes.
    """
    return ExactShape(tuple(poly for p in PARTS for poly in exact[p].polygons))


def _is_dyadic_scaling(sim: Similarity) -> bool:
    """A scaling about the origin by a power of two (exact on float64 coordinates, barring underflow)."""
    q = sim.ratio
    power_of_two = q.numerator & (q.numerator - 1) == 0 and q.denominator & (q.denominator - 1) == 0
    return sim.b == 0 and sim.tx == 0 and sim.ty == 0 and power_of_two and Fraction(2) ** -60 < q < 2**60


class _LazyExact(Mapping[str, ExactShape]):
    """Part name → its exact shape, read from the (exact) float64 part on first use."""

    def __init__(self, parts: dict[str, Any]) -> None:
        self._parts = parts
        self._done: dict[str, ExactShape] = {}

    def __getitem__(self, key: str) -> ExactShape:
        if key not in self._done:
            self._done[key] = ExactShape.from_geometry(self._parts[key])
        return self._done[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._parts)

    def __len__(self) -> int:
        return len(self._parts)


def _reconstruct_parts(
    pixels: dict[str, PixelSet], label_map: LabelMap, model: str, progress: ProgressLike | None
) -> tuple[dict[str, Any], bool]:
    """R of each part; under gauss the joint (watertight) reconstruction of the label map when available."""
    if model == "gauss":
        joint = optional_function("mrm.geometry.reconstruct.subdivision", "reconstruct_label_map")
        if joint is not None:
            by_label = joint(label_map, model)
            from shapely.geometry import Polygon

            return {p: by_label.get(i + 1, Polygon()) for i, p in enumerate(PARTS)}, True
    from mrm.geometry.reconstruct import reconstruct

    out = {}
    for i, p in enumerate(PARTS):
        out[p] = reconstruct(pixels[p], model)
        if progress is not None:
            progress.update(0.45 + 0.45 * (i + 1) / len(PARTS), f"continued {PART_TITLES[p]}")
    return out, False


# ---------------------------------------------------------------------------------------------- the specs
@dataclass(frozen=True)
class UnionParams:
    """Parameters of EDu."""

    model: str = model_param()


@dataclass(frozen=True)
class CorefineParams:
    """Parameters of EDco and EDco_α."""

    alpha: float | None = alpha_param(
        None,
        "Precision factor α of the precise co-refinement (error ≤ √2/α); empty: plain EDco.",
        optional=True,
    )
    model: str = model_param()


@dataclass(frozen=True)
class CorefineResult(OperationResult):
    """The three parts of a co-refinement, plus the label map of their pixels and each part's bound.

    Attributes
    ----------
    label_map : LabelMap or None
        The discrete parts (label i + 1 = ``PARTS[i]``; on the grid scaled by α for EDco_α).
    part_bounds : dict
        Part name → :class:`mrm.geometry.hausdorff.bounds.BoundResult` (one-sided: see that module).
    watertight : bool
        Whether the parts come from the joint gauss reconstruction (shared boundaries).
    """

    label_map: LabelMap | None = None
    part_bounds: dict[str, Any] = field(default_factory=dict)
    watertight: bool = False


def _estimate_pair(inputs: Sequence[Any], sim: Similarity | None, model: str) -> int:
    """The size of the joint box of the (scaled) discretizations, from bounding boxes alone."""
    return box_area(joint_box([source_box(src, sim or Similarity.identity(), model) for src in inputs]))


def estimate_union(inputs: Sequence[Any], params: UnionParams) -> int:
    """An upper bound of the pixels of D(E) ∪ D(E′)."""
    return _estimate_pair(inputs, None, params.model)


def estimate_corefine(inputs: Sequence[Any], params: CorefineParams) -> int:
    """An upper bound of the pixels of the (scaled) discretizations."""
    sim = None if params.alpha is None else Similarity.scaling(positive_number(params.alpha, "alpha"))
    return _estimate_pair(inputs, sim, params.model)


def union_chain_step(params: UnionParams) -> ChainStep:
    """EDu in the bound model of DESIGN §8."""
    return bounds.union()


def corefine_chain_step(params: CorefineParams, part: str = "a_minus_b") -> ChainStep:
    """EDco(_α) in the bound model; a chain continues with the first output, A ∖ B."""
    alpha = None if params.alpha is None else positive_number(params.alpha, "alpha")
    return bounds.corefine(alpha, BOUND_PART[part])


def run_union(
    inputs: Sequence[Any], params: UnionParams, progress: ProgressLike | None = None
) -> OperationResult:
    """Run EDu on two objects."""
    out = euclidean_discrete_union(inputs[0], inputs[1], params.model, progress=progress)
    return OperationResult(outputs=[("EDu", out.result)])


def run_corefine(
    inputs: Sequence[Any], params: CorefineParams, progress: ProgressLike | None = None
) -> CorefineResult:
    """Run EDco (or EDco_α) on two objects: three outputs, one per part (empty parts included)."""
    out = euclidean_discrete_corefinement(
        inputs[0], inputs[1], params.model, params.alpha, progress=progress, estimated=True
    )
    part_bounds = {p: bounds.bound_of_chain([corefine_chain_step(params, p)], params.model) for p in PARTS}
    return CorefineResult(
        outputs=[(p, out.result[p]) for p in PARTS],
        bound=part_bounds[PARTS[0]],
        label_map=out.extra["label_map"],
        part_bounds=part_bounds,
        watertight=bool(out.extra["watertight"]),
    )


def _register_pair(
    name: str, title: str, params: type, run: Any, estimate: Any, chain_step: Any, **declared: Any
) -> OperationSpec:
    """Register a two-object operation: it reads either representation and makes Euclidean parts."""
    return register(
        OperationSpec(
            name,
            title,
            2,
            params,
            run,
            "any",
            "euclidean",
            estimate=estimate,
            chain_step=chain_step,
            **declared,
        )
    )


UNION = "union"
COREFINE = "corefine"
UNION_SPEC = _register_pair(
    UNION,
    "Euclidean-discrete union EDu",
    UnionParams,
    run_union,
    estimate_union,
    union_chain_step,
    help="EDu(E, E′) = R(D(E) ∪ D(E′)): a robust union made in the discrete space (paper, Def. 17).",
    aliases=("EDu",),
)
COREFINE_SPEC = _register_pair(
    COREFINE,
    "Euclidean-discrete co-refinement EDco",
    CorefineParams,
    run_corefine,
    estimate_corefine,
    corefine_chain_step,
    help="EDco(E, E′): the parts A ∖ B, A ∩ B, B ∖ A made in the discrete space (paper, Defs. 18–19).",
    aliases=("EDco", "corefinement", "co_refinement"),
)


# ---------------------------------------------------------------------------------------------- measuring
def _polygonal(geom: Any) -> Any:
    """The polygonal part of an overlay result, as a valid Polygon / MultiPolygon."""
    import shapely
    from shapely.geometry import MultiPolygon, Polygon

    if not geom.is_valid:
        geom = shapely.make_valid(geom)
    polys = [g for g in shapely.get_parts(geom) if isinstance(g, Polygon) and not g.is_empty]
    for g in list(shapely.get_parts(geom)):
        if isinstance(g, MultiPolygon):
            polys.extend(g.geoms)
    if not polys:
        return Polygon()
    return polys[0] if len(polys) == 1 else MultiPolygon(polys)


def reference_parts(first: Any, second: Any, model: str) -> tuple[dict[str, Any], bool]:
    """The Euclidean parts E ∖ E′, E ∩ E′, E′ ∖ E and E ∪ E′ (keys of :data:`PARTS` and ``union``).

    A pixel set A stands for R(A). The overlays are GEOS's, which round the new vertices where boundaries
    cross; the flag says whether the reference is exact (the inputs' interiors and boundaries are disjoint:
    then no new vertex is made).
    """
    import shapely
    from shapely.geometry import MultiPolygon, Polygon

    e1, e2 = euclidean_input(first, model), euclidean_input(second, model)
    if shapely.disjoint(e1, e2):
        parts1 = list(e1.geoms) if isinstance(e1, MultiPolygon) else [e1] if not e1.is_empty else []
        parts2 = list(e2.geoms) if isinstance(e2, MultiPolygon) else [e2] if not e2.is_empty else []
        both = parts1 + parts2
        union = Polygon() if not both else both[0] if len(both) == 1 else MultiPolygon(both)
        return {"a_minus_b": e1, "a_and_b": Polygon(), "b_minus_a": e2, "union": union}, True
    return {
        "a_minus_b": _polygonal(shapely.difference(e1, e2)),
        "a_and_b": _polygonal(shapely.intersection(e1, e2)),
        "b_minus_a": _polygonal(shapely.difference(e2, e1)),
        "union": _polygonal(shapely.union(e1, e2)),
    }, False
