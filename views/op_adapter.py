"""How the GUI reads the model's operations: one place that knows the shape of :mod:`mrm.ops`.

The panels are generated from the registry (:func:`mrm.ops.base.operations`): every field of an operation's
parameters dataclass gives a control, its ``metadata["mrm"]`` (written by :func:`mrm.ops.base.param`, read
through :func:`mrm.ops.base.param_specs`) the kind, range, unit and help. Apply runs the pure
:func:`mrm.ops.base.plan_operation` on a worker thread with the input objects (immutable values); the GUI
thread pushes its results as one undo step — so a cancel or an error leaves the document untouched.
"""

from __future__ import annotations

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
        """Run the operation (validated, size-checked); returns (part name or None, source) pairs."""
        from mrm.ops.base import run_operation

        return normalise_results(run_operation(self.spec, list(inputs), params, progress=progress))


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
    if lo is not None and hi is not None and lo > 0 and hi / lo > _POSITIVE_RANGE[1] / _POSITIVE_RANGE[0]:
        # A factor with a wide declared range (1e-6 … 1e6): the slider covers the useful [1/64, 64]; the
        # model still checks the declared range.
        return max(lo, _POSITIVE_RANGE[0]), min(hi, _POSITIVE_RANGE[1]), True
    if spec.unit == "°" and (lo is None or lo <= _ANGLE_RANGE[0]) and (hi is None or hi >= _ANGLE_RANGE[1]):
        return (*_ANGLE_RANGE, False)  # one turn either way on the slider; the field takes the declared range
    if lo is None and hi is None:
        return (*_OPEN_RANGE, False)
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
    from mrm.core.grids import PixelSet

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


Runner = Callable[[Sequence[Any], Any, Any], Any]
