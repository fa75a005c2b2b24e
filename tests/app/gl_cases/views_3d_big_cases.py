"""Big voxel objects in the 3D views: a coarser level within the budget, arrays made off the GUI thread.

Run by tests/app/test_views_3d.py under its own Xvfb with GLX (see views_3d_cases.py).
"""

from __future__ import annotations

import numpy as np

from mrm.core.grids import VoxelSet
from mrm.document.commands import AddObject
from mrm.views import gl_mesh
from mrm.views.view3d import View3D
from tests.app.gl_cases.views_3d_cases import _frame, _hue_of, _hues, _near, _show_3d

R = 20  # a digital ball of radius 20: about 7,500 surfels


def test_a_voxel_object_over_the_budget_is_drawn_coarser_and_the_header_says_so(
    make_window, qtbot, monkeypatch
):
    monkeypatch.setattr(View3D, "SURFEL_BUDGET", 3000)
    win = make_window(threaded=True)
    z, y, x = np.mgrid[-R : R + 1, -R : R + 1, -R : R + 1]
    vs = VoxelSet(x * x + y * y + z * z <= R * R, (-R, -R, -R))
    obj = win.doc.make_object(vs, name="ball")
    win.doc.push(AddObject(obj))
    area = _show_3d(qtbot, win)
    region = win.scene.get(obj.id, "region")
    assert region.n_surfels > 3000
    for name in ("discrete3d", "region3d", "analytical3d"):
        view = area.by_name(name)
        data, items = view._items[obj.id]
        # fewer surfels than the budget, in blocks of f³ voxels, and the header says which level is shown
        assert data["factor"] >= 2 and len(data["faces"]) // 2 <= 3000, name
        assert view.coarsest_level() == data["factor"]
        assert f"blocks of {data['factor']}³ voxels" in view.status_label.text(), name
        for label in (view.header.subtitle_label, view.status_label):  # beside Slice, Paint, Erase
            shown, whole = label.displayed_text(), label.text()
            assert shown == whole or (shown.endswith("…") and whole.startswith(shown[:-1])), (name, shown)
        # the blocks cover the ball: the drawn box holds the ball's whole box of voxel cubes
        lo, hi = np.array(data["box"])
        assert (
            (lo <= -R - 0.5).all()
            and (hi >= R + 0.5).all()
            and (hi - lo <= 2 * R + 1 + 2 * data["factor"]).all()
        )
        # the GL item uploads the arrays made on the worker as they are (no per-face copies on the GUI thread)
        _frame(view)
        mesh = items[0]
        assert (
            mesh.vertexes is data["vertices"]
            and mesh.colors is data["colours"]
            and mesh.faces is data["faces"]
        )
    hues = _hues(_frame(area.by_name("discrete3d")))
    assert _near(hues, _hue_of(obj.style.fill)) > 0.9 * len(hues) > 500
    hues = _hues(_frame(area.by_name("region3d")))
    assert _near(hues, _hue_of(gl_mesh.COMPONENT_COLOURS_3D[0])) > 0.9 * len(hues) > 500
    # the analytical view's coarse surfels take their fine surfels' segment colours: several segments seen
    hues = _hues(_frame(area.by_name("analytical3d")))
    palette = {_hue_of(c) for c in gl_mesh.SEGMENT_COLOURS_3D}
    assert len({h for h in palette if _near(hues, h, 6) > 50}) >= 3


def test_a_voxel_object_within_the_budget_is_drawn_whole_with_an_empty_header(make_window, qtbot):
    win = make_window(threaded=True)
    z, y, x = np.mgrid[-R : R + 1, -R : R + 1, -R : R + 1]
    obj = win.doc.make_object(VoxelSet(x * x + y * y + z * z <= R * R, (-R, -R, -R)), name="ball")
    win.doc.push(AddObject(obj))
    area = _show_3d(qtbot, win)
    view = area.by_name("discrete3d")
    data, _items = view._items[obj.id]
    assert data["factor"] == 1 and len(data["faces"]) // 2 == win.scene.get(obj.id, "region").n_surfels
    assert view.coarsest_level() == 1 and "coarser" not in view.status_label.text()


def _two_balls(win):  # type: ignore[no-untyped-def]
    """Two balls of radius R side by side, added to the document."""
    z, y, x = np.mgrid[-R : R + 1, -R : R + 1, -R : R + 1]
    ball = x * x + y * y + z * z <= R * R
    objs = [win.doc.make_object(VoxelSet(ball, (-R + dx, -R, -R)), name=f"ball {dx}") for dx in (0, 3 * R)]
    for obj in objs:
        win.doc.push(AddObject(obj))
    return objs


def test_objects_in_view_share_the_surfel_budget_so_a_frame_stays_bounded(make_window, qtbot, monkeypatch):
    """Two balls of 7,500 surfels each under a 10,000-surfel budget: each drawn coarser, together within it.

    (Each got the whole budget before: three 10⁶-voxel objects in view took 0.5–0.8 s per frame on llvmpipe.)
    """
    monkeypatch.setattr(View3D, "SURFEL_BUDGET", 10_000)
    monkeypatch.setattr(View3D, "SURFEL_BUDGET_MIN", 1_000)
    win = make_window(threaded=True)
    objs = _two_balls(win)
    area = _show_3d(qtbot, win)
    view = area.by_name("discrete3d")
    assert all(win.scene.get(o.id, "region").n_surfels > 5_000 for o in objs)
    drawn = [view._items[o.id][0] for o in objs]
    assert all(d["factor"] >= 2 for d in drawn)
    assert sum(len(d["faces"]) // 2 for d in drawn) <= 10_000
    # one ball deleted: the other gets the whole budget back and is drawn at full detail again
    win.doc.history.undo()
    qtbot.waitUntil(win.is_drawn, timeout=60_000)
    assert view._items[objs[0].id][0]["factor"] == 1


def test_coarser_levels_are_pooled_off_the_gui_thread_once_per_object_and_view(
    make_window, qtbot, monkeypatch
):
    """Two balls over their share of the budget: the pooling of a coarser level (which reads every voxel of
    the mask) runs on a worker, and once per object and view, however many frames are drawn meanwhile.

    Before, the pooling ran on the GUI thread (100–200 ms for a 10⁶-voxel ball: the work was counted in
    surfels, not voxels); moved to a worker, each worker's result made the view forget the other objects'
    data and send them back to their workers, without end (the 3D stall benchmark never finished).
    """
    from mrm.geometry.topology import level_of_detail
    from tests.app.helpers import record_gui_thread_calls

    monkeypatch.setattr(View3D, "SURFEL_BUDGET", 10_000)
    monkeypatch.setattr(View3D, "SURFEL_BUDGET_MIN", 1_000)
    monkeypatch.setattr(View3D, "PREPARE_SYNC", 20_000)  # the voxels of the masks (69 k each) are over it
    calls = record_gui_thread_calls(monkeypatch, level_of_detail, "coarse_level")
    win = make_window(threaded=True)
    objs = _two_balls(win)
    area = _show_3d(qtbot, win)
    qtbot.wait(1000)  # frames and refreshes go on: nothing is prepared again
    assert win.is_drawn()
    pooled = ("discrete3d", "region3d", "analytical3d")  # the views that pool voxels
    assert calls and not any(calls), "a coarser level was pooled on the GUI thread"
    assert len(calls) <= len(pooled) * len(objs), f"{len(calls)} poolings for 2 objects in 3 views"
    for name in pooled:
        assert all(area.by_name(name)._items[o.id][0]["factor"] >= 2 for o in objs), name
