"""``mrm reconstruct IN... -o OUT``: the reversible continuation R of pixel files, written as vectors.

One input: ``OUT`` is the file to write (.geojson, .json, .wkt or .svg). Several inputs: ``OUT`` is either a
directory (existing, or a path ending with a separator or without an extension: it is created), where each
input ``NAME.png`` gives ``NAME.geojson``, or a pattern holding ``{stem}`` (the input's name without its
extension), e.g. ``out/{stem}-R.wkt``. Inputs may be directories (their pixel files) and quoted globs;
``--jobs N`` spreads them over N worker processes (at most the CPU count) and each input's line is printed
as soon as it is done. ``-`` reads standard input and ``-o -`` writes on standard output.
``--features components`` writes one GeoJSON Feature per 4-connected component (property ``part``).

Inputs are pixel files (.png .pbm .pgm .npz: grey images are cut at Otsu's threshold unless
``--threshold`` is given; ``--invert`` takes the dark pixels) or projects (.mrm: the union of their
objects' pixels under the model).
3D: a voxel file (.npz holding a 3-D mask, a multi-page .tif/.tiff, .nii, .nii.gz; ``--threshold`` for grey
volumes) gives R(A), a closed polyhedron with D(R(A)) = A in the chosen model, written as a triangle mesh
(.obj, .ply, .off exactly; .stl rounds to float32 and warns on stderr). OBJ and OFF hold one polygon per
face where a polygon can (its fan of triangles, as readers make of it, covers the face exactly), the face's
triangles otherwise; PLY and STL hold triangles; ``--triangles`` writes triangles to every format. Its
``--json`` summary holds the 3D keys of
``mrm info`` (``voxels``, ``components``, ``cavities``, ``tunnels``, ``euler``, ``surfels``,
``plane_segments``, ``faces``, ``vertices``) plus ``r`` (how R was made: ``grown hull``, ``spiked hull``,
``snapped core``, ``decimation`` or ``safety net``; the last is also noted on stderr, since it is not
compact), ``seconds``, ``input`` and ``output``.

``--json`` prints, for one 2D input, the info keys of the result (``model``, ``pixels``, ``components``,
``holes``, ``euler``, ``boundary_chains``, ``segments``, ``vertices``) plus ``seconds`` (the time R took),
``input`` and ``output``; for several inputs, the same keys summed over the inputs plus ``files``, the list
of the per-input summaries.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

from mrm.cli._common import (
    PROJECT_EXTENSION,
    add_batch_arguments,
    add_image_arguments,
    add_limit_argument,
    batch_total,
    compact_limit_int,
    discretize_geometry,
    extension_of,
    inputs_and_outputs,
    interruptible,
    is_3d_input,
    pixel_limit,
    read_input,
    read_voxel_input,
    run_inputs,
)
from mrm.core import limits
from mrm.core.errors import FileFormatError, ParameterError
from mrm.core.grids import PixelSet
from mrm.core.limits import check_reconstruct
from mrm.geometry.reconstruct import reconstruct, reconstruct_voxels_detailed
from mrm.io.georef import geojson_members, georef_summary, read_georef
from mrm.io.mesh_files import MESH_EXTENSIONS, write_mesh
from mrm.io.pixel_files import PIXEL_EXTENSIONS
from mrm.io.vector_files import (
    MAX_VECTOR_FILE_BYTES,
    VECTOR_EXTENSIONS,
    write_geojson,
    write_svg,
    write_wkt,
)
from mrm.io.voxel_files import VOXEL_EXTENSIONS
from mrm.reps.summary import count_vertices, summarize, summarize_voxels

NAME = "reconstruct"
HELP = (
    "reversible continuation of pixel files (.png .pbm .pgm .npz .mrm) into polygons (.geojson .wkt .svg), "
    "and in 3D of voxel files (.npz .tif .nii .nii.gz) into meshes (.obj .ply .off)"
)

INPUTS = tuple(dict.fromkeys((*PIXEL_EXTENSIONS, PROJECT_EXTENSION, *VOXEL_EXTENSIONS)))
OUTPUTS = (*VECTOR_EXTENSIONS, ".svg", *MESH_EXTENSIONS)
_SUM_KEYS = ("pixels", "components", "holes", "euler", "boundary_chains", "segments", "vertices", "seconds")
_SUM_KEYS_3D = (
    *("voxels", "components", "cavities", "tunnels", "euler", "surfels", "faces", "vertices", "seconds"),
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the inputs, ``-o OUT``, ``--jobs``, ``--threshold``, ``--invert`` and ``--limit``."""
    add_batch_arguments(
        parser,
        "pixel files (.png .pbm .pgm .npz) or projects (.mrm); 3D: voxel files (.npz .tif .nii .nii.gz)",
        "the vector file (.geojson .json .wkt .svg); for a voxel input the mesh file (.obj .ply .off; .stl "
        "rounds to float32)",
    )
    add_image_arguments(parser)
    parser.add_argument(
        "--features",
        choices=("one", "components"),
        default="one",
        help="GeoJSON: one Feature holding everything (default), or one Feature per 4-connected component "
        "(keeps large results within GDAL's object size limit)",
    )
    parser.add_argument(
        "--triangles",
        action="store_true",
        help="3D: write the mesh's triangles (default: one polygon per face in OBJ and OFF)",
    )
    parser.add_argument(
        "--compact-limit",
        type=compact_limit_int,
        metavar="N",
        help="3D: the most triangles of a safety net that R simplifies into a compact polyhedron (default "
        f"{limits.MAX_COMPACT_R_TRIANGLES:_}, about a ball of radius 30; the simplification takes about "
        "40-150 µs per triangle); beyond, R is the safety net: exact, not compact",
    )
    add_limit_argument(parser, voxels=True)


def _pixels_of(
    path: str, threshold: float | None, limit: int, model: str | None, invert: bool = False
) -> tuple[PixelSet, str]:
    src = read_input(path, INPUTS, threshold=threshold, invert=invert, limit=limit)
    chosen = model or src.model or "standard"
    if src.kind == "discrete":
        assert src.pixels is not None
        return src.pixels, chosen
    if threshold is not None or invert:
        raise ParameterError("--threshold and --invert apply to image inputs only")

    three_d = [obj.name for obj in src.objects if obj.dimension == 3]
    if three_d:  # a project's 3D objects: not yet an input here (their R is in the desktop and in .npz files)
        raise ParameterError(
            f"{Path(path).name}: {three_d[0]!r} is a 3D object; mrm reconstruct takes a project's pixel and "
            "polygon objects, and 3D objects as voxel files (.npz, .tif, .nii.gz): export its voxels from "
            "MR Modeler (File ▸ Export) and reconstruct that file"
        )
    union = PixelSet.empty()
    for obj in src.objects:
        union = union | (
            obj.source if isinstance(obj.source, PixelSet) else discretize_geometry(obj.source, chosen, limit)
        )
    return union, chosen


#: Bytes per vertex of a GeoJSON polygon at most: two 17-significant-digit coordinates, ``[``, ``,``, ``]``
#: and a separator, each coordinate up to 24 characters (``-1.2345678901234567e+300``).
_GEOJSON_BYTES_PER_VERTEX = 2 * 24 + 4


def _write(geom: Any, path: str, model: str, source: str, georef: Any = None, features: str = "one") -> None:
    ext = Path(path).suffix.lower()
    if ext in (".geojson", ".json"):
        # What we write must read back: refuse, before writing, a file the vector reader would refuse.
        size = count_vertices(geom) * _GEOJSON_BYTES_PER_VERTEX
        if size > MAX_VECTOR_FILE_BYTES:
            raise FileFormatError(
                f"{path}: the result has {count_vertices(geom):_} vertices, up to {size / 2**20:.0f} MB of "
                f"GeoJSON, more than the {MAX_VECTOR_FILE_BYTES >> 20} MB a vector file may hold to be read "
                "back; write .wkt or .svg, or reconstruct a part of the image"
            )
    if ext == ".svg":
        write_svg(geom, path)
    elif ext == ".wkt":
        write_wkt(geom, path)
    elif features == "components":
        parts = list(getattr(geom, "geoms", [] if geom.is_empty else [geom]))
        write_geojson(parts, path, properties={"model": model, "source": Path(source).name})
    else:
        members = geojson_members(georef, geom)
        write_geojson(geom, path, properties={"model": model, "source": Path(source).name}, members=members)


def reconstruct_volume(
    path: str,
    output: str,
    model: str | None,
    threshold: float | None,
    limit: int | None,
    bar: Any = None,
    triangles: bool = False,
    compact_limit: int | None = None,
) -> dict[str, Any]:
    """Read one voxel file, reconstruct it (R in 3D), write the mesh; return its summary."""
    chosen = model or "standard"
    extension_of(output, MESH_EXTENSIONS, "mesh output file for a voxel input")  # before any work
    vs = read_voxel_input(path, threshold, limit)
    check_reconstruct(vs, path)  # surfels bounded before any work (mrm.core.limits)
    if bar is not None:
        bar.update(None, f"{len(vs):_} voxels")
    t0 = time.perf_counter()
    # in a thread of its own: Ctrl+C stops a long decimation at once (a high --compact-limit takes minutes)
    r = interruptible(lambda p: reconstruct_voxels_detailed(vs, chosen, compact_limit, p), bar)
    poly, way = r.polyhedron, r.way
    seconds = time.perf_counter() - t0
    if r.note is not None:  # R met the contract but is not compact: say so
        hint = " (--compact-limit raises it)" if r.over_limit else ""
        print(f"mrm reconstruct: note: {path}: {r.note}{hint}", file=sys.stderr, flush=True)
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    warning = write_mesh(poly, output, triangles=triangles)
    if warning is not None:
        print(f"mrm reconstruct: warning: {warning}", file=sys.stderr, flush=True)
    summary: dict[str, Any] = {"input": str(path), "output": str(output)}
    summary.update(summarize_voxels(vs, chosen, faces=poly.n_faces, vertices=poly.n_vertices))
    summary["r"] = way
    summary["seconds"] = seconds
    return summary


def reconstruct_file(
    path: str,
    output: str,
    model: str | None,
    threshold: float | None,
    limit: int | None,
    invert: bool = False,
    features: str = "one",
    triangles: bool = False,
    compact_limit: int | None = None,
    bar: Any = None,
) -> dict[str, Any]:
    """Read one pixel or voxel file, reconstruct it, write the result; return its summary (for the pool)."""
    if is_3d_input(path):
        if invert:
            raise ParameterError(f"{path}: --invert applies to 2D images only")
        return reconstruct_volume(path, output, model, threshold, limit, bar, triangles, compact_limit)
    extension_of(output, (*VECTOR_EXTENSIONS, ".svg"), "vector output file for a 2D input")
    limit = pixel_limit(limit)
    ps, chosen = _pixels_of(path, threshold, limit, model, invert)
    check_reconstruct(ps, f"{path}")  # boundary length bounded before any work (mrm.core.limits)
    georef = None
    if Path(path).suffix.lower() in PIXEL_EXTENSIONS:
        georef = read_georef(path)  # a GeoTIFF's own, or a world file beside the image
    if bar is not None:
        bar.update(None, f"{len(ps):_} pixels")
    t0 = time.perf_counter()
    geom = reconstruct(ps, chosen)
    seconds = time.perf_counter() - t0
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    if bar is not None:
        bar.update(None, "writing")
    # The result lands where the raster is: grid coordinates mapped by its transform (mrm.io.georef).
    _write(geom if georef is None else georef.to_world(geom), output, chosen, path, georef, features)
    summary = {"input": str(path), "output": str(output), **summarize(ps, chosen, geom=geom)}
    summary["seconds"] = seconds
    summary.update(georef_summary(georef))
    return summary


def _line(f: dict[str, Any]) -> str:
    faces = f" {f['faces']} faces," if "faces" in f else ""
    return f"{f['input']} -> {f['output']}:{faces} {f['vertices']} vertices, {f['seconds']:.3f} s"


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Reconstruct every input and write it; return the summary (see the module docstring)."""
    pairs = inputs_and_outputs(
        args, INPUTS, "supported input file", OUTPUTS, ".geojson", "vector output file"
    )
    if len(pairs) > 1 and "{stem}" not in str(args.output):
        # A directory of outputs: a voxel input's default output is a mesh, not a GeoJSON file.
        pairs = [(i, o[: -len(".geojson")] + ".obj" if is_3d_input(i) else o) for i, o in pairs]
    jobs = [
        (
            i,
            o,
            args.model,
            args.threshold,
            args.limit,
            args.invert,
            args.features,
            args.triangles,
            args.compact_limit,
        )
        for i, o in pairs
    ]

    def total(files: list[dict[str, Any]], errors: list[str]) -> dict[str, Any]:
        head = {"model": args.model or (files[0]["model"] if files else "standard")}
        three_d = bool(files) and all("voxels" in f for f in files)
        return batch_total(args, head, len(jobs), files, errors, _SUM_KEYS_3D if three_d else _SUM_KEYS)

    first = f"reconstruct {Path(pairs[0][0]).name}"
    return run_inputs(args, reconstruct_file, jobs, _line, total, first=first, bar=True)
