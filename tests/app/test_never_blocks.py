"""The GUI thread never computes (issue 10, "never blocks"): heavy work runs on workers, with Cancel.

- The error inspector's picture of the differing pixels (the union of two results and their masks: seconds at
  10⁸ pixels) is made on a worker; the inspector shows the counts first and the picture when it arrives.
- Cancel in the status bar stops the derivations that follow an edit (not only an operation): what is computed
  stays drawn, the rest says "cancelled" and is computed again on request; the document is untouched.
"""

from __future__ import annotations

import threading

import numpy as np
from PySide6 import QtCore

import mrm.document.derive
import mrm.views.inspector
from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from tests.app.helpers import (
    HANG_MS,
    colour_at,
    is_background,
    record_gui_thread_calls,
    task_done,
    wait_drawn,
    wait_idle,
)
from tests.app.test_inspector import _chain

Qt = QtCore.Qt


def _inspector_colour(insp, x: int, y: int):  # type: ignore[no-untyped-def]
    """Colour the inspector's own plane shows at pixel (x, y)."""
    img = insp.plane.viewport().grab().toImage()
    p = insp.plane.map_from_plane(float(x), float(y))
    dpr = img.devicePixelRatio()
    return img.pixelColor(int(p.x() * dpr), int(p.y() * dpr))


def test_the_difference_picture_is_made_on_a_worker_and_drawn(make_window, qtbot, monkeypatch):
    threads: list[bool] = []
    original = mrm.views.inspector.diff_picture

    def recording(m, *rest):  # type: ignore[no-untyped-def]
        threads.append(threading.current_thread() is threading.main_thread())
        return original(m, *rest)

    monkeypatch.setattr(mrm.views.inspector, "diff_picture", recording)
    win = make_window(threaded=True, size=(1400, 900))
    insp = win.inspector
    with qtbot.waitSignal(insp.pictured, timeout=HANG_MS):  # the measurement, then its picture
        _chain(win, (2.0, 5.0, 0.1))  # α₁ = 2 then 5, back by 1/10: pixels differ (the paper's Figure 12)
    assert insp.picture is not None
    assert threads and not any(threads), "the picture was made on the GUI thread"
    m = insp.measurement
    light, dark = m.difference.light, m.difference.dark
    # Drawn from pictures made there too: converting a 4 M-pixel image in the first paint took 80 ms.
    assert insp.result_item.picture is not None and insp.result_item.picture is insp.picture.result_picture
    assert insp.picture.diff is None or insp.diff_item.picture is insp.picture.diff_picture is not None
    # The counts are in the text, the pixels in the picture, in the paper's two greys.
    assert f"{len(light):,} pixels only in the result" in insp.measured_label.text()
    assert not (light.is_empty() and dark.is_empty())
    for ps, grey in ((light, (200, 200, 200)), (dark, (95, 95, 95))):
        if not ps.is_empty():
            x, y = (int(v) for v in ps.points()[0])
            c = _inspector_colour(insp, x, y)
            assert (c.red(), c.green(), c.blue()) == grey
    # The overlay on the discrete view uses the same picture.
    insp.overlay.setChecked(True)
    wait_drawn(qtbot, win)
    if not light.is_empty():
        x, y = (int(v) for v in light.points()[0])
        c = colour_at(win.views.discrete, x, y)
        assert (c.red(), c.green(), c.blue()) == (200, 200, 200)
    # Unchecked, the overlay is gone from the discrete view.
    insp.overlay.setChecked(False)
    wait_drawn(qtbot, win)
    if not light.is_empty():
        x, y = (int(v) for v in light.points()[0])
        c = colour_at(win.views.discrete, x, y)
        assert (c.red(), c.green(), c.blue()) != (200, 200, 200)


def test_a_big_difference_picture_is_coarse_at_fit_all_and_exact_zoomed_in():
    """Differences of a 3000² result are drawn from a level-of-detail image, with the exact mask behind."""
    from mrm.ops.account import Account, PixelDifference

    result = np.ones((3000, 3000), bool)
    result[1500, 1500] = False
    direct = np.ones((3000, 3000), bool)
    direct[10, 20] = False
    r, d = PixelSet(result, (5, 7)), PixelSet(direct, (5, 7))
    m = Account(operation="dss", result=r, direct=d, difference=PixelDifference(light=r - d, dark=d - r))
    pic = mrm.views.inspector.diff_picture(m)
    assert pic is not None and pic.diff is not None
    assert pic.result.size <= mrm.views.canvas.LOD_PIXELS and pic.result_f > 1
    # The two differing pixels: light at (25, 17) (in the result only), dark at (1505, 1507).
    full, (ox, oy) = pic.diff_full, pic.diff_origin
    assert full[17 - oy, 25 - ox] == 1 and full[1507 - oy, 1505 - ox] == 2 and np.count_nonzero(full) == 2
    assert pic.box == (5, 7, 3004, 3006)


def _gate_regions(monkeypatch):  # type: ignore[no-untyped-def]
    """Make computing regions wait until the returned event is set (the derivation is then 'long')."""
    gate = threading.Event()
    started = threading.Event()
    original = mrm.document.derive.region_from_pixels

    def slow(ps):  # type: ignore[no-untyped-def]
        started.set()
        gate.wait(60)
        return original(ps)

    monkeypatch.setattr(mrm.document.derive, "region_from_pixels", slow)
    return gate, started


def _big_disk() -> PixelSet:
    yy, xx = np.mgrid[0:420, 0:420]
    return PixelSet((xx - 210) ** 2 + (yy - 210) ** 2 < 200**2, (0, 0))


def test_cancel_in_the_status_bar_stops_the_derivations_and_keeps_the_document(
    make_window, qtbot, monkeypatch
):
    gate, started = _gate_regions(monkeypatch)
    win = make_window(threaded=True, size=(1400, 900))
    obj = win.doc.make_object(_big_disk(), name="disk")
    win.doc.push(AddObject(obj, select=True))
    win.fit_all()
    qtbot.waitUntil(started.is_set, timeout=HANG_MS)
    # The derivation is in the status bar, with its progress and Cancel.
    status = win.status
    qtbot.waitUntil(lambda: status.progress_box.isVisible(), timeout=10_000)
    qtbot.waitUntil(lambda: "disk: computing the regions" in status.progress_label.text(), timeout=10_000)
    assert status.cancel_button.isEnabled()
    qtbot.mouseClick(status.cancel_button, Qt.MouseButton.LeftButton)
    gate.set()  # the running kernel ends; what comes after it does not run
    wait_idle(qtbot, win.runner)
    wait_drawn(qtbot, win)
    assert not status.progress_box.isVisible()
    # The document is intact: the object, its source, the undo history.
    assert [o.id for o in win.doc.objects] == [obj.id]
    assert win.doc.get(obj.id).source is obj.source
    assert win.doc.history.undo_label() == "Add disk"
    # The analytical view says what it did not compute, instead of "computing…" for ever.
    av = win.views.analytical
    assert "cancelled" in av.status_label.text()
    # So does the status bar: no "… components" as if they were on their way.
    qtbot.waitUntil(lambda: "segments not computed" in status.figures.text(), timeout=5000)
    assert "…" not in status.figures.text()
    assert "125\u2009609 pixels" in status.figures.text()  # what is computed is still given
    # The discrete view shows what was ready: the pixels themselves.
    c = colour_at(win.views.discrete, 210, 210)
    assert not is_background(win.views.discrete, c)
    # "Compute" in the view's header starts it again, and it completes.
    win.views.show_view(av)
    qtbot.waitUntil(av.resume_button.isVisible, timeout=5000)
    qtbot.mouseClick(av.resume_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: win.scene.get(obj.id, "analytical") is not None, timeout=HANG_MS)
    wait_drawn(qtbot, win)
    assert "cancelled" not in av.status_label.text()


def test_an_edit_after_a_cancel_computes_afresh(make_window, qtbot, monkeypatch):
    gate, started = _gate_regions(monkeypatch)
    win = make_window(threaded=True)
    obj = win.doc.make_object(_big_disk(), name="disk")
    win.doc.push(AddObject(obj, select=True))
    qtbot.waitUntil(started.is_set, timeout=HANG_MS)
    qtbot.waitUntil(lambda: win.status.progress_box.isVisible(), timeout=10_000)
    qtbot.mouseClick(win.status.cancel_button, Qt.MouseButton.LeftButton)
    gate.set()
    wait_idle(qtbot, win.runner)
    assert win.scene.is_cancelled(obj.id, "analytical")
    # A new version of the object (its pixels shifted) is not the cancelled one: it is computed.
    from mrm.document.commands import SetSource

    win.doc.push(SetSource(obj.id, _big_disk().translate(3, 0)))
    qtbot.waitUntil(lambda: win.scene.get(obj.id, "analytical") is not None, timeout=HANG_MS)
    wait_drawn(qtbot, win)
    assert "cancelled" not in win.views.analytical.status_label.text()


class _PaintCounter(QtCore.QObject):
    def __init__(self) -> None:
        super().__init__()
        self.count = 0

    def eventFilter(self, _obj, ev):  # type: ignore[no-untyped-def]
        if ev.type() == QtCore.QEvent.Type.Paint:
            self.count += 1
        return False


def test_the_coordinate_readout_follows_the_mouse_without_redrawing_the_views(make_window, qtbot):
    """Idle over a big object, a mouse move updates the readout and repaints no view (it used to redraw
    all four, images and outlines included, at every move: 1–2 s of lag at 85 M pixels)."""
    win = make_window(size=(1400, 900))
    yy, xx = np.mgrid[0:900, 0:900]
    ps = PixelSet((xx - 450) ** 2 + (yy - 450) ** 2 < 430**2, (0, 0))
    win.doc.push(AddObject(win.doc.make_object(ps, name="big"), select=True))
    wait_drawn(qtbot, win)
    win.views.camera.set(300.0, 300.0, 5.0)  # a pixel is 5 screen pixels wide: the readout is unambiguous
    wait_drawn(qtbot, win)
    counter = _PaintCounter()
    for v in win.views.views:
        v.plane.viewport().installEventFilter(counter)
    view = win.views.discrete
    vp = view.plane.viewport()
    QtCore.QCoreApplication.processEvents()
    counter.count = 0
    for x, y in ((300, 300), (301, 300), (330, 280), (275, 318)):
        qtbot.mouseMove(vp, view.plane.map_from_plane(float(x), float(y)))
        qtbot.waitUntil(lambda x=x, y=y: f"pixel ({x}, {y})" in win.status.cursor_label.text(), timeout=5000)
        QtCore.QCoreApplication.processEvents()
    assert counter.count == 0, f"{counter.count} view repaints for 4 mouse moves"
    # A tool that draws under the cursor (the brush outline) still repaints: the counter counts.
    win.tools.set_tool("paint")
    QtCore.QCoreApplication.processEvents()
    counter.count = 0
    qtbot.mouseMove(vp, view.plane.map_from_plane(200.0, 300.0))
    qtbot.waitUntil(lambda: counter.count > 0, timeout=5000)


def test_a_big_documents_autosave_is_written_by_a_worker_and_recovers_it(make_window, qtbot, monkeypatch):
    """Serialising 10⁸ pixels takes seconds: the autosave timer hands it to a worker; the side file is whole.

    (A big document is one over the 4 M-pixel-equivalent weight of app.files.BIG_FILE.)
    """
    from mrm.io import autosave
    from mrm.io.project import load_project

    threads = record_gui_thread_calls(monkeypatch, autosave, "dumps")
    win = make_window(threaded=True)
    m = np.zeros((4100, 4100), bool)  # above the 4 M-pixel-equivalent weight of a "big" document
    m[::3, ::5] = True
    obj = win.doc.make_object(PixelSet(m, (10, -20)), name="big")
    win.doc.push(AddObject(obj))
    a = win.files.autosaver
    a.interval = 0.0
    with task_done(qtbot, win.runner, "autosave"):
        win.files.autosave_tick()
    assert a.path.is_file()
    assert threads == [False], threads  # written once, not on the GUI thread
    assert a.failures == 0 and a.edits == 0
    back = load_project(a.path)
    assert [o.name for o in back] == ["big"] and back.get(back.objects[0].id).source == obj.source


def test_junctions_are_the_pointels_a_boundary_visits_twice():
    """The junction dots (computed without np.unique(axis=0), which holds the GIL) against a plain count."""
    from collections import Counter

    from mrm.reps.region import region_of
    from mrm.views.region_view import junctions

    rng = np.random.default_rng(7)
    for _ in range(12):
        m = rng.random((rng.integers(3, 30), rng.integers(3, 30))) < 0.45
        region = region_of(PixelSet(m, (int(rng.integers(-50, 50)), int(rng.integers(-50, 50)))))
        chains = list(region.boundary_chains)
        seen = Counter(tuple(int(v) for v in p) for c in chains if len(c) for p in list(c.points())[:-1])
        expected = sorted((x - 0.5, y - 0.5) for (x, y), n in seen.items() if n > 1)
        assert [tuple(p) for p in junctions(chains)] == expected


def test_a_big_outline_is_drawn_through_a_cache_and_follows_a_pan(make_window, qtbot):
    """Stroking 10⁵ outline pieces took 50–200 ms per view at every pan; cached, a pan moves the picture.

    What is drawn must still be right: the selected object's outline is where the object's edge is, before
    and after panning the views.
    """
    from PySide6 import QtWidgets

    win = make_window(size=(1400, 900))
    m = np.zeros((600, 600), bool)
    for y in range(0, 96, 6):
        for x in range(0, 600, 6):
            m[y : y + 4, x : x + 4] = True  # 1,600 blocks of 4 × 4: an outline of 25,600 sides, cheap for R
    m[100:500, 100:500] = True
    ps = PixelSet(m, (0, 0))
    obj = win.doc.make_object(ps, name="blocks")
    win.doc.push(AddObject(obj, select=True))
    wait_drawn(qtbot, win)
    view = win.views.discrete
    outline = view.layer(obj.id).outline
    assert outline.cacheMode() == QtWidgets.QGraphicsItem.CacheMode.DeviceCoordinateCache
    hl = view.highlight_colour()

    def edge_is_outlined() -> bool:
        # The left side of the solid square, x = 99.5, at a few heights: drawn in the highlight colour.
        img = view.plane.viewport().grab().toImage()
        dpr = img.devicePixelRatio()
        hits = 0
        for y in (200.0, 300.0, 400.0):
            p = view.plane.map_from_plane(99.5, y)
            c = img.pixelColor(int(p.x() * dpr), int(p.y() * dpr))
            hits += abs(c.red() - hl.red()) + abs(c.green() - hl.green()) + abs(c.blue() - hl.blue()) < 60
        return hits == 3

    cam = win.views.camera
    cam.set(150.0, 300.0, 1.0)
    wait_drawn(qtbot, win)
    assert edge_is_outlined()
    for dx in (37.0, -81.0):  # pans: only the view's translation changes, the cached picture is reused
        cam.set(cam.cx + dx, cam.cy + dx / 3, cam.scale)
        QtCore.QCoreApplication.processEvents()
        assert edge_is_outlined()


def test_a_long_path_is_built_in_short_reads_and_is_the_same_path(monkeypatch):
    """Qt reads a path from its stream with the GIL held (120–160 ms for 2 M elements on a worker, the
    window waiting meanwhile): :func:`array_path` reads it in chunks, and the path is the one of one read.
    """
    import pyqtgraph as pg

    from mrm.views import items

    reads: list[int] = []
    streamed = items._streamed_path
    monkeypatch.setattr(items, "_streamed_path", lambda k, x, y: reads.append(len(k)) or streamed(k, x, y))
    monkeypatch.setattr(items, "PATH_CHUNK", 16)
    rng = np.random.default_rng(3)
    for n in (10, 17, 200, 1000):
        xy = rng.normal(size=(n, 2)) * 50
        connect = (rng.random(n) > 0.15).astype(np.int32)
        connect[n // 2 : n // 2 + 3] = 0  # lone points: consecutive move-tos
        connect[-2:] = 0
        reads.clear()
        got = items.array_path(xy[:, 0], xy[:, 1], connect)
        want = pg.arrayToQPath(xy[:, 0], xy[:, 1], connect=connect)
        assert got.elementCount() == want.elementCount() == n
        for i in range(n):
            a, b = got.elementAt(i), want.elementAt(i)
            assert (a.type, a.x, a.y) == (b.type, b.x, b.y), i
        assert got.boundingRect() == want.boundingRect() and got.fillRule() == want.fillRule()
        # In chunks of about PATH_CHUNK (longer only by the move-tos a chunk may not end on).
        assert sum(reads) == (n if n > 16 else 0) and all(r <= 16 + 4 for r in reads)
