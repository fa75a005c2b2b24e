"""Discrete set operations on pixel sets as operations with provenance: union, intersection, difference.

They are exact (no discretization, no continuation), so their bound is 0 and a chain through them keeps the
bound of the steps around it: a union of discrete sets is the discrete step of the Euclidean-discrete union
``EDu(E, E′) = R(D(E) ∪ D(E′))``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from mrm.ops.base import OperationResult, OperationSpec, Output, ProgressLike, register
from mrm.reps.pixels import PixelSet

__all__ = ["DIFFERENCE", "INTERSECTION", "UNION", "SetOpParams"]


@dataclass(frozen=True)
class SetOpParams:
    """Discrete set operations take no parameters."""


def _pair(inputs: Sequence[Output]) -> tuple[PixelSet, PixelSet]:
    a, b = inputs
    assert isinstance(a, PixelSet) and isinstance(b, PixelSet)  # run_operation checked the kinds
    return a, b


def _estimate(inputs: Sequence[Output], params: Any) -> int:
    # A union covers at most the joint bounding box; intersections and differences are smaller.
    boxes = [p.bbox for p in inputs if isinstance(p, PixelSet) and p.bbox is not None]
    if not boxes:
        return 0
    x0, y0 = min(b[0] for b in boxes), min(b[1] for b in boxes)
    x1, y1 = max(b[2] for b in boxes), max(b[3] for b in boxes)
    return (x1 - x0 + 1) * (y1 - y0 + 1)


def _run_union(inputs: Sequence[Output], params: Any, progress: ProgressLike) -> OperationResult:
    a, b = _pair(inputs)
    return OperationResult(outputs=[("union", a | b)])


def _run_intersection(inputs: Sequence[Output], params: Any, progress: ProgressLike) -> OperationResult:
    a, b = _pair(inputs)
    return OperationResult(outputs=[("intersection", a & b)])


def _run_difference(inputs: Sequence[Output], params: Any, progress: ProgressLike) -> OperationResult:
    a, b = _pair(inputs)
    return OperationResult(outputs=[("difference", a - b)])


UNION = register(
    OperationSpec(
        name="discrete_union",
        title="Union (discrete)",
        arity=2,
        params=SetOpParams,
        run=_run_union,
        input_kind="discrete",
        output_kind="discrete",
        help="The pixels in either set (exact).",
        estimate=_estimate,
    )
)

INTERSECTION = register(
    OperationSpec(
        name="discrete_intersection",
        title="Intersection (discrete)",
        arity=2,
        params=SetOpParams,
        run=_run_intersection,
        input_kind="discrete",
        output_kind="discrete",
        help="The pixels in both sets (exact).",
        estimate=_estimate,
    )
)

DIFFERENCE = register(
    OperationSpec(
        name="discrete_difference",
        title="Difference (discrete)",
        arity=2,
        params=SetOpParams,
        run=_run_difference,
        input_kind="discrete",
        output_kind="discrete",
        help="The pixels of the first set that are not in the second (exact).",
        estimate=_estimate,
    )
)
