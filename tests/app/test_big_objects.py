"""Big objects: drawing data made on workers, coarser images beyond 4 M pixels, big files on workers.

The issue: after DSS 20 the window ignored the mouse for ~9 s while the views built their images and paths on
the GUI thread. Here the layers of a 5 M-pixel object wait for their data (the view says "computing…") instead
of computing it on the GUI thread, and the discrete view shows an image of at most 4 M pixels covering it.
"""

from __future__ import annotations

import numpy as np

from mrm.commands import AddObject
from mrm.reps.pixels import PixelSet
from mrm.views.canvas import LOD_PIXELS, lod_image


def test_lod_image_keeps_every_pixel_visible():
    m = np.zeros((3001, 2001), bool)
    m[1500, :] = True  # a one-pixel line
    m[7, 9] = True  # a lone pixel
    img, f = lod_image(m, limit=1_000_000)
    assert f == 3 and img.size <= 1_000_000
    assert img[500].all()  # the line is still drawn across
    assert img[7 // 3, 9 // 3] == 1 and img.sum() == img.shape[1] + 1


def test_a_big_object_is_prepared_off_the_gui_thread_and_shown_coarser(make_window, qtbot):
    win = make_window(threaded=True)
    m = np.ones((2000, 2500), bool)
    m[470:480, 210:230] = False  # a hole, seen when zoomed in at x 110 … 129, y 510 … 519
    ps = PixelSet(m, (-100, 40))
    obj = win.doc.make_object(ps, name="big")
    win.doc.push(AddObject(obj, select=True))
    dv = win.views.discrete
    # Right after the change nothing heavy ran on the GUI thread: the layer waits for a worker's image.
    dv.refresh()
    layer = dv.layer(obj.id)
    assert layer is not None and layer.waiting and not win.is_drawn()
    qtbot.waitUntil(lambda: win.is_drawn() and not win.runner.is_busy(), timeout=120_000)
    item = layer.mask
    assert item.image.size <= LOD_PIXELS and item.scale_factor == 2
    r = item.mapRectToParent(item.boundingRect())
    assert (r.left(), r.bottom() if r.bottom() > r.top() else r.top()) == (-100.5, 40 - 0.5 + 2000)
    assert r.width() == 2500
    # Zoomed in, the exact pixels of the visible part are drawn over the coarse image (nothing blocky).
    from tests.app.helpers import zoom_to

    zoom_to(win, 100, 500, 160, 540)
    detail = item._detail
    assert detail is not None and detail.isVisible()
    d = detail.mapRectToParent(detail.boundingRect())
    x0, y0 = int(d.left() + 0.5), int(min(d.top(), d.bottom()) + 0.5)
    w, h = round(d.width()), round(abs(d.height()))
    assert x0 <= 100 and x0 + w >= 160 and y0 <= 500 and y0 + h >= 540
    exact = ps.to_array((x0, y0, x0 + w - 1, y0 + h - 1))
    assert not exact.all()  # the hole is in view
    assert np.array_equal(detail.image.astype(bool), exact)
    # The other views drew it too, with their own prepared data.
    assert win.views.region.layer(obj.id).components.image.size <= LOD_PIXELS
    assert not win.views.euclidean.layer(obj.id).polygon.path().isEmpty()


def test_a_big_project_is_saved_and_opened_on_a_worker(make_window, qtbot, tmp_path):
    win = make_window(threaded=True)
    m = np.ones((4000, 4500), bool)
    m[1000:3000, 1000:3500] = False  # a frame: big, with a hole, cheap to derive
    ps = PixelSet(m, (0, 0))
    win.doc.push(AddObject(win.doc.make_object(ps, name="frame"), select=True))
    qtbot.waitUntil(lambda: win.is_drawn() and not win.runner.is_busy(), timeout=120_000)
    path = tmp_path / "big.mrm"
    assert win.files.save_as(path)
    assert win.runner.is_busy("file")  # written by a worker, the window stays live
    qtbot.waitUntil(lambda: not win.runner.is_busy("file"), timeout=120_000)
    assert path.stat().st_size > 10_000 and not win.doc.is_modified
    win2 = make_window(threaded=True)
    assert win2.files.open(path, ask=False)
    qtbot.waitUntil(lambda: len(win2.doc) == 1, timeout=120_000)
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
    qtbot.waitUntil(lambda: win.is_drawn() and not win.runner.is_busy(), timeout=120_000)
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
    qtbot.waitUntil(lambda: win.is_drawn() and not win.runner.is_busy(), timeout=120_000)
    for v in win.views.views[:3]:
        grab(v)
    for name, item in items.items():
        assert item.picture is pictures[name] and item.qimage is item.picture.qimage, name
    assert items["pixels"].opacity() > opacity["pixels"] and items["body"].opacity() > opacity["body"]
    # What the GUI thread would have drawn without the pictures is the same, pixel for pixel.
    win.doc.set_selection([])
    qtbot.waitUntil(lambda: win.is_drawn() and not win.runner.is_busy(), timeout=120_000)
    for item in items.values():
        item.picture = None
        item.qimage = None
        item._renderRequired = True
    after = {v.name: grab(v) for v in win.views.views[:3]}
    for name, img in before.items():
        assert img == after[name], name
