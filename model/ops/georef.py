"""The georeference of an operation's result, from its inputs' and its declaration (ADR 0021).

An operation says how a georeferenced input's grid carries to its result (:attr:`OperationSpec.grid`):
``same`` (the rotation turns the shape on the grid, so it turns in the world about the centre's world point;
the simplification and the co-refinement map their scaled work back; the union takes pixels) or ``scaled``
(DSS_α: the grid scaled by the operation's similarity, pixels α times smaller, the world outline where the
input's was).
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from typing import Any

from mrm.core.errors import MRMError
from mrm.core.georef import GeoRef
from mrm.ops.registry import get_operation

log = logging.getLogger(__name__)

__all__ = ["common_grid", "result_georef"]


def common_grid(inputs: Sequence[GeoRef | None], what: str = "the result") -> GeoRef | None:
    """The inputs' grid when they all share one, else None (a result of several grids has none).

    Mixing grids has no single right answer and MR Modeler does not resample: the result is then in plain grid
    coordinates, as on the canvas.
    """
    if not inputs or inputs[0] is None or any(g != inputs[0] for g in inputs[1:]):
        if any(g is not None for g in inputs):
            log.info("%s has no georeference: its inputs are not on one grid", what)
        return None
    return inputs[0]


def result_georef(
    operation: str, params: Mapping[str, Any] | Any, inputs: Sequence[GeoRef | None]
) -> GeoRef | None:
    """The georeference of the result of ``operation`` with ``params`` (JSON data or a parameters object).

    None when the inputs are not on one grid, or the operation's result has no grid of theirs.
    """
    grid = common_grid(inputs, f"the result of {operation}")
    if grid is None:
        return None
    try:
        spec = get_operation(operation)
        if spec.grid == "same":
            return grid
        if spec.grid == "scaled" and spec.similarity is not None:
            sim = spec.similarity(spec.read_params(params))
            if sim.b == 0:
                return grid.scaled(sim.a, (sim.tx, sim.ty))
    except MRMError as e:
        log.info("the result of %s has no georeference: %s", operation, e)
        return None
    log.info("the result of %s has no georeference: the operation keeps no grid", operation)
    return None
