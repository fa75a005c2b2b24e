"""``mrm discretize IN... -o OUT``: the exact discretization of a Euclidean geometry, written as pixels.

Georeferenced output (docs/gdal.md): ``--like RASTER`` burns on that raster's grid (its transform, size and
CRS; the input's coordinates are world coordinates in that CRS), ``--resolution R`` on a north-up grid of
R world units per pixel over ``--extent XMIN,YMIN,XMAX,YMAX`` (default: the input's bounds). The output is
then a GeoTIFF (.tif) or a PNG + world file (.pgw, and .prj for the CRS) covering the whole grid. A
geometry that covers fewer than a handful of pixels gets a warning on stderr (wrong units?).

Several inputs (files, directories, quoted globs; ``--jobs N`` workers) need ``-o`` to be a directory
(``NAME.geojson`` gives ``NAME.png``) or a pattern holding ``{stem}``, as for ``mrm reconstruct``.

``IN`` is a GeoJSON or WKT file (every geometry in it, combined) or a project (.mrm). For a project,
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
from mrm.core.grids import PixelSet
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
    "discretize a Euclidean geometry (.geojson, .wkt, .mrm) into a pixel file (.png, .pbm, .pgm, .npz, .svg)"
)

INPUTS = (*VECTOR_EXTENSIONS, PROJECT_EXTENSION)
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
    crs = read_geojson_crs(path) if Path(path).suffix.lower() in (".geojson", ".json") else None
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
    topology: bool = True,
) -> dict[str, Any]:
    """Read one input, discretize it, write the pixels; return the summary (batch workers call it).

    ``topology``: add the region's and the segmentation's keys (``components`` … ``segments``, what
    ``--json`` documents). Without ``--json`` they are left out: they load (on a fresh install, compile)
    the labelling, crack and segmentation kernels, twice the work of the discretization itself.
    """
    out_ext = extension_of(output, OUTPUTS, "pixel output file")  # fail before any work
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


def _line(f: dict[str, Any]) -> str:
    return f"{f['input']} -> {f['output']}: {f['pixels']} pixels, {f['seconds']:.3f} s"


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Discretize every input and write it; return the summary (several inputs: ``files`` and totals)."""
    inputs = expand_inputs([str(i) for i in args.inputs], INPUTS)
    outputs = batch_outputs(inputs, str(args.output), OUTPUTS, ".png", "pixel output file")
    jobs = [
        (i, o, args.object, args.model, args.limit, args.like, args.resolution, args.extent, args.json)
        for i, o in zip(inputs, outputs, strict=True)
    ]

    def total(files: list[dict[str, Any]], errors: list[str]) -> dict[str, Any]:
        refuse_failures(errors, len(jobs))
        return {"inputs": len(jobs), "pixels": sum(f["pixels"] for f in files), "files": files}

    return run_inputs(args, discretize_file, jobs, _line, total, first=f"discretize {inputs[0]}")
