"""The Properties panel: typed name, colour, opacity and vertex coordinates, each one undo step."""

from __future__ import annotations

import numpy as np
from PySide6 import QtCore, QtGui, QtWidgets
from shapely.geometry import Polygon

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from tests.app.helpers import HANG_MS, click_object, type_into

Qt = QtCore.Qt
CTRL_SHIFT = Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier


def _window_with(make_window, source, name="obj"):  # type: ignore[no-untyped-def]
    win = make_window()
    obj = win.doc.make_object(source, name=name)
    win.doc.push(AddObject(obj, select=True))
    win.registry["edit.properties"].trigger()  # Ctrl+Shift+O shows the panel
    assert win.properties_dock.isVisible()
    return win, obj.id


def _edit_cell(qtbot, table, row: int, col: int, text: str) -> None:  # type: ignore[no-untyped-def]
    """Click a cell of the vertex table, press F2 (edit), type, press Enter."""
    table.scrollTo(table.model().index(row, col))
    rect = table.visualRect(table.model().index(row, col))
    vp = table.viewport()
    qtbot.mouseClick(vp, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, rect.center())
    qtbot.keyClick(table, Qt.Key.Key_F2)

    def editor() -> QtWidgets.QLineEdit | None:
        eds = [e for e in vp.findChildren(QtWidgets.QLineEdit) if e.isVisible()]
        return eds[0] if eds else None

    qtbot.waitUntil(lambda: editor() is not None, timeout=3000)
    editor = editor()
    qtbot.keyClick(editor, Qt.Key.Key_A, Qt.KeyboardModifier.ControlModifier)
    qtbot.keyClicks(editor, text)
    qtbot.keyClick(editor, Qt.Key.Key_Return)
    # The delegate commits on the next turn of the event loop.
    qtbot.waitUntil(lambda: table.state() != QtWidgets.QAbstractItemView.State.EditingState, timeout=3000)
    qtbot.wait(20)  # and pushes the edit after that


def test_typing_a_vertex_coordinate_moves_it_and_ctrl_z_restores_it(make_window, qtbot):
    tri = Polygon([(0, 0), (8, 0), (0, 6)])
    win, oid = _window_with(make_window, tri)
    table = win.properties.table
    model = table.model()
    assert model.rowCount() == 3
    # Shown exactly as stored.
    assert [model.index(r, 3).data() for r in range(3)] == ["0", "8", "0"]
    _edit_cell(qtbot, table, 1, 3, "9.125")
    geom = win.doc.get(oid).source
    assert list(geom.exterior.coords)[:3] == [(0.0, 0.0), (9.125, 0.0), (0.0, 6.0)]
    assert model.index(1, 3).data() == "9.125"
    assert win.doc.history.undo_label() == "Move vertex"
    win.views.discrete.plane.setFocus()
    qtbot.keyClick(win.views.discrete.plane, Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier)
    assert win.doc.get(oid).source.equals_exact(tri, 0)
    assert model.index(1, 3).data() == "8"


def test_a_coordinate_that_makes_the_polygon_cross_itself_is_refused(make_window, qtbot):
    sq = Polygon([(0, 0), (4, 0), (4, 4), (0, 4)])
    win, oid = _window_with(make_window, sq)
    steps = win.doc.history.undo_label()
    # Vertex 1 at (−2, 0): its edge to (4, 4) crosses the edge (0, 4)–(0, 0).
    _edit_cell(qtbot, win.properties.table, 1, 3, "-2")
    assert win.doc.get(oid).source.equals_exact(sq, 0)
    assert "refused" in win.properties.status.text()
    assert win.doc.history.undo_label() == steps  # nothing recorded
    assert win.properties.table.model().index(1, 3).data() == "4"  # the table shows what is stored
    _edit_cell(qtbot, win.properties.table, 2, 4, "abc")
    assert "a coordinate must be a number, got 'abc'" in win.properties.status.text()
    assert win.doc.get(oid).source.equals_exact(sq, 0)


def test_name_colour_and_opacity_fields_push_one_step_each(make_window, qtbot):
    win, oid = _window_with(make_window, PixelSet(np.ones((3, 3), bool), (0, 0)), "before")
    type_into(qtbot, win.properties.name_edit, "after")
    assert win.doc.get(oid).name == "after"
    assert win.object_list.model.obj(0).name == "after"  # the list follows
    type_into(qtbot, win.properties.colour_edit, "#12ab34")
    assert win.doc.get(oid).style.fill == "#12ab34"
    type_into(qtbot, win.properties.opacity.lineEdit(), "25")
    assert win.doc.get(oid).style.opacity == 0.25
    labels = []
    for _ in range(3):
        labels.append(win.doc.history.undo_label())
        win.doc.undo()
    assert labels == ["Change style", "Change style", "Rename"]
    o = win.doc.get(oid)
    assert (o.name, o.style.opacity) == ("before", 0.6)
    type_into(qtbot, win.properties.colour_edit, "green-ish")
    assert "not a colour" in win.properties.status.text()
    assert win.doc.get(oid).style.fill != "green-ish"


def test_a_pixel_objects_vertices_are_those_of_its_continuation(make_window, qtbot):
    win, oid = _window_with(make_window, PixelSet(np.ones((2, 3), bool), (0, 0)))
    qtbot.waitUntil(lambda: win.properties.table.model().rowCount() > 0, timeout=10_000)
    r = win.scene.get(oid, "euclidean")
    xy = np.asarray(r.exterior.coords)[:-1]
    model = win.properties.table.model()
    rows = range(model.rowCount())
    shown = [(float(model.index(k, 3).data()), float(model.index(k, 4).data())) for k in rows]
    assert shown == [tuple(p) for p in xy.tolist()]
    assert "R(A)" in win.properties.vertex_note.text()


def test_delete_in_the_vertex_table_removes_that_vertex_not_the_object(make_window, qtbot):
    pent = Polygon([(0, 0), (4, 0), (5, 3), (2, 5), (-1, 3)])
    win, oid = _window_with(make_window, pent)
    table = win.properties.table
    rect = table.visualRect(table.model().index(2, 3))
    qtbot.mouseClick(
        table.viewport(), Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, rect.center()
    )
    qtbot.keyClick(table, Qt.Key.Key_Delete)
    assert oid in win.doc
    assert list(win.doc.get(oid).source.exterior.coords)[:-1] == [(0, 0), (4, 0), (2, 5), (-1, 3)]
    assert table.model().rowCount() == 4
    win.doc.undo()
    assert win.doc.get(oid).source.equals_exact(pent, 0)


def test_a_big_polygon_is_tabled_on_a_worker_and_edits_the_right_vertex(make_window, qtbot, monkeypatch):
    """A MultiPolygon of 20,000 squares (100,000 coordinates): the table is made off the GUI thread."""
    import threading

    from shapely.geometry import MultiPolygon

    import mrm.views.geometry_edit as ge

    on_gui: list[bool] = []
    original = ge.vertex_table

    def recording(g):  # type: ignore[no-untyped-def]
        on_gui.append(threading.current_thread() is threading.main_thread())
        return original(g)

    monkeypatch.setattr(ge, "vertex_table", recording)

    def square(k: int) -> Polygon:
        x = 3.0 * (k % 200)
        y = 3.0 * (k // 200)
        return Polygon([(x, y), (x + 2, y), (x + 2, y + 2), (x, y + 2)])

    geom = MultiPolygon([square(k) for k in range(20_000)])
    win = make_window(threaded=True)
    obj = win.doc.make_object(geom, name="grid")
    win.doc.push(AddObject(obj, select=True))
    win.registry["edit.properties"].trigger()
    panel = win.properties
    model = panel.table.model()
    qtbot.waitUntil(lambda: model.rowCount() == 80_000, timeout=HANG_MS)
    assert "80000 vertices" in panel.vertex_note.text()
    assert on_gui and not any(on_gui), "the vertex table was made on the GUI thread"
    # Row 4·k + i is vertex i of polygon k: (polygon, ring, index) and its coordinates.
    row = 4 * 12_345 + 2
    assert [model.index(row, c).data() for c in range(3)] == [12_345, 0, 2]
    x, y = 3.0 * (12_345 % 200), 3.0 * (12_345 // 200)
    assert [model.index(row, c).data() for c in (3, 4)] == [str(int(x + 2)), str(int(y + 2))]
    # The status bar counts the same vertices.
    qtbot.waitUntil(lambda: "80\u2009000 vertices" in win.status.figures.text(), timeout=HANG_MS)
    # Typing a coordinate moves that vertex of that polygon only.
    _edit_cell(qtbot, panel.table, row, 3, str(x + 2.5))
    qtbot.waitUntil(lambda: win.doc.history.undo_label() == "Move vertex", timeout=HANG_MS)
    moved = list(win.doc.get(obj.id).source.geoms)
    assert list(moved[12_345].exterior.coords)[2] == (x + 2.5, y + 2)
    assert list(moved[12_344].exterior.coords) == list(square(12_344).exterior.coords)


# ---------------------------------------------------------------------------------------------- issue 27
def _renames(win) -> list[str]:  # type: ignore[no-untyped-def]
    return [c.label for c in win.doc.history.steps() if "Rename" in c.label]


def _two_polygons(make_window):  # type: ignore[no-untyped-def]
    from mrm.app.gui import EXAMPLES

    win = make_window()
    assert win.files.open(EXAMPLES / "two-polygons.mrm", ask=False)
    assert sorted(o.name for o in win.doc.objects) == ["pentagon", "tilted square"]
    return win


def _apply(qtbot, win) -> None:  # type: ignore[no-untyped-def]
    n = len(win.doc)
    qtbot.mouseClick(win.operations.apply_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(win.doc) > n, timeout=30_000)


def _operation(win, name: str) -> None:  # type: ignore[no-untyped-def]
    """Operations ▸ <name> (a menu entry: triggered, as a menu cannot be clicked offscreen)."""
    win.findChild(QtGui.QAction, f"op.{name}").trigger()


def test_applying_a_rotation_twice_renames_no_object(make_window, qtbot):
    """Issue 27: the second Apply named the first result "tilted square" (Edit showed Undo Rename)."""
    win = _two_polygons(make_window)
    click_object(qtbot, win, "tilted square")
    _operation(win, "discrete_rotation")
    _apply(qtbot, win)
    first = win.doc.objects[-1].name
    assert first != "tilted square"
    _apply(qtbot, win)
    names = [o.name for o in win.doc.objects]
    assert len(names) == 4 and len(set(names)) == 4, names
    assert names[:3] == ["pentagon", "tilted square", first]
    assert _renames(win) == [] and "Rename" not in win.doc.history.undo_label()


def test_union_then_corefinement_renames_no_part(make_window, qtbot):
    """Issue 27: after EDu then EDco the part "A ∖ B" was named "EDu" (two objects named EDu)."""
    win = _two_polygons(make_window)
    click_object(qtbot, win, "tilted square")
    click_object(qtbot, win, "pentagon", Qt.KeyboardModifier.ControlModifier)
    _operation(win, "union")
    _apply(qtbot, win)
    made = [o.name for o in win.doc.objects[2:]]
    click_object(qtbot, win, "tilted square")
    click_object(qtbot, win, "pentagon", Qt.KeyboardModifier.ControlModifier)
    _operation(win, "corefine")
    _apply(qtbot, win)
    names = [o.name for o in win.doc.objects]
    assert len(set(names)) == len(names), names  # no two objects share a name
    assert names[2 : 2 + len(made)] == made
    assert _renames(win) == []


def test_a_typed_name_goes_to_its_object_only_when_committed(make_window, qtbot):
    win = make_window()
    a = win.doc.make_object(Polygon([(0, 0), (4, 0), (0, 4)]), name="a")
    b = win.doc.make_object(Polygon([(9, 0), (13, 0), (9, 4)]), name="b")
    win.doc.push(AddObject(a))
    win.doc.push(AddObject(b))
    click_object(qtbot, win, "a")
    win.registry["edit.properties"].trigger()
    field = win.properties.name_edit
    assert field.hasFocus() and field.text() == "a"
    # Leaving the field untouched renames nothing; the field follows the selection.
    click_object(qtbot, win, "b")
    assert field.text() == "b" and _renames(win) == []
    # Typed for b, then the selection changes without the field losing the focus (Ctrl+[): dropped.
    field.setFocus()
    qtbot.keyClicks(field, "XX")
    qtbot.keyClick(field, Qt.Key.Key_BracketLeft, Qt.KeyboardModifier.ControlModifier)
    assert win.scene.primary().name == "a" and field.text() == "a"
    qtbot.keyClick(field, Qt.Key.Key_Tab)  # the focus leaves: nothing to commit
    assert [o.name for o in win.doc.objects] == ["a", "b"] and _renames(win) == []
    # Typed and committed with Enter: that object only, one undo step.
    type_into(qtbot, field, "first")
    assert [o.name for o in win.doc.objects] == ["first", "b"]
    assert win.doc.history.undo_label() == "Rename"


def _click_dock_tab(qtbot, win, title: str) -> None:  # type: ignore[no-untyped-def]
    for bar in win.findChildren(QtWidgets.QTabBar):
        for i in range(bar.count()):
            if bar.tabText(i) == title and bar.isVisible():
                qtbot.mouseClick(bar, Qt.MouseButton.LeftButton, pos=bar.tabRect(i).center())
                return
    raise AssertionError(f"no dock tab {title!r}")


def test_tool_keys_reach_the_views_once_the_properties_tab_is_hidden(make_window, qtbot):
    """Issue 27: the hidden Properties tab kept the keyboard: B over a view typed into the name field."""
    win = make_window()
    win.doc.push(AddObject(win.doc.make_object(Polygon([(0, 0), (4, 0), (0, 4)]), name="tri"), select=True))
    qtbot.keyClick(win.views.discrete.plane, Qt.Key.Key_O, CTRL_SHIFT)  # Object Properties
    assert win.properties.name_edit.hasFocus()
    _click_dock_tab(qtbot, win, "Operations")
    assert not win.properties.name_edit.hasFocus()
    qtbot.mouseMove(win.views.discrete.plane.viewport())
    qtbot.keyClick(QtWidgets.QApplication.focusWidget(), Qt.Key.Key_B)  # where the key goes
    assert win.registry["tool.paint"].isChecked() and win.tools.tool is win.tools.tools["paint"]
    assert [o.name for o in win.doc.objects] == ["tri"] and _renames(win) == []
