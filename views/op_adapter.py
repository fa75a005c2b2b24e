"""How the GUI reads the model's operations: one place that knows the shape of :mod:`mrm.ops`.

The panels are generated from the registry (:func:`mrm.ops.base.operations`): every field of an operation's
parameters dataclass gives a control, its ``metadata["mrm"]`` (written by :func:`mrm.ops.base.param`, read
through :func:`mrm.ops.base.param_specs`) the kind, range, unit and help. Apply goes through
:func:`mrm.ops.apply.apply_operation` in a worker thread against a *staging* document (:func:`stage_apply`):
the operation reads the inputs and builds its results with their provenance there, and the GUI thread pushes
the one undo step it staged — so a cancel or an error leaves the real document untouched.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class ParamInfo:
    """One parameter as a control sees it."""

    name: str
    label: str
    kind: str  # "float", "int", "bool", "choice", "point", "text"
    default: Any
    minimum: float | None = None
    maximum: float | None = None
    unit: str = ""
    help: str = ""
    step: float | None = None
    log: bool = False
    choices: tuple[Any, ...] = ()
    optional: bool = False  # None is allowed (shown as "default" at the field's minimum / a cleared point)


@dataclass(frozen=True)
class OpInfo:
    """One operation as the panel sees it."""

    name: str
    title: str
    arity: int
    params: tuple[ParamInfo, ...]
    help: str
    spec: Any

    def make_params(self, values: Mapping[str, Any]) -> Any:
        """The operation's parameter object from control values, validated (raises ParameterError)."""
        from mrm.ops.base import validate_params

        params = self.spec.params(**values)
        validate_params(params)
        return params

    def run(self, inputs: Sequence[Any], params: Any, progress: Any) -> list[tuple[str | None, Any]]:
        """Run the operation; returns (part name or None, source) pairs."""
        out = self.spec.run(list(inputs), params, progress)
        return normalise_results(out)


#: Slider ranges for numbers whose metadata leaves a side open (the field still takes any valid value).
_POSITIVE_RANGE = (1 / 64, 64.0)
_ANGLE_RANGE = (-360.0, 360.0)
_OPEN_RANGE = (-1000.0, 1000.0)


def _range_of(spec: Any) -> tuple[float | None, float | None, bool]:
    """Control bounds (minimum, maximum, logarithmic) from the model's bounds, closed where they are open."""
    lo, hi = _num(spec.minimum), _num(spec.maximum)
    if lo == 0.0 and not spec.min_inclusive and hi is None:
        # A positive factor: a logarithmic slider over [1/64, 64]; exclusive 0 cannot be a slider end.
        return _POSITIVE_RANGE[0], _POSITIVE_RANGE[1], True
    if lo is not None and not spec.min_inclusive and lo == 0.0:
        lo = _POSITIVE_RANGE[0]
    if lo is None and hi is None:
        return (*(_ANGLE_RANGE if spec.unit == "°" else _OPEN_RANGE), False)
    if lo is None:
        lo = (hi or 0.0) - 1000.0
    if hi is None:
        hi = lo + 1000.0
    return lo, hi, lo > 0 and hi / lo >= 100


def param_infos(cls: type | None) -> tuple[ParamInfo, ...]:
    """The controls of a parameters dataclass, in field order, from ``metadata["mrm"]`` (:func:`param`)."""
    from mrm.ops.base import param_specs

    if cls is None:
        return ()
    out = []
    for spec in param_specs(cls):
        kind = "text" if spec.kind == "str" else str(spec.kind)
        lo = hi = None
        log = False
        if kind in ("float", "int"):
            lo, hi, log = _range_of(spec)
        out.append(
            ParamInfo(
                name=spec.name,
                label=spec.label,
                kind=kind,
                default=spec.default,
                minimum=lo,
                maximum=hi,
                unit=spec.unit,
                help=spec.help,
                log=log,
                choices=tuple(spec.choices),
                optional=spec.optional,
            )
        )
    return tuple(out)


def _num(v: Any) -> float | None:
    try:
        f = float(v)
    except (TypeError, ValueError):
        return None
    return f if math.isfinite(f) else None


def operations() -> list[OpInfo]:
    """Every operation of the model's registry (:func:`mrm.ops.base.operations`), the paper's first."""
    from mrm.ops.apply import load_paper_operations
    from mrm.ops.base import operations as registry

    load_paper_operations()
    specs = registry()
    paper = ("dss", "discrete_rotation", "simplify", "union", "corefine")
    specs.sort(key=lambda s: (paper.index(s.name) if s.name in paper else len(paper), s.name))
    return [
        OpInfo(
            name=spec.name,
            title=spec.title,
            arity=spec.arity,
            params=param_infos(spec.params),
            help=spec.help or (spec.__doc__ or ""),
            spec=spec,
        )
        for spec in specs
    ]


def normalise_results(out: Any) -> list[tuple[str | None, Any]]:
    """(part, source) pairs from whatever an operation returns."""
    from mrm.reps.pixels import PixelSet

    def source_of(r: Any) -> Any:
        for attr in ("source", "result", "value", "geometry", "pixels"):
            v = getattr(r, attr, None)
            if v is not None:
                return v
        return r

    if out is None:
        return []
    if isinstance(out, PixelSet) or hasattr(out, "geom_type"):
        return [(None, out)]
    for attr in ("parts", "results", "outputs"):
        parts = getattr(out, attr, None)
        if parts is not None:
            return normalise_results(parts)
    if isinstance(out, Mapping):
        return [(str(k), source_of(v)) for k, v in out.items()]
    res = []
    for r in out:
        if isinstance(r, tuple) and len(r) == 2 and isinstance(r[0], str | None):
            res.append((r[0], source_of(r[1])))
        else:
            res.append((getattr(r, "name", None) or getattr(r, "part", None), source_of(r)))
    return res


def json_params(params: Any) -> dict[str, Any]:
    """Parameters as JSON data for the provenance (tuples become lists)."""
    if dataclasses.is_dataclass(params) and not isinstance(params, type):
        d = dataclasses.asdict(params)
    elif isinstance(params, Mapping):
        d = dict(params)
    else:
        d = {}

    def conv(v: Any) -> Any:
        if isinstance(v, tuple | list):
            return [conv(x) for x in v]
        if isinstance(v, float | int | str | bool) or v is None:
            return v
        return str(v)

    return {k: conv(v) for k, v in d.items()}


@dataclass(frozen=True)
class StagedObject:
    """A result :func:`mrm.ops.apply.apply_operation` made, before it enters the real document."""

    source: Any
    name: str | None
    provenance: Any
    id: int = -1  # no id is reserved off the GUI thread; the real object gets one when it is pushed


class _StagingDocument:
    """The part of a Document that apply_operation uses, safe to use off the GUI thread.

    ``get`` reads a snapshot of the input objects (immutable values), ``make_object`` reserves no id and
    ``push`` records the command instead of changing anything.
    """

    def __init__(self, objects: Mapping[int, Any], model: str) -> None:
        self._objects = dict(objects)
        self.model = model
        self.label = ""
        self.staged: list[StagedObject] = []

    def get(self, obj_id: int) -> Any:
        return self._objects[obj_id]

    def make_object(
        self, source: Any, name: str | None = None, *, style: Any = None, provenance: Any = None
    ) -> StagedObject:
        return StagedObject(source, name, provenance)

    def push(self, command: Any) -> None:
        self.label = str(command.label)
        self.staged = list(command.add)


def stage_apply(
    objects: Mapping[int, Any],
    model: str,
    operation: str,
    ids: Sequence[int],
    params: Any,
    progress: Any,
    limit: int | None = None,
) -> tuple[str, list[StagedObject]]:
    """Run :func:`mrm.ops.apply.apply_operation` on a snapshot of the inputs; (undo label, results).

    ``limit`` is the largest result in pixels (the preference; the model's default when None).
    """
    from mrm.errors import DEFAULT_PIXEL_LIMIT
    from mrm.ops.apply import apply_operation

    staging = _StagingDocument(objects, model)
    apply_operation(
        staging, operation, ids, params, progress, limit=DEFAULT_PIXEL_LIMIT if limit is None else limit
    )
    return staging.label, staging.staged


Runner = Callable[[Sequence[Any], Any, Any], Any]
