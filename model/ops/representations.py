"""The representation an operation reads, from an object's source: D and R through their one entry points.

An object's discrete representation is D(E) of a Euclidean source E and A itself for a pixel source A; its
Euclidean representation is R(A), or E itself (docs/design.md §7). The operations read them here, and nowhere
else: :func:`mrm.geometry.discretize.discretize` and :func:`mrm.geometry.reconstruct.reconstruct` apply their
own limits (the pixel limit, the boundary length), so every path to D and R is guarded the same way.
"""

from __future__ import annotations

from typing import Any

from mrm.core.grids import PixelSet, VoxelSet, dimension_of
from mrm.core.limits import DEFAULT_PIXEL_LIMIT
from mrm.core.models import Model
from mrm.core.progress import ProgressLike
from mrm.geometry.discretize import discretize
from mrm.geometry.discretize.exact_shape import ExactShape
from mrm.geometry.discretize.exact_solid import ExactSolid
from mrm.geometry.discretize.rational import discretize_exact, discretize_image
from mrm.geometry.reconstruct import reconstruct

__all__ = ["discrete_of", "euclidean_of", "exact_of"]


def exact_of(geom: Any) -> ExactShape | ExactSolid:
    """A Euclidean object as an exact one: an ExactShape for a polygon, an ExactSolid for a polyhedron."""
    if dimension_of(geom) == 3:  # a polyhedron or an exact solid
        return ExactSolid.of(geom)
    return ExactShape.from_geometry(geom)


def euclidean_of(source: Any, model: Model | str) -> Any:
    """The Euclidean representation of a source: R(A) for a pixel or voxel set A, else the source itself.

    A source may be a shapely polygon or an exact :class:`~mrm.geometry.discretize.exact_shape.ExactShape`
    (a chain's exact intermediate result), kept as it is.
    """
    return reconstruct(source, model) if isinstance(source, PixelSet | VoxelSet) else source


def discrete_of(
    source: Any,
    model: Model | str,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    sim: Any = None,
    progress: ProgressLike | None = None,
    what: str = "the discretization of an input",
) -> Any:
    """D(T(X)) of a source X, exactly (T = ``sim``; None: no similarity, and a pixel or voxel set is itself).

    A 3D source (a voxel set, a polyhedron, an exact solid) gives a voxel set, through the exact image T(P)
    (:class:`~mrm.geometry.discretize.exact_solid.ExactSolid`).

    A float64 polygon takes the compiled exact discretization (under T: the integer kernels when they apply);
    an exact shape, or an image the kernels cannot take, the exact rational discretization. Every path gives
    the pixels of the definitions (docs/design.md §2).
    """
    if isinstance(source, PixelSet | VoxelSet) and sim is None:
        return source
    geom = euclidean_of(source, model)
    if dimension_of(geom) == 3:  # a polyhedron or an exact solid: the exact image T(P), discretized exactly
        solid = ExactSolid.of(geom) if sim is None else ExactSolid.of(geom).map(sim)
        return solid.discretize(str(Model.parse(model)), limit=limit, progress=progress)
    if not isinstance(geom, ExactShape):
        if sim is None:
            return discretize(geom, model, limit=limit)
        fast = discretize_image(geom, sim, model, limit=limit, what=what)
        if fast is not None:  # int64 kernels, no Fraction (the same pixels)
            return fast
    shape = ExactShape.from_geometry(geom)
    if sim is not None:
        shape = shape.map(sim)
    return discretize_exact(shape, model, limit=limit, progress=progress, what=what)
