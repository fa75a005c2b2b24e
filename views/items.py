"""Graphics items and path builders for plane geometry: polygons, crack edges, vertex handles, markers.

Paths are built from numpy arrays in one call (``pg.arrayToQPath``), never point by point in Python, so a
polygon with thousands of vertices or the crack boundary of a 2048² mask redraws within a frame.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pyqtgraph as pg
import shapely
from PySide6 import QtCore, QtGui, QtWidgets


# ---------------------------------------------------------------------------------------------- paths
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
    path = pg.arrayToQPath(xy[:, 0], xy[:, 1], connect=connect)
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


def geometry_path(geom: shapely.Geometry) -> QtGui.QPainterPath:
    """QPainterPath of a shapely Polygon / MultiPolygon (holes cut out)."""
    return rings_path(polygon_rings(geom))


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


def polyline_path(xy: np.ndarray, closed: bool = False) -> QtGui.QPainterPath:
    """Path through the points (x, y) in order."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    if len(xy) == 0:
        return QtGui.QPainterPath()
    if closed:
        xy = np.vstack([xy, xy[:1]])
    return pg.arrayToQPath(xy[:, 0], xy[:, 1], connect="all")


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


class MarkersItem(pg.GraphicsObject):
    """Points drawn as fixed-size screen symbols (vertex handles, junctions): one item, one paint call.

    ``highlight`` draws one point larger (the vertex under the cursor or being dragged).
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

    def set_highlight(self, index: int | None) -> None:
        if index != self.highlight:
            self.highlight = index
            self.update()

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
        # Map all points to device space with one matrix product, then draw in device pixels.
        m = np.array([[tr.m11(), tr.m12()], [tr.m21(), tr.m22()]])
        dev = self._xy @ m + np.array([tr.dx(), tr.dy()])
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
