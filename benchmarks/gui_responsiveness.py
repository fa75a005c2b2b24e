"""GUI responsiveness: event → repaint medians for the editing gestures, and start-up time.

Run:  .venv/bin/python benchmarks/gui_responsiveness.py   (offscreen unless a display is set)

Measured, each over many repeats (medians, with the 90th percentile):

1. dragging a vertex of a 500-vertex polygon on a 1024² grid — target ≤ 30 ms from the mouse-move event to the
   repainted Euclidean view (the direct feedback); also the time until all four views show the moved shape
   (D(E), region and analytical recomputed, off the GUI thread);
2. a brush dab on a 2048² object — target ≤ 16 ms from the mouse-move event to the repainted discrete view;
3. the window shown after launch — target ≤ 2 s from starting the process to the first painted window.

Peer measured in the same run: bare pyqtgraph — a PlotWidget repainting after ``ImageItem.setImage`` of the
same 2048² mask, and after ``PlotCurveItem.setData`` of the same 500-vertex ring. It is the floor any
pyqtgraph application pays; the ratio says what MR Modeler adds on top.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
if not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY"):
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("MRM_SETTINGS_ISOLATED", "1")

import numpy as np  # noqa: E402


def summary(ts: list[float]) -> str:
    ms = sorted(t * 1000 for t in ts)
    p90 = ms[min(len(ms) - 1, int(0.9 * len(ms)))]
    return f"median {statistics.median(ms):7.2f} ms   p90 {p90:7.2f} ms   (n={len(ms)})"


def make_window():  # type: ignore[no-untyped-def]
    from mrm.app.application import create_application

    app = create_application()
    from mrm.app.main_window import MainWindow
    from mrm.app.settings import Preferences, make_settings

    win = MainWindow(Preferences(make_settings()), autosave_dir=Path("/tmp") / "mrm-bench-autosave")
    win.resize(1400, 900)
    win.show()
    for _ in range(5):
        app.processEvents()
    return app, win


def wait_drawn(app, win, timeout: float = 60.0) -> float:  # type: ignore[no-untyped-def]
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < timeout:
        app.processEvents()
        if win.is_drawn() and not win.runner.is_busy():
            return time.perf_counter() - t0
        time.sleep(0.0005)
    raise RuntimeError("the views were not drawn in time")


def send_mouse(widget, kind, pos, button):  # type: ignore[no-untyped-def]
    from PySide6 import QtCore, QtGui, QtWidgets

    Qt = QtCore.Qt
    t = {"press": QtCore.QEvent.Type.MouseButtonPress, "move": QtCore.QEvent.Type.MouseMove,
         "release": QtCore.QEvent.Type.MouseButtonRelease}[kind]  # fmt: skip
    buttons = Qt.MouseButton.NoButton if kind == "release" else button
    ev = QtGui.QMouseEvent(
        t, QtCore.QPointF(pos), QtCore.QPointF(widget.mapToGlobal(pos)), button if kind != "move" else
        Qt.MouseButton.NoButton, buttons, Qt.KeyboardModifier.NoModifier,
    )  # fmt: skip
    QtWidgets.QApplication.sendEvent(widget, ev)


# ------------------------------------------------------------------------------------------- vertex drag
def bench_vertex_drag(moves: int = 60) -> tuple[list[float], list[float]]:
    from PySide6 import QtCore
    from shapely.geometry import Polygon

    from mrm.commands import AddObject

    app, win = make_window()
    k = np.arange(500)
    r = 480 + 30 * np.sin(k * 0.37)
    ring = np.stack([512 + r * np.cos(2 * np.pi * k / 500), 512 + r * np.sin(2 * np.pi * k / 500)], axis=1)
    poly = Polygon(ring)
    win.doc.push(AddObject(win.doc.make_object(poly, name="ring500"), select=True))
    win.views.camera.fit((0, 0, 1024, 1024))
    wait_drawn(app, win)
    win.tools.set_tool("vertex")
    view = win.views.euclidean
    vp = view.plane.viewport()
    x0, y0 = ring[0]
    start = view.plane.map_from_plane(float(x0), float(y0))
    send_mouse(vp, "move", start, QtCore.Qt.MouseButton.NoButton)
    send_mouse(vp, "press", start, QtCore.Qt.MouseButton.LeftButton)
    direct: list[float] = []
    follow: list[float] = []
    for i in range(moves):
        pos = QtCore.QPoint(start.x() - 1 - (i % 20), start.y() + (i % 7))
        t0 = time.perf_counter()
        send_mouse(vp, "move", pos, QtCore.Qt.MouseButton.LeftButton)
        view.refresh()  # what the 0 ms timer would run next
        vp.repaint()
        direct.append(time.perf_counter() - t0)
        wait_drawn(app, win)
        for v in win.views.views:
            v.plane.viewport().repaint()
        follow.append(time.perf_counter() - t0)
    send_mouse(vp, "release", pos, QtCore.Qt.MouseButton.LeftButton)
    assert win.doc.history.undo_label() == "Move vertex"
    win.close_now()
    return direct, follow


# ---------------------------------------------------------------------------------------------- 2. brush dab
def bench_brush(dabs: int = 80) -> list[float]:
    from PySide6 import QtCore

    from mrm.commands import AddObject
    from mrm.reps.pixels import PixelSet

    app, win = make_window()
    yy, xx = np.mgrid[0:2048, 0:2048]
    mask = (xx - 1024) ** 2 + (yy - 1024) ** 2 < 1000**2
    win.doc.push(AddObject(win.doc.make_object(PixelSet(mask, (0, 0)), name="disk2048"), select=True))
    wait_drawn(app, win, timeout=300)
    win.views.camera.fit((0, 0, 2048, 2048))
    wait_drawn(app, win, timeout=300)
    win.tools.set_tool("erase")
    win.brush_spin.setValue(9)
    view = win.views.discrete
    vp = view.plane.viewport()
    start = view.plane.map_from_plane(1024.0, 1024.0)
    send_mouse(vp, "move", start, QtCore.Qt.MouseButton.NoButton)
    send_mouse(vp, "press", start, QtCore.Qt.MouseButton.LeftButton)
    times: list[float] = []
    for i in range(dabs):
        pos = QtCore.QPoint(start.x() + (i % 40) * 2, start.y() + (i // 40) * 3)
        t0 = time.perf_counter()
        send_mouse(vp, "move", pos, QtCore.Qt.MouseButton.LeftButton)
        vp.repaint()
        times.append(time.perf_counter() - t0)
        app.processEvents()
    send_mouse(vp, "release", pos, QtCore.Qt.MouseButton.LeftButton)
    assert win.doc.history.undo_label() == "Erase"
    win.close_now()
    return times


# ---------------------------------------------------------------------------------------------- peer
def bench_peer(repeats: int = 60) -> tuple[list[float], list[float]]:
    import pyqtgraph as pg
    from PySide6 import QtWidgets

    from mrm.app.application import create_application

    app = create_application()
    w = pg.PlotWidget()
    w.resize(560, 420)
    w.show()
    yy, xx = np.mgrid[0:2048, 0:2048]
    mask = ((xx - 1024) ** 2 + (yy - 1024) ** 2 < 1000**2).astype(np.uint8)
    img = pg.ImageItem(axisOrder="row-major")
    w.addItem(img)
    img.setImage(mask, levels=(0, 1))
    w.getViewBox().autoRange()
    app.processEvents()
    image_times = []
    for i in range(repeats):
        mask[1000 + i % 20, 1000:1009] ^= 1
        t0 = time.perf_counter()
        img.setImage(mask, autoLevels=False)
        w.viewport().repaint()
        image_times.append(time.perf_counter() - t0)
    k = np.arange(501)
    curve = pg.PlotCurveItem()
    w.clear()
    w.addItem(curve)
    curve_times = []
    for i in range(repeats):
        x = 512 + 480 * np.cos(2 * np.pi * k / 500)
        y = 512 + 480 * np.sin(2 * np.pi * k / 500)
        x[0] = x[-1] = 512 + 480 + i % 10
        t0 = time.perf_counter()
        curve.setData(x, y)
        w.viewport().repaint()
        curve_times.append(time.perf_counter() - t0)
    w.close()
    QtWidgets.QApplication.processEvents()
    return image_times, curve_times


# ---------------------------------------------------------------------------------------------- 3. start-up
STARTUP = r"""
import os, sys, time
t0 = float(sys.argv[1])
sys.path.insert(0, sys.argv[2])
from PySide6 import QtCore
from mrm.app.application import create_application
app = create_application()
from mrm.app.main_window import MainWindow
from mrm.app.settings import Preferences, make_settings
from mrm.app.gui import default_example
win = MainWindow(Preferences(make_settings()))
win.resize(1400, 900)
class Probe(QtCore.QObject):
    def eventFilter(self, obj, ev):
        if ev.type() == QtCore.QEvent.Type.Paint:
            print(f"{time.time() - t0:.4f}", flush=True)
            os._exit(0)
        return False
probe = Probe()
win.views.discrete.plane.viewport().installEventFilter(probe)
win.show()
ex = default_example()
if ex is not None:  # as `mrm` does: the document loads once the window is up
    QtCore.QTimer.singleShot(0, lambda: win.files.open(ex, ask=False))
app.exec()
"""


def bench_startup(repeats: int = 5) -> list[float]:
    times = []
    for _ in range(repeats):
        t0 = time.time()
        out = subprocess.run(
            [sys.executable, "-c", STARTUP, repr(t0), str(ROOT)], capture_output=True, text=True, timeout=120
        )
        line = out.stdout.strip().splitlines()
        if not line:
            raise RuntimeError(f"start-up probe failed: {out.stderr[-2000:]}")
        times.append(float(line[-1]))
    return times


def main() -> int:
    print(
        "MR Modeler GUI responsiveness (offscreen)"
        if os.environ.get("QT_QPA_PLATFORM") == "offscreen"
        else ""
    )
    peer_image, peer_curve = bench_peer()
    direct, follow = bench_vertex_drag()
    print("1. drag a vertex of a 500-vertex polygon on a 1024² grid (target ≤ 30 ms)")
    print(f"   event → Euclidean view repainted   {summary(direct)}")
    print(f"   event → all four views repainted   {summary(follow)}")
    print(f"   peer: pyqtgraph curve setData+repaint {summary(peer_curve)}")
    print(f"   ratio (median) to the peer: {statistics.median(direct) / statistics.median(peer_curve):.1f}×")
    dab = bench_brush()
    print("2. brush dab on a 2048² object (target ≤ 16 ms)")
    print(f"   event → discrete view repainted    {summary(dab)}")
    print(f"   peer: pyqtgraph setImage+repaint   {summary(peer_image)}")
    print(f"   ratio (median) to the peer: {statistics.median(dab) / statistics.median(peer_image):.2f}×")
    st = bench_startup()
    print("3. window shown after launch (target ≤ 2 s)")
    print(f"   process start → first paint        median {statistics.median(st):.2f} s  (runs: "
          + ", ".join(f"{t:.2f}" for t in st) + ")")  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main())
