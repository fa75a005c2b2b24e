"""The 3D views on a real X server with OpenGL (run by tests/app/test_views_3d.py under its own Xvfb).

pyqtgraph's OpenGL widgets abort under Qt's offscreen platform, so these cases run in a pytest of their own,
started with ``--headed`` and ``DISPLAY`` set to an Xvfb with GLX (Mesa's llvmpipe). They drive the real
window with the keyboard and the mouse and read the rendered frame buffers back.
"""

from __future__ import annotations

import os

import numpy as np
from PySide6 import QtCore, QtGui, QtWidgets

from mrm.core.grids import VoxelSet
from mrm.document.commands import AddObject
from mrm.geometry.polyhedra import Polyhedron
from mrm.views import gl_mesh
from tests.app.helpers import press_key, send_mouse_move, send_wheel

Qt = QtCore.Qt

R = 6  # the digital octahedron |x| + |y| + |z| <= R: 8 plane segments, one per face


def _octahedron(win):  # type: ignore[no-untyped-def]
    n = 2 * R + 1
    z, y, x = np.mgrid[-R : R + 1, -R : R + 1, -R : R + 1]
    vs = VoxelSet(np.abs(x) + np.abs(y) + np.abs(z) <= R, (-R, -R, -R))
    obj = win.doc.make_object(vs, name="octahedron")
    win.doc.push(AddObject(obj))
    assert n == vs.mask.shape[0]
    return obj


def _key_3d(qtbot, win, key) -> None:  # type: ignore[no-untyped-def]
    pane = win.views.area3d.views[0].pane
    # Xvfb has no window manager: the window can lose activation to the GL surfaces; shortcuts need it.
    win.activateWindow()
    qtbot.waitUntil(lambda: QtWidgets.QApplication.activeWindow() is win, timeout=5000)
    pane.setFocus()
    qtbot.keyClick(pane, key)


def _show_3d(qtbot, win):  # type: ignore[no-untyped-def]
    press_key(qtbot, win.views.discrete, Qt.Key.Key_F3)
    qtbot.waitUntil(lambda: win.views.dimension == 3 and win.views.area3d is not None, timeout=5000)
    qtbot.waitUntil(win.is_drawn, timeout=60_000)
    qtbot.wait(50)  # one more frame: the camera fitted after the first refresh
    return win.views.area3d


def _frame(view, gizmo: bool = False) -> QtGui.QImage:  # type: ignore[no-untyped-def]
    """The view's rendered frame.

    Without ``gizmo``, the axis gizmo's corner is blacked out: its x axis is red like a cavity, its z axis
    blue like an object.
    """
    view.pane.update()
    img = view.pane.grabFramebuffer()
    if not gizmo:
        from mrm.views.view3d import GIZMO_MARGIN, GIZMO_RADIUS

        side = 2 * (GIZMO_MARGIN + GIZMO_RADIUS) + 12
        painter = QtGui.QPainter(img)
        painter.fillRect(0, img.height() - side, side, side, QtGui.QColor("black"))
        painter.end()

    if os.environ.get("MRM_GL_SAVE"):
        img.save(f"{os.environ['MRM_GL_SAVE']}/{view.name}.png")
    return img


def _hues(img: QtGui.QImage, min_saturation: int = 60) -> np.ndarray:
    """The hue (0-359) of every saturated pixel of the image."""
    img = img.convertToFormat(QtGui.QImage.Format.Format_RGB32)
    w, h = img.width(), img.height()
    arr = np.frombuffer(img.constBits(), np.uint8).reshape(h, img.bytesPerLine() // 4, 4)[:, :w, :3]
    rgb = arr[..., ::-1].reshape(-1, 3).astype(int)  # BGRA in memory
    hues = []
    mx, mn = rgb.max(axis=1), rgb.min(axis=1)
    sat = mx - mn
    keep = (sat >= min_saturation) & (mx >= 40)
    for r, g, b in rgb[keep][:: max(1, int(keep.sum()) // 20000)]:
        c = QtGui.QColor(int(r), int(g), int(b))
        hues.append(c.hsvHue())
    return np.array(hues, int)


def _hue_of(colour: str) -> int:
    return QtGui.QColor(colour).hsvHue()


def _near(hues: np.ndarray, hue: int, tol: int = 12) -> int:
    d = np.abs(hues - hue)
    return int(np.sum(np.minimum(d, 360 - d) <= tol))


def test_a_voxel_octahedron_is_drawn_in_its_four_3d_views(make_window, qtbot):
    win = make_window(threaded=True)
    obj = _octahedron(win)
    area = _show_3d(qtbot, win)
    assert [v.name for v in area.views] == ["discrete3d", "region3d", "analytical3d", "euclidean3d"]
    discrete, region, analytical, euclidean = area.views
    blue = _hue_of(obj.style.fill)
    # The discrete view: the surfels in the object's colour, shaded, over a good part of the pane.
    hues = _hues(_frame(discrete))
    assert _near(hues, blue) > 0.9 * len(hues) > 500
    # The region view: one component, in the first component colour.
    hues = _hues(_frame(region))
    assert _near(hues, _hue_of(gl_mesh.COMPONENT_COLOURS_3D[0])) > 0.9 * len(hues) > 500
    # The analytical view: the 8 faces of the octahedron are 8 plane segments in several colours.
    ana = win.scene.get(win.doc.objects[-1].id, "analytical")
    assert ana.n_segments == 8
    hues = _hues(_frame(analytical))
    palette = {_hue_of(c) for c in gl_mesh.SEGMENT_COLOURS_3D if QtGui.QColor(c).hsvSaturation() > 60}
    seen = {h for h in palette if _near(hues, h, 6) > 50}
    assert len(seen) >= 3, seen  # a view shows at least three faces of a convex solid, neighbours differ
    # The Euclidean view: the polyhedron R(A), in the object's colour, with dark face edges.
    hues = _hues(_frame(euclidean))
    assert _near(hues, blue) > 500
    items = euclidean._items[win.doc.objects[-1].id][1]
    assert any(type(it).__name__ == "GLLinePlotItem" for it in items)


def test_orbiting_one_3d_view_turns_the_four_and_the_buttons_set_them_all(make_window, qtbot):
    win = make_window(threaded=True)
    _octahedron(win)
    area = _show_3d(qtbot, win)
    panes = [v.pane for v in area.views]
    before = panes[0].cameraParams()
    # Drag with the left button in the Euclidean view: it orbits, and the other three follow exactly.
    pane = area.by_name("euclidean3d").pane
    c = pane.rect().center()
    qtbot.mousePress(pane, Qt.MouseButton.LeftButton, pos=c)
    for k in range(1, 8):
        send_mouse_move(pane, QtCore.QPoint(c.x() + 10 * k, c.y() + 3 * k), Qt.MouseButton.LeftButton)
    qtbot.mouseRelease(pane, Qt.MouseButton.LeftButton, pos=c)
    after = [p.cameraParams() for p in panes]
    assert after[0]["azimuth"] != before["azimuth"]
    assert all(a["azimuth"] == after[0]["azimuth"] and a["elevation"] == after[0]["elevation"] for a in after)
    # The wheel zooms all four.
    qtbot.wait(10)
    d0 = panes[0].cameraParams()["distance"]
    send_wheel(pane, c)
    assert all(p.cameraParams()["distance"] < d0 for p in panes)
    # Top: every view looks down the z axis.
    qtbot.mouseClick(area.buttons["top"], Qt.MouseButton.LeftButton)
    assert all(p.cameraParams()["elevation"] == 90.0 for p in panes)
    # Home fits the octahedron: its whole height is in view again after the zoom.
    _key_3d(qtbot, win, Qt.Key.Key_Home)
    assert all(abs(p.cameraParams()["distance"] - d0) < 1e-6 * d0 for p in panes)


def test_a_project_of_3d_objects_opens_in_the_3d_views_and_f3_goes_back(make_window, qtbot):
    win = make_window(threaded=True)
    poly = Polyhedron(
        [[4, 0, 0], [-4, 0, 0], [0, 4, 0], [0, -4, 0], [0, 0, 4], [0, 0, -4]],
        [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]],
    )
    win.doc.reset([win.doc.make_object(poly, name="solid")])  # as File ▸ Open does
    qtbot.waitUntil(lambda: win.views.dimension == 3, timeout=5000)
    assert win.registry["view.three_d"].isChecked()
    qtbot.waitUntil(win.is_drawn, timeout=60_000)
    euclidean = win.views.area3d.by_name("euclidean3d")
    data = euclidean._items[win.doc.objects[0].id][0]
    assert len(data["lines"]) == 2 * 12  # the octahedron's 12 edges, not the diagonals of a triangulation
    _key_3d(qtbot, win, Qt.Key.Key_F3)
    assert win.views.dimension == 2 and not win.registry["view.three_d"].isChecked()


def _corner_hues(view, colour: str) -> tuple[int, int, int, int]:  # type: ignore[no-untyped-def]
    """Pixels of ``colour`` on the gizmo's axes (its disk): (right of, left of, above, below) its centre."""
    from mrm.views.view3d import GIZMO_MARGIN, GIZMO_RADIUS

    img = _frame(view, gizmo=True).convertToFormat(QtGui.QImage.Format.Format_RGB32)
    cx, cy = GIZMO_MARGIN + GIZMO_RADIUS, img.height() - GIZMO_MARGIN - GIZMO_RADIUS
    hue = _hue_of(colour)
    counts = [0, 0, 0, 0]
    for x in range(max(0, cx - GIZMO_RADIUS - 12), cx + GIZMO_RADIUS + 12):
        for y in range(cy - GIZMO_RADIUS - 12, min(img.height(), cy + GIZMO_RADIUS + 12)):
            if (x - cx) ** 2 + (y - cy) ** 2 > (GIZMO_RADIUS - 4) ** 2:
                continue  # the axes' lines only, not their letters beyond their ends
            c = img.pixelColor(x, y)
            if c.hsvSaturation() < 120 or c.value() < 80:
                continue
            if min(abs(c.hsvHue() - hue), 360 - abs(c.hsvHue() - hue)) > 10:
                continue
            counts[0] += x > cx + 4
            counts[1] += x < cx - 4
            counts[2] += y < cy - 4
            counts[3] += y > cy + 4
    return counts[0], counts[1], counts[2], counts[3]


def test_the_axis_gizmo_turns_with_the_shared_camera(make_window, qtbot):
    from mrm.views.view3d import GIZMO_COLOURS

    win = make_window(threaded=True)
    _octahedron(win)
    area = _show_3d(qtbot, win)
    x, y, z = GIZMO_COLOURS
    area.buttons["front"].click()  # looking along +y: x to the right, z up, y away from the viewer
    for view in area.views:  # every view has its gizmo, and they agree
        right, left, up, down = _corner_hues(view, x)
        assert right > 20 and left == 0, view.name
        right, left, up, down = _corner_hues(view, z)
        assert up > 20 and down == 0, view.name
    area.buttons["top"].click()  # looking down z: x to the right, y up
    right, left, up, down = _corner_hues(area.views[0], y)
    assert up > 20 and down == 0
    area.buttons["side"].click()  # looking along −x: y to the right... of a viewer facing −x, z up
    right, left, up, down = _corner_hues(area.views[0], z)
    assert up > 20 and down == 0
    right, left, up, down = _corner_hues(area.views[0], x)
    assert right + left < 15  # x points at the viewer: seen end-on, a dot


def test_the_analytical_view_draws_each_plane_segments_normal(make_window, qtbot):
    """The octahedron's 8 plane segments: one outward line from the middle of each face, along a normal that
    separates the face's voxels from the voxels outside it (a normal of the segment's preimage)."""
    from mrm.geometry.topology.surfels import DIRS

    win = make_window(threaded=True)
    obj = _octahedron(win)
    area = _show_3d(qtbot, win)
    view = area.by_name("analytical3d")
    data, items = view._items[obj.id]
    lines = data["lines"].reshape(-1, 2, 3).astype(float)
    seg = win.scene.get(obj.id, "analytical").segmentation
    assert len(lines) == len(seg) == 8
    for start, end in lines:
        normal = end - start
        k = int(seg.segment_of[np.argmin(np.abs(seg.voxel - start).sum(axis=1))])  # the face it starts on
        members = seg.surfels_of(k)
        inner = seg.voxel[members]
        outer = inner + DIRS[seg.direction[members].astype(int)]
        assert (inner @ normal).max() < (outer @ normal).min(), k  # it separates: in the preimage
        assert np.allclose(np.abs(start).sum(), R + 0.5, atol=1.5)  # from the face's middle, outward
        assert start @ normal > 0 and np.sign(normal).tolist() == np.sign(start).tolist()
    assert len({tuple(np.sign(e - s).astype(int)) for s, e in lines}) == 8
    assert any(type(it).__name__ == "GLLinePlotItem" for it in items)


def _ell(win):  # type: ignore[no-untyped-def]
    mask = np.zeros((3, 4, 4), bool)
    mask[:, :2, :] = True
    mask[:, :, :2] = True  # an L-shaped prism: not digitally convex, so R is the decimation's
    ell = win.doc.make_object(VoxelSet(mask, (20, 0, 0)), name="ell")
    win.doc.push(AddObject(ell))
    return ell


def test_the_euclidean_view_says_when_r_is_the_safety_net_and_why(make_window, qtbot):
    # R(A) of a set past the decimation's size limit is the safety net: exact, but its faces are the voxels'
    # squares. The Euclidean view's header says so, and its tool tip says of which object and why; a convex
    # object's R (a hull) adds nothing; the tip ends with where the limit is raised.
    from mrm.document.commands import ChangeSettings

    win = make_window(threaded=True)
    # as Edit ▸ Discretization Model ▸ Compact R Limit… does (tests/app/test_3d_objects_in_plane_views.py)
    win.doc.push(ChangeSettings.compact_limit(win.doc, 10))
    octa = _octahedron(win)
    ell = _ell(win)
    view = _show_3d(qtbot, win).by_name("euclidean3d")
    qtbot.waitUntil(lambda: "safety net" in view.status_label.text(), timeout=30_000)
    assert view.status_label.text() == "R is the safety net (not compact)"
    n = win.scene.get(ell.id, "euclidean").n_triangles
    tip = view.status_label.toolTip()
    assert tip == (
        f"ell: R is the safety net (V(A) eroded by ¼, {n:,} triangles), not a compact R: the decimation "
        "takes sets whose safety net has at most 10 triangles (Edit ▸ Discretization Model ▸ Compact R "
        "Limit… raises it)"
    )
    assert octa.name not in tip
    # Ctrl+Z takes the L away: the note goes with it; Ctrl+Shift+Z brings both back.
    pane = view.pane
    win.activateWindow()
    qtbot.waitUntil(lambda: QtWidgets.QApplication.activeWindow() is win, timeout=5000)
    pane.setFocus()
    qtbot.keyClick(pane, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    qtbot.waitUntil(lambda: ell.id not in win.doc, timeout=5000)
    qtbot.waitUntil(lambda: view.status_label.text() == "", timeout=30_000)
    redo = Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier
    qtbot.keyClick(pane, Qt.Key.Key_Z, redo)
    qtbot.waitUntil(lambda: "safety net" in view.status_label.text(), timeout=30_000)


def test_the_safety_net_note_comes_before_a_coarser_level_in_the_header(make_window, qtbot, monkeypatch):
    # Both at once: what the object is (its R) before how it is drawn (a coarser level); the tip has both.
    from mrm.document.commands import ChangeSettings
    from mrm.views.view3d import View3D

    monkeypatch.setattr(View3D, "SURFEL_BUDGET", 20)
    win = make_window(threaded=True)
    win.doc.push(ChangeSettings.compact_limit(win.doc, 10))
    z, y, x = np.mgrid[0:10, 0:10, 0:10]
    # a staircase and a slab: not convex, and a safety net of 486 triangles, drawn in cubes wider than a voxel
    win.doc.push(
        AddObject(win.doc.make_object(VoxelSet((x + y + z <= 12) | (x >= 8), (0, 0, 0)), name="stairs"))
    )
    view = _show_3d(qtbot, win).by_name("euclidean3d")
    qtbot.waitUntil(lambda: "safety net" in view.status_label.text(), timeout=30_000)
    assert view.coarsest_level() > 1
    assert view.status_label.text().startswith("R is the safety net (not compact) · coarser level: vertices")
    tip = view.status_label.toolTip().split("\n")
    assert tip[0].startswith("stairs: R is the safety net") and tip[1].startswith(
        "A polyhedron has more than"
    )


def test_a_plane_segment_chosen_in_the_segments_panel_is_drawn_in_the_analytical_view(make_window, qtbot):
    # A click on a row of the Segments panel's plane segments draws that segment's surfels in yellow over the
    # analytical view; another object selected takes it away.
    from tests.app.helpers import click_object

    win = make_window(threaded=True)
    obj = _octahedron(win)
    view = _show_3d(qtbot, win).by_name("analytical3d")
    win.segments_dock.show()
    win.segments_dock.raise_()
    click_object(qtbot, win, "octahedron")
    table = win.segments.plane_table
    qtbot.waitUntil(lambda: table.model().rowCount() == 8, timeout=30_000)
    assert _near(_hues(_frame(view)), _hue_of(view.CHOSEN_COLOUR), 6) == 0  # no yellow yet
    rect = table.visualRect(table.model().index(3, 2))
    qtbot.mouseClick(
        table.viewport(), Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, rect.center()
    )
    assert win.scene.plane_segment == (obj.id, 3)
    seg = win.scene.get(obj.id, "analytical").segmentation
    n = len(seg.surfels_of(3))
    qtbot.waitUntil(lambda: view._chosen_item is not None, timeout=5000)
    hues = _hues(_frame(view))  # the first paint uploads the item's arrays
    assert len(view._chosen_item.faces) == 2 * n  # the segment's surfels, two triangles each
    assert _near(hues, _hue_of(view.CHOSEN_COLOUR), 6) > 50
    win.doc.set_selection([])  # nothing selected: nothing chosen
    qtbot.waitUntil(lambda: view._chosen_item is None, timeout=5000)
    assert win.scene.plane_segment == (-1, -1)
