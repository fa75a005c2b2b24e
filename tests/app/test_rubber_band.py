"""Rubber-band selection with the select tool: drag on empty canvas, the objects the rectangle touches."""

from __future__ import annotations

from dataclasses import replace

import pytest
from PySide6 import QtCore
from shapely.geometry import Polygon

from mrm.document.commands import AddObject, RestyleObject
from tests.app.helpers import click, colour_at, drag, grab, is_background, square, wait_drawn, zoom_to

Qt = QtCore.Qt
SHIFT = Qt.KeyboardModifier.ShiftModifier
NONE = Qt.KeyboardModifier.NoModifier


def _scene(win):  # type: ignore[no-untyped-def]
    objs = [
        win.doc.make_object(square(0, 0, 6), name="block"),  # pixels (0..5, 0..5)
        win.doc.make_object(Polygon([(10, 0), (14, 0), (10, 4)]), name="tri"),
        win.doc.make_object(Polygon([(20, 10), (24, 10), (24, 14), (20, 14)]), name="far"),
    ]
    for o in objs:
        win.doc.push(AddObject(o))
    win.doc.set_selection([])
    zoom_to(win, -2, -3, 28, 16)
    return objs


def test_dragging_on_empty_canvas_draws_a_band_and_selects_what_it_touches(make_window, qtbot):
    win = make_window()
    block, tri, far = _scene(win)
    wait_drawn(qtbot, win)
    view = win.views.discrete
    other = win.views.euclidean
    assert is_background(view, colour_at(view, 8, 1))
    vp = view.plane.viewport()
    start, mid, end = (view.plane.map_from_plane(*p) for p in ((-1, -1), (5, 0), (12, 2)))
    qtbot.mouseMove(vp, start)
    qtbot.mousePress(vp, Qt.MouseButton.LeftButton, NONE, start)
    qtbot.mouseMove(vp, mid)
    qtbot.mouseMove(vp, end)
    # While dragging: the band is drawn (in this view and the others), nothing is selected yet, no pan.
    assert not is_background(view, colour_at(view, 8, 1))
    assert not is_background(other, colour_at(other, 8, 1))
    assert is_background(view, colour_at(view, 8, 4))  # outside the band
    assert win.doc.selection == ()
    centre = (win.views.camera.cx, win.views.camera.cy)
    qtbot.mouseRelease(vp, Qt.MouseButton.LeftButton, NONE, end)
    assert set(win.doc.selection) == {block.id, tri.id}  # touched, not necessarily enclosed
    assert (win.views.camera.cx, win.views.camera.cy) == centre
    img = grab(view)
    assert is_background(view, colour_at(view, 8, 1, img))  # the band is gone

    # Shift+drag adds to the selection; a click on empty canvas clears it.
    drag(qtbot, view, [(19, 8), (22, 9), (23, 11)], modifiers=SHIFT)
    assert set(win.doc.selection) == {block.id, tri.id, far.id}
    drag(qtbot, view, [(19, 8), (22, 9), (23, 11)])  # without Shift: replaces it
    assert win.doc.selection == (far.id,)
    click(qtbot, view, 8, 8)
    assert win.doc.selection == ()


@pytest.mark.parametrize("name", ["discrete", "region", "analytical", "euclidean"])
def test_the_band_works_in_every_view(make_window, qtbot, name):
    win = make_window()
    _block, tri, _far = _scene(win)
    wait_drawn(qtbot, win)
    view = win.views.by_name(name)
    # From outside the triangle, across its hypotenuse only: it is touched, not enclosed.
    drag(qtbot, view, [(14, 4), (13, 3), (12, 1.6)])
    assert win.doc.selection == (tri.id,)


def test_hidden_objects_are_not_selected_and_esc_cancels_the_band(make_window, qtbot):
    win = make_window()
    block, tri, far = _scene(win)
    win.doc.push(RestyleObject(tri.id, replace(tri.style, visible=False)))
    win.doc.set_selection([far.id])
    view = win.views.euclidean
    drag(qtbot, view, [(-1, -1), (6, 2), (15, 5)])
    assert win.doc.selection == (block.id,)
    vp = view.plane.viewport()
    a, b = view.plane.map_from_plane(-1, -1), view.plane.map_from_plane(25, 15)
    qtbot.mouseMove(vp, a)
    qtbot.mousePress(vp, Qt.MouseButton.LeftButton, NONE, a)
    qtbot.mouseMove(vp, b)
    assert not is_background(view, colour_at(view, 17, 5))
    qtbot.keyClick(view.plane, Qt.Key.Key_Escape)
    assert is_background(view, colour_at(view, 17, 5))
    qtbot.mouseRelease(vp, Qt.MouseButton.LeftButton, NONE, b)
    assert win.doc.selection == (block.id,)  # unchanged


def test_a_drag_from_an_object_is_no_band(make_window, qtbot):
    win = make_window()
    block, _tri, far = _scene(win)
    wait_drawn(qtbot, win)
    win.doc.set_selection([far.id])
    view = win.views.discrete
    vp = view.plane.viewport()
    a, b = view.plane.map_from_plane(2, 2), view.plane.map_from_plane(12, 1)
    qtbot.mouseMove(vp, a)
    qtbot.mousePress(vp, Qt.MouseButton.LeftButton, NONE, a)
    qtbot.mouseMove(vp, b)
    assert win.tools.tool.band is None  # the view pans (pyqtgraph's drag) instead
    qtbot.mouseRelease(vp, Qt.MouseButton.LeftButton, NONE, b)
    assert win.doc.selection == (far.id,)
    assert block.id not in win.doc.selection
