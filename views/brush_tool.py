"""The paint and erase tools: a brush stroke on the selected object's pixels, one undo step."""

from __future__ import annotations

import itertools

import numpy as np
from PySide6 import QtCore, QtGui

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from mrm.document.edits import PaintPixels
from mrm.views import geometry_edit as ge
from mrm.views.canvas import PlaneView
from mrm.views.tool_base import Tool, ToolHost, accent_colour, cosmetic_pen

Qt = QtCore.Qt

#: What the pixel tools say on a label map (ADR 0033).
LABEL_MAP_EDIT = "a label map is not painted: Edit ▸ Split into Objects gives one pixel object per label"


class StrokeBuffer:
    """The pixels of an object during a brush stroke: a growable canvas and the footprint of the stroke."""

    def __init__(self, base: PixelSet, value: bool) -> None:
        self.value = value
        b = base.bbox
        if b is None:
            self.origin = (0, 0)
            self.canvas = np.zeros((0, 0), dtype=bool)
        else:
            self.origin = (b[0], b[1])
            self.canvas = base.to_array(b)
        self.touched = np.zeros(self.canvas.shape, dtype=bool)
        self.grew = False

    def _ensure(self, x0: int, y0: int, x1: int, y1: int) -> None:
        """Grow the arrays to hold pixels x0..x1, y0..y1 (with slack so that strokes rarely reallocate)."""
        h, w = self.canvas.shape
        ox, oy = self.origin
        if h and w and x0 >= ox and y0 >= oy and x1 < ox + w and y1 < oy + h:
            return
        if not (h and w):
            ox, oy, w, h = x0, y0, 0, 0
        pad = 32
        nx0 = min(ox, x0 - pad) if x0 < ox or not w else ox
        ny0 = min(oy, y0 - pad) if y0 < oy or not h else oy
        nx1 = max(ox + w - 1, x1 + pad) if x1 >= ox + w or not w else ox + w - 1
        ny1 = max(oy + h - 1, y1 + pad) if y1 >= oy + h or not h else oy + h - 1
        canvas = np.zeros((ny1 - ny0 + 1, nx1 - nx0 + 1), dtype=bool)
        touched = np.zeros_like(canvas)
        if h and w:
            canvas[oy - ny0 : oy - ny0 + h, ox - nx0 : ox - nx0 + w] = self.canvas
            touched[oy - ny0 : oy - ny0 + h, ox - nx0 : ox - nx0 + w] = self.touched
        self.canvas, self.touched, self.origin = canvas, touched, (nx0, ny0)
        self.grew = True

    def dab(self, foot: np.ndarray, at: tuple[int, int]) -> None:
        fh, fw = foot.shape
        self._ensure(at[0], at[1], at[0] + fw - 1, at[1] + fh - 1)
        r0 = at[1] - self.origin[1]
        c0 = at[0] - self.origin[0]
        cv = self.canvas[r0 : r0 + fh, c0 : c0 + fw]
        if self.value:
            cv |= foot
        else:
            cv &= ~foot
        self.touched[r0 : r0 + fh, c0 : c0 + fw] |= foot

    def pixels(self) -> PixelSet:
        return PixelSet(self.canvas, self.origin)

    def stroke(self) -> PixelSet:
        return PixelSet(self.touched, self.origin)


class BrushTool(Tool):
    """Paint (``value=True``) or erase pixels of the selected object; a stroke is one undo step.

    Painting with nothing selected creates a new discrete object.
    """

    cursor = Qt.CursorShape.CrossCursor
    busy_keys = (Qt.Key.Key_Escape,)
    #: Interval (ms) at which the other three views are given the stroke in progress.
    PREVIEW_MS = 40
    counter = itertools.count(1)

    def __init__(self, host: ToolHost, value: bool) -> None:
        super().__init__(host)
        self.value = value
        self.name = "paint" if value else "erase"
        self.hint = (
            f"{'Paint' if value else 'Erase'} pixels of the selected object"
            + (" (with nothing selected, a new object)" if value else "")
            + "; [ and ] change the brush size"
        )
        self.buffer: StrokeBuffer | None = None
        self.obj_id: int | None = None
        self.last: tuple[float, float] | None = None
        self._timer = QtCore.QTimer()
        self._timer.setSingleShot(True)
        self._timer.setInterval(self.PREVIEW_MS)
        self._timer.timeout.connect(self._publish_preview)
        self.dabs = 0

    def in_gesture(self) -> bool:
        return self.buffer is not None

    def footprint(self) -> np.ndarray:
        return ge.dab_offsets(self.host.brush_size, self.host.brush_shape)

    def press(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if ev.button() != Qt.MouseButton.LeftButton:
            return False
        obj = self.scene.primary()
        if obj is None and not self.value:
            obj = self.object_at(x, y)
            if obj is None:
                self.host.message.emit("select an object to erase from", 3000)
                return True
        base = PixelSet.empty()
        if obj is not None and obj.kind == "labels":
            self.host.message.emit(LABEL_MAP_EDIT, 5000)
            return True
        if obj is not None:
            ps = (
                self.scene.entry(obj.id).get("discrete")
                if self._cheap(obj.id)
                else self.scene.get(obj.id, "discrete")
            )
            if ps is None:
                self.host.message.emit("the object's pixels are still being computed", 2000)
                return True
            base = ps
        self.obj_id = obj.id if obj is not None else None
        self.buffer = StrokeBuffer(base, self.value)
        self.last = (x, y)
        self._dab_at(x, y)
        return True

    def _cheap(self, obj_id: int) -> bool:
        return True

    def move(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if self.buffer is None:
            return False
        assert self.last is not None
        for cx, cy in ge.stroke_centres(self.last, (x, y), self.host.brush_size):
            self._dab_at(cx, cy, show=False)
        self.last = (x, y)
        self._show()
        return True

    def _dab_at(self, x: float, y: float, show: bool = True) -> None:
        assert self.buffer is not None
        size = self.host.brush_size
        self.buffer.dab(self.footprint(), ge.dab_origin(x, y, size))
        self.dabs += 1
        if show:
            self._show()

    def _show(self) -> None:
        """The fast path: put the canvas straight into the discrete view, the others follow on a timer."""
        buf = self.buffer
        assert buf is not None
        dv = self.host.discrete_view
        if dv is not None and self.obj_id is not None:
            dv.show_stroke(self.obj_id, buf.canvas, buf.origin, buf.grew)
            buf.grew = False
        elif dv is not None:
            dv.show_stroke(None, buf.canvas, buf.origin, buf.grew)
            buf.grew = False
        if not self._timer.isActive():
            self._timer.start()

    def _publish_preview(self) -> None:
        if self.buffer is not None and self.obj_id is not None:
            self.scene.set_preview(self.obj_id, self.buffer.pixels())

    def release(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if self.buffer is None or ev.button() != Qt.MouseButton.LeftButton:
            return self.buffer is not None
        self._timer.stop()
        buf, obj_id = self.buffer, self.obj_id
        self.buffer = None
        self.obj_id = None
        stroke = buf.stroke()
        dv = self.host.discrete_view
        if dv is not None:
            dv.end_stroke()
        try:
            if obj_id is None:
                ps = buf.pixels()
                if not ps.is_empty():
                    obj = self.scene.doc.make_object(
                        ps, name=f"Pixels {next(self.counter)}", style=self.host.new_style()
                    )
                    self.host.push(AddObject(obj, select=True))
            else:
                self.host.push(PaintPixels(obj_id, stroke, self.value))
        finally:
            if obj_id is not None:
                self.scene.set_preview(obj_id, None)
        return True

    def cancel(self) -> None:
        self._timer.stop()
        if self.buffer is not None:
            if self.obj_id is not None:
                self.scene.set_preview(self.obj_id, None)
            dv = self.host.discrete_view
            if dv is not None:
                dv.end_stroke()
        self.buffer = None
        self.obj_id = None

    def key(self, view: PlaneView, ev: QtGui.QKeyEvent) -> bool:
        if ev.key() == Qt.Key.Key_Escape and self.buffer is not None:
            self.cancel()
            return True
        return False

    def paint_overlay(self, p: QtGui.QPainter, view: PlaneView) -> None:
        if self.hover is None:
            return
        size = self.host.brush_size
        ox, oy = ge.dab_origin(*self.hover, size)
        p.setPen(cosmetic_pen(accent_colour(view), 1.2))
        p.setBrush(Qt.BrushStyle.NoBrush)
        if self.host.brush_shape == "round" and size > 2:
            c = (size - 1) / 2.0
            p.drawEllipse(QtCore.QPointF(ox + c, oy + c), size / 2.0, size / 2.0)
        else:
            p.drawRect(QtCore.QRectF(ox - 0.5, oy - 0.5, size, size))
