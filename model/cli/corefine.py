"""``mrm corefine A B [--alpha α] -o OUT``: Euclidean-discrete co-refinement EDco (EDco_α with ``--alpha``).

The three parts are A ∖ B, A ∩ B and B ∖ A, named ``a_minus_b``, ``a_and_b`` and ``b_minus_a``. What is
written depends on OUT:

* ``OUT.geojson`` / ``OUT.json``: one FeatureCollection, one Feature per part with a ``part`` property;
* ``OUT.png`` / ``OUT.npz``: the label map of the three discrete parts (1 = a_minus_b, 2 = a_and_b,
  3 = b_minus_a; on the grid scaled by α for EDco_α);
* ``OUT.wkt`` / ``OUT.svg``: one file per part, ``OUT-a_minus_b.wkt`` and so on;
* any other OUT is a prefix: ``OUT-a_minus_b.geojson``, ``OUT-a_and_b.geojson``, ``OUT-b_minus_a.geojson``.

3D inputs (voxel files, meshes: docs/design.md §11) give polyhedra: ``OUT.npz`` is the label volume of the
three discrete parts, ``OUT.obj`` / ``OUT.ply`` / ``OUT.off`` one mesh per part (``OUT-a_minus_b.obj``…), a
folder or a prefix ``.obj`` meshes.

``--json``: the info keys of the whole result (the union of the parts), ``bound`` (null: a co-refinement
part only has a one-sided bound, given per part), ``measured`` (the largest Hausdorff distance between a part
and the matching Euclidean part of A and B), and ``parts`` with each part's info keys, one-sided bound and
measured distances. The bounds and distances are those of the one account of a result
(:func:`mrm.ops.account.account_of`), which the inspector and ``mrm account`` print too; the account's
recomputation is the result written, so nothing is computed twice.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import Any

import shapely
from shapely.geometry import Polygon

from mrm.cli._common import print_table
from mrm.cli._operation import TwoInputRun, result_summary, two_input_command, write_result
from mrm.core.errors import ParameterError
from mrm.core.grids import LabelVolume, dimension_of
from mrm.io.atomic import atomic_file_set
from mrm.io.georef import geojson_members, georef_summary
from mrm.io.pixel_files import write_label_map
from mrm.io.vector_files import write_geojson, write_svg, write_wkt
from mrm.io.voxel_files import write_label_volume
from mrm.ops.boolean import PARTS, euclidean_discrete_corefinement
from mrm.ops.registry import get_operation
from mrm.ops.representations import discrete_of
from mrm.reps.summary import count_vertices, summarize

NAME = get_operation("corefine").command  # declared by the operation (mrm.ops.boolean)
HELP = "Euclidean-discrete co-refinement EDco(_α) of two objects: the parts A∖B, A∩B, B∖A"


#: The mesh files a 3D co-refinement writes, one per part (OBJ, PLY, OFF keep float64 exactly).
_MESHES = (".obj", ".ply", ".off")


def _targets(output: str, solid: bool = False) -> tuple[str, dict[str, str]]:
    """('collection' | 'labels' | 'files', part → path); ``solid``: the parts are polyhedra."""
    p = Path(output)
    default = ".obj" if solid else ".geojson"
    if output.endswith(("/", os.sep)) or p.is_dir():  # a folder: one file per part, named after the part
        return "files", {part: str(p / f"{part}{default}") for part in PARTS}
    ext = p.suffix.lower()
    if solid:
        if ext == ".npz":
            return "labels", {}
        if ext in _MESHES:
            stem = str(p.with_suffix(""))
            return "files", {part: f"{stem}-{part}{ext}" for part in PARTS}
        if ext in (".geojson", ".json", ".png", ".wkt", ".svg"):
            raise ParameterError(
                f"{output}: the parts of 3D objects are written to a label volume (.npz) or to meshes "
                f"({' '.join(_MESHES)}), one per part"
            )
        return "files", {part: f"{output}-{part}{default}" for part in PARTS}
    if ext in (".geojson", ".json"):
        return "collection", {}
    if ext in (".png", ".npz"):
        return "labels", {}
    if ext in (".wkt", ".svg"):
        stem = str(p.with_suffix(""))
        return "files", {part: f"{stem}-{part}{ext}" for part in PARTS}
    return "files", {part: f"{output}-{part}.geojson" for part in PARTS}


def _write(
    kind: str,
    files: dict[str, str],
    output: str,
    result: dict[str, Any],
    labels: Any,
    model: str,
    georef: Any = None,
) -> None:
    """Write the parts, the vector files in world coordinates when the inputs share a georeference.

    An SVG stays a picture and a label map stays on the pixel grid.
    """
    if isinstance(labels, LabelVolume):  # 3D: the label volume, or one mesh per part
        if kind == "labels":
            write_label_volume(labels, output)
        else:
            for part, path in files.items():
                write_result(result[part], path, model)
        return
    world = {part: result[part] if georef is None else georef.to_world(result[part]) for part in PARTS}
    if kind == "collection":
        members = geojson_members(georef, shapely.GeometryCollection([world[p] for p in PARTS]))
        write_geojson(
            [(part, world[part]) for part in PARTS], output, properties={"model": model}, members=members
        )
    elif kind == "labels":
        write_label_map(labels, output)
    else:
        for part, path in files.items():
            if path.endswith(".wkt"):
                write_wkt(world[part], path)
            elif path.endswith(".svg"):
                write_svg(result[part], path)
            else:
                write_geojson(
                    world[part],
                    path,
                    properties={"model": model, "part": part},
                    members=geojson_members(georef, world[part]),
                )


def _check_output(output: str, n: int) -> None:
    """Refuse an output 3D parts cannot be written to, once the inputs are read and before any work."""
    if n == 3:
        _targets(output, solid=True)


def _direct(a: Any, b: Any, model: str, params: dict[str, Any], limit: int) -> Any:
    """EDco(_α) without its account (``--no-measure``): the whole outcome, label map included."""
    return euclidean_discrete_corefinement(a.value, b.value, model, params["alpha"], limit=limit)


def _finish(args: argparse.Namespace, done: TwoInputRun) -> dict[str, Any]:
    """Write the parts and return the summary (the numbers are the model's account of the result)."""
    acc, model, alpha_json = done.account, done.model, done.params["alpha"]
    out = acc.outcome if done.computed is None else done.computed
    solid = dimension_of(out.discrete) == 3
    kind, files = _targets(str(args.output), solid)
    if files:  # a folder target is created only now, when there is something to write into it
        Path(next(iter(files.values()))).parent.mkdir(parents=True, exist_ok=True)
    with atomic_file_set():  # the parts are replaced together or not at all (issue 32)
        _write(kind, files, str(args.output), out.result, out.extra["label_map"], model, done.georef)
    summary: dict[str, Any] = {"inputs": [str(args.first), str(args.second)], "output": str(args.output)}
    summary.update(operation="corefine", alpha=alpha_json)
    if files:
        summary["files"] = files
    pixels = dict(out.extra["pixels"])
    if alpha_json is not None:  # the parts' own discretizations, on the unscaled grid
        pixels = {p: discrete_of(out.result[p], model, limit=args.limit) for p in PARTS}
    support = pixels["a_minus_b"] | pixels["a_and_b"] | pixels["b_minus_a"]
    if solid:
        summary.update(result_summary(None, support, model))
        summary["vertices"] = sum(out.result[p].n_vertices for p in PARTS)
    else:
        summary.update(summarize(support, model, geom=Polygon()))
        summary["vertices"] = sum(count_vertices(out.result[p]) for p in PARTS)
    told = acc.summary()
    summary.update(
        bound=None,
        measured=None,
        watertight=out.extra["watertight"],
        chain=told["chain"],
        input_chains=told["input_chains"],
    )
    parts: dict[str, Any] = {}
    for pa in acc.parts:
        info = result_summary(out.result[pa.part], pixels[pa.part], model)
        info.update({k: v for k, v in pa.as_dict().items() if k != "part"})
        info.update(direction=info["directions"], exact=info["measured_exact"])  # the names it had before
        parts[pa.part] = info
    if not args.no_measure:
        values = [p["measured"] for p in parts.values()]
        summary["measured"] = None if any(v is None for v in values) else max(values)
        summary["reference_exact"] = acc.reference_exact
    summary["parts"] = parts
    summary["seconds"] = done.seconds
    summary.update(georef_summary(done.georef))
    if not args.json:
        print_table({k: v for k, v in summary.items() if k not in ("parts", "chain", "input_chains")})
        for part, info in parts.items():
            print(f"{part}: {info.get('vertices')} vertices, measured {info.get('measured')}")
    return summary


# A, B, --object, --alpha (from EDco's registry spec: its help and declared range), -o, --limit, --no-measure.
add_arguments, run = two_input_command(
    "corefine",
    "OUT.geojson (one FeatureCollection), OUT.png/.npz (the label map), OUT.wkt/.svg (one file per part) "
    "or a prefix (OUT-a_minus_b.geojson, …)",
    _finish,
    _direct,
    check_output=_check_output,
)
