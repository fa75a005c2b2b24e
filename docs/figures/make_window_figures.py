"""Take the user guide's pictures of the window that ``mrm --screenshot`` alone cannot stage.

Run from the repository root::

    .venv/bin/python docs/figures/make_window_figures.py [NAME ...]

It drives the real main window offscreen — the same :class:`~mrm.app.main_window.MainWindow`, fresh
preferences, the bundled examples — exactly as a user would (operations applied through the Operations
panel, measures through the Measure panel), waits until every view and background computation has finished
(:func:`mrm.app.gui.wait_until_drawn`) and saves ``window.grab()``. A context menu is a window of its own, so
its picture is drawn over the window's at the place it opened.

Pictures (docs/img): ``analytical-segment.png``, ``inspector.png``, ``dark.png``, ``properties-panel.png``,
``context-menu.png``, ``measure.png``, ``label-map.png``, ``history.png``, and ``views-3d.png`` and
``compact-limit.png``, which need a display with OpenGL (the 3D views abort offscreen)::

    xvfb-run -s "-screen 0 1600x1000x24 +extension GLX" env QT_QPA_PLATFORM=xcb \
        .venv/bin/python docs/figures/make_window_figures.py views-3d
"""

from __future__ import annotations

import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "docs" / "img"
EXAMPLES = ROOT / "resources" / "examples"
SIZE = (1440, 900)


def _app() -> Any:
    from mrm.app.application import create_application

    return create_application([sys.argv[0]], offscreen=True)


def _window(theme: str = "light") -> Any:
    from mrm.app.application import theme_controller
    from mrm.app.main_window import MainWindow
    from mrm.app.settings import Preferences, make_settings

    prefs = Preferences(make_settings(Path(tempfile.mkdtemp(prefix="mrm-fig-")) / "mrm.ini"))
    theme_controller().set_preference(theme)
    win = MainWindow(prefs)
    win.resize(*SIZE)
    win.show()
    return win


def _settle(app: Any, win: Any) -> None:
    from mrm.app.gui import wait_until_drawn

    wait_until_drawn(app, win, 300)


def _save(app: Any, win: Any, name: str, *, fit: bool = True, menu: Any = None) -> Path:
    from PySide6 import QtGui

    if fit:
        win.fit_all()
    _settle(app, win)
    pm = win.grab()
    # A window grab takes the 3D panes' last frames without what is painted over them (the axis gizmo);
    # each pane's own frame buffer has it.
    from PySide6 import QtCore, QtOpenGLWidgets

    panes = [w for w in win.findChildren(QtOpenGLWidgets.QOpenGLWidget) if w.isVisible()]
    if panes:
        p = QtGui.QPainter(pm)
        for pane in panes:
            p.drawImage(pane.mapTo(win, QtCore.QPoint(0, 0)), pane.grabFramebuffer())
        p.end()
    if menu is not None:
        p = QtGui.QPainter(pm)
        p.drawPixmap(win.mapFromGlobal(menu.pos()), menu.grab())
        p.end()
    out = OUT / name
    pm.save(str(out), "PNG")
    print(out.relative_to(ROOT))
    win.close_now()
    return out


def _apply(app: Any, win: Any, op: str, **values: str) -> None:
    """Apply ``op`` from the Operations panel to the selected object, fields typed as text."""
    panel = win.operations
    panel.select_operation(op)
    for name, text in values.items():
        field = panel.control(name).field
        field.setText(text)
        field.editingFinished.emit()
    panel.apply()
    _settle(app, win)
    win.doc.set_selection([win.doc.objects[-1].id])


def analytical_segment(app: Any) -> Path:
    """The analytical view with a digital straight segment picked (its preimage in the Segments dock)."""
    win = _window()
    win.files.open(EXAMPLES / "holes-and-components.mrm", ask=False)
    _settle(app, win)
    obj = win.doc.objects[0]
    win.doc.set_selection([obj.id])
    win.scene.select_segment(obj.id, 0, 3)
    return _save(app, win, "analytical-segment.png")


def _inspector_window(app: Any, theme: str = "light") -> Any:
    win = _window(theme)
    win.files.open(EXAMPLES / "two-polygons.mrm", ask=False)
    _settle(app, win)
    win.doc.set_selection([win.doc.find("pentagon")[0].id])
    for alpha in ("2", "5", "0.1"):
        _apply(app, win, "dss", alpha=alpha)
    win.show_inspector()
    _settle(app, win)
    win.inspector.start_measure()
    _settle(app, win)
    return win


def inspector(app: Any) -> Path:
    """The error inspector on DSS 2 → DSS 5 → DSS 0.1 of the pentagon, measured."""
    return _save(app, _inspector_window(app), "inspector.png")


def dark(app: Any) -> Path:
    """The window in the dark theme."""
    win = _window("dark")
    win.files.open(EXAMPLES / "holes-and-components.mrm", ask=False)
    _settle(app, win)
    win.doc.set_selection([win.doc.objects[0].id])
    out = _save(app, win, "dark.png")
    from mrm.app.application import theme_controller

    theme_controller().set_preference("light")
    return out


def properties_panel(app: Any) -> Path:
    """The Properties panel of a polygon: name, colour, opacity, its vertex table."""
    win = _window()
    win.files.open(EXAMPLES / "two-polygons.mrm", ask=False)
    _settle(app, win)
    win.doc.set_selection([win.doc.objects[-1].id])
    win.show_properties()
    win.tools.set_tool("vertex")
    _settle(app, win)
    win.properties.table.selectRow(1)
    return _save(app, win, "properties-panel.png")


def context_menu(app: Any) -> Path:
    """The right-click menu of the discrete view, opened inside a hole."""
    win = _window()
    win.files.open(EXAMPLES / "holes-and-components.mrm", ask=False)
    _settle(app, win)
    obj = win.doc.objects[0]
    win.doc.set_selection([obj.id])
    win.fit_all()
    _settle(app, win)
    view = win.views.discrete.plane
    # Right-click inside the ring's hole: the menu offers to fill it.
    x, y = _a_hole_pixel(win, obj.id)
    gpos = view.viewport().mapToGlobal(view.map_from_plane(x, y))
    menu = win.context_menus.open_view_menu(win.views.discrete, x, y, gpos)
    _settle(app, win)
    return _save(app, win, "context-menu.png", fit=False, menu=menu)


def _a_hole_pixel(win: Any, obj_id: int) -> tuple[int, int]:
    from mrm.document.edits import hole_pixels

    ps = win.scene.get(obj_id, "discrete")
    x, y = next(iter(hole_pixels(ps)))
    return int(x), int(y)


def measure(app: Any) -> Path:
    """A two-point measure drawn in the views and the Hausdorff distance of the two polygons."""
    from mrm.views.measure import PointMeasure

    win = _window()
    win.files.open(EXAMPLES / "two-polygons.mrm", ask=False)
    _settle(app, win)
    a, b = win.doc.objects[0], win.doc.objects[-1]
    win.doc.set_selection([a.id, b.id])
    win.measure_hausdorff()
    _settle(app, win)
    tool = win.tools.tools["measure"]
    win.tools.set_tool("measure")
    ga, gb = win.scene.get(a.id, "euclidean"), win.scene.get(b.id, "euclidean")
    pa, pb = ga.representative_point(), gb.representative_point()
    tool.result = PointMeasure((round(pa.x), round(pa.y)), (round(pb.x), round(pb.y)))
    win.host.measured.emit(tool.result)
    win.host.overlayChanged.emit()
    return _save(app, win, "measure.png")


def _parcels_png(path: Path) -> None:
    """An indexed PNG of 24 "parcels" (Voronoi cells of random seeds, labels 1–24) around an empty pond."""
    import numpy as np
    from PIL import Image

    rng = np.random.default_rng(11)
    h, w = 72, 96
    yy, xx = np.mgrid[0:h, 0:w]
    seeds = rng.integers(0, (w, h), size=(24, 2))
    d = (xx[..., None] - seeds[:, 0]) ** 2 + (yy[..., None] - seeds[:, 1]) ** 2
    lab = (np.argmin(d, axis=2) + 1).astype(np.uint8)
    lab[(xx - 60) ** 2 + (yy - 30) ** 2 < 60] = 0  # a pond: a hole in the parcels around it
    im = Image.fromarray(lab, "P")
    im.putpalette([v for k in range(256) for v in (k * 9 % 256, k * 5 % 256, k * 3 % 256)])
    im.save(path)


def label_map(app: Any) -> Path:
    """A label image imported as one label map: labels, cells, the subdivision, the legend in Properties."""
    from PySide6 import QtCore

    win = _window()
    png = Path(tempfile.mkdtemp(prefix="mrm-fig-")) / "parcels.png"
    _parcels_png(png)
    win.files.import_files([png])  # the dialog proposes the label map for an indexed image
    while win.files.image_dialog is None:  # the image is read on a worker before the dialog asks
        app.processEvents(QtCore.QEventLoop.ProcessEventsFlag.WaitForMoreEvents, 50)
    win.files.image_dialog.accept()
    _settle(app, win)
    win.doc.set_selection([win.doc.objects[0].id])
    win.show_properties()
    return _save(app, win, "label-map.png")


def history(app: Any) -> Path:
    """The History panel after two operations, a rename and one undo: the undone step greyed, redo-able."""
    from mrm.document.commands import RenameObject

    win = _window()
    win.files.open(EXAMPLES / "two-polygons.mrm", ask=False)
    _settle(app, win)
    pentagon = win.doc.find("pentagon")[0]
    win.doc.set_selection([pentagon.id])
    for alpha in ("2", "0.5"):
        _apply(app, win, "dss", alpha=alpha)
    win.doc.push(RenameObject(win.doc.objects[-1].id, "small pentagon"))
    win.doc.history.undo()
    win.history_dock.show()
    win.history_dock.raise_()
    return _save(app, win, "history.png")


def views_3d(app: Any) -> Path:
    """The four 3D views: a digital octahedron (its 8 plane segments listed) and a torus, obliquely."""
    import numpy as np

    from mrm.core.grids import VoxelSet

    r = 10
    z, y, x = np.mgrid[-r : r + 1, -r : r + 1, -r : r + 1]
    octahedron = VoxelSet(np.abs(x) + np.abs(y) + np.abs(z) <= r, (-r - 14, -r, -r))
    z, y, x = np.mgrid[-5:6, -13:14, -13:14]
    torus = VoxelSet((np.hypot(x, y) - 9.0) ** 2 + z**2 <= 3.6**2, (14 - 13, -13, -5))
    win = _window()
    objects = [win.doc.make_object(octahedron, name="octahedron"), win.doc.make_object(torus, name="torus")]
    win.doc.reset(objects)  # as File ▸ Open: a document of 3D objects only opens in the 3D views
    win.doc.set_selection([objects[0].id])  # the Segments panel lists the octahedron's 8 plane segments
    win.segments_dock.show()
    win.segments_dock.raise_()
    _settle(app, win)
    win.fit_all()
    _settle(app, win)
    ana = win.scene.get(objects[0].id, "analytical")
    front = next(k for k in range(len(ana)) if ana.segment(k).plane.normal == (-1, -1, 1))
    win.segments.plane_table.selectRow(front)  # the face towards the camera, drawn in amber
    return _save(app, win, "views-3d.png", fit=False)


def compact_limit(app: Any) -> Path:
    """A bumpy volume whose R is the safety net, and Edit ▸ Discretization Model ▸ Compact R Limit… open."""
    import numpy as np
    from PySide6 import QtWidgets

    from mrm.core.grids import VoxelSet

    f = np.random.default_rng(3).random((40, 40, 40))
    for _ in range(4):  # smoothed noise: blobs, not convex, a safety net of 38,736 triangles
        for axis in range(3):
            f = (np.roll(f, 1, axis) + f + np.roll(f, -1, axis)) / 3
    win = _window()
    blobs = win.doc.make_object(VoxelSet(f > 0.5, (0, 0, 0)), name="blobs")
    win.doc.reset([blobs])
    win.doc.set_selection([blobs.id])
    _settle(app, win)
    win.fit_all()
    _settle(app, win)
    win.registry["edit.compact_limit"].trigger()
    _settle(app, win)
    dialog = win.findChild(QtWidgets.QInputDialog, "compactLimitDialog")
    dialog.move(win.mapToGlobal(win.rect().center()) - dialog.rect().center())
    _settle(app, win)
    return _save(app, win, "compact-limit.png", fit=False, menu=dialog)


def _open_3d_example(app: Any, name: str, select: str) -> Any:
    """A window on a bundled 3D example with the object ``select`` selected and its account measured."""
    from dataclasses import replace

    from PySide6 import QtCore

    from mrm.document.commands import RestyleObject
    from mrm.resources import examples_dir

    win = _window()
    win.files.open(examples_dir() / name, ask=False)
    for o in win.doc.objects:  # the selected result alone: the others overlap it (same centre)
        if o.name != select:
            win.doc.push(RestyleObject(o.id, replace(o.style, visible=False)))
    _settle(app, win)
    obj = next(o for o in win.doc.objects if o.name == select)
    win.doc.set_selection([obj.id])
    win.inspector_dock.show()
    win.inspector_dock.raise_()
    deadline = QtCore.QDeadlineTimer(300_000)
    while win.inspector.difference3d is None and not deadline.hasExpired():
        app.processEvents(QtCore.QEventLoop.ProcessEventsFlag.AllEvents, 50)
    return win


def fig12_3d(app: Any) -> Path:
    """The paper's Figure 12 on a digital octahedron: DSS 5 of DSS 1.25(A), its voxels that differ in grey."""
    win = _open_3d_example(app, "fig12-3d-octahedron.mrm", "DSS 5")
    win.inspector.overlay.setChecked(True)
    return _save(app, win, "fig12-3d.png", fit=False)


def rotation_3d(app: Any) -> Path:
    """A brick turned by 30° about (1, 1, 1) and back: not A again, within the bound."""
    win = _open_3d_example(app, "rotation-3d.mrm", "dR-30 about (1,1,1) of A1")
    return _save(app, win, "rotation-3d.png", fit=False)


FIGURES: dict[str, Callable[[Any], Path]] = {
    "label-map": label_map,
    "analytical-segment": analytical_segment,
    "inspector": inspector,
    "dark": dark,
    "properties-panel": properties_panel,
    "context-menu": context_menu,
    "measure": measure,
    "history": history,
    "views-3d": views_3d,
    "fig12-3d": fig12_3d,
    "rotation-3d": rotation_3d,
    "compact-limit": compact_limit,
}
#: The pictures that need OpenGL (made under Xvfb, see the module docstring).
GL_FIGURES = ("views-3d", "fig12-3d", "rotation-3d", "compact-limit")


def main(names: list[str]) -> int:
    """Make the pictures ``names`` (all when empty)."""
    app = _app()
    from mrm.warmup import warm_up

    warm_up()
    from PySide6 import QtGui

    offscreen = QtGui.QGuiApplication.platformName() in ("offscreen", "minimal")
    for name in names or [n for n in FIGURES if not (offscreen and n in GL_FIGURES)]:
        FIGURES[name](app)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
