"""The issue's list of wrong or missing things, each driven through the real widgets.

Typed values are validated with the range shown and never rewritten; Ctrl+Y and Ctrl+Shift+Z redo; the
panel's model follows Edit ▸ Discretization Model; SVG export uses the object's colour; result names are
unique and readable; empty parts are reported, not created; the toolbar keeps short labels; F1 shows the
guide inside the application; the first Save As does not open the bundled examples; the window's
QWidget.actions() is not shadowed.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from PySide6 import QtCore, QtWidgets

from mrm.document.commands import AddObject
from tests.app.helpers import answer_file_dialog, square, type_into

Qt = QtCore.Qt


def _with_object(win, n: int = 6, name: str = "A"):  # type: ignore[no-untyped-def]
    a = win.doc.make_object(square(0, 0, n), name=name)
    win.doc.push(AddObject(a, select=True))
    return a


# ---------------------------------------------------------------------------------------------- fields
@pytest.mark.parametrize("typed", ["250000", "1e5", "1e9", "1000000000", "-3", "0", "abc", "-0.5"])
def test_typed_alpha_is_never_rewritten(make_window, qtbot, typed):
    win = make_window()
    _with_object(win)
    panel = win.operations
    panel.select_operation("dss")
    field = panel.control("alpha").field
    type_into(qtbot, field, typed)
    assert field.text() == typed  # exactly what was typed stays in the field
    value = panel.control("alpha").value()
    if typed in ("250000", "1e5"):
        assert value == float(typed) and field.is_valid()  # a large α is taken as typed, not 25 or 15
    else:
        # Out of the registry's declared range [1e-6, 1e6] (1e9 too) or not a number: marked, with the range.
        assert not field.is_valid() and field.property("invalid") is True
        assert "1e+06" in field.error
        # The panel refuses to apply it and says why; the document is untouched.
        n = len(win.doc)
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
        assert len(win.doc) == n
        assert field.error.split(",")[0] in panel.status.text()
    assert panel.control("alpha").range_label.text() == "× [1e−06, 1e+06]"


def test_an_invalid_value_corrected_is_accepted_and_unmarked(make_window, qtbot):
    win = make_window()
    _with_object(win)
    panel = win.operations
    panel.select_operation("dss")
    field = panel.control("alpha").field
    type_into(qtbot, field, "-3")
    assert not field.is_valid()
    type_into(qtbot, field, "3")
    assert field.is_valid() and field.property("invalid") is False
    assert panel.control("alpha").value() == 3.0
    n = len(win.doc)
    qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(win.doc) == n + 1, timeout=30_000)
    assert win.doc.objects[-1].provenance.params["alpha"] == 3.0


# ---------------------------------------------------------------------------------------------- redo
@pytest.mark.parametrize(
    "key, mods",
    [
        (Qt.Key.Key_Y, Qt.KeyboardModifier.ControlModifier),
        (Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier),
    ],
)
def test_ctrl_y_and_ctrl_shift_z_redo(make_window, qtbot, key, mods):
    win = make_window()
    a = _with_object(win)
    qtbot.keyClick(win, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    assert a.id not in win.doc
    qtbot.keyClick(win, key, mods)
    assert a.id in win.doc


# ---------------------------------------------------------------------------------------------- model
def test_the_panel_model_follows_edit_discretization_model(make_window, qtbot):
    win = make_window()
    _with_object(win)
    panel = win.operations
    panel.select_operation("dss")
    assert panel.control("model").value() == "standard"
    win.model_menu.actions()[1].trigger()  # Edit ▸ Discretization Model ▸ supercover
    assert win.doc.model == "supercover"
    assert panel.control("model").value() == "supercover"
    panel.select_operation("discrete_rotation")
    assert panel.control("model").value() == "supercover"


# ---------------------------------------------------------------------------------------------- export
def test_svg_export_uses_the_objects_colour(make_window, tmp_path: Path):
    from mrm.document import Style
    from mrm.document.commands import RestyleObject

    win = make_window()
    a = _with_object(win)
    win.doc.push(RestyleObject(a.id, Style(fill="#12ab34", opacity=0.7)))
    out = tmp_path / "a.svg"
    assert win.files.export(a.id, out)
    text = out.read_text()
    assert 'fill="#12ab34"' in text and 'fill-opacity="0.7"' in text
    assert "#4a90d9" not in text


# ---------------------------------------------------------------------------------------------- names
def test_result_names_are_unique_and_readable_and_empty_parts_are_reported(make_window, qtbot):
    win = make_window()
    doc, panel = win.doc, win.operations
    a = _with_object(win)
    panel.select_operation("dss")
    type_into(qtbot, panel.control("alpha").field, "2")
    for expected in (2, 3):
        n = len(doc)
        doc.set_selection([a.id])
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
        qtbot.waitUntil(lambda n=n: len(doc) == n + 1, timeout=30_000)
        assert len(doc) == expected
    names = [o.name for o in doc.objects]
    assert len(set(names)) == len(names), names
    # Co-refinement of two disjoint objects: A ∩ B is empty, reported and not created; readable names.
    b = doc.make_object(square(40, 40), name="B")
    doc.push(AddObject(b))
    panel.select_operation("corefine")
    panel.inputs[0].setCurrentIndex(panel.inputs[0].findData(a.id))
    panel.inputs[1].setCurrentIndex(panel.inputs[1].findData(b.id))
    n = len(doc)
    qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(doc) > n or "empty" in panel.status.text(), timeout=60_000)
    qtbot.waitUntil(lambda: not panel.is_running(), timeout=60_000)
    new = list(doc.objects[n:])
    assert len(new) == 2  # A ∖ B and B ∖ A
    assert all(len(win.scene.get(o.id, "discrete")) > 0 for o in new)
    assert all("_" not in o.name for o in new), [o.name for o in new]
    assert "A ∩ B" in panel.status.text() and "empty" in panel.status.text()


# ---------------------------------------------------------------------------------------------- layout
def test_toolbar_keeps_short_labels_and_the_window_does_not_widen(make_window, qtbot):
    win = make_window(size=(1024, 700))
    a = _with_object(win)
    panel = win.operations
    panel.select_operation("simplify")
    width = win.width()
    tb = win.findChild(QtWidgets.QToolBar, "toolbar_file")
    button = tb.widgetForAction(win.registry["edit.undo"])
    before = button.sizeHint().width()
    n = len(win.doc)
    win.doc.set_selection([a.id])
    qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(win.doc) == n + 1, timeout=30_000)
    assert button.text() == "Undo"
    assert "Undo" in button.toolTip() and len(button.toolTip()) > len("Undo ")
    assert button.sizeHint().width() == before
    assert win.width() == width


def test_the_window_keeps_qwidget_actions(make_window):
    win = make_window()
    acts = win.actions()
    assert isinstance(acts, list) and win.registry["edit.undo"] in acts


# ---------------------------------------------------------------------------------------------- help
def test_f1_shows_the_user_guide_inside_the_application(make_window, qtbot):
    win = make_window()
    qtbot.keyClick(win, Qt.Key.Key_F1)
    help_win = win.findChild(QtWidgets.QDialog, "helpWindow")
    assert help_win is not None and help_win.isVisible()
    text = help_win.browser.toPlainText()
    assert "MR Modeler" in text and "# " not in text.splitlines()[0]  # rendered, not raw Markdown
    help_win.find.setText("Discretization Model")
    assert help_win.find_next()


def _pictures(browser) -> list[tuple[str, float]]:  # type: ignore[no-untyped-def]
    """(name, shown width) of every picture of a text browser's document."""
    out = []
    block = browser.document().begin()
    while block.isValid():
        it = block.begin()
        while not it.atEnd():
            fmt = it.fragment().charFormat()
            if fmt.isImageFormat():
                img = fmt.toImageFormat()
                out.append((img.name(), img.width()))
            it += 1
        block = block.next()
    return out


def test_the_guide_pictures_fit_the_help_window(make_window, qtbot):
    """Issue 27: the user guide's pictures were wider than the help window (a sideways scroll bar)."""
    win = make_window()
    qtbot.keyClick(win, Qt.Key.Key_F1)
    help_win = win.findChild(QtWidgets.QDialog, "helpWindow")
    browser = help_win.browser
    for width in (520, 820):  # narrowed, then back to its own width
        help_win.resize(width, 600)

        def fitted() -> bool:
            room = browser.viewport().width()
            pics = _pictures(browser)
            return bool(pics) and all(0 < w <= room for _name, w in pics)

        qtbot.waitUntil(fitted, timeout=5000)
    assert browser.horizontalScrollBar().maximum() == 0  # at its own width, nothing is wider than the window


# ---------------------------------------------------------------------------------------------- save as
def test_first_save_as_of_an_example_starts_in_the_users_folder(make_window, qtbot, monkeypatch, tmp_path):
    from mrm.app.gui import default_example

    home = tmp_path / "home"
    (home / "Documents").mkdir(parents=True)
    monkeypatch.setenv("HOME", str(home))
    win = make_window()
    assert win.files.open(default_example(), ask=False)
    seen = answer_file_dialog(qtbot, "saveDialog", None)  # cancelled
    qtbot.keyClick(win, Qt.Key.Key_S, Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier)
    assert Path(str(seen["folder"])) in (home / "Documents", home)
    assert seen["name"] == default_example().stem + ".mrm"


# ---------------------------------------------------------------------------------------------- source column
def test_the_source_column_reads_as_words(make_window, qtbot):
    from mrm.views.object_list import COL_SOURCE

    win = make_window()
    a = _with_object(win)
    panel = win.operations
    panel.select_operation("discrete_rotation")
    type_into(qtbot, panel.control("angle").field, "30")
    win.doc.set_selection([a.id])
    qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(win.doc) == 2, timeout=30_000)
    model = win.object_list.model
    texts = [model.index(r, COL_SOURCE).data() for r in range(model.rowCount())]
    assert "pixels" in texts  # the drawn object
    rot = [t for t in texts if "rotation" in t]
    assert rot == ["pixels · rotation 30°"] and not any("_" in t for t in texts), texts


def test_object_names_are_shown_whole_at_1600_pixels(make_window, qtbot):
    """The issue: object names were cut even at 1600 px. Results of operations keep readable names whole."""
    win = make_window(size=(1600, 1000))
    a = _with_object(win, name="horse")
    panel = win.operations
    panel.select_operation("dss")
    type_into(qtbot, panel.control("alpha").field, "4.5")
    for _ in range(2):
        n = len(win.doc)
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
        qtbot.waitUntil(lambda n=n: len(win.doc) == n + 1, timeout=30_000)
        win.doc.set_selection([win.doc.objects[-1].id])
    panel.select_operation("discrete_rotation")
    n = len(win.doc)
    qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(win.doc) == n + 1, timeout=30_000)
    qtbot.wait(50)  # the list's columns settle
    view = win.object_list.view
    model = view.model()
    from mrm.views.object_list import COL_NAME

    names = []
    for row in range(model.rowCount()):
        index = model.index(row, COL_NAME)
        text = index.data()
        names.append(text)
        room = view.visualRect(index).width() - 2 * view.style().pixelMetric(
            QtWidgets.QStyle.PixelMetric.PM_FocusFrameHMargin
        )
        assert room >= view.fontMetrics().horizontalAdvance(text), (text, room)
    assert sorted(names) == sorted(o.name for o in win.doc.objects) and a.name in names and len(names) == 4
