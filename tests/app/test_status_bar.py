"""The status bar (issue 27): a task's whole message while it runs; a hint never running into the figures."""

from __future__ import annotations

import sys
import types

from PySide6 import QtCore, QtGui, QtWidgets

from mrm.document.commands import AddObject
from tests.app import process_job_fixtures as jobs
from tests.app.helpers import HANG_MS, square

Qt = QtCore.Qt


def test_the_status_bar_shows_the_running_operations_whole_message(make_window, qtbot):
    """The issue: the progress text of an operation was one letter ("c" of "continuing R(A)")."""
    win = make_window(threaded=True, size=(1360, 880))  # the window's default size
    a = win.doc.make_object(square(0, 0), name="A")
    win.doc.push(AddObject(a, select=True))
    panel, status = win.operations, win.status
    panel.select_operation("dss")
    panel.plan_job = jobs.planning_until_cancelled  # the job the window hands the panel, slow here
    with qtbot.waitSignal(status._show_timer.timeout, timeout=HANG_MS):  # the progress shows after 250 ms
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    with qtbot.waitSignal(
        win.runner.progressChanged, timeout=HANG_MS, check_params_cb=lambda _l, _f, m: m == "continuing R(A)"
    ):
        pass
    whole = f"{panel.op.title}: continuing R(A)"
    assert status.progress_box.isVisible() and status.progress_label.isVisible()
    assert status.progress_label.text() == whole
    # Drawn whole, not cut, once the status bar has laid out the new text (a layout pass, posted).
    qtbot.waitUntil(lambda: status.progress_label.displayed_text() == whole, timeout=HANG_MS)
    # It is drawn: the label's picture holds text across the message's width, not one letter's.
    img = status.progress_label.grab().toImage()
    inked = [x for x in range(img.width()) if _column_has_ink(img, x)]
    assert inked and inked[-1] - inked[0] > 0.8 * status.fontMetrics().horizontalAdvance(whole)
    with qtbot.waitSignal(win.runner.taskDone, timeout=HANG_MS):
        qtbot.mouseClick(status.cancel_button, Qt.MouseButton.LeftButton)
    assert "cancelled" in panel.status.text() and len(win.doc) == 1


def _column_has_ink(img: QtGui.QImage, x: int) -> bool:
    base = img.pixelColor(0, 0)
    return any(abs(img.pixelColor(x, y).lightness() - base.lightness()) > 60 for y in range(img.height()))


def test_a_long_hint_is_elided_before_the_figures_never_drawn_into_them(make_window, qtbot):
    win = make_window(size=(1000, 700))
    a = win.doc.make_object(square(0, 0), name="A rather long object name")
    win.doc.push(AddObject(a, select=True))
    status = win.status
    qtbot.waitUntil(lambda: "pixels" in status.figures.text(), timeout=HANG_MS)
    # The polygon tool's hint, as its key shows it.
    win.views.discrete.plane.setFocus()
    qtbot.keyClick(win.views.discrete.plane, Qt.Key.Key_P)
    hint = status.currentMessage()
    assert hint.startswith("Click to add vertices")
    QtCore.QCoreApplication.processEvents()
    # Nothing is drawn in the gap before the figures (the hint ran into them).
    fig = status.figures.geometry()
    img = status.grab().toImage()
    dpr = img.devicePixelRatio()
    gap = range(int((fig.left() - 3) * dpr), int(fig.left() * dpr))
    assert not any(_column_has_ink(img, x) for x in gap)
    # The hint is a widget of its own beside the figures, elided, whole in its tooltip.
    assert status.hint.text() == hint and status.hint.geometry().right() < fig.left()
    shown = status.hint.displayed_text()
    assert shown != hint and shown.endswith("…") and status.hint.toolTip() == hint


def _painters_left_active(widget: QtWidgets.QWidget) -> list[str]:
    """Repaint ``widget`` while keeping every paintEvent's frame alive past its return, as a sampling profiler
    does (``sys._current_frames``); return the classes whose painter was still active afterwards."""
    kept: list[types.FrameType] = []

    def profile(frame: types.FrameType, event: str, _arg: object) -> None:
        if event == "return" and frame.f_code.co_name == "paintEvent":
            kept.append(frame)

    sys.setprofile(profile)
    try:
        widget.repaint()
    finally:
        sys.setprofile(None)
    left = []
    for frame in kept:
        for value in frame.f_locals.values():
            if isinstance(value, QtGui.QPainter) and value.isActive():
                left.append(type(frame.f_locals["self"]).__name__)
    assert kept, "no paintEvent of ours ran"
    return left


def test_a_paint_ends_its_painter_even_when_its_frame_is_kept(make_window, qtbot):
    """A painter left to the garbage collector stays active while anything holds its frame: under a sampling
    profiler the status bar's next paint found it active, Qt warned "endPaint() called with active painter",
    and the window crashed (a segmentation fault) while a task reported its progress."""
    win = make_window(size=(1000, 700))
    status = win.status
    status.set_busy(True)
    status._show_progress(True)
    status.set_progress("DSS", 0.5, "continuing R(A)")
    qtbot.waitUntil(lambda: status.progress_label.isVisible(), timeout=HANG_MS)
    assert _painters_left_active(status) == []
    assert _painters_left_active(status.progress_label) == []
