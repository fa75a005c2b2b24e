"""The one-input operations (scale, rotate, simplify) and polygonize follow the batch conventions of ADR 0011.

Also: out-of-range parameters in one short line, no empty folder left by a failed run, georeferenced inputs
giving georeferenced results. Every test runs ``python -m mrm`` and looks at files, stdout and stderr.
"""

from __future__ import annotations

import json
import shlex
import subprocess
from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from test_conventions import PY, _stderr_on_a_terminal, mrm_run, one_error_line, sh

import mrm

OPERATIONS = [
    ("scale", ["--alpha", "2"], ".png"),
    ("rotate", ["--angle", "30", "--center", "1/2,1/2"], ".png"),
    ("simplify", ["--alpha", "1/2"], ".geojson"),
]


@pytest.fixture
def shapes(tmp_path: Path) -> Path:
    d = tmp_path / "in"
    d.mkdir()
    rng = np.random.default_rng(5)
    for k in range(4):
        img = rng.random((5, 6)) < 0.6
        img[0, 0] = True
        Image.fromarray(img).save(d / f"s{k}.png")
    (d / "notes.txt").write_text("not an input")  # a directory's other files are not inputs
    return d


def _same_result(a: Path, b: Path) -> bool:
    if a.suffix == ".png":
        return mrm.read_pixels(a) == mrm.read_pixels(b)
    return json.loads(a.read_text())["features"] == json.loads(b.read_text())["features"]


@pytest.mark.parametrize(("command", "params", "ext"), OPERATIONS)
def test_a_directory_gives_the_same_results_as_one_input_at_a_time(shapes, command, params, ext):
    root = shapes.parent
    done = mrm_run(command, "in", *params, "-o", "out/", "--jobs", "2", "--no-measure", "--json", cwd=root)
    assert done.returncode == 0, done.stderr
    summary = json.loads(done.stdout)
    assert summary["inputs"] == 4 and [Path(f["input"]).name for f in summary["files"]] == [
        f"s{k}.png" for k in range(4)
    ]
    assert sorted(p.name for p in (root / "out").iterdir()) == [f"s{k}{ext}" for k in range(4)]
    for k in range(4):
        one = mrm_run(command, f"in/s{k}.png", *params, "-o", f"one{k}{ext}", "--no-measure", cwd=root)
        assert one.returncode == 0, one.stderr
        assert _same_result(root / "out" / f"s{k}{ext}", root / f"one{k}{ext}")


def test_quoted_globs_and_stem_patterns(shapes):
    root = shapes.parent
    done = mrm_run("rotate", "in/s[12].png", "--angle", "90", "-o", "rot/{stem}-90.png", cwd=root)
    assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in (root / "rot").iterdir()) == ["s1-90.png", "s2-90.png"]
    lines = done.stdout.decode().splitlines()
    assert lines[0].startswith("in/s1.png -> rot/s1-90.png: ") and lines[1].startswith("in/s2.png -> ")
    quiet = mrm_run("scale", "in", "--alpha", "2", "-o", "q/", "--quiet", "--no-measure", cwd=root)
    assert quiet.returncode == 0 and b"->" not in quiet.stdout  # no per-file lines with --quiet
    labels = mrm_run("polygonize", "in/*.png", "-o", "poly/", "--json", cwd=root)
    assert labels.returncode == 0, labels.stderr
    assert json.loads(labels.stdout)["inputs"] == 4 and len(list((root / "poly").iterdir())) == 4


def test_results_are_streamed_and_a_bar_is_drawn_on_a_terminal(tmp_path):
    Image.fromarray(np.ones((2, 2), dtype=bool)).save(tmp_path / "a.png")
    rng = np.random.default_rng(0)
    Image.fromarray(rng.random((300, 300)) < 0.5).save(tmp_path / "z.png")  # seconds of work
    proc = subprocess.Popen(
        [PY, "-m", "mrm", "scale", "a.png", "z.png", "--alpha", "3", "-o", "out/", "--no-measure"],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    try:
        first = proc.stdout.readline().decode()
        still_running = proc.poll() is None
    finally:
        proc.kill()
        proc.wait()
    assert first.startswith("a.png -> out/a.png: ")
    assert still_running, "the first file's line should come before the last file is done"
    # tqdm draws its bar after a one-second delay: an input that takes longer than that to rotate (a 300²
    # noise took 0.4 s once R shared its rings between threads)
    Image.fromarray(rng.random((900, 900)) < 0.5).save(tmp_path / "y.png")
    status, seen = _stderr_on_a_terminal(
        ["rotate", "y.png", "--angle", "30", "-o", "r.png", "--no-measure"], tmp_path
    )
    assert status == 0 and b"rotate y.png" in seen
    status, seen = _stderr_on_a_terminal(
        ["rotate", "y.png", "--angle", "30", "-o", "q.png", "--no-measure", "--quiet"], tmp_path
    )
    assert status == 0 and seen == b""


def test_a_closed_pipe_ends_a_batch_quietly(shapes):
    script = (
        f"{shlex.quote(PY)} -m mrm scale in --alpha 2 -o out/ --no-measure 2>err.txt | head -c 1 >/dev/null;"
        " echo ${PIPESTATUS[0]}"
    )
    done = sh(script, shapes.parent)
    assert (shapes.parent / "err.txt").read_text() == ""
    assert done.stdout.strip() in ("0", "141")


def test_invert_and_threshold_apply_to_operation_inputs(tmp_path):
    img = np.full((4, 5), 255, dtype=np.uint8)
    img[1:3, 1:4] = 0  # a black 3×2 bar on white
    Image.fromarray(img).save(tmp_path / "ink.png")
    done = mrm_run(
        "rotate", "ink.png", "--angle", "90", "--invert", "-o", "r.png", "--no-measure", cwd=tmp_path
    )
    assert done.returncode == 0, done.stderr
    assert len(mrm.read_pixels(tmp_path / "r.png")) == 6  # the bar turned, not the white around it
    thr = mrm_run("scale", "ink.png", "--alpha", "1", "--threshold", "254", "-o", "t.png", cwd=tmp_path)
    assert thr.returncode == 0 and len(mrm.read_pixels(tmp_path / "t.png")) == 14


# ---------------------------------------------------------------------------------------------- item 3
@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (
            ["rotate", "--angle", "1e400"],
            "parameter 'angle' (θ) must be ≤ 3600, got 1e400 (allowed: -3600 ≤ θ ≤ 3600)",
        ),
        (["rotate", "--angle=-1e999"], "must be ≥ -3600, got -1e999"),
        (
            ["scale", "--alpha", "1e-400"],
            "parameter 'alpha' (α) must be ≥ 1e-06, got 1e-400 (allowed: 1e-06 ≤ α",
        ),
        (["scale", "--alpha", "1" + "0" * 500], "must be ≤ 1e+06, got 100000000000000000000..."),
        (["scale", "--alpha", "1/1e-400"], "must be a number, got '1/1e-400'"),
        (["scale", "--alpha", "2", "--center", "1e400,0"], "coordinates between"),
        (["simplify", "--alpha", "1e400"], "must be ≤ 1e+06"),
    ],
)
def test_huge_and_tiny_parameters_get_a_short_message_with_the_range(tmp_path, args, expected):
    Image.fromarray(np.ones((2, 2), dtype=bool)).save(tmp_path / "a.png")
    command, *rest = args
    line = one_error_line(mrm_run(command, "a.png", *rest, "-o", "new/x.png", cwd=tmp_path), command)
    assert expected in line and len(line) < 160, line
    assert not (tmp_path / "new").exists()


# ---------------------------------------------------------------------------------------------- item 4
def test_a_failed_run_leaves_no_empty_output_folder(shapes):
    root = shapes.parent
    (root / "kept").mkdir()
    cases = [
        ("rotate", "in/s0.png", "--angle", "30", "--limit", "1", "-o", "n1/deep/x.png"),  # at reading
        ("scale", "in", "--alpha", "2", "--limit", "1", "-o", "n2/deep/"),  # every input of a batch
        ("reconstruct", "in/s0.png", "-o", "n3/a/b/x.geojson", "--limit", "1"),
        ("discretize", "in/notes.txt", "-o", "n4/x.png"),
        ("scale", "in/s0.png", "--alpha", "2", "--limit", "1", "-o", "kept/x.png"),
    ]
    for args in cases:
        done = mrm_run(*args, cwd=root)
        assert done.returncode == 2 and b"Traceback" not in done.stderr, done.stderr
    assert sorted(p.name for p in root.iterdir()) == ["in", "kept"]  # a folder that was there stays


def test_a_partly_failed_batch_keeps_what_it_wrote(shapes):
    root = shapes.parent
    (shapes / "bad.png").write_bytes(b"\x89PNG\r\n\x1a\n broken")
    done = mrm_run("scale", "in", "--alpha", "2", "-o", "out/", "--no-measure", cwd=root)
    assert done.returncode == 2 and "bad.png" in done.stderr.decode()
    assert sorted(p.name for p in (root / "out").iterdir()) == [f"s{k}.png" for k in range(4)]


# ---------------------------------------------------------------------------------------------- georef
def test_operations_on_a_geotiff_give_georeferenced_results(tmp_path):
    rasterio = pytest.importorskip("rasterio")
    from rasterio.transform import from_origin

    t = from_origin(500_000.0, 4_200_000.0, 30.0, 30.0)
    mask = np.zeros((12, 16), dtype=np.uint8)
    mask[3:9, 4:12] = 1
    with rasterio.open(
        tmp_path / "m.tif", "w", driver="GTiff", width=16, height=12, count=1, dtype="uint8",
        transform=t, crs="EPSG:32633",
    ) as ds:  # fmt: skip
        ds.write(mask, 1)
    done = mrm_run("scale", "m.tif", "--alpha", "2", "-o", "s.tif", "--model", "gauss", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    with rasterio.open(tmp_path / "s.tif") as ds:
        assert ds.crs.to_epsg() == 32633 and (ds.transform.a, ds.transform.e) == (15.0, -15.0)
        ys, xs = np.nonzero(ds.read(1))
        west, north = ds.transform @ (xs.min(), ys.min())
        east, south = ds.transform @ (xs.max() + 1, ys.max() + 1)
    # The 8×6 block of 30 m pixels scaled on a grid twice as fine lands where the block is, within one fine
    # pixel (the fine grid is centred on the coarse pixel centres, so its edges are not the coarse ones);
    # tests/geo/test_project_georef.py compares such a result with GDAL's burn, pixel for pixel.
    block_edges = (500_120.0, 500_360.0, 4_199_910.0, 4_199_730.0)
    for got, block in zip((west, east, north, south), block_edges, strict=True):
        assert abs(got - block) <= 15.0, (got, block)
    assert (east - west) / 15 > 14 and (north - south) / 15 > 10  # the block's size, on 15 m pixels
    rot = mrm_run("rotate", "m.tif", "--angle", "90", "--center", "15/2,11/2", "-o", "r.tif", cwd=tmp_path)
    assert rot.returncode == 0, rot.stderr
    with rasterio.open(tmp_path / "r.tif") as ds:
        assert ds.transform == t and ds.crs.to_epsg() == 32633  # the input's grid, unchanged
        ys, xs = np.nonzero(ds.read(1))
        west, north = ds.transform @ (xs.min(), ys.min())
        east, south = ds.transform @ (xs.max() + 1, ys.max() + 1)
    # turned a quarter about the block's centre: 6 wide and 8 high, centred where the block was
    assert (east - west, north - south) == (6 * 30, 8 * 30)
    assert ((west + east) / 2, (north + south) / 2) == (500_000.0 + 8 * 30, 4_200_000.0 - 6 * 30)
    vec = mrm_run(
        "rotate", "m.tif", "--angle", "90", "--center", "15/2,11/2", "-o", "r.geojson", cwd=tmp_path
    )
    assert vec.returncode == 0, vec.stderr
    fc = json.loads((tmp_path / "r.geojson").read_text())
    assert fc["crs"]["properties"]["name"] == "urn:ogc:def:crs:EPSG::32633"
    xmin, ymin, xmax, ymax = fc["bbox"]
    assert abs((xmin + xmax) / 2 - 500_240.0) < 1e-6 and abs((ymin + ymax) / 2 - 4_199_820.0) < 1e-6


def test_union_and_corefine_of_two_geotiffs_on_one_grid_keep_it(tmp_path):
    rasterio = pytest.importorskip("rasterio")
    from rasterio.transform import from_origin

    t = from_origin(500_000.0, 4_200_000.0, 30.0, 30.0)

    def tif(name: str, rows: slice, cols: slice, transform=t) -> None:
        mask = np.zeros((12, 16), dtype=np.uint8)
        mask[rows, cols] = 1
        with rasterio.open(
            tmp_path / name, "w", driver="GTiff", width=16, height=12, count=1, dtype="uint8",
            transform=transform, crs="EPSG:32633",
        ) as ds:  # fmt: skip
            ds.write(mask, 1)

    tif("a.tif", slice(2, 6), slice(1, 9))  # two 30 m blocks that overlap in a 3×2-pixel corner
    tif("b.tif", slice(4, 10), slice(6, 14))
    done = mrm_run("union", "a.tif", "b.tif", "-o", "u.tif", "--json", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["crs"] == "EPSG:32633"
    with rasterio.open(tmp_path / "u.tif") as ds:
        assert ds.transform == t and ds.crs.to_epsg() == 32633
        ys, xs = np.nonzero(ds.read(1))
        burnt = {(int(x), int(y)) for x, y in zip(xs, ys, strict=True)}
    block_a = {(c, r) for r in range(2, 6) for c in range(1, 9)}
    block_b = {(c, r) for r in range(4, 10) for c in range(6, 14)}
    assert burnt == block_a | block_b  # the union, back on the rasters' own pixels
    done = mrm_run("corefine", "a.tif", "b.tif", "-o", "parts.geojson", "--model", "gauss", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    fc = json.loads((tmp_path / "parts.geojson").read_text())
    assert fc["crs"]["properties"]["name"] == "urn:ogc:def:crs:EPSG::32633"
    inter = next(f for f in fc["features"] if f["properties"]["part"] == "a_and_b")
    xs_, ys_ = zip(*inter["geometry"]["coordinates"][0], strict=True)
    # the overlap, columns 6–8 and rows 4–5, in world metres: within one pixel of its edges (gauss)
    assert min(xs_) > 500_180.0 - 30 and max(xs_) < 500_270.0 + 30
    assert min(ys_) > 4_199_820.0 - 30 and max(ys_) < 4_199_880.0 + 30
    tif("c.tif", slice(4, 10), slice(6, 14), from_origin(500_000.0, 4_200_000.0, 10.0, 10.0))
    other = mrm_run("union", "a.tif", "c.tif", "-o", "v.geojson", "--json", cwd=tmp_path)
    assert other.returncode == 0, other.stderr
    assert "crs" not in json.loads(other.stdout)  # two grids: no single answer, plain grid coordinates
