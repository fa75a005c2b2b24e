"""``mrm union A B -o OUT``: Euclidean-discrete union EDu(E, E′) = R(D(E) ∪ D(E′)).

A and B are pixel files, vector files or projects (``--object NAME``, given twice for two project inputs).
The output is a vector file (or, for a pixel file, D(EDu) = D(E) ∪ D(E′)). ``measured`` is the Hausdorff
distance between E ∪ E′ and the result (E ∪ E′ by GEOS when the inputs overlap: ``reference_exact`` false).
3D inputs (voxel files, meshes) give a polyhedron: written to a mesh (.obj .ply .off) or, as its voxels, to
a voxel file (.npz); E ∪ E′ is then manifold3d's when they overlap, and ``measured`` a certified interval's
upper end (``measured_interval``).
"""

from __future__ import annotations

import argparse
from typing import Any

from mrm.cli._common import print_table
from mrm.cli._operation import (
    OUTPUTS,
    TwoInputRun,
    check_3d_output,
    result_summary,
    two_input_command,
    write_result,
)
from mrm.io.georef import georef_summary
from mrm.ops.registry import get_operation, run_operation
from mrm.ops.representations import discrete_of

NAME = get_operation("union").command  # declared by the operation (mrm.ops.boolean)
HELP = "Euclidean-discrete union EDu of two objects: R(D(A) ∪ D(B))"


def _direct(a: Any, b: Any, model: str, params: dict[str, Any], limit: int) -> Any:
    """EDu without its account (``--no-measure``)."""
    return run_operation("union", [a.value, b.value], params, limit=limit).output


def _finish(args: argparse.Namespace, done: TwoInputRun) -> dict[str, Any]:
    """Write the result and return the summary (the numbers are the model's account of the result)."""
    acc, model = done.account, done.model
    result = acc.output if done.computed is None else done.computed
    write_result(result, args.output, model, {"operation": "union"}, done.georef)
    summary: dict[str, Any] = {"inputs": [str(args.first), str(args.second)], "output": str(args.output)}
    summary["operation"] = "union"
    pixels = acc.result if acc.result is not None else None
    if pixels is None:
        pixels = discrete_of(result, model, limit=args.limit)
    summary.update(result_summary(result, pixels, model))
    summary.update({k: v for k, v in acc.summary().items() if k not in ("operation", "model")})
    summary["seconds"] = done.seconds
    summary.update(georef_summary(done.georef))
    if not args.json:
        print_table({k: v for k, v in summary.items() if k not in ("steps", "parts")})
    return summary


# A, B, --object, -o, --limit, --no-measure; the options of EDu's registry spec (none besides --model).
add_arguments, run = two_input_command(
    "union",
    "the result: a vector file (.geojson .json .wkt .svg) or a pixel file (.png .pbm .npz)",
    _finish,
    _direct,
    outputs=OUTPUTS,
    check_output=lambda output, n: check_3d_output(output) if n == 3 else None,
)
