"""``mrm discretize IN... -o OUT``: the exact discretization of a Euclidean geometry, written as pixels.

Georeferenced output (docs/gdal.md): ``--like RASTER`` burns on that raster's grid (its transform, size and
CRS; the input's coordinates are world coordinates in that CRS), ``--resolution R`` on a north-up grid of
R world units per pixel over ``--extent XMIN,YMIN,XMAX,YMAX`` (default: the input's bounds). The output is
then a GeoTIFF (.tif) or a PNG + world file (.pgw, and .prj for the CRS) covering the whole grid. A
geometry that covers fewer than a handful of pixels gets a warning on stderr (wrong units?).

Several inputs (files, directories, quoted globs; ``--jobs N`` workers) need ``-o`` to be a directory
(``NAME.geojson`` gives ``NAME.png``) or a pattern holding ``{stem}``, as for ``mrm reconstruct``.

``--attribute FIELD`` burns each feature of a vector layer (GeoJSON, GeoPackage, Shapefile, FlatGeobuf,
read through pyogrio: the ``geo`` extra) with the value of its field ``FIELD`` into a label raster
(``gdal_rasterize -a``): each feature's pixels are its exact discretization under the model; where features
overlap, the **last one in the layer wins** (GDAL's rule); values are integers (a float field only with
integer values) that the output holds — 0 to 65535 in a PNG, a 32-bit integer in a GeoTIFF or NPZ — and 0 is
the background, so a feature of value 0 erases. With ``--like`` or ``--resolution`` the output is a GeoTIFF
or PNG + world file on that grid, with the template's (or the layer's) CRS; without, a label map (.png,
.npz) in the layer's own coordinates.

``IN`` is a GeoJSON, WKT, GeoPackage, Shapefile or FlatGeobuf file (every geometry in it, combined; the last
three through pyogrio, with their CRS checked against ``--like``'s) or a project (.mrm). For a project,
``--object NAME`` picks one object — a Euclidean object is discretized, a discrete object is written as it
is (it is its own discrete representation); without ``--object`` every Euclidean object of the project is
discretized, combined (D is union-stable, so this is the union of their discretizations). The model is
``--model``, else the project's, else 'standard'. An .svg output draws the pixels with the Euclidean input
outlined on top.

The table printed without ``--json`` holds the model, the pixels, their bounding box, the input's vertices
and the time; ``--json`` adds the region's and the segmentation's keys of ``mrm info`` (``components``,
``holes``, ``euler``, ``boundary_chains``, ``segments``), which load more kernels (``mrm info OUT`` shows them
for the written file).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from mrm.cli._common import (
    PROJECT_EXTENSION,
    add_inputs_argument,
    add_jobs_argument,
    add_limit_argument,
    add_output_argument,
    batch_outputs,
    discretize_geometry,
    expand_inputs,
    extension_of,
    finite_float,
    load_object,
    project_objects,
    refuse_failures,
    run_inputs,
)
from mrm.cli._project_input import add_object_argument
from mrm.core.errors import FileFormatError, ParameterError
from mrm.core.georef import GeoRef
from mrm.core.grids import LabelMap, PixelSet
from mrm.core.limits import check_pixels
from mrm.io.georef import few_pixels_warning, read_geojson_crs, read_georef, same_crs, write_georeferenced
from mrm.io.pixel_files import PIXEL_EXTENSIONS, write_pixels
from mrm.io.vector_files import VECTOR_EXTENSIONS, combine, write_svg
from mrm.reps.summary import summarize, summarize_pixels

if TYPE_CHECKING:
    from mrm.core.georef import GeoRef

NAME = "discretize"
#: What ``-o -`` writes without ``--format``.
STDOUT_FORMAT = ".png"
HELP = (
    "discretize a Euclidean geometry (.geojson .wkt .gpkg .shp .fgb .mrm) into a pixel file (.png .pbm .pgm "
    ".npz .tif .svg); --attribute burns a field's values into a label raster"
)

INPUTS = (*VECTOR_EXTENSIONS, PROJECT_EXTENSION, ".gpkg", ".shp", ".fgb")
OUTPUTS = (*PIXEL_EXTENSIONS, ".svg")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the inputs, ``--object``, ``-o OUT``, ``--jobs`` and ``--limit``."""
    add_inputs_argument(parser, "GeoJSON, WKT or project files")
    add_object_argument(parser)
    add_jobs_argument(parser)
    parser.add_argument(
        "--like",
        metavar="RASTER",
        default=None,
        help="burn on the grid of this georeferenced raster (.tif, or an image with a world file)",
    )
    parser.add_argument(
        "--resolution",
        type=finite_float,
        default=None,
        metavar="R",
        help="burn on a north-up grid of R world units per pixel (with --extent, or the input's bounds)",
    )
    parser.add_argument(
        "--extent",
        type=parse_extent,
        default=None,
        metavar="XMIN,YMIN,XMAX,YMAX",
        help="the world box the --resolution grid covers",
    )
    parser.add_argument(
        "--attribute",
        metavar="FIELD",
        default=None,
        help="burn each feature's integer value of FIELD into a label raster (the last feature wins where "
        "features overlap; 0 is the background); inputs .geojson .gpkg .shp .fgb",
    )
    add_output_argument(
        parser, "the pixel file to write (.png .pbm .pgm .npz; .svg draws the pixels with the input outlined)"
    )
    add_limit_argument(parser)


def _source(path: str, object_name: str | None, model: str | None, limit: int) -> tuple[Any, str]:
    """The geometry (or, for a discrete project object, the pixel set) to discretize, and the model."""
    if extension_of(path, INPUTS, "supported input file") == PROJECT_EXTENSION and object_name is None:
        objects, project_model = project_objects(path)
        euclidean = [o.source for o in objects if not isinstance(o.source, PixelSet)]
        if not euclidean:
            raise FileFormatError(
                f"{path}: the project holds no Euclidean object to discretize "
                "(--object NAME writes a discrete object's pixels)"
            )
        return combine(euclidean), model or project_model
    _, value, chosen = load_object(path, object_name, model, limit=limit)
    return value, chosen


def parse_extent(text: str) -> tuple[float, float, float, float]:
    """Argparse type of ``--extent``: four finite numbers XMIN,YMIN,XMAX,YMAX."""
    parts = text.split(",")
    try:
        values = tuple(float(p) for p in parts)
    except ValueError:
        values = ()
    if len(values) != 4 or not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"expected XMIN,YMIN,XMAX,YMAX (four numbers), got {text!r}")
    return values[0], values[1], values[2], values[3]


def _grid(path: str, geom: Any, like: str | None, resolution: float | None, extent: Any) -> GeoRef | None:
    """The georeferenced grid to burn on (None: the plain pixel grid of the input's coordinates)."""
    if like is None and resolution is None:
        if extent is not None:
            raise ParameterError("--extent needs --resolution (or use --like RASTER)")
        return None
    if geom is None:
        raise ParameterError(f"{path}: --like and --resolution apply to Euclidean inputs only")
    ext = Path(path).suffix.lower()
    crs = (
        read_geojson_crs(path)
        if ext in (".geojson", ".json")
        else _layer_crs(path)
        if ext in LAYER_ONLY
        else None
    )
    if like is not None:
        if resolution is not None or extent is not None:
            raise ParameterError("--like gives the grid: it excludes --resolution and --extent")
        grid = read_georef(like)
        if grid is None:
            raise ParameterError(f"{like}: the raster has no georeference (no GeoTIFF tags, no world file)")
        if crs is not None and grid.crs is not None and not same_crs(crs, grid.crs):
            raise ParameterError(
                f"{path} is in {crs} and {Path(like).name} in {grid.crs}: reproject one of them first "
                "(e.g. ogr2ogr -t_srs); MR Modeler does not reproject"
            )
        return grid
    assert resolution is not None
    return GeoRef.from_resolution(resolution, extent or tuple(geom.bounds), crs)


def discretize_file(
    path: str,
    output: str,
    object_name: str | None,
    model: str | None,
    limit: int,
    like: str | None = None,
    resolution: float | None = None,
    extent: tuple[float, float, float, float] | None = None,
    attribute: str | None = None,
    topology: bool = True,
) -> dict[str, Any]:
    """Read one input, discretize it, write the pixels; return the summary (batch workers call it).

    ``topology``: add the region's and the segmentation's keys (``components`` … ``segments``, what
    ``--json`` documents). Without ``--json`` they are left out: they load (on a fresh install, compile)
    the labelling, crack and segmentation kernels, twice the work of the discretization itself.
    """
    out_ext = extension_of(output, OUTPUTS, "pixel output file")  # fail before any work
    if attribute is not None:
        return burn_file(path, output, attribute, model, limit, like, resolution, extent)
    if Path(path).suffix.lower() in LAYER_ONLY:
        if object_name is not None:
            raise ParameterError(f"{path}: --object applies to projects (.mrm)")
        source, chosen = _layer_source(path), model or "standard"
    else:
        source, chosen = _source(path, object_name, model, limit)
    geom = None if isinstance(source, PixelSet) else source
    grid = _grid(path, geom, like, resolution, extent)
    if grid is not None:
        check_pixels(grid.width * grid.height, limit, f"{output}: the grid")
    t0 = time.perf_counter()
    if geom is None:
        ps = source
    elif grid is None:
        ps = discretize_geometry(geom, chosen, limit)
    else:
        ps = discretize_geometry(grid.to_grid(geom), chosen, limit).crop(grid.frame)
    seconds = time.perf_counter() - t0
    if geom is not None:
        warning = few_pixels_warning(ps, geom, Path(path).name)
        if warning is not None:
            print(f"mrm discretize: warning: {warning}", file=sys.stderr, flush=True)
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    if grid is not None and out_ext != ".svg":
        write_georeferenced(ps, output, grid)
    elif out_ext == ".svg":
        if geom is None:
            write_svg(ps, output)
        else:
            write_svg(geom, output, pixels=ps)
    else:
        write_pixels(ps, output)
    summary: dict[str, Any] = {"input": str(path), "output": str(output)}
    if object_name is not None:
        summary.update(object=object_name, source="discrete" if geom is None else "euclidean")
    if topology:
        summary.update(summarize(ps, chosen, geom=geom))
    else:
        summary.update(summarize_pixels(ps, chosen, geom))
    summary["seconds"] = seconds
    if grid is not None:
        summary["grid"] = grid.as_dict()
    return summary


#: Vector layer formats read only through pyogrio, for ``--attribute``.
LAYER_ONLY = (".gpkg", ".shp", ".fgb")
#: What ``--attribute`` writes without a grid: a label map in the layer's coordinates.
_LABEL_OUTPUTS = (".png", ".npz")


def _layer_source(path: str) -> Any:
    """Every feature of a GeoPackage, Shapefile or FlatGeobuf layer, combined (as for a GeoJSON file)."""
    from mrm.io.vector_files import check_geometry
    from mrm.io.vector_layers import read_layer

    geoms, _, _ = read_layer(path)
    return combine(
        check_geometry(g, f"{path}: feature {i}")
        for i, g in enumerate(geoms)
        if g is not None and not g.is_empty
    )


def _bounds(geom: Any) -> tuple[float, float, float, float]:
    xmin, ymin, xmax, ymax = (float(v) for v in geom.bounds)
    return xmin, ymin, xmax, ymax


def _layer_crs(path: str) -> str | None:
    from mrm.io.vector_layers import read_layer_crs

    return read_layer_crs(path)


def _burn_values(values: Any, path: str, field: str) -> npt.NDArray[np.int64]:
    """The field's values as int64, refusing missing or non-integer ones with one line."""
    v = np.asarray(values)
    if v.dtype.kind == "f":
        bad = ~np.isfinite(v) | (v != np.round(v)) | (np.abs(v) > 2**31)
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise ParameterError(
                f"{path}: feature {i}: {field} = {v[i]!r} is not an integer label (burnt values are integers)"
            )
    return v.astype(np.int64)


def burn_file(
    path: str,
    output: str,
    field: str,
    model: str | None,
    limit: int,
    like: str | None,
    resolution: float | None,
    extent: tuple[float, float, float, float] | None,
) -> dict[str, Any]:
    """``--attribute``: burn each feature's value of ``field`` into a label raster; return the summary."""
    from mrm.io.label_rasters import label_dtype, write_label_raster
    from mrm.io.pixel_files import write_label_map
    from mrm.io.vector_files import check_geometry
    from mrm.io.vector_layers import LAYER_EXTENSIONS, read_layer

    extension_of(path, LAYER_EXTENSIONS, "vector layer (with --attribute)")
    out_ext = Path(output).suffix.lower()
    georeferenced = like is not None or resolution is not None
    if not georeferenced and out_ext not in _LABEL_OUTPUTS:
        raise ParameterError(
            f"{output}: --attribute writes a label map (.png, .npz), or with --like or --resolution "
            "a .tif or .png"
        )
    if georeferenced and out_ext not in (".tif", ".tiff", ".png"):
        raise ParameterError(f"{output}: a georeferenced label raster is a .tif or a .png (+ world file)")
    chosen = model or "standard"
    geoms, raw, crs = read_layer(path, field)
    values = _burn_values(raw, path, field)
    feats = [
        (check_geometry(g, f"{path}: feature {i}"), int(v))
        for i, (g, v) in enumerate(zip(geoms, values.tolist(), strict=True))
        if g is not None and not g.is_empty
    ]
    lo, hi = min([0, *(v for _, v in feats)]), max([0, *(v for _, v in feats)])
    if out_ext in (".png", ".pgm") and (lo < 0 or hi > 65535):
        raise ParameterError(
            f"{path}: {field} runs from {lo} to {hi}; a PNG holds labels 0 to 65535 (write .tif)"
        )
    label_dtype(lo, hi)  # a 32-bit integer at most, refused here before any work
    grid: GeoRef | None = None
    if georeferenced:
        whole = combine([g for g, _ in feats]) if feats else None
        if like is not None:
            if resolution is not None or extent is not None:
                raise ParameterError("--like gives the grid: it excludes --resolution and --extent")
            grid = read_georef(like)
            if grid is None:
                raise ParameterError(
                    f"{like}: the raster has no georeference (no GeoTIFF tags, no world file)"
                )
            if crs is not None and grid.crs is not None and not same_crs(crs, grid.crs):
                raise ParameterError(
                    f"{path} is in {crs} and {Path(like).name} in {grid.crs}: reproject one of them first "
                    "(e.g. ogr2ogr -t_srs); MR Modeler does not reproject"
                )
        else:
            assert resolution is not None
            if extent is None and whole is None:
                raise ParameterError(f"{path}: no feature to burn and no --extent")
            box = extent if extent is not None else _bounds(whole)
            grid = GeoRef.from_resolution(resolution, box, crs)
        check_pixels(grid.width * grid.height, limit, f"{output}: the grid")
    t0 = time.perf_counter()
    parts = []
    for g, v in feats:  # in layer order: a later feature overwrites an earlier one (GDAL's rule)
        ps = discretize_geometry(g if grid is None else grid.to_grid(g), chosen, limit)
        parts.append((ps if grid is None else ps.crop(grid.frame), v))
    if grid is not None:
        x0, y0, x1, y1 = grid.frame
    else:
        boxes = [ps.bbox for ps, _ in parts if ps.bbox is not None]
        x0, y0 = min(b[0] for b in boxes) if boxes else 0, min(b[1] for b in boxes) if boxes else 0
        x1, y1 = max(b[2] for b in boxes) if boxes else 0, max(b[3] for b in boxes) if boxes else 0
        check_pixels((x1 - x0 + 1) * (y1 - y0 + 1), limit, f"{output}: the label map")
    rows = np.zeros((y1 - y0 + 1, x1 - x0 + 1), dtype=np.int64)  # bottom row first
    for ps, v in parts:
        if len(ps):
            pts = ps.points()
            rows[pts[:, 1] - y0, pts[:, 0] - x0] = v
    seconds = time.perf_counter() - t0
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    if grid is not None:
        write_label_raster(rows[::-1], output, grid)
    else:
        write_label_map(LabelMap(rows.astype(np.int32), (x0, y0)), output)
    summary: dict[str, Any] = {
        "input": str(path),
        "output": str(output),
        "model": chosen,
        "attribute": field,
        "features": len(feats),
        "labels": len({v for _, v in feats} - {0}),
        "pixels": int((rows != 0).sum()),
        "seconds": seconds,
    }
    if grid is not None:
        summary["grid"] = grid.as_dict()
    return summary


def _line(f: dict[str, Any]) -> str:
    return f"{f['input']} -> {f['output']}: {f['pixels']} pixels, {f['seconds']:.3f} s"


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Discretize every input and write it; return the summary (several inputs: ``files`` and totals)."""
    inputs = expand_inputs([str(i) for i in args.inputs], INPUTS)
    outputs = batch_outputs(inputs, str(args.output), OUTPUTS, ".png", "pixel output file")
    jobs = [
        (
            i,
            o,
            args.object,
            args.model,
            args.limit,
            args.like,
            args.resolution,
            args.extent,
            args.attribute,
            args.json,
        )
        for i, o in zip(inputs, outputs, strict=True)
    ]

    def total(files: list[dict[str, Any]], errors: list[str]) -> dict[str, Any]:
        refuse_failures(errors, len(jobs))
        return {"inputs": len(jobs), "pixels": sum(f["pixels"] for f in files), "files": files}

    return run_inputs(args, discretize_file, jobs, _line, total, first=f"discretize {inputs[0]}")
