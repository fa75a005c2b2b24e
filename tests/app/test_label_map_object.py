"""A label image imported as one label map object (ADR 0033), driven through the real dialog and views.

Its discrete view colours the labels, its region view shows its cells (1-cells and 0-cells), its Euclidean
view the watertight gauss subdivision (each shared boundary stroked once), the analytical view says it has
no segments of its own; it is saved and reopened, exported as one GeoJSON Feature per region, split into one
object per label, and the edits that do not apply say so.
"""

from __future__ import annotations

import json

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from PIL import Image
from PySide6 import QtCore, QtWidgets

from mrm.core.grids import LabelMap
from mrm.document.commands import AddObject
from mrm.geometry.discretize import discretize
from mrm.reps.cells import cells_of
from mrm.views.label_maps import label_colour
from tests.app.helpers import click, colour_at, grab, is_background, wait_drawn, zoom_to

Qt = QtCore.Qt


def _label_png(path):  # type: ignore[no-untyped-def]
    """An indexed PNG: labels 1, 2 (two regions), 3 around a hole, 7 next to 3; rows top first."""
    lab = np.zeros((16, 20), np.uint8)
    lab[1:7, 1:9] = 1
    lab[1:7, 9:18] = 2
    lab[9:15, 1:5] = 2  # a second region of label 2
    lab[8:15, 6:13] = 3
    lab[10:12, 8:10] = 0  # a hole in label 3
    lab[8:15, 13:19] = 7
    im = Image.fromarray(lab, "P")
    im.putpalette([v for k in range(256) for v in (k, 255 - k, (k * 7) % 256)])
    im.save(path)
    return LabelMap(lab[::-1].astype(np.int32), (0, 0))


def _import_map(win, qtbot, tmp_path):  # type: ignore[no-untyped-def]
    lm = _label_png(tmp_path / "parcels.png")
    assert win.files.import_files([tmp_path / "parcels.png"]) is False  # the dialog asks
    dlg = win.files.image_dialog
    assert dlg is not None and dlg.isVisible()
    # An indexed image's values are labels first: the label map is proposed, and the preview says so.
    assert dlg.map_mode.isChecked() and "1 label map object: 4 labels" in dlg.summary.text()
    qtbot.mouseClick(dlg.findChild(QtWidgets.QPushButton, "importButton"), Qt.MouseButton.LeftButton)
    assert len(win.doc) == 1
    obj = win.doc.objects[0]
    assert obj.kind == "labels" and obj.name == "parcels" and obj.source == lm
    return obj, lm


def test_the_import_dialog_calls_an_indexed_png_what_it_is(make_window, qtbot, tmp_path):
    """Issue 27: an indexed (palette) PNG was called a "grey image" in the import dialog."""
    win = make_window()
    _label_png(tmp_path / "parcels.png")
    win.files.import_files([tmp_path / "parcels.png"])
    qtbot.waitUntil(lambda: win.files.image_dialog is not None, timeout=30_000)
    text = win.files.image_dialog.description.text()
    assert text.startswith("parcels.png is an indexed-colour image (20 × 16") and "grey" not in text
    qtbot.keyClick(win.files.image_dialog, Qt.Key.Key_Escape)  # Cancel: nothing imported
    assert win.files.image_dialog is None and len(win.doc) == 0


def test_a_label_image_imports_as_one_label_map_drawn_in_every_view(make_window, qtbot, tmp_path):
    win = make_window()
    obj, lm = _import_map(win, qtbot, tmp_path)
    assert win.doc.history.undo_label() == "Import parcels"
    zoom_to(win, -1, -1, 21, 17)
    wait_drawn(qtbot, win)
    v = win.views
    # Discrete: every pixel in its label's colour, the background left empty.
    shown = grab(v.discrete)
    for x, y in ((3, 12), (12, 12), (2, 3), (7, 4), (15, 4)):
        label = lm.label_at((x, y))
        c = colour_at(v.discrete, x, y, shown)
        assert not is_background(v.discrete, c), (x, y)
        want = QtWidgetsColour(label_colour(lm, label))
        assert _hue_close(c, want), (x, y, label)
    assert is_background(v.discrete, colour_at(v.discrete, 8, 4, shown))  # the hole in label 3
    # Region: the 1-cells and 0-cells of the map.
    cells = cells_of(lm)
    layer = v.region.layer(obj.id)
    assert len(_subpaths(layer.lines.path())) == len(cells.one_cells)
    assert len(layer.points.points()) == len(cells.zero_cells) > 0
    # Euclidean: each label's part filled in its colour, each shared boundary stroked once.
    sd = win.scene.get(obj.id, "euclidean")
    assert sorted(sd.parts) == [1, 2, 3, 7]
    for label, part in sd.parts.items():
        assert discretize(part, "gauss") == lm.pixel_set(label)
    elayer = v.euclidean.layer(obj.id)
    assert len(_subpaths(elayer.lines.path())) == len(sd.polylines) == len(cells.one_cells)
    eshown = grab(v.euclidean)
    c = colour_at(v.euclidean, 12, 12, eshown)
    assert _hue_close(c, QtWidgetsColour(label_colour(lm, 2)))
    # Analytical: nothing drawn, and the view says why.
    click(qtbot, v.discrete, 3, 12)
    assert win.doc.selection == (obj.id,)
    v.analytical.refresh()
    assert "Split into Objects" in v.analytical.status_label.text()
    assert "label map" in v.euclidean.legend_label.text()
    assert "label map" in win.status.figures.text() and "4 labels" in win.status.figures.text()
    # One undo step removes the import; redo brings it back.
    win.registry["edit.undo"].trigger()
    assert len(win.doc) == 0
    win.registry["edit.redo"].trigger()
    assert win.doc.objects[0].source == lm


def QtWidgetsColour(name):  # type: ignore[no-untyped-def]
    from PySide6 import QtGui

    return QtGui.QColor(name)


def _hue_close(a, b) -> bool:  # type: ignore[no-untyped-def]
    """The same colour seen through some transparency over a light background (hue within 12°)."""
    ha, hb = a.hsvHue(), b.hsvHue()
    return ha >= 0 and hb >= 0 and min(abs(ha - hb), 360 - abs(ha - hb)) <= 12


def _subpaths(path):  # type: ignore[no-untyped-def]
    """The polylines of a QPainterPath, as lists of points."""
    out, cur = [], []
    for k in range(path.elementCount()):
        e = path.elementAt(k)
        if e.isMoveTo() and cur:
            out.append(cur)
            cur = []
        cur.append((e.x, e.y))
    if cur:
        out.append(cur)
    return [p for p in out if len(p) > 1]


def test_split_save_reopen_and_export(make_window, qtbot, tmp_path):
    win = make_window()
    obj, lm = _import_map(win, qtbot, tmp_path)
    wait_drawn(qtbot, win)
    # Saved and reopened as it was.
    path = tmp_path / "parcels.mrm"
    assert win.files.save_as(path)
    qtbot.waitUntil(lambda: not win.runner.is_busy("file"), timeout=30_000)
    win2 = make_window()
    assert win2.files.open(path, ask=False)
    qtbot.waitUntil(lambda: len(win2.doc) == 1, timeout=30_000)
    assert win2.doc.objects[0].kind == "labels" and win2.doc.objects[0].source == lm
    # Exported as one GeoJSON Feature per region, with its label and pixel count.
    out = tmp_path / "parcels.geojson"
    assert win.files.export(obj.id, out)
    qtbot.waitUntil(lambda: out.exists(), timeout=30_000)
    fc = json.loads(out.read_text())
    regions = sorted((f["properties"]["label"], f["properties"]["pixels"]) for f in fc["features"])
    assert [r[0] for r in regions] == [1, 2, 2, 3, 7]  # label 2 has two regions
    assert sum(p for lab, p in regions if lab == 2) == lm.pixel_set(2).count
    # A format without labels is refused with what to do instead.
    refused: list[str] = []
    win.files._error = lambda title, text: refused.append(text)  # type: ignore[method-assign]
    assert not win.files.export(obj.id, tmp_path / "parcels.svg")
    assert "GeoJSON" in refused[0] and "Split into Objects" in refused[0]
    # Split into objects: one pixel object per label, one undo step.
    win.doc.set_selection([obj.id])
    win.update_action_states()
    assert win.registry["edit.split_labels"].isEnabled()
    win.registry["edit.split_labels"].trigger()
    assert sorted(o.name for o in win.doc.objects) == [f"parcels label {v}" for v in (1, 2, 3, 7)]
    for o in win.doc.objects:
        assert o.kind == "discrete" and o.source == lm.pixel_set(int(o.name.rsplit(" ", 1)[1]))
    wait_drawn(qtbot, win)
    win.registry["edit.undo"].trigger()
    assert [o.id for o in win.doc.objects] == [obj.id]


def test_what_does_not_apply_to_a_label_map_says_so(make_window, qtbot, tmp_path):
    win = make_window()
    obj, _lm = _import_map(win, qtbot, tmp_path)
    box = win.doc.make_object(LabelMap(np.ones((2, 2), np.int32), (30, 30)).pixel_set(1), name="box")
    win.doc.push(AddObject(box))
    win.doc.set_selection([obj.id])
    wait_drawn(qtbot, win)
    messages: list[str] = []
    win.statusBar().messageChanged.connect(lambda m: messages.append(m) if m else None)
    # The brush.
    win.registry["tool.paint"].trigger()
    vp = win.views.discrete.plane.viewport()
    from tests.app.helpers import widget_pos

    qtbot.mouseClick(vp, Qt.MouseButton.LeftButton, pos=widget_pos(win.views.discrete, 3, 12))
    assert any("label map" in m and "Split into Objects" in m for m in messages), messages
    assert win.doc.get(obj.id).source is obj.source  # unchanged
    # The operations: a label map is no input, and the panel says why.
    panel = win.operations
    assert all(cb.findData(obj.id) < 0 for cb in panel.inputs)
    assert "no input of the operations" in panel.status.text()
    # The Properties panel lists the labels (the legend) instead of vertices.
    win.registry["edit.properties"].trigger()
    props = win.properties
    assert props.legend.isVisible() and not props.table.isVisible()
    rows = [props.legend.topLevelItem(k).text(0) for k in range(props.legend.topLevelItemCount())]
    assert rows == ["1", "2", "3", "7"]


@settings(max_examples=150, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(2, 11), st.tuples(st.integers(1, 14), st.integers(1, 14)))
def test_touching_labels_get_different_colours(seed: int, k: int, shape: tuple[int, int]) -> None:
    # Labels 1 and 11 used to share a colour (label mod the palette): any two labels whose regions touch,
    # at a side or a corner, are now coloured apart whenever the palette has a colour left for them.
    from mrm.views.label_maps import LABEL_COLOURS

    rng = np.random.default_rng(seed)
    labels = rng.choice(np.array([0, *rng.choice(np.arange(1, 40), size=k - 1, replace=False)]), size=shape)
    lm = LabelMap(labels.astype(np.int32))
    lab = lm.labels
    h, w = lab.shape
    room = len(lm.label_values()) <= len(LABEL_COLOURS)  # then a free colour always exists
    for r in range(h):
        for c in range(w):
            for dr, dc in ((0, 1), (1, 0), (1, 1), (1, -1)):
                r2, c2 = r + dr, c + dc
                if room and 0 <= r2 < h and 0 <= c2 < w and 0 != lab[r, c] != lab[r2, c2] != 0:
                    assert label_colour(lm, int(lab[r, c])) != label_colour(lm, int(lab[r2, c2]))


def test_a_label_map_too_costly_to_polygonize_is_refused_on_export_in_one_message(
    make_window, qtbot, tmp_path
):
    """Issue 32: the export shares mrm polygonize's cost check; nothing is written, the map stays."""
    win = make_window()
    lm = LabelMap((np.arange(150 * 150, dtype=np.int32) + 1).reshape(150, 150))  # 22,500 one-pixel labels
    obj = win.doc.make_object(lm, name="noise")
    win.doc.push(AddObject(obj))
    refused: list[tuple[str, str]] = []
    win.files._error = lambda title, text: refused.append((title, text))  # type: ignore[method-assign]
    out = tmp_path / "noise.geojson"
    win.files.export(obj.id, out)
    qtbot.waitUntil(lambda: bool(refused), timeout=30_000)
    title, text = refused[0]
    assert title == "Cannot export" and "22,500 labels" in text and "20,000" in text and "\n" not in text
    assert not out.exists() and win.doc.get(obj.id).source is lm
