"""Helpers shared by the ``mrm`` subcommands: argument types, reading inputs, the text table.

Subcommands that take one object read it with :func:`load_object` (a thin layer over
:func:`mrm.cli._project_input.load_input`, which picks a project's object with ``--object NAME``);
:func:`project_objects` gives every object of a project, for the commands that can take them all.
:func:`read_input` is the older all-objects reader, kept for the commands that still use it.

(A module whose name starts with "_" is not a subcommand.)
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mrm.cli._project_input import PROJECT_EXTENSIONS, Kind, load_input
from mrm.errors import DEFAULT_PIXEL_LIMIT, FileFormatError
from mrm.io.pixel_files import PIXEL_EXTENSIONS, read_pixels
from mrm.io.vector_files import VECTOR_EXTENSIONS, combine, read_geometry
from mrm.reps.pixels import PixelSet

PROJECT_EXTENSION = PROJECT_EXTENSIONS[0]


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
        A project's objects (``mrm.document.DocObject``), else empty.
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


def finite_float(text: str) -> float:
    """Argparse type: a finite number (for ``--threshold``)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
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


def project_objects(path: str | os.PathLike[str]) -> tuple[list[Any], str]:
    """Every object of a project file (``mrm.document.DocObject``, in document order) and its model."""
    from mrm.io.project import read_project

    proj = read_project(path)
    return list(proj.objects), str(proj.settings.model)


def load_object(
    path: str | os.PathLike[str],
    object_name: str | None = None,
    model: str | None = None,
    *,
    threshold: float | None = None,
    limit: int = DEFAULT_PIXEL_LIMIT,
) -> tuple[Kind, Any, str]:
    """Read one object: a pixel file, a vector file, or the object ``object_name`` of a project.

    Returns ``(kind, value, model)`` as :func:`mrm.cli._project_input.load_input` does (value in its
    source representation; model the one asked for, else the project's, else 'standard'), with ``limit``
    also bounding the size of an image read from a pixel file.
    """
    if object_name is None and Path(path).suffix.lower() in PIXEL_EXTENSIONS:
        # load_input reads images under the default limit only; read them here so that --limit applies.
        return "discrete", read_pixels(path, threshold=threshold, limit=limit), model or "standard"
    return load_input(path, object_name, model, threshold=threshold)


def read_project_input(path: str | os.PathLike[str]) -> Input:
    """Read every object of a project file; its Euclidean objects combined as ``geometry``."""
    objects, model = project_objects(path)
    euclidean = [o.source for o in objects if not isinstance(o.source, PixelSet)]
    geom = combine(euclidean) if euclidean else None
    return Input("project", geometry=geom, model=model, objects=objects)


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
    """D(geom) under ``model`` with :func:`mrm.geometry.discretize.discretize`."""
    from mrm.geometry.discretize import discretize

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
