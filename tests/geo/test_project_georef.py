"""An object's georeference in the document, the project file, the operations and the exports (ADR 0021).

GeoTIFFs are built here with rasterio; what comes out is read back with rasterio and compared with GDAL's own
rasterizer, never with our code.
"""

from __future__ import annotations

import json
from fractions import Fraction
from itertools import pairwise
from pathlib import Path

import numpy as np
import pytest
import rasterio
from rasterio.features import rasterize
from shapely.geometry import shape

from mrm.core.errors import FileFormatError
from mrm.core.georef import GeoRef
from mrm.core.grids import PixelSet
from mrm.document import Document, Settings
from mrm.document.apply import apply_operation
from mrm.document.commands import MergeObjects, RenameObject
from mrm.document.edits import PaintPixels
from mrm.io.export import export_object, export_objects_geojson
from mrm.io.georef import read_georef
from mrm.io.imports import import_file
from mrm.io.project import load_project, loads, save_project
from tests.geo.test_georef import CRS, T, blobs, write_tif

GOLDEN = Path(__file__).parents[1] / "model" / "golden"


def imported(tmp_path: Path, mask: np.ndarray, model: str = "gauss", **kw) -> tuple[Document, int]:
    write_tif(tmp_path / "dem_mask.tif", mask, **kw)
    doc = Document(Settings(model=model))
    (oid,) = import_file(doc, tmp_path / "dem_mask.tif")
    return doc, oid


@pytest.mark.parametrize("seed", [0, 1])
def test_geotiff_project_save_open_export_gives_the_same_transform_and_crs(tmp_path, seed):
    mask = blobs(40, 56, seed)
    doc, oid = imported(tmp_path, mask)
    save_project(doc, tmp_path / "p.mrm")
    again = load_project(tmp_path / "p.mrm")
    assert again.get(oid).georef == doc.get(oid).georef is not None
    export_object(again, oid, tmp_path / "out.tif")
    with rasterio.open(tmp_path / "out.tif") as src, rasterio.open(tmp_path / "dem_mask.tif") as ref:
        assert src.transform == ref.transform == T
        assert src.crs == ref.crs and src.crs.to_epsg() == 32633
        assert (src.width, src.height) == (ref.width, ref.height)
        assert (src.read(1).astype(bool) == mask).all()


def test_the_gauss_continuation_from_a_reopened_project_rasterizes_back_exactly(tmp_path):
    mask = blobs(48, 64, 4)
    doc, oid = imported(tmp_path, mask)
    save_project(doc, tmp_path / "p.mrm")
    export_object(load_project(tmp_path / "p.mrm"), oid, tmp_path / "out.geojson")
    fc = json.loads((tmp_path / "out.geojson").read_text())
    assert fc["crs"]["properties"]["name"] == "urn:ogc:def:crs:EPSG::32633"
    geoms = [shape(f["geometry"]) for f in fc["features"]]
    xmin, ymin, xmax, ymax = fc["bbox"]
    assert xmin >= 500_000 - 30 and xmax <= 500_000 + 64 * 30 + 30  # world coordinates, not grid ones
    assert ymin >= 4_200_000 - 48 * 30 - 30 and ymax <= 4_200_000 + 30
    burned = rasterize([(g, 1) for g in geoms], out_shape=mask.shape, transform=T, dtype="uint8")
    assert (burned.astype(bool) == mask).all()


def test_a_png_with_a_world_file_exports_with_one(tmp_path):
    from PIL import Image

    from mrm.io.georef import world_file_text

    mask = blobs(20, 30, 5)
    Image.fromarray(mask).save(tmp_path / "m.png")
    (tmp_path / "m.pgw").write_text(world_file_text(tuple(T)[:6]))
    doc = Document(Settings(model="gauss"))
    (oid,) = import_file(doc, tmp_path / "m.png")
    doc = loads(_saved(doc, tmp_path))
    (tmp_path / "out").mkdir()
    export_object(doc, oid, tmp_path / "out" / "o.png")
    g = read_georef(tmp_path / "out" / "o.png")
    assert g is not None and g.transform == tuple(T)[:6] and (g.width, g.height) == (30, 20)
    back = np.asarray(Image.open(tmp_path / "out" / "o.png")).astype(bool)
    assert (back == mask).all()


def _saved(doc: Document, tmp_path: Path) -> bytes:
    save_project(doc, tmp_path / "x.mrm")
    return (tmp_path / "x.mrm").read_bytes()


def test_undo_redo_and_edits_keep_the_georeference(tmp_path):
    doc, oid = imported(tmp_path, blobs(16, 16, 1))
    g = doc.get(oid).georef
    doc.push(RenameObject(oid, "lake"))
    doc.push(PaintPixels(oid, PixelSet.from_points([(100, 100)])))  # outside the raster's frame
    assert doc.get(oid).georef == g
    doc.undo()
    doc.undo()
    assert doc.get(oid).georef == g
    doc.redo()
    doc.redo()
    assert doc.get(oid).georef == g and (100, 100) in doc.get(oid).source
    # Exported, the frame grows to hold the painted pixel; the transform's corner stays on the same grid.
    export_object(doc, oid, tmp_path / "painted.tif")
    with rasterio.open(tmp_path / "painted.tif") as ds:
        assert ds.transform.a == 30 and ds.transform.c == 500_000.0
        assert ds.transform.f == 4_200_000.0 + 30 * (100 - 15)  # 85 rows added on top
        assert (ds.width, ds.height) == (101, 101)
        col, row = ~ds.transform @ (500_000.0 + 30 * 100.5, 4_200_000.0 - 30 * (15 - 100 + 0.5))
        assert ds.read(1)[int(row), int(col)] == 1


def _on_boundary(poly, x: Fraction, y: Fraction) -> bool:
    """Whether (x, y) lies exactly on a ring of ``poly`` (float vertices read as the rationals they are)."""
    rings = [r for p in getattr(poly, "geoms", [poly]) for r in (p.exterior, *p.interiors)]
    for ring in rings:
        pts = [(Fraction(a), Fraction(b)) for a, b in ring.coords]
        for (ax, ay), (bx, by) in pairwise(pts):
            if (bx - ax) * (y - ay) - (by - ay) * (x - ax) == 0 and (
                min(ax, bx) <= x <= max(ax, bx) and min(ay, by) <= y <= max(ay, by)
            ):
                return True
    return False


@pytest.mark.parametrize("seed", [2, 3])
def test_dss_results_get_the_scaled_transform_and_land_on_the_input(tmp_path, seed):
    """DSS_α(A) = D(Sc_α(R(A))): on the scaled transform it is GDAL's burn of R(A)'s world polygon.

    Except at ties, pixels whose centre falls exactly on R(A)'s boundary (frequent at α = 2, where the new
    centres include the old half-integer points): there GDAL's rule is not the gauss model's.
    """
    alpha = 2
    mask = blobs(24, 32, seed)
    doc, oid = imported(tmp_path, mask)
    (rid,) = apply_operation(doc, "dss", [oid], {"alpha": alpha, "model": "gauss"})
    g = doc.get(rid).georef
    assert g is not None and g.crs == CRS
    assert g.transform[0] == 15.0 and g.transform[4] == -15.0  # pixels twice as fine
    export_object(doc, rid, tmp_path / "scaled.tif")
    export_object(doc, oid, tmp_path / "input.geojson")
    geoms = [shape(f["geometry"]) for f in json.loads((tmp_path / "input.geojson").read_text())["features"]]
    with rasterio.open(tmp_path / "scaled.tif") as ds:
        ours = ds.read(1).astype(bool)
        gdal = rasterize([(p, 1) for p in geoms], out_shape=ours.shape, transform=ds.transform).astype(bool)
        assert ds.crs.to_epsg() == 32633
        written = g.covering(doc.get(rid).source.bbox)
        assert tuple(ds.transform)[:6] == written.transform
    assert ours.sum() > 3 * mask.sum()
    frame = written.frame  # the raster's pixel (col, row) is the result's grid pixel (col + x0, y1 − row)
    r_a = doc.derived(oid).get("euclidean")  # R(A) in grid coordinates
    rows, cols = np.nonzero(ours != gdal)
    for r, c in zip(rows, cols, strict=True):
        u, v = c + frame[0], frame[3] - r
        assert _on_boundary(r_a, Fraction(u, alpha), Fraction(v, alpha)), (u, v)


def test_rotation_and_union_keep_the_grid_and_mixed_grids_drop_it(tmp_path):
    doc, oid = imported(tmp_path, blobs(16, 20, 3))
    g = doc.get(oid).georef
    params = {"angle": 30, "center": [8, 8], "model": "gauss"}
    (rot,) = apply_operation(doc, "discrete_rotation", [oid], params)
    assert doc.get(rot).georef == g
    (uni,) = apply_operation(doc, "union", [oid, rot], {"model": "gauss"})
    assert doc.get(uni).georef == g
    plain = doc.make_object(PixelSet.from_points([(0, 0)]), "plain")
    from mrm.document.commands import AddObject

    doc.push(AddObject(plain))
    (mixed,) = apply_operation(doc, "union", [oid, plain.id], {"model": "gauss"})
    assert doc.get(mixed).georef is None  # a plain grid and a georeferenced one: no single place
    doc.push(MergeObjects([oid, rot]))
    merged = next(o for o in doc.objects if o.provenance is not None and o.provenance.operation == "merge")
    assert merged.georef == g


def test_several_objects_in_one_geojson_need_one_crs(tmp_path):
    doc, oid = imported(tmp_path, blobs(16, 16, 6))
    plain = doc.make_object(PixelSet.from_points([(0, 0)]), "plain")
    from mrm.document.commands import AddObject

    doc.push(AddObject(plain))
    with pytest.raises(Exception, match="not all georeferenced in one CRS"):
        export_objects_geojson(doc, [oid, plain.id], tmp_path / "both.geojson")
    export_objects_geojson(doc, [oid], tmp_path / "one.geojson")
    assert json.loads((tmp_path / "one.geojson").read_text())["crs"]["properties"]["name"].endswith("32633")


def test_the_v3_golden_file_holds_a_georeference_and_v2_files_have_none():
    doc = load_project(GOLDEN / "v3-georef.mrm")
    assert doc.get(3).georef == GeoRef(
        (30.0, 0.0, 499910.0, 0.0, -30.0, 4200090.0), 5, 5, "EPSG:32633", (-2, -2)
    )
    assert all(o.georef is None for o in doc.objects if o.id != 3)
    assert all(o.georef is None for o in load_project(GOLDEN / "v2-pinned-provenance.mrm").objects)


@pytest.mark.parametrize(
    ("value", "message"),
    [
        ({"transform": [1.0, 0.0, 0.0, 0.0, -1.0], "width": 2, "height": 2, "crs": None}, r"six numbers"),
        ({"transform": [1.0, 0.0, 0.0, 2.0, 0.0, 0.0], "width": 2, "height": 2, "crs": None}, "invertible"),
        ({"transform": [1, 0, 0, 0, -1, 0], "width": 0, "height": 2, "crs": None}, r"\.width: integer 0"),
        ({"transform": [1, 0, 0, 0, -1, 0], "width": 2, "height": 2, "crs": 7}, r"\.crs: expected a string"),
        ({"transform": [1, 0, 0, 0, -1, 0], "width": 2, "height": 2}, r"missing key 'crs'"),
    ],
)
def test_a_bad_georeference_in_a_project_is_named_by_its_path(value, message):
    data = json.loads((GOLDEN / "v3-georef.mrm").read_text())
    data["objects"][0]["georef"] = value
    with pytest.raises(FileFormatError, match=message) as info:
        loads(json.dumps(data).encode(), "bad.mrm")
    assert "$.objects[0].georef" in str(info.value)


def test_a_unit_grid_tif_reconstructs_in_place(tmp_path):
    """A .tif written from a pixel set off the origin reads back in place, and R lands where the set is."""
    import subprocess
    import sys

    import mrm

    ps = mrm.PixelSet.from_points([(3, -2), (4, -2), (3, 0)])
    mrm.write_pixels(ps, tmp_path / "u.tif")
    g = read_georef(tmp_path / "u.tif")
    assert g is not None and g.origin == (3, -2) and g.frame == (3, -2, 4, 0)
    done = subprocess.run(
        [sys.executable, "-m", "mrm", "reconstruct", "u.tif", "-o", "u.geojson", "--model", "gauss"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    assert mrm.discretize(mrm.read_geometry(tmp_path / "u.geojson"), "gauss") == ps  # not shifted
