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
from mrm.core.params import Parameters
from mrm.core.progress import ProgressLike
from mrm.ops.estimate import estimated_pixels
from mrm.ops.registry import OperationResult, OperationSpec, Output, register

__all__ = ["DIFFERENCE", "INTERSECTION", "UNION", "SetOpParams"]


@dataclass(frozen=True)
class SetOpParams(Parameters):
    """Discrete set operations take no parameters."""


def _pair(inputs: Sequence[Output]) -> tuple[PixelSet, PixelSet]:
    a, b = inputs
    assert isinstance(a, PixelSet) and isinstance(b, PixelSet)  # run_operation checked the kinds
    return a, b


def _estimate(inputs: Sequence[Output], params: Any) -> int:
    # A union covers at most the joint bounding box; intersections and differences are smaller.
    return estimated_pixels(inputs, None, "standard")


def _set_operation(
    name: str,
    title: str,
    output: str,
    combine: Callable[[PixelSet, PixelSet], PixelSet],
    help: str,
    exact: str,
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
            reads="discrete",
            produces="discrete",
            help=help,
            estimate=_estimate,
            exact=exact,
        )
    )


UNION = _set_operation(
    "discrete_union",
    "Union (discrete)",
    "union",
    operator.or_,
    "The pixels in either set (exact).",
    "a union of pixel sets is exact",
)
INTERSECTION = _set_operation(
    "discrete_intersection",
    "Intersection (discrete)",
    "intersection",
    operator.and_,
    "The pixels in both sets (exact).",
    "an intersection of pixel sets is exact",
)
DIFFERENCE = _set_operation(
    "discrete_difference",
    "Difference (discrete)",
    "difference",
    operator.sub,
    "The pixels of the first set that are not in the second (exact).",
    "a difference of pixel sets is exact",
)
