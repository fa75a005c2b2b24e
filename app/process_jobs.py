"""The jobs the window runs in worker processes (:mod:`mrm.app.processes`): plain model calls.

Each is a module-level function ``job(*args, progress)``, so that a child process can import it by name; none
of them imports Qt.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any


def warm(progress: Any) -> None:
    """Load the operations and the cached kernels: what a child started ahead of need does first.

    Each operation then runs once on a tiny input (a few hundredths of a second once the derivation kernels
    are loaded), so that the user's first operation finds every kernel it calls loaded.
    """
    from mrm.ops.account import account_of  # noqa: F401
    from mrm.ops.registry import operations
    from mrm.warmup import STEPS, is_warm, load_kernels

    operations()  # every operation module imported, the registry complete
    if is_warm():  # else the window's own warm-up is compiling them: not twice at once
        load_kernels()
        for what, step in STEPS:
            if what == "operation kernels":
                step()


def measure(provenance: Any, compact_limit: int | None, progress: Any) -> Any:
    """The inspector's account of a result, measured (:func:`mrm.ops.account.account_of`).

    ``compact_limit``: the document's, for the R of voxel sets computed again.
    """
    from mrm.ops.account import account_of

    return account_of(provenance, measure=True, progress=progress, compact_limit=compact_limit)


def plan(
    inputs: list[Any],
    op_name: str,
    params: Any,
    limit: int | None,
    held: list[Any],
    compact_limit: int | None,
    progress: Any,
) -> Any:
    """An operation planned on document objects (:func:`mrm.ops.registry.plan_operation`).

    ``held``: (input index, model, R(A)) for inputs whose R(A) the window holds already; ``compact_limit``:
    the document's, for every R of a voxel set the operation computes.
    """
    from mrm.ops.registry import plan_operation

    kw = {} if limit is None else {"limit": limit}
    return plan_operation(inputs, op_name, params, progress, held=held, compact_limit=compact_limit, **kw)


def read_project(path: str, progress: Any) -> Any:
    """A project file read and checked (:func:`mrm.io.project.read_project`)."""
    from mrm.io.project import read_project as read

    progress.update(0.0, f"reading {Path(path).name}")
    return read(Path(path))


def write_project(path: str, snapshot: Any, progress: Any) -> None:
    """A document snapshot serialised and written atomically (:func:`mrm.io.project.dumps`)."""
    from mrm.io.atomic import atomic_write_bytes
    from mrm.io.project import dumps

    progress.update(0.0, f"writing {Path(path).name}")
    atomic_write_bytes(Path(path), dumps(snapshot))
