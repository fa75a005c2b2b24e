"""The exact discretization against the Fraction reference (docs/design.md §2), on random and adversarial
input.

Each geometry is checked in the three models and along both arithmetic paths of the kernels: the automatic
choice (plain float arithmetic when it is provably exact, e.g. for snapped input) and the forced
float-filter + exact-expansion path, which snapped input drives through ties at every pixel side and corner.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.models import Model
from mrm.geometry.discretize import _discretize_pieces, _take_apart, discretize, discretize_segment
from mrm.geometry.discretize import _kernels as kernels
from mrm.geometry.discretize.exact import cell_index, closed_cell_range, float_predicates_are_exact
from tests.oracles.discretize_reference import reference_discretize, reference_segment
from tests.oracles.geometry_strategies import (
    floats,
    point_sets,
    polygonal,
    polylines,
    segments,
    slivers,
    snapper,
    star_polygons,
)

MODELS = Model.names()


def as_set(ps):  # type: ignore[no-untyped-def]
    return {(int(x), int(y)) for x, y in ps.points()}


def both_paths(geom, model):  # type: ignore[no-untyped-def]
    """D(geom) by the public function and by the forced filter/expansion path."""
    public = as_set(discretize(geom, model))
    filtered = as_set(_discretize_pieces(_take_apart(geom), model, None, exact_mode=False))
    return public, filtered


def assert_matches_reference(geom) -> None:  # type: ignore[no-untyped-def]
    for model in MODELS:
        expected = reference_discretize(geom, model)
        public, filtered = both_paths(geom, model)
        assert public == expected, (model, geom.wkt, sorted(public ^ expected))
        assert filtered == expected, (model, "filtered path", geom.wkt, sorted(filtered ^ expected))


# ----------------------------------------------------------------------------------------- polygons
@settings(max_examples=120)
@given(polygonal())
def test_polygons_match_reference(poly) -> None:  # type: ignore[no-untyped-def]
    assert_matches_reference(poly)


@settings(max_examples=40)
@given(st.lists(star_polygons(max_vertices=6, max_radius=3.0, holes=False), min_size=2, max_size=3))
def test_multipolygons_and_overlapping_collections_match_reference(polys) -> None:  # type: ignore[no-untyped-def]
    # Shifted copies: a collection may overlap (its D is the union); a MultiPolygon must be valid.
    shifted = [shapely.transform(p, lambda c, k=k: c + 9.0 * k) for k, p in enumerate(polys)]
    multi = shapely.MultiPolygon(shifted)
    if multi.is_valid:
        assert_matches_reference(multi)
    assert_matches_reference(shapely.GeometryCollection(polys))


def test_hand_picked_ties() -> None:
    cases = [
        shapely.box(0.5, 0.5, 3.5, 2.5),  # edges on pixel sides
        shapely.box(0, 0, 3, 2),  # edges through pixel centres
        shapely.Polygon([(0, 0), (10, 0), (0, 10)]),  # hypotenuse through centres
        shapely.Polygon([(0.5, 0.5), (4.5, 0.5), (0.5, 4.5)]),  # hypotenuse through corners
        shapely.Polygon([(0, -2), (2, 0), (0, 2), (-2, 0)]),  # diamond through centres
        shapely.Polygon([(0.5, -1.5), (2.5, 0.5), (0.5, 2.5), (-1.5, 0.5)]),  # diamond through corners
        shapely.Polygon([(0, 0), (1e-9, 0), (0, 1e-9)]),  # a speck at a pixel centre
        shapely.Polygon([(0.5, 0.5), (0.5 + 2.0**-40, 0.5), (0.5, 0.5 + 2.0**-40)]),  # a speck at a corner
        shapely.Polygon([(-0.5, -0.5), (0.5, 0.5), (0.5, 0.5 + 1e-12)]),  # sliver along a diagonal
        shapely.Polygon(
            [(-3, -3), (3, -3), (3, 3), (-3, 3)], [[(-1.5, -1.5), (-1.5, 1.5), (1.5, 1.5), (1.5, -1.5)]]
        ),  # a hole with sides on pixel sides
        shapely.Polygon([(0, 0), (4, 0), (4, 4), (2, 2), (0, 4)]),  # reflex vertex on a centre
        shapely.Polygon([(0.1, 0.2), (3.3, 0.7), (2.9, 3.1)]),  # non-dyadic floats
        shapely.Polygon([(1e12, 1e12), (1e12 + 3.5, 1e12), (1e12, 1e12 + 2.5)]),  # huge coordinates
    ]
    for poly in cases:
        assert poly.is_valid
        assert_matches_reference(poly)


# --------------------------------------------------------------------------------------- thin parts
@settings(max_examples=120)
@given(segments())
def test_segments_match_reference(seg) -> None:  # type: ignore[no-untyped-def]
    a, b = seg
    for model in MODELS:
        expected = reference_segment(a, b, model)
        assert as_set(discretize_segment(a, b, model)) == expected, (model, a, b)
        if a != b:
            line = shapely.LineString([a, b])
            assert both_paths(line, model) == (expected, expected), (model, a, b)


@settings(max_examples=40)
@given(polylines())
def test_polylines_match_reference(line) -> None:  # type: ignore[no-untyped-def]
    assert_matches_reference(line)
    if line.coords[0] != line.coords[-1] and len(line.coords) >= 3:
        ring = shapely.LinearRing(line.coords)
        assert_matches_reference(ring)


@settings(max_examples=40)
@given(point_sets())
def test_points_match_reference(points) -> None:  # type: ignore[no-untyped-def]
    assert_matches_reference(points)
    for model in MODELS:
        for p in points.geoms:
            assert as_set(discretize(p, model)) == reference_discretize(p, model)


@settings(max_examples=40)
@given(slivers(), polylines(), point_sets())
def test_mixed_collections_match_reference(poly, line, points) -> None:  # type: ignore[no-untyped-def]
    assert_matches_reference(shapely.GeometryCollection([poly, line, points]))


def test_gauss_drops_thin_parts() -> None:
    geom = shapely.GeometryCollection([shapely.LineString([(0, 0), (5, 3)]), shapely.Point(1, 1)])
    assert discretize(geom, "gauss").is_empty()
    assert discretize_segment((0, 0), (5, 3), "gauss").is_empty()
    assert not discretize(geom, "standard").is_empty()


# -------------------------------------------------------------------------------------- exact parts
def _frac_det(p1, p2, q1, q2, r1, r2, s1, s2):  # type: ignore[no-untyped-def]
    f = Fraction
    return (f(p1) - f(p2)) * (f(q1) - f(q2)) - (f(r1) - f(r2)) * (f(s1) - f(s2))


def _sign(v) -> int:  # type: ignore[no-untyped-def]
    return (v > 0) - (v < 0)


@settings(max_examples=300)
@given(st.data())
def test_exact_determinant_sign(data) -> None:  # type: ignore[no-untyped-def]
    # An orientation of a point on (or next to) the line through two others: the ties and near ties
    # where the float filter gives up and the expansion arithmetic decides.
    snap = data.draw(snapper())
    ax, ay, bx, by = (snap(data.draw(st.floats(-1e3, 1e3))) for _ in range(4))
    t = data.draw(st.sampled_from([0.0, 0.5, 1.0, 2.0, 1 / 3, -0.25]))
    cx, cy = ax + t * (bx - ax), ay + t * (by - ay)
    cx += data.draw(st.sampled_from([0.0, 0.0, 2.0**-52, -(2.0**-40), 1e-100]))
    args = (by, ay, cx, ax, bx, ax, cy, ay)
    scratch = np.zeros(kernels.SCRATCH_SIZE)
    assert kernels.det_sign(*args, False, scratch) == _sign(_frac_det(*args))


@st.composite
def segments_grazing_a_corner(draw):  # type: ignore[no-untyped-def]
    """A segment with full-mantissa float end points whose line passes within rounding of a pixel corner
    (or through it): the plain float orientation of that corner often has the wrong sign."""
    mag = st.sampled_from([1.0, 10.0, 50.0])
    ax = draw(floats(-1, 1)) * draw(mag)
    ay = draw(floats(-1, 1)) * draw(mag)
    cx = draw(st.integers(-12, 12)) + 0.5
    cy = draw(st.integers(-12, 12)) + 0.5
    if cx == ax:
        cx += 1.0
    t = draw(floats(1.0, 2.0))
    bx = ax + t * (cx - ax)
    by = ay + t * (cy - ay)  # rounded: the line passes through or next to (cx, cy)
    return (ax, ay), (bx, by), (cx, cy)


@settings(max_examples=200)
@given(segments_grazing_a_corner())
def test_exact_sign_where_float_orientation_fails(seg) -> None:  # type: ignore[no-untyped-def]
    (ax, ay), (bx, by), (cx, cy) = seg
    args = (by, ay, cx, ax, bx, ax, cy, ay)
    scratch = np.zeros(kernels.SCRATCH_SIZE)
    assert kernels.det_sign(*args, False, scratch) == _sign(_frac_det(*args))


@settings(max_examples=60)
@given(segments_grazing_a_corner())
def test_segments_grazing_a_corner_match_reference(seg) -> None:  # type: ignore[no-untyped-def]
    a, b, _ = seg
    for model in ("standard", "supercover"):
        assert as_set(discretize_segment(a, b, model)) == reference_segment(a, b, model), (model, a, b)


def test_exact_sign_of_ties_broken_by_rounding_errors_alone() -> None:
    # (1 + 2^-60)^2 - 1·(1 + 2^-59) = 2^-120: only the product of the two differences' rounding errors
    # decides, every other term cancels.
    scratch = np.zeros(kernels.SCRATCH_SIZE)
    t = 2.0**-60
    assert kernels.det_sign(1.0, -t, 1.0, -t, 1.0, 0.0, 1.0, -2 * t, False, scratch) == 1
    assert kernels.det_sign(1.0, 0.0, 1.0, -2 * t, 1.0, -t, 1.0, -t, False, scratch) == -1
    assert kernels.det_sign(1.0, -t, 1.0, -t, 1.0, -t, 1.0, -t, False, scratch) == 0


@settings(max_examples=200)
@given(st.data())
def test_float_exactness_claim(data) -> None:  # type: ignore[no-untyped-def]
    # When float_predicates_are_exact says so, plain float determinants over the data and the grid
    # numbers within a pixel of it are exact.
    snap = data.draw(snapper())
    scale = data.draw(st.sampled_from([1.0, 1e3, 1e6, 2.0**23]))
    vals = [snap(data.draw(st.floats(-1.0, 1.0)) * scale) for _ in range(4)]
    hi = max(abs(v) for v in vals)
    grid = [float(k) / 2 for k in range(int(-2 * hi) - 2, int(2 * hi) + 3, max(1, int(hi) // 3 or 1))]
    if not float_predicates_are_exact(np.array(vals)):
        return
    for g in grid[:8]:
        args = (vals[0], vals[1], g, vals[2], vals[3], g, vals[1], vals[2])
        f = (args[0] - args[1]) * (args[2] - args[3]) - (args[4] - args[5]) * (args[6] - args[7])
        assert Fraction(f) == _frac_det(*args)


@settings(max_examples=300)
@given(st.one_of(st.floats(-(2.0**51), 2.0**51), st.integers(-(2**40), 2**40).map(lambda k: k / 2)))
def test_cells_are_exact(u: float) -> None:
    k = cell_index(u)
    assert Fraction(k) - Fraction(1, 2) < Fraction(u) <= Fraction(k) + Fraction(1, 2)
    lo, hi = closed_cell_range(u)
    expected = [j for j in (k - 1, k, k + 1) if abs(Fraction(u) - j) <= Fraction(1, 2)]
    assert [lo, hi] == [expected[0], expected[-1]]


def test_rectilinear_multipolygon_with_holes() -> None:
    # A frame with an island in its hole and a second piece touching the frame at one corner.
    frame = shapely.box(-4.5, -4.5, 4.5, 4.5).difference(shapely.box(-2.5, -2.5, 2.5, 2.5))
    assert frame.geom_type == "Polygon"
    geom = shapely.MultiPolygon([frame, shapely.box(-0.5, -0.5, 0.5, 0.5), shapely.box(4.5, 4.5, 6.5, 6.0)])
    assert geom.is_valid
    assert_matches_reference(geom)
