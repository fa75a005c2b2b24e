"""Mesh files (mrm.io.mesh_files): OBJ, PLY, OFF, STL in; OBJ, PLY, OFF out bit for bit; hostile files.

Every hostile file is built here: files declaring 10⁸ triangles (refused from the header or the size, before
decoding, in bounded memory), corrupt and truncated files, and meshes that do not bound a solid (open,
non-manifold, self-intersecting, inverted, NaN/inf, zero-area triangles): each gets a clear one-line
message with the file's name and where the mesh is wrong.
"""

from __future__ import annotations

import contextlib
import logging
import math
import struct
import tracemalloc
from itertools import pairwise
from pathlib import Path

import numpy as np
import pytest
import trimesh
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from mrm.core.errors import FileFormatError, InvalidGeometryError
from mrm.geometry.polyhedra import Polyhedron
from mrm.geometry.polyhedra.predicates import orient3d_sign
from mrm.io.mesh_files import read_mesh, read_mesh_arrays, write_mesh
from tests.model.test_polyhedra import cube, cube_with_cavity, flipped, octahedron, union

EXACT = (".obj", ".ply", ".off")


def _obj(v: np.ndarray, t: np.ndarray) -> str:
    return "".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in v.tolist()) + "".join(
        f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in t.tolist()
    )


def _off(v: np.ndarray, t: np.ndarray) -> str:
    return (
        f"OFF\n{len(v)} {len(t)} 0\n"
        + "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in v.tolist())
        + "".join(f"3 {a} {b} {c}\n" for a, b, c in t.tolist())
    )


# ---------------------------------------------------------------------------------------------- round trips
@pytest.mark.parametrize("ext", EXACT)
def test_exact_formats_round_trip(tmp_path: Path, ext: str) -> None:
    p = Polyhedron(*cube_with_cavity()).translate((0.1, -0.3, 1e-7))
    path = tmp_path / f"m{ext}"
    assert write_mesh(p, path, triangles=True) is None
    v, t = read_mesh_arrays(path)
    assert v.tobytes() == p.vertices.tobytes() and np.array_equal(t, p.triangles)
    assert read_mesh(path) == p
    # By default a face is one polygon (OBJ, OFF): read back as its fan, the same faces on the same vertices.
    assert write_mesh(p, path) is None
    back = read_mesh(path)
    assert back.vertices.tobytes() == p.vertices.tobytes()
    assert faces_as_sets(back) == faces_as_sets(p) and back.signed_volume == p.signed_volume
    if ext == ".obj":  # 12 squares, not 24 triangles (PLY keeps triangles)
        assert sum(ln.startswith("f ") for ln in path.read_text().splitlines()) == 12
    elif ext == ".off":
        assert path.read_text().splitlines()[1].split()[1] == "12"


def faces_as_sets(p: Polyhedron) -> set[frozenset[int]]:
    """Each face of p as the set of its triangles' vertices."""
    out: dict[int, set[int]] = {}
    for f, tri in zip(p.face_of_triangle.tolist(), p.triangles.tolist(), strict=True):
        out.setdefault(f, set()).update(tri)
    return {frozenset(s) for s in out.values()}


@st.composite
def tetrahedra(draw: st.DrawFn) -> Polyhedron:
    """A tetrahedron with arbitrary float64 corners (subnormals, -0.0, huge, full mantissas)."""
    coord = st.one_of(
        st.floats(allow_nan=False, allow_infinity=False),
        st.floats(-1e3, 1e3),
        st.sampled_from((0.0, -0.0, 5e-324, -5e-324, 1.7976931348623157e308, 0.1, 1 / 3)),
    )
    v = np.array([[draw(coord) for _ in range(3)] for _ in range(4)], dtype=np.float64)
    assume(len({tuple(r) for r in (v + 0.0).tolist()}) == 4)
    s = orient3d_sign(v[0], v[1], v[2], v[3])
    assume(s != 0)
    t = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]], dtype=np.int64)
    if s < 0:
        t = t[:, ::-1].copy()
    try:
        return Polyhedron(v, t)
    except InvalidGeometryError:  # e.g. a flat face in exact arithmetic although not coplanar overall
        assume(False)
        raise


@settings(
    max_examples=60, suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.filter_too_much]
)
@given(tetrahedra(), st.sampled_from(EXACT))
def test_float64_round_trips_bit_for_bit(tmp_path: Path, p: Polyhedron, ext: str) -> None:
    path = tmp_path / f"t{ext}"
    write_mesh(p, path)
    v, t = read_mesh_arrays(path)
    assert v.tobytes() == p.vertices.tobytes()  # -0.0 stays -0.0, subnormals stay
    assert np.array_equal(t, p.triangles)


def test_obj_of_other_writers(tmp_path: Path) -> None:
    # Texture coordinates, normals, groups, materials, a quad per cube side and negative indices: one
    # vertex per position all the same (trimesh's OBJ reader would split them by texture coordinate).
    v, _ = cube()
    quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    lines = ["mtllib x.mtl", "o box"] + [f"v {x!r} {y!r} {z!r} 0.5 0.5 0.5" for x, y, z in v.tolist()]
    lines += ["vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1", "vn 0 0 1", "usemtl m", "s off"]
    for k, q in enumerate(quads):
        if k % 2:
            lines.append("f " + " ".join(f"{i - 8}/{j + 1}/1" for j, i in enumerate(q)))
        else:
            lines.append("f " + " ".join(f"{i + 1}//1" for i in q))
    path = tmp_path / "box.obj"
    path.write_text("\n".join(lines) + "\n")
    p = read_mesh(path)
    assert (p.n_vertices, p.n_triangles, p.n_faces, p.signed_volume) == (8, 12, 6, 1.0)
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")
    _refused(path, FileFormatError, "line 4", "not defined before it")
    path.write_text("v 0 0 0\nv 1 0 zero\n")
    _refused(path, FileFormatError, "line 2", "not a number")


def test_stl_warns_that_it_keeps_float32_only(tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    exact = Polyhedron(*cube_with_cavity())  # small integers: float32 holds them
    assert write_mesh(exact, tmp_path / "a.stl") is None
    assert read_mesh(tmp_path / "a.stl") == exact  # corners joined by equality, order of first use
    p = exact.translate((0.1, 0.0, 0.0))
    with caplog.at_level(logging.WARNING, logger="mrm.io.mesh_files"):
        w = write_mesh(p, tmp_path / "b.stl")
    assert w is not None and "float32" in w and "16 of 16 vertices" in w and "OBJ, PLY or OFF" in w
    assert w in caplog.text
    back = read_mesh(tmp_path / "b.stl")
    assert back.n_triangles == p.n_triangles and back != p
    assert np.allclose(back.vertices, np.float32(back.vertices))


def test_reads_binary_and_ascii_stl_of_other_writers(tmp_path: Path) -> None:
    box = trimesh.creation.box(extents=(2.0, 4.0, 8.0))
    for name, kind in (("bin.stl", "stl"), ("ascii.stl", "stl_ascii")):
        data = box.export(file_type=kind)
        (tmp_path / name).write_bytes(data if isinstance(data, bytes) else data.encode())
        p = read_mesh(tmp_path / name)
        assert (p.n_vertices, p.n_triangles, p.n_faces, p.signed_volume) == (8, 12, 6, 64.0)


def test_ply_from_trimesh_and_ascii_ply(tmp_path: Path) -> None:
    sphere = trimesh.creation.icosphere(subdivisions=2)
    for enc in ("binary", "ascii"):
        path = tmp_path / f"s_{enc}.ply"
        data = sphere.export(file_type="ply", encoding=enc)
        path.write_bytes(data if isinstance(data, bytes) else data.encode())
        p = read_mesh(path)
        assert p.n_triangles == len(sphere.faces) and p.n_shells == 1


# ---------------------------------------------------------------------------------------------- hostile
def _refused(path: Path, err: type[Exception], *fragments: str) -> str:
    with pytest.raises(err) as e:
        read_mesh(path)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith(path.name + ":"), msg
    for f in fragments:
        assert f in msg, msg
    return msg


def _peak(fn) -> int:  # type: ignore[no-untyped-def]
    tracemalloc.start()
    try:
        with contextlib.suppress(FileFormatError, InvalidGeometryError):
            fn()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_binary_stl_declaring_1e8_triangles(tmp_path: Path) -> None:
    path = tmp_path / "bomb.stl"
    path.write_bytes(b"\0" * 80 + struct.pack("<I", 10**8) + b"\0" * 50 * 10)
    _refused(path, FileFormatError, "declares 100,000,000 triangles", "nothing was decoded")
    assert _peak(lambda: read_mesh(path)) < 1 << 20
    # Within the limit but longer than the file: corrupt.
    path.write_bytes(b"\0" * 80 + struct.pack("<I", 1000) + b"\0" * 50 * 10)
    _refused(path, FileFormatError, "corrupt binary STL", "declares 1,000 triangles")


def test_ply_and_off_declaring_1e8_faces(tmp_path: Path) -> None:
    ply = tmp_path / "bomb.ply"
    ply.write_bytes(
        b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        b"property float z\nelement face 100000000\nproperty list uchar int vertex_indices\nend_header\n"
        + b"\0"
        * 100
    )
    _refused(ply, FileFormatError, "declares 100,000,000 faces")
    assert _peak(lambda: read_mesh(ply)) < 1 << 20
    off = tmp_path / "bomb.off"
    off.write_text("OFF\n3 100000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    _refused(off, FileFormatError, "declares 100,000,000 faces")


def test_declared_sizes_beyond_the_file(tmp_path: Path) -> None:
    ply = tmp_path / "short.ply"
    ply.write_bytes(
        b"ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty double x\nproperty double y\n"
        b"property double z\nelement face 10\nproperty list uchar int vertex_indices\nend_header\n"
        + b"\0"
        * 64
    )
    _refused(ply, FileFormatError, "truncated PLY", "24,130 bytes")
    off = tmp_path / "short.off"
    off.write_text("OFF\n100000 10 0\n0 0 0\n")
    _refused(off, FileFormatError, "corrupt or truncated OFF", "100,000 vertices")


def test_obj_over_the_limit_is_refused_before_decoding(tmp_path: Path) -> None:
    path = tmp_path / "many.obj"
    path.write_text(_obj(*cube()))
    with pytest.raises(FileFormatError, match="declares 12 faces, more than the limit of 11"):
        read_mesh(path, limit=11)


@pytest.mark.parametrize(
    ("name", "content", "fragment"),
    [
        ("junk.ply", b"\x89PNG\r\n\x1a\n" + b"\0" * 100, "not a PLY file"),
        ("junk.off", b"solid nonsense\n", "not an OFF file"),
        ("junk.stl", b"\x01\x02", "not an STL file"),
        ("bad.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", ""),
        ("words.obj", b"v a b c\nf 1 2 3\n", ""),
        ("badheader.ply", b"ply\nformat ascii 1.0\nelement vertex many\nend_header\n", "corrupt PLY header"),
        ("badcounts.off", b"OFF\nthree faces\n", "corrupt OFF header"),
        ("type.xyz", b"0 0 0\n", "unsupported mesh file type '.xyz'"),
        ("empty.obj", b"# nothing\n", "holds no triangle"),
    ],
)
def test_corrupt_files(tmp_path: Path, name: str, content: bytes, fragment: str) -> None:
    path = tmp_path / name
    path.write_bytes(content)
    with pytest.raises((FileFormatError, InvalidGeometryError)) as e:
        read_mesh(path)
    msg = str(e.value)
    assert msg.startswith(name + ":") and "\n" not in msg and fragment in msg, msg


def test_truncated_binary_ply_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "t.ply"
    write_mesh(Polyhedron(*cube()), path)
    data = path.read_bytes()
    path.write_bytes(data[: len(data) - 20])
    _refused(path, FileFormatError, "truncated PLY")


def test_a_fifo_is_not_read(tmp_path: Path) -> None:
    import os

    fifo = tmp_path / "pipe.obj"
    os.mkfifo(fifo)
    _refused(fifo, FileFormatError, "not a regular file")


@pytest.mark.parametrize("ext", [".obj", ".off"])
def test_invalid_meshes_say_where(tmp_path: Path, ext: str) -> None:
    write = _obj if ext == ".obj" else _off
    cases = {
        "open": (cube()[0], cube()[1][1:], "the surface is open", "edge (1.0, 0.0, 0.0)–(0.0, 1.0, 0.0)"),
        "inverted": (*flipped(cube()), "inside out", ""),
        "intersecting": (*union(cube(), (cube()[0] + 0.5, cube()[1])), "intersects itself", "triangles"),
        "nonmanifold": (
            np.vstack([octahedron()[0], np.delete(octahedron()[0] + [2.0, 0, 0], 1, axis=0)]),
            np.vstack([octahedron()[1], np.array([6, 0, 7, 8, 9, 10])[octahedron()[1]]]),
            "non-manifold vertex (1.0, 0.0, 0.0)",
            "",
        ),
        "flat": (
            np.vstack([cube()[0], [[2.0, 0.0, 0.0]]]),
            np.vstack([cube()[1], [[0, 1, 8]]]),
            "zero area",
            "(2.0, 0.0, 0.0)",
        ),
    }
    for key, (v, t, *fragments) in cases.items():
        path = tmp_path / f"{key}{ext}"
        path.write_text(write(v, t))
        _refused(path, InvalidGeometryError, *[f for f in fragments if f])


@pytest.mark.parametrize("bad", ["nan", "inf", "-inf"])
def test_non_finite_coordinates(tmp_path: Path, bad: str) -> None:
    v, t = cube()
    text = _obj(v, t).replace("v 1.0 1.0 1.0", f"v 1.0 {bad} 1.0")
    path = tmp_path / "n.obj"
    path.write_text(text)
    _refused(path, InvalidGeometryError, "vertex 7", "not a finite number", repr(float(bad)))


def test_a_failed_write_leaves_the_old_file(tmp_path: Path) -> None:
    path = tmp_path / "keep.obj"
    path.write_text("old")
    with pytest.raises(FileFormatError):
        write_mesh(Polyhedron(*cube()), tmp_path / "keep.xyz")
    assert path.read_text() == "old"
    write_mesh(Polyhedron(*cube()), path, triangles=True)
    assert read_mesh(path) == Polyhedron(*cube())
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]
    assert math.isfinite(read_mesh(path).signed_volume)


@pytest.mark.parametrize("shape", ["stairs", "box"])
@pytest.mark.parametrize("triangles", [False, True])
@pytest.mark.parametrize("ext", [".obj", ".off"])
def test_text_written_in_chunks_is_the_whole_text(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, ext: str, triangles: bool, shape: str
) -> None:
    # Big meshes are written a chunk of rows at a time (one whole-array tolist or join held the GIL for a
    # second and froze the desktop). With chunks of 3 rows every boundary is crossed: the file is the one a
    # plain writer makes, line for line, and reads back as the same solid.
    import mrm.io.mesh_files as mesh_files
    from mrm.core.grids import VoxelSet
    from mrm.geometry.reconstruct import reconstruct_voxels
    from tests.model.test_face_polygons import box_with_points_on_its_top

    # R of a staircase and a slab: polygons of several sizes; the box: vertices inside a face, in no polygon
    z, y, x = np.mgrid[0:6, 0:6, 0:6]
    if shape == "stairs":
        p = reconstruct_voxels(VoxelSet((x + y + z <= 6) | (x >= 4), (0, 0, 0)), "standard")
    else:
        p = box_with_points_on_its_top(3)
    write_mesh(p, tmp_path / f"whole{ext}", triangles=triangles)
    monkeypatch.setattr(mesh_files, "_ROWS", 3)
    write_mesh(p, tmp_path / f"parts{ext}", triangles=triangles)
    whole = (tmp_path / f"whole{ext}").read_text()
    assert (tmp_path / f"parts{ext}").read_text() == whole
    # and the whole text is what a plain writer makes: the vertices by repr, then one line per polygon
    ptr, idx = (np.arange(0, p.triangles.size + 1, 3), p.triangles.ravel()) if triangles else p.polygons
    used = np.unique(idx)
    number = {int(u): k for k, u in enumerate(used)}
    lines = whole.splitlines()
    verts = [" ".join(repr(float(c)) for c in p.vertices[u]) for u in used]
    faces = [[number[int(i)] for i in idx[a:b]] for a, b in pairwise(ptr.tolist())]
    if ext == ".obj":
        assert lines[1 : 1 + len(verts)] == [f"v {s}" for s in verts]
        assert lines[1 + len(verts) :] == ["f " + " ".join(str(i + 1) for i in f) for f in faces]
    else:
        assert lines[1] == f"{len(verts)} {len(faces)} 0"
        assert lines[2 : 2 + len(verts)] == verts
        assert lines[2 + len(verts) :] == [f"{len(f)} " + " ".join(map(str, f)) for f in faces]
    assert read_mesh(tmp_path / f"parts{ext}").signed_volume == p.signed_volume
