"""Pausing Python's cyclic garbage collector while a large acyclic structure is built."""

from __future__ import annotations

import gc
from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def paused_gc() -> Iterator[None]:
    """Pause the cyclic garbage collector while building many small acyclic objects.

    Each batch of allocations triggers a collection that walks every live container, so building 10⁵–10⁶
    chains, cells or coordinate lists is several times slower with it on, although none of them can be part
    of a cycle. The collector's previous state is restored, also on an exception.
    """
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was_enabled:
            gc.enable()
