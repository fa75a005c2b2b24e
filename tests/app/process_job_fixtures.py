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
    from mrm.core.errors import ParameterError

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


def over_limit(progress: Any) -> None:
    """Raise the size-limit error an operation raises before allocating a too-big result."""
    from mrm.core.errors import SizeLimitError

    raise SizeLimitError(158_000_000, 100_000_000, "DSS_4.5")


class _Stubborn(Exception):
    def __init__(self, a: int, b: int) -> None:  # the default reduction passes the message alone
        super().__init__(f"stubborn {a} {b}")


def unpicklable_error(progress: Any) -> None:
    """Raise an exception that pickles but cannot be unpickled."""
    raise _Stubborn(1, 2)


def unpicklable_result(provenance: Any, compact_limit: Any, progress: Any) -> Any:
    """A measurement whose result cannot be pickled back (as an account holding a closure once was)."""
    return lambda: provenance


def buggy(provenance: Any, compact_limit: Any, progress: Any) -> Any:
    """A measurement that fails with a bug, not a user error."""
    raise TypeError("unsupported operand type(s) for +: 'int' and 'str'")


def dying_measure(provenance: Any, compact_limit: Any, progress: Any) -> None:
    """A measurement whose process ends abruptly."""
    os._exit(3)


def planning_until_cancelled(
    inputs: Any, op_name: str, params: Any, limit: Any, held: Any, compact_limit: Any, progress: Any
) -> None:
    """An operation's plan that reports what it does ("continuing R(A)") until it is cancelled."""
    while True:
        progress.update(0.3, "continuing R(A)")
        time.sleep(0.01)


def modules_loaded(progress: Any) -> tuple[int, bool, int]:
    """The child's pid, whether the operations were loaded before this job, and its nice level."""
    import sys

    return os.getpid(), "mrm.ops.scaling" in sys.modules, os.nice(0)


def over_limit_reworded(
    inputs: Any, op_name: str, params: Any, limit: Any, held: Any, compact_limit: Any, progress: Any
) -> None:
    """An operation refused for its size whose message the model words otherwise than the window expects."""
    from mrm.core.errors import SizeLimitError

    exc = SizeLimitError(10_000, 5_000, "DSS_α result")
    exc.args = ("the result is too big",)  # the text changed; the fields did not
    raise exc
