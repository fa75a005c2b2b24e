"""The History panel: the document's undo steps, the position marked, a click undoes or redoes to a step."""

from __future__ import annotations

from PySide6 import QtCore, QtWidgets
from shapely.geometry import Polygon

from mrm.document.commands import AddObject
from mrm.document.edits import MoveVertex
from mrm.views.history_panel import INITIAL_LABEL, StateRole
from tests.app.helpers import click, press_key, zoom_to

Qt = QtCore.Qt
CTRL = Qt.KeyboardModifier.ControlModifier
SHIFT = Qt.KeyboardModifier.ShiftModifier


def _history_list(win, qtbot) -> QtWidgets.QListView:  # type: ignore[no-untyped-def]
    """The panel's list, brought forward as a click on its tab does."""
    win.history_dock.show()
    win.history_dock.raise_()
    view = win.history_panel.view
    qtbot.waitUntil(view.isVisible, timeout=3000)
    return view


def _rows(view: QtWidgets.QListView) -> list[tuple[str, str]]:
    m = view.model()
    return [(m.index(r, 0).data(), m.index(r, 0).data(StateRole)) for r in range(m.rowCount())]


def _click_row(qtbot, view: QtWidgets.QListView, row: int) -> None:  # type: ignore[no-untyped-def]
    idx = view.model().index(row, 0)
    view.scrollTo(idx)
    qtbot.mouseClick(view.viewport(), Qt.MouseButton.LeftButton, pos=view.visualRect(idx).center())


def _draw_triangle(qtbot, win, x0: float) -> None:  # type: ignore[no-untyped-def]
    win.registry["tool.polygon"].trigger()
    view = win.views.euclidean
    for x, y in [(x0, 0), (x0 + 4, 0), (x0, 4)]:
        click(qtbot, view, x, y, modifiers=SHIFT)
    press_key(qtbot, view, Qt.Key.Key_Return)


def test_the_view_menu_shows_and_hides_the_history_panel(make_window, qtbot):
    win = make_window()
    view_menu = next(m for m in win.menuBar().findChildren(QtWidgets.QMenu) if m.title() == "&View")
    toggle = next(a for a in view_menu.actions() if a.text() == "History")
    assert toggle is win.history_dock.toggleViewAction()
    _history_list(win, qtbot)
    toggle.trigger()
    assert not win.history_dock.isVisible()
    toggle.trigger()
    assert win.history_dock.isVisibleTo(win)


def test_steps_are_listed_live_and_a_click_undoes_or_redoes_to_that_step(make_window, qtbot):
    win = make_window()
    zoom_to(win, -2, -2, 30, 10)
    view = _history_list(win, qtbot)
    assert _rows(view) == [(f"{INITIAL_LABEL}  (saved)", "current")]
    _draw_triangle(qtbot, win, 0)
    _draw_triangle(qtbot, win, 10)
    _draw_triangle(qtbot, win, 20)
    names = [o.name for o in win.doc.objects]
    assert len(names) == 3
    # Every step as it was pushed, the last one current (and drawn bold), the saved state marked.
    assert _rows(view) == [
        (f"{INITIAL_LABEL}  (saved)", "done"),
        (f"Add {names[0]}", "done"),
        (f"Add {names[1]}", "done"),
        (f"Add {names[2]}", "current"),
    ]
    assert view.currentIndex().row() == 3
    assert view.model().index(3, 0).data(Qt.ItemDataRole.FontRole).bold()

    _click_row(qtbot, view, 1)  # two undos
    assert [o.name for o in win.doc.objects] == names[:1]
    assert win.doc.history.index == 1 and win.doc.history.count == 3  # the redo steps are kept
    assert [s for _, s in _rows(view)] == ["done", "current", "undone", "undone"]
    assert view.currentIndex().row() == 1
    assert win.registry["edit.redo"].isEnabled()

    press_key(qtbot, win.views.discrete, Qt.Key.Key_Z, CTRL | SHIFT)  # redo follows in the panel
    assert len(win.doc) == 2 and view.currentIndex().row() == 2

    _click_row(qtbot, view, 0)  # back to the saved state: the document is clean again
    assert len(win.doc) == 0 and not win.doc.is_modified
    assert not win.isWindowModified()

    _click_row(qtbot, view, 3)  # three redos
    assert [o.name for o in win.doc.objects] == names
    assert win.doc.is_modified

    _click_row(qtbot, view, 1)
    _draw_triangle(qtbot, win, 10)  # a new step after undoing drops the undone ones
    assert [s for _, s in _rows(view)] == ["done", "done", "current"]
    assert _rows(view)[2][0] == f"Add {win.doc.objects[-1].name}"


def test_the_panel_follows_merged_steps_and_a_project_switch(make_window, qtbot, tmp_path):
    win = make_window()
    view = _history_list(win, qtbot)
    tri = win.doc.make_object(Polygon([(0, 0), (4, 0), (0, 4)]), name="tri")
    win.doc.push(AddObject(tri, select=True))
    win.doc.push(MoveVertex(tri.id, (0, 0, 1), (5.0, 1.0), drag_id=99))
    assert len(_rows(view)) == 3
    # A drag that comes back to where it started merges into nothing: its row goes.
    win.doc.push(MoveVertex(tri.id, (0, 0, 1), (4.0, 0.0), drag_id=99))
    assert [s for _, s in _rows(view)] == ["done", "current"]
    # Opening a project starts a new history.
    path = tmp_path / "p.mrm"
    assert win.files.save_as(path)
    qtbot.waitUntil(lambda: not win.doc.is_modified, timeout=10_000)
    win.doc.push(MoveVertex(tri.id, (0, 0, 2), (0.0, 6.0)))
    assert len(_rows(view)) == 3
    assert win.files.open(path, ask=False)
    assert _rows(view) == [(f"{INITIAL_LABEL}  (saved)", "current")]


def test_a_click_in_the_panel_while_drawing_cancels_the_drawing_then_moves(make_window, qtbot):
    win = make_window()
    zoom_to(win, -2, -2, 30, 10)
    view = _history_list(win, qtbot)
    _draw_triangle(qtbot, win, 0)
    for x, y in [(10, 0), (14, 0)]:  # a polygon in progress
        click(qtbot, win.views.euclidean, x, y, modifiers=SHIFT)
    assert win.tools.tool.in_gesture()
    _click_row(qtbot, view, 0)
    assert not win.tools.tool.in_gesture()
    assert len(win.doc) == 0 and win.doc.history.index == 0
