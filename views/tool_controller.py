"""Routes the views' mouse and key events to the active tool and draws its feedback in every view."""

from __future__ import annotations

import math
from collections.abc import Callable

import pyqtgraph as pg
from PySide6 import QtCore, QtGui

from mrm.views.canvas import PlaneView
from mrm.views.tool_base import Tool, ToolHost
from mrm.views.tools import make_tools


def _is_menu_key(ev: QtCore.QEvent) -> bool:
    if not isinstance(ev, QtGui.QKeyEvent):
        return False
    k, mods = ev.key(), ev.modifiers()
    return k == QtCore.Qt.Key.Key_Menu or (
        k == QtCore.Qt.Key.Key_F10 and mods == QtCore.Qt.KeyboardModifier.ShiftModifier
    )


class ToolOverlay(pg.GraphicsObject):
    """Draws the active tool's feedback (rubber band, brush outline, hovered vertex) above everything."""

    def __init__(self, controller: ToolController, view: PlaneView) -> None:
        super().__init__()
        self.controller = controller
        self.view = view
        self._rect = QtCore.QRectF()
        self.setZValue(100_000)

    def view_changed(self, rect: QtCore.QRectF) -> None:
        self.prepareGeometryChange()
        self._rect = QtCore.QRectF(rect)

    def boundingRect(self) -> QtCore.QRectF:
        return self._rect

    def paint(self, p: QtGui.QPainter, *_args: object) -> None:
        tool = self.controller.tool
        p.setRenderHint(QtGui.QPainter.RenderHint.Antialiasing, True)
        if tool is not None:
            tool.paint_overlay(p, self.view)
        for x, y, label in self.controller.marks:
            self._paint_mark(p, x, y, label)

    def _paint_mark(self, p: QtGui.QPainter, x: float, y: float, label: str) -> None:
        """A point of interest (where a Hausdorff distance is reached): a ring and its label, screen-sized."""
        c = p.transform().map(QtCore.QPointF(x, y))
        colour = QtGui.QColor("#ffb000") if self.view.is_dark() else QtGui.QColor("#c2185b")
        p.save()
        p.resetTransform()
        pen = QtGui.QPen(colour)
        pen.setWidthF(2.0)
        p.setPen(pen)
        p.setBrush(QtCore.Qt.BrushStyle.NoBrush)
        p.drawEllipse(c, 6.0, 6.0)
        p.drawLine(c + QtCore.QPointF(-9, 0), c + QtCore.QPointF(9, 0))
        p.drawLine(c + QtCore.QPointF(0, -9), c + QtCore.QPointF(0, 9))
        p.drawText(c + QtCore.QPointF(9, -8), label)
        p.restore()


class ToolController(QtCore.QObject):
    """Owns the tools; ``set_tool(name)`` switches, ``toolChanged(name)`` tells the window.

    A right click that the active tool does not use (the polygon tool uses it while drawing, the vertex
    tool on a vertex) asks for the view's context menu: ``contextMenuRequested(view, x, y, global_pos)``,
    on release, so that it works the same on every platform.
    """

    toolChanged = QtCore.Signal(str)
    contextMenuRequested = QtCore.Signal(object, float, float, QtCore.QPoint)

    def __init__(self, host: ToolHost, views: list[PlaneView], parent: QtCore.QObject | None = None) -> None:
        super().__init__(parent)
        self.host = host
        self.tools = make_tools(host)
        self.tool: Tool | None = None
        self.views = views
        self.overlays: list[ToolOverlay] = []
        for v in views:
            ov = ToolOverlay(self, v)
            v.vb.addItem(ov, ignoreBounds=True)
            v.vb.sigRangeChanged.connect(lambda *_a, o=ov, vv=v: o.view_changed(vv.vb.viewRect()))
            ov.view_changed(v.vb.viewRect())
            self.overlays.append(ov)
            v.tool_handler = self._dispatch
        host.overlayChanged.connect(self._repaint)
        host.pointPicked.connect(self._picked)
        self._right_press: QtCore.QPointF | None = None
        #: Points drawn in every view whatever the tool: (x, y, label) — e.g. where H(A, B) is reached.
        self.marks: list[tuple[float, float, str]] = []
        self._pick_callback: Callable[[float, float], None] | None = None
        self._before_pick = "select"
        self.set_tool("select")

    def _dispatch(self, view: PlaneView, ev: QtCore.QEvent) -> bool:
        if self.tool is None:
            return False
        t = ev.type()
        if t == QtCore.QEvent.Type.KeyPress and _is_menu_key(ev) and not self.tool.in_gesture():
            # The keyboard's menu key (or Shift+F10): the menu of the point under the cursor, else the centre.
            vp = view.viewport()
            pos = vp.mapFromGlobal(QtGui.QCursor.pos())
            if not vp.rect().contains(pos):
                pos = vp.rect().center()
            x, y = view.map_to_plane(QtCore.QPointF(pos))
            self.contextMenuRequested.emit(view, x, y, vp.mapToGlobal(pos))
            return True
        right = isinstance(ev, QtGui.QMouseEvent) and ev.button() == QtCore.Qt.MouseButton.RightButton
        if right and t == QtCore.QEvent.Type.MouseButtonPress:
            assert isinstance(ev, QtGui.QMouseEvent)
            if self.tool.handle(view, ev):
                self._right_press = None
                return True
            self._right_press = ev.position()
            return True  # the context menu's click, not pyqtgraph's right-drag zoom
        if right and t == QtCore.QEvent.Type.MouseButtonRelease and self._right_press is not None:
            assert isinstance(ev, QtGui.QMouseEvent)
            moved = (ev.position() - self._right_press).manhattanLength()
            self._right_press = None
            if moved <= 6:
                x, y = view.map_to_plane(ev.position())
                gpos = view.viewport().mapToGlobal(ev.position().toPoint())
                self.contextMenuRequested.emit(view, x, y, gpos)
            return True
        return self.tool.handle(view, ev)

    def set_marks(self, marks: list[tuple[float, float, str]]) -> None:
        self.marks = list(marks)
        self._repaint()

    # ------------------------------------------------------------------ picking a point
    def pick_point(self, callback: Callable[[float, float], None]) -> None:
        """Let the next click in a view give a plane point to ``callback``; then back to the current tool.

        Esc (or choosing another tool) cancels: ``callback`` is not called.
        """
        if self.tool is not None and self.tool.name != "pick_point":
            self._before_pick = self.tool.name
        self._pick_callback = callback
        self.set_tool("pick_point")

    def is_picking(self) -> bool:
        return self.tool is not None and self.tool.name == "pick_point"

    def _picked(self, x: float, y: float) -> None:
        cb, self._pick_callback = self._pick_callback, None
        self.set_tool(self._before_pick)
        if cb is not None and not (math.isnan(x) or math.isnan(y)):
            cb(x, y)

    def _repaint(self) -> None:
        for ov in self.overlays:
            ov.update()

    def set_tool(self, name: str) -> None:
        tool = self.tools[name]
        if tool is self.tool:
            return
        if self.tool is not None:
            self.tool.deactivate()
        if name != "pick_point":
            self._pick_callback = None  # another tool chosen: the pick is abandoned
        self.tool = tool
        for v in self.views:
            v.setCursor(tool.cursor)
            # The select tool pans with the left button; drawing tools keep it for themselves.
        tool.activate()
        self._repaint()
        self.toolChanged.emit(name)

    def cancel(self) -> bool:
        """Cancel the gesture in progress; True if there was one."""
        if self.tool is not None and self.tool.in_gesture():
            self.tool.cancel()
            self._repaint()
            return True
        return False
