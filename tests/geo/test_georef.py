"""Georeferenced rasters (issue 12 deliverable 3): GeoTIFF and world files, transform and CRS carried through.

The rasters are built in the tests with rasterio; GDAL's own rasterizer (``rasterio.features.rasterize``) is
the reference the results are compared with, pixel for pixel.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import rasterio
from rasterio.features import rasterize
from rasterio.transform import from_origin
from shapely.geometry import box, shape

import mrm
from mrm.core.georef import GeoRef
from mrm.io.georef import parse_world_file, world_file_text

PY = sys.executable
T = from_origin(500_000.0, 4_200_000.0, 30.0, 30.0)  # UTM 33N, 30 m pixels
CRS = "EPSG:32633"


def mrm_run(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([PY, "-m", "mrm", *args], cwd=cwd, capture_output=True, text=True)


def blobs(h: int, w: int, seed: int) -> np.ndarray:
    """A mask with components, holes and diagonal contacts (a thresholded smooth noise)."""
    rng = np.random.default_rng(seed)
    noise = rng.random((h // 4 + 2, w // 4 + 2))
    big = np.kron(noise, np.ones((4, 4)))[:h, :w]
    return (big + 0.3 * rng.random((h, w))) > 0.75


def write_tif(path: Path, mask: np.ndarray, transform=T, crs=CRS) -> None:
    with rasterio.open(
        path,
        "w",
        driver="GTiff",
        width=mask.shape[1],
        height=mask.shape[0],
        count=1,
        dtype="uint8",
        transform=transform,
        crs=crs,
    ) as ds:
        ds.write(mask.astype(np.uint8), 1)


def features(path: Path) -> tuple[dict, list]:
    doc = json.loads(path.read_text())
    return doc, [shape(f["geometry"]) for f in doc["features"]]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_reconstruct_lands_on_the_raster_and_rasterizes_back_exactly(tmp_path, seed):
    mask = blobs(48, 64, seed)
    write_tif(tmp_path / "dem_mask.tif", mask)
    done = mrm_run("reconstruct", "dem_mask.tif", "-o", "out.geojson", "--model", "gauss", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    doc, geoms = features(tmp_path / "out.geojson")
    assert doc["crs"]["properties"]["name"] == "urn:ogc:def:crs:EPSG::32633"
    xmin, ymin, xmax, ymax = doc["bbox"]
    # The gauss boundary stays within the voxels of the border pixels on either side (docs/design.md §3.2): at
    # most one 30 m pixel beyond the raster's edge, where a blob touches it.
    px = 30
    assert xmin >= 500_000 - px and xmax <= 500_000 + 64 * 30 + px
    assert ymin >= 4_200_000 - 48 * 30 - px and ymax <= 4_200_000 + px
    burned = rasterize([(g, 1) for g in geoms], out_shape=mask.shape, transform=T, dtype="uint8")
    assert (burned.astype(bool) == mask).all()  # GDAL's centre rule gives the mask back, pixel for pixel


def test_png_with_a_world_file(tmp_path):
    from PIL import Image

    mask = blobs(20, 30, 5)
    Image.fromarray(mask).save(tmp_path / "m.png")
    (tmp_path / "m.pgw").write_text(world_file_text(tuple(T)[:6]))
    done = mrm_run("reconstruct", "m.png", "-o", "m.geojson", "--model", "gauss", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    _, geoms = features(tmp_path / "m.geojson")
    burned = rasterize([(g, 1) for g in geoms], out_shape=mask.shape, transform=T, dtype="uint8")
    assert (burned.astype(bool) == mask).all()


def test_discretize_like_burns_on_the_rasters_grid_as_gdal_does(tmp_path):
    write_tif(tmp_path / "dem_mask.tif", np.zeros((40, 50), dtype=bool))
    rng = np.random.default_rng(7)
    parcels = []
    for _ in range(6):
        x, y = 500_000 + rng.uniform(0, 1300), 4_200_000 - rng.uniform(100, 1100)
        parcels.append(box(x, y, x + rng.uniform(40, 300), y + rng.uniform(40, 300)).buffer(17.3, 3))
    fc = {
        "type": "FeatureCollection",
        "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32633"}},
        "features": [{"type": "Feature", "properties": {}, "geometry": p.__geo_interface__} for p in parcels],
    }
    (tmp_path / "parcels.geojson").write_text(json.dumps(fc))
    done = mrm_run(
        "discretize",
        "parcels.geojson",
        "--like",
        "dem_mask.tif",
        "-o",
        "out.tif",
        "--model",
        "gauss",
        cwd=tmp_path,
    )
    assert done.returncode == 0, done.stderr
    with rasterio.open(tmp_path / "out.tif") as ds:
        assert ds.transform == T and ds.crs.to_epsg() == 32633 and (ds.width, ds.height) == (50, 40)
        ours = ds.read(1).astype(bool)
    gdal = rasterize([(p, 1) for p in parcels], out_shape=(40, 50), transform=T, dtype="uint8").astype(bool)
    assert ours.any() and (ours == gdal).all()


def test_discretize_refuses_another_crs(tmp_path):
    write_tif(tmp_path / "r.tif", np.zeros((4, 4), dtype=bool))
    fc = {
        "type": "FeatureCollection",
        "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::4326"}},
        "features": [
            {"type": "Feature", "properties": {}, "geometry": box(10, 45, 11, 46).__geo_interface__}
        ],
    }
    (tmp_path / "p.geojson").write_text(json.dumps(fc))
    done = mrm_run("discretize", "p.geojson", "--like", "r.tif", "-o", "o.tif", cwd=tmp_path)
    assert done.returncode == 2 and "does not reproject" in done.stderr and not (tmp_path / "o.tif").exists()


def test_resolution_extent_and_the_few_pixels_warning(tmp_path):
    (tmp_path / "deg.wkt").write_text(
        "POLYGON ((10.0 45.0, 10.002 45.0, 10.002 45.001, 10.0 45.001, 10.0 45.0))"
    )
    tiny = mrm_run("discretize", "deg.wkt", "-o", "tiny.png", "--model", "gauss", cwd=tmp_path)
    assert tiny.returncode == 0
    assert "warning" in tiny.stderr and "--resolution" in tiny.stderr  # 1 pixel: degrees, not pixels
    fine = mrm_run(
        "discretize",
        "deg.wkt",
        "-o",
        "fine.tif",
        "--model",
        "gauss",
        "--resolution",
        "0.0001",
        "--extent",
        "9.999,44.999,10.003,45.002",
        cwd=tmp_path,
    )
    assert fine.returncode == 0 and "warning" not in fine.stderr, fine.stderr
    with rasterio.open(tmp_path / "fine.tif") as ds:
        assert ds.transform.almost_equals(from_origin(9.999, 45.002, 0.0001, 0.0001))
        assert (ds.width, ds.height) == (40, 30)
        burned = ds.read(1).astype(bool)
    ref = rasterize([(box(10.0, 45.0, 10.002, 45.001), 1)], out_shape=(30, 40), transform=ds.transform)
    assert (burned == ref.astype(bool)).all() and burned.sum() == 20 * 10
    png = mrm_run(
        "discretize", "deg.wkt", "-o", "fine.png", "--model", "gauss", "--resolution", "0.0001", cwd=tmp_path
    )
    assert png.returncode == 0, png.stderr
    assert (tmp_path / "fine.pgw").is_file()
    back = mrm_run("reconstruct", "fine.png", "-o", "back.geojson", "--model", "gauss", cwd=tmp_path)
    assert back.returncode == 0, back.stderr
    _, geoms = features(tmp_path / "back.geojson")
    assert geoms[0].bounds[0] == pytest.approx(10.0, abs=1e-4) and geoms[0].bounds[3] == pytest.approx(
        45.001, abs=1e-4
    )


def test_an_unreferenced_grid_is_gdals_from_origin(tmp_path):
    ps = mrm.PixelSet.from_points([(3, -2), (4, -2), (3, 0)])  # origin (3, -2), 2 wide, 3 high
    mrm.write_pixels(ps, tmp_path / "p.tif")
    with rasterio.open(tmp_path / "p.tif") as ds:
        assert ds.transform == from_origin(3 - 0.5, -2 + 3 - 0.5, 1, 1)
    assert mrm.read_pixels(tmp_path / "p.tif") == ps
    # and GDAL burns R(A) back to A on that grid
    poly = mrm.reconstruct(ps, "gauss")
    with rasterio.open(tmp_path / "p.tif") as ds:
        burned = rasterize([(poly, 1)], out_shape=(ds.height, ds.width), transform=ds.transform)
        assert (burned == ds.read(1)).all()


def test_world_file_convention():
    # A D B E C F with C, F the centre of the top-left pixel (GDAL: its corner)
    t = parse_world_file("30\n0\n0\n-30\n500015\n4199985\n", "x.pgw")
    assert t == (30.0, 0.0, 500_000.0, 0.0, -30.0, 4_200_000.0)
    assert parse_world_file(world_file_text(t), "y.pgw") == t
    g = GeoRef(t, 10, 10)
    corner = g.to_world(box(-0.5, 8.5, -0.4, 9.5))  # the top-left pixel's left side, grid (−½, 9½) on top
    assert corner.bounds[0] == 500_000.0 and corner.bounds[3] == 4_200_000.0


@pytest.mark.parametrize(
    ("model", "all_touched"), [("gauss", False), ("supercover", True), ("standard", True)]
)
def test_which_model_round_trips_through_gdal_rasterize(model, all_touched):
    """docs/gdal.md's table: R under `model`, burned by GDAL with or without -at, gives the mask back."""
    g = GeoRef(tuple(T)[:6], 64, 48)
    for seed in range(4):
        mask = blobs(48, 64, 10 + seed)
        poly = g.to_world(mrm.reconstruct(mrm.PixelSet.from_image(mask), model))
        burned = rasterize([(poly, 1)], out_shape=mask.shape, transform=T, all_touched=all_touched)
        assert (burned.astype(bool) == mask).all()


def test_gauss_does_not_round_trip_with_all_touched():
    """The compact gauss R leaves the mask's voxels (docs/design.md §3.2): GDAL's -at burns around it."""
    g = GeoRef(tuple(T)[:6], 64, 48)
    mask = blobs(48, 64, 3)
    poly = g.to_world(mrm.reconstruct(mrm.PixelSet.from_image(mask), "gauss"))
    burned = rasterize([(poly, 1)], out_shape=mask.shape, transform=T, all_touched=True).astype(bool)
    assert (burned & ~mask).any() and not (mask & ~burned).any()  # a superset: every pixel of A, and more


def test_the_covers_do_not_round_trip_with_the_centre_rule():
    g = GeoRef(tuple(T)[:6], 64, 48)
    mask = blobs(48, 64, 3)
    poly = g.to_world(mrm.reconstruct(mrm.PixelSet.from_image(mask), "supercover"))
    burned = rasterize([(poly, 1)], out_shape=mask.shape, transform=T).astype(bool)
    assert burned.sum() < mask.sum() and not (burned & ~mask).any()  # thinner: the cover's R hugs the voxels
