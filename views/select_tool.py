"""The select tool: click an object to select it; drag to pan."""

from __future__ import annotations

from PySide6 import QtCore, QtGui

from mrm.views.canvas import PlaneView
from mrm.views.tool_base import HIT_PX, Tool, ToolHost

Qt = QtCore.Qt


class SelectTool(Tool):
    name = "select"
    hover_feedback = False
    hint = "Click an object to select it (Shift: add to the selection); drag to pan, wheel to zoom"

    def __init__(self, host: ToolHost) -> None:
        super().__init__(host)
        self._press: QtCore.QPointF | None = None

    def press(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if ev.button() == Qt.MouseButton.LeftButton:
            self._press = ev.position()
        return False  # let the view pan

    def release(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if self._press is None or ev.button() != Qt.MouseButton.LeftButton:
            return False
        moved = (ev.position() - self._press).manhattanLength()
        self._press = None
        if moved > 4:
            return False
        obj = self.object_at(x, y)
        doc = self.scene.doc
        av = self.host.analytical_view
        if view.name == "analytical" and av is not None:
            # In the analytical view a click picks the digital straight segment under the cursor too.
            target = obj or self.scene.primary()
            seg = (
                av.segment_near(target.id, x, y, HIT_PX / max(view.pixels_per_unit(), 1e-9))
                if target
                else None
            )
            if seg is not None and target is not None:
                obj = target
                if obj.id not in doc.selection:
                    doc.set_selection([obj.id])
                self.scene.select_segment(obj.id, *seg)
                return False
        if ev.modifiers() & Qt.KeyboardModifier.ShiftModifier:
            if obj is not None:
                sel = [i for i in doc.selection if i != obj.id]
                if obj.id not in doc.selection:
                    sel.append(obj.id)
                doc.set_selection(sel)
        else:
            doc.set_selection([obj.id] if obj is not None else [])
        return False
