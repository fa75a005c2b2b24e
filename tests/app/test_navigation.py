"""Zoom to selection, zoom to differences, and picking an operation's centre by clicking in a view."""

from __future__ import annotations

import numpy as np
from PySide6 import QtCore

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from tests.app.helpers import click, square, type_into, zoom_to

Qt = QtCore.Qt
CTRL_SHIFT = Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier


def _view_rect(win):  # type: ignore[no-untyped-def]
    r = win.views.discrete.plane.vb.viewRect()
    return r.left(), r.top(), r.right(), r.bottom()


def _shows(win, x: float, y: float) -> bool:  # type: ignore[no-untyped-def]
    x0, y0, x1, y1 = _view_rect(win)
    return min(x0, x1) <= x <= max(x0, x1) and min(y0, y1) <= y <= max(y0, y1)


def _diamond() -> PixelSet:
    yy, xx = np.mgrid[-7:8, -7:8]
    return PixelSet((np.abs(xx) + np.abs(yy)) <= 6, (-7, -7))


def test_zoom_to_selection_frames_every_selected_object(make_window, qtbot):
    win = make_window()
    ids = []
    for x0 in (0, 200, 400):
        o = win.doc.make_object(square(x0, 0), name=f"s{x0}")
        win.doc.push(AddObject(o))
        ids.append(o.id)
    win.doc.set_selection([ids[0], ids[1]])
    zoom_to(win, 395, -5, 410, 10)
    win.views.discrete.plane.setFocus()
    qtbot.keyClick(win.views.discrete.plane, Qt.Key.Key_Home, Qt.KeyboardModifier.ShiftModifier)
    for x, y in [(0, 0), (5, 5), (200, 0), (205, 5)]:
        assert _shows(win, x, y)
    assert not _shows(win, 400, 0)  # the unselected one is not what was framed


def test_zoom_to_differences_frames_the_pixels_that_differ_from_the_direct_result(make_window, qtbot):
    win = make_window()
    diamond = _diamond()
    obj = win.doc.make_object(diamond, name="diamond")
    win.doc.push(AddObject(obj, select=True))
    op = win.operations
    op.select_operation("dss")
    for alpha in ("1.25", "0.8"):
        type_into(qtbot, op.control("alpha").field, alpha)
        qtbot.mouseClick(op.apply_button, Qt.MouseButton.LeftButton)
        win.doc.set_selection([win.doc.objects[-1].id])
    result = win.doc.objects[-1]
    assert result.name == "DSS 0.8"
    # DSS_0.8 ∘ DSS_1.25 scales by 1: the direct result D(R(A)) is A itself, so the differences are
    # result XOR A.
    differ = result.source.symmetric_difference(diamond)
    assert differ.count > 0
    zoom_to(win, 300, 300, 310, 310)  # looking elsewhere
    win.views.discrete.plane.setFocus()
    qtbot.keyClick(win.views.discrete.plane, Qt.Key.Key_D, CTRL_SHIFT)
    bx0, by0, bx1, by1 = differ.bbox
    cam = win.views.camera
    assert (cam.cx, cam.cy) == ((bx0 + bx1) / 2, (by0 + by1) / 2)  # centred on them
    for x, y in differ:  # every differing pixel's square is in sight
        assert _shows(win, x - 0.5, y - 0.5) and _shows(win, x + 0.5, y + 0.5)
    assert f"{differ.count} differing pixels" in win.status.currentMessage()


def test_zoom_to_differences_of_a_drawn_object_says_there_are_none(make_window, qtbot):
    win = make_window()
    o = win.doc.make_object(square(0, 0), name="drawn")
    win.doc.push(AddObject(o, select=True))
    assert not win.registry["view.fit_differences"].isEnabled()
    win.fit_differences()
    assert "result of an operation" in win.status.currentMessage()


def test_pick_button_then_a_click_in_a_view_sets_the_centre_fields(make_window, qtbot):
    win = make_window()
    win.doc.push(AddObject(win.doc.make_object(square(0, 0), name="A"), select=True))
    win.operations.select_operation("discrete_rotation")
    zoom_to(win, -2, -2, 12, 12)
    ctl = win.operations.centre_control()
    qtbot.mouseClick(ctl.pick_button, Qt.MouseButton.LeftButton)
    assert win.tools.is_picking()
    click(qtbot, win.views.region, 3.2, 4.9, modifiers=Qt.KeyboardModifier.ShiftModifier)
    assert (ctl.xs.value(), ctl.ys.value()) == (3.0, 5.0)
    assert win.operations.values()[ctl.info.name] == (3.0, 5.0)
    assert win.tools.tool.name == "select"  # back to the tool in use before
    # The shortcut, and pixel corners with Ctrl.
    win.views.region.plane.setFocus()
    qtbot.keyClick(win.views.region.plane, Qt.Key.Key_C, CTRL_SHIFT)
    assert win.tools.is_picking()
    click(qtbot, win.views.discrete, 7.3, 1.2, modifiers=Qt.KeyboardModifier.ControlModifier)
    assert (ctl.xs.value(), ctl.ys.value()) == (7.5, 1.5)
    # Esc abandons a pick and changes nothing.
    qtbot.mouseClick(ctl.pick_button, Qt.MouseButton.LeftButton)
    win.views.discrete.plane.setFocus()
    qtbot.keyClick(win.views.discrete.plane, Qt.Key.Key_Escape)
    assert not win.tools.is_picking()
    click(qtbot, win.views.discrete, 2, 2)
    assert (ctl.xs.value(), ctl.ys.value()) == (7.5, 1.5)


def test_the_axes_label_round_coordinates_where_they_are(make_window, qtbot):
    """The views' own axes (drawn directly, ADR 0025): round ticks, each label under its coordinate."""
    from mrm.views.canvas import tick_step, tick_text

    assert [tick_step(1000.0, 700.0), tick_step(7.0, 700.0), tick_step(0.35, 700.0)] == [100.0, 1.0, 0.05]
    assert [tick_text(-0.0, 1.0), tick_text(250.0, 50.0), tick_text(0.15, 0.05)] == ["0", "250", "0.15"]
    win = make_window()
    win.views.camera.set(40.0, 30.0, 10.0)  # 10 screen pixels per unit around (40, 30)
    view = win.views.discrete
    qtbot.waitUntil(view.is_drawn, timeout=5000)
    axis = view.plane.getPlotItem().getAxis("bottom")
    img = axis.parentItem().scene().views()[0].grab().toImage()
    # A tick mark is drawn just under the plot at x = 40 (a round value), and none half-way to x = 45.
    x40 = view.plane.map_from_plane(40.0, 30.0).x()
    x42 = view.plane.map_from_plane(42.5, 30.0).x()
    top = int(axis.mapToScene(0, 0).y()) + 2
    dpr = img.devicePixelRatio()

    def dark(x: int) -> bool:
        c = img.pixelColor(int(x * dpr), int(top * dpr))
        return c.lightness() < 200

    assert any(dark(x40 + d) for d in (-1, 0, 1))
    assert not any(dark(x42 + d) for d in (-1, 0, 1))
