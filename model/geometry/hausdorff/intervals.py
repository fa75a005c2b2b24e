"""Float intervals with outward rounding: the cheap enclosures that spare most exact computations.

Every exact number (:mod:`mrm.geometry.hausdorff.exact_numbers`) carries a float enclosure ``[lo, hi]`` built
with these operations, and its sign is read from the enclosure whenever 0 is outside it. :class:`_IV` is an
interval on its own: the shadow in which :func:`mrm.geometry.hausdorff.interior._may_improve` runs the solver
of equidistant points before paying for the exact one; it raises :class:`_Undecided` where a sign is not
certain.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Protocol

_INF = math.inf
_MAXF = 1.7976931348623157e308

Rat = int | Fraction


def _down(v: float) -> float:
    return math.nextafter(v, -_INF)


def _up(v: float) -> float:
    return math.nextafter(v, _INF)


def _rat_iv(x: Rat) -> tuple[float, float]:
    try:
        f = float(x)
    except OverflowError:
        return (_MAXF, _INF) if x > 0 else (-_INF, -_MAXF)
    return _down(f), _up(f)


def _iadd(alo: float, ahi: float, blo: float, bhi: float) -> tuple[float, float]:
    lo, hi = alo + blo, ahi + bhi
    if lo != lo or hi != hi:  # inf - inf
        return -_INF, _INF
    return _down(lo), _up(hi)


def _imul(alo: float, ahi: float, blo: float, bhi: float) -> tuple[float, float]:
    ps = (alo * blo, alo * bhi, ahi * blo, ahi * bhi)
    if any(p != p for p in ps):  # 0 * inf
        return -_INF, _INF
    return _down(min(ps)), _up(max(ps))


def _idiv1(lo: float, hi: float) -> tuple[float, float]:
    return _down(1.0 / hi), _up(1.0 / lo)


class _Enclosed(Protocol):
    """A number that carries a float enclosure ``[lo, hi]``: a tower element or an interval."""

    lo: float
    hi: float


def _iv(x: Rat | _Enclosed) -> tuple[float, float]:
    if isinstance(x, (int, Fraction)):
        return _rat_iv(x)
    return x.lo, x.hi


class _Undecided(Exception):
    """An interval computation met a sign it cannot decide: redo it exactly."""


class _IV:
    """A float interval with outward rounding: the cheap shadow of an exact computation."""

    __slots__ = ("hi", "lo")

    def __init__(self, lo: float, hi: float) -> None:
        self.lo = lo
        self.hi = hi

    def __add__(self, o: object) -> _IV:
        ol, oh = _iv(o)  # type: ignore[arg-type]
        return _IV(*_iadd(self.lo, self.hi, ol, oh))

    __radd__ = __add__

    def __neg__(self) -> _IV:
        return _IV(-self.hi, -self.lo)

    def __sub__(self, o: object) -> _IV:
        ol, oh = _iv(o)  # type: ignore[arg-type]
        return _IV(*_iadd(self.lo, self.hi, -oh, -ol))

    def __rsub__(self, o: object) -> _IV:
        ol, oh = _iv(o)  # type: ignore[arg-type]
        return _IV(*_iadd(ol, oh, -self.hi, -self.lo))

    def __mul__(self, o: object) -> _IV:
        ol, oh = _iv(o)  # type: ignore[arg-type]
        return _IV(*_imul(self.lo, self.hi, ol, oh))

    __rmul__ = __mul__


class _IVTower:
    """Stands in for a tower in interval mode."""

    def sqrt(self, x: Rat | _Enclosed) -> _IV:
        lo, hi = _iv(x)
        if hi < 0:
            raise ValueError("square root of a negative number")
        if lo <= 0:
            raise _Undecided
        return _IV(_down(math.sqrt(lo)), _up(math.sqrt(hi)))


_IV_TOWER = _IVTower()
