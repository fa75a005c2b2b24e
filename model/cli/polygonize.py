"""``mrm polygonize LABELS... -o OUT``: a label image or classified raster as polygons, one per region.

``LABELS`` is an integer label image: a grey (8 or 16 bits) or palette PNG, a PGM (the grey value is the
label), an NPZ holding ``labels`` (and optionally ``origin``) — label 0 is the background — or a classified
GeoTIFF (``.tif``): band ``--band N`` (default 1), its pixels of the file's nodata value (or ``--nodata V``)
and those ``--mask FILE`` leaves out are the background, every other value is a class, 0 included, as for
``gdal_polygonize``. ``--mask`` (a pixel file of the image's size, its zero pixels out) works for images and
GeoTIFFs.

Each region becomes one feature with the fields ``--field`` (default ``label``: the class value) and
``--pixels-field`` (default ``pixels``). A region is a 4-connected component of one value; with
``--connectivity 8`` it is an 8-connected one, written as a MultiPolygon of its 4-connected parts (the exact
contract gives one polygon per 4-connected component, docs/design.md §3: a single polygon joining two pixels
that touch at a corner would cross the boundary of the other diagonal pair). A boundary between two regions
is one polyline used by both (:mod:`mrm.geometry.reconstruct.polygonize`): the model is always ``gauss``,
the only one under which such a coverage burns back, with every centre-rule rasterizer (GDAL's
``rasterize``), to the label image exactly.

Output: GeoJSON (``.geojson``), GeoPackage (``.gpkg``), Shapefile (``.shp``) or FlatGeobuf (``.fgb``); the
last three need the ``geo`` extra (pyogrio). A georeferenced input (a GeoTIFF, a PNG with a world file) gives
world coordinates — the raster's transform applied to the polygons, exactly — and the layer its CRS (an EPSG
code, else the WKT; GeoJSON carries only EPSG codes and refuses another CRS: :mod:`mrm.io.vector_layers`).

``--json`` prints ``model``, ``labels`` (distinct classes), ``regions``, ``pixels``, ``vertices``,
``seconds`` (the time the polygonization took), ``input`` and ``output`` (and ``crs``).

3D: a label volume (an ``.npz`` holding a 3-D ``labels``, a multi-page ``.tif``/``.tiff``, ``.nii``,
``.nii.gz``: :func:`mrm.io.voxel_files.read_label_volume`, label 0 the background) gives one closed mesh per
region (a 6-connected component of one label), written to one OBJ file (``-o OUT.obj``): one shared vertex
list and one ``o label_L_k`` object per region (the k-th region of label L, in raster order of its first
voxel), grouped by label (``g label_L``). Each face is one polygon where a polygon can hold it, cut where the
region on its other side changes (``--triangles`` writes triangles): a face between two regions is the same
polygon (or triangles) in both objects, reversed (watertight, no T-junction); D_gauss of each object is its
region's voxels exactly, and every
coordinate is a multiple of ⅛, written exactly (:mod:`mrm.geometry.reconstruct.polygonize_3d`,
docs/polygonize-3d.md). Its ``--json`` gives ``model``, ``labels``, ``regions``, ``voxels``, ``surfels``
(unit squares between different regions, or a region and the background), ``triangles`` (both sides of a
shared face counted), ``faces`` (the polygons written, both sides counted; the triangles with
``--triangles``), ``vertices``, ``seconds``, ``input`` and ``output``. The raster options (``--band``,
``--nodata``, ``--mask``, ``--connectivity 8``) do not apply to volumes; a volume without any label is
refused.

Several inputs (files, directories, quoted globs, ``-``) work as for ``reconstruct`` (docs/adr/0011): ``-o``
is a directory or a pattern holding ``{stem}``, ``--jobs N`` spreads them over worker processes, each
input's line is printed when it is done; ``--json`` then gives ``inputs``, the sums and ``files``.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.geometry import MultiPolygon

from mrm.cli._common import (
    add_batch_arguments,
    add_limit_argument,
    batch_total,
    extension_of,
    inputs_and_outputs,
    pixel_limit,
    positive_int,
    run_inputs,
)
from mrm.core.errors import ParameterError
from mrm.core.georef import GeoRef
from mrm.core.grids import LabelMap
from mrm.core.models import Model
from mrm.geometry.reconstruct.polygonize import Region, polygonize
from mrm.geometry.reconstruct.polygonize_3d import polygonize_volume
from mrm.io.georef import GEOTIFF_EXTENSIONS, WORLD_FILE_EXTENSIONS, read_georef
from mrm.io.mesh_files import write_label_meshes
from mrm.io.pixel_files import LABEL_READ_EXTENSIONS, read_label_map
from mrm.io.vector_layers import LAYER_EXTENSIONS, check_field_names, check_layer_crs, write_layer
from mrm.io.voxel_files import VOXEL_EXTENSIONS, is_volume_file, read_label_volume
from mrm.reps.summary import count_vertices

NAME = "polygonize"
HELP = (
    "label image or classified GeoTIFF (.png .pgm .npz .tif) to one polygon per region, boundaries shared "
    "exactly (.geojson .gpkg .shp .fgb); a label volume (.npz .tif .nii .nii.gz) to one closed mesh per "
    "region, faces shared exactly (.obj)"
)
#: ``--model``'s help: polygonize always uses gauss (the generic help names the project default).
MODEL_HELP = (
    "only 'gauss', the default and the one model whose polygons share boundaries and burn back exactly"
)

INPUTS = tuple(dict.fromkeys((*LABEL_READ_EXTENSIONS, *GEOTIFF_EXTENSIONS, *VOXEL_EXTENSIONS)))
#: The one mesh format that holds several meshes on one vertex list (label volumes).
MESH_OUTPUTS = (".obj",)
OUTPUTS = (*LAYER_EXTENSIONS, *MESH_OUTPUTS)
OUTPUT_WHAT = "vector output file (GeoJSON, GeoPackage, Shapefile or FlatGeobuf; OBJ for a label volume)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the inputs, ``-o OUT``, ``--jobs``, the raster options, the field names and ``--limit``."""
    add_batch_arguments(
        parser,
        "label images (.png grey or palette, .pgm, .npz) or classified GeoTIFFs (.tif); 3D: label volumes "
        "(.npz .tif .tiff .nii .nii.gz)",
        "the vector layer to write (.geojson .gpkg .shp .fgb); for a label volume the meshes (.obj)",
    )
    parser.add_argument(
        "--band", type=positive_int, default=None, metavar="N", help="GeoTIFF band (default 1)"
    )
    parser.add_argument(
        "--nodata",
        type=_number,
        default=None,
        metavar="V",
        help="GeoTIFF: the value of the pixels that are no region (default: the file's nodata, if any)",
    )
    parser.add_argument(
        "--mask",
        default=None,
        metavar="FILE",
        help="a pixel file of the input's size: its zero pixels are no region",
    )
    parser.add_argument(
        "--connectivity",
        type=int,
        choices=(4, 8),
        default=4,
        help="regions are 4-connected (default) or 8-connected; an 8-connected region is one feature, a "
        "MultiPolygon of its 4-connected parts",
    )
    parser.add_argument(
        "--field", default="label", metavar="NAME", help="the class value's field (default label)"
    )
    parser.add_argument(
        "--pixels-field", default="pixels", metavar="NAME", help="the pixel count's field (default pixels)"
    )
    parser.add_argument(
        "--triangles",
        action="store_true",
        help="label volumes: write each region's triangles (default: one polygon per face)",
    )
    add_limit_argument(parser, voxels=True)


def _number(text: str) -> float:
    """Argparse type of ``--nodata``: a number (nan allowed, for a float band's NaN nodata)."""
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if math.isinf(v):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return v


def read_labels(path: str, limit: int) -> LabelMap:
    """Read an integer label image (see the module docstring): the library's reader, the GUI's too."""
    extension_of(path, LABEL_READ_EXTENSIONS, "label image")
    return read_label_map(path, limit=limit)


def _read_input(
    path: str, band: int | None, nodata: float | None, mask: str | None, limit: int
) -> tuple[LabelMap, np.ndarray | None, GeoRef | None]:
    """The label map, the class value of each label (None: the label itself) and the georeference."""
    ext = extension_of(path, INPUTS, "label image")
    if ext in GEOTIFF_EXTENSIONS:
        from mrm.io.label_rasters import read_label_raster

        lr = read_label_raster(path, band=band or 1, nodata=nodata, mask=mask, limit=limit)
        return lr.labels, lr.values, lr.georef
    if band not in (None, 1) or nodata is not None:
        raise ParameterError(
            f"{path}: --band and --nodata apply to GeoTIFF inputs (.tif); label 0 is no region"
        )
    lm = read_labels(path, limit)
    georef = read_georef(path) if ext in WORLD_FILE_EXTENSIONS else None
    if mask is not None:
        if ext == ".npz":
            raise ParameterError(
                f"{path}: --mask applies to images (.png .pgm) and GeoTIFFs; an .npz has no frame"
            )
        from mrm.io.georef import image_frame
        from mrm.io.label_rasters import mask_rows

        x0, y0, x1, y1 = image_frame(path) if georef is None else georef.frame
        h, w = y1 - y0 + 1, x1 - x0 + 1
        rows = np.zeros((h, w), dtype=np.int32)  # bottom row first, as a LabelMap holds it
        if not lm.is_empty():
            lx, ly = lm.origin
            lh, lw = lm.shape
            rows[ly - y0 : ly - y0 + lh, lx - x0 : lx - x0 + lw] = lm.labels
        keep = mask_rows(mask, (h, w), georef, Path(path).name)[::-1]
        lm = LabelMap(np.where(keep, rows, 0), (x0, y0))
    return lm, None, georef


def group_8_connected(regions: list[Region], lm: LabelMap) -> list[list[int]]:
    """The regions (4-connected) grouped into 8-connected ones: lists of indices, in output order.

    Two regions of one label are joined where a pixel of each touch at a corner. Each such pixel's region is
    the polygon holding its centre (the gauss contract: a region's polygon holds its pixels' centres
    strictly), found by one vectorized query.
    """
    n = len(regions)
    if n == 0:
        return []
    lab = np.asarray(lm.labels)
    x0, y0 = lm.origin
    pairs: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = []
    a, b = lab[:-1, :-1], lab[1:, 1:]  # (r, c) and (r + 1, c + 1)
    rr, cc = np.nonzero((a == b) & (a != 0) & (lab[:-1, 1:] != a) & (lab[1:, :-1] != a))
    pairs.append((rr, cc, rr + 1, cc + 1))
    a, b = lab[:-1, 1:], lab[1:, :-1]  # (r, c + 1) and (r + 1, c)
    rr, cc = np.nonzero((a == b) & (a != 0) & (lab[:-1, :-1] != a) & (lab[1:, 1:] != a))
    pairs.append((rr, cc + 1, rr + 1, cc))
    r1 = np.concatenate([p[0] for p in pairs])
    c1 = np.concatenate([p[1] for p in pairs])
    r2 = np.concatenate([p[2] for p in pairs])
    c2 = np.concatenate([p[3] for p in pairs])
    parent = np.arange(n)
    if r1.size:
        tree = shapely.STRtree([r.geometry for r in regions])
        pts = shapely.points(np.concatenate([x0 + c1, x0 + c2]), np.concatenate([y0 + r1, y0 + r2]))
        which, poly = tree.query(pts, predicate="within")
        owner = np.full(2 * r1.size, -1)
        owner[which] = poly
        u, v = owner[: r1.size], owner[r1.size :]
        ok = (u >= 0) & (v >= 0)
        u, v = u[ok], v[ok]
        while True:  # connected components by min-propagation and pointer jumping
            m = np.minimum(parent[u], parent[v])
            before = parent.copy()
            np.minimum.at(parent, u, m)
            np.minimum.at(parent, v, m)
            parent = parent[parent]
            if np.array_equal(parent, before):
                break
    groups: dict[int, list[int]] = {}
    for i, root in enumerate(parent.tolist()):
        groups.setdefault(root, []).append(i)
    return sorted(groups.values(), key=lambda g: g[0])


def polygonize_file(
    path: str,
    output: str,
    model: str | None,
    limit: int | None,
    band: int | None = None,
    nodata: float | None = None,
    mask: str | None = None,
    connectivity: int = 4,
    field: str = "label",
    pixels_field: str = "pixels",
    triangles: bool = False,
) -> dict[str, Any]:
    """Polygonize one label image (or volume) and write its features (meshes); return its summary.

    Batch workers call it; a label volume goes to :func:`polygonize_volume_file`.
    """
    if is_volume_file(path):
        if band is not None or nodata is not None or mask is not None or connectivity != 4:
            raise ParameterError(
                f"{path}: --band, --nodata, --mask and --connectivity apply to 2D label images; the regions "
                "of a label volume are its 6-connected components"
            )
        return polygonize_volume_file(path, output, model, limit, triangles)
    limit = pixel_limit(limit)
    extension_of(output, LAYER_EXTENSIONS, OUTPUT_WHAT + " for a 2D input")
    check_field_names([field, pixels_field], output)  # before any work
    lm, values, georef = _read_input(path, band, nodata, mask, limit)
    check_layer_crs(output, None if georef is None else georef.crs)
    chosen = model or "gauss"
    t0 = time.perf_counter()
    regions = polygonize(lm, model=chosen)
    groups = group_8_connected(regions, lm) if connectivity == 8 else [[i] for i in range(len(regions))]
    seconds = time.perf_counter() - t0
    geoms = [
        MultiPolygon([regions[i].geometry for i in g]) if connectivity == 8 else regions[g[0]].geometry
        for g in groups
    ]
    if georef is not None:
        geoms = [georef.to_world(g) for g in geoms]
    labels = np.array([regions[g[0]].label for g in groups], dtype=np.int64)
    classes = labels if values is None else values[labels - 1]
    pixels = np.array([sum(regions[i].pixels for i in g) for g in groups], dtype=np.int64)
    write_layer(
        geoms, {field: classes, pixels_field: pixels}, output, crs=None if georef is None else georef.crs
    )
    summary: dict[str, Any] = {
        "input": str(path),
        "output": str(output),
        "model": chosen,
        "labels": len(set(labels.tolist())),
        "regions": len(groups),
        "pixels": int(pixels.sum()),
        "vertices": sum(count_vertices(r.geometry) for r in regions),
        "seconds": seconds,
    }
    if georef is not None:
        summary["crs"] = georef.crs
    return summary


def polygonize_volume_file(
    path: str, output: str, model: str | None, limit: int | None, triangles: bool = False
) -> dict[str, Any]:
    """Polygonize one label volume into one OBJ of one object per region; return its summary."""
    extension_of(output, MESH_OUTPUTS, "mesh output file for a label volume (one object per region)")
    chosen = model or "gauss"
    if Model.parse(chosen).is_cover:  # before reading: the library says why
        polygonize_volume(np.zeros((1, 1, 1), np.int32), model=chosen)
    lv = read_label_volume(path, limit=limit)  # None: the label volumes' own limit
    if lv.is_empty():
        raise ParameterError(f"{path}: the volume holds no label (every voxel is 0): nothing to polygonize")
    t0 = time.perf_counter()
    out = polygonize_volume(lv, model=chosen)
    seconds = time.perf_counter() - t0
    count: dict[int, int] = {}
    objects = []
    for r in out.regions:
        count[r.label] = count.get(r.label, 0) + 1
        objects.append((f"label_{r.label}_{count[r.label]}", f"label_{r.label}", r.triangles))
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    polygons = None if triangles else out.polygons()
    write_label_meshes(out.vertices, objects, output, polygons)
    written = out.n_triangles if polygons is None else sum(int(ptr.size) - 1 for ptr, _ in polygons)
    return {
        "input": str(path),
        "output": str(output),
        "model": chosen,
        "labels": len(count),
        "regions": len(out.regions),
        "voxels": sum(r.voxels for r in out.regions),
        "surfels": out.surfels,
        "triangles": out.n_triangles,
        "faces": written,
        "vertices": int(out.vertices.shape[0]),
        "seconds": seconds,
    }


_2D_SUMS = ("regions", "pixels", "vertices", "seconds")


def _line(f: dict[str, Any]) -> str:
    return f"{f['input']} -> {f['output']}: {f['regions']} regions, {f['seconds']:.3f} s"


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Polygonize every label image and write the features; return the summary."""
    pairs = inputs_and_outputs(args, INPUTS, "label image", OUTPUTS, ".geojson", OUTPUT_WHAT)
    for _, o in pairs:
        check_field_names([args.field, args.pixels_field], o)
    jobs = [
        (
            i,
            o,
            args.model,
            args.limit,
            args.band,
            args.nodata,
            args.mask,
            args.connectivity,
            args.field,
            args.pixels_field,
            args.triangles,
        )
        for i, o in pairs
    ]

    def total(files: list[dict[str, Any]], errors: list[str]) -> dict[str, Any]:
        head = {"model": args.model or "gauss"}
        keys: tuple[str, ...] = ("regions", "pixels", "voxels", "surfels", "triangles", "vertices", "seconds")
        # 2D files have pixels, volumes voxels, surfels and triangles: sum what the files report.
        keys = tuple(k for k in keys if k in _2D_SUMS or any(k in f for f in files))
        return batch_total(args, head, len(jobs), files, errors, keys)

    return run_inputs(args, polygonize_file, jobs, _line, total, first=f"polygonize {Path(pairs[0][0]).name}")
