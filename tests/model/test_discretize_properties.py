"""Properties of the three discretization models (docs/design.md §2, docs/algorithms.md §1.4): sandwich,
union stability,
translation covariance, partition of tilings (gauss), no-bubble standard lines, 4-connectivity."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import shapely
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy import ndimage

from mrm.core.grids import PixelSet
from mrm.core.models import Model
from mrm.geometry.discretize import discretize, discretize_segment
from tests.oracles.discretize_reference import reference_discretize, standard_line_inequality
from tests.oracles.geometry_strategies import (
    floats,
    polygonal,
    polylines,
    rectilinear_shapes,
    segments,
    snapper,
    star_polygons,
)

MODELS = Model.names()

FOUR = np.array([[0, 1, 0], [1, 1, 1], [0, 1, 0]])


def as_set(ps: PixelSet) -> set[tuple[int, int]]:
    return {(int(x), int(y)) for x, y in ps.points()}


def union(sets: list[PixelSet]) -> PixelSet:
    out = PixelSet.empty()
    for s in sets:
        out = out | s
    return out


def four_components(ps: PixelSet) -> int:
    return int(ndimage.label(ps.mask, structure=FOUR)[1])


# ----------------------------------------------------------------------------------------- sandwich
@settings(max_examples=60)
@given(st.one_of(polygonal(), polylines()))
def test_sandwich_open_standard_supercover(geom) -> None:  # type: ignore[no-untyped-def]
    opened = reference_discretize(geom, "open")
    std = as_set(discretize(geom, "standard"))
    sup = as_set(discretize(geom, "supercover"))
    gauss = as_set(discretize(geom, "gauss"))
    assert opened <= std <= sup
    assert gauss <= std


# ---------------------------------------------------------------------------------- union stability
@st.composite
def convex_polygons_with_diagonal(draw):  # type: ignore[no-untyped-def]
    snap = draw(snapper())
    pts = [(snap(draw(floats(-6, 6))), snap(draw(floats(-6, 6)))) for _ in range(draw(st.integers(4, 9)))]
    hull = shapely.MultiPoint(pts).convex_hull
    assume(hull.geom_type == "Polygon" and hull.area > 0)
    ring = list(hull.exterior.coords)[:-1]
    assume(len(ring) >= 4)
    k = draw(st.integers(2, len(ring) - 2))
    return shapely.Polygon(ring), shapely.Polygon(ring[: k + 1]), shapely.Polygon([*ring[k:], ring[0]])


@settings(max_examples=60)
@given(convex_polygons_with_diagonal())
def test_union_stability_across_a_shared_diagonal(pieces) -> None:  # type: ignore[no-untyped-def]
    whole, left, right = pieces
    assume(left.is_valid and right.is_valid and left.area > 0 and right.area > 0)
    for model in MODELS:
        d_left, d_right = discretize(left, model), discretize(right, model)
        assert discretize(whole, model) == d_left | d_right, model
        if model == "gauss":  # the shared diagonal goes to exactly one side
            assert (d_left & d_right).is_empty()


@settings(max_examples=40)
@given(st.one_of(rectilinear_shapes(), st.lists(star_polygons(holes=True), min_size=2, max_size=3)))
def test_union_stability_of_multipolygons_and_collections(shape) -> None:  # type: ignore[no-untyped-def]
    if isinstance(shape, list):  # possibly overlapping members: a collection
        members = shape
        shape = shapely.GeometryCollection(members)
    else:
        members = list(getattr(shape, "geoms", [shape]))
    for model in MODELS:
        assert discretize(shape, model) == union([discretize(m, model) for m in members]), model


@settings(max_examples=40)
@given(star_polygons(max_vertices=6, holes=False), polylines())
def test_union_stability_of_mixed_members(poly, line) -> None:  # type: ignore[no-untyped-def]
    geom = shapely.GeometryCollection([poly, line])
    for model in MODELS:
        assert discretize(geom, model) == discretize(poly, model) | discretize(line, model), model


# ------------------------------------------------------------------------------------------ tilings
@st.composite
def triangulated_squares(draw):  # type: ignore[no-untyped-def]
    snap = draw(snapper())
    n = draw(st.sampled_from([4.0, 6.5, 8.0]))
    pts = [(0.0, 0.0), (n, 0.0), (n, n), (0.0, n)]
    for _ in range(draw(st.integers(1, 14))):
        x, y = snap(draw(floats(0, n))), snap(draw(floats(0, n)))
        if draw(st.integers(0, 4)) == 0:  # a point on the square's boundary
            y = 0.0
        pts.append((min(max(x, 0.0), n), min(max(y, 0.0), n)))
    tris = [t for t in shapely.delaunay_triangles(shapely.MultiPoint(pts)).geoms if t.area > 0]
    assert all(t.is_valid for t in tris)
    return shapely.box(0, 0, n, n), tris


@st.composite
def quad_grids(draw):  # type: ignore[no-untyped-def]
    """A k×k grid of quadrilaterals over [0, k·s]², inner vertices jittered on a lattice."""
    snap = draw(snapper())
    k = draw(st.integers(2, 4))
    s = draw(st.sampled_from([2.0, 2.5, 3.0]))
    v = {}
    for i in range(k + 1):
        for j in range(k + 1):
            jx = snap(draw(floats(-0.3, 0.3)) * s) if 0 < i < k else 0.0
            jy = snap(draw(floats(-0.3, 0.3)) * s) if 0 < j < k else 0.0
            v[i, j] = (i * s + jx, j * s + jy)
    quads = [
        shapely.Polygon([v[i, j], v[i + 1, j], v[i + 1, j + 1], v[i, j + 1]])
        for i in range(k)
        for j in range(k)
    ]
    assume(all(q.is_valid and q.area > 0 for q in quads))
    return shapely.box(0, 0, k * s, k * s), quads


@settings(max_examples=40)
@given(st.one_of(triangulated_squares(), quad_grids()))
def test_tilings(tiling) -> None:  # type: ignore[no-untyped-def]
    square, tiles = tiling
    for model in MODELS:
        parts = [discretize(t, model) for t in tiles]
        assert union(parts) == discretize(square, model), model
        if model == "gauss":  # a partition: every pixel centre of the square in exactly one tile
            assert sum(len(p) for p in parts) == len(discretize(square, "gauss"))


# ------------------------------------------------------------------------------------- translations
@settings(max_examples=60)
@given(st.one_of(polygonal(), polylines()), st.integers(-(2**20), 2**20), st.integers(-(2**20), 2**20))
def test_integer_translation_covariance(geom, tx, ty) -> None:  # type: ignore[no-untyped-def]
    moved = shapely.transform(geom, lambda c: c + np.array([tx, ty], dtype=float))
    a, b = shapely.get_coordinates(geom), shapely.get_coordinates(moved)
    exact = all(
        Fraction(float(u)) + t == Fraction(float(w))
        for row, row2 in zip(a, b, strict=True)
        for u, w, t in zip(row, row2, (tx, ty), strict=True)
    )
    assume(exact)  # the float translation must be the exact one
    for model in MODELS:
        assert discretize(moved, model) == discretize(geom, model).translate(tx, ty), model


# ----------------------------------------------------------------------------------- standard lines
@settings(max_examples=200)
@given(segments(lattice_points=True))
def test_standard_segment_between_centres_has_no_bubble(seg) -> None:  # type: ignore[no-untyped-def]
    (ax, ay), (bx, by) = seg
    ps = discretize_segment((ax, ay), (bx, by))
    dx, dy = int(bx - ax), int(by - ay)
    assert len(ps) == abs(dx) + abs(dy) + 1
    sx, sy = (1 if dx >= 0 else -1), (1 if dy >= 0 else -1)
    index = sorted(sx * x + sy * y for x, y in ps.points().tolist())
    start = sx * int(ax) + sy * int(ay)
    assert index == list(range(start, start + len(ps)))  # one pixel per diagonal index
    assert four_components(ps) == 1


@st.composite
def long_segments(draw):  # type: ignore[no-untyped-def]
    snap = draw(snapper())
    a = (snap(draw(floats(-12, 12))), snap(draw(floats(-12, 12))))
    b = (snap(draw(floats(-12, 12))), snap(draw(floats(-12, 12))))
    if draw(st.integers(0, 3)) == 0:
        b = (b[0], a[1]) if draw(st.booleans()) else (a[0], b[1])
    assume(a != b)
    return a, b


@settings(max_examples=150)
@given(long_segments())
def test_standard_segment_agrees_with_the_line_inequality(seg) -> None:  # type: ignore[no-untyped-def]
    a, b = seg
    fa = (Fraction(a[0]), Fraction(a[1]))
    dx, dy = Fraction(b[0]) - fa[0], Fraction(b[1]) - fa[1]
    # The line through a and b: dy·x − dx·y + (dx·a_y − dy·a_x) = 0.
    coef = (dy, -dx, dx * fa[1] - dy * fa[0])

    def span(u: float, v: float, moving: bool) -> tuple[int, int]:
        lo, hi = min(u, v), max(u, v)
        if moving:  # keep one pixel away from the end points: there the segment is the whole line
            return int(np.ceil(lo)) + 1, int(np.floor(hi)) - 1
        return int(np.floor(lo)) - 3, int(np.ceil(hi)) + 3

    x0, x1 = span(a[0], b[0], dx != 0)
    y0, y1 = span(a[1], b[1], dy != 0)
    assume(x0 <= x1 and y0 <= y1)
    window = (x0, y0, x1, y1)
    got = discretize_segment(a, b, "standard").crop(window)
    assert as_set(got) == standard_line_inequality(*coef, window)


# ------------------------------------------------------------------------------------- connectivity
@settings(max_examples=60)
@given(st.one_of(star_polygons(), polylines()))
def test_standard_and_supercover_of_connected_sets_are_4_connected(geom) -> None:  # type: ignore[no-untyped-def]
    assert four_components(discretize(geom, "standard")) == 1
    assert four_components(discretize(geom, "supercover")) == 1


# ----------------------------------------------------------------------------------------- symmetry
@settings(max_examples=60)
@given(st.one_of(polygonal(), polylines()))
def test_supercover_commutes_with_grid_symmetries(geom) -> None:  # type: ignore[no-untyped-def]
    # Negating or swapping coordinates is exact in floats and maps pixel centres to pixel centres.
    sup = discretize(geom, "supercover")
    mirror_x = shapely.transform(geom, lambda c: c * np.array([-1.0, 1.0]))
    mirror_y = shapely.transform(geom, lambda c: c * np.array([1.0, -1.0]))
    quarter_turn = shapely.transform(geom, lambda c: np.stack([-c[:, 1], c[:, 0]], axis=1))
    assert discretize(mirror_x, "supercover") == sup.flip_x(0)
    assert discretize(mirror_y, "supercover") == sup.flip_y(0)
    assert discretize(quarter_turn, "supercover") == sup.rotate90(1)


@given(st.one_of(polygonal(), st.lists(star_polygons(holes=True), min_size=2, max_size=3)))
def test_skipping_the_validity_check_keeps_the_pixels(shape) -> None:  # type: ignore[no-untyped-def]
    """check_validity=False (for callers holding a valid polygon, e.g. R's output) gives the same D."""
    geom = shapely.GeometryCollection(shape) if isinstance(shape, list) else shape
    for model in MODELS:
        assert discretize(geom, model, check_validity=False) == discretize(geom, model)


def test_the_validity_check_stays_on_by_default() -> None:
    """A bow-tie is still refused unless the caller says it knows the polygon valid."""
    import pytest

    from mrm.core.errors import InvalidGeometryError

    bowtie = shapely.Polygon([(0, 0), (4, 4), (4, 0), (0, 4)])
    with pytest.raises(InvalidGeometryError):
        discretize(bowtie)
