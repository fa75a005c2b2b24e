"""Classified GeoTIFFs to vector layers (issue 31 item 2): ``mrm polygonize`` with band, nodata, mask and
connectivity, written as GeoPackage, Shapefile, FlatGeobuf and GeoJSON with the CRS.

Every output is read back with pyogrio (GDAL) and compared exactly: the CRS, each polygon's world coordinates
against the raster's transform applied to the library's own grid polygons, and the burnt-back raster
(``rasterio.features.rasterize``, GDAL's centre rule) against the classified band, pixel for pixel.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pyogrio
import pytest
import rasterio
import shapely
from pyproj import CRS as ProjCRS
from rasterio.features import rasterize
from rasterio.transform import from_origin

from mrm.core.grids import LabelMap
from mrm.geometry.reconstruct.polygonize import polygonize
from mrm.io.georef import world_file_text

PY = sys.executable
#: The CRS comparisons go through PROJ strings (``to_dict``), which pyproj warns are lossy in general.
pytestmark = pytest.mark.filterwarnings("ignore:You will likely lose important projection information")
T = from_origin(500_000.0, 4_200_000.0, 30.0, 30.0)
CRS = "EPSG:32633"
#: A CRS without an EPSG code: a custom Lambert conformal conic.
CUSTOM = (
    "+proj=lcc +lat_1=41.5 +lat_2=47.5 +lat_0=44.25 +lon_0=2.7 +x_0=700000 +y_0=6600000 "
    "+ellps=GRS80 +units=m +no_defs"
)
NODATA = 255


def mrm_run(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([PY, "-m", "mrm", *args], cwd=cwd, capture_output=True, text=True)


def one_error_line(stderr: str) -> bool:
    """The command's refusal is one line (``mrm polygonize: error: …``), no traceback."""
    lines = [x for x in stderr.splitlines() if not x.startswith("mrm: first run")]
    return len(lines) == 1 and lines[0].startswith("mrm polygonize: error: ")


def classes(h: int, w: int, seed: int, k: int = 6) -> np.ndarray:
    """A classification: smoothed noise quantized into ``k`` classes (0 is a class), a nodata corner."""
    rng = np.random.default_rng(seed)
    big = np.kron(rng.random((h // 5 + 2, w // 5 + 2)), np.ones((5, 5)))[:h, :w] + 0.2 * rng.random((h, w))
    cls = np.minimum(big / 1.2 * k, k - 1).astype(np.uint8)
    cls[:3, :4] = NODATA
    return cls


def write_tif(path: Path, bands: list[np.ndarray], crs=CRS, nodata=NODATA, transform=T) -> None:
    with rasterio.open(
        path, "w", driver="GTiff", width=bands[0].shape[1], height=bands[0].shape[0], count=len(bands),
        dtype=bands[0].dtype, transform=transform, crs=crs, nodata=nodata,
    ) as ds:  # fmt: skip
        for i, b in enumerate(bands, 1):
            ds.write(b, i)


def grid_polygons(cls: np.ndarray) -> list:
    """The library's polygons of the classes (label = class + 1, nodata out), in grid coordinates."""
    lab = np.where(cls == NODATA, 0, cls.astype(np.int32) + 1)
    return polygonize(LabelMap(lab[::-1]))


def world(g, h: int):
    """Grid polygon -> world: T applied to the pixel-corner coordinates (col, row) = (u + ½, h − ½ − v)."""

    def corners(c):
        col, row = c[:, 0] + 0.5, h - 0.5 - c[:, 1]
        return np.column_stack((T.a * col + T.b * row + T.c, T.d * col + T.e * row + T.f))

    return shapely.transform(g, corners)


def read_back(path: Path, field: str = "label"):
    meta, _, wkb, data = pyogrio.raw.read(path)
    fields = list(meta["fields"])
    return meta, shapely.from_wkb(wkb), {f: np.asarray(data[i]) for i, f in enumerate(fields)}


@pytest.mark.parametrize("ext", [".gpkg", ".shp", ".fgb", ".geojson"])
def test_every_format_reads_back_with_the_crs_exact_coordinates_and_burns_back(tmp_path, ext):
    cls = classes(40, 50, 0)
    write_tif(tmp_path / "landcover.tif", [cls])
    done = mrm_run("polygonize", "landcover.tif", "-o", f"out{ext}", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    meta, geoms, fields = read_back(tmp_path / f"out{ext}")
    assert ProjCRS.from_user_input(meta["crs"]) == ProjCRS.from_epsg(32633)
    # Exactly the library's polygons, moved by the raster's transform (the same float64 coordinates).
    expected = grid_polygons(cls)
    assert len(geoms) == len(expected)
    got = sorted(shapely.normalize(geoms).tolist(), key=lambda g: g.wkb)
    want = sorted(shapely.normalize([world(r.geometry, 40) for r in expected]).tolist(), key=lambda g: g.wkb)
    assert all(shapely.equals_exact(a, b, tolerance=0) for a, b in zip(got, want, strict=True))
    # GDAL burns the features with their class value back to the band, nodata included (fill).
    burnt = rasterize(zip(geoms, fields["label"].tolist(), strict=True), out_shape=cls.shape, transform=T,
                      fill=NODATA, dtype="uint8")  # fmt: skip
    assert (burnt == cls).all()
    assert fields["pixels"].sum() == int((cls != NODATA).sum())


@pytest.mark.parametrize("ext", [".gpkg", ".shp", ".fgb"])
def test_a_crs_without_epsg_code_is_kept_as_wkt(tmp_path, ext):
    write_tif(tmp_path / "c.tif", [classes(20, 30, 1)], crs=CUSTOM)
    done = mrm_run("polygonize", "c.tif", "-o", f"out{ext}", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    meta, _, _ = read_back(tmp_path / f"out{ext}")
    assert meta["crs"] is not None
    # The same projection and parameters (a Shapefile's ESRI WKT renames the datum "D_Unknown…").
    assert ProjCRS.from_user_input(meta["crs"]).to_dict() == ProjCRS.from_proj4(CUSTOM).to_dict()


def test_geojson_refuses_a_crs_it_cannot_carry_in_one_line(tmp_path):
    write_tif(tmp_path / "c.tif", [classes(20, 30, 1)], crs=CUSTOM)
    done = mrm_run("polygonize", "c.tif", "-o", "out.geojson", cwd=tmp_path)
    assert done.returncode == 2
    assert one_error_line(done.stderr)
    assert "EPSG" in done.stderr and ".gpkg" in done.stderr
    assert not (tmp_path / "out.geojson").exists()


def test_band_nodata_option_mask_and_field_names(tmp_path):
    cls = classes(30, 40, 2)
    other = np.full(cls.shape, 7, np.uint8)
    write_tif(tmp_path / "two.tif", [other, cls], nodata=None)
    mask = np.ones(cls.shape, np.uint8)
    mask[10:20, 10:25] = 0
    write_tif(tmp_path / "mask.tif", [mask], nodata=None)
    done = mrm_run(
        "polygonize", "two.tif", "--band", "2", "--nodata", "255", "--mask", "mask.tif",
        "--field", "class", "--pixels-field", "n", "-o", "out.gpkg", cwd=tmp_path,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    _, geoms, fields = read_back(tmp_path / "out.gpkg")
    assert set(fields) == {"class", "n"}
    expected = np.where(mask == 0, NODATA, cls)
    burnt = rasterize(zip(geoms, fields["class"].tolist(), strict=True), out_shape=cls.shape, transform=T,
                      fill=NODATA, dtype="uint8")  # fmt: skip
    assert (burnt == expected).all()


def test_8_connected_regions_are_one_feature_each(tmp_path):
    from skimage.measure import label as cc

    cls = classes(40, 50, 3)
    write_tif(tmp_path / "c.tif", [cls])
    done = mrm_run("polygonize", "c.tif", "--connectivity", "8", "-o", "out.fgb", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    _, geoms, fields = read_back(tmp_path / "out.fgb")
    n8 = sum(int(cc(cls == k, connectivity=2).max()) for k in np.unique(cls) if k != NODATA)
    assert len(geoms) == n8 < len(grid_polygons(cls))
    burnt = rasterize(zip(geoms, fields["label"].tolist(), strict=True), out_shape=cls.shape, transform=T,
                      fill=NODATA, dtype="uint8")  # fmt: skip
    assert (burnt == cls).all()
    # Each feature's pixel count is its 8-connected component's.
    sizes = sorted(
        int(n)
        for k in np.unique(cls)
        if k != NODATA
        for n in np.bincount(cc(cls == k, connectivity=2).ravel())[1:]
    )
    assert sorted(fields["pixels"].tolist()) == sizes


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (("--band", "3"), "no band 3"),
        (("--nodata", "300"), "not a value of the band's type uint8"),
        (("--field", 'la"bel'), "field name"),
        (("--field", "label", "--pixels-field", "LABEL"), "twice"),
    ],
)
def test_hostile_options_give_one_line_and_write_nothing(tmp_path, args, words):
    write_tif(tmp_path / "c.tif", [classes(20, 30, 4)])
    done = mrm_run("polygonize", "c.tif", *args, "-o", "out.gpkg", cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    assert one_error_line(done.stderr)
    assert words in done.stderr
    assert list(tmp_path.iterdir()) == [tmp_path / "c.tif"]


def test_help_states_the_model_polygonize_uses(tmp_path):
    done = mrm_run("polygonize", "--help", cwd=tmp_path)
    assert done.returncode == 0
    text = " ".join(done.stdout.split())
    assert "only 'gauss'" in text and "'standard'" not in text


def test_a_float_band_with_nan_nodata_polygonizes_and_a_fraction_is_refused(tmp_path):
    cls = classes(30, 40, 5).astype(np.float32)
    cls[cls == NODATA] = np.nan
    write_tif(tmp_path / "f.tif", [cls], nodata=np.nan)
    done = mrm_run("polygonize", "f.tif", "-o", "f.gpkg", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    _, geoms, fields = read_back(tmp_path / "f.gpkg")
    burnt = rasterize(zip(geoms, fields["label"].tolist(), strict=True), out_shape=cls.shape, transform=T,
                      fill=-1, dtype="float32")  # fmt: skip
    assert (burnt == np.nan_to_num(cls, nan=-1)).all()
    cls[5, 5] = 2.5
    write_tif(tmp_path / "g.tif", [cls], nodata=np.nan)
    done = mrm_run("polygonize", "g.tif", "-o", "g.gpkg", cwd=tmp_path)
    assert done.returncode == 2 and one_error_line(done.stderr) and "found 2.5" in done.stderr, done.stderr
    assert not (tmp_path / "g.gpkg").exists()


def test_a_shapefile_rewritten_without_crs_loses_its_old_prj(tmp_path):
    from PIL import Image

    write_tif(tmp_path / "c.tif", [classes(20, 30, 6)])
    assert mrm_run("polygonize", "c.tif", "-o", "out.shp", cwd=tmp_path).returncode == 0
    assert (tmp_path / "out.prj").is_file()
    lab = np.zeros((8, 8), np.uint8)
    lab[2:6, 1:5] = 3
    Image.fromarray(lab).save(tmp_path / "plain.png")  # no world file: grid coordinates, no CRS
    done = mrm_run("polygonize", "plain.png", "-o", "out.shp", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert not (tmp_path / "out.prj").exists()  # the new layer is not placed by the old CRS
    meta, geoms, fields = read_back(tmp_path / "out.shp")
    assert meta["crs"] is None and fields["label"].tolist() == [3] and len(geoms) == 1


def test_a_png_label_image_with_a_world_file_and_a_mask(tmp_path):
    from PIL import Image

    cls = classes(20, 30, 7)
    cls[cls == NODATA] = 0  # a PNG label image: 0 is the background
    Image.fromarray(cls).save(tmp_path / "lab.png")
    (tmp_path / "lab.pgw").write_text(world_file_text(tuple(T)[:6]))
    mask = np.full(cls.shape, 255, np.uint8)
    mask[:, :10] = 0
    Image.fromarray(mask).save(tmp_path / "keep.png")
    done = mrm_run("polygonize", "lab.png", "--mask", "keep.png", "-o", "out.fgb", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    _, geoms, fields = read_back(tmp_path / "out.fgb")
    burnt = rasterize(zip(geoms, fields["label"].tolist(), strict=True), out_shape=cls.shape, transform=T,
                      fill=0, dtype="uint8")  # fmt: skip
    assert (burnt == np.where(mask == 0, 0, cls)).all()


@pytest.mark.parametrize(("shape", "name", "words"), [((20, 31), "m.tif", "not on the grid"),
                                                     ((20, 31), "m.png", "the mask has 31×20 pixels"),
                                                     ((20, 30), "m.npz", "a mask is an image")])  # fmt: skip
def test_a_mask_off_the_rasters_grid_gives_one_line(tmp_path, shape, name, words):
    from PIL import Image

    write_tif(tmp_path / "c.tif", [classes(20, 30, 8)])
    m = np.ones(shape, np.uint8)
    if name.endswith(".tif"):
        write_tif(tmp_path / name, [m], nodata=None)
    elif name.endswith(".png"):
        Image.fromarray(m * 255).save(tmp_path / name)
    else:
        np.savez(tmp_path / name, mask=m.astype(bool))
    done = mrm_run("polygonize", "c.tif", "--mask", name, "-o", "o.gpkg", cwd=tmp_path)
    assert done.returncode == 2 and one_error_line(done.stderr) and words in done.stderr, done.stderr
    assert not (tmp_path / "o.gpkg").exists()
