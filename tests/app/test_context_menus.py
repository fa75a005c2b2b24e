"""Right-click menus in the views and the object list: right-click opens the menu, choosing an item edits."""

from __future__ import annotations

import numpy as np
from PySide6 import QtCore, QtGui, QtWidgets
from shapely.geometry import Polygon

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from tests.app.helpers import click, square, wait_drawn, zoom_to

Qt = QtCore.Qt


def _add(win, source, name):  # type: ignore[no-untyped-def]
    obj = win.doc.make_object(source, name=name)
    win.doc.push(AddObject(obj))
    return obj.id


def _choose(qtbot, menu: QtWidgets.QMenu, name: str) -> None:  # type: ignore[no-untyped-def]
    """Click the menu item ``name`` (an action's object name) with the mouse, as a user does."""
    qtbot.waitUntil(menu.isVisible, timeout=3000)
    act = next(a for a in menu.actions() if a.objectName() == name)
    assert act.isEnabled(), f"{name} is disabled"
    pos = menu.actionGeometry(act).center()
    qtbot.mouseMove(menu, pos)
    qtbot.mouseClick(menu, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, pos)


def _ring(n: int = 9) -> PixelSet:
    m = np.ones((n, n), bool)
    m[3:6, 3:6] = False  # a 3×3 hole
    return PixelSet(m, (0, 0))


def test_right_click_on_an_object_selects_it_and_its_menu_deletes_it(make_window, qtbot):
    win = make_window()
    a = _add(win, square(0, 0), "A")
    b = _add(win, square(20, 0), "B")
    win.doc.set_selection([a])
    zoom_to(win, -2, -4, 28, 10)
    wait_drawn(qtbot, win)
    click(qtbot, win.views.discrete, 22, 2, button=Qt.MouseButton.RightButton)
    menu = win.context_menu
    assert menu is not None and menu.objectName() == "viewContextMenu"
    assert win.doc.selection == (b,)  # the right-clicked object is selected first
    texts = {a.objectName(): a for a in menu.actions()}
    # The menu's items carry the same shortcuts as the main menus.
    assert texts["edit.delete"].shortcut().toString() == "Del"
    assert texts["edit.copy"].shortcut().toString() == "Ctrl+C"
    _choose(qtbot, menu, "edit.delete")
    assert [o.name for o in win.doc.objects] == ["A"]
    win.doc.undo()
    assert [o.name for o in win.doc.objects] == ["A", "B"]


def test_view_menu_fills_the_hole_under_the_cursor(make_window, qtbot):
    win = make_window()
    oid = _add(win, _ring(), "ring")
    zoom_to(win, -2, -2, 11, 11)
    wait_drawn(qtbot, win)
    assert win.scene.get(oid, "region").n_holes == 1
    click(qtbot, win.views.discrete, 4, 4, button=Qt.MouseButton.RightButton)  # inside the hole
    menu = win.context_menu
    comp = next(a for a in menu.actions() if a.objectName() == "ctx.delete_component")
    assert not comp.isEnabled()  # no component under the cursor: there is a hole
    _choose(qtbot, menu, "ctx.fill_hole")
    assert win.doc.get(oid).source == PixelSet(np.ones((9, 9), bool), (0, 0))
    assert win.doc.history.undo_label() == "Fill hole"


def test_view_menu_deletes_the_component_under_the_cursor(make_window, qtbot):
    win = make_window()
    m = np.zeros((4, 12), bool)
    m[:, :4] = True
    m[:, 8:] = True  # two components
    oid = _add(win, PixelSet(m, (0, 0)), "two")
    zoom_to(win, -2, -2, 14, 6)
    wait_drawn(qtbot, win)
    click(qtbot, win.views.region, 10, 1, button=Qt.MouseButton.RightButton)
    _choose(qtbot, win.context_menu, "ctx.delete_component")
    left = np.zeros((4, 12), bool)
    left[:, :4] = True
    assert win.doc.get(oid).source == PixelSet(left, (0, 0))


def test_view_menu_sets_the_operation_centre(make_window, qtbot):
    win = make_window()
    _add(win, square(0, 0), "A")
    win.operations.select_operation("discrete_rotation")
    zoom_to(win, -2, -2, 10, 10)
    wait_drawn(qtbot, win)
    click(qtbot, win.views.euclidean, 3, 5, button=Qt.MouseButton.RightButton)
    _choose(qtbot, win.context_menu, "ctx.set_centre")
    cx, cy = win.operations.centre_control().value()
    assert abs(cx - 3) <= 0.2 and abs(cy - 5) <= 0.2  # where the click was, to a screen pixel


def _right_click_row(qtbot, win, row: int) -> None:  # type: ignore[no-untyped-def]
    """A right click on a row of the object list: the press, then the context-menu event Qt sends."""
    lst = win.object_list.view
    pos = lst.visualRect(win.object_list.model.index(row, 2)).center()
    qtbot.mouseClick(lst.viewport(), Qt.MouseButton.RightButton, Qt.KeyboardModifier.NoModifier, pos)
    ev = QtGui.QContextMenuEvent(QtGui.QContextMenuEvent.Reason.Mouse, pos, lst.viewport().mapToGlobal(pos))
    QtWidgets.QApplication.sendEvent(lst.viewport(), ev)


def test_list_menu_duplicates_and_hides(make_window, qtbot):
    win = make_window()
    _add(win, Polygon([(0, 0), (4, 0), (4, 3)]), "tri")
    _add(win, Polygon([(10, 0), (14, 0), (14, 3)]), "other")
    win.doc.set_selection([])
    _right_click_row(qtbot, win, 1)  # the bottom row: "tri"
    menu = win.context_menu
    assert menu.objectName() == "listContextMenu"
    assert [win.doc.get(i).name for i in win.doc.selection] == ["tri"]
    _choose(qtbot, menu, "edit.duplicate")
    assert sorted(o.name for o in win.doc.objects) == ["other", "tri", "tri copy"]
    assert win.doc.find("tri copy")[0].source.equals_exact(win.doc.find("tri")[0].source, 0)
    _right_click_row(qtbot, win, 0)
    _choose(qtbot, win.context_menu, "ctx.visibility")
    top = win.object_list.model.obj(0)
    assert not top.style.visible


def test_right_click_while_drawing_still_removes_the_last_vertex(make_window, qtbot):
    win = make_window()
    zoom_to(win, -2, -2, 22, 22)
    win.registry["tool.polygon"].trigger()
    view = win.views.euclidean
    for x, y in [(1, 1), (10, 1), (10, 10)]:
        click(qtbot, view, x, y, modifiers=Qt.KeyboardModifier.ShiftModifier)
    menu_before = win.context_menu
    click(qtbot, view, 5, 5, button=Qt.MouseButton.RightButton)
    assert win.tools.tool.points == [(1.0, 1.0), (10.0, 1.0)]
    assert win.context_menu is menu_before  # no menu over a drawing in progress


def test_the_menu_key_opens_the_views_menu(make_window, qtbot):
    win = make_window()
    _add(win, square(0, 0), "A")
    zoom_to(win, -2, -2, 10, 10)
    view = win.views.discrete.plane
    view.setFocus()
    qtbot.keyClick(view, Qt.Key.Key_F10, Qt.KeyboardModifier.ShiftModifier)
    menu = win.context_menu
    assert menu is not None and menu.objectName() == "viewContextMenu"
    qtbot.waitUntil(menu.isVisible, timeout=3000)
    qtbot.keyClick(menu, Qt.Key.Key_Escape)
    qtbot.waitUntil(lambda: not menu.isVisible(), timeout=3000)
    assert len(win.doc) == 1
