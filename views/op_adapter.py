"""How the GUI reads the model's operations: one place that knows the shape of :mod:`model.ops`.

The panels are generated from each operation's parameter dataclass: every field gives a control, its
metadata the range, unit and help (``min``, ``max``, ``unit``, ``help``, optionally ``step``, ``log`` and
``choices``). An operation spec offers ``name``, ``title`` (or ``label``), ``arity`` (inputs), ``params`` (the
dataclass) and ``run(inputs, params, progress)``; its results are sources (pixel sets or polygons), or objects
carrying one as ``source`` with an optional ``name``/``part``.
"""

from __future__ import annotations

import dataclasses
import importlib
import math
import typing
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
        """The operation's parameter object from control values (raises the model's ParameterError)."""
        cls = _params_class(self.spec)
        if cls is None:
            return dict(values)
        return cls(**values)

    def run(self, inputs: Sequence[Any], params: Any, progress: Any) -> list[tuple[str | None, Any]]:
        """Run the operation; returns (part name or None, source) pairs."""
        out = self.spec.run(list(inputs), params, progress)
        return normalise_results(out)


def _params_class(spec: Any) -> type | None:
    for attr in ("params", "Params", "params_type", "parameters"):
        cls = getattr(spec, attr, None)
        if isinstance(cls, type) and dataclasses.is_dataclass(cls):
            return cls
    return None


def _kind_of(tp: Any, default: Any, meta: Mapping[str, Any]) -> tuple[str, tuple[Any, ...]]:
    if "choices" in meta:
        return "choice", tuple(meta["choices"])
    origin = typing.get_origin(tp)
    if origin is typing.Literal:
        return "choice", typing.get_args(tp)
    if tp in (bool, "bool") or isinstance(default, bool):
        return "bool", ()
    if tp in (int, "int") or (isinstance(default, int) and not isinstance(default, bool)):
        return "int", ()
    if tp in (float, "float") or isinstance(default, float):
        return "float", ()
    if isinstance(default, tuple) and len(default) == 2:
        return "point", ()
    text = str(tp)
    if "tuple" in text or "Point" in text:
        return "point", ()
    if default is None and "float" in text:
        return "float", ()
    return "text", ()


def param_infos(cls: type | None) -> tuple[ParamInfo, ...]:
    """The controls of a parameter dataclass, in field order."""
    if cls is None:
        return ()
    hints = {}
    try:
        hints = typing.get_type_hints(cls)
    except Exception:  # unresolvable annotations: fall back to the defaults' types
        hints = {}
    out = []
    for f in dataclasses.fields(cls):
        meta = dict(f.metadata or {})
        if f.default is not dataclasses.MISSING:
            default = f.default
        elif f.default_factory is not dataclasses.MISSING:
            default = f.default_factory()
        else:
            default = meta.get("default")
        kind, choices = _kind_of(hints.get(f.name, f.type), default, meta)
        out.append(
            ParamInfo(
                name=f.name,
                label=str(meta.get("label", f.name.replace("_", " "))),
                kind=kind,
                default=default,
                minimum=_num(meta.get("min")),
                maximum=_num(meta.get("max")),
                unit=str(meta.get("unit", "")),
                help=str(meta.get("help", "")),
                step=_num(meta.get("step")),
                log=bool(meta.get("log", False)),
                choices=choices,
            )
        )
    return tuple(out)


def _num(v: Any) -> float | None:
    try:
        f = float(v)
    except (TypeError, ValueError):
        return None
    return f if math.isfinite(f) else None


def _registry_mapping() -> Mapping[str, Any]:
    for modname in ("model.ops", "model.ops.base", "model.ops.registry"):
        try:
            mod = importlib.import_module(modname)
        except ImportError:
            continue
        for attr in ("registry", "REGISTRY", "OPERATIONS", "operations", "all_operations"):
            r = getattr(mod, attr, None)
            if r is None:
                continue
            if callable(r) and not isinstance(r, Mapping):
                try:
                    r = r()
                except TypeError:
                    continue
            if isinstance(r, Mapping) and r:
                return r
            if isinstance(r, Sequence) and r:
                return {getattr(s, "name", str(k)): s for k, s in enumerate(r)}
    return {}


def operations() -> list[OpInfo]:
    """Every operation the model offers, in registry order (empty when model.ops is not there)."""
    out = []
    for name, spec in _registry_mapping().items():
        if not callable(getattr(spec, "run", None)):
            continue
        out.append(
            OpInfo(
                name=str(getattr(spec, "name", name)),
                title=str(getattr(spec, "title", None) or getattr(spec, "label", None) or name),
                arity=int(getattr(spec, "arity", None) or getattr(spec, "n_inputs", None) or 1),
                params=param_infos(_params_class(spec)),
                help=str(
                    getattr(spec, "help", None) or getattr(spec, "description", None) or (spec.__doc__ or "")
                ),
                spec=spec,
            )
        )
    return out


def normalise_results(out: Any) -> list[tuple[str | None, Any]]:
    """(part, source) pairs from whatever an operation returns."""
    from model.reps.pixels import PixelSet

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


Runner = Callable[[Sequence[Any], Any, Any], Any]
