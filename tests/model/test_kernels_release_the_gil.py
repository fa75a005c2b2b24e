"""Every numba kernel of the library releases the GIL and is cached on disk (docs/adr/0014).

A kernel compiled without ``nogil`` holds the GIL for its whole call, so a worker running it stops the GUI
thread as surely as if it ran there (issue 10's freezes); one compiled without ``cache=True`` compiles
again in every process, which is what ``python -m mrm.warmup`` exists to avoid. The test imports every
module of the Qt-free package (model/, walked with pkgutil; ``mrm.app`` and ``mrm.views`` live elsewhere
and hold no kernel) and checks every numba dispatcher it finds as a module attribute.
"""

from __future__ import annotations

import importlib
import pkgutil

import numba.core.caching
import numba.core.dispatcher

import mrm

#: Modules not imported, with the reason; each must still be found by the walk (no stale entry).
NOT_IMPORTED = {"mrm.__main__": "runs the command line when imported (`python -m mrm`)"}


def _library_modules() -> list[str]:
    unreadable: list[str] = []
    names = [m.name for m in pkgutil.walk_packages(mrm.__path__, "mrm.", onerror=unreadable.append)]
    assert not unreadable, f"packages that failed to import during the walk: {unreadable}"
    return ["mrm", *names]


def _kernels() -> dict[str, numba.core.dispatcher.Dispatcher]:
    """Every dispatcher found as a module attribute, by the qualified name of the function it compiles."""
    found: dict[str, numba.core.dispatcher.Dispatcher] = {}
    for name in _library_modules():
        if name in NOT_IMPORTED:
            continue
        module = importlib.import_module(name)  # an import error fails the test: nothing is skipped
        for value in vars(module).values():
            if isinstance(value, numba.core.dispatcher.Dispatcher):
                f = value.py_func
                found[f"{f.__module__}.{f.__qualname__}"] = value
    return found


def test_the_walk_finds_the_whole_library() -> None:
    names = set(_library_modules())
    assert set(NOT_IMPORTED) <= names, set(NOT_IMPORTED) - names
    # Sanity of the walk itself: it reaches sub-packages at every depth, kernels and io alike.
    assert {"mrm.geometry.reconstruct._dual", "mrm.io.png_stream", "mrm.geometry.topology.labeling"} <= names
    assert not any(n.startswith(("mrm.app", "mrm.views")) for n in names)


def test_every_kernel_releases_the_gil() -> None:
    kernels = _kernels()
    assert len(kernels) > 100  # the reconstruction alone has well over a hundred
    holding = sorted(name for name, d in kernels.items() if not d.targetoptions.get("nogil"))
    assert not holding, f"numba kernels compiled without nogil=True (use mrm.geometry._jit.njit): {holding}"


def test_every_kernel_is_cached_on_disk() -> None:
    uncached = sorted(
        name for name, d in _kernels().items() if isinstance(d._cache, numba.core.caching.NullCache)
    )
    assert not uncached, f"numba kernels compiled without cache=True: {uncached}"
