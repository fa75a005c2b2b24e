"""Input files of the ``mrm`` subcommands: pixel files, vector files, or an object of a project.

Every subcommand reads its inputs through :func:`load_input`, so each one accepts a project (``.mrm``) as
well as the plain files, with ``--object NAME`` (:func:`add_object_argument`) to pick an object::

    kind, value, model = load_input(args.input, args.object, args.model)
    # kind == "discrete": value is a PixelSet;  kind == "euclidean": value is a shapely geometry

``want=`` converts to the representation the subcommand needs (D or R under the model in force), so
``mrm reconstruct project.mrm --object triangle`` works for a Euclidean object too.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import Any, Literal

from mrm.core.errors import FileFormatError, ParameterError
from mrm.geometry.discretize import discretize
from mrm.geometry.reconstruct import reconstruct
from mrm.io.pixel_files import read_pixels
from mrm.io.project import read_project
from mrm.io.vector_files import read_geometry

Kind = Literal["discrete", "euclidean"]

#: Extensions of pixel files and of vector files.
PIXEL_EXTENSIONS = (".png", ".pbm", ".pgm", ".npz", ".tif", ".tiff")
VECTOR_EXTENSIONS = (".geojson", ".json", ".wkt")
PROJECT_EXTENSIONS = (".mrm",)


def add_object_argument(parser: argparse.ArgumentParser) -> None:
    """Add ``--object NAME`` (which object of a project input, or of an OBJ mesh, to use)."""
    parser.add_argument(
        "--object",
        metavar="NAME",
        default=None,
        help="for a project (.mrm) input: the name of the object to use (needed when it holds several); "
        "for an OBJ mesh: one of its objects ('o NAME', as mrm polygonize writes a label volume's regions)",
    )


def _pick(objects: list[Any], object_name: str | None, name: str) -> Any:
    names = [o.name for o in objects]
    if not objects:
        raise ParameterError(f"{name}: the project holds no object")
    if object_name is None:
        if len(objects) == 1:
            return objects[0]
        raise ParameterError(
            f"{name}: the project holds {len(objects)} objects; choose one with --object NAME "
            f"({_list(names)})"
        )
    found = [o for o in objects if o.name == object_name]
    if not found:
        raise ParameterError(f"{name}: no object named {object_name!r}; the project holds {_list(names)}")
    if len(found) > 1:
        raise ParameterError(
            f"{name}: {len(found)} objects are named {object_name!r}; rename them in MR Modeler to pick one"
        )
    return found[0]


def project_object(path: Path, object_name: str | None, model: str | None) -> tuple[Any, str, int]:
    """The object ``object_name`` of a project file (read once), the model in force and its compact limit.

    The object is a :class:`mrm.document.DocObject`, so a caller also gets its id, provenance and
    georeference; the model is ``model`` if given, else the project's; the compact limit is the project's
    (``Settings.compact_limit``: what its R of voxel sets simplifies, ADR 0073).
    """
    proj = read_project(path)
    return (
        _pick(proj.objects, object_name, path.name),
        model or proj.settings.model,
        proj.settings.compact_limit,
    )


def _list(names: list[str], limit: int = 12) -> str:
    shown = ", ".join(repr(n) for n in names[:limit])
    return shown + (f" and {len(names) - limit} more" if len(names) > limit else "")


def load_input(
    path: str | os.PathLike[str],
    object_name: str | None = None,
    model: str | None = None,
    *,
    want: Kind | None = None,
    threshold: float | None = None,
) -> tuple[Kind, Any, str]:
    """Read a subcommand's input.

    Parameters
    ----------
    path : str or path-like
        A pixel file (.png .pbm .pgm .npz), a vector file (.geojson .json .wkt) or a project (.mrm).
    object_name : str, optional
        For a project: the object's name (required when the project holds several objects). Refused for
        other files.
    model : str, optional
        The discretization model asked for on the command line; default: the project's, else 'standard'.
    want : {'discrete', 'euclidean'}, optional
        Convert to this representation: D(geometry) or R(pixels) under the model.
    threshold : float, optional
        Threshold for grey images (see :func:`mrm.io.pixel_files.read_pixels`).

    Returns
    -------
    kind : {'discrete', 'euclidean'}
        What ``value`` is.
    value : PixelSet or shapely geometry
        For a project object, its source representation (unless ``want`` converts it).
    model : str
        The model in force.

    Raises
    ------
    MRMError
        Unknown file type, unreadable file, no or ambiguous object (the message lists the names).
    """
    p = Path(path)
    ext = p.suffix.lower()
    if not p.exists():
        raise FileNotFoundError(2, "No such file", os.fspath(path))
    kind: Kind
    value: Any
    if ext in PROJECT_EXTENSIONS:
        obj, model, _ = project_object(p, object_name, model)
        kind, value = obj.kind, obj.source
    else:
        if object_name is not None:
            raise ParameterError(f"{p.name}: --object applies to project (.mrm) files only")
        model = model or "standard"
        if ext in PIXEL_EXTENSIONS:
            kind, value = "discrete", read_pixels(p, threshold=threshold)
        elif ext in VECTOR_EXTENSIONS:
            kind, value = "euclidean", read_geometry(p)
        else:
            shown = f"'{ext}'" if ext else "no extension"
            raise FileFormatError(
                f"{p.name}: {shown} is not an input type; use "
                + ", ".join(PIXEL_EXTENSIONS + VECTOR_EXTENSIONS + PROJECT_EXTENSIONS)
            )
    if want is not None and want != kind:
        value = discretize(value, model) if want == "discrete" else reconstruct(value, model)
        kind = want
    return kind, value, model
