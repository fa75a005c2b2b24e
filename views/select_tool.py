"""The select tool: click an object to select it, drag a rectangle on empty canvas to select what it touches.

The rectangle (the rubber band) selects every visible object it **touches**, as QGIS's rectangle selection
does: a polygon it meets (its interior or boundary), a pixel object or label map one of whose pixels (unit
squares) it meets. Shift adds to the selection; without Shift the band replaces it. A drag that starts on an
object pans the views instead, as the middle button does with every tool.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from PySide6 import QtCore, QtGui

from mrm.core.grids import LabelMap, PixelSet
from mrm.document import DocObject
from mrm.views.canvas import PlaneView
from mrm.views.tool_base import HIT_PX, Tool, ToolHost, accent_colour, cosmetic_pen

Qt = QtCore.Qt

#: Screen pixels the mouse moves, button held, before a press becomes a drag (a band or a pan).
DRAG_PX = 4

Box = tuple[float, float, float, float]


def touches(obj: DocObject, box: Box) -> bool:
    """True when the closed plane rectangle ``box`` = (xmin, ymin, xmax, ymax) meets the object's source.

    A polygon: shapely's ``intersects`` (a shared boundary point counts). Pixels (a pixel set, a label map's
    non-zero labels): one of them whose unit square [x−½, x+½]×[y−½, y+½] meets the rectangle.
    """
    src = obj.source
    xmin, ymin, xmax, ymax = box
    if isinstance(src, PixelSet | LabelMap):
        if src.is_empty():
            return False
        ox, oy = src.origin
        h, w = src.shape
        # Pixel x meets [xmin, xmax] when x − ½ ≤ xmax and x + ½ ≥ xmin.
        c0, c1 = max(math.ceil(xmin - 0.5) - ox, 0), min(math.floor(xmax + 0.5) - ox, w - 1)
        r0, r1 = max(math.ceil(ymin - 0.5) - oy, 0), min(math.floor(ymax + 0.5) - oy, h - 1)
        if c0 > c1 or r0 > r1:
            return False
        if isinstance(src, LabelMap):
            return bool(np.any(src.labels[r0 : r1 + 1, c0 : c1 + 1]))
        return bool(np.any(src.mask[r0 : r1 + 1, c0 : c1 + 1]))
    return bool(shapely.intersects(shapely.box(xmin, ymin, xmax, ymax), src))


class SelectTool(Tool):
    name = "select"
    hover_feedback = False
    hint = (
        "Click an object to select it (Shift: add to the selection); drag on empty canvas to select the "
        "objects a rectangle touches (Shift: add them); drag from an object to pan, wheel to zoom"
    )
    busy_keys = (Qt.Key.Key_Escape,)

    def __init__(self, host: ToolHost) -> None:
        super().__init__(host)
        self._press: QtCore.QPointF | None = None
        self._anchor: tuple[float, float] | None = None  # where a press on empty canvas was (plane)
        #: The rubber band being dragged: (x0, y0, x1, y1), anchor then cursor, in plane coordinates.
        self.band: Box | None = None

    def in_gesture(self) -> bool:
        return self.band is not None

    def cancel(self) -> None:
        self._anchor = None
        self._press = None
        if self.band is not None:
            self.band = None
            self.host.overlayChanged.emit()

    def key(self, view: PlaneView, ev: QtGui.QKeyEvent) -> bool:
        if ev.key() == Qt.Key.Key_Escape and self.band is not None:
            self.cancel()
            return True
        return False

    def press(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if ev.button() != Qt.MouseButton.LeftButton:
            return False
        self._press = ev.position()
        if self.object_at(x, y) is not None:
            self._anchor = None
            return False  # on an object: a drag pans the view
        self._anchor = (x, y)
        return True  # on empty canvas: a drag is a rubber band, not a pan

    def move(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if self._anchor is None or self._press is None:
            return False
        if not ev.buttons() & Qt.MouseButton.LeftButton:
            self.cancel()  # the release went elsewhere
            return False
        if self.band is None and (ev.position() - self._press).manhattanLength() <= DRAG_PX:
            return True
        self.band = (*self._anchor, x, y)
        self.host.overlayChanged.emit()
        return True

    def release(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if self._press is None or ev.button() != Qt.MouseButton.LeftButton:
            return False
        moved = (ev.position() - self._press).manhattanLength()
        self._press = None
        anchor, self._anchor = self._anchor, None
        if self.band is not None and anchor is not None:
            self.band = None
            self.select_band((*anchor, x, y), add=bool(ev.modifiers() & Qt.KeyboardModifier.ShiftModifier))
            self.host.overlayChanged.emit()
            return True
        if moved > DRAG_PX:
            return False
        self.click(view, x, y, ev)
        return anchor is not None

    def select_band(self, corners: Box, *, add: bool) -> list[int]:
        """Select the visible objects the rectangle with corners (x0, y0), (x1, y1) touches; their ids.

        ``add``: added to the selection (Shift), else the selection becomes them (nothing: cleared).
        """
        x0, y0, x1, y1 = corners
        box = (min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1))
        doc = self.scene.doc
        hit = [o.id for o in doc.plane_objects if o.style.visible and touches(o, box)]
        if add:
            doc.set_selection([*doc.selection, *hit])
        else:
            doc.set_selection(hit)
        n = len(hit)
        self.host.message.emit(f"{n} object{'s' if n != 1 else ''} in the rectangle", 2000)
        return hit

    def click(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> None:
        """A click: the object under the cursor (Shift: toggled in the selection); on empty canvas, none."""
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
                return
        if ev.modifiers() & Qt.KeyboardModifier.ShiftModifier:
            if obj is not None:
                sel = [i for i in doc.selection if i != obj.id]
                if obj.id not in doc.selection:
                    sel.append(obj.id)
                doc.set_selection(sel)
        else:
            doc.set_selection([obj.id] if obj is not None else [])

    def paint_overlay(self, p: QtGui.QPainter, view: PlaneView) -> None:
        if self.band is None:
            return
        x0, y0, x1, y1 = self.band
        acc = accent_colour(view)
        fill = QtGui.QColor(acc)
        fill.setAlpha(48)
        p.setPen(cosmetic_pen(acc, 1.2, Qt.PenStyle.DashLine))
        p.setBrush(fill)
        p.drawRect(QtCore.QRectF(QtCore.QPointF(x0, y0), QtCore.QPointF(x1, y1)).normalized())
