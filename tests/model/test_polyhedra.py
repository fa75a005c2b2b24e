"""Polyhedron: exact validation of closed oriented meshes, with messages that say where (design §11)."""

from __future__ import annotations

import pickle

import numpy as np
import pytest
import trimesh
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mrm.core.errors import InvalidGeometryError
from mrm.geometry.polyhedra import Polyhedron, repair
from mrm.geometry.polyhedra.self_intersection import first_intersecting_pair
from tests.oracles import polyhedra_reference as ref

CUBE_V = np.array(
    [[x, y, z] for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)], dtype=np.float64
)  # vertex i = (i & 1, i >> 1 & 1, i >> 2 & 1)
CUBE_T = np.array(
    [
        [0, 2, 1], [1, 2, 3],  # z = 0, facing -z
        [4, 5, 6], [5, 7, 6],  # z = 1
        [0, 1, 4], [1, 5, 4],  # y = 0
        [2, 6, 3], [3, 6, 7],  # y = 1
        [0, 4, 2], [2, 4, 6],  # x = 0
        [1, 3, 5], [3, 7, 5],  # x = 1
    ],
    dtype=np.int64,
)  # fmt: skip


def cube(lo: float = 0.0, size: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    return CUBE_V * size + lo, CUBE_T.copy()


def octahedron(r: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    v = np.array([[r, 0, 0], [-r, 0, 0], [0, r, 0], [0, -r, 0], [0, 0, r], [0, 0, -r]], dtype=np.float64)
    t = []
    for x in (0, 1):
        for y in (2, 3):
            for z in (4, 5):
                tri = [x, y, z]
                # outward: counter-clockwise seen from the octant's direction
                n = np.cross(v[y] - v[x], v[z] - v[x])
                if np.dot(n, v[x] + v[y] + v[z]) < 0:
                    tri = [x, z, y]
                t.append(tri)
    return v, np.array(t, dtype=np.int64)


def union(*parts: tuple[np.ndarray, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    vs, ts, n = [], [], 0
    for v, t in parts:
        vs.append(v)
        ts.append(t + n)
        n += len(v)
    return np.vstack(vs), np.vstack(ts)


def flipped(part: tuple[np.ndarray, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    return part[0], part[1][:, ::-1].copy()


def cube_with_cavity() -> tuple[np.ndarray, np.ndarray]:
    return union(cube(0.0, 3.0), flipped(cube(1.0, 1.0)))


# ---------------------------------------------------------------------------------------------- valid shapes
def test_cube() -> None:
    p = Polyhedron(*cube())
    assert (p.n_vertices, p.n_triangles, p.n_shells, p.n_faces) == (8, 12, 1, 6)
    assert p.signed_volume == 1.0
    assert p.bbox == ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))
    assert len(set(p.face_of_triangle[::2].tolist())) == 6


def test_octahedron_has_eight_faces() -> None:
    p = Polyhedron(*octahedron(2.0))
    assert (p.n_faces, p.n_shells, p.n_vertices) == (8, 1, 6)
    assert p.signed_volume == pytest.approx(4 * 8 / 3)


def test_two_shells_and_a_cavity() -> None:
    two = Polyhedron(*union(cube(), cube(5.0)))
    assert (two.n_shells, two.n_faces, two.signed_volume) == (2, 12, 2.0)
    cav = Polyhedron(*cube_with_cavity())
    assert (cav.n_shells, cav.n_faces, cav.signed_volume) == (2, 12, 26.0)
    # A solid inside the cavity: three nested shells, orientation alternating with the depth.
    nested = Polyhedron(*union(cube(0.0, 5.0), flipped(cube(1.0, 3.0)), cube(2.0, 1.0)))
    assert nested.n_shells == 3 and nested.signed_volume == 125.0 - 27.0 + 1.0


def test_torus_like_shapes() -> None:
    torus = trimesh.creation.torus(major_radius=2.0, minor_radius=0.5)
    p = Polyhedron(torus.vertices, torus.faces)
    assert p.n_shells == 1 and p.n_faces == len(torus.faces)  # no two triangles coplanar
    # A square frame (genus 1) from an extruded annulus: exactly coplanar triangles merge into faces.
    frame = trimesh.creation.annulus(r_min=1.0, r_max=2.0, height=1.0, sections=4)
    q = Polyhedron(frame.vertices, frame.faces)
    assert q.n_faces == 4 + 4 + 2  # outer sides, inner sides, top and bottom rings


def test_faces_need_exact_coplanarity() -> None:
    v, t = cube()
    v[7, 2] = 1.0 + 2.0**-52  # a top corner one ulp up: still in the planes x = 1 and y = 1, not z = 1
    p = Polyhedron(v, t)
    assert p.n_faces == 7
    assert p.face_of_triangle[2] != p.face_of_triangle[3]
    v[7, 0] = 1.0 - 2.0**-53  # and one ulp inward: the side x = 1 breaks too
    assert Polyhedron(v, t).n_faces == 8


def test_arrays_are_read_only_copies() -> None:
    v, t = cube()
    p = Polyhedron(v, t)
    v[0, 0] = 5.0
    assert p.vertices[0, 0] == 0.0
    with pytest.raises(ValueError):
        p.vertices[0, 0] = 1.0
    with pytest.raises(ValueError):
        p.triangles[0, 0] = 1
    assert p.vertices.dtype == np.float64 and p.triangles.dtype == np.int64


def test_equality_ignores_order_not_orientation() -> None:
    v, t = cube()
    p = Polyhedron(v, t)
    perm = np.array([3, 1, 7, 0, 2, 6, 5, 4])
    inv = np.argsort(perm)
    q = Polyhedron(v[perm], np.roll(inv[t], 1, axis=1)[::-1])
    assert p == q and hash(p) == hash(q)
    assert p != Polyhedron(*cube(0.0, 2.0))
    assert pickle.loads(pickle.dumps(p)) == p


def test_translate() -> None:
    p = Polyhedron(*cube_with_cavity())
    q = p.translate((2, -3, 5))
    assert q.bbox == ((2.0, -3.0, 5.0), (5.0, 0.0, 8.0)) and q.n_shells == 2
    assert q.translate((-2, 3, -5)) == p
    r = p.translate((0.1, 0.2, 0.3))  # rounded: validated again
    assert r.signed_volume == pytest.approx(26.0)
    with pytest.raises(InvalidGeometryError, match="three finite numbers"):
        p.translate((np.nan, 0, 0))


def test_empty() -> None:
    e = Polyhedron.empty()
    assert e.is_empty and e.n_shells == 0 and e.signed_volume == 0.0
    assert e == Polyhedron(np.zeros((0, 3)), np.zeros((0, 3), int))


@pytest.mark.parametrize("scale", [2.0**-300, 2.0**-150, 2.0**250, 1e300, 5e307])
def test_out_of_range_magnitudes_are_decided_exactly(scale: float) -> None:
    v, t = cube_with_cavity()
    p = Polyhedron(v * scale, t)
    assert (p.n_shells, p.n_faces) == (2, 12)
    with pytest.raises(InvalidGeometryError, match="inside out"):
        Polyhedron(v * scale, t[:, ::-1])


def test_far_from_the_origin() -> None:
    v, t = octahedron(1.0)
    p = Polyhedron(v + 2.0**40, t)
    assert p.n_faces == 8


# ---------------------------------------------------------------------------------------------- invalid
def _refused(v: object, t: object, *fragments: str) -> str:
    with pytest.raises(InvalidGeometryError) as e:
        Polyhedron(v, t)
    msg = str(e.value)
    assert isinstance(e.value, ValueError)
    for f in fragments:
        assert f in msg, msg
    return msg


def test_open_surface_names_the_edge() -> None:
    v, t = cube()
    # Without triangle [0, 2, 1] the first open edge is 1–2 of the new triangle 0.
    _refused(v, t[1:], "the surface is open", "edge (1.0, 0.0, 0.0)–(0.0, 1.0, 0.0)", "triangle 0 only")


def test_inconsistent_orientation_names_the_triangles() -> None:
    v, t = cube()
    t[3] = t[3, ::-1]
    _refused(v, t, "inconsistent orientation", "triangles 2 and 3", "(1.0, 0.0, 1.0)–(0.0, 1.0, 1.0)")


def test_non_manifold_edge() -> None:
    # Two cubes sharing the edge x = y = 1: four triangles on it.
    a, ta = cube()
    b = a + np.array([1.0, 1.0, 0.0])  # its vertices 0 and 4 are a's 3 and 7
    v = np.vstack([a, b[[1, 2, 3, 5, 6, 7]]])
    idx = np.array([3, 8, 9, 10, 7, 11, 12, 13])  # b's vertex i → its index in v
    _refused(
        v,
        np.vstack([ta, idx[ta]]),
        "non-manifold edge (1.0, 1.0, 1.0)–(1.0, 1.0, 0.0)",
        "4 triangles [7, 11, 16, 20]",
    )


def test_non_manifold_vertex() -> None:
    # Two octahedra touching at one shared vertex.
    a, ta = octahedron()
    b = a + np.array([2.0, 0.0, 0.0])  # b[1] = (1, 0, 0) = a[0]
    v = np.vstack([a, np.delete(b, 1, axis=0)])
    idx = np.array([6, 0, 7, 8, 9, 10])
    _refused(v, np.vstack([ta, idx[ta]]), "non-manifold vertex (1.0, 0.0, 0.0)", "2 separate fans")


@pytest.mark.parametrize(
    ("offset", "what"),
    [
        ((0.5, 0.25, 0.125), "overlap"),
        ((1.0, 0.25, 0.125), "face on face"),
        ((1.0, 1.0, 0.5), "edge along edge"),
        ((1.0, 0.5, 1.0), "corner on edge"),
        ((0.25, 0.25, 1.0), "inside a face"),
    ],
)
def test_self_intersection_names_the_first_pair(offset: tuple[float, float, float], what: str) -> None:
    a = cube()
    b = (a[0] + offset, a[1])
    v, t = union(a, b)
    msg = _refused(v, t, "intersects itself", "triangles")
    assert ref.first_intersecting_pair(v, t) is not None, what
    pair = first_intersecting_pair(v, t)
    assert pair == ref.first_intersecting_pair(v, t)
    assert f"triangles {pair[0]} " in msg and f" and {pair[1]} " in msg


def test_touching_corners_are_duplicate_vertices() -> None:
    v, t = union(cube(), cube(1.0))
    _refused(v, t, "vertices 7 and 8 are both at (1.0, 1.0, 1.0)", "repair()")


def test_inverted_and_outward_cavity() -> None:
    _refused(*flipped(cube()), "inside out", "shell of triangle 0")
    v, t = union(cube(0.0, 3.0), cube(1.0, 1.0))
    _refused(v, t, "faces outward", "shell of triangle 12", "(1.0, 1.0, 1.0)")


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_vertex(bad: float) -> None:
    v, t = cube()
    v[5, 1] = bad
    _refused(v, t, "vertex 5", "not a finite number", repr(float(bad)))


def test_zero_area_triangles() -> None:
    v, t = cube()
    _refused(v, np.vstack([t, [[0, 0, 1]]]), "triangle 12 has zero area", "repeats a vertex")
    v2 = np.vstack([v, [[2.0, 0.0, 0.0]]])
    _refused(v2, np.vstack([t, [[0, 1, 8]]]), "triangle 12 has zero area", "collinear", "(2.0, 0.0, 0.0)")


def test_malformed_arrays() -> None:
    v, t = cube()
    _refused(v, t + 1, "triangle", "refers to vertex", "8 vertices")
    _refused(v[:, :2], t, "shape (n, 3)")
    _refused(v, t.astype(float), "integer indices")
    _refused(np.vstack([v, [[9.0, 9.0, 9.0]]]), t, "vertex 8 (9.0, 9.0, 9.0) belongs to no triangle")
    _refused(
        np.vstack([v, v[:1]]), np.vstack([t, [[8, 2, 1]]]), "vertices 0 and 8 are both at (0.0, 0.0, 0.0)"
    )
    with pytest.raises(InvalidGeometryError, match="more than the limit"):
        Polyhedron(v, t, limit=11)


# ---------------------------------------------------------------------------------------------- the grid
@st.composite
def scattered_cubes(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray]:
    """A few cubes on a coarse lattice (touching, overlapping, apart), some rotated by a quarter turn."""
    parts = []
    for _ in range(draw(st.integers(2, 4))):
        lo = np.array([draw(st.integers(0, 4)) / 2.0 for _ in range(3)])
        size = draw(st.sampled_from((0.5, 1.0, 1.5)))
        v, t = cube(0.0, size)
        if draw(st.booleans()):
            v = v[:, [1, 2, 0]]  # a rotation: still outward
        parts.append((v + lo, t))
    return union(*parts)


@settings(max_examples=25)
@given(scattered_cubes())
def test_the_grid_finds_the_brute_force_first_pair(mesh: tuple[np.ndarray, np.ndarray]) -> None:
    v, t = mesh
    assert first_intersecting_pair(v, t) == ref.first_intersecting_pair(v, t)


def test_pair_tests_match_the_reference_on_sphere_neighbours() -> None:
    s = trimesh.creation.icosphere(subdivisions=1)
    v, t = np.asarray(s.vertices), np.asarray(s.faces, dtype=np.int64)
    assert first_intersecting_pair(v, t) is None
    # Push one vertex through the opposite side: now some pairs intersect.
    w = v.copy()
    w[0] = -1.5 * w[0]
    assert first_intersecting_pair(w, t) == ref.first_intersecting_pair(w, t) is not None


# ---------------------------------------------------------------------------------------------- repair
def test_repair_only_when_asked() -> None:
    a, ta = cube_with_cavity()
    v = np.vstack([a, a[:1]])
    t = np.vstack([ta[:, ::-1], [[0, 0, 3]], ta[:1, ::-1]])  # inverted, a flat and a repeated triangle
    t[0, 2] = 16  # a duplicate vertex in use
    with pytest.raises(InvalidGeometryError):
        Polyhedron(v, t)
    rv, rt, changes = repair(v, t)
    assert Polyhedron(rv, rt) == Polyhedron(*cube_with_cavity())
    joined = "; ".join(changes)
    for f in ("merged 1 duplicate vertex", "zero-area", "repeated triangle", "reversed 24 triangles"):
        assert f in joined, joined
    assert repair(*cube_with_cavity())[2] == []


@st.composite
def triangle_pairs(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray]:
    """Two non-flat triangles on a tiny lattice (so coplanar, collinear and touching cases are common),
    sharing 0, 1 or 2 vertices."""
    pt = st.tuples(*(st.integers(0, 2).map(float) for _ in range(3)))
    pts = draw(st.lists(pt, min_size=6, max_size=6, unique=True))
    v = np.array(pts, dtype=np.float64)
    shared = draw(st.integers(0, 2))
    a = [0, 1, 2]
    b = [[3, 4, 5], [0, 4, 5], [1, 0, 5]][shared]
    t = np.array([a, b], dtype=np.int64)
    for tri in t:
        p, q, r = v[tri]
        assume(np.cross(q - p, r - p).any())
    return v, t


@settings(max_examples=400)
@given(triangle_pairs())
def test_pair_test_matches_the_reference(pair: tuple[np.ndarray, np.ndarray]) -> None:
    from mrm.geometry.polyhedra.self_intersection import INTERSECT, triangles_meet_improperly

    v, t = pair
    expected = ref.triangles_meet_improperly(v, t[0].tolist(), t[1].tolist())
    assert (triangles_meet_improperly(v, t, 0, 1) == INTERSECT) == expected  # plain Python, exact
    assert (_compiled_pair(v, t) == INTERSECT) == expected


def _compiled_pair(v: np.ndarray, t: np.ndarray) -> int:
    from mrm.geometry.polyhedra.self_intersection import _test_cells

    lo = np.ascontiguousarray(v[t].min(axis=1))
    hi = np.ascontiguousarray(v[t].max(axis=1))
    c0 = np.zeros((2, 3), np.int64)
    a, _b, und = _test_cells(
        v, t, lo, hi, c0, np.zeros(2, np.int64), np.arange(2, dtype=np.int64), np.ones(3, np.int64)
    )
    assert und.size == 0
    return 1 if a >= 0 else 0


@pytest.mark.parametrize(
    "second",
    [
        [[2.0, 2.0, 0.0], [0.0, 2.0, 0.0]],  # adjacent angles sharing a side ray: they overlap along it
        [[0.0, 2.0, 0.0], [-1.0, 1.0, 0.0]],  # adjacent angles touching at v only
        [[1.0, 3.0, 0.0], [-1.0, 1.0, 0.0]],  # an edge crossing the other triangle's far edge
        [[3.0, 0.0, 0.0], [3.0, 3.0, 1.0]],  # not coplanar: a sheet through the other's side ray
    ],
)
def test_pairs_with_one_common_vertex(second: list[list[float]]) -> None:
    from mrm.geometry.polyhedra.self_intersection import INTERSECT, triangles_meet_improperly

    v = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], *second])
    t = np.array([[0, 1, 2], [0, 3, 4]], dtype=np.int64)
    expected = ref.triangles_meet_improperly(v, [0, 1, 2], [0, 3, 4])
    assert (triangles_meet_improperly(v, t, 0, 1) == INTERSECT) == expected
    assert (_compiled_pair(v, t) == INTERSECT) == expected


def test_repair_orients_a_flipped_triangle_and_keeps_what_it_cannot_fix() -> None:
    v, t = cube()
    t[5] = t[5, ::-1]
    with pytest.raises(InvalidGeometryError, match="inconsistent orientation"):
        Polyhedron(v, t)
    rv, rt, changes = repair(v, t)
    assert Polyhedron(rv, rt) == Polyhedron(*cube())
    assert changes == ["reversed 1 triangle to orient every shell outward (cavities inward)"]
    # An open surface stays open: repair does not invent triangles, validation still says where.
    rv, rt, _ = repair(v[:], cube()[1][1:])
    with pytest.raises(InvalidGeometryError, match="the surface is open"):
        Polyhedron(rv, rt)


@st.composite
def bent_octahedra(draw: st.DrawFn) -> np.ndarray:
    """An octahedron's six vertices on a small lattice: folded, flat, crossing and inverted triangles."""
    pt = st.tuples(*(st.integers(-2, 2).map(float) for _ in range(3)))
    return np.array(draw(st.lists(pt, min_size=6, max_size=6, unique=True)), dtype=np.float64)


@settings(max_examples=150)
@given(bent_octahedra())
def test_one_shell_accepted_iff_the_reference_says_valid(v: np.ndarray) -> None:
    _, t = octahedron()
    tl = t.tolist()
    expected = (
        not any(ref.is_flat(v, tri) for tri in tl)
        and ref.first_intersecting_pair(v, tl) is None
        and ref.volume6(v, tl) > 0
    )
    try:
        Polyhedron(v, t)
        accepted = True
    except InvalidGeometryError:
        accepted = False
    assert accepted == expected
