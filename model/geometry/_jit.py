"""numba's ``njit`` releasing the GIL: a kernel running on a worker thread must not stop the GUI thread.

numba holds the GIL for the whole call of a kernel compiled without ``nogil``; a reconstruction of a
17-million-pixel object then froze the window for seconds although it ran on a worker. Every kernel here works
on arrays only (nopython mode), so releasing the GIL is safe (docs/adr/0014).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar, cast

import numba

_F = TypeVar("_F", bound=Callable[..., Any])


def njit(**kwargs: Any) -> Callable[[_F], _F]:
    """``numba.njit(**kwargs)`` with ``nogil=True`` unless said otherwise: ``@njit(cache=True)``."""
    kwargs.setdefault("nogil", True)
    decorator: Callable[[_F], _F] = numba.njit(**kwargs)
    return decorator


def leaf_njit(**kwargs: Any) -> Callable[[_F], _F]:
    """:func:`njit` without numba's reference counting (NRT), for kernels that allocate no array.

    numba counts references to arrays with atomic increments and decrements: every array argument of a
    compiled call (or of an ``inline="always"`` helper) costs a pair of them, and on small helpers called in
    hot loops (R's clipping, gate and edge checks) those pairs took about half of R's time. A kernel that only
    reads and writes arrays its caller owns needs no counting; compiled without NRT it runs the same
    instructions minus the counting (numba refuses to compile one that allocates an array).
    """
    kwargs.setdefault("_nrt", False)
    return njit(**kwargs)


def py_func(kernel: _F) -> _F:
    """The plain Python function behind a kernel (numba's ``py_func``), e.g. to run it on Python ints."""
    return cast(_F, getattr(kernel, "py_func", kernel))
