"""Run slow work off the GUI thread: progress, cancel, "latest request wins", stale results dropped.

A task is a callable ``fn(progress) -> result`` submitted into a named *slot* ("derive:3:region", "preview",
"operation"). A new request in the same slot cancels the previous one; a result is delivered on the GUI thread
only if its task is still the newest of its slot and, when a document revision was given, the document has not
changed since. The callable reports progress with ``progress.update(fraction, message)``, which raises
:class:`mrm.core.errors.Cancelled` once the task is cancelled — the contract of the model's operations.

:class:`SynchronousTaskRunner` runs every task at once in the calling thread: tests use it to make the GUI
deterministic, and it shows that nothing in the GUI depends on the threading.
"""

from __future__ import annotations

import logging
import os
import sys
import threading
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from PySide6 import QtCore

from mrm.app.progress import TaskProgress
from mrm.core.errors import Cancelled
from mrm.views.failures import failure_message, log_failure

log = logging.getLogger(__name__)

Fn = Callable[["TaskProgress"], Any]


@dataclass(eq=False)
class Task:
    """One submitted piece of work and what to do with its outcome."""

    slot: str
    fn: Fn
    on_result: Callable[[Any], None] | None = None
    on_error: Callable[[BaseException], None] | None = None
    on_cancel: Callable[[], None] | None = None
    label: str = ""
    revision: int | None = None
    show_progress: bool = False
    progress: TaskProgress = field(default_factory=TaskProgress)
    done: bool = False
    at_par: bool = False
    drawing: bool = False

    def cancel(self) -> None:
        self.progress.cancel()


class _Signals(QtCore.QObject):
    """Carries outcomes from worker threads; created in the GUI thread, so its slots run there."""

    finished = QtCore.Signal(object, object)  # task, result
    failed = QtCore.Signal(object, object)  # task, exception
    progressed = QtCore.Signal(object, float, str)  # task, fraction, message


#: How much lower than the GUI thread the workers are scheduled (a nice increment, Linux only): on a busy
#: machine the GUI thread then gets a core before the derivations do, and the window keeps answering.
WORKER_NICENESS = 10
_worker_thread = threading.local()


def lower_thread_priority(increment: int = WORKER_NICENESS) -> None:
    """Schedule the calling thread ``increment`` nice levels below the others (Linux; elsewhere nothing).

    On Linux ``setpriority`` with a thread id applies to that thread only.
    """
    if getattr(_worker_thread, "lowered", False) or not sys.platform.startswith("linux"):
        return
    _worker_thread.lowered = True
    try:
        tid = threading.get_native_id()
        os.setpriority(os.PRIO_PROCESS, tid, min(19, os.getpriority(os.PRIO_PROCESS, tid) + increment))
    except OSError:  # not permitted in some sandboxes: the workers then simply share the CPU evenly
        pass


class _Worker(QtCore.QRunnable):
    def __init__(self, task: Task, signals: _Signals) -> None:
        super().__init__()
        self.task = task
        self.signals = signals
        self.setAutoDelete(True)

    def run(self) -> None:
        if not (self.task.at_par or self.task.drawing):
            # drawing data is short work the window waits for: lowered, its thread would hold the GIL
            # while starved of a core, and the window with it (ADR 0042)
            lower_thread_priority()
        task = self.task
        try:
            task.progress.check()
            result = task.fn(task.progress)
        except BaseException as exc:  # everything goes back to the GUI thread, never lost in a thread
            exc.__traceback_text__ = traceback.format_exc()  # type: ignore[attr-defined]
            self.signals.failed.emit(task, exc)
        else:
            self.signals.finished.emit(task, result)


class TaskRunner(QtCore.QObject):
    """Owns background tasks; see the module docstring for the delivery rules.

    Signals
    -------
    busyChanged(bool)
        Some task with ``show_progress`` is running (the status bar shows progress and Cancel).
    progressChanged(str label, float fraction, str message)
        Progress of the newest task with ``show_progress``.
    taskDone(str slot, str outcome)
        Any task ended: outcome is 'result', 'error', 'cancelled' or 'dropped'.
    taskFailed(str label, str message)
        A failure no one reported: a task's error without an error callback, or a callback that raised
        (the window shows it in its status bar; the traceback is logged). Nothing fails silently.
    idle()
        No task is pending any more.
    """

    busyChanged = QtCore.Signal(bool)
    progressChanged = QtCore.Signal(str, float, str)
    taskDone = QtCore.Signal(str, str)
    taskFailed = QtCore.Signal(str, str)
    idle = QtCore.Signal()

    def __init__(self, parent: QtCore.QObject | None = None, *, threads: int | None = None) -> None:
        super().__init__(parent)
        self._pool = QtCore.QThreadPool(self)
        if threads is not None:
            self._pool.setMaxThreadCount(max(1, threads))
        # Threads at the window's priority, for the few tasks submitted ``at_par`` (a thread once lowered
        # cannot be raised again without privileges, so they have their own).
        self._par_pool = QtCore.QThreadPool(self)
        self._par_pool.setMaxThreadCount(4)
        # The views' drawing data (``drawing=True``): short jobs the user is looking at, which must not queue
        # behind operations and derivations that hold the main pool's threads for seconds (a 3D view
        # waited 15 minutes behind them when it shared the pool). Two threads: one view at a time per core.
        self._draw_pool = QtCore.QThreadPool(self)
        self._draw_pool.setMaxThreadCount(2)
        self._signals = _Signals(self)
        self._signals.finished.connect(self._on_finished)
        self._signals.failed.connect(self._on_failed)
        self._signals.progressed.connect(self._on_progress)
        self._current: dict[str, Task] = {}  # newest task per slot
        self._running: set[Task] = set()  # every task not yet delivered
        self.revision_getter: Callable[[], int] | None = None
        self._busy = False
        self._closed = False

    # ------------------------------------------------------------------ public API
    def submit(
        self,
        slot: str,
        fn: Fn,
        *,
        on_result: Callable[[Any], None] | None = None,
        on_error: Callable[[BaseException], None] | None = None,
        on_cancel: Callable[[], None] | None = None,
        label: str = "",
        revision: int | None = None,
        show_progress: bool = False,
        at_par: bool = False,
        drawing: bool = False,
    ) -> Task:
        """Run ``fn(progress)``; cancel whatever ran in ``slot`` before. See the module docstring.

        ``at_par``: in a thread at the window's priority, not :data:`WORKER_NICENESS` below it. For short
        Python work the user waits for, such as loading the kernels at start-up: a lowered thread holding the
        GIL is starved on a busy machine, and the window, waiting for the GIL, with it (ADR 0042).

        ``drawing``: a view's drawing data, run on threads of their own, at the window's priority, so that it
        never waits for long work in the main pool.
        """
        old = self._current.get(slot)
        if old is not None and not old.done:
            old.cancel()
        task = Task(
            slot,
            fn,
            on_result,
            on_error,
            on_cancel,
            label,
            revision,
            show_progress,
            at_par=at_par,
            drawing=drawing,
        )
        if show_progress:
            task.progress = TaskProgress(lambda f, m, t=task: self._signals.progressed.emit(t, f, m))
        self._current[slot] = task
        self._running.add(task)
        self._update_busy()
        if self._closed:
            self._deliver(task, "cancelled", None)
        else:
            self._start(task)
        return task

    def cancel(self, slot: str | None = None) -> None:
        """Cancel the task of ``slot`` (every task when None)."""
        for task in list(self._running):
            if slot is None or task.slot == slot:
                task.cancel()

    def is_busy(self, slot: str | None = None) -> bool:
        """True while a task (of ``slot``) has not been delivered."""
        return any(slot is None or t.slot == slot for t in self._running)

    def is_busy_prefix(self, prefix: str) -> bool:
        """True while a task whose slot starts with ``prefix`` has not been delivered."""
        return any(t.slot.startswith(prefix) for t in self._running)

    def pending(self) -> int:
        return len(self._running)

    def call(self, fn: Callable[..., Any], args: tuple[Any, ...], progress: TaskProgress) -> Any:
        """Inside a task: ``fn(*args, progress)`` in a worker process (:mod:`mrm.app.processes`).

        For Python-heavy work, which in a thread would hold the GIL the window's painting needs. ``fn`` is a
        module-level function; what it takes and returns is pickled.
        """
        from mrm.app.processes import pool

        return pool().run(fn, args, progress)

    def warm_processes(self) -> None:
        """Start a worker process now that loads what the jobs need, so the first job finds it ready."""
        from mrm.app.processes import pool

        pool().warm()

    def shutdown(self, timeout_ms: int = 10_000) -> None:
        """Cancel everything and wait for the threads (window closing)."""
        self._closed = True
        self.cancel()
        self._pool.waitForDone(timeout_ms)
        self._par_pool.waitForDone(timeout_ms)
        self._draw_pool.waitForDone(timeout_ms)
        # Outcomes already queued are dropped: their receivers are going away.
        for task in list(self._running):
            task.done = True
        self._running.clear()
        self._update_busy()

    # ------------------------------------------------------------------ internals
    def _start(self, task: Task) -> None:
        pool = self._par_pool if task.at_par else self._draw_pool if task.drawing else self._pool
        pool.start(_Worker(task, self._signals))

    def _on_finished(self, task: Task, result: Any) -> None:
        self._deliver(task, "result", result)

    def _on_failed(self, task: Task, exc: BaseException) -> None:
        self._deliver(task, "cancelled" if isinstance(exc, Cancelled) else "error", exc)

    def _on_progress(self, task: Task, fraction: float, message: str) -> None:
        if not task.done and self._current.get(task.slot) is task:
            self.progressChanged.emit(task.label, fraction, message)

    def _deliver(self, task: Task, outcome: str, payload: Any) -> None:
        if task.done:
            return
        task.done = True
        self._running.discard(task)
        if self._current.get(task.slot) is task:
            del self._current[task.slot]
        else:
            outcome = "dropped" if outcome != "cancelled" else outcome
        if outcome in ("result", "error") and task.revision is not None and self._stale_revision(task):
            outcome = "dropped"
        what = task.label or task.slot
        try:
            if outcome == "result" and task.on_result is not None:
                task.on_result(payload)
            elif outcome == "error" and task.on_error is not None:
                task.on_error(payload)  # it shows the failure where the work was asked for
            elif outcome == "error":
                self._unreported(what, payload)
            elif outcome == "cancelled" and task.on_cancel is not None:
                task.on_cancel()
        except Exception as exc:
            # A callback that raised (an error callback passing on what it does not handle, or a bug in one):
            # the window still hears of it, and the traceback is logged.
            self._unreported(what, exc)
        finally:
            self._update_busy()
            self.taskDone.emit(task.slot, outcome)
            if not self._running:
                self.idle.emit()

    def _unreported(self, what: str, exc: BaseException) -> None:
        """A failure no callback reported: logged with its traceback, and said in the status bar."""
        log_failure(log, what, exc)
        self.taskFailed.emit(what, failure_message(exc))

    def _stale_revision(self, task: Task) -> bool:
        return self.revision_getter is not None and self.revision_getter() != task.revision

    def _update_busy(self) -> None:
        busy = any(t.show_progress for t in self._running)
        if busy != self._busy:
            self._busy = busy
            self.busyChanged.emit(busy)


class SynchronousTaskRunner(TaskRunner):
    """Runs each task immediately in the calling thread (tests); the delivery rules are the same."""

    def call(self, fn: Callable[..., Any], args: tuple[Any, ...], progress: TaskProgress) -> Any:
        return fn(*args, progress)  # in this thread too: the same function, no process

    def warm_processes(self) -> None:
        """No worker processes here."""

    def _start(self, task: Task) -> None:
        try:
            task.progress.check()
            result = task.fn(task.progress)
        except Cancelled:
            self._deliver(task, "cancelled", None)
        except Exception as exc:
            exc.__traceback_text__ = traceback.format_exc()  # type: ignore[attr-defined]
            self._deliver(task, "error", exc)
        else:
            self._deliver(task, "result", result)

    def shutdown(self, timeout_ms: int = 0) -> None:
        self._closed = True
        self._running.clear()
