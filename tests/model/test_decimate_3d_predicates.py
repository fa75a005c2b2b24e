"""The exact predicates of the 3D R's checked collapses (ADR 0064) against slow references in Fractions.

- a closed triangle meets a closed or an open box: the reference clips the triangle by the box's six closed
  half-spaces (Sutherland–Hodgman in Fractions); it meets the closed box when something is left, and the open
  box when the centroid of what is left lies strictly inside (the clipped polygon is convex and lies in the
  closed box, so a point of it is interior iff its relative interior is);
- a voxel centre + τ, τ = (ε, ε², ε³), in a tetrahedron: the reference takes ε = 10⁻³⁰ (every coefficient of
  the orientation polynomial is far below 10²⁹ here, so its sign is the infinitesimal's) and tests the four
  orientations with Fractions;
- a centre on a closed triangle, and the slab that the scans visit (no centre of a tetrahedron is missed).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.geometry.reconstruct import decimate_3d as D

coord = st.integers(-12, 12)
point = st.tuples(coord, coord, coord)
small = st.tuples(*(st.integers(-5, 5),) * 3)  # where a brute force over the box is the reference
quarters = st.tuples(*(st.integers(-24, 24),) * 3)  # corners in quarter voxels, anywhere in (¼Z)³


def clip(
    poly: list[tuple[Fraction, ...]], axis: int, bound: int, keep_below: bool
) -> list[tuple[Fraction, ...]]:
    def inside(p: tuple[Fraction, ...]) -> bool:
        return p[axis] <= bound if keep_below else p[axis] >= bound

    out: list[tuple[Fraction, ...]] = []
    for i, cur in enumerate(poly):
        prev = poly[i - 1]
        if inside(cur):
            if not inside(prev):
                out.append(cross(prev, cur, axis, bound))
            out.append(cur)
        elif inside(prev):
            out.append(cross(prev, cur, axis, bound))
    return out


def cross(a: tuple[Fraction, ...], b: tuple[Fraction, ...], axis: int, bound: int) -> tuple[Fraction, ...]:
    s = (Fraction(bound) - a[axis]) / (b[axis] - a[axis])
    return tuple(a[k] + s * (b[k] - a[k]) for k in range(3))


def reference_meets(tri: np.ndarray, lo: np.ndarray, hi: np.ndarray, open_box: bool) -> bool:
    poly = [tuple(Fraction(int(x)) for x in p) for p in tri]
    for axis in range(3):
        poly = clip(poly, axis, int(lo[axis]), keep_below=False)
        poly = clip(poly, axis, int(hi[axis]), keep_below=True)
        if not poly:
            return False
    if not open_box:
        return True
    c = [sum(p[k] for p in poly) / len(poly) for k in range(3)]
    return all(lo[k] < c[k] < hi[k] for k in range(3))


@settings(max_examples=1500, deadline=None)
@given(point, point, point, point, st.integers(1, 6), st.booleans())
def test_a_triangle_meets_a_box_exactly_as_the_clipping_reference_says(a, b, c, corner, size, open_box):
    tri = np.array([a, b, c], np.int64)
    lo = np.array(corner, np.int64)
    hi = lo + size
    got = D._triangle_meets_box(tri, lo, hi, open_box)
    assert got == reference_meets(tri, lo, hi, open_box)


EPS = Fraction(1, 10**30)


def orient(a, b, c, d) -> Fraction:
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    w = [d[k] - a[k] for k in range(3)]
    return (
        u[0] * (v[1] * w[2] - v[2] * w[1])
        - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
    )


def reference_holds(q: np.ndarray, p: tuple[int, int, int]) -> bool:
    t = [tuple(Fraction(int(x)) for x in row) for row in q]
    x = (p[0] + EPS, p[1] + EPS**2, p[2] + EPS**3)
    for f in range(4):
        a, b, c, d = t[(f + 1) % 4], t[(f + 2) % 4], t[(f + 3) % 4], t[f]
        if (orient(a, b, c, d) > 0) != (orient(a, b, c, x) > 0):
            return False
    return True


@settings(max_examples=1500, deadline=None)
@given(point, point, point, point, point)
def test_a_centre_plus_tau_is_in_a_tetrahedron_exactly_as_the_fraction_reference_says(a, b, c, d, p):
    q = np.array([a, b, c, d], np.int64)
    if orient(*[tuple(Fraction(int(x)) for x in row) for row in q]) == 0:
        return  # a flat tetrahedron is never asked about
    assert D._tet_holds(q, 0, 1, 2, 3, *p) == reference_holds(q, p)


def centres_in_box_held(q: np.ndarray) -> set[tuple[int, int, int]]:
    """The brute force: every centre of the tetrahedron's box that the Fraction reference puts inside."""
    lo = (q.min(axis=0) + 3) // 4
    hi = q.max(axis=0) // 4
    return {
        (x, y, z)
        for x in range(lo[0], hi[0] + 1)
        for y in range(lo[1], hi[1] + 1)
        for z in range(lo[2], hi[2] + 1)
        if reference_holds(q, (4 * x, 4 * y, 4 * z))
    }


@settings(max_examples=300, deadline=None)
@given(small, small, small, small)
def test_the_slab_scan_lists_every_centre_in_a_tetrahedron(a, b, c, d):
    # The scan visits only the slab between the base's plane and the apex; the brute force visits the box.
    q = 4 * np.array([a, b, c, d], np.int64) + np.array([1, 3, 1])  # vertices in Z + {1/4, 3/4}, like R's
    if orient(*[tuple(Fraction(int(x)) for x in row) for row in q]) == 0:
        return
    out = np.empty((4096, 3), np.int64)
    m = D._tet_centres(q, 0, 1, 2, 3, out, *(np.empty(3, np.int64) for _ in range(3)), False)
    brute = centres_in_box_held(q)
    assert m >= 0 and {tuple(int(v) for v in row) for row in out[:m]} == brute


@settings(max_examples=300, deadline=None)
@given(quarters, quarters, quarters, quarters)
def test_the_shadow_scan_lists_every_centre_in_a_tetrahedron_with_corners_on_any_quarter(a, b, c, d):
    # New vertices lie anywhere in (¼Z)³, on the centres' own lines too: the scan keeps to the tetrahedron's
    # shadow, row by row, and must still find every centre the brute force finds in the box; with first_only
    # it stops at one of them.
    q = np.array([a, b, c, d], np.int64)
    if orient(*[tuple(Fraction(int(x)) for x in row) for row in q]) == 0:
        return
    out = np.empty((4096, 3), np.int64)
    m = D._tet_centres(q, 0, 1, 2, 3, out, *(np.empty(3, np.int64) for _ in range(3)), False)
    brute = centres_in_box_held(q)
    assert m >= 0 and {tuple(int(v) for v in row) for row in out[:m]} == brute
    first = D._tet_centres(q, 0, 1, 2, 3, out, *(np.empty(3, np.int64) for _ in range(3)), True)
    assert first == min(1, len(brute))
    if first:
        assert tuple(int(v) for v in out[0]) in brute


def on_triangle(tri: np.ndarray, p: tuple[int, int, int]) -> bool:
    """The closed triangle holds p: in its plane, and on the inner side of (or on) each edge."""
    a, b, c = (np.array(v, dtype=object) for v in tri)
    x = np.array(p, dtype=object)
    n = np.cross(b - a, c - a)
    if np.dot(n, x - a) != 0:
        return False
    return all(np.dot(np.cross(e1 - e0, x - e0), n) >= 0 for e0, e1 in ((a, b), (b, c), (c, a)))


@settings(max_examples=300, deadline=None)
@given(point, point, point)
def test_a_centre_on_a_triangle_is_found_by_the_plane_scan(a, b, c):
    tri = np.array([a, b, c], np.int64) * 2  # even coordinates: centres (4·i) do land on some triangles
    n = np.cross(tri[1] - tri[0], tri[2] - tri[0])
    if not n.any():
        return
    lo, hi, idx = (np.empty(3, np.int64) for _ in range(3))
    got = D._centre_on(tri, lo, hi, idx)
    lo_i = (tri.min(axis=0) + 3) // 4
    hi_i = tri.max(axis=0) // 4
    brute = any(
        on_triangle(tri, (4 * x, 4 * y, 4 * z))
        for x in range(lo_i[0], hi_i[0] + 1)
        for y in range(lo_i[1], hi_i[1] + 1)
        for z in range(lo_i[2], hi_i[2] + 1)
    )
    assert got == brute


@settings(max_examples=300, deadline=None)
@given(small, small, small, st.integers(0, 2**32 - 1))
def test_the_forbidden_cube_scan_finds_every_forbidden_cube_the_triangle_meets(a, b, c, seed):
    # Voxel i's cube is [4i − 2, 4i + 2]³; the scan visits the cubes its plane's slab crosses, the brute force
    # every cube of the box, each decided by the clipping reference.
    tri = 4 * (np.array([a, b, c], np.int64) + 8) + np.array([1, 3, 1])  # inside a 19³ array, off its rim
    if not np.cross(tri[1] - tri[0], tri[2] - tri[0]).any():
        return
    forbidden = np.random.default_rng(seed).random((19, 19, 19)) < 0.01  # about half the triangles meet one
    lo, hi, clo, chi, idx = (np.empty(3, np.int64) for _ in range(5))
    got = D._meets_forbidden(tri, forbidden, lo, hi, clo, chi, idx)
    brute = any(
        reference_meets(tri, 4 * np.array(i) - 2, 4 * np.array(i) + 2, False)
        for i in zip(*np.nonzero(forbidden.transpose(2, 1, 0)), strict=True)
        if all((tri[:, k].min() - 2) <= 4 * i[k] <= tri[:, k].max() + 2 for k in range(3))
    )
    assert got == brute
