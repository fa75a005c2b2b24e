"""``mrm discretize`` and ``mrm info``: run as a user would, in-process and through the real entry point."""

from __future__ import annotations

import io
import json
import subprocess
import sys
import zlib
from pathlib import Path

import numpy as np
import pytest
from PIL import Image, PngImagePlugin

from mrm.cli import run_cli
from mrm.core.grids import PixelSet
from mrm.io.pixel_files import read_pixels, write_pixels

INFO_KEYS = {"model", "pixels", "components", "holes", "euler", "boundary_chains", "segments", "vertices"}

# The box [0, 2] × [0, 1] has its vertices on pixel centres. By the definitions of docs/design.md §2:
# standard: the open squares shifted by τ that meet it are those of x = 0, 1, 2 and y = 0, 1 (6 pixels);
# gauss: the shifted centres p + τ inside it are (0, 0) and (1, 0) (p + τ leaves it at x = 2 and y = 1).
BOX = '{"type": "Polygon", "coordinates": [[[0, 0], [2, 0], [2, 1], [0, 1], [0, 0]]]}'
BOX_STANDARD = {(x, y) for x in range(3) for y in range(2)}
BOX_GAUSS = {(0, 0), (1, 0)}

# A 3 × 3 ring: 8 pixels, one component, one hole, two boundary chains.
RING = PixelSet.from_points([(x, y) for x in range(3) for y in range(3) if (x, y) != (1, 1)])


def as_set(ps: PixelSet) -> set[tuple[int, int]]:
    return {(int(x), int(y)) for x, y in ps.points()}


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = run_cli([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def fails(capsys, command: str, *argv: str) -> str:
    code, out, err = run(capsys, command, *argv)
    assert code == 2
    assert err.startswith(f"mrm {command}: error: "), err
    assert "Traceback" not in err and out == ""
    return err


@pytest.fixture
def box_file(tmp_path: Path) -> Path:
    p = tmp_path / "box.geojson"
    p.write_text(BOX)
    return p


# ---------------------------------------------------------------------------------------------- discretize
@pytest.mark.parametrize("ext", [".png", ".pbm", ".pgm", ".npz"])
def test_discretize_writes_the_pixels(capsys, tmp_path, box_file, ext):
    out = tmp_path / f"out{ext}"
    code, stdout, err = run(capsys, "discretize", box_file, "-o", out, "--json")
    assert code == 0, err
    summary = json.loads(stdout)
    assert INFO_KEYS | {"seconds"} <= summary.keys()
    assert as_set(read_pixels(out)) == BOX_STANDARD
    assert summary["model"] == "standard" and summary["pixels"] == 6
    assert summary["vertices"] == 4  # the input polygon's
    assert isinstance(summary["seconds"], float) and summary["seconds"] >= 0
    assert (summary["components"], summary["holes"], summary["euler"], summary["boundary_chains"]) == (
        1,
        0,
        1,
        1,
    )


def test_discretize_with_another_model_and_wkt(capsys, tmp_path):
    src = tmp_path / "box.wkt"
    src.write_text("POLYGON ((0 0, 2 0, 2 1, 0 1, 0 0))\n")
    code, stdout, _ = run(capsys, "discretize", src, "-o", tmp_path / "g.npz", "--model", "gauss", "--json")
    assert code == 0
    assert as_set(read_pixels(tmp_path / "g.npz")) == BOX_GAUSS
    assert json.loads(stdout)["model"] == "gauss"


def test_discretize_overlapping_features_is_the_union(capsys, tmp_path):
    fc = {
        "type": "FeatureCollection",
        "features": [
            {"type": "Feature", "properties": {}, "geometry": json.loads(BOX)},
            {
                "type": "Feature",
                "properties": {},
                "geometry": {"type": "Polygon", "coordinates": [[[1, 0], [4, 0], [4, 1], [1, 1], [1, 0]]]},
            },
        ],
    }
    src = tmp_path / "two.geojson"
    src.write_text(json.dumps(fc))
    code, _, err = run(capsys, "discretize", src, "-o", tmp_path / "u.png")
    assert code == 0, err
    assert as_set(read_pixels(tmp_path / "u.png")) == {(x, y) for x in range(5) for y in range(2)}


def test_discretize_to_svg(capsys, tmp_path, box_file):
    code, _, _ = run(capsys, "discretize", box_file, "-o", tmp_path / "o.svg")
    assert code == 0
    assert (tmp_path / "o.svg").read_text().count("<rect") == 2  # one run per row


def test_discretize_prints_a_table_without_json(capsys, tmp_path, box_file):
    code, stdout, _ = run(capsys, "discretize", box_file, "-o", tmp_path / "o.png")
    assert code == 0
    rows = dict(line.split(None, 1) for line in stdout.splitlines() if line.split()[0] in ("pixels", "model"))
    assert rows == {"pixels": "6", "model": "standard"}
    assert "{" not in stdout


def test_discretize_refuses_a_result_over_the_limit(capsys, tmp_path, box_file):
    err = fails(capsys, "discretize", box_file, "-o", tmp_path / "o.png", "--limit", "5")
    assert "limit" in err
    assert not (tmp_path / "o.png").exists()


@pytest.mark.parametrize(
    ("content", "name", "message"),
    [
        ("POLYGON ((0 0, 2 2, 2 0, 0 2, 0 0))", "bow.wkt", "Self-intersection"),
        (
            '{"type": "Polygon", "coordinates": [[[0, 0], [1, 0]],]}',
            "bad.geojson",
            "malformed JSON at line 1",
        ),
        ("POINT (1 2", "open.wkt", "not closed"),
        ("nothing", "x.txt", "'.txt' is not a supported input file"),
    ],
)
def test_discretize_bad_input(capsys, tmp_path, content, name, message):
    src = tmp_path / name
    src.write_text(content)
    err = fails(capsys, "discretize", src, "-o", tmp_path / "o.png")
    assert message in err and name in err
    assert not (tmp_path / "o.png").exists()


def test_discretize_bad_output_extension_fails_before_reading(capsys, tmp_path):
    err = fails(capsys, "discretize", tmp_path / "missing.geojson", "-o", tmp_path / "o.jpg")
    assert "'.jpg' is not a pixel output file" in err


def test_discretize_missing_input_and_bad_model(capsys, tmp_path):
    err = fails(capsys, "discretize", tmp_path / "missing.wkt", "-o", tmp_path / "o.png")
    assert "missing.wkt" in err
    with pytest.raises(SystemExit) as e:
        run_cli(["discretize", str(tmp_path / "a.wkt"), "-o", "o.png", "--model", "voronoi"])
    assert e.value.code == 2
    assert "invalid choice" in capsys.readouterr().err
    with pytest.raises(SystemExit) as e:
        run_cli(["discretize", str(tmp_path / "a.wkt"), "-o", "o.png", "--limit", "-3"])
    assert e.value.code == 2


def test_project_input_that_is_not_a_project(capsys, tmp_path):
    src = tmp_path / "p.mrm"
    src.write_text("not a project")
    err = fails(capsys, "discretize", src, "-o", tmp_path / "o.png")
    assert "p.mrm" in err


# ---------------------------------------------------------------------------------------------- info
@pytest.mark.parametrize("ext", [".png", ".pbm", ".pgm", ".npz"])
def test_info_of_pixel_files(capsys, tmp_path, ext):
    p = tmp_path / f"ring{ext}"
    write_pixels(RING.translate(-7, 4), p)
    code, stdout, err = run(capsys, "info", p, "--json")
    assert code == 0, err
    s = json.loads(stdout)
    assert s.keys() >= INFO_KEYS
    assert (s["model"], s["pixels"], s["components"], s["holes"], s["euler"], s["boundary_chains"]) == (
        "standard",
        8,
        1,
        1,
        0,
        2,
    )
    assert s["bbox"] == [-7, 4, -5, 6]
    # the two crack chains have 12 + 4 steps; a closed chain needs at least two DSS and at most one per step
    # (the exact count is the DSS module's business, tested there)
    assert s["segments"] is None or 2 * 2 <= s["segments"] <= 12 + 4


def test_info_of_a_geometry_discretizes_it(capsys, box_file):
    code, stdout, _ = run(capsys, "info", box_file, "--json", "--model", "gauss")
    assert code == 0
    s = json.loads(stdout)
    assert (s["model"], s["pixels"], s["vertices"], s["components"]) == ("gauss", 2, 4, 1)


def test_info_threshold_for_grey_images(capsys, tmp_path):
    grey = np.array([[10, 200, 90], [0, 0, 0]], dtype=np.uint8)
    p = tmp_path / "g.png"
    Image.fromarray(grey).save(p)
    code, stdout, _ = run(capsys, "info", p, "--json", "--threshold", "50")
    assert code == 0 and json.loads(stdout)["pixels"] == 2
    (tmp_path / "box.geojson").write_text(BOX)
    err = fails(capsys, "info", tmp_path / "box.geojson", "--threshold", "5")
    assert "box.geojson" in err and "image inputs only" in err
    with pytest.raises(SystemExit):
        run_cli(["info", str(p), "--threshold", "nan"])


def test_info_table(capsys, tmp_path):
    p = tmp_path / "r.png"
    write_pixels(RING, p)
    code, stdout, _ = run(capsys, "info", p)
    assert code == 0
    table = {line.split("  ")[0].strip(): line.split("  ")[-1].strip() for line in stdout.splitlines()}
    assert table["pixels"] == "8" and table["holes"] == "1" and table["boundary chains"] == "2"


def hostile_files(tmp_path: Path) -> dict[str, Path]:
    good = io.BytesIO()
    Image.fromarray(np.ones((4, 4), dtype=bool)).save(good, format="PNG")
    data = good.getvalue()
    bad_origin = io.BytesIO()
    info = PngImagePlugin.PngInfo()
    info.add_text("mrm:origin", "left bottom")
    Image.fromarray(np.ones((4, 4), dtype=bool)).save(bad_origin, format="PNG", pnginfo=info)
    ihdr = (100_000).to_bytes(4, "big") * 2 + bytes([1, 0, 0, 0, 0])
    huge = b"\x89PNG\r\n\x1a\n" + len(ihdr).to_bytes(4, "big") + b"IHDR" + ihdr
    huge += zlib.crc32(b"IHDR" + ihdr).to_bytes(4, "big")
    obj = io.BytesIO()
    np.savez(obj, mask=np.array([{"a": 1}], dtype=object), origin=np.zeros(2, np.int64))
    files = {
        "truncated.png": data[: len(data) // 2],
        "random.png": bytes(np.random.default_rng(0).integers(0, 256, 256, dtype=np.uint8)),
        "text.png": b"just some text, renamed\n",
        "objects.npz": obj.getvalue(),
        "origin.png": bad_origin.getvalue(),
        "huge.png": huge,
    }
    out = {}
    for name, content in files.items():
        (tmp_path / name).write_bytes(content)
        out[name] = tmp_path / name
    return out


def test_info_on_hostile_files(capsys, tmp_path):
    expected = {
        "truncated.png": "truncated",
        "random.png": "not a PNG",
        "text.png": "text file",
        "objects.npz": "Python objects",
        "origin.png": "mrm:origin",
        "huge.png": "more than the limit",
    }
    for name, p in hostile_files(tmp_path).items():
        err = fails(capsys, "info", p, "--json")
        assert name in err and expected[name] in err, err


def test_info_bad_extension_and_directory(capsys, tmp_path):
    assert "'.jpeg'" in fails(capsys, "info", tmp_path / "a.jpeg")
    (tmp_path / "dir.png").mkdir()
    assert "dir.png" in fails(capsys, "info", tmp_path / "dir.png")


# ---------------------------------------------------------------------------------------------- entry point
def test_entry_points_in_a_subprocess(tmp_path, box_file):
    out = tmp_path / "o.png"
    mrm = Path(sys.executable).parent / "mrm"
    done = subprocess.run(
        [str(mrm), "discretize", str(box_file), "-o", str(out), "--json"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    assert as_set(read_pixels(out)) == BOX_STANDARD
    info = subprocess.run(
        [sys.executable, "-m", "mrm", "info", str(out), "--json"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert info.returncode == 0, info.stderr
    assert json.loads(info.stdout)["pixels"] == 6
    bad = subprocess.run(
        [sys.executable, "-m", "mrm", "info", str(tmp_path / "nope.png")],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert bad.returncode == 2
    assert bad.stderr.startswith("mrm info: error:") and "Traceback" not in bad.stderr


# ---------------------------------------------------------------------------------------------- projects
def test_project_files(capsys, tmp_path):
    from shapely.geometry import box

    from mrm.document import Document, Settings
    from mrm.io.project import save_project

    doc = Document(Settings(model="gauss"))
    a = doc.make_object(box(0, 0, 2, 1), "a box")
    b = doc.make_object(PixelSet.from_points([(10, 10)]), "a pixel")
    doc.insert_object(a)
    doc.insert_object(b)
    p = tmp_path / "two.mrm"
    save_project(doc, p)
    # discretize takes the Euclidean objects, under the project's model unless --model says otherwise
    code, stdout, err = run(capsys, "discretize", p, "-o", tmp_path / "d.npz", "--json")
    assert code == 0, err
    assert json.loads(stdout)["model"] == "gauss"
    assert as_set(read_pixels(tmp_path / "d.npz")) == BOX_GAUSS
    code, _, _ = run(capsys, "discretize", p, "-o", tmp_path / "s.npz", "--model", "standard")
    assert as_set(read_pixels(tmp_path / "s.npz")) == BOX_STANDARD
    # info summarises every object and their union
    code, stdout, err = run(capsys, "info", p, "--json")
    assert code == 0, err
    s = json.loads(stdout)
    assert s.keys() >= INFO_KEYS
    assert s["pixels"] == 3 and s["components"] == 2
    assert [(o["name"], o["source"], o["pixels"]) for o in s["objects"]] == [
        ("a box", "euclidean", 2),
        ("a pixel", "discrete", 1),
    ]
    # a project without Euclidean objects has nothing to discretize
    only_pixels = Document()
    only_pixels.insert_object(only_pixels.make_object(PixelSet.from_points([(0, 0)])))
    save_project(only_pixels, tmp_path / "px.mrm")
    assert "no Euclidean object" in fails(capsys, "discretize", tmp_path / "px.mrm", "-o", tmp_path / "x.png")
