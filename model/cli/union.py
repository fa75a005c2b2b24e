"""``mrm union A B -o OUT``: Euclidean-discrete union EDu(E, E′) = R(D(E) ∪ D(E′)).

A and B are pixel files, vector files or projects (``--object NAME``, given twice for two project inputs).
The output is a vector file (or, for a pixel file, D(EDu) = D(E) ∪ D(E′)). ``measured`` is the Hausdorff
distance between E ∪ E′ and the result (E ∪ E′ by GEOS when the inputs overlap: ``reference_exact`` false).
"""

from __future__ import annotations

import argparse
import time
from typing import Any

from mrm.cli._common import extension_of, print_table
from mrm.cli._operation import OUTPUTS, add_common, add_two_inputs, read_two, result_summary, write_result

NAME = "union"
HELP = "Euclidean-discrete union EDu of two objects: R(D(A) ∪ D(B))"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add A, B, ``--object``, ``-o``, ``--limit``, ``--no-measure``."""
    add_two_inputs(parser)
    add_common(
        parser, "the result: a vector file (.geojson .json .wkt .svg) or a pixel file (.png .pbm .npz)"
    )


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Unite, write the result, return the summary."""
    from mrm.geometry.bounds import bound_of_chain, union
    from mrm.ops.boolean import euclidean_discrete_union, reference_parts
    from mrm.ops.measure import measured_error

    extension_of(args.output, OUTPUTS, "output file")
    a, b, model = read_two(args)
    t0 = time.perf_counter()
    out = euclidean_discrete_union(a, b, model, limit=args.limit)
    seconds = time.perf_counter() - t0
    write_result(out.result, args.output, model, {"operation": "union"})
    summary: dict[str, Any] = {"inputs": [str(args.first), str(args.second)], "output": str(args.output)}
    summary["operation"] = "union"
    summary.update(result_summary(out.result, out.discrete, model))
    bound = bound_of_chain([union()], model)
    summary.update(bound=bound.bound, bound_one_sided=bound.one_sided, bound_formula=bound.formula)
    summary["measured"] = None
    if not args.no_measure:
        refs, exact_ref = reference_parts(a, b, model)
        summary.update(measured_error(refs["union"], out.euclidean).as_dict())
        summary["reference_exact"] = exact_ref
    summary["seconds"] = seconds
    if not args.json:
        print_table(summary)
    return summary
