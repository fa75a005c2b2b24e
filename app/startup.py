"""First start on a fresh install: the document opens at once while the kernels compile on a worker.

numba compiles each kernel on its first call (minutes of CPU for all of them) and caches it on disk. The
set-up script fills that cache ahead of time (``python -m mrm.warmup``); after a bare ``pip install`` it is
empty. :func:`prepare_then` then opens the document at once and compiles the kernels on a worker, with
progress in the status bar; meanwhile every derivation the views ask for runs on a worker too (the scene's
synchronous budget is zero), queued behind the compiles numba serializes, so the window never waits and no
request is refused (docs/adr/0051).
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

log = logging.getLogger(__name__)

#: The status bar's text while the kernels compile. No duration: it depends on the machine and its load
#: (one to several minutes of CPU), and the progress bar says how far it is.
PREPARING = "Compiling the geometry kernels (first start only; the document is usable meanwhile)"


def prepare_then(win: Any, then: Callable[[], Any], *, open_at_once: bool = True) -> bool:
    """Open the document (``then``) and, on a cold cache, compile the kernels on a worker; True if cold.

    Parameters
    ----------
    win : MainWindow
        Its task runner runs the warm-up and its status bar shows the progress.
    then : callable
        What to do next (open the document); called on the GUI thread.
    open_at_once : bool
        On a cold cache, call ``then`` at once (the default: the window is usable while the kernels
        compile, and what the user asks for meanwhile is queued on workers). False calls it once the
        kernels are compiled (a screenshot, which must show the finished drawing).
    """
    from mrm.warmup import STEPS, is_warm, warm_up

    if is_warm():
        preload(win)
        then()
        return False
    log.info("numba cache is cold: compiling the kernels on a worker")
    scene = win.scene
    cost = scene.sync_cost
    scene.sync_cost = 0.0  # every derivation on a worker until the kernels are compiled: none on this thread
    total = len(STEPS) + 1

    def work(progress: Any) -> None:
        def report(done: int, total_steps: int, what: str) -> None:
            step = min(done + 2, total)
            progress.update((done + 1) / total, f"{PREPARING}: {what} ({step}/{total})…")

        # First what the views call on this thread (the pools and region drawing, the PNG decoder), so that
        # the first drawings find it compiled; then every derivation and operation.
        progress.update(0.0, f"{PREPARING}: drawing kernels (1/{total})…")
        load_view_kernels()
        warm_up(report)
        win.runner.warm_processes()  # compiled: the worker process of the operations can load them now

    def finished(_r: object = None) -> None:
        scene.sync_cost = cost
        win.show_message("geometry kernels ready", 3000)
        if not open_at_once:
            then()

    def failed(exc: BaseException) -> None:
        # The kernels then compile on first use instead, each on the worker that needs it; say so, carry on.
        scene.sync_cost = cost
        log.warning("kernel warm-up failed: %s", exc)
        win.show_message(f"could not prepare the geometry kernels ahead: {exc}", 8000, error=True)
        if not open_at_once:
            then()

    def cancelled() -> None:
        scene.sync_cost = cost
        if not open_at_once:
            then()

    win.show_message(f"{PREPARING}…", 0)
    win.runner.submit(
        "warmup",
        work,
        on_result=finished,
        on_error=failed,
        on_cancel=cancelled,
        label=PREPARING,
        show_progress=True,
    )
    if open_at_once:
        then()
    return True


def preload(win: Any) -> None:
    """Load the derivation kernels from the disk cache on a worker; until then every derivation is async.

    Loading a cached kernel still costs 0.1–0.5 s on its first call: on the GUI thread that would freeze
    the window for seconds while the first document is drawn.
    """
    from mrm.warmup import load_kernels

    scene = win.scene
    cost = scene.sync_cost
    scene.sync_cost = 0.0

    def restore(_r: object = None) -> None:
        scene.sync_cost = cost

    from mrm.views.view3d import opengl_available

    gl = opengl_available()  # read here: Qt's platform is asked on the GUI thread

    def work(p: Any) -> None:
        # First the worker process of the operations and measurements (ADR 0025): it loads its modules and
        # kernels meanwhile, in parallel, so that the first Apply finds it ready (ADR 0042).
        win.runner.warm_processes()
        load_kernels()
        load_view_kernels()
        if gl:
            # pyqtgraph.opengl and PyOpenGL: 90 ms of imports the first 3D view would make on the GUI thread
            import pyqtgraph.opengl  # noqa: F401

    win.runner.submit(
        "warmup",
        work,
        on_result=restore,
        on_error=lambda _e: restore(),
        on_cancel=restore,
        at_par=True,  # the first drawings and operations wait for it (ADR 0042)
    )


def load_view_kernels() -> None:
    """Load the kernels the views and the import call on the GUI thread for small objects.

    The PNG decoder, the region labels and hole masks: each kernel's first call costs 0.1–0.5 s even from
    the disk cache.
    """
    import numpy as np

    from mrm.core.grids import PixelSet
    from mrm.reps.region import region_of
    from mrm.views.region_view import region_drawing
    from mrm.warmup import STEPS, warm_pools

    for what, step in STEPS:
        if what == "file decoders":
            step()
    yy, xx = np.mgrid[0:9, 0:9]
    ring = ((xx - 4) ** 2 + (yy - 4) ** 2 <= 12) & ((xx - 4) ** 2 + (yy - 4) ** 2 > 2)
    black = np.array([[0, 0, 0, 0], [0, 0, 0, 255]])
    region = region_of(PixelSet(ring, (0, 0)))
    region_drawing(region, black, black)
    # The pools of big objects' level-of-detail images: a kernel's first call holds the GIL while it loads.
    warm_pools(region.labels.labels, ring)


def when_exposed(win: Any, fn: Callable[[], Any], *, poll_ms: int = 15) -> None:
    """Call ``fn`` once the window is on screen and has painted once (the X server exposes it later).

    Loading a document before that first paint would leave a black window until the load returns.
    """
    from PySide6 import QtCore

    timer = QtCore.QTimer(win)
    timer.setInterval(poll_ms)

    def check() -> None:
        handle = win.windowHandle()
        if handle is None or not handle.isExposed():
            return
        timer.stop()
        timer.deleteLater()
        win.repaint()  # paint now: the first frame shows the empty window with its menus and docks
        QtCore.QTimer.singleShot(0, fn)

    timer.timeout.connect(check)
    timer.start()
