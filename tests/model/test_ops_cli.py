"""``mrm scale | rotate | simplify | union | corefine`` run as a user would (docs/design.md §9)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
import shapely
from shapely.geometry import box

from mrm.cli import run_cli
from mrm.core.grids import PixelSet
from mrm.document import Document, Settings
from mrm.geometry.discretize import discretize
from mrm.io.pixel_files import read_label_map, read_pixels, write_pixels
from mrm.io.project import save_project
from mrm.io.vector_files import read_geometries, read_geometry
from mrm.ops.boolean import euclidean_discrete_corefinement, euclidean_discrete_union
from mrm.ops.rotation import discrete_rotation
from mrm.ops.scaling import discrete_smooth_scaling

INFO_KEYS = {"model", "pixels", "components", "holes", "euler", "boundary_chains", "segments", "vertices"}
OP_KEYS = INFO_KEYS | {"bound", "measured"}

L_SHAPE = PixelSet.from_points([(x, y) for x in range(6) for y in range(4) if not (x > 2 and y > 1)])
TRIANGLE = shapely.Polygon([(0, 0), (9, 1), (2, 7)])
SQUARE = box(4, -1, 11, 5)


def run(capsys, *argv) -> tuple[int, str, str]:
    code = run_cli([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def run_json(capsys, *argv) -> dict:
    code, out, err = run(capsys, *argv, "--json")
    assert code == 0, err
    return json.loads(out)


def fails(capsys, command: str, *argv) -> str:
    code, out, err = run(capsys, command, *argv)
    assert code == 2
    assert err.startswith(f"mrm {command}: error: "), err
    assert "Traceback" not in err and out == ""
    return err


@pytest.fixture
def files(tmp_path: Path) -> dict[str, Path]:
    png = tmp_path / "l.png"
    write_pixels(L_SHAPE, png)
    tri = tmp_path / "tri.wkt"
    tri.write_text(TRIANGLE.wkt)
    sq = tmp_path / "sq.geojson"
    sq.write_text(json.dumps({"type": "Polygon", "coordinates": [list(SQUARE.exterior.coords)]}))
    return {"png": png, "tri": tri, "sq": sq, "dir": tmp_path}


@pytest.fixture
def project(tmp_path: Path) -> Path:
    doc = Document(Settings(model="supercover"))
    for src, name in ((TRIANGLE, "tri"), (SQUARE, "square"), (L_SHAPE, "L")):
        doc.insert_object(doc.make_object(src, name))
    path = tmp_path / "p.mrm"
    save_project(doc, path)
    return path


# ---------------------------------------------------------------------------------------------- unary
def test_scale_writes_the_pixels_and_reports_bound_and_measured(capsys, files):
    out = files["dir"] / "s.npz"
    s = run_json(capsys, "scale", files["png"], "--alpha", "0.2", "--center", "1,1", "-o", out)
    assert s.keys() >= OP_KEYS
    expected = discrete_smooth_scaling(L_SHAPE, 0.2, (1, 1)).result
    assert read_pixels(out) == expected
    assert s["pixels"] == len(expected)
    assert s["bound"] == 0.0 and s["measured"] == 0.0  # one DSS: A_last is T(A_first)
    assert s["params"] == {"alpha": 0.2, "center": [1, 1], "model": "standard"}


def test_scale_of_a_vector_file_to_a_vector_file(capsys, files):
    out = files["dir"] / "s.geojson"
    s = run_json(capsys, "scale", files["tri"], "--alpha", "1/3", "-o", out)
    expected = discrete_smooth_scaling(discretize(TRIANGLE), "1/3").result
    assert discretize(read_geometry(out)) == expected  # R of the result, which discretizes back to it
    assert s["pixels"] == len(expected)


def test_rotate_by_a_quarter_turn_is_exact(capsys, files):
    out = files["dir"] / "r.png"
    s = run_json(capsys, "rotate", files["png"], "--angle", "90", "--center", "2,1", "-o", out)
    assert read_pixels(out) == L_SHAPE.rotate90(1, (2, 1))
    assert s["bound"] == 0.0
    out2 = files["dir"] / "r2.png"
    run_json(capsys, "rotate", files["png"], "--angle", "30", "-o", out2)
    assert read_pixels(out2) == discrete_rotation(L_SHAPE, 30).result


def test_simplify_reports_the_theorem_15_bound_and_stays_within_it(capsys, files):
    out = files["dir"] / "sp.wkt"
    s = run_json(capsys, "simplify", files["tri"], "--alpha", "0.5", "-o", out)
    assert s["bound"] == pytest.approx(2 * math.sqrt(2))
    assert 0 < s["measured"] <= s["bound"]
    assert read_geometry(out).is_valid
    assert s["vertices"] == len(read_geometry(out).exterior.coords) - 1


def test_no_measure_gives_null(capsys, files):
    s = run_json(
        capsys, "simplify", files["tri"], "--alpha", "2", "-o", files["dir"] / "x.svg", "--no-measure"
    )
    assert s["measured"] is None and s["bound"] is not None
    assert (files["dir"] / "x.svg").read_text().startswith("<?xml")


def test_gauss_gives_a_null_two_sided_bound(capsys, files):
    s = run_json(
        capsys, "simplify", files["tri"], "--alpha", "0.5", "--model", "gauss", "-o", files["dir"] / "g.wkt"
    )
    assert s["bound"] is None
    assert s["bound_one_sided"] == pytest.approx(2 * math.sqrt(2))
    assert s["result_within"] <= s["bound_one_sided"]


# ---------------------------------------------------------------------------------------------- binary
def test_union_of_a_vector_file_and_a_pixel_file(capsys, files):
    out = files["dir"] / "u.geojson"
    s = run_json(capsys, "union", files["tri"], files["png"], "-o", out)
    expected = euclidean_discrete_union(TRIANGLE, L_SHAPE)
    assert discretize(read_geometry(out)) == expected.discrete
    assert s["pixels"] == len(expected.discrete)
    assert s["bound"] == pytest.approx(math.sqrt(2))
    assert s["measured"] <= s["bound"]


def test_corefine_to_a_prefix_writes_one_file_per_part(capsys, files):
    prefix = files["dir"] / "co"
    s = run_json(capsys, "corefine", files["tri"], files["sq"], "-o", prefix)
    expected = euclidean_discrete_corefinement(TRIANGLE, SQUARE)
    for part in ("a_minus_b", "a_and_b", "b_minus_a"):
        path = files["dir"] / f"co-{part}.geojson"
        assert discretize(read_geometry(path)) == expected.extra["pixels"][part]
        assert s["parts"][part]["pixels"] == len(expected.extra["pixels"][part])
        assert INFO_KEYS | {"measured", "bound_one_sided"} <= s["parts"][part].keys()
    assert s["bound"] is None
    assert s["measured"] == max(p["measured"] for p in s["parts"].values())
    # the one-sided bounds hold: a difference part lies within √2 of the Euclidean difference
    assert s["parts"]["a_minus_b"]["result_within"] <= math.sqrt(2)
    assert s["parts"]["a_and_b"]["source_within"] <= math.sqrt(2)


def test_corefine_to_a_folder_names_the_files_after_the_parts(capsys, files):
    folder = files["dir"] / "new" / "parts"
    run_json(capsys, "corefine", files["tri"], files["sq"], "-o", f"{folder}/")
    expected = euclidean_discrete_corefinement(TRIANGLE, SQUARE)
    assert sorted(p.name for p in folder.iterdir()) == [
        "a_and_b.geojson",
        "a_minus_b.geojson",
        "b_minus_a.geojson",
    ]
    for part in ("a_minus_b", "a_and_b", "b_minus_a"):
        assert discretize(read_geometry(folder / f"{part}.geojson")) == expected.extra["pixels"][part]


@pytest.mark.parametrize("alpha", ["1e400", "1e-400", "0", "-2"])
def test_corefine_refuses_alpha_out_of_range_in_one_short_line(capsys, files, alpha):
    out = files["dir"] / "x/"
    message = fails(capsys, "corefine", files["tri"], files["sq"], "--alpha", alpha, "-o", out)
    assert "1e-06 ≤ α ≤ 1e+06" in message
    assert len(message) < 200
    assert not (files["dir"] / "x").exists()


@pytest.mark.parametrize(("model", "alpha"), [("standard", None), ("gauss", "1.25"), ("supercover", "2")])
def test_corefine_prints_the_numbers_of_the_one_account(capsys, files, model, alpha):
    from mrm.ops.account import account_of
    from mrm.ops.provenance import Provenance

    extra = [] if alpha is None else ["--alpha", alpha]
    s = run_json(
        capsys, "corefine", files["tri"], files["sq"], "--model", model, *extra, "-o", files["dir"] / "c"
    )
    prov = Provenance("corefine", {"model": model, "alpha": alpha}, (1, 2), (TRIANGLE, SQUARE), (None, None))
    acc = account_of(prov)
    for pa in acc.parts:
        told = pa.as_dict()
        for key in ("bound", "bound_one_sided", "bound_coefficient", "directions", "measured"):
            assert s["parts"][pa.part][key] == told[key], (pa.part, key)
    assert s["measured"] == max(pa.measured.value for pa in acc.parts)


def test_corefine_to_geojson_is_one_feature_collection(capsys, files):
    out = files["dir"] / "co.geojson"
    run_json(capsys, "corefine", files["tri"], files["sq"], "--alpha", "2", "-o", out)
    data = json.loads(out.read_text())
    assert [f["properties"]["part"] for f in data["features"]] == ["a_minus_b", "a_and_b", "b_minus_a"]
    assert len(read_geometries(out)) == 3
    expected = euclidean_discrete_corefinement(TRIANGLE, SQUARE, alpha=2)
    got = shapely.geometry.shape(data["features"][1]["geometry"])
    assert got.equals_exact(expected.result["a_and_b"], 0)


def test_corefine_to_png_writes_the_label_map(capsys, files):
    out = files["dir"] / "labels.png"
    run_json(capsys, "corefine", files["tri"], files["sq"], "--model", "gauss", "-o", out)
    lm = read_label_map(out)
    expected = euclidean_discrete_corefinement(TRIANGLE, SQUARE, "gauss")
    assert lm == expected.extra["label_map"]


# ---------------------------------------------------------------------------------------------- projects
def test_project_inputs_with_object_names(capsys, project, tmp_path):
    out = tmp_path / "p.png"
    s = run_json(capsys, "scale", project, "--object", "L", "--alpha", "2", "-o", out)
    assert s["model"] == "supercover"  # the project's model
    assert read_pixels(out) == discrete_smooth_scaling(L_SHAPE, 2, None, "supercover").result
    u = tmp_path / "u.wkt"
    s = run_json(capsys, "union", project, project, "--object", "tri", "--object", "square", "-o", u)
    assert discretize(read_geometry(u), "supercover") == discretize(TRIANGLE, "supercover") | discretize(
        SQUARE, "supercover"
    )
    err = fails(capsys, "scale", project, "--alpha", "2", "-o", out)
    assert "--object" in err


# ---------------------------------------------------------------------------------------------- errors
@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (
            ["scale", "{png}", "--alpha", "0", "-o", "{dir}/o.png"],
            "'alpha' (α) must be ≥ 1e-06, got 0 (allowed: 1e-06 ≤ α ≤ 1e+06)",
        ),
        (["scale", "{png}", "--alpha", "nan", "-o", "{dir}/o.png"], "'alpha' (α) must be a finite number"),
        (["scale", "{png}", "--alpha", "1e6", "-o", "{dir}/o.png"], "would cover"),
        (["rotate", "{png}", "--angle", "inf", "-o", "{dir}/o.png"], "angle"),
        (["simplify", "{tri}", "--alpha", "-1", "-o", "{dir}/o.wkt"], "alpha"),
        (["scale", "{png}", "--alpha", "2", "-o", "{dir}/o.txt"], "output file"),
        (["union", "{png}", "{dir}/missing.png", "-o", "{dir}/o.wkt"], "missing.png"),
        (["corefine", "{tri}", "{sq}", "--alpha", "0", "-o", "{dir}/o"], "alpha"),
    ],
)
def test_bad_input_gets_a_message_and_writes_nothing(capsys, files, argv, message):
    args = [a.format(**{k: str(v) for k, v in files.items()}) for a in argv]
    before = sorted(p.name for p in files["dir"].iterdir())
    err = fails(capsys, *args)
    assert message in err
    assert sorted(p.name for p in files["dir"].iterdir()) == before


def test_the_real_entry_point(files):
    out = files["dir"] / "e.png"
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "mrm.app",
            "scale",
            str(files["png"]),
            "--alpha",
            "2",
            "-o",
            str(out),
            "--json",
        ],
        capture_output=True,
        text=True,
        timeout=300,
        cwd=Path(__file__).parents[2],
    )
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["pixels"] == len(read_pixels(out))
