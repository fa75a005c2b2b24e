"""Running an operation on a document's objects: all results in one undo step, or nothing at all.

:func:`apply_operation` reads the sources of the input objects, runs the operation (which never touches the
document), and only when it has finished pushes one :class:`~mrm.document.commands.ApplyResults` command that
adds the results with their provenance — the operation's name, its parameters, the ids of its inputs and their
content at that moment (pinned: editing an input later never changes a result's account). A failure (bad
parameter, size limit, invalid geometry) or a cancel raises before that push, so the document, its history and
its selection are exactly as they were: nothing is lost.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from mrm.core.limits import DEFAULT_PIXEL_LIMIT
from mrm.core.models import Model
from mrm.core.progress import ProgressLike
from mrm.document.commands import ApplyResults
from mrm.document.document import Document
from mrm.ops.registry import Plan, plan_operation


def apply_operation(
    doc: Document,
    operation: str,
    input_ids: Sequence[int],
    params: Any = None,
    progress: ProgressLike | None = None,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> list[int]:
    """Run ``operation`` on the objects ``input_ids`` of ``doc`` and add its results as one undo step.

    :func:`mrm.ops.registry.plan_operation` does the work (it never touches the document); this pushes its
    results. The GUI runs ``plan_operation`` on a worker and pushes on its own thread.

    Parameters
    ----------
    doc : mrm.document.Document
    operation : str
        A registered operation's name (``dss``, ``discrete_rotation``, ``simplify``, ``union``, ``corefine``).
    input_ids : sequence of int
        The input objects, as many as the operation's arity.
    params : parameter dataclass or mapping, optional
        The operation's parameters (defaults when None); pass ``model=doc.model`` so that the results keep
        the document's invariant D(Euclidean) = discrete under the model they were made with.
    progress : object with ``update(fraction, message)``, optional
    limit : int or None
        The largest result, checked on the estimate before running.

    Returns
    -------
    list of int
        The ids of the new objects.

    Raises
    ------
    ParameterError, SizeLimitError, InvalidGeometryError, Cancelled
        Before anything is changed.
    """
    ids = [int(i) for i in input_ids]
    plan = plan_operation(
        [doc.get(i) for i in ids],
        operation,
        params,
        progress,
        limit=limit,
        held=held_euclidean(doc, ids),
        compact_limit=doc.settings.compact_limit,
    )
    return push_plan(doc, plan)


def held_euclidean(doc: Document, input_ids: Sequence[int]) -> list[tuple[int, Model, Any]]:
    """R(A) that ``doc`` holds already for its pixel and voxel objects ``input_ids``: (index, model, R(A)).

    For :func:`mrm.ops.registry.run_operation`'s ``held``: every operation reads R(A) of a pixel input (DSS_α
    and dR_θ,C transform it, Sp_α and the boolean operations start from it). Only what the document has
    computed (its Euclidean views, :meth:`mrm.document.derive.Derived.peek`); nothing is computed here.
    """
    held = []
    for k, i in enumerate(input_ids):
        derived = doc.derived(int(i))
        euclid = derived.peek("euclidean") if derived.kind == "discrete" else None
        if euclid is not None:
            held.append((k, derived.model, euclid))
    return held


def push_plan(doc: Document, plan: Plan, styles: Sequence[Any] | None = None) -> list[int]:
    """Add the results of a plan to ``doc`` as one undo step; the ids of the new objects."""
    objects = [
        doc.make_object(
            r.source, r.name, provenance=r.provenance, style=styles[k] if styles is not None else None
        )
        for k, r in enumerate(plan.results)
    ]
    doc.push(ApplyResults(plan.label, add=objects))
    return [o.id for o in objects]
