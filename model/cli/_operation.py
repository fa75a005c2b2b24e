"""What the operation subcommands share (``mrm scale | rotate | simplify | union | corefine``, DESIGN §9).

Inputs are pixel files (.png .pbm .pgm .npz), vector files (.geojson .json .wkt) or projects (.mrm) with
``--object NAME``. An operation reads the representation it needs: DSS and dR the discrete one (D(E) of a
vector input), Sp the Euclidean one (R(A) of a pixel input), EDu and EDco either (a pixel set stands for
itself as D(E)).

Outputs: a pixel result goes to .png/.pbm/.pgm/.npz, a Euclidean result to .geojson/.json/.wkt/.svg; asking
for the other kind writes the result's other representation (R of a pixel result, D of a Euclidean one —
exact both ways, since D(R(A)) = A). Files are written atomically: a failure leaves no half-written file.

``--json`` prints the info keys of the result (:func:`mrm.summary.summarize`) plus ``bound`` (the error
bound of the operation as a chain, null where the model gives none) and ``measured`` (the exact Hausdorff
distance between the composite Euclidean transform of A_first and A_last; null with ``--no-measure``).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import Any

from mrm.cli._common import add_limit_argument, extension_of, load_object, print_table
from mrm.cli._project_input import add_object_argument
from mrm.errors import ParameterError
from mrm.io.pixel_files import PIXEL_EXTENSIONS, write_pixels
from mrm.io.vector_files import VECTOR_EXTENSIONS, write_geojson, write_svg, write_wkt
from mrm.reps.pixels import PixelSet
from mrm.summary import summarize

#: Input file types.
INPUTS = (*PIXEL_EXTENSIONS, *VECTOR_EXTENSIONS, ".mrm")
#: Output file types of a single result.
OUTPUTS = (*PIXEL_EXTENSIONS, *VECTOR_EXTENSIONS, ".svg")


def add_input(parser: argparse.ArgumentParser) -> None:
    """One input IN with ``--object``."""
    parser.add_argument("input", metavar="IN", help="a pixel file, a vector file or a project (.mrm)")
    add_object_argument(parser)


def add_two_inputs(parser: argparse.ArgumentParser) -> None:
    """Two inputs A B; ``--object`` may be given twice (for A, then for B)."""
    parser.add_argument("first", metavar="A", help="a pixel file, a vector file or a project (.mrm)")
    parser.add_argument("second", metavar="B", help="a pixel file, a vector file or a project (.mrm)")
    parser.add_argument(
        "--object",
        metavar="NAME",
        action="append",
        default=None,
        help="for project inputs: the object to use; give it twice for A and B (once: every project input)",
    )


def add_common(parser: argparse.ArgumentParser, output_help: str) -> None:
    """``-o OUT``, ``--limit`` and ``--no-measure``."""
    parser.add_argument("-o", "--output", required=True, metavar="OUT", help=output_help)
    add_limit_argument(parser)
    parser.add_argument(
        "--no-measure",
        action="store_true",
        help="skip the exact Hausdorff distance (measured: null); it can take seconds on large objects",
    )


def parse_point(text: str) -> tuple[str, str]:
    """Argparse type: ``X,Y`` (kept as text, read exactly by the operation)."""
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 2 or not all(parts):
        raise argparse.ArgumentTypeError(f"expected X,Y (two numbers), got {text!r}")
    return parts[0], parts[1]


def read_one(path: str, object_name: str | None, model: str | None, limit: int) -> tuple[Any, str]:
    """Read one input: (PixelSet or geometry, model)."""
    extension_of(path, INPUTS, "supported input file")
    _, value, chosen = load_object(path, object_name, model, limit=limit)
    return value, chosen


def read_two(args: argparse.Namespace) -> tuple[Any, Any, str]:
    """Read A and B with their ``--object`` names; the model is --model, else A's project's, else B's."""
    names = list(args.object or [])
    if len(names) > 2:
        raise ParameterError("--object is given at most twice (for A, then for B)")
    project = [Path(p).suffix.lower() == ".mrm" for p in (args.first, args.second)]
    if len(names) == 2:
        name_a, name_b = names
    elif len(names) == 1:
        if project[0] and project[1]:
            name_a = name_b = names[0]
        elif project[0] or project[1]:
            name_a, name_b = (names[0], None) if project[0] else (None, names[0])
        else:
            raise ParameterError("--object applies to project (.mrm) inputs only")
    else:
        name_a = name_b = None
    a, model_a = read_one(args.first, name_a, args.model, args.limit)
    b, model_b = read_one(args.second, name_b, args.model, args.limit)
    model = args.model or (model_a if project[0] else model_b if project[1] else model_a)
    return a, b, model


def write_result(result: Any, path: str, model: str, properties: dict[str, Any] | None = None) -> None:
    """Write a pixel set or a polygon to ``path``, converting to the representation the extension asks for."""
    ext = extension_of(path, OUTPUTS, "output file")
    if ext in PIXEL_EXTENSIONS:
        if not isinstance(result, PixelSet):
            from mrm.geometry.discretize import discretize

            result = discretize(result, model)
        write_pixels(result, path)
        return
    if ext == ".svg":
        write_svg(result, path)
        return
    if isinstance(result, PixelSet):
        from mrm.geometry.reconstruct import reconstruct

        result = reconstruct(result, model)
    if ext == ".wkt":
        write_wkt(result, path)
    else:
        write_geojson(result, path, properties={"model": model, **(properties or {})})


def result_summary(result: Any, pixels: PixelSet, model: str) -> dict[str, Any]:
    """The info keys of a result (its discrete representation, and the polygon when it is Euclidean)."""
    return summarize(pixels, model, geom=None if isinstance(result, PixelSet) else result)


def _input_record(path: str, object_name: str | None, source: Any) -> tuple[int, Any]:
    """(id, provenance) of a project input object, so that its own chain joins the account; else (0, None)."""
    if Path(path).suffix.lower() != ".mrm":
        return 0, None
    from mrm.io.project import read_project

    objs = [o for o in read_project(path).objects if object_name is None or o.name == object_name]
    if len(objs) == 1 and objs[0].source == source:
        return objs[0].id, objs[0].provenance
    return 0, None


def run_unary(args: argparse.Namespace, operation: str, params: dict[str, Any]) -> dict[str, Any]:
    """Run one unary operation, write its result, return the --json summary: the model's account.

    The parameters are read and range-checked by the registry (:func:`mrm.ops.base.coerce_params`); the
    numbers printed are :meth:`mrm.ops.account.Account.summary`, the same as the inspector's and
    ``mrm account``'s for the same chain (a project input's own chain is part of it).
    """
    import dataclasses

    from mrm.document import Provenance
    from mrm.ops.account import account_of
    from mrm.ops.base import coerce_params, get_operation, params_to_dict, run_operation

    extension_of(args.output, OUTPUTS, "output file")  # fail before any work
    spec = get_operation(operation)
    checked = coerce_params(spec, {k: v for k, v in params.items() if v is not None})  # before reading
    source, model = read_one(args.input, args.object, args.model, args.limit)
    checked = dataclasses.replace(checked, model=model)
    oid, parent = _input_record(args.input, args.object, source)
    prov = Provenance(spec.name, params_to_dict(checked), (oid,), (source,), (parent,))
    t0 = time.perf_counter()
    if args.no_measure:
        result = run_operation(spec, [source], checked, limit=args.limit).output
        acc = account_of(prov, measure=False, limit=args.limit)
    else:  # the account recomputes the step from its input: the result is made once
        acc = account_of(prov, measure=True, limit=args.limit)
        if acc.error:
            raise ParameterError(acc.error)
        result = acc.output
    seconds = time.perf_counter() - t0
    write_result(result, args.output, model, {"operation": spec.name})
    summary: dict[str, Any] = {"input": str(args.input), "output": str(args.output), "operation": spec.name}
    summary["params"] = params_to_dict(checked)
    pixels = acc.result if acc.result is not None else _pixels_of(result, model, args.limit)
    summary.update(result_summary(result, pixels, model))
    summary["account"] = acc.summary()
    summary.update({k: v for k, v in acc.summary().items() if k not in ("operation", "model")})
    summary["seconds"] = seconds
    if not args.json:
        print_table({k: v for k, v in summary.items() if k not in ("account", "steps", "parts")})
    return summary


def _pixels_of(result: Any, model: str, limit: int | None) -> PixelSet:
    if isinstance(result, PixelSet):
        return result
    from mrm.geometry.discretize import discretize

    return discretize(result, model, limit=limit)


def operation_command(operation: str, output_help: str) -> tuple[Any, Any]:
    """``(add_arguments, run)`` of a one-object subcommand, generated from the operation's registry spec.

    Every parameter of the spec's dataclass becomes an option (``--alpha``, ``--angle``, ``--center X,Y``)
    with its label, unit, help and declared range; ``model`` is the common ``--model``. The values are read
    exactly and range-checked by the registry (:func:`mrm.ops.base.coerce_params`), as the panel's are.
    """
    from mrm.ops.apply import load_paper_operations
    from mrm.ops.base import get_operation, range_text

    load_paper_operations()
    spec = get_operation(operation)
    fields = [p for p in spec.param_specs() if p.name != "model"]

    def add_arguments(parser: argparse.ArgumentParser) -> None:
        add_input(parser)
        for p in fields:
            unit = f" [{p.unit}]" if p.unit and p.unit != "×" else ""
            if p.kind == "point":
                parser.add_argument(
                    f"--{p.name}", type=parse_point, default=None, metavar="X,Y", help=f"{p.help}{unit}"
                )
            else:
                allowed = f" ({range_text(p)})" if p.minimum is not None or p.maximum is not None else ""
                parser.add_argument(
                    f"--{p.name}",
                    required=not p.optional,
                    metavar=p.label.upper() if p.label.isascii() else p.name[0].upper(),
                    help=f"{p.help}{unit}{allowed}; decimal or p/q, read exactly",
                )
        add_common(parser, output_help)

    def run(args: argparse.Namespace) -> dict[str, Any]:
        return run_unary(args, spec.name, {p.name: getattr(args, p.name) for p in fields})

    return add_arguments, run
