"""The one size estimate of the operations: how many pixels the largest pixel set they make can cover.

Every operation discretizes something — D(T(R(A))) for DSS_α and dR_θ,C, D(Sc_α(E)) for Sp_α, D(E) ∪ D(E′)
(scaled by α for EDco_α) for the two-object operations, A op B for the set operations — and its guard
(:func:`mrm.core.limits.check_pixels`, called by :func:`mrm.ops.registry.run_operation`) refuses the work
beyond the pixel limit *before* any of it, from bounding boxes alone (exact rational arithmetic: an absurd α
reports the absurd size it would have had).
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import Any, Literal

from mrm.core.grids import PixelSet, VoxelSet, box_area, dimension_of, joint_box
from mrm.core.models import Model
from mrm.geometry.discretize.exact_shape import ExactShape, mapped_bounds, pixel_box, voxel_bounds
from mrm.geometry.discretize.exact_solid import ExactSolid

__all__ = ["estimated_box", "estimated_pixels"]


def estimated_box(
    source: Any,
    sim: Any,
    model: Model | str,
    reads: Literal["discrete", "euclidean"] = "euclidean",
) -> tuple[int, ...] | None:
    """A pixel box holding D(T(X)) for an object's source X (T = ``sim``, None: no similarity).

    ``reads`` is the representation the operation transforms: ``discrete`` (DSS_α, dR_θ,C: a polygon E is
    first discretized, and T applies to R(D(E))) or ``euclidean`` (Sp_α, EDco_α: T applies to E itself, or to
    R(A) for a pixel set A).

    A pixel set A with no T is its own box. R(A) lies in V(bbox(A)) under the covers, and within one more
    pixel under ``gauss`` (its boundary stays within the voxels of the border pixels on either side,
    docs/design.md §3.2); a polygon lies in its bounds, and D of it in the supercover box of those. T's image
    of that rectangle is bounded exactly, and the box is that of its pixels under ``model``.
    """
    model = Model.parse(model)
    if source is None:
        return None
    box: tuple[int, ...] | None
    if isinstance(source, PixelSet | VoxelSet):
        box = source.bbox
    else:
        exact = _bounds(source)
        if exact is None:
            return None
        if reads == "euclidean":
            found: tuple[int, ...] | None = pixel_box(
                exact if sim is None else mapped_bounds(exact, sim), model
            )
            return found
        box = pixel_box(exact, Model.SUPERCOVER)  # D(E) lies in the closed cells E meets, in every model
    if sim is None or box is None:
        return box
    if not model.is_cover:
        n = len(box) // 2
        box = (*(b - 1 for b in box[:n]), *(b + 1 for b in box[n:]))
    mapped: tuple[int, ...] | None = pixel_box(mapped_bounds(voxel_bounds(box), sim), model)
    return mapped


def _bounds(source: Any) -> tuple[Fraction, ...] | None:
    """The exact bounds of a polygon (shapely or exact) or a solid, None when it is empty."""
    if isinstance(source, ExactShape | ExactSolid):
        return source.bounds()
    if source.is_empty:
        return None
    if dimension_of(source) == 3:  # a polyhedron
        lo, hi = source.bbox
        return (*(Fraction(v) for v in lo), *(Fraction(v) for v in hi))
    x0, y0, x1, y1 = (Fraction(float(v)) for v in source.bounds)
    return x0, y0, x1, y1


def estimated_pixels(
    sources: Sequence[Any],
    sim: Any,
    model: Model | str,
    reads: Literal["discrete", "euclidean"] = "euclidean",
) -> int:
    """An upper bound of the pixels of the joint box of D(T(X)) over the sources X: the one estimate."""
    return box_area(joint_box([estimated_box(s, sim, model, reads) for s in sources]))
