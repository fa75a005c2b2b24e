"""The exact voxelization against the Fraction reference (docs/design.md §11), on random and adversarial
meshes.

Each input is checked in the three models and along both arithmetic paths of the kernels: the automatic choice
(plain float arithmetic when it is provably exact, e.g. for snapped input) and the forced float-filter +
exact-expansion path, which snapped input drives through ties at every voxel face, edge and corner. Then the
properties of §2 and §11: union stability, monotonicity, Z³-translation covariance (large translations
included) and the sandwich gauss ⊆ standard ⊆ supercover.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import InvalidGeometryError, ParameterError, SizeLimitError
from mrm.core.models import Model, cell_of
from mrm.geometry.discretize import _kernels3d as k3
from mrm.geometry.discretize.voxels import (
    _run,
    estimate_voxels,
    voxelization_box,
    voxelize_points,
    voxelize_segments,
    voxelize_solid,
    voxelize_triangles,
)
from tests.oracles.mesh_strategies import (
    STAR_VERTICES,
    box_mesh,
    cavities,
    concat,
    points,
    separated_pairs,
    solids,
    star_mesh,
    tetra_mesh,
    translate,
    triangle_sets,
)
from tests.oracles.voxelize_reference import (
    exact_triangles,
    reference_voxelize,
    reference_voxelize_all,
    voxel_set,
)

MODELS = Model.names()


def voxels(mesh, model, solid=True, exact_mode=None):  # type: ignore[no-untyped-def]
    v, t = mesh
    return voxel_set(*_run(v, t, Model.parse(model), solid, None, exact_mode))


def assert_canonical(mask, origin) -> None:  # type: ignore[no-untyped-def]
    """Cropped to the bounding box: no empty outer slab (or the empty (0, 0, 0) array)."""
    if mask.size == 0:
        assert mask.shape == (0, 0, 0) and origin == (0, 0, 0)
        return
    for axis in range(3):
        other = tuple(a for a in range(3) if a != axis)
        line = mask.any(axis=other)
        assert line[0] and line[-1], (axis, mask.shape)


def assert_matches_reference(mesh, solid: bool) -> None:  # type: ignore[no-untyped-def]
    ref = reference_voxelize_all(exact_triangles(*mesh), solid)
    for model in MODELS:
        expected = ref[model]
        for exact_mode in (None, False):
            got = voxels(mesh, model, solid, exact_mode)
            assert got == expected, (model, exact_mode, sorted(got ^ expected), mesh)
        assert_canonical(*_run(mesh[0], mesh[1], Model.parse(model), solid, None))
    # the sandwich of §2 with the open cube: { p : int V(p) ∩ E ≠ ∅ } ⊆ standard
    assert ref["open"] <= ref["standard"]


# ------------------------------------------------------------------------------------ against the reference
@settings(max_examples=90)
@given(solids())
def test_solids_match_reference(mesh) -> None:  # type: ignore[no-untyped-def]
    assert_matches_reference(mesh, solid=True)


@settings(max_examples=25)
@given(solids(), st.tuples(*[st.sampled_from([2**40 + 3, -(2**33), 2**20 - 1, 2**48])] * 3))
def test_far_solids_match_reference(mesh, t) -> None:  # type: ignore[no-untyped-def]
    """Coordinates far from the origin (up to 2^48 + a fraction): the float filters' error bounds grow."""
    v, tri = mesh
    v = np.round(v * 16) / 16 + np.array(t, dtype=np.float64)  # exact: 2^48 + k/16 is a float64
    assert_matches_reference((v, tri), solid=True)


@settings(max_examples=120)
@given(triangle_sets())
def test_triangles_segments_points_match_reference(mesh) -> None:  # type: ignore[no-untyped-def]
    assert_matches_reference(mesh, solid=False)


ADVERSARIAL_SOLIDS = [
    # faces along voxel faces, vertices on voxel corners
    box_mesh((-0.5, -0.5, -0.5), (1.5, 0.5, 2.5)),
    # faces through voxel centres, vertices on centres
    box_mesh((0.0, 0.0, 0.0), (2.0, 1.0, 3.0)),
    # a unit cube centred on a voxel edge and a regular octahedron on the grid
    box_mesh((0.0, 0.5, -0.5), (1.0, 1.5, 0.5)),
    tetra_mesh((0.0, 0.0, 0.0), (2.0, 0.0, 0.0), (0.0, 2.0, 0.0), (0.0, 0.0, 2.0)),
    tetra_mesh((0.5, 0.5, 0.5), (2.5, 0.5, 0.5), (0.5, 2.5, 0.5), (0.5, 0.5, 2.5)),
    # a box with a cavity whose faces lie on voxel faces
    concat(
        box_mesh((-2.5, -2.5, -2.5), (2.5, 2.5, 2.5)), box_mesh((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5), True)
    ),
]
ADVERSARIAL_IDS = ["on-faces", "on-centres", "on-edge", "corner-tetra", "half-tetra", "cavity-on-faces"]


@pytest.mark.parametrize("mesh", ADVERSARIAL_SOLIDS, ids=ADVERSARIAL_IDS)
def test_adversarial_solids_match_reference(mesh) -> None:  # type: ignore[no-untyped-def]
    assert_matches_reference(mesh, solid=True)
    assert_matches_reference(mesh, solid=False)


# ----------------------------------------------------------------------------------- the grid of step N
#: Grid steps: odd (the exact images of DSS_α, α = p/q, voxelize on the grid of step N = the odd part of q),
#: even, and large.
STEPS = [1, 2, 3, 5, 7, 11, 125]


def assert_step_matches_reference(mesh, n: int) -> None:  # type: ignore[no-untyped-def]
    """Q = N·P (rounded where a free float times N is not a float64) on the grid of step N, whose voxel c is
    the cube of side N centred on N·c, is the reference D(Q / N) of the exact Q / N, in every model and along
    both arithmetic paths. P's grid-friendly vertices put Q's on that grid's centres N·k and planes N·(k ± ½),
    where the kernel's shift N·τ decides."""
    v, t = mesh
    q = v * n
    tris = [[tuple(u / n for u in p) for p in tri] for tri in exact_triangles(q, t)]
    ref = reference_voxelize_all(tris, True, MODELS)
    for model in MODELS:
        for exact_mode in (None, False):
            got = voxel_set(*_run(q, t, Model.parse(model), True, None, exact_mode, step=n))
            assert got == ref[model], (model, n, exact_mode, sorted(got ^ ref[model]), mesh)
        mask, origin = _run(q, t, Model.parse(model), True, None, step=n)
        assert_canonical(mask, origin)


@settings(max_examples=60)
@given(solids(), st.sampled_from(STEPS))
def test_solids_on_the_grid_of_step_n_match_reference(mesh, n) -> None:  # type: ignore[no-untyped-def]
    assert_step_matches_reference(mesh, n)


@pytest.mark.parametrize("n", [3, 5, 11, 125])
@pytest.mark.parametrize("mesh", ADVERSARIAL_SOLIDS, ids=ADVERSARIAL_IDS)
def test_adversarial_solids_on_the_grid_of_step_n_match_reference(mesh, n) -> None:  # type: ignore[no-untyped-def]
    """Faces on the planes N·(k ± ½), vertices on the centres N·k and corners, edges along voxel edges."""
    assert_step_matches_reference(mesh, n)


@settings(max_examples=25)
@given(
    solids(),
    st.sampled_from([3, 5, 125]),
    st.tuples(*[st.sampled_from([2**40 + 3, -(2**33), 2**20 - 1, 2**42 + 1])] * 3),
)
def test_far_solids_on_the_grid_of_step_n_match_reference(mesh, n, t) -> None:  # type: ignore[no-untyped-def]
    """Coordinates N·(2^42 + a fraction) ≈ 2^49: the float filters' bounds with cubes of side N."""
    v, tri = mesh
    v = np.round(v * 16) / 16 + np.array(t, dtype=np.float64)  # exact: 2^42 + k/16 is a float64
    assert_step_matches_reference((v, tri), n)


@pytest.mark.parametrize("n", [3, 125, 2**20 + 1])
def test_a_box_near_the_coordinate_limit_on_the_grid_of_step_n(n) -> None:
    """Q's coordinates near 2^51 and the grid planes N·(k ± ½) just below 2^52 stay exact half-integers."""
    base = box_mesh((0.0, 0.5, -0.5), (1.0, 1.5, 0.5))
    k = 2**51 // n - 3  # the box's voxels near 2^51 / N
    v = base[0] * n + np.array([k * n, -k * n, (k // 2) * n], dtype=np.float64)
    assert np.abs(v).max() <= 2.0**51 and (v == np.round(v * 2) / 2).all()
    for model in MODELS:
        got = voxel_set(*_run(v, base[1], Model.parse(model), True, None, step=n))
        unit = voxels(base, model)
        assert got == {(x + k, y - k, z + k // 2) for x, y, z in unit}, model


@pytest.mark.parametrize("step", [0, -3, 2**49 + 1, 1.5, True, "3"])
def test_a_bad_grid_step_is_refused_in_one_line(step) -> None:  # type: ignore[no-untyped-def]
    v, t = tetra_mesh((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    with pytest.raises(ParameterError) as info:
        voxelize_solid(v, t, step=step)
    assert "step" in str(info.value) and "\n" not in str(info.value)


def test_octahedron_gauss_is_the_digital_octahedron() -> None:
    """|x| + |y| + |z| ≤ r with the tie rule: on the faces, p + τ is inside iff τ points inward there."""
    r = 3.0
    v = np.array([[r, 0, 0], [-r, 0, 0], [0, r, 0], [0, -r, 0], [0, 0, r], [0, 0, -r]], dtype=float)
    t = []
    for sx in (0, 1):
        for sy in (2, 3):
            for sz in (4, 5):
                a, b, c = sx, sy, sz
                if np.linalg.det(np.array([v[a], v[b], v[c]])) < 0:  # outward: det[a, b, c] > 0 about 0
                    b, c = c, b
                t.append([a, b, c])
    mesh = (v, np.array(t))
    got = voxels(mesh, "gauss")
    rng = range(-4, 5)
    # On a face, p + τ is inside when τ points inward there: the reference decides which.
    expected = reference_voxelize(exact_triangles(*mesh), "gauss", True)
    assert got == expected
    strict = {(x, y, z) for x in rng for y in rng for z in rng if abs(x) + abs(y) + abs(z) < r}
    closed = {(x, y, z) for x in rng for y in rng for z in rng if abs(x) + abs(y) + abs(z) <= r}
    assert strict <= got <= closed


# ------------------------------------------------------------------------------------------------- points
@settings(max_examples=200)
@given(st.lists(st.tuples(*[st.integers(-8, 8).map(lambda n: n / 4)] * 3), min_size=1, max_size=5))
def test_points_go_to_their_cell(pts) -> None:  # type: ignore[no-untyped-def]
    """standard: the one voxel whose half-open cell (p − ½, p + ½]³ holds the point (the tie rule)."""
    got = voxel_set(*voxelize_points(pts, "standard"))
    assert got == {cell_of(p) for p in pts}
    sc = voxel_set(*voxelize_points(pts, "supercover"))
    assert got <= sc
    assert voxel_set(*voxelize_points(pts, "gauss")) == set()


def test_segment_along_a_voxel_edge() -> None:
    """On the edge y = z = ½ the standard segment takes the voxels below-left; supercover all four rows."""
    std = voxel_set(*voxelize_segments([(0.0, 0.5, 0.5)], [(2.0, 0.5, 0.5)], "standard"))
    assert std == {(0, 0, 0), (1, 0, 0), (2, 0, 0)}
    sc = voxel_set(*voxelize_segments([(0.0, 0.5, 0.5)], [(2.0, 0.5, 0.5)], "supercover"))
    assert sc == {(x, y, z) for x in (0, 1, 2) for y in (0, 1) for z in (0, 1)}


# ----------------------------------------------------------------------------------------------- properties
@settings(max_examples=40)
@given(separated_pairs())
def test_union_stability(pair) -> None:  # type: ignore[no-untyped-def]
    p, q = pair
    for model in MODELS:
        assert voxels(concat(p, q), model) == voxels(p, model) | voxels(q, model), model


@settings(max_examples=40)
@given(triangle_sets(max_size=6), st.integers(1, 5))
def test_union_stability_of_triangle_sets(mesh, cut) -> None:  # type: ignore[no-untyped-def]
    v, t = mesh
    cut = min(cut, t.shape[0])
    for model in MODELS:
        whole = voxels(mesh, model, solid=False)
        assert whole == voxels((v, t[:cut]), model, False) | voxels((v, t[cut:]), model, False), model


@settings(max_examples=30)
@given(
    points,
    st.lists(st.integers(1, 8).map(lambda n: n / 4), min_size=STAR_VERTICES, max_size=STAR_VERTICES),
    st.lists(st.integers(0, 4).map(lambda n: n / 4), min_size=STAR_VERTICES, max_size=STAR_VERTICES),
)
def test_monotone_under_growth(c, r, grow) -> None:  # type: ignore[no-untyped-def]
    """A star polyhedron with larger radii (same centre) contains the smaller one, and D keeps the order."""
    small = star_mesh(c, r)
    big = star_mesh(c, [u + g for u, g in zip(r, grow, strict=True)])
    for model in MODELS:
        assert voxels(small, model) <= voxels(big, model), model


@settings(max_examples=30)
@given(cavities())
def test_monotone_cavity_inside_its_box(mesh) -> None:  # type: ignore[no-untyped-def]
    v, t = mesh
    outer = (v[:8], t[:12])
    for model in MODELS:
        assert voxels(mesh, model) <= voxels(outer, model), model


tagged = st.one_of(solids().map(lambda m: (m, True)), triangle_sets().map(lambda m: (m, False)))


@settings(max_examples=40)
@given(tagged, st.tuples(*[st.sampled_from([0, 1, -3, 2**20, -(2**33), 2**40 + 7])] * 3))
def test_translation_covariance(tagged_mesh, t) -> None:  # type: ignore[no-untyped-def]
    """D(E + t) = D(E) + t for t ∈ Z³. The parity rule and the kernels hold this for any triangles, so
    vertices are first rounded to 2^-8 where needed to keep E + t exact in float64."""
    (v, tri), solid = tagged_mesh
    shift = np.array(t, dtype=np.float64)
    exact = all(
        Fraction(float(x)) + int(u) == Fraction(float(y))
        for x, u, y in zip(v.ravel(), np.tile(t, len(v)), (v + shift).ravel(), strict=True)
    )
    if not exact:
        v = np.round(v * 256) / 256
    mesh = (v, tri)
    moved = (v + shift, tri)
    for model in MODELS:
        base = voxels(mesh, model, solid)
        assert voxels(moved, model, solid) == {(x + t[0], y + t[1], z + t[2]) for x, y, z in base}, model


@settings(max_examples=60)
@given(tagged)
def test_sandwich(tagged_mesh) -> None:  # type: ignore[no-untyped-def]
    mesh, solid = tagged_mesh
    g, s, c = (voxels(mesh, m, solid) for m in ("gauss", "standard", "supercover"))
    assert g <= s <= c


# -------------------------------------------------------------------------------------------- exact signs
@settings(max_examples=300)
@given(
    st.lists(
        st.one_of(st.integers(-4, 4).map(lambda n: n / 2), st.floats(-1e6, 1e6)), min_size=12, max_size=12
    )
)
def test_det3_sign_is_exact(vals) -> None:  # type: ignore[no-untyped-def]
    a, b, c, d = (tuple(Fraction(u) for u in vals[i : i + 3]) for i in (0, 3, 6, 9))
    rows = [[a[i] - d[i] for i in range(3)], [b[i] - d[i] for i in range(3)], [c[i] - d[i] for i in range(3)]]
    det = (
        rows[0][0] * (rows[1][1] * rows[2][2] - rows[1][2] * rows[2][1])
        - rows[0][1] * (rows[1][0] * rows[2][2] - rows[1][2] * rows[2][0])
        + rows[0][2] * (rows[1][0] * rows[2][1] - rows[1][1] * rows[2][0])
    )
    expected = (det > 0) - (det < 0)
    scratch = np.zeros(k3.SCRATCH3_SIZE)
    assert k3.det3_sign(*vals, False, scratch) == expected
    assert k3._det3_exact(*vals, scratch) == expected


# -------------------------------------------------------------------------------------------------- input
def test_bad_input_is_refused_with_a_message() -> None:
    v, t = tetra_mesh((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    with pytest.raises(ParameterError, match="model"):
        voxelize_solid(v, t, "cubic")
    bad = v.copy()
    bad[2, 1] = np.nan
    with pytest.raises(InvalidGeometryError, match="supported range"):
        voxelize_solid(bad, t)
    bad[2, 1] = 1e300
    with pytest.raises(InvalidGeometryError, match="supported range"):
        voxelize_solid(bad, t)
    bad[2, 1] = 1e-100
    with pytest.raises(InvalidGeometryError, match="supported range"):
        voxelize_solid(bad, t)
    with pytest.raises(InvalidGeometryError, match="does not exist"):
        voxelize_solid(v, t + 1)
    with pytest.raises(InvalidGeometryError, match=r"\(n, 3\)"):
        voxelize_solid(v[:, :2], t)
    with pytest.raises(InvalidGeometryError, match="integer"):
        voxelize_solid(v, t.astype(float))
    with pytest.raises(SizeLimitError):
        voxelize_solid(v * 1000, t, limit=1000)


@pytest.mark.parametrize("model", MODELS)
def test_vertices_no_triangle_uses_neither_widen_the_box_nor_need_to_be_in_range(model) -> None:
    """Two extra vertices (one NaN, one at 10^300) that no triangle refers to change nothing."""
    v, t = tetra_mesh((0.0, 0.0, 0.0), (2.0, 0.0, 0.0), (0.0, 2.0, 0.0), (0.0, 0.0, 2.0))
    extra = np.concatenate([v[:2], [[np.nan, 0.0, 0.0], [1e300, -1e300, 0.0]], v[2:]])
    t2 = np.where(t >= 2, t + 2, t)
    mask, origin = voxelize_solid(extra, t2, model)
    assert voxel_set(mask, origin) == voxels((v, t), model)
    assert_canonical(mask, origin)
    assert voxelization_box(extra, t2, model) == voxelization_box(v, t, model)


def test_empty_inputs() -> None:
    for model in MODELS:
        mask, origin = voxelize_solid(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64), model)
        assert mask.shape == (0, 0, 0) and origin == (0, 0, 0)
        mask, origin = voxelize_points([], model)
        assert mask.shape == (0, 0, 0)
    # a solid thinner than a voxel that misses every shifted centre
    mesh = tetra_mesh((0.1, 0.1, 0.1), (0.4, 0.1, 0.1), (0.1, 0.4, 0.1), (0.1, 0.1, 0.4))
    assert voxelize_solid(*mesh, "gauss")[0].shape == (0, 0, 0)
    assert voxel_set(*voxelize_solid(*mesh, "standard")) == {(0, 0, 0)}


def test_boxes_and_estimates() -> None:
    v, t = box_mesh((0.0, 0.0, 0.0), (2.5, 1.0, 0.5))
    assert voxelization_box(v, t, "standard") == (0, 0, 0, 2, 1, 0)
    assert voxelization_box(v, t, "supercover") == (0, 0, 0, 3, 1, 1)
    assert estimate_voxels(v, t) == 4 * 2 * 2
    # gauss: p + τ within the extent, ⌈min⌉ ≤ p ≤ ⌈max⌉ − 1
    assert voxelization_box(v, t, "gauss") == (0, 0, 0, 2, 0, 0)
    assert voxel_set(*voxelize_solid(v, t, "gauss")) == {(0, 0, 0), (1, 0, 0), (2, 0, 0)}
    mask, origin = voxelize_triangles(v, t, "supercover")
    assert mask.shape == (2, 2, 4) and origin == (0, 0, 0)


def test_translated_big_mesh_far_away() -> None:
    """Coordinates near the limit (2^51 allows half-integers) keep their exact answer."""
    mesh = box_mesh((0.0, 0.5, -0.5), (1.0, 1.5, 0.5))
    t = (2.0**50, -(2.0**50), 2.0**49)
    for model in MODELS:
        base = voxels(mesh, model)
        moved = voxels(translate(mesh, t), model)
        assert moved == {(x + int(t[0]), y + int(t[1]), z + int(t[2])) for x, y, z in base}
