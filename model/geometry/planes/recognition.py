"""Recognition of digital plane segments, exact and incremental.

Reference: docs/design.md §11 (analytical representation).

A **standard arithmetic plane** is P(a, b, c, μ) = { p ∈ Z³ : μ ≤ a·x + b·y + c·z < μ + ω } with integers
gcd(a, b, c) = 1 and ω = |a| + |b| + |c| (Andres; DGtal's ``ChordGenericStandardPlaneComputer`` uses the same
width). Two questions are answered here, both by one exact engine, the :class:`~.cone.Cone` of admissible
normals:

* :class:`SurfelPlane` — **a patch of surfels**. A surfel joins a voxel p of A to its 6-neighbour q = p + e
  outside A. A patch is a *digital plane segment* when one plane n · x = h separates all its inner voxels from
  all its outer voxels: n · p < h < n · q. Then, for a primitive integer n in that open cone and t =
  max n · p, every inner voxel satisfies t − ω < n · p ≤ t (its outer neighbour is beyond t), so the inner
  voxels lie in the standard plane P(n, t − ω + 1) with n pointing outward. This is the condition R needs
  (docs/reconstruction.md): the plane chosen from the preimage puts the centres of the patch's voxels of A on
  one side and the centres outside on the other.
* :class:`PointPlane` — **a set of points**: is there a standard plane containing them all? For n in the
  closed octant of the sign vector s, |n|₁ = s · n, so the condition max n·p − min n·p < |n|₁ is the
  linear constraint n · (s − (p − p′)) > 0 for every pair of points: one cone per octant. This is the question
  DGtal's plane computers answer; the benchmark compares the two on the same point sets.

Both add points one at a time. Instead of the quadratic set of pair constraints, a new point is checked at
the cone's vertices only: the constraint functions are convex (a maximum of linear functions), so they hold
on the whole cone when they hold at its vertices; where a vertex fails, the pair that makes it fail cuts the
cone, and the check repeats. The cone left is exactly the set of admissible normals (each cut is one of the
pair constraints, and every pair constraint holds on it).

All arithmetic is on Python integers, so nothing overflows: the cone's rays are cross products of two
constraint vectors (coordinates below 2·d², d the extent of the points), and the dot products the checks take
are computed with numpy's int64 only while they are provably below 2⁶² (:data:`INT64_SAFE_EXTENT`), with
Python integers beyond that.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from itertools import product
from math import ceil, floor

import numpy as np
import numpy.typing as npt

from mrm.geometry.planes.cone import Cone, Vec, dot, octant_cone, primitive, start_cone

IntArray = npt.NDArray[np.int64]

#: Points (and outer voxels) whose coordinates differ by at most this much are handled with int64 dot
#: products: a cone ray is below 2·(2d)² ≤ 2⁴³ in each coordinate for d = 2¹⁹, and 3 · 2⁴³ · 2¹⁹ < 2⁶³ for
#: the products with translated points. Beyond it, Python integers.
INT64_SAFE_EXTENT = 1 << 19

#: ... and whose cone rays are below this in each coordinate (3 · 2⁴² · 2¹⁹ < 2⁶³).
MAX_INT64_RAY = 1 << 42

#: How far :func:`smallest_normal` scans the max-norm before it settles for the cone's interior ray.
MAX_NORMAL_SCAN = 4096


@dataclass(frozen=True)
class DigitalPlane:
    """A standard arithmetic plane μ ≤ a·x + b·y + c·z < μ + ω, ω = |a| + |b| + |c|, gcd(a, b, c) = 1.

    Attributes
    ----------
    a, b, c : int
        The normal, primitive; for a surfel patch it points out of the object.
    mu : int
        The lower bound of the remainder a·x + b·y + c·z.
    """

    a: int
    b: int
    c: int
    mu: int

    @property
    def omega(self) -> int:
        """The arithmetic thickness |a| + |b| + |c|."""
        return abs(self.a) + abs(self.b) + abs(self.c)

    @property
    def normal(self) -> Vec:
        """(a, b, c)."""
        return (self.a, self.b, self.c)

    def remainder(self, p: Sequence[int]) -> int:
        """a·x + b·y + c·z."""
        return dot(self.normal, p)

    def contains(self, p: Sequence[int]) -> bool:
        """Whether the point p is in the plane."""
        r = self.remainder(p)
        return self.mu <= r < self.mu + self.omega


class _Points:
    """A growing set of integer points with its translation-safe dot products against cone rays."""

    def __init__(self) -> None:
        self._buf = np.zeros((16, 3), np.int64)
        self.n = 0
        self._seen: set[Vec] = set()
        self.origin: Vec | None = None

    def add(self, p: Vec) -> bool:
        if p in self._seen:
            return False
        self._seen.add(p)
        if self.origin is None:
            self.origin = p
        if self.n == len(self._buf):
            self._buf = np.concatenate([self._buf, np.zeros_like(self._buf)])
        o = self.origin
        self._buf[self.n] = (p[0] - o[0], p[1] - o[1], p[2] - o[2])
        self.n += 1
        return True

    def __contains__(self, p: object) -> bool:
        return p in self._seen

    @property
    def rel(self) -> IntArray:
        """The points relative to :attr:`origin`."""
        return self._buf[: self.n]

    def extent(self) -> int:
        return int(np.abs(self.rel).max()) if self.n else 0

    def dots(self, r: Vec, extent: int) -> tuple[int, int, int, int]:
        """(max r·p, index, min r·p, index) over the points, relative to :attr:`origin`."""
        rel = self.rel
        if extent <= INT64_SAFE_EXTENT and max(abs(c) for c in r) < MAX_INT64_RAY:
            d = rel @ np.array(r, np.int64)
            i_max, i_min = int(np.argmax(d)), int(np.argmin(d))
            return int(d[i_max]), i_max, int(d[i_min]), i_min
        vals = [dot(r, (int(x), int(y), int(z))) for x, y, z in rel]
        i_max = max(range(len(vals)), key=vals.__getitem__)
        i_min = min(range(len(vals)), key=vals.__getitem__)
        return vals[i_max], i_max, vals[i_min], i_min

    def point(self, i: int) -> Vec:
        o = self.origin
        assert o is not None
        x, y, z = (int(c) for c in self._buf[i])
        return (x + o[0], y + o[1], z + o[2])


def _sub(u: Vec, v: Vec) -> Vec:
    return (u[0] - v[0], u[1] - v[1], u[2] - v[2])


def _add(u: Vec, v: Vec) -> Vec:
    return (u[0] + v[0], u[1] + v[1], u[2] + v[2])


class SurfelPlane:
    """Incremental recognition of a surfel patch as a digital plane segment (see the module docstring).

    Add surfels with :meth:`add`; it returns False, and leaves the recognizer unchanged, when the surfel
    would leave no plane that separates the inner voxels from the outer ones.

    Like DGtal's recognizers it keeps a *witness*, one normal from the interior of the preimage with the
    extreme dot products of the points along it: a surfel that this normal still separates is taken in
    constant time, and the cone is cut by the points taken so only when the witness fails (or when the
    preimage is asked for).

    Examples
    --------
    >>> rec = SurfelPlane()
    >>> all(rec.add((x, y, 0), (0, 0, 1)) for x in range(3) for y in range(2))
    True
    >>> rec.plane()
    DigitalPlane(a=0, b=0, c=1, mu=0)
    >>> rec.add((1, 1, 1), (0, 0, 1))  # a step up in the middle of the patch: no plane separates it
    False
    """

    def __init__(self) -> None:
        self.inner = _Points()
        self.outer = _Points()
        self._first: Vec | None = None  # the first surfel's outward direction e (n · e > 0 for every n)
        self._cone: Cone | None = None  # cut by every point up to the last witness failure
        self._stale = False  # whether points were taken since, on the witness's word only
        self._witness: Vec = (0, 0, 0)
        self._w_hi = 0  # max witness · p over the inner voxels
        self._w_lo = 0  # min witness · q over the outer voxels
        self.n_surfels = 0

    @property
    def cone(self) -> Cone | None:
        """The preimage cone (None while the patch has one surfel: every n with n · e > 0 is admissible)."""
        self._refresh()
        return self._cone

    def add(self, p: Sequence[int], e: Sequence[int]) -> bool:
        """Add the surfel between the voxel ``p`` of A and its neighbour ``p + e`` outside A.

        Parameters
        ----------
        p : (int, int, int)
            The voxel of A.
        e : (int, int, int)
            The outward unit normal (one of ±x, ±y, ±z).

        Returns
        -------
        bool
            Whether the patch with this surfel is still a digital plane segment (then it is added).
        """
        pv: Vec = (int(p[0]), int(p[1]), int(p[2]))
        ev: Vec = (int(e[0]), int(e[1]), int(e[2]))
        qv = (pv[0] + ev[0], pv[1] + ev[1], pv[2] + ev[2])
        if pv in self.outer or qv in self.inner:
            return False  # a voxel on both sides: no plane separates it from itself
        if pv in self.inner and qv in self.outer:
            self.n_surfels += 1
            return True  # both voxels are there already: no new constraint
        if self._first is None:
            self._first = ev
        elif self._cone is None:
            cone = self._start(pv, qv)
            if cone is None:
                return False
            self._set(cone, pv, qv)
        else:
            w = self._witness
            wp, wq = dot(w, pv), dot(w, qv)
            if max(self._w_hi, wp) < min(self._w_lo, wq):
                self._w_hi, self._w_lo = max(self._w_hi, wp), min(self._w_lo, wq)
                self._stale = True
            else:
                cone = self._cut(self._cone, pv, qv)
                if cone is None:
                    return False
                self._set(cone, pv, qv)
        self.inner.add(pv)
        self.outer.add(qv)
        self.n_surfels += 1
        return True

    def _set(self, cone: Cone, p: Vec, q: Vec) -> None:
        """Take ``cone`` (cut by every point and p, q) and its interior ray as the new witness."""
        self._cone, self._stale = cone, False
        w = self._witness = cone.middle_ray()
        self._w_hi = max(self._extreme(self.inner, w)[0], dot(w, p))
        self._w_lo = min(self._extreme(self.outer, w)[1], dot(w, q))

    @staticmethod
    def _extreme(points: _Points, n: Vec) -> tuple[int, int]:
        """(max n·x, min n·x) over the points, exactly."""
        o = points.origin or (0, 0, 0)
        hi, _, lo, _ = points.dots(n, points.extent())
        return hi + dot(n, o), lo + dot(n, o)

    def _start(self, p: Vec, q: Vec) -> Cone | None:
        # Still the half-space n · e > 0 (only one surfel so far): start the cone with the first pair
        # constraint that is independent of e, then cut by every pair (few points exist yet).
        e = self._first
        assert e is not None
        inner, outer = self.inner, self.outer
        ps = [inner.point(i) for i in range(inner.n)] + [p]
        qs = [outer.point(i) for i in range(outer.n)] + [q]
        vs = [_sub(b, a) for a in ps for b in qs]
        start = next((v for v in vs if primitive(v) != primitive(e)), None)
        if start is None:
            # Every pair differs by a multiple of e: the new surfel is the old one moved along e, and one of
            # the two pairs then points against e.
            return None
        cone = start_cone(e, start)
        return None if cone is None else cone.clip_all(vs)

    def _cut(self, cone: Cone, p: Vec | None, q: Vec | None) -> Cone | None:
        """The cone cut until every point (and p, q when given) is separated at each of its vertices."""
        inner, outer = self.inner, self.outer
        extent = max(inner.extent(), outer.extent())
        o, op = inner.origin or (0, 0, 0), outer.origin or (0, 0, 0)

        def failing_pair(r: Vec) -> Vec | None:
            # The highest voxel of A and the lowest voxel outside along r: apart, or the cut they give.
            hi, ihi, _, _ = inner.dots(r, extent)
            _, _, lo, ilo = outer.dots(r, extent)
            hi, lo = hi + dot(r, o), lo + dot(r, op)
            a, b = inner.point(ihi), outer.point(ilo)
            if p is not None and q is not None:
                rp, rq = dot(r, p), dot(r, q)
                if rp > hi:
                    hi, a = rp, p
                if rq < lo:
                    lo, b = rq, q
            return _sub(b, a) if hi > lo else None

        return cone.cut_until(failing_pair)

    def _refresh(self) -> None:
        if self._stale and self._cone is not None:
            cone = self._cut(self._cone, None, None)
            # The witness separated every point taken, so the cut cone still holds it.
            assert cone is not None
            self._cone, self._stale = cone, False

    def accepts(self, n: Sequence[int]) -> bool:
        """Whether the plane normal n separates strictly: max n·p < min n·q (checked on the points)."""
        t, u = self.offsets(n)
        return t < u

    def preimage(self) -> Cone:
        """The closed cone of admissible normals (its interior separates strictly).

        For a single surfel (every n with n · e > 0 separates) this is the square pyramid of the normals
        at most 45° from e, where the chosen normal is searched.
        """
        cone = self.cone
        if cone is not None:
            return cone
        e = self._first
        if e is None:
            raise ValueError("an empty patch has no preimage")
        return Cone.pyramid(e)

    def normal(self) -> Vec:
        """The chosen normal: the smallest admissible one (see :func:`smallest_normal`)."""
        return smallest_normal(self.preimage(), self.accepts, open_cone=True)

    def plane(self, n: Sequence[int] | None = None) -> DigitalPlane:
        """The standard arithmetic plane (n, μ) holding the inner voxels, n the chosen normal by default."""
        nv = self.normal() if n is None else (int(n[0]), int(n[1]), int(n[2]))
        t, _ = self.offsets(nv)
        return DigitalPlane(nv[0], nv[1], nv[2], t - (abs(nv[0]) + abs(nv[1]) + abs(nv[2])) + 1)

    def offsets(self, n: Sequence[int]) -> tuple[int, int]:
        """(max n·p over the inner voxels, min n·q over the outer voxels)."""
        nv: Vec = (int(n[0]), int(n[1]), int(n[2]))
        return self._extreme(self.inner, nv)[0], self._extreme(self.outer, nv)[1]

    def euclidean_plane(self, n: Sequence[int] | None = None) -> tuple[Vec, Fraction]:
        """The chosen Euclidean plane n · x = h, midway between the inner and the outer voxel centres."""
        nv = self.normal() if n is None else (int(n[0]), int(n[1]), int(n[2]))
        t, u = self.offsets(nv)
        return nv, Fraction(t + u, 2)


@dataclass
class _Octant:
    """One octant's cone of :class:`PointPlane`, with its witness normal and the extremes along it."""

    sign: Vec
    cone: Cone
    stale: bool = False
    witness: Vec = (0, 0, 0)
    hi: int = 0
    lo: int = 0
    has_witness: bool = False


class PointPlane:
    """Incremental recognition of a point set as a piece of a standard arithmetic plane.

    One cone per octant of normals; each keeps a witness normal as :class:`SurfelPlane` does, and a point
    that some octant's witness still admits is taken in constant time.

    Examples
    --------
    >>> rec = PointPlane()
    >>> all(rec.add((x, y, (x + 2 * y) // 3)) for x in range(4) for y in range(4))
    True
    >>> rec.add((0, 0, 5))
    False
    """

    def __init__(self) -> None:
        self.points = _Points()
        octants: list[Vec] = [(a, b, c) for a, b, c in product((1, -1), repeat=3)]
        self._octants: list[_Octant] = [_Octant(s, octant_cone(s)) for s in octants]

    @property
    def cones(self) -> dict[Vec, Cone]:
        """The exact cone of admissible normals of each octant that still has one."""
        self._octants = [oc for oc in self._octants if self._refresh(oc)]
        return {oc.sign: oc.cone for oc in self._octants}

    def add(self, p: Sequence[int]) -> bool:
        """Add the point p; False (and no change) when no standard plane holds the points with it."""
        pv: Vec = (int(p[0]), int(p[1]), int(p[2]))
        if pv in self.points:
            return True
        if self.points.n == 0:
            self.points.add(pv)
            return True
        dead: list[int] = []
        taken = False
        for k, oc in enumerate(self._octants):
            if oc.has_witness:
                x = dot(oc.witness, pv)
                hi, lo = max(oc.hi, x), min(oc.lo, x)
                if hi - lo < dot(oc.witness, oc.sign):
                    oc.hi, oc.lo, oc.stale = hi, lo, True
                    taken = True
                    break
            # Points taken without this octant's cone being cut by them: cut it by all of them first (p
            # aside), so that an empty cone here means empty with or without p.
            if oc.stale and not self._refresh(oc):
                dead.append(k)
                continue
            cone = self._cut(oc.cone, oc.sign, pv)
            if cone is None:
                dead.append(k)
                continue
            oc.cone, oc.stale = cone, False
            w = oc.witness = cone.middle_ray()
            oc.hi, oc.lo = self._extreme(w)
            x = dot(w, pv)
            oc.hi, oc.lo, oc.has_witness = max(oc.hi, x), min(oc.lo, x), True
            taken = True
            break
        if not taken:
            return False  # the octants are unchanged: the cut cones were not kept
        # The octants after the one that took p have not seen it: their witness no longer speaks for all
        # the points, so they are cut by every point when next asked. Octants found empty with p are empty
        # for good now that p is taken.
        for j in range(k + 1, len(self._octants)):
            oc = self._octants[j]
            oc.has_witness, oc.stale = False, True
            if _sub(pv, oc.sign) in self.points or _add(pv, oc.sign) in self.points:
                dead.append(j)  # the pair's constraint reads 0 > 0, which cutting cannot see
        for j in sorted(dead, reverse=True):
            del self._octants[j]
        self.points.add(pv)
        return True

    def _extreme(self, n: Vec) -> tuple[int, int]:
        o = self.points.origin or (0, 0, 0)
        hi, _, lo, _ = self.points.dots(n, self.points.extent())
        return hi + dot(n, o), lo + dot(n, o)

    def _refresh(self, oc: _Octant) -> bool:
        """Cut a stale octant's cone by every point; False when it is empty (the octant is dead)."""
        if oc.stale:
            cone = self._cut(oc.cone, oc.sign, None)
            if cone is None:
                return False
            oc.cone, oc.stale = cone, False
        return True

    def _cut(self, cone: Cone, s: Vec, p: Vec | None) -> Cone | None:
        pts = self.points
        o = pts.origin
        assert o is not None
        extent = pts.extent()
        if p is not None:
            if _sub(p, s) in pts or _add(p, s) in pts:
                # Two points apart by s: the constraint n · (s − (p − p′)) > 0 reads 0 > 0. The closed
                # cone does not see it (its half-space is everything), so it is checked here.
                return None
            extent += abs(p[0] - o[0]) + abs(p[1] - o[1]) + abs(p[2] - o[2])

        def failing_pair(r: Vec) -> Vec | None:
            # The points farthest apart along r: within |r|₁ (r · s in the octant), or the cut they give.
            hi, ihi, lo, ilo = pts.dots(r, extent)
            a, b = _sub(pts.point(ihi), o), _sub(pts.point(ilo), o)
            if p is not None:
                x_rel = _sub(p, o)
                x = dot(r, x_rel)
                if x > hi:
                    hi, a = x, x_rel
                if x < lo:
                    lo, b = x, x_rel
            return _sub(s, _sub(a, b)) if hi - lo > dot(r, s) else None

        return cone.cut_until(failing_pair)

    def accepts(self, n: Sequence[int]) -> bool:
        """Whether the points' width along n is below |n|₁."""
        nv: Vec = (int(n[0]), int(n[1]), int(n[2]))
        if nv == (0, 0, 0):
            return False
        hi, lo = self._extreme(nv)
        return hi - lo < abs(nv[0]) + abs(nv[1]) + abs(nv[2])

    def normal(self) -> Vec:
        """The chosen normal: the smallest admissible one over the eight octants."""
        best: Vec | None = None
        for cone in self.cones.values():
            n = smallest_normal(cone, self.accepts)
            if best is None or _size_key(n) < _size_key(best):
                best = n
        if best is None:
            raise ValueError("the points lie in no standard plane")
        return best

    def plane(self) -> DigitalPlane:
        """The standard arithmetic plane of the chosen normal, μ the smallest remainder."""
        n = self.normal()
        _, lo = self._extreme(n)
        return DigitalPlane(n[0], n[1], n[2], lo)


def _size_key(n: Vec) -> tuple[int, int, Vec]:
    return (max(abs(c) for c in n), abs(n[0]) + abs(n[1]) + abs(n[2]), n)


def smallest_normal(cone: Cone, accepts: Callable[[Vec], bool], *, open_cone: bool = False) -> Vec:
    """The admissible normal of smallest max-norm (then L1 norm, then lexicographic) in a cone.

    The candidates at max-norm N are the integer points of the cone's slices by the faces of the cube
    [−N, N]³, enumerated in the bounding box of each slice, kept when they are in the closed cone (the
    open one with ``open_cone``) and ``accepts`` them (the exact definition of the recognizer). The scan
    stops at :data:`MAX_NORMAL_SCAN` or at the max-norm of the cone's interior ray, which is always
    admissible.
    """
    fallback = cone.interior_ray()
    if not accepts(fallback):
        # The interior of an exact preimage always separates; reaching this is a bug, not bad input.
        raise AssertionError(f"the interior ray {fallback} of the preimage is not admissible")
    cap = min(max(abs(c) for c in fallback), MAX_NORMAL_SCAN)
    normals = cone.edge_normals()
    # When the admissible normals are exactly the open cone (a surfel patch), a candidate on its boundary is
    # never admissible: filtering it out here spares ``accepts`` (a pass over the points) on the many
    # lattice points a boundary face can hold, e.g. the (a, b, 0) of a long rod's segment.
    least = 0 if open_cone else -1
    slices = _face_slices(cone)
    for big_n in range(1, cap + 1):
        found: list[Vec] = []
        for axis, sign, lo_u, hi_u, lo_v, hi_v in slices:
            for u in range(max(-big_n, ceil(lo_u * big_n)), min(big_n, floor(hi_u * big_n)) + 1):
                for v in range(max(-big_n, ceil(lo_v * big_n)), min(big_n, floor(hi_v * big_n)) + 1):
                    n = _on_face(axis, sign * big_n, u, v)
                    if all(dot(c, n) > least for c in normals):
                        found.append(n)
        for n in sorted(set(found), key=_size_key):
            if primitive(n) == n and accepts(n):
                return n
    return fallback


def _on_face(axis: int, w: int, u: int, v: int) -> Vec:
    if axis == 0:
        return (w, u, v)
    if axis == 1:
        return (v, w, u)
    return (u, v, w)


def _face_slices(cone: Cone) -> list[tuple[int, int, Fraction, Fraction, Fraction, Fraction]]:
    """(axis, sign, bounds of u/w and v/w) for each cube face: the cone cut by the face's pyramid."""
    out = []
    for axis in range(3):
        for sign in (1, -1):
            u_ax, v_ax = (axis + 1) % 3, (axis + 2) % 3
            w_unit = [0, 0, 0]
            w_unit[axis] = sign
            pyramid: list[Sequence[int]] = []
            for k, s in ((u_ax, 1), (u_ax, -1), (v_ax, 1), (v_ax, -1)):
                c = [0, 0, 0]
                c[axis] = sign
                c[k] = -s
                pyramid.append(c)
            part = cone.clip_all(pyramid)
            if part is None:
                continue
            us = [Fraction(r[u_ax], sign * r[axis]) for r in part.rays]
            vs = [Fraction(r[v_ax], sign * r[axis]) for r in part.rays]
            out.append((axis, sign, min(us), max(us), min(vs), max(vs)))
    return out


def recognize_surfels(surfels: Iterable[tuple[Sequence[int], Sequence[int]]]) -> DigitalPlane | None:
    """The digital plane of a whole surfel patch given as (voxel of A, outward normal) pairs, or None."""
    rec = SurfelPlane()
    for p, e in surfels:
        if not rec.add(p, e):
            return None
    return rec.plane() if rec.n_surfels else None


def recognize_points(points: Iterable[Sequence[int]]) -> DigitalPlane | None:
    """A standard arithmetic plane holding every point, or None when there is none."""
    rec = PointPlane()
    for p in points:
        if not rec.add(p):
            return None
    return rec.plane() if rec.points.n else None


def standard_plane_prefix(points: npt.ArrayLike) -> tuple[int, DigitalPlane | None]:
    """How many of the points, taken in order, lie in one standard arithmetic plane, and that plane.

    The compiled form of feeding the points to :class:`PointPlane` until one is refused (the same decisions
    and the same chosen plane; the tests hold the two together). Points farther than
    :data:`~mrm.geometry.planes._kernels.MAX_EXTENT` from the first one end the prefix too.

    Parameters
    ----------
    points : int array (n, 3)

    Returns
    -------
    (int, DigitalPlane or None)
        The length of the prefix, and its plane (None for no point).

    Examples
    --------
    A flat 3 × 3 square, then a bump in its middle (a point set's normal is defined up to its sign; the
    smallest comes first in lexicographic order):

    >>> standard_plane_prefix([(x, y, 0) for x in range(3) for y in range(3)] + [(1, 1, 1)])
    (9, DigitalPlane(a=0, b=0, c=-1, mu=0))
    """
    from mrm.geometry.planes._kernels import point_plane_prefix

    pts = np.ascontiguousarray(points, np.int64).reshape(-1, 3)
    taken, rays, counts = point_plane_prefix(pts)
    if taken == 0:
        return 0, None
    kept = pts[:taken] - pts[0]

    def extremes(n: Vec) -> tuple[int, int]:
        if max(abs(c) for c in n) < MAX_INT64_RAY:
            d = kept @ np.array(n, np.int64)
            return int(d.max()), int(d.min())
        vals = [dot(n, (int(x), int(y), int(z))) for x, y, z in kept]
        return max(vals), min(vals)

    def accepts(n: Vec) -> bool:
        hi, lo = extremes(n)
        return any(n) and hi - lo < abs(n[0]) + abs(n[1]) + abs(n[2])

    best: Vec | None = None
    for o in range(8):
        if counts[o] == 0:
            continue
        cone = Cone(tuple((int(x), int(y), int(z)) for x, y, z in rays[o, : counts[o]]))
        n = smallest_normal(cone, accepts)
        if best is None or _size_key(n) < _size_key(best):
            best = n
    assert best is not None  # the first point alone lies in every octant's planes
    _, lo = extremes(best)
    return taken, DigitalPlane(
        best[0], best[1], best[2], lo + dot(best, (int(pts[0, 0]), int(pts[0, 1]), int(pts[0, 2])))
    )
