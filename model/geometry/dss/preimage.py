"""The preimage of a standard digital straight segment: the lines compatible with it.

Reference: docs/algorithms.md §2.4.

Parameter space
---------------
A standard DSS with DGtal characteristics (a, b) runs in the direction (b, a). Its **frame** is the reflection
(x, y) ↦ (σx·x, σy·y), σx = sign(b), σy = sign(a) (+1 for a zero component), which maps that direction into
the closed first quadrant. In frame coordinates (x', y') = (σx·x, σy·y) a line is written

    u·x' − (1 − u)·y' = w,      0 ≤ u ≤ 1,

so that its direction is (1 − u, u) (u = 0 horizontal, u = ½ at 45°, u = 1 vertical) and its normal has L1
norm 1. In the original coordinates it is the line  u·σx·x − (1 − u)·σy·y = w. Every line whose direction
lies in the frame's closed quadrant has exactly one parameter point (u, w).

The line meets the open pixel square of (x, y) iff |u·x' − (1 − u)·y' − w| < ½ (the normal's L1 norm is 1),
two linear inequalities in (u, w): each pixel contributes a strip, and the preimage is their intersection
with 0 ≤ u ≤ 1 — a convex polygon, kept exactly (Fractions) and updated by clipping as pixels are added
(O(1) per pixel: a DSS preimage has at most 4 vertices besides the chart's sides u = 0, u = 1).

:class:`Preimage` stores the **closed** polygon (lines meeting every closed pixel square). The *open* preimage
(lines crossing the open square of every pixel, :meth:`Preimage.contains_open`) is its interior plus the
non-constraint parts of the chart sides u = 0, u = 1. The lines whose standard discretization (docs/design.md
§2, the τ tie rule) contains every pixel lie between the two, and :func:`standard_contains` decides that
exactly for any line. A 4-connected path whose steps all point into the frame's quadrant is a standard DSS iff
its open preimage is non-empty, i.e. iff the polygon has an interior.

Lines with a direction outside the frame's quadrant are not represented; they can meet all the pixels only
for axis-parallel runs (a = 0 or b = 0), whose preimage is symmetric about the run's axis: it is the stored
polygon plus its mirror image (u ↦ u, w unchanged in the mirrored frame).

The median line a·x − b·y = (lo + hi)/2 of a standard DSS (lo = μ, hi = μ + ω − 1) always lies in the open
preimage (:func:`median_parameters`).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from fractions import Fraction

from mrm.geometry.dss import Segment

Vertex = tuple[Fraction, Fraction]
_HALF = Fraction(1, 2)


def _sign(v: int) -> int:
    return -1 if v < 0 else 1


def frame_of(a: int, b: int) -> tuple[int, int]:
    """Return the frame (σx, σy) = (sign(b), sign(a)) of a DSS of slope (a, b), +1 for a zero component."""
    return _sign(b), _sign(a)


def _cross(o: Vertex, p: Vertex, q: Vertex) -> Fraction:
    return (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])


class Preimage:
    """The preimage of a set of pixels in the (u, w) line space of a frame, as an exact convex polygon.

    Parameters
    ----------
    frame : (int, int)
        (σx, σy), each +1 or −1 (see the module docstring); :func:`frame_of` gives a DSS's frame.
    points : iterable of (int, int), optional
        Pixels to add at once.

    Notes
    -----
    Before any pixel is added the preimage is the whole chart (every line of the quadrant) and ``vertices``
    is empty; afterwards it is a bounded convex polygon, possibly empty (``is_empty``) once pixels that no
    common line meets have been added. Adding pixels in any order gives the same polygon.
    """

    __slots__ = ("_started", "count", "frame", "vertices")

    def __init__(self, frame: tuple[int, int] = (1, 1), points: Iterable[Sequence[int]] = ()) -> None:
        sx, sy = int(frame[0]), int(frame[1])
        if sx not in (1, -1) or sy not in (1, -1):
            raise ValueError(f"a frame is a pair of signs ±1, not {frame!r}")
        self.frame: tuple[int, int] = (sx, sy)
        #: The polygon's vertices (u, w), counter-clockwise, without repetition.
        self.vertices: list[Vertex] = []
        #: How many pixels have been added.
        self.count = 0
        self._started = False
        for p in points:
            self.add(p)

    # ------------------------------------------------------------------------------------------- building
    def _to_frame(self, p: Sequence[int]) -> tuple[int, int]:
        return self.frame[0] * int(p[0]), self.frame[1] * int(p[1])

    def add(self, p: Sequence[int]) -> bool:
        """Intersect with the lines meeting the pixel p = (x, y); return whether the preimage is non-empty.

        The pixel contributes the strip  u·(x' + y') − y' − ½ ≤ w ≤ u·(x' + y') − y' + ½  (frame coordinates).
        """
        x, y = self._to_frame(p)
        s = x + y
        self.count += 1
        if not self._started:
            # the strip cut by the chart 0 <= u <= 1: a parallelogram
            self._started = True
            self.vertices = [
                (Fraction(0), Fraction(-y) - _HALF),
                (Fraction(1), Fraction(x) - _HALF),
                (Fraction(1), Fraction(x) + _HALF),
                (Fraction(0), Fraction(-y) + _HALF),
            ]
            return True
        # w − u·s + y + ½ >= 0  and  −w + u·s − y + ½ >= 0
        self._clip(-s, 1, Fraction(y) + _HALF)
        self._clip(s, -1, Fraction(-y) + _HALF)
        return bool(self.vertices)

    def _clip(self, cu: int, cw: int, c0: Fraction) -> None:
        # Keep the half-plane cu·u + cw·w + c0 >= 0 (Sutherland-Hodgman on a convex polygon, exact).
        vs = self.vertices
        if not vs:
            return
        vals = [cu * u + cw * w + c0 for u, w in vs]
        if all(v >= 0 for v in vals):
            return
        out: list[Vertex] = []
        n = len(vs)
        for k in range(n):
            p, vp = vs[k], vals[k]
            q, vq = vs[(k + 1) % n], vals[(k + 1) % n]
            if vp >= 0:
                out.append(p)
            if (vp > 0 and vq < 0) or (vp < 0 and vq > 0):
                t = vp / (vp - vq)
                out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
        # drop repeated vertices (a clip line through a vertex) and collinear ones
        dedup: list[Vertex] = []
        for v in out:
            if not dedup or dedup[-1] != v:
                dedup.append(v)
        while len(dedup) > 1 and dedup[0] == dedup[-1]:
            dedup.pop()
        k = 0
        while len(dedup) >= 3 and k < len(dedup):
            if _cross(dedup[k - 1], dedup[k], dedup[(k + 1) % len(dedup)]) == 0:
                del dedup[k]
            else:
                k += 1
        self.vertices = dedup

    # ------------------------------------------------------------------------------------------- reading
    @property
    def is_empty(self) -> bool:
        """True when no line of the chart meets every pixel's closed square (pixels were added)."""
        return self._started and not self.vertices

    @property
    def has_interior(self) -> bool:
        """True when the polygon has a non-empty interior (some line meets every open square)."""
        return len(self.vertices) >= 3

    def contains(self, u: Fraction | int, w: Fraction | int) -> bool:
        """Return whether (u, w) lies in the closed polygon (the line meets every closed pixel square)."""
        return self._side(Fraction(u), Fraction(w), strict=False)

    def contains_open(self, u: Fraction | int, w: Fraction | int) -> bool:
        """Return whether the line (u, w) crosses the open square of every pixel added.

        That is the polygon's interior plus the points of its sides on the chart's border u = 0 or u = 1
        (horizontal or vertical lines) that are not on a pixel's constraint.
        """
        return self._side(Fraction(u), Fraction(w), strict=True)

    def _side(self, u: Fraction, w: Fraction, strict: bool) -> bool:
        if not self._started:
            return 0 <= u <= 1
        vs = self.vertices
        if not vs:
            return False
        if len(vs) < 3:
            if strict:
                return False
            if len(vs) == 1:
                return (u, w) == vs[0]
            p, q = vs
            return (
                _cross(p, q, (u, w)) == 0
                and min(p[0], q[0]) <= u <= max(p[0], q[0])
                and min(p[1], q[1]) <= w <= max(p[1], q[1])
            )
        n = len(vs)
        for k in range(n):
            p, q = vs[k], vs[(k + 1) % n]
            c = _cross(p, q, (u, w))
            if c < 0:
                return False
            if c == 0 and strict and not (p[0] == q[0] and p[0] in (0, 1)):
                return False  # on a pixel's constraint: the line only touches that pixel's square
        return True

    def line(self, u: Fraction | int, w: Fraction | int) -> tuple[Fraction, Fraction, Fraction]:
        """Return the line of parameters (u, w) in original coordinates, as (A, B, C): A·x + B·y = C."""
        u, w = Fraction(u), Fraction(w)
        return u * self.frame[0], -(1 - u) * self.frame[1], w

    def parameters_of(self, a: int | Fraction, b: int | Fraction, c: int | Fraction) -> Vertex:
        """Return (u, w) of the line a·x − b·y = c (DGtal form, original coordinates) in this frame.

        Raises
        ------
        ValueError
            If the line's direction (b, a) is not in the frame's quadrant (nor its opposite), or a = b = 0.
        """
        p = Fraction(a) * self.frame[0]
        q = Fraction(b) * self.frame[1]
        if p < 0 or q < 0:
            p, q, c = -p, -q, -Fraction(c)
        if p < 0 or q < 0 or p + q == 0:
            raise ValueError(f"the line {a}·x − {b}·y = {c} has no parameters in the frame {self.frame}")
        return p / (p + q), Fraction(c) / (p + q)

    def __repr__(self) -> str:
        vs = ", ".join(f"({u}, {w})" for u, w in self.vertices)
        return f"Preimage(frame={self.frame}, pixels={self.count}, vertices=[{vs}])"


def preimage_of(points: Iterable[Sequence[int]], a: int, b: int) -> Preimage:
    """Return the preimage of a standard DSS's pixels in the frame of its slope (a, b).

    Parameters
    ----------
    points : iterable of (int, int)
        The pixels of the segment (any order).
    a, b : int
        The segment's DGtal slope (direction (b, a)), which fixes the frame (:func:`frame_of`).
    """
    return Preimage(frame_of(a, b), points)


def segment_preimage(points: Sequence[Sequence[int]], segment: Segment) -> Preimage:
    """Return the preimage of a segment of a chain (``points[first … last]``, indices mod len(points))."""
    m = len(points)
    return preimage_of((points[k % m] for k in range(segment.first, segment.last + 1)), segment.a, segment.b)


def median_parameters(segment: Segment) -> Vertex:
    """Return (u, w) of the segment's median line a·x − b·y = μ + (ω − 1)/2 in its own frame.

    Raises
    ------
    ValueError
        For a one-point segment (a = b = 0): its median line is undefined.
    """
    a, b, c = segment.median_line
    if a == 0 and b == 0:
        raise ValueError("a one-point segment has no median line")
    return Preimage(frame_of(a, b)).parameters_of(a, b, c)


def standard_contains(
    points: Iterable[Sequence[int]], A: Fraction | int, B: Fraction | int, C: Fraction | int
) -> bool:
    """Return whether the standard discretization of the line A·x + B·y = C contains every pixel.

    docs/design.md §2: with the normal oriented A > 0, or A = 0 and B > 0, pixel p is in the standard
    discretization iff −ω/2 ≤ A·pₓ + B·p_y − C < ω/2, ω = |A| + |B|. Exact for rational A, B, C.
    """
    A, B, C = Fraction(A), Fraction(B), Fraction(C)
    if A == 0 and B == 0:
        raise ValueError("not a line: A = B = 0")
    if A < 0 or (A == 0 and B < 0):
        A, B, C = -A, -B, -C
    half = (abs(A) + abs(B)) / 2
    return all(-half <= A * int(p[0]) + B * int(p[1]) - C < half for p in points)
