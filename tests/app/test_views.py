"""What the views draw: region (components, holes, cracks, junctions), analytical segments and the segment
table, the pixel grid, the status bar, themes; object list operations."""

from __future__ import annotations

import numpy as np
from PySide6 import QtCore, QtGui
from shapely.geometry import Polygon

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from mrm.reps.region import region_of
from tests.app.helpers import (
    click,
    click_object,
    colour_at,
    is_background,
    wait_drawn,
    widget_pos,
    zoom_to,
)

Qt = QtCore.Qt

# Two components: a ring of pixels x, y ∈ {0, 1, 2} around the hole (1, 1), and the pixel (3, 3) touching
# the ring's corner pixel (2, 2) at one pointel. mask[row, col] is pixel (col, row): row 0 is y = 0.
RING = np.array(
    [
        [1, 1, 1, 0],
        [1, 0, 1, 0],
        [1, 1, 1, 0],
        [0, 0, 0, 1],
    ],
    dtype=bool,
)


def _add_pixels(win, mask, origin=(0, 0), name="px", select=True):  # type: ignore[no-untyped-def]
    obj = win.doc.make_object(PixelSet(mask, origin), name=name)
    win.doc.push(AddObject(obj, select=select))
    return obj


def test_region_view_components_holes_cracks_junctions(make_window, qtbot):
    win = make_window()
    obj = _add_pixels(win, RING)
    zoom_to(win, -1, -1, 5, 5)
    wait_drawn(qtbot, win)
    rv = win.views.region
    layer = rv.layer(obj.id)
    # Components coloured by label: the ring is component 1, the corner pixel component 2.
    lab = layer.components.image
    assert lab[0, 0] == 1 and lab[3, 3] == 2 and lab[1, 1] == 0
    img = rv.plane.viewport().grab().toImage()
    ring_c, corner_c = colour_at(rv, 0, 0, img), colour_at(rv, 3, 3, img)
    assert ring_c != corner_c and not is_background(rv, ring_c) and not is_background(rv, corner_c)
    # The hole pixel (1, 1) is marked as a hole (grey), not left as background.
    assert layer.holes.image[1, 1] == 1 and layer.holes.image.sum() == 1
    assert not is_background(rv, colour_at(rv, 1, 1, img))
    assert is_background(rv, colour_at(rv, 3, 1, img))
    # Crack boundaries along the pixel sides: outer chains cover [−½, 3½]², the hole chain [½, 1½]².
    outer = layer.outer.path().boundingRect()
    assert (outer.left(), outer.right(), outer.top(), outer.bottom()) == (-0.5, 3.5, -0.5, 3.5)
    inner = layer.inner.path().boundingRect()
    assert (inner.left(), inner.right(), inner.top(), inner.bottom()) == (0.5, 1.5, 0.5, 1.5)
    # Junction: the pointel where the two components touch, (3 − ½, 3 − ½).
    assert [tuple(p) for p in layer.junctions.points()] == [(2.5, 2.5)]


def test_analytical_view_and_segment_table(make_window, qtbot):
    win = make_window()
    tri = Polygon([(0, 0), (30, 0), (26, 13), (9, 17), (0, 9)])
    obj = win.doc.make_object(tri, name="tri")
    win.doc.push(AddObject(obj, select=True))
    zoom_to(win, -2, -2, 32, 20)
    wait_drawn(qtbot, win)
    ana = win.doc.derived(obj.id).get("analytical")
    table = win.segments
    assert table.model.rowCount() == ana.n_segments >= 5
    first = ana.chains[0].segments[1]
    row = [table.model.index(1, c).data() for c in range(2, 8)]
    assert row == [first.first, first.last, first.a, first.b, first.mu, first.omega]
    # Segments are drawn in alternating colours on their border pixels.
    av = win.views.analytical
    layer = av.layer(obj.id)
    colours = set(np.unique(layer.border.image)) - {0}
    assert colours >= {1, 2}
    # Picking a row selects the segment: the view draws its chosen line, the preimage plot its polygon.
    table.table.selectRow(1)
    assert win.scene.segment == (obj.id, 0, 1)
    assert not av.chosen.path().isEmpty() and not av.extremes.path().isEmpty()
    assert not table.preimage_item.path().isEmpty()
    assert "Chosen line" in table.plot_caption.text()
    # Clicking a boundary in the analytical view selects the segment under the cursor, and the table follows.
    seg0 = ana.chains[0].segment_points(0)
    mid = seg0[len(seg0) // 2] - 0.5
    click(qtbot, av, float(mid[0]) + 0.3, float(mid[1]))
    assert win.scene.segment[:2] == (obj.id, 0)
    assert table.table.currentIndex().row() == win.scene.segment[2]


def test_pixel_grid_appears_when_zoomed_in(make_window, qtbot):
    win = make_window()
    view = win.views.discrete
    zoom_to(win, 0, 0, 400, 400)
    assert not view.plane.grid.is_drawn()
    zoom_to(win, 0, 0, 10, 10)
    assert view.plane.grid.is_drawn()
    img = view.plane.viewport().grab().toImage()
    # A grid line at x = 4.5 darkens the background there; the pixel centre (4, 4) keeps the background.
    # The line is one device pixel wide and not antialiased, so look within one device pixel of x = 4.5:
    # Qt may round the line's position either way.
    p = widget_pos(view, 4.5, 4.0)
    dpr = img.devicePixelRatio()
    near_line = [img.pixelColor(int(p.x() * dpr) + d, int(p.y() * dpr)) for d in (-1, 0, 1)]
    centre = colour_at(view, 4.0, 4.0, img)
    assert is_background(view, centre)
    assert any(not is_background(view, c) for c in near_line)
    win.registry["view.pixel_grid"].trigger()  # G toggles it off
    assert not view.plane.grid.is_drawn()
    img = view.plane.viewport().grab().toImage()
    assert all(
        is_background(view, img.pixelColor(int(p.x() * dpr) + d, int(p.y() * dpr))) for d in (-1, 0, 1)
    )


def test_status_bar_shows_cursor_and_figures(make_window, qtbot):
    win = make_window()
    obj = _add_pixels(win, RING, (10, 20))
    zoom_to(win, 9, 19, 17, 26)
    wait_drawn(qtbot, win)
    view = win.views.region
    qtbot.mouseMove(view.plane.viewport(), view.plane.map_from_plane(12.2, 21.9))
    text = win.status.cursor_label.text()
    assert "pixel (12, 22)" in text
    x = float(text.split()[1])
    assert abs(x - 12.2) < 0.1
    win.status.update_figures()
    f = win.status.figures.text()
    region = region_of(obj.source)
    assert f"{obj.source.count} pixels" in f
    assert "2 components" in f and "1 hole" in f and f"{region.n_components}" in f
    ana = win.doc.derived(obj.id).get("analytical")
    assert f"{ana.n_segments} segments" in f


def test_layout_tabs_and_linked_zoom(make_window, qtbot):
    win = make_window()
    win.registry["view.tabs_layout"].trigger()
    assert win.views.layout_mode == "tabs"
    assert win.prefs.layout == "tabs"
    win.registry["view.euclidean"].trigger()
    assert win.views.current_view() is win.views.euclidean
    win.registry["view.zoom_in"].trigger()
    s = win.views.camera.scale
    win.registry["view.grid_layout"].trigger()
    qtbot.waitUntil(lambda: abs(win.views.discrete.plane.pixels_per_unit() - s) < 1e-6)


def test_object_list_visibility_colour_rename_reorder(make_window, qtbot):
    win = make_window()
    a = _add_pixels(win, np.ones((3, 3), bool), (0, 0), "a")
    b = _add_pixels(win, np.ones((3, 3), bool), (10, 0), "b")
    ol = win.object_list
    model = ol.model
    assert model.ids() == [b.id, a.id]  # top row is drawn on top
    # Visibility checkbox: one undo step, and the pixels disappear from the discrete view.
    model.setData(model.index(1, 0), Qt.CheckState.Unchecked.value, Qt.ItemDataRole.CheckStateRole)
    assert not win.doc.get(a.id).style.visible
    zoom_to(win, -1, -1, 14, 4)
    wait_drawn(qtbot, win)
    assert is_background(win.views.discrete, colour_at(win.views.discrete, 1, 1))
    win.registry["edit.undo"].trigger()
    assert win.doc.get(a.id).style.visible
    # Rename through the editor.
    model.setData(model.index(0, 2), "bee", Qt.ItemDataRole.EditRole)
    assert win.doc.get(b.id).name == "bee"
    # Raise "a" above "b" with the button, then drop "b" back on top (the drag-and-drop path).
    win.doc.set_selection([a.id])
    ol.raise_button.click()
    assert win.doc.ids == (b.id, a.id) and model.ids() == [a.id, b.id]
    mime = model.mimeData([model.index(1, 2)])
    model.dropMimeData(mime, Qt.DropAction.MoveAction, 0, 0, QtCore.QModelIndex())
    assert model.ids() == [b.id, a.id]
    win.registry["edit.undo"].trigger()
    assert model.ids() == [a.id, b.id]


def test_dark_theme_follows_preference(make_window, qtbot):
    from mrm.app.application import theme_controller

    win = make_window()
    ctl = theme_controller()
    try:
        ctl.set_preference("dark")
        qtbot.waitUntil(lambda: win.views.discrete.is_dark())
        base = win.views.discrete.plane.backgroundBrush().color()
        assert base.lightness() < 80
        ctl.set_preference("light")
        qtbot.waitUntil(lambda: not win.views.discrete.is_dark())
        assert win.views.discrete.plane.backgroundBrush().color().lightness() > 200
    finally:
        ctl.set_preference("system")


def test_hidpi_grab_is_sharp(make_window, qtbot):
    win = make_window()
    _add_pixels(win, RING)
    zoom_to(win, -1, -1, 5, 5)
    wait_drawn(qtbot, win)
    img = win.views.discrete.plane.viewport().grab().toImage()
    assert img.devicePixelRatio() == win.views.discrete.plane.viewport().devicePixelRatioF()
    # Pixels are drawn as hard-edged squares: just inside and just outside a voxel side differ sharply.
    inside = colour_at(win.views.discrete, 0.0, -0.45, img)
    outside = colour_at(win.views.discrete, 0.0, -0.55, img)
    assert not is_background(win.views.discrete, inside) and is_background(win.views.discrete, outside)
    _ = QtGui


def test_tool_keys_work_after_a_click_in_the_object_list(make_window, qtbot):
    """Issue 27: M did not pick the measure tool after a click in the list (its type-ahead took the key).

    A text field keeps its typing: the same keys in the Properties name field are letters of the name.
    """
    from PySide6 import QtWidgets

    win = make_window()
    for name in ("measured", "brushed", "erased"):  # names starting with the tool keys: type-ahead bait
        win.doc.push(AddObject(win.doc.make_object(Polygon([(0, 0), (4, 0), (0, 4)]), name=name)))
    for key, action in ((Qt.Key.Key_M, "tool.measure"), (Qt.Key.Key_B, "tool.paint"),
                        (Qt.Key.Key_E, "tool.erase"), (Qt.Key.Key_S, "tool.select")):  # fmt: skip
        click_object(qtbot, win, "brushed" if key == Qt.Key.Key_M else "measured")
        assert QtWidgets.QApplication.focusWidget() is win.object_list.view
        selected = list(win.doc.selection)
        qtbot.keyClick(win.object_list.view, key)
        assert win.registry[action].isChecked(), action
        assert list(win.doc.selection) == selected  # the list did not jump to a name starting with the key
    win.registry["edit.properties"].trigger()
    field = win.properties.name_edit
    qtbot.keyClick(field, Qt.Key.Key_End)
    qtbot.keyClicks(field, "mb")
    assert field.text() == "measuredmb" and win.registry["tool.select"].isChecked()
