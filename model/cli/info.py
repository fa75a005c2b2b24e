"""``mrm info IN``: the four representations of a pixel file, a geometry or a project, summarised."""

from __future__ import annotations

import argparse
import math
from typing import Any

from model.cli._common import (
    PROJECT_EXTENSION,
    add_limit_argument,
    discretize_geometry,
    extension_of,
    print_table,
    read_input,
)
from model.errors import ParameterError
from model.io.pixel_files import PIXEL_EXTENSIONS
from model.io.vector_files import VECTOR_EXTENSIONS
from model.reps.pixels import PixelSet
from model.summary import summarize

NAME = "info"
HELP = "summarise the four representations of a pixel, vector or project file"

INPUTS = (*PIXEL_EXTENSIONS, *VECTOR_EXTENSIONS, PROJECT_EXTENSION)


def _threshold(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return value


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the input, ``--threshold`` and ``--limit``."""
    parser.add_argument("input", metavar="IN", help="a pixel (.png .pbm .pgm .npz), vector or project file")
    parser.add_argument(
        "--threshold",
        type=_threshold,
        default=None,
        metavar="T",
        help="grey images: pixels brighter than T are in the set (default: binary images as they are, "
        "others at Otsu's threshold)",
    )
    add_limit_argument(parser)


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Read the input and return its summary (see :func:`model.summary.summarize`)."""
    ext = extension_of(args.input, INPUTS, "supported input file")
    if args.threshold is not None and ext not in PIXEL_EXTENSIONS:
        raise ParameterError(f"{args.input}: --threshold applies to image inputs only")
    src = read_input(args.input, INPUTS, threshold=args.threshold, limit=args.limit)
    model = args.model or src.model or "standard"
    if src.kind == "discrete":
        assert src.pixels is not None
        summary = summarize(src.pixels, model)
    elif src.kind == "euclidean":
        summary = summarize(discretize_geometry(src.geometry, model, args.limit), model, geom=src.geometry)
    else:
        summary = _project_summary(src.objects, model, args.limit)
    summary = {"input": str(args.input), **summary}
    if not args.json:
        print_table(summary)
    return summary


def _project_summary(objects: list[Any], model: str, limit: int) -> dict[str, Any]:
    """The union of every object's pixels, plus one summary per object under ``objects``."""
    per_object = []
    union = PixelSet.empty()
    for obj in objects:
        if isinstance(obj.source, PixelSet):
            ps, geom = obj.source, None
        else:
            ps, geom = discretize_geometry(obj.source, model, limit), obj.source
        union = union | ps
        per_object.append(
            {"id": obj.id, "name": obj.name, "source": obj.kind, **summarize(ps, model, geom=geom)}
        )
    all_euclidean = bool(objects) and all(not isinstance(o.source, PixelSet) for o in objects)
    geoms = [o.source for o in objects] if all_euclidean else None
    if geoms is not None:
        from model.io.vector_files import combine

        summary = summarize(union, model, geom=combine(geoms))
    else:
        summary = summarize(union, model)
    summary["objects"] = per_object
    return summary
