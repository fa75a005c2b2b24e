"""An exact convex cone of plane normals: the preimage of a digital plane segment.

Reference: docs/design.md §11 (analytical representation), docs/reconstruction.md ("Digital plane segments").

Every recognizer of :mod:`mrm.geometry.planes` asks the same question: which normals n ∈ R³ satisfy
n · v ≥ 0 for a growing set of integer vectors v (one per pair of points that a plane must keep apart)? The
answer is a convex polyhedral cone, and it is kept as the spherical polygon it cuts on the unit sphere: its
extreme rays, primitive integer vectors in cyclic order, every edge an arc shorter than a half circle.

Clipping by a half-space is Sutherland–Hodgman on the sphere: a vertex r stays when r · v ≥ 0, and an edge
(r, s) crossing the great circle v⊥ gets the new vertex |v·r| s + |v·s| r, a positive combination of its
ends, reduced by the gcd of its coordinates. Every vertex is therefore, up to scale, the cross product of two
constraint vectors, so its coordinates stay below 2·|v|² whatever the history: Python integers keep it exact,
and their size stays small.

A cone is *full* (three-dimensional) when its vertices do not all lie on one plane through 0; the open cone
{ n · v > 0 } is non-empty exactly when the closed one is full, which is what recognition needs (a plane that
separates strictly). A degenerate clip result is reported as ``None``: the constraints only grow, so it stays
empty for good.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from math import gcd

Vec = tuple[int, int, int]


def dot(u: Sequence[int], v: Sequence[int]) -> int:
    """The exact dot product of two integer 3-vectors."""
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


def cross(u: Sequence[int], v: Sequence[int]) -> Vec:
    """The exact cross product u × v of two integer 3-vectors."""
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def det3(u: Sequence[int], v: Sequence[int], w: Sequence[int]) -> int:
    """The exact determinant det(u, v, w) = (u × v) · w."""
    return dot(cross(u, v), w)


def primitive(v: Sequence[int]) -> Vec:
    """``v`` divided by the gcd of its coordinates (the zero vector stays zero)."""
    g = gcd(gcd(int(v[0]), int(v[1])), int(v[2]))
    if g <= 1:
        return (int(v[0]), int(v[1]), int(v[2]))
    return (int(v[0]) // g, int(v[1]) // g, int(v[2]) // g)


@dataclass(frozen=True)
class Cone:
    """A closed, pointed, three-dimensional convex cone { n : n · v ≥ 0 for every constraint v }.

    Attributes
    ----------
    rays : tuple of (int, int, int)
        Its extreme rays, primitive integer vectors in cyclic order around the cone (at least three, not all
        on one plane through 0); consecutive rays are less than a half turn apart.
    """

    rays: tuple[Vec, ...]

    @staticmethod
    def half_space_pair(e: Sequence[int], v: Sequence[int]) -> Cone | None:
        """The cone { n · e ≥ 0, n · v ≥ 0 }: a lune, or ``None`` when e and v are opposite.

        Parameters
        ----------
        e, v : integer 3-vectors, non-zero.

        Returns
        -------
        Cone or None
            ``None`` when v is a negative multiple of e (no normal has n · e > 0 and n · v > 0); when v is a
            positive multiple of e the result is not pointed, so this also returns ``None`` for that case and
            the caller must pick a v independent of e (see :func:`start_cone`).
        """
        w = primitive(cross(e, v))
        if w == (0, 0, 0):
            return None
        ee = dot(e, e)
        ev = dot(e, v)
        vv = dot(v, v)
        # a: on the great circle e⊥, on the side v > 0 (the part of v orthogonal to e);
        # b: on the great circle v⊥, on the side e > 0 (the part of e orthogonal to v). Both are orthogonal
        # to w, so the four arcs w → a → −w → b → w are quarter circles.
        a = primitive(tuple(ee * vi - ev * ei for vi, ei in zip(v, e, strict=True)))
        b = primitive(tuple(vv * ei - ev * vi for vi, ei in zip(v, e, strict=True)))
        neg_w = (-w[0], -w[1], -w[2])
        return Cone((w, a, neg_w, b))

    def clip(self, v: Sequence[int]) -> Cone | None:
        """The cone cut by the half-space n · v ≥ 0, or ``None`` when what is left is not full."""
        if not any(v):
            return None  # n · 0 > 0 holds for no n: the open cone is empty
        rays = self.rays
        signs = [dot(r, v) for r in rays]
        if min(signs) >= 0:
            return self
        if max(signs) <= 0:
            return None
        out: list[Vec] = []
        m = len(rays)
        for i in range(m):
            r, sr = rays[i], signs[i]
            s, ss = rays[(i + 1) % m], signs[(i + 1) % m]
            if sr >= 0:
                out.append(r)
            if (sr > 0 > ss) or (sr < 0 < ss):
                # |v·r| s + |v·s| r lies on v⊥ between r and s (both weights positive).
                ar, as_ = abs(sr), abs(ss)
                out.append(
                    primitive((ar * s[0] + as_ * r[0], ar * s[1] + as_ * r[1], ar * s[2] + as_ * r[2]))
                )
        out = self._split_half_turns(out, v)
        if len(out) < 3:
            return None
        cone = Cone(tuple(out))
        return cone if cone.is_full() else None

    def _split_half_turns(self, out: list[Vec], v: Sequence[int]) -> list[Vec]:
        # A cut whose great circle v⊥ passes through two opposite vertices (the lune's w and −w) leaves an
        # edge of a half turn, which the arc formulas cannot follow: it gets its midpoint on v⊥, the one of
        # ±(v × w) that lies in the cone being cut (the new edge runs inside it).
        m = len(out)
        if m < 2:
            return out
        res: list[Vec] = []
        for i in range(m):
            r, s = out[i], out[(i + 1) % m]
            res.append(r)
            if r == (-s[0], -s[1], -s[2]):
                mid = primitive(cross(v, r))
                if not self.contains(mid):
                    mid = (-mid[0], -mid[1], -mid[2])
                res.append(mid)
        return res

    def cut_until(self, failing: Callable[[Vec], Sequence[int] | None]) -> Cone | None:
        """Cut the cone until ``failing`` finds nothing at any vertex; ``None`` once it is not full.

        ``failing(r)`` returns the constraint vector v (r · v < 0) of a condition that fails at the vertex r,
        or None where all hold. For conditions convex in n (a maximum of linear constraints, as the
        recognizers' are) holding at every vertex means holding on the whole cone, so what is left is the
        cone cut by exactly the constraints that matter.
        """
        cone: Cone | None = self
        while cone is not None:
            cut = next((v for v in map(failing, cone.rays) if v is not None), None)
            if cut is None:
                return cone
            cone = cone.clip(cut)
        return None

    @staticmethod
    def pyramid(e: Sequence[int]) -> Cone:
        """The square pyramid of the normals within 45° of the axis vector e (± a unit vector)."""
        k = next(i for i in range(3) if e[i] != 0)
        rays: list[Vec] = []
        for su, sv in ((1, 1), (-1, 1), (-1, -1), (1, -1)):
            r = [0, 0, 0]
            r[k], r[(k + 1) % 3], r[(k + 2) % 3] = int(e[k]), su, sv
            rays.append((r[0], r[1], r[2]))
        return Cone(tuple(rays))

    def clip_all(self, vs: Iterable[Sequence[int]]) -> Cone | None:
        """The cone cut by every half-space n · v ≥ 0 of ``vs`` in turn (``None`` once not full)."""
        cone: Cone | None = self
        for v in vs:
            if cone is None:
                return None
            cone = cone.clip(v)
        return cone

    def is_full(self) -> bool:
        """Whether the rays span three dimensions (the open cone is then non-empty)."""
        rays = self.rays
        m = len(rays)
        # Consecutive triples: a fixed first ray may be opposite another one (a lune), spanning nothing.
        return any(det3(rays[i], rays[(i + 1) % m], rays[(i + 2) % m]) != 0 for i in range(m))

    def edge_normals(self) -> tuple[Vec, ...]:
        """The inward normals c of its faces: n is in the closed cone iff n · c ≥ 0 for each c."""
        rays = self.rays
        m = len(rays)
        inside = primitive(tuple(sum(r[k] for r in rays) for k in range(3)))
        out: list[Vec] = []
        for i in range(m):
            c = primitive(cross(rays[i], rays[(i + 1) % m]))
            if c == (0, 0, 0):
                continue  # two equal rays cannot occur; a zero normal would add no constraint
            if dot(c, inside) < 0:
                c = (-c[0], -c[1], -c[2])
            out.append(c)
        return tuple(out)

    def contains(self, n: Sequence[int]) -> bool:
        """Whether n is in the closed cone."""
        return all(dot(c, n) >= 0 for c in self.edge_normals())

    def interior_ray(self) -> Vec:
        """A primitive integer vector inside the open cone: the sum of the extreme rays."""
        return primitive(tuple(sum(r[k] for r in self.rays) for k in range(3)))

    def middle_ray(self) -> Vec:
        """A primitive integer vector inside the open cone, near its middle (the witness of a recognizer).

        The sum of the unit rays, rounded to integers below 2²⁰ and checked exactly against the faces;
        :meth:`interior_ray` when rounding left it outside (a very thin cone). The integer sum is inside
        too, but a long ray outweighs the others and puts it near one side.
        """
        f = [0.0, 0.0, 0.0]
        for r in self.rays:
            nrm = math.sqrt(float(r[0]) ** 2 + float(r[1]) ** 2 + float(r[2]) ** 2)
            for k in range(3):
                f[k] += r[k] / nrm
        big = max(abs(c) for c in f)
        if big > 0.0:
            scale = float(1 << 20) / big
            w = primitive(tuple(round(c * scale) for c in f))
            if all(dot(w, c) > 0 for c in self.edge_normals()):
                return w
        return self.interior_ray()


def start_cone(e: Sequence[int], v: Sequence[int]) -> Cone | None:
    """The first cone of a recognition: { n · e ≥ 0, n · v ≥ 0 }, with v not a multiple of e.

    A thin wrapper of :meth:`Cone.half_space_pair` that names what recognizers use it for.
    """
    return Cone.half_space_pair(e, v)


def octant_cone(signs: Sequence[int]) -> Cone:
    """The closed octant { s_i n_i ≥ 0 } of the sign vector ``signs`` (each ±1): a spherical triangle."""
    sx, sy, sz = (int(s) for s in signs)
    return Cone(((sx, 0, 0), (0, sy, 0), (0, 0, sz)))
