"""``mrm info`` and ``mrm discretize`` on project files: every object, or one picked with ``--object``."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from shapely.geometry import Polygon, box

from mrm.cli import run_cli
from mrm.core.grids import PixelSet, VoxelSet
from mrm.document import Document, Settings
from mrm.geometry.discretize import discretize
from mrm.io.pixel_files import read_pixels
from mrm.io.project import read_project, save_project

EXAMPLES = sorted((Path(__file__).parents[2] / "resources" / "examples").glob("*.mrm"))
INFO_KEYS = {"model", "pixels", "components", "holes", "euler", "boundary_chains", "segments", "vertices"}
SVG = "{http://www.w3.org/2000/svg}"

# The box [0, 2] × [0, 1] has its vertices on pixel centres. By the definitions of docs/design.md §2:
# standard: the open squares shifted by τ that meet it are those of x = 0, 1, 2 and y = 0, 1 (6 pixels);
# gauss: the shifted centres p + τ inside it are (0, 0) and (1, 0) (p + τ leaves it at x = 2 and y = 1).
BOX = box(0, 0, 2, 1)
BOX_STANDARD = {(x, y) for x in range(3) for y in range(2)}
BOX_GAUSS = {(0, 0), (1, 0)}


def as_set(ps: PixelSet) -> set[tuple[int, int]]:
    return {(int(x), int(y)) for x, y in ps.points()}


def run(capsys, *argv) -> tuple[int, str, str]:
    code = run_cli([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def fails(capsys, command: str, *argv) -> str:
    code, out, err = run(capsys, command, *argv)
    assert code == 2
    assert err.startswith(f"mrm {command}: error: "), err
    assert "Traceback" not in err and out == ""
    return err


def example_path(name: str) -> Path:
    (path,) = (p for p in EXAMPLES if p.name == name)
    return path


def test_the_examples_are_there():
    # the parametrized tests below run once per example: none must go missing unnoticed
    assert {p.name for p in EXAMPLES} >= {"diamond.mrm", "holes-and-components.mrm", "two-polygons.mrm"}


#: The 3D keys of mrm info (docs/design.md §11).
INFO_KEYS_3D = {"voxels", "components", "cavities", "tunnels", "euler", "surfels", "plane_segments", "faces",
                "vertices"}  # fmt: skip


def voxels_of(obj, model: str) -> VoxelSet:
    """A 3D object's voxels: the set itself, or D of a polyhedron (the voxelizer, not the info command)."""
    from mrm.geometry.discretize.voxels import voxelize

    return obj.source if isinstance(obj.source, VoxelSet) else voxelize(obj.source, model)


def pixels_of(obj, model: str) -> PixelSet:
    """An object's discrete representation, straight from the discretization module."""
    return obj.source if isinstance(obj.source, PixelSet) else discretize(obj.source, model)


@pytest.fixture
def gauss_project(tmp_path: Path) -> Path:
    """A gauss-model project: a box, a pixel, and two objects that share a name."""
    doc = Document(Settings(model="gauss"))
    for src, name in (
        (BOX, "box"),
        (PixelSet.from_points([(10, 10)]), "pixel"),
        (box(20, 0, 21, 1), "twin"),
        (box(30, 0, 31, 1), "twin"),
    ):
        doc.insert_object(doc.make_object(src, name))
    path = tmp_path / "gauss.mrm"
    save_project(doc, path)
    return path


# ---------------------------------------------------------------------------------------------- info
@pytest.mark.parametrize("example", EXAMPLES, ids=lambda p: p.name)
def test_info_of_an_example_with_and_without_object(capsys, example):
    project = read_project(example)
    model = project.settings.model
    code, out, err = run(capsys, "info", example, "--json")
    assert code == 0, err
    whole = json.loads(out)
    assert whole.keys() >= INFO_KEYS and whole["model"] == model
    union = PixelSet.empty()
    solids = VoxelSet.empty()
    for obj in project.objects:
        if obj.dimension == 3:  # a 3D object: its voxels, listed with the 3D keys (the plane union skips it)
            solids = solids | voxels_of(obj, model)
        else:
            union = union | pixels_of(obj, model)
    assert whole["pixels"] == union.count
    assert whole.get("voxels", 0) == len(solids)
    assert [(o["name"], o["source"]) for o in whole["objects"]] == [(o.name, o.kind) for o in project.objects]
    for obj, listed in zip(project.objects, whole["objects"], strict=True):
        code, out, err = run(capsys, "info", example, "--object", obj.name, "--json")
        assert code == 0, err
        one = json.loads(out)
        assert (one["object"], one["source"], one["model"]) == (obj.name, obj.kind, model)
        assert "objects" not in one
        if obj.dimension == 3:
            assert one["voxels"] == len(voxels_of(obj, model))
            keys = INFO_KEYS_3D
        else:
            assert one["pixels"] == pixels_of(obj, model).count
            keys = INFO_KEYS
        # the summary of one object is the one listed for it in the whole project's
        assert {k: one[k] for k in keys} == {k: listed[k] for k in keys}


def test_info_object_in_the_projects_model_unless_model_is_given(capsys, gauss_project):
    code, out, _ = run(capsys, "info", gauss_project, "--object", "box", "--json")
    assert code == 0
    s = json.loads(out)
    assert (s["model"], s["pixels"], s["vertices"]) == ("gauss", len(BOX_GAUSS), 4)
    code, out, _ = run(capsys, "info", gauss_project, "--object", "box", "--json", "--model", "standard")
    assert (json.loads(out)["model"], json.loads(out)["pixels"]) == ("standard", len(BOX_STANDARD))
    code, out, _ = run(capsys, "info", gauss_project, "--object", "pixel", "--json")
    s = json.loads(out)
    assert (s["source"], s["pixels"], s["bbox"]) == ("discrete", 1, [10, 10, 10, 10])


def test_info_object_table(capsys):
    code, out, _ = run(capsys, "info", example_path("two-polygons.mrm"), "--object", "pentagon")
    assert code == 0
    rows = {line.split("  ")[0].strip(): line.split("  ")[-1].strip() for line in out.splitlines()}
    assert rows["object"] == "pentagon" and rows["source"] == "euclidean" and rows["vertices"] == "5"


# ---------------------------------------------------------------------------------------------- discretize
def test_discretize_one_object_of_an_example(capsys, tmp_path):
    example = example_path("two-polygons.mrm")
    objects = {o.name: o for o in read_project(example).objects}
    assert sorted(objects) == ["pentagon", "tilted square"]
    for name, obj in objects.items():
        out = tmp_path / f"{name}.png"
        code, stdout, err = run(capsys, "discretize", example, "--object", name, "-o", out, "--json")
        assert code == 0, err
        s = json.loads(stdout)
        assert (s["object"], s["source"], s["model"]) == (name, "euclidean", "standard")
        assert read_pixels(out) == discretize(obj.source, "standard")
        assert s["pixels"] == read_pixels(out).count
    # --model overrides the project's
    out = tmp_path / "sc.npz"
    code, _, _ = run(
        capsys, "discretize", example, "--object", "pentagon", "-o", out, "--model", "supercover"
    )
    assert code == 0 and read_pixels(out) == discretize(objects["pentagon"].source, "supercover")
    # without --object: every Euclidean object, combined
    code, _, _ = run(capsys, "discretize", example, "-o", tmp_path / "all.png")
    assert code == 0
    expected = discretize(objects["pentagon"].source, "standard") | discretize(
        objects["tilted square"].source, "standard"
    )
    assert read_pixels(tmp_path / "all.png") == expected


def test_discretize_a_discrete_object_writes_its_pixels(capsys, tmp_path):
    example = example_path("diamond.mrm")
    (diamond,) = read_project(example).objects
    code, stdout, err = run(
        capsys, "discretize", example, "--object", "diamond", "-o", tmp_path / "d.png", "--json"
    )
    assert code == 0, err
    assert json.loads(stdout)["source"] == "discrete"
    assert read_pixels(tmp_path / "d.png") == diamond.source
    # without --object there is no Euclidean object to discretize, and the message says what to do
    err = fails(capsys, "discretize", example, "-o", tmp_path / "x.png")
    assert "no Euclidean object" in err and "--object" in err
    assert not (tmp_path / "x.png").exists()


def test_discretize_object_in_the_projects_model(capsys, tmp_path, gauss_project):
    code, _, _ = run(capsys, "discretize", gauss_project, "--object", "box", "-o", tmp_path / "g.npz")
    assert code == 0 and as_set(read_pixels(tmp_path / "g.npz")) == BOX_GAUSS
    code, _, _ = run(
        capsys,
        "discretize",
        gauss_project,
        "--object",
        "box",
        "-o",
        tmp_path / "s.npz",
        "--model",
        "standard",
    )
    assert code == 0 and as_set(read_pixels(tmp_path / "s.npz")) == BOX_STANDARD


def test_discretize_to_svg_draws_the_pixels_under_the_outline(capsys, tmp_path):
    tri = Polygon([(-0.5, -0.5), (3.5, -0.5), (-0.5, 2.5)])
    src = tmp_path / "tri.wkt"
    src.write_text(tri.wkt + "\n")
    code, _, err = run(capsys, "discretize", src, "-o", tmp_path / "t.svg", "--model", "supercover")
    assert code == 0, err
    root = ET.parse(tmp_path / "t.svg").getroot()
    drawn = set()
    for r in root.iter(f"{SVG}rect"):
        x, y, w = float(r.get("x")), float(r.get("y")), int(float(r.get("width")))
        drawn |= {(int(x + 0.5) + k, int(-y - 0.5)) for k in range(w)}
    assert drawn == as_set(discretize(tri, "supercover"))
    (outline,) = root.findall(f"{SVG}path")
    assert outline.get("fill") == "none"
    numbers = [
        float(v) for v in outline.get("d").replace("M", " ").replace("L", " ").replace("Z", " ").split()
    ]
    assert list(zip(numbers[::2], numbers[1::2], strict=True)) == [(x, -y) for x, y in tri.exterior.coords]


# ---------------------------------------------------------------------------------------------- bad --object
@pytest.mark.parametrize("command", ["info", "discretize"])
def test_unknown_object_lists_the_names(capsys, tmp_path, command):
    example = example_path("two-polygons.mrm")
    out = ["-o", tmp_path / "o.png"] if command == "discretize" else []
    err = fails(capsys, command, example, "--object", "hexagon", *out)
    assert "'hexagon'" in err and "'pentagon'" in err and "'tilted square'" in err
    assert not (tmp_path / "o.png").exists()


@pytest.mark.parametrize("command", ["info", "discretize"])
def test_ambiguous_object_and_object_of_a_plain_file(capsys, tmp_path, gauss_project, command):
    out = ["-o", tmp_path / "o.png"] if command == "discretize" else []
    err = fails(capsys, command, gauss_project, "--object", "twin", *out)
    assert "'twin'" in err and "2 objects" in err
    plain = tmp_path / "box.wkt"
    plain.write_text(BOX.wkt)
    err = fails(capsys, command, plain, "--object", "box", *out)
    assert "project (.mrm) files only" in err
    assert not (tmp_path / "o.png").exists()
