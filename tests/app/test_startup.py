"""First start: a cold kernel cache compiles on a worker with progress (CLI: tests/cli/test_first_run.py)."""

from __future__ import annotations

import threading
from pathlib import Path

import pytest

from mrm import warmup
from mrm.app.gui import default_example
from mrm.app.startup import PREPARING, prepare_then
from tests.app.helpers import HANG_MS


@pytest.fixture
def cold(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Path:
    """A stamp location of this test only, so the cache looks cold until a warm-up writes it."""
    stamp = tmp_path / "numba-cache" / warmup.STAMP_NAME
    monkeypatch.setattr(warmup, "stamp_path", lambda: stamp)
    return stamp


def test_cold_start_opens_the_document_at_once_and_queues_derivations_while_compiling(  # type: ignore[no-untyped-def]
    make_window, qtbot, cold, monkeypatch
):
    """Issue 31: the cold start kept the window empty behind "Preparing … about a minute" for 540 s.

    Now the document opens at once; the compile runs on a worker with progress, and what the views ask for
    meanwhile is computed on workers (never on the GUI thread), not refused.
    """
    from mrm.app import startup

    win = make_window(threaded=True)
    gate = threading.Event()
    real = startup.load_view_kernels

    def held_view_kernels() -> None:
        gate.wait(20)  # hold the compile so that the test sees the window while it runs
        real()

    monkeypatch.setattr(startup, "load_view_kernels", held_view_kernels)
    monkeypatch.setattr(warmup, "STEPS", warmup.STEPS[:3])
    opened: list[bool] = []
    example = default_example()
    shown: list[tuple[str, str]] = []  # (label, message) of every progress the status bar was given
    win.runner.progressChanged.connect(lambda label, _f, message: shown.append((label, message)))
    try:
        assert prepare_then(win, lambda: opened.append(win.files.open(example, ask=False))) is True
        # The document is there at once, while the kernels compile with progress in the status bar.
        assert opened == [True] and len(win.doc) > 0
        qtbot.waitUntil(lambda: win.status.progress_box.isVisible(), timeout=HANG_MS)
        qtbot.waitUntil(
            lambda: any(lb == PREPARING and "drawing kernels (1/4)" in m for lb, m in shown), timeout=HANG_MS
        )
        # A derivation asked for meanwhile goes to a worker (none runs on the GUI thread) and arrives.
        obj = next(iter(win.doc))
        assert win.scene.sync_cost == 0
        value = win.scene.get(obj.id, "region")
        if value is None:
            assert win.runner.is_busy(f"derive:{obj.id}:region")
        qtbot.waitUntil(lambda: win.scene.get(obj.id, "region") is not None, timeout=HANG_MS)
        assert not gate.is_set() and win.runner.is_busy("warmup")  # all that while the compile still ran
    finally:
        gate.set()
    qtbot.waitUntil(lambda: not win.runner.is_busy("warmup"), timeout=HANG_MS)
    assert warmup.is_warm()  # the stamp is written: the next start skips the compile
    assert win.scene.sync_cost > 0
    qtbot.waitUntil(lambda: not win.status.progress_box.isVisible(), timeout=HANG_MS)


def test_a_cold_screenshot_waits_for_the_kernels_before_opening(make_window, qtbot, cold, monkeypatch):
    from mrm.app import startup

    win = make_window(threaded=True)
    monkeypatch.setattr(startup, "load_view_kernels", lambda: None)
    monkeypatch.setattr(warmup, "STEPS", warmup.STEPS[:1])
    opened: list[bool] = []
    assert prepare_then(win, lambda: opened.append(True), open_at_once=False) is True
    assert not opened
    qtbot.waitUntil(lambda: bool(opened), timeout=HANG_MS)


def test_warm_start_opens_at_once_and_keeps_kernel_loading_off_the_gui_thread(make_window, qtbot, cold):
    win = make_window(threaded=True)
    warmup._write_stamp()
    opened: list[bool] = []
    assert prepare_then(win, lambda: opened.append(True)) is False
    assert opened == [True]
    assert win.scene.sync_cost == 0  # every derivation runs on a worker until the kernels are loaded
    qtbot.waitUntil(lambda: win.scene.sync_cost > 0, timeout=HANG_MS)


def test_checking_the_kernel_cache_does_not_import_numba():
    """The start asks ``is_warm()`` on the GUI thread before the document shows: importing numba there cost
    a second or more of the ≤ 5 s to a painted window (issue 10); its version comes from the metadata."""
    import subprocess
    import sys

    code = "import sys; from mrm.warmup import is_warm; is_warm(); print('numba' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_a_warm_start_starts_the_worker_process_of_the_operations_at_once(
    make_window, qtbot, cold, monkeypatch
):
    """Issue 27: the first operation after a start waited for its worker process to start and load.

    The child is started first and loads meanwhile, not after the window's own kernels are loaded.
    """
    from mrm.app import processes

    processes.close_pool()  # no child of an earlier test
    children_then: list[int] = []
    real = warmup.load_kernels

    def load_kernels() -> None:
        children_then.append(processes.pool()._count)
        real()

    monkeypatch.setattr(warmup, "load_kernels", load_kernels)
    win = make_window(threaded=True)
    warmup._write_stamp()
    with qtbot.waitSignal(
        win.runner.taskDone, timeout=HANG_MS, check_params_cb=lambda slot, _outcome: slot == "warmup"
    ):
        prepare_then(win, lambda: None)
    assert children_then == [1]  # the worker process was on its way while the window loaded its kernels
    pool = processes.pool()
    assert pool._count == 1 and len(pool._idle) == 1  # idle for the first job
