"""One-click tools: fill a hole, delete a component, pick a point (the operation's centre)."""

from __future__ import annotations

import math

from PySide6 import QtCore, QtGui

from mrm.core.errors import ParameterError
from mrm.document.edits import DeleteComponent, FillHole
from mrm.views import geometry_edit as ge
from mrm.views.canvas import PlaneView
from mrm.views.tool_base import Tool, accent_colour, cosmetic_pen, snap_mode

Qt = QtCore.Qt


class _ClickPixelTool(Tool):
    cursor = Qt.CursorShape.PointingHandCursor

    def press(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if ev.button() != Qt.MouseButton.LeftButton:
            return False
        self.click(ge.pixel_at(x, y))
        return True

    def click(self, px: tuple[int, int]) -> None:
        raise NotImplementedError

    def paint_overlay(self, p: QtGui.QPainter, view: PlaneView) -> None:
        if self.hover is None:
            return
        x, y = ge.pixel_at(*self.hover)
        p.setPen(cosmetic_pen(accent_colour(view), 1.5))
        p.setBrush(Qt.BrushStyle.NoBrush)
        p.drawRect(QtCore.QRectF(x - 0.5, y - 0.5, 1, 1))


class FillHoleTool(_ClickPixelTool):
    name = "fill_hole"
    hint = "Click inside a hole of an object to fill it"

    def click(self, px: tuple[int, int]) -> None:
        doc = self.scene.doc
        cands = [o for o in ([self.scene.primary(), *list(reversed(doc.plane_objects))]) if o is not None]
        tried: set[int] = set()  # the selected object first, then top to bottom, each once
        for obj in cands:
            if obj.id in tried:
                continue
            tried.add(obj.id)
            if obj.kind == "labels":
                continue  # a label map's holes are regions of label 0, not holes to fill
            ps = self.scene.get(obj.id, "discrete")
            b = ps.bbox if ps is not None else None
            if b is None or not obj.style.visible or px in ps:
                continue
            if not (b[0] < px[0] < b[2] and b[1] < px[1] < b[3]):
                continue  # outside the object's box: in no hole of it
            try:
                doc.push(FillHole(obj.id, px))  # the model's command finds the hole (docs/design.md §4)
            except ParameterError:
                continue  # not in a hole of this object: try the next one
            doc.set_selection([obj.id])
            return
        self.host.message.emit("no hole there", 2500)


class DeleteComponentTool(_ClickPixelTool):
    name = "delete_component"
    hint = "Click a component (4-connected piece) of an object to delete it"

    def click(self, px: tuple[int, int]) -> None:
        obj = self.object_at(px[0], px[1])
        if obj is None:
            self.host.message.emit("no component there", 2500)
            return
        self.host.push(DeleteComponent(obj.id, px))


class PickPointTool(Tool):
    """A one-click tool: the click's plane point goes to ``host.pointPicked`` (the operation's centre).

    The tool controller switches back to the previous tool after the click (or Esc).
    """

    name = "pick_point"
    cursor = Qt.CursorShape.CrossCursor
    hint = "Click in a view to set the centre (Shift: snap to a pixel centre, Ctrl: to a corner); Esc cancels"
    busy_keys = (Qt.Key.Key_Escape,)

    def in_gesture(self) -> bool:
        return True

    def cancel(self) -> None:
        self.host.pointPicked.emit(math.nan, math.nan)

    def deactivate(self) -> None:
        pass  # switching away is the end of the pick, not a cancel to report

    def press(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if ev.button() != Qt.MouseButton.LeftButton:
            return False
        self.host.pointPicked.emit(*ge.snap(x, y, snap_mode(ev.modifiers())))
        return True

    def key(self, view: PlaneView, ev: QtGui.QKeyEvent) -> bool:
        if ev.key() == Qt.Key.Key_Escape:
            self.host.pointPicked.emit(math.nan, math.nan)
            return True
        return False

    def paint_overlay(self, p: QtGui.QPainter, view: PlaneView) -> None:
        if self.hover is None:
            return
        x, y = self.hover
        c = p.transform().map(QtCore.QPointF(x, y))
        p.save()
        p.resetTransform()
        p.setPen(cosmetic_pen(accent_colour(view), 1.2))
        p.drawLine(QtCore.QPointF(c.x() - 9, c.y()), QtCore.QPointF(c.x() + 9, c.y()))
        p.drawLine(QtCore.QPointF(c.x(), c.y() - 9), QtCore.QPointF(c.x(), c.y() + 9))
        p.restore()

    def move(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        self.hover = ge.snap(x, y, snap_mode(ev.modifiers()))
        return False
