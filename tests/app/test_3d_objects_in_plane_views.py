"""A project holding voxel objects (docs/design.md §11) opens in the desktop: the plane views draw its 2D
objects and leave the 3D ones out, the object list says what they are, and saving keeps them."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from PySide6 import QtCore, QtWidgets

from mrm.core.grids import LabelVolume, VoxelSet
from mrm.io.project import load_project
from mrm.views.object_list import COL_SOURCE
from tests.app.helpers import (
    click_object,
    colour_at,
    grab,
    is_background,
    press_key,
    shown_dialog,
    wait_drawn,
    zoom_to,
)

GOLDEN_V5 = Path(__file__).parents[1] / "model" / "golden" / "v5-voxels.mrm"


def test_a_project_with_voxel_objects_opens_draws_its_plane_objects_and_saves_them_back(
    make_window, qtbot, tmp_path
):
    win = make_window()
    assert win.files.open(GOLDEN_V5, ask=False)
    wait_drawn(qtbot, win)
    # The 2 × 2 pixel square is drawn in the discrete view; the octahedron's voxels are not drawn as pixels
    # (its (x, y) = (10, -20) column would otherwise show there).
    zoom_to(win, -4.0, -24.0, 14.0, 4.0)
    view = win.views.discrete
    image = grab(view)
    assert not is_background(view, colour_at(view, 0.0, 0.0, image))
    assert is_background(view, colour_at(view, 10.0, -20.0, image))
    model = win.object_list.model
    texts = {model.obj(r).name: model.data(model.index(r, COL_SOURCE)) for r in range(model.rowCount())}
    assert texts["octahedron"] == "voxels (3D)" and texts["labels 3D"] == "label volume (3D)"
    assert texts["square"] == "pixels" and texts["solid octahedron"] == "polyhedron (3D)"
    # Choosing the 3D object breaks nothing: the views stay drawn and the selection is the octahedron.
    click_object(qtbot, win, "octahedron")
    wait_drawn(qtbot, win)
    assert [win.doc.get(i).name for i in win.doc.selection] == ["octahedron"]
    out = tmp_path / "again.mrm"
    win.files.save_as(out)
    again = load_project(out)
    assert isinstance(again.find("octahedron")[0].source, VoxelSet)
    assert isinstance(again.find("labels 3D")[0].source, LabelVolume)
    assert again.find("octahedron")[0].source == win.doc.find("octahedron")[0].source
    assert again.find("solid octahedron")[0].source == win.doc.find("solid octahedron")[0].source


def test_choosing_a_plane_tool_in_the_3d_views_brings_the_plane_views_forward(make_window, qtbot):
    # The drawing tools act in the plane views: P pressed while the 3D views were shown chose Draw Polygon,
    # which did nothing the user could see. Now the plane views come forward and the status bar says how to
    # go back; S (select, which the 3D views use too) leaves the 3D views alone.
    from PySide6 import QtCore

    from tests.app.helpers import press_key

    win = make_window()
    assert win.files.open(GOLDEN_V5, ask=False)
    wait_drawn(qtbot, win)
    press_key(qtbot, win.views.discrete, QtCore.Qt.Key.Key_F3)
    assert win.views.dimension == 3
    win.activateWindow()
    qtbot.keyClick(win.views.area3d, QtCore.Qt.Key.Key_S)
    assert win.views.dimension == 3 and win.tools.tool.name == "select"
    qtbot.keyClick(win.views.area3d, QtCore.Qt.Key.Key_P)
    assert win.views.dimension == 2 and win.views.discrete.isVisible()
    assert win.tools.tool.name == "polygon" and win.registry["tool.polygon"].isChecked()
    assert win.status.currentMessage() == "Draw Polygon works in the plane views (F3 for the 3D views)"
    assert not win.registry["view.three_d"].isChecked()


def test_a_selected_3d_object_shows_in_the_properties_and_segments_panels(make_window, qtbot):
    # Both panels said "Select an object…" with a 3D object selected. Now the Properties panel edits its name
    # (one undo step) and says what its R(A) is; the Segments panel lists its digital plane segments.
    import numpy as np

    from mrm.document.commands import AddObject
    from tests.app.helpers import type_into

    win = make_window(threaded=True)
    assert win.files.open(GOLDEN_V5, ask=False)
    wait_drawn(qtbot, win)
    win.registry["edit.properties"].trigger()
    click_object(qtbot, win, "octahedron")
    panel = win.properties
    obj = win.doc.find("octahedron")[0]
    assert panel.name_edit.text() == "octahedron" and not panel.table.isVisible()
    assert panel.source_label.text().startswith("voxels (3D)")
    qtbot.waitUntil(lambda: "R(A), exact" in panel.vertex_note.text(), timeout=30_000)
    r = win.scene.get(obj.id, "euclidean")
    assert f"{r.n_triangles:,} triangles, {r.n_vertices:,} vertices" in panel.vertex_note.text()
    assert "safety net" not in panel.vertex_note.text()  # a convex set: its hull
    type_into(qtbot, panel.name_edit, "diamond")
    assert win.doc.get(obj.id).name == "diamond"
    assert win.doc.history.undo_label() == "Rename"
    click_object(qtbot, win, "solid octahedron")
    solid = win.doc.find("solid octahedron")[0].source
    qtbot.waitUntil(lambda: "A polyhedron of" in panel.vertex_note.text(), timeout=5000)
    assert f"{solid.n_triangles:,} triangles" in panel.vertex_note.text()
    # The Segments panel lists the plane segments of a digital octahedron of radius 4: one per face, normals
    # (±1, ±1, ±1), thickness 3, together all its surfels.
    z, y, x = np.mgrid[-4:5, -4:5, -4:5]
    octa = win.doc.make_object(VoxelSet(abs(x) + abs(y) + abs(z) <= 4, (30, -4, -4)), name="octa 4")
    win.doc.push(AddObject(octa))
    click_object(qtbot, win, "octa 4")
    segments = win.segments
    qtbot.waitUntil(
        lambda: "8 digital plane segments on 1 surface" in segments.caption.text(), timeout=30_000
    )
    assert segments.plane_table.isVisible() and not segments.table.isVisible()
    planes = segments.plane_table.model()
    rows = [[planes.index(r, c).data() for c in range(8)] for r in range(planes.rowCount())]
    assert sorted(tuple(row[2:5]) for row in rows) == sorted(
        (a, b, c) for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)
    )
    n_surfels = win.scene.get(octa.id, "region").n_surfels
    assert {row[6] for row in rows} == {3} and sum(row[7] for row in rows) == n_surfels
    # A plane object again: the segments of its boundaries, in the table of digital straight segments.
    click_object(qtbot, win, "square")
    qtbot.waitUntil(lambda: segments.table.isVisible() and not segments.plane_table.isVisible(), timeout=5000)


def test_a_3d_object_exports_its_polyhedron_or_its_voxels(make_window, qtbot, tmp_path):
    # Ctrl+E with a 3D object selected said "Select the object to export first". Now the voxel octahedron
    # exports R(A) (reads back as a polyhedron whose voxels are A again) or its voxels, the polyhedron its
    # mesh, the label volume its labels; a mesh type for a label volume is refused with what it takes.
    import numpy as np
    from PySide6 import QtCore, QtWidgets

    import mrm
    from tests.app.helpers import answer_file_dialog

    win = make_window()
    assert win.files.open(GOLDEN_V5, ask=False)
    wait_drawn(qtbot, win)
    octa = win.doc.find("octahedron")[0]
    click_object(qtbot, win, "octahedron")
    seen = answer_file_dialog(qtbot, "exportDialog", tmp_path / "octa.obj")
    qtbot.keyClick(win.views.discrete, QtCore.Qt.Key.Key_E, QtCore.Qt.KeyboardModifier.ControlModifier)
    qtbot.waitUntil(lambda: (tmp_path / "octa.obj").exists(), timeout=30_000)
    assert seen["name"] == "octahedron.obj"
    model = win.doc.settings.model
    back = mrm.read_mesh(tmp_path / "octa.obj")
    assert mrm.voxelize(back, model) == octa.source
    assert "safety net" not in win.status.currentMessage()
    assert win.files.export(octa.id, tmp_path / "octa.nii.gz")
    qtbot.waitUntil(lambda: (tmp_path / "octa.nii.gz").exists(), timeout=30_000)
    assert mrm.read_voxels(tmp_path / "octa.nii.gz") == octa.source
    solid = win.doc.find("solid octahedron")[0]
    assert win.files.export(solid.id, tmp_path / "solid.off")
    qtbot.waitUntil(lambda: (tmp_path / "solid.off").exists(), timeout=30_000)
    assert mrm.read_mesh(tmp_path / "solid.off") == solid.source
    labels = win.doc.find("labels 3D")[0]
    assert win.files.export(labels.id, tmp_path / "labels.npz")
    qtbot.waitUntil(lambda: (tmp_path / "labels.npz").exists(), timeout=30_000)
    assert np.array_equal(mrm.read_label_volume(tmp_path / "labels.npz").labels, labels.source.labels)
    box = {}

    def refused() -> bool:
        boxes = [w for w in QtWidgets.QApplication.topLevelWidgets() if w.objectName() == "errorDialog"]
        if boxes and boxes[0].isVisible():
            box["text"] = f"{boxes[0].text()} {boxes[0].informativeText()}"
            boxes[0].close()
            return True
        return False

    assert not win.files.export(labels.id, tmp_path / "labels.obj")
    qtbot.waitUntil(refused, timeout=5000)
    assert "labels 3D is a 3D object: it exports as .npz, .tif, .nii.gz" in box["text"]
    assert not (tmp_path / "labels.obj").exists()


def test_the_compact_limit_is_chosen_in_its_dialog_said_on_export_and_undone(make_window, qtbot, tmp_path):
    # Edit ▸ Discretization Model ▸ Compact R Limit…: past the limit R(A) is the safety net, the exported
    # mesh is exact but not compact, and the status bar says so and where the limit is raised; Ctrl+Z gives
    # the compact R back.
    import numpy as np

    import mrm
    from mrm.document.commands import AddObject

    win = make_window()
    z, y, x = np.mgrid[0:10, 0:10, 0:10]
    stairs = win.doc.make_object(VoxelSet((x + y + z <= 12) | (x >= 8), (0, 0, 0)), name="stairs")
    win.doc.push(AddObject(stairs))
    assert win.registry["edit.compact_limit"] in win.model_menu.actions()
    ctrl_alt = QtCore.Qt.KeyboardModifier.ControlModifier | QtCore.Qt.KeyboardModifier.AltModifier
    press_key(qtbot, win.views.discrete, QtCore.Qt.Key.Key_L, ctrl_alt)  # Ctrl+Alt+L, as the menu says
    spin = shown_dialog(qtbot, "compactLimitDialog").findChild(QtWidgets.QSpinBox)
    assert spin.value() == 20_000  # the document's limit, the default
    spin.lineEdit().selectAll()
    qtbot.keyClicks(spin.lineEdit(), "10")
    qtbot.keyClick(spin.lineEdit(), QtCore.Qt.Key.Key_Return)
    qtbot.waitUntil(lambda: win.doc.settings.compact_limit == 10, timeout=5000)
    assert win.doc.history.undo_label() == "Compact R up to 10 triangles"

    def export() -> tuple[str, Any]:
        win.status.show_text("")
        assert win.files.export(stairs.id, tmp_path / "stairs.obj")
        qtbot.waitUntil(lambda: "Exported stairs.obj" in win.status.currentMessage(), timeout=30_000)
        mesh = mrm.read_mesh(tmp_path / "stairs.obj")
        assert mrm.voxelize(mesh, win.doc.settings.model) == stairs.source  # exact either way
        return win.status.currentMessage(), mesh

    said, net = export()
    assert "holds R's safety net, exact but not compact" in said
    assert "a higher Compact R Limit, in Edit ▸ Discretization Model, gives a compact R" in said
    assert "safety net" in win.scene.r_note(stairs.id)
    assert win.scene.r_note(stairs.id).endswith("(Edit ▸ Discretization Model ▸ Compact R Limit… raises it)")
    qtbot.keyClick(win.views.discrete, QtCore.Qt.Key.Key_Z, QtCore.Qt.KeyboardModifier.ControlModifier)
    assert win.doc.settings.compact_limit == 20_000
    said, compact = export()
    assert "safety net" not in said and win.scene.r_note(stairs.id) is None
    assert compact.n_faces < net.n_faces


def test_a_slow_compact_r_shows_its_progress_and_cancel_stops_it(make_window, qtbot):
    # With a high compact limit R(A) of a bumpy volume takes seconds, on a worker: the status bar says what
    # it is doing, and its Cancel stops the simplification itself (not only the waiting), so the worker is
    # free again long before R would have been done. A lower limit then gives the safety net at once.
    from mrm.document.commands import AddObject, ChangeSettings
    from mrm.geometry.discretize.voxels import voxelize
    from mrm.views.scene import CANCELLED
    from tests.model.voxel_shapes import smoothed_noise

    win = make_window(threaded=True)
    blobs = win.doc.make_object(VoxelSet(smoothed_noise(64, 3), (0, 0, 0)), name="blobs")
    win.doc.push(AddObject(blobs))
    win.doc.push(ChangeSettings.compact_limit(win.doc, 1_000_000))
    assert win.scene.get(blobs.id, "euclidean") is None  # asked for as a view asks: computed on a worker
    button = win.status.cancel_button
    qtbot.waitUntil(
        lambda: button.isVisible() and "simplifying a safety net of" in win.status.progress_box.toolTip(),
        timeout=120_000,
    )
    assert win.status.progress_box.toolTip().startswith("blobs")
    qtbot.mouseClick(button, QtCore.Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: not win.runner.is_busy(), timeout=5000)  # R itself would take 15 s or more
    assert win.scene.error(blobs.id, "euclidean") == CANCELLED
    qtbot.keyClick(win.views.discrete, QtCore.Qt.Key.Key_Z, QtCore.Qt.KeyboardModifier.ControlModifier)
    assert win.doc.settings.compact_limit == 20_000 and blobs.id in win.doc
    qtbot.waitUntil(lambda: win.scene.get(blobs.id, "euclidean") is not None, timeout=60_000)
    assert "safety net" in win.scene.r_note(blobs.id)
    assert voxelize(win.scene.get(blobs.id, "euclidean"), "standard") == blobs.source


def test_the_operations_panel_scales_the_r_of_the_documents_compact_limit(make_window, qtbot):
    # Under a compact limit of 10 a staircase's R is its safety net: DSS 1.5 from the Operations panel scales
    # that net (what the Euclidean view shows), not the default limit's compact R.
    from mrm.document.commands import AddObject, ChangeSettings
    from mrm.geometry.polyhedra import Polyhedron
    from mrm.geometry.reconstruct.safety_net_3d import safety_net_3d
    from mrm.ops.registry import run_operation
    from tests.app.helpers import type_into

    win = make_window()
    z, y, x = np.mgrid[0:6, 0:6, 0:6]
    a = VoxelSet((x + y + z <= 7) | (x >= 4), (0, 0, 0))
    stairs = win.doc.make_object(a, name="stairs")
    win.doc.push(AddObject(stairs, select=True))
    win.doc.push(ChangeSettings.compact_limit(win.doc, 10))
    net = safety_net_3d(a.mask, a.origin)
    expected = run_operation(
        "dss", [a], {"alpha": 1.5}, held=[(0, "standard", Polyhedron(net.vertices, net.triangles))]
    ).output
    assert expected != run_operation("dss", [a], {"alpha": 1.5}).output  # the limit matters here
    panel = win.operations
    panel.select_operation("dss")
    type_into(qtbot, panel.control("alpha").field, "1.5")
    n = len(win.doc)
    qtbot.mouseClick(panel.apply_button, QtCore.Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(win.doc) == n + 1, timeout=30_000)
    assert win.doc.objects[-1].source == expected
