"""Importing grey, colour and label images asks once: threshold (Otsu shown, adjustable, previewed), invert,
or one object per label. Binary images import without a question."""

from __future__ import annotations

import numpy as np
from PIL import Image
from PySide6 import QtCore, QtWidgets

from mrm.core.grids import PixelSet
from mrm.core.threshold import otsu_threshold
from tests.app.helpers import HANG_MS

Qt = QtCore.Qt


def _grey_png(path):  # type: ignore[no-untyped-def]
    yy, xx = np.mgrid[0:20, 0:30]
    g = np.full((20, 30), 40, np.uint8)
    g[(xx - 10) ** 2 + (yy - 10) ** 2 < 36] = 200
    g[(xx - 22) ** 2 + (yy - 9) ** 2 < 16] = 120
    Image.fromarray(g, "L").save(path)
    return g


def _dialog(win):  # type: ignore[no-untyped-def]
    dlg = win.files.image_dialog
    assert dlg is not None and dlg.isVisible()
    return dlg


def _click(qtbot, w):  # type: ignore[no-untyped-def]
    qtbot.mouseClick(w, Qt.MouseButton.LeftButton, pos=QtCore.QPoint(8, w.height() // 2))


def _expected(g: np.ndarray, keep: np.ndarray) -> PixelSet:
    # Image row 0 is the top row; pixel (x, y) has y up from the bottom row.
    return PixelSet(keep[::-1], (0, 0))


def test_a_grey_image_asks_for_the_threshold_with_otsu_shown(make_window, qtbot, tmp_path):
    win = make_window()
    g = _grey_png(tmp_path / "grey.png")
    assert win.files.import_files([tmp_path / "grey.png"]) is False  # waits for the answer
    dlg = _dialog(win)
    otsu = otsu_threshold(np.bincount(g.ravel(), minlength=256))
    assert dlg.description.text().startswith("grey.png is a grey image (30 × 20")
    assert dlg.otsu_button.text() == f"Otsu: {otsu}" and dlg.spin.value() == otsu
    before = dlg.summary.text()
    # Adjust: a threshold above 120 keeps only the bright disc; the preview says so before importing.
    dlg.spin.setFocus()
    qtbot.keyClick(dlg.spin, Qt.Key.Key_A, Qt.KeyboardModifier.ControlModifier)
    qtbot.keyClicks(dlg.spin, "150")
    qtbot.keyClick(dlg.spin, Qt.Key.Key_Tab)
    assert dlg.spin.value() == 150 and dlg.slider.value() == 150
    assert dlg.summary.text() != before and f"{int((g > 150).sum()):,} pixels" in dlg.summary.text()
    qtbot.mouseClick(dlg.findChild(QtWidgets.QPushButton, "importButton"), Qt.MouseButton.LeftButton)
    assert len(win.doc) == 1
    assert win.doc.objects[0].source == _expected(g, g > 150)
    assert win.files.image_dialog is None  # asked once


def test_invert_imports_the_dark_pixels(make_window, qtbot, tmp_path):
    win = make_window()
    g = _grey_png(tmp_path / "grey.png")
    win.files.import_files([tmp_path / "grey.png"])  # its values are looked at on a worker too
    qtbot.waitUntil(lambda: win.files.image_dialog is not None, timeout=30_000)
    dlg = _dialog(win)
    _click(qtbot, dlg.invert)
    assert dlg.invert.isChecked()
    t = dlg.spin.value()
    qtbot.mouseClick(dlg.findChild(QtWidgets.QPushButton, "importButton"), Qt.MouseButton.LeftButton)
    assert win.doc.objects[0].source == _expected(g, g <= t)


def test_one_object_per_label(make_window, qtbot, tmp_path):
    win = make_window()
    lab = np.zeros((10, 12), np.uint8)
    lab[1:4, 1:4] = 1
    lab[5:9, 2:5] = 2
    lab[2:8, 7:11] = 7
    Image.fromarray(lab, "L").save(tmp_path / "labels.png")
    win.files.import_files([tmp_path / "labels.png"])
    dlg = _dialog(win)
    _click(qtbot, dlg.labels_mode)
    assert dlg.labels_mode.isChecked() and "3 objects" in dlg.summary.text()
    qtbot.mouseClick(dlg.findChild(QtWidgets.QPushButton, "importButton"), Qt.MouseButton.LeftButton)
    assert len(win.doc) == 3
    for o, v in zip(win.doc.objects, (1, 2, 7), strict=True):
        assert o.source == _expected(lab, lab == v)
        assert o.name == f"labels label {v}"


def test_a_grey_pgm_asks_too_and_its_labels_import(make_window, qtbot, tmp_path):
    # A grey PGM was Otsu-thresholded with no question (the dialog looked at PNG and NPZ only).
    win = make_window()
    lab = np.zeros((6, 9), np.uint8)
    lab[1:3, 1:4] = 3
    lab[3:5, 5:8] = 9
    lab[0, 8] = 200
    (tmp_path / "grey.pgm").write_bytes(b"P5 9 6 255\n" + lab.tobytes())
    assert win.files.import_files([tmp_path / "grey.pgm"]) is False  # waits for the answer
    dlg = _dialog(win)
    assert dlg.labels_mode.isEnabled() and dlg.map_mode.isEnabled()
    _click(qtbot, dlg.labels_mode)
    assert "3 objects" in dlg.summary.text()
    qtbot.mouseClick(dlg.findChild(QtWidgets.QPushButton, "importButton"), Qt.MouseButton.LeftButton)
    assert [o.name for o in win.doc.objects] == ["grey label 3", "grey label 9", "grey label 200"]
    for o, v in zip(win.doc.objects, (3, 9, 200), strict=True):
        assert o.source == _expected(lab, lab == v)
    # The same file as a threshold: the pixels above it, as PNG gives them.
    win.files.import_files([tmp_path / "grey.pgm"])
    dlg = _dialog(win)
    dlg.spin.setValue(5)
    qtbot.mouseClick(dlg.findChild(QtWidgets.QPushButton, "importButton"), Qt.MouseButton.LeftButton)
    assert win.doc.objects[-1].source == _expected(lab, lab > 5)


def test_a_colour_image_offers_no_labels_and_cancel_adds_nothing(make_window, qtbot, tmp_path):
    win = make_window()
    rgb = np.zeros((8, 8, 3), np.uint8)
    rgb[2:6, 2:6] = (250, 40, 40)
    rgb[0:2, :] = (20, 200, 20)
    Image.fromarray(rgb, "RGB").save(tmp_path / "colour.png")
    win.files.import_files([tmp_path / "colour.png"])
    dlg = _dialog(win)
    assert not dlg.labels_mode.isEnabled()
    dlg.reject()
    assert len(win.doc) == 0 and "cancelled" in win.statusBar().currentMessage()


def test_a_binary_image_imports_without_a_question(make_window, tmp_path):
    win = make_window()
    m = np.zeros((6, 6), np.uint8)
    m[1:5, 2:4] = 255
    Image.fromarray(m, "L").save(tmp_path / "bin.png")
    assert win.files.import_files([tmp_path / "bin.png"]) is True
    assert win.files.image_dialog is None and len(win.doc) == 1


def test_a_big_image_is_read_on_a_worker_and_added_as_one_step(make_window, qtbot, tmp_path):
    # Decoding a 10⁷-pixel image took 0.4 s on the GUI thread (1.5 s at 10⁸): the window froze. The file is
    # read on a worker now; the object arrives as one undo step, with the dialog's choice applied there too.
    win = make_window(threaded=True)
    yy, xx = np.mgrid[0:3000, 0:3000]
    disc = (xx - 1500) ** 2 + (yy - 1500) ** 2 < 1400**2
    Image.fromarray(disc).save(tmp_path / "big.png")
    assert win.files.import_files([tmp_path / "big.png"]) is True
    assert len(win.doc) == 0  # not read yet: the call returned at once
    qtbot.waitUntil(lambda: len(win.doc) == 1, timeout=HANG_MS)
    assert win.doc.objects[0].source == _expected(disc, disc)
    assert win.doc.history.undo_label() == "Import big"
    g = _grey_png(tmp_path / "grey.png")
    win.files.import_files([tmp_path / "grey.png"])  # its values are looked at on a worker too
    qtbot.waitUntil(lambda: win.files.image_dialog is not None, timeout=HANG_MS)
    dlg = _dialog(win)
    _click(qtbot, dlg.invert)
    t = dlg.spin.value()
    qtbot.mouseClick(dlg.findChild(QtWidgets.QPushButton, "importButton"), Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(win.doc) == 2, timeout=HANG_MS)
    assert win.doc.objects[1].source == _expected(g, g <= t)
