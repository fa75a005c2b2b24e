"""The honest live preview: off by default and remembered; a grey ghost of the current input and parameters.

The issue: the preview was on at every start, drew results in object colours that mixed with real objects,
counted in Fit All, and went stale (after choosing another input it still showed the old one's result; right
after Apply it previewed the operation applied again to the new result).
"""

from __future__ import annotations

from PySide6 import QtCore

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from mrm.views.scene import GHOST_FILL, GHOST_STYLE
from tests.app.helpers import square, type_into

Qt = QtCore.Qt


def _click_live(qtbot, panel) -> None:  # type: ignore[no-untyped-def]
    qtbot.mouseClick(panel.live, Qt.MouseButton.LeftButton, pos=QtCore.QPoint(8, panel.live.height() // 2))


def _dss_result(panel, src: PixelSet, alpha: float) -> PixelSet:  # type: ignore[no-untyped-def]
    from mrm.ops.registry import run_operation

    spec = panel.op.spec
    return run_operation(spec, [src], spec.params(alpha=alpha)).outputs[0][1]


def test_preview_is_off_by_default_and_the_choice_is_remembered(make_window, prefs, qtbot):
    win = make_window()
    panel = win.operations
    assert not panel.live.isChecked()
    a = win.doc.make_object(square(0, 0), name="A")
    win.doc.push(AddObject(a, select=True))
    panel.select_operation("dss")
    type_into(qtbot, panel.control("alpha").field, "3")
    qtbot.wait(100)
    assert panel.scene.phantoms() == []  # nothing previewed while it is off
    _click_live(qtbot, panel)
    assert prefs.live_preview is True
    # A new window with the same preferences starts with the preview on; opening a project keeps it.
    win2 = make_window(prefs_=prefs)
    assert win2.operations.live.isChecked()
    _click_live(qtbot, win2.operations)
    assert prefs.live_preview is False
    assert not make_window(prefs_=prefs).operations.live.isChecked()


def test_the_ghost_is_grey_listed_nowhere_and_not_counted_by_fit_all(make_window, qtbot):
    win = make_window()
    doc, panel = win.doc, win.operations
    a = doc.make_object(square(100, 100, 4), name="A")
    doc.push(AddObject(a, select=True))
    panel.select_operation("dss")
    _click_live(qtbot, panel)
    type_into(qtbot, panel.control("alpha").field, "20")  # about the origin: far from A, 20× bigger
    expected = _dss_result(panel, a.source, 20.0)
    qtbot.waitUntil(lambda: [p.source for p in panel.scene.phantoms()] == [expected], timeout=30_000)
    ghost = panel.scene.phantoms()[0]
    assert ghost.style == GHOST_STYLE
    assert all(o.style.fill.lower() != GHOST_FILL for o in doc.objects)
    assert GHOST_FILL not in [c.lower() for c in win.host.colours]  # no new object gets the ghost's colour
    assert win.object_list.model.rowCount() == 1  # listed nowhere
    # Drawn in the discrete view in the ghost colour; the region and analytical views do not draw it.
    qtbot.waitUntil(lambda: win.views.discrete.layer(ghost.id) is not None, timeout=5000)
    lut = win.views.discrete.layer(ghost.id).mask._lut
    assert tuple(lut[1][:3]) == (0x9A, 0x9A, 0x9A)
    assert win.views.region.layer(ghost.id) is None and win.views.analytical.layer(ghost.id) is None
    # Fit All frames A only: the ghost (from 2000 to 2080) stays outside.
    win.registry["view.fit"].trigger()
    qtbot.wait(50)
    (x0, x1), (y0, y1) = win.views.discrete.plane.vb.viewRange()
    assert x0 <= 100 and x1 >= 104 and y0 <= 100 and y1 >= 104
    assert x1 < 1000 and y1 < 1000


def test_the_ghost_follows_the_input_and_is_cleared_after_apply(make_window, qtbot):
    win = make_window()
    doc, panel = win.doc, win.operations
    a = doc.make_object(square(0, 0), name="A")
    b = doc.make_object(square(40, 0, 9), name="B")
    doc.push(AddObject(a))
    doc.push(AddObject(b, select=True))
    panel.select_operation("dss")
    _click_live(qtbot, panel)
    type_into(qtbot, panel.control("alpha").field, "2")
    of_b = _dss_result(panel, b.source, 2.0)
    qtbot.waitUntil(lambda: [p.source for p in panel.scene.phantoms()] == [of_b], timeout=30_000)
    assert "on B" in panel.status.text()
    # Another object is selected: at no moment does the old ghost stay; then A's appears.
    doc.set_selection([a.id])
    assert panel.scene.phantoms() == []
    of_a = _dss_result(panel, a.source, 2.0)
    qtbot.waitUntil(lambda: [p.source for p in panel.scene.phantoms()] == [of_a], timeout=30_000)
    assert "on A" in panel.status.text()
    # A parameter changes: the former ghost goes at once.
    type_into(qtbot, panel.control("alpha").field, "3")
    of_a3 = _dss_result(panel, a.source, 3.0)
    qtbot.waitUntil(lambda: [p.source for p in panel.scene.phantoms()] == [of_a3], timeout=30_000)
    # Apply: the result is an object; no ghost of "DSS 3 applied again to the result" follows.
    n = len(doc)
    qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(doc) == n + 1, timeout=30_000)
    qtbot.wait(200)
    assert panel.scene.phantoms() == []
    # Editing a parameter again resumes the preview, of the panel's current input.
    type_into(qtbot, panel.control("alpha").field, "2")
    cur = doc.get(panel.input_ids()[0])
    expected = _dss_result(panel, cur.source, 2.0)
    qtbot.waitUntil(lambda: [p.source for p in panel.scene.phantoms()] == [expected], timeout=30_000)
