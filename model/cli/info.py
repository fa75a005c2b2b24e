"""``mrm info IN...``: the four representations of a pixel file, a geometry or a project, summarised.

Several inputs (files, directories, quoted globs; ``--jobs N`` workers) print one line per input as soon as
it is done; ``--json`` then gives ``{"inputs": n, "files": [summary, …]}`` in input order.

3D inputs: a voxel file (.npz holding a 3-D mask, a multi-page .tif/.tiff, .nii, .nii.gz; ``--threshold``
for grey volumes) gives the keys of :func:`mrm.reps.summary.summarize_voxels` — ``voxels``, ``components``,
``cavities``, ``tunnels``, ``euler``, ``surfels``, ``plane_segments`` (the greedy digital plane segments of
the surfaces), and the ``faces`` and ``vertices`` of R(A); a mesh file (.obj .ply .off .stl) gives those of
its voxelization D under the model, with the ``faces`` and ``vertices`` of the polyhedron itself.

A label volume (an .npz holding ``labels``, or any voxel file with ``--labels``) gives ``model``,
``labels`` (distinct non-zero labels), ``regions`` (6-connected components of one label), ``voxels``
(non-zero), ``bbox``, ``two_cells``, ``one_cells``, ``zero_cells`` and ``adjacencies`` (pairs of 6-adjacent
labels, background included) of :func:`mrm.reps.cells_3d.cells_3d_of`.

For a project (.mrm) the summary is that of one object with ``--object NAME``; without it, that of the
union of every object's pixels, with one summary per object under ``objects``. The model is ``--model``,
else the project's, else 'standard'. A label map object (ADR 0033) is summarised as the 3D label volumes are,
in the plane: ``model``, ``labels``, ``regions`` (4-connected components of one label), ``pixels``
(non-zero), ``bbox``, ``one_cells``, ``zero_cells`` and ``adjacencies`` (pairs of 4-adjacent labels,
background included) of :func:`mrm.reps.cells.cells_of`; its non-zero pixels count in the project's union.
"""

from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path
from typing import Any

import numpy as np

from mrm.cli._common import (
    PROJECT_EXTENSION,
    add_image_arguments,
    add_inputs_argument,
    add_jobs_argument,
    add_limit_argument,
    discretize_geometry,
    expand_inputs,
    extension_of,
    has_extension,
    is_3d_input,
    load_object,
    pixel_limit,
    project_objects,
    read_voxel_input,
    refuse_failures,
    run_inputs,
    voxel_limit,
)
from mrm.cli._project_input import add_object_argument
from mrm.core.errors import LimitError, ParameterError
from mrm.core.grids import LabelMap, LabelVolume, PixelSet, VoxelSet, dimension_of
from mrm.core.limits import MAX_LABEL_COUNT_BYTES
from mrm.core.models import Model
from mrm.geometry.discretize.voxels import voxelize
from mrm.geometry.reconstruct import reconstruct_voxels
from mrm.io.mesh_files import MESH_EXTENSIONS, read_mesh
from mrm.io.pixel_files import PIXEL_EXTENSIONS
from mrm.io.vector_files import VECTOR_EXTENSIONS, combine
from mrm.io.voxel_files import VOXEL_EXTENSIONS, read_label_volume
from mrm.reps.cells import cell_counts
from mrm.reps.cells_3d import cells_3d_of
from mrm.reps.summary import summarize, summarize_voxels

log = logging.getLogger(__name__)

NAME = "info"
HELP = (
    "summarise the four representations of a pixel, vector or project file, "
    "or in 3D of a voxel file (.npz .tif .nii .nii.gz) or a mesh (.obj .ply .off .stl)"
)

_2D = (*PIXEL_EXTENSIONS, *VECTOR_EXTENSIONS, PROJECT_EXTENSION)
INPUTS = tuple(dict.fromkeys((*_2D, *VOXEL_EXTENSIONS, *MESH_EXTENSIONS)))


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the inputs, ``--object``, ``--jobs``, ``--threshold``, ``--invert`` and ``--limit``."""
    add_inputs_argument(
        parser,
        "pixel (.png .pbm .pgm .npz .tif), vector or project files; 3D: voxel files (.npz .tif .nii .nii.gz) "
        "or meshes (.obj .ply .off .stl)",
    )
    add_object_argument(parser)
    add_jobs_argument(parser)
    add_image_arguments(parser)
    add_limit_argument(parser, voxels=True)
    parser.add_argument(
        "--labels",
        action="store_true",
        help="3D: read a voxel file as a label volume (0 = background; automatic for an .npz holding "
        "'labels')",
    )


def info_file(
    path: str,
    object_name: str | None,
    model: str | None,
    threshold: float | None,
    invert: bool,
    limit: int | None,
    labels: bool = False,
) -> dict[str, Any]:
    """The summary of one input (a module-level function: batch workers call it)."""
    ext = extension_of(path, INPUTS, "supported input file")
    if is_3d_input(path):
        if object_name is not None and ext != ".obj":
            raise ParameterError(f"{path}: --object applies to project (.mrm) and OBJ files only")
        if labels or _holds_labels(path):
            if threshold is not None or invert:
                raise ParameterError(f"{path}: --threshold and --invert do not apply to label volumes")
            return {"input": str(path), **label_volume_info(path, model or "standard", limit)}
        summary = info_3d(path, model or "standard", threshold, invert, limit, object_name)
        return {"input": str(path), **({"object": object_name} if object_name else {}), **summary}
    if labels:
        raise ParameterError(f"{path}: --labels applies to voxel files (.npz .tif .nii .nii.gz) only")
    limit = pixel_limit(limit)
    if (threshold is not None or invert) and ext not in PIXEL_EXTENSIONS:
        raise ParameterError(f"{path}: --threshold and --invert apply to image inputs only")
    if ext == PROJECT_EXTENSION and object_name is None:
        objects, project_model = project_objects(path)
        summary = _project_summary(objects, model or project_model, limit)
    else:
        kind, value, chosen = load_object(
            path, object_name, model, threshold=threshold, invert=invert, limit=limit
        )
        summary = _summary(value, chosen, limit)
        if object_name is not None:
            summary = {"object": object_name, "source": kind, **summary}
    return {"input": str(path), **summary}


def info_3d(
    path: str,
    model: str,
    threshold: float | None,
    invert: bool,
    limit: int | None,
    object_name: str | None = None,
) -> dict[str, Any]:
    """The 3D summary of a voxel file (R(A) gives faces and vertices) or of a mesh (D under ``model``).

    ``object_name`` picks one object of an OBJ mesh (:func:`mrm.read_mesh`).
    """
    if invert:
        raise ParameterError(f"{path}: --invert applies to 2D images only")
    if Path(path).suffix.lower() in MESH_EXTENSIONS:
        if threshold is not None:
            raise ParameterError(f"{path}: --threshold applies to images and voxel files only")
        return summary_3d(read_mesh(path, object_name=object_name), model, limit, path)
    return summary_3d(read_voxel_input(path, threshold, limit), model, limit, path)


def summary_3d(source: Any, model: str, limit: int | None, what: str) -> dict[str, Any]:
    """The 3D summary of a voxel set (R(A) gives faces and vertices) or a polyhedron (D under ``model``)."""
    if not isinstance(source, VoxelSet):  # a polyhedron: its own faces and vertices, its voxels D(P)
        vs = voxelize(source, model, limit=voxel_limit(limit))
        return summarize_voxels(vs, model, faces=source.n_faces, vertices=source.n_vertices)
    try:
        poly = reconstruct_voxels(source, model)
    except LimitError as e:
        # The discrete and region summaries stand without R: say why faces and vertices are missing.
        log.info("no continuation for %s: %s", what, e)
        print(f"mrm info: warning: {e}; faces and vertices not computed", file=sys.stderr, flush=True)
        return summarize_voxels(source, model, faces=None, vertices=None)
    return summarize_voxels(source, model, faces=poly.n_faces, vertices=poly.n_vertices)


def _holds_labels(path: str) -> bool:
    """True for an .npz voxel file holding ``labels`` (a label volume by its content, never a mask)."""
    if not has_extension(path, (".npz",)):
        return False
    import zipfile

    try:
        with zipfile.ZipFile(path) as zf:
            return "labels.npy" in zf.namelist() and "mask.npy" not in zf.namelist()
    except (OSError, zipfile.BadZipFile):
        return False  # the voxel reader says what is wrong


def label_volume_info(path: str, model: str, limit: int | None) -> dict[str, Any]:
    """The summary of a label volume: its labels, regions, cells and adjacencies."""
    return label_volume_summary(read_label_volume(path, limit=limit), model, limit)


def label_volume_summary(lv: LabelVolume, model: str, limit: int | None) -> dict[str, Any]:
    """A label volume's labels, regions, cells and adjacencies (a file's or a project object's)."""
    Model.parse(model)
    cells = cells_3d_of(lv.labels, lv.origin, limit=voxel_limit(limit))
    bbox = lv.bbox
    return {
        "model": model,
        "labels": len(lv.label_values()),
        "regions": len(cells.regions),
        "voxels": int(np.count_nonzero(lv.labels)),
        "bbox": None if bbox is None else list(bbox),
        "two_cells": len(cells.two_cells),
        "one_cells": len(cells.one_cells),
        "zero_cells": len(cells.zero_cells),
        "adjacencies": len(cells.adjacency),
    }


def label_map_info(lm: LabelMap, model: str, held: int | None = None) -> dict[str, Any]:
    """The summary of a label map: labels, regions, cells and adjacencies (as :func:`label_volume_info`).

    ``held``: the bytes of grids the summary already holds (the map's own labels by default, a whole
    project's grids for a project); the counting gets what :data:`MAX_LABEL_COUNT_BYTES` leaves of them.
    """
    Model.parse(model)
    counts: Any = None
    held = lm.labels.nbytes if held is None else held
    try:  # counted with arrays: cells_of's objects take gigabytes on a checkerboard
        counts = cell_counts(lm, budget=max(0, MAX_LABEL_COUNT_BYTES - held))
    except LimitError as e:
        log.info("no cell counts: %s", e)
        print(f"mrm info: warning: {e}; regions and cells not counted", file=sys.stderr, flush=True)
    bbox = lm.bbox
    return {
        "model": model,
        "labels": len(lm.label_values()),
        "regions": None if counts is None else counts.regions,
        "pixels": int(np.count_nonzero(lm.labels)),
        "bbox": None if bbox is None else list(bbox),
        "one_cells": None if counts is None else counts.one_cells,
        "zero_cells": None if counts is None else counts.zero_cells,
        "adjacencies": None if counts is None else counts.adjacencies,
    }


def _line(s: dict[str, Any]) -> str:
    if "regions" in s:
        size = f"{s['voxels']} voxels" if "voxels" in s else f"{s['pixels']} pixels"
        return f"{s['input']}: {s['labels']} labels, {s['regions']} regions, {size}"
    if "voxels" in s:
        return (
            f"{s['input']}: {s['voxels']} voxels, {s['components']} components, {s['cavities']} cavities, "
            f"{s['tunnels']} tunnels, {s['faces']} faces"
        )
    return (
        f"{s['input']}: {s['pixels']} pixels, {s['components']} components, {s['holes']} holes, "
        f"{s['vertices']} vertices"
    )


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Read the inputs and return the summary (see :func:`mrm.reps.summary.summarize`)."""
    inputs = expand_inputs([str(i) for i in args.inputs], INPUTS)
    jobs = [
        (i, args.object, args.model, args.threshold, args.invert, args.limit, args.labels) for i in inputs
    ]

    def total(files: list[dict[str, Any]], errors: list[str]) -> dict[str, Any]:
        refuse_failures(errors, len(jobs))
        return {"inputs": len(jobs), "files": files}

    return run_inputs(args, info_file, jobs, _line, total, first=f"info {inputs[0]}")


def _summary(source: Any, model: str, limit: int) -> dict[str, Any]:
    """The summary of one object given by its source.

    Pixels, a label map, a geometry (discretized), or a 3D object (voxels, a polyhedron, a label volume: the
    3D keys).
    """
    if isinstance(source, LabelVolume):
        return label_volume_summary(source, model, None)
    if dimension_of(source) == 3:
        return summary_3d(source, model, None, "a 3D object")
    if isinstance(source, PixelSet):
        return summarize(source, model)
    if isinstance(source, LabelMap):
        return label_map_info(source, model)
    return summarize(discretize_geometry(source, model, limit), model, geom=source)


def _project_summary(objects: list[Any], model: str, limit: int) -> dict[str, Any]:
    """The union of every plane object's pixels, plus one summary per object under ``objects``.

    A 3D object is listed with the 3D keys of its own (voxels, components, cavities…); the project's
    ``voxels`` counts the union of their voxels.
    """
    per_object = []
    union = PixelSet.empty()
    solids = VoxelSet.empty()
    # The grids the loaded project holds: what the label maps' counting must share the budget with.
    held = sum(o.source.labels.nbytes for o in objects if isinstance(o.source, LabelMap)) + sum(
        o.source.mask.nbytes for o in objects if isinstance(o.source, PixelSet)
    )
    for obj in objects:
        head = {"id": obj.id, "name": obj.name, "source": obj.kind}
        if isinstance(obj.source, LabelVolume):
            per_object.append({**head, **label_volume_summary(obj.source, model, None)})
            continue
        if obj.dimension == 3:
            one = summary_3d(obj.source, model, None, obj.name)
            solids = solids | (
                obj.source if isinstance(obj.source, VoxelSet) else voxelize(obj.source, model)
            )
            per_object.append({**head, **one})
            continue
        if isinstance(obj.source, LabelMap):
            union = union | obj.source.support()
            per_object.append({**head, **label_map_info(obj.source, model, held)})
            continue
        if isinstance(obj.source, PixelSet):
            ps, geom = obj.source, None
        else:
            ps, geom = discretize_geometry(obj.source, model, limit), obj.source
        union = union | ps
        per_object.append({**head, **summarize(ps, model, geom=geom)})
    plane = [o for o in objects if o.dimension == 2]
    all_euclidean = bool(plane) and all(o.kind == "euclidean" for o in plane)
    if all_euclidean:
        summary = summarize(union, model, geom=combine([o.source for o in plane]))
    else:
        summary = summarize(union, model)
    if len(plane) < len(objects):
        summary["voxels"] = len(solids)
    summary["objects"] = per_object
    return summary
