"""R of a digitally convex voxel set with many facets under the covers: its core, snapped inward, with spikes.

Reference: docs/design.md §11, "Continuation R in 3D"; the decision is docs/adr/0070.

The covers' R of a lattice polytope (:func:`.convex_3d.convex_cover_r`) cuts the **core** — each facet
a·x ≤ b of Q = conv(A) moved to a·x ≤ b + ¾ − |a|₁/2, which meets no cube outside A — out of a box in
Fractions, and its corners must be float64 numbers. A ball's hull has thousands of facets: the Fractions
would take minutes, and the core's corners are rationals whose denominators are determinants of three
normals, not powers of two. So for such an A:

1. **The core's corners from its dual.** With c a lattice point strictly inside the core, the core is
   { x : 4a·(x − c) ≤ w } with w = 4b + 3 − 2|a|₁ − 4a·c > 0, an integer, for every facet. Its corners are
   the facets of the convex hull of the dual points 4a / w, which the exact quickhull of
   :mod:`.convex_3d` finds on the homogeneous integers (4a, w): each hull triangle is a corner, the
   solution of its three planes (Cramer's rule, in integers).
2. **Snapped inward.** Each corner y is replaced by the point q of the grid 2⁻ᵍ with q − c the truncation
   of y − c toward zero, checked in integers against the core's faces through y and pulled further toward c
   while outside one. P = conv(q's) (an exact hull of integer points, its coplanar triangles merged into
   faces). g is as fine as the hull's integer predicates allow (|2ᵍ (q − c)| < 2¹⁵). A snapped point lies
   within |a|₁ (pulls + 1) 2⁻ᵍ of the core in a's units, and a cube outside A a quarter beyond it, so P
   usually meets no cube outside A; whether it does is decided exactly by climbing P's edges to its
   highest corner along each facet's normal (:func:`_clear_of_outside_cubes`).
3. **Spikes.** The core may miss a few cubes of A (a ball's six tips) and P, a hair smaller, a few more.
   Each such voxel p gets a spike: a corner v of P goes to a point of p's cube on the segment v→p (a
   multiple of 1/64 of the way, a sixteenth inside), and each edge from v is cut at a point an eighth of a
   voxel or less from v, at most half way (a power of two of the way), so that the spike stays near v; the
   rest of each triangle around v stays in its face. v is the first of the four corners nearest p whose
   spike is proven (:func:`_spike_keeps_d`) and whose cone meets no other triangle; else a new corner on
   the face nearest p, or nearest a point of a neighbour of p in A a quarter from p's cube (a cone from
   there into p's cube crosses their common face only): a + s (b − a) + t (c − a) with s, t multiples of
   1/64, exactly on the face's plane, the face's triangle split in three around it.
4. **Discretized once, by rows.** A convex P's cubes in a row along x are a run whose two ends are cubes
   ∂P meets, so only the triangles are discretized (the threads share them), and each row of A (a run) is
   compared with the run between its first and last mark: the voxels of A to spike, and any cube outside
   A that P meets. Under standard the supercover is needed only when the climb of step 2 did not prove
   P ⊂ V(A).

Nothing here is assumed right: :func:`.convex_3d.convex_reconstruction` checks P as every R is checked
(valid polyhedron, D(P) = A in the model and P ⊂ V(A)), and the caller goes the general way when it fails.
Every vertex is dyadic (float64 holds it exactly). The hull and the snapping are computed in the canonical
pose of Q's corners; P is turned back before it is discretized and spiked (the standard cell is not
invariant under the rotations of the cube), the spikes keeping the turned frame's order, so R(g A) = g R(A)
for the rotations g of the cube (up to A's own symmetries, as for the general R), and R(A + t) = R(A) + t.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from itertools import combinations
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from mrm.core.errors import InvalidGeometryError
from mrm.geometry._jit import njit
from mrm.geometry.discretize.voxels import voxelize_triangles
from mrm.geometry.polyhedra import Polyhedron
from mrm.geometry.polyhedra.self_intersection import first_intersecting_pair
from mrm.geometry.polyhedra.validation import Topology, validate

if TYPE_CHECKING:
    from mrm.geometry.reconstruct.convex_3d import _Hull

logger = logging.getLogger(__name__)

FloatArray = npt.NDArray[np.float64]
Int64Array = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]

#: Bound on the dual hull's predicates: 1536 · (largest |normal coordinate|)³ · (largest w) must stay below
#: this (a 4 × 4 determinant of the homogeneous dual points (4a, w), expanded by minors, stays inside int64).
_DUAL_BOUND = 1 << 62
#: Bits of the snapped corners' offsets from c, scaled by 2ᵍ: the hull of them runs on integers below 2¹⁵.
_SNAP_BITS = 15
#: Times a snapped corner outside the core is pulled toward c (by 1/64 of its offset each) before it is
#: dropped.
_PULLS = 64
#: Corners tried for a spike, nearest first, before the snapped core is given up.
_SPIKE_CHOICES = 4


def snapped_cover_r(
    hull: _Hull, mask: BoolArray, origin: tuple[int, int, int], model: str, max_spikes: int
) -> tuple[FloatArray, Int64Array, bool, Polyhedron] | None:
    """The covers' P of a digitally convex A from its snapped core, with spikes (module docstring).

    Parameters
    ----------
    hull : conv(A) (:func:`.convex_3d._hull`), in A's box.
    mask : A's voxels (z, y, x).
    origin : the world (x, y, z) of A's voxel at index (0, 0, 0).
    model : ``"standard"`` or ``"supercover"``.
    max_spikes : the most voxels of A the snapped core may miss.

    Returns
    -------
    vertices : float64 (n, 3), world coordinates, dyadic.
    triangles : int64 (m, 3), outward.
    proven : bool
        Whether D(P) = A in the model (and P ⊂ V(A)) is proven already: P was discretized exactly, and each
        spike changed D(P) nowhere but at its own voxel (:func:`_spikes`). The caller need not discretize P
        again.
    polyhedron : Polyhedron
        P, validated exactly: P before the spikes as a whole (on R's worker thread, while P is discretized),
        the spikes' cones against their neighbours (:func:`_valid`).
        Or None when no lattice point lies strictly inside the core, when the dual's integers would leave
        int64, when P meets a cube outside A or misses more than ``max_spikes`` cubes of A, or when a
        spike cannot be placed. The caller checks the rest.
    """
    from mrm.geometry._threads import side_pool
    from mrm.geometry.reconstruct.convex_3d import (
        _corner_pose,
        _exact_faces,
        _fans,
        _propose_hull,
        _quickhull,
    )
    from mrm.geometry.reconstruct.decimate_3d import ROTATIONS, turn_back_points, turn_points

    size = hull.size
    perm, signs = ROTATIONS[_corner_pose(hull.corners, size)]
    corners = turn_points(hull.corners, perm, signs, size)
    normals, offsets = _turn_planes(hull.normals, hull.offsets, perm, signs, size)
    quarters = 4 * offsets + 3 - 2 * np.abs(normals).sum(axis=1)  # the core: 4a·x ≤ quarters
    c = np.rint(corners.mean(axis=0)).astype(np.int64)
    w = quarters - 4 * (normals @ c)
    if w.min() <= 0:
        logger.debug("the core holds no lattice point of conv(A)'s corners' mean: the general way")
        return None
    big_a, big_w = int(np.abs(normals).max()), int(w.max())
    if 1536 * (4 * big_a) ** 3 * big_w >= _DUAL_BOUND:
        return None
    dual = np.empty((normals.shape[0], 4), np.int64)
    dual[:, :3] = 4 * normals
    dual[:, 3] = w
    tri, ok = _quickhull(dual)
    if not ok:
        return None
    reach = int(np.abs(corners - c).max()) + 2  # |y − c| for every corner y of the core
    g = _SNAP_BITS - reach.bit_length()  # 2ᵍ · reach < 2¹⁵
    if g < 0:
        return None
    snapped = _unique_rows(_snap(dual, tri, g))[0]
    if snapped.shape[0] < 4:
        return None
    proposed = _propose_hull(snapped)
    faces = _exact_faces(*proposed) if proposed is not None else None
    if faces is None:
        return None
    q, face_ptr, face_corner, _, _ = faces
    triangles = _fans(q, face_ptr, face_corner)
    # Whether P meets no cube outside A, proven; else under standard P's supercover decides it.
    clear = _clear_of_outside_cubes(normals, offsets, c, q, triangles, g)
    # P is discretized, and spiked, in A's own frame: the standard cell (x − ½, x + ½] is not invariant under
    # the rotations of the cube, so D(P) = A shown in the turned frame need not hold in A's. The rotations
    # keep distances, so the spikes' choices are the same; the missed voxels go in the turned frame's order,
    # and a spike tries the neighbours of its voxel in that frame's order.
    v = turn_back_points(c + q / float(1 << g), perm, signs, size)  # dyadic: q below 2¹⁵, c below 2¹⁶
    # P's triangles are searched for improper pairs on R's worker thread while this one discretizes P (under
    # standard in the supercover too, unless the snapping proved P ⊂ V(A)).
    pool = side_pool()
    pairs = pool.submit(first_intersecting_pair, v, triangles) if pool is not None else None
    try:
        models = [model, "supercover"] if model == "standard" and not clear else [model]
        missed = _missed(v, triangles, mask, models, max_spikes)
    finally:
        crossing = pairs.result() if pairs is not None else first_intersecting_pair(v, triangles)
    if missed is None or crossing is not None:
        return None
    proven = True
    cones: list[Int64Array] = []
    if missed.shape[0]:
        turned = turn_points(missed, perm, signs, size)
        missed = missed[np.lexsort((turned[:, 0], turned[:, 1], turned[:, 2]))]
        steps = turn_back_points(np.array(_SIX, np.float64), perm, signs, size)
        steps -= turn_back_points(np.zeros((1, 3)), perm, signs, size)
        six = [(int(a), int(b), int(d)) for a, b, d in steps.tolist()]
        spiked = _spikes(v, triangles, missed, mask, model, six)
        if spiked is None:
            return None
        v, triangles, proven, cones = spiked
    valid = _valid(v, triangles, cones)
    if valid is None:
        return None
    out = v + np.asarray(origin, np.float64)
    return out, triangles, proven, Polyhedron._trusted(out, triangles, valid)


def _valid(v: FloatArray, t: Int64Array, cones: list[Int64Array]) -> Topology | None:
    # The spiked P's topology when it is a valid polyhedron, else None. P before the spikes had no improper
    # pair of triangles (checked by the caller). A spike splits each triangle (v, a, b) around its corner into
    # (ra, a, b) and (ra, b, rb), inside the old one and meeting their neighbours' pieces along shared sides,
    # and the cone (apex, ra, rb): only the cones are new geometry, so only they are tested, against every
    # triangle whose box meets theirs. Everything else is checked as for any polyhedron.
    if cones and not _cones_meet_nothing(v, t, cones):
        logger.debug("a spike's cone meets another triangle: the general way")
        return None
    try:
        return validate(v, t, pairs=False)
    except InvalidGeometryError as e:
        logger.debug("the spiked core is not a valid polyhedron (%s): the general way", e)
        return None


def _cones_meet_nothing(v: FloatArray, t: Int64Array, cones: list[Int64Array]) -> bool:
    # Whether no triangle of a cone (rows of t) meets another triangle improperly: each cone is tested with
    # the triangles whose boxes meet its box.
    corners = v[t]
    lo, hi = corners.min(axis=1), corners.max(axis=1)
    near = np.zeros(t.shape[0], np.bool_)
    for rows in cones:
        near |= np.all((lo <= hi[rows].max(axis=0)) & (hi >= lo[rows].min(axis=0)), axis=1)
    return first_intersecting_pair(v, t[np.flatnonzero(near)]) is None


_DROPPED = np.iinfo(np.int64).min


def _snap(dual: Int64Array, tri: Int64Array, g: int) -> Int64Array:
    # Row k: 2ᵍ (q − c) for one corner of the core, q its snap (module docstring, step 2), or no row when no
    # pull brought it inside. A corner is checked against the planes of every dual
    # triangle that snaps to the same point first: all the core's faces through it (the planes of the dual
    # points inside a dual face are implied by its corners'); the others are left to
    # _clear_of_outside_cubes and the check of P.
    first = _first_snaps(dual, tri, g)
    points, group = _unique_rows(first)
    order = np.argsort(group.ravel(), kind="stable")
    ptr = np.searchsorted(group.ravel()[order], np.arange(points.shape[0] + 1))
    out = _pull_inside(
        dual, tri, np.ascontiguousarray(points), order.astype(np.int64), ptr.astype(np.int64), g
    )
    kept: Int64Array = out[out[:, 0] != _DROPPED]
    return kept


def _unique_rows(points: Int64Array) -> tuple[Int64Array, Int64Array]:
    # np.unique(points, axis=0, return_inverse=True) for rows of three integers below 2¹⁵ in magnitude
    # (the snapped offsets), through one int64 key per row: the same rows in the same (lexicographic) order,
    # several times faster than sorting rows.
    b = np.int64(1) << 16
    if points.size and np.abs(points).max() >= b // 2:  # not a snap's offsets: the general way
        rows, inverse = np.unique(points, axis=0, return_inverse=True)
        return rows, inverse.ravel().astype(np.int64)
    key = ((points[:, 0] + b // 2) * b + (points[:, 1] + b // 2)) * b + (points[:, 2] + b // 2)
    _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    return points[first], inverse.astype(np.int64)


@njit(cache=True)
def _first_snaps(dual: Int64Array, tri: Int64Array, g: int) -> Int64Array:  # pragma: no cover - compiled
    # Row t: 2ᵍ (y − c) truncated toward zero, y the core's corner of dual triangle t. The dual rows are
    # (4a, w): the core is 4a·(x − c) ≤ w, and y solves the triangle's three planes (Cramer's rule).
    m = tri.shape[0]
    out = np.empty((m, 3), np.int64)
    scale = np.int64(1) << g
    for t in range(m):
        i, j, k = tri[t, 0], tri[t, 1], tri[t, 2]
        a0, a1, a2 = dual[i, 0], dual[i, 1], dual[i, 2]
        b0, b1, b2 = dual[j, 0], dual[j, 1], dual[j, 2]
        c0, c1, c2 = dual[k, 0], dual[k, 1], dual[k, 2]
        wa, wb, wc = dual[i, 3], dual[j, 3], dual[k, 3]
        det = a0 * (b1 * c2 - b2 * c1) - a1 * (b0 * c2 - b2 * c0) + a2 * (b0 * c1 - b1 * c0)
        y0 = wa * (b1 * c2 - b2 * c1) - a1 * (wb * c2 - b2 * wc) + a2 * (wb * c1 - b1 * wc)
        y1 = a0 * (wb * c2 - b2 * wc) - wa * (b0 * c2 - b2 * c0) + a2 * (b0 * wc - wb * c0)
        y2 = a0 * (b1 * wc - wb * c1) - a1 * (b0 * wc - wb * c0) + wa * (b0 * c1 - b1 * c0)
        out[t, 0] = _toward_zero(y0 * scale, det)
        out[t, 1] = _toward_zero(y1 * scale, det)
        out[t, 2] = _toward_zero(y2 * scale, det)
    return out


@njit(cache=True)
def _pull_inside(
    dual: Int64Array, tri: Int64Array, points: Int64Array, order: Int64Array, ptr: Int64Array, g: int
) -> Int64Array:  # pragma: no cover - compiled
    # Each point (2ᵍ (q − c)) checked against the planes of its triangles (order[ptr[k]:ptr[k + 1]]) and
    # pulled toward c by 1/64 while outside one; _DROPPED in column 0 after _PULLS pulls.
    out = points.copy()
    scale = np.int64(1) << g
    for k in range(points.shape[0]):
        q0, q1, q2 = points[k, 0], points[k, 1], points[k, 2]
        inside = False
        for _ in range(_PULLS):
            inside = True
            for s in range(ptr[k], ptr[k + 1]):
                for e in range(3):
                    f = tri[order[s], e]
                    if dual[f, 0] * q0 + dual[f, 1] * q1 + dual[f, 2] * q2 > dual[f, 3] * scale:
                        inside = False
            if inside:
                break
            q0, q1, q2 = _toward_zero(q0 * 63, 64), _toward_zero(q1 * 63, 64), _toward_zero(q2 * 63, 64)
        out[k, 0] = q0 if inside else _DROPPED
        out[k, 1], out[k, 2] = q1, q2
    return out


@njit(cache=True)
def _clear_of_outside_cubes(
    normals: Int64Array, offsets: Int64Array, c: Int64Array, q: Int64Array, tris: Int64Array, g: int
) -> bool:  # pragma: no cover - compiled
    # Whether the convex P (corners c + q / 2ᵍ, triangles tris) has a·x < b + 1 − |a|₁/2 for every facet
    # a·x ≤ b of conv(A): then P meets no cube outside A (a centre outside a digitally convex A has
    # a·x ≥ b + 1 for a facet, and its cube a·x ≥ b + 1 − |a|₁/2). The largest a·q over P's corners is found
    # by climbing P's edges while a·q grows, from the last facet's best corner: a corner of a convex
    # polytope with no edge going up is its highest. Exact, in integers.
    n = q.shape[0]
    count = np.zeros(n + 1, np.int64)
    for t in range(tris.shape[0]):
        for e in range(3):
            count[tris[t, e] + 1] += 1
    ptr = np.cumsum(count)
    nxt = np.empty(ptr[n], np.int64)
    fill = ptr[:n].copy()
    for t in range(tris.shape[0]):
        for e in range(3):
            u = tris[t, e]
            nxt[fill[u]] = tris[t, (e + 1) % 3]  # each edge comes the other way in the other triangle
            fill[u] += 1
    scale = np.int64(1) << g
    at = tris[0, 0]  # a corner of P: a point of q inside P has no edge to climb
    for f in range(normals.shape[0]):
        a0, a1, a2 = normals[f, 0], normals[f, 1], normals[f, 2]
        best = a0 * q[at, 0] + a1 * q[at, 1] + a2 * q[at, 2]
        up = True
        while up:
            up = False
            for k in range(ptr[at], ptr[at + 1]):
                u = nxt[k]
                h = a0 * q[u, 0] + a1 * q[u, 1] + a2 * q[u, 2]
                if h > best:
                    best, at, up = h, u, True
                    break
        ac = a0 * c[0] + a1 * c[1] + a2 * c[2]
        if 2 * best + 2 * scale * ac >= scale * (2 * offsets[f] + 2 - abs(a0) - abs(a1) - abs(a2)):
            return False
    return True


@njit(cache=True, inline="always")
def _toward_zero(a: int, b: int) -> int:  # pragma: no cover - compiled
    # a / b truncated toward zero, exactly (b ≠ 0).
    q: int = abs(a) // abs(b)
    return q if (a >= 0) == (b > 0) else -q


def _missed(v: FloatArray, t: Int64Array, mask: BoolArray, models: list[str], most: int) -> Int64Array | None:
    # The voxels (x, y, z) of A whose cubes the convex P misses in models[0], or None when there are more
    # than most or P meets a cube outside A in a model. Only P's triangles are discretized: in a row along x
    # the cubes a convex P meets are a run, whose two ends are cubes ∂P meets (the one beyond an end lies
    # outside P, and a cube inside P shares a face with each neighbour). A's rows are runs too.
    missed: Int64Array | None = None
    for model in models:
        marks, (ax, ay, az) = voxelize_triangles(v, t, model, limit=None)
        keep = most + 1 if missed is None else 0
        lost, n, extra = _compare_rows(mask, marks, ax, ay, az, keep)
        if extra:
            return None  # P meets a cube outside A: A is not digitally convex
        if missed is None:
            if n > most:
                return None
            missed = lost
    return missed


@njit(cache=True)
def _row_ends(row: BoolArray) -> tuple[int, int]:  # pragma: no cover - compiled
    # The first and last True of a row, (0, −1) when there is none.
    n = row.shape[0]
    s = 0
    while s < n and not row[s]:
        s += 1
    if s == n:
        return 0, -1
    e = n - 1
    while not row[e]:
        e -= 1
    return s, e


@njit(cache=True)
def _compare_rows(
    a: BoolArray, marks: BoolArray, ax: int, ay: int, az: int, most: int
) -> tuple[Int64Array, int, bool]:  # pragma: no cover - compiled
    # A (its rows along x single runs) against D(P) of a convex P, given by marks: the cubes ∂P meets, at
    # (ax, ay, az) in A's box. D(P)'s row is the run between its row's first and last mark. Returns the
    # voxels (x, y, z) of A that D(P) lacks (the first `most`), how many it lacks, and whether D(P) holds a
    # voxel outside A (then the rest is not computed).
    lost = np.empty((max(most, 1), 3), np.int64)
    n = 0
    nz, ny, _ = a.shape
    mz, my, _ = marks.shape
    for k in range(mz):  # marks in rows outside A's box
        for j in range(my):
            if not (0 <= k + az < nz and 0 <= j + ay < ny) and _row_ends(marks[k, j])[1] >= 0:
                return lost[:0], 0, True
    for z in range(nz):
        for y in range(ny):
            s, e = _row_ends(a[z, y])
            first, last = 0, -1
            if 0 <= z - az < mz and 0 <= y - ay < my:
                first, last = _row_ends(marks[z - az, y - ay])
                first, last = first + ax, last + ax
            if last >= first:
                if e < s or first < s or last > e:
                    return lost[:0], 0, True
            else:
                first, last = e + 1, e  # D(P)'s row is empty: A's whole row is lost
            for lo, hi in ((s, min(e, first - 1)), (max(s, last + 1), e)):  # A's row beyond D(P)'s
                for x in range(lo, hi + 1):
                    if n < most:
                        lost[n, 0], lost[n, 1], lost[n, 2] = x, y, z
                    n += 1
    return lost[: min(n, most)], n, False


def _turn_planes(
    normals: Int64Array,
    offsets: Int64Array,
    perm: tuple[int, int, int],
    signs: tuple[int, int, int],
    size: tuple[int, int, int],
) -> tuple[Int64Array, Int64Array]:
    # The planes a·x ≤ b in the turned frame of decimate_3d.turn_points: there x'ₖ = sₖ x_perm[k] + oₖ,
    # oₖ = size[perm[k]] − 1 when sₖ < 0 (else 0), so a'ₖ = sₖ a_perm[k] and b' = b + Σ a'ₖ oₖ.
    turned = np.empty_like(normals)
    shift = np.zeros(3, np.int64)
    for k in range(3):
        turned[:, k] = signs[k] * normals[:, perm[k]]
        shift[k] = size[perm[k]] - 1 if signs[k] < 0 else 0
    return turned, offsets + turned @ shift


def _spikes(
    v: FloatArray,
    t: Int64Array,
    missed: Int64Array,
    mask: BoolArray,
    model: str,
    six: Sequence[tuple[int, int, int]] | None = None,
) -> tuple[FloatArray, Int64Array, bool, list[Int64Array]] | None:
    # A spike to each missed voxel (module docstring, step 3), whether D(P) = A is proven still, and each
    # cone's triangles (the new geometry); None when no spike to a voxel is proven and its nearest corners
    # are all moved already.
    #
    # The spike at p changes P only inside conv(v, apex, ring): the old triangles (v, a, b) lose (v, ra, rb)
    # and gain (apex, ra, rb), both fans over the same ring; :func:`_spike_keeps_d` decides from that hull
    # whether D(P) is still A. Each spike is proven when it is placed, and all again at the end: a later
    # spike may move a corner an earlier proof counted on.
    n0 = v.shape[0]
    w = v.copy()  # every point so far: P's corners first, then each spike's ring
    tris = t.copy()
    moved = np.zeros(n0, np.bool_)
    sites = []
    cones: list[Int64Array] = []
    for p in missed:
        target = p.astype(np.float64)
        # The nearest corner no earlier spike moved (two missed voxels side by side at a tip may share one),
        # the first of equals: distances are exact, the points dyadic. A neighbour of an earlier spike's
        # corner is fine: its triangles are pieces of the split ones, and its cone is checked like any.
        order = np.argsort(((w[:n0] - target) ** 2).sum(axis=1), kind="stable")[:_SPIKE_CHOICES]
        free = [k for k in order.tolist() if not moved[k]]
        # Of those, the first whose spike keeps D(P) = A as far as it can tell; else a new corner on P's
        # surface next to the voxel (a face far from the tip has its corners two voxels away or more, and a
        # cone from there crosses cubes outside A); else the nearest corner. All are proven again at the end.
        options: list[tuple[FloatArray, Int64Array, int]] = [(w, tris, k) for k in free]
        placed = _first_keeping_d(options, p, mask, missed, model)
        if placed is None:
            # The face point nearest the voxel; then, for each neighbour u of p in A, the one nearest to a
            # point of u's cube a quarter from p's: a cone from u's cube into p's through their common face
            # stays in the two (a box), where the straight way from a face farther off may cross a cube
            # outside A.
            toward = [target] + [
                target + 0.75 * np.array(d, np.float64)
                for d in six or _SIX
                if _in_mask(mask, p + np.array(d, np.int64))
            ]
            splits = [s for s in (_split_nearest_face(w, tris, x) for x in toward) if s is not None]
            placed = _first_keeping_d(splits, p, mask, missed, model)
        if placed is None:
            if not free:
                return None
            placed = _place(w, tris, _spike_at(free[0], target, w, tris))
        w, tris, rows, i, hull = placed
        if i < n0:
            moved[i] = True
        cones.append(rows)
        sites.append(hull)
    proven = all(_spike_keeps_d(hull, w, tris, mask, missed, model) for hull in sites)
    return w, tris, proven, cones


_Spike = tuple[int, FloatArray, FloatArray, Int64Array, Int64Array, Int64Array]

#: The six face neighbours' offsets (x, y, z).
_SIX = ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1))


def _in_mask(mask: BoolArray, q: Int64Array) -> bool:
    # Whether voxel q (x, y, z) is in the mask (False beyond its box).
    nz, ny, nx = mask.shape
    return bool(0 <= q[0] < nx and 0 <= q[1] < ny and 0 <= q[2] < nz and mask[q[2], q[1], q[0]])


def _first_keeping_d(
    options: list[tuple[FloatArray, Int64Array, int]],
    p: Int64Array,
    mask: BoolArray,
    missed: Int64Array,
    model: str,
) -> tuple[FloatArray, Int64Array, Int64Array, int, FloatArray] | None:
    # The first of (points, triangles, corner k) whose spike to p keeps D(P) = A locally and whose cone meets
    # no other triangle, placed (:func:`_place`); None when none does.
    target = p.astype(np.float64)
    for w, tris, k in options:
        placed = _place(w, tris, _spike_at(k, target, w, tris))
        w2, t2, rows, _, hull = placed
        if _spike_keeps_d(hull, w2, t2, mask, missed, model) and _cones_meet_nothing(w2, t2, [rows]):
            return placed
    return None


def _place(
    w: FloatArray, tris: Int64Array, spike: _Spike
) -> tuple[FloatArray, Int64Array, Int64Array, int, FloatArray]:
    # P with the spike: its points and triangles (new arrays), the cone's rows, the moved corner's index and
    # the spike's points (corner, apex, ring). Each triangle (i, a, b) around the corner becomes the cone's
    # (i, ra, rb) — i now at the apex — and the pieces (ra, a, b), (ra, b, rb), added at the end at once:
    # a later spike at a neighbour finds them in its star.
    i, apex, ring, rows, a, b = spike
    near = np.unique(np.concatenate([a, b]))
    first = w.shape[0]
    out = np.vstack([w, ring])
    ra = first + np.searchsorted(near, a)
    rb = first + np.searchsorted(near, b)
    t = tris.copy()
    t[rows] = np.stack([np.full(rows.size, i), ra, rb], axis=1)
    t = np.concatenate([t, np.stack([ra, a, b], axis=1), np.stack([ra, b, rb], axis=1)])
    hull = np.vstack([w[i], apex, ring])
    out[i] = apex
    return out, t, rows, i, hull


def _split_nearest_face(
    w: FloatArray, tris: Int64Array, target: FloatArray
) -> tuple[FloatArray, Int64Array, int] | None:
    # P with a new corner x on its triangle nearest to target: x = a + s (b − a) + t (c − a), s and t
    # multiples of 1/64 inside the triangle, so that x is dyadic and exactly on its plane; the triangle
    # becomes three around x (the same face). None when no triangle has such a point.
    corners = w[tris]
    lo, hi = corners.min(axis=1), corners.max(axis=1)
    gap = np.maximum(np.maximum(lo - target, target - hi), 0).max(axis=1)
    best: tuple[float, int, float, float] | None = None
    for r in np.flatnonzero(gap <= gap.min() + 2.0).tolist():
        a, b, c = corners[r]
        e1, e2 = b - a, c - a
        m = np.array([[e1 @ e1, e1 @ e2], [e1 @ e2, e2 @ e2]])
        if np.linalg.det(m) <= 0:
            continue
        st = np.linalg.solve(m, np.array([e1 @ (target - a), e2 @ (target - a)]))
        s_, t_ = (np.clip(np.round(st * 64), 1, 62) / 64).tolist()
        if s_ + t_ > 63 / 64:
            s_, t_ = s_ * (63 / 64) / (s_ + t_), t_ * (63 / 64) / (s_ + t_)
            s_, t_ = max(np.floor(s_ * 64), 1) / 64, max(np.floor(t_ * 64), 1) / 64
        x = a + s_ * e1 + t_ * e2
        d = float(((x - target) ** 2).sum())
        if best is None or d < best[0]:
            best = (d, r, s_, t_)
    if best is None:
        return None
    _, r, s_, t_ = best
    a, b, c = corners[r]
    x = a + s_ * (b - a) + t_ * (c - a)
    i = w.shape[0]
    ia, ib, ic = tris[r].tolist()
    out = np.concatenate([tris, np.array([[i, ib, ic], [i, ic, ia]], np.int64)])
    out[r] = (i, ia, ib)
    return np.vstack([w, x]), out, i


def _spike_at(i: int, target: FloatArray, points: FloatArray, tris: Int64Array) -> _Spike:
    # The spike from corner i toward the voxel at target: (i, its apex, its ring — one point on each edge
    # from i, in the order of the neighbours' indices — the rows of its triangles, and each row's other two
    # corners a, b in order).
    rows = np.flatnonzero((tris == i).any(axis=1))
    corner = points[i]
    apex = corner
    for n in range(1, 65):
        apex = corner + (n / 64) * (target - corner)
        if np.abs(apex - target).max() <= 0.5 - 1 / 16:
            break
    star = tris[rows]
    at = np.argmax(star == i, axis=1)
    k = np.arange(rows.size)
    a, b = star[k, (at + 1) % 3], star[k, (at + 2) % 3]
    near = np.unique(np.concatenate([a, b]))
    step = points[near] - corner  # a neighbour may be an earlier spike's ring point
    # At most half the way: a neighbour within an eighth would otherwise be its own ring point, a second
    # vertex on the same spot.
    e = np.full(near.size, 0.5)
    far = np.abs(step).max(axis=1)
    while np.any(far * e > 1 / 8):
        e = np.where(far * e > 1 / 8, e / 2, e)
    return i, apex, corner + e[:, None] * step, rows, a, b


def _spike_keeps_d(
    hull: FloatArray,
    w: FloatArray,
    tris: Int64Array,
    mask: BoolArray,
    missed: Int64Array,
    model: str,
) -> bool:
    # Whether the spike whose points are hull (its corner, apex and ring) leaves D(P) = A, P being w, tris
    # with the spike; decided exactly (the points are dyadic).
    #
    # The spike changes P only inside conv(hull): D(P) can gain only voxels whose closed cubes meet it, and
    # lose only those whose closed cubes meet the cap conv(corner, ring) it cuts off. D(P) = A still when the
    # first are all in A and each of the second but the missed voxels (each reached by its own spike) is in
    # D of the new P's triangles near it, in the model.
    met = _cubes_met(hull)
    nz, ny, nx = mask.shape
    if np.any(met < 0) or np.any(met >= np.array([nx, ny, nz])):
        return False
    if not mask[met[:, 2], met[:, 1], met[:, 0]].all():
        return False
    cut = _cubes_met(np.vstack([hull[:1], hull[2:]]))
    spiked = {tuple(int(x) for x in q) for q in missed}
    need = np.array([q for q in cut.tolist() if tuple(q) not in spiked], np.int64).reshape(-1, 3)
    if need.shape[0] == 0:
        return True
    lo, hi = need.min(axis=0) - 0.5, need.max(axis=0) + 0.5
    corners = w[tris]
    close = np.all((corners.max(axis=1) >= lo) & (corners.min(axis=1) <= hi), axis=1)
    marks, origin = voxelize_triangles(w, tris[close], model, limit=None)
    at = need - np.array(origin, np.int64)
    size = np.array([marks.shape[2], marks.shape[1], marks.shape[0]])
    if np.any(at < 0) or np.any(at >= size):
        return False
    return bool(marks[at[:, 2], at[:, 1], at[:, 0]].all())


def _cubes_met(points: FloatArray) -> Int64Array:
    # The voxels (x, y, z) whose closed cubes meet conv(points), exactly, for points within an eighth of a
    # voxel of a segment (a spike's): the triangles on every three of them lie in the hull and cover its
    # boundary, and so thin a hull holds no whole cube.
    tri = np.array(list(combinations(range(points.shape[0]), 3)), np.int64)
    marks, (ox, oy, oz) = voxelize_triangles(points, tri, "supercover", limit=None)
    k, j, i = np.nonzero(marks)
    return np.stack([i + ox, j + oy, k + oz], axis=1).astype(np.int64)
