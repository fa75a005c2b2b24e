"""dR_θ,C(A) = D(rot_θ,C(R(A))): exact quarter turns about pixel centres, and the exact rational rotation."""

from __future__ import annotations

import math
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import ParameterError
from mrm.core.grids import PixelSet
from mrm.geometry.discretize.exact_shape import rotation_cos_sin
from mrm.geometry.reconstruct import reconstruct
from mrm.ops.registry import run_operation
from mrm.ops.rotation import RotationParams, discrete_rotation
from tests.oracles.ops_reference import (
    MODELS,
    objects,
    pixel_sets,
    polygons_of,
    reference_discretize_rings,
    rotated,
)

# ---------------------------------------------------------------------------------------------- quarter turns


@settings(max_examples=60)
@given(
    pixel_sets(max_side=7),
    st.integers(-3, 5),
    st.tuples(st.integers(-4, 4), st.integers(-4, 4)),
    st.sampled_from(MODELS),
)
def test_a_quarter_turn_about_a_pixel_centre_is_the_pixel_rotation(a, k, center, model):
    out = discrete_rotation(a, 90 * k, center, model)
    assert out.result == a.rotate90(k % 4, center)


@settings(max_examples=30)
@given(objects(), st.sampled_from(MODELS))
def test_a_half_turn_about_a_pixel_corner_is_exact_too(a, model):
    # rot_180 about (½, ½) maps pixel corners to pixel corners: p ↦ (1, 1) − p on pixels.
    out = discrete_rotation(a, 180, (0.5, 0.5), model)
    expected = PixelSet.from_points([(1 - x, 1 - y) for x, y in a.points()])
    assert out.result == expected


def test_quarter_turn_cos_sin_are_exact():
    for deg, cs in ((0, (1, 0)), (90, (0, 1)), (180, (-1, 0)), (270, (0, -1)), (-90, (0, -1)), (450, (0, 1))):
        assert rotation_cos_sin(Fraction(deg)) == (Fraction(cs[0]), Fraction(cs[1]))


@settings(max_examples=200)
@given(st.floats(-720, 720, allow_nan=False))
def test_the_rotation_applied_is_an_exact_isometry_at_the_asked_angle(deg):
    c, s = rotation_cos_sin(Fraction(repr(deg)))
    assert c * c + s * s == 1
    err = math.remainder(math.atan2(float(s), float(c)) - math.radians(deg), 2 * math.pi)
    assert abs(err) < 1e-14


# ---------------------------------------------------------------------------------------------- the contract
@settings(max_examples=80)
@given(
    objects(),
    st.sampled_from([30, -17.5, 45, 123.25, 200, 1e-3]),
    st.tuples(st.sampled_from([0, 2, -1.5, 0.3]), st.sampled_from([0, 1, 2.5, -0.7])),
    st.sampled_from(MODELS),
)
def test_discrete_rotation_is_exactly_D_of_the_rotated_continuation(a, deg, center, model):
    out = discrete_rotation(a, deg, center, model)
    c, s = rotation_cos_sin(Fraction(repr(deg)))
    cx, cy = (Fraction(repr(v)) for v in center)
    reference = reference_discretize_rings(rotated(polygons_of(reconstruct(a, model)), c, s, (cx, cy)), model)
    assert out.result == reference


def test_rotating_back_composes_to_the_identity_exactly():
    a = PixelSet.box(0, 0, 3, 1)
    fwd = discrete_rotation(a, 37.5, (3, -1)).transform
    back = discrete_rotation(a, -37.5, (3, -1)).transform
    assert fwd.then(back).is_identity


def test_run_and_provenance():
    a = PixelSet.from_points([(0, 0), (1, 0), (2, 0), (2, 1)])
    res = run_operation("discrete_rotation", [a], RotationParams(angle=90.0, center=(1.0, 0.0)))
    assert res.output == a.rotate90(1, (1, 0))
    assert res.provenance["operation"] == "discrete_rotation"
    assert res.provenance["params"] == {
        "angle": 90.0,
        "center": [1.0, 0.0],
        "model": "standard",
        "axis": None,
    }


def test_angle_errors_name_the_parameter():
    a = PixelSet.box(0, 0, 2, 2)
    for bad in (float("nan"), float("inf"), "ten", None):
        with pytest.raises(ParameterError, match="angle"):
            discrete_rotation(a, bad)
    with pytest.raises(ParameterError, match="center"):
        discrete_rotation(a, 10, (1, float("nan")))
    with pytest.raises(ParameterError, match="center"):
        discrete_rotation(a, 10, (1, 2, 3))
