"""Reading the views: marks only on the selected object, the chosen segment cleared with the selection,
the preimage in the segment's own frame with readable signs, distinct region colours, a legend per view."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from PySide6 import QtGui
from shapely.geometry import Polygon

from mrm.core.grids import PixelSet
from mrm.document import Style
from mrm.document.commands import AddObject
from mrm.views.region_view import colour_distance
from mrm.views.segment_table import linear
from tests.app.helpers import click, grab, wait_drawn, zoom_to


def _two_objects(win):  # type: ignore[no-untyped-def]
    a = win.doc.make_object(Polygon([(0, 0), (20, 0), (17, 9), (0, 6)]), name="A")
    b = win.doc.make_object(Polygon([(30, 0), (45, 0), (40, 12)]), name="B")
    win.doc.push(AddObject(a))
    win.doc.push(AddObject(b, select=True))
    return a, b


def test_handles_and_junctions_only_on_the_selected_object(make_window, qtbot):
    win = make_window()
    a, b = _two_objects(win)
    zoom_to(win, -2, -2, 48, 14)
    wait_drawn(qtbot, win)
    av, ev = win.views.analytical, win.views.euclidean
    assert av.layer(b.id).ends.isVisible() and not av.layer(a.id).ends.isVisible()
    assert ev.layer(b.id).handles.isVisible() and not ev.layer(a.id).handles.isVisible()
    # Select A by clicking it in the Euclidean view: the marks move with the selection.
    click(qtbot, ev, 8.0, 3.0)
    wait_drawn(qtbot, win)
    assert win.doc.selection == (a.id,)
    assert av.layer(a.id).ends.isVisible() and not av.layer(b.id).ends.isVisible()
    assert not ev.layer(b.id).handles.isVisible()


def test_the_chosen_segment_line_goes_when_another_object_is_selected(make_window, qtbot):
    win = make_window()
    a, b = _two_objects(win)
    zoom_to(win, -2, -2, 48, 14)
    wait_drawn(qtbot, win)
    win.segments.table.selectRow(1)
    av = win.views.analytical
    assert win.scene.segment[0] == b.id and not av.chosen.path().isEmpty()
    click(qtbot, win.views.euclidean, 8.0, 3.0)  # select A
    wait_drawn(qtbot, win)
    assert win.doc.selection == (a.id,)
    assert win.scene.segment == (-1, -1, -1)
    assert av.chosen.path().isEmpty() and av.extremes.path().isEmpty() and av.highlight.path().isEmpty()


def test_the_preimage_is_drawn_in_the_segments_local_frame(make_window, qtbot):
    win = make_window()
    far = Polygon([(5000, -3000), (5040, -3000), (5031, -2987), (5000, -2990)])
    obj = win.doc.make_object(far, name="far")
    win.doc.push(AddObject(obj, select=True))
    wait_drawn(qtbot, win)
    table = win.segments
    table.table.selectRow(1)
    ana = win.doc.derived(obj.id).get("analytical")
    chain = ana.chains[0]
    seg = chain.segments[1]
    i0, j0 = (int(v) for v in chain.points()[seg.first % len(chain.points())])
    # Every vertex of the drawn polygon is the exact preimage vertex with w moved to the first pointel.
    sx, sy = chain.preimage(1).frame
    want = [(float(u), float(w - u * sx * i0 + (1 - u) * sy * j0)) for u, w in chain.preimage(1).vertices]
    r = table.preimage_item.path().boundingRect()
    ws = [w for _u, w in want]
    assert abs(r.top() - min(ws)) < 1e-9 and abs(r.bottom() - max(ws)) < 1e-9
    assert max(abs(w) for w in ws) < 2  # near 0 in the local frame, not thousands
    text = table.plot_caption.text()
    assert "− -" not in text and "+ -" not in text and "− −" not in text
    assert f"({i0}, {j0})".replace("-", "−") in text


def test_linear_forms_read_naturally():
    assert linear(4, 3) == "4·i + 3·j"
    assert linear(4, -3) == "4·i − 3·j"
    assert linear(-1, -3) == "−i − 3·j"
    assert linear(0, 2) == "2·j"
    assert linear(Fraction(1, 2), -1) == "1/2·i − j"


def test_region_components_get_clearly_different_colours(make_window, qtbot):
    win = make_window()
    m = np.zeros((5, 20), bool)
    for k in range(5):
        m[1:4, 4 * k : 4 * k + 3] = True  # five separate components
    obj = win.doc.make_object(PixelSet(m), name="five", style=Style(fill="#4c72b0"))
    win.doc.push(AddObject(obj, select=True))
    wait_drawn(qtbot, win)
    lut = win.views.region.layer(obj.id).components._lut
    colours = ["#" + "".join(f"{int(c):02x}" for c in lut[k][:3]) for k in range(1, 6)]
    for i in range(5):
        for j in range(i + 1, 5):
            assert colour_distance(colours[i], colours[j]) > 60, colours  # not two blues (≈ 12 apart)


def test_every_view_has_a_legend(make_window, qtbot):
    win = make_window()
    for v in win.views.views:
        assert v.legend_label.isVisibleTo(win) and v.legend_label.text()
    assert "hole boundary" in win.views.region.legend_label.text()
    assert "junction" in win.views.region.legend_label.text()
    assert "preview" in win.views.discrete.legend_label.text()


def test_view_subtitles_are_not_cut_when_nothing_is_computing(make_window, qtbot):
    win = make_window(size=(1600, 1000))
    wait_drawn(qtbot, win)
    qtbot.wait(50)  # the header layouts settle after the status labels were hidden
    for v in win.views.views:
        label = v.subtitle_label
        assert label.width() >= label.fontMetrics().horizontalAdvance(label.text()), v.name


def test_tiny_components_are_dots_at_fit_all_and_outlines_zoomed_in(make_window, qtbot):
    """A ring plus lone pixels: zoomed out, the lone pixels' strokes become dots; zoomed in, full paths."""
    win = make_window()
    yy, xx = np.mgrid[0:600, 0:600]
    r2 = (xx - 300) ** 2 + (yy - 300) ** 2
    mask = (r2 < 280**2) & (r2 > 250**2)
    rng = np.random.default_rng(3)
    lone = rng.integers(0, 300, size=(200, 2)) * 2  # even coordinates: never 4-adjacent to each other
    mask[lone[:, 1], lone[:, 0]] |= r2[lone[:, 1], lone[:, 0]] > 285**2
    obj = win.doc.make_object(PixelSet(mask, (0, 0)), name="speckled")
    win.doc.push(AddObject(obj, select=True))
    zoom_to(win, 0, 0, 600, 600)
    wait_drawn(qtbot, win)
    scale = win.views.camera.scale
    assert scale < 1.5
    for item in (*win.views.analytical.layer(obj.id).cracks, win.views.region.layer(obj.id).outer):
        if item.levels:
            paths, dots = item.drawn(scale)
            # The ring's stroke is drawn; the lone pixels are dots, not strokes.
            assert paths > 0 or item in win.views.analytical.layer(obj.id).cracks[1:]
            assert dots > 0
    outer = win.views.region.layer(obj.id).outer
    n_lone = int((mask & (r2 > 285**2)).sum())
    assert outer.drawn(scale)[1] == n_lone
    poly = win.views.euclidean.layer(obj.id).polygon
    assert poly.drawn(scale)[1] == n_lone
    # Zoomed in: every component is stroked in full.
    assert outer.drawn(8.0) == (outer.path().elementCount(), 0)
    assert poly.drawn(8.0) == (poly.path().elementCount(), 0)
    # The selected object's vertex handles: a handle overlapping another by more than half its size is not
    # drawn (the lone pixels' handles made a black field at fit-all), one clear of every other is drawn.
    handles = win.views.euclidean.layer(obj.id).handles
    xy = handles.points()
    ring_handles = len(xy) - 3 * n_lone  # a lone pixel's continuation is a triangle: three handles
    assert handles.isVisible() and ring_handles > 0
    cheb = np.abs(xy[:, None, :] - xy[None, :, :]).max(axis=2)
    np.fill_diagonal(cheb, np.inf)
    nearest = cheb.min(axis=1)  # in units; times the scale: screen pixels
    for s in (scale, 4.0, 16.0):
        shown = handles.drawn(s)
        assert not shown[nearest * s < handles.size / 2].any(), s
        assert shown[nearest * s >= handles.size].all(), s
    assert handles.drawn(scale).sum() <= ring_handles  # no lone pixel's handle at fit-all
    assert handles.drawn(16.0).sum() > ring_handles  # zoomed in, the lone pixels' handles too


def _polylines(path):  # type: ignore[no-untyped-def]
    """The polylines of a QPainterPath, as shapely LineStrings."""
    import shapely

    lines, cur = [], []
    for k in range(path.elementCount()):
        e = path.elementAt(k)
        if e.isMoveTo() and len(cur) > 1:
            lines.append(shapely.LineString(cur))
        if e.isMoveTo():
            cur = []
        cur.append((e.x, e.y))
    if len(cur) > 1:
        lines.append(shapely.LineString(cur))
    return shapely.MultiLineString(lines)


def test_the_discrete_outline_has_the_same_level_of_detail_and_stays_exact_on_screen(make_window, qtbot):
    """The selected object's outline in the discrete view has the level of detail of the other views.

    Specks are dots at fit-all zoom, and the big outline is stroked with fewer corners, never more than half
    a screen pixel off the crack boundary; zoomed in, in full. The same holds in every view that strokes
    outlines.
    """
    from mrm.views.items import COARSE_PX

    win = make_window()
    yy, xx = np.mgrid[0:1500, 0:1500]
    r2 = (xx - 750) ** 2 + (yy - 750) ** 2
    mask = (r2 < 700**2) & (r2 > 400**2)
    lone = np.random.default_rng(5).integers(0, 750, size=(150, 2)) * 2
    far = r2[lone[:, 1], lone[:, 0]] > 705**2
    mask[lone[far, 1], lone[far, 0]] = True
    n_lone = int(far.sum())
    obj = win.doc.make_object(PixelSet(mask, (0, 0)), name="ring")
    win.doc.push(AddObject(obj, select=True))
    zoom_to(win, 0, 0, 1500, 1500)
    wait_drawn(qtbot, win)
    scale = win.views.camera.scale
    assert scale < 0.5
    outline = win.views.discrete.layer(obj.id).outline
    assert outline.isVisible() and outline.levels
    paths, dots = outline.drawn(scale)
    assert dots == n_lone
    full = outline.path().elementCount()
    assert 0 < paths < full / 4  # the ring's staircases, simplified
    # Zoomed in, every crack is stroked.
    assert outline.drawn(8.0) == (full, 0)
    # What is stroked at fit-all lies within half a screen pixel of the crack boundary, and covers it.
    cracks = win.views.analytical.layer(obj.id).cracks
    for item in (
        outline,
        win.views.region.layer(obj.id).outer,
        win.views.euclidean.layer(obj.id).polygon,
        *cracks,
    ):
        big = [lv for lv in item.levels if lv.extent * scale >= 4.0]
        assert big or item is cracks[2]  # the third colour only ends odd chains: the ring's may be specks
        for level in big:
            exact, shown = _polylines(level.path), _polylines(level.path_at(scale))
            assert shown.hausdorff_distance(exact) <= COARSE_PX / scale + 1e-9
            assert level.path_at(scale).elementCount() < level.path.elementCount()


def _grabs(win):  # type: ignore[no-untyped-def]
    """What each view shows now, as arrays (the paint of every item done afresh)."""
    from PySide6 import QtWidgets

    out = {}
    for v in win.views.visible_views():
        for item in v.plane.scene().items():
            item.update()  # drops Qt's device-pixel cache: the next paint strokes again
        QtWidgets.QApplication.processEvents()
        img = grab(v).convertToFormat(QtGui.QImage.Format.Format_ARGB32)
        out[v.name] = np.frombuffer(img.constBits(), np.uint8).reshape(img.height(), img.width(), 4).copy()
    return out


def test_zoomed_in_a_long_outline_is_stroked_in_view_only_and_drawn_as_in_full(
    make_window, qtbot, monkeypatch
):
    """Zoomed in on part of a long outline, the views stroke only what is in view (its chunks) and show
    exactly what stroking every outline in full shows, after a zoom and after a pan."""
    from mrm.views.items import LodPathItem

    win = make_window()
    yy, xx = np.mgrid[0:1200, 0:1200]
    r2 = (xx - 600) ** 2 + (yy - 600) ** 2
    # A ring with a rough outer boundary: thousands of crack corners, and as many slanted polygon edges.
    t = np.arctan2(yy - 600, xx - 600)
    wave = 560 + 8 * np.sin(57 * t) + 6 * np.sin(211 * t) + 4 * np.sin(503 * t) + 3 * np.sin(1009 * t)
    mask = (r2 < wave**2) & (r2 > 300**2)
    obj = win.doc.make_object(PixelSet(mask, (0, 0)), name="wavy ring")
    win.doc.push(AddObject(obj, select=True))
    zoom_to(win, 0, 0, 1200, 1200)
    wait_drawn(qtbot, win)
    v = win.views
    items = [
        (v.discrete, v.discrete.layer(obj.id).outline),
        (v.region, v.region.layer(obj.id).outer),
        (v.euclidean, v.euclidean.layer(obj.id).polygon),
        *((v.analytical, c) for c in v.analytical.layer(obj.id).cracks[:2]),
    ]
    for where in ((1130, 560, 1190, 620), (1100, 600, 1180, 680)):  # a zoom in, then a pan
        zoom_to(win, *where)
        wait_drawn(qtbot, win)
        scale = win.views.camera.scale
        assert scale > 2  # the pens are 2 to 3 screen pixels wide, not hairlines
        for view, item in items:
            stroked, _dots = item.drawn(scale, view.plane.vb.viewRect())
            full, _ = item.drawn(scale)
            assert 0 < stroked < full / 4, item  # the outline crosses the view; most of it is elsewhere
        shown = _grabs(win)
        monkeypatch.setattr(LodPathItem, "tiled", False)
        reference = _grabs(win)
        monkeypatch.setattr(LodPathItem, "tiled", True)
        for name, img in shown.items():
            background = (img == img[0, 0]).all(axis=2)
            assert not background.all(), name  # the outline and the pixels are in view
            assert np.array_equal(img, reference[name]), (
                name,
                int((img != reference[name]).any(axis=2).sum()),
            )
