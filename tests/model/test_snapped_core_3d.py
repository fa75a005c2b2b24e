"""R under the covers of digitally convex sets with many facets: the snapped core, with spikes (ADR 0070).

The core's corners, found from the dual hull on homogeneous integers, are held to the exact polytope of
half-spaces in Fractions (itself held to a brute force in test_convex_cover_r_3d.py); R to the contract of
docs/design.md §11 (D(R(A)) = A in the model and R ⊂ V(A), one shell, covariance) on balls up to r = 64 and
on random turned ellipsoids, every result discretized again here, whatever R proved on its way.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mrm
from mrm.core.grids import VoxelSet
from mrm.geometry.discretize.voxels import voxelize_solid, voxelize_triangles
from mrm.geometry.reconstruct import FALLBACKS
from mrm.geometry.reconstruct._halfspaces import convex_polytope
from mrm.geometry.reconstruct.convex_3d import (
    _exact_faces,
    _fans,
    _propose_hull,
    _quickhull,
    convex_reconstruction,
)
from mrm.geometry.reconstruct.snapped_core import (
    _clear_of_outside_cubes,
    _compare_rows,
    _spike_keeps_d,
    _unique_rows,
)
from tests.model.voxel_shapes import assert_convex_r_commutes_with_the_cube, ball

COVERS = ["standard", "supercover"]


def cramer(a, b, c, p, q, r) -> tuple[Fraction, Fraction, Fraction]:
    """The point on the three planes a·x = p, b·x = q, c·x = r, in Fractions."""

    def det(m):
        return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))  # fmt: skip

    m = [list(a), list(b), list(c)]
    d = det(m)
    out = []
    for k in range(3):
        mk = [row[:] for row in m]
        for i, rhs in enumerate((p, q, r)):
            mk[i][k] = rhs
        out.append(Fraction(det(mk), d))
    return out[0], out[1], out[2]


@settings(max_examples=150, deadline=None)
@given(
    raw=st.lists(st.tuples(st.tuples(*[st.integers(-4, 4)] * 3), st.integers(1, 60)), min_size=4, max_size=30)
)
def test_the_dual_hull_gives_the_cores_corners_exactly(raw):
    # The half-spaces a·x ≤ w (w > 0: the origin strictly inside) as the snapped core takes them: the dual
    # points (a, w) on homogeneous integers, their exact hull, a corner per hull triangle.
    normals, offsets, seen = [], [], set()
    for a, w in raw:
        g = int(np.gcd.reduce(np.abs(a))) if any(a) else 0
        if g == 0 or tuple(x // g for x in a) in seen:
            continue
        seen.add(tuple(x // g for x in a))
        normals.append(tuple(x // g for x in a))
        offsets.append(w)
    lo, hi = (Fraction(-1000),) * 3, (Fraction(1000),) * 3
    expected = convex_polytope(normals, [Fraction(w) for w in offsets], lo, hi)
    if expected is None or any(abs(x) == 1000 for p in expected.corners for x in p):
        return  # unbounded: the origin is not inside the dual hull, no core to find
    dual = np.array([[*a, w] for a, w in zip(normals, offsets, strict=True)], np.int64)
    tri, ok = _quickhull(dual)
    assert ok
    got = {cramer(*(normals[i] for i in t), *(offsets[i] for i in t)) for t in tri}
    assert got == set(expected.corners)
    planes_used = {int(i) for t in tri for i in t}
    assert planes_used == set(expected.planes)  # a hull corner per facet of the core, none for the others


def assert_covers_r(poly: mrm.Polyhedron, vs: VoxelSet, model: str) -> None:
    assert mrm.voxelize(poly, model) == vs
    assert mrm.voxelize(poly, "supercover") == vs  # R ⊂ V(A): it meets no closed cube outside A
    assert poly.n_shells == 1


@pytest.mark.parametrize("model", COVERS)
@pytest.mark.parametrize("r", [8, 21, 33, 64])
def test_balls_get_the_snapped_core_under_the_covers(r, model):
    vs = VoxelSet(ball(r, 2 * r + 5), (-r - 2, 7, 2**20))
    found = convex_reconstruction(vs, model)
    assert found is not None and found.facets > 64  # a ball is no lattice polytope: the snapped core
    assert_covers_r(found.polyhedron, vs, model)
    # Marching cubes gives about two triangles per surfel: the snapped core less than a tenth of that from
    # r = 21 on (r = 8: 584 triangles for 1,182 surfels, where R takes the decimation's, half as many).
    assert found.polyhedron.n_triangles < (0.1 if r > 8 else 0.25) * 2 * found.surfels
    before = FALLBACKS[0]
    poly = mrm.reconstruct(vs, model)
    assert FALLBACKS[0] == before
    assert_covers_r(poly, vs, model)
    assert poly.n_triangles <= found.polyhedron.n_triangles


def ellipsoid(seed: int, shortest: float = 4, longest: float = 14) -> VoxelSet:
    """The voxels of a randomly turned and placed ellipsoid, axes 4 to 14 by default: digitally convex."""
    rng = np.random.default_rng(seed)
    axes = rng.uniform(shortest, longest, 3)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    centre = rng.uniform(0, 1, 3)
    n = int(axes.max()) + 2
    z, y, x = np.mgrid[-n : n + 1, -n : n + 1, -n : n + 1]
    p = np.stack([x, y, z], axis=-1) - centre
    u = p @ q
    mask = ((u / axes) ** 2).sum(axis=-1) <= 1
    return VoxelSet(mask, (-n, -n, -n))


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), model=st.sampled_from(COVERS))
def test_turned_ellipsoids_get_a_right_r(seed, model):
    vs = ellipsoid(seed)
    found = convex_reconstruction(vs, model)
    if found is not None:  # whatever R proved on its way (the spikes' local check), discretized again here
        assert_covers_r(found.polyhedron, vs, model)
    assert_covers_r(mrm.reconstruct(vs, model), vs, model)


def test_turned_ellipsoids_take_the_snapped_core():
    # Seed 16 took the general way until a ring point was allowed onto a neighbour within an eighth (two
    # vertices on one spot).
    for seed in range(20):
        for model in COVERS:
            found = convex_reconstruction(ellipsoid(seed), model)
            assert found is not None and found.facets > 64, (seed, model)


@pytest.mark.parametrize("model", COVERS)
@pytest.mark.parametrize("seed", [9, 10, 15, 18, 19, 21])
def test_bigger_turned_ellipsoids_take_the_snapped_core(seed, model):
    # Axes 25 to 60: their tip voxels lie on flat parts of the core, two voxels or more from any corner,
    # and a cone from the nearest corners crossed a cube outside A in each of these. They are reached now
    # from a new corner on the face nearest the voxel, or nearest a neighbour of it in A.
    vs = ellipsoid(seed, 25, 60)
    found = convex_reconstruction(vs, model)
    assert found is not None and found.facets > 64
    assert_covers_r(found.polyhedron, vs, model)


@pytest.mark.parametrize("model", COVERS)
def test_the_snapped_core_commutes_with_the_rotations_and_translations(model):
    found = assert_convex_r_commutes_with_the_cube(ellipsoid(7), model)  # no symmetry: 24 different sets
    assert found.facets > 64


@pytest.mark.parametrize("model", COVERS)
def test_a_spike_touching_a_cube_outside_a_is_not_proven(model):
    # A spike's points (the corner it moved, the apex and a ring point) in a 5³ block of A with one voxel,
    # (4, 2, 2), outside: the hull of the points reaching x = 3.5 touches that voxel's closed cube.
    mask = np.ones((5, 5, 5), bool)
    mask[2, 2, 4] = False
    v, t = box_mesh((1, 1, 1), (3, 3, 3))
    reaching = np.array([[1.25, 2.0, 2.0], [2.0, 2.75, 2.0], [1.375, 2.125, 2.0], [3.5, 2.0, 2.0]])
    assert not _spike_keeps_d(reaching, v, t, mask, np.array([[2, 2, 2]]), model)
    inside = reaching.copy()
    inside[3, 0] = 3.25  # a quarter short of it: the cubes it meets are all in A, and P covers them
    assert _spike_keeps_d(inside, v, t, mask, np.array([[2, 2, 2]]), model)


@pytest.mark.parametrize("model", COVERS)
def test_a_spike_is_proven_only_where_the_cubes_of_its_cut_still_meet_p(model):
    # The spike's corner (1.25, 2, 2) and ring cut a cap out of the cube of (1, 2, 2) alone; the apex went
    # to the cube of (2, 2, 2). The cube of (1, 2, 2) must still meet a triangle of the new P: one far off
    # does not show it, one inside that cube does.
    mask = np.ones((5, 5, 5), bool)
    spike = np.array([[1.25, 2.0, 2.0], [2.0, 2.0, 2.25], [1.375, 2.0, 2.0], [1.3125, 2.125, 2.0]])
    others = [[3, 3, 3], [3.25, 3, 3], [3, 3.25, 3], [0.75, 2, 2], [1, 2, 2], [0.75, 2.25, 2]]
    w = np.vstack([spike[1:], others])
    far, close = np.array([[3, 4, 5]]), np.array([[3, 4, 5], [6, 7, 8]])
    missed = np.array([[2, 2, 2]])
    assert not _spike_keeps_d(spike, w, far, mask, missed, model)
    assert _spike_keeps_d(spike, w, close, mask, missed, model)


@pytest.mark.parametrize("model", COVERS)
def test_a_proven_spike_gives_d_of_p_plus_its_voxel_exactly(model):
    # The local proof held to the definition: P a random convex hull (eighths of a voxel), A = D(P) and a
    # voxel p next to it; P spiked from its corner nearest p (or from a point of its nearest face). Whenever
    # the spike is proven (and its cone meets no other triangle, as R asks), D of the spiked P is A exactly.
    # Proofs must come up often enough for the test to mean something.
    from mrm.geometry.reconstruct.snapped_core import (
        _cones_meet_nothing,
        _place,
        _spike_at,
        _split_nearest_face,
    )

    rng = np.random.default_rng(11)
    proven = 0
    for _ in range(60):
        hull = random_hull(rng.integers(40, 120, (12, 3)))
        if hull is None:
            continue
        q, tris = hull
        v = q / 8.0
        got, (ox, oy, oz) = voxelize_solid(v, tris, model, limit=None)
        a = np.zeros((20, 20, 20), bool)
        a[oz : oz + got.shape[0], oy : oy + got.shape[1], ox : ox + got.shape[2]] = got
        inside = np.argwhere(a)[:, ::-1]
        step = np.array([(1, 0, 0), (0, 1, 0), (0, 0, 1)])[rng.integers(3)] * rng.choice([-1, 1])
        p = inside[rng.integers(len(inside))]
        while a[p[2], p[1], p[0]]:
            p = p + step  # the first voxel past A along the step
        a[p[2], p[1], p[0]] = True
        target = p.astype(float)
        used = np.unique(tris)
        k = int(used[np.argmin(((v[used] - target) ** 2).sum(axis=1))])
        for w, t, i in [(v, tris, k), _split_nearest_face(v, tris, target)]:
            w2, t2, rows, _, points = _place(w, t, _spike_at(i, target, w, t))
            if _spike_keeps_d(points, w2, t2, a, p[None], model) and _cones_meet_nothing(w2, t2, [rows]):
                proven += 1
                d, (dx, dy, dz) = voxelize_solid(w2, t2, model, limit=None)
                expected = np.argwhere(a)[:, ::-1]
                assert {tuple(x) for x in (np.argwhere(d)[:, ::-1] + [dx, dy, dz]).tolist()} == {
                    tuple(x) for x in expected.tolist()
                }
    assert proven >= 20


def box_mesh(lo, hi) -> tuple[np.ndarray, np.ndarray]:
    """The box [lo, hi] as 8 vertices and 12 outward triangles."""
    v = np.array([[hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]]
                  for i in range(8)], float)  # fmt: skip
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    t = np.array([tri for a, b, c, d in quads for tri in ((a, b, c), (a, c, d))], np.int64)
    return v, t


def test_a_spike_through_the_solid_is_refused():
    # A thin box whose corner (1, 1, 1.5) is spiked up toward the voxel (1, 1, 2): a valid polyhedron. The
    # same spike with its apex moved below the box, at (2, 2, 0), pierces the bottom face: refused.
    from mrm.geometry.reconstruct.snapped_core import _spikes, _valid

    v, t = box_mesh((1, 1, 1), (5, 5, 1.5))
    assert mrm.Polyhedron(v, t).n_shells == 1
    spiked = _spikes(v, t, np.array([[1, 1, 2]], np.int64), np.ones((8, 8, 8), bool), "supercover")
    assert spiked is not None
    w, tris, _, cones = spiked
    apex = int(np.flatnonzero(np.all(v == [1, 1, 1.5], axis=1))[0])
    assert w[apex, 2] > 1.5 and np.abs(w[apex] - [1, 1, 2]).max() < 0.5
    assert _valid(w, tris, cones) is not None
    assert mrm.Polyhedron(w, tris).n_triangles == tris.shape[0]  # the full validation agrees
    w[apex] = [2, 2, 0]
    assert _valid(w, tris, cones) is None


def test_spikes_at_two_neighbouring_corners():
    # Two missed voxels whose nearest corners, (1, 1, 1.5) and (5, 1, 1.5), share an edge: the second
    # corner's triangles include pieces of those the first spike split. Both spikes are placed, and P stays a
    # valid polyhedron with both apexes in their cubes.
    from mrm.geometry.reconstruct.snapped_core import _spikes, _valid

    v, t = box_mesh((1, 1, 1), (5, 5, 1.5))
    missed = np.array([[1, 1, 2], [5, 1, 2]], np.int64)
    spiked = _spikes(v, t, missed, np.ones((8, 8, 8), bool), "supercover")
    assert spiked is not None
    w, tris, _, cones = spiked
    assert len(cones) == 2
    assert _valid(w, tris, cones) is not None
    poly = mrm.Polyhedron(w, tris)
    assert poly.n_shells == 1
    for p in missed:
        assert np.any(np.abs(poly.vertices - p).max(axis=1) <= 0.5 - 1 / 16)


def random_hull(raw) -> tuple[np.ndarray, np.ndarray] | None:
    """The exact hull of integer points as the snapped core builds P: its points and outward fans."""
    proposed = _propose_hull(np.unique(np.array(raw, np.int64), axis=0))
    faces = _exact_faces(*proposed) if proposed is not None else None
    if faces is None:
        return None  # coplanar points: no solid
    q, face_ptr, face_corner, _, _ = faces
    return q, _fans(q, face_ptr, face_corner)


@settings(max_examples=200, deadline=None)
@given(
    raw=st.lists(st.tuples(*[st.integers(-60, 60)] * 3), min_size=4, max_size=40),
    planes=st.lists(
        st.tuples(st.tuples(*[st.integers(-6, 6)] * 3), st.integers(-1, 1)), min_size=1, max_size=12
    ),
    c=st.tuples(*[st.integers(-5, 5)] * 3),
    g=st.integers(0, 5),
)
def test_the_climb_decides_whether_p_clears_every_cube_outside_a(raw, planes, c, g):
    # P (corners c + q / 2ᵍ) clears the facet a·x ≤ b of conv(A) when a·x < b + 1 − |a|₁/2 on all of P:
    # the climb over P's edges against every corner, in Fractions. Each b sits within a unit of the edge,
    # so both answers come up.
    hull = random_hull(raw)
    if hull is None:
        return
    q, tris = hull
    corners = [tuple(c[k] + Fraction(int(p[k]), 2**g) for k in range(3)) for p in q[np.unique(tris)]]
    normals, offsets = [], []
    for a, shift in planes:
        if not any(a):
            continue
        top = max(sum(ak * xk for ak, xk in zip(a, x, strict=True)) for x in corners)
        normals.append(a)
        offsets.append(int(np.floor(top - 1 + Fraction(sum(map(abs, a)), 2))) + shift)
    if not normals:
        return
    expected = all(
        sum(ak * xk for ak, xk in zip(a, x, strict=True)) < b + 1 - Fraction(sum(map(abs, a)), 2)
        for a, b in zip(normals, offsets, strict=True)
        for x in corners
    )
    got = _clear_of_outside_cubes(
        np.array(normals, np.int64), np.array(offsets, np.int64), np.array(c, np.int64), q, tris, g
    )
    assert got == expected


@pytest.mark.parametrize("model", COVERS)
@settings(max_examples=60, deadline=None)
@given(raw=st.lists(st.tuples(*[st.integers(-40, 40)] * 3), min_size=4, max_size=30))
def test_a_convex_solids_d_is_its_triangles_cubes_filled_along_rows(model, raw):
    # The snapped core discretizes only P's triangles: in a row along x, D(P) of a convex P is the run
    # between the first and last cube ∂P meets. Held to voxelize_solid on the exact hulls of random points
    # (eighths of a voxel), with A = D(P) and A one voxel off at a row's end either way.
    hull = random_hull(raw)
    if hull is None:
        return
    q, tris = hull
    v = q / 8.0
    solid, (sx, sy, sz) = voxelize_solid(v, tris, model, limit=None)
    marks, (mx, my, mz) = voxelize_triangles(v, tris, model, limit=None)
    pad = 2  # A's box: D(P)'s and a margin, at the origin of A's array
    a = np.zeros(tuple(n + 2 * pad for n in solid.shape), bool)
    a[pad:-pad, pad:-pad, pad:-pad] = solid
    ox, oy, oz = sx - pad, sy - pad, sz - pad
    args = (mx - ox, my - oy, mz - oz)
    lost, n, extra = _compare_rows(a, marks, *args, 10)
    assert (n, extra) == (0, False)
    k, j, i = np.argwhere(a)[0]  # the first voxel of a row: one more beyond it is lost, one fewer is extra
    grown = a.copy()
    grown[k, j, i - 1] = True
    lost, n, extra = _compare_rows(grown, marks, *args, 10)
    assert (n, extra) == (1, False) and lost.tolist() == [[i - 1, j, k]]
    shrunk = a.copy()
    shrunk[k, j, i] = False
    assert _compare_rows(shrunk, marks, *args, 10)[2]
    apart = a.copy()  # a whole row D(P) has none of
    apart[1, 1, 3:6] = True
    lost, n, extra = _compare_rows(apart, marks, *args, 2)
    assert (n, extra, lost.tolist()) == (3, False, [[3, 1, 1], [4, 1, 1]])


def test_under_standard_a_balls_core_is_proven_inside_its_cubes_without_the_supercover(monkeypatch):
    # The snapping's bound (each snapped point within the facets moved out by a quarter, checked by the
    # climb) proves R ⊂ V(A), so standard discretizes P once; the result is still held to both covers.
    import mrm.geometry.reconstruct.snapped_core as sc

    seen = []
    real = sc._missed

    def spy(v, t, mask, models, most):
        seen.extend(models)
        return real(v, t, mask, models, most)

    monkeypatch.setattr(sc, "_missed", spy)
    vs = VoxelSet(ball(40, 85), (3, -9, 11))
    found = convex_reconstruction(vs, "standard")
    assert found is not None and seen == ["standard"]
    assert_covers_r(found.polyhedron, vs, "standard")


@settings(max_examples=100, deadline=None)
@given(
    rows=st.lists(st.tuples(*[st.integers(-(2**15) + 1, 2**15 - 1)] * 3), max_size=30),
    big=st.booleans(),
)
def test_the_snaps_rows_are_made_unique_as_numpy_does(rows, big):
    # One int64 key per row of snapped offsets (|x| < 2¹⁵), else numpy's row sort: the same rows, order
    # and inverse as np.unique on rows.
    points = np.array(rows + [(2**40, 0, -3)] * big, np.int64).reshape(-1, 3)
    got, inverse = _unique_rows(points)
    expected, exp_inverse = np.unique(points, axis=0, return_inverse=True)
    assert np.array_equal(got, expected) and np.array_equal(inverse, exp_inverse.ravel())


@pytest.mark.parametrize(("seed", "axes"), [(219, (3, 30)), (230, (20, 70)), (240, (20, 70))])
def test_under_standard_the_core_is_discretized_in_a_s_own_frame(seed, axes):
    # The standard cell (x − ½, x + ½] is not invariant under the rotations of the cube: P discretized in
    # the canonical pose once met every cell of A there, and missed one in A's own frame. These ellipsoids
    # each lost a voxel that way; P is now discretized and spiked in A's frame.
    vs = ellipsoid(seed, *axes)
    found = convex_reconstruction(vs, "standard")
    assert found is not None and found.facets > 64
    assert_covers_r(found.polyhedron, vs, "standard")
