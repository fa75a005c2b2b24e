"""Bad input, empty input, size limits and the box helpers of mrm.geometry.discretize."""

from __future__ import annotations

import math
import tracemalloc

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import InvalidGeometryError, MRMError, ParameterError, SizeLimitError
from mrm.core.limits import DEFAULT_PIXEL_LIMIT
from mrm.core.models import Model
from mrm.geometry.discretize import (
    _ring_proved_simple,
    discretization_box,
    discretize,
    discretize_segment,
    estimate_pixels,
)
from tests.oracles.geometry_strategies import point_sets, polygonal, polylines

MODELS = Model.names()

NAN = float("nan")
INF = float("inf")


# ------------------------------------------------------------------------------------ invalid input
def test_self_intersecting_polygon_is_refused_with_a_repair_hint() -> None:
    bowtie = shapely.Polygon([(0, 0), (2, 2), (2, 0), (0, 2)])
    with pytest.raises(InvalidGeometryError) as err:
        discretize(bowtie)
    msg = str(err.value)
    assert "Self-intersection" in msg
    assert "make_valid" in msg and "buffer(0)" in msg
    assert "(1, 1)" in msg  # where the ring crosses itself


@pytest.mark.parametrize(
    "geom",
    [
        shapely.Polygon([(0, 0), (4, 0), (4, 4), (0, 4)], [[(5, 5), (6, 5), (6, 6)]]),  # hole outside shell
        shapely.MultiPolygon([shapely.box(0, 0, 2, 2), shapely.box(1, 1, 3, 3)]),  # overlapping parts
        shapely.GeometryCollection(
            [shapely.Polygon([(0, 0), (2, 2), (2, 0), (0, 2)])]
        ),  # inside a collection
        shapely.Polygon([(0, 0), (1, 0), (2, 0), (0, 0)]),  # zero area
    ],
)
def test_invalid_polygons_are_refused(geom) -> None:  # type: ignore[no-untyped-def]
    for model in MODELS:
        with pytest.raises(InvalidGeometryError, match="make_valid"):
            discretize(geom, model)


@pytest.mark.filterwarnings("ignore:invalid value encountered:RuntimeWarning")
@pytest.mark.parametrize("bad", [NAN, INF, -INF])
@pytest.mark.parametrize(
    "build",
    [
        lambda v: shapely.Polygon([(0, 0), (4, 0), (v, 4)]),
        lambda v: shapely.LineString([(0, 0), (v, 1)]),
        lambda v: shapely.MultiPoint([(0, 0), (1, v)]),
    ],
)
def test_non_finite_coordinates_are_refused(build, bad) -> None:  # type: ignore[no-untyped-def]
    geom = build(bad)
    with pytest.raises(InvalidGeometryError, match="non-finite"):
        discretize(geom)
    with pytest.raises(InvalidGeometryError, match="non-finite"):
        discretize_segment((0.0, 0.0), (bad, 1.0))


def test_out_of_range_coordinates_are_refused() -> None:
    with pytest.raises(InvalidGeometryError, match="too large"):
        discretize(shapely.Point(1e16, 0))
    with pytest.raises(InvalidGeometryError, match="too close to 0"):
        discretize(shapely.LineString([(0, 0), (1e-200, 1)]))
    # The limits themselves are fine.
    assert discretize(shapely.Point(2.0**51, -(2.0**51))).points().tolist() == [[2**51, -(2**51)]]
    assert len(discretize(shapely.LineString([(0, 0), (2.0**-400, 1)]))) == 2


def test_unknown_model_and_bad_limit_are_parameter_errors() -> None:
    square = shapely.box(0, 0, 1, 1)
    with pytest.raises(ParameterError, match="standard, supercover, gauss"):
        discretize(square, "naive")
    # A model's name is read as people write it, in any case (mrm.core.models.Model.parse).
    assert discretize_segment((0, 0), (1, 1), "Standard") == discretize_segment((0, 0), (1, 1), "standard")
    with pytest.raises(ParameterError):
        discretize(square, limit=-1)


def test_non_geometry_input_is_refused() -> None:
    with pytest.raises(InvalidGeometryError, match="shapely geometry"):
        discretize([(0, 0), (1, 1)])


def test_user_errors_are_mrm_errors() -> None:
    for exc in (InvalidGeometryError, ParameterError, SizeLimitError):
        assert issubclass(exc, MRMError)


# -------------------------------------------------------------------------------------- empty input
@pytest.mark.parametrize(
    "geom",
    [
        shapely.Polygon(),
        shapely.MultiPolygon(),
        shapely.LineString(),
        shapely.Point(),
        shapely.MultiPoint(),
        shapely.GeometryCollection(),
        shapely.GeometryCollection([shapely.Polygon(), shapely.LineString()]),
    ],
)
def test_empty_geometry_gives_the_empty_set(geom) -> None:  # type: ignore[no-untyped-def]
    for model in MODELS:
        assert discretize(geom, model).is_empty()
    assert estimate_pixels(geom) == 0
    assert discretization_box(geom) is None


def test_gauss_of_a_sliver_between_centres_is_empty() -> None:
    sliver = shapely.Polygon([(0.1, 0.1), (5.9, 0.2), (0.1, 0.3)])
    assert discretize(sliver, "gauss").is_empty()
    assert len(discretize(sliver, "standard")) == 7  # x = 0.1 … 5.9 lies in the cells of pixels 0 … 6


# -------------------------------------------------------------------------------------- size limits
def test_huge_polygon_is_refused_before_allocating() -> None:
    huge = shapely.box(0, 0, 1e6, 1e6)
    expected = (10**6 + 1) ** 2  # pixels 0..10^6 in each direction
    tracemalloc.start()
    try:
        with pytest.raises(SizeLimitError) as err:
            discretize(huge)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert err.value.estimated == expected
    assert err.value.limit == DEFAULT_PIXEL_LIMIT
    assert f"{expected:,}" in str(err.value)
    assert peak < 1_000_000  # nothing of the result's size was allocated


def test_limit_is_the_box_area() -> None:
    square = shapely.box(0, 0, 9, 9)  # pixels 0..9: 100 in every model
    for model in MODELS:
        assert len(discretize(square, model, limit=100)) > 0
        with pytest.raises(SizeLimitError):
            discretize(square, model, limit=99)
    assert len(discretize(square, limit=None)) == 100
    on_sides = shapely.box(0.5, 0.5, 9.5, 9.5)  # closed squares reach pixels 0..10
    assert estimate_pixels(on_sides) == 121
    with pytest.raises(SizeLimitError):
        discretize(on_sides, "supercover", limit=120)
    assert len(discretize(on_sides, "standard", limit=100)) == 100
    diagonal = ((0.0, 0.0), (1e5, 1e5))  # a thin result still needs its whole box
    with pytest.raises(SizeLimitError):
        discretize_segment(*diagonal)


# -------------------------------------------------------------------------------------------- boxes
@settings(max_examples=60)
@given(st.one_of(polygonal(), polylines(), point_sets()))
def test_boxes_are_tight_for_covers_and_contain_gauss(geom) -> None:  # type: ignore[no-untyped-def]
    for model in ("standard", "supercover"):
        assert discretize(geom, model).bbox == discretization_box(geom, model)
    gauss = discretize(geom, "gauss").bbox
    std_box = discretization_box(geom, "standard")
    if gauss is not None:
        assert std_box is not None
        assert std_box[0] <= gauss[0] and std_box[1] <= gauss[1]
        assert gauss[2] <= std_box[2] and gauss[3] <= std_box[3]
    sup_box = discretization_box(geom, "supercover")
    assert sup_box is not None
    assert estimate_pixels(geom) == (sup_box[2] - sup_box[0] + 1) * (sup_box[3] - sup_box[1] + 1)


def test_box_of_points_on_pixel_sides() -> None:
    assert discretization_box(shapely.Point(0.5, -0.5), "standard") == (0, -1, 0, -1)
    assert discretization_box(shapely.Point(0.5, -0.5), "supercover") == (0, -1, 1, 0)


# ----------------------------------------------------------------------------------- validity sweep
@st.composite
def rings(draw):  # type: ignore[no-untyped-def]
    """Random rings, mostly invalid, many degenerate: lattice points (touching, collinear, repeated
    vertices) or star-shaped ones pushed around."""
    n = draw(st.integers(3, 14))
    kind = draw(st.sampled_from(["grid", "half", "float", "star"]))
    if kind == "star":
        ang = sorted(draw(st.lists(st.integers(0, 359), min_size=n, max_size=n, unique=True)))
        rad = draw(st.lists(st.integers(1, 4), min_size=n, max_size=n))
        pts = [
            (round(r * math.cos(math.radians(a)) * 2) / 2, round(r * math.sin(math.radians(a)) * 2) / 2)
            for a, r in zip(ang, rad, strict=True)
        ]
    else:
        coord = {
            "grid": st.integers(0, 3).map(float),
            "half": st.integers(0, 6).map(lambda k: k / 2),
            "float": st.floats(0, 4),
        }[kind]
        pts = [(draw(coord), draw(coord)) for _ in range(n)]
    return pts


@settings(max_examples=600)
@given(rings())
def test_ring_sweep_never_accepts_an_invalid_ring(pts) -> None:  # type: ignore[no-untyped-def]
    if _ring_proved_simple(np.asarray(pts, dtype=float)):
        assert shapely.Polygon(pts).is_valid, shapely.is_valid_reason(shapely.Polygon(pts))


def test_ring_sweep_proves_generic_star_polygons() -> None:
    rng = np.random.default_rng(5)
    for n in (3, 10, 100, 1000):
        ang = np.sort(rng.uniform(0, 2 * np.pi, n))
        rad = rng.uniform(0.2, 1.0, n) * 100
        pts = np.c_[rad * np.cos(ang), rad * np.sin(ang)]
        assert shapely.Polygon(pts).is_valid
        assert _ring_proved_simple(pts)


@pytest.mark.parametrize("defect", ["crossing", "touching", "fold"])
def test_large_invalid_rings_are_refused(defect: str) -> None:
    # Large enough (≥ 64 vertices) for the sweep to run first; it must leave the verdict to GEOS.
    n = 100
    ang = np.linspace(0, 2 * np.pi, n, endpoint=False)
    pts = np.c_[50 * np.cos(ang), 50 * np.sin(ang)].round(3)
    if defect == "crossing":
        pts[10] = (-60.0, 3.0)
    elif defect == "touching":
        pts[10] = ((pts[40] + pts[41]) / 2).tolist()  # a vertex on another edge
        pts[10] = [float(v) for v in pts[10]]
    else:
        pts[11] = pts[9]  # the ring runs back over itself
    poly = shapely.Polygon(pts)
    assert not poly.is_valid
    with pytest.raises(InvalidGeometryError, match="make_valid"):
        discretize(poly)
