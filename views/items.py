"""Graphics items and path builders for plane geometry: polygons, crack edges, vertex handles, markers.

Paths are built from numpy arrays (:func:`array_path`), never point by point in Python, so a polygon with
thousands of vertices or the crack boundary of a 2048² mask redraws within a frame.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import pyqtgraph as pg
import shapely
from PySide6 import QtCore, QtGui, QtWidgets

# ---------------------------------------------------------------------------------------------- paths
#: Elements a path is built from per call into Qt (:func:`array_path`).
PATH_CHUNK = 32_768
_ELEMENT = np.dtype([("c", ">i4"), ("x", ">f8"), ("y", ">f8")])


def _streamed_path(kind: np.ndarray, x: np.ndarray, y: np.ndarray) -> QtGui.QPainterPath:
    """A path of elements ``kind[i]`` (0 move to, 1 line to) at (x[i], y[i]), read from Qt's stream format."""
    n = len(kind)
    raw = bytearray(4 + 20 * n + 8)  # count, elements, then cStart and the fill rule (both 0: odd-even)
    raw[:4] = n.to_bytes(4, "big")
    arr = np.frombuffer(raw, dtype=_ELEMENT, count=n, offset=4)
    arr["c"] = kind
    arr["x"] = x
    arr["y"] = y
    path = QtGui.QPainterPath()
    QtCore.QDataStream(QtCore.QByteArray(raw)) >> path
    return path


def array_path(x: np.ndarray, y: np.ndarray, connect: np.ndarray) -> QtGui.QPainterPath:
    """``pg.arrayToQPath(x, y, connect=connect)`` (point i joins point i + 1 when ``connect[i]``; any thread).

    Built :data:`PATH_CHUNK` elements at a time: Qt reads a path from its stream format with the GIL held,
    about 70 ns an element, so a worker building the 2 M-element outline of a 10⁸-pixel object in one call
    held it 120–160 ms, and every paint of the window waited that long. Each chunk holds it 2–3 ms. The
    elements are the same as those of one call (a chunk may begin with a line to; a path read from the
    stream is not checked for a leading move to), so the path draws the same.
    """
    n = len(x)
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if n <= PATH_CHUNK or not (np.isfinite(x).all() and np.isfinite(y).all()):
        return pg.arrayToQPath(x, y, connect=np.asarray(connect, dtype=np.int32))
    kind = np.empty(n, dtype=np.int32)
    kind[0] = 0
    kind[1:] = np.asarray(connect[:-1]) != 0
    path = QtGui.QPainterPath()
    path.reserve(n)
    start = 0
    while start < n:
        end = min(n, start + PATH_CHUNK)
        # addPath drops a trailing move to of the path it adds to: a chunk never ends on one. It also drops
        # a path of one move to: the last point is never a chunk of its own.
        while end < n and kind[end - 1] == 0:
            end += 1
        if n - end == 1:
            end = n
        path.addPath(_streamed_path(kind[start:end], x[start:end], y[start:end]))
        start = end
    return path


def rings_path(rings: Sequence[np.ndarray], close: bool = True) -> QtGui.QPainterPath:
    """One path of several rings (arrays of (x, y)); the odd-even rule makes holes of inner rings."""
    rings = [np.asarray(r, dtype=float).reshape(-1, 2) for r in rings if len(r)]
    if not rings:
        return QtGui.QPainterPath()
    if close:
        rings = [r if len(r) < 2 or (r[0] == r[-1]).all() else np.vstack([r, r[:1]]) for r in rings]
    xy = np.concatenate(rings)
    connect = np.ones(len(xy), dtype=np.int32)
    ends = np.cumsum([len(r) for r in rings]) - 1
    connect[ends] = 0
    path = array_path(xy[:, 0], xy[:, 1], connect)
    path.setFillRule(QtCore.Qt.FillRule.OddEvenFill)
    return path


def polygon_rings(geom: shapely.Geometry) -> list[np.ndarray]:
    """The rings (exterior then interiors) of every polygon of a Polygon / MultiPolygon."""
    out: list[np.ndarray] = []
    if geom is None or geom.is_empty:
        return out
    for poly in shapely.get_parts(geom):
        if poly.geom_type != "Polygon" or poly.is_empty:
            continue
        out.append(np.asarray(poly.exterior.coords)[:, :2])
        out.extend(np.asarray(r.coords)[:, :2] for r in poly.interiors)
    return out


def _runs(edges: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Maximal runs of True along the last axis: (row, first, last) arrays."""
    e = edges.astype(np.int8)
    d = np.diff(np.pad(e, ((0, 0), (1, 1))), axis=1)
    rs, cs = np.nonzero(d == 1)
    _re, ce = np.nonzero(d == -1)
    return rs, cs, ce - 1


def crack_segments(mask: np.ndarray, origin: tuple[int, int]) -> np.ndarray:
    """The crack boundary of ``mask`` (pixel sides between inside and outside) as merged straight pieces.

    Returns an (N, 4) array of (x1, y1, x2, y2) in plane coordinates (pixel sides lie on half-integers).
    """
    if mask.size == 0:
        return np.zeros((0, 4))
    x0, y0 = origin
    p = np.pad(mask.astype(bool), 1)
    horiz = p[1:, :] != p[:-1, :]  # (h+1, w+2): side between padded rows k-1 and k
    r, c1, c2 = _runs(horiz)
    hy = y0 + r - 0.5
    h = np.stack([x0 + c1 - 1.5, hy, x0 + c2 - 0.5, hy], axis=1)
    vert = (p[:, 1:] != p[:, :-1]).T  # (w+1, h+2): side between padded cols k-1 and k
    c, r1, r2 = _runs(vert)
    vx = x0 + c - 0.5
    v = np.stack([vx, y0 + r1 - 1.5, vx, y0 + r2 - 0.5], axis=1)
    return np.concatenate([h, v]).astype(float)


def segments_path(segs: np.ndarray) -> QtGui.QPainterPath:
    """Path of disjoint straight pieces given as (N, 4) rows (x1, y1, x2, y2)."""
    if len(segs) == 0:
        return QtGui.QPainterPath()
    x = segs[:, [0, 2]].ravel()
    y = segs[:, [1, 3]].ravel()
    return pg.arrayToQPath(x, y, connect="pairs")


def cosmetic_pen(
    colour: QtGui.QColor | str, width: float = 1.0, style: QtCore.Qt.PenStyle | None = None
) -> QtGui.QPen:
    """A pen of constant screen width, whatever the zoom."""
    pen = QtGui.QPen(QtGui.QColor(colour))
    pen.setCosmetic(True)
    pen.setWidthF(width)
    pen.setJoinStyle(QtCore.Qt.PenJoinStyle.MiterJoin)
    if style is not None:
        pen.setStyle(style)
    return pen


#: Paths with more elements, and marker sets with more points, are drawn through a device-pixel cache.
CACHE_ELEMENTS = 4000


class PathItem(QtWidgets.QGraphicsPathItem):
    """A filled and/or stroked path in plane coordinates (cosmetic pen: constant screen width)."""

    def __init__(self, path: QtGui.QPainterPath | None = None) -> None:
        super().__init__(path or QtGui.QPainterPath())
        self.setPen(QtGui.QPen(QtCore.Qt.PenStyle.NoPen))
        self.setBrush(QtGui.QBrush(QtCore.Qt.BrushStyle.NoBrush))

    def setPath(self, path: QtGui.QPainterPath) -> None:
        # A big path (the outline of 10⁸ pixels: 10⁵–10⁶ segments) takes 50–200 ms to stroke; cached in
        # device pixels it is stroked once per zoom, and a pan only moves the cached picture (ADR 0019).
        big = path.elementCount() > CACHE_ELEMENTS
        mode = QtWidgets.QGraphicsItem.CacheMode
        self.setCacheMode(mode.DeviceCoordinateCache if big else mode.NoCache)
        super().setPath(path)

    def shape(self) -> QtGui.QPainterPath:
        # Qt's own shape strokes the whole path, and pyqtgraph asks for it at every mouse move (hover
        # events): seconds for the outline of 10⁸ pixels. The tools hit-test the model, never these items.
        out = QtGui.QPainterPath()
        out.addRect(self.path().controlPointRect())  # not boundingRect(): Qt's calls shape()
        return out

    def set_style(
        self,
        fill: QtGui.QColor | None = None,
        stroke: QtGui.QColor | None = None,
        width: float = 1.0,
        pen_style: QtCore.Qt.PenStyle | None = None,
        brush_style: QtCore.Qt.BrushStyle | None = None,
    ) -> None:
        if fill is None:
            self.setBrush(QtGui.QBrush(QtCore.Qt.BrushStyle.NoBrush))
        else:
            b = QtGui.QBrush(fill, brush_style or QtCore.Qt.BrushStyle.SolidPattern)
            if brush_style is not None and brush_style != QtCore.Qt.BrushStyle.SolidPattern:
                # Hatching patterns are defined in device space; keep them constant on screen.
                b.setTransform(QtGui.QTransform())
            self.setBrush(b)
        self.setPen(
            QtGui.QPen(QtCore.Qt.PenStyle.NoPen) if stroke is None else cosmetic_pen(stroke, width, pen_style)
        )


# ---------------------------------------------------------------------------------------------- stroke LOD
#: A component drawn smaller than this many screen pixels is a dot, not a stroked outline.
DOT_PX = 4.0


class Tiles(NamedTuple):
    """Polylines cut into chunks by grid cell (:func:`tile_polylines`), to stroke only what is in view.

    Chunk k runs through the points ``start[k]`` … ``end[k]`` (the last point of a chunk is the first of the
    next one when the polyline goes on) and lies within ``box[k]`` (x0, y0, x1, y1).
    """

    xy: np.ndarray
    start: np.ndarray
    end: np.ndarray
    box: np.ndarray

    def path_in(self, rect: QtCore.QRectF) -> QtGui.QPainterPath | None:
        """The polylines through every chunk that meets ``rect``, or None when that is every chunk.

        Consecutive chunks are joined again, so a polyline is cut only where it leaves the rectangle: what
        lies inside is stroked exactly as the whole path strokes it (joins, caps, antialiasing).
        """
        b = self.box
        sel = (b[:, 0] <= rect.right()) & (b[:, 2] >= rect.left()) & (b[:, 1] <= rect.bottom())
        sel &= b[:, 3] >= rect.top()
        if sel.all():
            return None
        idx = np.flatnonzero(sel)
        if not len(idx):
            return QtGui.QPainterPath()
        starts, ends = self.start[idx], self.end[idx]
        first = np.r_[True, starts[1:] != ends[:-1]]  # a chunk that does not go on from the one before
        run_start = starts[first]
        run_end = ends[np.r_[first[1:], True]]
        lens = run_end - run_start + 1
        offsets = np.cumsum(lens) - lens
        points = np.arange(int(lens.sum())) + np.repeat(run_start - offsets, lens)
        xy = self.xy[points]
        connect = np.ones(len(xy), dtype=np.int32)
        connect[offsets + lens - 1] = 0
        return array_path(xy[:, 0], xy[:, 1], connect)


#: Paths with more elements than this are also cut into chunks by grid cell (:class:`Tiles`).
TILE_ELEMENTS = 2000
#: Grid cells along the longer side of a size class's box: zoomed in on a long outline, a paint strokes
#: the few cells in view, not the whole outline (Qt's stroker handles every element, off-screen ones too).
TILE_CELLS = 64


def tile_polylines(xy: np.ndarray, connect: np.ndarray) -> Tiles | None:
    """:class:`Tiles` of polylines given as :func:`stroke_levels` takes them, or None when small (any thread).

    A segment belongs to the grid cell of its first point; a chunk is a run of consecutive segments of one
    polyline in one cell. The cells are 1/:data:`TILE_CELLS` of the box's longer side.
    """
    if len(xy) <= TILE_ELEMENTS:
        return None
    lo = xy.min(axis=0)
    cell = max(float((xy.max(axis=0) - lo).max()) / TILE_CELLS, 1.0)
    ij = np.floor((xy - lo) / cell).astype(np.int64)
    key = ij[:, 0] * (TILE_CELLS + 1) + ij[:, 1]
    seg = np.flatnonzero(np.asarray(connect[:-1]) != 0)  # segment j joins point j to point j + 1
    if not len(seg):
        return None
    first = np.r_[True, (seg[1:] != seg[:-1] + 1) | (key[seg[1:]] != key[seg[:-1]])]
    heads = np.flatnonzero(first)
    a, b = xy[seg], xy[seg + 1]
    box = np.concatenate(
        [np.minimum.reduceat(np.minimum(a, b), heads), np.maximum.reduceat(np.maximum(a, b), heads)], axis=1
    )
    return Tiles(xy, seg[first], seg[np.r_[first[1:], True]] + 1, box)


class StrokeLevel(NamedTuple):
    """One size class of components (:func:`stroke_levels`)."""

    extent: float  # the class's components are smaller than this (plane units)
    path: QtGui.QPainterPath  # their outlines in full
    centres: np.ndarray  # (n, 2): where their dots go when they are drawn smaller than DOT_PX
    # (tolerance, simplified outlines, their tiles), coarsest last
    coarse: tuple[tuple[float, QtGui.QPainterPath, Tiles | None], ...]
    tiles: Tiles | None = None  # of the full outlines

    def strokes_at(self, scale: float) -> tuple[QtGui.QPainterPath, Tiles | None]:
        """The outlines to stroke at ``scale`` screen pixels per unit, with their tiles (:meth:`path_at`)."""
        best = self.path, self.tiles
        for tolerance, path, tiles in self.coarse:
            if tolerance * scale <= COARSE_PX:
                best = path, tiles
        return best

    def path_at(self, scale: float) -> QtGui.QPainterPath:
        """The outlines to stroke at ``scale`` screen pixels per unit: the coarsest still exact on screen."""
        return self.strokes_at(scale)[0]


def ring_groups(rings: Sequence[np.ndarray], group: Sequence[int] | np.ndarray) -> tuple[np.ndarray, ...]:
    """``(xy, connect, point_group)`` of polylines ``rings`` (each (n, 2)); ring i is in ``group[i]``.

    The layout :func:`stroke_levels` takes: points in order, ``connect[i]`` 1 when point i joins point i + 1.
    """
    rings = [np.asarray(r, dtype=float).reshape(-1, 2) for r in rings]
    if not rings:
        return np.zeros((0, 2)), np.zeros(0, np.int32), np.zeros(0, np.int64)
    lens = np.array([len(r) for r in rings])
    xy = np.concatenate(rings)
    connect = np.ones(len(xy), dtype=np.int32)
    connect[np.cumsum(lens) - 1] = 0
    return xy, connect, np.repeat(np.asarray(group, dtype=np.int64), lens)


def stroke_levels(
    xy: np.ndarray,
    connect: np.ndarray,
    group: np.ndarray,
    fill_rule: QtCore.Qt.FillRule | None = None,
    extents: np.ndarray | None = None,
) -> list[StrokeLevel]:
    """The strokes of components by size class, for :meth:`LodPathItem.set_levels` (any thread).

    ``group[i]`` is the component of point i (points of one component consecutive). Components whose
    extent (the longer side of their box) lies in [2ᵏ, 2ᵏ⁺¹) form class k: one path and the components'
    centres; ``extents[g]``, when given, is component g's extent instead (its points spread over several
    items). Each class also comes simplified (:func:`coarse_paths`), for the zooms at which a plane unit is
    less than a screen pixel. Returns one :class:`StrokeLevel` per class, smallest first. Vectorised: a
    worker building the classes of 10⁵ components holds the GIL only for a few numpy and shapely calls.
    """
    if len(xy) == 0:
        return []
    starts = np.flatnonzero(np.r_[True, group[1:] != group[:-1]])
    lo = np.minimum.reduceat(xy, starts, axis=0)
    hi = np.maximum.reduceat(xy, starts, axis=0)
    extent = np.maximum((hi - lo).max(axis=1), 1.0) if extents is None else extents[group[starts]]
    cls = np.floor(np.log2(extent)).astype(np.int64)
    lens = np.diff(np.r_[starts, len(xy)])
    point_cls = np.repeat(cls, lens)
    centres = (lo + hi) / 2
    out = []
    for k in np.unique(cls):
        sel = point_cls == k
        cxy, cc = xy[sel], connect[sel]
        path = array_path(cxy[:, 0], cxy[:, 1], cc)
        coarse = coarse_paths(cxy, cc, float(2.0 ** (k + 1)))
        if fill_rule is not None:
            path.setFillRule(fill_rule)
            for _t, p, _tiles in coarse:
                p.setFillRule(fill_rule)
        tiles = tile_polylines(cxy, cc)
        out.append(StrokeLevel(float(2.0 ** (k + 1)), path, centres[cls == k], tuple(coarse), tiles))
    return out


#: A simplified outline is drawn when its error (the simplification's tolerance) is under this many screen
#: pixels: what differs from the full outline is then hidden by the pen's own width.
COARSE_PX = 0.5


def coarse_paths(
    xy: np.ndarray, connect: np.ndarray, extent: float
) -> list[tuple[float, QtGui.QPainterPath, Tiles | None]]:
    """``(tolerance, path, tiles)``: polylines simplified by 1, 2, 4, … units (Douglas–Peucker), finest first.

    Polylines as :func:`stroke_levels` takes them. A level is kept only if it has at most 2/3 of the elements
    of the one before (a crack staircase loses most of its corners at a tolerance of one pixel); the
    tolerances stop below ``extent`` / 4, where the component is drawn as a dot anyway. Shapely's calls run
    without the GIL.
    """
    out: list[tuple[float, QtGui.QPainterPath, Tiles | None]] = []
    if len(xy) < 8:
        return out
    line = np.cumsum(np.r_[0, connect[:-1] == 0])  # polyline of each point
    counts = np.bincount(line)
    keep = counts[line] >= 2  # a lone point (no piece) draws nothing
    if not keep.any():
        return out
    lines = shapely.linestrings(xy[keep], indices=line[keep])
    lines = lines[~shapely.is_missing(lines)]
    elements = int(keep.sum())
    tolerance = 1.0
    while tolerance < extent / 4:
        simple = shapely.simplify(lines, tolerance, preserve_topology=False)
        pts, idx = shapely.get_coordinates(simple, return_index=True)
        if len(pts) > elements * 2 // 3:
            tolerance *= 2
            continue
        cc = np.ones(len(pts), dtype=np.int32)
        cc[np.flatnonzero(np.r_[idx[1:] != idx[:-1], True])] = 0
        out.append((tolerance, array_path(pts[:, 0], pts[:, 1], cc), tile_polylines(pts, cc)))
        elements = len(pts)
        tolerance *= 2
    return out


def levels_path(levels: Sequence[StrokeLevel]) -> QtGui.QPainterPath:
    """All classes' paths in one (the item's own path: its bounds, and what it draws zoomed in)."""
    path = QtGui.QPainterPath()
    for level in levels:
        path.addPath(level.path)
    if levels:
        path.setFillRule(levels[0].path.fillRule())
    return path


def geometry_levels(geom: shapely.Geometry) -> list[StrokeLevel]:
    """:func:`stroke_levels` of a Polygon / MultiPolygon: one component per polygon (holes cut out)."""
    rings: list[np.ndarray] = []
    group: list[int] = []
    if geom is not None and not geom.is_empty:
        for k, poly in enumerate(shapely.get_parts(geom)):
            if poly.geom_type != "Polygon" or poly.is_empty:
                continue
            for r in (poly.exterior, *poly.interiors):
                rings.append(np.asarray(r.coords)[:, :2])
                group.append(k)
    return stroke_levels(*ring_groups(rings, group), fill_rule=QtCore.Qt.FillRule.OddEvenFill)


class LodPathItem(PathItem):
    """A path of many components drawn with level of detail.

    A component smaller than :data:`DOT_PX` screen pixels is one dot at its centre (thousands of lone
    pixels stroked at fit-all zoom are a black field); bigger ones are stroked (and filled), simplified as
    far as the screen cannot tell (:meth:`StrokeLevel.path_at`): at fit-all zoom a 10⁸-pixel object's crack
    staircase has ten times more corners than the screen has pixels along it. Classes come from
    :func:`stroke_levels`, built on a worker; what is drawn at a zoom is cached in device pixels like any
    big path (:class:`PathItem`).
    """

    def __init__(self) -> None:
        super().__init__()
        self.levels: list[StrokeLevel] = []

    def set_levels(
        self,
        levels: Sequence[StrokeLevel],
        path: QtGui.QPainterPath | None = None,
    ) -> None:
        """Show ``levels``; ``path`` is their union (:func:`levels_path`, built beside them on a worker)."""
        self._setting = True
        try:
            self.setPath(levels_path(levels) if path is None else path)
        finally:
            self._setting = False
        self.levels = list(levels)

    def setPath(self, path: QtGui.QPainterPath) -> None:
        if not getattr(self, "_setting", False) and hasattr(self, "levels"):
            self.levels = []  # a plain path replaces the classes
        super().setPath(path)

    #: Cut strokes to the view (:class:`Tiles`); off, every paint strokes whole paths (the reference).
    tiled = True

    def drawn(self, scale: float, rect: QtCore.QRectF | None = None) -> tuple[int, int]:
        """(path elements stroked, dots) at ``scale`` screen pixels per unit: what :meth:`paint` draws.

        With ``rect`` (plane units), what a paint of that part of the plane strokes.
        """
        if not self.levels:
            return self.path().elementCount(), 0
        paths = dots = 0
        for lv in self.levels:
            if lv.extent * scale < DOT_PX:
                dots += len(lv.centres)
                continue
            path, tiles = lv.strokes_at(scale)
            part = tiles.path_in(rect) if rect is not None and tiles is not None and self.tiled else None
            paths += (path if part is None else part).elementCount()
        return paths, dots

    def paint(self, painter: QtGui.QPainter, option: object, widget: object = None) -> None:
        if not self.levels:
            super().paint(painter, option, widget)
            return
        tr = painter.transform()
        scale = math.hypot(tr.m11(), tr.m12())
        pen = self.pen()
        brush = self.brush()
        # Zoomed in on a long outline, the stroke of the whole path costs 20–70 ms per item (Qt's stroker
        # handles every element, off-screen ones too, for pens wider than one pixel): a solid pen strokes
        # the chunks in view only. Dashes are left whole (their stroker skips what is off-screen itself,
        # and cut paths would restart the pattern).
        cut = self.tiled and pen.style() == QtCore.Qt.PenStyle.SolidLine
        seen = visible_rect(painter, pen.widthF() + 2.0)
        view = seen if cut else None
        small = []
        for level in self.levels:
            if level.extent * scale < DOT_PX:
                if len(level.centres):
                    small.append(level.centres)
                continue
            path, tiles = level.strokes_at(scale)
            part = tiles.path_in(view) if view is not None and tiles is not None else None
            if part is None:
                painter.setPen(pen)
                painter.setBrush(brush)
                painter.drawPath(path)
                continue
            if brush.style() != QtCore.Qt.BrushStyle.NoBrush:
                painter.setPen(QtCore.Qt.PenStyle.NoPen)  # a fill needs the whole outline (it is cheap)
                painter.setBrush(brush)
                painter.drawPath(path)
            painter.setPen(pen)
            painter.setBrush(QtCore.Qt.BrushStyle.NoBrush)
            painter.drawPath(part)
        if not small or pen.style() == QtCore.Qt.PenStyle.NoPen:
            return
        c = np.concatenate(small)
        if seen is not None:  # the dots in view only: zoomed in, most are elsewhere
            c = c[
                (c[:, 0] >= seen.left())
                & (c[:, 0] <= seen.right())
                & (c[:, 1] >= seen.top())
                & (c[:, 1] <= seen.bottom())
            ]
            if not len(c):
                return
        dev = np.floor(to_device(c, tr)).astype(np.int64)
        # One dot per screen pixel: a 1-D unique of one key per pixel (a row-wise unique sorts 3× slower).
        lo = dev.min(axis=0)
        span = int(dev[:, 1].max() - lo[1]) + 1
        keys = np.unique((dev[:, 0] - lo[0]) * span + (dev[:, 1] - lo[1]))
        dev = np.stack([keys // span + lo[0], keys % span + lo[1]], axis=1).astype(float)
        dot = QtGui.QPen(pen.color())
        dot.setCosmetic(True)
        dot.setWidthF(max(1.0, min(pen.widthF(), 2.0)))
        dot.setCapStyle(QtCore.Qt.PenCapStyle.SquareCap)
        painter.save()
        painter.resetTransform()
        painter.setPen(dot)
        painter.drawPoints(pg.functions.arrayToQPolygonF(dev[:, 0] + 0.5, dev[:, 1] + 0.5))
        painter.restore()


def to_device(xy: np.ndarray, tr: QtGui.QTransform) -> np.ndarray:
    """Points (n, 2) through an affine transform, as ``xy @ [[m11, m12], [m21, m22]] + (dx, dy)``.

    Elementwise, not a matrix product: numpy hands ``@`` to OpenBLAS, whose threads then spin for a while
    after each call, on the cores the window shares with the workers (seen at every paint of dots).
    """
    x, y = xy[:, 0], xy[:, 1]
    out = np.empty((len(xy), 2))
    out[:, 0] = x * tr.m11() + y * tr.m21() + tr.dx()
    out[:, 1] = x * tr.m12() + y * tr.m22() + tr.dy()
    return out


def visible_rect(painter: QtGui.QPainter, margin_px: float = 0.0) -> QtCore.QRectF | None:
    """The part of the item's plane a paint can reach: its device (or clip), widened by ``margin_px``.

    None when the painter's transform cannot be inverted. In an item's paint the device is the view or the
    item's device-pixel cache, which Qt keeps to the viewport.
    """
    inverse, ok = painter.transform().inverted()
    if not ok:
        return None
    r = QtCore.QRectF(painter.viewport())
    if painter.hasClipping():
        r = r.intersected(painter.transform().mapRect(painter.clipBoundingRect()))
    r.adjust(-margin_px, -margin_px, margin_px, margin_px)
    return inverse.mapRect(r)


def distinguishable(dev: np.ndarray, size: float) -> np.ndarray:
    """Which device points get a symbol: those with no other point closer than ``size / 2`` on both axes.

    Zoomed out, the handles of thousands of tiny components overlap into a solid black field, and none of
    them could be picked anyway; their components are drawn as dots by the outlines' level of detail
    (:class:`LodPathItem`). Zoomed in, every handle stands apart and is drawn. A point is kept when it is
    alone in its cell of ``size`` pixels in four grids shifted by half a cell on each axis: two points
    closer than half a cell on both axes share a cell in at least one of them.
    """
    keep = np.ones(len(dev), dtype=bool)
    if not len(dev):
        return keep
    for shift in ((0.0, 0.0), (0.5, 0.0), (0.0, 0.5), (0.5, 0.5)):
        cells = np.floor(dev / size + np.array(shift)).astype(np.int64)
        cells -= cells.min(axis=0)
        key = cells[:, 0] * (int(cells[:, 1].max()) + 1) + cells[:, 1]  # one integer per cell: a 1-D unique
        _, inverse, counts = np.unique(key, return_inverse=True, return_counts=True)
        keep &= counts[inverse] == 1
    return keep


class MarkersItem(pg.GraphicsObject):
    """Points drawn as fixed-size screen symbols (vertex handles, junctions): one item, one paint call.

    ``highlight`` draws one point larger (the vertex under the cursor or being dragged). Only handles
    that can be told apart are drawn (:func:`distinguishable`); the highlighted one always is.
    """

    def __init__(self, size: float = 7.0, shape: str = "square") -> None:
        super().__init__()
        self.size = float(size)
        self.symbol = shape  # not "shape": that would hide QGraphicsItem.shape()
        self._xy = np.zeros((0, 2))
        self._pen = cosmetic_pen("#000000", 1.0)
        self._brush = QtGui.QBrush(QtGui.QColor("#ffffff"))
        self.highlight: int | None = None
        self._hl_brush = QtGui.QBrush(QtGui.QColor("#ffcc00"))
        self._bounds = QtCore.QRectF()
        self._pad = 0.0

    def set_points(self, xy: np.ndarray) -> None:
        self.prepareGeometryChange()
        self._xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        mode = QtWidgets.QGraphicsItem.CacheMode
        # Thousands of handles are drawn in Python: once per zoom, not at every pan (see PathItem.setPath).
        self.setCacheMode(mode.DeviceCoordinateCache if len(self._xy) > CACHE_ELEMENTS // 4 else mode.NoCache)
        if len(self._xy):
            lo = self._xy.min(axis=0)
            hi = self._xy.max(axis=0)
            self._bounds = QtCore.QRectF(lo[0], lo[1], hi[0] - lo[0], hi[1] - lo[1])
        else:
            self._bounds = QtCore.QRectF()
        self.update()

    def points(self) -> np.ndarray:
        return self._xy

    def set_colours(
        self, pen: QtGui.QColor, brush: QtGui.QColor, highlight: QtGui.QColor | None = None
    ) -> None:
        self._pen = cosmetic_pen(pen, 1.0)
        self._brush = QtGui.QBrush(brush)
        if highlight is not None:
            self._hl_brush = QtGui.QBrush(highlight)
        self.update()

    def drawn(self, scale: float) -> np.ndarray:
        """Which points a paint at ``scale`` screen pixels per unit draws (all points in view)."""
        return distinguishable(self._xy * np.array([scale, -scale]), self.size)

    def viewTransformChanged(self) -> None:
        self.prepareGeometryChange()
        px = self.pixelLength(pg.Point(1, 0))
        self._pad = (px or 0.0) * (self.size + 4)

    def boundingRect(self) -> QtCore.QRectF:
        if not len(self._xy):
            return QtCore.QRectF()
        p = self._pad
        return self._bounds.adjusted(-p, -p, p, p)

    def paint(self, painter: QtGui.QPainter, *_args: object) -> None:
        if not len(self._xy):
            return
        tr = painter.transform()
        # Map all points to device space at once, then draw in device pixels.
        dev = to_device(self._xy, tr)
        painter.save()
        painter.resetTransform()
        painter.setRenderHint(QtGui.QPainter.RenderHint.Antialiasing, self.symbol == "circle")
        painter.setPen(self._pen)
        painter.setBrush(self._brush)
        s = self.size
        h = s / 2
        vis = painter.viewport() if painter.viewport().isValid() else None
        if vis is not None:
            keep = (
                (dev[:, 0] > vis.left() - s)
                & (dev[:, 0] < vis.right() + s)
                & (dev[:, 1] > vis.top() - s)
                & (dev[:, 1] < vis.bottom() + s)
            )
        else:
            keep = np.ones(len(dev), dtype=bool)
        # Only the points in view (with a margin of one symbol, which holds every neighbour that could hide
        # a visible one): zoomed in, a paint looks at a few handles, not all of them.
        keep[keep] = distinguishable(dev[keep], s)
        rects = [QtCore.QRectF(x - h, y - h, s, s) for x, y in dev[keep]]
        if self.symbol == "circle":
            for r in rects:
                painter.drawEllipse(r)
        else:
            painter.drawRects(rects)
        if self.highlight is not None and 0 <= self.highlight < len(dev):
            x, y = dev[self.highlight]
            painter.setBrush(self._hl_brush)
            hs = s + 4
            r = QtCore.QRectF(x - hs / 2, y - hs / 2, hs, hs)
            painter.drawEllipse(r) if self.symbol == "circle" else painter.drawRect(r)
        painter.restore()
