"""Exact numbers: the one reader of a parameter's value and its one spelling (docs/design.md §8).

Every number a user gives — in a form, on the command line, in a chain's text, through the library, in a
project file — is read here, once, into a :class:`fractions.Fraction`, and nothing later converts it again:

* a float is read as the decimal it prints as (``repr``): ``0.2`` means 1/5 and ``1.25`` means 5/4, which is
  what a person typing them means (the binary value of 0.2 is 3602879701896397/2⁵⁴);
* integers, Fractions and Decimals are read exactly as they are;
* text is a decimal (``1.25``, ``2e-1``), a fraction (``1/3``) or an integer, as people type it: spaces
  around, a typographic minus (``−3``), a decimal comma (``2,5``) and a trailing unit (``30°``, ``2×``, ``4
  px``) are accepted.

Refused, with a message that names the parameter: booleans, None, NaN, infinities, text that is no number,
and numbers whose spelling would cost more than :data:`MAX_DIGITS` digits (``1e-1000000`` would otherwise be
a million-digit integer before any range check could look at it).

:func:`to_json` writes a number so that :func:`read_number` reads it back exactly (an int, the shortest
float, or ``"p/q"``), and :func:`spell` writes it for people (a terminating decimal, else ``p/q``).
"""

from __future__ import annotations

import math
import re
import reprlib
from decimal import Decimal, localcontext
from fractions import Fraction
from typing import Any

from mrm.core.errors import ParameterError

__all__ = [
    "MAX_DIGITS",
    "Point",
    "brief",
    "fraction_text",
    "read_number",
    "read_pixel",
    "read_point",
    "read_positive",
    "spell",
    "to_json",
    "value_text",
]

#: A point: exact coordinates (two in the plane, three in space).
Point = tuple[Fraction, ...]

#: Longest number read, in digits of its numerator or denominator or in its decimal exponent: far beyond any
#: range an operation declares (10⁻⁶ … 10⁶ for a factor, ±3600° for an angle, ±2³¹ for a coordinate), and
#: small enough that the exact arithmetic it starts costs nothing.
MAX_DIGITS = 4000

#: Units a form or a command line may leave after a number (``30°``, ``2×``, ``4 px``).
_UNITS = ("px", "°", "×", "deg")
_DECIMAL = re.compile(r"^[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE]([+-]?\d+))?$")
_RATIO = re.compile(r"^[+-]?\d+/\d+$")
_NOT_FINITE = ("nan", "inf", "infinity")


class _Short(reprlib.Repr):
    """``repr`` cut short, for messages: long texts and sequences abbreviated, huge integers described."""

    def __init__(self) -> None:
        super().__init__()
        self.maxstring = self.maxother = self.maxlong = 40
        self.maxlist = self.maxtuple = self.maxdict = self.maxset = 4

    def repr_int(self, x: int, level: int) -> str:
        # repr of an integer beyond 4300 digits raises ValueError (CPython's conversion limit), and a long one
        # says nothing a reader can use: its size does.
        if x.bit_length() > 128:
            return f"{'-' if x < 0 else ''}<an integer of about {int(x.bit_length() * 0.30103) + 1:,} digits>"
        return super().repr_int(x, level)


_SHORT = _Short()


def value_text(value: object) -> str:
    """``value`` as a message shows what a user gave: its ``repr``, at most about 40 characters.

    Never fails: a 5000-digit integer (whose ``repr`` raises ValueError), a huge sequence or an object with a
    broken ``repr`` each become a short description, so that the message refusing a value can be written.
    """
    try:
        return _SHORT.repr(value)
    except Exception:  # a repr that fails is the caller's object's bug: name its type
        return f"<{type(value).__name__}>"


def _normalise(text: str) -> str:
    t = text.strip().replace("\u2212", "-").replace("\u2009", "").replace("\u202f", "").replace(" ", "")
    for unit in _UNITS:
        if t.endswith(unit) and len(t) > len(unit):
            t = t[: -len(unit)]
            break
    if t.count(",") == 1 and "." not in t and "/" not in t:
        t = t.replace(",", ".")  # a decimal comma, as a form in many languages writes it
    return t


def _from_text(text: str, what: str) -> Fraction:
    t = _normalise(text)
    if t.lower().lstrip("+-") in _NOT_FINITE:
        raise ParameterError(f"{what} must be a finite number, got {text.strip()!r}")
    shown = text.strip() if len(text.strip()) <= 24 else text.strip()[:21] + "..."
    m = _DECIMAL.match(t)
    if m is not None:
        exponent = int(m.group(1)) if m.group(1) is not None and len(m.group(1)) <= 8 else None
        if m.group(1) is not None and (exponent is None or abs(exponent) > MAX_DIGITS):
            raise ParameterError(f"{what} is out of every allowed range, got {shown}")
    elif _RATIO.match(t) is None:
        raise ParameterError(f"{what} must be a number, got {shown!r}")
    if len(t) > MAX_DIGITS:
        raise ParameterError(f"{what} has more than {MAX_DIGITS} digits, got {shown}")
    try:
        return Fraction(t)
    except ZeroDivisionError:
        raise ParameterError(f"{what} divides by zero: {shown!r}") from None


def read_number(value: object, what: str) -> Fraction:
    """``value`` as an exact Fraction: the one reader of every number a user gives (module docstring).

    Parameters
    ----------
    value : int, float, Fraction, Decimal, str or numpy scalar
        The number.
    what : str
        What it is, for the message (``"parameter 'alpha' (α)"``).

    Raises
    ------
    ParameterError
        For booleans, None, non-finite values, text that is no number, and absurdly long numbers.

    Examples
    --------
    >>> read_number(0.2, "α"), read_number("1/3", "α"), read_number("−2,5°", "θ")
    (Fraction(1, 5), Fraction(1, 3), Fraction(-5, 2))
    """
    if isinstance(value, bool) or value is None:
        raise ParameterError(f"{what} must be a number, got {value_text(value)}")
    if isinstance(value, Fraction):
        q = value
    elif isinstance(value, int):
        q = Fraction(value)
    elif isinstance(value, float):
        if not math.isfinite(value):
            raise ParameterError(f"{what} must be a finite number, got {value_text(value)}")
        q = Fraction(repr(float(value)))  # float(): numpy's float64 is a float whose repr is np.float64(…)
    elif isinstance(value, str):
        q = _from_text(value, what)
    elif isinstance(value, Decimal):
        if not value.is_finite():
            raise ParameterError(f"{what} must be a finite number, got {value_text(value)}")
        q = _from_text(str(value), what)
    elif hasattr(value, "dtype") and hasattr(value, "item") and getattr(value, "ndim", 0) == 0:
        return read_number(value.item(), what)  # numpy scalars (and 0-d arrays)
    else:
        raise ParameterError(f"{what} must be a number, got {value_text(value)}")
    if max(q.numerator.bit_length(), q.denominator.bit_length()) > 3.33 * MAX_DIGITS:
        raise ParameterError(f"{what} has more than {MAX_DIGITS} digits")
    return q


def read_positive(value: object, what: str) -> Fraction:
    """:func:`read_number`, refusing zero and negative values."""
    q = read_number(value, what)
    if q <= 0:
        raise ParameterError(f"{what} must be positive, got {spell(q)}")
    return q


def read_point(value: object, what: str, dimension: int = 2) -> Point:
    """A point of ``dimension`` exact coordinates: a sequence of numbers, or text ``"x,y"`` (``;`` also).

    Raises
    ------
    ParameterError
        Naming the coordinate that is wrong, or saying how many are expected.
    """
    if isinstance(value, str):
        value = [p for p in value.replace(";", ",").split(",")]
    elif hasattr(value, "tolist") and not isinstance(value, (list, tuple)):
        value = value.tolist()
    if dimension == 0 and isinstance(value, (list, tuple)) and len(value) in (2, 3):
        dimension = len(value)  # either: the caller decides from its inputs (a centre in 2D or 3D)
    if not isinstance(value, (list, tuple)) or len(value) != dimension:
        names = ", ".join("xyz"[: dimension or 3])
        count = dimension or "2 or 3"
        raise ParameterError(f"{what} must be {count} numbers ({names}), got {value_text(value)}")
    return tuple(read_number(v, f"{what} {'xyz'[k]}") for k, v in enumerate(value))


def read_pixel(value: object, what: str, bound: int, dimension: int = 2) -> tuple[int, ...]:
    """A pixel (or voxel): :func:`read_point` with integer coordinates of magnitude at most ``bound``.

    Raises
    ------
    ParameterError
        Naming the point, for anything else (``(1.5, 0)``, ``(1e300, 0)``, ``"x"``).
    """
    if isinstance(value, bool):
        raise ParameterError(f"{what} must be {dimension} integers, got {value!r}")
    pt = read_point(value, what, dimension)
    if any(c.denominator != 1 or abs(c) > bound for c in pt):
        raise ParameterError(
            f"{what} must be {dimension} integers between {-bound} and {bound}, got "
            f"({', '.join(brief(c) for c in pt)})"
        )
    return tuple(int(c) for c in pt)


def fraction_text(q: Fraction) -> str:
    """``q`` as ``p/q`` (``p`` for an integer): exact, for formulas."""
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


def _terminating(q: Fraction) -> bool:
    d = q.denominator
    while d % 2 == 0:
        d //= 2
    while d % 5 == 0:
        d //= 5
    return d == 1


def spell(q: Fraction) -> str:
    """``q`` for people, exactly: a terminating decimal (``1.25``, ``0.2``) or ``p/q`` (``1/3``)."""
    if q.denominator == 1:
        return str(q.numerator)
    if _terminating(q):
        k = _decimal_places(q)
        if k <= 24:
            digits = str(abs(q.numerator) * 10**k // q.denominator).rjust(k + 1, "0")
            return ("-" if q < 0 else "") + digits[:-k] + "." + digits[-k:]
        scientific = _scientific(q)
        if scientific is not None and len(scientific) < len(fraction_text(q)):
            return scientific
    return fraction_text(q)


def _decimal_places(q: Fraction) -> int:
    d, twos, fives = q.denominator, 0, 0
    while d % 2 == 0:
        d //= 2
        twos += 1
    while d % 5 == 0:
        d //= 5
        fives += 1
    return max(twos, fives)


def brief(q: Fraction) -> str:
    """``q`` for a message: :func:`spell` when that is short, else six significant digits."""
    text = spell(q)
    if len(text) <= 24:
        return text
    with localcontext() as ctx:
        ctx.prec = 6
        return f"{Decimal(q.numerator) / Decimal(q.denominator):.5e}"


def to_json(q: Fraction) -> float | int | str:
    """A JSON value that :func:`read_number` reads back as ``q``: an int, a float or exact text."""
    if q.denominator == 1:
        return int(q.numerator)
    f = float(q)
    if math.isfinite(f) and Fraction(repr(f)) == q:
        return f
    ratio = fraction_text(q)
    decimal = _scientific(q)
    return decimal if decimal is not None and len(decimal) < len(ratio) else ratio


def _scientific(q: Fraction) -> str | None:
    """``q`` as an exact ``"me-k"`` text when it is a decimal (``1e-400`` instead of a 401-digit fraction)."""
    if not _terminating(q):
        return None
    k = _decimal_places(q)
    m = q.numerator * 10**k // q.denominator
    return f"{m}e-{k}"


def is_float(q: Fraction) -> bool:
    """True when ``q`` is exactly a float64 value."""
    d = q.denominator
    if d & (d - 1):
        return False  # not dyadic
    try:
        return Fraction(float(q)) == q
    except OverflowError:
        return False


def as_number(value: Any) -> Any:
    """A JSON-ready copy of a parameter value: Fractions :func:`to_json`, sequences element-wise."""
    if isinstance(value, Fraction):
        return to_json(value)
    if isinstance(value, (tuple, list)):
        return [as_number(v) for v in value]
    if isinstance(value, str):
        return str(value)  # a str enum (a Model) as its plain name
    return value
