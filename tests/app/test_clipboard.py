"""Copy and paste of objects with Ctrl+C / Ctrl+V: our own clipboard format, a GeoJSON/WKT text fallback."""

from __future__ import annotations

import json

import numpy as np
import shapely
from PySide6 import QtCore, QtGui
from shapely.geometry import Polygon

from mrm.app.clipboard import MIME
from mrm.commands import AddObject
from mrm.document import Style
from mrm.reps.pixels import PixelSet
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
