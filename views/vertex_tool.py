"""The vertex tool: drag a vertex, click an edge to insert one, right-click or Delete to remove one."""

from __future__ import annotations

import itertools

import shapely
from PySide6 import QtCore, QtGui

from mrm.core.errors import MRMError
from mrm.document import DocObject
from mrm.document.edits import DeleteVertex, InsertVertex, MoveVertex
from mrm.views import geometry_edit as ge
from mrm.views.canvas import PlaneView
from mrm.views.snapping import SnapExclusion
from mrm.views.tool_base import HIT_PX, Tool, ToolHost, accent_colour, cosmetic_pen, screen_square, snap_mode

Qt = QtCore.Qt
_drag_ids = itertools.count(1)


class VertexTool(Tool):
    name = "vertex"
    cursor = Qt.CursorShape.ArrowCursor
    hint = (
        "Drag a vertex to move it; click an edge to insert a vertex; right-click a vertex (or hover it and "
        "press Delete) to remove it. A dragged vertex snaps to the vertices and edges of objects (Alt held: "
        "not); Shift snaps to pixel centres, Ctrl to pixel corners"
    )
    busy_keys = (Qt.Key.Key_Delete, Qt.Key.Key_Backspace, Qt.Key.Key_Escape)

    def __init__(self, host: ToolHost) -> None:
        super().__init__(host)
        self.obj_id: int | None = None
        self.base: shapely.Geometry | None = None  # geometry at the start of the drag
        self.ref: ge.VertexRef | None = None
        self.inserting = False
        self.insert_at: tuple[float, float] | None = None
        self.hover_vertex: ge.VertexRef | None = None
        self.hover_edge: tuple[ge.VertexRef, tuple[float, float]] | None = None
        self.current: shapely.Geometry | None = None
        self.last_xy: tuple[float, float] | None = None
        #: What of the edited object must not attract the dragged vertex (itself, the edges it moves).
        self.exclusion: SnapExclusion | None = None

    def in_gesture(self) -> bool:
        return self.ref is not None

    def wants_key(self, key: int) -> bool:
        # Delete acts on the hovered vertex even between gestures.
        return key in self.busy_keys and (self.ref is not None or self.hover_vertex is not None)

    def _geometry(self) -> tuple[DocObject, shapely.Geometry] | None:
        obj = self.scene.primary()
        if obj is None or obj.kind == "labels":  # its polygons are derived from its labels (ADR 0033)
            return None
        geom = self.scene.get(obj.id, "euclidean")
        if geom is None or geom.is_empty:
            return None
        return obj, geom

    def move(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if self.ref is not None:
            self._drag_to(self.snapped(view, x, y, ev.modifiers(), self.exclusion))
            return True
        self._update_hover(view, x, y)
        return False

    def _update_hover(self, view: PlaneView, x: float, y: float) -> None:
        self.hover_vertex = None
        self.hover_edge = None
        og = self._geometry()
        if og is None:
            return
        radius = HIT_PX / max(view.pixels_per_unit(), 1e-9)
        self.hover_vertex = ge.nearest_vertex(og[1], x, y, radius)
        if self.hover_vertex is None:
            self.hover_edge = ge.nearest_edge(og[1], x, y, radius * 0.75)
        view.setCursor(
            Qt.CursorShape.SizeAllCursor
            if self.hover_vertex is not None
            else (Qt.CursorShape.CrossCursor if self.hover_edge is not None else Qt.CursorShape.ArrowCursor)
        )

    def press(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        self._update_hover(view, x, y)
        og = self._geometry()
        if og is None:
            obj = self.object_at(x, y)
            if obj is not None and ev.button() == Qt.MouseButton.LeftButton:
                self.scene.doc.set_selection([obj.id])
                return True
            return False
        obj, geom = og
        if ev.button() == Qt.MouseButton.RightButton:
            if self.hover_vertex is not None:
                self.delete(obj.id, self.hover_vertex)
                return True
            return False
        if ev.button() != Qt.MouseButton.LeftButton:
            return False
        if self.hover_vertex is not None:
            self._start(obj.id, geom, self.hover_vertex, inserting=False)
            return True
        if self.hover_edge is not None:
            ref, foot = self.hover_edge
            foot = ge.snap(*foot, snap_mode(ev.modifiers()))
            try:
                inserted = ge.inserted_vertex(geom, ref, foot)
            except MRMError as e:
                self.host.error.emit(f"cannot insert a vertex there: {e}")
                return True
            self.insert_at = foot
            self._start(obj.id, geom, ref, inserting=True)
            self.current = inserted
            self.last_xy = foot
            self.scene.set_preview(obj.id, inserted)
            return True
        hit = self.object_at(x, y)
        if hit is not None and hit.id != obj.id:
            self.scene.doc.set_selection([hit.id])
            return True
        return False

    def _start(self, obj_id: int, geom: shapely.Geometry, ref: ge.VertexRef, inserting: bool) -> None:
        self.obj_id = obj_id
        self.base = geom
        self.ref = ref
        self.inserting = inserting
        self.current = None
        self.last_xy = None
        p, r, i = ref
        refs = ge.vertex_table(geom)[1]
        # Moving: the vertex itself and its two edges; inserting before i: the edge from vertex i − 1.
        self.exclusion = (
            SnapExclusion(obj_id, split=refs.index((p, r, i - 1)), geom=geom)
            if inserting
            else SnapExclusion(obj_id, moving=refs.index(ref), geom=geom)
        )

    def _drag_to(self, xy: tuple[float, float]) -> None:
        assert self.obj_id is not None and self.ref is not None and self.base is not None
        try:
            if self.inserting:
                geom = ge.inserted_vertex(self.base, self.ref, xy)
            else:
                geom = ge.moved_vertex(self.base, self.ref, xy)
        except MRMError as e:
            # Keep the last valid shape on screen; say why this position is refused.
            self.host.message.emit(f"refused: {e}", 2000)
            return
        self.current = geom
        self.last_xy = xy
        self.scene.set_preview(self.obj_id, geom)

    def release(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        if self.ref is None or ev.button() != Qt.MouseButton.LeftButton:
            return self.ref is not None
        if self.last_xy is not None:
            # Where the button is released counts, with the modifiers held at that moment (snapping).
            self._drag_to(self.snapped(view, x, y, ev.modifiers(), self.exclusion))
        self.snap_target = None
        obj_id, ref, xy, inserting = self.obj_id, self.ref, self.last_xy, self.inserting
        self.ref = None
        self.obj_id = None
        assert obj_id is not None
        try:
            if xy is None:
                return True  # a click on a vertex without moving it
            if inserting:
                with self.scene.doc.history.macro("Insert vertex"):
                    self.scene.doc.push(InsertVertex(obj_id, ref, self.insert_at or xy))
                    if xy != self.insert_at:
                        self.scene.doc.push(MoveVertex(obj_id, ref, xy))
            else:
                self.scene.doc.push(MoveVertex(obj_id, ref, xy, drag_id=next(_drag_ids)))
        except MRMError as e:
            self.host.error.emit(f"vertex edit refused: {e}")
        finally:
            self.scene.set_preview(obj_id, None)
            self.current = None
            self._update_hover(view, x, y)
            self.host.overlayChanged.emit()
        return True

    def delete(self, obj_id: int, ref: ge.VertexRef) -> None:
        if self.host.push(DeleteVertex(obj_id, ref)):
            self.hover_vertex = None
            self.host.overlayChanged.emit()

    def key(self, view: PlaneView, ev: QtGui.QKeyEvent) -> bool:
        if ev.key() == Qt.Key.Key_Escape and self.ref is not None:
            self.cancel()
            return True
        if ev.key() in (Qt.Key.Key_Delete, Qt.Key.Key_Backspace) and self.hover_vertex is not None:
            obj = self.scene.primary()
            if obj is not None:
                self.delete(obj.id, self.hover_vertex)
            return True
        return False

    def cancel(self) -> None:
        if self.obj_id is not None:
            self.scene.set_preview(self.obj_id, None)
        self.ref = None
        self.obj_id = None
        self.current = None
        self.hover_vertex = None
        self.hover_edge = None
        self.snap_target = None

    def leave(self, view: PlaneView) -> None:
        if self.ref is None:
            self.hover_vertex = None
            self.hover_edge = None

    def paint_overlay(self, p: QtGui.QPainter, view: PlaneView) -> None:
        acc = accent_colour(view)
        p.setPen(cosmetic_pen(acc, 1.5))
        if self.ref is not None and self.last_xy is not None:
            screen_square(p, *self.last_xy, 11, QtGui.QColor(acc))
            self.paint_snap_marker(p)
            return
        og = self._geometry()
        if og is None:
            return
        if self.hover_vertex is not None:
            xy, refs = ge.vertex_table(og[1])
            k = refs.index(self.hover_vertex)
            screen_square(p, float(xy[k, 0]), float(xy[k, 1]), 11)
        elif self.hover_edge is not None:
            fx, fy = self.hover_edge[1]
            p.setBrush(QtGui.QColor(acc))
            c = p.transform().map(QtCore.QPointF(fx, fy))
            p.save()
            p.resetTransform()
            p.drawEllipse(c, 4.0, 4.0)
            p.restore()
