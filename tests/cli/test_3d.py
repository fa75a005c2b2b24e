"""3D on the command line (issue 28 item 6): ``mrm voxelize``, ``mrm info`` and ``mrm reconstruct`` on voxel
files and meshes, run as a user would (``run_cli``, the ``mrm`` subcommand layer, and one real subprocess).

Every input is built here: meshes written with the library's exact writer (or by hand, when the point is a
broken file), voxel sets from points.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import mrm
from mrm.cli import run_cli
from mrm.io.voxel_files import read_voxels, write_label_volume, write_voxels
from mrm.reps.cells_3d import cells_3d_of
from mrm.reps.summary import summarize

KEYS_3D = {
    "model",
    "voxels",
    "bbox",
    "components",
    "cavities",
    "tunnels",
    "euler",
    "surfels",
    "plane_segments",
    "faces",
    "vertices",
}


def run(capsys, *argv: object) -> tuple[int, str, str]:
    code = run_cli([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def fails(capsys, command: str, *argv: object) -> str:
    """The one error line of a refused run (exit status 2, nothing on stdout, no traceback)."""
    code, out, err = run(capsys, command, *argv)
    assert code == 2, err
    lines = [ln for ln in err.splitlines() if not ln.startswith("mrm: first run")]
    assert len(lines) == 1 and lines[0].startswith(f"mrm {command}: error: "), err
    assert "Traceback" not in err and out == ""
    return lines[0]


# The box [x0, x1] × [y0, y1] × [z0, z1]: eight corners, twelve triangles, outward.
_BOX_TRIANGLES = [
    [0, 2, 1], [0, 3, 2],  # z = z0, seen from below
    [4, 5, 6], [4, 6, 7],  # z = z1
    [0, 1, 5], [0, 5, 4],  # y = y0
    [2, 3, 7], [2, 7, 6],  # y = y1
    [1, 2, 6], [1, 6, 5],  # x = x1
    [3, 0, 4], [3, 4, 7],  # x = x0
]  # fmt: skip


def box(lo: tuple[float, float, float], hi: tuple[float, float, float]) -> tuple[np.ndarray, list[list[int]]]:
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0]]
    v += [[x, y, z1] for x, y, _ in v]
    return np.array(v, dtype=float), [list(t) for t in _BOX_TRIANGLES]


def write_off(path: Path, v: np.ndarray, t: list[list[int]]) -> Path:
    """An OFF file by hand (so that broken meshes can be written too)."""
    lines = ["OFF", f"{len(v)} {len(t)} 0"]
    lines += [" ".join(repr(float(c)) for c in p) for p in v]
    lines += ["3 " + " ".join(str(i) for i in tri) for tri in t]
    path.write_text("\n".join(lines) + "\n")
    return path


def box_file(path: Path, lo=(0, 0, 0), hi=(3, 2, 1)) -> Path:
    """The box written with the library's exact writer (STL too: its corners are float32 values)."""
    assert mrm.write_mesh(mrm.Polyhedron(*box(lo, hi)), path) is None
    return path


# The box [0, 3] × [0, 2] × [0, 1] has its corners on voxel centres. By docs/design.md §11, gauss keeps the
# centres p + τ inside: x ∈ {0, 1, 2}, y ∈ {0, 1}, z = 0 (p + τ leaves it at x = 3, y = 2, z = 1); standard
# keeps the voxels whose open cube, shifted by τ, meets it: x ∈ 0..3, y ∈ 0..2, z ∈ 0..1.
BOX_GAUSS = {(x, y, 0) for x in range(3) for y in range(2)}
BOX_STANDARD = {(x, y, z) for x in range(4) for y in range(3) for z in range(2)}


def reference_plane_segments(points) -> int:
    """The number of greedy digital plane segments, by the pure-Python reference segmentation."""
    from mrm.geometry.planes.segmentation import plane_segments_reference
    from mrm.geometry.topology.labeling_3d import label_runs_3d
    from mrm.geometry.topology.surfels import surfels_of

    vs = points if isinstance(points, mrm.VoxelSet) else mrm.VoxelSet.from_points(sorted(points))
    s = surfels_of(label_runs_3d(vs.mask, 6))
    return len(plane_segments_reference(s.voxel, s.direction, s.neighbour))


def as_set(vs: mrm.VoxelSet) -> set[tuple[int, int, int]]:
    return {(int(x), int(y), int(z)) for x, y, z in vs.points()}


def hollow_cube() -> mrm.VoxelSet:
    """A 3³ cube without its centre: one component, one cavity."""
    return mrm.VoxelSet.from_points(
        [(x, y, z) for x in range(3) for y in range(3) for z in range(3) if (x, y, z) != (1, 1, 1)]
    )


def ring() -> mrm.VoxelSet:
    """A square ring of 8 voxels in the plane z = 5, far from the origin: one tunnel."""
    return mrm.VoxelSet.from_points(
        [(100 + x, -40 + y, 5) for x in range(3) for y in range(3) if (x, y) != (1, 1)]
    )


# ---------------------------------------------------------------------------------------------- voxelize
@pytest.mark.parametrize("mesh_ext", [".obj", ".ply", ".off", ".stl"])
@pytest.mark.parametrize("out_ext", [".npz", ".tif", ".nii.gz"])
def test_voxelize_writes_the_exact_voxels(capsys, tmp_path, mesh_ext, out_ext):
    mesh = box_file(tmp_path / f"box{mesh_ext}")
    out = tmp_path / "deep" / f"box{out_ext}"
    code, stdout, _ = run(capsys, "voxelize", mesh, "-o", out, "--model", "gauss", "--json")
    assert code == 0
    summary = json.loads(stdout)
    assert as_set(read_voxels(out)) == BOX_GAUSS
    assert set(summary) >= KEYS_3D and summary["input"] == str(mesh) and summary["output"] == str(out)
    assert summary["voxels"] == 6 and summary["bbox"] == [0, 0, 0, 2, 1, 0]
    assert (summary["components"], summary["cavities"], summary["tunnels"]) == (1, 0, 0)
    assert summary["surfels"] == 2 * 6 + 2 * 3 + 2 * 2
    assert summary["plane_segments"] == reference_plane_segments(BOX_GAUSS)
    assert (summary["faces"], summary["vertices"]) == (6, 8)  # the input box's


def test_voxelize_default_model_is_standard_and_prints_a_table(capsys, tmp_path):
    mesh = box_file(tmp_path / "b.off")
    code, stdout, _ = run(capsys, "voxelize", mesh, "-o", tmp_path / "b.npz")
    assert code == 0
    assert as_set(read_voxels(tmp_path / "b.npz")) == BOX_STANDARD
    assert "voxels" in stdout and "24" in stdout and "cavities" in stdout


def test_voxelize_limit(capsys, tmp_path):
    mesh = write_off(tmp_path / "b.off", *box((0, 0, 0), (30, 20, 10)))
    line = fails(capsys, "voxelize", mesh, "-o", tmp_path / "out" / "b.npz", "--limit", "1000")
    assert "1,000" in line or "1000" in line or "limit" in line
    assert not (tmp_path / "out").exists()


def _broken_meshes(tmp_path: Path) -> dict[str, Path]:
    v, t = box((0, 0, 0), (2, 2, 2))
    flipped = [list(tri) for tri in t]
    flipped[0] = flipped[0][::-1]
    nan = v.copy()
    nan[3, 1] = np.nan
    v2, t2 = box((1, 1, 1), (3, 3, 3))  # a second box overlapping the first: the surfaces cross
    return {
        "open": write_off(tmp_path / "open.off", v, t[:-1]),
        "orientation": write_off(tmp_path / "flipped.off", v, flipped),
        "nan": write_off(tmp_path / "nan.off", nan, t),
        "intersect": write_off(
            tmp_path / "two.off", np.vstack([v, v2]), t + [[i + 8 for i in tri] for tri in t2]
        ),
    }


@pytest.mark.parametrize("kind", ["open", "orientation", "nan", "intersect"])
def test_voxelize_refuses_an_invalid_mesh_and_writes_nothing(capsys, tmp_path, kind):
    mesh = _broken_meshes(tmp_path)[kind]
    out = tmp_path / "out" / "v.npz"
    line = fails(capsys, "voxelize", mesh, "-o", out)
    assert mesh.name in line
    assert not out.exists() and not (tmp_path / "out").exists()  # no file, no empty folder left behind


def test_voxelize_refuses_bad_extensions_before_reading(capsys, tmp_path):
    mesh = write_off(tmp_path / "b.off", *box((0, 0, 0), (1, 1, 1)))
    assert "voxel output file" in fails(capsys, "voxelize", mesh, "-o", tmp_path / "b.png")
    (tmp_path / "b.geojson").write_text("{}")
    assert "mesh file" in fails(capsys, "voxelize", tmp_path / "b.geojson", "-o", tmp_path / "b.npz")
    assert not (tmp_path / "b.npz").exists() and not (tmp_path / "b.png").exists()


def test_voxelize_several_meshes_into_a_folder(capsys, tmp_path):
    write_off(tmp_path / "a.off", *box((0, 0, 0), (3, 2, 1)))
    box_file(tmp_path / "b.ply", (10, 0, 0), (13, 2, 1))
    code, stdout, _ = run(
        capsys, "voxelize", tmp_path / "a.off", tmp_path / "b.ply", "-o", tmp_path / "vox", "--json"
    )
    assert code == 0
    summary = json.loads(stdout)
    assert summary["inputs"] == 2 and summary["voxels"] == 2 * 24
    assert as_set(read_voxels(tmp_path / "vox" / "a.npz")) == BOX_STANDARD
    assert as_set(read_voxels(tmp_path / "vox" / "b.npz")) == {(x + 10, y, z) for x, y, z in BOX_STANDARD}


def test_the_entry_point_runs_voxelize_and_its_help_says_3d(tmp_path):
    mesh = write_off(tmp_path / "b.off", *box((0, 0, 0), (3, 2, 1)))
    done = subprocess.run(
        [sys.executable, "-m", "mrm", "voxelize", str(mesh), "-o", "b.nii", "--model", "gauss", "--json"],
        cwd=tmp_path,
        capture_output=True,
    )
    assert done.returncode == 0, done.stderr.decode()
    assert json.loads(done.stdout)["voxels"] == 6 and as_set(read_voxels(tmp_path / "b.nii")) == BOX_GAUSS
    top = subprocess.run([sys.executable, "-m", "mrm", "--help"], capture_output=True, text=True).stdout
    line = next(ln for ln in top.splitlines() if ln.strip().startswith("voxelize"))
    assert "3D" in line


def help_text(capsys, command: str) -> str:
    with pytest.raises(SystemExit):
        run_cli([command, "-h"])
    return capsys.readouterr().out


# ---------------------------------------------------------------------------------------------- info
@pytest.mark.parametrize("ext", [".npz", ".tif", ".nii", ".nii.gz"])
def test_info_of_voxel_files(capsys, tmp_path, ext):
    write_voxels(hollow_cube(), tmp_path / f"h{ext}")
    write_voxels(ring(), tmp_path / f"r{ext}")
    code, stdout, _ = run(capsys, "info", tmp_path / f"h{ext}", "--json")
    assert code == 0
    h = json.loads(stdout)
    assert set(h) == KEYS_3D | {"input"}
    assert (h["voxels"], h["components"], h["cavities"], h["tunnels"], h["euler"]) == (26, 1, 1, 0, 2)
    assert h["surfels"] == 6 * 9 + 6
    # The 6 surfels around the one-voxel cavity need several planes: no plane has all six neighbours of a
    # voxel on one side and the voxel on the other.
    assert h["plane_segments"] == reference_plane_segments(hollow_cube()) > 2
    r_of_a = mrm.reconstruct(hollow_cube(), "standard")
    assert (h["faces"], h["vertices"]) == (r_of_a.n_faces, r_of_a.n_vertices)
    code, stdout, _ = run(capsys, "info", tmp_path / f"r{ext}", "--json", "--model", "gauss")
    r = json.loads(stdout)
    assert (r["model"], r["voxels"], r["components"], r["cavities"], r["tunnels"], r["euler"]) == (
        "gauss", 8, 1, 0, 1, 0,
    )  # fmt: skip
    assert r["bbox"] == [100, -40, 5, 102, -38, 5]


def test_info_counts_the_eight_plane_segments_of_the_digital_octahedron(capsys, tmp_path):
    r = 6
    octahedron = mrm.VoxelSet.from_points(
        [
            (x, y, z)
            for x in range(-r, r + 1)
            for y in range(-r, r + 1)
            for z in range(-r, r + 1)
            if abs(x) + abs(y) + abs(z) <= r
        ]
    )
    write_voxels(octahedron, tmp_path / "oct.npz")
    code, stdout, _ = run(capsys, "info", tmp_path / "oct.npz", "--json")
    assert code == 0 and json.loads(stdout)["plane_segments"] == 8  # its 8 faces (docs/design.md §11)


def test_info_of_a_grey_volume_needs_a_threshold(capsys, tmp_path):
    import nibabel as nib
    import tifffile

    grey = np.zeros((2, 3, 4), dtype=np.uint8)  # [z, y, x]
    grey[0, 1, 1:3] = 200
    grey[1, 1, 1] = 90
    tifffile.imwrite(tmp_path / "g.tif", grey[:, ::-1, :], photometric="minisblack")  # pages top row first
    nib.save(nib.Nifti1Image(grey.transpose(2, 1, 0).astype(np.float32), np.eye(4)), tmp_path / "g.nii.gz")
    for name in ("g.tif", "g.nii.gz"):
        line = fails(capsys, "info", tmp_path / name)
        assert "threshold" in line
        code, stdout, _ = run(capsys, "info", tmp_path / name, "--threshold", "100", "--json")
        assert code == 0 and json.loads(stdout)["voxels"] == 2
        code, stdout, _ = run(capsys, "info", tmp_path / name, "--threshold", "50", "--json")
        assert code == 0 and json.loads(stdout)["voxels"] == 3
    assert "--invert" in fails(capsys, "info", tmp_path / "g.tif", "--threshold", "50", "--invert")


def test_info_of_a_mesh_summarises_its_voxelization(capsys, tmp_path):
    mesh = box_file(tmp_path / "b.obj")
    code, stdout, _ = run(capsys, "info", mesh, "--json", "--model", "gauss")
    assert code == 0
    s = json.loads(stdout)
    assert set(s) == KEYS_3D | {"input"}
    assert (s["voxels"], s["faces"], s["vertices"]) == (6, 6, 8)
    code, stdout, _ = run(capsys, "info", mesh, "--json")
    assert json.loads(stdout)["voxels"] == len(BOX_STANDARD)
    assert "b.obj" in fails(capsys, "info", _broken_meshes(tmp_path)["open"].rename(tmp_path / "b.obj"))


def test_info_of_a_label_volume(capsys, tmp_path):
    # Two labels in one slice: 1 holds two separate regions (x = 0 and x = 3), 2 one region between them.
    labels = np.array([[[1, 2, 2, 1], [0, 2, 0, 0]]], dtype=np.int32)  # [z, y, x]
    lv = mrm.LabelVolume(labels, (10, 20, 30))
    write_label_volume(lv, tmp_path / "l.npz")
    write_label_volume(lv, tmp_path / "l.nii.gz")
    code, stdout, _ = run(capsys, "info", tmp_path / "l.npz", "--json")  # .npz 'labels': a label volume
    assert code == 0
    s = json.loads(stdout)
    cells = cells_3d_of(labels, (10, 20, 30))
    assert (s["labels"], s["regions"], s["voxels"], s["bbox"]) == (2, 3, 5, [10, 20, 30, 13, 21, 30])
    assert (s["two_cells"], s["one_cells"], s["zero_cells"], s["adjacencies"]) == (
        len(cells.two_cells), len(cells.one_cells), len(cells.zero_cells), len(cells.adjacency),
    )  # fmt: skip
    assert "label" in fails(capsys, "info", tmp_path / "l.nii.gz")  # many values: a mask needs a choice
    code, stdout, _ = run(capsys, "info", tmp_path / "l.nii.gz", "--labels", "--json")
    assert code == 0 and json.loads(stdout) == {**s, "input": str(tmp_path / "l.nii.gz")}
    assert "--threshold" in fails(capsys, "info", tmp_path / "l.npz", "--threshold", "1")
    mrm.write_pixels(mrm.PixelSet.from_points([(0, 0)]), tmp_path / "p.png")
    assert "--labels" in fails(capsys, "info", tmp_path / "p.png", "--labels")


def test_info_help_says_3d(capsys):
    text = help_text(capsys, "info")
    assert "3D" in text and ".nii.gz" in text and ".obj" in text


def test_info_keeps_2d_output_and_takes_both_in_one_batch(capsys, tmp_path):
    flat = mrm.PixelSet.from_points([(0, 0), (1, 0), (0, 1)])
    mrm.write_pixels(flat, tmp_path / "a.npz")
    write_voxels(hollow_cube(), tmp_path / "b.npz")  # a 3-D .npz: once refused, now a voxel file
    code, stdout, _ = run(capsys, "info", tmp_path / "a.npz", "--json")
    assert code == 0 and json.loads(stdout) == {
        "input": str(tmp_path / "a.npz"),
        **summarize(flat, "standard"),
    }
    code, stdout, _ = run(capsys, "info", tmp_path, "--json")
    assert code == 0
    files = json.loads(stdout)["files"]
    assert [f.get("pixels") for f in files] == [3, None] and [f.get("voxels") for f in files] == [None, 26]
    code, stdout, _ = run(capsys, "info", tmp_path)
    assert code == 0 and "26 voxels, 1 components, 1 cavities" in stdout


# ---------------------------------------------------------------------------------------------- reconstruct
def noise(seed: int) -> mrm.VoxelSet:
    rng = np.random.default_rng(seed)
    return mrm.VoxelSet(rng.random((5, 6, 7)) < 0.45, (-1000, 7, 123))


@pytest.mark.parametrize(
    ("model", "mesh_ext"), [("standard", ".obj"), ("supercover", ".ply"), ("gauss", ".off")]
)
def test_reconstruct_writes_a_mesh_that_discretizes_back(capsys, tmp_path, model, mesh_ext):
    a = noise(7) | hollow_cube() | ring()
    write_voxels(a, tmp_path / "a.tif")
    out = tmp_path / f"r{mesh_ext}"
    code, stdout, _ = run(capsys, "reconstruct", tmp_path / "a.tif", "-o", out, "--model", model, "--json")
    assert code == 0
    summary = json.loads(stdout)
    poly = mrm.read_mesh(out)  # a valid closed polyhedron, read back exactly
    assert mrm.voxelize(poly, model) == a  # D(R(A)) = A
    assert set(summary) >= KEYS_3D and summary["voxels"] == len(a)
    assert (summary["faces"], summary["vertices"]) == (poly.n_faces, poly.n_vertices)
    assert summary["seconds"] >= 0


def test_reconstruct_of_voxels_refuses_a_vector_output_and_2d_refuses_a_mesh(capsys, tmp_path):
    write_voxels(ring(), tmp_path / "r.nii.gz")
    mrm.write_pixels(mrm.PixelSet.from_points([(0, 0)]), tmp_path / "p.png")
    assert "mesh output file" in fails(
        capsys, "reconstruct", tmp_path / "r.nii.gz", "-o", tmp_path / "r.geojson"
    )
    assert "vector output file" in fails(capsys, "reconstruct", tmp_path / "p.png", "-o", tmp_path / "p.obj")
    assert not (tmp_path / "r.geojson").exists() and not (tmp_path / "p.obj").exists()


def test_reconstruct_a_folder_of_pixels_and_voxels(capsys, tmp_path):
    src = tmp_path / "in"
    src.mkdir()
    write_voxels(ring(), src / "ring.nii.gz")
    write_voxels(hollow_cube(), src / "cube.npz")
    mrm.write_pixels(mrm.PixelSet.from_points([(0, 0), (1, 1)]), src / "flat.png")
    code, stdout, _ = run(capsys, "reconstruct", src, "-o", tmp_path / "out", "--model", "gauss", "--json")
    assert code == 0
    assert json.loads(stdout)["inputs"] == 3
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["cube.obj", "flat.geojson", "ring.obj"]
    assert mrm.voxelize(mrm.read_mesh(tmp_path / "out" / "ring.obj"), "gauss") == ring()
    assert mrm.voxelize(mrm.read_mesh(tmp_path / "out" / "cube.obj"), "gauss") == hollow_cube()


def test_reconstruct_help_says_3d(capsys):
    text = help_text(capsys, "reconstruct")
    assert "3D" in text and ".nii.gz" in text and ".obj" in text


def test_reconstruct_says_how_r_was_made_and_notes_the_safety_net(capsys, tmp_path, monkeypatch):
    # `r` in --json: the octahedron's hulls; a small non-convex set's decimation; the same set past the
    # decimation's size limit gets the safety net, which meets the contract but is not compact: noted on
    # stderr.
    from mrm.core import limits

    z, y, x = np.mgrid[-7:8, -7:8, -7:8]
    write_voxels(mrm.VoxelSet(abs(x) + abs(y) + abs(z) <= 6, (-7, -7, -7)), tmp_path / "oct.npz")
    for model, way in (("gauss", "grown hull"), ("supercover", "spiked hull")):
        code, stdout, err = run(capsys, "reconstruct", tmp_path / "oct.npz", "-o", tmp_path / "o.obj",
                                "--model", model, "--json")  # fmt: skip
        assert code == 0 and json.loads(stdout)["r"] == way and "safety net" not in err
    a = noise(3) | ring()
    write_voxels(a, tmp_path / "a.npz")
    code, stdout, err = run(capsys, "reconstruct", tmp_path / "a.npz", "-o", tmp_path / "a.obj", "--json")
    assert code == 0 and json.loads(stdout)["r"] == "decimation" and "note" not in err
    monkeypatch.setattr(limits, "MAX_COMPACT_R_TRIANGLES", 10)
    code, stdout, err = run(capsys, "reconstruct", tmp_path / "a.npz", "-o", tmp_path / "a.obj", "--json")
    summary = json.loads(stdout)
    assert code == 0 and summary["r"] == "safety net"
    assert "R is the safety net" in err and "at most 10 triangles (--compact-limit raises it)" in err
    assert mrm.voxelize(mrm.read_mesh(tmp_path / "a.obj"), "standard") == a  # still exact
    net_faces = summary["faces"]
    # --compact-limit raises the limit for one run: the compact R again, fewer faces, no note.
    code, stdout, err = run(capsys, "reconstruct", tmp_path / "a.npz", "-o", tmp_path / "a.obj", "--json",
                            "--compact-limit", "1_000_000")  # fmt: skip
    summary = json.loads(stdout)
    assert code == 0 and summary["r"] == "decimation" and "note" not in err
    assert summary["faces"] < net_faces
    assert mrm.voxelize(mrm.read_mesh(tmp_path / "a.obj"), "standard") == a
    # A limit that is no whole number of triangles a polyhedron can have is refused before any work.
    range_ = "the compact limit is a whole number of triangles from 1 to 20,000,000"
    for bad, says in (
        ("0", f"{range_}, not 0"),
        ("30_000_000", f"{range_}, not 30000000"),
        ("1e5", "expected a whole number, got '1e5'"),
    ):
        with pytest.raises(SystemExit) as exit_:
            run_cli(
                [
                    "reconstruct",
                    str(tmp_path / "a.npz"),
                    "-o",
                    str(tmp_path / "b.obj"),
                    "--compact-limit",
                    bad,
                ]
            )
        assert exit_.value.code == 2
        assert f"argument --compact-limit: {says}" in capsys.readouterr().err
        assert not (tmp_path / "b.obj").exists()


def test_operations_on_a_project_read_the_r_of_its_compact_limit(capsys, tmp_path):
    # A project keeps its compact limit: mrm scale and mrm account on it read the R the desktop shows there
    # (a staircase's safety net under a limit of 10), not the default limit's compact R.
    from mrm.document import Document, Settings
    from mrm.document.commands import AddObject
    from mrm.geometry.reconstruct.safety_net_3d import safety_net_3d
    from mrm.io.project import save_project
    from mrm.ops.registry import run_operation

    z, y, x = np.mgrid[0:6, 0:6, 0:6]
    a = mrm.VoxelSet((x + y + z <= 7) | (x >= 4), (0, 0, 0))
    outs = {}
    for limit in (10, 20_000):
        doc = Document(Settings(compact_limit=limit))
        doc.push(AddObject(doc.make_object(a, name="stairs")))
        save_project(doc, tmp_path / f"p{limit}.mrm")
        code, _, err = run(
            capsys, "scale", tmp_path / f"p{limit}.mrm", "--alpha", "1.5", "-o", tmp_path / f"s{limit}.npz"
        )
        assert code == 0, err
        outs[limit] = mrm.read_voxels(tmp_path / f"s{limit}.npz")
    net = safety_net_3d(a.mask, a.origin)
    held = [(0, "standard", mrm.Polyhedron(net.vertices, net.triangles))]
    assert outs[10] == run_operation("dss", [a], {"alpha": 1.5}, held=held).output
    assert outs[10] != outs[20_000] == run_operation("dss", [a], {"alpha": 1.5}).output


def test_reconstruct_says_how_to_take_a_projects_3d_object(capsys, tmp_path):
    # A project's voxel object is not an input of mrm reconstruct yet: the error says what is, not that a
    # VoxelSet is no shapely geometry.
    from mrm.document import Document
    from mrm.document.commands import AddObject
    from mrm.io.project import save_project

    doc = Document()
    doc.push(AddObject(doc.make_object(mrm.VoxelSet(np.ones((2, 2, 2), bool), (0, 0, 0)), name="cube")))
    save_project(doc, tmp_path / "p.mrm")
    said = fails(capsys, "reconstruct", tmp_path / "p.mrm", "-o", tmp_path / "p.geojson")
    assert "'cube' is a 3D object" in said and "voxel files (.npz, .tif, .nii.gz)" in said
    assert not (tmp_path / "p.geojson").exists()


def test_ctrl_c_stops_a_long_reconstruction_at_once_and_writes_nothing(tmp_path):
    # A high --compact-limit makes R of a bumpy 64³ volume a decimation of tens of seconds. Ctrl+C stops it
    # (the kernel reads its stop flag): "interrupted", exit status 130, no file, no traceback. Before, the
    # signal waited for the kernel's end and surfaced as a SystemError.
    import signal
    import subprocess
    import sys
    import time

    from tests.model.voxel_shapes import smoothed_noise

    np.savez(tmp_path / "b.npz", mask=smoothed_noise(64, 3), origin=np.zeros(3, int))
    files = [str(tmp_path / "b.npz"), "-o", str(tmp_path / "b.obj")]
    proc = subprocess.Popen(
        [sys.executable, "-m", "mrm", "reconstruct", *files, "--compact-limit", "10000000"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),  # as a terminal's Ctrl+C reaches it
    )
    try:
        time.sleep(4)  # into the decimation (the net takes well under a second on a warm cache)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=10)  # the whole decimation would take tens of seconds more
    finally:
        proc.kill()
    assert proc.returncode == 130 and err.strip().endswith("mrm reconstruct: interrupted")
    assert "Traceback" not in err and not (tmp_path / "b.obj").exists()
