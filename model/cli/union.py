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
from mrm.cli._operation import (
    OUTPUTS,
    add_common,
    add_two_inputs,
    read_two,
    result_summary,
    two_input_georef,
    two_input_provenance,
    write_result,
)
from mrm.io.georef import georef_summary

NAME = "union"
HELP = "Euclidean-discrete union EDu of two objects: R(D(A) ∪ D(B))"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add A, B, ``--object``, ``-o``, ``--limit``, ``--no-measure``."""
    add_two_inputs(parser)
    add_common(
        parser, "the result: a vector file (.geojson .json .wkt .svg) or a pixel file (.png .pbm .npz)"
    )


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Unite, write the result, return the summary (the numbers are the model's account of the result)."""
    from mrm.ops.account import account_of
    from mrm.ops.base import run_operation

    extension_of(args.output, OUTPUTS, "output file")
    a, b, model = read_two(args)
    prov = two_input_provenance("union", {"model": model}, a, b)
    t0 = time.perf_counter()
    if args.no_measure:
        result = run_operation("union", [a.value, b.value], {"model": model}, limit=args.limit).output
        acc = account_of(prov, measure=False, limit=args.limit)
    else:  # the account makes the union once, from the inputs, and measures it
        acc = account_of(prov, measure=True, limit=args.limit)
        result = acc.output
    seconds = time.perf_counter() - t0
    georef = two_input_georef("union", a, b)
    write_result(result, args.output, model, {"operation": "union"}, georef)
    summary: dict[str, Any] = {"inputs": [str(args.first), str(args.second)], "output": str(args.output)}
    summary["operation"] = "union"
    pixels = acc.result if acc.result is not None else None
    if pixels is None:
        from mrm.geometry.discretize import discretize

        pixels = discretize(result, model, limit=args.limit)
    summary.update(result_summary(result, pixels, model))
    summary.update({k: v for k, v in acc.summary().items() if k not in ("operation", "model")})
    summary["seconds"] = seconds
    summary.update(georef_summary(georef))
    if not args.json:
        print_table({k: v for k, v in summary.items() if k not in ("steps", "parts")})
    return summary
