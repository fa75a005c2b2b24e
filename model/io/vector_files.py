"""Euclidean geometry files: GeoJSON and WKT in and out, SVG out (docs/design.md §9).

Reading goes through ``json`` and shapely (``shapely.geometry.shape``, ``shapely.from_wkt``); every
geometry is then checked (:func:`check_geometry`): finite coordinates, a supported type, validity in the OGC
sense with the reason and a way to repair it. Z values are dropped (the plane is 2-D).

Writing uses ``repr`` for every coordinate, so a float64 read back is the same float64. All writes are
atomic (:mod:`mrm.io.atomic`).
"""

from __future__ import annotations

import json
import math
import os
import re
from collections.abc import Iterable, Mapping, Sequence
from itertools import pairwise
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.errors import GEOSException
from shapely.geometry import (
    GeometryCollection,
    LinearRing,
    LineString,
    MultiLineString,
    MultiPoint,
    MultiPolygon,
    Point,
    Polygon,
    shape,
)
from shapely.geometry.base import BaseGeometry

from mrm.core.errors import FileFormatError, InvalidGeometryError
from mrm.core.gc_pause import paused_gc
from mrm.core.grids import PixelSet, joint_box
from mrm.core.limits import MAX_GEOMETRY_NESTING, MAX_OBJECT_VERTICES, check_output_bytes, clean_name
from mrm.io.atomic import atomic_open
from mrm.io.reading import open_regular

PathLike = str | os.PathLike[str]
NamedGeometry = tuple[str | None, BaseGeometry]

#: Extensions read by :func:`read_geometries`.
VECTOR_EXTENSIONS = (".geojson", ".json", ".wkt")
#: Vector files larger than this are refused before they are read.
MAX_VECTOR_FILE_BYTES = 100 * 1024 * 1024

_SUPPORTED = (Point, MultiPoint, LineString, MultiLineString, Polygon, MultiPolygon, GeometryCollection)
# GeoJSON geometry type → nesting depth of its "coordinates" (0 = one position).
_GEOJSON_DEPTH = {
    "Point": 0,
    "MultiPoint": 1,
    "LineString": 1,
    "MultiLineString": 2,
    "Polygon": 2,
    "MultiPolygon": 3,
}

# Repair advice keyed by the start of GEOS's invalidity reason.
_HINTS = (
    ("Ring Self-intersection", "a ring touches itself; split it into two rings or move the touching vertex"),
    (
        "Self-intersection",
        "move the vertices so that no edge crosses another (a figure-eight is two polygons)",
    ),
    ("Hole lies outside shell", "put the hole inside its shell, or make it a polygon of its own"),
    ("Nested holes", "a hole cannot lie inside another hole; make the inner one a separate polygon"),
    ("Interior is disconnected", "the holes cut the polygon in pieces; split it into several polygons"),
    ("Nested shells", "the polygons of a MultiPolygon cannot contain each other; use separate features"),
    ("Duplicate Rings", "remove the repeated ring"),
    ("Too few points", "a ring needs 3 distinct points and a line 2"),
    ("Ring is not closed", "repeat the first point of the ring at its end"),
)


# ---------------------------------------------------------------------------------------------- checking
def check_geometry(geom: BaseGeometry, where: str) -> BaseGeometry:
    """Return ``geom`` as a usable 2-D geometry, or raise with what is wrong and how to fix it.

    Parameters
    ----------
    geom : shapely geometry
    where : str
        Where the geometry comes from (file and feature or line), for messages.

    Returns
    -------
    shapely geometry
        ``geom`` without Z values; a LinearRing becomes the LineString of the same points.

    Raises
    ------
    InvalidGeometryError
        Unsupported type (curves, …), NaN or infinite coordinates, or an invalid polygon; the message gives
        GEOS's reason (``shapely.is_valid_reason``) and a way to repair it.
    """
    if isinstance(geom, LinearRing):
        geom = LineString(geom.coords)
    if not isinstance(geom, _SUPPORTED):
        raise InvalidGeometryError(f"{where}: unsupported geometry type {geom.geom_type}")
    if isinstance(geom, GeometryCollection) and not geom.is_empty:
        parts = [check_geometry(g, where) for g in geom.geoms]
        return GeometryCollection(parts)
    if shapely.has_z(geom):
        geom = shapely.force_2d(geom)
    coords = shapely.get_coordinates(geom)
    if coords.size and not np.isfinite(coords).all():
        bad = coords[~np.isfinite(coords).all(axis=1)][0]
        raise InvalidGeometryError(
            f"{where}: coordinates must be finite numbers, found ({float(bad[0])!r}, {float(bad[1])!r})"
        )
    if not shapely.is_valid(geom):
        reason = str(shapely.is_valid_reason(geom))
        hint = next((h for key, h in _HINTS if reason.startswith(key)), None)
        if hint is None:
            hint = "repair it in a GIS or with shapely.make_valid (which rounds coordinates)"
        if reason.startswith("Self-intersection") and isinstance(geom, MultiPolygon):
            hint += "; overlapping polygons can be written as separate features, which are united exactly"
        raise InvalidGeometryError(f"{where}: invalid {geom.geom_type}: {reason}; {hint}")
    return geom


def combine(geoms: Iterable[BaseGeometry]) -> BaseGeometry:
    """Return one geometry holding every point of ``geoms``, without rounding any coordinate.

    Non-overlapping polygons become a MultiPolygon, lines a MultiLineString, points a MultiPoint. Polygons
    that overlap or share an edge cannot form a valid MultiPolygon and computing their union with GEOS would
    round the new vertices, so they are kept as they are in a GeometryCollection: its point set is their
    union, and every discretization model is union-stable, D(A ∪ B) = D(A) ∪ D(B).
    """
    flat = [part for g in geoms for part in _flatten(g)]
    if not flat:
        return GeometryCollection()
    if len(flat) == 1:
        return flat[0]
    if all(isinstance(g, Polygon) for g in flat):
        mp = MultiPolygon(flat)
        if shapely.is_valid(mp):
            return mp
    elif all(isinstance(g, LineString) for g in flat):
        return MultiLineString(flat)
    elif all(isinstance(g, Point) for g in flat):
        return MultiPoint(flat)
    return GeometryCollection(flat)


def _flatten(g: BaseGeometry) -> list[BaseGeometry]:
    """The non-empty single parts (Point, LineString, Polygon) of a geometry, in order."""
    if g.is_empty:
        return []
    if isinstance(g, MultiPolygon | MultiLineString | MultiPoint | GeometryCollection):
        return [p for part in g.geoms for p in _flatten(part)]
    return [g]


# ---------------------------------------------------------------------------------------------- reading
def _read_text(path: PathLike) -> str:

    name = os.fspath(path)
    with open_regular(path, name) as fh:  # a FIFO or device is refused, never waited on
        size = os.fstat(fh.fileno()).st_size
        if size > MAX_VECTOR_FILE_BYTES:
            raise FileFormatError(
                f"{name}: the file is {size / 2**20:.0f} MB, more than the "
                f"{MAX_VECTOR_FILE_BYTES // 2**20} MB accepted for vector files"
            )
        data = fh.read(MAX_VECTOR_FILE_BYTES + 1)
    if len(data) > MAX_VECTOR_FILE_BYTES:
        raise FileFormatError(f"{name}: more than the {MAX_VECTOR_FILE_BYTES // 2**20} MB accepted")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise FileFormatError(f"{name}: not a UTF-8 text file (invalid byte at position {e.start})") from None


def _reject_constant(token: str) -> Any:
    raise ValueError(f"{token} is not a JSON number")


def _clean_coordinates(coords: Any, depth: int, where: str) -> Any:
    """Check the nesting and numbers of GeoJSON coordinates; return them with 2-D positions."""
    if depth == 0:
        if not isinstance(coords, list):
            raise FileFormatError(f"{where}: a position must be an array of numbers, found {coords!r:.60}")
        if not coords:
            return coords  # an empty Point
        if len(coords) < 2:
            raise FileFormatError(f"{where}: a position needs two numbers, found {coords!r:.60}")
        x, y = coords[0], coords[1]
        for v in (x, y):
            if isinstance(v, bool) or not isinstance(v, int | float):
                raise FileFormatError(f"{where}: coordinates must be numbers, found {v!r:.60}")
        return [x, y]
    if not isinstance(coords, list):
        raise FileFormatError(f"{where}: coordinates nested wrongly, expected an array, found {coords!r:.60}")
    return [_clean_coordinates(c, depth - 1, where) for c in coords]


def _count_positions(coords: Any, depth: int) -> int:
    if depth == 0:
        return 1
    if depth == 1:
        return len(coords)
    return sum(_count_positions(c, depth - 1) for c in coords)


def _geojson_geometry(obj: Any, where: str, name: str, depth: int = 1) -> BaseGeometry:
    if not isinstance(obj, dict):
        raise FileFormatError(f"{where}: a geometry must be a JSON object")
    gtype = obj.get("type")
    if gtype == "GeometryCollection":
        if depth > MAX_GEOMETRY_NESTING:
            raise FileFormatError(
                f"{where}: geometry collections nested more than {MAX_GEOMETRY_NESTING} deep"
            )
        members = obj.get("geometries")
        if not isinstance(members, list):
            raise FileFormatError(f"{where}: a GeometryCollection needs a 'geometries' array")
        return GeometryCollection(
            [_geojson_geometry(g, f"{where}, geometry {i}", name, depth + 1) for i, g in enumerate(members)]
        )
    if gtype not in _GEOJSON_DEPTH:
        raise FileFormatError(f"{where}: unsupported GeoJSON geometry type {gtype!r}")
    if "coordinates" not in obj:
        raise FileFormatError(f"{where}: the {gtype} has no 'coordinates'")
    coords = _clean_coordinates(obj["coordinates"], _GEOJSON_DEPTH[str(gtype)], where)
    n = _count_positions(coords, _GEOJSON_DEPTH[str(gtype)])
    if n > MAX_OBJECT_VERTICES:
        raise FileFormatError(f"{where}: {n:,} positions, more than the limit of {MAX_OBJECT_VERTICES:,}")
    try:
        geom = shape({"type": gtype, "coordinates": coords})
    except Exception as e:  # shapely's constructors raise ValueError, GEOSException, …
        raise InvalidGeometryError(f"{where}: cannot build the {gtype}: {e}") from None
    return check_geometry(geom, where)


def _feature_name(feature: dict[str, Any]) -> str | None:
    props = feature.get("properties")
    if isinstance(props, dict):
        for key in ("part", "name"):
            if props.get(key) is not None:
                return str(props[key])
    if feature.get("id") is not None:
        return str(feature["id"])
    return None


def _clean_label(label: str | None) -> str | None:
    """A feature name made storable: no lone surrogate, at most the name limit (mrm.core.limits)."""
    return None if label is None else clean_name(label)


def _read_geojson(path: PathLike) -> list[NamedGeometry]:
    name = os.fspath(path)
    text = _read_text(path)
    try:
        doc = json.loads(text, parse_constant=_reject_constant)
    except json.JSONDecodeError as e:
        raise FileFormatError(
            f"{name}: malformed JSON at line {e.lineno}, column {e.colno}: {e.msg}"
        ) from None
    except ValueError as e:
        raise FileFormatError(f"{name}: malformed JSON: {e}") from None
    except RecursionError:
        raise FileFormatError(f"{name}: the JSON is nested too deeply") from None
    if not isinstance(doc, dict) or not isinstance(doc.get("type"), str):
        raise FileFormatError(f"{name}: not GeoJSON: expected an object with a 'type'")
    kind = doc["type"]
    if kind == "FeatureCollection":
        features = doc.get("features")
        if not isinstance(features, list):
            raise FileFormatError(f"{name}: a FeatureCollection needs a 'features' array")
    elif kind == "Feature":
        features = [doc]
    else:
        return [(None, _geojson_geometry(doc, f"{name}: the geometry", name))]
    out: list[NamedGeometry] = []
    for i, feature in enumerate(features):
        where = f"{name}: feature {i}"
        if not isinstance(feature, dict) or feature.get("type") != "Feature":
            raise FileFormatError(f"{where} is not a GeoJSON Feature")
        label = _clean_label(_feature_name(feature))
        if label is not None:
            where += f" ({label!r})"
        if "geometry" not in feature:
            raise FileFormatError(f"{where} has no 'geometry' member")
        if feature["geometry"] is None:
            continue  # an unlocated feature holds no point
        out.append((label, _geojson_geometry(feature["geometry"], where, name)))
    return out


def _read_wkt(path: PathLike) -> list[NamedGeometry]:
    """One geometry per statement; a statement may span lines (it ends when its parentheses balance)."""
    name = os.fspath(path)
    text = _read_text(path)
    deepest = max_nesting(text)
    if deepest > MAX_GEOMETRY_NESTING:
        # GEOS parses nesting by recursion: 20,000 levels crash the process, 1,000 overflow Python's stack.
        raise FileFormatError(
            f"{name}: the WKT nests parentheses {deepest:,} deep, more than the {MAX_GEOMETRY_NESTING} "
            "a geometry can need"
        )
    out: list[NamedGeometry] = []
    buf: list[str] = []
    depth = 0
    start = 0
    for lineno, line in enumerate(text.splitlines(), start=1):
        if not buf and not line.strip():
            continue
        if not buf:
            start = lineno
        buf.append(line)
        depth += line.count("(") - line.count(")")
        if depth < 0:
            raise FileFormatError(f"{name}: line {lineno}: unbalanced ')'")
        if depth > 0:
            continue
        out.append((None, _parse_wkt("\n".join(buf), f"{name}: line {start}")))
        buf = []
    if buf:
        raise FileFormatError(f"{name}: line {start}: the geometry is not closed (missing ')')")
    return out


def max_nesting(text: str, open_: str = "(", close: str = ")", chunk: int = 1 << 22) -> int:
    """The deepest nesting of ``open_``/``close`` in ``text`` (linear, a few MB of memory at most)."""
    if open_ not in text:
        return 0
    o, c = ord(open_), ord(close)
    deepest = 0
    level = 0
    for start in range(0, len(text), chunk):
        b = np.frombuffer(text[start : start + chunk].encode("utf-8", "replace"), dtype=np.uint8)
        steps = (b == o).astype(np.int32) - (b == c).astype(np.int32)
        if not steps.any():
            continue
        run = np.cumsum(steps, dtype=np.int64) + level
        deepest = max(deepest, int(run.max()))
        level = int(run[-1])
    return deepest


def _parse_wkt(text: str, where: str) -> BaseGeometry:
    positions = text.count(",") + 1
    if positions > MAX_OBJECT_VERTICES:
        raise FileFormatError(
            f"{where}: about {positions:,} positions, more than the limit of {MAX_OBJECT_VERTICES:,}"
        )
    try:
        # NaN coordinates make GEOS's parser raise a floating-point warning; the check below gives the
        # message, so the warning (printed above it) is silenced here, for this thread only.
        with np.errstate(invalid="ignore"):
            geom = shapely.from_wkt(text)
    except GEOSException as e:
        raise FileFormatError(f"{where}: malformed WKT: {str(e).removeprefix('ParseException: ')}") from None
    except NotImplementedError as e:  # curved types
        raise InvalidGeometryError(f"{where}: unsupported geometry: {e}") from None
    except Exception as e:
        raise FileFormatError(f"{where}: malformed WKT: {e}") from None
    return check_geometry(geom, where)


def read_geometries(path: PathLike) -> list[NamedGeometry]:
    """Read every geometry of a GeoJSON or WKT file, each with its name.

    Parameters
    ----------
    path : str or path-like
        ``.geojson`` / ``.json`` (a Feature, a FeatureCollection or a bare geometry) or ``.wkt`` (one
        geometry, or several one after the other — one per line, or spanning lines).

    Returns
    -------
    list of (str or None, shapely geometry)
        In file order. The name is a feature's ``part`` or ``name`` property, else its ``id``, else None
        (always None for WKT). Features without geometry are skipped.

    Raises
    ------
    FileFormatError
        Unknown extension, file over 100 MB, not UTF-8, malformed JSON (with line and column) or WKT
        (with line), not GeoJSON, non-numeric coordinates.
    InvalidGeometryError
        See :func:`check_geometry`.
    """
    ext = Path(path).suffix.lower()
    try:
        if ext in (".geojson", ".json"):
            return _read_geojson(path)
        if ext == ".wkt":
            return _read_wkt(path)
    except RecursionError:  # every import error is a message, never an escaping exception
        raise FileFormatError(f"{os.fspath(path)}: the geometry is nested too deeply") from None
    except MemoryError:
        raise FileFormatError(f"{os.fspath(path)}: not enough memory to read the geometry") from None
    shown = f"'{ext}'" if ext else "no extension"
    raise FileFormatError(
        f"{os.fspath(path)}: {shown} is not a vector file type; use .geojson, .json or .wkt"
    )


def read_geometry(path: PathLike) -> BaseGeometry:
    """Read a GeoJSON or WKT file as one geometry: all its geometries combined (see :func:`combine`)."""
    return combine(g for _, g in read_geometries(path))


# ---------------------------------------------------------------------------------------------- writing
def _num(v: float) -> str:
    """A coordinate as text that reads back as the same float64."""
    f = float(v)
    if not math.isfinite(f):
        raise InvalidGeometryError(f"cannot write the non-finite coordinate {f!r}")
    return repr(f)


def _polygon_coordinates(polys: Any) -> list[Any]:
    """The GeoJSON coordinates of each polygon of ``polys``, in a few array passes.

    One pass over a large result instead of one shapely call per ring: a 50 % noise image has 42,000
    components and 44,000 rings, and reading them ring by ring took longer than reconstructing them.
    Rings are oriented as RFC 7946 asks (exterior counter-clockwise, holes clockwise); GEOS reverses a ring
    in place, first point kept, exactly as :func:`shapely.geometry.polygon.orient` does. An empty polygon
    gives ``[]``.
    """
    polys = shapely.orient_polygons(np.asarray(polys, dtype=object))
    rings, ring_of = shapely.get_rings(polys, return_index=True)
    coords, coord_of = shapely.get_coordinates(rings, return_index=True)
    flat = coords.tolist()  # Python floats, each written by json with repr: it reads back identical
    ring_lists = _split(flat, np.bincount(coord_of, minlength=len(rings)))
    return _split(ring_lists, np.bincount(ring_of, minlength=len(polys)))


def _split(items: list[Any], counts: np.ndarray) -> list[list[Any]]:
    """``items`` cut into consecutive lists of ``counts[i]`` items."""
    return [items[a:b] for a, b in pairwise([0, *np.cumsum(counts).tolist()])]


def _geojson_of(g: BaseGeometry) -> dict[str, Any]:
    def pos(c: Sequence[float]) -> list[float]:
        return [float(c[0]), float(c[1])]

    if isinstance(g, Point):
        return {"type": "Point", "coordinates": [] if g.is_empty else pos(g.coords[0])}
    if isinstance(g, LineString):
        return {"type": "LineString", "coordinates": [pos(c) for c in g.coords]}
    if isinstance(g, Polygon):
        return {"type": "Polygon", "coordinates": _polygon_coordinates([g])[0]}
    if isinstance(g, MultiPolygon):
        return {"type": "MultiPolygon", "coordinates": _polygon_coordinates(shapely.get_parts(g))}
    if isinstance(g, MultiPoint | MultiLineString):
        return {
            "type": g.geom_type,
            "coordinates": [_geojson_of(part)["coordinates"] for part in g.geoms],
        }
    if isinstance(g, GeometryCollection):
        return {"type": "GeometryCollection", "geometries": [_geojson_of(part) for part in g.geoms]}
    raise InvalidGeometryError(f"cannot write a {g.geom_type} as GeoJSON")


#: Upper bounds of the bytes written per coordinate pair (two float reprs and punctuation) and per SVG run.
_BYTES_PER_POSITION = 52
_BYTES_PER_RUN = 80


def _check_geometry_output(geoms: Iterable[BaseGeometry], path: PathLike) -> None:
    """Refuse, before building any text, a file larger than :data:`mrm.core.limits.MAX_OUTPUT_BYTES`."""
    n = sum(int(shapely.get_num_coordinates(g)) for g in geoms)
    check_output_bytes(n * _BYTES_PER_POSITION, f"{os.fspath(path)} ({n:,} positions)")


def _parts(geom_or_parts: Any) -> list[tuple[Any, BaseGeometry]] | None:
    """None for a single geometry, else [(part name, geometry)]."""
    if isinstance(geom_or_parts, BaseGeometry):
        return None
    if isinstance(geom_or_parts, Mapping):
        return list(geom_or_parts.items())
    out: list[tuple[Any, BaseGeometry]] = []
    for i, item in enumerate(geom_or_parts):
        if isinstance(item, BaseGeometry):
            out.append((i, item))
        else:
            label, g = item
            out.append((label, g))
    return out


def write_geojson(
    geom_or_parts: BaseGeometry | Mapping[Any, BaseGeometry] | Iterable[Any],
    path: PathLike,
    properties: Mapping[str, Any] | None = None,
    *,
    members: Mapping[str, Any] | None = None,
) -> None:
    """Write a FeatureCollection, atomically.

    Parameters
    ----------
    geom_or_parts : shapely geometry, or parts
        One geometry gives one Feature. Parts — a mapping name → geometry, a list of (name, geometry) or a
        list of geometries (named 0, 1, …) — give one Feature each, with a ``part`` property.
    path : str or path-like
    properties : mapping, optional
        Properties added to every Feature.
    members : mapping, optional
        Members added to the FeatureCollection (``crs``, ``bbox`` of a georeferenced result: mrm.io.georef).

    Notes
    -----
    Polygons are oriented as RFC 7946 asks (exterior counter-clockwise); coordinates are written with
    ``repr`` and read back identical.
    """
    parts = _parts(geom_or_parts)
    _check_geometry_output([geom_or_parts] if parts is None else [g for _, g in parts], path)
    base = dict(properties or {})
    try:
        with paused_gc():  # 10⁵–10⁶ coordinate lists, none in a cycle
            if parts is None:
                assert isinstance(geom_or_parts, BaseGeometry)
                geometry = _geojson_of(geom_or_parts)
                features = [{"type": "Feature", "properties": base, "geometry": geometry}]
            else:
                features = [
                    {"type": "Feature", "properties": {**base, "part": label}, "geometry": _geojson_of(g)}
                    for label, g in parts
                ]
            doc = {"type": "FeatureCollection", **dict(members or {}), "features": features}
            text = json.dumps(doc, allow_nan=False)
    except ValueError:
        raise InvalidGeometryError(f"{os.fspath(path)}: cannot write NaN or infinite coordinates") from None
    with atomic_open(path, "w") as fh:
        fh.write(text + "\n")


def write_regions_geojson(
    regions: Iterable[Any], path: PathLike, *, members: Mapping[str, Any] | None = None
) -> None:
    """Write a label map's regions as a FeatureCollection, atomically: one Feature per region.

    ``regions`` are those of :func:`mrm.geometry.reconstruct.polygonize.polygonize` (label, pixels, geometry);
    each Feature has the properties ``label`` and ``pixels``. What ``mrm polygonize`` and the application's
    export of a label map object write (ADR 0033).
    """
    regions = list(regions)
    write_features(
        [r.geometry for r in regions],
        [{"label": r.label, "pixels": r.pixels} for r in regions],
        path,
        members=members,
    )


def write_features(
    geometries: Sequence[BaseGeometry],
    properties: Sequence[Mapping[str, Any]],
    path: PathLike,
    *,
    members: Mapping[str, Any] | None = None,
) -> None:
    """Write one Feature per geometry, with its properties, as a FeatureCollection, atomically.

    Coordinates are written with ``repr`` (they read back identical), polygons oriented as RFC 7946 asks;
    ``members`` are added to the FeatureCollection (``crs``, ``bbox``).
    """
    _check_geometry_output(geometries, path)
    try:
        with paused_gc():
            features = [
                {"type": "Feature", "properties": dict(props), "geometry": _geojson_of(g)}
                for g, props in zip(geometries, properties, strict=True)
            ]
            text = json.dumps({"type": "FeatureCollection", **dict(members or {}), "features": features},
                              allow_nan=False)  # fmt: skip
    except ValueError:
        raise InvalidGeometryError(f"{os.fspath(path)}: cannot write NaN or infinite coordinates") from None
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with atomic_open(path, "w") as fh:
        fh.write(text + "\n")


def wkt_of(g: BaseGeometry) -> str:
    """Return the WKT of a 2-D geometry with every coordinate written exactly (``repr``)."""

    def seq(coords: Any) -> str:
        return ", ".join(f"{_num(c[0])} {_num(c[1])}" for c in coords)

    def body(g: BaseGeometry) -> str:
        if isinstance(g, Point):
            return f"({seq(g.coords)})"
        if isinstance(g, LineString):
            return f"({seq(g.coords)})"
        if isinstance(g, Polygon):
            rings = [g.exterior, *g.interiors]
            return "(" + ", ".join(f"({seq(r.coords)})" for r in rings) + ")"
        if isinstance(g, MultiPoint | MultiLineString | MultiPolygon):
            return "(" + ", ".join(body(p) for p in g.geoms) + ")"
        if isinstance(g, GeometryCollection):
            return "(" + ", ".join(wkt_of(p) for p in g.geoms) + ")"
        raise InvalidGeometryError(f"cannot write a {g.geom_type} as WKT")

    kind = "LINESTRING" if isinstance(g, LinearRing) else g.geom_type.upper()
    if g.is_empty:
        return f"{kind} EMPTY"
    return f"{kind} {body(g)}"


def write_wkt(geom: BaseGeometry | Iterable[BaseGeometry], path: PathLike) -> None:
    """Write one geometry, or several (one per line), as WKT, atomically and exactly."""
    geoms = [geom] if isinstance(geom, BaseGeometry) else list(geom)
    _check_geometry_output(geoms, path)
    text = "".join(wkt_of(g) + "\n" for g in geoms)
    with atomic_open(path, "w") as fh:
        fh.write(text)


# ---------------------------------------------------------------------------------------------- SVG
# Colours: a geometry alone is filled; over pixels it is only outlined, in a colour that stands out from
# the light pixel squares, so that both representations stay readable.
_DARK = "#1f4e79"
_OUTLINE = "#c2410c"
_LIGHT_PIXELS = "#bcd6f0"
_FILL = f'fill="#4a90d9" fill-opacity="0.55" stroke="{_DARK}"'


def _svg_path(coords: Any, close: bool) -> str:
    pts = [f"{_num(c[0])} {_num(-float(c[1]))}" for c in coords]
    if not pts:
        return ""
    return "M " + " L ".join(pts) + (" Z" if close else "")


def _svg_elements(g: BaseGeometry, r: float, outline: bool = False, fill: str = _FILL) -> list[str]:
    """SVG elements of a geometry: polygons filled (or only outlined), lines stroked, points as dots."""
    if g.is_empty:
        return []
    color = _OUTLINE if outline else _DARK
    if isinstance(g, Polygon):
        d = " ".join(_svg_path(ring.coords, True) for ring in [g.exterior, *g.interiors])
        paint = f'fill="none" stroke="{color}" stroke-width="2" stroke-linejoin="round"' if outline else fill
        return [f'<path d="{d}" fill-rule="evenodd" {paint} vector-effect="non-scaling-stroke"/>']
    if isinstance(g, LineString):
        return [
            f'<path d="{_svg_path(g.coords, False)}" fill="none" stroke="{color}" stroke-width="2" '
            'vector-effect="non-scaling-stroke"/>'
        ]
    if isinstance(g, Point):
        return [f'<circle cx="{_num(g.x)}" cy="{_num(-g.y)}" r="{_num(r)}" fill="{color}"/>']
    if isinstance(g, MultiPolygon | MultiLineString | MultiPoint | GeometryCollection):
        return [e for part in g.geoms for e in _svg_elements(part, r, outline, fill)]
    raise InvalidGeometryError(f"cannot draw a {g.geom_type} in SVG")


def _run_count(ps: PixelSet) -> int:
    """The number of maximal horizontal runs of pixels (one SVG rectangle each), a strip at a time."""
    m = ps.mask
    runs = 0
    for r0 in range(0, m.shape[0], 1024):
        s = m[r0 : r0 + 1024]
        runs += int(np.count_nonzero(s[:, 0])) + int(np.count_nonzero(s[:, 1:] & ~s[:, :-1]))
    return runs


def _pixel_rects(ps: PixelSet) -> list[str]:
    """One rectangle per maximal horizontal run of pixels: pixel (x, y) covers [x−½, x+½] × [y−½, y+½]."""
    if ps.is_empty():
        return []
    x0, y0 = ps.origin
    m = ps.mask
    padded = np.zeros((m.shape[0], m.shape[1] + 2), dtype=np.int8)
    padded[:, 1:-1] = m
    d = np.diff(padded, axis=1)
    rows_s, starts = np.nonzero(d == 1)
    _, ends = np.nonzero(d == -1)  # same row order as the starts, one end per start
    out = []
    for row, s, e in zip(rows_s.tolist(), starts.tolist(), ends.tolist(), strict=True):
        x, y = x0 + s, y0 + row
        out.append(f'<rect x="{_num(x - 0.5)}" y="{_num(-(y + 0.5))}" width="{e - s}" height="1"/>')
    return out


def write_svg(
    geom_or_pixels: BaseGeometry | PixelSet | None,
    path: PathLike,
    *,
    pixels: PixelSet | None = None,
    colour: str | None = None,
    opacity: float = 0.55,
) -> None:
    """Draw a geometry, a pixel set, or a geometry over a pixel set as an SVG picture, upright, atomically.

    Parameters
    ----------
    geom_or_pixels : shapely geometry or PixelSet or None
        What to draw. A geometry alone is filled (polygons with holes by the even-odd rule); a pixel set
        alone is drawn dark, as its voxels merged into one rectangle per horizontal run.
    path : str or path-like
        The .svg file to write.
    pixels : PixelSet, optional
        With a geometry (or None) as first argument: a pixel set drawn underneath as light squares, the
        geometry then only outlined on top of them — a picture of a discretization or a reconstruction.
    colour : str, optional
        The fill of the polygons (an object's colour, ``#rrggbb``); the outline is the same colour,
        darkened. A blue by default.
    opacity : float
        The fill's opacity, with ``colour``.

    Notes
    -----
    Plane coordinates are written as they are, exactly, except y, which is negated: SVG's y axis points
    down, so the point (x, y) is written (x, −y) and the picture is upright (y up). The viewBox holds
    everything drawn (voxels and geometry) with a small margin. The pixels are in ``<g id="pixels">``;
    the geometry's elements follow, at the top level, so they are drawn on top.
    """
    if isinstance(geom_or_pixels, PixelSet):
        if pixels is not None:
            raise TypeError("write_svg: give the pixels once (a geometry first, or pixels= alone)")
        geom, pixels = None, geom_or_pixels
        pixel_fill = _DARK
    else:
        geom = geom_or_pixels
        pixel_fill = _LIGHT_PIXELS
    boxes: list[tuple[float, float, float, float]] = []
    if pixels is not None and pixels.bbox is not None:
        x0, y0, x1, y1 = pixels.bbox
        boxes.append((x0 - 0.5, y0 - 0.5, x1 + 0.5, y1 + 0.5))
    if geom is not None and not geom.is_empty:
        gx0, gy0, gx1, gy1 = (float(b) for b in geom.bounds)
        boxes.append((gx0, gy0, gx1, gy1))
    estimate = 0
    if pixels is not None and not pixels.is_empty():
        estimate += _run_count(pixels) * _BYTES_PER_RUN
    if geom is not None:
        estimate += int(shapely.get_num_coordinates(geom)) * _BYTES_PER_POSITION
    check_output_bytes(estimate, f"{os.fspath(path)} (an SVG picture)")  # before any text is built
    bounds = joint_box(boxes) or (0.0, 0.0, 1.0, 1.0)
    size = max(bounds[2] - bounds[0], bounds[3] - bounds[1], 1.0)
    body: list[str] = []
    if pixels is not None:
        body += [
            f'<g id="pixels" fill="{pixel_fill}" shape-rendering="crispEdges">',
            *_pixel_rects(pixels),
            "</g>",
        ]
    fill = _FILL
    if colour is not None:
        if not re.fullmatch(r"#[0-9a-fA-F]{6}", colour):
            raise ValueError(f"write_svg: colour must look like #rrggbb, got {colour!r}")
        rgb = [int(colour[i : i + 2], 16) for i in (1, 3, 5)]
        edge = "#" + "".join(f"{round(c * 0.6):02x}" for c in rgb)
        fill = f'fill="{colour}" fill-opacity="{min(1.0, max(0.0, opacity)):.3g}" stroke="{edge}"'
    if geom is not None:
        body += _svg_elements(geom, size / 200, outline=pixels is not None, fill=fill)
    margin = max(size * 0.02, 0.5)
    xmin, ymin, xmax, ymax = bounds[0] - margin, bounds[1] - margin, bounds[2] + margin, bounds[3] + margin
    w, h = xmax - xmin, ymax - ymin
    scale = 800 / max(w, h)
    header = (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{w * scale:.1f}" height="{h * scale:.1f}" '
        f'viewBox="{_num(xmin)} {_num(-ymax)} {_num(w)} {_num(h)}">\n'
    )
    with atomic_open(path, "w") as fh:
        fh.write(header + "".join(line + "\n" for line in body) + "</svg>\n")
