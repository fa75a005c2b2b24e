"""Orientation and nesting of the shells of a valid-so-far mesh, decided exactly.

A set of disjoint closed oriented shells bounds a solid when every point has winding number 0 or 1: an outer
shell (inside no other solid part) must turn its normals outward (positive volume) and the shell of a cavity
inward (negative volume), and so on down nested levels. With w the winding number of all the *other* shells
at a point of shell s and o(s) = ±1 the sign of s's volume, the two sides of s have winding numbers w and
w + o(s), so the mesh is a solid iff (o(s), w) is (+1, 0) or (−1, 1) for every shell.

- **The volume's sign** is Σ det[a − o, b − o, c − o] / 6 over the shell's triangles (o one of its
  vertices), summed in float64 with a proven error bound (Shewchuk's bound per term plus the summation's);
  when the sum does not clear the bound, the exact sum of the 24 exact products of every det[a, b, c] is
  rounded once by ``math.fsum`` (correct rounding keeps the sign), or summed as Fractions out of range.
- **The winding number** at a vertex p of s is counted along the ray p + t·d, d = (1, ε, ε²), ε → 0⁺ (the
  τ of docs/design.md §2 and §11): every triangle a b c of another shell whose projection along d strictly
  contains p's adds the sign of n·d (n its normal) when the crossing is ahead (t > 0). All three quantities
  are polynomials in ε whose coefficients are exact orient2d / orient3d signs, so no ray ever grazes an edge.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import numpy.typing as npt
from numba.extending import register_jitable

from mrm.core.errors import InvalidGeometryError
from mrm.geometry._jit import njit
from mrm.geometry.polyhedra.manifold import fmt_point
from mrm.geometry.polyhedra.predicates import _HIGH, _LOW, UNKNOWN, _push_det3, o2, o3

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

_EPS = 2.0**-53


# ---------------------------------------------------------------------------------------------- volume
@njit(cache=True)
def _volume_sums(v: Floats, t: Ints, shell: Ints, base: Ints, nshells: int) -> tuple[Floats, Floats, Floats]:
    """Per shell: Σ det[a − o, b − o, c − o] in float64, Σ of its permanents, and whether all is in range."""
    total = np.zeros(nshells)
    perm = np.zeros(nshells)
    ok = np.ones(nshells)
    for f in range(t.shape[0]):
        s = shell[f]
        o = base[s]
        ux, uy, uz = v[t[f, 0], 0] - v[o, 0], v[t[f, 0], 1] - v[o, 1], v[t[f, 0], 2] - v[o, 2]
        vx, vy, vz = v[t[f, 1], 0] - v[o, 0], v[t[f, 1], 1] - v[o, 1], v[t[f, 1], 2] - v[o, 2]
        wx, wy, wz = v[t[f, 2], 0] - v[o, 0], v[t[f, 2], 1] - v[o, 1], v[t[f, 2], 2] - v[o, 2]
        for c in (ux, uy, uz, vx, vy, vz, wx, wy, wz):
            a = abs(c)
            if a != 0.0 and (a < _LOW or a > 2.0 * _HIGH):
                ok[s] = 0.0
        vywz, vzwy = vy * wz, vz * wy
        vzwx, vxwz = vz * wx, vx * wz
        vxwy, vywx = vx * wy, vy * wx
        total[s] += ux * (vywz - vzwy) + uy * (vzwx - vxwz) + uz * (vxwy - vywx)
        perm[s] += (
            abs(ux) * (abs(vywz) + abs(vzwy))
            + abs(uy) * (abs(vzwx) + abs(vxwz))
            + abs(uz) * (abs(vxwy) + abs(vywx))
        )
    return total, perm, ok


@njit(cache=True)
def _det_components(v: Floats, t: Ints) -> Floats:
    """24 doubles per triangle whose exact sum is Σ det[a, b, c] (coordinates in the exact range)."""
    out = np.empty(24 * t.shape[0])
    n = 0
    for f in range(t.shape[0]):
        n = _push_det3(out, n, 1.0, v[t[f, 0]], v[t[f, 1]], v[t[f, 2]])
    return out


def _in_range(v: Floats) -> bool:
    a = np.abs(v)
    return bool(np.all((a == 0) | ((a >= _LOW) & (a <= _HIGH))))


def _exact_volume_sign(v: Floats, t: Ints) -> int:
    used = v[np.unique(t)]
    if _in_range(used):
        s = math.fsum(_det_components(v, t).tolist())
        return (s > 0) - (s < 0)
    q = [[Fraction(float(c)) for c in row] for row in v.tolist()]
    total = Fraction(0)
    for a, b, c in t.tolist():
        pa, pb, pc = q[a], q[b], q[c]
        total += (
            pa[0] * (pb[1] * pc[2] - pb[2] * pc[1])
            + pa[1] * (pb[2] * pc[0] - pb[0] * pc[2])
            + pa[2] * (pb[0] * pc[1] - pb[1] * pc[0])
        )
    return (total > 0) - (total < 0)


def volume_signs(v: Floats, t: Ints, shell: Ints, nshells: int) -> Ints:
    """The exact sign of every shell's volume (−1, 0, 1)."""
    base = np.empty(nshells, np.int64)
    first_tri = np.unique(shell, return_index=True)[1]
    base[:] = t[first_tri, 0]
    total, perm, ok = _volume_sums(v, t, shell, base, nshells)
    counts = np.bincount(shell, minlength=nshells).astype(float)
    # Per term: Shewchuk's orient3d bound (7 + 56ε)ε·permanent; the float sum of k terms adds at most
    # (k − 1)ε·Σ|term| ≤ (k − 1)ε·Σ permanent (|term| ≤ permanent·(1 + 8ε)); doubled for the slack.
    bound = 2.0 * ((7.0 + 56.0 * _EPS) * _EPS + (counts + 1.0) * _EPS * 1.01) * perm
    signs = np.where(total > bound, 1, np.where(total < -bound, -1, 0)).astype(np.int64)
    for s in np.flatnonzero((signs == 0) | (ok == 0)).tolist():
        signs[s] = _exact_volume_sign(v, t[shell == s])
    return signs


# ---------------------------------------------------------------------------------------------- winding
@register_jitable
def _leading(v: Floats, a: int, b: int, c: int) -> int:
    """Sign of ((b − a) × (c − a))·(1, ε, ε²): the first non-zero of its x, y, z components' signs."""
    for k in range(3):
        s = o2(v, a, b, c, (k + 1) % 3, (k + 2) % 3)
        if s != 0:
            return s  # UNKNOWN passes through
    return 0


@register_jitable
def ray_crossing(v: Floats, p: int, a: int, b: int, c: int) -> int:
    """What triangle a b c adds to the winding number at p along p + t(1, ε, ε²): −1, 0, 1 or UNKNOWN."""
    s1 = _leading(v, p, a, b)
    if s1 == 0:
        return 0
    s2 = _leading(v, p, b, c)
    if s2 != s1 and s2 != UNKNOWN and s1 != UNKNOWN:
        return 0
    s3 = _leading(v, p, c, a)
    if s1 == UNKNOWN or s2 == UNKNOWN or s3 == UNKNOWN:
        return UNKNOWN
    if s2 != s1 or s3 != s1:
        return 0
    nd = _leading(v, a, b, c)
    side = o3(v, a, b, c, p)
    if nd == UNKNOWN or side == UNKNOWN:
        return UNKNOWN
    # The crossing is at t = n·(a − p) / n·d = −side / nd (in sign): ahead when −side and nd agree.
    if side == 0 or -side != nd:
        return 0
    return nd


@njit(cache=True)
def _windings(
    v: Floats,
    t: Ints,
    order: Ints,
    starts: Ints,
    reps: Ints,
    lo: Floats,
    hi: Floats,
    slo: Floats,
    shi: Floats,
) -> tuple[Ints, Ints]:
    """Winding number of the other shells at every shell's representative vertex; 1 where undecided.

    ``order[starts[g]:starts[g + 1]]`` are the triangles of shell g: a shell whose box the ray misses is
    skipped whole, so many small shells cost O(shells²) box tests, not O(shells × triangles).
    """
    ns = reps.shape[0]
    wind = np.zeros(ns, np.int64)
    unknown = np.zeros(ns, np.int64)
    for s in range(ns):
        p = reps[s]
        px, py, pz = v[p, 0], v[p, 1], v[p, 2]
        for g in range(ns):
            if g == s:
                continue
            if px >= shi[g, 0] or py < slo[g, 1] or py > shi[g, 1] or pz < slo[g, 2] or pz > shi[g, 2]:
                continue
            for e in range(starts[g], starts[g + 1]):
                f = order[e]
                if hi[f, 0] <= px or py < lo[f, 1] or py > hi[f, 1] or pz < lo[f, 2] or pz > hi[f, 2]:
                    continue
                c = ray_crossing(v, p, t[f, 0], t[f, 1], t[f, 2])
                if c == UNKNOWN:
                    unknown[s] = 1
                else:
                    wind[s] += c
    return wind, unknown


def shell_windings(v: Floats, t: Ints, shell: Ints, nshells: int) -> tuple[Ints, Ints, Ints]:
    """Per shell: its first triangle, a vertex of it, and the winding number of the other shells there.

    The shells must be closed, oriented and pairwise disjoint (checked before).
    """
    first_tri = np.unique(shell, return_index=True)[1]
    reps = t[first_tri, 0].astype(np.int64)
    if nshells == 1:
        return first_tri, reps, np.zeros(1, np.int64)
    corners = v[t]
    lo, hi = corners.min(axis=1), corners.max(axis=1)
    slo = np.full((nshells, 3), np.inf)
    shi = np.full((nshells, 3), -np.inf)
    np.minimum.at(slo, shell, lo)
    np.maximum.at(shi, shell, hi)
    order = np.argsort(shell, kind="stable").astype(np.int64)
    starts = np.searchsorted(shell[order], np.arange(nshells + 1)).astype(np.int64)
    wind, unknown = _windings(v, t, order, starts, reps, lo, hi, slo, shi)
    for s in np.flatnonzero(unknown).tolist():
        # Plain Python, exact Fractions: the same crossing test over the other shells' triangles.
        p = int(reps[s])
        wind[s] = sum(
            ray_crossing(v, p, int(a), int(b), int(c))
            for (a, b, c), g in zip(t.tolist(), shell.tolist(), strict=True)
            if g != s
        )
    return first_tri, reps, wind


def check_shells(v: Floats, t: Ints, shell: Ints, nshells: int) -> None:
    """Refuse shells whose orientation contradicts their nesting (an inverted solid, an outward cavity).

    Raises
    ------
    InvalidGeometryError
        Naming the shell (a triangle and a vertex of it) and what is wrong.
    """
    signs = volume_signs(v, t, shell, nshells)
    first_tri, reps, wind = shell_windings(v, t, shell, nshells)
    for s in np.argsort(first_tri, kind="stable").tolist():
        o, w = int(signs[s]), int(wind[s])
        where = f"the shell of triangle {int(first_tri[s])} (vertex {fmt_point(v[reps[s]])})"
        if (o, w) in ((1, 0), (-1, 1)):
            continue
        if o == 0:
            raise InvalidGeometryError(f"{where} encloses no volume")
        if w == 0:
            raise InvalidGeometryError(
                f"{where} is inside out: its triangles face inward although it is not inside another shell "
                "(orient them counter-clockwise seen from outside, or use repair())"
            )
        if w == 1:
            raise InvalidGeometryError(
                f"{where} lies inside the solid but faces outward: a cavity's triangles must face into "
                "the cavity (flip them), or the shell is a second solid inside the first"
            )
        raise InvalidGeometryError(f"{where} is nested {abs(w)} levels deep with the wrong orientation")


__all__ = ["check_shells", "ray_crossing", "shell_windings", "volume_signs"]
