"""The task runner: work off the GUI thread, progress, cancel, latest request wins, stale results dropped."""

from __future__ import annotations

import threading

import pytest
from PySide6 import QtCore

from mrm.app.tasks import WORKER_NICENESS, SynchronousTaskRunner, TaskRunner
from mrm.core.errors import Cancelled
from tests.app.helpers import HANG_MS


def _spin(progress, steps=10_000, gate=None):  # type: ignore[no-untyped-def]
    """A long computation that reports progress (and so can be cancelled) at every step."""
    if gate is not None:
        gate.wait(10)
    total = 0
    for i in range(steps):
        progress.update(i / steps, f"step {i}")
        total += i
    return total


def test_results_arrive_on_the_gui_thread(qtbot):
    runner = TaskRunner()
    gui = threading.get_ident()
    seen = {}

    def work(_p):  # type: ignore[no-untyped-def]
        seen["worker"] = threading.get_ident()
        return 42

    def done(v):  # type: ignore[no-untyped-def]
        seen["result"] = (v, threading.get_ident())

    with qtbot.waitSignal(runner.idle, timeout=10_000):
        runner.submit("a", work, on_result=done)
    assert seen["result"] == (42, gui) and seen["worker"] != gui
    runner.shutdown()


def test_a_new_request_in_the_same_slot_cancels_the_previous(qtbot):
    runner = TaskRunner()
    gate = threading.Event()
    outcomes = []
    runner.taskDone.connect(lambda slot, outcome: outcomes.append(outcome))
    results = []
    runner.submit("preview", lambda p: _spin(p, 10**7, gate), on_result=results.append)
    runner.submit("preview", lambda p: _spin(p, 10), on_result=results.append)
    gate.set()
    qtbot.waitUntil(lambda: len(outcomes) == 2, timeout=HANG_MS)
    assert results == [sum(range(10))]  # only the newest result is delivered
    assert sorted(outcomes) == ["cancelled", "result"]
    runner.shutdown()


def test_results_of_an_older_revision_are_dropped(qtbot):
    runner = TaskRunner()
    rev = [1]
    runner.revision_getter = lambda: rev[0]
    gate = threading.Event()
    results = []
    outcomes = []
    runner.taskDone.connect(lambda s, o: outcomes.append(o))
    runner.submit("derive", lambda p: (gate.wait(10), "old")[1], on_result=results.append, revision=1)
    rev[0] = 2  # the document changed while the task ran
    gate.set()
    qtbot.waitUntil(lambda: outcomes == ["dropped"], timeout=HANG_MS)
    assert results == []
    runner.shutdown()


def test_cancel_a_long_task_through_the_status_bar(make_window, qtbot):
    win = make_window(threaded=True)
    runner = win.runner
    gate = threading.Event()
    cancelled = []
    results = []
    runner.submit(
        "operation",
        lambda p: _spin(p, 10**8, gate),
        on_result=results.append,
        on_cancel=lambda: cancelled.append(True),
        label="Long operation",
        show_progress=True,
    )
    gate.set()
    qtbot.waitUntil(lambda: win.status.progress_box.isVisible(), timeout=HANG_MS)
    # The window stays responsive: progress is reported while the work runs.
    qtbot.waitUntil(lambda: win.status.progress.value() > 0, timeout=HANG_MS)
    assert "step" in win.status.progress_label.text()
    qtbot.mouseClick(win.status.cancel_button, QtCore.Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: cancelled == [True], timeout=HANG_MS)
    assert results == []
    assert not win.status.progress_box.isVisible()
    assert not runner.is_busy()


def test_escape_cancels_the_running_task(make_window, qtbot):
    win = make_window(threaded=True)
    gate = threading.Event()
    cancelled = []
    win.runner.submit(
        "operation",
        lambda p: _spin(p, 10**8, gate),
        on_cancel=lambda: cancelled.append(1),
        show_progress=True,
    )
    gate.set()
    qtbot.waitUntil(lambda: win.status.progress_box.isVisible(), timeout=HANG_MS)
    win.views.discrete.plane.setFocus()
    qtbot.keyClick(win.views.discrete.plane, QtCore.Qt.Key.Key_Escape)
    qtbot.waitUntil(lambda: cancelled == [1], timeout=HANG_MS)


def test_progress_raises_cancelled_after_cancel():
    runner = SynchronousTaskRunner()
    seen = []

    def work(p):  # type: ignore[no-untyped-def]
        p.cancel()
        with pytest.raises(Cancelled):
            p.update(0.5)
        seen.append("raised")
        raise Cancelled("stop")

    runner.submit("x", work, on_cancel=lambda: seen.append("cancelled"))
    assert seen == ["raised", "cancelled"]


def test_errors_go_to_the_error_callback(qtbot):
    runner = TaskRunner()
    errors = []

    def boom(_p):  # type: ignore[no-untyped-def]
        raise ValueError("bad input")

    with qtbot.waitSignal(runner.idle, timeout=10_000):
        runner.submit("x", boom, on_error=errors.append)
    assert isinstance(errors[0], ValueError) and "bad input" in str(errors[0])
    runner.shutdown()


def test_workers_run_below_the_gui_threads_priority(qtbot):
    """On a loaded machine the window must get the CPU before the derivations (issue 10: never blocks).

    Per-thread nice levels are Linux's (the platform of the project's CI and set-up).
    """
    import os

    from mrm.app.tasks import WORKER_NICENESS

    runner = TaskRunner()
    seen = []
    runner.submit(
        "x", lambda p: os.getpriority(os.PRIO_PROCESS, threading.get_native_id()), on_result=seen.append
    )
    qtbot.waitUntil(lambda: bool(seen), timeout=HANG_MS)
    gui = os.getpriority(os.PRIO_PROCESS, threading.get_native_id())
    assert seen[0] == min(19, gui + WORKER_NICENESS)
    runner.shutdown()


def test_a_task_at_par_runs_at_the_windows_priority(qtbot):
    """A lowered thread holding the GIL is starved on a busy machine, and the window with it (ADR 0042)."""
    import os

    runner = TaskRunner()
    seen = []
    nice = lambda p: os.getpriority(os.PRIO_PROCESS, threading.get_native_id())  # noqa: E731
    with qtbot.waitSignal(runner.idle, timeout=HANG_MS):
        runner.submit("par", nice, on_result=seen.append, at_par=True)
    with qtbot.waitSignal(runner.idle, timeout=HANG_MS):
        runner.submit("lowered", nice, on_result=seen.append)
    gui = os.getpriority(os.PRIO_PROCESS, threading.get_native_id())
    assert seen == [gui, min(19, gui + WORKER_NICENESS)]
    runner.shutdown()
