"""DSS_α(A) = D(Sc_α(R(A))) exactly, the exact rational discretization behind it, DSS as a user runs it."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mrm.core.errors import ParameterError
from mrm.core.grids import PixelSet
from mrm.geometry.discretize import discretize
from mrm.geometry.discretize.exact_shape import ExactShape
from mrm.geometry.discretize.rational import discretize_exact
from mrm.geometry.reconstruct import reconstruct
from mrm.ops.provenance import Provenance
from mrm.ops.registry import run_operation
from mrm.ops.scaling import DSSParams, discrete_smooth_scaling, run
from tests.oracles.geometry_strategies import star_polygons
from tests.oracles.ops_reference import MODELS, objects, polygons_of, reference_discretize_rings, scaled

# Scale factors as a user types them; each is read as the exact rational it prints as.
ALPHAS = [
    (5, Fraction(5)),
    (0.2, Fraction(1, 5)),
    (1.25, Fraction(5, 4)),
    (0.8, Fraction(4, 5)),
    (3, Fraction(3)),
    ("2/3", Fraction(2, 3)),
    (2.5, Fraction(5, 2)),
    (0.5, Fraction(1, 2)),
    (1.7, Fraction(17, 10)),
]


centres = st.one_of(
    st.none(),
    st.tuples(st.integers(-3, 3), st.integers(-3, 3)),
    st.tuples(st.sampled_from([-1.5, 0.5, 2.5]), st.sampled_from([-0.5, 1.5])),
    st.tuples(st.sampled_from([0.1, 1.3]), st.sampled_from([-0.7, 2.2])),
)


# ---------------------------------------------------------------------------------------------- the contract
@settings(max_examples=120)
@given(objects(), st.sampled_from(ALPHAS), centres, st.sampled_from(MODELS))
def test_dss_is_exactly_D_of_the_scaled_continuation(a, alpha, center, model):
    typed, exact = alpha
    out = discrete_smooth_scaling(a, typed, center, model)
    c = (Fraction(0), Fraction(0)) if center is None else tuple(Fraction(repr(v)) for v in center)
    reference = reference_discretize_rings(scaled(polygons_of(reconstruct(a, model)), exact, c), model)
    assert out.result == reference


def test_dss_by_a_power_of_two_matches_plain_discretization():
    # Scaling by 2 is exact in floats, so D of the float-scaled continuation is the reference too.
    a = PixelSet.from_points([(0, 0), (1, 0), (1, 1), (3, 2), (4, 2), (4, 3)])
    for model in MODELS:
        r = reconstruct(a, model)
        doubled = shapely.transform(r, lambda xy: xy * 2.0)
        assert discrete_smooth_scaling(a, 2, None, model).result == discretize(doubled, model)


def test_the_centre_moves_the_result_by_the_centre_times_one_minus_alpha():
    a = PixelSet.from_points([(0, 0), (1, 0), (2, 0), (2, 1), (2, 2), (0, 1)])
    for model in MODELS:
        base = discrete_smooth_scaling(a, 3, None, model).result
        # Sc_3 about (1, 2) is Sc_3 about the origin followed by the integer translation (1−3)·(1, 2).
        moved = discrete_smooth_scaling(a, 3, (1, 2), model).result
        assert moved == base.translate(-2, -4)


# ---------------------------------------------------------------------------------------------- the exact D
RATIONALS = [Fraction(1, 3), Fraction(2, 5), Fraction(7, 3), Fraction(5, 6), Fraction(3, 7)]


@st.composite
def rational_shapes(draw):
    """Star polygons scaled by a non-dyadic rational: vertices that are not float64 values."""
    poly = draw(star_polygons(max_vertices=7, max_radius=4.0))
    q = draw(st.sampled_from(RATIONALS))
    return poly, q


@settings(max_examples=200)
@given(rational_shapes(), st.sampled_from(MODELS))
def test_rational_discretization_follows_the_definitions(shape_and_q, model):
    poly, q = shape_and_q
    exact = ExactShape.from_geometry(poly)
    polys = scaled(polygons_of(poly), q)
    from mrm.geometry.discretize.exact_shape import Similarity

    got = discretize_exact(exact.map(Similarity.scaling(q)), model)
    assert got == reference_discretize_rings(polys, model)


@settings(max_examples=300)
@given(star_polygons(max_vertices=8, max_radius=6.0), st.sampled_from(MODELS))
def test_integer_path_agrees_with_the_compiled_discretization(poly, model):
    # On float64 input both paths apply; the snapped lattices make them face every tie.
    exact = ExactShape.from_geometry(poly)
    assert discretize_exact(exact, model, force_integer=True) == discretize(poly, model)


# ---------------------------------------------------------------------------------------------- the operation
def test_the_registered_operation_gives_one_result_with_its_provenance():
    a = PixelSet.box(0, 0, 3, 2)
    res = run_operation("dss", [a], DSSParams(alpha=0.5, center=(1.0, 1.0), model="supercover"))
    assert res.outputs == [("DSS 0.5", discrete_smooth_scaling(a, 0.5, (1, 1), "supercover").result)]
    assert res.provenance["operation"] == "dss"
    assert res.provenance["params"] == {"alpha": 0.5, "center": [1.0, 1.0], "model": "supercover"}
    # one DSS alone is exact in the paper's sense: A_last = Sc_α(R(A)) = T(A_first)
    assert res.bound is not None and res.bound.bound == 0.0
    # run alone only computes: run_operation is the one place that stamps provenance and bound
    direct = run([a], DSSParams(alpha=0.5, center=(1.0, 1.0), model="supercover"))
    assert direct.outputs == res.outputs and direct.provenance == {} and direct.bound is None
    assert Provenance("dss", res.provenance["params"]).params == res.provenance["params"]


def test_a_polygon_input_is_scaled_through_its_discretization():
    tri = shapely.Polygon([(0, 0), (6, 0), (0, 4)])
    assert run([tri], DSSParams(alpha=2.0)).output == discrete_smooth_scaling(discretize(tri), 2).result


def test_scale_factor_errors_name_the_parameter():
    a = PixelSet.box(0, 0, 2, 2)
    for bad in (0, -1.5, float("nan"), float("inf"), "abc", True, None):
        with pytest.raises(ParameterError, match="alpha"):
            discrete_smooth_scaling(a, bad)
    with pytest.raises(ParameterError, match="model"):
        discrete_smooth_scaling(a, 2, None, "nearest")


CENTRES = [
    None,
    (Fraction(1, 2), Fraction(-3, 10)),
    (Fraction(1, 3), Fraction(2, 7)),
    (Fraction(5), Fraction(0)),
]


@settings(max_examples=200)
@given(rational_shapes(), st.sampled_from(MODELS), st.sampled_from(CENTRES))
def test_the_fraction_free_compiled_path_follows_the_definitions(shape_and_q, model, centre):
    """D(Sc_q,C(E)) by int64 kernels (no Fraction) = the slow Fraction reference = the Python-integer path."""
    from mrm.geometry.discretize.exact_shape import Similarity
    from mrm.geometry.discretize.rational import discretize_image

    poly, q = shape_and_q
    # Vertices on a 1/64 grid, as a continuation R(A) has them: the int64 path applies.
    poly = shapely.transform(poly, lambda c: np.round(c * 64) / 64)
    assume(poly.is_valid and not poly.is_empty)
    sim = Similarity.scaling(q, centre)
    got = discretize_image(poly, sim, model)
    assert got is not None
    polys = scaled(polygons_of(poly), q, centre)
    assert got == reference_discretize_rings(polys, model)
    exact = ExactShape.from_geometry(poly).map(sim)
    assert got == discretize_exact(exact, model, force_integer=True, compiled=False)


@settings(max_examples=100)
@given(objects(), st.sampled_from([0.2, 0.8, 1.25, 3.0]), st.sampled_from(MODELS))
def test_dss_by_the_compiled_path_is_the_definition(a, alpha, model):
    """DSS_α(A) = D(Sc_α(R(A))) with α the decimal it prints as, against the Fraction reference."""
    out = discrete_smooth_scaling(a, alpha, None, model)
    polys = scaled(polygons_of(reconstruct(a, model)), Fraction(str(alpha)))
    assert out.result == reference_discretize_rings(polys, model)
    assert out.euclidean == ExactShape.from_geometry(reconstruct(a, model)).map(
        __import__("mrm.geometry.discretize.exact_shape", fromlist=["Similarity"]).Similarity.scaling(
            Fraction(str(alpha))
        )
    )


# ------------------------------------------------------------------------------ DSS_1/k from the pixels alone
@settings(max_examples=200, deadline=None)
@given(
    objects(),
    st.integers(1, 7),
    st.tuples(st.integers(-6, 6), st.integers(-6, 6)).map(lambda t: (Fraction(t[0], 2), Fraction(t[1], 2))),
    st.sampled_from(MODELS),
)
def test_dss_by_one_over_k_from_the_pixels_is_the_definition(a, k, centre, model):
    """Pooling (covers) and sampling (gauss) of A give D(Sc_1/k(R(A))) whenever they apply."""
    from mrm.geometry.discretize.exact_shape import Similarity
    from mrm.ops.outcome import scaling_by_pixels

    sim = Similarity.scaling(Fraction(1, k), centre)
    got = scaling_by_pixels(a, sim, model)
    c = [(1 - k) * v for v in centre]
    aligned = (
        all(v.denominator == 1 for v in c)
        if model == "gauss"
        else all((v - Fraction(k - 1, 2)).denominator == 1 for v in c)
    )
    assert (got is not None) == aligned
    if got is not None:
        polys = scaled(polygons_of(reconstruct(a, model)), Fraction(1, k), centre)
        assert got == reference_discretize_rings(polys, model)


@pytest.mark.parametrize("model", MODELS)
def test_dss_one_fifth_of_a_large_object_is_the_computed_definition(model):
    """The shortcut on a 300² noisy object equals D(Sc_1/5(R(A))) computed by the exact discretization."""
    from mrm.geometry.discretize.exact_shape import Similarity
    from mrm.geometry.discretize.rational import discretize_image

    rng = np.random.default_rng(5)
    yy, xx = np.mgrid[0:300, 0:300]
    blob = ((xx - 150.0) ** 2 + (yy - 140.0) ** 2 < 130**2) ^ (rng.random((300, 300)) < 0.05)
    a = PixelSet(blob, (-7, 3))
    out = discrete_smooth_scaling(a, 0.2, None, model)
    assert out.result == discretize_image(reconstruct(a, model), Similarity.scaling(Fraction(1, 5)), model)
    assert out.euclidean == ExactShape.from_geometry(reconstruct(a, model)).map(
        Similarity.scaling(Fraction(1, 5))
    )


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize(
    "a",
    [PixelSet.box(0, 0, 0, 0), PixelSet.box(-3, 5, 40, 7), PixelSet(np.eye(6, dtype=bool), (999_998, -2))],
    ids=["one pixel", "a bar", "a diagonal across a block side"],
)
@pytest.mark.parametrize("k", [33, 10**6])
def test_dss_by_one_over_a_huge_k_is_the_definition_without_a_k_by_k_array(a, k, model):
    """Issue 32: DSS_10⁻⁶ with aligned grids padded A to whole 10⁶ × 10⁶ blocks (931 GiB, MemoryError).

    The result is a pixel or two; it is the definition D(Sc_1/k(R(A))), computed by the references.
    """
    import mrm
    from mrm.geometry.discretize.exact_shape import Similarity
    from mrm.ops.outcome import scaling_by_pixels

    centre = (Fraction(-1, 2), Fraction(-1, 2)) if model != "gauss" else (Fraction(0), Fraction(0))
    assert scaling_by_pixels(a, Similarity.scaling(Fraction(1, k), centre), model) is not None  # the shortcut
    got = mrm.scale(a, Fraction(1, k), centre, model)
    polys = scaled(polygons_of(reconstruct(a, model)), Fraction(1, k), centre)
    assert got == reference_discretize_rings(polys, model)
