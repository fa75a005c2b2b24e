"""Euclidean-discrete union and co-refinement (the paper's Definitions 17–19, docs/design.md §8).

* ``EDu(E, E′) = R(D(E) ∪ D(E′))``;
* ``EDco(E, E′) = { R(D(E) ∖ D(E′)), R(D(E) ∩ D(E′)), R(D(E′) ∖ D(E)) }``, given as three polygons and as
  one label map of the three discrete parts (1 = E ∖ E′, 2 = E ∩ E′, 3 = E′ ∖ E; 0 = neither);
* ``EDco_α``: the same on ``Sc_α(E)`` and ``Sc_α(E′)`` (exact rationals, discretized exactly), each part
  mapped back by ``Sc_1/α`` exactly and rounded once to float64. Its label map lives on the scaled grid.

An input may be a polygon E or a pixel set A; for a pixel set, D(E) is A itself (an object's discrete
representation is always D of its Euclidean one) and, for EDco_α, E is R(A).

The same definitions run in space (docs/design.md §11): on two polyhedra or voxel sets the discrete parts are
voxel sets, the label map a :class:`~mrm.core.grids.LabelVolume`, each part a polyhedron (R in 3D), and
EDco_α maps each part back by Sc_1/α exactly (an :class:`ExactSolid`) and rounds it once to float64, as Sp_α
does in space. No joint watertight reconstruction of a label volume exists yet: in 3D each part is
continued on its own under every model (``watertight`` False).

The discrete parts partition D(E) ∪ D(E′). Under the cover models each R(part) lies in V(part), so the three
polygons have disjoint interiors. Under ``gauss`` the joint reconstruction of the label map
(``mrm.geometry.reconstruct.subdivision.reconstruct_label_map``), when it is available, makes them a
watertight
subdivision: neighbouring parts share their boundaries exactly.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import partial
from typing import Any

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.grids import LabelMap, LabelVolume, PixelSet, VoxelSet, box_area, joint_box
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, MAX_LABEL_VOXELS, check_pixels
from mrm.core.models import Model
from mrm.core.numbers import spell
from mrm.core.params import Parameters
from mrm.core.progress import ProgressLike, sub_progress
from mrm.geometry.discretize.exact_shape import ExactShape, Similarity
from mrm.geometry.discretize.exact_solid import ExactSolid, identity_map, scaling_map
from mrm.geometry.hausdorff.bounds import (
    BoundResult,
    BoundStep,
    CorefinePart,
    bound_of_chain,
    corefine_step,
    union_step,
)
from mrm.geometry.reconstruct import reconstruct
from mrm.geometry.reconstruct.subdivision import reconstruct_label_map
from mrm.ops.declare import alpha_param, model_param
from mrm.ops.estimate import estimated_pixels
from mrm.ops.outcome import StepOutcome
from mrm.ops.registry import OperationResult, OperationSpec, input_dimension, register
from mrm.ops.representations import discrete_of, euclidean_of

log = logging.getLogger(__name__)

#: The parts of a co-refinement, in label order (label = index + 1), as files and properties name them.
PARTS = ("a_minus_b", "a_and_b", "b_minus_a")
#: The part of each in :mod:`mrm.geometry.hausdorff.bounds` terms, and how a chain's text writes it.
BOUND_PART: dict[str, CorefinePart] = {"a_minus_b": "first", "a_and_b": "common", "b_minus_a": "second"}
#: What each part is.
PART_TITLES = {"a_minus_b": "A ∖ B", "a_and_b": "A ∩ B", "b_minus_a": "B ∖ A"}


def parts_label_map(a: PixelSet | VoxelSet, b: PixelSet | VoxelSet) -> LabelMap | LabelVolume:
    """The label map of the three parts of D(E) and D(E′): 1 = a ∖ b, 2 = a ∩ b, 3 = b ∖ a.

    The same labels as ``LabelMap.from_sets([a - b, a & b, b - a])``, read from one table lookup of
    ``a + 2·b`` over the joint box (a sixth of the time on a 800² co-refinement). Two voxel sets give a
    :class:`~mrm.core.grids.LabelVolume`.
    """
    n = a.ndim
    grid: type[LabelMap] | type[LabelVolume] = LabelVolume if n == 3 else LabelMap
    box = joint_box([a.bbox, b.bbox])
    if box is None:
        return grid(np.zeros((0,) * n, dtype=np.int32))
    # one box for both (same dimension): the type checker cannot tie a's box type to b's
    ua, ub = a.to_array(box).view(np.uint8), b.to_array(box).view(np.uint8)  # type: ignore[arg-type]
    # the Gray code of a + 2·b: 0 neither, 1 only a, 2 both, 3 only b
    labels = ((ua ^ ub) | (ub << 1)).astype(np.int32)
    # a and b are cropped and the box is their joint box: the support touches every side
    return grid._canonical(labels, box[:n])


def euclidean_discrete_union(
    first: Any,
    second: Any,
    model: Model | str = Model.STANDARD,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
) -> StepOutcome:
    """Return EDu(E, E′) = R(D(E) ∪ D(E′)).

    Parameters
    ----------
    first, second : shapely Polygon / MultiPolygon, or PixelSet; or Polyhedron, or VoxelSet
        E and E′ (a pixel or voxel set stands for itself as D(E)); both of one dimension.
    model : Model or str
    limit : int or None
        Largest discretization of an input and largest union (pixels, or voxels, of their bounding boxes).
    progress : object with ``update(fraction, message)``, optional

    Returns
    -------
    StepOutcome
        ``result`` (the polygon, or the polyhedron), ``discrete`` (D(E) ∪ D(E′)), ``euclidean`` (the
        result, exact).
    """
    model = Model.parse(model)
    n = input_dimension([first, second])
    if n == 3:  # from the bounding boxes, before anything is voxelized (in the plane each D checks its own)
        check_pixels(estimated_pixels([first, second], None, model), limit, "the union", unit="voxels")
    a = discrete_of(first, model, limit=limit, progress=sub_progress(progress, 0.0, 0.2))
    b = discrete_of(second, model, limit=limit, progress=sub_progress(progress, 0.2, 0.4))
    check_pixels(box_area(joint_box([a.bbox, b.bbox])), limit, "the union", unit=_UNIT[n])
    union = a | b
    if progress is not None:
        progress.update(0.5, "continuing the union")
    geom = reconstruct(union, model)
    if progress is not None:
        progress.update(1.0, "done")
    exact_image = ExactSolid(geom) if n == 3 else partial(ExactShape.from_geometry, geom)
    return StepOutcome(geom, identity_map(n), exact_image, union)


def euclidean_discrete_corefinement(
    first: Any,
    second: Any,
    model: Model | str = Model.STANDARD,
    alpha: object = None,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
    estimated: bool = False,
) -> StepOutcome:
    """Return EDco(E, E′), or EDco_α(E, E′) when ``alpha`` is given.

    Parameters
    ----------
    first, second : shapely Polygon / MultiPolygon, or PixelSet; or Polyhedron, or VoxelSet
        E and E′, both of one dimension.
    model : Model or str
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
        ``result``: a dict part name → polygon (float64; a polyhedron in 3D), in :data:`PARTS` order;
        ``discrete``: the support D(E) ∪ D(E′) (at scale α); ``extra``: ``label_map`` (LabelMap, or
        LabelVolume in 3D; label i+1 = ``PARTS[i]``), ``pixels`` (part → PixelSet or VoxelSet), ``exact``
        (part → ExactShape or ExactSolid, before rounding), ``alpha`` and ``watertight`` (whether the joint
        gauss reconstruction was used).
    """
    params = CorefineParams.read(alpha=alpha, model=model)
    model = params.model
    n = input_dimension([first, second])
    sim = None if params.alpha is None else scaling_map(params.alpha, None, n)
    what = "the co-refinement"
    if params.alpha is not None:
        what = f"the discretization at scale α = {spell(params.alpha)}"
    if sim is not None or n == 3:  # from the bounding boxes, before anything is discretized or continued
        size = estimated_pixels([first, second], sim, model)
        if not estimated:
            check_pixels(size, limit, what, unit=_UNIT[n])
        if n == 3:  # the label volume holds four bytes a voxel
            check_pixels(size, MAX_LABEL_VOXELS, f"{what}'s label volume", unit="voxels")
    a = discrete_of(first, model, limit=limit, sim=sim, progress=sub_progress(progress, 0.0, 0.2))
    b = discrete_of(second, model, limit=limit, sim=sim, progress=sub_progress(progress, 0.2, 0.4))
    check_pixels(box_area(joint_box([a.bbox, b.bbox])), limit, "the co-refinement", unit=_UNIT[n])
    pixels = {"a_minus_b": a - b, "a_and_b": a & b, "b_minus_a": b - a}
    label_map = parts_label_map(a, b)
    if progress is not None:
        progress.update(0.45, "continuing the parts")
    geoms, watertight = _reconstruct_parts(pixels, label_map, model, progress)
    exact: Mapping[str, Any]
    everything: Callable[[], Any]  # the parts together, exact, when the account asks for them
    if n == 3:
        result, exact = _solids_back(geoms, sim, what)
        identity, everything = identity_map(3), partial(_all_solids, exact)
    else:
        back = sim.inverse() if sim is not None else Similarity.identity()
        if _is_dyadic_scaling(back):
            # Scaling back by a power of two is exact in float64: the parts need no Fraction; their exact
            # form is made only when asked for (the account measures it).
            r = float(back.ratio)
            result = {p: geoms[p] if r == 1 else affinity.scale(geoms[p], r, r, origin=(0, 0)) for p in PARTS}
            exact = _LazyExact(result)
        else:
            exact = {p: ExactShape.from_geometry(g).map(back) for p, g in geoms.items()}
            result = {p: exact[p].to_geometry() for p in PARTS}
        identity, everything = Similarity.identity(), partial(_all_parts, exact)
    if progress is not None:
        progress.update(1.0, "done")
    extra = {
        "label_map": label_map,
        "pixels": pixels,
        "exact": exact,
        "alpha": None if sim is None else sim.ratio,
        "watertight": watertight,
    }
    return StepOutcome(result, identity, everything, a | b, extra)


def _all_parts(exact: Mapping[str, ExactShape]) -> ExactShape:
    """The parts together, exact: a co-refinement's Euclidean object (made when the account asks for it)."""
    return ExactShape(tuple(poly for p in PARTS for poly in exact[p].polygons))


#: What a size counts, by dimension (the messages of the size checks).
_UNIT = {2: "pixels", 3: "voxels"}


def _solids_back(
    geoms: Mapping[str, Any], sim: Any, what: str
) -> tuple[dict[str, Any], dict[str, ExactSolid]]:
    """Each part R(·) in space mapped back by Sc_1/α exactly, and rounded once to float64 (as Sp_α in 3D).

    Returns the polyhedra and their exact solids (the account measures these). A part that is no valid
    solid once rounded is refused in one line.
    """
    from mrm.geometry.polyhedra import Polyhedron  # 3D only: the plane work never loads the polyhedra

    back = identity_map(3) if sim is None else sim.inverse()
    exact = {p: ExactSolid(geoms[p]).map(back) for p in PARTS}
    result: dict[str, Any] = {}
    for p, solid in exact.items():
        if solid.transform.is_identity or solid.is_empty():
            result[p] = solid.base
            continue
        vertices, _ = solid.float_vertices()
        try:
            result[p] = Polyhedron(vertices, solid.base.triangles)
        except InvalidGeometryError as e:
            raise ParameterError(
                f"{what}: the part {PART_TITLES[p]} is no valid solid once written in float64 ({e})"
            ) from None
    return result, exact


def _all_solids(exact: Mapping[str, ExactSolid]) -> ExactSolid:
    """The parts together in space, exact: one solid of their shells (they share the map back)."""
    from mrm.geometry.polyhedra import Polyhedron

    bases = [exact[p].base for p in PARTS if not exact[p].is_empty()]
    if not bases:
        return exact[PARTS[0]]
    offsets = np.cumsum([0] + [b.n_vertices for b in bases[:-1]])
    vertices = np.vstack([b.vertices for b in bases])
    triangles = np.vstack([b.triangles + k for b, k in zip(bases, offsets, strict=True)])
    # R of disjoint voxel sets: disjoint solids (the 3D continuation stays inside the parts' own voxels)
    return ExactSolid(Polyhedron(vertices, triangles), exact[PARTS[0]].transform)


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
    pixels: Mapping[str, PixelSet | VoxelSet],
    label_map: LabelMap | LabelVolume,
    model: str,
    progress: ProgressLike | None,
) -> tuple[dict[str, Any], bool]:
    """R of each part; under gauss the joint (watertight) reconstruction of the label map when available."""
    if model == Model.GAUSS and isinstance(label_map, LabelMap):
        # In space no joint watertight reconstruction of a label volume exists yet: each part on its own.
        by_label = reconstruct_label_map(label_map, model, what="the co-refinement's parts together")
        return {p: by_label.get(i + 1, Polygon()) for i, p in enumerate(PARTS)}, True
    out = {}
    for i, p in enumerate(PARTS):
        out[p] = reconstruct(pixels[p], model)
        if progress is not None:
            progress.update(0.45 + 0.45 * (i + 1) / len(PARTS), f"continued {PART_TITLES[p]}")
    return out, False


# ---------------------------------------------------------------------------------------------- the specs
@dataclass(frozen=True)
class UnionParams(Parameters):
    """Parameters of EDu."""

    model: Model = model_param()


@dataclass(frozen=True)
class CorefineParams(Parameters):
    """Parameters of EDco and EDco_α."""

    alpha: Fraction | None = alpha_param(
        None,
        "Precision factor α of the precise co-refinement (error ≤ √2/α); empty: plain EDco.",
        optional=True,
    )
    model: Model = model_param()


@dataclass(frozen=True)
class CorefineResult(OperationResult):
    """The three parts of a co-refinement, plus the label map of their pixels and each part's bound.

    Attributes
    ----------
    label_map : LabelMap, LabelVolume or None
        The discrete parts (label i + 1 = ``PARTS[i]``; on the grid scaled by α for EDco_α).
    part_bounds : dict
        Part name → :class:`mrm.geometry.hausdorff.bounds.BoundResult` (one-sided: see that module).
    watertight : bool
        Whether the parts come from the joint gauss reconstruction (shared boundaries).
    """

    label_map: LabelMap | LabelVolume | None = None
    part_bounds: dict[str, BoundResult] = field(default_factory=dict)
    watertight: bool = False


def _scaling(params: CorefineParams, n: int = 2) -> Any:
    """Sc_α about the origin in dimension ``n`` (None for plain EDco)."""
    return None if params.alpha is None else scaling_map(params.alpha, None, n)


def estimate_union(inputs: Sequence[Any], params: UnionParams) -> int:
    """An upper bound of the pixels (voxels) of D(E) ∪ D(E′)."""
    return estimated_pixels(inputs, None, params.model)


def estimate_corefine(inputs: Sequence[Any], params: CorefineParams) -> int:
    """An upper bound of the pixels (voxels) of the (scaled) discretizations."""
    return estimated_pixels(inputs, _scaling(params, input_dimension(inputs)), params.model)


def union_bound(params: UnionParams, part: str, n: int = 2) -> BoundStep:
    """EDu in the bound rule: one round trip of the union (√n)."""
    return union_step(UNION_SPEC.label(params))


def corefine_bound(params: CorefineParams, part: str, n: int = 2) -> BoundStep:
    """EDco(_α) in the bound rule on inputs of dimension ``n``, following ``part``."""
    return corefine_step(
        COREFINE_SPEC.label(params, part), _scaling(params, n) or identity_map(n), BOUND_PART[part]
    )


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
    n = input_dimension(inputs)
    part_bounds = {p: bound_of_chain([corefine_bound(params, p, n)], params.model, n=n) for p in PARTS}
    return CorefineResult(
        outputs=[(p, out.result[p]) for p in PARTS],
        bound=part_bounds[PARTS[0]],
        label_map=out.extra["label_map"],
        part_bounds=part_bounds,
        watertight=bool(out.extra["watertight"]),
    )


UNION = "union"
COREFINE = "corefine"
UNION_SPEC = register(
    OperationSpec(
        name=UNION,
        title="Euclidean-discrete union EDu",
        arity=2,
        params=UnionParams,
        run=run_union,
        reads="any",
        produces="euclidean",
        help="EDu(E, E′) = R(D(E) ∪ D(E′)): a robust union made in the discrete space (paper, Def. 17).",
        estimate=estimate_union,
        bound=union_bound,
        symbol="EDu",
        aliases=("union",),
        grid="same",
        command="union",
    )
)
COREFINE_SPEC = register(
    OperationSpec(
        name=COREFINE,
        title="Euclidean-discrete co-refinement EDco",
        arity=2,
        params=CorefineParams,
        run=run_corefine,
        reads="any",
        produces="euclidean",
        help="EDco(E, E′): the parts A ∖ B, A ∩ B, B ∖ A made in the discrete space (paper, Defs. 18–19).",
        estimate=estimate_corefine,
        bound=corefine_bound,
        symbol="EDco",
        aliases=("corefine", "co-refine", "corefinement", "co_refinement"),
        parts=PARTS,
        part_words=BOUND_PART,
        default_part="a_and_b",
        grid="same",
        command="corefine",
    )
)


# ---------------------------------------------------------------------------------------------- measuring
def _polygonal(geom: Any) -> Any:
    """The polygonal part of an overlay result, as a valid Polygon / MultiPolygon."""
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
    then no new vertex is made). Solids (a voxel set standing for R(A)) take :func:`reference_solids`.
    """
    e1, e2 = euclidean_of(first, model), euclidean_of(second, model)
    if input_dimension([e1, e2]) == 3:
        return reference_solids(e1, e2)
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


def reference_solids(first: Any, second: Any) -> tuple[dict[str, Any], bool]:
    """:func:`reference_parts` in space: E ∖ E′, E ∩ E′, E′ ∖ E and E ∪ E′ of two solids, as polyhedra.

    When the exact bounding boxes of E and E′ are disjoint (apart along some axis: closed boxes that do not
    meet), so are the solids: the parts are E, ∅, E′ and E ∪ E′ is their shells together, exactly (the
    flag is True). Otherwise the parts are manifold3d's mesh Booleans on the float64 vertices (docs/adr/0061):
    robust, but their new vertices, where the surfaces cross, are rounded to float64 (the flag is False). An
    exact image that is not float64 (an :class:`ExactSolid` under a map) is rounded once first.
    """
    from mrm.geometry.polyhedra import Polyhedron  # 3D only: the plane work never loads the polyhedra

    s1, s2 = ExactSolid.of(first), ExactSolid.of(second)
    b1, b2 = s1.bounds(), s2.bounds()
    exact = s1.transform.is_identity and s2.transform.is_identity  # else the vertices are rounded
    p1 = s1.base if s1.transform.is_identity else Polyhedron(s1.float_vertices()[0], s1.base.triangles)
    p2 = s2.base if s2.transform.is_identity else Polyhedron(s2.float_vertices()[0], s2.base.triangles)
    if b1 is None or b2 is None or any(b1[d + 3] < b2[d] or b2[d + 3] < b1[d] for d in range(3)):
        if p1.is_empty or p2.is_empty:
            union = p2 if p1.is_empty else p1
        else:
            vertices = np.vstack([p1.vertices, p2.vertices])
            triangles = np.vstack([p1.triangles, p2.triangles + p1.n_vertices])
            union = Polyhedron(vertices, triangles)  # apart: the shells of both make one valid solid
        return {"a_minus_b": p1, "a_and_b": Polyhedron.empty(), "b_minus_a": p2, "union": union}, exact
    from manifold3d import Manifold  # the mesh Booleans: loaded only when two solids overlap

    m1, m2 = _manifold(p1), _manifold(p2)
    found = {"a_minus_b": m1 - m2, "a_and_b": m1 ^ m2, "b_minus_a": m2 - m1, "union": m1 + m2}
    out = {}
    for key, m in found.items():
        assert isinstance(m, Manifold)
        out[key] = _polyhedron_of(m, key)
    return out, False


def _manifold(solid: Any) -> Any:
    """A polyhedron as a manifold3d Manifold, from its float64 vertices (Mesh64: never float32)."""
    from manifold3d import Error, Manifold, Mesh64

    vertices = np.array(solid.vertices, dtype=np.float64, order="C")  # fresh and writeable, as nanobind takes
    triangles = np.array(solid.triangles, dtype=np.uint64, order="C")
    m = Manifold(Mesh64(vert_properties=vertices, tri_verts=triangles))
    if m.status() != Error.NoError:
        raise ParameterError(f"the mesh Booleans refused a solid as the reference ({m.status()})")
    return m


@dataclass(frozen=True, eq=False)
class ReferenceMesh:
    """A closed, outward triangle mesh that is no :class:`Polyhedron`: manifold3d's result with pinches.

    Where E and E′ share a face or an edge (R of voxel sets lie on common planes), a part of them touches
    itself along an edge or at a point; manifold3d keeps such a pinch as two vertices at one position, which
    a polyhedron refuses (one vertex per point, manifold vertices) but the measure of the distance does not
    need (it reads triangles and crossings: :func:`mrm.geometry.hausdorff.solids.solid_hausdorff`). It has
    what :class:`ExactSolid` reads of a polyhedron.
    """

    vertices: np.ndarray
    triangles: np.ndarray

    @property
    def is_empty(self) -> bool:
        """True for no triangle."""
        return len(self.triangles) == 0

    @property
    def n_vertices(self) -> int:
        """The number of vertices."""
        return len(self.vertices)

    @property
    def bbox(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """((xmin, ymin, zmin), (xmax, ymax, zmax)) of the vertices."""
        lo, hi = self.vertices.min(axis=0), self.vertices.max(axis=0)
        return (float(lo[0]), float(lo[1]), float(lo[2])), (float(hi[0]), float(hi[1]), float(hi[2]))


def _polyhedron_of(m: Any, key: str) -> Any:
    """manifold3d's result as a polyhedron (its float64 mesh), or a :class:`ReferenceMesh` with pinches."""
    from mrm.geometry.polyhedra import Polyhedron

    mesh = m.to_mesh64()
    vertices = np.array(mesh.vert_properties, dtype=np.float64)[:, :3].copy()
    triangles = np.array(mesh.tri_verts, dtype=np.int64).reshape(-1, 3)
    if len(triangles) == 0:
        return Polyhedron.empty()
    try:
        return Polyhedron(vertices, triangles)
    except InvalidGeometryError as e:  # a pinch (two vertices at one point): closed and outward all the same
        log.debug("the reference %s is no polyhedron (%s): measured as its mesh", key, e)
        return ReferenceMesh(vertices, triangles)
