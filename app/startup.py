"""First start on a fresh install: compile the geometry kernels on a worker while the window shows progress.

numba compiles each kernel on its first call (a minute or more for all of them) and caches it on disk. The
set-up script fills that cache ahead of time (``python -m mrm.warmup``); after a bare ``pip install`` it is
empty, and the first derivation would compile on the GUI thread with the window black. :func:`prepare_then`
runs the warm-up on a worker instead, with a progress bar and a message in the status bar, and opens the
document when it is done.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

log = logging.getLogger(__name__)

#: The status bar's text while the kernels compile.
PREPARING = "Preparing the geometry kernels (first start only, about a minute)"


def prepare_then(win: Any, then: Callable[[], Any]) -> bool:
    """Call ``then`` once the kernels are compiled; True when a warm-up had to run first (on a worker).

    Parameters
    ----------
    win : MainWindow
        Its task runner runs the warm-up and its status bar shows the progress.
    then : callable
        What to do next (open the document); called on the GUI thread.
    """
    from mrm.warmup import is_warm, warm_up

    if is_warm():
        preload(win)
        then()
        return False
    log.info("numba cache is cold: compiling the kernels on a worker")

    def work(progress: Any) -> None:
        def report(done: int, total: int, what: str) -> None:
            step = min(done + 1, total)
            progress.update(done / total, f"{PREPARING}: {what} ({step}/{total})…")

        warm_up(report)
        win.runner.warm_processes()  # compiled: the worker process of the operations can load them now

    def failed(exc: BaseException) -> None:
        # The kernels then compile on first use instead; say so and carry on.
        log.warning("kernel warm-up failed: %s", exc)
        win.show_message(f"could not prepare the geometry kernels ahead: {exc}", 8000, error=True)
        then()

    win.show_message(f"{PREPARING}…", 0)
    win.runner.submit(
        "warmup",
        work,
        on_result=lambda _r: (win.show_message("geometry kernels ready", 3000), then()),
        on_error=failed,
        on_cancel=then,
        label=PREPARING,
        show_progress=True,
    )
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

    def work(p: Any) -> None:
        # First the worker process of the operations and measurements (ADR 0025): it loads its modules and
        # kernels meanwhile, in parallel, so that the first Apply finds it ready (ADR 0042).
        win.runner.warm_processes()
        load_kernels()
        load_view_kernels()

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
