"""``mrm discretize IN... -o OUT``: the exact discretization of a Euclidean geometry, written as pixels.

Several inputs (files, directories, quoted globs; ``--jobs N`` workers) need ``-o`` to be a directory
(``NAME.geojson`` gives ``NAME.png``) or a pattern holding ``{stem}``, as for ``mrm reconstruct``.

``IN`` is a GeoJSON or WKT file (every geometry in it, combined) or a project (.mrm). For a project,
``--object NAME`` picks one object — a Euclidean object is discretized, a discrete object is written as it
is (it is its own discrete representation); without ``--object`` every Euclidean object of the project is
discretized, combined (D is union-stable, so this is the union of their discretizations). The model is
``--model``, else the project's, else 'standard'. An .svg output draws the pixels with the Euclidean input
outlined on top.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import Any

from mrm.cli._common import (
    PROJECT_EXTENSION,
    add_inputs_argument,
    add_jobs_argument,
    add_limit_argument,
    batch_outputs,
    discretize_geometry,
    expand_inputs,
    extension_of,
    load_object,
    print_table,
    progress,
    project_objects,
    run_batch,
)
from mrm.cli._project_input import add_object_argument
from mrm.errors import FileFormatError
from mrm.io.pixel_files import PIXEL_EXTENSIONS, write_pixels
from mrm.io.vector_files import VECTOR_EXTENSIONS, combine, write_svg
from mrm.reps.pixels import PixelSet
from mrm.summary import summarize

NAME = "discretize"
HELP = (
    "discretize a Euclidean geometry (.geojson, .wkt, .mrm) into a pixel file (.png, .pbm, .pgm, .npz, .svg)"
)

INPUTS = (*VECTOR_EXTENSIONS, PROJECT_EXTENSION)
OUTPUTS = (*PIXEL_EXTENSIONS, ".svg")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the inputs, ``--object``, ``-o OUT``, ``--jobs`` and ``--limit``."""
    add_inputs_argument(parser, "GeoJSON, WKT or project files")
    add_object_argument(parser)
    add_jobs_argument(parser)
    parser.add_argument(
        "-o",
        "--output",
        required=True,
        metavar="OUT",
        help="the pixel file to write (.png .pbm .pgm .npz; .svg draws the pixels with the input outlined); "
        "for several inputs a directory or a pattern holding {stem}",
    )
    add_limit_argument(parser)


def _source(path: str, object_name: str | None, model: str | None, limit: int) -> tuple[Any, str]:
    """The geometry (or, for a discrete project object, the pixel set) to discretize, and the model."""
    if extension_of(path, INPUTS, "supported input file") == PROJECT_EXTENSION and object_name is None:
        objects, project_model = project_objects(path)
        euclidean = [o.source for o in objects if not isinstance(o.source, PixelSet)]
        if not euclidean:
            raise FileFormatError(
                f"{path}: the project holds no Euclidean object to discretize "
                "(--object NAME writes a discrete object's pixels)"
            )
        return combine(euclidean), model or project_model
    _, value, chosen = load_object(path, object_name, model, limit=limit)
    return value, chosen


def discretize_file(
    path: str, output: str, object_name: str | None, model: str | None, limit: int
) -> dict[str, Any]:
    """Read one input, discretize it, write the pixels; return the summary (batch workers call it)."""
    out_ext = extension_of(output, OUTPUTS, "pixel output file")  # fail before any work
    source, chosen = _source(path, object_name, model, limit)
    geom = None if isinstance(source, PixelSet) else source
    t0 = time.perf_counter()
    ps = source if geom is None else discretize_geometry(geom, chosen, limit)
    seconds = time.perf_counter() - t0
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    if out_ext == ".svg":
        if geom is None:
            write_svg(ps, output)
        else:
            write_svg(geom, output, pixels=ps)
    else:
        write_pixels(ps, output)
    summary: dict[str, Any] = {"input": str(path), "output": str(output)}
    if object_name is not None:
        summary.update(object=object_name, source="discrete" if geom is None else "euclidean")
    summary.update(summarize(ps, chosen, geom=geom))
    summary["seconds"] = seconds
    return summary


def _line(f: dict[str, Any]) -> str:
    return f"{f['input']} -> {f['output']}: {f['pixels']} pixels, {f['seconds']:.3f} s"


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Discretize every input and write it; return the summary (several inputs: ``files`` and totals)."""
    inputs = expand_inputs([str(i) for i in args.inputs], INPUTS)
    outputs = batch_outputs(inputs, str(args.output), OUTPUTS, ".png", "pixel output file")
    jobs = [(i, o, args.object, args.model, args.limit) for i, o in zip(inputs, outputs, strict=True)]
    if len(jobs) == 1:
        with progress(args, desc=f"discretize {inputs[0]}"):
            summary = discretize_file(*jobs[0])
        if not args.json:
            print_table(summary)
        return summary
    files, errors = run_batch(args, discretize_file, jobs, _line, desc="discretize")
    if errors:
        raise FileFormatError(f"{len(errors)} of {len(jobs)} inputs failed: " + "; ".join(errors))
    return {"inputs": len(jobs), "pixels": sum(f["pixels"] for f in files), "files": files}
