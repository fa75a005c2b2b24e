"""What every editing tool shares: the host (the window's side of a tool), the base class, drawing helpers.

A tool receives the mouse and key events of whichever view the user works in (the four views show the same
plane), previews its edit live through :meth:`Scene.set_preview` — so the other views follow while dragging or
painting — and pushes exactly one command (or one macro) when the gesture ends: every edit is one undo step.
Middle-drag pans and the wheel zooms with every tool. The tools themselves live in one module each
(:mod:`mrm.views.select_tool`, :mod:`mrm.views.polygon_tool`, ...); :func:`mrm.views.tools.make_tools` makes
one of each.
"""

from __future__ import annotations

from typing import Any

from PySide6 import QtCore, QtGui

from mrm.core.errors import MRMError
from mrm.document import DocObject, Style
from mrm.views import geometry_edit as ge
from mrm.views.canvas import PlaneView
from mrm.views.scene import Scene
from mrm.views.snapping import ObjectSnapper, SnapExclusion, SnapTarget

Qt = QtCore.Qt
E = QtCore.QEvent.Type

#: Hit radius of vertices and edges, in screen pixels.
HIT_PX = 8.0
#: Distance, in screen pixels, within which a drawn or dragged point snaps to an object's vertex or edge.
SNAP_PX = 10.0
#: The colour of the snap marker: magenta, as in QGIS, distinct from the tools' accent and the selection.
SNAP_COLOUR = "#e6007e"


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
        #: Snapping to the vertices and edges of objects (View ▸ Snap to Objects; Alt held suspends it).
        self.snap_to_objects = True
        self.snapper = ObjectSnapper(scene)

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
        #: The object point the last snapped position is on (drawn as the snap marker), if any.
        self.snap_target: SnapTarget | None = None

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
            self.snap_target = None
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
    def snapped(
        self,
        view: PlaneView,
        x: float,
        y: float,
        mods: Qt.KeyboardModifier,
        exclude: SnapExclusion | None = None,
    ) -> tuple[float, float]:
        """Where a drawn or dragged point at (x, y) goes, with the modifiers ``mods`` held.

        In order: Shift or Ctrl snap to the pixel grid (centres, corners), whatever else is near; else,
        unless snapping to objects is off or Alt is held, the nearest vertex of a visible object within
        :data:`SNAP_PX` screen pixels, else the nearest point of an edge within that distance; else the point
        itself. :attr:`snap_target` says which object point was taken (None: none).
        """
        self.snap_target = None
        mode = snap_mode(mods)
        if mode is not None:
            return ge.snap(x, y, mode)
        if self.host.snap_to_objects and not mods & Qt.KeyboardModifier.AltModifier:
            target = self.host.snapper.find(x, y, plane_radius(view, SNAP_PX), exclude)
            if target is not None:
                self.snap_target = target
                return target.x, target.y
        return x, y

    def paint_snap_marker(self, p: QtGui.QPainter) -> None:
        """Mark the snap target: a square on a vertex, a cross on an edge (screen-sized, in every view)."""
        t = self.snap_target
        if t is None:
            return
        c = p.transform().map(QtCore.QPointF(t.x, t.y))
        p.save()
        p.resetTransform()
        p.setPen(cosmetic_pen(SNAP_COLOUR, 2.0))
        p.setBrush(Qt.BrushStyle.NoBrush)
        if t.kind == "vertex":
            p.drawRect(QtCore.QRectF(c.x() - 6, c.y() - 6, 12, 12))
        else:
            p.drawLine(c + QtCore.QPointF(-5, -5), c + QtCore.QPointF(5, 5))
            p.drawLine(c + QtCore.QPointF(-5, 5), c + QtCore.QPointF(5, -5))
        p.restore()

    def object_at(self, x: float, y: float) -> DocObject | None:
        """The topmost visible object whose discrete representation holds the pixel under (x, y)."""
        px = ge.pixel_at(x, y)
        for obj in reversed(self.scene.doc.plane_objects):
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


def cosmetic_pen(
    colour: QtGui.QColor | str, width: float = 1.5, style: Qt.PenStyle = Qt.PenStyle.SolidLine
) -> QtGui.QPen:
    """A pen of constant screen width (cosmetic), whatever the zoom."""
    pen = QtGui.QPen(QtGui.QColor(colour))
    pen.setCosmetic(True)
    pen.setWidthF(width)
    pen.setStyle(style)
    return pen


def accent_colour(view: PlaneView) -> QtGui.QColor:
    """The colour of tool feedback, readable on the view's light or dark background."""
    return QtGui.QColor("#ffb000") if view.is_dark() else QtGui.QColor("#d35400")


def screen_square(
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


def plane_radius(view: PlaneView, px: float) -> float:
    """``px`` screen pixels of ``view`` in plane units."""
    return px / max(view.pixels_per_unit(), 1e-9)
