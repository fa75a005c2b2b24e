"""Routes the views' mouse and key events to the active tool and draws its feedback in every view."""

from __future__ import annotations

import pyqtgraph as pg
from PySide6 import QtCore, QtGui

from mrm.views.canvas import PlaneView
from mrm.views.tools import Tool, ToolHost, make_tools


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
        if tool is not None:
            p.setRenderHint(QtGui.QPainter.RenderHint.Antialiasing, True)
            tool.paint_overlay(p, self.view)


class ToolController(QtCore.QObject):
    """Owns the tools; ``set_tool(name)`` switches, ``toolChanged(name)`` tells the window."""

    toolChanged = QtCore.Signal(str)

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
        self.set_tool("select")

    def _dispatch(self, view: PlaneView, ev: QtCore.QEvent) -> bool:
        return self.tool.handle(view, ev) if self.tool is not None else False

    def _repaint(self) -> None:
        for ov in self.overlays:
            ov.update()

    def set_tool(self, name: str) -> None:
        tool = self.tools[name]
        if tool is self.tool:
            return
        if self.tool is not None:
            self.tool.deactivate()
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
