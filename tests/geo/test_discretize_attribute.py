"""``mrm discretize --attribute FIELD`` (issue 31 item 2): each feature's value burnt into a label raster on
a template's grid, as ``gdal_rasterize -a`` does, read from GeoJSON, GeoPackage, Shapefile and FlatGeobuf.

GDAL (``rasterio.features.rasterize``, the centre rule, the last feature winning where they overlap) is the
reference under ``gauss`` (the centre rule model); the output's CRS and transform are the template's.
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
import shapely.affinity
from rasterio.features import rasterize
from rasterio.transform import from_origin
from shapely.geometry import Polygon

PY = sys.executable
T = from_origin(500_000.0, 4_200_000.0, 30.0, 30.0)
CRS = "EPSG:32633"


def mrm_run(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([PY, "-m", "mrm", *args], cwd=cwd, capture_output=True, text=True)


def one_error_line(stderr: str) -> bool:
    lines = [x for x in stderr.splitlines() if not x.startswith("mrm: first run")]
    return len(lines) == 1 and lines[0].startswith("mrm discretize: error: ")


def template(path: Path, crs: str = CRS) -> None:
    with rasterio.open(path, "w", driver="GTiff", width=60, height=40, count=1, dtype="uint8", transform=T,
                       crs=crs) as ds:  # fmt: skip
        ds.write(np.zeros((40, 60), np.uint8), 1)


def fields_layer(seed: int) -> list[Polygon]:
    """Overlapping convex polygons with vertices off the pixel centres (no centre-rule ties)."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(12):
        cx, cy = 500_000 + rng.uniform(100, 1700), 4_200_000 - rng.uniform(100, 1100)
        n = int(rng.integers(3, 6))
        ang = np.sort(rng.uniform(0, 2 * np.pi, n))
        r = rng.uniform(60, 400, n)
        pts = shapely.multipoints(np.column_stack((cx + r * np.cos(ang), cy + r * np.sin(ang))) + 0.123)
        out.append(shapely.convex_hull(pts))
    return out


def write_layer(path: Path, geoms, values, crs=CRS, name="cls") -> None:
    pyogrio.raw.write(path, shapely.to_wkb(geoms), field_data=[np.asarray(values)], fields=[name],
                      geometry_type="Polygon", crs=crs, driver=None)  # fmt: skip


@pytest.mark.parametrize("ext", [".gpkg", ".shp", ".fgb", ".geojson"])
def test_burns_each_features_value_as_gdal_does_on_the_templates_grid(tmp_path, ext):
    template(tmp_path / "grid.tif")
    geoms = fields_layer(0)
    values = np.arange(1, len(geoms) + 1) * 11
    write_layer(tmp_path / f"fields{ext}", geoms, values)
    args = ("--attribute", "cls", "--like", "grid.tif", "--model", "gauss", "-o", "out.tif")
    done = mrm_run("discretize", f"fields{ext}", *args, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    with rasterio.open(tmp_path / "out.tif") as ds:
        assert ds.crs == rasterio.crs.CRS.from_epsg(32633)
        assert ds.transform == T and (ds.width, ds.height) == (60, 40)
        got = ds.read(1)
    # The layer's order as GDAL reads it (FlatGeobuf's spatial index reorders the features it writes).
    _, _, wkb, data = pyogrio.raw.read(tmp_path / f"fields{ext}")
    layer = zip(shapely.from_wkb(wkb), np.asarray(data[0]).tolist(), strict=True)
    want = rasterize(layer, out_shape=(40, 60), transform=T, dtype="int32")
    assert (got == want).all()  # the same pixels, the last feature winning where they overlap
    assert len(np.unique(got)) > 5


def test_a_png_output_carries_the_templates_crs_for_gdal(tmp_path):
    template(tmp_path / "grid.tif")
    geoms = fields_layer(1)
    write_layer(tmp_path / "f.gpkg", geoms, np.full(len(geoms), 9))
    done = mrm_run(
        "discretize", "f.gpkg", "--attribute", "cls", "--like", "grid.tif", "-o", "out.png", cwd=tmp_path
    )
    assert done.returncode == 0, done.stderr
    with rasterio.open(tmp_path / "out.png") as ds:
        assert ds.crs == rasterio.crs.CRS.from_epsg(32633) and ds.transform == T
        assert set(np.unique(ds.read(1)).tolist()) == {0, 9}


@pytest.mark.parametrize(
    ("values", "args", "words"),
    [
        (np.array(["a", "b"] * 6, dtype=object), (), "burning needs integers"),
        (np.linspace(0.5, 6, 12), (), "is not an integer label"),
        (np.arange(12), ("--attribute", "nope"), "no field 'nope'"),
        (np.arange(12) + 70_000, ("-o", "out.png"), "a PNG holds labels 0 to 65535"),
    ],
)
def test_values_that_cannot_be_labels_give_one_line(tmp_path, values, args, words):
    template(tmp_path / "grid.tif")
    write_layer(tmp_path / "f.gpkg", fields_layer(2), values)
    opts = {"--attribute": "cls", "-o": "out.tif"}
    for k, v in zip(args[::2], args[1::2], strict=True):
        opts[k] = v
    done = mrm_run(
        "discretize", "f.gpkg", "--like", "grid.tif", *[x for kv in opts.items() for x in kv], cwd=tmp_path
    )
    assert done.returncode == 2, done.stderr
    assert one_error_line(done.stderr) and words in done.stderr, done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.gpkg", "grid.tif"]


def test_a_layer_in_another_crs_than_the_template_is_refused(tmp_path):
    template(tmp_path / "grid.tif")
    write_layer(tmp_path / "f.fgb", fields_layer(3), np.arange(12), crs="EPSG:4326")
    done = mrm_run(
        "discretize", "f.fgb", "--attribute", "cls", "--like", "grid.tif", "-o", "o.tif", cwd=tmp_path
    )
    assert done.returncode == 2 and one_error_line(done.stderr) and "reproject" in done.stderr


@pytest.mark.filterwarnings("ignore:'crs' was not provided")
def test_resolution_grid_takes_the_layers_crs_and_no_grid_gives_a_label_map(tmp_path):
    geoms = fields_layer(4)
    write_layer(tmp_path / "f.gpkg", geoms, np.arange(1, 13))
    grid = ("--resolution", "30", "--extent", "500000,4198800,501800,4200000")
    done = mrm_run(
        "discretize", "f.gpkg", "--attribute", "cls", *grid, "--model", "gauss", "-o", "r.tif", cwd=tmp_path
    )
    assert done.returncode == 0, done.stderr
    with rasterio.open(tmp_path / "r.tif") as ds:
        assert ds.crs == rasterio.crs.CRS.from_epsg(32633) and ds.transform == T
        got = ds.read(1)
    want = rasterize(zip(geoms, range(1, 13), strict=True), out_shape=got.shape, transform=T, dtype="int32")
    assert (got == want).all()
    # Without a grid: a label map in the layer's own coordinates (pixel (x, y) centred on (x, y)).
    from mrm.io.pixel_files import read_label_map

    small = [shapely.affinity.translate(shapely.affinity.scale(g, 0.05, 0.05, origin=(500_000, 4_199_000)),
                                        -500_000, -4_199_000) for g in geoms]  # fmt: skip
    write_layer(tmp_path / "g.fgb", small, np.arange(1, 13) * 1000, crs=None)
    done = mrm_run(
        "discretize", "g.fgb", "--attribute", "cls", "--model", "gauss", "-o", "g.npz", cwd=tmp_path
    )
    assert done.returncode == 0, done.stderr
    lm = read_label_map(tmp_path / "g.npz")
    assert set(lm.label_values()) <= set(range(1000, 13_000, 1000)) and len(lm.label_values()) > 3


@pytest.mark.parametrize("ext", [".gpkg", ".shp", ".fgb"])
def test_without_attribute_a_layer_is_discretized_whole(tmp_path, ext):
    template(tmp_path / "grid.tif")
    geoms = fields_layer(5)
    write_layer(tmp_path / f"f{ext}", geoms, np.arange(12))
    done = mrm_run(
        "discretize", f"f{ext}", "--like", "grid.tif", "--model", "gauss", "-o", "m.tif", cwd=tmp_path
    )
    assert done.returncode == 0, done.stderr
    with rasterio.open(tmp_path / "m.tif") as ds:
        assert ds.crs == rasterio.crs.CRS.from_epsg(32633) and ds.transform == T
        got = ds.read(1)
    assert (got == rasterize([(g, 1) for g in geoms], out_shape=(40, 60), transform=T, dtype="uint8")).all()
    write_layer(tmp_path / f"w{ext}", geoms, np.arange(12), crs="EPSG:4326")
    done = mrm_run("discretize", f"w{ext}", "--like", "grid.tif", "-o", "w.tif", cwd=tmp_path)
    assert done.returncode == 2 and one_error_line(done.stderr) and "reproject" in done.stderr


@pytest.mark.parametrize(("name", "content"), [("f.gpkg", b"<VRTDataset>"), ("f.fgb", b"{}"), ("f.shp", b"")])
def test_a_file_that_is_not_the_layer_its_name_says_gives_one_line(tmp_path, name, content):
    template(tmp_path / "grid.tif")
    (tmp_path / name).write_bytes(content)
    done = mrm_run(
        "discretize", name, "--attribute", "cls", "--like", "grid.tif", "-o", "o.tif", cwd=tmp_path
    )
    assert done.returncode == 2 and one_error_line(done.stderr), done.stderr
    assert "not a" in done.stderr and not (tmp_path / "o.tif").exists()
