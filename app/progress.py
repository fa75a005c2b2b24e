"""The progress object a GUI task sees, in a thread of the window or in a worker process (no Qt here)."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

from mrm.errors import Cancelled


class TaskProgress:
    """What a task's callable sees: ``update(fraction, message)`` reports and checks for a cancel.

    It duck-types the model's progress object (``update`` raises :class:`Cancelled` once cancelled;
    ``cancelled`` tells without raising), so operations take it unchanged.
    """

    #: Progress signals are throttled to this interval (seconds); the last one always goes through.
    MIN_INTERVAL = 0.05

    def __init__(
        self, report: Callable[[float, str], None] | None = None, event: threading.Event | None = None
    ) -> None:
        self._event = event if event is not None else threading.Event()
        self._report = report
        self._last = 0.0
        self.fraction = 0.0
        self.message = ""

    def cancel(self) -> None:
        """Ask the task to stop at its next ``update``."""
        self._event.set()

    @property
    def cancelled(self) -> bool:
        """True once :meth:`cancel` was called."""
        return self._event.is_set()

    def check(self) -> None:
        """Raise :class:`Cancelled` if the task was cancelled."""
        if self._event.is_set():
            raise Cancelled("cancelled")

    def update(self, fraction: float | None = None, message: str | None = None) -> None:
        """Report ``fraction`` in [0, 1] and an optional message; raise :class:`Cancelled` after a cancel."""
        self.check()
        if fraction is not None:
            self.fraction = min(1.0, max(0.0, float(fraction)))
        if message is not None:
            self.message = str(message)
        if self._report is not None:
            now = time.monotonic()
            if now - self._last >= self.MIN_INTERVAL or self.fraction >= 1.0:
                self._last = now
                self._report(self.fraction, self.message)

    # mrm.ops.base may name it differently; accept the common spellings.
    __call__ = update
    report = update
