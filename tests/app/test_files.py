"""Files through the window: save, close, reopen; prompts; hostile files; recovery; import/export; drops."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import shapely
from PySide6 import QtCore, QtGui, QtWidgets
from shapely.geometry import Polygon

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject, RenameObject
from tests.app.helpers import HANG_MS, answer_dialog, answer_file_dialog, colour_at, is_background, wait_drawn

Qt = QtCore.Qt
CTRL = Qt.KeyboardModifier.ControlModifier
SQUARE = Polygon([(0, 0), (12, 0), (12, 9), (0, 9)], [[(3, 3), (6, 3), (6, 6), (3, 6)]])


def _populate(win) -> None:  # type: ignore[no-untyped-def]
    doc = win.doc
    doc.push(AddObject(doc.make_object(SQUARE, name="square"), select=True))
    m = np.zeros((5, 7), bool)
    m[1:4, 1:6] = True
    m[0, 0] = True
    doc.push(AddObject(doc.make_object(PixelSet(m, (20, -3)), name="blob")))


def _error_boxes(win) -> list[QtWidgets.QMessageBox]:  # type: ignore[no-untyped-def]
    return [b for b in win.findChildren(QtWidgets.QMessageBox, "errorDialog") if b.isVisible()]


def test_save_close_reopen(make_window, qtbot, tmp_path):
    win = make_window()
    _populate(win)
    assert win.isWindowModified()
    path = tmp_path / "p.mrm"
    assert win.files.save_as(path)
    assert path.is_file()
    assert not win.isWindowModified() and not win.doc.is_modified
    assert "p.mrm" in win.windowTitle()
    before = [(o.name, o.kind, o.style) for o in win.doc.objects]
    sources = [o.source for o in win.doc.objects]
    win.close_now()
    win2 = make_window()
    assert win2.files.open(path, ask=False)
    after = win2.doc.objects
    assert [(o.name, o.kind, o.style) for o in after] == before
    assert after[0].source.equals_exact(sources[0], 0) and after[1].source == sources[1]
    assert not win2.doc.is_modified
    wait_drawn(qtbot, win2)
    assert not is_background(win2.views.discrete, colour_at(win2.views.discrete, 1, 1))
    assert str(path.resolve()) in win2.prefs.recent_files()
    assert any("p.mrm" in a.text() for a in win2.recent_menu.actions())


def test_unsaved_changes_prompt(make_window, qtbot):
    win = make_window()
    _populate(win)
    answer_dialog(qtbot, "unsavedDialog", "Cancel")
    win.registry["file.new"].trigger()
    assert len(win.doc) == 2  # cancelled: nothing lost
    texts = answer_dialog(qtbot, "unsavedDialog", "Discard")
    win.registry["file.new"].trigger()
    assert len(win.doc) == 0 and not win.doc.is_modified
    assert "Untitled" in texts[0]


def test_hostile_files_show_an_error_and_keep_the_document(make_window, qtbot, tmp_path):
    win = make_window()
    _populate(win)
    win.doc.push(RenameObject(win.doc.objects[0].id, "kept"))
    state = [(o.id, o.name) for o in win.doc.objects]
    rev = win.doc.revision
    hostile = {
        "garbage.mrm": b"\x00\xff not json at all",
        "png.mrm": b"\x89PNG\r\n\x1a\n" + b"\x00" * 64,
        "nested.mrm": b"[" * 100_000 + b"]" * 100_000,
        "wrong.mrm": b'{"format": "mrm-project", "schema_version": 1, "settings": {"model": "standard"}, '
        b'"objects": [{"id": 1, "name": "x", "source": {"kind": "discrete", "origin": [0, 0], '
        b'"shape": [100000, 100000], "bits": "AAAA"}}]}',
        "future.mrm": b'{"format": "mrm-project", "schema_version": 999, "settings": {}, "objects": []}',
    }
    for name, data in hostile.items():
        p = tmp_path / name
        p.write_bytes(data)
        assert not win.files.open(p, ask=False), name
        boxes = _error_boxes(win)
        assert boxes, name
        assert name in boxes[-1].informativeText() or "project" in boxes[-1].informativeText().lower()
        for b in boxes:
            b.close()
        assert [(o.id, o.name) for o in win.doc.objects] == state
        assert win.doc.revision == rev
    assert not win.files.open(tmp_path / "missing.mrm", ask=False)
    assert "no such file" in _error_boxes(win)[-1].informativeText()


def test_recovery_after_a_crash_of_a_saved_project(make_window, qtbot, tmp_path):
    win = make_window()
    _populate(win)
    path = tmp_path / "r.mrm"
    assert win.files.save_as(path)
    win.doc.push(RenameObject(win.doc.objects[0].id, "edited after saving"))
    win.files.autosaver.interval = 0.0  # due at once: the next timer tick writes the side file
    win.files.autosave_tick()
    side = win.files.autosaver.path
    assert side.is_file()
    win.close_now(discard_autosave=False)  # the "crash": the side file stays
    assert side.is_file()

    win2 = make_window()
    texts = answer_dialog(qtbot, "recoveryDialog", "Recover")
    assert win2.files.open(path, ask=False)
    assert "r.mrm" in texts[0]
    assert win2.doc.objects[0].name == "edited after saving"
    assert win2.doc.is_modified and win2.isWindowModified()
    assert win2.doc.path == path.resolve()
    assert win2.files.save()
    assert not win2.doc.is_modified
    assert not side.exists()


def test_recovery_of_an_untitled_document_from_a_dead_process(make_window, qtbot, autosave_dir):
    win = make_window()
    _populate(win)
    win.files.autosaver.write_now()
    side = win.files.autosaver.path
    win.close_now(discard_autosave=False)
    # The crashed session's process is gone: give the file the pid of a process that has exited.
    dead = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True
    )
    orphan = side.with_name(f"untitled-{int(dead.stdout)}-deadbeef.mrm.autosave")
    side.rename(orphan)
    win2 = make_window()
    answer_dialog(qtbot, "recoveryDialog", "Recover")
    assert win2.files.check_orphans()
    assert [o.name for o in win2.doc.objects] == ["square", "blob"]
    assert win2.doc.is_modified and win2.doc.path is None
    assert not orphan.exists()
    # Discarding deletes the autosave and keeps the current document.
    win2.files.autosaver.write_now()
    moved = win2.files.autosaver.path.rename(orphan)
    win3 = make_window()
    answer_dialog(qtbot, "recoveryDialog", "Discard")
    assert not win3.files.check_orphans()
    assert len(win3.doc) == 0 and not Path(moved).exists()


def test_export_and_import_round_trip(make_window, qtbot, tmp_path):
    win = make_window()
    _populate(win)
    square, blob = win.doc.objects
    for ext in (".png", ".npz", ".geojson", ".wkt", ".svg"):
        assert win.files.export(square.id, tmp_path / f"sq{ext}"), ext
    assert win.files.export(blob.id, tmp_path / "blob.png")
    win2 = make_window()
    assert win2.files.import_files(
        [tmp_path / "sq.png", tmp_path / "sq.geojson", tmp_path / "sq.wkt", tmp_path / "blob.png"]
    )
    objs = win2.doc.objects
    assert len(objs) == 4
    assert win2.doc.history.index == 1  # one undo step for the whole import
    disc = win.doc.derived(square.id).get("discrete")
    assert objs[0].source == disc  # pixels come back on their place on the grid
    # GeoJSON orients rings as RFC 7946 asks; the coordinates themselves come back bit for bit.
    for o in objs[1:3]:
        assert shapely.normalize(o.source).equals_exact(shapely.normalize(SQUARE), 0)
    assert objs[3].source == blob.source
    assert "<svg" in (tmp_path / "sq.svg").read_text()
    win2.registry["edit.undo"].trigger()
    assert len(win2.doc) == 0


def test_a_bad_import_is_reported_and_adds_nothing(make_window, tmp_path):
    win = make_window()
    (tmp_path / "bad.geojson").write_text(
        '{"type": "Polygon", "coordinates": [[[0, 0], [1, 1], [0, 1], [1, 0], [0, 0]]]}'
    )
    (tmp_path / "bad.png").write_bytes(b"not a png")
    assert not win.files.import_files([tmp_path / "bad.geojson", tmp_path / "bad.png"])
    assert len(win.doc) == 0
    text = _error_boxes(win)[-1].informativeText()
    assert "bad.geojson" in text and "bad.png" in text


def _drag_enter(pos: QtCore.QPointF, mime: QtCore.QMimeData) -> QtGui.QDragEnterEvent:
    args = (
        QtCore.Qt.DropAction.CopyAction,
        mime,
        QtCore.Qt.MouseButton.LeftButton,
        QtCore.Qt.KeyboardModifier.NoModifier,
    )
    try:  # PySide6 ≥ 6.12 takes a QPointF (the QPoint form is deprecated there)
        return QtGui.QDragEnterEvent(pos, *args)
    except TypeError:
        return QtGui.QDragEnterEvent(pos.toPoint(), *args)


def _drop(win, paths) -> bool:  # type: ignore[no-untyped-def]
    """Drag files over the window and drop them, as a file manager does."""
    mime = QtCore.QMimeData()
    mime.setUrls([QtCore.QUrl.fromLocalFile(str(p)) for p in paths])
    pos = QtCore.QPointF(win.width() / 2, win.height() / 2)
    buttons, mods = QtCore.Qt.MouseButton.LeftButton, QtCore.Qt.KeyboardModifier.NoModifier
    enter = _drag_enter(pos, mime)
    QtWidgets.QApplication.sendEvent(win, enter)
    if not enter.isAccepted():
        return False
    drop = QtGui.QDropEvent(pos, QtCore.Qt.DropAction.CopyAction, mime, buttons, mods)
    QtWidgets.QApplication.sendEvent(win, drop)
    return drop.isAccepted()


def test_dropping_files_on_the_window(make_window, qtbot, tmp_path):
    src = make_window()
    _populate(src)
    assert src.files.export(src.doc.objects[1].id, tmp_path / "blob.png")
    assert src.files.save_as(tmp_path / "d.mrm")
    win = make_window()
    assert _drop(win, [tmp_path / "blob.png"])
    qtbot.waitUntil(lambda: len(win.doc) == 1)
    assert win.doc.objects[0].name == "blob"
    answer_dialog(qtbot, "unsavedDialog", "Discard")
    assert _drop(win, [tmp_path / "d.mrm"])
    qtbot.waitUntil(lambda: win.doc.path is not None)
    assert [o.name for o in win.doc.objects] == ["square", "blob"]
    # Something that is not a file (text from another application) is refused.
    mime = QtCore.QMimeData()
    mime.setText("hello")
    enter = _drag_enter(QtCore.QPointF(5, 5), mime)
    QtWidgets.QApplication.sendEvent(win, enter)
    assert not enter.isAccepted()


def test_a_geotiff_keeps_its_place_through_the_window(make_window, tmp_path):
    """Import a GeoTIFF, save, reopen, export: the same transform, CRS and pixels (ADR 0021)."""
    import rasterio
    from rasterio.transform import from_origin

    t = from_origin(500_000.0, 4_200_000.0, 30.0, 30.0)
    mask = np.zeros((10, 12), dtype=np.uint8)
    mask[2:7, 3:10] = 1
    mask[4, 5] = 0
    with rasterio.open(
        tmp_path / "m.tif", "w", driver="GTiff", width=12, height=10, count=1, dtype="uint8",
        transform=t, crs="EPSG:32633",
    ) as ds:  # fmt: skip
        ds.write(mask, 1)
    win = make_window()
    assert win.files.import_files([tmp_path / "m.tif"])
    (obj,) = win.doc.objects
    assert obj.georef is not None and obj.georef.transform == tuple(t)[:6]
    assert win.files.save_as(tmp_path / "p.mrm")
    win2 = make_window()
    assert win2.files.open(tmp_path / "p.mrm", ask=False)
    assert win2.files.export(win2.doc.objects[0].id, tmp_path / "back.tif")
    with rasterio.open(tmp_path / "back.tif") as ds:
        assert ds.transform == t and ds.crs.to_epsg() == 32633 and (ds.width, ds.height) == (12, 10)
        assert (ds.read(1) == mask).all()


def test_export_and_import_run_on_workers_and_round_trip(make_window, qtbot, tmp_path):
    # With the real runner, export and import return at once and finish on a worker (a 10⁸-pixel PNG takes
    # seconds to encode or decode); the file and the objects are the same as with the synchronous runner.
    win = make_window(threaded=True)
    _populate(win)
    square, blob = win.doc.objects
    for ext in (".png", ".geojson"):
        assert win.files.export(square.id, tmp_path / f"sq{ext}") is True
    # Two exports in a row both finish: the second does not cancel the first.
    qtbot.waitUntil(
        lambda: all((tmp_path / f"sq{e}").exists() for e in (".png", ".geojson")), timeout=HANG_MS
    )
    assert win.files.export(blob.id, tmp_path / "blob.png") is True
    qtbot.waitUntil(lambda: (tmp_path / "blob.png").exists(), timeout=HANG_MS)
    win2 = make_window(threaded=True)
    win2.files.import_files([tmp_path / "sq.png", tmp_path / "sq.geojson", tmp_path / "blob.png"])
    qtbot.waitUntil(lambda: len(win2.doc) == 3, timeout=HANG_MS)
    objs = win2.doc.objects
    assert objs[0].source == win.doc.derived(square.id).get("discrete")
    assert shapely.normalize(objs[1].source).equals_exact(shapely.normalize(SQUARE), 0)
    assert objs[2].source == blob.source
    assert win2.doc.history.index == 1  # one undo step for the whole import


# ---------------------------------------------------------------------------------------------- issue 27
def test_ctrl_i_opens_the_import_dialog_and_imports_the_chosen_file(make_window, qtbot, tmp_path):
    """Issue 27: File ▸ Import… and Ctrl+I did nothing (TypeError: an attribute hid the method)."""
    (tmp_path / "triangle.wkt").write_text("POLYGON ((0 0, 8 0, 0 6, 0 0))")
    win = make_window()
    win.prefs.last_directory = str(tmp_path)
    seen = answer_file_dialog(qtbot, "importDialog", tmp_path / "triangle.wkt")
    qtbot.keyClick(win.views.discrete.plane, Qt.Key.Key_I, CTRL)
    assert seen["title"] == "Import" and Path(str(seen["folder"])) == tmp_path
    qtbot.waitUntil(lambda: len(win.doc) == 1, timeout=10_000)
    (obj,) = win.doc.objects
    assert obj.name == "triangle" and obj.source.equals(Polygon([(0, 0), (8, 0), (0, 6)]))
    assert win.doc.history.undo_label() == "Import triangle"
    # The menu entry is the same action; cancelling its dialog adds nothing and says nothing.
    answer_file_dialog(qtbot, "importDialog", None)
    win.registry["file.import"].trigger()
    assert len(win.doc) == 1 and not _error_boxes(win)


def _activate(qtbot, win) -> None:  # type: ignore[no-untyped-def]
    """Give the window back the activation a closed dialog took (a desktop does; offscreen does not)."""
    win.activateWindow()
    qtbot.waitUntil(lambda: QtWidgets.QApplication.activeWindow() is win, timeout=5000)


def _example_action(win, stem: str) -> QtGui.QAction:  # type: ignore[no-untyped-def]
    (act,) = [a for a in win.examples_menu.actions() if a.text() == stem]
    return act


def test_ctrl_s_on_an_example_asks_for_a_path_and_leaves_the_bundled_file_alone(
    make_window, qtbot, tmp_path, monkeypatch
):
    """Issue 27: Ctrl+S on a bundled example overwrote the installed file without a dialog."""
    from mrm.app.gui import EXAMPLES

    home = tmp_path / "home"
    (home / "Documents").mkdir(parents=True)
    monkeypatch.setenv("HOME", str(home))
    bundled = EXAMPLES / "diamond.mrm"
    before = bundled.read_bytes()
    win = make_window()
    _example_action(win, "diamond").trigger()  # File ▸ Open Example ▸ diamond
    assert win.doc.path is None and len(win.doc) > 0
    assert "Untitled" in win.windowTitle() and "diamond.mrm" in win.windowTitle()
    n = len(win.doc)
    # An edit: select the top object in the list and press Delete.
    view = win.object_list.view
    rect = view.visualRect(win.object_list.model.index(0, 2))
    qtbot.mouseClick(view.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
    qtbot.keyClick(view, Qt.Key.Key_Delete)
    assert len(win.doc) == n - 1 and win.doc.is_modified
    seen = answer_file_dialog(qtbot, "saveDialog", None)  # Save As appears; cancelled
    qtbot.keyClick(win.views.discrete.plane, Qt.Key.Key_S, CTRL)
    assert seen["title"] == "Save project"
    assert Path(str(seen["folder"])) in (home / "Documents", home) and seen["name"] == "diamond.mrm"
    assert bundled.read_bytes() == before and win.doc.is_modified
    mine = tmp_path / "mine.mrm"
    _activate(qtbot, win)
    answer_file_dialog(qtbot, "saveDialog", mine)
    qtbot.keyClick(win.views.discrete.plane, Qt.Key.Key_S, CTRL)
    assert mine.is_file() and bundled.read_bytes() == before
    assert win.doc.path == mine.resolve() and not win.doc.is_modified
    assert win.windowTitle().startswith("mine.mrm")
    # Now titled: Ctrl+S saves in place, with no dialog.
    _activate(qtbot, win)
    qtbot.keyClick(win.views.discrete.plane, Qt.Key.Key_Z, CTRL)  # the deleted object is back
    assert len(win.doc) == n and win.doc.is_modified
    qtbot.keyClick(win.views.discrete.plane, Qt.Key.Key_S, CTRL)
    assert not win.doc.is_modified and bundled.read_bytes() == before


def test_open_example_lists_every_bundled_example_and_opens_an_untitled_copy(make_window, qtbot):
    from mrm.app.gui import EXAMPLES
    from mrm.io.project import load_project

    win = make_window()
    files = sorted(EXAMPLES.glob("*.mrm"))
    assert len(files) >= 5
    assert [a.text() for a in win.examples_menu.actions()] == [p.stem for p in files]
    for p in (files[0], EXAMPLES / "two-polygons.mrm"):
        _example_action(win, p.stem).trigger()
        assert [o.name for o in win.doc.objects] == [o.name for o in load_project(p).objects]
        assert win.doc.path is None and not win.doc.is_modified
        assert win.windowTitle().startswith(f"Untitled (copy of the example {p.name})")
    # An example is not the user's file: not among the recent files, and Save As does not start there.
    assert not win.prefs.recent_files()


def test_recent_files_show_their_folder(make_window, qtbot, tmp_path):
    """Issue 27: two recent files of the same name could not be told apart."""
    win = make_window()
    _populate(win)
    for d in ("first", "second"):
        (tmp_path / d).mkdir()
        assert win.files.save_as(tmp_path / d / "plan.mrm")
    texts = [a.text() for a in win.recent_menu.actions() if a.text().startswith("&")]
    assert texts == [f"&1 plan.mrm — {tmp_path / 'second'}", f"&2 plan.mrm — {tmp_path / 'first'}"]
    tips = [a.toolTip() for a in win.recent_menu.actions() if a.text().startswith("&")]
    assert tips == [str((tmp_path / d / "plan.mrm").resolve()) for d in ("second", "first")]


def test_meshes_and_voxel_volumes_are_imported_and_dropped_as_3d_objects(make_window, qtbot, tmp_path):
    """File ▸ Import and drops read meshes and volumes: a polyhedron, a voxel set and a label volume come in
    as 3D objects (one undo step per import), exactly as the files hold them; a 3-D .npz asks no threshold."""
    import mrm
    from mrm.core.grids import LabelVolume, VoxelSet
    from mrm.geometry.polyhedra import Polyhedron

    octa = Polyhedron(
        [[3, 0, 0], [-3, 0, 0], [0, 3, 0], [0, -3, 0], [0, 0, 3], [0, 0, -3]],
        [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]],
    )
    mrm.write_mesh(octa, tmp_path / "octa.obj")
    z, y, x = np.mgrid[-3:4, -3:4, -3:4]
    ball = VoxelSet(x**2 + y**2 + z**2 <= 9, (10, -3, -3))
    mrm.write_voxels(ball, tmp_path / "ball.nii.gz")
    mrm.write_voxels(ball, tmp_path / "ball.npz")
    labels = np.zeros((2, 3, 4), np.int32)
    labels[0, :, :2], labels[1, 1:, 2:] = 1, 7
    mrm.write_label_volume(LabelVolume(labels, (0, 0, 5)), tmp_path / "parts.npz")

    win = make_window()
    assert win.files.import_files([tmp_path / "octa.obj", tmp_path / "ball.nii.gz"])
    qtbot.waitUntil(lambda: len(win.doc) == 2)
    sources = {o.name: o.source for o in win.doc.objects}
    assert sources["octa"] == octa and sources["ball"] == ball
    assert all(o.dimension == 3 for o in win.doc.objects)
    assert _drop(win, [tmp_path / "ball.npz", tmp_path / "parts.npz"])
    qtbot.waitUntil(lambda: len(win.doc) == 4)
    assert win.findChild(QtWidgets.QDialog, "imageImportDialog") is None  # no threshold asked
    dropped = {o.name: o.source for o in win.doc.objects[2:]}
    assert dropped["ball"] == ball
    assert isinstance(dropped["parts"], LabelVolume) and np.array_equal(dropped["parts"].labels, labels)
    win.doc.history.undo()
    assert len(win.doc) == 2


def test_a_label_volumes_meshes_are_imported_one_object_per_region(make_window, qtbot, tmp_path):
    """An OBJ of `mrm polygonize` (regions sharing their faces: no solid as a whole) comes in as one
    polyhedron object per region, in one undo step; each burns back to its region's voxels under gauss."""
    import mrm
    from mrm.cli import run_cli

    labels = np.zeros((3, 4, 5), np.int32)
    labels[:, :2, :] = 1
    labels[:, 2:, :3] = 2
    np.savez(tmp_path / "seg.npz", labels=labels)
    assert run_cli(["polygonize", str(tmp_path / "seg.npz"), "-o", str(tmp_path / "seg.obj")]) == 0
    win = make_window()
    assert win.files.import_files([tmp_path / "seg.obj"])
    qtbot.waitUntil(lambda: len(win.doc) == 2)
    assert [o.name for o in win.doc.objects] == ["seg label_1_1", "seg label_2_1"]
    for o, label in zip(win.doc.objects, (1, 2), strict=True):
        assert o.dimension == 3
        z, y, x = np.nonzero(labels == label)
        assert mrm.voxelize(o.source, "gauss") == mrm.VoxelSet.from_points(np.stack([x, y, z], axis=1))
    win.doc.history.undo()
    assert len(win.doc) == 0


def test_importing_voxels_into_the_plane_views_brings_the_3d_views_forward_and_back(
    make_window, qtbot, tmp_path
):
    """A voxel file dropped on the plane views was drawn nowhere (empty grids): the 3D views come forward and
    the status bar says F3 goes back; a polygon file dropped then brings the plane views back; a mix of both
    leaves the views as they are."""
    import mrm
    from mrm.core.grids import VoxelSet

    z, y, x = np.mgrid[-3:4, -3:4, -3:4]
    mrm.write_voxels(VoxelSet(x**2 + y**2 + z**2 <= 9, (0, 0, 0)), tmp_path / "ball.npz")
    (tmp_path / "sq.wkt").write_text("POLYGON ((0 0, 4 0, 4 4, 0 4, 0 0))")
    win = make_window()
    three_d = win.registry["view.three_d"]
    assert win.views.dimension == 2
    assert _drop(win, [tmp_path / "ball.npz"])
    qtbot.waitUntil(lambda: len(win.doc) == 1)
    assert win.views.dimension == 3 and three_d.isChecked()
    assert win.status.currentMessage() == "showing the 3D views (F3 for the plane views)"
    assert _drop(win, [tmp_path / "sq.wkt"])
    qtbot.waitUntil(lambda: len(win.doc) == 2)
    assert win.views.dimension == 2 and not three_d.isChecked() and win.views.discrete.isVisible()
    assert win.status.currentMessage() == "showing the plane views (F3 for the 3D views)"
    assert _drop(win, [tmp_path / "sq.wkt", tmp_path / "ball.npz"])
    qtbot.waitUntil(lambda: len(win.doc) == 4)
    assert win.views.dimension == 2
