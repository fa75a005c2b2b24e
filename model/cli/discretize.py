"""``mrm discretize IN -o OUT``: the exact discretization of a Euclidean geometry, written as pixels.

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
from typing import Any

from mrm.cli._common import (
    PROJECT_EXTENSION,
    add_limit_argument,
    discretize_geometry,
    extension_of,
    load_object,
    print_table,
    project_objects,
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
    """Add the input, ``--object``, ``-o OUT`` and ``--limit``."""
    parser.add_argument("input", metavar="IN", help="a GeoJSON, WKT or project file")
    add_object_argument(parser)
    parser.add_argument(
        "-o",
        "--output",
        required=True,
        metavar="OUT",
        help="the pixel file to write (.png .pbm .pgm .npz; .svg draws the pixels with the input outlined)",
    )
    add_limit_argument(parser)


def _source(args: argparse.Namespace) -> tuple[Any, str]:
    """The geometry (or, for a discrete project object, the pixel set) to discretize, and the model."""
    if extension_of(args.input, INPUTS, "supported input file") == PROJECT_EXTENSION and args.object is None:
        objects, project_model = project_objects(args.input)
        euclidean = [o.source for o in objects if not isinstance(o.source, PixelSet)]
        if not euclidean:
            raise FileFormatError(
                f"{args.input}: the project holds no Euclidean object to discretize "
                "(--object NAME writes a discrete object's pixels)"
            )
        return combine(euclidean), args.model or project_model
    _, value, model = load_object(args.input, args.object, args.model, limit=args.limit)
    return value, model


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Read the geometry, discretize it, write the pixels; return the summary of the result."""
    out_ext = extension_of(args.output, OUTPUTS, "pixel output file")  # fail before any work
    source, model = _source(args)
    geom = None if isinstance(source, PixelSet) else source
    t0 = time.perf_counter()
    ps = source if geom is None else discretize_geometry(geom, model, args.limit)
    seconds = time.perf_counter() - t0
    if out_ext == ".svg":
        if geom is None:
            write_svg(ps, args.output)
        else:
            write_svg(geom, args.output, pixels=ps)
    else:
        write_pixels(ps, args.output)
    summary: dict[str, Any] = {"input": str(args.input), "output": str(args.output)}
    if args.object is not None:
        summary.update(object=args.object, source="discrete" if geom is None else "euclidean")
    summary.update(summarize(ps, model, geom=geom))
    summary["seconds"] = seconds
    if not args.json:
        print_table(summary)
    return summary
