"""New objects outside the view are brought into it (issue 27, item 4); objects in view move nothing."""

from __future__ import annotations

from PySide6 import QtCore, QtWidgets

from mrm.document.commands import AddObject
from tests.app.helpers import answer_dialog, square, task_done

Qt = QtCore.Qt


def _fully_shown(win, obj_id: int) -> bool:  # type: ignore[no-untyped-def]
    """Every visible view shows the object's whole box."""
    from mrm.views.view_area import object_box

    x0, y0, x1, y1 = object_box(win.scene.source(obj_id))
    for v in win.views.visible_views():
        vp = v.plane.viewport().rect()
        for x, y in ((x0, y0), (x1, y1)):
            if not vp.contains(v.plane.map_from_plane(x, y)):
                return False
    return True


def _camera(win):  # type: ignore[no-untyped-def]
    c = win.views.camera
    return (c.cx, c.cy, c.scale)


def _apply_dss(qtbot, win, alpha: str) -> int:  # type: ignore[no-untyped-def]
    from tests.app.helpers import type_into

    panel = win.operations
    panel.select_operation("dss")
    type_into(qtbot, panel.control("alpha").field, alpha)
    n = len(win.doc)
    with task_done(qtbot, win.runner, "operation"):
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    assert len(win.doc) == n + 1
    return win.doc.objects[-1].id


def test_a_result_outside_the_view_is_brought_into_view(make_window, qtbot):
    win = make_window()
    a = win.doc.make_object(square(0, 0), name="A")
    win.doc.push(AddObject(a, select=True))
    win.fit_all()
    assert _fully_shown(win, a.id)
    big = _apply_dss(qtbot, win, "12")  # 0…72: far beyond the framed square
    assert _fully_shown(win, big) and _fully_shown(win, a.id)  # extended, keeping what was shown


def test_a_new_object_already_in_view_moves_nothing(make_window, qtbot):
    win = make_window()
    a = win.doc.make_object(square(0, 0), name="A")
    win.doc.push(AddObject(a, select=True))
    win.fit_all()
    win.views.camera.zoom(0.5)  # room around it
    before = _camera(win)
    same = _apply_dss(qtbot, win, "1")
    assert _fully_shown(win, same) and _camera(win) == before


def test_a_paste_into_an_empty_document_is_framed(make_window, qtbot):
    win = make_window()
    far = win.doc.make_object(square(900, -700, 10), name="far")
    win.doc.push(AddObject(far, select=True))
    plane = win.views.discrete.plane
    plane.setFocus()
    qtbot.keyClick(plane, Qt.Key.Key_C, Qt.KeyboardModifier.ControlModifier)
    answer_dialog(qtbot, "unsavedDialog", "Discard")
    qtbot.keyClick(win, Qt.Key.Key_N, Qt.KeyboardModifier.ControlModifier)  # File ▸ New
    QtCore.QCoreApplication.processEvents()  # its deferred Fit All of the empty document
    assert len(win.doc) == 0
    win.activateWindow()  # back from the dialog: window shortcuts reach the active window only
    qtbot.waitUntil(lambda: QtWidgets.QApplication.activeWindow() is win, timeout=5000)
    plane.setFocus()
    qtbot.keyClick(plane, Qt.Key.Key_V, Qt.KeyboardModifier.ControlModifier)
    qtbot.waitUntil(lambda: len(win.doc) == 1, timeout=10_000)
    (pasted,) = win.doc.objects
    assert _fully_shown(win, pasted.id)
    # Framed, not merely included: the object spans most of the narrowest view.
    x0, _y0, x1, _y1 = win.views.visible_rect()
    assert (x1 - x0) < 3 * 11
