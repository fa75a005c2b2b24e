"""The polygon tool: click the vertices of a new polygon (or, Alt held on the first click, of a hole)."""

from __future__ import annotations

import itertools

import numpy as np
import shapely
from PySide6 import QtCore, QtGui, QtWidgets

from mrm.core.errors import MRMError
from mrm.document.commands import AddObject, SetSource
from mrm.views import geometry_edit as ge
from mrm.views.canvas import PlaneView
from mrm.views.tool_base import HIT_PX, Tool, ToolHost, accent_colour, cosmetic_pen, screen_square

Qt = QtCore.Qt


class PolygonTool(Tool):
    name = "polygon"
    cursor = Qt.CursorShape.CrossCursor
    hint = (
        "Click to add vertices; click the first vertex or press Enter to close, Backspace removes the last, "
        "Esc cancels. Start with Alt held to draw a hole in the polygon under it. "
        "Points snap to the vertices and edges of objects (Alt held: not); Shift snaps to pixel centres, "
        "Ctrl to pixel corners"
    )
    busy_keys = (Qt.Key.Key_Return, Qt.Key.Key_Enter, Qt.Key.Key_Escape, Qt.Key.Key_Backspace)
    counter = itertools.count(1)

    def __init__(self, host: ToolHost) -> None:
        super().__init__(host)
        self.points: list[tuple[float, float]] = []
        self.hole = False

    def in_gesture(self) -> bool:
        return bool(self.points)

    def cancel(self) -> None:
        if self.points:
            self.points = []
            self.host.overlayChanged.emit()

    def press(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if ev.button() == Qt.MouseButton.RightButton:
            if not self.points:
                return False  # nothing drawn yet: the view's context menu
            self.points.pop()
            self.host.overlayChanged.emit()
            return True
        if ev.button() != Qt.MouseButton.LeftButton:
            return False
        mods = ev.modifiers()
        x, y = self.snapped(view, x, y, mods)
        if not self.points:
            self.hole = bool(mods & Qt.KeyboardModifier.AltModifier)
        elif len(self.points) >= 3:
            fx, fy = self.points[0]
            c = view.map_from_plane(fx, fy)
            if (QtCore.QPointF(c) - ev.position()).manhattanLength() <= HIT_PX * 1.5:
                self.finish()
                return True
        if not self.points or (x, y) != self.points[-1]:
            self.points.append((x, y))
        self.host.overlayChanged.emit()
        return True

    def double_click(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        # The double click's first press already added the vertex: close there.
        if ev.button() == Qt.MouseButton.LeftButton and len(self.points) >= 3:
            self.finish()
            return True
        return self.press(view, x, y, ev)

    def move(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        self.hover = self.snapped(view, x, y, ev.modifiers())
        return bool(self.points)

    def key(self, view: PlaneView, ev: QtGui.QKeyEvent) -> bool:
        k = ev.key()
        if not self.points:
            return False
        if k in (Qt.Key.Key_Return, Qt.Key.Key_Enter):
            self.finish()
            return True
        if k == Qt.Key.Key_Escape:
            self.cancel()
            return True
        if k == Qt.Key.Key_Backspace:
            self.points.pop()
            self.host.overlayChanged.emit()
            return True
        return False

    def finish(self) -> None:
        pts, self.points = self.points, []
        self.host.overlayChanged.emit()
        if len(pts) < 3:
            self.host.error.emit("a polygon needs at least 3 vertices")
            return
        ring = np.asarray(pts, dtype=float)
        try:
            if self.hole:
                self._add_hole(ring)
                return
            geom = ge.new_polygon(ring)
        except MRMError as e:
            if not shapely.Polygon(ring).is_valid and len(pts) >= 3:
                self.offer_repair(pts)  # a self-crossing outline: repair it or keep editing, never lose it
            else:
                self.host.error.emit(f"polygon refused: {e}")
            return
        self._add(geom)

    def _add(self, geom: shapely.Geometry) -> None:
        doc = self.scene.doc
        obj = doc.make_object(geom, name=f"Polygon {next(self.counter)}", style=self.host.new_style())
        self.host.push(AddObject(obj, select=True))

    def offer_repair(self, pts: list[tuple[float, float]]) -> QtWidgets.QMessageBox:
        """Ask whether to repair a self-crossing outline (shapely ``make_valid``) or go on editing it.

        The box is window-modal but does not block the caller; ``self.repair_box`` is the open one.
        """
        repaired = repair_polygon(np.asarray(pts, dtype=float))
        parent = self.host.parent() if isinstance(self.host.parent(), QtWidgets.QWidget) else None
        box = QtWidgets.QMessageBox(parent)
        box.setObjectName("repairPolygon")
        box.setIcon(QtWidgets.QMessageBox.Icon.Question)
        box.setWindowTitle("The outline crosses itself")
        n = len(shapely.get_parts(repaired)) if repaired is not None else 0
        box.setText("The outline you drew crosses itself, so it is not a valid polygon.")
        box.setInformativeText(
            (
                f"Repair splits it where it crosses into {n} valid polygon{'s' if n != 1 else ''} "
                f"(area {repaired.area:.4g}). "
                if repaired is not None
                else "It encloses no area, so it cannot be repaired. "
            )
            + "Keep editing goes back to the drawing with every vertex (Backspace removes the last one)."
        )
        repair = box.addButton("Repair", QtWidgets.QMessageBox.ButtonRole.AcceptRole)
        repair.setObjectName("repairButton")
        repair.setEnabled(repaired is not None)
        keep = box.addButton("Keep editing", QtWidgets.QMessageBox.ButtonRole.RejectRole)
        keep.setObjectName("keepEditingButton")
        box.setDefaultButton(keep)

        def chosen(button: QtWidgets.QAbstractButton) -> None:
            if button is repair and repaired is not None:
                self._add(repaired)
            else:
                self.points = list(pts)
                self.host.overlayChanged.emit()
                self.host.message.emit("drawing kept: move the mouse and click to go on", 4000)

        box.buttonClicked.connect(chosen)
        box.setWindowModality(QtCore.Qt.WindowModality.WindowModal)
        box.show()
        self.repair_box = box
        return box

    def _add_hole(self, ring: np.ndarray) -> None:
        doc = self.scene.doc
        hole = shapely.Polygon(ring)
        candidates = [self.scene.primary(), *list(reversed(doc.plane_objects))]
        for obj in candidates:
            if obj is None or not obj.style.visible or obj.kind == "labels":  # a subdivision: no holes drawn
                continue
            geom = self.scene.get(obj.id, "euclidean")
            if geom is None or not geom.contains(hole):
                continue
            new = ge.with_hole(geom, ring)
            if new is not None:
                self.host.push(SetSource(obj.id, new, label="Draw hole"))
                return
        self.host.error.emit("a hole must be drawn inside a polygon")

    def paint_overlay(self, p: QtGui.QPainter, view: PlaneView) -> None:
        if not self.points and self.hover is None:
            return
        acc = accent_colour(view)
        pts = list(self.points)
        if self.hover is not None and pts:
            pts.append(self.hover)
        if len(pts) >= 2:
            p.setPen(cosmetic_pen(acc, 1.6, Qt.PenStyle.DashLine if self.hole else Qt.PenStyle.SolidLine))
            p.drawPolyline(QtGui.QPolygonF([QtCore.QPointF(a, b) for a, b in pts]))
        p.setPen(cosmetic_pen(acc, 1.0))
        for k, (a, b) in enumerate(self.points):
            screen_square(p, a, b, 9 if k == 0 else 6, QtGui.QColor("#ffffff") if k else acc)
        if self.hover is not None and not self.points:
            p.setPen(cosmetic_pen(acc, 1.0))
            screen_square(p, *self.hover, 5)
        if self.hover is not None:
            self.paint_snap_marker(p)


def repair_polygon(ring: np.ndarray) -> shapely.Geometry | None:
    """The valid polygon(s) shapely's ``make_valid`` makes of a self-crossing ring (None: no area)."""
    from mrm.document import validate_geometry

    fixed = shapely.make_valid(shapely.Polygon(ring))
    polys = [p for p in shapely.get_parts(fixed) if isinstance(p, shapely.Polygon) and p.area > 0]
    if not polys:
        # A collection may hold a MultiPolygon among lines and points.
        for g in shapely.get_parts(fixed):
            if isinstance(g, shapely.MultiPolygon):
                polys.extend(p for p in g.geoms if p.area > 0)
    if not polys:
        return None
    geom = shapely.MultiPolygon(polys) if len(polys) > 1 else polys[0]
    return validate_geometry(orient_all(geom))


def orient_all(geom: shapely.Geometry) -> shapely.Geometry:
    """Counter-clockwise exteriors (as drawn polygons are stored)."""
    from shapely.geometry.polygon import orient

    if isinstance(geom, shapely.MultiPolygon):
        return shapely.MultiPolygon([orient(p, 1.0) for p in geom.geoms])
    return orient(geom, 1.0)
