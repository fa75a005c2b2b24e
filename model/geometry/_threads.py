"""The geometry's worker threads: one pool for work beside the calling thread's.

The kernels release the GIL (:mod:`mrm.geometry._jit`), so two threads run two kernels at once. R's rings
(2D), its checks beside the hull (3D) and the discretization's triangle chunks share this pool. The desktop
sets ``MRM_THREADS=1`` (its GUI thread needs the other core) and a batch gives each worker one thread.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import TypeVar

#: The most threads the geometry uses, the calling one included.
MAX_THREADS = 4

_T = TypeVar("_T")
_pool: ThreadPoolExecutor | None = None


def threads() -> int:
    """The cores this process may use, at most :data:`MAX_THREADS`; ``MRM_THREADS=n`` sets it.

    1 means no threads (many processes side by side, or the desktop's GUI process).
    """
    wanted = os.environ.get("MRM_THREADS", "")
    if wanted.isdigit():
        return max(1, min(MAX_THREADS, int(wanted)))
    try:
        return max(1, min(MAX_THREADS, len(os.sched_getaffinity(0))))
    except AttributeError:  # not on Linux
        return max(1, min(MAX_THREADS, os.cpu_count() or 1))


def side_pool() -> ThreadPoolExecutor | None:
    """The worker threads, for work beside the calling thread's; None when one core only may be used."""
    global _pool
    if threads() < 2:
        return None
    if _pool is None:
        _pool = ThreadPoolExecutor(max_workers=MAX_THREADS, thread_name_prefix="mrm-R")
    return _pool


def share_out(work: Callable[[int], _T], n: int) -> list[_T]:
    """``[work(0), …, work(n − 1)]``, the calls shared between this thread and the pool's.

    Each thread takes the next undone index until none is left, so a thread that starts late (the pool busy
    with other work) takes fewer. A helper that has not started when this thread runs out of work is
    cancelled, never waited for: a caller that is itself a pool thread cannot deadlock on a full pool. The
    first exception raised by a call is raised here.
    """
    pool = side_pool() if n > 1 else None
    if pool is None:
        return [work(i) for i in range(n)]
    out: list[_T | None] = [None] * n
    lock = threading.Lock()
    undone = iter(range(n))

    def take() -> None:
        while True:
            with lock:
                i = next(undone, None)
            if i is None:
                return
            out[i] = work(i)

    helpers = [pool.submit(take) for _ in range(min(threads(), n) - 1)]
    try:
        take()
    finally:
        for h in helpers:
            if not h.cancel():
                h.result()
    return out  # type: ignore[return-value]  # every index was done


def _forget_pool() -> None:
    # A forked child has none of its parent's threads: it makes its own pool when it needs one.
    global _pool
    _pool = None


os.register_at_fork(after_in_child=_forget_pool)
