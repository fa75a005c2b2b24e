"""Exact Hausdorff distance between filled polygonal sets (Polygon / MultiPolygon with holes).

What is computed
----------------
For closed sets ``A`` and ``B`` the directed distance is ``h(A, B) = max_{a ∈ A} d(a, B)`` and the
Hausdorff distance ``H(A, B) = max(h(A, B), h(B, A))``. The sets are the *filled* polygons, which is what
the paper's ``H`` between Euclidean objects means: a point of ``A`` inside ``B`` is at distance 0. This
differs from the distance between the boundaries (what ``shapely.hausdorff_distance`` approximates, from
densified vertices): for ``A`` a disc of radius 10 and ``B`` the same disc with a small hole of radius 1, the
boundaries are 9 apart (the hole's rim is far from A's rim) while ``h(B, A) = 0`` and ``h(A, B) = 1``, the
radius of the largest disc that fits in the hole. For disjoint convex sets the two notions agree.

Where the maximum is (the argument the algorithm rests on)
-----------------------------------------------------------
Write ``f = d(·, B)``: 0 on ``B``, the distance to ``∂B`` outside. Split ``∂B`` into *features*: its vertices
(distance ``|x − v|``) and its edges seen as lines, valid only in the edge's slab (distance ``|ℓ(x)|/|m|``);
``f`` is the minimum of the valid features. Let ``R_k`` be the part of ``A ∖ int B`` where feature ``k`` is
nearest. On ``R_k``, ``f`` equals a convex function, so its maximum over ``R_k`` is reached on ``∂R_k``, which
is made of pieces of ``∂A``, of ``∂B`` (where ``f = 0``) and of bisectors ``{d_k = d_j}`` (a slab's side is
the bisector of the edge and its end vertex). Along a piece of ``∂A`` (a segment) ``f`` is again convex
between two consecutive changes of the nearest feature, and along a bisector (a line or a parabola) the
distance has no interior maximum (convex along a line; monotone on each side of a parabola's apex). Hence the
maximum of ``f`` over ``A`` is reached at one of

1. a vertex of ``A``;
2. a point of an edge of ``A`` where two features are equally near (the edge crosses a bisector) or where a
   line feature's slab starts or ends;
3. a point of ``int A`` equidistant from three features: a vertex of the Voronoi diagram of ``∂B``.

Case 3 is real: when ``A`` fills a hole of ``B`` (a hole of ``R(A)`` that vanished after ``DSS_1/5``), the
farthest point is the centre of the hole, not on ``∂A``. Checking vertices only — or sampling — is wrong.

How it is computed
------------------
Coordinates (float64, so dyadic rationals) are scaled by a common power of two to integers. Case 1 is
rational. For case 2 each squared feature distance is a quadratic in the edge's parameter ``t`` with rational
coefficients, so crossings are roots in ``Q(√D)``. For case 3 the equidistant points of three features are
solved symbolically (circumcentre; a bisector line meeting a parabola; angle bisectors with coefficients in
``Q(√(N₁N₂))`` meeting a parabola; three lines), which needs nested square roots. All of these numbers live
in one *tower of quadratic extensions* ``Q(√δ₁)(√δ₂)…`` in which every comparison is decided exactly (the sign
of ``a + b·√δ`` follows from the signs of ``a``, ``b`` and ``a² − b²δ``), after a float interval filter with
outward rounding settles the easy cases.

The search is a branch-and-bound that never needs to be lucky:

- case 2 splits each edge of A into pieces, drops a piece when an exact rational bound shows it cannot beat
  the best value (Lipschitz ``f(c) + r ≤ L``; the largest distance to one edge of ∂B, convex, at the piece's
  ends; the piece lies inside B), and examines the exact candidates of the remaining pieces;
- case 3 covers A with boxes, first in floats (vectorized; every float inequality carries a proven rounding
  allowance and whatever the floats cannot settle is kept), then in rationals (the convex bound taken over the
  vertices of ``box ∩ A``), and solves the triples of features that can be nearest in a small box — after an
  interval shadow of the solver has discarded the triples that certainly cannot win;
- a feature is dropped only where it cannot be the nearest one of a point outside B (an edge whose line
  leaves the box on B's side, a reflex vertex, a point outside a vertex's normal cone);
- spatial indexes (GEOS STRtree) only select *supersets* of the edges that matter, with outward-rounded boxes.

Guarantee: the result is the exact maximum. ``squared`` (a Fraction when rational) and the comparisons
(:meth:`HausdorffDistance.compare`, :meth:`HausdorffDistance.exceeds_sqrt_multiple`) are exact; ``value`` is
the float nearest to it, computed from a 2⁻²⁰⁰-wide enclosure. Typical reconstructions of a few hundred
vertices take a fraction of a second; a hole shaped like a regular polygon (many edges almost equidistant
from its centre) costs a few seconds, and the cost grows with the number of edges near the farthest points.
"""

from __future__ import annotations

import heapq
import itertools
import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np
import numpy.typing as npt
import shapely
from shapely.geometry import MultiPolygon, Polygon
from shapely.geometry.base import BaseGeometry
from shapely.geometry.polygon import orient

from mrm.core.errors import InvalidGeometryError
from mrm.core.progress import ProgressLike

__all__ = ["HausdorffDistance", "directed_hausdorff", "hausdorff_distance"]

_INF = math.inf
_MAXF = 1.7976931348623157e308


# ============================================================================================================
# Exact real arithmetic in a tower of quadratic extensions
# ============================================================================================================

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

    def __neg__(self) -> Num:
        return _neg(self)

    def __sub__(self, o: Num) -> Num:
        return _add(self, _neg(o))

    def __rsub__(self, o: Num) -> Num:
        return _add(o, _neg(self))

    def __mul__(self, o: Num) -> Num:
        return _mul(self, o)

    __rmul__ = __mul__

    def __truediv__(self, o: Num) -> Num:
        return _mul(self, _inv(o))

    def __rtruediv__(self, o: Num) -> Num:
        return _mul(o, _inv(self))

    def __lt__(self, o: Num) -> bool:
        return _sign(_add(self, _neg(o))) < 0

    def __le__(self, o: Num) -> bool:
        return _sign(_add(self, _neg(o))) <= 0

    def __gt__(self, o: Num) -> bool:
        return _sign(_add(self, _neg(o))) > 0

    def __ge__(self, o: Num) -> bool:
        return _sign(_add(self, _neg(o))) >= 0

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

    def __truediv__(self, o: Num) -> Num:
        return _mul(self, _inv(o))

    def __rtruediv__(self, o: Num) -> Num:
        return _mul(_inv(self), o)


class _IVTower:
    """Stands in for a tower in interval mode."""

    def sqrt(self, x: Num) -> Num:
        lo, hi = _iv(x)
        if hi < 0:
            raise ValueError("square root of a negative number")
        if lo <= 0:
            raise _Undecided
        return _IV(_down(math.sqrt(lo)), _up(math.sqrt(hi)))


_IV_TOWER = _IVTower()

Num = int | Fraction | _Ext | _IV


def _iv(x: Num) -> tuple[float, float]:
    if isinstance(x, (_Ext, _IV)):
        return x.lo, x.hi
    return _rat_iv(x)


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


def _idiv1(lo: float, hi: float) -> tuple[float, float]:
    return _down(1.0 / hi), _up(1.0 / lo)


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


# ============================================================================================================
# Prepared polygonal sets
# ============================================================================================================


@dataclass
class _Shape:
    """A polygonal set on the common integer grid: edges with the interior on their left."""

    edges: list[tuple[int, int, int, int]]
    norms: list[int]
    wedges: dict[tuple[int, int], list[tuple[int, int, int, int]]]
    vertices: list[tuple[int, int]]
    tree: Any
    xmax_orig: float
    bbox: tuple[int, int, int, int]
    reflex: dict[tuple[int, int], bool]
    fe: npt.NDArray[np.float64]  # the edges in original coordinates, (m, 4): ux, uy, wx, wy
    mag: float  # the largest coordinate magnitude


def _polygons(geom: BaseGeometry, what: str) -> list[Polygon]:
    if geom is None:
        raise InvalidGeometryError(f"{what}: no geometry")
    if geom.is_empty:
        return []
    if isinstance(geom, Polygon):
        polys = [geom]
    elif isinstance(geom, MultiPolygon):
        polys = list(geom.geoms)
    else:
        raise InvalidGeometryError(f"{what}: expected a Polygon or MultiPolygon, got a {geom.geom_type}")
    for p in polys:
        coords = shapely.get_coordinates(p)
        if not all(math.isfinite(v) for v in coords.ravel()):
            raise InvalidGeometryError(f"{what}: non-finite coordinates")
    if not geom.is_valid:
        raise InvalidGeometryError(f"{what}: invalid geometry ({shapely.is_valid_reason(geom)})")
    return [p for p in polys if not p.is_empty]


def _rings(polys: list[Polygon]) -> list[list[tuple[float, float]]]:
    rings: list[list[tuple[float, float]]] = []
    for p in polys:
        p = orient(p, 1.0)  # exterior counter-clockwise, holes clockwise: the interior is on the left
        for ring in [p.exterior, *p.interiors]:
            pts: list[tuple[float, float]] = []
            for x, y in list(ring.coords)[:-1]:
                q = (float(x), float(y))
                if not pts or pts[-1] != q:
                    pts.append(q)
            while len(pts) > 1 and pts[0] == pts[-1]:
                pts.pop()
            if len(pts) >= 3:
                rings.append(pts)
    return rings


def _scale_exponent(rings: list[list[tuple[float, float]]]) -> int:
    k = 0
    for ring in rings:
        for x, y in ring:
            for v in (x, y):
                d = v.as_integer_ratio()[1]
                k = max(k, d.bit_length() - 1)
    return k


def _prepare(rings: list[list[tuple[float, float]]], k: int) -> _Shape:
    def scaled(v: float) -> int:
        n, d = v.as_integer_ratio()
        return n * ((1 << k) // d)

    edges: list[tuple[int, int, int, int]] = []
    lines = []
    wedges: dict[tuple[int, int], list[tuple[int, int, int, int]]] = {}
    xmax = -_INF
    for ring in rings:
        pts = [(scaled(x), scaled(y)) for x, y in ring]
        m = len(pts)
        for i in range(m):
            u, w = pts[i], pts[(i + 1) % m]
            edges.append((u[0], u[1], w[0], w[1]))
            lines.append(((ring[i][0], ring[i][1]), (ring[(i + 1) % m][0], ring[(i + 1) % m][1])))
            prev = pts[i - 1]
            wedges.setdefault(u, []).append((u[0] - prev[0], u[1] - prev[1], w[0] - u[0], w[1] - u[1]))
            xmax = max(xmax, ring[i][0])
    norms = [(wx - ux) ** 2 + (wy - uy) ** 2 for ux, uy, wx, wy in edges]
    tree = shapely.STRtree(shapely.linestrings(lines)) if lines else None
    xs = [e[0] for e in edges]
    ys = [e[1] for e in edges]
    bbox = (min(xs), min(ys), max(xs), max(ys)) if edges else (0, 0, 0, 0)
    # A strictly reflex vertex (every wedge turns right) is never the nearest point of an outside point.
    reflex = {v: all(ix * oy - iy * ox < 0 for ix, iy, ox, oy in ws) for v, ws in wedges.items()}
    fe = np.array([[p[0][0], p[0][1], p[1][0], p[1][1]] for p in lines], dtype=np.float64).reshape(-1, 4)
    mag = float(np.abs(fe).max()) if fe.size else 0.0
    return _Shape(edges, norms, wedges, list(wedges), tree, xmax, bbox, reflex, fe, mag)


# ============================================================================================================
# Exact predicates and distances (points may be rationals or tower elements; shapes are integer)
# ============================================================================================================


def _dseg2(s: _Shape, e: int, px: Num, py: Num) -> tuple[Num, int, Num]:
    """Squared distance from p to edge e, the kind of nearest point and the cross product.

    Kind 0: the nearest point is inside the edge, 1: it is u, 2: it is w. The cross product is positive when
    p is on the interior side of the edge's line.
    """
    ux, uy, wx, wy = s.edges[e]
    mx, my = wx - ux, wy - uy
    dx, dy = px - ux, py - uy
    cross = mx * dy - my * dx
    proj = dx * mx + dy * my
    if _sign(proj) <= 0:
        return dx * dx + dy * dy, 1, cross
    n = s.norms[e]
    if _cmp(proj, n) >= 0:
        ex, ey = px - wx, py - wy
        return ex * ex + ey * ey, 2, cross
    return _div(cross * cross, n), 0, cross


def _in_wedges(s: _Shape, v: tuple[int, int], dx: Num, dy: Num) -> bool:
    """Tell whether the direction (dx, dy) from vertex v points into the interior."""
    for ix, iy, ox, oy in s.wedges[v]:
        left_in = _sign(ix * dy - iy * dx) > 0
        left_out = _sign(ox * dy - oy * dx) > 0
        turn = ix * oy - iy * ox
        if turn > 0:
            inside = left_in and left_out
        elif turn < 0:
            inside = left_in or left_out
        else:
            inside = left_in
        if inside:
            return True
    return False


def _to_orig_iv(x: Num, k: int) -> tuple[float, float]:
    lo, hi = _iv(x)
    return _down(math.ldexp(lo, -k)), _up(math.ldexp(hi, -k))


def _radius_orig(d2: Num, k: int) -> float:
    """A float ≥ √d2 in original units."""
    hi = _iv(d2)[1]
    if hi == _INF:
        return _INF
    return _up(math.ldexp(_up(math.sqrt(max(hi, 0.0))), -k))


def _query(s: _Shape, xlo: float, ylo: float, xhi: float, yhi: float) -> list[int]:
    if s.tree is None:
        return []
    if not all(math.isfinite(v) for v in (xlo, ylo, xhi, yhi)):
        return list(range(len(s.edges)))
    return [int(i) for i in s.tree.query(shapely.box(xlo, ylo, xhi, yhi))]


@dataclass
class _Near:
    f2: Num  # squared distance to the set (0 inside)
    edge: int  # an edge of the boundary at minimum distance
    inside: bool


def _near(s: _Shape, k: int, px: Num, py: Num) -> _Near:
    """Exact squared distance from p to the filled set s (and whether p is inside)."""
    xlo, xhi = _to_orig_iv(px, k)
    ylo, yhi = _to_orig_iv(py, k)
    assert s.tree is not None
    xm = 0.5 * (xlo + xhi) if math.isfinite(xlo + xhi) else 0.0
    ym = 0.5 * (ylo + yhi) if math.isfinite(ylo + yhi) else 0.0
    first = int(s.tree.query_nearest(shapely.Point(xm, ym))[0])
    d0, _, _ = _dseg2(s, first, px, py)
    if _sign(d0) == 0:
        return _Near(0, first, True)
    r = _radius_orig(d0, k)
    cands = _query(s, _down(xlo - r), _down(ylo - r), _up(xhi + r), _up(yhi + r))
    best: Num = d0
    best_edges: list[tuple[int, int, Num]] = []
    for e in cands:
        d2, kind, cross = _dseg2(s, e, px, py)
        c = _cmp(d2, best)
        if c < 0:
            best, best_edges = d2, [(e, kind, cross)]
        elif c == 0:
            best_edges.append((e, kind, cross))
    if not best_edges:  # the first edge is always a candidate; keep the code total anyway
        d2, kind, cross = _dseg2(s, first, px, py)
        best_edges = [(first, kind, cross)]
    if _sign(best) == 0:
        return _Near(0, best_edges[0][0], True)
    # The side of p: from an edge whose nearest point is inside it, else from the wedges at the vertex.
    for e, kind, cross in best_edges:
        if kind == 0:
            return _Near(best, e, _sign(cross) > 0)
    e, kind, _ = best_edges[0]
    ux, uy, wx, wy = s.edges[e]
    v = (ux, uy) if kind == 1 else (wx, wy)
    inside = _in_wedges(s, v, px - v[0], py - v[1])
    return _Near(best, e, inside)


def _contains(s: _Shape, k: int, px: Num, py: Num) -> bool:
    """Is p in the closed set s? (exact crossing number, boundary included)."""
    xlo, _ = _to_orig_iv(px, k)
    ylo, yhi = _to_orig_iv(py, k)
    cands = _query(s, xlo, ylo, _up(max(s.xmax_orig, xlo) + 1.0), yhi)
    inside = False
    for e in cands:
        ax, ay, bx, by = s.edges[e]
        cross = (bx - ax) * (py - ay) - (by - ay) * (px - ax)
        sc = _sign(cross)
        # On the supporting line and between the endpoints: on the edge.
        if (
            sc == 0
            and _cmp(px, min(ax, bx)) >= 0
            and _cmp(px, max(ax, bx)) <= 0
            and _cmp(py, min(ay, by)) >= 0
            and _cmp(py, max(ay, by)) <= 0
        ):
            return True
        a_above = _cmp(py, ay) < 0  # ay > py
        b_above = _cmp(py, by) < 0
        if a_above != b_above and ((by > ay and sc > 0) or (by < ay and sc < 0)):
            inside = not inside
    return inside


def _seg_seg_dist2(p: tuple[Rat, Rat], q: tuple[Rat, Rat], s: _Shape, e: int) -> Rat:
    ux, uy, wx, wy = s.edges[e]

    def orient2(ax: Rat, ay: Rat, bx: Rat, by: Rat, cx: Rat, cy: Rat) -> int:
        v = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
        return (v > 0) - (v < 0)

    o1 = orient2(p[0], p[1], q[0], q[1], ux, uy)
    o2 = orient2(p[0], p[1], q[0], q[1], wx, wy)
    o3 = orient2(ux, uy, wx, wy, p[0], p[1])
    o4 = orient2(ux, uy, wx, wy, q[0], q[1])
    if o1 * o2 < 0 and o3 * o4 < 0:
        return 0
    cands = [
        _pt_seg2(ux, uy, p, q),
        _pt_seg2(wx, wy, p, q),
        _pt_seg2(p[0], p[1], (ux, uy), (wx, wy)),
        _pt_seg2(q[0], q[1], (ux, uy), (wx, wy)),
    ]
    return min(cands)


def _pt_seg2(px: Rat, py: Rat, a: tuple[Rat, Rat], b: tuple[Rat, Rat]) -> Rat:
    mx, my = b[0] - a[0], b[1] - a[1]
    dx, dy = px - a[0], py - a[1]
    proj = dx * mx + dy * my
    if proj <= 0:
        return dx * dx + dy * dy
    n = mx * mx + my * my
    if proj >= n:
        ex, ey = px - b[0], py - b[1]
        return ex * ex + ey * ey
    cross = mx * dy - my * dx
    return Fraction(cross * cross, 1) / n


Box = tuple[Fraction, Fraction, Fraction, Fraction]


def _pt_box2(px: Rat, py: Rat, q: Box) -> Rat:
    dx: Rat = q[0] - px if px < q[0] else (px - q[2] if px > q[2] else 0)
    dy: Rat = q[1] - py if py < q[1] else (py - q[3] if py > q[3] else 0)
    return dx * dx + dy * dy


def _pt_box_max2(px: Rat, py: Rat, q: Box) -> Rat:
    dx = max(abs(px - q[0]), abs(px - q[2]))
    dy = max(abs(py - q[1]), abs(py - q[3]))
    return dx * dx + dy * dy


def _corners(q: Box) -> list[tuple[Fraction, Fraction]]:
    return [(q[0], q[1]), (q[2], q[1]), (q[2], q[3]), (q[0], q[3])]


def _seg_box2(s: _Shape, e: int, q: Box) -> Rat:
    ux, uy, wx, wy = s.edges[e]
    if (q[0] <= ux <= q[2] and q[1] <= uy <= q[3]) or (q[0] <= wx <= q[2] and q[1] <= wy <= q[3]):
        return 0
    cs = _corners(q)
    # does the segment cross the box? (it has no endpoint inside, so it crosses two sides)
    sides = [0, 0, 0, 0]
    for i, (cx, cy) in enumerate(cs):
        v = (wx - ux) * (cy - uy) - (wy - uy) * (cx - ux)
        sides[i] = (v > 0) - (v < 0)
    # Separating axes: the box's two axes and the segment's normal.
    straddles = not (all(x > 0 for x in sides) or all(x < 0 for x in sides))
    overlaps = max(ux, wx) >= q[0] and min(ux, wx) <= q[2] and max(uy, wy) >= q[1] and min(uy, wy) <= q[3]
    if straddles and overlaps:
        return 0
    best = min(_pt_box2(ux, uy, q), _pt_box2(wx, wy, q))
    for cx, cy in cs:
        best = min(best, _pt_seg2(cx, cy, (ux, uy), (wx, wy)))
    return best


# ============================================================================================================
# The directed distance
# ============================================================================================================

#: A box or a piece of edge becomes a leaf when at most this many features can be nearest in it.
_LEAF_FEATURES = 6
#: Depth at which a box becomes a leaf whatever its features: only exact ties get there (a square hole's
#: centre is equidistant from four edges), and those involve few features.
_MAX_DEPTH = 200


@dataclass
class _Best:
    f2: Num = -1
    x: Num = 0
    y: Num = 0
    where: str = ""


@dataclass
class _Run:
    a: _Shape
    b: _Shape
    k: int
    t: _Tower
    progress: ProgressLike | None
    best: _Best = field(default_factory=_Best)
    ticks: int = 0

    def tick(self) -> None:
        self.ticks += 1
        if self.progress is not None and self.ticks % 64 == 0:
            self.progress.update(None)

    _llo: float | None = None

    def offer(self, f2: Num, x: Num, y: Num, where: str) -> None:
        if _cmp(f2, self.best.f2) > 0:
            self.best = _Best(f2, x, y, where)
            self._llo = None

    def l_lo(self) -> float:
        """A float ≤ the best distance so far, in original units (-inf before any)."""
        if self._llo is None:
            lo = _iv(self.best.f2)[0] if _sign(self.best.f2) > 0 else -1.0
            self._llo = _down(math.ldexp(_down(math.sqrt(lo)), -self.k)) if lo > 0 else -_INF
        return self._llo


def _directed(run: _Run) -> None:
    a, b, k = run.a, run.b, run.k
    # 1. Vertices of A.
    near_at: dict[tuple[int, int], _Near] = {}
    for v in a.vertices:
        run.tick()
        nr = _near(b, k, v[0], v[1])
        near_at[v] = nr
        run.offer(0 if nr.inside else nr.f2, v[0], v[1], "vertex")
    # 2. Edges of A, most promising first.
    todo: list[tuple[float, int, Rat]] = []
    for i, (px, py, qx, qy) in enumerate(a.edges):
        # f ≤ d(·, e) for any edge e of ∂B, and d(·, e) is convex: its largest value on the edge is at an end.
        u2 = min(
            max(_rat(_dseg2(b, nr.edge, px, py)[0]), _rat(_dseg2(b, nr.edge, qx, qy)[0]))
            for nr in (near_at[(px, py)], near_at[(qx, qy)])
        )
        todo.append((-float(u2), i, u2))
    todo.sort()
    for _, i, u2 in todo:
        run.tick()
        if _cmp(u2, run.best.f2) <= 0:
            continue
        _edge(run, i, u2)
    # 3. Points of int A equidistant from three features.
    _interior(run)


def _features_near_segment(
    run: _Run, p: tuple[Rat, Rat], q: tuple[Rat, Rat], u2: Rat
) -> tuple[list[int], list[tuple[int, int]]]:
    """Features of ∂B that can be nearest to an outside point of segment pq at distance ≤ √u2."""
    b, k = run.b, run.k
    r = _radius_orig(u2, k)
    xlo, _ = _to_orig_iv(min(p[0], q[0]), k)
    ylo, _ = _to_orig_iv(min(p[1], q[1]), k)
    _, xhi = _to_orig_iv(max(p[0], q[0]), k)
    _, yhi = _to_orig_iv(max(p[1], q[1]), k)
    edges = []
    verts: set[tuple[int, int]] = set()
    for e in _query(b, _down(xlo - r), _down(ylo - r), _up(xhi + r), _up(yhi + r)):
        if _seg_seg_dist2(p, q, b, e) > u2:
            continue
        ux, uy, wx, wy = b.edges[e]
        for vv in ((ux, uy), (wx, wy)):
            if vv not in verts and not b.reflex[vv] and _pt_seg2(vv[0], vv[1], p, q) <= u2:
                verts.add(vv)
        mx, my = wx - ux, wy - uy
        if any(mx * (cy - uy) - my * (cx - ux) < 0 for cx, cy in (p, q)):
            edges.append(e)
    return edges, sorted(verts)


#: A piece of an edge of A becomes a leaf when at most this many features can be nearest on it.
_LEAF_FEATURES_1D = 6


def _edge(run: _Run, i: int, u2: Rat) -> None:
    """Offer the maximum of d(·, B) along edge i of A.

    A branch-and-bound over pieces [t0, t1] of the edge; its leaves examine the exact candidates (feature
    crossings and slab ends).
    """
    a, b, k = run.a, run.b, run.k
    px, py, qx, qy = a.edges[i]
    dx, dy = qx - px, qy - py
    length2 = dx * dx + dy * dy
    stack: list[tuple[Fraction, Fraction, int]] = [(Fraction(0), Fraction(1), 0)]
    while stack:
        t0, t1, depth = stack.pop()
        run.tick()
        p0 = (px + t0 * dx, py + t0 * dy)
        p1 = (px + t1 * dx, py + t1 * dy)
        tm = (t0 + t1) / 2
        cx, cy = px + tm * dx, py + tm * dy
        nr = _near(b, k, cx, cy)
        if nr.inside and not _segment_meets_boundary(run, p0, p1):
            continue  # the piece lies inside B
        piece_u2 = max(_rat(_dseg2(b, nr.edge, p0[0], p0[1])[0]), _rat(_dseg2(b, nr.edge, p1[0], p1[1])[0]))
        if depth == 0:
            piece_u2 = min(piece_u2, u2)
        if _cmp(piece_u2, run.best.f2) <= 0:
            continue
        if _lipschitz_prunes(run, (t1 - t0) ** 2 * length2 / 4, nr.f2):
            continue
        edges, verts = _features_near_segment(run, p0, p1, piece_u2)
        if len(edges) + len(verts) > _LEAF_FEATURES_1D and depth < _MAX_DEPTH:
            stack.append((t0, tm, depth + 1))
            stack.append((tm, t1, depth + 1))
            continue
        _edge_leaf(run, (px, py), (dx, dy), t0, t1, edges, verts)


def _segment_meets_boundary(run: _Run, p: tuple[Rat, Rat], q: tuple[Rat, Rat]) -> bool:
    b, k = run.b, run.k
    xlo, _ = _to_orig_iv(min(p[0], q[0]), k)
    ylo, _ = _to_orig_iv(min(p[1], q[1]), k)
    _, xhi = _to_orig_iv(max(p[0], q[0]), k)
    _, yhi = _to_orig_iv(max(p[1], q[1]), k)
    return any(_seg_seg_dist2(p, q, b, e) == 0 for e in _query(b, xlo, ylo, xhi, yhi))


_Quad = tuple[Rat, Rat, Rat, Rat | None, Rat | None]


def _edge_leaf(
    run: _Run,
    p: tuple[int, int],
    d: tuple[int, int],
    t0: Fraction,
    t1: Fraction,
    edges: list[int],
    verts: list[tuple[int, int]],
) -> None:
    b = run.b
    (px, py), (dx, dy) = p, d
    # Each feature's squared distance along the edge: c2·t² + c1·t + c0, valid for lo ≤ t ≤ hi.
    feats: list[_Quad] = []
    for vx, vy in verts:
        wx, wy = px - vx, py - vy
        feats.append((dx * dx + dy * dy, 2 * (dx * wx + dy * wy), wx * wx + wy * wy, None, None))
    ends: list[Rat] = []
    for e in edges:
        ux, uy, ex, ey = b.edges[e]
        mx, my = ex - ux, ey - uy
        n = b.norms[e]
        l0 = mx * (py - uy) - my * (px - ux)
        l1 = mx * dy - my * dx
        pi0 = (px - ux) * mx + (py - uy) * my
        pi1 = dx * mx + dy * my
        lo: Rat | None = None
        hi: Rat | None = None
        if pi1 == 0:
            if not 0 <= pi0 <= n:
                continue
        else:
            ta, tb = Fraction(-pi0, pi1), Fraction(n - pi0, pi1)
            lo, hi = min(ta, tb), max(ta, tb)
            if hi < t0 or lo > t1:
                continue
            ends.extend(t for t in (lo, hi) if t0 <= t <= t1)
        feats.append((Fraction(l1 * l1, n), Fraction(2 * l0 * l1, n), Fraction(l0 * l0, n), lo, hi))

    def valid(f: _Quad, t: Num) -> bool:
        return (f[3] is None or _cmp(t, f[3]) >= 0) and (f[4] is None or _cmp(t, f[4]) <= 0)

    def value(f: _Quad, t: Num) -> Num:
        return (f[0] * t + f[1]) * t + f[2]

    cands: list[tuple[Num, int]] = [(t, -1) for t in ends]
    for j1 in range(len(feats)):
        for j2 in range(j1 + 1, len(feats)):
            f, g = feats[j1], feats[j2]
            roots = _solve_quadratic(run.t, f[0] - g[0], f[1] - g[1], f[2] - g[2])
            for t in roots or ():
                if _cmp(t, t0) >= 0 and _cmp(t, t1) <= 0 and valid(f, t) and valid(g, t):
                    cands.append((t, j1))
    for t, j in cands:
        if j >= 0 and _cmp(value(feats[j], t), run.best.f2) <= 0:
            continue  # f(t) ≤ this feature's distance ≤ the best so far
        if any(valid(f, t) and _cmp(value(f, t), run.best.f2) <= 0 for f in feats):
            continue
        x, y = px + t * dx, py + t * dy
        nr = _near(b, run.k, x, y)
        if not nr.inside:
            run.offer(nr.f2, x, y, "edge")


def _box_orig(q: Box, k: int, pad: float = 0.0) -> tuple[float, float, float, float]:
    xlo, _ = _to_orig_iv(q[0], k)
    ylo, _ = _to_orig_iv(q[1], k)
    _, xhi = _to_orig_iv(q[2], k)
    _, yhi = _to_orig_iv(q[3], k)
    if pad:
        return _down(xlo - pad), _down(ylo - pad), _up(xhi + pad), _up(yhi + pad)
    return xlo, ylo, xhi, yhi


def _interior(run: _Run) -> None:
    """Branch-and-bound over boxes for the points of int A equidistant from three features of ∂B.

    A first stage works on batches of float boxes (dyadic, so exact) with vectorized float tests whose
    rounding is bounded: a box is dropped when ``f(c) + r ≤ best`` (Lipschitz, with an upper bound of
    ``d(c, ∂B)``), or when it certainly misses ∂A with its centre certainly outside A, or certainly misses ∂B
    with its centre certainly inside B; whatever the floats cannot settle is kept. Boxes with few edges of ∂B
    nearby, or below float resolution, go to the exact stage (:func:`_exact_boxes`).
    """
    a, b, k = run.a, run.b, run.k
    if not a.edges or b.tree is None:
        return
    x0, y0 = float(a.fe[:, [0, 2]].min()), float(a.fe[:, [1, 3]].min())
    x1, y1 = float(a.fe[:, [0, 2]].max()), float(a.fe[:, [1, 3]].max())
    # A root square whose corner is on a power-of-two grid and whose side is a power of two: every sub-box
    # then has float corners and an exact centre.
    grid = math.ldexp(1.0, math.frexp(max(x1 - x0, y1 - y0, 1e-300))[1] - 1)
    rx, ry = math.floor(x0 / grid) * grid, math.floor(y0 / grid) * grid
    side = math.ldexp(1.0, math.frexp(max(x1 - rx, y1 - ry))[1])
    # Rounding allowance of the float distance bounds: a few ulps of the largest coordinate in play, the
    # boxes' included (see _fl_nearest_up).
    mag = max(a.mag, b.mag, abs(rx) + side, abs(ry) + side)
    slack = math.ldexp(mag + 1.0, -44)
    counter = itertools.count()
    heap: list[tuple[float, int, float, float, float, int]] = [(0.0, next(counter), rx, ry, side, 0)]
    while heap:
        batch = [heapq.heappop(heap) for _ in range(min(len(heap), _BATCH))]
        run.tick()
        bx0 = np.array([t[2] for t in batch])
        by0 = np.array([t[3] for t in batch])
        sz = np.array([t[4] for t in batch])
        depth = np.array([t[5] for t in batch])
        bx1, by1 = bx0 + sz, by0 + sz
        cx, cy = bx0 + sz / 2, by0 + sz / 2
        r = _vup(_vup(_vup(np.hypot(sz, sz)) / 2) + slack)
        fup = _fl_nearest_up(b, cx, cy, slack)
        upper = _vup(fup + r)
        llo = run.l_lo()
        live = upper > llo  # else f ≤ f(c) + r ≤ best on the box
        # Outside A: misses ∂A and the centre is outside. Inside B: misses ∂B and the centre is inside.
        idx = np.flatnonzero(live)
        if idx.size:
            misses_a = _fl_misses(a, bx0[idx], by0[idx], bx1[idx], by1[idx])
            if misses_a.any():
                j = idx[misses_a]
                ins, sure = _fl_inside(a, cx[j], cy[j])
                live[j[sure & ~ins]] = False
            idx = np.flatnonzero(live)
            misses_b = _fl_misses(b, bx0[idx], by0[idx], bx1[idx], by1[idx])
            if misses_b.any():
                j = idx[misses_b]
                ins, sure = _fl_inside(b, cx[j], cy[j])
                live[j[sure & ins]] = False
        idx = np.flatnonzero(live)
        if not idx.size:
            continue
        # Below ~2⁻³² of the coordinates floats no longer tell features apart: exact arithmetic decides; it
        # also takes over where few edges of ∂B are near (its bounds are sharper there).
        tiny = r[idx] <= 4096 * slack
        split = ~tiny
        ask = np.flatnonzero(split)
        if ask.size:
            j = idx[ask]
            split[ask] = _fl_count_near(b, bx0[j], by0[j], bx1[j], by1[j], upper[j]) > _LEAF_EDGES
        for i, sp in zip(idx.tolist(), split.tolist(), strict=True):
            if sp:
                h = float(sz[i]) / 2
                for ox, oy in ((0.0, 0.0), (h, 0.0), (0.0, h), (h, h)):
                    item = (
                        -float(upper[i]),
                        next(counter),
                        float(bx0[i]) + ox,
                        float(by0[i]) + oy,
                        h,
                        int(depth[i]) + 1,
                    )
                    heapq.heappush(heap, item)
            else:
                scale = 1 << k
                q = (
                    Fraction(float(bx0[i])) * scale,
                    Fraction(float(by0[i])) * scale,
                    Fraction(float(bx1[i])) * scale,
                    Fraction(float(by1[i])) * scale,
                )
                _exact_boxes(run, q, int(depth[i]))


#: How many float boxes the first stage handles at once.
_BATCH = 256
#: A box goes to the exact stage when at most this many edges of ∂B lie within its float upper bound.
_LEAF_EDGES = 4


def _exact_boxes(run: _Run, root: Box, depth0: int) -> None:
    """The exact stage: exact tests, exact bounds, subdivision in rationals, leaves solved exactly."""
    a, b, k = run.a, run.b, run.k
    counter = itertools.count()
    heap: list[tuple[float, int, Box, int]] = [(0.0, next(counter), root, depth0)]
    while heap:
        _, _, q, depth = heapq.heappop(heap)
        run.tick()
        box_f = _box_orig(q, k)
        cx, cy = (q[0] + q[2]) / 2, (q[1] + q[3]) / 2
        a_edges = [e for e in _query(a, *box_f) if _seg_box2(a, e, q) == 0]
        if not a_edges and not _contains(a, k, cx, cy):
            continue  # the box misses ∂A and its centre is outside A: it is outside A
        if not _meets_boundary(b, k, q, box_f) and _contains(b, k, cx, cy):
            continue  # inside B: d(·, B) = 0 on the box
        nr = _near(b, k, cx, cy)
        if not nr.inside and _contains(a, k, cx, cy):
            run.offer(nr.f2, cx, cy, "interior")  # any point of A gives a lower bound
        # f ≤ d(·, e) for the edge e nearest to the centre; d(·, e) is convex, so its maximum over the polygon
        # Q ∩ A is at one of that polygon's vertices.
        u2 = max(_rat(_dseg2(b, nr.edge, x, y)[0]) for x, y in _clip_vertices(run, q, a_edges))
        if _cmp(u2, run.best.f2) <= 0:
            continue
        verts, edges = _features_near_box(run, q, u2)
        if len(verts) + len(edges) > _LEAF_FEATURES and depth < _MAX_DEPTH:
            key = -math.ldexp(math.sqrt(float(u2)), -k)
            for child in (
                (q[0], q[1], cx, cy),
                (cx, q[1], q[2], cy),
                (q[0], cy, cx, q[3]),
                (cx, cy, q[2], q[3]),
            ):
                heapq.heappush(heap, (key, next(counter), child, depth + 1))
            continue
        _leaf(run, q, u2, verts, edges)


def _clip_vertices(run: _Run, q: Box, a_edges: list[int]) -> list[tuple[Rat, Rat]]:
    """A superset of the vertices of the polygon Q ∩ A, all rational.

    Q's corners in A, A's vertices in Q, and the points where the edges of A meeting Q cross Q's sides.
    """
    a, k = run.a, run.k
    if not a_edges:
        return list(_corners(q))
    pts: list[tuple[Rat, Rat]] = [c for c in _corners(q) if _contains(a, k, c[0], c[1])]
    x0, y0, x1, y1 = q
    for e in a_edges:
        ux, uy, wx, wy = a.edges[e]
        for vx, vy in ((ux, uy), (wx, wy)):
            if x0 <= vx <= x1 and y0 <= vy <= y1:
                pts.append((vx, vy))
        if ux != wx:
            for x in (x0, x1):
                if (ux - x) * (wx - x) <= 0:
                    y = uy + (x - ux) * (wy - uy) / Fraction(wx - ux)
                    if y0 <= y <= y1:
                        pts.append((x, y))
        if uy != wy:
            for y in (y0, y1):
                if (uy - y) * (wy - y) <= 0:
                    x = ux + (y - uy) * (wx - ux) / Fraction(wy - uy)
                    if x0 <= x <= x1:
                        pts.append((x, y))
    return pts or list(_corners(q))


F64 = npt.NDArray[np.float64]
Bools = npt.NDArray[np.bool_]


def _vup(x: F64) -> F64:
    return np.nextafter(x, np.inf)


def _fl_nearest_up(s: _Shape, px: F64, py: F64, slack: float) -> F64:
    """Floats ≥ the distance from each point to ∂s, through one nearby edge.

    The clamped projection ``q = u + t·(w − u)`` (t ∈ [0, 1] exactly) is a point of the segment up to the
    rounding of three operations on numbers of magnitude ≤ 2M (M the largest coordinate), and ``hypot`` is
    within one ulp, so the computed distance is off by less than ``2⁻⁴⁷·M``: ``slack = 2⁻⁴⁴·(M + 1)`` covers
    it, with the result rounded up.
    """
    pairs = s.tree.query_nearest(shapely.points(px, py))
    _, first = np.unique(pairs[0], return_index=True)
    e = s.fe[pairs[1][first]]
    ux, uy, wx, wy = e[:, 0], e[:, 1], e[:, 2], e[:, 3]
    mx, my = wx - ux, wy - uy
    nn = mx * mx + my * my
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(nn > 0, ((px - ux) * mx + (py - uy) * my) / np.where(nn > 0, nn, 1.0), 0.0)
    t = np.clip(t, 0.0, 1.0)
    d = np.hypot(px - (ux + t * mx), py - (uy + t * my))
    return _vup(_vup(d) + slack)


def _fl_pairs(s: _Shape, x0: F64, y0: F64, x1: F64, y1: F64) -> tuple[npt.NDArray[np.intp], F64]:
    """(box index, edge coordinates) for every edge whose envelope meets each box."""
    pairs = s.tree.query(shapely.box(x0, y0, x1, y1))
    return pairs[0], s.fe[pairs[1]]


def _fl_sides(e: F64, cx: F64, cy: F64) -> tuple[F64, F64]:
    """Orientation of (cx, cy) to each edge's line, with a bound on its rounding error."""
    ux, uy, wx, wy = e[:, 0], e[:, 1], e[:, 2], e[:, 3]
    p1 = (wx - ux) * (cy - uy)
    p2 = (wy - uy) * (cx - ux)
    # Each product has a relative error below 3u (u = 2⁻⁵³), the difference adds u: 2⁻⁵⁰ covers it.
    return p1 - p2, np.ldexp(np.abs(p1) + np.abs(p2), -50)


def _fl_misses(s: _Shape, x0: F64, y0: F64, x1: F64, y1: F64) -> Bools:
    """Boxes that certainly miss every edge (separated along an axis or by the edge's line)."""
    n = x0.size
    i, e = _fl_pairs(s, x0, y0, x1, y1)
    if not i.size:
        return np.ones(n, dtype=bool)
    bx0, by0, bx1, by1 = x0[i], y0[i], x1[i], y1[i]
    ux, uy, wx, wy = e[:, 0], e[:, 1], e[:, 2], e[:, 3]
    apart = (np.maximum(ux, wx) < bx0) | (np.minimum(ux, wx) > bx1)
    apart |= (np.maximum(uy, wy) < by0) | (np.minimum(uy, wy) > by1)
    pos = np.ones(i.size, dtype=bool)
    neg = np.ones(i.size, dtype=bool)
    for cx, cy in ((bx0, by0), (bx1, by0), (bx1, by1), (bx0, by1)):
        v, err = _fl_sides(e, cx, cy)
        pos &= v > err
        neg &= v < -err
    meets = ~(apart | pos | neg)
    misses: Bools = np.bincount(i[meets], minlength=n) == 0
    return misses


def _fl_inside(s: _Shape, px: F64, py: F64) -> tuple[Bools, Bools]:
    """Crossing-number point-in-set test in floats: (inside, certain) for each point."""
    n = px.size
    i, e = _fl_pairs(s, px, py, np.full(n, s.xmax_orig + 1.0), py)
    inside = np.zeros(n, dtype=bool)
    sure = np.ones(n, dtype=bool)
    if i.size:
        x, y = px[i], py[i]
        ay, by = e[:, 1], e[:, 3]
        straddle = (ay > y) != (by > y)
        v, err = _fl_sides(e, x, y)
        unsure = straddle & (np.abs(v) <= err)
        cross = straddle & (((by > ay) & (v > 0)) | ((by < ay) & (v < 0)))
        inside = np.bincount(i[cross], minlength=n) % 2 == 1
        sure = np.bincount(i[unsure], minlength=n) == 0
    return inside, sure


def _fl_count_near(s: _Shape, x0: F64, y0: F64, x1: F64, y1: F64, radius: F64) -> npt.NDArray[np.intp]:
    """About how many edges lie within ``radius`` of each box (decides splitting only, never a result)."""
    n = x0.size
    i, e = _fl_pairs(s, x0 - radius, y0 - radius, x1 + radius, y1 + radius)
    if not i.size:
        return np.zeros(n, dtype=np.intp)
    bx0, by0, bx1, by1, rad = x0[i], y0[i], x1[i], y1[i], radius[i]
    ux, uy, wx, wy = e[:, 0], e[:, 1], e[:, 2], e[:, 3]
    mx, my = wx - ux, wy - uy
    nn = np.maximum(mx * mx + my * my, 1e-300)
    best = np.full(i.size, np.inf)
    corners = ((bx0, by0), (bx1, by0), (bx1, by1), (bx0, by1))
    for cx, cy in corners:
        t = np.clip(((cx - ux) * mx + (cy - uy) * my) / nn, 0.0, 1.0)
        best = np.minimum(best, np.hypot(cx - ux - t * mx, cy - uy - t * my))
    for px, py in ((ux, uy), (wx, wy)):
        dx = np.maximum(np.maximum(bx0 - px, 0.0), px - bx1)
        dy = np.maximum(np.maximum(by0 - py, 0.0), py - by1)
        best = np.minimum(best, np.hypot(dx, dy))
    sides = np.stack([mx * (cy - uy) - my * (cx - ux) for cx, cy in corners])
    crossing = ~(np.all(sides > 0, axis=0) | np.all(sides < 0, axis=0))
    crossing &= (np.maximum(ux, wx) >= bx0) & (np.minimum(ux, wx) <= bx1)
    crossing &= (np.maximum(uy, wy) >= by0) & (np.minimum(uy, wy) <= by1)
    best[crossing] = 0.0
    return np.bincount(i[best <= rad * (1 + 1e-9)], minlength=n)


def _meets_boundary(s: _Shape, k: int, q: Box, box_f: tuple[float, float, float, float]) -> bool:
    """Tell exactly whether some edge of s meets the closed box q."""
    return any(_seg_box2(s, e, q) == 0 for e in _query(s, *box_f))


def _lipschitz_prunes(run: _Run, r2: Rat, fc2: Num) -> bool:
    """Tell exactly whether f(c) + √r2 ≤ best (then f ≤ best on the ball of radius √r2 about c)."""
    if _sign(run.best.f2) <= 0:
        return False
    llo = _iv(run.best.f2)[0]
    if llo <= 0:
        return False
    l_lo = Fraction(_down(math.sqrt(llo)))
    try:
        r_up = Fraction(_up(math.sqrt(_up(float(r2)))))
    except OverflowError:
        return False
    if l_lo <= r_up:
        return False
    return _cmp(fc2, (l_lo - r_up) ** 2) <= 0


def _features_near_box(run: _Run, q: Box, u2: Rat) -> tuple[list[tuple[int, int]], list[int]]:
    b, k = run.b, run.k
    r = _radius_orig(u2, k)
    edges = []
    verts: set[tuple[int, int]] = set()
    for e in _query(b, *_box_orig(q, k, r)):
        if _seg_box2(b, e, q) > u2:
            continue
        ux, uy, wx, wy = b.edges[e]
        for vv in ((ux, uy), (wx, wy)):
            if vv not in verts and _pt_box2(vv[0], vv[1], q) <= u2 and not b.reflex[vv]:
                verts.add(vv)
        # A point outside B has its nearest edge on the outer side (ℓ < 0): an edge whose line leaves the
        # whole box on the inner side is never the nearest feature of a point that counts.
        mx, my = wx - ux, wy - uy
        if any(mx * (cy - uy) - my * (cx - ux) < 0 for cx, cy in _corners(q)):
            edges.append(e)
    return sorted(verts), edges


def _leaf(run: _Run, q: Box, u2: Rat, verts: list[tuple[int, int]], edges: list[int]) -> None:
    """Points of the box equidistant from three features that can be nearest in it."""
    b = run.b
    feats: list[tuple[str, Any, Rat, Rat]] = []
    for v in verts:
        feats.append(("v", v, _pt_box2(v[0], v[1], q), _pt_box_max2(v[0], v[1], q)))
    for e in edges:
        ux, uy, wx, wy = b.edges[e]
        mx, my = wx - ux, wy - uy
        top = max(Fraction((mx * (cy - uy) - my * (cx - ux)) ** 2, b.norms[e]) for cx, cy in _corners(q))
        feats.append(("e", e, _seg_box2(b, e, q), top))
    for f1, f2, f3 in itertools.combinations(feats, 3):
        lo = max(f1[2], f2[2], f3[2])
        hi = min(f1[3], f2[3], f3[3], u2)
        if lo > hi or _cmp(hi, run.best.f2) <= 0:
            continue  # the three distances cannot meet above the best value inside the box
        run.tick()
        trio = (f1, f2, f3)
        if not _may_improve(run, q, trio):
            continue
        for x, y in _equidistant(run, trio, run.t):
            if not (_cmp(x, q[0]) >= 0 and _cmp(x, q[2]) <= 0 and _cmp(y, q[1]) >= 0 and _cmp(y, q[3]) <= 0):
                continue
            if not _could_be_nearest(b, trio, x, y):
                continue
            if not _contains(run.a, run.k, x, y):
                continue
            nr = _near(b, run.k, x, y)
            if not nr.inside:
                run.offer(nr.f2, x, y, "interior")


def _may_improve(run: _Run, q: Box, trio: tuple[tuple[str, Any, Rat, Rat], ...]) -> bool:
    """Interval shadow of :func:`_equidistant`: False only when no solution can beat the best in the box."""
    try:
        pts = _equidistant(run, trio, _IV_TOWER)
    except (_Undecided, ZeroDivisionError):
        return True
    best_lo = _iv(run.best.f2)[0] if _sign(run.best.f2) > 0 else -_INF
    f = trio[0]
    for x, y in pts:
        xl, xh = _iv(x)
        yl, yh = _iv(y)
        if xh < q[0] or xl > q[2] or yh < q[1] or yl > q[3]:
            continue
        try:
            if not _could_be_nearest(run.b, trio, x, y):
                continue
        except _Undecided:
            pass
        if f[0] == "v":
            d2 = (x - f[1][0]) * (x - f[1][0]) + (y - f[1][1]) * (y - f[1][1])
        else:
            la, lb, lc, n = _line(run.b, f[1])
            ell = la * x + lb * y + lc
            d2 = ell * ell * Fraction(1, n)
        if _iv(d2)[1] <= best_lo:
            continue
        return True
    return False


def _could_be_nearest(b: _Shape, trio: tuple[tuple[str, Any, Rat, Rat], ...], x: Num, y: Num) -> bool:
    """Check necessary conditions for the three features to be nearest to (x, y) outside B.

    The point lies on the outer side of each edge's line and in its slab, and in each vertex's normal cone
    (no incident edge comes nearer). Raises _Undecided in interval mode when a sign is unclear.
    """
    for kind, f, _, _ in trio:
        if kind == "e":
            ux, uy, wx, wy = b.edges[f]
            mx, my = wx - ux, wy - uy
            if _sign(mx * (y - uy) - my * (x - ux)) > 0:
                return False
            proj = (x - ux) * mx + (y - uy) * my
            if _sign(proj) < 0 or _sign(proj - b.norms[f]) > 0:
                return False
        else:
            vx, vy = f
            dx, dy = x - vx, y - vy
            for ix, iy, ox, oy in b.wedges[f]:
                if _sign(dx * ix + dy * iy) < 0 or _sign(dx * ox + dy * oy) > 0:
                    return False
    return True


def _in_slab(b: _Shape, e: int, x: Num, y: Num) -> bool:
    ux, uy, wx, wy = b.edges[e]
    proj = (x - ux) * (wx - ux) + (y - uy) * (wy - uy)
    return _sign(proj) >= 0 and _cmp(proj, b.norms[e]) <= 0


def _line(b: _Shape, e: int) -> tuple[int, int, int, int]:
    """(a, b, c, N) with ℓ(x) = a·x + b·y + c = cross(w − u, x − u) and N = a² + b²."""
    ux, uy, wx, wy = b.edges[e]
    mx, my = wx - ux, wy - uy
    return -my, mx, my * ux - mx * uy, b.norms[e]


def _equidistant(
    run: _Run, trio: tuple[tuple[str, Any, Rat, Rat], ...], t: _Tower | _IVTower
) -> list[tuple[Num, Num]]:
    """The points equidistant from three features (exact with a tower, enclosures with the interval kit)."""
    b = run.b
    vs = [f[1] for f in trio if f[0] == "v"]
    es = [_line(b, f[1]) for f in trio if f[0] == "e"]
    out: list[tuple[Num, Num]] = []
    if len(vs) == 3:
        (x1, y1), (x2, y2), (x3, y3) = vs
        ax, ay, bx, by = x2 - x1, y2 - y1, x3 - x1, y3 - y1
        det = 2 * (ax * by - ay * bx)
        if det == 0:
            return []
        ra, rb = ax * ax + ay * ay, bx * bx + by * by
        ux = Fraction(by * ra - ay * rb, det)
        uy = Fraction(ax * rb - bx * ra, det)
        return [(x1 + ux, y1 + uy)]
    if len(vs) == 2:
        la, lb, lc, n = es[0]
        on = [la * v[0] + lb * v[1] + lc == 0 for v in vs]
        if on[0] and on[1]:
            return []  # both on the line: their normal lines are parallel
        if on[0]:
            vs = vs[::-1]  # the parabola of a vertex on the line degenerates: use the other vertex
        (x1, y1), (x2, y2) = vs
        nx, ny = x2 - x1, y2 - y1
        h = Fraction(x2 * x2 + y2 * y2 - x1 * x1 - y1 * y1, 2)
        nn = nx * nx + ny * ny
        x0, y0 = nx * h / nn, ny * h / nn
        mx, my = -ny, nx
        return _line_meets_parabola(t, x0, y0, mx, my, (x1, y1), (la, lb, lc, n))
    if len(vs) == 1:
        (vx, vy) = vs[0]
        on = [e[0] * vx + e[1] * vy + e[2] == 0 for e in es]
        if on[0] and on[1]:
            return []  # the normal lines at v of both lines meet at v only (distance 0)
        if on[0] or on[1]:
            # d(x, v) = d(x, line) for v on the line is the normal line at v; meet it with the other parabola.
            na, nb, _, _ = es[0] if on[0] else es[1]
            other = es[1] if on[0] else es[0]
            return _line_meets_parabola(t, vx, vy, na, nb, (vx, vy), other)
        (a1, b1, c1, n1), (a2, b2, c2, n2) = es
        kk = t.sqrt(n1 * n2)
        for sg in (1, -1):
            # The angle bisector N2·ℓ1 = σ·√(N1N2)·ℓ2, i.e. ba·x + bb·y + bc = 0.
            ba: Num = n2 * a1 - sg * kk * a2
            bb: Num = n2 * b1 - sg * kk * b2
            bc: Num = n2 * c1 - sg * kk * c2
            sa, sb = _sign(ba), _sign(bb)
            if sa == 0 and sb == 0:
                continue
            # A point of the bisector: where it meets the x axis, or the y axis when it is horizontal.
            px0, py0 = (_neg(_div(bc, ba)), 0) if sa != 0 else (0, _neg(_div(bc, bb)))
            out.extend(_line_meets_parabola(t, px0, py0, _neg(bb), ba, vs[0], (a1, b1, c1, n1)))
        return out
    (a1, b1, c1, n1), (a2, b2, c2, n2), (a3, b3, c3, n3) = es
    k12, k13 = t.sqrt(n1 * n2), t.sqrt(n1 * n3)
    for s2 in (1, -1):
        for s3 in (1, -1):
            ra = (n2 * a1 - s2 * k12 * a2, n2 * b1 - s2 * k12 * b2, n2 * c1 - s2 * k12 * c2)
            rb = (n3 * a1 - s3 * k13 * a3, n3 * b1 - s3 * k13 * b3, n3 * c1 - s3 * k13 * c3)
            det = ra[0] * rb[1] - rb[0] * ra[1]
            if _sign(det) == 0:
                continue
            x = _div(ra[1] * rb[2] - rb[1] * ra[2], det)
            y = _div(rb[0] * ra[2] - ra[0] * rb[2], det)
            out.append((x, y))
    return out


def _line_meets_parabola(
    t: _Tower | _IVTower,
    x0: Num,
    y0: Num,
    mx: Num,
    my: Num,
    v: tuple[int, int],
    line: tuple[int, int, int, int],
) -> list[tuple[Num, Num]]:
    """Points x0 + s·m with ℓ(x)² = N·|x − v|²."""
    la, lb, lc, n = line
    p0 = la * x0 + lb * y0 + lc
    p1 = la * mx + lb * my
    wx, wy = x0 - v[0], y0 - v[1]
    mm = mx * mx + my * my
    qa = p1 * p1 - n * mm
    qb = 2 * (p0 * p1 - n * (wx * mx + wy * my))
    qc = p0 * p0 - n * (wx * wx + wy * wy)
    roots = _solve_quadratic(t, qa, qb, qc)
    return [(x0 + s * mx, y0 + s * my) for s in roots or ()]


# ============================================================================================================
# Public API
# ============================================================================================================


@dataclass(frozen=True)
class HausdorffDistance:
    """An exact (directed) Hausdorff distance.

    Attributes
    ----------
    value : float
        The distance, the float nearest to the exact value (``inf`` when one set is empty and not the other).
    witness : tuple of float or None
        A point of the first set where the distance is reached (rounded to floats), None for 0 or inf.
    location : str
        Where the witness is: ``vertex``, ``edge`` (inside an edge of the first set), ``interior`` (a vertex
        of the Voronoi diagram of the second set's boundary), or ``""``.
    """

    value: float
    witness: tuple[float, float] | None
    location: str
    _sq: Num = field(repr=False, compare=False)
    _k: int = field(repr=False, compare=False)

    @property
    def is_infinite(self) -> bool:
        """True when one set is empty and the other is not."""
        return self.value == _INF

    @property
    def squared(self) -> Fraction | None:
        """The exact squared distance when it is rational (None when irrational or infinite)."""
        if self.is_infinite or isinstance(self._sq, _Ext):
            return None
        return Fraction(_rat(self._sq)) / (1 << (2 * self._k))

    def squared_enclosure(self, bits: int = 200) -> tuple[Fraction, Fraction]:
        """Rational bounds ``lo ≤ distance² ≤ hi`` (equal when rational)."""
        if self.is_infinite:
            raise ValueError("infinite distance")
        lo, hi = _enclose(self._sq, bits)
        s = Fraction(1, 1 << (2 * self._k))
        return lo * s, hi * s

    def compare(self, x: float | Fraction | int) -> int:
        """Exact sign of ``distance − x`` for a finite ``x``."""
        q = Fraction(x)
        if self.is_infinite:
            return 1
        if q < 0:
            return 1
        return _cmp(self._sq, q * q * (1 << (2 * self._k)))

    def exceeds_sqrt_multiple(self, coefficient: Fraction | int, n: int = 2) -> bool:
        """Exactly: is the distance greater than ``coefficient · √n``? (the form of every bound)."""
        c = Fraction(coefficient)
        if self.is_infinite:
            return True
        if c < 0:
            return True
        return _cmp(self._sq, c * c * n * (1 << (2 * self._k))) > 0

    def __float__(self) -> float:
        return self.value


def _finish(best: _Best, k: int, t: _Tower) -> HausdorffDistance:
    sq = best.f2
    if _sign(sq) <= 0:
        return HausdorffDistance(0.0, None, "", 0, k)
    lo, hi = _enclose(sq, 200)
    bits = 200
    scale = 1 << (2 * bits)
    d_lo = Fraction(math.isqrt(math.floor(lo * scale)), 1 << bits)
    d_hi = Fraction(math.isqrt(math.ceil(hi * scale)) + 1, 1 << bits)
    value = math.ldexp(float((d_lo + d_hi) / 2), -k)
    wx = math.ldexp(float(sum(_enclose(best.x, 60)) / 2), -k)
    wy = math.ldexp(float(sum(_enclose(best.y, 60)) / 2), -k)
    return HausdorffDistance(value, (wx, wy), best.where, sq, k)


def _setup(a: BaseGeometry, b: BaseGeometry) -> tuple[_Shape, _Shape, int]:
    ra = _rings(_polygons(a, "first geometry"))
    rb = _rings(_polygons(b, "second geometry"))
    k = max(_scale_exponent(ra), _scale_exponent(rb))
    return _prepare(ra, k), _prepare(rb, k), k


def _directed_on(sa: _Shape, sb: _Shape, k: int, t: _Tower, progress: ProgressLike | None) -> _Best | None:
    if not sa.edges:
        return _Best(0)
    if not sb.edges:
        return None  # infinite
    run = _Run(sa, sb, k, t, progress)
    _directed(run)
    return run.best


_INFINITE = HausdorffDistance(_INF, None, "", 0, 0)


def directed_hausdorff(
    a: BaseGeometry, b: BaseGeometry, *, progress: ProgressLike | None = None
) -> HausdorffDistance:
    """Exact directed Hausdorff distance ``h(A, B) = max_{x ∈ A} d(x, B)`` between filled polygonal sets.

    Parameters
    ----------
    a, b : shapely Polygon, MultiPolygon or empty geometry
        Valid polygonal sets (holes allowed), float64 coordinates.
    progress : object with ``update(fraction, message)``, optional
        Called now and then without a fraction; its ``Cancelled`` propagates (cancellation).

    Returns
    -------
    HausdorffDistance
        0 when ``a`` is empty, infinite when ``b`` is empty and ``a`` is not.

    Raises
    ------
    InvalidGeometryError
        A geometry that is not a valid (Multi)Polygon or has non-finite coordinates.
    """
    sa, sb, k = _setup(a, b)
    t = _Tower()
    best = _directed_on(sa, sb, k, t, progress)
    if best is None:
        return _INFINITE
    return _finish(best, k, t)


def hausdorff_distance(
    a: BaseGeometry, b: BaseGeometry, *, progress: ProgressLike | None = None
) -> HausdorffDistance:
    """Exact Hausdorff distance ``H(A, B) = max(h(A, B), h(B, A))`` between filled polygonal sets.

    See :func:`directed_hausdorff`; the witness is a point of whichever set reaches the maximum.
    Two empty sets are at distance 0; an empty and a non-empty set at infinite distance.
    """
    sa, sb, k = _setup(a, b)
    if not sa.edges and not sb.edges:
        return HausdorffDistance(0.0, None, "", 0, k)
    if not sa.edges or not sb.edges:
        return _INFINITE
    t = _Tower()
    ab = _directed_on(sa, sb, k, t, progress)
    ba = _directed_on(sb, sa, k, t, progress)
    assert ab is not None and ba is not None
    best = ab if _cmp(ab.f2, ba.f2) >= 0 else ba
    return _finish(best, k, t)
