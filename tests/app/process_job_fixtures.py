"""Jobs for the worker-process tests: module-level (a child imports them by name), importing nothing heavy."""

from __future__ import annotations

import os
import time
from typing import Any


def whoami(progress: Any) -> int:
    """The child's process id."""
    progress.update(1.0, "done")
    return os.getpid()


def counting(seconds: float, progress: Any) -> str:
    """Report progress every 10 ms for ``seconds`` (a Cancel stops it at the next report)."""
    t0 = time.monotonic()
    while time.monotonic() - t0 < seconds:
        progress.update((time.monotonic() - t0) / seconds, "counting")
        time.sleep(0.01)
    return "finished"


def deaf(seconds: float, progress: Any) -> str:
    """Sleep without ever looking at the progress (a long kernel)."""
    time.sleep(seconds)
    return "finished"


def dying(progress: Any) -> None:
    """End the child abruptly."""
    os._exit(3)


def refusing(progress: Any) -> None:
    """Raise a user error."""
    from mrm.errors import ParameterError

    raise ParameterError("α must be positive, got -3")


def echo(value: Any, progress: Any) -> Any:
    """Return ``value`` (a round trip through the pipe both ways)."""
    return value


def dying_mid_transfer(progress: Any) -> None:
    """Begin to send a big result (its array spilled to a file in memory), then end abruptly."""
    import numpy as np

    from mrm.app import processes

    processes._spill(memoryview(np.zeros(2 * processes.SPILL_BYTES, np.uint8)))
    os._exit(3)


def spilling_then_deaf(seconds: float, progress: Any) -> str:
    """Begin to send a big result, then hang without looking at the progress (killed after a Cancel)."""
    import numpy as np

    from mrm.app import processes

    processes._spill(memoryview(np.zeros(2 * processes.SPILL_BYTES, np.uint8)))
    time.sleep(seconds)
    return "finished"
