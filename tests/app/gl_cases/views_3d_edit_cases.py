"""Editing voxels in the 3D views: the slice plane, painting and erasing on it, components and cavities.

Run by tests/app/test_views_3d.py under its own Xvfb with GLX (see views_3d_cases.py).
"""

from __future__ import annotations

import numpy as np
from PySide6 import QtCore, QtGui

from mrm.core.grids import VoxelSet
from mrm.document.commands import AddObject
from mrm.views import gl_mesh
from mrm.views.view3d import SLICE_VOXEL_RGBA
from tests.app.gl_cases.views_3d_cases import R, _frame, _hues, _near, _octahedron, _show_3d
from tests.app.helpers import send_mouse_move

Qt = QtCore.Qt


def _drag(qtbot, view, voxels) -> None:  # type: ignore[no-untyped-def]
    """A left-button drag in the view's pane through the screen points of ``voxels`` (world x, y, z)."""
    pane = view.pane
    points = [view.screen_of(v).toPoint() for v in voxels]
    qtbot.mousePress(pane, Qt.MouseButton.LeftButton, pos=points[0])
    for p in points[1:]:
        send_mouse_move(pane, p, Qt.MouseButton.LeftButton)
    qtbot.mouseRelease(pane, Qt.MouseButton.LeftButton, pos=points[-1])


def test_the_slice_plane_moves_with_pgup_pgdn_and_the_spin_box_and_shows_its_voxels(make_window, qtbot):
    win = make_window(threaded=True)
    _octahedron(win)
    area = _show_3d(qtbot, win)
    view = area.by_name("discrete3d")
    orange = QtGui.QColor(*SLICE_VOXEL_RGBA[:3]).hsvHue()
    assert view.slice_z is None and _near(_hues(_frame(view)), orange, 8) == 0
    view.pane.setFocus()
    qtbot.keyClick(view.pane, Qt.Key.Key_PageUp)  # the first press shows the plane through the middle
    assert view.slice_z == 0 and view.slice_button.isChecked() and view.slice_spin.value() == 0
    qtbot.keyClick(view.pane, Qt.Key.Key_PageUp)
    qtbot.keyClick(view.pane, Qt.Key.Key_PageUp)
    qtbot.keyClick(view.pane, Qt.Key.Key_PageDown)
    assert view.slice_z == 1 and view.slice_spin.value() == 1
    view.slice_spin.setValue(-3)
    assert view.slice_z == -3
    # drawn: the slice's voxels highlighted over the surfaces (a 2·3+1 = 7-wide diamond at z = −3 of R = 6)
    assert _near(_hues(_frame(view)), orange, 8) > 200
    view.slice_button.click()
    assert view.slice_z is None and not view.slice_spin.isEnabled()
    assert _near(_hues(_frame(view)), orange, 8) == 0


def test_painting_and_erasing_on_the_slice_plane_are_one_undo_step_each(make_window, qtbot):
    win = make_window(threaded=True)
    obj = _octahedron(win)
    area = _show_3d(qtbot, win)
    view = area.by_name("discrete3d")
    before = win.doc.get(obj.id).source
    # Paint, under the oblique camera: a stroke on the plane z = 0 from (R + 1, 0) to (R + 3, 0), outside A.
    view.paint_button.click()
    assert view.slice_z == 0
    azimuth = view.pane.cameraParams()["azimuth"]
    _drag(qtbot, view, [(R + 1, 0, 0), (R + 2, 0, 0), (R + 3, 0, 0)])
    assert view.pane.cameraParams()["azimuth"] == azimuth  # the drag painted, it did not orbit
    after = win.doc.get(obj.id).source
    added = {tuple(p) for p in (after - before).points().tolist()}
    assert added == {(R + 1, 0, 0), (R + 2, 0, 0), (R + 3, 0, 0)}
    assert win.doc.history.undo_label() == "Paint voxels"
    qtbot.waitUntil(win.is_drawn, timeout=60_000)
    # Erase, looking from the top: a fast stroke from (0, −2) to (0, 2) erases every voxel between them.
    qtbot.mouseClick(area.buttons["top"], Qt.MouseButton.LeftButton)
    view.erase_button.click()
    assert not view.paint_button.isChecked()
    _drag(qtbot, view, [(0, -2, 0), (0, 2, 0)])
    erased = {tuple(p) for p in (after - win.doc.get(obj.id).source).points().tolist()}
    assert erased == {(0, y, 0) for y in range(-2, 3)}
    assert win.doc.history.undo_label() == "Erase voxels"
    # Each stroke is one step: two undos give the octahedron back exactly.
    win.doc.history.undo()
    assert win.doc.get(obj.id).source == after
    win.doc.history.undo()
    assert win.doc.get(obj.id).source == before
    qtbot.waitUntil(win.is_drawn, timeout=60_000)


def _hollow_cube_and_a_cube():  # type: ignore[no-untyped-def]
    m = np.zeros((9, 9, 16), bool)
    m[1:8, 1:8, 1:8] = True
    m[3:6, 3:6, 3:6] = False  # a 3³ cavity (26 voxels around the one floating in it)
    m[4, 4, 4] = True
    m[2:5, 2:5, 11:14] = True  # a separate 3³ cube
    return VoxelSet(m, (-8, -4, -4))


def test_the_region_views_menu_fills_a_cavity_and_deletes_a_component_each_one_undo_step(make_window, qtbot):
    win = make_window(threaded=True)
    vs = _hollow_cube_and_a_cube()
    obj = win.doc.make_object(vs, name="solids")
    win.doc.push(AddObject(obj))
    area = _show_3d(qtbot, win)
    view = area.by_name("region3d")
    second = QtGui.QColor(gl_mesh.COMPONENT_COLOURS_3D[1]).hsvHue()  # the separate cube's colour
    assert _near(_hues(_frame(view)), second, 6) > 100

    def trigger(text: str) -> None:
        menu = view.context_menu()
        acts = {a.text(): a for a in menu.actions() if a.text()}
        assert text in acts, list(acts)
        acts[text].trigger()

    trigger("Fill cavity 1 of component 1 (26 voxels)")
    filled = win.doc.get(obj.id).source
    assert filled.count == vs.count + 26 and vs.issubset(filled)
    assert win.doc.history.undo_label() == "Fill cavity"
    qtbot.waitUntil(win.is_drawn, timeout=60_000)
    region = win.scene.get(obj.id, "region")
    assert region.n_cavities == 0 and [c.voxels for c in region.components] == [7**3, 27]
    trigger("Delete component 2 (27 voxels)")
    assert win.doc.get(obj.id).source.count == 7**3
    assert win.doc.history.undo_label() == "Delete component"
    qtbot.waitUntil(win.is_drawn, timeout=60_000)
    assert _near(_hues(_frame(view)), second, 6) == 0  # the cube is gone from the region view
    win.doc.history.undo()
    assert win.doc.get(obj.id).source == filled
    win.doc.history.undo()
    assert win.doc.get(obj.id).source == vs
    qtbot.waitUntil(win.is_drawn, timeout=60_000)
    assert _near(_hues(_frame(view)), second, 6) > 100


def test_the_region_views_cut_opens_the_cavity_and_pgup_moves_it(make_window, qtbot):
    """Seen from the top, a cavity is hidden; cut through it, its red walls show, until the cut passes it."""
    win = make_window(threaded=True)
    obj = win.doc.make_object(_hollow_cube_and_a_cube(), name="solids")  # the cavity is at z = −1 … 1
    win.doc.push(AddObject(obj))
    area = _show_3d(qtbot, win)
    area.buttons["top"].click()
    view = area.by_name("region3d")
    red = QtGui.QColor(gl_mesh.CAVITY_COLOUR).hsvHue()
    assert _near(_hues(_frame(view)), red, 6) == 0  # closed: nothing of the cavity shows
    qtbot.mouseClick(view.cut_button, Qt.MouseButton.LeftButton)
    assert view.cut == 0 and view.cut_spin.isEnabled()  # through the middle of the target's box
    qtbot.waitUntil(win.is_drawn, timeout=60_000)
    assert _near(_hues(_frame(view)), red, 6) > 100  # opened: its walls are seen from above
    data = view._items[obj.id][0]
    assert data["box"][1][2] == 0.5  # nothing drawn above the cut's layer z = 0
    view.pane.setFocus()
    qtbot.keyClick(view.pane, Qt.Key.Key_PageUp)
    qtbot.keyClick(view.pane, Qt.Key.Key_PageUp)
    assert view.cut == 2
    qtbot.waitUntil(win.is_drawn, timeout=60_000)
    assert _near(_hues(_frame(view)), red, 6) == 0  # the cut's faces at z = 2 close it again
    qtbot.mouseClick(view.cut_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(win.is_drawn, timeout=60_000)
    assert view.cut is None and view._items[obj.id][0]["box"][1][2] == 3.5  # whole again
