"""Helpers for driving the real views with the mouse and keyboard, and for reading back what they drew."""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
from PySide6 import QtCore, QtGui, QtWidgets

from mrm.app.main_window import MainWindow
from mrm.core.grids import PixelSet
from mrm.views.base_view import RepresentationView

Qt = QtCore.Qt


def widget_pos(view: RepresentationView, x: float, y: float) -> QtCore.QPoint:
    """Viewport position of the plane point (x, y) in ``view``."""
    return view.plane.map_from_plane(x, y)


def click(
    qtbot,
    view: RepresentationView,
    x: float,
    y: float,
    button=Qt.MouseButton.LeftButton,
    modifiers=Qt.KeyboardModifier.NoModifier,
) -> None:  # type: ignore[no-untyped-def]
    vp = view.plane.viewport()
    pos = widget_pos(view, x, y)
    qtbot.mouseMove(vp, pos)
    qtbot.mouseClick(vp, button, modifiers, pos)


def drag(
    qtbot,
    view: RepresentationView,
    points: Iterable[tuple[float, float]],
    modifiers=Qt.KeyboardModifier.NoModifier,
) -> None:  # type: ignore[no-untyped-def]
    """Press at the first point, move through the others, release at the last (left button)."""
    vp = view.plane.viewport()
    pts = [widget_pos(view, x, y) for x, y in points]
    qtbot.mouseMove(vp, pts[0])
    qtbot.mousePress(vp, Qt.MouseButton.LeftButton, modifiers, pts[0])
    for p in pts[1:]:
        qtbot.mouseMove(vp, p)
    qtbot.mouseRelease(vp, Qt.MouseButton.LeftButton, modifiers, pts[-1])


def send_mouse_move(
    widget: QtWidgets.QWidget, pos: QtCore.QPoint, buttons: Qt.MouseButton = Qt.MouseButton.NoButton
) -> None:
    """A mouse move with ``buttons`` held and no key, sent straight to ``widget``.

    qtbot.mouseMove carries the keyboard modifiers QTest took from the last mouse event it sent (an earlier
    test's Shift-click leaves Shift "held"); a move built here says exactly what is held.
    """
    ev = QtGui.QMouseEvent(
        QtCore.QEvent.Type.MouseMove,
        QtCore.QPointF(pos),
        QtCore.QPointF(widget.mapToGlobal(pos)),
        Qt.MouseButton.NoButton,
        buttons,
        Qt.KeyboardModifier.NoModifier,
    )
    QtCore.QCoreApplication.sendEvent(widget, ev)


def send_wheel(widget: QtWidgets.QWidget, pos: QtCore.QPoint, degrees_x8: int = 240) -> None:
    """A vertical wheel turn at ``pos`` (in eighths of a degree: 120 is one notch), sent to ``widget``."""
    ev = QtGui.QWheelEvent(
        QtCore.QPointF(pos),
        QtCore.QPointF(widget.mapToGlobal(pos)),
        QtCore.QPoint(0, 0),
        QtCore.QPoint(0, degrees_x8),
        Qt.MouseButton.NoButton,
        Qt.KeyboardModifier.NoModifier,
        Qt.ScrollPhase.NoScrollPhase,
        False,
    )
    QtCore.QCoreApplication.sendEvent(widget, ev)


def press_key(qtbot, view: RepresentationView, key, modifiers=Qt.KeyboardModifier.NoModifier) -> None:  # type: ignore[no-untyped-def]
    view.plane.setFocus()
    qtbot.keyClick(view.plane, key, modifiers)


def grab(view: RepresentationView) -> QtGui.QImage:
    """What the view's plot area shows now (device pixels)."""
    view.refresh()
    return view.plane.viewport().grab().toImage()


def colour_at(
    view: RepresentationView, x: float, y: float, image: QtGui.QImage | None = None
) -> QtGui.QColor:
    """Colour drawn at the plane point (x, y)."""
    img = image if image is not None else grab(view)
    p = widget_pos(view, x, y)
    dpr = img.devicePixelRatio()
    return img.pixelColor(int(p.x() * dpr), int(p.y() * dpr))


def is_background(view: RepresentationView, c: QtGui.QColor) -> bool:
    base = view.plane.backgroundBrush().color()
    return abs(c.red() - base.red()) + abs(c.green() - base.green()) + abs(c.blue() - base.blue()) < 40


def wait_drawn(qtbot, win: MainWindow, timeout: int | None = None) -> None:  # type: ignore[no-untyped-def]
    """Wait until every view shows the document (its derivations done): however long a machine takes."""
    qtbot.waitUntil(win.is_drawn, timeout=HANG_MS if timeout is None else timeout)


def zoom_to(win: MainWindow, xmin: float, ymin: float, xmax: float, ymax: float) -> None:
    win.views.camera.fit((xmin, ymin, xmax, ymax), margin=0.0)
    QtWidgets.QApplication.processEvents()


def shown_dialog(qtbot, object_name: str) -> QtWidgets.QDialog:  # type: ignore[no-untyped-def]
    """The modal dialog named ``object_name`` once it is the active modal widget (waits up to 5 s)."""
    found: list[QtWidgets.QDialog] = []

    def shown() -> bool:
        w = QtWidgets.QApplication.activeModalWidget()
        if w is not None and w.objectName() == object_name:
            found.append(w)
        return bool(found)

    qtbot.waitUntil(shown, timeout=5000)
    return found[0]


def _when_modal(kind: type, object_name: str, act) -> None:  # type: ignore[no-untyped-def]
    """Call ``act(widget)`` once the active modal widget is a ``kind`` named ``object_name``."""
    tries = [0]

    def poll() -> None:
        tries[0] += 1
        if tries[0] > 1000:  # ~10 s: give up rather than poll into the next test
            return
        w = QtWidgets.QApplication.activeModalWidget()
        if isinstance(w, kind) and w.objectName() == object_name:
            act(w)
            return
        QtCore.QTimer.singleShot(10, poll)

    QtCore.QTimer.singleShot(0, poll)


def answer_dialog(qtbot, object_name: str, button_text: str) -> list[str]:  # type: ignore[no-untyped-def]
    """Click ``button_text`` in the next modal QMessageBox named ``object_name``; returns its texts."""
    seen: list[str] = []

    def act(w: QtWidgets.QMessageBox) -> None:
        seen.extend([w.text(), w.informativeText()])
        for b in w.buttons():
            if b.text().replace("&", "") == button_text:
                b.click()
                return
        raise AssertionError(f"no button {button_text!r} in {[b.text() for b in w.buttons()]}")

    _when_modal(QtWidgets.QMessageBox, object_name, act)
    return seen


def answer_file_dialog(qtbot, object_name: str, path=None) -> dict[str, object]:  # type: ignore[no-untyped-def]
    """Answer the next modal file dialog named ``object_name``.

    With ``path``: pick that file (its folder shown, its name in the name field) and click Open or Save;
    with None: press Escape (cancel). Returns what the dialog showed first: ``folder`` (its directory),
    ``name`` (the proposed file name) and ``title``, filled once it has been answered. (Typing the path
    would be closer to a user, but the field's completer pops up when the folder listing arrives, at a
    time no test can wait for, and takes the Enter.)
    """
    seen: dict[str, object] = {}

    def act(dlg: QtWidgets.QFileDialog) -> None:
        edit = dlg.findChild(QtWidgets.QLineEdit, "fileNameEdit")
        seen["folder"] = dlg.directory().absolutePath()
        seen["name"] = edit.text() if edit is not None else ""
        seen["title"] = dlg.windowTitle()
        if path is None:
            qtbot.keyClick(dlg, Qt.Key.Key_Escape)
            return
        dlg.selectFile(str(path))
        box = dlg.findChild(QtWidgets.QDialogButtonBox)
        assert box is not None, "not Qt's own file dialog (a native one?)"
        accept = QtWidgets.QDialogButtonBox.ButtonRole.AcceptRole
        (ok,) = [b for b in box.buttons() if box.buttonRole(b) == accept]
        qtbot.mouseClick(ok, Qt.MouseButton.LeftButton)

    _when_modal(QtWidgets.QFileDialog, object_name, act)
    return seen


def square(x0: int, y0: int, n: int = 6) -> PixelSet:
    """An n×n block of pixels with its bottom-left pixel at (x0, y0)."""
    return PixelSet(np.ones((n, n), bool), (x0, y0))


def type_into(qtbot, field, text: str) -> None:  # type: ignore[no-untyped-def]
    """Replace a line edit's text as a user does: select all, type, press Enter."""
    field.setFocus()
    qtbot.keyClick(field, Qt.Key.Key_A, Qt.KeyboardModifier.ControlModifier)
    qtbot.keyClicks(field, text)
    qtbot.keyClick(field, Qt.Key.Key_Return)


#: How long a test waits for the signal that ends slow work before calling it a hang. A hang detector, far
#: beyond what any machine takes (a loaded one included): the wait itself ends when the signal comes.
HANG_MS = 900_000


def click_object(qtbot, win: MainWindow, obj: str | int, modifiers=Qt.KeyboardModifier.NoModifier) -> None:  # type: ignore[no-untyped-def]
    """Click an object's name in the object list, as a user selects it (``obj``: its name or its id)."""
    from mrm.views.object_list import COL_NAME

    obj_id = win.doc.find(obj)[0].id if isinstance(obj, str) else obj
    model, view = win.object_list.model, win.object_list.view
    index = model.index(model.row_of(obj_id), COL_NAME)
    view.scrollTo(index)
    qtbot.mouseClick(view.viewport(), Qt.MouseButton.LeftButton, modifiers, view.visualRect(index).center())


def task_done(qtbot, runner, slot: str):  # type: ignore[no-untyped-def]
    """``with task_done(qtbot, win.runner, "operation"): click…`` waits until the task of ``slot`` ends.

    However it ends (result, error, cancel): on the runner's signal, not on the machine's speed.
    """
    return qtbot.waitSignal(
        runner.taskDone, timeout=HANG_MS, check_params_cb=lambda done_slot, _outcome: done_slot == slot
    )


def wait_idle(qtbot, runner) -> None:  # type: ignore[no-untyped-def]
    """Wait until the runner has no task left: on its ``idle`` signal, not on the machine's speed."""
    if runner.is_busy():
        with qtbot.waitSignal(runner.idle, timeout=HANG_MS):
            pass


def record_gui_thread_calls(monkeypatch, owner, name: str) -> list[bool]:  # type: ignore[no-untyped-def]
    """Wrap ``owner.name``: each call appends whether it ran on the GUI (main) thread, then runs it."""
    import threading

    calls: list[bool] = []
    real = getattr(owner, name)

    def recording(*args, **kwargs):  # type: ignore[no-untyped-def]
        calls.append(threading.current_thread() is threading.main_thread())
        return real(*args, **kwargs)

    monkeypatch.setattr(owner, name, recording)
    return calls
