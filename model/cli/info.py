"""``mrm info IN``: the four representations of a pixel file, a geometry or a project, summarised.

For a project (.mrm) the summary is that of one object with ``--object NAME``; without it, that of the
union of every object's pixels, with one summary per object under ``objects``. The model is ``--model``,
else the project's, else 'standard'.
"""

from __future__ import annotations

import argparse
from typing import Any

from mrm.cli._common import (
    PROJECT_EXTENSION,
    add_limit_argument,
    discretize_geometry,
    extension_of,
    finite_float,
    load_object,
    print_table,
    project_objects,
)
from mrm.cli._project_input import add_object_argument
from mrm.errors import ParameterError
from mrm.io.pixel_files import PIXEL_EXTENSIONS
from mrm.io.vector_files import VECTOR_EXTENSIONS
from mrm.reps.pixels import PixelSet
from mrm.summary import summarize

NAME = "info"
HELP = "summarise the four representations of a pixel, vector or project file"

INPUTS = (*PIXEL_EXTENSIONS, *VECTOR_EXTENSIONS, PROJECT_EXTENSION)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the input, ``--object``, ``--threshold`` and ``--limit``."""
    parser.add_argument("input", metavar="IN", help="a pixel (.png .pbm .pgm .npz), vector or project file")
    add_object_argument(parser)
    parser.add_argument(
        "--threshold",
        type=finite_float,
        default=None,
        metavar="T",
        help="grey images: pixels brighter than T are in the set (default: binary images as they are, "
        "others at Otsu's threshold)",
    )
    add_limit_argument(parser)


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Read the input and return its summary (see :func:`mrm.summary.summarize`)."""
    ext = extension_of(args.input, INPUTS, "supported input file")
    if args.threshold is not None and ext not in PIXEL_EXTENSIONS:
        raise ParameterError(f"{args.input}: --threshold applies to image inputs only")
    if ext == PROJECT_EXTENSION and args.object is None:
        objects, project_model = project_objects(args.input)
        summary = _project_summary(objects, args.model or project_model, args.limit)
    else:
        kind, value, model = load_object(
            args.input, args.object, args.model, threshold=args.threshold, limit=args.limit
        )
        summary = _summary(value, model, args.limit)
        if args.object is not None:
            summary = {"object": args.object, "source": kind, **summary}
    summary = {"input": str(args.input), **summary}
    if not args.json:
        print_table(summary)
    return summary


def _summary(source: Any, model: str, limit: int) -> dict[str, Any]:
    """The summary of one object given by its source: pixels, or a geometry (discretized under ``model``)."""
    if isinstance(source, PixelSet):
        return summarize(source, model)
    return summarize(discretize_geometry(source, model, limit), model, geom=source)


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
    if all_euclidean:
        from mrm.io.vector_files import combine

        summary = summarize(union, model, geom=combine([o.source for o in objects]))
    else:
        summary = summarize(union, model)
    summary["objects"] = per_object
    return summary
