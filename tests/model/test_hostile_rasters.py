"""Issue 32, classes 1, 2 and 4 (and the world files of 5): rasters and their georeference, read defensively.

1. Only real TIFFs reach GDAL, through the GTiff driver alone, on the file that was checked: a ``.tif``
   holding a GDAL VRT is refused whatever it points at, before any of it is opened (ADR 0047).
2. A georeference beyond the limits (world coordinates, CRS length) is refused at import with one line, by
   the same check the project loader applies: what imports, saves and reopens.
4. Decoding bombs: a raster is decoded a window at a time, a world file is read bounded, and a project's
   label maps count their four bytes a label in the file's budget, checked before any is inflated.

Every hostile file is built here (tests/model/hostile.py). Whole-process memory is bounded by running the
command line in a child process under ``RLIMIT_AS`` (1.5 GB): a reader that decodes too much fails there with
a MemoryError instead of passing.
"""

from __future__ import annotations

import base64
import json
import os
import resource
import socket
import subprocess
import sys
import tracemalloc
import zlib
from pathlib import Path

import hostile
import numpy as np
import pytest
import rasterio
from PIL import Image

import mrm.core.limits as limits
from mrm.core.errors import FileFormatError, LimitError, MRMError
from mrm.core.georef import GeoRef
from mrm.core.grids import LabelMap, PixelSet
from mrm.document import Document
from mrm.document.commands import AddObject
from mrm.io.georef import read_georef, read_pixels_georef, same_crs, write_world_file
from mrm.io.imports import import_file
from mrm.io.pixel_files import read_pixels
from mrm.io.project import dumps, loads, read_project

# Plain TIFFs (no georeference) are written and read on purpose here.
pytestmark = pytest.mark.filterwarnings("ignore::rasterio.errors.NotGeoreferencedWarning")

#: The address space a child process gets: a reader that decodes a bomb whole runs out of it.
AS_LIMIT = 1536 << 20


def run_cli(
    *args: str, cwd: Path, limit_memory: bool = False, timeout: float = 120
) -> subprocess.CompletedProcess:
    """``python -m mrm ARGS`` in a child (optionally under :data:`AS_LIMIT`), killed after ``timeout``."""

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (AS_LIMIT, AS_LIMIT))

    return subprocess.run(
        [sys.executable, "-m", "mrm", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=timeout,
        preexec_fn=limit if limit_memory else None,
    )


def one_line_error(done: subprocess.CompletedProcess, pattern: str) -> None:
    """The command failed with exit status 2 and one ``mrm …: error:`` line matching ``pattern``."""
    import re

    lines = done.stderr.strip().splitlines()
    assert done.returncode == 2, (done.returncode, done.stdout[-500:], done.stderr[-2000:])
    assert len(lines) == 1 and lines[0].startswith("mrm") and ": error: " in lines[0], done.stderr[-2000:]
    assert re.search(pattern, lines[0]), lines[0]


def geotiff(path: Path, mask: np.ndarray, transform=None, crs: str | None = None) -> Path:
    h, w = mask.shape
    with rasterio.open(
        path, "w", driver="GTiff", width=w, height=h, count=1, dtype="uint8", transform=transform, crs=crs
    ) as ds:
        ds.write(mask.astype(np.uint8), 1)
    return path


def png(path: Path, mask: np.ndarray, world: str | None = None, prj: str | None = None) -> Path:
    Image.fromarray(mask.astype(np.uint8) * 255).save(path)
    if world is not None:
        path.with_suffix(".pgw").write_text(world)
    if prj is not None:
        path.with_suffix(".prj").write_text(prj)
    return path


MASK = np.eye(6, dtype=bool) | np.eye(6, dtype=bool)[::-1]


# ---------------------------------------------------------------------------------------------- class 1
@pytest.fixture
def listener():
    """A TCP port on the loopback that records whether anything connected to it."""
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    s.listen(8)
    s.setblocking(False)
    yield s
    s.close()


def _nobody_connected(s: socket.socket) -> bool:
    try:
        conn, _ = s.accept()
    except BlockingIOError:
        return True
    conn.close()
    return False


def _vrt_target(kind: str, tmp_path: Path, listener: socket.socket) -> str:
    if kind == "file":  # another local TIFF, which the VRT would read as the pixels of x.tif
        return str(geotiff(tmp_path / "secret.tif", np.ones((16, 16), bool)))
    if kind == "fifo":  # a named pipe nobody writes to: opening it for reading blocks forever
        os.mkfifo(tmp_path / "pipe")
        return str(tmp_path / "pipe")
    return f"/vsicurl/http://127.0.0.1:{listener.getsockname()[1]}/x.tif"  # GDAL would fetch it


COMMANDS = {
    "info": lambda p: ("info", p),
    "reconstruct": lambda p: ("reconstruct", p, "-o", "out.geojson"),
    "discretize --like": lambda p: ("discretize", "square.geojson", "--like", p, "-o", "out.tif"),
}


@pytest.mark.parametrize("command", sorted(COMMANDS))
@pytest.mark.parametrize("target", ["file", "fifo", "url"])
def test_a_vrt_named_tif_is_refused_before_anything_it_names_is_opened(tmp_path, listener, target, command):
    (tmp_path / "x.tif").write_text(hostile.vrt(_vrt_target(target, tmp_path, listener)))
    (tmp_path / "square.geojson").write_text(
        json.dumps({"type": "Polygon", "coordinates": [[[0, 0], [4, 0], [4, 4], [0, 4], [0, 0]]]})
    )
    done = run_cli(*COMMANDS[command]("x.tif"), cwd=tmp_path, timeout=60)  # a FIFO opened would hang here
    one_line_error(done, r"x\.tif: not a GeoTIFF \(it is a text file\); only TIFF files are read")
    assert done.stdout == ""
    assert _nobody_connected(listener)
    assert not (tmp_path / "out.geojson").exists() and not (tmp_path / "out.tif").exists()


def test_the_gui_import_and_the_library_refuse_a_vrt_before_gdal(tmp_path, monkeypatch):
    geotiff(tmp_path / "secret.tif", np.ones((16, 16), bool))
    p = tmp_path / "x.tif"
    p.write_text(hostile.vrt(str(tmp_path / "secret.tif")))

    def gdal_opened(*a, **k):
        raise AssertionError(f"GDAL was asked to open {a}")

    monkeypatch.setattr(rasterio, "open", gdal_opened)
    doc = Document()
    for read in (read_pixels, read_georef, read_pixels_georef, lambda q: import_file(doc, q)):
        with pytest.raises(FileFormatError, match=r"x\.tif: not a GeoTIFF"):
            read(p)
    assert len(doc) == 0


def test_a_tiff_magic_does_not_let_another_format_through(tmp_path):
    p = tmp_path / "x.tif"
    p.write_bytes(b"II*\x00" + hostile.vrt(str(geotiff(tmp_path / "secret.tif", MASK))).encode())
    with pytest.raises(FileFormatError, match=r"x\.tif: not a readable GeoTIFF"):
        read_pixels_georef(p)


def test_gdal_looks_up_no_sidecar_file(tmp_path):
    # A plain TIFF with sidecars GDAL would read by itself: a PAM .aux.xml giving it a georeference, an
    # external mask. MR Modeler reads the TIFF and, documented, its world file, nothing else.
    p = geotiff(tmp_path / "m.tif", MASK)
    (tmp_path / "m.tif.aux.xml").write_text(
        "<PAMDataset><GeoTransform>1000, 2, 0, 5000, 0, -2</GeoTransform></PAMDataset>\n"
    )
    geotiff(tmp_path / "m.tif.msk", np.zeros_like(MASK))
    ps, georef = read_pixels_georef(p)
    assert georef is None and ps == PixelSet(MASK[::-1])
    (tmp_path / "m.tfw").write_text("30\n0\n0\n-30\n500015\n4199985\n")  # the documented sidecar
    assert read_georef(p).transform == (30.0, 0.0, 500000.0, 0.0, -30.0, 4200000.0)


def test_a_crs_text_naming_a_file_is_never_read(tmp_path):
    # GDAL's general CRS parser reads a file (or fetches a URL) a CRS text names: a .prj or a GeoJSON
    # "crs" member saying a path must stay text.
    named = tmp_path / "crs.wkt"
    named.write_text(rasterio.crs.CRS.from_epsg(32633).to_wkt())
    assert not same_crs(str(named), "EPSG:32633")
    p = png(tmp_path / "m.png", MASK, world="1\n0\n0\n-1\n0.5\n5.5\n", prj=str(named))
    georef = read_georef(p)
    assert georef.crs == str(named)
    write_world_file(tmp_path / "out.png", georef)
    assert (tmp_path / "out.prj").read_text() == f"{named}\n"
    assert same_crs("EPSG:32633", rasterio.crs.CRS.from_epsg(32633).to_wkt())  # WKT and codes still compare


# ---------------------------------------------------------------------------------------------- class 2
def _hostile_georef(kind: str, tmp_path: Path) -> Path:
    if kind.startswith("world file"):
        v = kind.split()[-1]
        return png(tmp_path / "m.png", MASK, world=f"{v} 0 0 -{v} 0 0\n")
    p = tmp_path / "m.tif"
    p.write_bytes(hostile.tiff(6, 6, fill=1, geo=(1e305, 1e305, 0.0, 0.0)))
    return p


@pytest.mark.parametrize("kind", ["world file 1e305", "world file 1e308", "GeoTIFF 1e305"])
def test_a_georeference_beyond_the_limits_is_refused_at_import(tmp_path, kind):
    p = _hostile_georef(kind, tmp_path)
    doc = Document()
    with pytest.raises(LimitError, match=r"would put pixels at world coordinates beyond ±1e\+100") as e:
        import_file(doc, p)
    assert str(e.value).startswith(("m.pgw: ", "m.tif: ")) and "\n" not in str(e.value)
    assert len(doc) == 0


def test_a_prj_of_150012_characters_is_refused_at_import(tmp_path):
    p = png(tmp_path / "m.png", MASK, world="1\n0\n0\n-1\n0.5\n5.5\n", prj="X" * 150_012)
    doc = Document()
    with pytest.raises(LimitError, match=r"m\.prj: the CRS is a text of 150,012 characters, longer than"):
        import_file(doc, p)
    assert len(doc) == 0


def test_georeferences_within_the_limits_save_and_reopen_and_beyond_them_are_refused_alike():
    doc = Document()
    edge = GeoRef((1e89, 0.0, 5e99, 0.0, -1e89, -5e99), 6, 6, "W" * limits.MAX_CRS_CHARS)
    doc.push(AddObject(doc.make_object(PixelSet(MASK), "edge", georef=edge)))
    assert loads(dumps(doc)).objects[0].georef == edge
    # The limit is the map's: the frame grown to the whole grid a document can hold keeps it.
    grown = edge.covering((-(2**31), -(2**31), 2**31, 2**31))
    assert grown.frame == (-(2**31), -(2**31), 2**31, 2**31)
    assert np.allclose(grown.grid_to_world(), edge.grid_to_world(), rtol=1e-12, atol=0)
    for t in ((1e89, 0.0, 1e100, 0.0, -1e89, 0.0), (1e92, 0.0, 0.0, 0.0, -1.0, 0.0)):
        with pytest.raises(LimitError, match="beyond ±1e"):
            GeoRef(t, 6, 6)
        raw = json.loads(dumps(doc))
        raw["objects"][0]["georef"]["transform"] = list(t)
        with pytest.raises(FileFormatError, match=r"\.georef: the raster's transform .* beyond ±1e\+100"):
            loads(json.dumps(raw).encode())
    with pytest.raises(LimitError, match="longer than the limit of 100,000"):
        GeoRef(edge.transform, 6, 6, "W" * (limits.MAX_CRS_CHARS + 1))


@pytest.mark.parametrize("command", ["reconstruct", "discretize --like"])
def test_the_command_line_refuses_a_1e308_world_file_with_one_line(tmp_path, command):
    png(tmp_path / "m.png", MASK, world="1e308 0 0 -1e308 0 0\n")
    (tmp_path / "square.geojson").write_text(
        json.dumps({"type": "Polygon", "coordinates": [[[0, 0], [4, 0], [4, 4], [0, 4], [0, 0]]]})
    )
    args = (
        ("reconstruct", "m.png", "-o", "x.geojson")
        if command == "reconstruct"
        else ("discretize", "square.geojson", "--like", "m.png", "-o", "x.png")
    )
    done = run_cli(*args, cwd=tmp_path)
    one_line_error(done, r"m\.pgw: the raster's transform .* beyond ±1e\+100")
    assert not (tmp_path / "x.geojson").exists() and not (tmp_path / "x.png").exists()


# ---------------------------------------------------------------------------------------------- class 4
BOMBS = {
    # name: (dtype, rows per strip, fill, extra arguments, pixels expected)
    "complex128": ("complex128", 64, 0, (), 0),
    "complex128 --threshold": ("complex128", 64, 0, ("--threshold", "0.5"), 0),
    "uint8 --threshold": ("uint8", 1024, 1, ("--threshold", "0"), 14000 * 14000),
}


@pytest.mark.parametrize("case", sorted(BOMBS))
def test_a_geotiff_bomb_is_read_within_the_memory_budget(tmp_path, case):
    dtype, rows, fill, extra, expected = BOMBS[case]
    p = tmp_path / "bomb.tif"
    p.write_bytes(hostile.tiff(14000, 14000, dtype=dtype, rows_per_strip=rows, fill=fill))
    assert p.stat().st_size < 100_000  # 3 GB of complex samples, 196 MB of bytes
    done = run_cli("info", "bomb.tif", *extra, "--json", cwd=tmp_path, limit_memory=True)
    assert done.returncode == 0, done.stderr[-2000:]
    assert json.loads(done.stdout)["pixels"] == expected


def test_a_geotiff_of_one_huge_block_is_refused_before_decoding(tmp_path):
    p = tmp_path / "bomb.tif"
    p.write_bytes(hostile.tiff(14000, 14000, dtype="complex128"))  # one strip of 3 GB
    assert p.stat().st_size < 10_000_000
    done = run_cli("info", "bomb.tif", cwd=tmp_path, limit_memory=True)
    one_line_error(done, r"bomb\.tif: the TIFF stores its samples in blocks of 14000×14000 pixels")


def test_a_huge_world_file_is_refused_without_reading_it(tmp_path):
    p = png(tmp_path / "m.png", MASK)
    with open(tmp_path / "m.pgw", "wb") as fh:
        fh.write(b"1 0 0 -1 0 0\n")
        fh.truncate(144 << 20)  # sparse: 144 MB on paper
    tracemalloc.start()
    try:
        with pytest.raises(
            FileFormatError, match=r"m\.pgw: the file is 150,994,944 bytes, more than the 4,096"
        ):
            read_georef(p)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 1 << 20


def _label_bomb(tmp_path: Path, maps: int, side: int = 7071) -> Path:
    """A project of ``maps`` label maps of side² pixels, all label 1: 200 MB each, 250 KB in the file."""
    comp = zlib.compressobj(9)
    row = np.ones(side, "<i4").tobytes()
    packed = b"".join(comp.compress(row) for _ in range(side)) + comp.flush()
    doc = Document()
    doc.push(AddObject(doc.make_object(LabelMap(np.ones((2, 2), np.int32)), "L")))
    raw = json.loads(dumps(doc))
    o = raw["objects"][0]
    o["source"].update(shape=[side, side], labels=base64.b64encode(packed).decode())
    raw["objects"] = [dict(o, id=i + 1, name=f"L{i}") for i in range(maps)]
    raw.pop("selection", None)
    p = tmp_path / "labels.mrm"
    p.write_text(json.dumps(raw))
    return p


def test_a_project_of_20_compressed_label_maps_is_refused_before_inflating_any(tmp_path):
    p = _label_bomb(tmp_path, 20)
    assert p.stat().st_size < 10_000_000
    done = run_cli("info", p.name, cwd=tmp_path, limit_memory=True)
    first_over = limits.MAX_FILE_PIXELS // (7071 * 7071 * limits.LABEL_WEIGHT)  # the map that crosses it
    one_line_error(
        done,
        rf"\$\.objects\[{first_over}\]\.source\.shape: the masks of the file hold more than "
        + f"{limits.MAX_FILE_PIXELS:,}",
    )


def test_the_largest_label_project_the_budget_admits_is_summarised_within_1_gb(tmp_path):
    # Three label maps filling the grid budget, compressed into well under 1 MB: mrm info loads them and
    # summarises them (its cell counting gets what the held grids leave of its own budget). The peak
    # resident memory of the mrm process, read by a parent that has no other child, stays below 1 GB.
    from math import isqrt

    side = isqrt(limits.MAX_FILE_PIXELS // limits.LABEL_WEIGHT // 3)
    p = _label_bomb(tmp_path, 3, side=side)
    assert p.stat().st_size < 1_000_000
    probe = (
        "import resource, subprocess, sys; "
        "r = subprocess.run([sys.executable, '-m', 'mrm', 'info', sys.argv[1], '--json'], "
        "capture_output=True); "
        "print(r.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)"
    )
    done = subprocess.run([sys.executable, "-c", probe, str(p)], capture_output=True, text=True, timeout=300)
    code, peak_kb = (int(v) for v in done.stdout.split())
    assert code == 0, done.stderr
    assert peak_kb * 1024 < 1_000_000_000, f"mrm info peaked at {peak_kb // 1024} MB"


def test_a_label_counts_its_weight_in_the_documents_budget(monkeypatch, tmp_path):
    monkeypatch.setattr(limits, "MAX_FILE_PIXELS", 25 * limits.LABEL_WEIGHT)
    doc = Document()
    doc.push(AddObject(doc.make_object(LabelMap(np.ones((5, 5), np.int32)), "a")))  # 25 labels: the budget
    with pytest.raises(MRMError, match=f"label counts as {limits.LABEL_WEIGHT}"):
        doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 0, 0), "one more pixel")))
    p = tmp_path / "d.mrm"
    p.write_bytes(dumps(doc))
    assert read_project(p).objects == list(doc.objects)  # the budget the document keeps, the file keeps


@pytest.mark.parametrize("budget", [9_000, 40_000, 64 << 20])  # a block at a time, a few, all rows at once
@pytest.mark.parametrize(("dtype", "nodata"), [("float32", -9999.0), ("int16", -1), ("float64", None)])
def test_windowed_decoding_gives_the_documented_rules(tmp_path, monkeypatch, budget, dtype, nodata):
    # The rules of read_raster applied to the whole band at once (as before the windows): non-zero or above
    # the threshold, never nodata, never NaN.
    from mrm.core.threshold import binarize

    monkeypatch.setattr(limits, "MAX_DECODED_BYTES", budget)
    rng = np.random.default_rng(7)
    a = (rng.random((301, 257)) * 10 - 3).astype(dtype)
    if a.dtype.kind == "f":
        a[rng.random(a.shape) < 0.05] = np.nan
    if nodata is not None:
        a[rng.random(a.shape) < 0.1] = nodata
    p = tmp_path / "n.tif"
    with rasterio.open(
        p, "w", driver="GTiff", width=257, height=301, count=1, dtype=dtype, nodata=nodata,
        tiled=True, blockxsize=32, blockysize=32,
    ) as ds:  # fmt: skip
        ds.write(a, 1)
    for threshold in (None, 2.5):
        valid = np.ones(a.shape, bool) if nodata is None else a != nodata
        if a.dtype.kind == "f":
            rows = (a > (threshold or 0.0)) & valid & np.isfinite(a)
        elif threshold is None:
            rows = (a != 0) & valid
        else:
            rows = binarize(np.clip(np.where(valid, a, 0).astype(np.int64), 0, None), threshold) & valid
        assert read_pixels_georef(p, threshold=threshold)[0] == PixelSet(rows[::-1])
