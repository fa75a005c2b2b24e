"""GUI responsiveness: event → repaint medians for the editing gestures, and start-up time.

Run:  .venv/bin/python benchmarks/gui_responsiveness.py   (offscreen unless a display is set)

Measured, each over many repeats (medians, with the 90th percentile):

1. dragging a vertex of a 500-vertex polygon on a 1024² grid — target ≤ 30 ms from the mouse-move event to the
   repainted Euclidean view (the direct feedback); also the time until all four views show the moved shape
   (D(E), region and analytical recomputed, off the GUI thread);
2. a brush dab on a 2048² object — target ≤ 16 ms from the mouse-move event to the repainted discrete view;
3. the window shown after launch — target ≤ 2 s from starting the process to the first painted window;
4. the longest GUI-thread stall (a 10 ms heartbeat timer's lateness) through the issue's workflows: import,
   DSS 20 (≈ 8 M pixels), DSS 3 of that result (≈ 70 M pixels) while panning and zooming, a rotation of the
   8 M-pixel object, saving and opening the project — target ≤ 100 ms in every workflow. The peer is the
   heartbeat's lateness on the same event loop left idle. ``--stalls`` runs only this part; ``--scale F``
   shrinks every workflow's object linearly by F (F = 1: the issue's sizes); ``--trace`` samples where the GUI
   thread and the workers are every 10 ms of a stall and prints it, with the GIL waits of a probe thread, what
   the GUI thread did in each workflow's longest stall (paints, refreshes, deliveries, camera moves, garbage
   collections: wall and CPU ms) and the gaps of a probe in another process (the machine's own lateness,
   no GIL involved); ``--timeline`` prints only those two, which cost the GUI thread less. Every run prints
   the GUI thread's CPU time in the longest stall (near the stall: it was working; far below: it was
   waiting, for the GIL or a core). ``--steps 3`` stops after DSS 3. Pan and
   zoom move the shared camera every 100 ms (a wheel step with a drag: all views follow, the event loop
   repaints them); ``--forced-repaint`` moves each view alone and repaints it at once instead (the gesture of
   the previous sessions' figures).

``--stalls3d [SIDE]`` measures the 3D workflow instead (a display with OpenGL needed, e.g. an Xvfb with
GLX): a ball of SIDE³ voxels (512 by default) added and shown in the 3D views, orbiting every 100 ms while its
representations and drawing data are computed, then orbiting for 5 s; DSS 1.25 and dR 30° about (1, 1, 1) of
it applied from the Operations panel, orbiting; the project saved and opened again (target ≤ 100 ms).

``--startup [N]`` measures instead the real ``mrm`` on a virtual X server, N starts (target ≤ 5 s to the
painted window, the check of ``tests/app/test_real_display.py``).

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

    from mrm.document.commands import AddObject

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

    from mrm.core.grids import PixelSet
    from mrm.document.commands import AddObject

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


def bench_startup_x(repeats: int = 5) -> list[float]:
    """Seconds from launching the real ``mrm`` on a virtual X server (Xvfb) to its painted window.

    The same check as ``tests/app/test_real_display.py``: the window is mapped, titled with the example's
    name, and the screen read back with ``xwd`` shows more than 50 colours.
    """
    import shutil
    import tempfile

    from mrm.app.gui import default_example
    from tests.app.test_real_display import _colours, _mrm_command, _start_xvfb, _stop, read_xwd

    example = default_example()
    assert example is not None
    tmp = Path(tempfile.mkdtemp(prefix="mrm-startx-"))
    xvfb, display = _start_xvfb(tmp)
    env = {k: v for k, v in os.environ.items() if k not in ("QT_QPA_PLATFORM", "WAYLAND_DISPLAY")}
    env.update(DISPLAY=display)
    xdotool, xwd = shutil.which("xdotool"), shutil.which("xwd")
    assert xdotool and xwd, "xdotool and xwd are needed (bash .ci/setup.sh installs them)"
    times = []
    try:
        for k in range(repeats):
            home = tmp / f"run{k}"
            (home / "run").mkdir(parents=True, mode=0o700)
            env.update(HOME=str(home), XDG_CONFIG_HOME=str(home / "config"))
            env.update(XDG_RUNTIME_DIR=str(home / "run"))
            t0 = time.monotonic()
            quiet = subprocess.DEVNULL
            app = subprocess.Popen(_mrm_command(), env=env, stdout=quiet, stderr=quiet)
            try:
                while time.monotonic() - t0 < 120:
                    if app.poll() is not None:
                        print(f"   run {k + 1}: mrm exited with {app.returncode} before its window was seen")
                        break
                    wids = subprocess.run(
                        [xdotool, "search", "--onlyvisible", "--name", "MR Modeler"],
                        env=env, capture_output=True, text=True,
                    ).stdout.split()  # fmt: skip
                    if wids:
                        title = subprocess.run(
                            [xdotool, "getwindowname", wids[0]], env=env, capture_output=True, text=True
                        ).stdout
                        if example.name in title:
                            shot = [xwd, "-root", "-silent"]
                            dump = subprocess.run(shot, env=env, capture_output=True).stdout
                            if _colours(read_xwd(dump)) > 50:
                                times.append(time.monotonic() - t0)
                                break
                    time.sleep(0.02)
                else:
                    print(f"   run {k + 1}: no painted window after 120 s")
            finally:
                _stop(app)
    finally:
        _stop(xvfb)
    return times


# ---------------------------------------------------------------------------------------------- 4. stalls
class Heartbeat:
    """A 10 ms timer on the GUI thread; the longest lateness of a tick is the longest stall.

    With ``trace``, a sampler thread looks at the GUI thread every 10 ms and, while a tick is more than
    ``trace_after`` seconds late, records where the GUI thread is (``sys._current_frames``);
    :meth:`report` sums the samples up per section (:meth:`mark`). A second thread sleeps 1 ms at a time:
    when it wakes more than ``gil_after`` late, some thread held the GIL that long (a C call that does not
    release it; at the 1 ms switch interval a thread running Python gives it up within a millisecond), and
    where the other threads are then is recorded (the holder is on the line of that call).

    ``worst_cpu`` is the GUI thread's own CPU time in the longest stall: close to the stall, the GUI thread
    was working (painting); far below it, it was waiting (for the GIL, or for a core).
    """

    def __init__(
        self, interval_ms: int = 10, trace: bool = False, trace_after: float = 0.05, gil_after: float = 0.01
    ) -> None:
        import threading

        from PySide6 import QtCore

        self.interval = interval_ms / 1000
        self.trace_after = trace_after
        self.gil_after = gil_after
        self.samples: dict[str, dict[str, int]] = {}
        self._section: dict[str, int] | None = None
        self.holds: dict[str, dict[str, list[float]]] = {}  # section -> where -> GIL waits (s)
        self._holds: dict[str, list[float]] | None = None
        self.timer = QtCore.QTimer()
        self.timer.setTimerType(QtCore.Qt.TimerType.PreciseTimer)
        self.timer.setInterval(interval_ms)
        self.timer.timeout.connect(self._tick)
        self.reset()
        self.timer.start()
        if trace:
            self._gui = threading.get_ident()
            threading.Thread(target=self._sample, daemon=True).start()
            threading.Thread(target=self._probe_gil, daemon=True).start()
            import gc

            self._gc_start = 0.0
            self._ident = threading.get_ident
            gc.callbacks.append(self._gc)

    def reset(self) -> None:
        self.last = time.perf_counter()
        self.last_cpu = time.thread_time()
        self.worst = 0.0
        self.worst_cpu = 0.0
        self.worst_window = (self.last, self.last)
        self.lates: list[float] = []

    def mark(self, label: str) -> None:
        """Start a new section of the samples."""
        self._section = self.samples.setdefault(label, {})
        self._holds = self.holds.setdefault(label, {})

    def _tick(self) -> None:
        now = time.perf_counter()
        cpu = time.thread_time()  # the GUI thread's own
        late = max(0.0, now - self.last - self.interval)
        self.lates.append(late)
        if late > self.worst:
            self.worst = late
            self.worst_cpu = cpu - self.last_cpu
            self.worst_window = (self.last, now)
        self.last = now
        self.last_cpu = cpu

    def _gc(self, phase: str, info: dict[str, int]) -> None:
        """Record the cyclic collector's passes over 5 ms: they hold the GIL, in whichever thread ran them."""
        if phase == "start":
            self._gc_start = time.perf_counter()
            return
        took = time.perf_counter() - self._gc_start
        holds = self._holds
        if holds is not None and took >= 0.005:
            who = "GUI" if self._ident() == self._gui else "a worker"
            where = f"gc generation {info.get('generation')} ({who} thread)"
            holds.setdefault(where, []).append(took)

    def _probe_gil(self) -> None:
        import threading
        import traceback

        me = threading.get_ident()
        while True:
            t0 = time.perf_counter()
            time.sleep(0.001)
            waited = time.perf_counter() - t0 - 0.001
            holds = self._holds
            if holds is None or waited < self.gil_after:
                continue
            for ident, frame in sys._current_frames().items():
                if ident in (me, self._gui):
                    continue
                stack = traceback.extract_stack(frame)[::-1]
                own = [f for f in stack if _is_own(f.filename)] or stack
                if not own or "threading.py" in own[0].filename:
                    continue  # an idle pool thread
                where = f"{stack[0].name} | " + " < ".join(
                    f"{Path(f.filename).name}:{f.lineno} {f.name}" for f in own[:3]
                )
                holds.setdefault(where, []).append(waited)

    def _sample(self) -> None:
        import threading
        import traceback

        while True:
            time.sleep(0.01)
            section = self._section
            if section is None or time.perf_counter() - self.last < self.interval + self.trace_after:
                continue
            for ident, frame in sys._current_frames().items():
                if ident == threading.get_ident():
                    continue
                stack = traceback.extract_stack(frame)[::-1]  # innermost first
                own = [f for f in stack if _is_own(f.filename)] or stack
                where = " < ".join(f"{Path(f.filename).name}:{f.lineno} {f.name}" for f in own[:4])
                # A worker holding the GIL stops the GUI thread as surely as the GUI thread's own work.
                key = f"GUI: {where}" if ident == self._gui else f"worker: {stack[0].name} | {where}"
                section[key] = section.get(key, 0) + 1

    def report(self, top: int = 14) -> str:
        """Per section: the GUI thread's innermost project frames seen most often during stalls."""
        out = []
        for label, c in self.samples.items():
            if c:
                out.append(f"   {label}: {sum(c.values())} samples of 10 ms")
                for stack, n in sorted(c.items(), key=lambda kv: -kv[1])[:top]:
                    out.append(f"      {n:4d}  {stack}")
        for label, h in self.holds.items():
            if h:
                head = f"GIL waits over {self.gil_after * 1000:.0f} ms of a probe thread"
                out.append(f"   {label}: {head}, where the other threads were (count, longest, total ms)")
                for where, w in sorted(h.items(), key=lambda kv: -max(kv[1]))[:top]:
                    out.append(f"      {len(w):4d} {max(w) * 1000:6.0f} {sum(w) * 1000:7.0f}  {where}")
        return "\n".join(out)


def _is_own(path: str) -> bool:
    """Frames of MR Modeler or pyqtgraph (not of this benchmark, not of the standard library)."""
    mine = (str(ROOT) in path and "site-packages" not in path) or "pyqtgraph" in path
    return mine and "benchmarks" not in path


def _blob(scale: float) -> np.ndarray:
    """A horse-sized silhouette: a body, a neck, a head, four legs and a hole (≈ 42,000 pixels at scale 1)."""
    s = scale
    h, w = int(260 * s), int(300 * s)
    yy, xx = np.mgrid[0:h, 0:w] / s
    body = ((xx - 150) / 95) ** 2 + ((yy - 150) / 45) ** 2 < 1
    neck = (xx > 205) & (xx < 240) & (yy > 150) & (yy < 225) & (xx - 205 > (yy - 150) * 0.2)
    head = ((xx - 250) / 30) ** 2 + ((yy - 228) / 16) ** 2 < 1
    legs = np.zeros_like(body)
    for x0 in (75, 100, 195, 220):
        legs |= (xx > x0) & (xx < x0 + 14) & (yy > 20) & (yy < 150)
    hole = ((xx - 140) / 18) ** 2 + ((yy - 150) / 10) ** 2 < 1
    return ((body | neck | head | legs) & ~hole)[::-1]


def _busy_except_measuring(runner) -> bool:  # type: ignore[no-untyped-def]
    return any(not t.slot.startswith("inspect") for t in runner._running)


def run_until_drawn(app, win, beat, timeout, during=None):  # type: ignore[no-untyped-def]
    """Process events until the window is drawn and idle; ``during()`` runs every 100 ms meanwhile."""
    from PySide6 import QtCore

    t0 = time.perf_counter()
    next_during = t0
    settled = 0
    while time.perf_counter() - t0 < timeout:
        app.processEvents(QtCore.QEventLoop.ProcessEventsFlag.AllEvents, 5)
        if during is not None and time.perf_counter() >= next_during:
            during()
            next_during = time.perf_counter() + 0.1
        # The inspector's exact measurement of a 10⁸-pixel result takes minutes on a worker: the workflow
        # goes on meanwhile (its stalls still count), as a user would.
        if win.is_drawn() and not _busy_except_measuring(win.runner):
            settled += 1
            if settled > 5:
                return time.perf_counter() - t0
        else:
            settled = 0
        time.sleep(0.002)
    raise RuntimeError(f"not drawn after {timeout:.0f} s")


_BEAT: list[Heartbeat] = []

_SYSTEM_PROBE = r"""
import sys, time
last = time.perf_counter()
while True:
    time.sleep(0.001)
    now = time.perf_counter()
    if now - last > 0.011:
        print(f"{last:.6f} {now - last - 0.001:.6f}", flush=True)
    last = now
"""


class SystemProbe:
    """A separate interpreter sleeping 1 ms at a time: its lateness is the machine's, not the GIL's.

    It shares no GIL with the window, so a gap there means no core ran it (the cores busy at a higher
    priority, or the virtual machine's cores held up): the window's timers are late for the same reason.
    ``time.perf_counter`` is the same clock in both processes (``CLOCK_MONOTONIC``).
    """

    def __init__(self) -> None:
        import threading

        self.gaps: list[tuple[float, float]] = []
        self.proc = subprocess.Popen([sys.executable, "-c", _SYSTEM_PROBE], stdout=subprocess.PIPE, text=True)
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            t, g = line.split()
            self.gaps.append((float(t), float(g)))

    def summary(self, since: float, w0: float, w1: float) -> str:
        """The probe's gaps over 10 ms since ``since``, and those overlapping the window [w0, w1]."""
        gaps = [(t, g) for t, g in self.gaps if t >= since]
        inside = [g for t, g in gaps if t < w1 and t + g > w0]
        worst = max((g for _t, g in gaps), default=0.0)
        shown = ", ".join(f"{g * 1000:.0f}" for g in inside) or "none"
        head = f"system probe (another process): {len(gaps)} gaps over 10 ms, longest {worst * 1000:.0f} ms"
        return f"{head}; in the longest stall: {shown}"


def _time_gui_work(timeline: list[tuple[float, float, float, str]]) -> None:
    """Record (start, end, GUI-thread CPU, what) of the GUI thread's paints, view refreshes, task deliveries,
    camera moves and garbage collections, to say what a stall was made of (``--trace``)."""
    import gc
    import threading

    import pyqtgraph as pg

    from mrm.app.tasks import TaskRunner
    from mrm.views.base_view import RepresentationView
    from mrm.views.canvas import Camera

    def timed(cls, name, label):  # type: ignore[no-untyped-def]
        orig = getattr(cls, name)

        def wrapper(self, *a, **k):  # type: ignore[no-untyped-def]
            t0, c0 = time.perf_counter(), time.thread_time()
            try:
                return orig(self, *a, **k)
            finally:
                timeline.append((t0, time.perf_counter(), time.thread_time() - c0, label(self, *a)))

        setattr(cls, name, wrapper)

    # Before the window exists: PySide looks a Python override up once per object.
    timed(pg.GraphicsView, "paintEvent", lambda v, *_a: f"paint {getattr(v, 'name', type(v).__name__)}")
    timed(RepresentationView, "refresh", lambda v, *_a: f"refresh {v.name}")
    timed(TaskRunner, "_deliver", lambda _r, task, *_a: f"deliver {task.slot}")
    timed(Camera, "set", lambda *_a: "camera move")
    gui = threading.get_ident()
    started = [0.0, 0.0]

    def collected(phase: str, info: dict[str, int]) -> None:
        if threading.get_ident() != gui:
            return
        if phase == "start":
            started[:] = [time.perf_counter(), time.thread_time()]
        else:
            timeline.append((started[0], time.perf_counter(), time.thread_time() - started[1],
                             f"gc{info['generation']}"))  # fmt: skip

    gc.callbacks.append(collected)


def bench_stalls(
    scale: float = 1.0, timeout: float = 900.0, trace: bool = False
) -> list[tuple[str, float, float, str]]:
    import tempfile

    from PIL import Image

    from mrm.app.startup import preload

    timeline: list[tuple[float, float, float, str]] = []
    probe = None
    # --timeline: only what the GUI thread did in the longest stalls, and the other process's probe (the
    # sampler and GIL probe threads of --trace take the GIL themselves and change the timing a little).
    timed = trace or "--timeline" in sys.argv
    if timed:
        _time_gui_work(timeline)
        probe = SystemProbe()
    app, win = make_window()
    beat = Heartbeat(trace=trace)
    _BEAT[:] = [beat]
    out: list[tuple[str, float, float, str]] = []
    # As `mrm` does at start: the cached kernels load on a worker (not measured: the window is idle then).
    preload(win)
    run_until_drawn(app, win, beat, timeout)
    # The largest result the preference allows: the document's own limit on a pixel object (ADR 0010). At
    # --scale 1 DSS 3 of the DSS 20 result (a box of about 180 M pixels estimated, 70 M set) stays within it;
    # DSS 4.5, the step of earlier sessions, is a box of 404 M pixels estimated, and refused.
    from mrm.core.limits import MAX_OBJECT_PIXELS

    win.prefs.pixel_limit = MAX_OBJECT_PIXELS
    # The peer: the same heartbeat on the same loop, idle for 2 s.
    beat.mark("idle")
    beat.reset()
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < 2.0:
        app.processEvents()
        time.sleep(0.002)
    out.append(("idle event loop (peer)", beat.worst, 2.0, ""))
    tmp = Path(tempfile.mkdtemp(prefix="mrm-stalls-"))
    png = tmp / "horse.png"
    Image.fromarray(_blob(scale).astype(np.uint8) * 255, "L").save(png)
    panel = win.operations

    def step(label: str, action, during=None) -> None:  # type: ignore[no-untyped-def]
        beat.mark(label)
        beat.reset()
        t = time.perf_counter()
        action()
        took = run_until_drawn(app, win, beat, timeout, during)
        if timed:
            w0, w1 = beat.worst_window
            inside = [e for e in timeline if e[1] > w0 and e[0] < w1]
            work = "; ".join(f"{lab} {(b - a) * 1000:.0f}/{c * 1000:.0f}" for a, b, c, lab in inside)
            gap = f"{(w1 - w0) * 1000:.0f} ms between ticks"
            print(f"      in the longest stall ({gap}), GUI work (wall/CPU ms): {work or 'none'}")
            if probe is not None:
                print(f"      {probe.summary(t, w0, w1)}")
            timeline.clear()
        obj = win.scene.primary()
        ps = win.doc.derived(obj.id).peek("discrete") if obj is not None else None
        size = f"{ps.count:,} pixels" if ps is not None else ""
        out.append((label, beat.worst, time.perf_counter() - t if took else 0.0, size))
        print(f"   {label:<44} longest stall {beat.worst * 1000:8.1f} ms   ({time.perf_counter() - t:6.1f} s"
              f"{', ' + size if size else ''}; the GUI thread's CPU in it {beat.worst_cpu * 1000:.0f} ms)",
              flush=True)  # fmt: skip
        note = panel.status.text()
        if note:
            print(f"      panel: {note}", flush=True)
        if win.inspector.is_measuring():
            print("      (the inspector's measurement still runs on a worker)", flush=True)

    def apply(op: str, value: float, name: str) -> None:
        panel.select_operation(op)
        panel.control(name).set_value(value)
        panel.apply()

    steps = int(sys.argv[sys.argv.index("--steps") + 1]) if "--steps" in sys.argv else 99
    step("import (PNG)", lambda: win.files.import_files([png]))
    step("DSS 20", lambda: apply("dss", 20.0, "alpha"))
    big = win.scene.primary()
    zoom = [1.0]

    forced = "--forced-repaint" in sys.argv

    def pan_zoom() -> None:
        zoom[0] = 0.8 if zoom[0] > 1 else 1.25
        if forced:  # the previous sessions' gesture: each view moved alone and repainted at once
            for v in win.views.visible_views():
                v.plane.vb.scaleBy((zoom[0], zoom[0]))
                v.plane.vb.translateBy((3.0, 2.0))
                v.plane.viewport().repaint()
            return
        # What a wheel step with a drag does: the shared camera moves every view, the event loop repaints.
        cam = win.views.camera
        cam.set(cam.cx + 3.0, cam.cy + 2.0, cam.scale * zoom[0])

    step("DSS 3 of the result, panning and zooming", lambda: apply("dss", 3.0, "alpha"), pan_zoom)
    if steps <= 3:
        win.close_now()
        if probe is not None:
            probe.proc.kill()
        return out
    huge = win.scene.primary()
    if big is not None:
        win.doc.set_selection([big.id])
    step("rotation 30° of the DSS 20 result", lambda: apply("discrete_rotation", 30.0, "angle"), pan_zoom)
    project = tmp / "big.mrm"
    step("save the project", lambda: win.files.save_as(project))
    mb = project.stat().st_size / 1e6 if project.exists() else 0.0
    out[-1] = (out[-1][0], out[-1][1], out[-1][2], f"{mb:.0f} MB")
    step(f"open the project ({mb:.0f} MB)", lambda: win.files.open(project, ask=False))
    del huge
    beat.mark("closing (not measured)")
    win.close_now()
    if probe is not None:
        probe.proc.kill()
    return out


def bench_stalls_3d(side: int = 512, timeout: float = 1800.0) -> list[tuple[str, float, float, str]]:
    """The longest GUI-thread stalls of the 3D workflow: a ball of ``side``³ voxels added, the 3D views shown
    (their surfaces drawn at a coarser level beyond the views' budget), orbiting every 100 ms while the
    region, the plane segments and the polyhedron are computed; then orbiting the drawn views for 5 s.

    Needs a display with OpenGL (an Xvfb with GLX: ``Xvfb :91 -screen 0 1600x1200x24 +extension GLX``).
    """
    from PySide6 import QtCore

    from mrm.app.startup import preload
    from mrm.core.grids import VoxelSet
    from mrm.document.commands import AddObject
    from mrm.views.view3d import opengl_available

    app, win = make_window()
    if not opengl_available():
        raise RuntimeError("the 3D workflow needs a display with OpenGL (run it under Xvfb +extension GLX)")
    beat = Heartbeat(trace="--trace" in sys.argv)
    _BEAT[:] = [beat]
    preload(win)
    run_until_drawn(app, win, beat, timeout)
    out: list[tuple[str, float, float, str]] = []
    beat.reset()
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < 2.0:
        app.processEvents()
        time.sleep(0.002)
    out.append(("idle event loop (peer)", beat.worst, 2.0, ""))
    r = (side - 1) / 2
    c = np.arange(side, dtype=np.float32) - r
    ball = (c[:, None, None] ** 2 + c[None, :, None] ** 2 + c[None, None, :] ** 2) <= r * r
    vs = VoxelSet(ball, (0, 0, 0))
    del ball
    voxels = int(vs.count)

    def orbit() -> None:
        area = win.views.area3d
        if area is not None and area.views:
            p = area.camera.params()
            area.camera.set(azimuth=float(p.get("azimuth", 0.0)) + 4.0)

    def step(label: str, action, during=None, seconds: float = 0.0) -> None:  # type: ignore[no-untyped-def]
        beat.mark(label)
        beat.reset()
        t = time.perf_counter()
        action()
        if seconds:
            next_during = t
            while time.perf_counter() - t < seconds:
                app.processEvents(QtCore.QEventLoop.ProcessEventsFlag.AllEvents, 5)
                if during is not None and time.perf_counter() >= next_during:
                    during()
                    next_during = time.perf_counter() + 0.1
                time.sleep(0.002)
        else:
            run_until_drawn(app, win, beat, timeout, during)
        took = time.perf_counter() - t
        area = win.views.area3d
        level = max((getattr(v, "coarsest_level", lambda: 1)() for v in area.views), default=1) if area else 1
        note = f"{voxels:,} voxels, drawn at level {level}"
        out.append((label, beat.worst, took, note))
        print(f"   {label:<52} longest stall {beat.worst * 1000:8.1f} ms   ({took:6.1f} s; {note}; "
              f"the GUI thread's CPU in it {beat.worst_cpu * 1000:.0f} ms)", flush=True)  # fmt: skip

    def add_and_show() -> None:
        win.doc.push(AddObject(win.doc.make_object(vs, name=f"ball{side}"), select=True))
        if win.views.dimension != 3:
            win.registry["view.three_d"].trigger()

    step(f"add a {side}³ ball, show the 3D views, orbit while computing", add_and_show, orbit)
    step("orbit the drawn views for 5 s", lambda: None, orbit, seconds=5.0)
    panel = win.operations
    ball_id = win.doc.objects[-1].id

    def apply3d(op: str, **values: object) -> None:
        win.doc.set_selection([ball_id])
        panel.select_operation(op)
        panel.inputs[0].setCurrentIndex(panel.inputs[0].findData(ball_id))
        for name, value in values.items():
            panel.control(name).set_value(value)
        panel.apply()

    # the paper's operations on the ball from the Operations panel (issue 30): the work and the result's
    # representations on workers, the inspector's measurement in a worker process, orbiting all along
    step("DSS 1.25 of the ball from the panel, orbiting", lambda: apply3d("dss", alpha=1.25), orbit)
    step(
        "dR 30° about (1,1,1) of the ball, orbiting",
        lambda: apply3d("discrete_rotation", angle=30.0, axis=(1.0, 1.0, 1.0)),
        orbit,
    )
    import tempfile

    project = Path(tempfile.mkdtemp(prefix="mrm-stalls3d-")) / "balls.mrm"
    step("save the project", lambda: win.files.save_as(project))
    step("open the project, orbiting while it is drawn", lambda: win.files.open(project, ask=False), orbit)
    win.close_now()
    return out


def main() -> int:
    args = sys.argv[1:]
    scale = float(args[args.index("--scale") + 1]) if "--scale" in args else 1.0
    if "--startup" in args:
        n = int(args[args.index("--startup") + 1]) if len(args) > args.index("--startup") + 1 else 5
        st = bench_startup_x(n)
        load = Path("/proc/loadavg").read_text().split()[0]
        print(f"window painted on a real X server (Xvfb) after launching `mrm` (target ≤ 5 s), load {load}")
        print(f"   median {statistics.median(st):.2f} s  (runs: " + ", ".join(f"{t:.2f}" for t in st) + ")")
        return 0
    if "--stalls3d" in args:
        i = args.index("--stalls3d")
        side = int(args[i + 1]) if len(args) > i + 1 and args[i + 1].isdigit() else 512
        print(f"4b. longest GUI-thread stall in the 3D workflow (target ≤ 100 ms), a {side}³ ball")
        rows = bench_stalls_3d(side)
        peer = max(rows[0][1], 1e-4)
        print(f"   peer: idle event loop                         longest stall {rows[0][1] * 1000:8.1f} ms")
        for label, worst, _took, _size in rows[1:]:
            print(f"   ratio to the peer, {label:<52} {worst / peer:8.1f}×")
        if "--trace" in args:
            print("   where the GUI thread was during the stalls (innermost project frames):")
            print(_BEAT[0].report() if _BEAT else "")
        return 0
    if "--stalls" in args:
        print(f"4. longest GUI-thread stall per workflow (target ≤ 100 ms), scale {scale:g}")
        trace = "--trace" in args
        rows = bench_stalls(scale, trace=trace)
        peer = max(rows[0][1], 1e-4)
        print(f"   peer: idle event loop                         longest stall {rows[0][1] * 1000:8.1f} ms")
        for label, worst, _took, _size in rows[1:]:
            print(f"   ratio to the peer, {label:<40} {worst / peer:8.1f}×")
        if trace:
            print("   where the GUI thread was during the stalls (innermost project frames):")
            print(_BEAT[0].report() if _BEAT else "")
        return 0
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
