"""Digital plane segments: the exact recognizers against Fourier–Motzkin elimination (tests/oracles)."""

from __future__ import annotations

import random
from itertools import product

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.geometry.planes import PointPlane, SurfelPlane, recognize_points, recognize_surfels
from mrm.geometry.planes.cone import Cone, cross, dot, start_cone
from mrm.geometry.topology.labeling_3d import label_runs_3d
from mrm.geometry.topology.surfels import DIRS, surfels_of
from tests.oracles.plane_reference import (
    feasible,
    points_in_standard_plane,
    separates,
    surfel_patch_is_plane,
)

Patch = list[tuple[tuple[int, int, int], tuple[int, int, int]]]


def _patch(mask: np.ndarray, rng: random.Random, size: int) -> Patch:
    """A connected patch of ``size`` surfels of the mask (edge-adjacent, grown from a random surfel)."""
    s = surfels_of(label_runs_3d(mask, 6))
    if len(s.direction) == 0:
        return []
    start = rng.randrange(len(s.direction))
    seen, order = {start}, [start]
    frontier = [start]
    while frontier and len(order) < size:
        i = frontier.pop(rng.randrange(len(frontier)))
        for j in s.neighbour[i]:
            if int(j) not in seen and len(order) < size:
                seen.add(int(j))
                order.append(int(j))
                frontier.append(int(j))
    return [
        (tuple(int(c) for c in s.voxel[i]), tuple(int(c) for c in DIRS[s.direction[i]]))  # type: ignore[misc]
        for i in order
    ]


masks = st.tuples(st.integers(0, 2**32 - 1), st.sampled_from([0.2, 0.5, 0.8]), st.integers(1, 14))


@settings(max_examples=300, deadline=None)
@given(masks)
def test_a_surfel_patch_is_recognized_exactly_when_a_plane_separates_its_voxels(args):
    seed, density, size = args
    rng = random.Random(seed)
    mask = np.random.default_rng(seed).random((4, 4, 4)) < density
    patch = _patch(mask, rng, size)
    if not patch:
        return
    plane = recognize_surfels(patch)
    assert (plane is not None) == surfel_patch_is_plane(patch)
    if plane is not None:
        n = plane.normal
        assert separates(n, patch)
        for p, e in patch:
            q = tuple(a + b for a, b in zip(p, e, strict=True))
            assert plane.contains(p)  # the voxels of A are in the standard plane …
            assert dot(n, q) >= plane.mu + plane.omega  # … and the voxels outside beyond it


@settings(max_examples=150, deadline=None)
@given(masks)
def test_the_chosen_normal_is_the_smallest_separating_one(args):
    seed, density, size = args
    rng = random.Random(seed)
    mask = np.random.default_rng(seed).random((4, 4, 4)) < density
    patch = _patch(mask, rng, size)
    plane = recognize_surfels(patch) if patch else None
    if plane is None:
        return
    big = max(abs(c) for c in plane.normal)
    smaller = [n for n in product(range(-big + 1, big), repeat=3) if any(n) and separates(n, patch)]
    assert smaller == []


@settings(max_examples=200, deadline=None)
@given(
    st.tuples(st.integers(-9, 9), st.integers(-9, 9), st.integers(-9, 9)).filter(any),
    st.integers(-20, 20),
    st.integers(0, 2**32 - 1),
)
def test_the_surfels_of_a_digital_half_space_form_one_plane_segment(n, h, seed):
    # A = { p : n · p ≤ h } in a box; its surfels facing the plane (n · e > 0) away from the box's walls.
    coords = np.stack(np.meshgrid(*[np.arange(-4, 5)] * 3, indexing="ij"), -1).reshape(-1, 3)
    inside = {tuple(int(c) for c in p) for p in coords if dot(n, p) <= h}
    patch = [
        (p, e)
        for p in inside
        for e in map(tuple, DIRS.tolist())
        if dot(n, e) > 0
        and tuple(a + b for a, b in zip(p, e, strict=True)) not in inside
        and all(abs(a + b) <= 4 for a, b in zip(p, e, strict=True))
    ]
    random.Random(seed).shuffle(patch)
    if not patch:
        return
    plane = recognize_surfels(patch)
    assert plane is not None
    assert separates(plane.normal, patch)


def test_the_octahedron_face_is_one_plane_with_its_own_parameters():
    r = 9
    patch = [
        ((x, y, z), e)
        for x, y, z in product(range(r + 1), repeat=3)
        if x + y + z == r
        for e in ((1, 0, 0), (0, 1, 0), (0, 0, 1))
    ]
    rec = SurfelPlane()
    assert all(rec.add(p, e) for p, e in patch)
    plane = rec.plane()
    assert (plane.a, plane.b, plane.c, plane.mu, plane.omega) == (1, 1, 1, r - 2, 3)
    normal, h = rec.euclidean_plane()
    assert normal == (1, 1, 1) and h == r + 0.5  # |x| + |y| + |z| = r + ½ (docs/design.md §11)


def test_recognition_is_covariant_under_far_translations():
    rng = random.Random(5)
    mask = np.random.default_rng(5).random((4, 4, 4)) < 0.5
    shift = (2**40 + 3, -(2**41) + 7, 2**45)
    tried = 0
    for _ in range(60):
        patch = _patch(mask, rng, rng.randrange(2, 10))
        plane = recognize_surfels(patch)
        moved = recognize_surfels(
            [(tuple(a + b for a, b in zip(p, shift, strict=True)), e) for p, e in patch]
        )
        assert (plane is None) == (moved is None)
        if plane is not None and moved is not None:
            tried += 1
            assert moved.normal == plane.normal
            assert moved.mu == plane.mu + dot(plane.normal, shift)
    assert tried > 10


def test_a_step_inside_a_flat_patch_is_refused_and_leaves_the_patch_as_it_was():
    rec = SurfelPlane()
    for x, y in product(range(4), range(4)):
        assert rec.add((x, y, 0), (0, 0, 1))
    before = rec.cone
    assert not rec.add((1, 1, 1), (0, 0, 1))
    assert rec.cone == before and rec.n_surfels == 16
    assert rec.plane().normal == (0, 0, 1)


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(*[st.integers(-3, 3)] * 3), min_size=1, max_size=9))
def test_a_point_set_is_recognized_exactly_when_a_standard_plane_holds_it(points):
    plane = recognize_points(points)
    assert (plane is not None) == points_in_standard_plane(points)
    if plane is not None:
        assert all(plane.contains(p) for p in points)


@settings(max_examples=150, deadline=None)
@given(
    st.tuples(st.integers(-7, 7), st.integers(-7, 7), st.integers(-7, 7)).filter(any),
    st.integers(-10, 10),
)
def test_every_piece_of_a_standard_plane_is_recognized(n, mu):
    omega = sum(map(abs, n))
    pts = [p for p in product(range(-4, 5), repeat=3) if mu <= dot(n, p) < mu + omega]
    rec = PointPlane()
    assert all(rec.add(p) for p in pts)
    if pts:
        plane = rec.plane()
        assert all(plane.contains(p) for p in pts)
        assert max(map(abs, plane.normal)) <= max(map(abs, n))  # the smallest normal, never a bigger one


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(*[st.integers(-4, 4)] * 3).filter(any), min_size=2, max_size=8))
def test_the_cone_is_exactly_the_solution_set_of_its_constraints(vs):
    e = vs[0]
    cone: Cone | None = None
    rest = [v for v in vs[1:] if any(cross(v, e))]  # the first constraint not parallel to e
    if not rest:
        return
    cone = start_cone(e, rest[0])
    if cone is not None:
        cone = cone.clip_all(vs)
    assert (cone is not None) == feasible(vs)
    if cone is not None:
        inside = cone.interior_ray()
        assert all(dot(inside, v) > 0 for v in vs)
        for r in cone.rays:
            assert all(dot(r, v) >= 0 for v in vs)


def _segmentation(mask: np.ndarray, origin=(0, 0, 0)):
    from mrm.geometry.planes.segmentation import plane_segments

    s = surfels_of(label_runs_3d(mask, 6))
    return s, plane_segments(s.voxel + np.array(origin), s.direction, s.neighbour)


def _octahedron(r: int) -> np.ndarray:
    g = np.arange(-r - 1, r + 2)
    z, y, x = np.meshgrid(g, g, g, indexing="ij")
    return (abs(x) + abs(y) + abs(z)) <= r


def test_the_digital_octahedron_has_eight_plane_segments_on_its_faces():
    for r in (2, 4, 11, 40):  # r = 1, the 3D cross of 7 voxels, needs only 4
        _, seg = _segmentation(_octahedron(r), (-r - 1,) * 3)
        assert sorted(sg.plane.normal for sg in seg.segments) == sorted(product((1, -1), repeat=3))
        for sg in seg.segments:
            assert sg.plane.mu == r - 2 and sg.offset == r + 0.5


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from([0.15, 0.5, 0.85]))
def test_every_surfel_is_in_one_connected_plane_segment_of_its_surface(seed, density):
    mask = np.random.default_rng(seed).random((4, 5, 3)) < density
    origin = (7, -3, 2**33)
    s, seg = _segmentation(mask, origin)
    counts = np.zeros(len(s.direction), int)
    for k, sg in enumerate(seg.segments):
        counts[sg.surfels] += 1
        assert (seg.segment_of[sg.surfels] == k).all()
        assert len(set(s.surface[sg.surfels].tolist())) == 1  # one surface
        members = set(sg.surfels.tolist())
        reached, todo = {int(sg.surfels[0])}, [int(sg.surfels[0])]
        while todo:
            for j in s.neighbour[todo.pop()]:
                if int(j) in members and int(j) not in reached:
                    reached.add(int(j))
                    todo.append(int(j))
        assert reached == members  # edge-connected
        patch = [
            (
                tuple(int(c) + o for c, o in zip(s.voxel[i], origin, strict=True)),
                tuple(DIRS[s.direction[i]].tolist()),
            )
            for i in sg.surfels
        ]
        assert separates(sg.plane.normal, patch)
        normal, h = sg.plane.normal, sg.offset
        assert all(
            dot(normal, p) < h < dot(normal, tuple(a + b for a, b in zip(p, e, strict=True)))
            for p, e in patch
        )
        if len(patch) <= 12:
            assert surfel_patch_is_plane(patch)
    assert (counts == 1).all()


@settings(max_examples=80, deadline=None)
@given(
    st.integers(0, 2**32 - 1),
    st.sampled_from([0.1, 0.3, 0.5, 0.7, 0.9]),
    st.sampled_from([(6, 6, 6), (3, 9, 5), (1, 12, 12)]),
)
def test_the_compiled_segmentation_is_the_reference_one(seed, density, shape):
    from mrm.geometry.planes.segmentation import plane_segments, plane_segments_reference

    mask = np.random.default_rng(seed).random(shape) < density
    s = surfels_of(label_runs_3d(mask, 6))
    voxel = s.voxel + np.array([-(2**40), 5, 2**36])
    fast = plane_segments(voxel, s.direction, s.neighbour)
    slow = plane_segments_reference(voxel, s.direction, s.neighbour)
    assert np.array_equal(fast.segment_of, slow.segment_of)
    assert np.array_equal(fast.members, slow.members)
    for k in range(len(fast)):
        assert set(map(tuple, fast.preimage(k).rays)) == set(map(tuple, slow.preimage(k).rays))


def _adversarial_masks() -> dict[str, np.ndarray]:
    i, j, k = np.indices((6, 6, 6))
    ball = np.add.reduce([(c - 3.2) ** 2 for c in (i, j, k)]) <= 7.5
    sheet = np.zeros((5, 5, 5), bool)
    sheet[2] = True
    rods = np.zeros((5, 5, 5), bool)
    rods[:, 2, 2] = rods[2, :, 0] = True
    corners = np.zeros((4, 4, 4), bool)
    corners[0, 0, 0] = corners[1, 1, 1] = corners[2, 2, 1] = corners[2, 1, 2] = (
        True  # corner- and edge-touching
    )
    shell = np.ones((5, 5, 5), bool)
    shell[2, 2, 2] = False  # a cavity
    torus = np.zeros((3, 6, 6), bool)
    torus[1, 1:5, 1:5] = True
    torus[1, 2:4, 2:4] = False
    return {
        "checkerboard": (i + j + k) % 2 == 0,
        "ball": ball,
        "sheet": sheet,
        "rods": rods,
        "corners": corners,
        "shell with a cavity": shell,
        "torus": torus,
    }


def test_the_compiled_segmentation_is_the_reference_one_on_adversarial_sets():
    from mrm.geometry.planes.segmentation import plane_segments, plane_segments_reference

    for name, mask in _adversarial_masks().items():
        s = surfels_of(label_runs_3d(mask, 6))
        fast = plane_segments(s.voxel, s.direction, s.neighbour)
        slow = plane_segments_reference(s.voxel, s.direction, s.neighbour)
        assert np.array_equal(fast.segment_of, slow.segment_of), name
        for sg in fast.segments:
            inner = fast.voxel[sg.surfels]
            outer = inner + DIRS[fast.direction[sg.surfels]]
            n = np.array(sg.plane.normal)
            assert (inner @ n).max() < sg.offset < (outer @ n).min(), name


def test_a_segment_never_reaches_beyond_the_compiled_bound():
    from mrm.geometry.planes._kernels import MAX_EXTENT
    from mrm.geometry.planes.segmentation import plane_segments

    rod = np.ones((MAX_EXTENT + 9, 1, 1), bool)  # along z, longer than a segment may reach
    s = surfels_of(label_runs_3d(rod, 6))
    seg = plane_segments(s.voxel, s.direction, s.neighbour)
    # Two sides and an end make one plane segment (normal about (1, 1, 0)), but only as far as the bound:
    # the 2·(2¹⁶ + 1) side surfels nearest the seed, then the rest.
    assert len(seg) > 2
    assert max(np.diff(seg.member_ptr)) == 2 * (MAX_EXTENT + 1) + 1
    for sg in seg.segments:
        vox = seg.voxel[sg.surfels]
        assert (vox.max(0) - vox.min(0)).max() <= MAX_EXTENT
        n = np.array(sg.plane.normal)
        assert (vox @ n).max() < sg.offset < ((vox + DIRS[seg.direction[sg.surfels]]) @ n).min()


@settings(max_examples=300, deadline=None)
@given(
    st.lists(st.tuples(*[st.integers(-3, 3)] * 3), min_size=1, max_size=14),
    st.tuples(st.integers(-(2**40), 2**40), st.integers(-5, 5), st.integers(-5, 5)),
)
def test_the_compiled_point_recognizer_takes_the_same_prefix_and_plane_as_the_reference(points, shift):
    from mrm.geometry.planes.recognition import standard_plane_prefix

    moved = [tuple(a + b for a, b in zip(p, shift, strict=True)) for p in points]
    taken, plane = standard_plane_prefix(moved)
    rec = PointPlane()
    expected = next((k for k, p in enumerate(moved) if not rec.add(p)), len(moved))
    assert taken == expected
    assert points_in_standard_plane(points[:taken])
    if taken < len(points):
        assert not points_in_standard_plane(points[: taken + 1])
    assert plane == rec.plane()
    assert all(plane.contains(p) for p in moved[:taken])
