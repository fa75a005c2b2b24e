"""Reference predicates and pair tests for polyhedra, written with fractions.Fraction (docs/design.md §11).

Independent of mrm.geometry.polyhedra: no float filter, no expansion, no grid. ``orient3d`` is the 4×4
determinant with a column of ones evaluated by cofactor expansion on Fractions; the triangle–triangle test
decides whether two closed triangles share a point outside their common vertices by exact linear
programming in barycentric coordinates would be heavy, so it is the textbook separating-axis-free test:
closed segment–triangle intersections computed as actual rational points.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

Q = Fraction
Pt = tuple[Fraction, Fraction, Fraction]


def q(p: Sequence[float]) -> Pt:
    return (Q(float(p[0])), Q(float(p[1])), Q(float(p[2])))


def _det3(m: list[list[Fraction]]) -> Fraction:
    return (
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )


def _sign(x: Fraction) -> int:
    return (x > 0) - (x < 0)


def orient3d(a: Sequence[float], b: Sequence[float], c: Sequence[float], d: Sequence[float]) -> int:
    """Sign of det[[1, a], [1, b], [1, c], [1, d]] = det[b − a, c − a, d − a], by cofactors on the ones."""
    pts = [list(q(p)) for p in (a, b, c, d)]
    total = Q(0)
    for i in range(4):
        minor = [pts[r] for r in range(4) if r != i]
        total += (-1) ** i * _det3(minor)
    return _sign(total)


def orient2d(p: Sequence[float], r: Sequence[float], s: Sequence[float], i: int, j: int) -> int:
    m = [[Q(1), Q(float(x[i])), Q(float(x[j]))] for x in (p, r, s)]
    return _sign(_det3(m))


def _sub(a: Pt, b: Pt) -> Pt:
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _dot(a: Pt, b: Pt) -> Fraction:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a: Pt, b: Pt) -> Pt:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _in_triangle(x: Pt, tri: Sequence[Pt]) -> bool:
    """x (in the triangle's plane) inside the closed triangle: barycentric signs via cross products."""
    n = _cross(_sub(tri[1], tri[0]), _sub(tri[2], tri[0]))
    for k in range(3):
        e = _sub(tri[(k + 1) % 3], tri[k])
        if _dot(_cross(e, _sub(x, tri[k])), n) < 0:
            return False
    return True


def _clip(a: Pt, b: Pt, tri: Sequence[Pt]) -> list[tuple[Fraction, Fraction]]:
    """Parameter intervals [t0, t1] ⊂ [0, 1] of a + t(b − a) inside the closed triangle (coplanar or not)."""
    n = _cross(_sub(tri[1], tri[0]), _sub(tri[2], tri[0]))
    da = _dot(n, _sub(a, tri[0]))
    db = _dot(n, _sub(b, tri[0]))
    if da == 0 and db == 0:
        lo, hi = Q(0), Q(1)
        d = _sub(b, a)
        for k in range(3):
            e = _sub(tri[(k + 1) % 3], tri[k])
            # inside half-plane: (e × (x − v_k))·n ≥ 0, linear in t: c0 + t c1 ≥ 0
            c0 = _dot(_cross(e, _sub(a, tri[k])), n)
            c1 = _dot(_cross(e, d), n)
            if c1 == 0:
                if c0 < 0:
                    return []
            elif c1 > 0:
                lo = max(lo, -c0 / c1)
            else:
                hi = min(hi, -c0 / c1)
        return [(lo, hi)] if lo <= hi else []
    if (da > 0 and db > 0) or (da < 0 and db < 0):
        return []
    t = da / (da - db)
    x = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]))
    return [(t, t)] if _in_triangle(x, tri) else []


def triangles_meet_improperly(v: Sequence[Sequence[float]], ta: Sequence[int], tb: Sequence[int]) -> bool:
    """Do closed triangles ta, tb share a point that is not in the simplex of their common vertices?

    Every common point lies on an edge of one of them (or both triangles meet along edges): each edge is
    clipped against the other triangle, and each clipped piece is tested against the common face.
    """
    common = sorted(set(ta) & set(tb))
    P = [q(p) for p in v]
    A = [P[i] for i in ta]
    B = [P[i] for i in tb]
    C = [P[i] for i in common]

    def in_common(x: Pt) -> bool:
        if not C:
            return False
        if len(C) == 1:
            return x == C[0]
        if len(C) == 2:
            d = _sub(C[1], C[0])
            w = _sub(x, C[0])
            if _cross(d, w) != (0, 0, 0):
                return False
            t = _dot(w, d) / _dot(d, d)
            return 0 <= t <= 1
        return True

    for X, Y in ((A, B), (B, A)):
        for k in range(3):
            a, b = X[k], X[(k + 1) % 3]
            for t0, t1 in _clip(a, b, Y):
                for t in (t0, t1, (t0 + t1) / 2):
                    x = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]))
                    if not in_common(x):
                        return True
    return False


def first_intersecting_pair(
    v: Sequence[Sequence[float]], t: Sequence[Sequence[int]]
) -> tuple[int, int] | None:
    """Brute force over all pairs, smallest (a, b) first."""
    for a in range(len(t)):
        for b in range(a + 1, len(t)):
            if triangles_meet_improperly(v, t[a], t[b]):
                return a, b
    return None


def volume6(v: Sequence[Sequence[float]], t: Sequence[Sequence[int]]) -> Fraction:
    """Six times the signed volume, exactly: Σ det[a, b, c] over the triangles."""
    total = Q(0)
    for a, b, c in t:
        total += _det3([list(q(v[a])), list(q(v[b])), list(q(v[c]))])
    return total


def is_flat(v: Sequence[Sequence[float]], tri: Sequence[int]) -> bool:
    a, b, c = (q(v[i]) for i in tri)
    return _cross(_sub(b, a), _sub(c, a)) == (0, 0, 0)
