"""Pure helpers for the editing tools: vertex references, hit tests, the preview of a vertex edit, brush dabs.

Vertex references follow :mod:`mrm.document.commands` (``VertexRef`` = (polygon, ring, index), closing point
not counted, polygons in MultiPolygon order, ring 0 the exterior), so a preview computed here and the command
pushed on release describe the same edit.
"""

from __future__ import annotations

import bisect
import math

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon
from shapely.geometry.polygon import orient

from mrm.core.models import cell_of
from mrm.document import validate_geometry

VertexRef = tuple[int, int, int]


def rings_of(geom: shapely.Geometry) -> tuple[bool, list[list[np.ndarray]]]:
    """(is_multi, polygons as lists of rings without the closing point)."""
    if geom is None or geom.is_empty:
        return False, []
    polys = list(geom.geoms) if isinstance(geom, MultiPolygon) else [geom]
    out = []
    for p in polys:
        rings = [np.asarray(p.exterior.coords, dtype=float)[:-1, :2]]
        rings += [np.asarray(r.coords, dtype=float)[:-1, :2] for r in p.interiors]
        out.append(rings)
    return isinstance(geom, MultiPolygon), out


def build(multi: bool, polys: list[list[np.ndarray]]) -> shapely.Geometry:
    """Rebuild a geometry from rings and validate it (raises InvalidGeometryError)."""
    built = []
    for rings in polys:
        if any(len(r) < 3 for r in rings):
            from mrm.core.errors import InvalidGeometryError

            raise InvalidGeometryError("a polygon ring needs at least 3 vertices")
        built.append(Polygon(np.vstack([rings[0], rings[0][:1]]), [np.vstack([h, h[:1]]) for h in rings[1:]]))
    geom = MultiPolygon(built) if multi else built[0]
    return validate_geometry(geom)


class VertexRefs:
    """The references of every vertex of a geometry, in ring order, computed per row on demand.

    A list of 10⁶ ``(polygon, ring, index)`` tuples takes about 0.3 s to build on the GUI thread; this holds
    only the polygon, ring number and first row of each ring, and a row is found by bisection.
    """

    __slots__ = ("_poly", "_ring", "_starts")

    def __init__(self, poly: np.ndarray, ring: np.ndarray, counts: np.ndarray) -> None:
        # Python lists: a table view asks for rows one by one, and bisect on a list takes a microsecond.
        self._poly: list[int] = np.asarray(poly, dtype=np.int64).tolist()
        self._ring: list[int] = np.asarray(ring, dtype=np.int64).tolist()
        self._starts: list[int] = [0, *np.cumsum(np.asarray(counts, dtype=np.int64)).tolist()]

    def __len__(self) -> int:
        return self._starts[-1]

    def __getitem__(self, k: int) -> VertexRef:
        n = self._starts[-1]
        if k < 0:
            k += n
        if not 0 <= k < n:
            raise IndexError(k)
        i = bisect.bisect_right(self._starts, k) - 1
        return (self._poly[i], self._ring[i], k - self._starts[i])

    def __iter__(self):  # type: ignore[no-untyped-def]
        for k in range(len(self)):
            yield self[k]

    def index(self, ref: VertexRef) -> int:
        """The row of ``ref`` (ValueError when the geometry has no such vertex)."""
        p, r, i = ref
        for k, (pk, rk) in enumerate(zip(self._poly, self._ring, strict=True)):
            if (pk, rk) == (p, r) and 0 <= i < self._starts[k + 1] - self._starts[k]:
                return self._starts[k] + i
        raise ValueError(f"no vertex {ref!r}")


def _ragged(geom: shapely.Geometry) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(coordinates, ring offsets, polygon offsets) of a Polygon or MultiPolygon, closing points included."""
    _kind, coords, offsets = shapely.to_ragged_array([geom])
    rings, polys = np.asarray(offsets[0], dtype=np.int64), np.asarray(offsets[1], dtype=np.int64)
    return coords, rings, polys


def _rings(geom: shapely.Geometry) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The rings of a non-empty Polygon or MultiPolygon, as arrays.

    (vertices (n, 2) in ring order without closing points, polygon of each ring, ring number in its polygon,
    vertices per ring).
    """
    coords, rings, polys = _ragged(geom)
    keep = np.ones(len(coords), dtype=bool)
    keep[rings[1:] - 1] = False  # each ring's closing point
    poly_of = np.repeat(np.arange(len(polys) - 1), np.diff(polys))
    ring_in_poly = np.arange(len(rings) - 1) - polys[poly_of]
    xy = np.ascontiguousarray(coords[keep, :2], dtype=np.float64)
    return xy, poly_of, ring_in_poly, np.diff(rings) - 1


def vertex_table(geom: shapely.Geometry) -> tuple[np.ndarray, VertexRefs]:
    """All vertices as an (n, 2) array and their references (a lazy sequence), in ring order.

    Vectorised (shapely's ragged arrays, no object per ring), so that a continuation of 10⁵ rings is
    tabled in milliseconds.
    """
    if geom is None or geom.is_empty:
        return np.zeros((0, 2)), VertexRefs(np.zeros(0), np.zeros(0), np.zeros(0))
    xy, poly_of, ring_in_poly, counts = _rings(geom)
    return xy, VertexRefs(poly_of, ring_in_poly, counts)


def vertex_count(geom: shapely.Geometry) -> int:
    """The number of vertices of a polygon or multipolygon, closing points not counted (as in the table)."""
    if geom is None or geom.is_empty:
        return 0
    parts = shapely.get_parts(geom)
    rings = len(parts) + int(shapely.get_num_interior_rings(parts).sum())
    return int(shapely.get_num_coordinates(geom)) - rings


def nearest_vertex(geom: shapely.Geometry, x: float, y: float, radius: float) -> VertexRef | None:
    """The vertex closest to (x, y) within ``radius`` (plane units), if any."""
    xy, refs = vertex_table(geom)
    if not len(xy):
        return None
    d = np.hypot(xy[:, 0] - x, xy[:, 1] - y)
    k = int(np.argmin(d))
    return refs[k] if d[k] <= radius else None


def nearest_edge(
    geom: shapely.Geometry, x: float, y: float, radius: float
) -> tuple[VertexRef, tuple[float, float]] | None:
    """The edge closest to (x, y) within ``radius``: (reference of the insertion place, foot point)."""
    _multi, polys = rings_of(geom)
    best: tuple[float, VertexRef, tuple[float, float]] | None = None
    for p, rings in enumerate(polys):
        for r, ring in enumerate(rings):
            a = ring
            b = np.roll(ring, -1, axis=0)
            ab = b - a
            ap = np.array([x, y]) - a
            den = np.einsum("ij,ij->i", ab, ab)
            t = np.clip(np.einsum("ij,ij->i", ap, ab) / np.where(den > 0, den, 1.0), 0.0, 1.0)
            foot = a + ab * t[:, None]
            d = np.hypot(foot[:, 0] - x, foot[:, 1] - y)
            k = int(np.argmin(d))
            if d[k] <= radius and (best is None or d[k] < best[0]):
                best = (float(d[k]), (p, r, k + 1), (float(foot[k, 0]), float(foot[k, 1])))
    return None if best is None else (best[1], best[2])


def moved_vertex(geom: shapely.Geometry, ref: VertexRef, xy: tuple[float, float]) -> shapely.Geometry:
    """``geom`` with vertex ``ref`` at ``xy`` (validated)."""
    multi, polys = rings_of(geom)
    p, r, i = ref
    polys[p][r] = polys[p][r].copy()
    polys[p][r][i] = xy
    return build(multi, polys)


def inserted_vertex(geom: shapely.Geometry, ref: VertexRef, xy: tuple[float, float]) -> shapely.Geometry:
    """``geom`` with a vertex at ``xy`` inserted before ``ref`` (validated)."""
    multi, polys = rings_of(geom)
    p, r, i = ref
    polys[p][r] = np.insert(polys[p][r], i, xy, axis=0)
    return build(multi, polys)


def with_hole(geom: shapely.Geometry, ring: np.ndarray) -> shapely.Geometry | None:
    """``geom`` with ``ring`` added as a hole of the polygon that contains it (None if none does)."""
    hole = Polygon(ring)
    multi, polys = rings_of(geom)
    for _p, rings in enumerate(polys):
        outer = Polygon(rings[0])
        if outer.contains(hole):
            rings.append(np.asarray(ring, dtype=float))
            return build(multi, polys)
    return None


def new_polygon(ring: np.ndarray) -> shapely.Geometry:
    """A validated polygon from a drawn ring, oriented counter-clockwise."""
    return validate_geometry(orient(Polygon(np.asarray(ring, dtype=float)), 1.0))


# ---------------------------------------------------------------------------------------------- snapping
def snap(x: float, y: float, mode: str | None) -> tuple[float, float]:
    """'centre': nearest pixel centre (integers); 'corner': nearest pixel corner (half-integers)."""
    if mode == "centre":
        cx, cy = cell_of((x, y))
        return float(cx), float(cy)
    if mode == "corner":
        return math.floor(x) + 0.5, math.floor(y) + 0.5
    return x, y


class SnapIndex:
    """The vertices and edges of one polygonal geometry, sorted for the nearest one to a cursor.

    Vertex ``k`` is row ``k`` of :func:`vertex_table` (ring order, closing points left out); edge ``k`` runs
    from vertex ``k`` to the next vertex of its ring (the last one closes the ring). Built once per geometry
    (about 0.1 s for 10⁶ vertices); a query then looks only at what lies near the cursor: the vertices and
    the short edges are sorted by x and found by bisection, the few long edges (over the 99th percentile of
    the edges' widths) are checked one by one.
    """

    #: Share of edges tested one by one at every query (the widest ones).
    LONG_EDGES = 0.01

    def __init__(self, geom: shapely.Geometry) -> None:
        if geom is None or geom.is_empty:
            xy = np.zeros((0, 2), dtype=np.float64)
            counts = np.zeros(0, dtype=np.int64)
        else:
            xy, _poly, _ring, counts = _rings(geom)
        n = len(xy)
        starts = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
        nxt = np.arange(1, n + 1, dtype=np.int64)
        if n:
            nxt[starts + counts - 1] = starts
        self.xy = xy
        self.next = nxt
        self.prev = np.empty_like(nxt)
        self.prev[nxt] = np.arange(n, dtype=np.int64)
        self._vorder = np.argsort(xy[:, 0], kind="stable")
        self._vx = xy[self._vorder, 0]
        a, b = xy, xy[nxt]
        self._a = a
        self._ab = b - a
        self._lo = np.minimum(a, b)
        self._hi = np.maximum(a, b)
        width = self._hi[:, 0] - self._lo[:, 0]
        self._reach = float(np.quantile(width, 1 - self.LONG_EDGES)) if n else 0.0
        long = width > self._reach
        self._long = np.flatnonzero(long)
        short = np.flatnonzero(~long)
        self._sorder = short[np.argsort(self._lo[short, 0], kind="stable")]
        self._sx = self._lo[self._sorder, 0]

    def __len__(self) -> int:
        return len(self.xy)

    def nearest_vertex(
        self, x: float, y: float, radius: float, skip: tuple[int, ...] = ()
    ) -> tuple[float, int] | None:
        """(distance, row) of the vertex nearest to (x, y) within ``radius``, rows in ``skip`` left out."""
        lo = int(np.searchsorted(self._vx, x - radius, "left"))
        hi = int(np.searchsorted(self._vx, x + radius, "right"))
        rows = self._vorder[lo:hi]
        pts = self.xy[rows]
        near = np.abs(pts[:, 1] - y) <= radius
        rows, pts = rows[near], pts[near]
        if skip:
            keep = ~np.isin(rows, skip)
            rows, pts = rows[keep], pts[keep]
        if not len(rows):
            return None
        d = np.hypot(pts[:, 0] - x, pts[:, 1] - y)
        k = int(np.argmin(d))
        return (float(d[k]), int(rows[k])) if d[k] <= radius else None

    def nearest_edge(
        self, x: float, y: float, radius: float, skip: tuple[int, ...] = ()
    ) -> tuple[float, int, tuple[float, float]] | None:
        """(distance, edge, foot) of the edge point nearest to (x, y) within ``radius``, ``skip`` left out."""
        lo = int(np.searchsorted(self._sx, x - radius - self._reach, "left"))
        hi = int(np.searchsorted(self._sx, x + radius, "right"))
        rows = np.concatenate([self._sorder[lo:hi], self._long])
        box_lo, box_hi = self._lo[rows], self._hi[rows]
        near = (
            (box_hi[:, 0] >= x - radius)
            & (box_lo[:, 0] <= x + radius)
            & (box_hi[:, 1] >= y - radius)
            & (box_lo[:, 1] <= y + radius)
        )
        rows = rows[near]
        if skip:
            rows = rows[~np.isin(rows, skip)]
        if not len(rows):
            return None
        a, ab = self._a[rows], self._ab[rows]
        ap = np.array([x, y]) - a
        den = np.einsum("ij,ij->i", ab, ab)
        t = np.clip(np.einsum("ij,ij->i", ap, ab) / np.where(den > 0, den, 1.0), 0.0, 1.0)
        foot = a + ab * t[:, None]
        d = np.hypot(foot[:, 0] - x, foot[:, 1] - y)
        k = int(np.argmin(d))
        if d[k] > radius:
            return None
        return float(d[k]), int(rows[k]), (float(foot[k, 0]), float(foot[k, 1]))


def pixel_at(x: float, y: float) -> tuple[int, int]:
    """The pixel under the plane point (x, y): the one tie rule of the product.

    A point on a pixel side goes to the pixel on its left or below, as D_standard of a point does
    (:func:`mrm.core.models.cell_of`).
    """
    px, py = cell_of((x, y))
    return px, py


# ---------------------------------------------------------------------------------------------- brush
def dab_offsets(size: int, shape: str = "round") -> np.ndarray:
    """Boolean footprint (size × size) of a brush; its centre is at ((size−1)/2, (size−1)/2)."""
    size = max(1, int(size))
    if shape == "square" or size <= 2:
        return np.ones((size, size), dtype=bool)
    c = (size - 1) / 2.0
    yy, xx = np.mgrid[0:size, 0:size]
    return (xx - c) ** 2 + (yy - c) ** 2 <= (size / 2.0) ** 2


def dab_origin(x: float, y: float, size: int) -> tuple[int, int]:
    """Pixel of footprint[0, 0] for a dab centred on the plane point (x, y)."""
    c = (max(1, int(size)) - 1) / 2.0
    px, py = cell_of((x - c, y - c))
    return px, py


def stroke_centres(a: tuple[float, float], b: tuple[float, float], size: int) -> list[tuple[float, float]]:
    """Dab centres from a (excluded) to b (included), close enough that the stroke has no gaps."""
    step = max(0.5, size / 4.0)
    dist = math.hypot(b[0] - a[0], b[1] - a[1])
    n = max(1, math.ceil(dist / step))
    return [(a[0] + (b[0] - a[0]) * k / n, a[1] + (b[1] - a[1]) * k / n) for k in range(1, n + 1)]
