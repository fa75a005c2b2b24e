"""How the GUI reads the model's operations: one place that knows the shape of :mod:`mrm.ops`.

The panels are generated from the registry (:func:`mrm.ops.registry.operations`): every declared parameter
(:meth:`mrm.core.params.Parameters.specs`) gives a control with its kind, range, unit and help. A field's text
is read once, exactly, by the parameter's own declaration (:meth:`mrm.core.params.ParamSpec.read`: ``0.2`` is
1/5); Apply runs the pure :func:`mrm.ops.registry.plan_operation` on a worker with the input objects
(immutable values), and the GUI thread pushes its results as one undo step — so a cancel or an error leaves
the document untouched.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from mrm.core.params import ParamSpec
from mrm.ops.registry import OperationSpec, run_operation
from mrm.ops.registry import operations as registry


@dataclass(frozen=True)
class ParamInfo:
    """One parameter as a control sees it: its declaration, and the part of its range a slider spans."""

    spec: ParamSpec
    minimum: float | None = None
    maximum: float | None = None
    log: bool = False

    def __getattr__(self, name: str) -> Any:
        # name, label, kind, default, unit, help, optional, choices: the declaration's own. (Only called for
        # what the instance lacks; "spec" itself is refused so that a half-made copy cannot recurse.)
        if name == "spec":
            raise AttributeError(name)
        return getattr(self.spec, name)


@dataclass(frozen=True)
class OpInfo:
    """One operation as the panel sees it."""

    name: str
    title: str
    arity: int
    params: tuple[ParamInfo, ...]
    help: str
    spec: OperationSpec

    def run(
        self,
        inputs: Sequence[Any],
        params: Any,
        progress: Any,
        held: Any = (),
        compact_limit: int | None = None,
    ) -> list[tuple[str, Any]]:
        """Run the operation (read, size-checked); its (part name, source) outputs."""
        out = run_operation(
            self.spec, list(inputs), params, progress=progress, held=held, compact_limit=compact_limit
        )
        return list(out.outputs)


#: Slider ranges for numbers whose declaration leaves a side open (the field still takes any valid value).
_POSITIVE_RANGE = (1 / 64, 64.0)
_ANGLE_RANGE = (-360.0, 360.0)
_OPEN_RANGE = (-1000.0, 1000.0)


def _num(v: Fraction | None) -> float | None:
    return None if v is None else float(v)


def slider_range(spec: ParamSpec) -> tuple[float | None, float | None, bool]:
    """The part of a number's declared range a slider spans (minimum, maximum, logarithmic).

    The field takes the whole declared range; the slider covers a useful part of it: a positive factor on a
    logarithmic scale over [1/64, 64], an angle one turn either way.
    """
    lo, hi = _num(spec.minimum), _num(spec.maximum)
    if lo == 0.0 and not spec.min_inclusive and hi is None:
        return _POSITIVE_RANGE[0], _POSITIVE_RANGE[1], True
    if lo is not None and not spec.min_inclusive and lo == 0.0:
        lo = _POSITIVE_RANGE[0]
    if lo is not None and hi is not None and lo > 0 and hi / lo > _POSITIVE_RANGE[1] / _POSITIVE_RANGE[0]:
        return max(lo, _POSITIVE_RANGE[0]), min(hi, _POSITIVE_RANGE[1]), True
    if spec.unit == "°" and (lo is None or lo <= _ANGLE_RANGE[0]) and (hi is None or hi >= _ANGLE_RANGE[1]):
        return (*_ANGLE_RANGE, False)
    if lo is None and hi is None:
        return (*_OPEN_RANGE, False)
    if lo is None:
        lo = (hi or 0.0) - 1000.0
    if hi is None:
        hi = lo + 1000.0
    return lo, hi, lo > 0 and math.isfinite(hi / lo) and hi / lo >= 100


def param_infos(cls: type | None) -> tuple[ParamInfo, ...]:
    """The controls of a parameters class, in field order."""
    if cls is None:
        return ()
    out = []
    for spec in cls.specs():  # type: ignore[attr-defined]
        lo = hi = None
        log = False
        if spec.is_number:
            lo, hi, log = slider_range(spec)
        out.append(ParamInfo(spec, lo, hi, log))
    return tuple(out)


def operations() -> list[OpInfo]:
    """Every operation of the model's registry, the paper's first."""
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
