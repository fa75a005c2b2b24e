"""GeoJSON / WKT / SVG files: exact coordinates, validation with useful messages, atomic writes."""

from __future__ import annotations

import itertools
import json
import math
import os
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import (
    GeometryCollection,
    LinearRing,
    LineString,
    MultiLineString,
    MultiPoint,
    MultiPolygon,
    Point,
    Polygon,
    box,
)

from mrm.core.errors import FileFormatError, InvalidGeometryError
from mrm.core.grids import PixelSet
from mrm.io.vector_files import (
    MAX_VECTOR_FILE_BYTES,
    combine,
    read_geometries,
    read_geometry,
    write_geojson,
    write_svg,
    write_wkt,
)

SVG = "{http://www.w3.org/2000/svg}"


def write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


def coords_of(g) -> list[tuple[float, float]]:
    return [tuple(c) for c in shapely.get_coordinates(g).tolist()]


def same_floats(a: list[tuple[float, float]], b: list[tuple[float, float]]) -> bool:
    """Bit-for-bit equality, so that -0.0 and 0.0 differ."""
    return len(a) == len(b) and all(
        np.float64(x).tobytes() == np.float64(y).tobytes()
        for p, q in zip(a, b, strict=True)
        for x, y in zip(p, q, strict=True)
    )


# -------------------------------------------------------------------------------------------- reading GeoJSON
def test_feature_collection_with_names(tmp_path):
    doc = {
        "type": "FeatureCollection",
        "features": [
            {
                "type": "Feature",
                "properties": {"name": "a"},
                "geometry": {"type": "Point", "coordinates": [1, 2]},
            },
            {
                "type": "Feature",
                "id": 7,
                "properties": None,
                "geometry": {"type": "LineString", "coordinates": [[0, 0], [1, 1]]},
            },
            {
                "type": "Feature",
                "properties": {"part": "p", "name": "n"},
                "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [2, 0], [2, 2], [0, 0]]]},
            },
            {"type": "Feature", "properties": {}, "geometry": None},
            {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [3, 4, 99]}},
        ],
    }
    p = write(tmp_path / "f.geojson", json.dumps(doc))
    got = read_geometries(p)
    assert [n for n, _ in got] == ["a", "7", "p", None]
    assert got[0][1].equals(Point(1, 2))
    assert got[2][1].equals(Polygon([(0, 0), (2, 0), (2, 2)]))
    assert not got[3][1].has_z and coords_of(got[3][1]) == [(3.0, 4.0)]  # Z dropped


def test_bare_geometry_and_single_feature(tmp_path):
    p = write(tmp_path / "g.json", '{"type": "MultiPolygon", "coordinates": [[[[0,0],[1,0],[1,1],[0,0]]]]}')
    assert read_geometry(p).equals(MultiPolygon([Polygon([(0, 0), (1, 0), (1, 1)])]))
    f = write(
        tmp_path / "f.geojson",
        '{"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [5, 6]}}',
    )
    assert read_geometries(f) == [(None, Point(5, 6))]
    gc = write(
        tmp_path / "c.geojson",
        '{"type": "GeometryCollection", "geometries": [{"type": "Point", "coordinates": [0, 0]},'
        ' {"type": "LineString", "coordinates": [[0, 0], [3, 0]]}]}',
    )
    assert read_geometry(gc).equals(GeometryCollection([Point(0, 0), LineString([(0, 0), (3, 0)])]))


def test_features_are_combined_without_rounding(tmp_path):
    a = Polygon([(0, 0), (1 / 3, 0), (1 / 3, 1 / 7), (0, 1 / 7)])
    b = Polygon([(0.1, 0.05), (0.9, 0.05), (0.9, 0.9)])  # overlaps a
    c = Polygon([(5, 5), (6, 5), (6, 6)])
    write_geojson([("a", a), ("b", b), ("c", c)], tmp_path / "o.geojson")
    g = read_geometry(tmp_path / "o.geojson")
    # overlapping polygons cannot form a valid MultiPolygon: kept as they are, same coordinates
    assert isinstance(g, GeometryCollection) and len(g.geoms) == 3
    assert all(same_floats(coords_of(x), coords_of(y)) for x, y in zip(g.geoms, (a, b, c), strict=True))
    # its point set is the union
    assert abs(shapely.union_all(g.geoms).area - shapely.union_all([a, b, c]).area) < 1e-12
    # disjoint polygons make a MultiPolygon, lines a MultiLineString, points a MultiPoint
    assert isinstance(combine([a, c]), MultiPolygon)
    assert isinstance(combine([LineString([(0, 0), (1, 1)]), LineString([(0, 1), (1, 0)])]), MultiLineString)
    assert isinstance(combine([Point(0, 0), MultiPoint([(1, 1), (2, 2)])]), MultiPoint)
    assert combine([]).is_empty and combine([Polygon()]).is_empty
    # polygons sharing an edge are not a valid MultiPolygon either
    assert isinstance(combine([box(0, 0, 1, 1), box(1, 0, 2, 1)]), GeometryCollection)


# ---------------------------------------------------------------------------------------------- exactness
finite = st.floats(allow_nan=False, allow_infinity=False, width=64)
nice = st.one_of(
    finite.filter(lambda v: abs(v) < 1e300),
    st.integers(-(2**53), 2**53).map(float),
    st.integers(-(10**6), 10**6).map(lambda k: k / 2),
    st.sampled_from([0.0, -0.0, 0.1, 1 / 3, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e300]),
)


@st.composite
def boxes(draw):
    x0, x1 = sorted(draw(st.lists(nice, min_size=2, max_size=2, unique=True)))
    y0, y1 = sorted(draw(st.lists(nice, min_size=2, max_size=2, unique=True)))
    g = box(x0, y0, x1, y1)  # counter-clockwise exterior: written as is
    if not shapely.is_valid(g) or g.area == 0:
        return Point(x0, y0)
    return g


geoms = st.one_of(
    boxes(),
    st.builds(lambda x, y: Point(x, y), nice, nice),
    st.builds(lambda a, b, c, d: LineString([(a, b), (c, d)]), nice, nice, nice, nice).filter(
        lambda g: shapely.is_valid(g)
    ),
)


@settings(max_examples=80)
@given(geoms)
def test_geojson_and_wkt_round_trips_are_bit_exact(g):
    with tempfile.TemporaryDirectory() as d:
        write_geojson(g, Path(d) / "a.geojson")
        write_wkt(g, Path(d) / "a.wkt")
        for name in ("a.geojson", "a.wkt"):
            back = read_geometry(Path(d) / name)
            assert back.geom_type == g.geom_type
            assert same_floats(coords_of(back), coords_of(g)), name


def test_wkt_several_geometries_and_multiline(tmp_path):
    text = "POINT (1 2)\n\nPOLYGON ((0 0,\n  4 0, 4 4,\n  0 0))\nLINESTRING (0 0, 1 1)  \nPOINT EMPTY\n"
    got = read_geometries(write(tmp_path / "m.wkt", text))
    assert [g.geom_type for _, g in got] == ["Point", "Polygon", "LineString", "Point"]
    assert got[1][1].equals(Polygon([(0, 0), (4, 0), (4, 4)]))
    assert all(n is None for n, _ in got)
    write_wkt([Point(0.5, -0.25), box(0, 0, 1, 1)], tmp_path / "w.wkt")
    assert (tmp_path / "w.wkt").read_text().count("\n") == 2
    assert [g.geom_type for _, g in read_geometries(tmp_path / "w.wkt")] == ["Point", "Polygon"]


def test_linear_ring_reads_as_a_line(tmp_path):
    p = write(tmp_path / "r.wkt", "LINEARRING (0 0, 1 0, 1 1, 0 0)")
    assert read_geometry(p).equals(LineString([(0, 0), (1, 0), (1, 1), (0, 0)]))
    write_wkt(LinearRing([(0, 0), (1, 0), (1, 1)]), tmp_path / "w.wkt")
    assert (tmp_path / "w.wkt").read_text().startswith("LINESTRING (")


def test_geojson_polygons_follow_rfc7946_orientation(tmp_path):
    cw = Polygon([(0, 0), (0, 2), (2, 2), (2, 0)], [[(0.5, 0.5), (1.5, 0.5), (1.5, 1.5), (0.5, 1.5)]])
    write_geojson(cw, tmp_path / "o.geojson")
    ring_coords = json.loads((tmp_path / "o.geojson").read_text())["features"][0]["geometry"]["coordinates"]

    def signed_area(ring):
        return sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in itertools.pairwise(ring)) / 2

    assert signed_area(ring_coords[0]) > 0 and signed_area(ring_coords[1]) < 0
    assert read_geometry(tmp_path / "o.geojson").equals(cw)


def _reference_rings(p: Polygon) -> list[list[list[float]]]:
    """A polygon's GeoJSON rings, one at a time: exterior counter-clockwise, holes clockwise (Fractions)."""

    def twice_area(ring):
        from fractions import Fraction

        pts = [(Fraction(x), Fraction(y)) for x, y in ring]
        return sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in itertools.pairwise(pts))

    out = []
    for i, r in enumerate([p.exterior, *p.interiors]):
        ring = [[float(x), float(y)] for x, y in r.coords]
        if (twice_area(ring) > 0) != (i == 0):
            ring = ring[::-1]
        out.append(ring)
    return out


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    density=st.floats(0.2, 0.8),
    flips=st.lists(st.booleans(), min_size=1, max_size=8),
)
def test_geojson_of_many_polygons_is_each_polygon_oriented_alone(tmp_path_factory, seed, density, flips):
    # The writer orients and lists every ring of a large result in a few array passes; each polygon must
    # come out exactly as orienting it alone does, whatever the orientation of its rings on the way in.
    from mrm.geometry.reconstruct import reconstruct

    rng = np.random.default_rng(seed)
    geom = reconstruct(PixelSet(rng.random((12, 14)) < density, (int(rng.integers(-9, 9)), 3)))
    polys = list(getattr(geom, "geoms", [geom]))
    polys = [shapely.reverse(p) if flips[i % len(flips)] else p for i, p in enumerate(polys)]
    out = tmp_path_factory.mktemp("g") / "m.geojson"
    write_geojson(MultiPolygon(polys) if len(polys) > 1 else polys[0], out)
    got = json.loads(out.read_text())["features"][0]["geometry"]
    expected = [_reference_rings(p) for p in polys]
    assert got["coordinates"] == (expected if len(polys) > 1 else expected[0])


def test_parts_get_a_part_property(tmp_path):
    write_geojson(
        {"left": box(0, 0, 1, 1), "right": box(2, 0, 3, 1)}, tmp_path / "p.geojson", properties={"run": 3}
    )
    doc = json.loads((tmp_path / "p.geojson").read_text())
    assert doc["type"] == "FeatureCollection"
    assert [f["properties"] for f in doc["features"]] == [
        {"run": 3, "part": "left"},
        {"run": 3, "part": "right"},
    ]
    write_geojson([box(0, 0, 1, 1), box(2, 0, 3, 1)], tmp_path / "q.geojson")
    assert [n for n, _ in read_geometries(tmp_path / "q.geojson")] == ["0", "1"]


# ---------------------------------------------------------------------------------------------- bad input
def test_malformed_json_gives_line_and_column(tmp_path):
    p = write(tmp_path / "m.geojson", '{\n  "type": "Point",\n  "coordinates": [1, 2,]\n}\n')
    with pytest.raises(FileFormatError, match=r"m\.geojson: malformed JSON at line 3, column 24"):
        read_geometries(p)


@pytest.mark.parametrize(
    ("text", "error", "message"),
    [
        ('{"type": "Point", "coordinates": [NaN, 1]}', FileFormatError, "NaN"),
        ('{"type": "Point", "coordinates": [Infinity, 1]}', FileFormatError, "Infinity"),
        ('{"type": "Point", "coordinates": [1e999, 1]}', InvalidGeometryError, "finite"),
        ('{"type": "Point", "coordinates": ["1", 2]}', FileFormatError, "numbers"),
        ('{"type": "Point", "coordinates": [true, 2]}', FileFormatError, "numbers"),
        ('{"type": "Point", "coordinates": [1]}', FileFormatError, "two numbers"),
        ('{"type": "Polygon", "coordinates": [[0, 0], [1, 1]]}', FileFormatError, "position"),
        ('{"type": "Circle", "coordinates": [0, 0], "radius": 1}', FileFormatError, "unsupported GeoJSON"),
        ('{"type": "LineString", "coordinates": [[0, 0]]}', InvalidGeometryError, "LineString"),
        ('{"type": "Polygon", "coordinates": [[[0, 0], [1, 1], [0, 0]]]}', InvalidGeometryError, "Polygon"),
        ('{"type": "Polygon"}', FileFormatError, "coordinates"),
        ('{"type": "FeatureCollection"}', FileFormatError, "features"),
        (
            '{"type": "FeatureCollection", "features": [{"type": "Point"}]}',
            FileFormatError,
            "not a GeoJSON Feature",
        ),
        ('{"type": "Feature", "properties": {}}', FileFormatError, "no 'geometry'"),
        ("[1, 2]", FileFormatError, "not GeoJSON"),
        ("", FileFormatError, "malformed JSON"),
        ("[" * 100_000, FileFormatError, "nested too deeply|malformed"),
    ],
)
def test_bad_geojson(tmp_path, text, error, message):
    p = write(tmp_path / "b.geojson", text)
    with pytest.raises(error, match=message) as e:
        read_geometries(p)
    assert "b.geojson" in str(e.value)


@pytest.mark.parametrize(
    ("wkt", "reason", "hint"),
    [
        ("POLYGON ((0 0, 2 2, 2 0, 0 2, 0 0))", "Self-intersection", "no edge crosses"),
        (
            "POLYGON ((0 0, 4 0, 4 4, 0 4, 0 0), (5 5, 6 5, 6 6, 5 5))",
            "Hole lies outside shell",
            "inside its shell",
        ),
        (
            "MULTIPOLYGON (((0 0, 2 0, 2 2, 0 2, 0 0)), ((1 1, 3 1, 3 3, 1 3, 1 1)))",
            "Self-intersection",
            "separate features",
        ),
        (
            "POLYGON ((0 0, 4 0, 4 4, 0 4, 0 0), (0 2, 2 0, 4 2, 2 4, 0 2))",
            "Interior is disconnected",
            "split it",
        ),
    ],
)
def test_invalid_polygons_say_why_and_how_to_repair(tmp_path, wkt, reason, hint):
    p = write(tmp_path / "i.wkt", "POINT (0 0)\n" + wkt + "\n")
    with pytest.raises(InvalidGeometryError) as e:
        read_geometry(p)
    msg = str(e.value)
    assert "i.wkt: line 2" in msg and reason in msg and hint in msg


@pytest.mark.parametrize(
    ("text", "error", "message"),
    [
        ("POINT (1 2", FileFormatError, "not closed"),
        ("POINT (1 2))", FileFormatError, "unbalanced"),
        ("POINT (1 2) POINT (3 4)", FileFormatError, "malformed WKT"),
        ("POLYGON ((0 0, 1 0, 1 x, 0 0))", FileFormatError, "malformed WKT"),
        ("CIRCULARSTRING (0 0, 1 1, 2 0)", InvalidGeometryError, "unsupported"),
        ("POINT (nan 1)", InvalidGeometryError, "finite"),
        ("hello world", FileFormatError, "malformed WKT"),
    ],
)
def test_bad_wkt(tmp_path, text, error, message):
    p = write(tmp_path / "w.wkt", text)
    with pytest.raises(error, match=message) as e:
        read_geometries(p)
    assert "w.wkt: line 1" in str(e.value)


def test_bad_files(tmp_path):
    big = tmp_path / "big.geojson"
    with open(big, "wb") as fh:
        fh.truncate(MAX_VECTOR_FILE_BYTES + 1)  # sparse: costs no disk space
    with pytest.raises(FileFormatError, match="MB"):
        read_geometries(big)
    latin = tmp_path / "l.wkt"
    latin.write_bytes(b"POINT (1 2) \xe9")
    with pytest.raises(FileFormatError, match="UTF-8"):
        read_geometries(latin)
    with pytest.raises(FileFormatError, match=r"'\.shp'"):
        read_geometries(tmp_path / "x.shp")
    with pytest.raises(FileNotFoundError):
        read_geometries(tmp_path / "missing.wkt")
    bom = tmp_path / "bom.geojson"
    bom.write_bytes(b'\xef\xbb\xbf{"type": "Point", "coordinates": [1, 2]}')
    assert read_geometry(bom).equals(Point(1, 2))


def test_non_finite_geometry_is_not_written(tmp_path):
    p = tmp_path / "keep.wkt"
    write_wkt(Point(1, 2), p)
    q = tmp_path / "keep.geojson"
    write_geojson(Point(1, 2), q)
    bad = Point(float("nan"), 1)
    with pytest.raises(InvalidGeometryError):
        write_wkt(bad, p)
    with pytest.raises(InvalidGeometryError):
        write_geojson(bad, q)
    assert p.read_text() == "POINT (1.0 2.0)\n"
    assert read_geometry(q).equals(Point(1, 2))
    assert sorted(os.listdir(tmp_path)) == ["keep.geojson", "keep.wkt"]


# ---------------------------------------------------------------------------------------------- SVG
def parse_path(d: str) -> list[list[tuple[float, float]]]:
    rings, cur = [], []
    tokens = d.replace("M", " M ").replace("L", " L ").replace("Z", " Z ").split()
    i = 0
    while i < len(tokens):
        t = tokens[i]
        if t == "M":
            if cur:
                rings.append(cur)
            cur = []
            i += 1
        elif t == "L":
            i += 1
        elif t == "Z":
            rings.append(cur)
            cur = []
            i += 1
        else:
            cur.append((float(tokens[i]), float(tokens[i + 1])))
            i += 2
    if cur:
        rings.append(cur)
    return rings


def test_svg_of_a_polygon_with_a_hole_is_upright_and_exact(tmp_path):
    g = Polygon([(0, 0), (10, 0), (10, 20), (0, 20)], [[(2, 2), (4, 2), (4, 4), (2, 4)]])
    write_svg(g, tmp_path / "p.svg")
    root = ET.parse(tmp_path / "p.svg").getroot()
    paths = root.findall(f"{SVG}path")
    assert len(paths) == 1 and paths[0].get("fill-rule") == "evenodd"
    rings = parse_path(paths[0].get("d"))
    assert rings[0] == [(x, -y) for x, y in g.exterior.coords]  # y flipped: higher y is higher up
    assert rings[1] == [(x, -y) for x, y in g.interiors[0].coords]
    vx, vy, vw, vh = (float(v) for v in root.get("viewBox").split())
    assert vx <= 0 and vx + vw >= 10 and vy <= -20 and vy + vh >= 0


def test_svg_of_lines_points_and_empty(tmp_path):
    g = GeometryCollection([LineString([(0, 0), (3, 1)]), Point(2, 5)])
    write_svg(g, tmp_path / "g.svg")
    root = ET.parse(tmp_path / "g.svg").getroot()
    assert root.find(f"{SVG}path").get("fill") == "none"
    c = root.find(f"{SVG}circle")
    assert (float(c.get("cx")), float(c.get("cy"))) == (2.0, -5.0)
    write_svg(Polygon(), tmp_path / "e.svg")
    assert ET.parse(tmp_path / "e.svg").getroot().tag == f"{SVG}svg"


pixel_sets = st.sets(st.tuples(st.integers(-8, 8), st.integers(-8, 8)), max_size=60)


@settings(max_examples=60)
@given(pixel_sets)
def test_svg_of_pixels_draws_exactly_the_voxels_one_rect_per_run(pts):
    ps = PixelSet.from_points(sorted(pts))
    with tempfile.TemporaryDirectory() as d:
        write_svg(ps, Path(d) / "px.svg")
        root = ET.parse(Path(d) / "px.svg").getroot()
    rects = root.iter(f"{SVG}rect")
    covered = []
    for r in rects:
        x, y, w, h = (float(r.get(k)) for k in ("x", "y", "width", "height"))
        assert h == 1 and w >= 1 and w == int(w)
        top = -y  # SVG y of the top edge is −(pixel y + ½)
        py = top - 0.5
        assert py == int(py) and x + 0.5 == int(x + 0.5)
        covered.extend((int(x + 0.5) + k, int(py)) for k in range(int(w)))
    assert sorted(covered) == sorted(pts)  # no pixel twice, none missing
    runs = sum(1 for x, y in pts if (x - 1, y) not in pts)
    assert len(list(root.iter(f"{SVG}rect"))) == runs


def test_svg_coordinates_are_exact(tmp_path):
    g = Point(0.1, 1 / 3)
    write_svg(g, tmp_path / "x.svg")
    c = ET.parse(tmp_path / "x.svg").getroot().find(f"{SVG}circle")
    assert float(c.get("cx")) == 0.1 and float(c.get("cy")) == -(1 / 3)
    assert math.isfinite(float(c.get("r")))


# ---------------------------------------------------------------------------------------------- SVG: both
def drawn_pixels(group) -> list[tuple[int, int]]:
    """The pixels covered by the <rect> runs of an SVG group (y flipped back), each as often as drawn."""
    out = []
    for r in group.iter(f"{SVG}rect"):
        x, y, w, h = (float(r.get(k)) for k in ("x", "y", "width", "height"))
        assert h == 1 and w == int(w) >= 1
        px, py = x + 0.5, -y - 0.5  # the rect's left side is x − ½, its top (SVG y) −(y + ½)
        assert px == int(px) and py == int(py)
        out.extend((int(px) + k, int(py)) for k in range(int(w)))
    return out


def view_box(root) -> tuple[float, float, float, float]:
    """The viewBox as plane bounds (xmin, ymin, xmax, ymax), y flipped back."""
    vx, vy, vw, vh = (float(v) for v in root.get("viewBox").split())
    return vx, -(vy + vh), vx + vw, -vy


def test_svg_of_a_geometry_over_pixels(tmp_path):
    # A right triangle with a vertex on a pixel corner and its legs along pixel sides, over the pixels
    # whose open square meets its interior (3x + 4y < 12 with x, y ≥ 0), written out by hand.
    tri = Polygon([(-0.5, -0.5), (3.5, -0.5), (-0.5, 2.5)])
    pts = {(0, 0), (1, 0), (2, 0), (3, 0), (0, 1), (1, 1), (2, 1), (0, 2), (1, 2)}
    write_svg(tri, tmp_path / "both.svg", pixels=PixelSet.from_points(sorted(pts)))
    root = ET.parse(tmp_path / "both.svg").getroot()
    children = list(root)
    # the pixels first (underneath), then the outline on top
    assert [c.tag for c in children] == [f"{SVG}g", f"{SVG}path"]
    group, outline = children
    assert group.get("id") == "pixels"
    assert sorted(drawn_pixels(group)) == sorted(pts)
    assert outline.get("fill") == "none" and outline.get("stroke") not in (None, "none")
    assert group.get("fill") != outline.get("stroke")  # the outline stands out from the squares
    assert parse_path(outline.get("d")) == [[(x, -y) for x, y in tri.exterior.coords]]
    # the viewBox holds every voxel and the triangle, with a margin of at most a couple of pixels
    x0, y0, x1, y1 = view_box(root)
    assert x0 < -0.5 and y0 < -0.5 and x1 > 3.5 and y1 > 2.5
    assert x0 >= -0.5 - 2 and y0 >= -0.5 - 2 and x1 <= 3.5 + 2 and y1 <= 2.5 + 2


def test_svg_view_box_is_fitted_to_both(tmp_path):
    far = box(100, 50, 101, 52)
    write_svg(far, tmp_path / "far.svg", pixels=PixelSet.from_points([(0, 0)]))
    x0, y0, x1, y1 = view_box(ET.parse(tmp_path / "far.svg").getroot())
    assert x0 < -0.5 and y0 < -0.5 and x1 > 101 and y1 > 52  # the pixel's voxel and the far box
    assert x1 - x0 < 101.5 * 1.1 and y1 - y0 < 52.5 * 1.1  # and not much more


def test_svg_of_empty_geometry_over_pixels_and_lines_over_pixels(tmp_path):
    write_svg(Polygon(), tmp_path / "e.svg", pixels=PixelSet.box(5, 5, 6, 5))
    root = ET.parse(tmp_path / "e.svg").getroot()
    assert sorted(drawn_pixels(root)) == [(5, 5), (6, 5)]
    assert root.find(f"{SVG}path") is None
    x0, y0, x1, y1 = view_box(root)
    assert x0 < 4.5 and x1 > 6.5 and y0 < 4.5 and y1 > 5.5 and x1 - x0 < 5
    # a segment and a point over their pixels: the segment stroked, the point a dot, both on top
    g = GeometryCollection([LineString([(0, 0), (2, 1)]), Point(4, 4)])
    write_svg(g, tmp_path / "l.svg", pixels=PixelSet.from_points([(0, 0), (1, 0), (1, 1), (2, 1), (4, 4)]))
    root = ET.parse(tmp_path / "l.svg").getroot()
    assert [c.tag for c in root] == [f"{SVG}g", f"{SVG}path", f"{SVG}circle"]
    assert parse_path(root[1].get("d")) == [[(0.0, 0.0), (2.0, -1.0)]]
    assert (float(root[2].get("cx")), float(root[2].get("cy"))) == (4.0, -4.0)


def test_svg_pixels_are_given_once(tmp_path):
    with pytest.raises(TypeError):
        write_svg(PixelSet.from_points([(0, 0)]), tmp_path / "x.svg", pixels=PixelSet.from_points([(1, 1)]))
    assert not (tmp_path / "x.svg").exists()


@settings(max_examples=40)
@given(
    pixel_sets,
    st.tuples(*[st.integers(-40, 40).map(lambda v: v / 4) for _ in range(4)]).filter(
        lambda t: t[0] < t[2] and t[1] < t[3]
    ),
)
def test_svg_both_draws_every_pixel_once_and_the_polygon_exactly(pts, corners):
    poly = box(*corners)
    ps = PixelSet.from_points(sorted(pts))
    with tempfile.TemporaryDirectory() as d:
        write_svg(poly, Path(d) / "b.svg", pixels=ps)
        root = ET.parse(Path(d) / "b.svg").getroot()
    assert sorted(drawn_pixels(root)) == sorted(pts)
    (path,) = root.findall(f"{SVG}path")
    assert parse_path(path.get("d")) == [[(x, -y) for x, y in poly.exterior.coords]]
    x0, y0, x1, y1 = view_box(root)
    inner = [(x - 0.5, y - 0.5) for x, y in pts] + [(x + 0.5, y + 0.5) for x, y in pts]
    inner += [(corners[0], corners[1]), (corners[2], corners[3])]
    assert all(x0 < x < x1 and y0 < y < y1 for x, y in inner)


def test_export_of_both_representations_to_svg(tmp_path):
    from mrm.core.errors import ParameterError
    from mrm.document import Document, Settings
    from mrm.document.commands import AddObject
    from mrm.io.export import export_object

    square = Polygon([(0.5, -0.5), (2.5, -0.5), (2.5, 1.5), (0.5, 1.5)])  # the voxels of x = 1, 2; y = 0, 1
    doc = Document(Settings("supercover"))
    doc.push(AddObject(doc.make_object(square, "square")))
    assert export_object(doc, doc.ids[0], tmp_path / "b.svg", rep="both") == "both"
    root = ET.parse(tmp_path / "b.svg").getroot()
    # supercover: every pixel whose closed square the square touches — its 4 voxels and the 12 around them
    assert sorted(drawn_pixels(root)) == sorted((x, y) for x in range(0, 4) for y in range(-1, 3))
    (outline,) = root.findall(f"{SVG}path")
    assert outline.get("fill") == "none"
    assert parse_path(outline.get("d")) == [[(x, -y) for x, y in square.exterior.coords]]
    # the default for .svg stays the shape alone (a vector format: ready for an SVG editor)
    assert export_object(doc, doc.ids[0], tmp_path / "e.svg") == "euclidean"
    assert list(ET.parse(tmp_path / "e.svg").getroot().iter(f"{SVG}rect")) == []
    with pytest.raises(ParameterError):
        export_object(doc, doc.ids[0], tmp_path / "b.png", rep="both")
