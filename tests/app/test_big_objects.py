"""Big objects: drawing data made on workers, coarser images beyond 4 M pixels, big files on workers.

The issue: after DSS 20 the window ignored the mouse for ~9 s while the views built their images and paths on
the GUI thread. Here the layers of a 5 M-pixel object wait for their data (the view says "computing…") instead
of computing it on the GUI thread, and the discrete view shows an image of at most 4 M pixels covering it.
"""

from __future__ import annotations

import numpy as np

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from mrm.views.canvas import LOD_PIXELS, lod_factor, lod_image
from tests.app.helpers import HANG_MS, task_done


def test_lod_image_keeps_every_pixel_visible():
    m = np.zeros((3001, 2001), bool)
    m[1500, :] = True  # a one-pixel line
    m[7, 9] = True  # a lone pixel
    img, f = lod_image(m, limit=1_000_000)
    assert f == 3 and img.size <= 1_000_000
    assert img[500].all()  # the line is still drawn across
    assert img[7 // 3, 9 // 3] == 1 and img.sum() == img.shape[1] + 1


def _padded_max_pool(img: np.ndarray, f: int) -> np.ndarray:
    """The reference: pad with 0 to multiples of f, then the maximum of each f × f block."""
    h, w = img.shape
    pad = np.zeros((-(-h // f) * f, -(-w // f) * f), np.uint8)
    pad[:h, :w] = img
    return pad.reshape(pad.shape[0] // f, f, pad.shape[1] // f, f).max(axis=(1, 3))


def test_the_region_views_coarse_images_are_pooled_in_one_pass_as_before():
    """The region view's images come pooled straight from the labels and the runs (no full-size temporaries:
    at 10⁸ pixels they were 2 GB of fresh memory), and are what the full-size arithmetic gave: labels beyond
    255 cycled through 1 … 255 and max-pooled, the holes (bounded 8-components of the complement) max-pooled.
    """
    from mrm.reps.region import region_of
    from mrm.views.canvas import max_pool
    from mrm.views.region_view import hole_mask, region_drawing

    rng = np.random.default_rng(11)
    for limit in (10**9, 900, 250):
        m = rng.random((61, 47)) < 0.55
        m[20:30, 10:25] = True
        m[24:26, 15:18] = False  # a hole
        region = region_of(PixelSet(m, (5, -3)))
        lut = np.zeros((256, 4), np.uint8)
        (img, f, _p), (holes, hf, _hp), *_rest = region_drawing(region, lut, lut, limit)
        data = region.labels.labels
        assert f == hf == lod_factor(data.size, limit) and (f > 1 or limit > data.size)
        cycled = np.where(data > 0, (data - 1) % 255 + 1, 0).astype(np.uint8)
        assert np.array_equal(img, _padded_max_pool(cycled, f))
        # The complement's bounded 8-components, the old way: labelling the padded complement.
        from mrm.geometry.topology.labeling import label

        lab, _n = label(np.pad(data == 0, 1, constant_values=True), connectivity=8)
        expected = ((lab != lab[0, 0]) & (lab > 0))[1:-1, 1:-1]
        assert expected.any() and np.array_equal(hole_mask(data > 0), expected)
        assert np.array_equal(holes, _padded_max_pool(expected.view(np.uint8), f))
        # A crop, read in place (the exact detail of a view), pools as its copy does.
        assert np.array_equal(max_pool(m[3:50, 1:40], 3), _padded_max_pool(m[3:50, 1:40].view(np.uint8), 3))
    big = np.zeros((1000, 300), np.int32)
    big[::7, ::3] = 300  # beyond 255: cycles to 45
    from mrm.geometry.topology.labeling import pooled_labels

    assert np.array_equal(
        pooled_labels(big, 4), _padded_max_pool(np.where(big > 0, 45, 0).astype(np.uint8), 4)
    )


def test_big_pictures_and_the_border_image_are_made_without_full_size_temporaries(monkeypatch):
    """A big picture comes from a compiled lookup (numpy's take first copied the indices to int64), the
    analytical view's border image straight at its level of detail; both are what they were.
    """
    import mrm.views.canvas as canvas
    from mrm.reps.analytical import analytical_of
    from mrm.reps.region import region_of
    from mrm.views.analytical_view import segment_pixel_image

    rng = np.random.default_rng(2)
    img = rng.integers(0, 4, (300, 200)).astype(np.uint8)
    lut = rng.integers(0, 256, (4, 4)).astype(np.uint8)
    want = canvas.make_picture(img, lut)
    monkeypatch.setattr(canvas, "PICTURE_KERNEL_PIXELS", 100)
    got = canvas.make_picture(img, lut)
    assert np.array_equal(got.argb, want.argb) and got.qimage == want.qimage
    for _ in range(5):
        m = rng.random((50, 70)) < 0.6
        ana = analytical_of(region_of(PixelSet(m, (3, -8))))
        full, origin, f = segment_pixel_image(ana, 10**9)
        assert f == 1
        for limit in (1000, 300, 100):
            pooled, o, f = segment_pixel_image(ana, limit)
            assert o == origin and f > 1 and np.array_equal(pooled, _padded_max_pool(full, f))


def test_a_big_object_is_prepared_off_the_gui_thread_and_shown_coarser(make_window, qtbot):
    win = make_window(threaded=True)
    m = np.ones((2000, 2500), bool)
    m[470:480, 210:230] = False  # a hole, seen when zoomed in at x 110 … 129, y 510 … 519
    m[495, 200:260] = False  # a one-pixel gap at y 535, which the coarse image (2 × 2 maxima) fills
    ps = PixelSet(m, (-100, 40))
    obj = win.doc.make_object(ps, name="big")
    win.doc.push(AddObject(obj, select=True))
    dv = win.views.discrete
    # Right after the change nothing heavy ran on the GUI thread: the layer waits for a worker's image.
    dv.refresh()
    layer = dv.layer(obj.id)
    assert layer is not None and layer.waiting and not win.is_drawn()
    qtbot.waitUntil(lambda: win.is_drawn() and not win.runner.is_busy(), timeout=HANG_MS)
    item = layer.mask
    assert item.image.size <= LOD_PIXELS and item.scale_factor == 2
    # The status bar gives its pixel count, counted on the worker that made its region.
    assert f"{ps.count:,} pixels".replace(",", "\u2009") in win.status.figures.text()
    r = item.mapRectToParent(item.boundingRect())
    assert (r.left(), r.bottom() if r.bottom() > r.top() else r.top()) == (-100.5, 40 - 0.5 + 2000)
    assert r.width() == 2500
    # Zoomed in, the exact pixels of the visible part are drawn over the coarse image (nothing blocky).
    from tests.app.helpers import zoom_to

    zoom_to(win, 100, 500, 160, 540)
    qtbot.waitUntil(win.is_drawn, timeout=HANG_MS)  # the detail is cropped and pooled on a worker
    detail = item._detail
    assert detail is not None and detail.isVisible()
    d = detail.mapRectToParent(detail.boundingRect())
    x0, y0 = int(d.left() + 0.5), int(min(d.top(), d.bottom()) + 0.5)
    w, h = round(d.width()), round(abs(d.height()))
    assert x0 <= 100 and x0 + w >= 160 and y0 <= 500 and y0 + h >= 540
    exact = ps.to_array((x0, y0, x0 + w - 1, y0 + h - 1))
    assert not exact.all()  # the hole is in view
    assert np.array_equal(detail.image.astype(bool), exact)
    # And that is what the view shows: the gap and the hole are not filled in by the coarse image below.
    from tests.app.helpers import colour_at, grab, is_background

    shown = grab(dv)
    assert is_background(dv, colour_at(dv, 130, 535, shown))
    assert is_background(dv, colour_at(dv, 120, 515, shown))
    assert not is_background(dv, colour_at(dv, 130, 533, shown))
    assert not is_background(dv, colour_at(dv, 130, 537, shown))
    # The other views drew it too, with their own prepared data.
    assert win.views.region.layer(obj.id).components.image.size <= LOD_PIXELS
    assert not win.views.euclidean.layer(obj.id).polygon.path().isEmpty()


def test_a_big_project_is_saved_and_opened_on_a_worker(make_window, qtbot, tmp_path):
    win = make_window(threaded=True)
    m = np.ones((4000, 4500), bool)
    m[1000:3000, 1000:3500] = False  # a frame: big, with a hole, cheap to derive
    ps = PixelSet(m, (0, 0))
    win.doc.push(AddObject(win.doc.make_object(ps, name="frame"), select=True))
    qtbot.waitUntil(lambda: win.is_drawn() and not win.runner.is_busy(), timeout=HANG_MS)
    path = tmp_path / "big.mrm"
    with task_done(qtbot, win.runner, "file"):
        assert win.files.save_as(path)
        assert win.runner.is_busy("file")  # written by a worker, the window stays live
    assert path.stat().st_size > 10_000 and not win.doc.is_modified
    win2 = make_window(threaded=True)
    assert win2.files.open(path, ask=False)  # on a worker if the file is big, else at once
    qtbot.waitUntil(lambda: len(win2.doc) == 1, timeout=HANG_MS)
    assert win2.doc.objects[0].source == ps


def _mask_items(win, obj_id):  # type: ignore[no-untyped-def]
    """Every pixel image drawing the object, by name."""
    d, r, a = (
        win.views.discrete.layer(obj_id),
        win.views.region.layer(obj_id),
        win.views.analytical.layer(obj_id),
    )
    return {
        "pixels": d.mask,
        "components": r.components,
        "holes": r.holes,
        "body": a.body,
        "border": a.border,
    }


def test_big_images_are_made_ready_to_draw_on_workers_and_look_the_same(make_window, qtbot):
    """After a big object arrives, the paint only draws its images: each was converted on a worker.

    The issue: the first paint after DSS 4.5 converted about six 4 M-pixel images on the GUI thread, 6–12 ms
    each, on top of the first strokes. Here every image of a 3 M-pixel object comes with its picture, the view
    draws exactly what it would have converted itself, and selecting the object changes its opacity only.
    """
    from tests.app.helpers import grab

    win = make_window(threaded=True)
    yy, xx = np.mgrid[0:1500, 0:2000]
    m = ((xx - 1000) ** 2 / 900**2 + (yy - 750) ** 2 / 600**2 < 1) & (
        (xx - 700) ** 2 + (yy - 700) ** 2 > 150**2
    )
    ps = PixelSet(m, (0, 0))
    obj = win.doc.make_object(ps, name="big")
    win.doc.push(AddObject(obj, select=False))
    qtbot.waitUntil(lambda: win.is_drawn() and not win.runner.is_busy(), timeout=HANG_MS)
    win.registry["view.fit"].trigger()
    items = _mask_items(win, obj.id)
    for name, item in items.items():
        assert item.picture is not None, name
    before = {v.name: grab(v) for v in win.views.views[:3]}
    for name, item in items.items():
        assert item.qimage is item.picture.qimage, (name, item.qimage)  # drawn as made on the worker
    # Selecting the object makes it more opaque: the same pictures, drawn at another opacity.
    opacity = {name: item.opacity() for name, item in items.items()}
    pictures = {name: item.picture for name, item in items.items()}
    win.doc.set_selection([obj.id])
    qtbot.waitUntil(lambda: win.is_drawn() and not win.runner.is_busy(), timeout=HANG_MS)
    for v in win.views.views[:3]:
        grab(v)
    for name, item in items.items():
        assert item.picture is pictures[name] and item.qimage is item.picture.qimage, name
    assert items["pixels"].opacity() > opacity["pixels"] and items["body"].opacity() > opacity["body"]
    # What the GUI thread would have drawn without the pictures is the same, pixel for pixel.
    win.doc.set_selection([])
    qtbot.waitUntil(lambda: win.is_drawn() and not win.runner.is_busy(), timeout=HANG_MS)
    for item in items.values():
        item.picture = None
        item.qimage = None
        item._renderRequired = True
    after = {v.name: grab(v) for v in win.views.views[:3]}
    for name, img in before.items():
        assert img == after[name], name


def test_part_way_zoomed_in_the_detail_is_as_fine_as_the_screen(make_window, qtbot):
    """Between fit-all and one screen pixel per pixel the exact detail is pooled to the screen's resolution.

    The issue: zoomed in, every view change cropped and converted up to 4 M pixels on the GUI thread. Here a
    coarse image of 3 × 3 maxima, zoomed to 1–2 units per screen pixel, gets a detail of 2 × 2 maxima made on
    a worker, no bigger than a few times the view, and the one-pixel line still shows where it is.
    """
    from mrm.views.canvas import max_pool
    from tests.app.helpers import colour_at, grab, is_background

    win = make_window(threaded=True)
    m = np.zeros((4500, 4000), bool)
    m[:3500, :] = True
    m[3800, 100:3900] = True  # a one-pixel line at y = 3800
    m[-1, -1] = True
    ps = PixelSet(m, (0, 0))
    obj = win.doc.make_object(ps, name="big")
    win.doc.push(AddObject(obj, select=False))
    qtbot.waitUntil(lambda: win.is_drawn() and not win.runner.is_busy(), timeout=HANG_MS)
    dv = win.views.discrete
    item = dv.layer(obj.id).mask
    assert item.scale_factor == 3
    from tests.app.helpers import zoom_to

    zoom_to(win, 1700, 3550, 2150, 4050)
    qtbot.waitUntil(win.is_drawn, timeout=HANG_MS)
    px = dv.plane.pixels_per_unit()
    assert 1 / 2 <= px < 1
    detail = item._detail
    assert detail is not None and detail.isVisible()
    d = detail.mapRectToParent(detail.boundingRect())
    x0, y0 = round(d.left() + 0.5), round(min(d.top(), d.bottom()) + 0.5)
    h, w = detail.image.shape
    assert d.width() == 2 * w  # each detail pixel is 2 × 2 pixels of the plane
    view_pixels = dv.plane.viewport().width() * dv.plane.viewport().height()
    assert detail.image.size <= 4 * view_pixels
    exact = ps.to_array((x0, y0, x0 + 2 * w - 1, y0 + 2 * h - 1))
    assert np.array_equal(detail.image, max_pool(exact, 2))
    shown = grab(dv)
    # The line: drawn within a screen pixel (two units) of where it is.
    assert any(not is_background(dv, colour_at(dv, 1900, y, shown)) for y in np.arange(3798, 3802.1, 0.5))
    assert is_background(dv, colour_at(dv, 1900, 3700, shown))
