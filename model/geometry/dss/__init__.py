"""Digital straight segments: the incremental arithmetic recognizer.

Reference: docs/design.md §5, docs/algorithms.md §2.1-2.2.

Conventions are DGtal's ``ArithmeticalDSL`` / ``ArithmeticalDSS``, so results can be compared with it:

* a digital straight line (DSL) is D(a, b, μ, ω) = { (x, y) ∈ Z² : μ ≤ a·x − b·y < μ + ω } with
  gcd(a, b) = 1 and direction vector (b, a); the *remainder* of a point is r(x, y) = a·x − b·y;
* ω = |a| + |b| for **standard** (4-connected) lines, adjacency 4; ω = max(|a|, |b|) for **naive**
  (8-connected) lines, adjacency 8;
* a digital straight segment (DSS) is a connected run of points of a DSL, read in order (from its *back*
  ``F`` to its *front* ``L``); it is stored with the minimal characteristics (a, b, μ, ω) and its leaning
  points: upper ones (r = μ, first ``Uf`` and last ``Ul``) and lower ones (r = μ + ω − 1, ``Lf``, ``Ll``).
  The direction (b, a) points from the back to the front.
* a one-point DSS has a = b = 0, μ = 0 and ω = 1 (as in DGtal).

:class:`ArithmeticalDSS` is the readable pure-Python recognizer (Debled-Rennesson & Reveillès 1995 for
extension, Lachaud, de Vieilleville & Feschet 2007 for the O(1) retraction), step for step the algorithm of
DGtal. The numba kernels in :mod:`mrm.geometry.dss._kernels` are the same algorithm on an int64 state; the
segmentations in :mod:`mrm.geometry.dss.segmentation` use those.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Literal

from mrm.geometry._jit import py_func
from mrm.geometry.dss._kernels import shift_of as _shift_of
from mrm.geometry.dss._kernels import steps_of as _steps_of

Point = tuple[int, int]
Adjacency = Literal[4, 8]


def _norm(dx: int, dy: int, adjacency: int) -> int:
    if adjacency == 4:
        return abs(dx) + abs(dy)
    return max(abs(dx), abs(dy))


def steps_of(a: int, b: int, adjacency: int) -> tuple[Point, Point]:
    """Return the two elementary steps of the DSLs of slope (a, b); the second is (0, 0) if there is one.

    Parameters
    ----------
    a, b : int
        The slope; the direction vector is (b, a).
    adjacency : {4, 8}
        4 for standard lines (4-steps), 8 for naive ones (8-steps).

    Returns
    -------
    tuple of two points
        DGtal ``ArithmeticalDSLKernel::steps``: the steps that occur along a DSL of that slope.
    """
    s1x, s1y, s2x, s2y = py_func(_steps_of)(a, b, adjacency)
    return (s1x, s1y), (s2x, s2y)


def shift_of(a: int, b: int, adjacency: int) -> Point:
    """Return the shift vector of the DSLs of slope (a, b): r(p + shift) = r(p) + ω (DGtal's ``shift``)."""
    x, y = py_func(_shift_of)(a, b, adjacency)
    return (x, y)


class ArithmeticalDSS:
    """A digital straight segment recognised incrementally, with minimal characteristics.

    Parameters
    ----------
    point : tuple of int
        The single point of the initial segment.
    adjacency : {4, 8}
        4: standard DSS (consecutive points 4-adjacent, ω = |a| + |b|); 8: naive DSS (8-adjacent,
        ω = max(|a|, |b|)).

    Notes
    -----
    ``extend_front(q)`` / ``extend_back(q)`` add a point after the front / before the back and return
    False, leaving the segment unchanged, when the result would not be a DSS; ``retract_back()`` /
    ``retract_front()`` remove an end point (False when only one point is left). Every operation is O(1).
    The state (a, b, lo = μ, hi = μ + ω − 1, F, L, Uf, Ul, Lf, Ll, steps, shift) is DGtal's; ``lo`` and
    ``hi`` are the remainders of the upper and lower leaning points.

    As in DGtal, adding a point equal to the front is accepted and leaves the segment as it is; the
    segmentations never do that (they require chains without repeated consecutive points).
    """

    __slots__ = ("F", "L", "Lf", "Ll", "Uf", "Ul", "a", "adjacency", "b", "hi", "lo", "s1", "s2", "shift")

    def __init__(self, point: Point, adjacency: Adjacency = 4) -> None:
        if adjacency not in (4, 8):
            raise ValueError(f"adjacency must be 4 or 8, not {adjacency!r}")
        p = (int(point[0]), int(point[1]))
        self.adjacency: int = adjacency
        self.a = 0
        self.b = 0
        self.lo = 0
        self.hi = 0
        self.F = self.L = self.Uf = self.Ul = self.Lf = self.Ll = p
        self.s1: Point = (0, 0)
        self.s2: Point = (0, 0)
        self.shift: Point = (0, 0)

    # ----------------------------------------------------------------------------------------- reading
    @property
    def mu(self) -> int:
        """The lower bound μ of the remainders (the remainder of the upper leaning points)."""
        return self.lo

    @property
    def omega(self) -> int:
        """The arithmetical thickness ω (= |a| + |b| standard, max(|a|, |b|) naive; 1 for one point)."""
        return self.hi - self.lo + 1

    def remainder(self, p: Point) -> int:
        """Return a·x − b·y for p = (x, y)."""
        return self.a * p[0] - self.b * p[1]

    def copy(self) -> ArithmeticalDSS:
        """Return an independent copy."""
        c = ArithmeticalDSS.__new__(ArithmeticalDSS)
        for k in self.__slots__:
            setattr(c, k, getattr(self, k))
        return c

    def characteristics(self) -> tuple[int, int, int, int]:
        """Return (a, b, mu, omega)."""
        return self.a, self.b, self.lo, self.omega

    def leaning_points(self) -> tuple[Point, Point, Point, Point]:
        """Return (Uf, Ul, Lf, Ll)."""
        return self.Uf, self.Ul, self.Lf, self.Ll

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ArithmeticalDSS):
            return NotImplemented
        return all(getattr(self, k) == getattr(other, k) for k in self.__slots__)

    __hash__ = None  # type: ignore[assignment]  # mutable

    def __repr__(self) -> str:
        return (
            f"ArithmeticalDSS(a={self.a}, b={self.b}, mu={self.lo}, omega={self.omega}, "
            f"back={self.F}, front={self.L}, Uf={self.Uf}, Ul={self.Ul}, Lf={self.Lf}, Ll={self.Ll})"
        )

    # ----------------------------------------------------------------------------------------- extension
    def is_extendable_front(self, q: Point) -> int:
        """Return DGtal's case code for adding q at the front: 0 if impossible, 1-9 otherwise.

        1 first step, 2 first step repeated, 3 / 4 second step (on the upper / lower side), 5 / 6 weakly
        interior (new upper / lower leaning point), 7 / 8 weakly exterior (the slope changes), 9 strictly
        interior (or q equals the front).
        """
        dx = q[0] - self.L[0]
        dy = q[1] - self.L[1]
        dev = _norm(dx, dy, self.adjacency)
        if dev == 0:
            return 9
        if dev > 1:
            return 0
        if self.s1 == (0, 0):
            return 1
        if self.s2 == (0, 0):
            if (dx, dy) == self.s1:
                return 2
            # the background of a 4-connected line is 8-connected and vice versa
            if _norm(dx - self.s1[0], dy - self.s1[1], 12 - self.adjacency) == 1:
                return 3 if self.remainder(q) == self.lo - 1 else 4
            return 0
        if (dx, dy) != self.s1 and (dx, dy) != self.s2:
            return 0
        r = self.remainder(q)
        if r < self.lo - 1 or r > self.hi + 1:
            return 0
        if r == self.lo:
            return 5
        if r == self.hi:
            return 6
        if r == self.lo - 1:
            return 7
        if r == self.hi + 1:
            return 8
        return 9

    def extend_front(self, q: Point) -> bool:
        """Add q after the front if the points still form a DSS; return whether q was added."""
        q = (int(q[0]), int(q[1]))
        c = self.is_extendable_front(q)
        if c == 0:
            return False
        L = self.L
        if c == 1:
            self.s1 = (q[0] - L[0], q[1] - L[1])
            self.a, self.b = self.s1[1], self.s1[0]
            self.lo, self.hi = self.remainder(self.Uf), self.remainder(self.Lf)
            self.Ul = self.Ll = q
            self.shift = shift_of(self.a, self.b, self.adjacency)
        elif c == 2:
            self.Ul = self.Ll = q
        elif c == 3:
            self.a = (self.Ul[1] - self.Uf[1]) + (q[1] - L[1])
            self.b = (self.Ul[0] - self.Uf[0]) + (q[0] - L[0])
            self.lo, self.hi = self.remainder(self.Uf), self.remainder(self.Ll)
            self.Ul = q
            self.Lf = self.Ll
            self._reset_steps_from_two()
        elif c == 4:
            self.a = (self.Ll[1] - self.Lf[1]) + (q[1] - L[1])
            self.b = (self.Ll[0] - self.Lf[0]) + (q[0] - L[0])
            self.lo, self.hi = self.remainder(self.Ul), self.remainder(self.Lf)
            self.Ll = q
            self.Uf = self.Ul
            self._reset_steps_from_two()
        elif c == 5:
            self.Ul = q
        elif c == 6:
            self.Ll = q
        elif c == 7:
            self.a, self.b = q[1] - self.Uf[1], q[0] - self.Uf[0]
            self.lo, self.hi = self.remainder(self.Uf), self.remainder(self.Ll)
            self.Ul = q
            self.Lf = self.Ll
        elif c == 8:
            self.a, self.b = q[1] - self.Lf[1], q[0] - self.Lf[0]
            self.lo, self.hi = self.remainder(self.Ul), self.remainder(self.Lf)
            self.Ll = q
            self.Uf = self.Ul
        self.L = q
        return True

    def _reset_steps_from_two(self) -> None:
        self.s1, self.s2 = steps_of(self.a, self.b, self.adjacency)
        self.shift = (self.s1[0] - self.s2[0], self.s1[1] - self.s2[1])

    def negate(self) -> ArithmeticalDSS:
        """Return the same segment read backwards: (−a, −b, −hi, −lo), back and front swapped."""
        c = self.copy()
        c.a, c.b = -self.a, -self.b
        c.lo, c.hi = -self.hi, -self.lo
        c.F, c.L = self.L, self.F
        c.Uf, c.Ul, c.Lf, c.Ll = self.Ll, self.Lf, self.Ul, self.Uf
        c.s1 = (-self.s1[0], -self.s1[1])
        c.s2 = (-self.s2[0], -self.s2[1])
        c.shift = (-self.shift[0], -self.shift[1])
        return c

    def _assign(self, other: ArithmeticalDSS) -> None:
        for k in self.__slots__:
            setattr(self, k, getattr(other, k))

    def extend_back(self, q: Point) -> bool:
        """Add q before the back if the points still form a DSS; return whether q was added."""
        opp = self.negate()
        if not opp.extend_front(q):
            return False
        self._assign(opp.negate())
        return True

    # ----------------------------------------------------------------------------------------- retraction
    def next_point(self) -> Point:
        """Return the point that follows the back in the segment (the back itself for one point)."""
        if self.s1 == (0, 0):
            return self.F
        p = (self.F[0] + self.s1[0], self.F[1] + self.s1[1])
        if self.s2 == (0, 0) or self.lo <= self.remainder(p) <= self.hi:
            return p
        return (self.F[0] + self.s2[0], self.F[1] + self.s2[1])

    def retract_back(self) -> bool:
        """Remove the back point; return False (and do nothing) when only one point is left."""
        if self.F == self.L:
            return False
        nxt = self.next_point()
        if nxt == self.L:
            self._assign(ArithmeticalDSS(nxt, self.adjacency))  # type: ignore[arg-type]
            return True
        n = self.adjacency
        if self.Uf == self.F:
            bez = (self.Uf[0] + self.shift[0], self.Uf[1] + self.shift[1])
            if self.Lf == self.Ll:
                # the only upper leaning point goes: the slope turns to (Lf − Bezout point)
                nd = (self.Lf[0] - bez[0], self.Lf[1] - bez[1])
                nn = _norm(nd[0], nd[1], n)
                k = _norm(self.Ul[0] - nxt[0], self.Ul[1] - nxt[1], n) // nn
                self.Uf = (self.Ul[0] - nd[0] * k, self.Ul[1] - nd[1] * k)
                k = _norm(self.L[0] - self.Lf[0], self.L[1] - self.Lf[1], n) // nn
                self.Ll = (self.Lf[0] + nd[0] * k, self.Lf[1] + nd[1] * k)
                self._retract_update_parameters(nd)
            else:
                self.Uf = (self.Uf[0] + self.b, self.Uf[1] + self.a)
        if self.Lf == self.F:
            bez = (self.Lf[0] - self.shift[0], self.Lf[1] - self.shift[1])
            if self.Uf == self.Ul:
                nd = (self.Uf[0] - bez[0], self.Uf[1] - bez[1])
                nn = _norm(nd[0], nd[1], n)
                k = _norm(self.Ll[0] - nxt[0], self.Ll[1] - nxt[1], n) // nn
                self.Lf = (self.Ll[0] - nd[0] * k, self.Ll[1] - nd[1] * k)
                k = _norm(self.L[0] - self.Uf[0], self.L[1] - self.Uf[1], n) // nn
                self.Ul = (self.Uf[0] + nd[0] * k, self.Uf[1] + nd[1] * k)
                self._retract_update_parameters(nd)
            else:
                self.Lf = (self.Lf[0] + self.b, self.Lf[1] + self.a)
        self.F = nxt
        return True

    def _retract_update_parameters(self, nd: Point) -> None:
        self.a, self.b = nd[1], nd[0]
        self.lo, self.hi = self.remainder(self.Uf), self.remainder(self.Lf)
        if self.Uf == self.Lf:
            self.s1, self.s2 = steps_of(self.a, self.b, self.adjacency)
            self.shift = shift_of(self.a, self.b, self.adjacency)

    def retract_front(self) -> bool:
        """Remove the front point; return False (and do nothing) when only one point is left."""
        opp = self.negate()
        if not opp.retract_back():
            return False
        self._assign(opp.negate())
        return True


def recognize(points: object, adjacency: Adjacency = 4) -> ArithmeticalDSS | None:
    """Recognize a whole point sequence from scratch; return its DSS, or None if it is not one.

    Parameters
    ----------
    points : sequence of (x, y) integer pairs
        At least one point, in order.
    adjacency : {4, 8}
        Standard (4) or naive (8) segments.
    """
    pts = [(int(p[0]), int(p[1])) for p in points]  # type: ignore[attr-defined]
    if not pts:
        raise ValueError("a segment needs at least one point")
    dss = ArithmeticalDSS(pts[0], adjacency)
    for q in pts[1:]:
        if not dss.extend_front(q):
            return None
    return dss


@dataclass(frozen=True)
class Segment:
    """One digital straight segment of a chain of points.

    Attributes
    ----------
    first, last : int
        Index range (both included) in the chain's points. On a closed chain of m points, ``first`` is in
        [0, m) and ``last`` may reach ``first + m``; point k is ``points[k mod m]``.
    a, b, mu, omega : int
        Minimal characteristics, DGtal convention: μ ≤ a·x − b·y < μ + ω for every point, direction (b, a)
        from ``first`` to ``last``.
    uf, ul, lf, ll : tuple of int
        First / last upper leaning points (remainder μ) and lower ones (remainder μ + ω − 1).
    """

    first: int
    last: int
    a: int
    b: int
    mu: int
    omega: int
    uf: Point
    ul: Point
    lf: Point
    ll: Point

    @property
    def length(self) -> int:
        """The number of points in the segment."""
        return self.last - self.first + 1

    def as_list(self) -> list[int]:
        """Return ``[first, last, a, b, mu, omega]`` (the ``mrm segment --json`` row)."""
        return [self.first, self.last, self.a, self.b, self.mu, self.omega]

    @property
    def median_line(self) -> tuple[int, int, Fraction]:
        """The median line a·x − b·y = c with c = (lo + hi) / 2 = μ + (ω − 1) / 2, as (a, b, c).

        Every point of the segment has |r − c| ≤ (ω − 1) / 2 < ω / 2, so for a standard segment the line
        meets the open square of every point (docs/algorithms.md §2.4).
        """
        return self.a, self.b, Fraction(2 * self.mu + self.omega - 1, 2)
