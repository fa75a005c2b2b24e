"""Messages that help: a self-crossing drawing is offered a repair or kept for editing (never raw GEOS text,
never lost); the pixel-limit message points at a Preferences entry that exists and works."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6 import QtCore, QtWidgets

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from tests.app.helpers import click, press_key, task_done, zoom_to

Qt = QtCore.Qt

BOWTIE = [(0, 0), (10, 0), (0, 10), (10, 10)]  # the second and fourth edges cross at (5, 5)


def _draw_bowtie(win, qtbot):  # type: ignore[no-untyped-def]
    zoom_to(win, -2, -2, 14, 14)
    win.registry["tool.polygon"].trigger()
    view = win.views.euclidean
    for x, y in BOWTIE:
        click(qtbot, view, x, y, modifiers=Qt.KeyboardModifier.ShiftModifier)
    press_key(qtbot, view, Qt.Key.Key_Return)
    box = win.findChild(QtWidgets.QMessageBox, "repairPolygon")
    assert box is not None and box.isVisible()
    text = box.text() + box.informativeText()
    assert "crosses itself" in text and "Self-intersection" not in text and "[" not in text
    return box


def test_a_self_crossing_drawing_is_repaired_on_request(make_window, qtbot):
    win = make_window()
    box = _draw_bowtie(win, qtbot)
    assert "2 valid polygons" in box.informativeText()
    qtbot.mouseClick(box.findChild(QtWidgets.QPushButton, "repairButton"), Qt.MouseButton.LeftButton)
    assert len(win.doc) == 1
    geom = win.doc.objects[0].source
    assert geom.is_valid and geom.geom_type == "MultiPolygon" and len(geom.geoms) == 2
    assert abs(geom.area - 50.0) < 1e-9  # two triangles of 25 each, meeting at (5, 5)


def test_a_self_crossing_drawing_can_be_kept_for_editing(make_window, qtbot):
    win = make_window()
    box = _draw_bowtie(win, qtbot)
    qtbot.mouseClick(box.findChild(QtWidgets.QPushButton, "keepEditingButton"), Qt.MouseButton.LeftButton)
    assert len(win.doc) == 0
    tool = win.tools.tools["polygon"]
    assert [tuple(p) for p in tool.points] == [tuple(map(float, p)) for p in BOWTIE]  # nothing lost
    # Fix it by hand: drop the last vertex, put it where the outline no longer crosses, close it.
    view = win.views.euclidean
    press_key(qtbot, view, Qt.Key.Key_Backspace)
    press_key(qtbot, view, Qt.Key.Key_Backspace)
    click(qtbot, view, 10, 10, modifiers=Qt.KeyboardModifier.ShiftModifier)
    click(qtbot, view, 0, 10, modifiers=Qt.KeyboardModifier.ShiftModifier)
    press_key(qtbot, view, Qt.Key.Key_Return)
    assert len(win.doc) == 1 and win.doc.objects[0].source.area == 100.0


@pytest.mark.parametrize("threaded", [False, True], ids=["in-process", "worker-process"])
def test_the_pixel_limit_message_points_at_a_preference_that_works(make_window, prefs, qtbot, threaded):
    # With the real runner the refusal comes from a worker process: the error must cross back intact
    # (it once arrived as a TypeError about SizeLimitError's constructor, and no message was shown).
    from mrm.app.preferences_dialog import PIXEL_LIMIT_LABEL, PreferencesDialog

    win = make_window(threaded=threaded)
    a = win.doc.make_object(PixelSet(np.ones((10, 10), bool)), name="A")
    win.doc.push(AddObject(a, select=True))
    # Lower the limit in the dialog, as a user does.
    dlg = PreferencesDialog(prefs, win.registry, win)
    field = dlg.findChild(QtWidgets.QDoubleSpinBox, "prefPixelLimit")
    form = field.parentWidget().layout()
    assert form.labelForField(field).text() == PIXEL_LIMIT_LABEL
    field.setValue(5_000)
    dlg.accept()
    assert prefs.pixel_limit == 5_000
    panel = win.operations
    panel.select_operation("dss")
    panel.control("alpha").set_value(10.0)  # 100 pixels × 100 = 10,000 > 5,000
    n = len(win.doc)
    # Waits for the operation's end, however long a loaded machine takes (a 30 s limit failed there).
    with task_done(qtbot, win.runner, "operation"):
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    assert not panel.is_running() and len(win.doc) == n
    msg = panel.status.text()
    assert "5,000" in msg and f"Preferences ▸ General ▸ {PIXEL_LIMIT_LABEL}" in msg
    assert msg.count(panel.op.title) == 1  # named once, not "DSS_α: DSS_α result would…"
    # Raised again, the same operation runs.
    prefs.pixel_limit = 1_000_000
    with task_done(qtbot, win.runner, "operation"):
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    assert len(win.doc) == n + 1
    # The preference stops at the largest pixel object a document holds; beyond it the message says so
    # instead of pointing at a setting that cannot help.
    from mrm.core.limits import MAX_OBJECT_PIXELS

    dlg = PreferencesDialog(prefs, win.registry, win)
    field = dlg.findChild(QtWidgets.QDoubleSpinBox, "prefPixelLimit")
    field.setValue(10 * MAX_OBJECT_PIXELS)
    assert field.value() == MAX_OBJECT_PIXELS
    dlg.accept()
    assert prefs.pixel_limit == MAX_OBJECT_PIXELS
    win.doc.set_selection([a.id])
    panel.select_operation("dss")
    panel.control("alpha").set_value(2000.0)  # 100 pixels × 2000² = 4·10⁸
    with task_done(qtbot, win.runner, "operation"):
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    assert len(win.doc) == n + 1
    msg = panel.status.text()
    assert f"{MAX_OBJECT_PIXELS:,}" in msg and "the largest pixel object a document holds" in msg
    assert "Preferences" not in msg


def test_the_pixel_limit_message_is_made_from_the_errors_fields(make_window, qtbot):
    """Not by rewriting the model's wording: reworded, the message still says where to raise the limit."""
    from mrm.app.preferences_dialog import PIXEL_LIMIT_LABEL
    from tests.app import process_job_fixtures as jobs

    win = make_window()
    a = win.doc.make_object(PixelSet(np.ones((10, 10), bool)), name="A")
    win.doc.push(AddObject(a, select=True))
    panel = win.operations
    panel.select_operation("dss")
    panel.plan_job = jobs.over_limit_reworded  # the job the window hands the panel
    with task_done(qtbot, win.runner, "operation"):
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    msg = panel.status.text()
    assert "10,000 pixels, more than the limit of 5,000" in msg, msg
    assert f"raise the limit in File ▸ Preferences ▸ General ▸ {PIXEL_LIMIT_LABEL}" in msg
