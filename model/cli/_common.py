"""Helpers shared by the ``mrm`` subcommands: reading any input, argument types, the text table.

(A module whose name starts with "_" is not a subcommand.)
"""

from __future__ import annotations

import argparse
import os
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from model.errors import DEFAULT_PIXEL_LIMIT, FileFormatError
from model.io.pixel_files import PIXEL_EXTENSIONS, read_pixels
from model.io.vector_files import VECTOR_EXTENSIONS, combine, read_geometry
from model.reps.pixels import PixelSet
from model.summary import optional_function

PROJECT_EXTENSION = ".mrm"


@dataclass
class Input:
    """What a subcommand read: a geometry, a pixel set, or the objects of a project.

    Attributes
    ----------
    kind : {"euclidean", "discrete", "project"}
    geometry : shapely geometry or None
        The Euclidean input; for a project, its Euclidean objects combined (None if it has none).
    pixels : PixelSet or None
        The discrete input; for a project, None (its objects are discretized under the chosen model).
    model : str or None
        The project's model, else None.
    objects : list
        A project's objects (``model.document.DocObject``), else empty.
    """

    kind: str
    geometry: Any = None
    pixels: PixelSet | None = None
    model: str | None = None
    objects: list[Any] = field(default_factory=list)


def positive_int(text: str) -> int:
    """Argparse type: an integer ≥ 1 (underscores allowed, e.g. 200_000_000)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    return value


def add_limit_argument(parser: argparse.ArgumentParser) -> None:
    """Add ``--limit N``, the largest result (in pixels) a command may create."""
    parser.add_argument(
        "--limit",
        type=positive_int,
        default=DEFAULT_PIXEL_LIMIT,
        metavar="N",
        help=f"largest number of pixels of an image or result (default {DEFAULT_PIXEL_LIMIT:_})",
    )


def extension_of(path: str | os.PathLike[str], allowed: tuple[str, ...], what: str) -> str:
    """Return the lower-case extension of ``path`` or raise a FileFormatError listing ``allowed``."""
    ext = Path(path).suffix.lower()
    if ext not in allowed:
        shown = f"'{ext}'" if ext else "no extension"
        raise FileFormatError(f"{os.fspath(path)}: {shown} is not a {what}; use {', '.join(allowed)}")
    return ext


def read_project_input(path: str | os.PathLike[str]) -> Input:
    """Read a project file with :func:`model.io.project.load_project`, if that exists yet."""
    load_project = optional_function("model.io.project", "load_project")
    if load_project is None:
        raise FileFormatError(f"{os.fspath(path)}: project files (.mrm) are not supported yet")
    doc = load_project(path)
    objects = list(doc.objects)
    euclidean = [o.source for o in objects if not isinstance(o.source, PixelSet)]
    geom = combine(euclidean) if euclidean else None
    return Input("project", geometry=geom, model=str(doc.model), objects=objects)


def read_input(
    path: str | os.PathLike[str],
    allowed: tuple[str, ...],
    *,
    threshold: float | None = None,
    limit: int = DEFAULT_PIXEL_LIMIT,
) -> Input:
    """Read a pixel file, a vector file or a project, chosen by the extension (one of ``allowed``)."""
    ext = extension_of(path, allowed, "supported input file")
    if ext == PROJECT_EXTENSION:
        return read_project_input(path)
    if ext in PIXEL_EXTENSIONS:
        return Input("discrete", pixels=read_pixels(path, threshold=threshold, limit=limit))
    if ext in VECTOR_EXTENSIONS:
        return Input("euclidean", geometry=read_geometry(path))
    raise FileFormatError(f"{os.fspath(path)}: cannot read {ext} files")  # unreachable with sane ``allowed``


def discretize_geometry(geom: Any, model: str, limit: int) -> PixelSet:
    """D(geom) under ``model`` with :func:`model.geometry.discretize.discretize`."""
    from model.geometry.discretize import discretize

    return discretize(geom, model, limit=limit)


_LABELS = {
    "boundary_chains": "boundary chains",
    "bbox": "bounding box",
}


def _shown(value: Any) -> str:
    if value is None:
        return "–"
    if isinstance(value, float):
        return f"{value:.3f}"
    if isinstance(value, list | tuple):
        return " ".join(str(v) for v in value)
    return str(value)


def print_table(summary: dict[str, Any], keys: list[str] | None = None) -> None:
    """Print ``summary`` as a two-column table on stdout (None shows as "–")."""
    rows = [
        (k, summary[k]) for k in (keys or list(summary)) if k in summary and not isinstance(summary[k], dict)
    ]
    rows = [(k, v) for k, v in rows if not (isinstance(v, list) and v and isinstance(v[0], dict))]
    width = max((len(_LABELS.get(k, k)) for k, _ in rows), default=0)
    for k, v in rows:
        print(f"{_LABELS.get(k, k):<{width}}  {_shown(v)}", file=sys.stdout)
