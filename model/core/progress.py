"""Progress and cancellation: the one protocol every long computation of the library reports through.

A computation takes ``progress`` (anything with ``update(fraction, message)``, see :class:`ProgressLike`),
calls it now and then, and stops with :class:`mrm.core.errors.Cancelled` when ``update`` raises it. The
geometry kernels, the exact operations, the account, the CLI's bar and the application's task progress
(``mrm.app.progress.TaskProgress``) all speak this protocol; :class:`Progress` is the library's own
thread-safe implementation, :class:`SubProgress` maps a part of the work onto a range of its parent, and
:data:`NO_PROGRESS` records nothing.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Protocol, runtime_checkable

import numpy as np
import numpy.typing as npt

from mrm.core.errors import Cancelled

__all__ = [
    "NO_PROGRESS",
    "NullProgress",
    "Progress",
    "ProgressLike",
    "SubProgress",
    "stop_flag",
    "sub_progress",
]


@runtime_checkable
class ProgressLike(Protocol):
    """What an operation needs from a progress object."""

    def update(self, fraction: float | None = None, message: str | None = None) -> None:
        """Report ``fraction`` in [0, 1] (or None) and a message; raise Cancelled after a cancel."""


class Progress:
    """Thread-safe progress with prompt cancellation.

    Parameters
    ----------
    callback : callable, optional
        ``callback(fraction, message)``, called on updates (from the working thread).
    event : threading.Event, optional
        The cancel flag, when it is shared with something else (a worker process's signal handler);
        a fresh one by default.
    min_interval : float
        Calls of ``callback`` closer together than this (seconds) are dropped, except the one that reaches
        a fraction of 1: a window's progress bar needs no more than 20 a second.

    Notes
    -----
    ``cancel()`` may be called from any thread; the next ``update()`` (or ``check()``) in the working thread
    raises :class:`mrm.core.errors.Cancelled`. Fractions are clamped to [0, 1] and never go backwards.
    """

    def __init__(
        self,
        callback: Callable[[float, str], None] | None = None,
        *,
        event: threading.Event | None = None,
        min_interval: float = 0.0,
    ) -> None:
        self._lock = threading.Lock()
        self._event = event if event is not None else threading.Event()
        self._callback = callback
        self._min_interval = float(min_interval)
        self._last_call = -float("inf")
        self._fraction = 0.0
        self._message = ""

    @property
    def fraction(self) -> float:
        """The last reported fraction, in [0, 1]."""
        with self._lock:
            return self._fraction

    @property
    def message(self) -> str:
        """The last reported message."""
        with self._lock:
            return self._message

    @property
    def cancelled(self) -> bool:
        """True once :meth:`cancel` was called."""
        return self._event.is_set()

    def cancel(self) -> None:
        """Ask the work to stop at its next report (any thread)."""
        self._event.set()

    def check(self) -> None:
        """Raise :class:`Cancelled` if the work was cancelled."""
        if self._event.is_set():
            raise Cancelled("cancelled")

    def update(self, fraction: float | None = None, message: str | None = None) -> None:
        """Report progress; raise :class:`Cancelled` after a cancel.

        Parameters
        ----------
        fraction : float, optional
            Done so far, in [0, 1] (clamped; NaN ignored).
        message : str, optional
            What is being done.
        """
        self.check()
        with self._lock:
            if fraction is not None and fraction == fraction:
                self._fraction = max(self._fraction, min(1.0, max(0.0, float(fraction))))
            if message is not None:
                self._message = str(message)
            snapshot = (self._fraction, self._message)
            call = self._callback is not None
            if call and self._min_interval > 0:
                now = time.monotonic()
                call = now - self._last_call >= self._min_interval or self._fraction >= 1.0
                if call:
                    self._last_call = now
        if call and self._callback is not None:
            self._callback(*snapshot)

    def sub(self, start: float, stop: float) -> SubProgress:
        """A progress for a part of the work that maps its [0, 1] onto [start, stop] of this one."""
        return SubProgress(self, start, stop)


class SubProgress:
    """The part [start, stop] of a parent progress (cancellation is the parent's)."""

    def __init__(self, parent: ProgressLike | None, start: float, stop: float) -> None:
        self._parent: ProgressLike = NO_PROGRESS if parent is None else parent
        self._start = float(start)
        self._stop = float(stop)

    @property
    def cancelled(self) -> bool:
        """True once the parent was cancelled."""
        return bool(getattr(self._parent, "cancelled", False))

    def update(self, fraction: float | None = None, message: str | None = None) -> None:
        """Report ``fraction`` of this part to the parent; raise Cancelled after a cancel."""
        mapped = None
        if fraction is not None and fraction == fraction:
            f = min(1.0, max(0.0, float(fraction)))
            mapped = self._start + f * (self._stop - self._start)
        self._parent.update(mapped, message)

    def sub(self, start: float, stop: float) -> SubProgress:
        """A nested part."""
        span = self._stop - self._start
        return SubProgress(self._parent, self._start + start * span, self._start + stop * span)


class NullProgress:
    """A progress that records nothing and is never cancelled: for scripts and tests."""

    cancelled = False

    def update(self, fraction: float | None = None, message: str | None = None) -> None:
        """Do nothing."""

    def sub(self, start: float, stop: float) -> NullProgress:
        """Itself."""
        return self


#: The shared no-op progress.
NO_PROGRESS = NullProgress()


def sub_progress(inner: ProgressLike | None, lo: float, hi: float) -> ProgressLike:
    """A progress for a sub-task that reports into [lo, hi] of ``inner`` (and checks its cancel)."""
    return SubProgress(inner, lo, hi)


#: How often (seconds) :func:`stop_flag` looks whether its progress was cancelled.
STOP_POLL = 0.05


@contextmanager
def stop_flag(progress: ProgressLike | None, poll: float = STOP_POLL) -> Iterator[npt.NDArray[np.uint8]]:
    """A one-byte array that a compiled kernel reads to stop early: set to 1 once ``progress`` is cancelled.

    A numba kernel cannot report through ``progress`` (it runs without the interpreter), so it reads this
    flag between its steps and returns early when it is set; the caller then raises
    :class:`~mrm.core.errors.Cancelled`. While the block runs, a watcher thread looks at
    ``progress.cancelled`` every ``poll`` seconds (whoever set it: ``Progress.cancel()``, or a worker
    process's signal handler through the shared event). Without a progress that can be cancelled the flag
    stays 0 and no thread is started.

    At its first look the watcher also reports again what the progress last said (``update(None)``): a
    throttled progress (a window's, a ``Progress`` with ``min_interval``) drops a report made just after
    another, and the kernel, which reports nothing, would leave that last message unsaid until it ends. The
    working thread reports nothing meanwhile (it is in the kernel, and joins the watcher before going on).
    """
    flag = np.zeros(1, np.uint8)
    if progress is None or not hasattr(progress, "cancelled"):
        yield flag
        return
    finished = threading.Event()

    def watch() -> None:
        said = False
        while not finished.wait(poll):
            if progress.cancelled:
                flag[0] = 1
                return
            if not said:
                said = True
                try:
                    progress.update(None)
                except Cancelled:
                    flag[0] = 1
                    return

    watcher = threading.Thread(target=watch, name="mrm-stop-flag", daemon=True)
    watcher.start()
    try:
        yield flag
    finally:
        finished.set()
        watcher.join()
