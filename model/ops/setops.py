"""Discrete set operations on pixel sets as operations with provenance: union, intersection, difference.

They are exact (no discretization, no continuation), so their bound is 0 and a chain through them keeps the
bound of the steps around it: a union of discrete sets is the discrete step of the Euclidean-discrete union
``EDu(E, E′) = R(D(E) ∪ D(E′))``.
"""

from __future__ import annotations

import operator
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from mrm.core.grids import PixelSet
from mrm.core.progress import ProgressLike
from mrm.geometry.discretize.exact_shape import box_area
from mrm.ops.base import OperationResult, OperationSpec, Output, register
from mrm.ops.outcome import joint_box

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
    return box_area(joint_box([p.bbox for p in inputs if isinstance(p, PixelSet)]))


def _set_operation(
    name: str, title: str, output: str, combine: Callable[[PixelSet, PixelSet], PixelSet], help: str
) -> OperationSpec:
    """Register the exact set operation ``combine`` of two pixel sets; its result is named ``output``."""

    def run(inputs: Sequence[Output], params: Any, progress: ProgressLike) -> OperationResult:
        return OperationResult(outputs=[(output, combine(*_pair(inputs)))])

    return register(
        OperationSpec(
            name=name,
            title=title,
            arity=2,
            params=SetOpParams,
            run=run,
            input_kind="discrete",
            output_kind="discrete",
            help=help,
            estimate=_estimate,
        )
    )


UNION = _set_operation(
    "discrete_union", "Union (discrete)", "union", operator.or_, "The pixels in either set (exact)."
)
INTERSECTION = _set_operation(
    "discrete_intersection",
    "Intersection (discrete)",
    "intersection",
    operator.and_,
    "The pixels in both sets (exact).",
)
DIFFERENCE = _set_operation(
    "discrete_difference",
    "Difference (discrete)",
    "difference",
    operator.sub,
    "The pixels of the first set that are not in the second (exact).",
)
