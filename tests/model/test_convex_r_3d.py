"""R under gauss of digitally convex voxel sets: the convex hull grown by a dyadic homothety (ADR 0068).

The hull is found in integers by :mod:`mrm.geometry.reconstruct.convex_3d`; here it is held to another
algorithm (qhull, through scipy, with its facets regrouped exactly on the integer points) and R to the
contract of docs/design.md §11 (D(R(A)) = A by the exact voxelizer, ∂R within the border voxels' cubes,
one shell), on random convex solids: intersections of half-spaces with small integer normals, and ellipsoids.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import mrm
from mrm.core import limits
from mrm.core.grids import VoxelSet
from mrm.geometry.reconstruct import FALLBACKS
from mrm.geometry.reconstruct.convex_3d import convex_reconstruction
from mrm.reps.region_3d import region_3d_of
from tests.model.voxel_shapes import assert_within_border_cubes, solid_torus


def hull_faces(points: np.ndarray) -> set[tuple[int, int, int, int]]:
    """The facets of conv(points) as primitive integer planes (a, b, c, d), a·p <= d on every point: qhull's
    simplices, their planes recomputed in integers on the integer points and merged when equal."""
    from scipy.spatial import ConvexHull

    hull = ConvexHull(points.astype(float))
    planes = set()
    for s in hull.simplices:
        p, q, r = (points[i].astype(object) for i in s)
        n = np.cross(q - p, r - p)
        g = math.gcd(*(int(x) for x in n))
        n = [int(x) // g for x in n]
        d = sum(n[i] * int(p[i]) for i in range(3))
        if max(sum(n[i] * int(x[i]) for i in range(3)) for x in points) > d:
            n, d = [-x for x in n], -d  # qhull orders a simplex's corners either way
        planes.add((*n, d))
    return planes


def r_faces(poly: mrm.Polyhedron) -> set[tuple[int, int, int]]:
    """The primitive integer normals of R's triangles (float64 vertices: exact rationals)."""
    from fractions import Fraction

    out = set()
    for t in poly.triangles:
        p, q, r = ([Fraction(float(x)) for x in poly.vertices[i]] for i in t)
        u = [q[i] - p[i] for i in range(3)]
        w = [r[i] - p[i] for i in range(3)]
        n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        den = math.lcm(*(x.denominator for x in n))
        ints = [int(x * den) for x in n]
        g = math.gcd(*ints)
        out.add(tuple(x // g for x in ints))
    return out


def convex_solid(seed: int, kind: str, size: int) -> VoxelSet:
    """A seeded random convex solid's Gauss digitization (centres in the closed solid), by its definition."""
    rng = np.random.default_rng(seed)
    z, y, x = np.mgrid[0:size, 0:size, 0:size]
    c = rng.uniform(size / 2 - 1, size / 2 + 1, 3)
    if kind == "ellipsoid":
        axes = rng.uniform(2.5, size / 2 - 1, 3)
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        d = np.stack([x - c[0], y - c[1], z - c[2]], axis=-1) @ q
        mask = ((d / axes) ** 2).sum(axis=-1) <= 1
    else:  # half-spaces a·(p − c) <= h with small integer normals: exactly coplanar lattice faces
        mask = np.ones(x.shape, bool)
        for _ in range(int(rng.integers(4, 16))):
            a = rng.integers(-3, 4, 3)
            if not a.any():
                continue
            h = rng.uniform(2.5, size / 2 - 1) * float(np.abs(a).max())
            mask &= a[0] * (x - c[0]) + a[1] * (y - c[1]) + a[2] * (z - c[2]) <= h
    return VoxelSet(mask, tuple(int(v) for v in rng.integers(-50, 50, 3)))


@settings(max_examples=150, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1), kind=st.sampled_from(["ellipsoid", "polytope"]), size=st.integers(7, 16)
)
def test_a_convex_solids_voxels_get_their_hull_grown(seed, kind, size):
    vs = convex_solid(seed, kind, size)
    assume(vs.count >= 27)
    found = convex_reconstruction(vs)
    region = region_3d_of(vs.mask, vs.origin)
    if (region.n_components, region.n_cavities, region.euler) != (1, 0, 1):
        # A sliver joined by an edge only, or a tunnel between voxels meeting at an edge: not a ball's
        assert found is None
        assert mrm.voxelize(mrm.reconstruct(vs, "gauss"), "gauss") == vs
        return
    assert found is not None
    poly = found.polyhedron
    assert mrm.voxelize(poly, "gauss") == vs
    assert_within_border_cubes(poly, vs)
    assert poly.n_shells == 1
    # Its faces are conv(A)'s facets, each grown: planes a·x = d + δ with 0 < δ < 1, so exactly as many.
    facets = hull_faces(vs.points())
    assert r_faces(poly) == {f[:3] for f in facets}
    assert poly.n_faces == len(facets)


def test_the_product_keeps_the_smaller_of_hull_and_decimation(monkeypatch):
    from tests.model.voxel_shapes import ball

    vs = VoxelSet(ball(8, 19), (0, 0, 0))
    hull = convex_reconstruction(vs)
    assert hull is not None
    small = mrm.reconstruct(vs, "gauss")  # 1,200 surfels: the decimation is tried too, and wins
    assert small.n_triangles < hull.polyhedron.n_triangles
    monkeypatch.setattr(limits, "MAX_RIVAL_SURFELS", 0)
    assert mrm.reconstruct(vs, "gauss") == hull.polyhedron


@pytest.mark.parametrize("r", [20, 64, 130, 200])
def test_digital_octahedra_up_to_r_200_have_eight_faces_under_gauss(r):
    # issue 29: |x| + |y| + |z| <= r, r = 4…200, exactly 8 faces; its vertices on the axes, just beyond ±r
    z, y, x = np.ogrid[-r : r + 1, -r : r + 1, -r : r + 1]
    vs = VoxelSet(np.abs(x) + np.abs(y) + np.abs(z) <= r, (-r, -r, -r))
    before = FALLBACKS[0]
    poly = mrm.reconstruct(vs, "gauss")
    assert FALLBACKS[0] == before
    assert poly.n_faces == 8 and poly.n_vertices == 6
    v = poly.vertices
    assert (np.count_nonzero(v, axis=1) == 1).all() and (r < np.abs(v).max(axis=1)).all()
    assert (np.abs(v).max(axis=1) < r + 1).all()
    if r & (r - 1) == 0:  # grown about 0 by 1 + 1/(2r): |x| + |y| + |z| <= r + 1/2, §11's answer
        assert (np.abs(v).max(axis=1) == r + 0.5).all()
    assert mrm.voxelize(poly, "gauss") == vs


@pytest.mark.parametrize(
    "name, mask",
    [
        ("torus", solid_torus(11, 3.5, 1.5)),
        ("two rows in a slice", np.array([[[1, 1, 0, 1]]], bool)),
        ("a flat square", np.ones((1, 5, 5), bool)),
        ("a cube with a cavity", np.pad(np.ones((5, 5, 5), bool), 0) & ~np.pad(np.ones((1, 1, 1), bool), 2)),
        ("two voxels sharing an edge", np.array([[[1, 0], [0, 1]]], bool)),
    ],
)
def test_sets_that_are_not_a_convex_solids_take_the_general_way(name, mask):
    vs = VoxelSet(mask, (3, -2, 7))
    assert convex_reconstruction(vs) is None, name
    assert mrm.voxelize(mrm.reconstruct(vs, "gauss"), "gauss") == vs


#: The lattice points of a small lattice polyhedron, found by a random search (see the test below).
THIN = [(1, 3, 0), (2, 2, 1), (1, 3, 1), (2, 3, 1), (3, 1, 2), (2, 2, 2), (3, 2, 2), (1, 3, 2),
        (2, 3, 2), (3, 3, 2)]  # fmt: skip


def test_a_convex_set_whose_grown_hull_leaves_the_border_cubes_is_refused():
    # THIN is digitally convex, one
    # 6-component without tunnel, and the grown hull gives it back under gauss, but it is so thin that the
    # homothety pushes a corner out of the border voxels' cubes. The hull is refused there
    # (§11 item 2), and R is the general one.
    from mrm.geometry.reconstruct.convex_3d import _hull, convex_r
    from mrm.geometry.topology.labeling_3d import label_runs_3d

    vs = VoxelSet.from_points(np.array(THIN))
    hull = _hull(label_runs_3d(vs.mask, 6))
    assert hull is not None
    grown = convex_r(hull, vs.origin)
    assert grown is not None
    assert mrm.voxelize(mrm.Polyhedron(*grown[:2]), "gauss") == vs
    assert convex_reconstruction(vs) is None
    poly = mrm.reconstruct(vs, "gauss")
    assert mrm.voxelize(poly, "gauss") == vs
    assert_within_border_cubes(poly, vs)


def test_one_thread_gives_the_same_r(monkeypatch):
    # The border check runs beside the validation on R's worker thread, or after it with MRM_THREADS=1.
    vs = convex_solid(7, "ellipsoid", 14)
    threaded = convex_reconstruction(vs)
    monkeypatch.setenv("MRM_THREADS", "1")
    alone = convex_reconstruction(vs)
    assert threaded is not None and alone is not None
    assert alone.polyhedron == threaded.polyhedron
    assert convex_reconstruction(VoxelSet.from_points(np.array(THIN))) is None  # refused by the border check
