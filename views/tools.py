"""Editing tools: select, draw polygon, edit vertices, paint, erase, fill hole, delete component.

A tool receives the mouse and key events of whichever view the user works in (the four views show the same
plane), previews its edit live through :meth:`Scene.set_preview` — so the other views follow while dragging
or painting — and pushes exactly one command (or one macro) when the gesture ends: every edit is one undo
step. Middle-drag pans and the wheel zooms with every tool; the select tool also pans with the left button.
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np
import shapely
from PySide6 import QtCore, QtGui, QtWidgets

from mrm.core.errors import MRMError, ParameterError
from mrm.core.grids import PixelSet
from mrm.document import DocObject, Style
from mrm.document.commands import (
    AddObject,
    DeleteComponent,
    DeleteVertex,
    FillHole,
    InsertVertex,
    MoveVertex,
    PaintPixels,
    SetSource,
)
from mrm.views import geometry_edit as ge
from mrm.views.canvas import PlaneView
from mrm.views.scene import Scene

Qt = QtCore.Qt
E = QtCore.QEvent.Type

#: Hit radius of vertices and edges, in screen pixels.
HIT_PX = 8.0
#: What the pixel tools say on a label map (ADR 0033).
LABEL_MAP_EDIT = "a label map is not painted: Edit ▸ Split into Objects gives one pixel object per label"
_drag_ids = itertools.count(1)


def snap_mode(mods: Qt.KeyboardModifier) -> str | None:
    """Shift snaps to pixel centres, Ctrl to pixel corners."""
    if mods & Qt.KeyboardModifier.ControlModifier:
        return "corner"
    if mods & Qt.KeyboardModifier.ShiftModifier:
        return "centre"
    return None


class ToolHost(QtCore.QObject):
    """What tools need from the window: the scene, brush settings, messages, overlay repaints."""

    message = QtCore.Signal(str, int)  # text, milliseconds (0 = until replaced)
    error = QtCore.Signal(str)
    overlayChanged = QtCore.Signal()
    brushChanged = QtCore.Signal()
    measured = QtCore.Signal(object)  # a PointMeasure of the measure tool
    pointPicked = QtCore.Signal(float, float)  # the pick-point tool's click

    def __init__(self, scene: Scene, parent: QtCore.QObject | None = None) -> None:
        super().__init__(parent)
        self.scene = scene
        self.brush_size = 3
        self.brush_shape = "round"
        self.discrete_view: Any = None  # set by the window: the fast path of the brush
        self.analytical_view: Any = None  # set by the window: picking segments
        self.colours: list[str] = []  # fill colours of new objects, in turn (preferences)

    def new_style(self, offset: int = 0) -> Style | None:
        """The style of the next new object (None: the model's default palette)."""
        if not self.colours:
            return None
        k = len(self.scene.doc) + offset
        return Style(fill=self.colours[k % len(self.colours)])

    def push(self, cmd: Any) -> bool:
        try:
            self.scene.doc.push(cmd)
        except MRMError as e:
            self.error.emit(str(e))
            return False
        return True


class Tool:
    """Base class: event dispatch in plane coordinates."""

    name = "tool"
    cursor = Qt.CursorShape.ArrowCursor
    hint = ""
    #: Keys the tool wants before the window's shortcuts while it is in the middle of something.
    busy_keys: tuple[int, ...] = ()

    #: The tool draws feedback under the cursor (every mouse move repaints the views' overlays then).
    hover_feedback = True

    def __init__(self, host: ToolHost) -> None:
        self.host = host
        self.scene = host.scene
        self.hover: tuple[float, float] | None = None

    # -------------------------------------------------------------- dispatch
    def handle(self, view: PlaneView, ev: QtCore.QEvent) -> bool:
        t = ev.type()
        if t == E.ShortcutOverride:
            assert isinstance(ev, QtGui.QKeyEvent)
            return self.wants_key(ev.key())
        if t == E.KeyPress:
            assert isinstance(ev, QtGui.QKeyEvent)
            return self.key(view, ev)
        if t == E.KeyRelease:
            return False
        if t == E.Leave:
            self.hover = None
            self.leave(view)
            if self.hover_feedback:
                self.host.overlayChanged.emit()
            return False
        if not isinstance(ev, QtGui.QMouseEvent):
            return False
        x, y = view.map_to_plane(ev.position())
        if t == E.MouseMove:
            self.hover = (x, y)
            r = self.move(view, x, y, ev)
            if self.hover_feedback:
                self.host.overlayChanged.emit()  # repaints every view: only for a tool that draws there
            return r
        if ev.button() == Qt.MouseButton.MiddleButton:
            return False  # pan with every tool
        if t == E.MouseButtonPress:
            view.setFocus()
            return self.press(view, x, y, ev)
        if t == E.MouseButtonRelease:
            return self.release(view, x, y, ev)
        if t == E.MouseButtonDblClick:
            return self.double_click(view, x, y, ev)
        return False

    def press(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        return False

    def move(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        return False

    def release(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        return False

    def double_click(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        return self.press(view, x, y, ev)

    def key(self, view: PlaneView, ev: QtGui.QKeyEvent) -> bool:
        return False

    def leave(self, view: PlaneView) -> None:
        pass

    def activate(self) -> None:
        self.host.message.emit(self.hint, 0)

    def deactivate(self) -> None:
        self.cancel()

    def cancel(self) -> None:
        pass

    def in_gesture(self) -> bool:
        """True in the middle of a gesture (a polygon being drawn, a drag, a stroke): Esc/undo cancel it."""
        return False

    def wants_key(self, key: int) -> bool:
        """True when the tool needs ``key`` now, before the window's shortcuts (Enter, Esc, Delete…)."""
        return self.in_gesture() and key in self.busy_keys

    def paint_overlay(self, p: QtGui.QPainter, view: PlaneView) -> None:
        """Draw the tool's feedback (plane coordinates; cosmetic pens)."""

    # -------------------------------------------------------------- helpers
    def object_at(self, x: float, y: float) -> DocObject | None:
        """The topmost visible object whose discrete representation holds the pixel under (x, y)."""
        px = ge.pixel_at(x, y)
        for obj in reversed(self.scene.doc.objects):
            if not obj.style.visible:
                continue
            ps = self.scene.get(obj.id, "discrete")
            if ps is not None and px in ps:
                return obj
        return None

    def target(self, x: float | None = None, y: float | None = None) -> DocObject | None:
        """The object an edit applies to: the selected one, else the one under the cursor."""
        obj = self.scene.primary()
        if obj is None and x is not None and y is not None:
            obj = self.object_at(x, y)
        return obj


def _pen(
    colour: QtGui.QColor | str, width: float = 1.5, style: Qt.PenStyle = Qt.PenStyle.SolidLine
) -> QtGui.QPen:
    pen = QtGui.QPen(QtGui.QColor(colour))
    pen.setCosmetic(True)
    pen.setWidthF(width)
    pen.setStyle(style)
    return pen


def _accent(view: PlaneView) -> QtGui.QColor:
    return QtGui.QColor("#ffb000") if view.is_dark() else QtGui.QColor("#d35400")


def _screen_square(
    p: QtGui.QPainter, x: float, y: float, size: float, brush: QtGui.QColor | None = None
) -> None:
    """A square of ``size`` screen pixels centred on the plane point (x, y)."""
    c = p.transform().map(QtCore.QPointF(x, y))
    p.save()
    p.resetTransform()
    if brush is not None:
        p.setBrush(brush)
    p.drawRect(QtCore.QRectF(c.x() - size / 2, c.y() - size / 2, size, size))
    p.restore()


# ---------------------------------------------------------------------------------------------- select
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


# ---------------------------------------------------------------------------------------------- polygon
class PolygonTool(Tool):
    name = "polygon"
    cursor = Qt.CursorShape.CrossCursor
    hint = (
        "Click to add vertices; click the first vertex or press Enter to close, Backspace removes the last, "
        "Esc cancels. Start with Alt held to draw a hole in the polygon under it. "
        "Shift snaps to pixel centres, Ctrl to pixel corners"
    )
    busy_keys = (Qt.Key.Key_Return, Qt.Key.Key_Enter, Qt.Key.Key_Escape, Qt.Key.Key_Backspace)
    counter = itertools.count(1)

    def __init__(self, host: ToolHost) -> None:
        super().__init__(host)
        self.points: list[tuple[float, float]] = []
        self.hole = False
        self._snap: str | None = None

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
        self._snap = snap_mode(mods)
        x, y = ge.snap(x, y, self._snap)
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
        self.hover = ge.snap(x, y, snap_mode(ev.modifiers()))
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
        candidates = [self.scene.primary(), *list(reversed(doc.objects))]
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
        acc = _accent(view)
        pts = list(self.points)
        if self.hover is not None and pts:
            pts.append(self.hover)
        if len(pts) >= 2:
            p.setPen(_pen(acc, 1.6, Qt.PenStyle.DashLine if self.hole else Qt.PenStyle.SolidLine))
            p.drawPolyline(QtGui.QPolygonF([QtCore.QPointF(a, b) for a, b in pts]))
        p.setPen(_pen(acc, 1.0))
        for k, (a, b) in enumerate(self.points):
            _screen_square(p, a, b, 9 if k == 0 else 6, QtGui.QColor("#ffffff") if k else acc)
        if self.hover is not None and not self.points:
            p.setPen(_pen(acc, 1.0))
            _screen_square(p, *self.hover, 5)


# ---------------------------------------------------------------------------------------------- vertices
class VertexTool(Tool):
    name = "vertex"
    cursor = Qt.CursorShape.ArrowCursor
    hint = (
        "Drag a vertex to move it; click an edge to insert a vertex; right-click a vertex (or hover it and "
        "press Delete) to remove it. Shift snaps to pixel centres, Ctrl to pixel corners"
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
            self._drag_to(ge.snap(x, y, snap_mode(ev.modifiers())))
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
            self._drag_to(ge.snap(x, y, snap_mode(ev.modifiers())))
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

    def leave(self, view: PlaneView) -> None:
        if self.ref is None:
            self.hover_vertex = None
            self.hover_edge = None

    def paint_overlay(self, p: QtGui.QPainter, view: PlaneView) -> None:
        acc = _accent(view)
        p.setPen(_pen(acc, 1.5))
        if self.ref is not None and self.last_xy is not None:
            _screen_square(p, *self.last_xy, 11, QtGui.QColor(acc))
            return
        og = self._geometry()
        if og is None:
            return
        if self.hover_vertex is not None:
            xy, refs = ge.vertex_table(og[1])
            k = refs.index(self.hover_vertex)
            _screen_square(p, float(xy[k, 0]), float(xy[k, 1]), 11)
        elif self.hover_edge is not None:
            fx, fy = self.hover_edge[1]
            p.setBrush(QtGui.QColor(acc))
            c = p.transform().map(QtCore.QPointF(fx, fy))
            p.save()
            p.resetTransform()
            p.drawEllipse(c, 4.0, 4.0)
            p.restore()


# ---------------------------------------------------------------------------------------------- brush
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
        p.setPen(_pen(_accent(view), 1.2))
        p.setBrush(Qt.BrushStyle.NoBrush)
        if self.host.brush_shape == "round" and size > 2:
            c = (size - 1) / 2.0
            p.drawEllipse(QtCore.QPointF(ox + c, oy + c), size / 2.0, size / 2.0)
        else:
            p.drawRect(QtCore.QRectF(ox - 0.5, oy - 0.5, size, size))


# ---------------------------------------------------------------------------------------------- region edits
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
        p.setPen(_pen(_accent(view), 1.5))
        p.setBrush(Qt.BrushStyle.NoBrush)
        p.drawRect(QtCore.QRectF(x - 0.5, y - 0.5, 1, 1))


class FillHoleTool(_ClickPixelTool):
    name = "fill_hole"
    hint = "Click inside a hole of an object to fill it"

    def click(self, px: tuple[int, int]) -> None:
        doc = self.scene.doc
        cands = [o for o in ([self.scene.primary(), *list(reversed(doc.objects))]) if o is not None]
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
                doc.push(FillHole(obj.id, px))  # the model's command finds the hole (DESIGN §4)
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
        p.setPen(_pen(_accent(view), 1.2))
        p.drawLine(QtCore.QPointF(c.x() - 9, c.y()), QtCore.QPointF(c.x() + 9, c.y()))
        p.drawLine(QtCore.QPointF(c.x(), c.y() - 9), QtCore.QPointF(c.x(), c.y() + 9))
        p.restore()

    def move(self, view: PlaneView, x: float, y: float, ev: QtGui.QMouseEvent) -> bool:
        self.hover = ge.snap(x, y, snap_mode(ev.modifiers()))
        return False


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


def make_tools(host: ToolHost) -> dict[str, Tool]:
    """One instance of every tool, by name."""
    tools: list[Tool] = [
        SelectTool(host),
        PolygonTool(host),
        VertexTool(host),
        BrushTool(host, True),
        BrushTool(host, False),
        FillHoleTool(host),
        DeleteComponentTool(host),
        PickPointTool(host),
    ]
    from mrm.views.measure import MeasureTool  # it builds on this module's helpers

    tools.append(MeasureTool(host))
    return {t.name: t for t in tools}


def plane_radius(view: PlaneView, px: float) -> float:
    return px / max(view.pixels_per_unit(), 1e-9)


__all__ = ["BrushTool", "PolygonTool", "SelectTool", "Tool", "ToolHost", "VertexTool", "make_tools", "math"]
