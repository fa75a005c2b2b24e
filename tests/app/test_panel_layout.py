"""Panels that show all they hold (issue 27, item 4): the inspector, its provenance list, the Operations
panel after a project switch, the exact vertex coordinates of the Properties panel."""

from __future__ import annotations

from PySide6 import QtCore, QtGui, QtWidgets
from shapely.geometry import Polygon

from mrm.document.commands import AddObject
from mrm.resources import examples_dir
from tests.app.helpers import HANG_MS, answer_dialog, click_object, square, task_done

Qt = QtCore.Qt
FIG09 = examples_dir() / "fig09-10-union-corefinement.mrm"


def _measured_part(make_window, qtbot):  # type: ignore[no-untyped-def]
    win = make_window(size=(1360, 880))  # the window's default size
    assert win.files.open(FIG09, ask=False)
    (obj,) = win.doc.find("EDco: E ∩ E'")
    with qtbot.waitSignal(win.inspector.measureEnded, timeout=HANG_MS) as ended:
        click_object(qtbot, win, obj.id)
    assert ended.args == ["measured"]
    QtWidgets.QApplication.processEvents()
    return win


def test_the_inspectors_picture_and_legend_do_not_overlap(make_window, qtbot):
    """The issue: the picture's tick labels ran under the legend below it."""
    win = _measured_part(make_window, qtbot)
    insp = win.inspector
    plane, legend = insp.plane.geometry(), insp.legend.geometry()
    assert plane.bottom() < legend.top(), (plane, legend)
    # The bottom axis (its tick labels) is inside the picture's own widget.
    axis = insp.plane.getPlotItem().getAxis("bottom")
    bottom = insp.plane.mapFromScene(axis.sceneBoundingRect().bottomLeft()).y()
    assert bottom <= insp.plane.height()


def test_the_provenance_list_shows_whole_rows(make_window, qtbot):
    """The issue: the list showed 2½ rows of a 3-row chain."""
    win = _measured_part(make_window, qtbot)
    tree = win.inspector.chain
    vp = tree.viewport().rect()
    rows = [tree.visualItemRect(tree.topLevelItem(k)) for k in range(tree.topLevelItemCount())]
    assert len(rows) == 3
    assert all(vp.top() <= r.top() and r.bottom() <= vp.bottom() for r in rows), (vp, rows)  # all whole
    assert vp.height() - sum(r.height() for r in rows) < rows[0].height()  # and no half-empty room


def test_a_long_chain_shows_a_whole_number_of_rows(make_window, qtbot):
    from mrm.document.apply import apply_operation
    from mrm.ops.scaling import DSSParams

    win = make_window(size=(1360, 880))
    doc = win.doc
    a = doc.make_object(square(0, 0, 8), name="A")
    doc.push(AddObject(a))
    last = a
    for alpha in (2.0, 0.5) * 4:
        (new,) = apply_operation(doc, "dss", [last.id], DSSParams(alpha=alpha))
        last = doc.get(new)
    with qtbot.waitSignal(win.inspector.measureEnded, timeout=HANG_MS):
        click_object(qtbot, win, last.id)
    tree = win.inspector.chain
    assert tree.topLevelItemCount() == 9
    row = tree.visualItemRect(tree.topLevelItem(0)).height()
    assert tree.viewport().height() == 6 * row  # six whole rows; the others scroll


def test_file_new_clears_the_operation_messages_of_the_previous_project(make_window, qtbot):
    win = make_window()
    a = win.doc.make_object(square(0, 0), name="A")
    win.doc.push(AddObject(a, select=True))
    panel = win.operations
    panel.select_operation("dss")
    with task_done(qtbot, win.runner, "operation"):
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    assert "1 object added" in panel.status.text()
    answer_dialog(qtbot, "unsavedDialog", "Discard")
    qtbot.keyClick(win, Qt.Key.Key_N, Qt.KeyboardModifier.ControlModifier)  # File ▸ New
    assert len(win.doc) == 0
    assert "added" not in panel.status.text() and "DSS" not in panel.status.text()


def test_vertex_coordinates_are_shown_exactly_and_copied_exactly(make_window, qtbot):
    """The user guide promises the stored float64; the issue saw '10.162819…'."""
    x = 10.162819384765625  # a float64 with 17 significant digits
    y = -3.3333333333333335
    win = make_window(size=(1024, 700))
    poly = Polygon([(0, 0), (x, 0.5), (x, y), (0.25, y)])
    obj = win.doc.make_object(poly, name="P")
    win.doc.push(AddObject(obj, select=True))
    qtbot.keyClick(win, Qt.Key.Key_O, Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier)
    table = win.properties.table
    model = table.model()
    qtbot.waitUntil(lambda: model.rowCount() == 4, timeout=HANG_MS)
    QtWidgets.QApplication.processEvents()
    fm = table.fontMetrics()
    for row in range(4):
        for col in (3, 4):
            index = model.index(row, col)
            text = index.data()
            assert float(text) == float(poly.exterior.coords[row][col - 3])  # exactly the stored value
            # Drawn whole: the cell is as wide as the text (no "…").
            assert table.visualRect(index).width() >= fm.horizontalAdvance(text), (
                text,
                table.visualRect(index),
            )
    assert model.index(1, 3).data() == repr(x) and model.index(2, 4).data() == repr(y)
    # Ctrl+C in the table copies the selected cells' exact text (not the object).
    rect = table.visualRect(model.index(2, 3))
    qtbot.mouseClick(table.viewport(), Qt.MouseButton.LeftButton, pos=rect.center())
    qtbot.mouseClick(
        table.viewport(),
        Qt.MouseButton.LeftButton,
        Qt.KeyboardModifier.ShiftModifier,
        table.visualRect(model.index(2, 4)).center(),
    )
    qtbot.keyClick(table, Qt.Key.Key_C, Qt.KeyboardModifier.ControlModifier)
    assert QtGui.QGuiApplication.clipboard().text() == f"{x!r}\t{y!r}"
    assert len(win.doc) == 1
