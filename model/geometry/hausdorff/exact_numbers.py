"""Exact real numbers in a tower of quadratic extensions ``Q(√δ₀)(√δ₁)…``.

Every number the algorithm meets is rational or an element of such a tower (a crossing on an edge is a root
of a rational quadratic; a point equidistant from three features needs nested roots). An element
``a + b·√δ`` carries a float enclosure (:mod:`mrm.geometry.hausdorff.intervals`), so most signs are read
from it; the others follow exactly from the signs of ``a``, ``b`` and ``a² − b²δ``. :data:`Num` is what the
geometric formulas take: a rational, a tower element, or (in the interval shadow) an interval.
"""

from __future__ import annotations

import math
from fractions import Fraction

from mrm.geometry.hausdorff.intervals import (
    _INF,
    _IV,
    Rat,
    _down,
    _iadd,
    _idiv1,
    _imul,
    _iv,
    _IVTower,
    _Undecided,
    _up,
)


class _Tower:
    """A growing tower ``Q(√δ₀)(√δ₁)…`` of quadratic extensions.

    Generator ``i`` is the positive root of ``δ_i``, an element of the levels below ``i``.
    """

    def __init__(self) -> None:
        self.delta: list[Num] = []
        self.root_iv: list[tuple[float, float]] = []
        self._rat_roots: dict[int, int] = {}
        self._enc_cache: dict[tuple[int, int], tuple[Fraction, Fraction]] = {}

    def _new(self, delta: Num) -> int:
        lo, hi = _iv(delta)
        glo = _down(math.sqrt(lo)) if lo > 0 else 0.0
        glo = max(glo, 0.0)
        ghi = _up(math.sqrt(hi)) if hi < _INF else _INF
        self.delta.append(delta)
        self.root_iv.append((glo, ghi))
        return len(self.delta) - 1

    def sqrt(self, x: Num) -> Num:
        """The non-negative square root of ``x`` (``x ≥ 0``), rational when it is."""
        s = _sign(x)
        if s < 0:
            raise ValueError("square root of a negative number")
        if s == 0:
            return 0
        if not isinstance(x, _Ext):
            q = Fraction(_rat(x))
            p, r = q.numerator, q.denominator
            m = p * r  # √(p/r) = √(p·r)/r
            root = math.isqrt(m)
            if root * root == m:
                return Fraction(root, r)
            lvl = self._rat_roots.get(m)
            if lvl is None:
                lvl = self._new(m)
                self._rat_roots[m] = lvl
            return _Ext(self, lvl, 0, Fraction(1, r))
        return _Ext(self, self._new(x), 0, 1)


class _Ext:
    """``a + b·√δ_lvl`` with ``a``, ``b`` of lower levels; carries a float enclosure ``[lo, hi]``."""

    __slots__ = ("a", "b", "hi", "lo", "lvl", "t")

    def __init__(self, t: _Tower, lvl: int, a: Num, b: Num) -> None:
        self.t = t
        self.lvl = lvl
        self.a = a
        self.b = b
        alo, ahi = _iv(a)
        blo, bhi = _iv(b)
        glo, ghi = t.root_iv[lvl]
        plo, phi = _imul(blo, bhi, glo, ghi)
        self.lo, self.hi = _iadd(alo, ahi, plo, phi)

    # Operators, so that geometric formulas read the same for rationals and tower elements.
    def __add__(self, o: Num) -> Num:
        return _add(self, o)

    __radd__ = __add__

    def __sub__(self, o: Num) -> Num:
        return _add(self, _neg(o))

    def __rsub__(self, o: Num) -> Num:
        return _add(o, _neg(self))

    def __mul__(self, o: Num) -> Num:
        return _mul(self, o)

    __rmul__ = __mul__

    def __eq__(self, o: object) -> bool:
        if not isinstance(o, (int, Fraction, _Ext)):
            return NotImplemented
        return _sign(_add(self, _neg(o))) == 0

    def __ne__(self, o: object) -> bool:
        if not isinstance(o, (int, Fraction, _Ext)):
            return NotImplemented
        return _sign(_add(self, _neg(o))) != 0

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"<{self.a!r} + {self.b!r}·√δ{self.lvl} ∈ [{self.lo:.6g}, {self.hi:.6g}]>"


Num = int | Fraction | _Ext | _IV


def _rat(x: Num) -> Rat:
    """``x`` where it is known to be rational (an int or a Fraction)."""
    assert isinstance(x, (int, Fraction)), f"expected a rational number, got {x!r}"
    return x


def _lvl(x: Num) -> int:
    return x.lvl if isinstance(x, _Ext) else -1


def _is_zero_rat(x: Num) -> bool:
    return not isinstance(x, _Ext) and x == 0


def _mk(t: _Tower, lvl: int, a: Num, b: Num) -> Num:
    if _is_zero_rat(b):
        return a
    return _Ext(t, lvl, a, b)


def _add(x: Num, y: Num) -> Num:
    if isinstance(x, _IV):
        return x + y
    if isinstance(y, _IV):
        return y + x
    xe, ye = isinstance(x, _Ext), isinstance(y, _Ext)
    if not xe and not ye:
        return _rat(x) + _rat(y)
    lx, ly = _lvl(x), _lvl(y)
    if lx > ly:
        assert isinstance(x, _Ext)
        return _mk(x.t, lx, _add(x.a, y), x.b)
    if ly > lx:
        assert isinstance(y, _Ext)
        return _mk(y.t, ly, _add(x, y.a), y.b)
    assert isinstance(x, _Ext) and isinstance(y, _Ext)
    return _mk(x.t, lx, _add(x.a, y.a), _add(x.b, y.b))


def _neg(x: Num) -> Num:
    if isinstance(x, _IV):
        return -x
    if isinstance(x, _Ext):
        return _Ext(x.t, x.lvl, _neg(x.a), _neg(x.b))
    return -x


def _mul(x: Num, y: Num) -> Num:
    if isinstance(x, _IV):
        return x * y
    if isinstance(y, _IV):
        return y * x
    xe, ye = isinstance(x, _Ext), isinstance(y, _Ext)
    if not xe and not ye:
        return _rat(x) * _rat(y)
    if _is_zero_rat(x) or _is_zero_rat(y):
        return 0
    lx, ly = _lvl(x), _lvl(y)
    if lx > ly:
        assert isinstance(x, _Ext)
        return _mk(x.t, lx, _mul(x.a, y), _mul(x.b, y))
    if ly > lx:
        assert isinstance(y, _Ext)
        return _mk(y.t, ly, _mul(x, y.a), _mul(x, y.b))
    assert isinstance(x, _Ext) and isinstance(y, _Ext)
    t = x.t
    a = _add(_mul(x.a, y.a), _mul(_mul(x.b, y.b), t.delta[lx]))
    b = _add(_mul(x.a, y.b), _mul(x.b, y.a))
    return _mk(t, lx, a, b)


def _sign(x: Num) -> int:
    if isinstance(x, _IV):
        if x.lo > 0:
            return 1
        if x.hi < 0:
            return -1
        raise _Undecided
    if not isinstance(x, _Ext):
        return (x > 0) - (x < 0)
    if x.lo > 0:
        return 1
    if x.hi < 0:
        return -1
    sa, sb = _sign(x.a), _sign(x.b)
    if sb == 0:
        return sa
    if sa == 0 or sa == sb:
        return sb
    # a and b·√δ have opposite signs: the larger magnitude wins.
    d = _add(_mul(x.a, x.a), _neg(_mul(_mul(x.b, x.b), x.t.delta[x.lvl])))
    return sa * _sign(d)


def _inv(x: Num) -> Num:
    if isinstance(x, _IV):
        if x.lo > 0 or x.hi < 0:
            return _IV(*_idiv1(x.lo, x.hi))
        raise _Undecided
    if not isinstance(x, _Ext):
        if x == 0:
            raise ZeroDivisionError("division by zero")
        return Fraction(1) / x
    a, b, t = x.a, x.b, x.t
    den = _add(_mul(a, a), _neg(_mul(_mul(b, b), t.delta[x.lvl])))
    if _sign(den) == 0:
        # √δ = ±a/b is in the lower field: x is 2a or 0.
        if _sign(a) * _sign(b) > 0:
            return _inv(_mul(2, a))
        raise ZeroDivisionError("division by zero")
    inv_den = _inv(den)
    return _mk(t, x.lvl, _mul(a, inv_den), _neg(_mul(b, inv_den)))


def _div(x: Num, y: Num) -> Num:
    return _mul(x, _inv(y))


def _cmp(x: Num, y: Num) -> int:
    return _sign(_add(x, _neg(y)))


def _enclose(x: Num, bits: int) -> tuple[Fraction, Fraction]:
    """A rational enclosure of ``x`` (roots bracketed at 2^-bits)."""
    if not isinstance(x, _Ext):
        q = Fraction(_rat(x))
        return q, q
    alo, ahi = _enclose(x.a, bits)
    blo, bhi = _enclose(x.b, bits)
    glo, ghi = _root_enclose(x.t, x.lvl, bits)
    ps = (blo * glo, blo * ghi, bhi * glo, bhi * ghi)
    return alo + min(ps), ahi + max(ps)


def _root_enclose(t: _Tower, lvl: int, bits: int) -> tuple[Fraction, Fraction]:
    key = (lvl, bits)
    got = t._enc_cache.get(key)
    if got is not None:
        return got
    dlo, dhi = _enclose(t.delta[lvl], bits)
    scale = 1 << (2 * bits)
    lo_n = math.isqrt(math.floor(max(dlo, Fraction(0)) * scale))
    hi_n = math.isqrt(math.ceil(dhi * scale)) + 1
    res = (Fraction(lo_n, 1 << bits), Fraction(hi_n, 1 << bits))
    t._enc_cache[key] = res
    return res


def _solve_quadratic(t: _Tower | _IVTower, a: Num, b: Num, c: Num) -> list[Num] | None:
    """Real roots of ``a·s² + b·s + c``; None when every s is a root."""
    if _sign(a) == 0:
        if _sign(b) == 0:
            return None if _sign(c) == 0 else []
        return [_neg(_div(c, b))]
    disc = _add(_mul(b, b), _neg(_mul(_mul(4, a), c)))
    sd = _sign(disc)
    if sd < 0:
        return []
    two_a = _mul(2, a)
    if sd == 0:
        return [_neg(_div(b, two_a))]
    r = t.sqrt(disc)
    inv2a = _inv(two_a)
    nb = _neg(b)
    return [_mul(_add(nb, _neg(r)), inv2a), _mul(_add(nb, r), inv2a)]
