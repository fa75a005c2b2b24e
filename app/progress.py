"""The progress object a GUI task sees, in a thread of the window or in a worker process (no Qt here)."""

from __future__ import annotations

import threading
from collections.abc import Callable

from mrm.core.progress import Progress


class TaskProgress(Progress):
    """The library's :class:`~mrm.core.progress.Progress`, with the reports a window's progress bar wants.

    ``report(fraction, message)`` is called at most every :attr:`MIN_INTERVAL` seconds (and always when
    the work is done); ``event`` is the cancel flag, shared with a worker process's signal handler there.
    """

    #: Progress signals are throttled to this interval (seconds); the last one always goes through.
    MIN_INTERVAL = 0.05

    def __init__(
        self, report: Callable[[float, str], None] | None = None, event: threading.Event | None = None
    ) -> None:
        super().__init__(report, event=event, min_interval=self.MIN_INTERVAL)
