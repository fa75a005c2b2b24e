"""``mrm discretize IN -o OUT``: the exact discretization of a Euclidean geometry, written as pixels."""

from __future__ import annotations

import argparse
import time
from typing import Any

from model.cli._common import (
    PROJECT_EXTENSION,
    add_limit_argument,
    discretize_geometry,
    extension_of,
    print_table,
    read_input,
)
from model.errors import FileFormatError
from model.io.pixel_files import PIXEL_EXTENSIONS, write_pixels
from model.io.vector_files import VECTOR_EXTENSIONS, write_svg
from model.summary import summarize

NAME = "discretize"
HELP = (
    "discretize a Euclidean geometry (.geojson, .wkt, .mrm) into a pixel file (.png, .pbm, .pgm, .npz, .svg)"
)

INPUTS = (*VECTOR_EXTENSIONS, PROJECT_EXTENSION)
OUTPUTS = (*PIXEL_EXTENSIONS, ".svg")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the input, ``-o OUT`` and ``--limit``."""
    parser.add_argument("input", metavar="IN", help="a GeoJSON, WKT or project file")
    parser.add_argument(
        "-o",
        "--output",
        required=True,
        metavar="OUT",
        help="the pixel file to write (.png .pbm .pgm .npz .svg)",
    )
    add_limit_argument(parser)


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Read the geometry, discretize it, write the pixels; return the summary of the result."""
    out_ext = extension_of(args.output, OUTPUTS, "pixel output file")  # fail before any work
    src = read_input(args.input, INPUTS)
    model = args.model or src.model or "standard"
    geom = src.geometry
    if geom is None:
        raise FileFormatError(f"{args.input}: the project holds no Euclidean object to discretize")
    t0 = time.perf_counter()
    ps = discretize_geometry(geom, model, args.limit)
    seconds = time.perf_counter() - t0
    if out_ext == ".svg":
        write_svg(ps, args.output)
    else:
        write_pixels(ps, args.output)
    summary = {"input": str(args.input), "output": str(args.output), **summarize(ps, model, geom=geom)}
    summary["seconds"] = seconds
    if not args.json:
        print_table(summary)
    return summary
