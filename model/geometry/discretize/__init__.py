"""The exact discretization D of Euclidean geometry into pixels, in three models (docs/design.md §2).

Every model is a narrow offset discretization: a kernel K(p) ⊂ V(p) is fixed for each pixel p and

    D(E) = { p ∈ Z² : E ∩ K(p) ≠ ∅ },        τ = (ε, ε²), ε → 0⁺.

============== ================================================= ============================================
model          K(p)                                              reads
============== ================================================= ============================================
``standard``   the open unit square int V(p), shifted by τ       Andres' standard model; no bubbles; a cover
``supercover`` the closed unit square V(p)                       every pixel the closed set touches
``gauss``      the single point p + τ                            pixel-centre sampling with a tie rule
============== ================================================= ============================================

How each is computed (docs/algorithms.md §1.7). For a polygonal set P (rings of polygons, holes included):

* gauss: { p : p + τ ∈ P }, an exact scanline. On row y = j an edge a→b counts when a_y ≤ j < b_y (or
  b_y ≤ j < a_y) and p_x < X strictly, X being where it crosses the row; p is inside when the count is odd.
* standard: gauss(P) ∪ the standard walks of all edges;  supercover: gauss(P) ∪ the supercover walks.
  (If K(p) meets P but no edge, the connected K(p) lies inside P and so does p + τ.)

Segments and points are discretized by their walks / cells. Under ``gauss`` a segment or a point
contains no p + τ, so it discretizes to the empty set: thin parts of a geometry vanish in that model.

All decisions are exact for float64 input (dyadic rationals): a float filter decides the easy cases and
floating-point expansions decide the rest, or plain float arithmetic when it is provably exact for the
whole geometry (snapped input). Nothing uses an epsilon and shapely never decides a pixel.

Input rules (InvalidGeometryError otherwise): coordinates finite, |v| ≤ 2^51, and v = 0 or |v| ≥ 2^-400
(the exact arithmetic must neither overflow nor underflow); polygons valid in the OGC sense. Validity of a
large hole-less polygon is proved by an exact sweep (GEOS can be slow on spiky rings); every other case, and
every failure to prove, goes to GEOS, whose reason and location end up in the message. The size limit is
checked on the bounding box before any pixel array is allocated.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
import shapely

from mrm.core.errors import InvalidGeometryError
from mrm.core.grids import Box, PixelSet, box_area
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, check_pixels
from mrm.core.models import Model, cell_index
from mrm.geometry.discretize import _kernels as _k
from mrm.geometry.discretize.exact import (
    MAX_ABS_COORD,
    MIN_ABS_COORD,
    check_coordinate_range,
    closed_cell_range,
    float_predicates_are_exact,
)

#: The discretization models, the default first.

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

_EMPTY = np.zeros(0, dtype=np.float64)
_POINT, _LINESTRING, _LINEARRING, _POLYGON = 0, 1, 2, 3
_MULTIPOINT, _MULTILINESTRING, _MULTIPOLYGON, _COLLECTION = 4, 5, 6, 7


@dataclass(frozen=True)
class _Pieces:
    """A geometry taken apart into what the kernels need, all float64 and validated."""

    # Edges of polygonal members, grouped: group g is fill_*[starts[g]:starts[g+1]] (one Polygon or one
    # valid MultiPolygon, whose pieces have disjoint interiors, so the even-odd rule holds for the group).
    fill_ax: Floats
    fill_ay: Floats
    fill_bx: Floats
    fill_by: Floats
    starts: Ints
    # Segments of linear members (polygon edges are added for the walks).
    line_ax: Floats
    line_ay: Floats
    line_bx: Floats
    line_by: Floats
    # Isolated points.
    px: Floats
    py: Floats

    def coordinates(self, with_thin: bool = True) -> Floats:
        """All coordinates that matter (x and y values together), optionally without lines and points."""
        parts = [self.fill_ax, self.fill_ay]
        if with_thin:
            parts += [self.line_ax, self.line_ay, self.line_bx, self.line_by, self.px, self.py]
        return np.concatenate(parts)

    def extent(self, with_thin: bool = True) -> tuple[float, float, float, float] | None:
        """(xmin, ymin, xmax, ymax) of the coordinates, or None when there are none."""
        xs = [self.fill_ax]
        ys = [self.fill_ay]
        if with_thin:
            xs += [self.line_ax, self.line_bx, self.px]
            ys += [self.line_ay, self.line_by, self.py]
        x = np.concatenate(xs)
        y = np.concatenate(ys)
        if x.size == 0:
            return None
        return float(x.min()), float(y.min()), float(x.max()), float(y.max())


# --------------------------------------------------------------------------------------- public API
def discretize(
    geom: Any,
    model: str = "standard",
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    check_validity: bool = True,
) -> PixelSet:
    """Return the exact discretization D(geom) in one of the three models (docs/design.md §2).

    Parameters
    ----------
    geom : shapely geometry
        Polygon or MultiPolygon (holes allowed), LineString, LinearRing or MultiLineString (polylines),
        Point or MultiPoint, a GeometryCollection of those, or an empty geometry. Polygons must be valid;
        the members of a collection may overlap (the result is the union of their discretizations).
    model : {"standard", "supercover", "gauss"}
        The kernel: shifted open square, closed square, or shifted centre. Under ``"gauss"`` segments and
        points (and every part thinner than the pixel spacing that misses all centres) discretize to nothing.
    limit : int or None
        Largest bounding-box size (in pixels) allowed for the result; None for no limit. Checked before any
        pixel array is allocated.
    check_validity : bool
        False skips the validity check of the polygons (shapely's ``is_valid``, a third of the time of D on
        a 1024² object) for a caller that knows them valid, e.g. R's output under an exact scaling. D of an
        invalid polygon is then undefined.

    Returns
    -------
    PixelSet
        The pixels p with geom ∩ K(p) ≠ ∅, empty for an empty geometry.

    Raises
    ------
    ParameterError
        Unknown model or bad limit.
    InvalidGeometryError
        Not a supported shapely geometry, a NaN / infinite / out-of-range coordinate, or an invalid polygon
        (the message says where and how to repair it).
    SizeLimitError
        The result's bounding box would exceed ``limit`` pixels.
    """
    model = Model.parse(model)
    pieces = _take_apart(geom, check_validity=check_validity)
    return _discretize_pieces(pieces, model, limit)


def discretize_segment(
    p: tuple[float, float],
    q: tuple[float, float],
    model: str = "standard",
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> PixelSet:
    """Return D([p, q]) for the closed segment from ``p`` to ``q`` (a point when p == q).

    ``"standard"`` gives the 4-connected standard line (|Δx| + |Δy| + 1 pixels between pixel centres, one
    per diagonal index); ``"supercover"`` adds the bubbles at pixel corners and both sides of a segment that
    runs along a grid line; ``"gauss"`` gives the empty set (a segment holds no shifted centre).
    """
    model = Model.parse(model)
    arr = np.array([p[0], p[1], q[0], q[1]], dtype=np.float64)
    _check_values(arr, "segment")
    one = np.zeros(1, dtype=np.float64)
    pieces = _Pieces(
        _EMPTY,
        _EMPTY,
        _EMPTY,
        _EMPTY,
        np.zeros(1, dtype=np.int64),
        one + arr[0],
        one + arr[1],
        one + arr[2],
        one + arr[3],
        _EMPTY,
        _EMPTY,
    )
    return _discretize_pieces(pieces, model, limit)


def discretization_box(geom: Any, model: str = "standard") -> Box | None:
    """Return the pixel box (xmin, ymin, xmax, ymax) that holds D(geom), or None for an empty geometry.

    The box is exact (tight) for ``"standard"`` and ``"supercover"``: D of a set is the union of D of its
    points, and the extreme coordinates' cells are reached. For ``"gauss"`` it is the standard box, which
    contains the result. Validates coordinates but not polygon validity.
    """
    return _box(_take_apart(geom, check_validity=False), Model.parse(model))


def estimate_pixels(geom: Any, model: str = "supercover") -> int:
    """Return the number of pixels of the array D(geom) needs: the area of :func:`discretization_box`.

    The default model gives the largest box of the three, an upper bound for any model.
    """
    return box_area(discretization_box(geom, model))


# ------------------------------------------------------------------------------------------- checks
def _check_values(values: Floats, what: str, coords: Floats | None = None) -> None:
    """Refuse NaN, infinite, too large and too tiny coordinates, naming the vertex."""
    found = check_coordinate_range(values)
    if found is None:
        return
    i, v = found
    where = ""
    if coords is not None and coords.size:
        x, y = coords.reshape(-1)[2 * (i // 2) : 2 * (i // 2) + 2]
        where = f" at vertex {i // 2} ({x!r}, {y!r})"
    if not np.isfinite(v):
        raise InvalidGeometryError(
            f"the {what} has a non-finite coordinate ({v!r}){where}; remove or repair that vertex"
        )
    if abs(v) > MAX_ABS_COORD:
        raise InvalidGeometryError(
            f"the {what} has a coordinate too large for exact pixel indices ({v!r}){where}: "
            f"|coordinates| must not exceed 2^51 ≈ {MAX_ABS_COORD:.3g}; translate or rescale the geometry"
        )
    raise InvalidGeometryError(
        f"the {what} has a non-zero coordinate too close to 0 for exact evaluation ({v!r}){where}: "
        f"|coordinates| must be 0 or at least 2^-400 ≈ {MIN_ABS_COORD:.3g}; round it to 0 or rescale"
    )


_LOCATION = re.compile(r"\[\s*([-+0-9.eEinfa]+)\s+([-+0-9.eEinfa]+)")


def _invalid_polygon_message(poly: Any) -> str:
    reason = str(shapely.is_valid_reason(poly))
    where = ""
    found = _LOCATION.search(reason)
    if found:
        where = f", or fix the ring at ({found.group(1)}, {found.group(2)})"
    return (
        f"invalid polygon: {reason}. Repair it with shapely.make_valid(geom) or geom.buffer(0){where}; "
        "a polygon must be valid (no self-intersection, holes inside their shell) to be discretized"
    )


# ------------------------------------------------------------------------------------- taking apart
def _take_apart(geom: Any, check_validity: bool = True) -> _Pieces:
    if not isinstance(geom, shapely.Geometry):
        raise InvalidGeometryError(
            "expected a shapely geometry (Polygon, MultiPolygon, LineString, Point, ...), "
            f"got {type(geom).__name__}"
        )
    polys: list[Any] = []
    lines: list[Any] = []
    points: list[Any] = []
    _sort_members(geom, polys, lines, points)

    all_coords = shapely.get_coordinates(geom)
    _check_values(all_coords.reshape(-1), "geometry", all_coords)

    if polys and check_validity:
        unproved = [p for p in polys if not _proved_valid(p)]
        if unproved:
            valid = shapely.is_valid(np.array(unproved, dtype=object))
            if not np.all(valid):
                raise InvalidGeometryError(_invalid_polygon_message(unproved[int(np.flatnonzero(~valid)[0])]))

    fill = _polygon_edges(polys)
    segs = _line_segments(lines)
    if points:
        pc = shapely.get_coordinates(np.array(points, dtype=object))
        px, py = np.ascontiguousarray(pc[:, 0]), np.ascontiguousarray(pc[:, 1])
    else:
        px, py = _EMPTY, _EMPTY
    return _Pieces(*fill, *segs, px, py)


#: Rings with fewer vertices are left to GEOS, which is fast on them.
_SWEEP_MIN_VERTICES = 64


def _proved_valid(poly: Any) -> bool:
    """True when an exact sweep proves ``poly`` a valid hole-less polygon (its ring is simple).

    GEOS's validity check can take tens of milliseconds on spiky polygons of a few thousand vertices (its
    noder tests every pair of edges whose boxes overlap); the sweep costs O(n log n + n·s), s the number of
    edges a vertical line crosses. False only means "not proved": GEOS then decides and explains.
    """
    if int(shapely.get_type_id(poly)) != _POLYGON or shapely.get_num_interior_rings(poly) != 0:
        return False
    coords = shapely.get_coordinates(poly)[:-1]  # the ring without its closing vertex
    if coords.shape[0] < _SWEEP_MIN_VERTICES:
        return False
    return _ring_proved_simple(coords)


def _ring_proved_simple(coords: Floats) -> bool:
    """True when the exact sweep proves the closed ring through ``coords`` (N, 2) simple; False = unknown.

    ``coords`` holds each vertex once (no closing repeat); repeated consecutive vertices are dropped here.
    """
    keep = np.any(coords != np.roll(coords, 1, axis=0), axis=1)
    xs = np.ascontiguousarray(coords[keep, 0], dtype=np.float64)
    ys = np.ascontiguousarray(coords[keep, 1], dtype=np.float64)
    if xs.size < 3:
        return False
    return bool(_k.ring_is_simple(xs, ys, np.lexsort((ys, xs)).astype(np.int64)))


def _sort_members(geom: Any, polys: list[Any], lines: list[Any], points: list[Any]) -> None:
    """Sort the non-empty members of ``geom`` into polygonal, linear and point members (recursively)."""
    if geom.is_empty:
        return
    tid = int(shapely.get_type_id(geom))
    if tid in (_POLYGON, _MULTIPOLYGON):
        polys.append(geom)
    elif tid in (_LINESTRING, _LINEARRING, _MULTILINESTRING):
        lines.append(geom)
    elif tid in (_POINT, _MULTIPOINT):
        points.append(geom)
    elif tid == _COLLECTION:
        for part in shapely.get_parts(geom):
            _sort_members(part, polys, lines, points)
    else:  # pragma: no cover - shapely 2 has no other 2-D types
        raise InvalidGeometryError(f"unsupported geometry type {geom.geom_type}")


def _pairs(coords: Floats, index: Ints) -> tuple[Floats, Floats, Floats, Floats, Ints]:
    """Segments between consecutive coordinates of the same part: (ax, ay, bx, by, part index)."""
    same = index[1:] == index[:-1]
    a = coords[:-1][same]
    b = coords[1:][same]
    return (
        np.ascontiguousarray(a[:, 0]),
        np.ascontiguousarray(a[:, 1]),
        np.ascontiguousarray(b[:, 0]),
        np.ascontiguousarray(b[:, 1]),
        index[:-1][same],
    )


def _polygon_edges(polys: list[Any]) -> tuple[Floats, Floats, Floats, Floats, Ints]:
    if not polys:
        return _EMPTY, _EMPTY, _EMPTY, _EMPTY, np.zeros(1, dtype=np.int64)
    parts, part_member = shapely.get_parts(np.array(polys, dtype=object), return_index=True)
    rings, ring_part = shapely.get_rings(parts, return_index=True)
    coords, coord_ring = shapely.get_coordinates(rings, return_index=True)
    ax, ay, bx, by, edge_ring = _pairs(coords, coord_ring)
    edge_member = part_member[ring_part[edge_ring]]  # non-decreasing: shapely keeps the input order
    # The fill kernel wants each group's edges sorted by their first row ⌈min y⌉.
    order = np.lexsort((np.ceil(np.minimum(ay, by)), edge_member))
    ax, ay, bx, by = (np.ascontiguousarray(v[order]) for v in (ax, ay, bx, by))
    starts = np.searchsorted(edge_member, np.arange(len(polys) + 1)).astype(np.int64)
    return ax, ay, bx, by, starts


def _line_segments(lines: list[Any]) -> tuple[Floats, Floats, Floats, Floats]:
    if not lines:
        return _EMPTY, _EMPTY, _EMPTY, _EMPTY
    parts = shapely.get_parts(np.array(lines, dtype=object))
    coords, index = shapely.get_coordinates(parts, return_index=True)
    ax, ay, bx, by, _ = _pairs(coords, index)
    return ax, ay, bx, by


# -------------------------------------------------------------------------------------------- boxes
def _box(pieces: _Pieces, model: str) -> Box | None:
    ext = pieces.extent(with_thin=model != "gauss")
    if ext is None:
        return None
    xmin, ymin, xmax, ymax = ext
    if model == "supercover":
        return (
            closed_cell_range(xmin)[0],
            closed_cell_range(ymin)[0],
            closed_cell_range(xmax)[1],
            closed_cell_range(ymax)[1],
        )
    return cell_index(xmin), cell_index(ymin), cell_index(xmax), cell_index(ymax)


# ---------------------------------------------------------------------------------------- computing
def _discretize_pieces(
    pieces: _Pieces, model: str, limit: int | None, exact_mode: bool | None = None
) -> PixelSet:
    """Run the kernels. ``exact_mode`` forces (True) or forbids (False) plain float predicates; None = auto.

    Forcing True on data that does not satisfy :func:`float_predicates_are_exact` gives wrong results; the
    override exists so that tests can drive the filtered/expansion path on snapped (tie-rich) input.
    """
    gauss = model == "gauss"
    supercover = model == "supercover"
    box = _box(pieces, model)
    if box is None:
        return PixelSet.empty()
    check_pixels(box_area(box), limit, "discretization")
    if exact_mode is None:
        exact_mode = float_predicates_are_exact(pieces.coordinates(with_thin=not gauss))
    x0, y0, x1, y1 = box
    mask = np.zeros((y1 - y0 + 1, x1 - x0 + 1), dtype=bool)
    scratch = np.zeros(_k.SCRATCH_SIZE, dtype=np.float64)
    big = np.iinfo(np.int64).max
    ext = np.array([big, big, -big, -big], dtype=np.int64)
    bad = 0
    if pieces.fill_ax.size:
        bad += _k.fill_groups(
            mask,
            x0,
            y0,
            pieces.fill_ax,
            pieces.fill_ay,
            pieces.fill_bx,
            pieces.fill_by,
            pieces.starts,
            exact_mode,
            scratch,
            ext,
        )
    if not gauss:
        for ax, ay, bx, by in (
            (pieces.fill_ax, pieces.fill_ay, pieces.fill_bx, pieces.fill_by),
            (pieces.line_ax, pieces.line_ay, pieces.line_bx, pieces.line_by),
        ):
            if ax.size:
                bad += _k.walk_segments(mask, x0, y0, ax, ay, bx, by, supercover, exact_mode, scratch)
        if pieces.px.size:
            bad += _k.mark_points(mask, x0, y0, pieces.px, pieces.py, supercover)
    if bad:  # pragma: no cover - the boxes above are proven to hold every pixel
        raise RuntimeError(f"internal error: {bad} pixels fell outside the discretization box {box}")
    if gauss:
        if ext[0] > ext[2]:
            return PixelSet.empty()
        gx0, gy0, gx1, gy1 = (int(v) for v in ext)
        if (gx0, gy0, gx1, gy1) != box:
            # Crop once here (one copy) rather than in PixelSet, which would copy twice.
            mask = np.ascontiguousarray(mask[gy0 - y0 : gy1 - y0 + 1, gx0 - x0 : gx1 - x0 + 1])
            x0, y0 = gx0, gy0
    return PixelSet.taking_over(mask, (x0, y0))  # the mask is ours alone: frozen in place, not copied
