"""Copy and paste of objects with Ctrl+C / Ctrl+V: our own clipboard format, a GeoJSON/WKT text fallback."""

from __future__ import annotations

import json

import numpy as np
import shapely
from PySide6 import QtCore, QtGui, QtWidgets
from shapely.geometry import Polygon

from mrm.app.clipboard import MIME
from mrm.core.grids import PixelSet
from mrm.document import Style
from mrm.document.commands import AddObject
from tests.app.helpers import HANG_MS

Qt = QtCore.Qt
CTRL = Qt.KeyboardModifier.ControlModifier


def _keys(qtbot, win, key) -> None:  # type: ignore[no-untyped-def]
    plane = win.views.discrete.plane
    plane.setFocus()
    qtbot.keyClick(plane, key, CTRL)


def _clipboard() -> QtGui.QClipboard:
    return QtGui.QGuiApplication.clipboard()


def test_copy_paste_round_trips_objects_exactly_in_one_undo_step(make_window, qtbot):
    win = make_window()
    m = np.ones((7, 7), bool)
    m[2:5, 2:5] = False
    pixels = PixelSet(m, (-3, 11))
    poly = Polygon([(0.1, 0.2), (7 / 3, 0.0), (1e-7, 5.5)])  # floats that text would not keep by accident
    pa = win.doc.make_object(pixels, name="ring", style=Style(fill="#123456", opacity=0.3))
    pb = win.doc.make_object(poly, name="tri")
    win.doc.push(AddObject(pa))
    win.doc.push(AddObject(pb))
    win.doc.set_selection([pa.id, pb.id])
    _keys(qtbot, win, Qt.Key.Key_C)
    md = _clipboard().mimeData()
    assert md.hasFormat(MIME)
    # The text fallback is GeoJSON of the Euclidean representations, with the coordinates as stored.
    fc = json.loads(md.text())
    names = [f["properties"]["name"] for f in fc["features"]]
    assert names == ["ring", "tri"]
    tri = shapely.geometry.shape(fc["features"][1]["geometry"])
    assert tri.equals_exact(poly, 0)
    before = len(win.doc)
    _keys(qtbot, win, Qt.Key.Key_V)
    assert len(win.doc) == before + 2
    new = [win.doc.get(i) for i in win.doc.selection]
    assert sorted(o.name for o in new) == ["ring (2)", "tri (2)"]  # unique names
    by = {o.name: o for o in new}
    assert by["ring (2)"].source == pixels and by["ring (2)"].style == pa.style
    assert shapely.to_wkb(by["tri (2)"].source) == shapely.to_wkb(poly)  # bit for bit
    assert win.doc.history.undo_label() == "Paste 2 objects"
    win.doc.undo()
    assert [o.name for o in win.doc.objects] == ["ring", "tri"]
    # Pasting again gives yet other names.
    _keys(qtbot, win, Qt.Key.Key_V)
    _keys(qtbot, win, Qt.Key.Key_V)
    assert sorted(o.name for o in win.doc.objects) == [
        "ring",
        "ring (2)",
        "ring (3)",
        "tri",
        "tri (2)",
        "tri (3)",
    ]


def test_paste_of_wkt_or_geojson_text_from_another_program(make_window, qtbot):
    win = make_window()
    _clipboard().setText("POLYGON ((0 0, 3 0, 0 4, 0 0))")
    _keys(qtbot, win, Qt.Key.Key_V)
    assert len(win.doc) == 1
    obj = win.doc.objects[0]
    assert obj.kind == "euclidean"
    assert obj.source.equals_exact(Polygon([(0, 0), (3, 0), (0, 4)]), 0)
    gj = {
        "type": "Feature",
        "properties": {"name": "parcel"},
        "geometry": {"type": "Polygon", "coordinates": [[[10, 0], [12.5, 0], [10, 2], [10, 0]]]},
    }
    _clipboard().setText(json.dumps(gj))
    _keys(qtbot, win, Qt.Key.Key_V)
    assert [o.name for o in win.doc.objects][-1] == "parcel"
    assert win.doc.objects[-1].source.equals_exact(Polygon([(10, 0), (12.5, 0), (10, 2)]), 0)


def test_pasted_text_shapes_get_readable_unique_names(make_window, qtbot):
    """Issue 27: a pasted WKT polygon was named after a temporary file ("mrm-paste-lt5dwgqw")."""
    win = make_window()
    _clipboard().setText("POLYGON ((0 0, 3 0, 0 4, 0 0))")
    _keys(qtbot, win, Qt.Key.Key_V)
    _keys(qtbot, win, Qt.Key.Key_V)
    _clipboard().setText("LINESTRING (0 10, 6 13)")  # a line is discretized: a pixel object
    _keys(qtbot, win, Qt.Key.Key_V)
    names = [o.name for o in win.doc.objects]
    assert names == ["Pasted polygon", "Pasted polygon (2)", "Pasted pixels"], names


def test_paste_of_text_that_is_no_shape_says_so_and_changes_nothing(make_window, qtbot):
    win = make_window()
    _clipboard().setText("hello, world")
    _keys(qtbot, win, Qt.Key.Key_V)
    assert len(win.doc) == 0
    assert "paste:" in win.status.currentMessage() and "WKT" in win.status.currentMessage()
    assert not win.doc.history.can_undo()


def test_copy_is_encoded_and_paste_read_on_a_worker(make_window, qtbot, monkeypatch):
    import threading

    import mrm.app.clipboard as clipboard

    on_gui: list[bool] = []
    original = clipboard.objects_from_payload

    def recording(*a):  # type: ignore[no-untyped-def]
        on_gui.append(threading.current_thread() is threading.main_thread())
        return original(*a)

    monkeypatch.setattr(clipboard, "objects_from_payload", recording)
    win = make_window(threaded=True)
    _clipboard().clear()
    ps = PixelSet(np.ones((300, 400), bool), (5, -7))
    o = win.doc.make_object(ps, name="block")
    win.doc.push(AddObject(o, select=True))
    _keys(qtbot, win, Qt.Key.Key_C)

    def copied() -> bool:
        md = _clipboard().mimeData()
        return md is not None and md.hasFormat(MIME)

    qtbot.waitUntil(copied, timeout=HANG_MS)
    _keys(qtbot, win, Qt.Key.Key_V)
    qtbot.waitUntil(lambda: len(win.doc) == 2, timeout=HANG_MS)
    assert on_gui == [False], "the paste was parsed on the GUI thread"
    assert [x.name for x in win.doc.objects] == ["block", "block (2)"]
    assert win.doc.objects[-1].source == ps
    assert win.doc.history.undo_label() == "Paste"


def test_ctrl_c_in_a_text_field_copies_its_text_not_the_objects(make_window, qtbot):
    win = make_window()
    o = win.doc.make_object(Polygon([(0, 0), (3, 0), (0, 4)]), name="tri")
    win.doc.push(AddObject(o, select=True))
    _clipboard().clear()
    win.registry["edit.properties"].trigger()  # focuses the name field, its text selected
    field = win.properties.name_edit
    qtbot.waitUntil(field.hasFocus, timeout=3000)
    qtbot.keyClick(field, Qt.Key.Key_C, CTRL)
    md = _clipboard().mimeData()
    assert md is not None and md.text() == "tri" and not md.hasFormat(MIME)
    qtbot.keyClick(field, Qt.Key.Key_V, CTRL)  # and Ctrl+V pastes text there, not objects
    assert len(win.doc) == 1


def _three_objects(win):  # type: ignore[no-untyped-def]
    pixels = PixelSet(np.ones((3, 4), bool), (-6, 2))
    poly = Polygon([(0.1, 0.2), (7 / 3, 0.0), (1e-7, 5.5)])
    objs = [
        win.doc.make_object(pixels, name="block"),
        win.doc.make_object(poly, name="tri"),
        win.doc.make_object(Polygon([(20, 0), (24, 0), (24, 3)]), name="other"),
    ]
    for o in objs:
        win.doc.push(AddObject(o))
    return objs


def test_cut_copies_then_deletes_in_one_undo_step_and_paste_brings_them_back(make_window, qtbot):
    win = make_window()
    block, tri, other = _three_objects(win)
    win.doc.set_selection([block.id, tri.id])
    _clipboard().clear()
    steps = win.doc.history.index
    _keys(qtbot, win, Qt.Key.Key_X)
    assert [o.name for o in win.doc.objects] == ["other"]
    assert win.doc.history.index == steps + 1  # one undo step
    assert win.doc.history.undo_label() == "Cut 2 objects"
    md = _clipboard().mimeData()
    assert md.hasFormat(MIME)  # Copy's format: the objects as a project file, GeoJSON as text
    assert [f["properties"]["name"] for f in json.loads(md.text())["features"]] == ["block", "tri"]
    _keys(qtbot, win, Qt.Key.Key_V)
    assert [o.name for o in win.doc.objects] == ["other", "block", "tri"]  # their names are free again
    assert win.doc.objects[1].source == block.source
    assert shapely.to_wkb(win.doc.objects[2].source) == shapely.to_wkb(tri.source)  # bit for bit
    assert set(win.doc.selection) == {win.doc.objects[1].id, win.doc.objects[2].id}
    win.registry["edit.undo"].trigger()  # the paste
    win.registry["edit.undo"].trigger()  # the cut: the very objects are back, in their places
    assert win.doc.objects == (block, tri, other)
    assert win.doc.history.index == steps


def test_cut_is_in_the_edit_menu_with_the_standard_key_and_needs_a_selection(make_window, qtbot):
    win = make_window()
    _three_objects(win)
    edit = next(m for m in win.menuBar().findChildren(QtWidgets.QMenu) if m.title() == "&Edit")
    ids = [a.objectName() for a in edit.actions()]
    assert (
        ids.index("edit.cut")
        < ids.index("edit.copy")
        < ids.index("edit.paste")
        < ids.index("edit.select_all")
    )
    assert win.registry["edit.cut"].shortcut().toString() == "Ctrl+X"
    assert win.registry["edit.select_all"].shortcut().toString() == "Ctrl+A"
    win.doc.set_selection([])
    _keys(qtbot, win, Qt.Key.Key_X)
    assert len(win.doc) == 3 and not win.registry["edit.cut"].isEnabled()


def test_a_cut_whose_copy_fails_deletes_nothing(make_window, qtbot, monkeypatch):
    import mrm.io.project
    from mrm.core.errors import FileFormatError

    def refuse(_doc):  # type: ignore[no-untyped-def]
        raise FileFormatError("disk full")

    win = make_window()
    objs = _three_objects(win)
    win.doc.set_selection([objs[0].id])
    monkeypatch.setattr(mrm.io.project, "dumps", refuse)
    steps = win.doc.history.index
    _keys(qtbot, win, Qt.Key.Key_X)
    assert win.doc.objects == tuple(objs)
    assert win.doc.history.index == steps
    assert "disk full" in win.status.currentMessage() and "nothing deleted" in win.status.currentMessage()


def test_ctrl_a_selects_every_object_in_the_document_and_the_list(make_window, qtbot):
    from dataclasses import replace

    from mrm.document.commands import RestyleObject

    win = make_window()
    objs = _three_objects(win)
    win.doc.push(RestyleObject(objs[2].id, replace(objs[2].style, visible=False)))  # hidden ones too
    win.doc.set_selection([objs[0].id])
    _keys(qtbot, win, Qt.Key.Key_A)
    assert win.doc.selection == tuple(o.id for o in objs)
    rows = win.object_list.view.selectionModel().selectedRows()
    assert len(rows) == 3
    # Then Ctrl+X cuts them all.
    _keys(qtbot, win, Qt.Key.Key_X)
    assert len(win.doc) == 0


def test_text_fields_keep_their_own_ctrl_a_and_ctrl_x(make_window, qtbot):
    win = make_window()
    objs = _three_objects(win)
    win.doc.set_selection([objs[1].id])
    _clipboard().clear()
    win.registry["edit.properties"].trigger()  # focuses the name field
    field = win.properties.name_edit
    qtbot.waitUntil(field.hasFocus, timeout=3000)
    qtbot.keyClick(field, Qt.Key.Key_End)
    assert field.selectedText() == ""
    qtbot.keyClick(field, Qt.Key.Key_A, CTRL)
    assert field.selectedText() == "tri"
    assert win.doc.selection == (objs[1].id,)  # not every object
    qtbot.keyClick(field, Qt.Key.Key_X, CTRL)
    assert field.text() == ""
    md = _clipboard().mimeData()
    assert md is not None and md.text() == "tri" and not md.hasFormat(MIME)
    assert win.doc.objects == tuple(objs)  # no object cut
