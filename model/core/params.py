"""Parameters: declared once, read and checked once, exact from then on (docs/adr/0041).

An operation's parameters are a frozen dataclass deriving from :class:`Parameters` whose fields are declared
with :func:`param` (label, kind, unit, help, range, whether None is allowed, whether a chain's text writes the
value after the operation's name). Making one reads every field with its declaration (:meth:`ParamSpec.read`):

* numbers become exact :class:`fractions.Fraction` (:func:`mrm.core.numbers.read_number`: 0.2 is 1/5) and
  are checked against their range exactly;
* points become tuples of Fractions, models :class:`~mrm.core.models.Model`, choices one of their values.

So a parameters object that exists is valid and exact: a form field, a command-line option, a library call,
a chain's text and a project file all hand their raw values to the same constructor (or to
:meth:`Parameters.from_json` for a mapping), and nothing downstream reads or checks a number again.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Literal, Self, TypeAlias

from mrm.core.errors import ParameterError
from mrm.core.models import Model
from mrm.core.numbers import as_number, brief, read_number, read_point, spell, value_text

__all__ = [
    "POINT_LIMIT",
    "ParamKind",
    "ParamSpec",
    "Parameters",
    "param",
]

ParamKind: TypeAlias = Literal["number", "int", "bool", "point", "choice", "model", "text"]

#: Largest magnitude of a point parameter's coordinates (a centre), as for Euclidean sources.
POINT_LIMIT = Fraction(2**31)


def _fmt(v: Fraction) -> str:
    f = float(v)
    return f"{f:g}" if Fraction(f"{f:g}") == v else spell(v)


@dataclass(frozen=True)
class ParamSpec:
    """The declaration of one parameter (from the field's ``metadata["mrm"]``, written by :func:`param`).

    Attributes
    ----------
    name : str
        The field name.
    label : str
        A short label for a form (the name when not given).
    kind : str
        ``number`` (exact), ``int``, ``bool``, ``point`` (exact coordinates), ``choice``, ``model`` or
        ``text``.
    default : object
        The default value, as the field holds it (already read).
    unit : str
        The unit shown after the value (``px``, ``°``, ``×``).
    help : str
        One or two sentences for a tooltip and ``--help``.
    minimum, maximum : Fraction or None
        The range of a number, exact; ``min_inclusive``/``max_inclusive`` say whether the ends are allowed.
    choices : tuple
        The allowed values of a ``choice``.
    optional : bool
        Whether None is allowed (e.g. "no centre: the origin").
    positional : bool
        Whether a chain's text writes the value right after the operation's name (``DSS 5``).
    dimension : int
        The number of coordinates of a ``point``; 0 for two or three (a centre: the inputs' dimension).
    """

    name: str
    label: str
    kind: ParamKind
    default: Any
    unit: str = ""
    help: str = ""
    minimum: Fraction | None = None
    maximum: Fraction | None = None
    min_inclusive: bool = True
    max_inclusive: bool = True
    choices: tuple[Any, ...] = ()
    optional: bool = False
    positional: bool = False
    dimension: int = 2

    @property
    def what(self) -> str:
        """How a message names the parameter: ``parameter 'alpha' (α)``."""
        return f"parameter {self.name!r}" + (f" ({self.label})" if self.label != self.name else "")

    @property
    def is_number(self) -> bool:
        """True for ``number`` and ``int``."""
        return self.kind in ("number", "int")

    def range_text(self) -> str:
        """The allowed values as a reader writes them: ``0 < α ≤ 1e+06``, ``-3600 ≤ θ ≤ 3600``."""
        lo, hi = self.minimum, self.maximum
        left = "" if lo is None else f"{_fmt(lo)} {'≤' if self.min_inclusive else '<'} "
        right = "" if hi is None else f" {'≤' if self.max_inclusive else '<'} {_fmt(hi)}"
        if not left and not right:
            return f"{self.label} any finite number"
        return f"{left}{self.label}{right}"

    def read(self, value: Any) -> Any:
        """The one reading of a raw value (a form's text, an option, a library argument, a file's JSON).

        Returns the exact value the parameters hold; raises :class:`ParameterError` naming the parameter
        and, for a number out of range, giving the allowed range.
        """
        if value is None:
            if self.optional:
                return None
            raise ParameterError(f"{self.what} is required")
        if self.kind in ("number", "int"):
            return self._read_number(value)
        if self.kind == "point":
            if isinstance(value, bool):
                raise ParameterError(f"{self.what} must be a pair of numbers, got {value_text(value)}")
            pt = read_point(value, self.what, self.dimension)
            if any(abs(c) > POINT_LIMIT for c in pt):
                raise ParameterError(
                    f"{self.what} must have coordinates between {-POINT_LIMIT} and {POINT_LIMIT}, got "
                    f"({', '.join(brief(c) for c in pt)})"
                )
            return pt
        if self.kind == "model":
            return Model.parse(value)
        if self.kind == "bool":
            if isinstance(value, bool):
                return value
            if isinstance(value, str) and value.strip().lower() in ("true", "false"):
                return value.strip().lower() == "true"
            raise ParameterError(f"{self.what} must be true or false, got {value_text(value)}")
        if self.kind == "choice":
            for c in self.choices:
                if value == c:
                    return c
            raise ParameterError(
                f"{self.what} must be one of {', '.join(map(str, self.choices))}, got {value_text(value)}"
            )
        if not isinstance(value, str):
            raise ParameterError(f"{self.what} must be text, got {value_text(value)}")
        return value

    def _read_number(self, value: Any) -> Fraction | int:
        q = read_number(value, self.what)
        if self.kind == "int" and q.denominator != 1:
            raise ParameterError(f"{self.what} must be an integer, got {_shown(value, q)}")
        lo, hi = self.minimum, self.maximum
        if lo is not None and (q < lo or (q == lo and not self.min_inclusive)):
            first = (
                "positive"
                if lo == 0 and not self.min_inclusive
                else f"{'≥' if self.min_inclusive else '>'} {_fmt(lo)}"
            )
            raise ParameterError(
                f"{self.what} must be {first}, got {_shown(value, q)} (allowed: {self.range_text()})"
            )
        if hi is not None and (q > hi or (q == hi and not self.max_inclusive)):
            rel = "≤" if self.max_inclusive else "<"
            raise ParameterError(
                f"{self.what} must be {rel} {_fmt(hi)}, got {_shown(value, q)} (allowed: {self.range_text()})"
            )
        return int(q) if self.kind == "int" else q

    def as_dict(self) -> dict[str, Any]:
        """A JSON-ready description (for forms and documentation)."""
        d = dataclasses.asdict(self)
        d["default"] = as_number(self.default)
        d["minimum"] = None if self.minimum is None else as_number(self.minimum)
        d["maximum"] = None if self.maximum is None else as_number(self.maximum)
        d["choices"] = list(self.choices)
        return d


def _shown(value: Any, q: Fraction) -> str:
    """A number in a message: as the user wrote it when it came as text (``got 1e400``), else briefly."""
    if not isinstance(value, str):
        return brief(q)
    t = value.strip()
    return t if len(t) <= 24 else t[:21] + "..."


def _bound(v: float | Fraction | None) -> Fraction | None:
    return None if v is None else read_number(v, "a declared bound")


def param(
    default: Any,
    *,
    kind: ParamKind | None = None,
    label: str = "",
    unit: str = "",
    help: str = "",
    minimum: float | Fraction | None = None,
    maximum: float | Fraction | None = None,
    min_inclusive: bool = True,
    max_inclusive: bool = True,
    positive: bool = False,
    choices: Sequence[Any] | None = None,
    optional: bool = False,
    positional: bool = False,
    dimension: int = 2,
) -> Any:
    """A dataclass field carrying a parameter's declaration (read back by :meth:`Parameters.specs`).

    ``positive=True`` means ``minimum=0`` excluded. The kind is inferred from the default (a number, an int,
    a bool, a pair, a Model, one of ``choices``) unless given; give it when the default is None.

    Examples
    --------
    >>> @dataclass(frozen=True)
    ... class ScaleParams(Parameters):
    ...     alpha: Fraction = param(2, kind="number", label="α", positive=True, help="scale factor")
    >>> ScaleParams(0.2).alpha
    Fraction(1, 5)
    """
    if positive:
        minimum, min_inclusive = 0, False
    if kind is None:
        if choices is not None:
            kind = "choice"
        elif isinstance(default, Model):
            kind = "model"
        elif isinstance(default, bool):
            kind = "bool"
        elif isinstance(default, int):
            kind = "int"
        elif isinstance(default, (float, Fraction)):
            kind = "number"
        elif isinstance(default, tuple) and len(default) in (2, 3):
            kind, dimension = "point", len(default)
        elif isinstance(default, str):
            kind = "text"
        else:
            raise TypeError(f"cannot infer the kind of a parameter with default {default!r}; give kind=")
    meta = {
        "label": label,
        "kind": kind,
        "unit": unit,
        "help": help,
        "minimum": _bound(minimum),
        "maximum": _bound(maximum),
        "min_inclusive": min_inclusive,
        "max_inclusive": max_inclusive,
        "choices": tuple(choices or ()),
        "optional": optional,
        "positional": positional,
        "dimension": dimension,
    }
    return field(default=default, metadata={"mrm": meta})


#: The declarations of each parameters class, read once (a class's fields never change).
_SPECS: dict[type, tuple[ParamSpec, ...]] = {}


def _specs(cls: type) -> tuple[ParamSpec, ...]:
    known = _SPECS.get(cls)
    if known is not None:
        return known
    if not dataclasses.is_dataclass(cls):
        raise TypeError(f"{cls!r} is not a parameters dataclass")
    specs = []
    for f in dataclasses.fields(cls):
        meta = f.metadata.get("mrm")
        if meta is None:
            raise TypeError(
                f"field {f.name!r} of {cls.__name__} has no parameter metadata (declare it with param())"
            )
        spec = ParamSpec(name=f.name, label=meta["label"] or f.name, default=None, **_rest(meta))
        default = f.default if f.default is not dataclasses.MISSING else None
        specs.append(dataclasses.replace(spec, default=spec.read(default) if default is not None else None))
    _SPECS[cls] = tuple(specs)
    return _SPECS[cls]


def _rest(meta: Mapping[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in meta.items() if k != "label"}


class Parameters:
    """The base of every operation's parameters: a frozen dataclass of fields declared with :func:`param`.

    Making one reads every field once (:meth:`ParamSpec.read`), so its values are exact and in range:

    >>> from mrm.ops.scaling import DSSParams
    >>> DSSParams(alpha="1/3", center=(0.5, 2)).alpha
    Fraction(1, 3)
    """

    def __post_init__(self) -> None:
        for spec in _specs(type(self)):
            object.__setattr__(self, spec.name, spec.read(getattr(self, spec.name)))

    @classmethod
    def specs(cls) -> tuple[ParamSpec, ...]:
        """The declaration of every field, in order."""
        return _specs(cls)

    @classmethod
    def spec(cls, name: str) -> ParamSpec:
        """The declaration of the field ``name``."""
        for s in _specs(cls):
            if s.name == name:
                return s
        raise KeyError(name)

    @classmethod
    def read(cls, **values: Any) -> Self:
        """The parameters from raw values (text, floats, Fractions, sequences), read as every path reads them.

        The boundary of a typed caller: the fields' types are those of the exact values they hold.
        """
        return cls(**values)

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> Self:
        """Read the parameters from a mapping (a project file, ``--json``); unknown names are refused."""
        if not isinstance(data, Mapping):
            raise ParameterError(f"{cls.__name__}: parameters must be a mapping, got {type(data).__name__}")
        names = [s.name for s in _specs(cls)]
        unknown = sorted(set(map(str, data)) - set(names))
        if unknown:
            raise ParameterError(
                f"unknown parameter(s) {', '.join(unknown)} (expected {', '.join(names) or 'none'})"
            )
        return cls(**data)

    def to_json(self) -> dict[str, Any]:
        """The values as JSON data that :meth:`from_json` reads back exactly (Fractions as exact numbers)."""
        return {s.name: as_number(getattr(self, s.name)) for s in _specs(type(self))}

    def replace(self, **changes: Any) -> Self:
        """A copy with some values changed (read and checked like the others)."""
        return dataclasses.replace(self, **changes)  # type: ignore[type-var]
