"""Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))): idempotence, the paper's bound, and the operation as a user runs it."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import ParameterError
from mrm.core.grids import PixelSet
from mrm.geometry.discretize import discretize
from mrm.geometry.reconstruct import reconstruct
from mrm.ops.measure import measured_error
from mrm.ops.registry import run_operation
from mrm.ops.simplify import SimplifyParams, simplification
from tests.oracles.geometry_strategies import star_polygons
from tests.oracles.ops_reference import COVERS, MODELS, polygons_of, reference_discretize_rings, scaled

ALPHAS = [0.5, 0.25, 2, 0.3, 1.7, 3, "1/3", 0.8]
SMALL_ALPHAS = [0.5, 0.25, 0.3, 1.7, "1/3", 0.8, "2/3"]


def coords(geom) -> np.ndarray:
    return shapely.get_coordinates(geom)


def exact(alpha) -> Fraction:
    return Fraction(repr(alpha)) if isinstance(alpha, float) else Fraction(alpha)


# ---------------------------------------------------------------------------------------------- the contract
@settings(max_examples=40)
@given(star_polygons(max_vertices=6, max_radius=4.0), st.sampled_from(SMALL_ALPHAS), st.sampled_from(MODELS))
def test_simplification_is_the_scaled_back_continuation_of_the_scaled_discretization(poly, alpha, model):
    out = simplification(poly, alpha, None, model)
    a = exact(alpha)
    # D(Sc_α(E)), by the definitions
    assert out.discrete == reference_discretize_rings(scaled(polygons_of(poly), a), model)
    # and the result is Sc_1/α of its continuation, vertex for vertex (rounded once to float64)
    back = scaled(polygons_of(reconstruct(out.discrete, model)), 1 / a)
    expected = np.array([(float(x), float(y)) for p in back for r in p for x, y in r]).reshape(-1, 2)
    assert np.array_equal(coords(out.result), expected)


@settings(max_examples=80)
@given(star_polygons(max_vertices=7, max_radius=5.0), st.sampled_from(ALPHAS), st.sampled_from(MODELS))
def test_simplifying_twice_is_simplifying_once(poly, alpha, model):
    once = simplification(poly, alpha, None, model).result
    twice = simplification(once, alpha, None, model).result
    assert np.array_equal(coords(once), coords(twice))


@settings(max_examples=30)
@given(
    star_polygons(max_vertices=6, max_radius=4.0), st.sampled_from([0.5, 1, 2, 0.3]), st.sampled_from(MODELS)
)
def test_the_simplification_stays_within_the_papers_bound(poly, alpha, model):
    # Theorem 15: H(E, Sp_α(E)) ≤ √2/α for the cover models; under gauss every point of the result is
    # within √2/α of E (the one direction that model keeps).
    out = simplification(poly, alpha, None, model)
    m = measured_error(poly, out.euclidean)
    coefficient = 1 / exact(alpha)
    if model in COVERS:
        assert not m.exceeds(coefficient)
    else:
        assert not m.exceeds(coefficient, direction="result_within")
    assert m.value <= math.sqrt(2) / float(alpha) * (1 + 1e-12) or model == "gauss"


def test_a_coarse_simplification_removes_a_small_hole_and_keeps_the_shape():
    outer = [(0, 0), (20, 0), (20, 12), (0, 12)]
    hole = [(9, 5), (10.5, 5), (10.5, 6.5), (9, 6.5)]
    poly = shapely.Polygon(outer, [hole])
    out = simplification(poly, 0.25, None, "standard").result
    assert len(out.interiors) == 0  # a 1.5-wide hole is below the 4-unit grid
    assert discretize(out, "standard").issubset(discretize(poly.buffer(2 * 4 * math.sqrt(2)), "standard"))


def test_a_pixel_input_is_simplified_through_its_continuation():
    a = PixelSet.box(0, 0, 7, 4)
    res = run_operation("simplify", [a], SimplifyParams(alpha=0.5))
    assert np.array_equal(coords(res.output), coords(simplification(reconstruct(a), 0.5).result))
    assert res.provenance == {
        "operation": "simplify",
        "params": {"alpha": 0.5, "center": None, "model": "standard"},
        "inputs": [{"input": 0}],
    }


def test_errors_name_the_parameter():
    tri = shapely.Polygon([(0, 0), (4, 0), (0, 3)])
    for bad in (0, -2, float("nan"), float("-inf"), "x"):
        with pytest.raises(ParameterError, match="alpha"):
            simplification(tri, bad)


# Valid shapes with a coordinate of 3·2⁻⁴⁰⁰: D takes them (|v| ≥ 2⁻⁴⁰⁰), and Sc_α for α < 1/3 moves it below.
TINY = 3 * 2.0**-400
TINY_SHAPES = {
    "triangle": shapely.Polygon([(0, 0), (TINY, 0), (0, TINY)]),
    "sliver": shapely.Polygon([(0, 0), (8, 0), (8, TINY)]),
}


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("alpha", [0.25, "1/524288"])
@pytest.mark.parametrize("name", TINY_SHAPES)
def test_a_tiny_but_valid_shape_is_simplified_exactly_not_refused(name, alpha, model):
    """Issue 32: Sc_α(E) had a coordinate below 2⁻⁴⁰⁰, which D's float kernels refuse ("too close to 0")."""
    poly = TINY_SHAPES[name]
    discretize(poly, model)  # the input is one D takes
    out = simplification(poly, alpha, None, model)
    a = exact(alpha)
    assert out.discrete == reference_discretize_rings(scaled(polygons_of(poly), a), model)
    back = scaled(polygons_of(reconstruct(out.discrete, model)), 1 / a)
    expected = np.array([(float(x), float(y)) for p in back for r in p for x, y in r]).reshape(-1, 2)
    assert np.array_equal(coords(out.result), expected)
