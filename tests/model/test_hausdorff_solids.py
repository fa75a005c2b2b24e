"""The measured error in 3D: a certified interval for the Hausdorff distance between two filled solids.

Closed forms are checked exactly (the bounds squared as Fractions against the integer squares of the true
values); random voxel objects' reconstructions against a brute-force reference written here (winding
numbers and point–triangle distances in numpy over a dense sample of A): the sampled maximum is a lower
bound of the true value, so the certified upper bound must not fall below it.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import Cancelled, ParameterError
from mrm.core.progress import Progress
from mrm.geometry.hausdorff import _solids_kernels as K
from mrm.geometry.hausdorff.solids import SolidHausdorff, solid_hausdorff
from mrm.geometry.reconstruct.safety_net_3d import safety_net_3d

# Triangles of a box whose vertex i is (x[i & 1], y[i >> 1 & 1], z[i >> 2]), counter-clockwise from outside.
_BOX_TRIS = np.array(
    [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
     (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)],
    dtype=np.int64,
)  # fmt: skip


def box(lo: tuple[float, float, float], hi: tuple[float, float, float]) -> tuple[np.ndarray, np.ndarray]:
    v = np.array(
        [[(lo, hi)[i & 1][0], (lo, hi)[i >> 1 & 1][1], (lo, hi)[i >> 2][2]] for i in range(8)], float
    )
    return v, _BOX_TRIS.copy()


def with_cavity(outer: tuple, inner: tuple) -> tuple[np.ndarray, np.ndarray]:
    """A box with a box-shaped cavity: the cavity's triangles face into it (reversed)."""
    vo, to = box(*outer)
    vi, ti = box(*inner)
    return np.vstack([vo, vi]), np.vstack([to, ti[:, ::-1] + 8])


def octahedron(r: float) -> tuple[np.ndarray, np.ndarray]:
    v = np.array([[r, 0, 0], [-r, 0, 0], [0, r, 0], [0, -r, 0], [0, 0, r], [0, 0, -r]], float)
    tris = []
    for sx, ix in ((1, 0), (-1, 1)):
        for sy, iy in ((1, 2), (-1, 3)):
            for sz, iz in ((1, 4), (-1, 5)):
                t = (ix, iy, iz)
                tris.append(t if sx * sy * sz > 0 else (ix, iz, iy))
    return v, np.array(tris, np.int64)


def brackets(interval: tuple[float, float], square: Fraction | int) -> bool:
    """lo ≤ √square ≤ hi, decided exactly."""
    lo, hi = interval
    return Fraction(lo) ** 2 <= square <= Fraction(hi) ** 2 and 0 <= lo <= hi


def tolerance_of(*meshes: tuple[np.ndarray, np.ndarray]) -> float:
    pts = np.vstack([m[0] for m in meshes])
    return max(1e-6 * float(np.linalg.norm(pts.max(axis=0) - pts.min(axis=0))), 1e-9)


def assert_tight(r: SolidHausdorff, tol: float) -> None:
    assert r.stopped == "tolerance"
    assert r.a_within[1] - r.a_within[0] <= tol
    assert r.b_within[1] - r.b_within[0] <= tol


# ------------------------------------------------------------------------------------------ closed forms
def test_two_boxes_maxima_at_corners_are_measured_within_tolerance() -> None:
    a = box((0, 0, 0), (2, 2, 2))
    b = box((1, 1, 1), (3, 4, 3))
    r = solid_hausdorff(*a, *b)
    # h(A, B): A's corner (0, 0, 0) is √(1 + 1 + 1) from B's corner (1, 1, 1); h(B, A): B's corner (3, 4, 3)
    # is √(1 + 4 + 1) from A's corner (2, 2, 2).
    assert brackets(r.a_within, 3)
    assert brackets(r.b_within, 6)
    assert brackets(r.value, 6)
    assert_tight(r, tolerance_of(a, b))


def test_a_cube_inside_its_enlargement_is_exactly_zero_one_way_and_the_corner_offset_the_other() -> None:
    a = box((-1, -1, -1), (1, 1, 1))
    b = box((-1.25, -1.25, -1.25), (1.25, 1.25, 1.25))
    r = solid_hausdorff(*a, *b)
    assert r.a_within == (0.0, 0.0)  # A ⊆ B, proved: no interval around 0
    assert brackets(r.b_within, Fraction(3, 16))  # (0.25·√3)²
    assert_tight(r, tolerance_of(a, b))
    assert not r.exact


def test_concentric_octahedra_are_a_vertex_gap_apart_not_the_face_gap() -> None:
    # |x|+|y|+|z| ≤ 1 inside ≤ 3/2. Parallel faces are (r' − r)/√3 apart, but B's vertex (3/2, 0, 0) is
    # r' − r = 1/2 from A (its nearest point is A's vertex (1, 0, 0)): h(B, A) = 1/2.
    a = octahedron(1.0)
    b = octahedron(1.5)
    r = solid_hausdorff(*a, *b)
    assert r.a_within == (0.0, 0.0)
    assert brackets(r.b_within, Fraction(1, 4))
    assert r.b_within[0] > 0.5 / math.sqrt(3) + 0.1
    assert_tight(r, tolerance_of(a, b))


def test_a_filled_box_is_farthest_from_a_box_with_a_cavity_at_the_cavitys_centre() -> None:
    # Every vertex of the filled box lies on the hollow one (distance 0): sampling vertices gives 0. The
    # maximum is inside A, at the cavity's centre, 1 from the cavity's walls.
    filled = box((0, 0, 0), (4, 4, 4))
    hollow = with_cavity(((0, 0, 0), (4, 4, 4)), ((1, 1, 1), (3, 3, 3)))
    r = solid_hausdorff(*filled, *hollow)
    assert brackets(r.a_within, 1)
    # The hollow box lies in the filled one and shares its whole outer boundary: 0, within the tolerance
    # (the shared faces, edges and corners do not stall the search).
    assert r.b_within[0] == 0.0
    assert_tight(r, tolerance_of(filled, hollow))


def test_a_cavity_that_another_solid_fills_counts_in_both_orders_of_shells() -> None:
    hollow = with_cavity(((0, 0, 0), (4, 4, 4)), ((1, 1, 1), (3, 3, 3)))
    v, t = hollow
    swapped = (v, np.vstack([t[12:], t[:12]]))  # the cavity's shell first
    r = solid_hausdorff(*box((0, 0, 0), (4, 4, 4)), *swapped)
    assert brackets(r.a_within, 1)


def test_disjoint_solids_are_measured_between_their_far_corners() -> None:
    a = box((0, 0, 0), (1, 1, 1))
    b = box((2, 3, 2), (3, 4, 3))
    r = solid_hausdorff(*a, *b)
    # A's corner (0, 0, 0) to B's (2, 3, 2): √17; B's (3, 4, 3) to A's (1, 1, 1): √17.
    assert brackets(r.a_within, 17)
    assert brackets(r.b_within, 17)
    assert_tight(r, tolerance_of(a, b))


def test_a_solid_against_itself_is_exactly_zero() -> None:
    a = with_cavity(((0, 0, 0), (4, 4, 4)), ((1, 1, 1), (3, 3, 3)))
    r = solid_hausdorff(*a, *a)
    assert r.value == (0.0, 0.0)
    assert r.exact


def test_empty_solids() -> None:
    empty = (np.zeros((0, 3)), np.zeros((0, 3), np.int64))
    a = box((0, 0, 0), (1, 1, 1))
    r = solid_hausdorff(*empty, *a)
    assert r.a_within == (0.0, 0.0)
    assert r.b_within == (math.inf, math.inf)
    assert r.value == (math.inf, math.inf)
    r = solid_hausdorff(*a, *empty)
    assert r.value == (math.inf, math.inf)
    r = solid_hausdorff(*empty, *empty)
    assert r.value == (0.0, 0.0)
    assert r.exact


def test_hostile_parameters_are_refused_in_one_line() -> None:
    a = box((0, 0, 0), (1, 1, 1))
    with pytest.raises(ParameterError, match="vertex_error"):
        solid_hausdorff(*a, *a, vertex_error=-1.0)
    with pytest.raises(ParameterError, match="tolerance"):
        solid_hausdorff(*a, *a, tolerance=math.nan)
    with pytest.raises(ParameterError, match="finite"):
        solid_hausdorff(np.full((8, 3), math.inf), _BOX_TRIS, *a)
    with pytest.raises(ParameterError, match="does not exist"):
        solid_hausdorff(a[0], a[1] + 1, *a)
    with pytest.raises(ParameterError, match="magnitude"):
        solid_hausdorff(a[0] * 2.0**60, a[1], *a)


def voxel_ball(n: int) -> np.ndarray:
    zz, yy, xx = np.mgrid[:n, :n, :n].astype(float)
    c = (n - 1) / 2
    return (xx - c) ** 2 + (yy - c) ** 2 + (zz - c) ** 2 <= (0.45 * n) ** 2


def test_a_one_voxel_cavity_of_a_reconstructed_ball_is_measured_at_its_centre() -> None:
    # R(A) of a ball with one voxel removed has a cube-shaped cavity of half-side 3/4 (the voxel grown by
    # the ¼ erosion of the safety net): the ball without the hole reaches 3/4 outside it, at the cavity's
    # centre, while every vertex of the full ball is on the holed one's surface or inside it.
    full = voxel_ball(12)
    holed = full.copy()
    holed[5, 5, 5] = False
    a = solid_of(full, (0, 0, 0))
    b = solid_of(holed, (0, 0, 0))
    r = solid_hausdorff(*a, *b)
    assert brackets(r.a_within, Fraction(9, 16))
    assert r.b_within == (0.0, 0.0)  # the holed ball lies in the full one; their outer surfaces coincide
    assert_tight(r, tolerance_of(a, b))


def test_a_reconstructed_ball_and_its_translate_close_at_the_tolerance() -> None:
    # Every face of the staircase that faces the shift is exactly 1 away: the maximum is spread over whole
    # faces and along their edges, where neither vertex sampling nor d(c, B) + r settles anything.
    ball = voxel_ball(12)
    a = solid_of(ball, (0, 0, 0))
    b = solid_of(ball, (1, 0, 0))
    r = solid_hausdorff(*a, *b)
    assert brackets(r.a_within, 1)
    assert brackets(r.b_within, 1)
    assert_tight(r, tolerance_of(a, b))


def test_a_voxel_object_inside_another_sharing_concave_edges_is_exactly_zero_away() -> None:
    # B: a 4³ block with a 2³ notch (concave edges and a concave corner); A: B without a row and a voxel.
    # Their reconstructions share faces triangulated differently and the notch's concave edges, where
    # neither the convex certificate nor equal triangles apply: the axis-aligned boxes settle them.
    big = np.ones((4, 4, 4), bool)
    big[2:, 2:, 2:] = False
    small = big.copy()
    small[0, 0, :] = False
    small[3, 0, 0] = False
    a = solid_of(small, (0, 0, 0))
    b = solid_of(big, (0, 0, 0))
    r = solid_hausdorff(*a, *b)
    assert r.a_within == (0.0, 0.0)
    assert r.stopped == "tolerance"
    assert r.b_within[1] >= sampled_max(b, a, 0.25)


def test_progress_is_reported_and_a_cancel_stops_the_measure() -> None:
    a = box((0, 0, 0), (4, 4, 4))
    b = with_cavity(((0, 0, 0), (4, 4, 4)), ((1, 1, 1), (3, 3, 3)))
    seen: list[float | None] = []
    progress = Progress(lambda f, _m: seen.append(f))
    solid_hausdorff(*a, *b, progress=progress)
    assert seen and seen[-1] == 1.0
    cancelled = Progress()
    cancelled.cancel()
    with pytest.raises(Cancelled):
        solid_hausdorff(*a, *b, progress=cancelled)


# ------------------------------------------------------------------------------------------ vertex error
def test_vertex_error_widens_the_interval_to_cover_the_true_solids() -> None:
    # The true solids are the boxes; the given ones have every vertex moved by up to e in each coordinate.
    e = 0.01
    rng = np.random.default_rng(3)
    true_a = box((0, 0, 0), (2, 2, 2))
    true_b = box((1, 1, 1), (3, 4, 3))
    given_a = (true_a[0] + rng.uniform(-e, e, (8, 3)), true_a[1])
    given_b = (true_b[0] + rng.uniform(-e, e, (8, 3)), true_b[1])
    plain = solid_hausdorff(*given_a, *given_b)
    wide = solid_hausdorff(*given_a, *given_b, vertex_error=e)
    w = 2 * math.sqrt(3) * e
    assert wide.a_within[0] <= plain.a_within[0] - w
    assert wide.a_within[1] >= plain.a_within[1] + w
    assert brackets(wide.a_within, 3)
    assert brackets(wide.b_within, 6)
    assert not wide.exact


# ------------------------------------------------------------------------------ the distance enclosure
def exact_square_distance(q: np.ndarray, tri: np.ndarray) -> Fraction:
    """The exact squared distance from q to the triangle (Fractions of the float coordinates)."""
    p = [tuple(Fraction(float(x)) for x in row) for row in tri]
    qq = tuple(Fraction(float(x)) for x in q)

    def sub(u: tuple, v: tuple) -> tuple:
        return tuple(x - y for x, y in zip(u, v, strict=True))

    def dot(u: tuple, v: tuple) -> Fraction:
        return sum((x * y for x, y in zip(u, v, strict=True)), Fraction(0))

    def cross(u: tuple, v: tuple) -> tuple:
        return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])

    best = None
    for i in range(3):
        a, b = p[i], p[(i + 1) % 3]
        e = sub(b, a)
        ee = dot(e, e)
        t = Fraction(0) if ee == 0 else min(max(dot(sub(qq, a), e) / ee, Fraction(0)), Fraction(1))
        w = sub(qq, tuple(x + t * y for x, y in zip(a, e, strict=True)))
        best = dot(w, w) if best is None else min(best, dot(w, w))
    n = cross(sub(p[1], p[0]), sub(p[2], p[0]))
    nn = dot(n, n)
    if nn > 0 and all(dot(cross(sub(p[(i + 1) % 3], p[i]), sub(qq, p[i])), n) >= 0 for i in range(3)):
        best = min(best, dot(sub(qq, p[0]), n) ** 2 / nn)
    assert best is not None
    return best


# The solids' coordinates are 0 or of magnitude in [2⁻²⁴⁰, 2⁵⁰] (checked at the entry).
coords = st.floats(-64, 64, allow_nan=False, allow_subnormal=False).filter(
    lambda x: x == 0 or abs(x) >= 2.0**-240
)


@settings(max_examples=300, deadline=None)
@given(
    st.lists(st.tuples(coords, coords, coords), min_size=4, max_size=4),
    st.floats(0, 1),
    st.integers(0, 60),
)
def test_point_triangle_enclosures_contain_the_exact_distance(pts: list, slant: float, flat: int) -> None:
    # Slivers too: the third vertex is pulled towards the first edge by 2^-flat of the way.
    q, a, b, c = (np.array(x, float) for x in pts)
    c = a + slant * (b - a) + (c - a) * 2.0**-flat
    tri = np.vstack([a, b, c])
    big = float(np.abs(np.vstack([tri, q])).max())
    lo, hi = K.tri_dist(q[0], q[1], q[2], tri, np.array([[0, 1, 2]], np.int64), 0, K.ABS * big)
    d2 = exact_square_distance(q, tri)
    assert Fraction(lo) ** 2 <= d2 <= Fraction(hi) ** 2


# ------------------------------------------------------------------------------------ brute-force reference
def _winding(points: np.ndarray, v: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Generalized winding numbers (Van Oosterom–Strackee solid angles), ≈ 1 inside and ≈ 0 outside."""
    a = v[t[:, 0]][None] - points[:, None]
    b = v[t[:, 1]][None] - points[:, None]
    c = v[t[:, 2]][None] - points[:, None]
    la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
    num = np.einsum("pti,pti->pt", a, np.cross(b, c))
    den = la * lb * lc + np.einsum("pti,pti->pt", a, b) * lc
    den += np.einsum("pti,pti->pt", b, c) * la + np.einsum("pti,pti->pt", c, a) * lb
    return np.arctan2(num, den).sum(axis=1) / (2 * math.pi)


def _point_triangle(p: np.ndarray, v: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Distances from one point to every triangle: the plane when the projection is inside, else edges."""
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1)[:, None]
    s = np.einsum("ti,ti->t", p - a, n)
    q = p - s[:, None] * n
    inside = np.ones(len(t), bool)
    for x, y in ((a, b), (b, c), (c, a)):
        inside &= np.einsum("ti,ti->t", np.cross(y - x, q - x), n) >= 0
    best = np.where(inside, np.abs(s), np.inf)
    for x, y in ((a, b), (b, c), (c, a)):
        e = y - x
        u = np.clip(np.einsum("ti,ti->t", p - x, e) / np.einsum("ti,ti->t", e, e), 0, 1)
        best = np.minimum(best, np.linalg.norm(x + u[:, None] * e - p, axis=1))
    return best


def sampled_max(a: tuple[np.ndarray, np.ndarray], b: tuple[np.ndarray, np.ndarray], step: float) -> float:
    """max d(x, B) over A's vertices and the grid points of A (a lower bound of h(A, B))."""
    va, ta = a
    vb, tb = b
    lo, hi = va.min(axis=0), va.max(axis=0)
    axes = [np.arange(lo[i] + step / 3, hi[i], step) for i in range(3)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    wa = _winding(grid, va, ta)
    pts = np.vstack([va, grid[wa > 0.9]])
    wb = _winding(pts, vb, tb)
    best = 0.0
    for p, w in zip(pts, wb, strict=True):
        if w > 0.5:
            continue  # inside B: distance 0
        best = max(best, float(_point_triangle(p, vb, tb).min()))
    return best


masks = st.tuples(st.integers(1, 3), st.integers(1, 3), st.integers(1, 3)).flatmap(
    lambda s: st.lists(st.booleans(), min_size=s[0] * s[1] * s[2], max_size=s[0] * s[1] * s[2]).map(
        lambda bits: np.array(bits, bool).reshape(s)
    )
)


def solid_of(mask: np.ndarray, origin: tuple[int, int, int]) -> tuple[np.ndarray, np.ndarray]:
    # The safety net (V(A) eroded by ¼): solids whose faces lie on a few planes, shared between masks that
    # share voxels — the hard cases of the measure (R itself simplifies them away).
    net = safety_net_3d(mask, origin)
    return net.vertices, net.triangles


@settings(max_examples=25, deadline=None)
@given(
    masks.filter(lambda m: m.any()),
    masks.filter(lambda m: m.any()),
    st.tuples(st.integers(-1, 1), st.integers(-1, 1), st.integers(-1, 1)),
)
def test_reconstructions_pairwise_bracket_a_dense_sample(
    m1: np.ndarray, m2: np.ndarray, shift: tuple
) -> None:
    a = solid_of(m1, (0, 0, 0))
    b = solid_of(m2, shift)
    r = solid_hausdorff(*a, *b, cell_budget=20_000)
    slack = 1e-9
    for (lo, hi), ref in ((r.a_within, sampled_max(a, b, 0.25)), (r.b_within, sampled_max(b, a, 0.25))):
        assert 0.0 <= lo <= hi
        assert hi >= ref - slack
    if r.stopped == "tolerance":
        tol = tolerance_of(a, b)
        assert r.a_within[1] - r.a_within[0] <= tol
        assert r.b_within[1] - r.b_within[0] <= tol


@settings(max_examples=15, deadline=None)
@given(
    st.tuples(st.integers(1, 3), st.integers(1, 3), st.integers(1, 3)),
    st.tuples(st.integers(-3, 3), st.integers(-3, 3), st.integers(-3, 3)).filter(lambda t: all(t)),
)
def test_integer_translates_of_a_box_object_are_exactly_the_translation_apart(size: tuple, t: tuple) -> None:
    # R of a box of voxels is a box (convex): h(A, A + t) = |t|, at the corner opposite to t.
    mask = np.ones(size[::-1], bool)
    a = solid_of(mask, (0, 0, 0))
    b = solid_of(mask, t)
    r = solid_hausdorff(*a, *b)
    square = t[0] ** 2 + t[1] ** 2 + t[2] ** 2
    assert brackets(r.a_within, square)
    assert brackets(r.b_within, square)
    assert_tight(r, tolerance_of(a, b))


@settings(max_examples=15, deadline=None)
@given(masks.filter(lambda m: m.any()), st.tuples(st.integers(-2, 2), st.integers(-2, 2), st.integers(-2, 2)))
def test_a_translate_of_any_object_is_at_most_the_translation_away(m: np.ndarray, t: tuple) -> None:
    # h(A, A + t) ≤ |t| for any set (every a has a + t); the certified lower bound never exceeds it.
    a = solid_of(m, (0, 0, 0))
    b = solid_of(m, t)
    r = solid_hausdorff(*a, *b, cell_budget=20_000)
    square = t[0] ** 2 + t[1] ** 2 + t[2] ** 2
    assert Fraction(r.a_within[0]) ** 2 <= square
    assert Fraction(r.b_within[0]) ** 2 <= square
    assert r.a_within[1] >= sampled_max(a, b, 0.25) - 1e-9
