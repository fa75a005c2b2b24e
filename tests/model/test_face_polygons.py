"""A polyhedron's faces as polygons (Polyhedron.polygons), as OBJ and OFF files hold them (design §11).

A reader makes the fan of triangles from a polygon's first vertex; the polygons must give back, that way, a
valid polyhedron with the same faces and the same solid. A face that one polygon cannot hold (a hole, a corner
met twice, a right turn, no vertex between two corners) is given as its triangles.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mrm
from mrm.core.grids import VoxelSet
from mrm.geometry.polyhedra import Polyhedron
from mrm.geometry.reconstruct.safety_net_3d import safety_net_3d

MODELS = ["standard", "supercover", "gauss"]


def read_back(p: Polyhedron) -> Polyhedron:
    """What a mesh reader makes of p's polygons: the fan from each polygon's first vertex, on the vertices
    the polygons use (a vertex inside a face is in none, and a file of the polygons leaves it out)."""
    ptr, idx = p.polygons
    used = np.unique(idx)
    local = np.searchsorted(used, idx)
    fans = [
        (local[a], local[a + j], local[a + j + 1])
        for a, b in itertools.pairwise(ptr.tolist())
        for j in range(1, b - a - 1)
    ]
    return Polyhedron(p.vertices[used], np.array(fans, np.int64).reshape(-1, 3))


def faces_as_points(p: Polyhedron) -> list[set[tuple[float, ...]]]:
    """Each face of p as the set of its triangles' corners (coordinates)."""
    out: dict[int, set[tuple[float, ...]]] = {}
    for f, tri in zip(p.face_of_triangle.tolist(), p.triangles.tolist(), strict=True):
        out.setdefault(f, set()).update(tuple(p.vertices[i].tolist()) for i in tri)
    return list(out.values())


def faces_as_sets(p: Polyhedron) -> set[frozenset[int]]:
    """Each face of p as the set of its triangles' vertices."""
    out: dict[int, set[int]] = {}
    for f, tri in zip(p.face_of_triangle.tolist(), p.triangles.tolist(), strict=True):
        out.setdefault(f, set()).update(tri)
    return {frozenset(s) for s in out.values()}


def assert_polygons_give_back(p: Polyhedron) -> Polyhedron:
    """The polygons read back: a valid polyhedron with p's faces and solid; returned."""
    ptr, idx = p.polygons
    assert ptr[0] == 0 and ptr[-1] == idx.size and np.all(np.diff(ptr) >= 3)
    q = read_back(p)  # validated exactly: closed, manifold, no flat triangle, no crossing
    assert q.n_faces == p.n_faces
    assert q.signed_volume == pytest.approx(p.signed_volume, rel=1e-12)
    mine = faces_as_points(p)
    assert all(any(face <= m for m in mine) for face in faces_as_points(q))
    for a, b in itertools.pairwise(ptr.tolist()):  # each polygon within one face
        assert any({tuple(x) for x in p.vertices[idx[a:b]].tolist()} <= m for m in mine)
    assert p.n_faces <= ptr.size - 1 <= p.n_triangles  # one polygon per face, or the face's triangles
    return q


@settings(max_examples=60, deadline=None)
@given(
    bits=st.lists(st.booleans(), min_size=64, max_size=64),
    model=st.sampled_from(MODELS),
)
def test_every_r_of_random_voxels_reads_back_from_its_polygons(bits, model):
    # R of random 4×4×4 sets (the decimation's faces: convex and not, with holes) in every model: the
    # polygons give back the same faces, and the same voxels under D.
    mask = np.array(bits).reshape(4, 4, 4)
    if not mask.any():
        return
    vs = VoxelSet(mask, (3, -2, 7))
    p = mrm.reconstruct(vs, model)
    q = assert_polygons_give_back(p)
    assert mrm.voxelize(q, model) == vs


@pytest.mark.parametrize("model", MODELS)
def test_an_octahedrons_r_is_its_faces(model):
    # Under gauss 8 triangles; under the covers 8 hexagons (the faces moved in, their tips cut) and the 24
    # triangles of the spikes: one polygon per face.
    z, y, x = np.mgrid[-9:10, -9:10, -9:10]
    p = mrm.reconstruct(VoxelSet(abs(x) + abs(y) + abs(z) <= 8, (-9, -9, -9)), model)
    ptr, _ = p.polygons
    sizes = sorted(np.diff(ptr).tolist())
    assert sizes == ([3] * 8 if model == "gauss" else [3] * 24 + [6] * 8)
    assert_polygons_give_back(p)


def test_a_face_with_a_hole_or_a_right_turn_is_given_as_its_triangles():
    # The safety net of a 3×3×1 ring of voxels: its top and bottom faces are squares with a square hole, and
    # two of its outer walls have two vertices on each long side (no vertex between two corners). An L of
    # three voxels: its top and bottom faces turn right once. Those faces are their triangles; the other
    # sides one polygon each.
    ring = np.ones((1, 3, 3), bool)
    ring[0, 1, 1] = False
    ell = np.zeros((1, 2, 2), bool)
    ell[0, 0, :] = True
    ell[0, 1, 0] = True
    for mask, not_one in ((ring, 4), (ell, 2)):
        net = safety_net_3d(mask)
        p = Polyhedron(net.vertices, net.triangles)
        ptr, idx = p.polygons
        whole = {frozenset(idx[a:b].tolist()) for a, b in itertools.pairwise(ptr.tolist())}
        assert len(faces_as_sets(p) - whole) == not_one
        assert_polygons_give_back(p)


def box_with_points_on_its_top(per_side: int) -> Polyhedron:
    """The box [0, 3]² × [0, 1] whose top has per_side points on each side (the sides share them)."""
    corners = [(0, 0), (3, 0), (3, 3), (0, 3)]
    ring: list[tuple[float, float]] = []
    for k in range(4):
        (x0, y0), (x1, y1) = corners[k], corners[(k + 1) % 4]
        ring += [(x0 + (x1 - x0) * j / (per_side + 1), y0 + (y1 - y0) * j / (per_side + 1))
                 for j in range(per_side + 1)]  # fmt: skip
    n = len(ring)
    v = [(x, y, 1.0) for x, y in ring] + [(x, y, 0.0) for x, y in corners] + [(1.5, 1.5, 1.0)]
    top = [(i, (i + 1) % n, n + 4) for i in range(n)]  # a fan from the top's centre
    bottom = [(n, n + 2, n + 1), (n, n + 3, n + 2)]
    sides = []
    for k in range(4):  # each side: the bottom edge's ends and the top's points above it
        a, b = n + k, n + (k + 1) % 4
        up = [k * (per_side + 1) + j for j in range(per_side + 2)]
        up[-1] %= n
        sides += [(a, b, up[-1])] + [(a, up[j + 1], up[j]) for j in range(per_side + 1)]
    return Polyhedron(np.array(v, float), np.array(top + bottom + sides))


def test_a_convex_face_becomes_one_polygon_when_a_vertex_sits_between_two_corners():
    # One point on each side of the top: a fan from a point between two corners has no flat triangle. Two
    # points on each side: every vertex has a straight neighbour, so the top stays its triangles.
    one = box_with_points_on_its_top(1)
    sizes = sorted(np.diff(one.polygons[0]).tolist())
    assert sizes == [4, 5, 5, 5, 5, 8]  # the bottom, the four sides, the top
    assert_polygons_give_back(one)
    two = box_with_points_on_its_top(2)
    sizes = np.diff(two.polygons[0]).tolist()
    assert sizes.count(3) == 12 and sorted(s for s in sizes if s != 3) == [4, 6, 6, 6, 6]
    assert_polygons_give_back(two)


@pytest.mark.parametrize("ext", [".obj", ".off"])
def test_a_written_file_holds_one_polygon_per_face_and_reads_back(tmp_path, ext):
    z, y, x = np.mgrid[-9:10, -9:10, -9:10]
    vs = VoxelSet(abs(x) + abs(y) + abs(z) <= 8, (-9, -9, -9))
    p = mrm.reconstruct(vs, "supercover")
    path = tmp_path / f"r{ext}"
    mrm.write_mesh(p, path)
    back = mrm.read_mesh(path)
    assert back.n_faces == 32 and mrm.voxelize(back, "supercover") == vs
    text = path.read_text().splitlines()
    assert (sum(ln.startswith("f ") for ln in text) if ext == ".obj" else int(text[1].split()[1])) == 32
    mrm.write_mesh(p, path, triangles=True)
    assert mrm.read_mesh(path) == p


def square_tube() -> Polyhedron:
    """[0, 3]² × [0, 1] with the hole [1, 2]² × [0, 1] through it: its top and bottom are square annuli."""
    outer = [(0, 0), (3, 0), (3, 3), (0, 3)]
    inner = [(1, 1), (2, 1), (2, 2), (1, 2)]
    v = [(x, y, z) for z in (0.0, 1.0) for x, y in outer + inner]  # bottom 0–7, top 8–15
    t = []
    for k in range(4):
        o0, o1, i0, i1 = k, (k + 1) % 4, 4 + k, 4 + (k + 1) % 4
        t += [(8 + o0, 8 + o1, 8 + i1), (8 + o0, 8 + i1, 8 + i0)]  # top: counter-clockwise from above
        t += [(o0, i1, o1), (o0, i0, i1)]  # bottom: seen from below
        t += [(o0, o1, 8 + o1), (o0, 8 + o1, 8 + o0)]  # outer wall, facing out
        t += [(i0, 8 + i1, i1), (i0, 8 + i0, 8 + i1)]  # inner wall, facing the hole
    return Polyhedron(np.array(v, float), np.array(t))


def test_a_face_with_a_hole_is_its_triangles_even_when_both_loops_are_convex():
    p = square_tube()
    assert p.n_faces == 10
    sizes = np.diff(p.polygons[0]).tolist()
    assert sorted(sizes) == [3] * 16 + [4] * 8  # the annuli's triangles, the eight walls
    assert_polygons_give_back(p)
