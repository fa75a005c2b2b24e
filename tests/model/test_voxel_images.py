"""D(T(P)) of an exact rational affine image of a polyhedron (docs/design.md §11, §8; ADRs 0058, 0062).

DSS_α(A) = D(Sc_α(R(A))) and the quarter turns dR(A) = D(rot(R(A))) on voxel sets, with α = p/q whose image
is not float64 (α = 1/5, 4/5 of the paper's Figure 12): every result is compared with the Fraction reference
of the definitions (tests/oracles/voxelize_reference.py) given the exact image, on R(A) of random voxel sets,
on tetrahedra and split octahedra with free float vertices, and on images lying on the result's voxel centres
and faces (where the grid of step N decides ties by N·τ). Then D(Sc_1(R(A))) = A, quarter turns of R(A) are
A's quarter turns, DSS_1/k by pooling A's voxels is the computed definition, and a ratio with a large odd
denominator costs its result only.
"""

from __future__ import annotations

import math
import tracemalloc
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mrm.core.errors import InvalidGeometryError, ParameterError, SizeLimitError
from mrm.core.grids import VoxelSet
from mrm.core.models import Model
from mrm.geometry.discretize.voxel_images import voxelize_image
from mrm.geometry.polyhedra import Polyhedron
from mrm.geometry.reconstruct import reconstruct
from mrm.ops.outcome import scaling_by_pixels
from tests.oracles.mesh_strategies import box_mesh, stars, tetra_mesh, tetras
from tests.oracles.voxelize_reference import reference_voxelize

MODELS = Model.names()
F = Fraction
ALPHAS = [F(1, 5), F(4, 5), F(5, 4), F(2, 3), F(3), F(1, 2), F(7, 3)]
IDENTITY = ((1, 0, 0), (0, 1, 0), (0, 0, 1))

#: Voxel sets of up to 3 × 3 × 3 (the reference is slow), anywhere near the origin.
small_sets = st.builds(
    lambda bits, origin: VoxelSet(np.array(bits, dtype=bool).reshape(3, 3, 3), origin),
    st.lists(st.booleans(), min_size=27, max_size=27),
    st.tuples(*[st.integers(-3, 3)] * 3),
).filter(lambda a: not a.is_empty())

#: Rational centres: the origin, voxel centres, voxel corners, and thirds between them.
centres = st.one_of(
    st.just((F(0), F(0), F(0))),
    st.tuples(*[st.integers(-3, 3).map(F)] * 3),
    st.tuples(*[st.integers(-6, 6).map(lambda n: F(n, 2))] * 3),
    st.tuples(*[st.integers(-9, 9).map(lambda n: F(n, 3))] * 3),
)


def quarter_turn(axis: int, k: int) -> tuple[tuple[int, int, int], ...]:
    """k quarter turns counter-clockwise about the coordinate axis ``axis``: a signed permutation matrix."""
    a, b = [(1, 2), (2, 0), (0, 1)][axis]
    m = [[int(i == j) for j in range(3)] for i in range(3)]
    for _ in range(k % 4):
        rows = [list(r) for r in m]
        m[a], m[b] = [-u for u in rows[b]], rows[a]
    return tuple(tuple(r) for r in m)


def similarity(alpha: Fraction, rot: tuple[tuple[int, ...], ...], centre) -> tuple[list[list[F]], list[F]]:  # type: ignore[no-untyped-def]
    """v ↦ α·rot·(v − C) + C as (linear, offset), exactly."""
    lin = [[alpha * rot[i][j] for j in range(3)] for i in range(3)]
    off = [centre[i] - sum(lin[i][j] * centre[j] for j in range(3)) for i in range(3)]
    return lin, off


def exact_image(solid: Polyhedron, lin, off) -> list[list[tuple[F, F, F]]]:  # type: ignore[no-untyped-def]
    """T(P)'s triangles with Fraction vertices: what the reference takes."""
    pts = []
    for row in solid.vertices.tolist():
        v = [F(u) for u in row]
        pts.append(tuple(sum((lin[i][j] * v[j] for j in range(3)), off[i]) for i in range(3)))
    return [[pts[i] for i in tri] for tri in solid.triangles.tolist()]


def voxels(vs: VoxelSet) -> set[tuple[int, int, int]]:
    return {(int(x), int(y), int(z)) for x, y, z in vs.points().tolist()}


def float_refusal_is_due(tris) -> bool:  # type: ignore[no-untyped-def]
    """True when N·T(P), N the odd part of the coordinates' common denominator, is not float64 in range."""
    coords = [c for t in tris for p in t for c in p]
    den = math.lcm(*(c.denominator for c in coords))
    n = den >> ((den & -den).bit_length() - 1)
    for c in coords:
        q = n * c
        try:
            f = float(q)
        except OverflowError:
            return True
        if F(f) != q or abs(f) > 2.0**51 or (f != 0 and abs(f) < 2.0**-250):
            return True
    return False


# --------------------------------------------------------------------------------- against the reference
@settings(max_examples=40)
@given(
    small_sets,
    st.sampled_from(ALPHAS),
    centres,
    st.tuples(st.integers(0, 2), st.integers(0, 3)),
    st.sampled_from(MODELS),
)
def test_dss_and_quarter_turns_of_r_of_a_voxel_set_are_the_definition(a, alpha, centre, turn, model):
    """D(α·rot·(R(A) − C) + C) equals the Fraction reference given the exact image, in every model."""
    solid = reconstruct(a, model)
    lin, off = similarity(alpha, quarter_turn(*turn), centre)
    got = voxelize_image(solid, lin, off, model)
    assert voxels(got) == reference_voxelize(exact_image(solid, lin, off), model, True)


@settings(max_examples=40)
@given(
    st.one_of(tetras(), stars(max_radius=1.5)),
    st.sampled_from(ALPHAS),
    centres,
    st.tuples(st.integers(0, 2), st.integers(0, 3)),
    st.sampled_from(MODELS),
)
def test_exact_images_of_float_polyhedra_are_the_definition_or_refused_when_not_float(
    mesh, alpha, centre, turn, model
):
    """Tetrahedra and split octahedra with free float64 vertices: the definition, or a one-line refusal
    exactly when the image scaled by N is not made of float64 numbers (53-bit mantissas)."""
    try:
        solid = Polyhedron(*mesh)
    except InvalidGeometryError:
        assume(False)
    lin, off = similarity(alpha, quarter_turn(*turn), centre)
    tris = exact_image(solid, lin, off)
    try:
        got = voxelize_image(solid, lin, off, model)
    except ParameterError as e:
        assert "\n" not in str(e) and "float64" in str(e)
        assert float_refusal_is_due(tris)
        return
    assert voxels(got) == reference_voxelize(tris, model, True)


@pytest.mark.parametrize("model", MODELS)
def test_vertices_spanning_more_bits_than_int64_are_exact(model):
    """Coordinates 2⁻⁶⁰ and 6 in one solid (65 bits apart) take Python integers, with the same voxels."""
    solid = Polyhedron(
        *tetra_mesh((2.0**-60, 0.25, 0.5), (6.0, 0.5, 0.25), (0.5, 6.0, 0.75), (0.75, 0.5, 6.0))
    )
    lin, off = similarity(F(4, 5), IDENTITY, (F(0), F(0), F(0)))
    got = voxelize_image(solid, lin, off, model)
    assert voxels(got) == reference_voxelize(exact_image(solid, lin, off), model, True)
    assert len(got) > 0


# ------------------------------------------------------------------------------------------ properties
@settings(max_examples=40)
@given(
    st.builds(
        lambda bits, shape, origin: VoxelSet(
            np.array(bits[: math.prod(shape)], dtype=bool).reshape(shape), origin
        ),
        st.lists(st.booleans(), min_size=216, max_size=216),
        st.tuples(*[st.integers(1, 6)] * 3),
        st.tuples(*[st.integers(-50, 50)] * 3),
    ),
    centres,
    st.tuples(st.integers(0, 2), st.integers(0, 3), st.tuples(*[st.integers(-3, 3)] * 3)),
    st.sampled_from(MODELS),
)
def test_dss_one_is_the_identity_and_quarter_turns_are_the_voxels_turned(a, centre, turn, model):
    """D(Sc_1(R(A))) = A about any centre, and D(rot(R(A))) = A's quarter turn about a voxel centre."""
    solid = reconstruct(a, model)
    lin, off = similarity(F(1), IDENTITY, centre)
    assert voxelize_image(solid, lin, off, model) == a
    axis, k, c = turn
    lin, off = similarity(F(1), quarter_turn(axis, k), tuple(F(u) for u in c))
    assert voxelize_image(solid, lin, off, model) == a.rotate90(k, axis, c)


@settings(max_examples=60)
@given(
    st.builds(
        lambda bits, origin: VoxelSet(np.array(bits, dtype=bool).reshape(5, 4, 6), origin),
        st.lists(st.booleans(), min_size=120, max_size=120),
        st.tuples(*[st.integers(-9, 9)] * 3),
    ).filter(lambda a: not a.is_empty()),
    st.integers(1, 5),
    st.tuples(*[st.integers(-6, 6).map(lambda n: F(n, 2))] * 3),
    st.sampled_from(MODELS),
)
def test_dss_one_over_k_by_pooling_voxels_is_the_computed_definition(a, k, centre, model):
    """scaling_by_pixels in 3D (k × k × k pooling, or sampling for gauss) = D(Sc_1/k(R(A))) computed."""
    alpha = F(1, k)
    lin, off = similarity(alpha, IDENTITY, centre)
    got = scaling_by_pixels(a, (alpha, off), model)
    c = [(1 - k) * u for u in centre]  # Sc_1/α = v ↦ k·v + c
    half = F(k - 1, 2)
    aligned = all((u if model == "gauss" else u - half).denominator == 1 for u in c)
    assert (got is not None) == aligned
    if got is not None:
        assert got == voxelize_image(reconstruct(a, model), lin, off, model)


@pytest.mark.parametrize("model", MODELS)
def test_dss_one_fifth_by_pooling_of_a_noisy_ball_is_the_computed_definition(model):
    """A 40³ noisy ball: DSS_1/5 by pooling A equals D(Sc_1/5(R(A))) computed on the grid of step 5."""
    rng = np.random.default_rng(7)
    z, y, x = np.mgrid[0:40, 0:40, 0:40]
    ball = ((x - 19.5) ** 2 + (y - 20.0) ** 2 + (z - 18.0) ** 2 < 17**2) ^ (rng.random((40, 40, 40)) < 0.03)
    a = VoxelSet(ball, (-7, 3, 11))
    centre = (F(-1, 2), F(-1, 2), F(-1, 2)) if model != "gauss" else (F(0), F(0), F(0))
    lin, off = similarity(F(1, 5), IDENTITY, centre)
    pooled = scaling_by_pixels(a, (F(1, 5), off), model)
    assert pooled is not None
    assert pooled == voxelize_image(reconstruct(a, model), lin, off, model)


@settings(max_examples=200)
@given(
    st.lists(
        st.one_of(
            st.floats(allow_nan=False, allow_infinity=False),
            st.integers(-(2**20), 2**20).map(lambda n: n / 4),
            st.sampled_from([0.0, -0.0, 5e-324, 2.0**-60, 6.0, 2.0**62, -(2.0**70)]),
        ),
        min_size=1,
        max_size=12,
    )
)
def test_integer_vertices_are_the_values_times_the_least_power_of_two(values):
    """v = X·2^-k exactly with k ≥ 0 least, X int64 when it fits (else Python integers): the reading of
    the vertices that every exact image starts from."""
    from mrm.geometry.discretize.voxel_images import integer_vertices

    v = np.array(values + [0.0] * (-len(values) % 3), dtype=np.float64).reshape(-1, 3)
    x, k = integer_vertices(v)
    assert k >= 0 and x.shape == v.shape
    assert all(F(int(xi), 2**k) == F(vi) for xi, vi in zip(x.reshape(-1), v.reshape(-1), strict=True))
    if k > 0:  # least: some value is not an integer times 2^-(k-1)
        assert any((F(vi) * 2 ** (k - 1)).denominator > 1 for vi in v.reshape(-1))
    assert (x.dtype == np.int64) == all(abs(F(vi)) * 2**k < 2**62 for vi in v.reshape(-1))


@pytest.mark.parametrize(
    ("numerators", "odd", "expected"),
    [
        ([25] * 100 + [10], 75, 5),  # the value that lowers the gcd comes after the first 64
        ([15] * 100, 75, 15),
        ([15] * 100 + [7], 75, 1),
        ([0] * 70, 9, 9),
        ([-45, 0, 30], 15, 15),
    ],
)
def test_the_odd_denominator_is_reduced_by_every_numerator(numerators, odd, expected):
    """N is the least odd factor: gcd(odd, every numerator), whichever value lowers it."""
    from mrm.geometry.discretize.voxel_images import _gcd_with

    assert _gcd_with(np.array(numerators, dtype=np.int64), odd) == expected
    assert _gcd_with(np.array(numerators, dtype=object), odd) == expected


# -------------------------------------------------------------------------------------------- refusals
@pytest.mark.parametrize("model", MODELS)
def test_a_ratio_with_a_large_odd_denominator_costs_its_result_only(model):
    """α = 127/125 (N = 125) on a 64³ cube: computed on the grid of step 125 within a few megabytes (a
    125-times finer grid would hold 3·10¹¹ voxels, refused before), and it is D of the scaled box: on each
    axis the voxels whose kernel meets [α·lo, α·hi], [lo, hi] the extent of R(A)."""
    a = VoxelSet.box(0, 0, 0, 63, 63, 63)
    solid = reconstruct(a, model)
    alpha = F(127, 125)
    lin, off = similarity(alpha, IDENTITY, (F(0), F(0), F(0)))
    tracemalloc.start()
    try:
        got = voxelize_image(solid, lin, off, model, what="DSS 1.016")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert solid.n_vertices == 8  # R(A) is the box [lo, hi]³
    lo, hi = alpha * F(float(solid.vertices.min())), alpha * F(float(solid.vertices.max()))
    if model == "gauss":  # lo ≤ c < hi
        c_lo, c_hi = math.ceil(lo), math.ceil(hi) - 1
    else:  # the cells (c − ½, c + ½] of the ends (neither end is a half-integer)
        assert (2 * lo).denominator > 1 and (2 * hi).denominator > 1
        c_lo, c_hi = math.ceil(lo - F(1, 2)), math.ceil(hi - F(1, 2))
    assert got == VoxelSet.box(c_lo, c_lo, c_lo, c_hi, c_hi, c_hi) != a
    assert peak < 8 << 20  # the 65³ result is 0.3 MB


#: Ratios with odd denominators up to 375, and the lattice of the image's vertices (below).
LATTICE_ALPHAS = [F(1, 5), F(4, 5), F(2, 3), F(1, 7), F(3, 11), F(1, 125), F(64, 375)]


@settings(max_examples=60, deadline=None)
@given(
    st.sampled_from(LATTICE_ALPHAS),
    st.lists(st.tuples(*[st.integers(-3, 3)] * 3), min_size=4, max_size=4, unique=True),
    st.tuples(*[st.integers(-2, 2)] * 3),
    st.tuples(st.integers(0, 2), st.integers(0, 3)),
    st.booleans(),
    st.sampled_from(MODELS),
)
def test_images_on_the_coarse_grid_planes_and_centres_are_the_definition(
    alpha, ms, shift, turn, as_box, model
):
    """Images whose vertices lie on the result's voxel centres (integers) and faces (half-integers), with
    edges and faces along them, so that Q = N·T(P) lies on the centres N·c and planes N·(k ± ½) of the grid
    of step N where the shift N·τ decides: a tetrahedron or an axis-aligned box with vertices w in the lattice
    (p'/2)·Z³ (p' the odd part of α's numerator), P = T⁻¹ of it (float64: T⁻¹(w) = rot⁻¹(w − C)/α + C with
    C in the lattice). Compared with the Fraction reference, in every model."""
    unit = F(alpha.numerator >> ((alpha.numerator & -alpha.numerator).bit_length() - 1), 2)
    ws = [tuple(unit * u for u in m) for m in ms]
    centre = tuple(unit * u for u in shift)
    if as_box:
        lo = [min(w[d] for w in ws[:2]) for d in range(3)]
        hi = [max(w[d] for w in ws[:2]) for d in range(3)]
        assume(all(lo[d] < hi[d] for d in range(3)))
        corners = [tuple((lo, hi)[(n >> d) & 1][d] for d in range(3)) for n in range(8)]
    else:
        corners = ws
    rot = quarter_turn(*turn)
    lin, off = similarity(alpha, rot, centre)
    # T⁻¹(w) = rotᵀ·(w − C)/α + C, exactly; float64 by the choice of the lattice
    pre = [
        tuple(sum(rot[j][i] * (w[j] - centre[j]) for j in range(3)) / alpha + centre[i] for i in range(3))
        for w in corners
    ]
    assert all(F(float(u)) == u for p in pre for u in p)
    if as_box:  # box_mesh's outward triangles on the corners' preimages (T keeps orientation)
        v, t = np.array([[float(u) for u in p] for p in pre]), box_mesh((0, 0, 0), (1, 1, 1))[1]
    else:
        v, t = tetra_mesh(*[tuple(float(u) for u in p) for p in pre])
    try:
        solid = Polyhedron(v, t)
    except InvalidGeometryError:
        assume(False)
    got = voxelize_image(solid, lin, off, model)
    assert voxels(got) == reference_voxelize(exact_image(solid, lin, off), model, True)


@pytest.mark.parametrize("model", MODELS)
def test_a_denominator_near_the_grid_step_limit_is_exact_and_one_beyond_is_refused(model):
    """α = 1/3³⁰ (N ≈ 2^47.5): a tetrahedron of size ~2^48 about a voxel face shrinks to a few voxels, decided
    on the grid of step N as the reference decides; α = 1/(2⁵⁰ + 1) is refused in one line (the grid
    numbers N·(k ± ½) would leave the exact half-integers)."""
    n = 3**30
    tetra = Polyhedron(
        *tetra_mesh((-n / 2, -n / 2, 0.0), (2.0 * n, 0.0, 0.0), (0.0, 1.5 * n, 0.0), (0.0, 0.0, n))
    )
    lin, off = similarity(F(1, n), IDENTITY, (F(0), F(0), F(0)))
    got = voxelize_image(tetra, lin, off, model)
    assert voxels(got) == reference_voxelize(exact_image(tetra, lin, off), model, True)
    assert len(got) > 0
    lin, off = similarity(F(1, 2**50 + 1), IDENTITY, (F(0), F(0), F(0)))
    with pytest.raises(ParameterError) as info:
        voxelize_image(tetra, lin, off, model)
    assert "2^49" in str(info.value) and "\n" not in str(info.value)


def test_a_result_beyond_the_limit_is_refused_before_the_finer_grid():
    a = VoxelSet.box(0, 0, 0, 9, 9, 9)
    lin, off = similarity(F(2, 5), IDENTITY, (F(0), F(0), F(0)))
    with pytest.raises(SizeLimitError) as info:
        voxelize_image(reconstruct(a, "gauss"), lin, off, "gauss", limit=20)
    assert info.value.estimated <= 5**3 and "finer" not in str(info.value)


@pytest.mark.parametrize(
    ("linear", "offset", "words"),
    [
        ([[1, 0, 0], [0, 1, 0], [0, 0, -1]], [0, 0, 0], "determinant"),
        ([[1, 0, 0], [0, 1, 0], [0, 0, 0]], [0, 0, 0], "determinant"),
        ([[1, 0], [0, 1]], [0, 0], "3 × 3"),
        ([[1, 0, 0], [0, 1, 0], [0, 0, 1]], [0, float("nan"), 0], "finite"),
        ([[1, 0, 0], [0, "1", 0], [0, 0, 1]], [0, 0, 0], "rational"),
    ],
    ids=["a mirror", "flat", "2 × 2", "NaN offset", "a string"],
)
def test_maps_that_are_not_exact_orientation_keeping_bijections_are_refused_in_one_line(
    linear, offset, words
):
    solid = reconstruct(VoxelSet.box(0, 0, 0, 1, 1, 1), "standard")
    with pytest.raises(ParameterError) as info:
        voxelize_image(solid, linear, offset, "standard")
    assert words in str(info.value) and "\n" not in str(info.value)


def test_an_image_with_coordinates_beyond_53_bits_is_refused_in_one_line():
    """x = 1 + 2⁻⁵² scaled by 3 has 54 significant bits: no float64 holds it, so no exact kernel runs."""
    solid = Polyhedron(
        *tetra_mesh((1 + 2.0**-52, 0.0, 0.0), (4.0, 0.0, 0.0), (1.0, 3.0, 0.0), (1.0, 0.0, 3.0))
    )
    lin, off = similarity(F(3), IDENTITY, (F(0), F(0), F(0)))
    with pytest.raises(ParameterError) as info:
        voxelize_image(solid, lin, off, "gauss")
    assert "float64" in str(info.value) and "\n" not in str(info.value)


def test_the_docstring_example_runs():
    """DSS_1/5 of a 10³ cube about a voxel corner is the 2³ cube its docstring shows."""
    import doctest

    import mrm.geometry.discretize.voxel_images as module

    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE, verbose=False)
    assert result.failed == 0 and result.attempted > 0


def test_a_cancelled_voxelization_stops_with_cancelled():
    """The progress object's Cancelled (the GUI's cancel button) stops the work and reaches the caller."""
    from mrm.core.errors import Cancelled

    class CancelAtOnce:
        calls = 0

        def update(self, fraction=None, message=None):  # type: ignore[no-untyped-def]
            self.calls += 1
            raise Cancelled("cancelled")

    progress = CancelAtOnce()
    lin, off = similarity(F(4, 5), IDENTITY, (F(0), F(0), F(0)))
    with pytest.raises(Cancelled):
        voxelize_image(reconstruct(VoxelSet.box(0, 0, 0, 9, 9, 9), "standard"), lin, off, progress=progress)
    assert progress.calls == 1


@pytest.mark.parametrize("model", MODELS)
def test_a_dyadic_map_is_computed_in_float64_only_when_nothing_rounds(model):
    """Dyadic α about a dyadic centre and quarter turns skip the integer reading of the vertices, only when
    every product and sum is exact in float64: then the image is the very one (the definition); when a sum
    rounds (0.05 + 0.5), the integer path decides, and refuses an image float64 cannot hold."""
    from mrm.geometry.discretize.voxel_images import _dyadic_image

    tetra = Polyhedron(*tetra_mesh((0.1, 0.0, 0.0), (3.3, 0.0, 0.0), (0.0, 2.7, 0.0), (0.0, 0.0, 1.9)))
    rounds = similarity(F(1, 2), quarter_turn(2, 1), (F(1), F(1), F(1)))
    exact = similarity(F(4), quarter_turn(0, 3), (F(0), F(0), F(0)))
    box = Polyhedron(*box_mesh((-1.25, 0.5, 2.0), (3.75, 4.5, 2.5)))
    for solid, (lin, off), fast in ((tetra, rounds, False), (tetra, exact, True), (box, rounds, True)):
        m = [[F(x) for x in row] for row in lin]
        t = [F(x) for x in off]
        q = _dyadic_image(np.asarray(solid.vertices), m, t)
        assert (q is not None) == fast
        if q is None:
            with pytest.raises(ParameterError, match="float64"):
                voxelize_image(solid, lin, off, model)
            continue
        want = [[sum((m[i][j] * F(v[j]) for j in range(3)), t[i]) for i in range(3)] for v in solid.vertices]
        assert [[F(c) for c in row] for row in q.tolist()] == want  # every coordinate, exactly
        got = voxelize_image(solid, lin, off, model)
        assert voxels(got) == reference_voxelize(exact_image(solid, lin, off), model, True)
