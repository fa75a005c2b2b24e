"""Slow references for digital plane recognition: Fourier–Motzkin elimination on integer constraints.

A homogeneous system { n · v > 0 (strict) , n · w ≥ 0 } in three unknowns is decided by eliminating the
unknowns one after the other: each pair of constraints with opposite signs on the eliminated coordinate gives
their positive combination without it (strict when either is). What is left are constants: the system is
feasible iff no "0 > 0" and no "c ≥ 0" with c < 0 remains. Integers only, so nothing is rounded.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from itertools import product
from math import gcd

Row = tuple[tuple[int, ...], bool]  # (coefficients, strict)


def _norm(coef: Sequence[int], strict: bool) -> Row:
    g = 0
    for c in coef:
        g = gcd(g, c)
    if g > 1:
        coef = tuple(c // g for c in coef)
    return tuple(coef), strict


def feasible(strict: Iterable[Sequence[int]], closed: Iterable[Sequence[int]] = ()) -> bool:
    """Whether some n ∈ R³ has n · v > 0 for every v of ``strict`` and n · w ≥ 0 for every w of ``closed``."""
    rows: dict[tuple[int, ...], bool] = {}
    for vs, flag in ((strict, True), (closed, False)):
        for v in vs:
            c, s = _norm(tuple(int(x) for x in v), flag)
            rows[c] = rows.get(c, False) or s
    for k in range(3):
        pos = [(c, s) for c, s in rows.items() if c[k] > 0]
        neg = [(c, s) for c, s in rows.items() if c[k] < 0]
        new: dict[tuple[int, ...], bool] = {c: s for c, s in rows.items() if c[k] == 0}
        for (cp, sp), (cn, sn) in product(pos, neg):
            a, b = -cn[k], cp[k]
            comb = tuple(a * x + b * y for x, y in zip(cp, cn, strict=True))
            c, s = _norm(comb, sp or sn)
            new[c] = new.get(c, False) or s
        rows = new
    for c, s in rows.items():
        assert all(x == 0 for x in c)
        if s:
            return False
    return True


def surfel_patch_is_plane(surfels: Sequence[tuple[Sequence[int], Sequence[int]]]) -> bool:
    """Whether a plane separates strictly every inner voxel p from every outer voxel p + e."""
    inner = {tuple(p) for p, _ in surfels}
    outer = {tuple(a + b for a, b in zip(p, e, strict=True)) for p, e in surfels}
    vs = [tuple(q[i] - p[i] for i in range(3)) for p in inner for q in outer]
    return feasible(vs)


def points_in_standard_plane(points: Sequence[Sequence[int]]) -> bool:
    """Whether some integer n ≠ 0 has max n·p − min n·p < |n|₁ over the points (one check per octant)."""
    pts = {tuple(int(x) for x in p) for p in points}
    diffs = {tuple(a[i] - b[i] for i in range(3)) for a in pts for b in pts}
    for s in product((1, -1), repeat=3):
        closed = [tuple(s[i] if i == k else 0 for i in range(3)) for k in range(3)]
        strict = [tuple(s[i] - d[i] for i in range(3)) for d in diffs]
        if feasible(strict, closed):
            return True
    return False


def separates(n: Sequence[int], surfels: Sequence[tuple[Sequence[int], Sequence[int]]]) -> bool:
    """Whether n · p < n · q for every inner voxel p and outer voxel q of the patch."""
    inner = [tuple(p) for p, _ in surfels]
    outer = [tuple(a + b for a, b in zip(p, e, strict=True)) for p, e in surfels]
    dot = lambda u: sum(a * b for a, b in zip(n, u, strict=True))  # noqa: E731
    return max(map(dot, inner)) < min(map(dot, outer))
