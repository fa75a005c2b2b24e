"""The exact (directed) Hausdorff distance: the public functions and the search over the three cases.

:func:`_directed` offers the vertices of A (case 1), then searches the edges of A, most promising first
(case 2, :mod:`mrm.geometry.hausdorff.along_edges`), then the interior of A (case 3,
:mod:`mrm.geometry.hausdorff.interior`); the package docstring gives the argument.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

from shapely.geometry.base import BaseGeometry

from mrm.core.progress import ProgressLike
from mrm.geometry.hausdorff.along_edges import _edge
from mrm.geometry.hausdorff.branch_and_bound import _Best, _Run
from mrm.geometry.hausdorff.exact_numbers import Num, _cmp, _enclose, _Ext, _rat, _sign, _Tower
from mrm.geometry.hausdorff.interior import _interior
from mrm.geometry.hausdorff.intervals import _INF, Rat
from mrm.geometry.hausdorff.shapes import _dseg2, _setup, _Shape
from mrm.geometry.hausdorff.spatial import _Near, _near

__all__ = ["HausdorffDistance", "directed_hausdorff", "hausdorff_distance"]


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


def _finish(best: _Best, k: int) -> HausdorffDistance:
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
    return _finish(best, k)


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
    return _finish(best, k)
