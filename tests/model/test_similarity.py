"""Euclidean similarities: correctly rounded translations and scalings, exact quarter turns."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely import affinity
from shapely.geometry import MultiPolygon, Polygon, box

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.ops import similarity
from mrm.ops.registry import get_operation, run_operation
from mrm.ops.similarity import rotate_geometry, scale_geometry, translate_geometry

finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False)
dyadic = st.integers(-4000, 4000).map(lambda n: n / 8)


def coords(g: shapely.Geometry) -> np.ndarray:
    return shapely.get_coordinates(g)


points3 = st.lists(st.tuples(finite, finite), min_size=3, max_size=3)


def exact_image(v: float, c_in: float, s: Fraction, c_out: float) -> float:
    """The reference: c_out + s·(v − c_in) in rationals, rounded once."""
    return float(Fraction(c_out) + s * (Fraction(v) - Fraction(c_in)))


@settings(max_examples=80)
@given(points3, finite, finite)
def test_translation_is_correctly_rounded(pts: list[tuple[float, float]], dx: float, dy: float) -> None:
    g = shapely.MultiPoint(pts)
    out = coords(translate_geometry(g, dx, dy))
    for (x, y), (ox, oy) in zip(coords(g), out, strict=True):
        assert ox == exact_image(x, 0, Fraction(1), dx) and oy == exact_image(y, 0, Fraction(1), dy)


@settings(max_examples=80)
@given(
    points3,
    st.floats(min_value=1e-3, max_value=1e3, allow_nan=False),
    st.tuples(finite, finite) | st.tuples(dyadic, dyadic),
)
def test_scaling_is_correctly_rounded(
    pts: list[tuple[float, float]], s: float, c: tuple[float, float]
) -> None:
    g = shapely.MultiPoint(pts)  # any geometry: the map acts on coordinates (a sliver polygon may flip)
    out = coords(scale_geometry(g, s, c))
    for (x, y), (ox, oy) in zip(coords(g), out, strict=True):
        assert ox == exact_image(x, c[0], Fraction(s), c[0])
        assert oy == exact_image(y, c[1], Fraction(s), c[1])


@settings(max_examples=80)
@given(
    st.lists(st.tuples(dyadic, dyadic), min_size=3, max_size=8), st.tuples(dyadic, dyadic), st.integers(-9, 9)
)
def test_quarter_turns_are_exact(pts: list[tuple[float, float]], c: tuple[float, float], k: int) -> None:
    g = shapely.MultiPoint(pts)  # any geometry: the map acts on coordinates
    out = coords(rotate_geometry(g, 90 * k, c))
    turns = k % 4
    for (x, y), (ox, oy) in zip(coords(g), out, strict=True):
        dx, dy = Fraction(x) - Fraction(c[0]), Fraction(y) - Fraction(c[1])
        for _ in range(turns):
            dx, dy = -dy, dx
        assert (Fraction(ox), Fraction(oy)) == (Fraction(c[0]) + dx, Fraction(c[1]) + dy)


@settings(max_examples=60)
@given(points3, st.tuples(finite, finite), st.integers(1, 3))
def test_quarter_turns_of_any_floats_are_correctly_rounded(
    pts: list[tuple[float, float]], c: tuple[float, float], k: int
) -> None:
    g = shapely.MultiPoint(pts)
    out = coords(rotate_geometry(g, 90 * k, c))
    for (x, y), (ox, oy) in zip(coords(g), out, strict=True):
        dx, dy = Fraction(x) - Fraction(c[0]), Fraction(y) - Fraction(c[1])
        for _ in range(k):
            dx, dy = -dy, dx
        assert (ox, oy) == (float(Fraction(c[0]) + dx), float(Fraction(c[1]) + dy))


@settings(max_examples=40)
@given(st.lists(st.tuples(dyadic, dyadic), min_size=3, max_size=6), st.tuples(dyadic, dyadic))
def test_four_quarter_turns_are_the_identity_on_dyadic_data(
    pts: list[tuple[float, float]], c: tuple[float, float]
) -> None:
    g = shapely.MultiPoint(pts)
    out = g
    for _ in range(4):
        out = rotate_geometry(out, 90, c)
    assert np.array_equal(coords(out), coords(g))
    assert np.array_equal(coords(rotate_geometry(rotate_geometry(g, 90, c), -90, c)), coords(g))


def test_a_quarter_turn_about_a_pixel_centre_is_exact() -> None:
    g = Polygon([(0.5, 0.5), (3.5, 0.5), (3.5, 1.5)])
    ours = rotate_geometry(g, 90, (1, 1))
    assert coords(ours).tolist() == [[1.5, 0.5], [1.5, 3.5], [0.5, 3.5], [1.5, 0.5]]
    theirs = affinity.rotate(g, 90, origin=(1, 1))
    assert np.allclose(coords(theirs), coords(ours), atol=1e-12)


@settings(max_examples=60)
@given(points3, st.floats(min_value=-720, max_value=720, allow_nan=False), st.tuples(dyadic, dyadic))
def test_other_rotations_are_within_a_few_ulps(
    pts: list[tuple[float, float]], angle: float, c: tuple[float, float]
) -> None:
    g = shapely.MultiPoint(pts)
    out = coords(rotate_geometry(g, angle, c))
    t = math.radians(angle)
    co, si = Fraction(math.cos(t)), Fraction(math.sin(t))
    for (x, y), (ox, oy) in zip(coords(g), out, strict=True):
        dx, dy = Fraction(x) - Fraction(c[0]), Fraction(y) - Fraction(c[1])
        ex = Fraction(c[0]) + co * dx - si * dy
        ey = Fraction(c[1]) + si * dx + co * dy
        scale = max(abs(x - c[0]), abs(y - c[1]), abs(c[0]), abs(c[1]), 1e-300)
        assert abs(float(ex - Fraction(ox))) <= 8 * math.ulp(scale)
        assert abs(float(ey - Fraction(oy))) <= 8 * math.ulp(scale)


def test_holes_and_multipolygons_keep_their_structure_and_validity() -> None:
    ring = box(0, 0, 10, 10)
    holed = Polygon(ring.exterior.coords, [box(2, 2, 4, 4).exterior.coords, box(6, 6, 8, 7).exterior.coords])
    mp = MultiPolygon([holed, box(20, 0, 21, 1)])
    for out in (
        translate_geometry(mp, 0.25, -3),
        scale_geometry(mp, 0.5, (1, 1)),
        rotate_geometry(mp, -90, (0.5, 0.5)),
        rotate_geometry(mp, 33, (0, 0)),
    ):
        assert isinstance(out, MultiPolygon) and out.is_valid
        assert [len(p.interiors) for p in out.geoms] == [2, 0]
    assert scale_geometry(mp, 3.0).area == pytest.approx(9 * mp.area)
    assert rotate_geometry(Polygon(), 90).is_empty


def test_bad_parameters() -> None:
    g = box(0, 0, 1, 1)
    with pytest.raises(ParameterError, match="positive"):
        scale_geometry(g, 0.0)
    with pytest.raises(ParameterError, match="finite"):
        scale_geometry(g, float("nan"))
    with pytest.raises(ParameterError, match="finite"):
        rotate_geometry(g, float("inf"))
    with pytest.raises(ParameterError, match="finite"):
        translate_geometry(g, 1.0, float("-inf"))
    with pytest.raises(ParameterError, match="centre"):
        scale_geometry(g, 2.0, (float("nan"), 0))
    with pytest.raises(InvalidGeometryError, match="overflow"):
        scale_geometry(box(0, 0, 1e300, 1e300), 1e10)


def test_as_operations() -> None:
    g = box(0, 0, 2, 1)
    res = run_operation("rotate", [g], similarity.RotateParams(angle=180, center=(1.0, 0.5)))
    assert res.output.equals(g) and res.outputs[0][0] == "rotated"
    assert res.provenance == {
        "operation": "rotate",
        "params": {"angle": 180, "center": [1.0, 0.5]},
        "inputs": [{"input": 0}],
    }
    assert res.bound is not None and res.bound.bound == 0.0
    res = run_operation("scale", [g], similarity.ScaleParams(factor=0.5, center=(0.0, 0.0)))
    assert res.output.equals(box(0, 0, 1, 0.5))
    with pytest.raises(ParameterError, match=r"'factor' must be ≥ 1e-06, got -2"):
        run_operation("scale", [g], similarity.ScaleParams(factor=-2.0))
    with pytest.raises(ParameterError, match="'angle'"):
        run_operation("rotate", [g], similarity.RotateParams(angle=float("nan")))


def chain_step(operation: str, geom: object, **params: object) -> object:
    """The operation as a step of a chain (what the account recomputes), read from JSON-like values."""
    spec = get_operation(operation)
    return spec.outcome(geom, spec.read_params(params)).result


def test_the_registry_and_the_chain_read_parameters_the_same_way() -> None:
    """One arithmetic: 0.4 is 2/5 and a rotation is the exact rational one on every path."""
    from fractions import Fraction

    from mrm.geometry.discretize.exact_shape import ExactShape, Similarity

    g = box(0, 0, 3, 3)
    res = run_operation("scale", [g], similarity.ScaleParams(factor=0.4, center=(0.0, 0.0)))
    assert res.output.bounds == (0.0, 0.0, 1.2, 1.2)  # the float nearest to 3·2/5, not 3·fl(0.4)
    assert res.output.equals_exact(chain_step("scale", g, factor=0.4), 0.0)
    assert res.bound is not None and res.bound.steps[0].label == "SCALE 0.4"
    assert similarity.ScaleParams(factor=0.4).factor == Fraction(2, 5)
    rot = run_operation("rotate", [g], similarity.RotateParams(angle=30.0, center=(1.0, 1.0)))
    exact = ExactShape.from_geometry(g).map(Similarity.rotation(Fraction(30), (Fraction(1), Fraction(1))))
    assert rot.output.equals_exact(exact.to_geometry(), 0.0)
    assert rot.output.equals_exact(chain_step("rotate", g, angle=30.0, center=(1.0, 1.0)), 0.0)


decimal_factor = st.integers(1, 10**6).map(lambda n: n / 1000)  # 0.001 … 1000 as the user types them
decimal_angle = st.integers(-36000, 36000).map(lambda n: n / 10)


@settings(max_examples=60, deadline=None)
@given(dyadic, dyadic, st.integers(1, 40), st.integers(1, 40), decimal_factor, dyadic, dyadic)
def test_the_registry_scale_reads_the_decimal_and_rounds_once(x0, y0, w, h, factor, cx, cy) -> None:
    """``scale`` by 0.4 is the exact scaling by 2/5, each coordinate rounded once, as the chain's step."""
    g = box(x0, y0, x0 + w, y0 + h)
    res = run_operation("scale", [g], {"factor": factor, "center": (cx, cy)})
    q = Fraction(repr(factor))
    expected = {(exact_image(x, cx, q, cx), exact_image(y, cy, q, cy)) for x, y in coords(g)}
    assert {tuple(v) for v in coords(res.output)} == expected
    assert res.output.equals_exact(chain_step("scale", g, factor=factor, center=(cx, cy)), 0.0)


@settings(max_examples=60, deadline=None)
@given(dyadic, dyadic, st.integers(1, 40), st.integers(1, 40), decimal_angle, dyadic, dyadic)
def test_the_registry_rotate_is_the_exact_rational_rotation_rounded_once(x0, y0, w, h, angle, cx, cy) -> None:
    """``rotate`` applies the chain step's exact rational rotation (rational cos, sin), rounded once."""
    from mrm.geometry.discretize.exact_shape import rotation_cos_sin

    g = box(x0, y0, x0 + w, y0 + h)
    res = run_operation("rotate", [g], {"angle": angle, "center": (cx, cy)})
    c, s = rotation_cos_sin(Fraction(repr(angle)))
    assert c * c + s * s == 1  # an isometry, exactly
    fx, fy = Fraction(cx), Fraction(cy)
    expected = {
        (
            float(fx + c * (Fraction(x) - fx) - s * (Fraction(y) - fy)),
            float(fy + s * (Fraction(x) - fx) + c * (Fraction(y) - fy)),
        )
        for x, y in coords(g)
    }
    assert {tuple(v) for v in coords(res.output)} == expected
    assert res.output.equals_exact(chain_step("rotate", g, angle=angle, center=(cx, cy)), 0.0)
