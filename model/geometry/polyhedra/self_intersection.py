"""Exact self-intersection test of a closed triangle mesh: a uniform grid over boxes, exact pair tests.

Two triangles of a valid polyhedron meet only in what they share: nothing, one common vertex, or one common
edge (docs/design.md §11). Every pair whose closed bounding boxes overlap is tested exactly with the
predicates of :mod:`~mrm.geometry.polyhedra.predicates`:

- **no common vertex**: two closed triangles meet iff an edge of one meets the other (when they meet, an end
  of their intersection lies on an edge of one of them), so six closed segment–triangle tests decide;
- **one common vertex v**, t₁ = (v, p, q), t₂ = (v, r, s): they meet beyond v iff [r, s] meets t₁ or [p, q]
  meets t₂ (a point x ≠ v in both lies on a ray from v that leaves t₂ across [r, s] and t₁ across [p, q];
  whichever exit comes first lies in the other triangle);
- **a common edge** u v: they overlap iff the other two vertices are coplanar with it and on the same side of
  it (the mesh has already been checked for consistent orientation, so the triangles fold onto each other).

A segment meets a closed triangle when its ends are not strictly on one side of the triangle's plane and
the line crosses the triangle (the three tetrahedra with the triangle's edges have no two opposite signs), or,
in the plane, by the 2-D tests on the projection on the coordinate plane where the triangle is not flat.

The geometric tests are ``register_jitable``: compiled in :func:`intersecting_pairs` (with the float-filtered
predicates), and run as plain Python with exact Fractions for the pairs a kernel could not decide (a
coordinate out of the compiled predicates' range).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from numba.extending import register_jitable

from mrm.geometry._jit import njit
from mrm.geometry.polyhedra.predicates import UNKNOWN, o2, o3

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

#: Pair test results.
DISJOINT, INTERSECT, UNDECIDED = 0, 1, UNKNOWN
#: The grid is coarsened until the triangles occupy at most this many cells each on average.
_CELLS_PER_TRIANGLE = 8
#: At most this many cells along an axis (cell keys stay far inside int64).
_MAX_AXIS_CELLS = 1 << 20


# ---------------------------------------------------------------------------------------------- 2-D tests
@register_jitable
def flat_axes(v: Floats, p: int, q: int, r: int) -> int:
    """K such that the triangle p q r projected on the axes ((k+1)%3, (k+2)%3) is not flat; -1 if unknown."""
    for k in range(3):
        s = o2(v, p, q, r, (k + 1) % 3, (k + 2) % 3)
        if s == UNKNOWN:
            return -1
        if s != 0:
            return k
    return -1  # a flat triangle: refused before any pair test


@register_jitable
def _point_in_triangle_2d(v: Floats, x: int, p: int, q: int, r: int, i: int, j: int) -> int:
    s1 = o2(v, p, q, x, i, j)
    s2 = o2(v, q, r, x, i, j)
    s3 = o2(v, r, p, x, i, j)
    if s1 == UNKNOWN or s2 == UNKNOWN or s3 == UNKNOWN:
        return UNDECIDED
    if (s1 >= 0 and s2 >= 0 and s3 >= 0) or (s1 <= 0 and s2 <= 0 and s3 <= 0):
        return INTERSECT
    return DISJOINT


@register_jitable
def _within_box(v: Floats, x: int, a: int, b: int, i: int, j: int) -> bool:
    """For x collinear with a, b (in projection): True when x is on the closed segment a b."""
    for k in (i, j):
        lo = min(v[a, k], v[b, k])
        hi = max(v[a, k], v[b, k])
        if v[x, k] < lo or v[x, k] > hi:
            return False
    return True


@register_jitable
def _segments_meet_2d(v: Floats, a: int, b: int, c: int, d: int, i: int, j: int) -> int:
    d1 = o2(v, a, b, c, i, j)
    d2 = o2(v, a, b, d, i, j)
    d3 = o2(v, c, d, a, i, j)
    d4 = o2(v, c, d, b, i, j)
    if d1 == UNKNOWN or d2 == UNKNOWN or d3 == UNKNOWN or d4 == UNKNOWN:
        return UNDECIDED
    if d1 * d2 < 0 and d3 * d4 < 0:
        return INTERSECT
    if (
        (d1 == 0 and _within_box(v, c, a, b, i, j))
        or (d2 == 0 and _within_box(v, d, a, b, i, j))
        or (d3 == 0 and _within_box(v, a, c, d, i, j))
        or (d4 == 0 and _within_box(v, b, c, d, i, j))
    ):
        return INTERSECT
    return DISJOINT


@register_jitable
def _segment_meets_triangle_2d(v: Floats, a: int, b: int, p: int, q: int, r: int, i: int, j: int) -> int:
    s = _point_in_triangle_2d(v, a, p, q, r, i, j)
    if s != DISJOINT:
        return s
    s = _point_in_triangle_2d(v, b, p, q, r, i, j)
    if s != DISJOINT:
        return s
    s = _segments_meet_2d(v, a, b, p, q, i, j)
    if s != DISJOINT:
        return s
    s = _segments_meet_2d(v, a, b, q, r, i, j)
    if s != DISJOINT:
        return s
    return _segments_meet_2d(v, a, b, r, p, i, j)


@register_jitable
def _segment_meets_triangle_in_plane(v: Floats, a: int, b: int, p: int, q: int, r: int) -> int:
    k = flat_axes(v, p, q, r)
    if k < 0:
        return UNDECIDED
    return _segment_meets_triangle_2d(v, a, b, p, q, r, (k + 1) % 3, (k + 2) % 3)


@register_jitable
def _ray_in_cone(v: Floats, o: int, p: int, q: int, sp: int, x: int, i: int, j: int) -> int:
    """Whether the ray o→x lies in the closed cone at o spanned by o→p and o→q (orientation sp ≠ 0)."""
    s1 = o2(v, o, p, x, i, j)
    s2 = o2(v, o, x, q, i, j)
    if s1 == UNKNOWN or s2 == UNKNOWN:
        return UNDECIDED
    return INTERSECT if s1 * sp >= 0 and s2 * sp >= 0 else DISJOINT


@register_jitable
def _beyond_an_edge(
    v: Floats, p0: int, p1: int, p2: int, sp: int, q0: int, q1: int, q2: int, i: int, j: int
) -> bool:
    """Whether q0 q1 q2 lie strictly outside one edge line of p0 p1 p2 (of orientation sp ≠ 0)."""
    for e in range(3):
        a = p0 if e == 0 else (p1 if e == 1 else p2)
        b = p1 if e == 0 else (p2 if e == 1 else p0)
        s0 = o2(v, a, b, q0, i, j)
        if s0 == UNKNOWN or s0 * sp >= 0:
            continue
        s1 = o2(v, a, b, q1, i, j)
        if s1 == UNKNOWN or s1 * sp >= 0:
            continue
        s2 = o2(v, a, b, q2, i, j)
        if s2 != UNKNOWN and s2 * sp < 0:
            return True
    return False


@register_jitable
def _triangles_meet_in_plane(v: Floats, a0: int, a1: int, a2: int, b0: int, b1: int, b2: int) -> int:
    """Coplanar triangles without a common vertex: an edge of b meets a, or a lies inside b."""
    k = flat_axes(v, a0, a1, a2)
    if k < 0:
        return UNDECIDED
    i, j = (k + 1) % 3, (k + 2) % 3
    # Quick rejection: one triangle strictly beyond an edge line of the other (the common case for
    # neighbours in a flat region); the full test below decides the rest.
    sa = o2(v, a0, a1, a2, i, j)
    sb = o2(v, b0, b1, b2, i, j)
    if sa == UNKNOWN or sb == UNKNOWN:
        return UNDECIDED
    if _beyond_an_edge(v, a0, a1, a2, sa, b0, b1, b2, i, j) or _beyond_an_edge(
        v, b0, b1, b2, sb, a0, a1, a2, i, j
    ):
        return DISJOINT
    s = _segment_meets_triangle_2d(v, b0, b1, a0, a1, a2, i, j)
    if s != DISJOINT:
        return s
    s = _segment_meets_triangle_2d(v, b1, b2, a0, a1, a2, i, j)
    if s != DISJOINT:
        return s
    s = _segment_meets_triangle_2d(v, b2, b0, a0, a1, a2, i, j)
    if s != DISJOINT:
        return s
    return _point_in_triangle_2d(v, a0, b0, b1, b2, i, j)


# ---------------------------------------------------------------------------------------------- 3-D tests
@register_jitable
def _crossing_segment_meets_triangle(
    v: Floats, a: int, b: int, p: int, q: int, r: int, oa: int, ob: int
) -> int:
    """:func:`segment_meets_triangle` given the sides oa, ob of a and b (known, not both 0)."""
    if oa * ob > 0:
        return DISJOINT
    s1 = o3(v, a, b, p, q)
    s2 = o3(v, a, b, q, r)
    s3 = o3(v, a, b, r, p)
    if s1 == UNKNOWN or s2 == UNKNOWN or s3 == UNKNOWN:
        return UNDECIDED
    if (s1 >= 0 and s2 >= 0 and s3 >= 0) or (s1 <= 0 and s2 <= 0 and s3 <= 0):
        return INTERSECT
    return DISJOINT


@register_jitable
def segment_meets_triangle(v: Floats, a: int, b: int, p: int, q: int, r: int) -> int:
    """Whether the closed segment a b meets the closed triangle p q r: INTERSECT, DISJOINT or UNDECIDED."""
    oa = o3(v, p, q, r, a)
    ob = o3(v, p, q, r, b)
    if oa == UNKNOWN or ob == UNKNOWN:
        return UNDECIDED
    if oa == 0 and ob == 0:
        return _segment_meets_triangle_in_plane(v, a, b, p, q, r)
    return _crossing_segment_meets_triangle(v, a, b, p, q, r, oa, ob)


@register_jitable
def triangles_meet_improperly(v: Floats, t: Ints, ta: int, tb: int) -> int:
    """Whether triangles ta and tb meet beyond their common vertices and edge (module docstring)."""
    a0, a1, a2 = t[ta, 0], t[ta, 1], t[ta, 2]
    b0, b1, b2 = t[tb, 0], t[tb, 1], t[tb, 2]
    shared = 0
    for x in (a0, a1, a2):
        if x in (b0, b1, b2):
            shared += 1
    if shared == 0:
        s0 = o3(v, a0, a1, a2, b0)
        s1 = o3(v, a0, a1, a2, b1)
        s2 = o3(v, a0, a1, a2, b2)
        if s0 == UNKNOWN or s1 == UNKNOWN or s2 == UNKNOWN:
            return UNDECIDED
        if (s0 > 0 and s1 > 0 and s2 > 0) or (s0 < 0 and s1 < 0 and s2 < 0):
            return DISJOINT  # tb strictly on one side of ta's plane
        if s0 == 0 and s1 == 0 and s2 == 0:
            return _triangles_meet_in_plane(v, a0, a1, a2, b0, b1, b2)
        r0 = o3(v, b0, b1, b2, a0)
        r1 = o3(v, b0, b1, b2, a1)
        r2 = o3(v, b0, b1, b2, a2)
        if r0 == UNKNOWN or r1 == UNKNOWN or r2 == UNKNOWN:
            return UNDECIDED
        if (r0 > 0 and r1 > 0 and r2 > 0) or (r0 < 0 and r1 < 0 and r2 < 0):
            return DISJOINT
        # Not coplanar: an edge of one meets the other; every side needed is known already.
        sa = (r0, r1, r2)
        sb = (s0, s1, s2)
        for e in range(3):
            f = (e + 1) % 3
            if not (sa[e] == 0 and sa[f] == 0):
                s = _crossing_segment_meets_triangle(v, t[ta, e], t[ta, f], b0, b1, b2, sa[e], sa[f])
                if s != DISJOINT:
                    return s
            if not (sb[e] == 0 and sb[f] == 0):
                s = _crossing_segment_meets_triangle(v, t[tb, e], t[tb, f], a0, a1, a2, sb[e], sb[f])
                if s != DISJOINT:
                    return s
            # An edge lying in the other's plane (the planes differ): the line where they meet is that
            # edge's line, and the other triangle's edges crossing it are tested from the other side.
        return DISJOINT
    if shared == 1:
        # Rotate both so that the common vertex comes first (rotation keeps the orientation).
        while a0 != b0 and a0 != b1 and a0 != b2:
            a0, a1, a2 = a1, a2, a0
        while b0 != a0:
            b0, b1, b2 = b1, b2, b0
        s1 = o3(v, a0, a1, a2, b1)
        s2 = o3(v, a0, a1, a2, b2)
        if s1 == UNKNOWN or s2 == UNKNOWN:
            return UNDECIDED
        if s1 == 0 and s2 == 0:  # coplanar: both tests in the plane, with one projection
            k = flat_axes(v, a0, a1, a2)
            if k < 0:
                return UNDECIDED
            # Near v each triangle is its angle (a convex cone under 180°): they meet beyond v iff the
            # cones do, iff a side ray of one lies in the other (closed) cone.
            i, j = (k + 1) % 3, (k + 2) % 3
            turn_a = o2(v, a0, a1, a2, i, j)
            turn_b = o2(v, b0, b1, b2, i, j)
            if turn_a == UNKNOWN or turn_b == UNKNOWN:
                return UNDECIDED
            for x in (b1, b2):
                s = _ray_in_cone(v, a0, a1, a2, turn_a, x, i, j)
                if s != DISJOINT:
                    return s
            for x in (a1, a2):
                s = _ray_in_cone(v, b0, b1, b2, turn_b, x, i, j)
                if s != DISJOINT:
                    return s
            return DISJOINT
        s = _crossing_segment_meets_triangle(v, b1, b2, a0, a1, a2, s1, s2)
        if s != DISJOINT:
            return s
        return segment_meets_triangle(v, a1, a2, b0, b1, b2)
    if shared == 2:
        # a0 a1 a2 rotated so that a2 is the vertex not in tb; q is tb's vertex not in ta.
        while a2 in (b0, b1, b2):
            a0, a1, a2 = a1, a2, a0
        q = b0
        if b1 != a0 and b1 != a1:
            q = b1
        elif b2 != a0 and b2 != a1:
            q = b2
        s = o3(v, a0, a1, a2, q)
        if s == UNKNOWN:
            return UNDECIDED
        if s != 0:
            return DISJOINT
        k = flat_axes(v, a0, a1, a2)
        if k < 0:
            return UNDECIDED
        i, j = (k + 1) % 3, (k + 2) % 3
        sp = o2(v, a0, a1, a2, i, j)
        sq = o2(v, a0, a1, q, i, j)
        if sp == UNKNOWN or sq == UNKNOWN:
            return UNDECIDED
        return INTERSECT if sp == sq else DISJOINT
    return INTERSECT  # the same three vertices twice


# ---------------------------------------------------------------------------------------------- the grid
@njit(cache=True)
def _cell_ranges(lo: Floats, hi: Floats, origin: Floats, h: float, c0: Ints, c1: Ints) -> float:
    """Cells of every box (floor((x − origin)/h), monotone in x); returns the total count (as a float)."""
    total = 0.0
    for t in range(lo.shape[0]):
        n = 1.0
        for k in range(3):
            c0[t, k] = math.floor((lo[t, k] - origin[k]) / h)
            c1[t, k] = math.floor((hi[t, k] - origin[k]) / h)
            n *= c1[t, k] - c0[t, k] + 1
        total += n
    return total


@njit(cache=True)
def _cell_entries(c0: Ints, c1: Ints, dims: Ints, total: int) -> tuple[Ints, Ints]:
    keys = np.empty(total, np.int64)
    tris = np.empty(total, np.int64)
    n = 0
    for t in range(c0.shape[0]):
        for z in range(c0[t, 2], c1[t, 2] + 1):
            for y in range(c0[t, 1], c1[t, 1] + 1):
                for x in range(c0[t, 0], c1[t, 0] + 1):
                    keys[n] = (z * dims[1] + y) * dims[0] + x
                    tris[n] = t
                    n += 1
    return keys, tris


@njit(cache=True)
def _test_cells(
    v: Floats, t: Ints, lo: Floats, hi: Floats, c0: Ints, keys: Ints, tris: Ints, dims: Ints
) -> tuple[int, int, Ints]:
    """Test every candidate pair once (in the first cell both boxes share); the least intersecting pair.

    Returns (a, b, undecided): the intersecting pair with the smallest (a, b), a < b, or (-1, -1), and the
    pairs the compiled predicates could not decide, as a flat array a0, b0, a1, b1, ...
    """
    best_a, best_b = -1, -1
    undecided = np.empty(64, np.int64)
    nu = 0
    n = keys.shape[0]
    # The boxes and first cells copied in entry order: the double loop below then reads memory
    # sequentially instead of jumping across the triangle arrays (cache misses were most of its time).
    box = np.empty((n, 9))
    for e in range(n):
        f = tris[e]
        for k in range(3):
            box[e, k] = lo[f, k]
            box[e, 3 + k] = hi[f, k]
            box[e, 6 + k] = c0[f, k]
    start = 0
    while start < n:
        end = start + 1
        while end < n and keys[end] == keys[start]:
            end += 1
        key = keys[start]
        cx = key % dims[0]
        cy = (key // dims[0]) % dims[1]
        cz = key // (dims[0] * dims[1])
        for ii in range(start, end):
            for jj in range(ii + 1, end):
                if (
                    box[ii, 0] > box[jj, 3]
                    or box[jj, 0] > box[ii, 3]
                    or box[ii, 1] > box[jj, 4]
                    or box[jj, 1] > box[ii, 4]
                    or box[ii, 2] > box[jj, 5]
                    or box[jj, 2] > box[ii, 5]
                ):
                    continue
                # Tested only in the first cell the two boxes share, so every pair is tested once.
                if (
                    max(box[ii, 6], box[jj, 6]) != cx
                    or max(box[ii, 7], box[jj, 7]) != cy
                    or max(box[ii, 8], box[jj, 8]) != cz
                ):
                    continue
                ta, tb = tris[ii], tris[jj]
                a, b = (ta, tb) if ta < tb else (tb, ta)
                if best_a >= 0 and (a > best_a or (a == best_a and b >= best_b)):
                    continue
                s = triangles_meet_improperly(v, t, a, b)
                if s == INTERSECT:
                    best_a, best_b = a, b
                elif s == UNDECIDED:
                    if nu + 2 > undecided.shape[0]:
                        grown = np.empty(2 * undecided.shape[0], np.int64)
                        grown[:nu] = undecided[:nu]
                        undecided = grown
                    undecided[nu] = a
                    undecided[nu + 1] = b
                    nu += 2
        start = end
    return best_a, best_b, undecided[:nu].copy()


def _grid(lo: Floats, hi: Floats) -> tuple[Ints, Ints, Ints, int]:
    """Cell ranges of the boxes on a grid fine enough to separate them, coarse enough to stay small."""
    m = lo.shape[0]
    if not np.isfinite(hi.max(axis=0) - lo.min(axis=0)).all():
        # Coordinates near the float64 limits: the extent overflows. The grid only needs cell indices
        # that never decrease with x, which a quarter of every coordinate still gives.
        lo, hi = lo * 0.25, hi * 0.25
    origin = lo.min(axis=0)
    span = float((hi.max(axis=0) - origin).max())
    ext = (hi - lo).max(axis=1)
    size = float(np.partition(ext, m // 2)[m // 2])  # a median that never averages (no overflow)
    h = max(2.0 * size, span / _MAX_AXIS_CELLS, np.finfo(float).tiny)
    c0 = np.empty((m, 3), np.int64)
    c1 = np.empty((m, 3), np.int64)
    while True:
        total = _cell_ranges(lo, hi, origin, h, c0, c1)
        if total <= _CELLS_PER_TRIANGLE * m + 1024:
            break
        h *= 2.0  # some large triangles: coarser cells cost fewer entries than many small ones save
    dims = c1.max(axis=0) + 1
    return c0, c1, dims.astype(np.int64), int(total)


def first_intersecting_pair(vertices: Floats, triangles: Ints) -> tuple[int, int] | None:
    """The intersecting pair of triangles (a < b) with the smallest (a, b), or None if there is none.

    ``vertices`` must be finite and distinct, ``triangles`` not flat and the mesh an oriented 2-manifold
    (checked before: the pair tests rely on it).
    """
    if triangles.shape[0] < 2:
        return None
    corners = vertices[triangles]  # (m, 3, 3)
    lo = np.ascontiguousarray(corners.min(axis=1))
    hi = np.ascontiguousarray(corners.max(axis=1))
    c0, c1, dims, total = _grid(lo, hi)
    keys, tris = _cell_entries(c0, c1, dims, total)
    order = np.argsort(keys, kind="stable")
    a, b, undecided = _test_cells(vertices, triangles, lo, hi, c0, keys[order], tris[order], dims)
    best = (int(a), int(b)) if a >= 0 else None
    for ua, ub in undecided.reshape(-1, 2).tolist():
        if best is not None and (ua, ub) >= best:
            continue
        # Plain Python on exact Fractions: the same test, never undecided.
        if triangles_meet_improperly(vertices, triangles, ua, ub) == INTERSECT:
            best = (ua, ub)
    return best


__all__ = ["first_intersecting_pair", "flat_axes", "segment_meets_triangle", "triangles_meet_improperly"]
