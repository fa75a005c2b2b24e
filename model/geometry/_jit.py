"""numba's ``njit`` releasing the GIL: a kernel running on a worker thread must not stop the GUI thread.

numba holds the GIL for the whole call of a kernel compiled without ``nogil``; a reconstruction of a
17-million-pixel object then froze the window for seconds although it ran on a worker. Every kernel here works
on arrays only (nopython mode), so releasing the GIL is safe (docs/adr/0014).
"""

from __future__ import annotations

from typing import Any

import numba


def njit(*args: Any, **kwargs: Any) -> Any:
    """``numba.njit`` with ``nogil=True`` unless the caller says otherwise."""
    kwargs.setdefault("nogil", True)
    return numba.njit(*args, **kwargs)
