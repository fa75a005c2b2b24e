"""The compact 3D continuation: the safety net, simplified by edge collapses that are each proved exactly.

Reference: docs/design.md §11, "Continuation R in 3D"; the decision is docs/adr/0064.

R(A) starts as the safety net (:mod:`.safety_net_3d`), which meets items 1–5 of the contract in every model,
and changes it by three moves (docs/adr/0066): **half-edge collapses** u → v (u goes, its triangles take v
instead), **collapses onto a point** (u and v both go to a new vertex w) and **moves** of a vertex u to a new
point w. Every change is the collapse of u v onto w (w = v, w new, or v = u for a move), and the volume it
sweeps is coned from w over the old triangles. A change is kept only when every one of these holds, each
decided exactly in integers:

1. **The surface stays a closed 2-manifold of the same topology**: the link condition (u and v have exactly
   the two vertices opposite their edge as common neighbours), and no new triangle is flat.
2. **No centre of Z³ changes side.** The old and the new triangles bound a closed surface; a point's side
   changes iff its winding number about that surface is not 0, and coned from w it is the signed count of
   the tetrahedra (w, a, b, c), (a, b, c) an old triangle, that hold the point. A centre is taken as c + τ,
   τ = (ε, ε², ε³) — the ties rule of §2 — so it is never on a face, and each count is exact.
3. **No new triangle meets a forbidden closed cube**: under the covers, the cube V(q) of every voxel q
   outside A (so R(A) ⊂ V(A) and misses every V(q), q ∉ A); under ``gauss``, the cube of every voxel
   whose 3×3×3 block lies on one side of A (so ∂R(A) stays within the cubes of the border voxels on either
   side). Triangle–box overlap by separating axes, closed on both sides.
4. **No new triangle meets another triangle** beyond their common vertices and edge (the exact pair test of
   :mod:`~mrm.geometry.polyhedra.self_intersection`), against every triangle whose box is near.
5. **Every shell keeps the sign of its volume** (six times it, exactly, updated by the swept tetrahedra): a
   small shell that holds no centre could otherwise turn inside out under the covers unseen by 2.

Together with the safety net's own guarantees they keep D(R(A)) = A in the model (by 2 every centre keeps
its side; by 3 under the covers every V(q), q ∉ A, stays outside R(A) since it misses the surface and its
centre is outside), the shells and their genus (1, 4 and 5), and validity. Vertices lie in (¼Z)³: the safety
net's in Z + {¼, ¾}, the new ones anywhere a quarter voxel allows. Coordinates are held as integers, four
times the offset from a corner of the box, and every predicate of 2 and 3 is a product of three differences
inside one change's box (at most :data:`_MAX_EXTENT`, so far below 2⁵³).

The order, in rounds: half-edge collapses (vertices in turn, each trying its neighbours farthest first: a long
collapse straightens the most staircase) in passes until one removes nothing; collapses onto a point (the
quadric's point of the edge's triangles, and the midpoint rounded every way, cheapest quadric first); moves
that make faces exactly coplanar; edge flips that bend less. The result is checked again as a whole by the
caller.

Most changes tried are refused, so refusals are made cheap (docs/adr/0067): a change that leaves the surface
the same set of points needs no proof (:func:`_same_point_set`); the check likelier to refuse runs first; a
tetrahedron's centres are sought within its shadow only; the star and bucket pools are compacted, not grown.
"""

from __future__ import annotations

import itertools
from typing import NamedTuple, TypeVar, cast

import numpy as np
import numpy.typing as npt

from mrm.core.errors import Cancelled
from mrm.core.progress import ProgressLike, stop_flag
from mrm.geometry._jit import njit
from mrm.geometry.polyhedra.manifold import components
from mrm.geometry.polyhedra.self_intersection import DISJOINT, triangles_meet_improperly

FloatArray = npt.NDArray[np.float64]
Int64Array = npt.NDArray[np.int64]
PointsT = TypeVar("PointsT", npt.NDArray[np.int64], npt.NDArray[np.float64])
Int32Array = npt.NDArray[np.int32]
Int16Array = npt.NDArray[np.int16]
BoolArray = npt.NDArray[np.bool_]

#: Voxels of padding around A in the forbidden-cube array (beyond it every cube is forbidden).
PAD = 3
#: Grid cell of the triangle buckets, in the integer units (4 per voxel).
_CELL = 8
#: A collapse may turn a triangle's normal by acos(MIN_COS) at most (no fold-overs: they make spikes).
MIN_COS = 0.0
#: Collapses onto a point tried at most per vertex and pass, cheapest quadric first (each failed one costs a
#: full proof, and a long edge's proof scans the area it sweeps).
_POINT_TRIES = 4
#: Largest extent of a change's box, in integer units (128 voxels): it bounds the winding numbers' array (the
#: centres of the box, at most 130³) and keeps every product of three differences far inside 2⁵³ (the pair
#: test reads floats). A ridge of the ideal solid is one edge only if its box fits.
_MAX_EXTENT = 512


def forbidden_cubes(mask: BoolArray, gauss: bool) -> BoolArray:
    """The voxels whose closed cube R(A)'s boundary must not meet, over A's box padded by :data:`PAD`.

    Parameters
    ----------
    mask : bool (nz, ny, nx)
        A.
    gauss : bool
        ``gauss``: voxels whose 3×3×3 block is all in A or all outside (∂R(A) stays in the border voxels'
        cubes); the covers: every voxel outside A.
    """
    a = np.pad(mask, PAD)
    if not gauss:
        return ~a
    out = np.empty(a.shape, np.bool_)
    _uniform_blocks(a, out)
    return out


@njit(cache=True)
def _uniform_blocks(a: BoolArray, out: BoolArray) -> None:  # pragma: no cover - compiled
    # out[v] = whether the 3×3×3 block of v is all in a or all outside (beyond the array every voxel is
    # outside). One pass, no count array: at 256³ the counts and their padded copies took 90 MB.
    nz, ny, nx = a.shape
    for z in range(nz):
        for y in range(ny):
            for x in range(nx):
                n_in = 0
                n_all = 27
                for dz in range(-1, 2):
                    zz = z + dz
                    for dy in range(-1, 2):
                        yy = y + dy
                        for dx in range(-1, 2):
                            xx = x + dx
                            if 0 <= zz < nz and 0 <= yy < ny and 0 <= xx < nx and a[zz, yy, xx]:
                                n_in += 1
                out[z, y, x] = n_in == 0 or n_in == n_all


@njit(cache=True, inline="always")
def _normal(
    ax: int, ay: int, az: int, bx: int, by: int, bz: int, cx: int, cy: int, cz: int
) -> tuple[int, int, int]:  # pragma: no cover - compiled
    # (b − a) × (c − a): the normal of triangle a b c, counter-clockwise seen from where it points.
    ux, uy, uz = bx - ax, by - ay, bz - az
    vx, vy, vz = cx - ax, cy - ay, cz - az
    return uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx


@njit(cache=True, inline="always")
def _normal_of(p: Int64Array) -> tuple[int, int, int]:  # pragma: no cover - compiled
    # The normal of the triangle whose corners are the rows of p (3 × 3).
    return _normal(p[0, 0], p[0, 1], p[0, 2], p[1, 0], p[1, 1], p[1, 2], p[2, 0], p[2, 1], p[2, 2])


@njit(cache=True, inline="always")
def _axes(nx: int, ny: int, nz: int) -> tuple[int, int, int]:  # pragma: no cover - compiled
    # (i, j, k): k the axis of the normal's largest coordinate, i and j the other two in cyclic order — the
    # order every slab scan takes them in.
    if abs(nz) >= abs(nx) and abs(nz) >= abs(ny):
        return 0, 1, 2
    if abs(ny) >= abs(nx):
        return 2, 0, 1
    return 1, 2, 0


@njit(cache=True, inline="always")
def _side(
    ax: int, ay: int, az: int, bx: int, by: int, bz: int, cx: int, cy: int, cz: int, px: int, py: int, pz: int
) -> int:  # pragma: no cover - compiled
    # Sign of det(b − a, c − a, p + τ − a), τ = (ε, ε², ε³): the plain determinant, else the normal's first
    # non-zero coordinate (the triangle is not flat, so one is).
    nx, ny, nz = _normal(ax, ay, az, bx, by, bz, cx, cy, cz)
    d = nx * (px - ax) + ny * (py - ay) + nz * (pz - az)
    if d == 0:
        d = nx
        if d == 0:
            d = ny
            if d == 0:
                d = nz
    return 1 if d > 0 else (-1 if d < 0 else 0)


@njit(cache=True, inline="always")
def _det(
    ax: int, ay: int, az: int, bx: int, by: int, bz: int, cx: int, cy: int, cz: int, dx: int, dy: int, dz: int
) -> int:  # pragma: no cover - compiled
    # det(b − a, c − a, d − a) = ((b − a) × (c − a)) · (d − a)
    nx, ny, nz = _normal(ax, ay, az, bx, by, bz, cx, cy, cz)
    return nx * (dx - ax) + ny * (dy - ay) + nz * (dz - az)


@njit(cache=True)
def _tet_holds(
    q: Int64Array, t0: int, t1: int, t2: int, t3: int, px: int, py: int, pz: int
) -> bool:  # pragma: no cover
    # Whether the non-flat tetrahedron t0 t1 t2 t3 holds p + τ (never on a face).
    idx = (t0, t1, t2, t3)
    for f in range(4):
        a, b, c, d = idx[(f + 1) % 4], idx[(f + 2) % 4], idx[(f + 3) % 4], idx[f]
        s_d = _det(
            q[a, 0],
            q[a, 1],
            q[a, 2],
            q[b, 0],
            q[b, 1],
            q[b, 2],
            q[c, 0],
            q[c, 1],
            q[c, 2],
            q[d, 0],
            q[d, 1],
            q[d, 2],
        )
        s_p = _side(
            q[a, 0], q[a, 1], q[a, 2], q[b, 0], q[b, 1], q[b, 2], q[c, 0], q[c, 1], q[c, 2], px, py, pz
        )
        if (s_d > 0) != (s_p > 0):
            return False
    return True


@njit(cache=True)
def _axis_apart(
    ax: int, ay: int, az: int, p: Int64Array, lo: Int64Array, hi: Int64Array, open_box: bool
) -> bool:  # pragma: no cover
    # Whether axis (ax, ay, az) separates the triangle's points p (3 × 3) from the box: the closed box
    # [lo, hi], or (open_box) its interior, whose projection is the open interval.
    if ax == 0 and ay == 0 and az == 0:
        return False
    t_min = p[0, 0] * ax + p[0, 1] * ay + p[0, 2] * az
    t_max = t_min
    for k in range(1, 3):
        x = p[k, 0] * ax + p[k, 1] * ay + p[k, 2] * az
        t_min = min(t_min, x)
        t_max = max(t_max, x)
    b_min = 0
    b_max = 0
    for k, a in enumerate((ax, ay, az)):
        if a > 0:
            b_min += lo[k] * a
            b_max += hi[k] * a
        else:
            b_min += hi[k] * a
            b_max += lo[k] * a
    if open_box:
        return bool(t_max <= b_min or b_max <= t_min)
    return bool(t_max < b_min or b_max < t_min)


@njit(cache=True)
def _triangle_meets_box(
    p: Int64Array, lo: Int64Array, hi: Int64Array, open_box: bool
) -> bool:  # pragma: no cover
    # Separating axes of a closed triangle and a box, closed or (open_box) open: the box's 3 axes, the
    # normal, the 9 edge crosses (the facet normals of their Minkowski difference).
    for k in range(3):
        t_max = max(p[0, k], p[1, k], p[2, k])
        t_min = min(p[0, k], p[1, k], p[2, k])
        if t_max < lo[k] or t_min > hi[k] or (open_box and (t_max == lo[k] or t_min == hi[k])):
            return False
    nx, ny, nz = _normal_of(p)
    if _axis_apart(nx, ny, nz, p, lo, hi, open_box):
        return False
    for i in range(3):
        # edge i, read off the points (no array per call: this runs for every cube a triangle's plane meets)
        i1 = (i + 1) % 3
        ex, ey, ez = p[i1, 0] - p[i, 0], p[i1, 1] - p[i, 1], p[i1, 2] - p[i, 2]
        # unit axis × edge
        if _axis_apart(0, -ez, ey, p, lo, hi, open_box):
            return False
        if _axis_apart(ez, 0, -ex, p, lo, hi, open_box):
            return False
        if _axis_apart(-ey, ex, 0, p, lo, hi, open_box):
            return False
    return True


class _Scratch(NamedTuple):
    """The working arrays of the checks, allocated once per run (numba takes a named tuple of arrays)."""

    pts: Int64Array  # (3, 3): a triangle's corners
    lo_i: Int64Array
    hi_i: Int64Array
    idx: Int64Array
    clo: Int64Array
    chi: Int64Array
    cb: Int64Array  # (6,): a box of grid cells
    cells: Int64Array  # grid cells a triangle's plane crosses
    acc: Int16Array  # (nz, ny, nx): winding numbers over the box of a change (|each| ≤ its tetrahedra, ≤ 512)
    seen: Int64Array  # (4096, 3): the cells of acc written
    found: Int64Array  # (4096, 3): the centres in one tetrahedron
    flips: Int64Array  # (4096, 3): the centres that change side


#: The gauss model, and the covers: standard and supercover share one R, whose checks are the stricter
#: of the two and invariant under the rotations of the cube (closed forbidden cubes, open cubes met).
GAUSS, COVERS = 0, 1


@njit(cache=True, inline="always")
def _cell_box(q: Int64Array, t: Int64Array, k: int, out: Int64Array) -> None:  # pragma: no cover
    # The grid cells of triangle k's box: out = (lo x, lo y, lo z, hi x, hi y, hi z).
    for d in range(3):
        a, b, c = q[t[k, 0], d], q[t[k, 1], d], q[t[k, 2], d]
        out[d] = min(a, b, c) // _CELL
        out[3 + d] = max(a, b, c) // _CELL


@njit(cache=True)
def _triangle_cells(
    q: Int64Array, t: Int64Array, k: int, gx: int, gy: int, cb: Int64Array, cells: Int64Array
) -> int:  # pragma: no cover - compiled
    # The grid cells of triangle k's box that its plane's slab crosses (a cell [8c, 8c + 8)³ meets the plane
    # only if |n · (its centre) − d| ≤ 4 (|nx| + |ny| + |nz|)), into cells; their number (−1: too many).
    _cell_box(q, t, k, cb)
    a = t[k, 0]
    nx, ny, nz = _normal(
        q[a, 0], q[a, 1], q[a, 2], q[t[k, 1], 0], q[t[k, 1], 1], q[t[k, 1], 2], q[t[k, 2], 0], q[t[k, 2], 1],
        q[t[k, 2], 2],
    )  # fmt: skip
    d0 = nx * q[a, 0] + ny * q[a, 1] + nz * q[a, 2]
    r = 4 * (abs(nx) + abs(ny) + abs(nz))
    ki, kj, kk = _axes(nx, ny, nz)
    m = 0
    idx = (0, 0, 0)
    for ci in range(cb[ki], cb[3 + ki] + 1):
        for cj in range(cb[kj], cb[3 + kj] + 1):
            lo, hi = _slab(nx, ny, nz, d0 - r, d0 + r, ci, cj, cb[kk], cb[3 + kk], _CELL, _CELL // 2)
            for ck in range(lo, hi + 1):
                if m == cells.shape[0]:
                    return -1
                if kk == 2:
                    idx = (ci, cj, ck)
                elif kk == 1:
                    idx = (cj, ck, ci)
                else:
                    idx = (ck, ci, cj)
                cells[m] = (idx[2] * gy + idx[1]) * gx + idx[0]
                m += 1
    return m


@njit(cache=True)
def _bucket(
    q: Int64Array,
    t: Int64Array,
    k: int,
    ghead: Int32Array,
    g_next: Int32Array,
    g_tri: Int32Array,
    ng: int,
    gx: int,
    gy: int,
    cb: Int64Array,
    cells: Int64Array,
) -> tuple[Int32Array, Int32Array, int]:  # pragma: no cover
    # Triangle k into the buckets of the cells its plane crosses in its box (the pools double when full).
    m = _triangle_cells(q, t, k, gx, gy, cb, cells)
    if m < 0:  # a triangle too big for the list: every cell of its box
        m = 0
        for c2 in range(cb[2], cb[5] + 1):
            for c1 in range(cb[1], cb[4] + 1):
                for c0 in range(cb[0], cb[3] + 1):
                    if m == cells.shape[0]:
                        cells = np.concatenate((cells, np.empty(m, np.int64)))
                    cells[m] = (c2 * gy + c1) * gx + c0
                    m += 1
    for i in range(m):
        if ng == g_next.shape[0]:
            g_next = np.concatenate((g_next, np.empty(ng, np.int32)))
            g_tri = np.concatenate((g_tri, np.empty(ng, np.int32)))
        cell = cells[i]
        g_next[ng] = ghead[cell]
        g_tri[ng] = k
        ghead[cell] = ng
        ng += 1
    return g_next, g_tri, ng


@njit(cache=True)
def _rebucket(
    q: Int64Array, t: Int64Array, alive: BoolArray, ghead: Int32Array, g_next: Int32Array, g_tri: Int32Array,
    gx: int, gy: int, cb: Int64Array, cells: Int64Array,
) -> tuple[Int32Array, Int32Array, int]:  # fmt: skip  # pragma: no cover - compiled
    # The buckets again, of the live triangles only. A change adds its triangles to the cells of their new
    # boxes and leaves the old entries (skipped when read); a big triangle that changes often fills many
    # cells with them, and every later scan of those cells walks them.
    ghead[:] = -1
    ng = 0
    for k in range(t.shape[0]):
        if alive[k]:
            g_next, g_tri, ng = _bucket(q, t, k, ghead, g_next, g_tri, ng, gx, gy, cb, cells)
    if ng + 2 * _ROOM > g_next.shape[0]:  # room for the changes to come (the live entries need it)
        m = ng + ng // 2 + 2 * _ROOM
        g_next = np.concatenate((g_next[:ng], np.empty(m - ng, np.int32)))
        g_tri = np.concatenate((g_tri[:ng], np.empty(m - ng, np.int32)))
    return g_next, g_tri, ng


#: Free entries kept in the star and bucket pools: below it they are compacted (_tidy) before a vertex's
#: changes (one change adds at most 512 star entries; a bucket pool still grows should one change need more).
_ROOM = 4096


@njit(cache=True)
def _restar(
    vhead: Int64Array, s_next: Int32Array, s_tri: Int32Array, alive: BoolArray, t: Int64Array, n_now: int
) -> tuple[Int32Array, Int32Array, int]:  # pragma: no cover - compiled
    # The star lists with their stale entries (dead, or no longer at the vertex) dropped, every list in its
    # order: what every reader of a list sees stays the same.
    cap = s_next.shape[0]
    n = 0
    for x in range(n_now):
        e = vhead[x]
        while e >= 0:
            k = s_tri[e]
            e = s_next[e]
            if alive[k] and (t[k, 0] == x or t[k, 1] == x or t[k, 2] == x):
                n += 1
    cap = max(cap, n + n // 2 + 2 * _ROOM)
    n_next = np.empty(cap, np.int32)
    n_tri = np.empty(cap, np.int32)
    n = 0
    for x in range(n_now):
        e = vhead[x]
        vhead[x] = -1
        last = -1
        while e >= 0:
            k = s_tri[e]
            e = s_next[e]
            if alive[k] and (t[k, 0] == x or t[k, 1] == x or t[k, 2] == x):
                n_tri[n] = k
                n_next[n] = -1
                if last < 0:
                    vhead[x] = n
                else:
                    n_next[last] = n
                last = n
                n += 1
    return n_next, n_tri, n


@njit(cache=True)
def _tidy(
    q: Int64Array, t: Int64Array, alive: BoolArray, ghead: Int32Array, g_next: Int32Array, g_tri: Int32Array,
    ng: int, ng_fresh: int, gx: int, gy: int, cb: Int64Array, cells: Int64Array, vhead: Int64Array,
    s_next: Int32Array, s_tri: Int32Array, ns: int, n_now: int,
) -> tuple[Int32Array, Int32Array, int, int, Int32Array, Int32Array, int]:  # fmt: skip  # pragma: no cover
    # The pools compacted when stale entries have doubled the buckets (every scan walks them) or either pool
    # is nearly full (instead of doubling it: at 256³ the grown pools were most of the memory).
    if ng > 2 * ng_fresh or ng > g_next.shape[0] - _ROOM:
        g_next, g_tri, ng = _rebucket(q, t, alive, ghead, g_next, g_tri, gx, gy, cb, cells)
        ng_fresh = ng
    if ns > s_next.shape[0] - _ROOM:
        s_next, s_tri, ns = _restar(vhead, s_next, s_tri, alive, t, n_now)
    return g_next, g_tri, ng, ng_fresh, s_next, s_tri, ns


@njit(cache=True)
def _holds_point(p: Int64Array, x: int, y: int, z: int) -> bool:  # pragma: no cover
    # Whether the closed, non-flat triangle p (3 × 3) holds the point: in its plane, and on the inner side
    # of each edge in the projection that drops the normal's largest coordinate.
    n0, n1, n2 = _normal_of(p)
    if n0 * (x - p[0, 0]) + n1 * (y - p[0, 1]) + n2 * (z - p[0, 2]) != 0:
        return False
    i, j, _k = _axes(n0, n1, n2)
    pt = (x, y, z)
    pos = 0
    neg = 0
    for e in range(3):
        a, b = e, (e + 1) % 3
        o = (p[b, i] - p[a, i]) * (pt[j] - p[a, j]) - (p[b, j] - p[a, j]) * (pt[i] - p[a, i])
        if o > 0:
            pos += 1
        elif o < 0:
            neg += 1
    return pos == 0 or neg == 0


@njit(cache=True)
def _cube_range(pts: Int64Array, lo_i: Int64Array, hi_i: Int64Array) -> None:  # pragma: no cover
    # The voxels whose cube [4i − 2, 4i + 2] meets the box of the points.
    for d in range(3):
        lo_i[d] = (min(pts[0, d], pts[1, d], pts[2, d]) - 2 + 3) // 4
        hi_i[d] = (max(pts[0, d], pts[1, d], pts[2, d]) + 2) // 4


@njit(cache=True)
def _tet_centres(
    q: Int64Array,
    apex: int,
    p: int,
    r: int,
    s: int,
    out: Int64Array,
    lo: Int64Array,
    hi: Int64Array,
    idx: Int64Array,
    first_only: bool,
) -> int:  # pragma: no cover
    # The voxels whose centre + τ lies in the non-flat tetrahedron (apex, p, r, s), into out (indices); their
    # number, or −1 when out is full; with first_only, stop at the first. Only the slab between the plane of
    # p r s and its parallel through the apex is scanned, within the tetrahedron's shadow.
    nx, ny, nz = _normal(q[p, 0], q[p, 1], q[p, 2], q[r, 0], q[r, 1], q[r, 2], q[s, 0], q[s, 1], q[s, 2])
    dp = nx * q[p, 0] + ny * q[p, 1] + nz * q[p, 2]
    da = nx * q[apex, 0] + ny * q[apex, 1] + nz * q[apex, 2]
    for d in range(3):
        lo[d] = (min(q[apex, d], q[p, d], q[r, d], q[s, d]) + 3) // 4
        hi[d] = max(q[apex, d], q[p, d], q[r, d], q[s, d]) // 4
    ki, kj, kk = _axes(nx, ny, nz)
    corners = (apex, p, r, s)
    m = 0
    for ii in range(lo[ki], hi[ki] + 1):
        # The columns of row ii within the tetrahedron's shadow on the (ki, kj) plane: at X = 4·ii the shadow
        # (the hull of the four corners' shadows) spans the least and the greatest of the corners at X and of
        # the six segments between corners crossing X, exactly (a long sliver's box is mostly empty).
        x = 4 * ii
        j_lo = hi[kj] + 1
        j_hi = lo[kj] - 1
        for a in range(4):
            pa = corners[a]
            ax, ay = q[pa, ki], q[pa, kj]
            if ax == x:
                j_lo = min(j_lo, -((-ay) // 4))
                j_hi = max(j_hi, ay // 4)
            for b in range(a + 1, 4):
                pb = corners[b]
                bx, by = q[pb, ki], q[pb, kj]
                if min(ax, bx) < x < max(ax, bx):
                    den = bx - ax
                    num = ay * den + (by - ay) * (x - ax)
                    if den < 0:
                        num, den = -num, -den
                    # the crossing is at num / den: the centres 4·jj around it
                    j_lo = min(j_lo, -((-num) // (4 * den)))
                    j_hi = max(j_hi, num // (4 * den))
        for jj in range(max(lo[kj], j_lo), min(hi[kj], j_hi) + 1):
            k0, k1 = _slab(nx, ny, nz, min(dp, da), max(dp, da), ii, jj, lo[kk], hi[kk], 4, 0)
            for kx in range(k0, k1 + 1):
                idx[ki], idx[kj], idx[kk] = ii, jj, kx
                if _tet_holds(q, apex, p, r, s, 4 * idx[0], 4 * idx[1], 4 * idx[2]):
                    if m == out.shape[0]:
                        return -1
                    out[m, 0], out[m, 1], out[m, 2] = idx[0], idx[1], idx[2]
                    m += 1
                    if first_only:
                        return m
    return m


@njit(cache=True)
def _centre_on(
    pts: Int64Array, lo_i: Int64Array, hi_i: Int64Array, idx: Int64Array
) -> bool:  # pragma: no cover
    # Whether a voxel centre (4·i in these units) lies on the closed triangle pts: only the centres of its
    # box in its plane are tried.
    nx, ny, nz = _normal_of(pts)
    d0 = nx * pts[0, 0] + ny * pts[0, 1] + nz * pts[0, 2]
    for d in range(3):
        lo_i[d] = (min(pts[0, d], pts[1, d], pts[2, d]) + 3) // 4
        hi_i[d] = max(pts[0, d], pts[1, d], pts[2, d]) // 4
    ki, kj, kk = _axes(nx, ny, nz)
    for ii in range(lo_i[ki], hi_i[ki] + 1):
        for jj in range(lo_i[kj], hi_i[kj] + 1):
            k0, k1 = _slab(nx, ny, nz, d0, d0, ii, jj, lo_i[kk], hi_i[kk], 4, 0)
            for kx in range(k0, k1 + 1):
                idx[ki], idx[kj], idx[kk] = ii, jj, kx
                if _holds_point(pts, 4 * idx[0], 4 * idx[1], 4 * idx[2]):
                    return True
    return False


@njit(cache=True)
def _slab(
    nx: int,
    ny: int,
    nz: int,
    lo_val: int,
    hi_val: int,
    i: int,
    j: int,
    lo_k: int,
    hi_k: int,
    step: int,
    offset: int,
) -> tuple[int, int]:  # pragma: no cover - compiled
    # The indices i_k along the normal's largest axis k (see _axes), within [lo_k, hi_k], of the points
    # step · (i, j, i_k) + offset (voxel centres: step 4, offset 0; grid cells' centres: 8, 4) with
    # lo_val ≤ n · point ≤ hi_val: the scans visit the slab a triangle or a tetrahedron lies in, not its box.
    n = (nx, ny, nz)
    ki, kj, kk = _axes(nx, ny, nz)
    s = n[ki] * (step * i + offset) + n[kj] * (step * j + offset) + n[kk] * offset
    nk = step * n[kk]
    if nk == 0:
        return (lo_k, hi_k) if lo_val <= s <= hi_val else (1, 0)
    a, b = lo_val - s, hi_val - s  # nk · i_k in [a, b]
    if nk < 0:
        a, b, nk = -b, -a, -nk
    return max(lo_k, -((-a) // nk)), min(hi_k, b // nk)


@njit(cache=True)
def _meets_forbidden(
    pts: Int64Array,
    forbidden: BoolArray,
    lo_i: Int64Array,
    hi_i: Int64Array,
    clo: Int64Array,
    chi: Int64Array,
    idx: Int64Array,
) -> bool:  # pragma: no cover - compiled
    # Whether the closed triangle pts meets the closed cube [4i − 2, 4i + 2]³ of a forbidden voxel (or leaves
    # the array). Only the voxels of its box whose cube meets its plane's slab are tested.
    fz, fy, fx = forbidden.shape
    _cube_range(pts, lo_i, hi_i)
    if min(lo_i[0], lo_i[1], lo_i[2]) < 0 or hi_i[0] >= fx or hi_i[1] >= fy or hi_i[2] >= fz:
        return True
    nx, ny, nz = _normal_of(pts)
    d0 = nx * pts[0, 0] + ny * pts[0, 1] + nz * pts[0, 2]
    r = 2 * (abs(nx) + abs(ny) + abs(nz))  # the cube's reach along n
    ki, kj, kk = _axes(nx, ny, nz)
    for ii in range(lo_i[ki], hi_i[ki] + 1):
        for jj in range(lo_i[kj], hi_i[kj] + 1):
            k0, k1 = _slab(nx, ny, nz, d0 - r, d0 + r, ii, jj, lo_i[kk], hi_i[kk], 4, 0)
            for kx in range(k0, k1 + 1):
                idx[ki], idx[kj], idx[kk] = ii, jj, kx
                if forbidden[idx[2], idx[1], idx[0]]:
                    for d in range(3):
                        clo[d] = 4 * idx[d] - 2
                        chi[d] = 4 * idx[d] + 2
                    if _triangle_meets_box(pts, clo, chi, False):
                        return True
    return False


@njit(cache=True)
def _cell_is_met(
    q: Int64Array,
    t: Int64Array,
    alive: BoolArray,
    ix: int,
    iy: int,
    iz: int,
    open_box: bool,
    ghead: Int32Array,
    g_next: Int32Array,
    g_tri: Int32Array,
    gx: int,
    gy: int,
    gz: int,
    moved: Int64Array,
    n_moved: int,
    stamp: Int64Array,
    epoch: int,
    pts: Int64Array,
    clo: Int64Array,
    chi: Int64Array,
) -> bool:  # pragma: no cover - compiled
    # Whether a triangle meets voxel i's cube, closed or (open_box) open: the moved triangles (not yet in
    # the buckets of their new boxes), then the buckets of the cube's grid cells.
    clo[0], clo[1], clo[2] = 4 * ix - 2, 4 * iy - 2, 4 * iz - 2
    chi[0], chi[1], chi[2] = 4 * ix + 2, 4 * iy + 2, 4 * iz + 2
    for i in range(n_moved):
        o = moved[i]
        for c in range(3):
            for d in range(3):
                pts[c, d] = q[t[o, c], d]
        if _triangle_meets_box(pts, clo, chi, open_box):
            return True
    for c2 in range(max(0, clo[2] // _CELL), min(gz - 1, chi[2] // _CELL) + 1):
        for c1 in range(max(0, clo[1] // _CELL), min(gy - 1, chi[1] // _CELL) + 1):
            for c0 in range(max(0, clo[0] // _CELL), min(gx - 1, chi[0] // _CELL) + 1):
                e = ghead[(c2 * gy + c1) * gx + c0]
                while e >= 0:
                    o = g_tri[e]
                    e = g_next[e]
                    if stamp[o] == epoch or not alive[o]:
                        continue
                    stamp[o] = epoch
                    for c in range(3):
                        for d in range(3):
                            pts[c, d] = q[t[o, c], d]
                    if _triangle_meets_box(pts, clo, chi, open_box):
                        return True
    return False


@njit(cache=True)
def _turns_too_far(
    q: Int64Array, t: Int64Array, k: int, u: int, v: int, min_cos: float
) -> bool:  # pragma: no cover
    # Whether triangle k's normal turns by more than acos(min_cos) when u becomes v: a heuristic of shape (a
    # collapse that folds a triangle over makes spikes), not of correctness, so plain floats.
    a, b, c = t[k, 0], t[k, 1], t[k, 2]
    n0 = _float_normal(q[a], q[b], q[c])
    pa, pb, pc = q[v] if a == u else q[a], q[v] if b == u else q[b], q[v] if c == u else q[c]
    n1 = _float_normal(pa, pb, pc)
    return n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2] < min_cos


@njit(cache=True)
def _float_normal(
    a: Int64Array, b: Int64Array, c: Int64Array
) -> tuple[float, float, float]:  # pragma: no cover
    # The unit normal in floats (for the shape heuristics only).
    ix, iy, iz = _normal(a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2])
    nx, ny, nz = float(ix), float(iy), float(iz)
    m = (nx * nx + ny * ny + nz * nz) ** 0.5
    if m == 0.0:
        return 0.0, 0.0, 0.0
    return nx / m, ny / m, nz / m


@njit(cache=True)
def _flatter_across(q: Int64Array, a: int, b: int, c: int, d: int) -> bool:  # pragma: no cover - compiled
    # Whether triangles (c, a, d), (d, b, c) bend less than (a, b, c), (b, a, d): the cosine between the two
    # normals grows (a heuristic: which flips to try; each is then proved like a collapse).
    n1 = _float_normal(q[a], q[b], q[c])
    n2 = _float_normal(q[b], q[a], q[d])
    m1 = _float_normal(q[c], q[a], q[d])
    m2 = _float_normal(q[d], q[b], q[c])
    if m1 == (0.0, 0.0, 0.0) or m2 == (0.0, 0.0, 0.0):
        return False
    before = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2]
    after = m1[0] * m2[0] + m1[1] * m2[1] + m1[2] * m2[2]
    return after > before + 1e-9


@njit(cache=True)
def _new_meet_forbidden(
    q: Int64Array, t: Int64Array, new: Int64Array, n_new: int, forbidden: BoolArray, s: _Scratch
) -> bool:  # pragma: no cover - compiled
    # Whether a new triangle meets a forbidden closed cube.
    pts = s.pts
    for i in range(n_new):
        for c in range(3):
            for d in range(3):
                pts[c, d] = q[t[new[i], c], d]
        if _meets_forbidden(pts, forbidden, s.lo_i, s.hi_i, s.clo, s.chi, s.idx):
            return True
    return False


@njit(cache=True)
def _change_is_right(
    q: Int64Array,
    qf: FloatArray,
    t: Int64Array,
    alive: BoolArray,
    new: Int64Array,
    n_new: int,
    tets: Int64Array,
    n_tets: int,
    blo: Int64Array,
    bhi: Int64Array,
    covers: bool,
    in_a: BoolArray,
    inside: BoolArray,
    forbidden: BoolArray,
    s: _Scratch,
    ghead: Int32Array,
    g_next: Int32Array,
    g_tri: Int32Array,
    gx: int,
    gy: int,
    gz: int,
    stamp: Int64Array,
    epoch: int,
) -> tuple[bool, int]:  # pragma: no cover - compiled
    # Whether a change already made in t (a collapse or a flip) keeps the contract: its new triangles, the
    # tetrahedra (apex, old triangle) it swept, and the box of everything it touched. `inside` is updated
    # when it does; the epoch returned is past every stamp used.
    pts = s.pts
    # 1. No new triangle is flat (cheap; every later check needs planes).
    for i in range(n_new):
        for c in range(3):
            for d in range(3):
                pts[c, d] = q[t[new[i], c], d]
        if _normal_of(pts) == (0, 0, 0):
            return False, epoch
    # The cheaper refusal first: under gauss most changes refused are refused for a centre (2), under the
    # covers for a forbidden cube (3). The checks have no effect on a change refused, so the order is free.
    if covers and _new_meet_forbidden(q, t, new, n_new, forbidden, s):
        return False, epoch
    # 2. The centres that change side: each swept tetrahedron adds its sign to the centres it holds (the
    # winding number of the old star minus the new one, coned from the apex). None may under gauss, nor lie
    # on a new triangle; under the covers only centres of A may.
    acc, seen, found, flips = s.acc, s.seen, s.found, s.flips
    c0x, c0y, c0z = (blo[0] + 3) // 4, (blo[1] + 3) // 4, (blo[2] + 3) // 4
    touched = 0
    # Under gauss, tetrahedra all of one sign cannot cancel: the first centre in any refuses the change, and
    # none in any means none changes side (no winding numbers to add up).
    one_sign = not covers
    sign = 0
    for j in range(n_tets if one_sign else 0):
        apex, p, r, w = tets[j, 0], tets[j, 1], tets[j, 2], tets[j, 3]
        vol = _det(
            q[apex, 0], q[apex, 1], q[apex, 2], q[p, 0], q[p, 1], q[p, 2], q[r, 0], q[r, 1], q[r, 2], q[w, 0],
            q[w, 1], q[w, 2],
        )  # fmt: skip
        if vol != 0:
            if sign != 0 and (vol > 0) != (sign > 0):
                one_sign = False
                break
            sign = 1 if vol > 0 else -1
    for j in range(n_tets if one_sign else 0):
        apex, p, r, w = tets[j, 0], tets[j, 1], tets[j, 2], tets[j, 3]
        if _det(
            q[apex, 0], q[apex, 1], q[apex, 2], q[p, 0], q[p, 1], q[p, 2], q[r, 0], q[r, 1], q[r, 2], q[w, 0],
            q[w, 1], q[w, 2],
        ) != 0 and _tet_centres(q, apex, p, r, w, found, s.lo_i, s.hi_i, s.idx, True) != 0:  # fmt: skip
            return False, epoch
    for j in range(0 if one_sign else n_tets):
        apex, p, r, w = tets[j, 0], tets[j, 1], tets[j, 2], tets[j, 3]
        vol = _det(
            q[apex, 0], q[apex, 1], q[apex, 2], q[p, 0], q[p, 1], q[p, 2], q[r, 0], q[r, 1], q[r, 2], q[w, 0],
            q[w, 1], q[w, 2],
        )  # fmt: skip
        if vol == 0:
            continue
        m = _tet_centres(q, apex, p, r, w, found, s.lo_i, s.hi_i, s.idx, False)
        if m < 0:
            touched = seen.shape[0] + 1
            break
        for e in range(m):
            cz, cy, cx = found[e, 2] - c0z, found[e, 1] - c0y, found[e, 0] - c0x
            acc[cz, cy, cx] += np.int16(1 if vol > 0 else -1)
            if touched < seen.shape[0]:
                seen[touched, 0], seen[touched, 1], seen[touched, 2] = cz, cy, cx
            touched += 1
    if touched > seen.shape[0]:  # too many to list (never in practice): clear it all, refuse the change
        acc[:, :, :] = 0
        return False, epoch
    n_flips = 0
    bad = False
    for e in range(touched):
        kz, ky, kx = seen[e, 0], seen[e, 1], seen[e, 2]
        if acc[kz, ky, kx] == 0:
            continue  # cancelled, or met already
        acc[kz, ky, kx] = 0
        ix, iy, iz = c0x + kx, c0y + ky, c0z + kz
        if bad or not covers or not in_a[iz, iy, ix] or n_flips == flips.shape[0]:
            bad = True
            continue
        flips[n_flips, 0], flips[n_flips, 1], flips[n_flips, 2] = ix, iy, iz
        n_flips += 1
    if bad:
        return False, epoch
    if not covers:
        for i in range(n_new):
            for c in range(3):
                for d in range(3):
                    pts[c, d] = q[t[new[i], c], d]
            if _centre_on(pts, s.lo_i, s.hi_i, s.idx):
                return False, epoch
    # 3. No new triangle meets a forbidden closed cube (under gauss; under the covers before 2).
    if not covers and _new_meet_forbidden(q, t, new, n_new, forbidden, s):
        return False, epoch
    # 4. No new triangle meets another beyond what they share: each other, then the triangles of the grid
    # cells their planes cross (the new ones are not yet in the buckets of their new boxes).
    for i in range(n_new):
        for j in range(i + 1, n_new):
            if triangles_meet_improperly(qf, t, new[i], new[j]) != DISJOINT:
                return False, epoch
    for i in range(n_new):
        k = new[i]
        epoch += 1
        for j in range(n_new):
            stamp[new[j]] = epoch
        m = _triangle_cells(q, t, k, gx, gy, s.cb, s.cells)
        if m < 0:
            return False, epoch + 1
        k0, k1, k2 = t[k, 0], t[k, 1], t[k, 2]
        x0, x1 = min(q[k0, 0], q[k1, 0], q[k2, 0]), max(q[k0, 0], q[k1, 0], q[k2, 0])
        y0, y1 = min(q[k0, 1], q[k1, 1], q[k2, 1]), max(q[k0, 1], q[k1, 1], q[k2, 1])
        z0, z1 = min(q[k0, 2], q[k1, 2], q[k2, 2]), max(q[k0, 2], q[k1, 2], q[k2, 2])
        for ci in range(m):
            e = ghead[s.cells[ci]]
            while e >= 0:
                o = g_tri[e]
                e = g_next[e]
                if stamp[o] == epoch or not alive[o]:
                    continue
                stamp[o] = epoch
                # Closed boxes apart: the triangles are too (most of a cell's triangles; exact, and far
                # cheaper than the pair test's orientation predicates).
                o0, o1, o2 = t[o, 0], t[o, 1], t[o, 2]
                if (
                    max(q[o0, 0], q[o1, 0], q[o2, 0]) < x0
                    or min(q[o0, 0], q[o1, 0], q[o2, 0]) > x1
                    or max(q[o0, 1], q[o1, 1], q[o2, 1]) < y0
                    or min(q[o0, 1], q[o1, 1], q[o2, 1]) > y1
                    or max(q[o0, 2], q[o1, 2], q[o2, 2]) < z0
                    or min(q[o0, 2], q[o1, 2], q[o2, 2]) > z1
                ):
                    continue
                if triangles_meet_improperly(qf, t, k, o) != DISJOINT:
                    return False, epoch + 1
    # 5. Covers: every voxel of A near the change whose centre is outside R(A) now (it left in this change
    # or before) still meets R(A) in its open cube, through a triangle (its centre is outside, so the cube is
    # not inside R).
    if covers:
        for f in range(n_flips):
            inside[flips[f, 2], flips[f, 1], flips[f, 0]] ^= True
        for iz in range((blo[2] - 2 + 3) // 4, (bhi[2] + 2) // 4 + 1):
            for iy in range((blo[1] - 2 + 3) // 4, (bhi[1] + 2) // 4 + 1):
                for ix in range((blo[0] - 2 + 3) // 4, (bhi[0] + 2) // 4 + 1):
                    if not in_a[iz, iy, ix] or inside[iz, iy, ix]:
                        continue
                    epoch += 1
                    if not _cell_is_met(
                        q, t, alive, ix, iy, iz, True, ghead, g_next, g_tri, gx, gy, gz, new, n_new, stamp,
                        epoch, pts, s.clo, s.chi,
                    ):  # fmt: skip
                        for f in range(n_flips):
                            inside[flips[f, 2], flips[f, 1], flips[f, 0]] ^= True
                        return False, epoch + 1
    return True, epoch + 1


@njit(cache=True)
def _neighbours(
    vhead: Int64Array,
    s_next: Int32Array,
    s_tri: Int32Array,
    alive: BoolArray,
    t: Int64Array,
    x: int,
    out: Int64Array,
) -> int:  # pragma: no cover - compiled
    # The distinct neighbours of vertex x (from its star's live triangles) into out; −1 beyond its size.
    n = 0
    e = vhead[x]
    while e >= 0:
        k = s_tri[e]
        e = s_next[e]
        if not alive[k] or (t[k, 0] != x and t[k, 1] != x and t[k, 2] != x):
            continue
        for c in range(3):
            w = t[k, c]
            if w == x:
                continue
            known = False
            for j in range(n):
                if out[j] == w:
                    known = True
                    break
            if not known:
                if n == out.shape[0]:
                    return -1
                out[n] = w
                n += 1
    return n


#: The moves, each with its own flag of the vertices to try again (their star changed since it failed there):
#: half-edge collapses, collapses onto a point, moves of a vertex.
_HALF, _POINT, _MOVE = 0, 1, 2
#: What :func:`_collapse` returns: kept or not, the star pools and their size, the bucket pools and their
#: size, the epoch.
_Collapsed = tuple[bool, Int32Array, Int32Array, int, Int32Array, Int32Array, int, int]


class _Buffers(NamedTuple):
    """The working arrays of one collapse, allocated once per run."""

    star_u: Int64Array  # (256,): the live triangles at u
    star_v: Int64Array  # (256,): the live triangles at v
    moved: Int64Array  # (512,): the triangles a collapse keeps, with new corners
    old: Int64Array  # (512, 3): their corners before it (to undo a refused one)
    gone: Int64Array  # (2,): the two triangles of the edge
    nbr_u: Int64Array  # (256,)
    nbr_v: Int64Array  # (256,)
    tets: Int64Array  # (512, 4): the tetrahedra (apex, old triangle) swept
    blo: Int64Array  # (3,): the box of everything a change touches
    bhi: Int64Array  # (3,)
    quad: FloatArray  # (3, 4): the normal equations of a quadric's point
    shell: Int64Array  # (triangles,): the shell of each triangle (a change keeps every triangle in its shell)
    volume: Int64Array  # (shells,): six times each shell's signed volume, in the integer units


@njit(cache=True)
def _star(
    vhead: Int64Array, s_next: Int32Array, s_tri: Int32Array, alive: BoolArray, t: Int64Array, x: int,
    out: Int64Array,
) -> int:  # fmt: skip  # pragma: no cover - compiled
    # The distinct live triangles at vertex x into out (an entry may be stale or repeated: a triangle that
    # left x and came back has two); −1 beyond out's size.
    n = 0
    e = vhead[x]
    while e >= 0:
        k = s_tri[e]
        e = s_next[e]
        if not alive[k] or (t[k, 0] != x and t[k, 1] != x and t[k, 2] != x):
            continue
        known = False
        for j in range(n):
            if out[j] == k:
                known = True
                break
        if known:
            continue
        if n == out.shape[0]:
            return -1
        out[n] = k
        n += 1
    return n


@njit(cache=True, inline="always")
def _holds_vertex(t: Int64Array, k: int, x: int) -> bool:  # pragma: no cover - compiled
    # Whether triangle k has the vertex x.
    return bool(t[k, 0] == x or t[k, 1] == x or t[k, 2] == x)


@njit(cache=True)
def _shells(q: Int64Array, t: Int64Array) -> tuple[Int64Array, Int64Array]:  # pragma: no cover - compiled
    # The shell of each triangle (the components of the vertex graph: shells share no vertex) and six times
    # each shell's signed volume (Σ a · (b × c) over its triangles).
    n, ids = components(q.shape[0], np.concatenate((t[:, 0], t[:, 0])), np.concatenate((t[:, 1], t[:, 2])))
    shell = np.empty(t.shape[0], np.int64)
    for k in range(t.shape[0]):
        shell[k] = ids[t[k, 0]]
    volume = np.zeros(n, np.int64)
    for k in range(t.shape[0]):
        a, b, c = t[k, 0], t[k, 1], t[k, 2]
        volume[shell[k]] += _det(
            0, 0, 0, q[a, 0], q[a, 1], q[a, 2], q[b, 0], q[b, 1], q[b, 2], q[c, 0], q[c, 1], q[c, 2]
        )
    return shell, volume


@njit(cache=True)
def _volume_after(q: Int64Array, tets: Int64Array, n_tets: int, before: int) -> int:  # pragma: no cover
    # Six times the shell's signed volume after a change that swept these tetrahedra (old surface minus new,
    # coned from the apex), or 0 when its sign changes or it vanishes: the checks of centres, cubes and
    # intersections do not see a small shell that holds no centre turn inside out (under the covers its
    # centres may leave), its volume's sign does — an embedded closed surface faces all out or all in.
    swept = 0
    for j in range(n_tets):
        a, p, r, w = tets[j, 0], tets[j, 1], tets[j, 2], tets[j, 3]
        swept += _det(
            q[a, 0], q[a, 1], q[a, 2], q[p, 0], q[p, 1], q[p, 2], q[r, 0], q[r, 1], q[r, 2], q[w, 0], q[w, 1],
            q[w, 2],
        )  # fmt: skip
    after = before - swept
    return after if (after > 0) == (before > 0) and after != 0 else 0


@njit(cache=True)
def _same_point_set(
    q: Int64Array,
    t: Int64Array,
    tets: Int64Array,
    n_tets: int,
    moved: Int64Array,
    n_moved: int,
    old: Int64Array,
) -> bool:  # pragma: no cover - compiled
    # Whether a collapse, made tentatively, leaves the surface the same set of points: it sweeps no volume
    # (w lies in the plane of every old triangle, so the star and its new fan lie in the same planes, which
    # all hold w) and no new triangle turns over in its plane. In each plane the old and the new triangles
    # then have the same boundary but for segments on the lines where the planes meet, so they cover the
    # same region once (each covers it as many times as the boundary winds, once: the old star is a disk).
    # Then every check of _change_is_right holds as it held before: nothing to test. Most collapses of the
    # safety net's flat staircase are such.
    for j in range(n_tets):
        a, p, r, c = tets[j, 0], tets[j, 1], tets[j, 2], tets[j, 3]
        if _det(
            q[a, 0], q[a, 1], q[a, 2], q[p, 0], q[p, 1], q[p, 2], q[r, 0], q[r, 1], q[r, 2], q[c, 0], q[c, 1],
            q[c, 2],
        ) != 0:  # fmt: skip
            return False
    for i in range(n_moved):
        k = moved[i]
        nx, ny, nz = _normal(
            q[t[k, 0], 0], q[t[k, 0], 1], q[t[k, 0], 2], q[t[k, 1], 0], q[t[k, 1], 1], q[t[k, 1], 2],
            q[t[k, 2], 0], q[t[k, 2], 1], q[t[k, 2], 2],
        )  # fmt: skip
        ox, oy, oz = _normal(
            q[old[i, 0], 0], q[old[i, 0], 1], q[old[i, 0], 2], q[old[i, 1], 0], q[old[i, 1], 1],
            q[old[i, 1], 2], q[old[i, 2], 0], q[old[i, 2], 1], q[old[i, 2], 2],
        )  # fmt: skip
        if nx * ox + ny * oy + nz * oz <= 0:
            return False
    return True


@njit(cache=True)
def _collapse(
    u: int, v: int, w: int, q: Int64Array, qf: FloatArray, t: Int64Array, alive: BoolArray,
    vdead: BoolArray, dirty: BoolArray, vhead: Int64Array, s_next: Int32Array,
    s_tri: Int32Array, ns: int, ghead: Int32Array, g_next: Int32Array, g_tri: Int32Array, ng: int, gx: int,
    gy: int, gz: int, stamp: Int64Array, epoch: int, b: _Buffers, covers: bool, in_a: BoolArray,
    inside: BoolArray, forbidden: BoolArray, sc: _Scratch, min_cos: float,
) -> _Collapsed:  # fmt: skip  # pragma: no cover
    # Collapse the edge u v onto w, and keep it only if it is right: w = v (a half-edge collapse: u goes, its
    # triangles take v) or a new vertex whose q is set (u and v both go). The two triangles of the edge go;
    # every other triangle at u or v takes w. The volume swept is coned from w over the old triangles. With
    # v = u, u moves to the new vertex w (no triangle goes).
    fail = (False, s_next, s_tri, ns, g_next, g_tri, ng, epoch)
    n_u = _star(vhead, s_next, s_tri, alive, t, u, b.star_u)
    n_v = _star(vhead, s_next, s_tri, alive, t, v, b.star_v)
    if n_u < 0 or n_v < 0:
        return fail
    moved, gone = b.moved, b.gone
    n_gone = 0
    n_moved = 0
    relocate = v == u
    for i in range(n_u):
        k = b.star_u[i]
        if not relocate and _holds_vertex(t, k, v):
            if n_gone == 2:
                return fail
            gone[n_gone] = k
            n_gone += 1
        else:
            moved[n_moved] = k
            n_moved += 1
    if n_gone != (0 if relocate else 2):
        return fail
    if w != v and not relocate:
        for i in range(n_v):
            k = b.star_v[i]
            if not _holds_vertex(t, k, u):
                moved[n_moved] = k
                n_moved += 1
    # Link condition: the common neighbours of u and v are the two opposite vertices.
    n_nu = _neighbours(vhead, s_next, s_tri, alive, t, u, b.nbr_u)
    n_nv = _neighbours(vhead, s_next, s_tri, alive, t, v, b.nbr_v)
    if n_nu < 0 or n_nv < 0:
        return fail
    common = 0 if relocate else 2
    for i in range(n_nu if not relocate else 0):
        x = b.nbr_u[i]
        if x == v:
            continue
        for j in range(n_nv):
            if b.nbr_v[j] == x:
                common -= 1
                break
    if common != 0:
        return fail
    # The box of the change (u, v, w and every corner of the moved triangles), and its extent.
    blo, bhi = b.blo, b.bhi
    for d in range(3):
        blo[d] = min(q[u, d], q[v, d], q[w, d])
        bhi[d] = max(q[u, d], q[v, d], q[w, d])
    for i in range(n_moved):
        for c in range(3):
            x = t[moved[i], c]
            for d in range(3):
                blo[d] = min(blo[d], q[x, d])
                bhi[d] = max(bhi[d], q[x, d])
    if max(bhi[0] - blo[0], bhi[1] - blo[1], bhi[2] - blo[2]) > _MAX_EXTENT:
        return fail
    # No new triangle turns over (a heuristic of shape: fold-overs make spikes).
    for i in range(n_moved):
        k = moved[i]
        if _turns_too_far(q, t, k, u if _holds_vertex(t, k, u) else v, w, min_cos):
            return fail
    # The swept tetrahedra (w, old triangle) — those at w are flat and count nothing — then the collapse,
    # made tentatively, is checked.
    tets = b.tets
    n_tets = 0
    for i in range(n_moved + n_gone * (w != v)):
        k = moved[i] if i < n_moved else gone[i - n_moved]
        tets[n_tets, 0] = w
        tets[n_tets, 1], tets[n_tets, 2], tets[n_tets, 3] = t[k, 0], t[k, 1], t[k, 2]
        n_tets += 1
    volume = _volume_after(q, tets, n_tets, b.volume[b.shell[moved[0]]])
    if volume == 0:
        return fail
    for i in range(n_moved):
        k = moved[i]
        for c in range(3):
            b.old[i, c] = t[k, c]
            if t[k, c] == u or t[k, c] == v:
                t[k, c] = w
    for i in range(n_gone):
        alive[gone[i]] = False
    if _same_point_set(q, t, tets, n_tets, moved, n_moved, b.old):
        ok = True
    else:
        ok, epoch = _change_is_right(
            q, qf, t, alive, moved, n_moved, tets, n_tets, blo, bhi, covers, in_a, inside, forbidden, sc,
            ghead, g_next, g_tri, gx, gy, gz, stamp, epoch,
        )  # fmt: skip
    if not ok:
        for i in range(n_moved):
            for c in range(3):
                t[moved[i], c] = b.old[i, c]
        for i in range(n_gone):
            alive[gone[i]] = True
        return (False, s_next, s_tri, ns, g_next, g_tri, ng, epoch)
    # Kept: w's star and the buckets learn the moved triangles.
    b.volume[b.shell[moved[0]]] = volume
    vdead[u] = True
    vdead[v] = w != v
    vdead[w] = False
    for i in range(n_moved):
        k = moved[i]
        for c in range(3):
            dirty[t[k, c], :] = True
        if ns == s_next.shape[0]:
            s_next = np.concatenate((s_next, np.empty(ns, np.int32)))
            s_tri = np.concatenate((s_tri, np.empty(ns, np.int32)))
        s_next[ns] = vhead[w]
        s_tri[ns] = k
        vhead[w] = ns
        ns += 1
        g_next, g_tri, ng = _bucket(q, t, k, ghead, g_next, g_tri, ng, gx, gy, sc.cb, sc.cells)
    return (True, s_next, s_tri, ns, g_next, g_tri, ng, epoch)


@njit(cache=True)
def _point_for(
    q: Int64Array, t: Int64Array, b: _Buffers, n_u: int, n_v: int, u: int, v: int, lo: Int64Array,
    hi: Int64Array, out: Int64Array,
) -> None:  # fmt: skip  # pragma: no cover - compiled
    # Where the edge u v might collapse to: the point nearest, in squares, to the planes of the triangles at
    # u and v (their quadric), held near the edge's midpoint where those planes leave it free, rounded to
    # the integer units and clamped to the box lo..hi of the stars. A heuristic of shape (the collapse is
    # then proved like any other), so plain floats. Into out.
    m = b.quad  # the normal equations [M | r], solved by Cramer's rule
    m[:, :] = 0.0
    for i in range(n_u + n_v):
        k = b.star_u[i] if i < n_u else b.star_v[i - n_u]
        if i >= n_u and _holds_vertex(t, k, u):
            continue  # the edge's two triangles, counted once
        a = t[k, 0]
        nx, ny, nz = _float_normal(q[a], q[t[k, 1]], q[t[k, 2]])
        n = (nx, ny, nz)
        d = nx * q[a, 0] + ny * q[a, 1] + nz * q[a, 2]
        for i2 in range(3):
            m[i2, 3] += n[i2] * d
            for j2 in range(3):
                m[i2, j2] += n[i2] * n[j2]
    lam = 1e-3
    for i2 in range(3):
        m[i2, i2] += lam
        m[i2, 3] += lam * 0.5 * (q[u, i2] + q[v, i2])
    det = _det_columns(m, 0, 1, 2)
    for i2 in range(3):
        di = _det_columns(m, 3 if i2 == 0 else 0, 3 if i2 == 1 else 1, 3 if i2 == 2 else 2)
        out[i2] = min(max(int(np.rint(di / det)), lo[i2]), hi[i2])


@njit(cache=True, inline="always")
def _det_columns(m: FloatArray, c0: int, c1: int, c2: int) -> float:  # pragma: no cover - compiled
    # The determinant of the 3 × 3 matrix of m's columns c0, c1, c2.
    return float(
        m[0, c0] * (m[1, c1] * m[2, c2] - m[1, c2] * m[2, c1])
        - m[0, c1] * (m[1, c0] * m[2, c2] - m[1, c2] * m[2, c0])
        + m[0, c2] * (m[1, c0] * m[2, c1] - m[1, c1] * m[2, c0])
    )


@njit(cache=True)
def _quadric(
    q: Int64Array, t: Int64Array, b: _Buffers, n_u: int, n_v: int, u: int, p: Int64Array
) -> float:  # pragma: no cover - compiled
    # The sum of the squared distances from p to the planes of the triangles at u and v (floats: an order of
    # candidates, not a check).
    cost = 0.0
    for i in range(n_u + n_v):
        k = b.star_u[i] if i < n_u else b.star_v[i - n_u]
        if i >= n_u and _holds_vertex(t, k, u):
            continue
        a = t[k, 0]
        nx, ny, nz = _float_normal(q[a], q[t[k, 1]], q[t[k, 2]])
        e = nx * (p[0] - q[a, 0]) + ny * (p[1] - q[a, 1]) + nz * (p[2] - q[a, 2])
        cost += e * e
    return cost


@njit(cache=True)
def _bend(
    q: Int64Array, t: Int64Array, alive: BoolArray, vhead: Int64Array, s_next: Int32Array, s_tri: Int32Array,
    b: _Buffers, n_u: int, u: int, p: Int64Array, pts: Int64Array,
) -> float:  # fmt: skip  # pragma: no cover - compiled
    # How much the surface bends at u's star with u at p: the number of the star's triangle edges whose two
    # triangles are not coplanar (exactly), plus a thousandth of Σ (1 − cos) over them (a heuristic of
    # shape: a move that makes faces coplanar opens collapses; one that only rounds a corner does not).
    bent = 0
    total = 0.0
    for i in range(n_u):
        k = b.star_u[i]
        for c in range(3):
            for d in range(3):
                pts[c, d] = p[d] if t[k, c] == u else q[t[k, c], d]
        m1 = _normal_of(pts)
        n1 = _float_normal(pts[0], pts[1], pts[2])
        for c in range(3):
            x, y = t[k, c], t[k, (c + 1) % 3]
            e = vhead[x]
            o = -1
            while e >= 0 and o < 0:
                k2 = s_tri[e]
                e = s_next[e]
                if k2 != k and alive[k2]:
                    for j in range(3):
                        if t[k2, j] == y and t[k2, (j + 1) % 3] == x:
                            o = k2
            if o < 0:
                continue
            for c2 in range(3):
                for d in range(3):
                    pts[c2, d] = p[d] if t[o, c2] == u else q[t[o, c2], d]
            m2 = _normal_of(pts)
            n2 = _float_normal(pts[0], pts[1], pts[2])
            cx = m1[1] * m2[2] - m1[2] * m2[1]
            cy = m1[2] * m2[0] - m1[0] * m2[2]
            cz = m1[0] * m2[1] - m1[1] * m2[0]
            if cx != 0 or cy != 0 or cz != 0 or m1[0] * m2[0] + m1[1] * m2[1] + m1[2] * m2[2] <= 0:
                bent += 1
            total += 1.0 - (n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2])
    return bent + 1e-3 * total


@njit(cache=True)
def _sort_candidates(
    cand: Int64Array, key: FloatArray, pts: Int64Array, n: int
) -> None:  # pragma: no cover - compiled
    # The first n candidates by key, then by index (insertion sort: a vertex has a few neighbours).
    for i in range(1, n):
        j = i
        while j > 0 and (key[j - 1] > key[j] or (key[j - 1] == key[j] and cand[j - 1] > cand[j])):
            key[j - 1], key[j] = key[j], key[j - 1]
            cand[j - 1], cand[j] = cand[j], cand[j - 1]
            for d in range(3):
                pts[j - 1, d], pts[j, d] = pts[j, d], pts[j - 1, d]
            j -= 1


@njit(cache=True)
def _more_vertices(
    q: Int64Array, qf: FloatArray, vdead: BoolArray, dirty: BoolArray, vhead: Int64Array
) -> tuple[Int64Array, FloatArray, BoolArray, BoolArray, Int64Array]:  # pragma: no cover - compiled
    # The vertex arrays grown by half (the new rows: dead, dirty, with no star).
    n = q.shape[0]
    m = n // 2 + 16
    q2 = np.zeros((n + m, 3), np.int64)
    q2[:n] = q
    qf2 = np.zeros((n + m, 3), np.float64)
    qf2[:n] = qf
    vdead2 = np.ones(n + m, np.bool_)
    vdead2[:n] = vdead
    dirty2 = np.ones((n + m, 3), np.bool_)
    dirty2[:n] = dirty
    vhead2 = np.full(n + m, -1, np.int64)
    vhead2[:n] = vhead
    return q2, qf2, vdead2, dirty2, vhead2


@njit(cache=True)
def _decimate(
    q0: Int64Array,
    tri: Int64Array,
    in_a: BoolArray,
    forbidden: BoolArray,
    model: int,
    max_passes: int,
    max_collapses: int,
    max_rounds: int,
    min_cos: float,
    stop: npt.NDArray[np.uint8],
) -> tuple[Int64Array, Int64Array, BoolArray, BoolArray, int]:  # pragma: no cover - compiled
    # stop[0] set (by another thread: mrm.core.progress.stop_flag) makes it return at the next vertex or
    # triangle it looks at, with −1 removed: the caller discards the result.
    nv = q0.shape[0]
    nt = tri.shape[0]
    # Room for the new vertices (a collapse onto a point removes two vertices and adds one, a move replaces
    # one): grown by half when used up (_more_vertices).
    cap = nv + nv // 2 + 16
    q = np.zeros((cap, 3), np.int64)
    q[:nv] = q0
    qf = q.astype(np.float64)  # the exact predicates of the pair test read floats; these are small integers
    t = tri.copy()
    alive = np.ones(nt, np.bool_)
    vdead = np.ones(cap, np.bool_)
    vdead[:nv] = False
    # Whose star changed since a move last failed at it: per move (_HALF, _POINT, _MOVE).
    dirty = np.ones((cap, 3), np.bool_)
    covers = model != GAUSS
    # The side of every centre: the safety net holds exactly the centres of A. Only the covers let a centre
    # change side (of A, leaving); under gauss none does, so the array is A's own.
    inside = in_a.copy() if covers else in_a

    # Vertex stars: linked lists of triangle entries; stale ones (dead, or no longer at the vertex) skipped.
    vhead = np.full(cap, -1, np.int64)
    s_cap = 3 * nt + 2 * _ROOM
    s_next = np.empty(s_cap, np.int32)
    s_tri = np.empty(s_cap, np.int32)
    ns = 0
    for k in range(nt):
        for c in range(3):
            w = t[k, c]
            s_next[ns] = vhead[w]
            s_tri[ns] = k
            vhead[w] = ns
            ns += 1

    # Triangle buckets on a uniform grid (cells of _CELL units), also linked lists. New vertices stay in the
    # box of their stars, so inside this grid.
    gx = q0[:, 0].max() // _CELL + 1
    gy = q0[:, 1].max() // _CELL + 1
    gz = q0[:, 2].max() // _CELL + 1
    ghead = np.full(gx * gy * gz, -1, np.int32)  # int32: one per cell of the box, 2 voxels wide
    g_next = np.empty(4 * nt + 2 * _ROOM, np.int32)
    g_tri = np.empty(4 * nt + 2 * _ROOM, np.int32)
    ng = 0
    cb = np.empty(6, np.int64)
    cells = np.empty(1 << 14, np.int64)
    for k in range(nt):
        g_next, g_tri, ng = _bucket(q, t, k, ghead, g_next, g_tri, ng, gx, gy, cb, cells)

    stamp = np.zeros(nt, np.int64)
    epoch = 0
    cand = np.empty(9 * 256, np.int64)  # up to nine points per neighbour
    clen = np.empty(9 * 256, np.float64)
    cpts = np.empty((9 * 256, 3), np.int64)
    # The winding numbers of the centres of a change's box: as big as the largest box, or as A's box.
    side = _MAX_EXTENT // 4 + 2
    nz, ny, nx = in_a.shape
    sc = _Scratch(
        np.empty((3, 3), np.int64),
        np.empty(3, np.int64),
        np.empty(3, np.int64),
        np.empty(3, np.int64),
        np.empty(3, np.int64),
        np.empty(3, np.int64),
        cb,
        cells,
        np.zeros((min(side, nz + 2), min(side, ny + 2), min(side, nx + 2)), np.int16),
        np.empty((4096, 3), np.int64),
        np.empty((4096, 3), np.int64),
        np.empty((4096, 3), np.int64),
    )
    shell, volume = _shells(q0, t)
    b = _Buffers(
        np.empty(256, np.int64),
        np.empty(256, np.int64),
        np.empty(512, np.int64),
        np.empty((512, 3), np.int64),
        np.empty(2, np.int64),
        np.empty(256, np.int64),
        np.empty(256, np.int64),
        np.empty((512, 4), np.int64),
        np.empty(3, np.int64),
        np.empty(3, np.int64),
        np.empty((3, 4), np.float64),
        shell,
        volume,
    )
    plo = np.empty(3, np.int64)
    phi = np.empty(3, np.int64)
    pt = np.empty(3, np.int64)
    removed = 0
    n_now = nv  # vertices so far, new ones included
    ng_fresh = ng  # the buckets' entries when last rebuilt
    for round_ in range(max_rounds + 1):
        # Half-edge collapses: every vertex in turn tries its neighbours, farthest first (a long collapse
        # straightens the most staircase), passes until one removes nothing.
        changed = True
        passes = 0
        while changed and passes < max_passes:
            changed = False
            passes += 1
            for u in range(n_now):
                if stop[0] != 0:
                    return q[:n_now], t, alive, vdead[:n_now], -1
                if vdead[u] or not dirty[u, _HALF] or removed == max_collapses:
                    continue
                g_next, g_tri, ng, ng_fresh, s_next, s_tri, ns = _tidy(
                    q, t, alive, ghead, g_next, g_tri, ng, ng_fresh, gx, gy, cb, cells, vhead, s_next, s_tri,
                    ns, n_now,
                )  # fmt: skip
                dirty[u, _HALF] = False
                n_nu = _neighbours(vhead, s_next, s_tri, alive, t, u, b.nbr_u)
                if n_nu < 0:
                    continue
                for i in range(n_nu):
                    w = b.nbr_u[i]
                    dx, dy, dz = q[w, 0] - q[u, 0], q[w, 1] - q[u, 1], q[w, 2] - q[u, 2]
                    cand[i] = w
                    clen[i] = -float(dx * dx + dy * dy + dz * dz)
                _sort_candidates(cand, clen, cpts, n_nu)
                for ci in range(n_nu):
                    ok, s_next, s_tri, ns, g_next, g_tri, ng, epoch = _collapse(
                        u, cand[ci], cand[ci], q, qf, t, alive, vdead, dirty, vhead, s_next, s_tri,
                        ns, ghead, g_next, g_tri, ng, gx, gy, gz, stamp, epoch, b, covers, in_a, inside,
                        forbidden, sc, min_cos,
                    )  # fmt: skip
                    if ok:
                        removed += 1
                        changed = True
                        break  # u is gone

        # Collapses onto a point: an edge whose two ends both go, to the point its triangles' planes meet
        # nearest (rounded to the integer units: a quarter voxel) — off the safety net's lattice, where a
        # tip or a ridge of the ideal solid lies. Cheapest quadric first; new half-edge collapses follow.
        pointed = 0
        changed = True
        passes = 0
        while changed and passes < max_passes:
            changed = False
            passes += 1
            for u in range(n_now):
                if stop[0] != 0:
                    return q[:n_now], t, alive, vdead[:n_now], -1
                if vdead[u] or not dirty[u, _POINT] or removed == max_collapses:
                    continue
                g_next, g_tri, ng, ng_fresh, s_next, s_tri, ns = _tidy(
                    q, t, alive, ghead, g_next, g_tri, ng, ng_fresh, gx, gy, cb, cells, vhead, s_next, s_tri,
                    ns, n_now,
                )  # fmt: skip
                dirty[u, _POINT] = False
                n_nu = _neighbours(vhead, s_next, s_tri, alive, t, u, b.nbr_u)
                n_su = _star(vhead, s_next, s_tri, alive, t, u, b.star_u)
                if n_nu < 0 or n_su < 0:
                    continue
                n_c = 0
                for i in range(n_nu):
                    v = b.nbr_u[i]
                    n_sv = _star(vhead, s_next, s_tri, alive, t, v, b.star_v)
                    if n_sv < 0:
                        continue
                    for d in range(3):
                        plo[d] = min(q[u, d], q[v, d])
                        phi[d] = max(q[u, d], q[v, d])
                    for j in range(n_su + n_sv):
                        k = b.star_u[j] if j < n_su else b.star_v[j - n_su]
                        for c in range(3):
                            for d in range(3):
                                plo[d] = min(plo[d], q[t[k, c], d])
                                phi[d] = max(phi[d], q[t[k, c], d])
                    # The points tried: the quadric's, and the edge's midpoint rounded every way to the
                    # integer units (where a tip or a ridge of two vertices closes).
                    _point_for(q, t, b, n_su, n_sv, u, v, plo, phi, pt)
                    first = n_c
                    for which in range(9):
                        if which > 0:
                            twice = False  # an even sum has one rounding: that with up = 0
                            for d in range(3):
                                up = (which - 1) >> d & 1
                                s2 = q[u, d] + q[v, d]
                                twice = twice or (up == 1 and s2 % 2 == 0)
                                pt[d] = (s2 + up) // 2
                            if twice:
                                continue
                        if (pt[0] == q[u, 0] and pt[1] == q[u, 1] and pt[2] == q[u, 2]) or (
                            pt[0] == q[v, 0] and pt[1] == q[v, 1] and pt[2] == q[v, 2]
                        ):
                            continue  # a half-edge collapse, tried already
                        known = False
                        for ci in range(first, n_c):
                            known = known or (
                                cpts[ci, 0] == pt[0] and cpts[ci, 1] == pt[1] and cpts[ci, 2] == pt[2]
                            )
                        if known:
                            continue
                        cand[n_c] = v
                        clen[n_c] = _quadric(q, t, b, n_su, n_sv, u, pt)
                        cpts[n_c, 0], cpts[n_c, 1], cpts[n_c, 2] = pt[0], pt[1], pt[2]
                        n_c += 1
                _sort_candidates(cand, clen, cpts, n_c)
                for ci in range(min(n_c, _POINT_TRIES)):
                    if n_now == q.shape[0]:
                        q, qf, vdead, dirty, vhead = _more_vertices(q, qf, vdead, dirty, vhead)
                    w = n_now
                    for d in range(3):
                        q[w, d] = cpts[ci, d]
                        qf[w, d] = float(cpts[ci, d])
                    ok, s_next, s_tri, ns, g_next, g_tri, ng, epoch = _collapse(
                        u, cand[ci], w, q, qf, t, alive, vdead, dirty, vhead, s_next, s_tri, ns,
                        ghead, g_next, g_tri, ng, gx, gy, gz, stamp, epoch, b, covers, in_a, inside,
                        forbidden, sc, min_cos,
                    )  # fmt: skip
                    if ok:
                        n_now += 1
                        removed += 1
                        pointed += 1
                        changed = True
                        break  # u is gone
        # Moves: a vertex goes a quarter voxel when that makes more of its star's neighbouring triangles
        # exactly coplanar (a vertex left off the ridge or the tip of the ideal solid stops the collapses that
        # would straighten it). One pass per round, the best three tried, each proved like a collapse.
        for u in range(n_now):
            if stop[0] != 0:
                return q[:n_now], t, alive, vdead[:n_now], -1
            if vdead[u] or not dirty[u, _MOVE]:
                continue
            g_next, g_tri, ng, ng_fresh, s_next, s_tri, ns = _tidy(
                q, t, alive, ghead, g_next, g_tri, ng, ng_fresh, gx, gy, cb, cells, vhead, s_next, s_tri,
                ns, n_now,
            )  # fmt: skip
            dirty[u, _MOVE] = False
            n_su = _star(vhead, s_next, s_tri, alive, t, u, b.star_u)
            if n_su < 0:
                continue
            for d in range(3):
                plo[d] = q[u, d]
                phi[d] = q[u, d]
            for j in range(n_su):
                for c in range(3):
                    for d in range(3):
                        plo[d] = min(plo[d], q[t[b.star_u[j], c], d])
                        phi[d] = max(phi[d], q[t[b.star_u[j], c], d])
            here = _bend(q, t, alive, vhead, s_next, s_tri, b, n_su, u, q[u], sc.pts)
            n_c = 0
            for dz in range(-1, 2):
                for dy in range(-1, 2):
                    for dx in range(-1, 2):
                        pt[0], pt[1], pt[2] = q[u, 0] + dx, q[u, 1] + dy, q[u, 2] + dz
                        if (dx == 0 and dy == 0 and dz == 0) or not (
                            plo[0] <= pt[0] <= phi[0]
                            and plo[1] <= pt[1] <= phi[1]
                            and plo[2] <= pt[2] <= phi[2]
                        ):
                            continue
                        there = _bend(q, t, alive, vhead, s_next, s_tri, b, n_su, u, pt, sc.pts)
                        if there < here - 1e-9:
                            cand[n_c] = u
                            clen[n_c] = there
                            cpts[n_c, 0], cpts[n_c, 1], cpts[n_c, 2] = pt[0], pt[1], pt[2]
                            n_c += 1
            _sort_candidates(cand, clen, cpts, n_c)
            for ci in range(min(n_c, 3)):
                if n_now == q.shape[0]:
                    q, qf, vdead, dirty, vhead = _more_vertices(q, qf, vdead, dirty, vhead)
                w = n_now
                for d in range(3):
                    q[w, d] = cpts[ci, d]
                    qf[w, d] = float(cpts[ci, d])
                ok, s_next, s_tri, ns, g_next, g_tri, ng, epoch = _collapse(
                    u, u, w, q, qf, t, alive, vdead, dirty, vhead, s_next, s_tri, ns, ghead, g_next, g_tri,
                    ng, gx, gy, gz, stamp, epoch, b, covers, in_a, inside, forbidden, sc, min_cos,
                )  # fmt: skip
                if ok:
                    n_now += 1
                    pointed += 1
                    break

        # Edge flips: an edge whose two triangles would be flatter across the other diagonal is flipped, under
        # the same checks as a collapse (the swept volume is the tetrahedron a b c d); new collapses follow.
        if round_ == max_rounds:
            break
        flipped = 0
        for k in range(nt):
            if stop[0] != 0:
                return q[:n_now], t, alive, vdead[:n_now], -1
            if not alive[k]:
                continue
            g_next, g_tri, ng, ng_fresh, s_next, s_tri, ns = _tidy(
                q, t, alive, ghead, g_next, g_tri, ng, ng_fresh, gx, gy, cb, cells, vhead, s_next, s_tri,
                ns, n_now,
            )  # fmt: skip
            for c_ in range(3):
                a, b_, c = t[k, c_], t[k, (c_ + 1) % 3], t[k, (c_ + 2) % 3]
                # the triangle across a b: (b, a, d)
                k2 = -1
                e = vhead[a]
                while e >= 0:
                    o = s_tri[e]
                    e = s_next[e]
                    if o != k and alive[o]:
                        for j in range(3):
                            if t[o, j] == b_ and t[o, (j + 1) % 3] == a:
                                k2 = o
                                break
                    if k2 >= 0:
                        break
                if k2 < 0 or k2 < k:  # each edge once (from its lower triangle)
                    continue
                d = t[k2, 0] + t[k2, 1] + t[k2, 2] - a - b_
                if d == c:
                    continue
                # c and d must not be neighbours already
                adjacent = False
                e = vhead[c]
                while e >= 0 and not adjacent:
                    o = s_tri[e]
                    e = s_next[e]
                    if alive[o] and (t[o, 0] == c or t[o, 1] == c or t[o, 2] == c):
                        adjacent = t[o, 0] == d or t[o, 1] == d or t[o, 2] == d
                if adjacent:
                    continue
                if not _flatter_across(q, a, b_, c, d):
                    continue
                ext = 0
                for dd in range(3):
                    lo_ = min(q[a, dd], q[b_, dd], q[c, dd], q[d, dd])
                    hi_ = max(q[a, dd], q[b_, dd], q[c, dd], q[d, dd])
                    b.blo[dd] = lo_
                    b.bhi[dd] = hi_
                    ext = max(ext, hi_ - lo_)
                if ext > _MAX_EXTENT:
                    continue
                # tentatively: k = (c, a, d), k2 = (d, b, c); the volume swept is the tetrahedron (d, a, b, c)
                t[k, 0], t[k, 1], t[k, 2] = c, a, d
                t[k2, 0], t[k2, 1], t[k2, 2] = d, b_, c
                b.moved[0], b.moved[1] = k, k2
                b.tets[0, 0], b.tets[0, 1], b.tets[0, 2], b.tets[0, 3] = d, a, b_, c
                after = _volume_after(q, b.tets, 1, b.volume[b.shell[k]])
                ok = after != 0
                if ok:
                    ok, epoch = _change_is_right(
                        q, qf, t, alive, b.moved, 2, b.tets, 1, b.blo, b.bhi, covers, in_a, inside, forbidden,
                        sc, ghead, g_next, g_tri, gx, gy, gz, stamp, epoch,
                    )  # fmt: skip
                if not ok:
                    t[k, 0], t[k, 1], t[k, 2] = a, b_, c
                    t[k2, 0], t[k2, 1], t[k2, 2] = b_, a, d
                    continue
                b.volume[b.shell[k]] = after
                flipped += 1
                for x in (a, b_, c, d):
                    dirty[x, :] = True
                for kk, w in ((k, d), (k2, c)):
                    if ns == s_next.shape[0]:
                        s_next = np.concatenate((s_next, np.empty(ns, np.int32)))
                        s_tri = np.concatenate((s_tri, np.empty(ns, np.int32)))
                    s_next[ns] = vhead[w]
                    s_tri[ns] = kk
                    vhead[w] = ns
                    ns += 1
                    g_next, g_tri, ng = _bucket(q, t, kk, ghead, g_next, g_tri, ng, gx, gy, cb, cells)
                break  # k changed: its other edges wait for the next round
        if flipped == 0 and pointed == 0:
            break
    return q[:n_now], t, alive, vdead[:n_now], removed


#: The 24 rotations of the cube as signed permutations of (x, y, z):
#: new coordinate k = sign[k] · old[perm[k]].
ROTATIONS: tuple[tuple[tuple[int, int, int], tuple[int, int, int]], ...] = tuple(
    (cast(tuple[int, int, int], perm), cast(tuple[int, int, int], signs))
    for perm in itertools.permutations(range(3))
    for signs in itertools.product((1, -1), repeat=3)
    if round(float(np.linalg.det(np.eye(3)[list(perm)] * np.array(signs)))) == 1
)


def _turn(mask: BoolArray, perm: tuple[int, ...], signs: tuple[int, ...]) -> BoolArray:
    # The mask (z, y, x) of the turned set, placed at the origin of its own box.
    out = mask.transpose([2 - perm[2], 2 - perm[1], 2 - perm[0]])
    flips = tuple(2 - k for k in range(3) if signs[k] < 0)
    return np.flip(out, flips) if flips else out


def turn_points(
    p: PointsT, perm: tuple[int, int, int], signs: tuple[int, int, int], size: tuple[int, int, int]
) -> PointsT:
    """Points (x, y, z) of A's box (array indices) in the turned frame of :func:`_turn`.

    Turned coordinate k is ``signs[k] · p[perm[k]]``, plus ``size[perm[k]] − 1`` when flipped: the turned
    box starts at 0 again. ``size`` is A's box (nx, ny, nz).
    """
    out = np.empty_like(p)
    for k in range(3):
        j = perm[k]
        out[:, k] = p[:, j] if signs[k] > 0 else (size[j] - 1) - p[:, j]
    return out


def turn_back_points(
    w: FloatArray, perm: tuple[int, int, int], signs: tuple[int, int, int], size: tuple[int, int, int]
) -> FloatArray:
    """The inverse of :func:`turn_points`: turned points back in A's box (array indices), exactly."""
    out = np.empty_like(w)
    for k in range(3):
        j = perm[k]
        out[:, j] = w[:, k] if signs[k] > 0 else (size[j] - 1) - w[:, k]
    return out


def canonical_pose(mask: BoolArray) -> tuple[tuple[int, int, int], tuple[int, int, int]]:
    """The rotation of the cube that turns A into its canonical pose: the smallest key of the 24 turns.

    R is computed in that pose and turned back, so that R(g A) = g R(A) for every rotation g of the cube
    when A has no symmetry of its own (a symmetric A gets one of its poses, the same for all its turns).
    The key of a turn is its shape, then its exact moments of order 1 and 2, then a 64-bit hash of its
    surfels: a function of the turned set, so the same pose up to A's own symmetries for every turn of A.
    Moments and hash are computed once, in A's frame (the turns' follow by algebra, the hash is a sum over
    the surfels turned), not on 24 turned copies: those took seven seconds at 256³.

    Only the hash is not exact: two different turns of A with equal shapes and moments (already rare) would
    share a hash with probability about 2⁻⁶⁴, and then the order of :data:`ROTATIONS` picks. R(A) is the
    same either way in all that matters (D(R(A)) = A does not depend on the pose); only the covariance
    would fail for that A.
    """
    nz, ny, nx = mask.shape
    size = (nx, ny, nz)
    # Moments of A in its frame, as Python integers: N, S_i = Σ x_i, S_ij = Σ x_i x_j (i, j: x, y, z).
    p_yx = mask.sum(axis=0, dtype=np.int64)
    p_zx = mask.sum(axis=1, dtype=np.int64)
    p_zy = mask.sum(axis=2, dtype=np.int64)
    xs, ys, zs = (np.arange(n, dtype=np.int64) for n in size)
    n_a = int(p_yx.sum())
    s1 = [int(xs @ p_yx.sum(axis=0)), int(ys @ p_yx.sum(axis=1)), int(zs @ p_zy.sum(axis=1))]
    s2 = [[0] * 3 for _ in range(3)]
    s2[0][0] = int((xs * xs) @ p_yx.sum(axis=0))
    s2[1][1] = int((ys * ys) @ p_yx.sum(axis=1))
    s2[2][2] = int((zs * zs) @ p_zy.sum(axis=1))
    s2[0][1] = s2[1][0] = int(ys @ p_yx @ xs)
    s2[0][2] = s2[2][0] = int(zs @ p_zx @ xs)
    s2[1][2] = s2[2][1] = int(zs @ p_zy @ ys)

    def moments(perm: tuple[int, int, int], signs: tuple[int, int, int]) -> tuple[int, ...]:
        # Turned coordinate k is a_k + b_k · x[perm[k]] (module docstring of compact_r's back()).
        a = [0 if signs[k] > 0 else size[perm[k]] - 1 for k in range(3)]
        b = list(signs)
        first = [a[k] * n_a + b[k] * s1[perm[k]] for k in range(3)]
        second = [
            a[k] * a[m] * n_a
            + a[k] * b[m] * s1[perm[m]]
            + a[m] * b[k] * s1[perm[k]]
            + b[k] * b[m] * s2[perm[k]][perm[m]]
            for k, m in ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))
        ]
        return (size[perm[2]], size[perm[1]], size[perm[0]], *first, *second)

    keys = [moments(perm, signs) for perm, signs in ROTATIONS]
    low = min(keys)
    tied = [i for i, k in enumerate(keys) if k == low]
    if len(tied) == 1:
        return ROTATIONS[tied[0]]
    perms = np.array([ROTATIONS[i][0] for i in tied], np.int64)
    signs_ = np.array([ROTATIONS[i][1] for i in tied], np.int64)
    hashes = _surfel_hashes(np.ascontiguousarray(mask), perms, signs_)
    best = min(range(len(tied)), key=lambda j: (int(hashes[j]), j))
    return ROTATIONS[tied[best]]


@njit(cache=True, inline="always")
def _mix(x: np.uint64) -> np.uint64:  # pragma: no cover - compiled
    # splitmix64's finalizer: a bijection of 64-bit words that spreads every input bit over the output.
    x = (x ^ (x >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    x = (x ^ (x >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return x ^ (x >> np.uint64(31))


@njit(cache=True)
def _surfel_hashes(
    mask: BoolArray, perms: Int64Array, signs: Int64Array
) -> npt.NDArray[np.uint64]:  # pragma: no cover
    # For each turn (perms[i], signs[i]): the sum, modulo 2⁶⁴, of the mixed keys of A's surfels in the turned
    # frame (a surfel: the centre of a face between a voxel of A and one outside, in doubled coordinates).
    # The surfels determine A, and a sum does not depend on the order they are met in.
    nz, ny, nx = mask.shape
    size = (nx, ny, nz)
    m = perms.shape[0]
    out = np.zeros(m, np.uint64)
    c = np.empty(3, np.int64)
    for z in range(nz):
        for y in range(ny):
            for x in range(nx):
                if not mask[z, y, x]:
                    continue
                for d in range(6):
                    axis = d >> 1
                    step = 1 if d & 1 else -1
                    zz, yy, xx = z, y, x
                    if axis == 0:
                        xx += step
                    elif axis == 1:
                        yy += step
                    else:
                        zz += step
                    if 0 <= zz < nz and 0 <= yy < ny and 0 <= xx < nx and mask[zz, yy, xx]:
                        continue
                    c[0], c[1], c[2] = 2 * x, 2 * y, 2 * z
                    c[axis] += step
                    for i in range(m):
                        key = np.uint64(0)
                        for k in range(3):
                            j = perms[i, k]
                            v = c[j] if signs[i, k] > 0 else 2 * (size[j] - 1) - c[j]
                            key = key * np.uint64(1 << 21) + np.uint64(v + 1)
                        out[i] += _mix(key)
    return out


def decimate(
    vertices: FloatArray,
    triangles: Int64Array,
    mask: BoolArray,
    origin: tuple[int, int, int],
    model: str,
    max_passes: int = 64,
    max_collapses: int = -1,
    max_rounds: int = 8,
    min_cos: float = MIN_COS,
    progress: ProgressLike | None = None,
) -> tuple[FloatArray, Int64Array]:
    """Simplify the safety net of A by exactly checked collapses and moves (module docstring).

    Parameters
    ----------
    vertices, triangles : the safety net of A (:func:`~.safety_net_3d.safety_net_3d`).
    mask, origin : A.
    model : {"gauss", "standard", "supercover"}
    max_passes : int
        Passes of collapses over the vertices at most, per round (a round stops when a pass removes nothing).
    max_collapses : int
        Collapses at most (−1: no limit); to look at R part way, when debugging a check.
    max_rounds : int
        Rounds of edge flips at most, each followed by collapses and moves again.
    min_cos : float
        A collapse may turn a triangle's normal by acos(min_cos) at most (:data:`MIN_COS`).
    progress : ProgressLike, optional
        Cancelling it stops the simplification within about 50 ms (:func:`mrm.core.progress.stop_flag`).

    Returns
    -------
    vertices : float64 (n, 3), in (¼Z)³: those of the safety net that stay, in their order, then the new ones.
    triangles : int64 (m, 3), outward.

    Raises
    ------
    Cancelled
        When ``progress`` was cancelled (nothing of the simplification is kept).
    """
    if triangles.shape[0] == 0:
        return vertices, triangles
    corner = np.asarray(origin, np.float64) - PAD
    scaled = (vertices - corner) * 4.0
    q = np.rint(scaled).astype(np.int64)
    if not np.array_equal(q.astype(np.float64), scaled):
        raise ValueError("the safety net's vertices lie in Z + {1/4, 3/4}")
    code = GAUSS if model == "gauss" else COVERS
    forbidden = forbidden_cubes(mask, code == GAUSS)
    # A's sides are read by the covers' checks only (centres of A that leave, cubes still met): under gauss
    # the forbidden cubes stand in for them, unread, and A's padded box is not copied (18 MB at 256³).
    in_a = np.pad(mask, PAD) if code == COVERS else forbidden
    del scaled
    with stop_flag(progress) as stop:
        q, t, alive, vdead, removed = _decimate(
            q,
            np.ascontiguousarray(triangles, np.int64),
            in_a,
            forbidden,
            code,
            max_passes,
            max_collapses,
            max_rounds,
            min_cos,
            stop,
        )
    if removed < 0:
        raise Cancelled("cancelled")
    keep = ~vdead
    index = np.cumsum(keep) - 1
    # Four times the offset from the corner, in integers: exact in float64 (quarters of small integers).
    return q[keep] / 4.0 + corner, index[t[alive]]


def compact_r(
    mask: BoolArray,
    origin: tuple[int, int, int],
    model: str,
    max_triangles: int,
    progress: ProgressLike | None = None,
) -> tuple[FloatArray, Int64Array, FloatArray, Int64Array]:
    """R(A) in the model, computed in A's canonical pose and turned back (:func:`canonical_pose`).

    A safety net of more than ``max_triangles`` triangles is not decimated: the net itself is returned, as
    both results (the same arrays). ``progress`` is told the net's size and can cancel the decimation
    (:class:`~mrm.core.errors.Cancelled`).

    Returns
    -------
    vertices, triangles : the compact R(A).
    net_vertices, net_triangles : the safety net of A (the fallback).
    """
    from mrm.geometry.reconstruct.safety_net_3d import safety_net_3d

    perm, signs = canonical_pose(mask)
    turned = np.ascontiguousarray(_turn(mask, perm, signs))
    net = safety_net_3d(turned, (0, 0, 0))
    if net.triangles.shape[0] > max_triangles:
        v, t = net.vertices, net.triangles
    else:
        if progress is not None:
            progress.update(None, f"simplifying a safety net of {net.triangles.shape[0]:,} triangles")
        v, t = decimate(net.vertices, net.triangles, turned, (0, 0, 0), model, progress=progress)
    size = cast(tuple[int, int, int], mask.shape[::-1])
    shift = np.asarray(origin, np.float64)

    def back(w: FloatArray) -> FloatArray:
        return turn_back_points(w, perm, signs, size) + shift

    if t is net.triangles:
        w = back(v)
        return w, t, w, t
    return back(v), t, back(net.vertices), net.triangles
