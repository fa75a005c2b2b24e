"""Snapping to the vertices and edges of objects while drawing a polygon or dragging a vertex."""

from __future__ import annotations

import math

import pytestqt.exceptions
import shapely
from PySide6 import QtCore, QtGui
from shapely.geometry import Polygon

from mrm.app.settings import Preferences
from mrm.document.commands import AddObject
from mrm.views.tool_base import SNAP_COLOUR
from tests.app.helpers import (
    click,
    grab,
    press_key,
    send_mouse_move,
    square,
    wait_drawn,
    widget_pos,
    zoom_to,
)

Qt = QtCore.Qt
ALT = Qt.KeyboardModifier.AltModifier
SHIFT = Qt.KeyboardModifier.ShiftModifier
NONE = Qt.KeyboardModifier.NoModifier

#: A vertex no click lands on by chance: the snapped point must be this float64 exactly.
V = (10.123456789012345, 3.987654321098765)
A_RING = [(4.0, 0.5), V, (8.0, 9.0)]


def _setup(win, qtbot):  # type: ignore[no-untyped-def]
    a = win.doc.make_object(Polygon(A_RING), name="A")
    win.doc.push(AddObject(a))
    win.doc.set_selection([])
    zoom_to(win, -2, -2, 22, 14)
    wait_drawn(qtbot, win)
    return a


def _marker_near(view, x: float, y: float) -> bool:  # type: ignore[no-untyped-def]
    """True when the snap marker's colour is drawn within 9 screen pixels of the plane point (x, y)."""
    img = grab(view)
    c = widget_pos(view, x, y)
    dpr = img.devicePixelRatio()
    want = QtGui.QColor(SNAP_COLOUR)
    for dx in range(-9, 10):
        for dy in range(-9, 10):
            col = img.pixelColor(int((c.x() + dx) * dpr), int((c.y() + dy) * dpr))
            if (
                abs(col.red() - want.red()) + abs(col.green() - want.green()) + abs(col.blue() - want.blue())
                < 60
            ):
                return True
    return False


def _near(view, x: float, y: float, dx_px: int, dy_px: int) -> QtCore.QPoint:  # type: ignore[no-untyped-def]
    """The viewport point ``dx_px``, ``dy_px`` screen pixels from the plane point (x, y)."""
    return widget_pos(view, x, y) + QtCore.QPoint(dx_px, dy_px)


def _click_at(qtbot, view, pos: QtCore.QPoint, mods=NONE) -> None:  # type: ignore[no-untyped-def]
    vp = view.plane.viewport()
    qtbot.mouseMove(vp, pos)
    qtbot.mouseClick(vp, Qt.MouseButton.LeftButton, mods, pos)


def _on_segment(p, a, b) -> float:  # type: ignore[no-untyped-def]
    return shapely.distance(shapely.Point(p), shapely.LineString([a, b]))


def test_a_polygon_vertex_snaps_exactly_to_a_vertex_with_a_marker_in_every_view(make_window, qtbot):
    win = make_window()
    _setup(win, qtbot)
    win.registry["tool.polygon"].trigger()
    view, other = win.views.euclidean, win.views.discrete

    def hovered_with_markers() -> bool:
        # 5 screen pixels off the vertex, with no key held (see _hover), moved again at each poll.
        # no key held: after an earlier test's Shift-click qtbot.mouseMove carried Shift, which snapped the
        # hover to the pixel grid (hover (10.5, 4.5), no target) in full CI runs and never alone
        send_mouse_move(view.plane.viewport(), _near(view, *V, 4, -3))
        return _marker_near(view, *V) and _marker_near(other, *V)

    try:
        qtbot.waitUntil(hovered_with_markers, timeout=30_000)
    except (
        pytestqt.exceptions.TimeoutError
    ):  # say what is missing: it failed twice in loaded CI runs and never alone
        tool = win.tools.tool
        raise AssertionError(
            f"marker in the Euclidean view {_marker_near(view, *V)}, in the discrete view "
            f"{_marker_near(other, *V)}; tool {type(tool).__name__}, hover {tool.hover}, "
            f"snap target {tool.snap_target}"
        ) from None
    _click_at(qtbot, view, _near(view, *V, 4, -3))
    click(qtbot, view, 16, 1, modifiers=SHIFT)
    click(qtbot, view, 16, 8, modifiers=SHIFT)
    press_key(qtbot, view, Qt.Key.Key_Return)
    new = win.doc.objects[-1].source
    assert V in list(new.exterior.coords)  # the very float64 coordinates: the vertices coincide exactly
    # Away from every object, no marker.
    qtbot.mouseMove(view.plane.viewport(), widget_pos(view, 18, 12))
    assert not _marker_near(view, 18, 12)


def test_an_edge_snaps_to_its_nearest_point_and_a_vertex_beats_an_edge(make_window, qtbot):
    win = make_window()
    a = _setup(win, qtbot)
    win.registry["tool.polygon"].trigger()
    view = win.views.euclidean
    # Middle of the edge V → (8, 9), 4 px off to the side: on the edge, not where the cursor was.
    mx, my = (V[0] + 8.0) / 2, (V[1] + 9.0) / 2
    pos = _near(view, mx, my, 4, 0)
    _click_at(qtbot, view, pos)
    p0 = win.tools.tool.points[0]
    assert _on_segment(p0, V, (8.0, 9.0)) < 1e-9
    assert p0 != view.plane.map_to_plane(QtCore.QPointF(pos))
    # 6 px from the vertex along its edge: the edge is nearer (0 px) but the vertex wins.
    ux, uy = 8.0 - V[0], 9.0 - V[1]
    k = 6 / view.plane.pixels_per_unit() / math.hypot(ux, uy)
    pos = widget_pos(view, V[0] + ux * k, V[1] + uy * k)
    _click_at(qtbot, view, pos)
    assert win.tools.tool.points[1] == V
    press_key(qtbot, view, Qt.Key.Key_Escape)
    assert win.doc.objects == (a,)


def test_alt_suspends_it_the_toggle_turns_it_off_and_is_remembered(make_window, qtbot, prefs):
    win = make_window()
    _setup(win, qtbot)
    win.registry["tool.polygon"].trigger()
    view = win.views.euclidean
    pos = _near(view, *V, 3, 3)
    raw = view.plane.map_to_plane(QtCore.QPointF(pos))
    click(qtbot, view, 16, 1, modifiers=SHIFT)
    _click_at(qtbot, view, pos, ALT)  # Alt held: the point where the cursor is
    assert win.tools.tool.points[-1] == raw
    assert not _marker_near(view, *V)
    press_key(qtbot, view, Qt.Key.Key_Escape)
    # Shift+S turns snapping to objects off (View ▸ Snap to Objects), and the preference keeps it.
    assert win.registry["view.snap"].isChecked()
    press_key(qtbot, view, Qt.Key.Key_S, SHIFT)
    assert not win.registry["view.snap"].isChecked()
    assert Preferences(prefs.settings).snap_to_objects is False
    _click_at(qtbot, view, pos)
    assert win.tools.tool.points == [raw]
    press_key(qtbot, view, Qt.Key.Key_Escape)
    press_key(qtbot, view, Qt.Key.Key_S, SHIFT)
    assert win.registry["view.snap"].isChecked() and prefs.snap_to_objects is True
    _click_at(qtbot, view, pos)
    assert win.tools.tool.points == [V]


def test_the_pixel_grid_keys_take_precedence(make_window, qtbot):
    win = make_window()
    _setup(win, qtbot)
    win.registry["tool.polygon"].trigger()
    view = win.views.euclidean
    _click_at(qtbot, view, _near(view, *V, 2, 2), SHIFT)  # Shift: the nearest pixel centre, not the vertex
    assert win.tools.tool.points == [(10.0, 4.0)]
    _click_at(qtbot, view, _near(view, *V, 2, 2), Qt.KeyboardModifier.ControlModifier)  # Ctrl: a corner
    assert win.tools.tool.points[-1] in {(9.5, 3.5), (10.5, 3.5), (9.5, 4.5), (10.5, 4.5)}


def test_a_dragged_vertex_snaps_to_a_vertex_and_to_an_edge_but_not_to_itself(make_window, qtbot):
    win = make_window()
    _setup(win, qtbot)
    b = win.doc.make_object(Polygon([(14, 1), (19, 1), (19, 6)]), name="B")
    win.doc.push(AddObject(b, select=True))
    wait_drawn(qtbot, win)
    win.registry["tool.vertex"].trigger()
    view, other = win.views.euclidean, win.views.region
    vp = view.plane.viewport()
    start = widget_pos(view, 14, 1)
    qtbot.mouseMove(vp, start)
    qtbot.mousePress(vp, Qt.MouseButton.LeftButton, NONE, start)
    qtbot.mouseMove(vp, _near(view, 13, 2, 0, 0))
    qtbot.mouseMove(vp, _near(view, *V, -4, 4))
    assert _marker_near(view, *V) and _marker_near(other, *V)  # drawn during the drag
    qtbot.mouseRelease(vp, Qt.MouseButton.LeftButton, NONE, _near(view, *V, -4, 4))
    ring = list(win.doc.get(b.id).source.exterior.coords)
    assert V in ring and (14.0, 1.0) not in ring
    assert win.doc.history.undo_label() == "Move vertex"
    win.registry["edit.undo"].trigger()
    assert (14.0, 1.0) in list(win.doc.get(b.id).source.exterior.coords)
    # Onto A's edge (4, 0.5) → V: the vertex lands on the edge.
    mx, my = (4.0 + V[0]) / 2, (0.5 + V[1]) / 2
    end = _near(view, mx, my, 0, 5)
    qtbot.mouseMove(vp, start)
    qtbot.mousePress(vp, Qt.MouseButton.LeftButton, NONE, start)
    qtbot.mouseMove(vp, end)
    qtbot.mouseRelease(vp, Qt.MouseButton.LeftButton, NONE, end)
    moved = next(p for p in win.doc.get(b.id).source.exterior.coords if p not in {(19.0, 1.0), (19.0, 6.0)})
    assert _on_segment(moved, (4.0, 0.5), V) < 1e-9
    win.registry["edit.undo"].trigger()
    # A small drag away from where the vertex was: its own old place does not pull it back.
    end = _near(view, 14, 1, 5, 0)
    qtbot.mouseMove(vp, start)
    qtbot.mousePress(vp, Qt.MouseButton.LeftButton, NONE, start)
    qtbot.mouseMove(vp, end)
    qtbot.mouseRelease(vp, Qt.MouseButton.LeftButton, NONE, end)
    assert view.plane.map_to_plane(QtCore.QPointF(end)) in list(win.doc.get(b.id).source.exterior.coords)


def test_the_vertices_of_a_pixel_objects_continuation_are_targets(make_window, qtbot):
    win = make_window()
    o = win.doc.make_object(square(2, 2, 5), name="pixels")
    win.doc.push(AddObject(o))
    win.doc.set_selection([])
    zoom_to(win, -2, -2, 14, 12)
    wait_drawn(qtbot, win)
    r = win.doc.derived(o.id).peek("euclidean")
    assert r is not None  # the Euclidean view asked for it
    target = tuple(map(float, r.exterior.coords[0]))
    win.registry["tool.polygon"].trigger()
    view = win.views.euclidean
    _click_at(qtbot, view, _near(view, *target, 3, -2))
    assert win.tools.tool.points == [target]


def test_a_large_object_is_indexed_on_a_worker_then_snapped_to(make_window, qtbot, monkeypatch):
    import threading

    import mrm.views.geometry_edit as ge
    import mrm.views.snapping as snapping

    monkeypatch.setattr(snapping, "SYNC_VERTICES", 2)  # every object counts as large
    built_on_gui: list[bool] = []
    original = ge.SnapIndex.__init__

    def recording(self, geom):  # type: ignore[no-untyped-def]
        built_on_gui.append(threading.current_thread() is threading.main_thread())
        original(self, geom)

    monkeypatch.setattr(ge.SnapIndex, "__init__", recording)
    win = make_window(threaded=True)
    _setup(win, qtbot)
    win.registry["tool.polygon"].trigger()
    view = win.views.euclidean
    qtbot.mouseMove(view.plane.viewport(), _near(view, *V, 3, 3))  # asks for the index
    qtbot.waitUntil(lambda: not win.runner.is_busy_prefix("snap-index"), timeout=10_000)
    assert built_on_gui == [False]
    _click_at(qtbot, view, _near(view, *V, 3, 2))
    assert win.tools.tool.points == [V]


def test_a_vertex_inserted_on_an_edge_is_not_held_on_that_edge(make_window, qtbot):
    win = make_window()
    _setup(win, qtbot)
    b = win.doc.make_object(Polygon([(14, 1), (20, 1), (20, 7)]), name="B")
    win.doc.push(AddObject(b, select=True))
    wait_drawn(qtbot, win)
    win.registry["tool.vertex"].trigger()
    view = win.views.euclidean
    vp = view.plane.viewport()
    start = widget_pos(view, 17, 1)  # on the edge (14, 1) → (20, 1)
    end = start + QtCore.QPoint(0, -6)  # 6 screen pixels off it, within the snapping distance
    qtbot.mouseMove(vp, start)
    qtbot.mousePress(vp, Qt.MouseButton.LeftButton, NONE, start)
    qtbot.mouseMove(vp, end)
    qtbot.mouseRelease(vp, Qt.MouseButton.LeftButton, NONE, end)
    ring = list(win.doc.get(b.id).source.exterior.coords)[:-1]
    assert len(ring) == 4
    assert view.plane.map_to_plane(QtCore.QPointF(end)) in ring
    assert win.doc.history.undo_label() == "Insert vertex"
