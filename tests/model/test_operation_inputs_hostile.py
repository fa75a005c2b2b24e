"""Issue 32, class 8: valid inputs that `info` and `discretize` take are taken by the operations too, or
refused with a user-level message — never "a pinned input content must be a source" or "expected a shapely
geometry".

A vector input that is not one polygon (overlapping features, lines, points) enters an operation as its
discretization D(E) = ∪ D(feature); a label map object is summarised by `mrm info` and refused by operations.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import shapely

from mrm.cli import run_cli
from mrm.core.grids import LabelMap
from mrm.document import Document, Settings
from mrm.io.pixel_files import read_pixels
from mrm.io.project import save_project
from mrm.io.vector_files import read_geometries

A = shapely.box(0, 0, 10, 10)
B = shapely.box(5, 5, 15, 15)
SQUARE = shapely.Polygon([(2, 1), (9, 2), (8, 9), (1, 8)])


def feature_collection(*geoms: shapely.Geometry) -> str:
    feats = [
        {"type": "Feature", "properties": {}, "geometry": json.loads(shapely.to_geojson(g))} for g in geoms
    ]
    return json.dumps({"type": "FeatureCollection", "features": feats})


def run(capsys, *argv) -> tuple[int, str, str]:
    code = run_cli([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def ok(capsys, *argv) -> None:
    measure = [] if argv[0] == "discretize" else ["--no-measure"]
    code, _, err = run(capsys, *argv, *measure)
    assert code == 0, err
    assert "Traceback" not in err


def same_output(a: Path, b: Path) -> bool:
    if a.suffix == ".png":
        return read_pixels(a) == read_pixels(b)
    return [g.wkb for _, g in read_geometries(a)] == [g.wkb for _, g in read_geometries(b)]


@pytest.fixture
def inputs(tmp_path: Path) -> dict[str, Path]:
    overlapping = tmp_path / "two.geojson"
    overlapping.write_text(feature_collection(A, B))
    union = tmp_path / "union.wkt"  # the exact union: integer corners, nothing rounded
    union.write_text(shapely.union(A, B).wkt)
    assert shapely.union(A, B).area == 175
    mixed = tmp_path / "mixed.wkt"
    mixed.write_text(
        "GEOMETRYCOLLECTION (POLYGON ((0 0, 10 0, 10 10, 0 10, 0 0)), LINESTRING (20 0, 30 5), POINT (40 40))"
    )
    square = tmp_path / "square.wkt"
    square.write_text(SQUARE.wkt)
    return {"two": overlapping, "union": union, "mixed": mixed, "square": square, "dir": tmp_path}


COMMANDS = [
    ("scale", ["--alpha", "2"], ".png", False),
    ("rotate", ["--angle", "30", "--center", "1/2,0"], ".png", False),
    ("union", [], ".geojson", True),
    ("corefine", [], ".geojson", True),
]


@pytest.mark.parametrize(("command", "params", "ext", "two_inputs"), COMMANDS)
def test_overlapping_features_give_what_their_exact_union_gives(
    capsys, inputs, command, params, ext, two_inputs
):
    d = inputs["dir"]
    second = [inputs["square"]] if two_inputs else []
    ok(capsys, command, inputs["two"], *second, *params, "-o", d / f"from-features{ext}")
    ok(capsys, command, inputs["union"], *second, *params, "-o", d / f"from-union{ext}")
    assert same_output(d / f"from-features{ext}", d / f"from-union{ext}")


@pytest.mark.parametrize("source", ["two", "mixed"])
@pytest.mark.parametrize(
    ("command", "params", "ext"),
    [("simplify", ["--alpha", "2"], ".geojson"), ("scale", ["--alpha", "3/2"], ".png")],
)
def test_a_collection_enters_an_operation_as_its_discretization(capsys, inputs, source, command, params, ext):
    d = inputs["dir"]
    ok(capsys, "discretize", inputs[source], "-o", d / "pixels.png")
    ok(capsys, command, inputs[source], *params, "-o", d / f"from-vector{ext}")
    ok(capsys, command, d / "pixels.png", *params, "-o", d / f"from-pixels{ext}")
    assert same_output(d / f"from-vector{ext}", d / f"from-pixels{ext}")


def test_measured_operations_on_a_collection_report_a_bound(capsys, inputs):
    code, out, err = run(
        capsys, "simplify", inputs["mixed"], "--alpha", "2", "-o", inputs["dir"] / "s.geojson", "--json"
    )
    assert code == 0, err
    s = json.loads(out)
    assert s["measured"] is not None and s["measured"] <= s["bound"]


# ---------------------------------------------------------------------------------------------- label maps
LABELS = np.array([[1, 1, 0, 1], [0, 2, 2, 2], [3, 3, 0, 0]], dtype=np.int32)  # label 1: two regions


@pytest.fixture
def with_labels(tmp_path: Path) -> Path:
    doc = Document(Settings(model="standard"))
    doc.insert_object(doc.make_object(LabelMap(LABELS), "classes"))
    doc.insert_object(doc.make_object(shapely.box(10, 10, 12, 12), "square"))
    path = tmp_path / "labels.mrm"
    save_project(doc, path)
    return path


def test_info_on_a_project_holding_a_label_map(capsys, with_labels):
    code, out, err = run(capsys, "info", with_labels, "--json")
    assert code == 0, err
    s = json.loads(out)
    classes, square = s["objects"]
    assert classes["source"] == "labels"
    assert {k: classes[k] for k in ("labels", "regions", "pixels")} == {
        "labels": 3,
        "regions": 4,
        "pixels": 8,
    }
    assert classes["bbox"] == [0, 0, 3, 2] and classes["adjacencies"] > 0
    assert square["pixels"] == 9
    assert s["pixels"] == 8 + 9  # the union holds the map's labelled pixels


def test_info_on_the_label_map_object_itself(capsys, with_labels):
    code, out, err = run(capsys, "info", with_labels, "--object", "classes")
    assert code == 0, err
    assert "regions" in out and "4" in out
    code, out, err = run(capsys, "info", with_labels, with_labels, "--object", "classes")
    assert code == 0 and out.count("3 labels, 4 regions, 8 pixels") == 2, (out, err)


@pytest.mark.parametrize(
    "argv",
    [
        ["scale", "{p}", "--object", "classes", "--alpha", "2", "-o", "{d}/x.png"],
        ["union", "{p}", "{p}", "--object", "classes", "--object", "square", "-o", "{d}/x.geojson"],
    ],
)
def test_an_operation_on_a_label_map_says_what_to_do(capsys, with_labels, argv):
    args = [a.format(p=with_labels, d=with_labels.parent) for a in argv]
    code, out, err = run(capsys, *args)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and "Traceback" not in err
    assert "'classes' is a label map" in err and "Split into Objects" in err
    assert not list(with_labels.parent.glob("x.*"))


def test_cell_counts_agree_with_the_cells():
    """The counts `mrm info` prints are cells_of's, without its objects (random maps, rings, pinches)."""
    from mrm.reps.cells import cell_counts, cells_of

    rng = np.random.default_rng(32)
    maps = [
        np.array([[1, 1, 1], [1, 2, 1], [1, 1, 1]]),  # a loop through no 0-cell
        np.array([[1, 2], [2, 1]]),  # a diagonal pinch
        np.array([[0, 0], [0, 0]]),
        np.array([[5]]),
    ]
    for _ in range(300):
        h, w = rng.integers(1, 10, 2)
        m = rng.integers(0, rng.integers(1, 5) + 1, (h, w))
        maps.append(np.kron(m, np.ones(rng.integers(1, 4, 2), dtype=np.int64)) if rng.random() < 0.3 else m)
    for m in maps:
        lm = LabelMap(m.astype(np.int32))
        cells, counts = cells_of(lm), cell_counts(lm)
        assert (counts.one_cells, counts.zero_cells, counts.adjacencies) == (
            len(cells.one_cells),
            len(cells.zero_cells),
            len(cells.adjacency),
        ), m


def test_a_label_map_too_costly_to_count_gets_a_warning_not_gigabytes(capsys, with_labels, monkeypatch):
    import mrm.cli.info as info

    monkeypatch.setattr(info, "MAX_LABEL_COUNT_BYTES", 100)  # a 2000² checkerboard (38 KB) needs 690 MB
    code, out, err = run(capsys, "info", with_labels, "--object", "classes", "--json")
    assert code == 0
    s = json.loads(out)
    assert s["labels"] == 3 and s["pixels"] == 8 and s["regions"] is None and s["one_cells"] is None
    assert err.startswith("mrm info: warning: counting the cells of a 4×3 label map") and err.count("\n") == 1
