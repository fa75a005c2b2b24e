"""Running an operation on a document's objects: all results in one undo step, or nothing at all.

:func:`apply_operation` reads the sources of the input objects, runs the operation (which never touches the
document), and only when it has finished pushes one :class:`~mrm.commands.ApplyResults` command that adds
the results with their provenance — the operation's name, its parameters and the ids of its inputs. A
failure (bad parameter, size limit, invalid geometry) or a cancel raises before that push, so the document,
its history and its selection are exactly as they were: nothing is lost.
"""

from __future__ import annotations

import importlib
from collections.abc import Sequence
from typing import Any

from mrm.errors import DEFAULT_PIXEL_LIMIT
from mrm.ops.base import ProgressLike, get_operation, params_to_dict, run_operation

#: The modules that register the paper's operations (``dss``, ``discrete_rotation``, ``simplify``, ``union``,
#: ``corefine``) when imported.
PAPER_OPERATIONS = ("mrm.ops.scaling", "mrm.ops.rotation", "mrm.ops.simplify", "mrm.ops.boolean")


def load_paper_operations() -> None:
    """Import the modules of the paper's operations, so that the registry holds them."""
    for mod in PAPER_OPERATIONS:
        importlib.import_module(mod)


def apply_operation(
    doc: Any,
    operation: str,
    input_ids: Sequence[int],
    params: Any = None,
    progress: ProgressLike | None = None,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> list[int]:
    """Run ``operation`` on the objects ``input_ids`` of ``doc`` and add its results as one undo step.

    Parameters
    ----------
    doc : mrm.document.Document
    operation : str
        A registered operation's name (``dss``, ``discrete_rotation``, ``simplify``, ``union``, ``corefine``).
    input_ids : sequence of int
        The input objects, as many as the operation's arity.
    params : parameter dataclass, optional
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
    from mrm.commands import ApplyResults
    from mrm.document import Provenance

    load_paper_operations()
    spec = get_operation(operation)
    if params is None:
        params = spec.default_params()
    ids = [int(i) for i in input_ids]
    sources = [doc.get(i).source for i in ids]
    out = run_operation(spec, sources, params, progress=progress, limit=limit)  # checks arity and size first
    base = params_to_dict(params)
    objects = []
    for name, source in out.outputs:
        p = {**base, "part": name} if spec.name == "corefine" else base
        prov = Provenance(spec.name, p, tuple(ids))
        objects.append(doc.make_object(source, name, provenance=prov))
    doc.push(ApplyResults(spec.title, add=objects))
    return [o.id for o in objects]
