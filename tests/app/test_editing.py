"""Editing with the mouse in the real views: polygons, vertices, brush; the other views follow."""

from __future__ import annotations

import numpy as np
from PySide6 import QtCore
from shapely.geometry import Polygon

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from mrm.geometry.discretize import discretize
from tests.app.helpers import (
    click,
    colour_at,
    drag,
    is_background,
    press_key,
    send_wheel,
    wait_drawn,
    zoom_to,
)

Qt = QtCore.Qt


def test_window_shows_four_linked_views(make_window, qtbot):
    win = make_window()
    names = [v.name for v in win.views.views]
    assert names == ["discrete", "region", "analytical", "euclidean"]
    zoom_to(win, 0, 0, 20, 20)
    cams = {
        (round(v.plane.vb.viewRect().center().x(), 6), round(v.plane.pixels_per_unit(), 6))
        for v in win.views.views
    }
    assert len(cams) == 1  # same centre and zoom everywhere
    # Zoom one view with the wheel: every view follows.
    view = win.views.discrete
    before = view.plane.pixels_per_unit()
    pos = view.plane.map_from_plane(10, 10)
    qtbot.wait(1)
    send_wheel(view.plane.viewport(), pos)
    after = {round(v.plane.pixels_per_unit(), 6) for v in win.views.views}
    assert len(after) == 1 and next(iter(after)) > before * 1.2


def test_draw_polygon_updates_the_other_views(make_window, qtbot):
    win = make_window()
    zoom_to(win, -2, -2, 22, 22)
    win.registry["tool.polygon"].trigger()
    view = win.views.euclidean
    corners = [(1.2, 1.3), (15.4, 2.1), (12.8, 14.6), (2.3, 11.7)]
    for x, y in corners:
        click(qtbot, view, x, y, modifiers=Qt.KeyboardModifier.ShiftModifier)  # snap to pixel centres
    click(qtbot, view, 1, 1)  # back on the first vertex closes the ring
    assert len(win.doc) == 1
    obj = win.doc.objects[0]
    assert obj.kind == "euclidean"
    assert sorted(obj.source.exterior.coords[:-1]) == sorted(
        [(1.0, 1.0), (15.0, 2.0), (13.0, 15.0), (2.0, 12.0)]
    )
    assert win.doc.selection == (obj.id,)
    wait_drawn(qtbot, win)
    # The discrete view draws exactly D(polygon): its image item holds the mask at the right place.
    expected = discretize(obj.source, "standard")
    item = win.views.discrete.layer(obj.id).mask
    assert np.array_equal(item.image.astype(bool), expected.mask)
    # ... and on screen: a pixel inside is coloured, one outside is background, in discrete and region views.
    for v in (win.views.discrete, win.views.region):
        assert not is_background(v, colour_at(v, 7, 7))
        assert is_background(v, colour_at(v, 19, 19))
    # Undo removes it in one step, everywhere.
    win.registry["edit.undo"].trigger()
    assert len(win.doc) == 0
    wait_drawn(qtbot, win)
    assert is_background(win.views.discrete, colour_at(win.views.discrete, 7, 7))


def test_polygon_tool_keys_enter_backspace_escape(make_window, qtbot):
    win = make_window()
    zoom_to(win, -2, -2, 22, 22)
    win.registry["tool.polygon"].trigger()
    view = win.views.discrete
    for x, y in [(0, 0), (10, 0), (17, 17), (10, 10)]:
        click(qtbot, view, x, y, modifiers=Qt.KeyboardModifier.ShiftModifier)
    press_key(qtbot, view, Qt.Key.Key_Backspace)  # drops (17, 17)... no: drops the last, (10, 10)
    press_key(qtbot, view, Qt.Key.Key_Return)
    assert len(win.doc) == 1
    assert sorted(win.doc.objects[0].source.exterior.coords[:-1]) == [(0.0, 0.0), (10.0, 0.0), (17.0, 17.0)]
    for x, y in [(0, 5), (3, 5), (3, 8)]:
        click(qtbot, view, x, y)
    press_key(qtbot, view, Qt.Key.Key_Escape)  # cancels the polygon in progress, not a running task
    assert len(win.doc) == 1


def test_hole_drawn_with_alt(make_window, qtbot):
    win = make_window()
    sq = Polygon([(0, 0), (20, 0), (20, 20), (0, 20)])
    win.doc.push(AddObject(win.doc.make_object(sq, name="square"), select=True))
    zoom_to(win, -2, -2, 22, 22)
    win.registry["tool.polygon"].trigger()
    view = win.views.euclidean
    alt_shift = Qt.KeyboardModifier.AltModifier | Qt.KeyboardModifier.ShiftModifier
    click(qtbot, view, 5, 5, modifiers=alt_shift)
    for x, y in [(12, 5), (12, 12), (5, 12)]:
        click(qtbot, view, x, y, modifiers=Qt.KeyboardModifier.ShiftModifier)
    press_key(qtbot, view, Qt.Key.Key_Return)
    assert len(win.doc) == 1
    g = win.doc.objects[0].source
    assert len(g.interiors) == 1 and g.area == 400 - 49
    wait_drawn(qtbot, win)
    assert is_background(win.views.discrete, colour_at(win.views.discrete, 8, 8))
    assert not is_background(win.views.discrete, colour_at(win.views.discrete, 2, 8))


def test_drag_vertex_previews_live_and_undoes_in_one_step(make_window, qtbot):
    win = make_window()
    tri = Polygon([(0, 0), (16, 0), (0, 16)])
    obj = win.doc.make_object(tri, name="tri")
    win.doc.push(AddObject(obj, select=True))
    zoom_to(win, -2, -2, 22, 22)
    win.registry["tool.vertex"].trigger()
    view = win.views.euclidean
    steps_before = win.doc.history.index
    seen_previews = []
    win.scene.previewChanged.connect(lambda i: seen_previews.append(win.scene.has_preview(i)))
    disc = win.views.discrete
    vp = view.plane.viewport()
    start = view.plane.map_from_plane(16, 0)
    qtbot.mouseMove(vp, start)
    qtbot.mousePress(vp, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, start)
    mid = view.plane.map_from_plane(18, 14)
    qtbot.mouseMove(vp, mid)
    # While dragging, the document is untouched but the discrete view already shows the moved shape.
    assert win.doc.get(obj.id).source.equals(tri)
    assert win.scene.has_preview(obj.id)
    disc.refresh()
    assert not is_background(disc, colour_at(disc, 14, 12))
    end = view.plane.map_from_plane(18, 16)
    qtbot.mouseMove(vp, end)
    qtbot.mouseRelease(vp, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.ShiftModifier, end)
    new = win.doc.get(obj.id).source
    assert win.doc.history.index == steps_before + 1
    assert (18.0, 16.0) in [tuple(map(round, c)) for c in new.exterior.coords]
    assert not win.scene.has_preview(obj.id)
    assert True in seen_previews
    wait_drawn(qtbot, win)
    win.registry["edit.undo"].trigger()
    assert win.doc.get(obj.id).source.equals(tri)
    assert win.doc.history.index == steps_before
    wait_drawn(qtbot, win)
    assert is_background(disc, colour_at(disc, 14, 12))


def test_insert_and_delete_vertex(make_window, qtbot):
    win = make_window()
    sq = Polygon([(0, 0), (16, 0), (16, 16), (0, 16)])
    obj = win.doc.make_object(sq, name="sq")
    win.doc.push(AddObject(obj, select=True))
    zoom_to(win, -2, -2, 22, 22)
    win.registry["tool.vertex"].trigger()
    view = win.views.euclidean
    # Drag from the middle of the bottom edge: inserts a vertex and moves it, as one step.
    drag(qtbot, view, [(8, 0), (8, -1), (8, -2)], modifiers=Qt.KeyboardModifier.ShiftModifier)
    g = win.doc.get(obj.id).source
    assert len(g.exterior.coords) == 6
    assert (8.0, -2.0) in [tuple(c) for c in np.round(np.asarray(g.exterior.coords), 6)]
    assert win.doc.history.undo_label() == "Insert vertex"
    # Right-click the new vertex deletes it.
    click(qtbot, view, 8, -2, button=Qt.MouseButton.RightButton)
    assert len(win.doc.get(obj.id).source.exterior.coords) == 5
    win.registry["edit.undo"].trigger()
    win.registry["edit.undo"].trigger()
    assert win.doc.get(obj.id).source.equals(sq)


def test_self_crossing_drag_is_refused(make_window, qtbot):
    win = make_window()
    sq = Polygon([(0, 0), (16, 0), (16, 16), (0, 16)])
    obj = win.doc.make_object(sq, name="sq")
    win.doc.push(AddObject(obj, select=True))
    zoom_to(win, -2, -2, 22, 22)
    win.registry["tool.vertex"].trigger()
    # Dragging (16, 0) to the far side of the left edge would cross the polygon with itself.
    drag(qtbot, win.views.euclidean, [(16, 0), (-3, 8)])
    g = win.doc.get(obj.id).source
    assert g.is_valid
    assert "refused" in win.statusBar().currentMessage()


def test_paint_new_object_then_erase_in_one_step_each(make_window, qtbot):
    win = make_window()
    zoom_to(win, -2, -2, 30, 30)
    win.brush_spin.setValue(1)
    win.registry["tool.paint"].trigger()
    view = win.views.discrete
    drag(qtbot, view, [(2, 2), (12, 2)])
    assert len(win.doc) == 1
    obj = win.doc.objects[0]
    assert obj.kind == "discrete"
    assert obj.source == PixelSet.from_points([(x, 2) for x in range(2, 13)])
    assert win.doc.history.index == 1
    win.brush_spin.setValue(3)
    drag(qtbot, view, [(5, 8), (5, 14)])
    ps = win.doc.get(obj.id).source
    assert all((x, y) in ps for x in (4, 5, 6) for y in range(8, 15))
    assert win.doc.history.index == 2
    win.registry["tool.erase"].trigger()
    win.brush_spin.setValue(1)
    drag(qtbot, view, [(5, 2), (7, 2)])
    ps = win.doc.get(obj.id).source
    assert (5, 2) not in ps and (7, 2) not in ps and (4, 2) in ps and (8, 2) in ps
    wait_drawn(qtbot, win)
    assert is_background(view, colour_at(view, 6, 2))
    assert not is_background(view, colour_at(view, 4, 2))
    win.registry["edit.undo"].trigger()
    assert (6, 2) in win.doc.get(obj.id).source


def test_painting_a_polygon_changes_its_source(make_window, qtbot):
    win = make_window()
    sq = Polygon([(-0.5, -0.5), (9.5, -0.5), (9.5, 9.5), (-0.5, 9.5)])
    obj = win.doc.make_object(sq, name="sq")
    win.doc.push(AddObject(obj, select=True))
    zoom_to(win, -2, -2, 20, 20)
    win.brush_spin.setValue(1)
    win.registry["tool.paint"].trigger()
    drag(qtbot, win.views.discrete, [(10, 4), (14, 4)])
    new = win.doc.get(obj.id)
    assert new.kind == "discrete"
    # Under the standard model the sides on x = −½ and y = −½ go to the pixels left of and below them.
    assert new.source == discretize(sq, "standard") | PixelSet.from_points([(x, 4) for x in range(10, 15)])
    win.registry["edit.undo"].trigger()
    assert win.doc.get(obj.id).kind == "euclidean"


def test_fill_hole_and_delete_component_by_clicking(make_window, qtbot):
    win = make_window()
    m = np.zeros((7, 12), bool)
    m[0:5, 0:5] = True
    m[2, 2] = False  # a hole made of (2, 2) ...
    m[1:4, 3] = False  # ... and (3, 1), (3, 2), (3, 3)
    m[5:7, 8:11] = True  # a second component
    obj = win.doc.make_object(PixelSet(m, (0, 0)), name="holey")
    win.doc.push(AddObject(obj, select=True))
    zoom_to(win, -1, -1, 12, 8)
    wait_drawn(qtbot, win)
    region = win.doc.derived(obj.id).get("region")
    assert region.n_components == 2 and region.n_holes == 1
    win.registry["tool.fill_hole"].trigger()
    click(qtbot, win.views.region, 3, 2)
    ps = win.doc.get(obj.id).source
    assert all(p in ps for p in [(2, 2), (3, 1), (3, 2), (3, 3)])
    assert win.doc.history.undo_label() == "Fill hole"
    from mrm.document.edits import DeleteComponent, FillHole

    assert isinstance(win.doc.history._steps[win.doc.history.index - 1], FillHole)  # the model's command
    assert win.doc.derived(obj.id).get("region").n_holes == 0
    click(qtbot, win.views.region, 20, 20)  # not a hole: nothing happens
    assert "no hole" in win.statusBar().currentMessage()
    win.registry["tool.delete_component"].trigger()
    click(qtbot, win.views.region, 9, 6)
    ps = win.doc.get(obj.id).source
    assert (9, 6) not in ps and (0, 0) in ps
    assert isinstance(win.doc.history._steps[win.doc.history.index - 1], DeleteComponent)
    assert win.doc.derived(obj.id).get("region").n_components == 1
    wait_drawn(qtbot, win)
    assert is_background(win.views.discrete, colour_at(win.views.discrete, 9, 6))
    win.registry["edit.undo"].trigger()
    win.registry["edit.undo"].trigger()
    assert win.doc.get(obj.id).source == PixelSet(m, (0, 0))
