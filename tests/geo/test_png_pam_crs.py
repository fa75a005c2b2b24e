"""PNG + world file carry the CRS the way GDAL does (issue 31 item 2): GDAL ignores a ``.prj`` beside a PNG
and reads the PAM side file ``name.png.aux.xml``. MR Modeler writes it with the world file (one output set)
and reads it with its own bounded parser; rasterio (GDAL) is the judge of what is written.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import rasterio
from pyproj import CRS as ProjCRS
from rasterio.transform import from_origin

PY = sys.executable
#: The CRS comparisons go through PROJ strings (``to_dict``), which pyproj warns are lossy in general.
pytestmark = pytest.mark.filterwarnings("ignore:You will likely lose important projection information")
T = from_origin(500_000.0, 4_200_000.0, 30.0, 30.0)
CUSTOM = (
    "+proj=lcc +lat_1=41.5 +lat_2=47.5 +lat_0=44.25 +lon_0=2.7 +x_0=700000 +y_0=6600000 "
    "+ellps=GRS80 +units=m +no_defs"
)


def mrm_run(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([PY, "-m", "mrm", *args], cwd=cwd, capture_output=True, text=True)


def write_tif(path: Path, a: np.ndarray, crs: str) -> None:
    with rasterio.open(path, "w", driver="GTiff", width=a.shape[1], height=a.shape[0], count=1, dtype="uint8",
                       transform=T, crs=crs) as ds:  # fmt: skip
        ds.write(a, 1)


@pytest.mark.parametrize("crs", ["EPSG:32633", CUSTOM])
def test_gdal_reads_the_crs_of_the_png_we_write(tmp_path, crs):
    write_tif(tmp_path / "grid.tif", np.zeros((20, 30), np.uint8), crs)
    (tmp_path / "field.wkt").write_text(
        "POLYGON ((500100 4199500, 500700 4199500, 500700 4199800, 500100 4199500))"
    )
    done = mrm_run("discretize", "field.wkt", "--like", "grid.tif", "-o", "field.png", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "field.png.aux.xml").is_file()
    with rasterio.open(tmp_path / "field.png") as ds:
        assert ds.transform == T
        assert ds.crs is not None
        assert ProjCRS.from_user_input(ds.crs.to_wkt()).to_dict() == ProjCRS.from_user_input(crs).to_dict()


def test_we_read_the_crs_gdal_writes_beside_a_png(tmp_path):
    a = np.zeros((20, 30), np.uint8)
    a[5:12, 4:20] = 255
    profile = dict(driver="PNG", width=30, height=20, count=1, dtype="uint8", transform=T, crs="EPSG:32633")
    with rasterio.Env(GDAL_PAM_ENABLED="YES"), rasterio.open(tmp_path / "m.png", "w", **profile) as ds:
        ds.write(a, 1)
    (tmp_path / "m.pgw").write_text("30\n0\n0\n-30\n500015\n4199985\n")
    assert (tmp_path / "m.png.aux.xml").is_file()
    assert not (tmp_path / "m.prj").exists()
    done = mrm_run("reconstruct", "m.png", "-o", "m.geojson", "--model", "gauss", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    doc = json.loads((tmp_path / "m.geojson").read_text())
    assert doc["crs"]["properties"]["name"] == "urn:ogc:def:crs:EPSG::32633"


@pytest.mark.parametrize(
    ("content", "words"),
    [
        (
            '<?xml version="1.0"?><!DOCTYPE x [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;">]>'
            "<PAMDataset><SRS>&b;</SRS></PAMDataset>",
            "document type declaration",
        ),
        ("<PAMDataset><SRS>" + "x" * 600_000 + "</SRS></PAMDataset>", "bytes"),
        ("<PAMDataset><SRS>unclosed", "not a GDAL .aux.xml"),
        ("<svg><SRS>EPSG:4326</SRS></svg>", "not a GDAL .aux.xml"),
    ],
)
def test_a_hostile_aux_xml_gives_one_line(tmp_path, content, words):
    from PIL import Image

    Image.fromarray(np.full((10, 10), 255, np.uint8)).save(tmp_path / "m.png")
    (tmp_path / "m.pgw").write_text("30\n0\n0\n-30\n500015\n4199985\n")
    (tmp_path / "m.png.aux.xml").write_text(content)
    done = mrm_run("reconstruct", "m.png", "-o", "m.geojson", cwd=tmp_path)
    assert done.returncode == 2, done.stderr
    lines = [x for x in done.stderr.splitlines() if not x.startswith("mrm: first run")]
    assert len(lines) == 1 and "error: " in lines[0] and words in lines[0], done.stderr
    assert not (tmp_path / "m.geojson").exists()
