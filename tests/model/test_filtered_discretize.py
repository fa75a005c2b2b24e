"""The float-filtered exact discretization of similarity images (rotations; scalings beyond int64).

``mrm.geometry.discretize.rational.filtered_image`` decides D(T(E)) from float64 images of the vertices with a
proven error bound and hands the edges with a near-tie to the integer definitions. Every test compares it
with the slow Fraction reference of tests/oracles (the definitions of docs/design.md §2 on the exact rational
image) and with the Python-integer path, on random and adversarial input: vertices on pixel centres, sides
and corners, near-ties, exact ties made by a Pythagorean rotation, objects far from the origin.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from shapely.geometry import Polygon

import mrm.geometry.discretize.rational as rational
import mrm.geometry.discretize.rational_kernels as grd
from mrm.core.grids import PixelSet
from mrm.geometry.discretize.exact_shape import ExactShape, Similarity, rotation_cos_sin
from mrm.geometry.discretize.rational import discretize_exact, discretize_image
from mrm.geometry.reconstruct import reconstruct
from mrm.ops.rotation import discrete_rotation
from mrm.ops.scaling import discrete_smooth_scaling
from tests.oracles.geometry_strategies import star_polygons
from tests.oracles.ops_reference import (
    MODELS,
    objects,
    polygons_of,
    reference_discretize_rings,
    rotated,
    scaled,
)

Q = Fraction

ANGLES = [30, -17.5, 45, 123.25, 200, 1e-3, 89.999, 0.5, -44.75]
CENTRES = [(0, 0), (0.5, 0.5), (2, -1), (-1.5, 0.3), (0.25, 3.75)]


def _image_rings(poly, sim):
    """The exact image of a shapely polygon's rings under ``sim``, as the reference reads them."""
    return [[[sim(p) for p in ring] for ring in rings] for rings in polygons_of(poly)]


def _counting(monkeypatch):
    """Count the edges the filtered path hands to the exact integer definitions (where it calls them)."""
    calls = {"crossings": 0, "walks": 0}
    crossings, walks = grd.integer_crossings, grd.integer_walks

    def counted_crossings(*args):
        calls["crossings"] += 1
        return crossings(*args)

    def counted_walks(*args):
        calls["walks"] += 1
        return walks(*args)

    monkeypatch.setattr(rational, "integer_crossings", counted_crossings)
    monkeypatch.setattr(rational, "integer_walks", counted_walks)
    return calls


@settings(max_examples=300, deadline=None)
@given(
    star_polygons(max_vertices=7, max_radius=5.0),
    st.sampled_from(ANGLES),
    st.sampled_from(CENTRES),
    st.sampled_from(MODELS),
)
def test_a_rotated_polygon_is_discretized_as_the_definition_says(poly, deg, centre, model):
    sim = Similarity.rotation(Q(repr(float(deg))), (Q(repr(float(centre[0]))), Q(repr(float(centre[1])))))
    got = discretize_image(poly, sim, model)
    assert got is not None
    c, s = rotation_cos_sin(Q(repr(float(deg))))
    cx, cy = (Q(repr(float(v))) for v in centre)
    assert got == reference_discretize_rings(rotated(polygons_of(poly), c, s, (cx, cy)), model)
    exact = ExactShape.from_geometry(poly).map(sim)
    assert got == discretize_exact(exact, model, force_integer=True, compiled=False)


@st.composite
def tie_polygons(draw):
    """Star polygons on the half-integer lattice scaled by 5 (or 10): their images under the rotation
    (c, s) = (3/5, 4/5) land on pixel centres, sides and corners."""
    poly = draw(star_polygons(max_vertices=6, max_radius=3.0, holes=False))
    factor = draw(st.sampled_from([5.0, 10.0]))
    snapped = shapely.transform(poly, lambda c: np.round(c * 2) / 2 * factor)
    assume(snapped.is_valid and not snapped.is_empty and snapped.area > 0)
    return snapped


@settings(max_examples=120, deadline=None)
@given(
    tie_polygons(),
    st.sampled_from([(Q(3, 5), Q(4, 5)), (Q(-4, 5), Q(3, 5)), (Q(5, 13), Q(-12, 13))]),
    st.tuples(st.integers(-4, 4), st.integers(-4, 4)).map(lambda t: (Q(t[0], 2), Q(t[1], 2))),
    st.sampled_from(MODELS),
)
def test_exact_ties_are_decided_by_the_integer_definitions(poly, cs, t, model):
    c, s = cs
    sim = Similarity(c, s, t[0], t[1], Q(1))
    got = discretize_image(poly, sim, model)
    assert got is not None
    assert got == reference_discretize_rings(_image_rings(poly, sim), model)


def test_the_tie_case_really_takes_the_exact_path(monkeypatch):
    # A square of side 10 on pixel centres, rotated by (3/5, 4/5): its vertices (0,0), (6,8), (−2,14), (−8,6)
    # are pixel centres, so every edge has a tie the float data cannot decide.
    calls = _counting(monkeypatch)
    poly = Polygon([(0, 0), (10, 0), (10, 10), (0, 10)])
    sim = Similarity(Q(3, 5), Q(4, 5), Q(0), Q(0), Q(1))
    for model in MODELS:
        got = discretize_image(poly, sim, model)
        assert got == reference_discretize_rings(_image_rings(poly, sim), model)
    assert calls["crossings"] > 0 and calls["walks"] > 0


def test_a_generic_rotation_decides_every_edge_in_float(monkeypatch):
    calls = _counting(monkeypatch)
    poly = Polygon([(0.3, 0.1), (40.7, 3.2), (35.1, 29.9), (2.2, 33.3)])
    sim = Similarity.rotation(Q(30), (Q(1, 2), Q(1, 2)))
    for model in MODELS:
        got = discretize_image(poly, sim, model)
        assert got == reference_discretize_rings(_image_rings(poly, sim), model)
    assert calls == {"crossings": 0, "walks": 0}


FAR = 2**30 + 12345


@settings(max_examples=60, deadline=None)
@given(
    objects(),
    st.sampled_from(ANGLES),
    st.sampled_from([(0.0, 0.0), (0.5, 0.5), (3.0, -2.5)]),
    st.sampled_from(MODELS),
    st.sampled_from([(FAR, -FAR), (-(2**31) + 64, 2**31 - 64)]),
)
def test_dr_far_from_the_origin_is_the_definition(a, deg, offset, model, where):
    """dR_θ,C of an object near the coordinate limits (±2³¹), rotated about a centre next to it."""
    far = a.translate(where[0], where[1])
    centre = (where[0] + offset[0], where[1] + offset[1])
    out = discrete_rotation(far, deg, centre, model)
    c, s = rotation_cos_sin(Q(repr(float(deg))))
    cx, cy = (Q(repr(float(v))) for v in centre)
    polys = rotated(polygons_of(reconstruct(far, model)), c, s, (cx, cy))
    assert out.result == reference_discretize_rings(polys, model)


@settings(max_examples=60, deadline=None)
@given(
    star_polygons(max_vertices=6, max_radius=4.0, holes=False),
    st.sampled_from([Q(1, 3), Q(5, 7), Q(9, 10)]),
    st.sampled_from(MODELS),
)
def test_a_scaling_beyond_int64_is_the_definition_too(poly, alpha, model):
    """Full-mantissa vertices near 2²⁹ scaled by 1/3: the int64 kernels would overflow, the filter decides."""
    far = shapely.affinity.translate(poly, 2.0**29 + 0.1, -(2.0**29) - 0.3)
    assume(far.is_valid)
    sim = Similarity.scaling(alpha, (Q(2**29), Q(0)))
    got = discretize_image(far, sim, model)
    assert got is not None
    assert got == reference_discretize_rings(_image_rings(far, sim), model)


@pytest.mark.parametrize("model", MODELS)
def test_dr_of_a_large_object_equals_the_python_integer_path(model):
    yy, xx = np.mgrid[0:120, 0:150]
    blob = ((xx - 70.3) ** 2 / 4900 + (yy - 58.1) ** 2 / 2500 <= 1) & ((xx + 2 * yy) % 37 > 3)
    a = PixelSet(blob, (-40, 17))
    for deg, centre in ((30, (511.5, 511.5)), (-73.25, (0, 0)), (0.001, (3.5, 2))):
        out = discrete_rotation(a, deg, centre, model)
        sim = Similarity.rotation(Q(repr(float(deg))), tuple(Q(repr(float(v))) for v in centre))
        exact = ExactShape.from_geometry(reconstruct(a, model)).map(sim)
        assert out.result == discretize_exact(exact, model, force_integer=True, compiled=False)


def test_dss_of_a_far_object_by_a_third_is_the_definition():
    a = PixelSet.box(0, 0, 4, 2).translate(2**30, 2**30)
    for model in MODELS:
        out = discrete_smooth_scaling(a, "1/3", None, model)
        polys = scaled(polygons_of(reconstruct(a, model)), Q(1, 3))
        assert out.result == reference_discretize_rings(polys, model)


@settings(max_examples=150, deadline=None)
@given(
    st.one_of(tie_polygons(), star_polygons(max_vertices=6, max_radius=4.0)),
    st.sampled_from(
        [
            Similarity(Q(3, 5), Q(4, 5), Q(1, 2), Q(-3, 2), Q(1)),
            Similarity.rotation(Q(30), (Q(1, 3), Q(2, 7))),
            Similarity.scaling(Q(1, 3), (Q(2**30), Q(-(2**30)))),
            Similarity.rotation(Q("-73.25"), (Q(2**31 - 7), Q(0))),
        ]
    ),
    st.sampled_from(MODELS),
)
def test_rational_shapes_by_the_filter_are_the_definition(poly, sim, model):
    """discretize_exact of an ExactShape with non-float64 coordinates (an account's T(A_first))."""
    exact = ExactShape.from_geometry(poly).map(sim)
    assume(not exact.is_float_exact())
    got = discretize_exact(exact, model)
    assert got == reference_discretize_rings(_image_rings(poly, sim), model)
    assert got == discretize_exact(exact, model, force_integer=True, compiled=False)
