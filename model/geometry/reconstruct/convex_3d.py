"""R of a digitally convex voxel set under ``gauss``: its convex hull, grown by a dyadic homothety.

Reference: docs/design.md §11, "Continuation R in 3D"; the decision is docs/adr/0068.

When A = conv(A) ∩ Z³ (the Gauss digitization of any convex solid is such a set: balls, ellipsoids, the
octahedron), the convex hull Q = conv(A) holds every centre of A and no other. Its vertices are centres of A,
on ∂Q, so Q itself does not separate strictly; P = c + (1 + 2⁻ᴷ)(Q − c), for a dyadic point c strictly inside
Q, does: each face a·x ≤ b of Q (a primitive, b integer) becomes a·x ≤ b + 2⁻ᴷ(b − a·c), and K is the least
power making every such growth at most ½, so every centre of A is strictly inside, every other strictly
outside (it has a·p ≥ b + 1 for some face), and P has Q's faces. Its vertices v + 2⁻ᴷ(v − c) are dyadic:
float64 holds them exactly, and the faces stay exactly planar.

Everything is decided in integers: the hull by a quickhull whose predicates are exact (on the corners of each
slice's own hull of the rows' ends), its triangles grouped by plane into faces, each face's corners by an
exact convex hull in its plane (points on a side dropped), every side shared by two faces in opposite
directions, every edge strictly convex, Euler's formula. :func:`convex_reconstruction` then checks P as a
whole, like every R (topology, valid polyhedron, D(P) = A exactly, ∂P within the border voxels' cubes); the
caller goes the general way (:mod:`.decimate_3d`) when any of this fails.

Under the covers the hull's facets move in instead (:func:`convex_cover_r`, ADR 0069; with many facets,
:mod:`.snapped_core`, ADR 0070). The quickhull runs on homogeneous integer points (x, y, z, w), so that the
snapped core can take the hull of its dual points with the same code.

c (the centre of the corners' box when inside, else their mean rounded to a dyadic grid) and the faces'
triangulation are chosen in the canonical pose of Q's corners (of the 24 turns of the cube, the one whose
sorted corners come first) and turned back, so that R(g A) = g R(A) for the rotations g of the cube, as for
the general R.
"""

from __future__ import annotations

import logging
import math
from fractions import Fraction
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import njit
from mrm.geometry.planes._kernels import _set_primitive
from mrm.geometry.reconstruct._base import _grow1, _grow2
from mrm.geometry.reconstruct._check import _orient
from mrm.geometry.reconstruct._halfspaces import ConvexPolytope, Normal, Point, convex_polytope, cut_polytope
from mrm.geometry.reconstruct.decimate_3d import ROTATIONS, turn_back_points, turn_points
from mrm.geometry.topology.labeling_3d import Runs3D, euler_per_label, label_runs_3d, surfel_count

if TYPE_CHECKING:
    from mrm.core.grids import VoxelSet
    from mrm.geometry.polyhedra import Polyhedron

logger = logging.getLogger(__name__)

FloatArray = npt.NDArray[np.float64]
Int64Array = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]

#: Largest extent of A's box, in voxels, for which the face planes' integers stay far inside int64: the
#: normals of triangles with coordinates below 2¹⁶ are below 2³³, their offsets below 2⁵¹.
MAX_EXTENT = 1 << 16

#: Most facets of conv(A) for which A counts as a lattice polytope (the octahedron's 8, a box's 6; a ball of
#: radius 8 has 140). Under the covers R of such an A is tried from its hull — cut out in Fractions, about
#: facets² × corners operations — and beside the decimation it is judged by faces, then vertices (§11's
#: measure: such a shape is made of its faces). A finer hull is judged by triangles: its faces are fans of
#: many small facets, and its triangles are the mesh the user gets.
FEW_FACETS = 64
#: Most voxels of A whose cubes the covers' convex core may miss, each then reached by a spike (the
#: octahedron's six tips); more means A is not a lattice polytope, and the decimation makes its R.
MAX_SPIKES = 24


class ConvexR(NamedTuple):
    """R(A) of a digitally convex A (:func:`convex_reconstruction`), and A's surfels."""

    polyhedron: Polyhedron
    surfels: int
    facets: int  #: conv(A)'s facets


def convex_reconstruction(vs: VoxelSet, model: str = "gauss") -> ConvexR | None:
    """R(A) for a digitally convex A from its convex hull, checked as a whole; else None.

    Under ``gauss`` P is the hull grown by a dyadic homothety (:func:`convex_r`); under the covers, the
    hull's facets moved in (:func:`convex_cover_r`). Checked like every R (docs/design.md §11, items 1–4): A
    is one 6-component without cavity or tunnel (a convex solid's topology); P is a valid polyhedron; D(P) = A
    exactly. Under ``gauss`` ∂P stays within the cubes of the border voxels — the cubes P meets (its
    supercover, exactly) all have a voxel of A in their 3×3×3 block (the cubes of A's inner voxels lie inside
    conv(A), itself inside P's interior). Under the covers P ⊂ V(A): its supercover is A (under
    ``standard`` this is checked too). None when A is not digitally convex or any check fails: the caller
    then takes the general way.
    """
    from mrm.core.grids import VoxelSet
    from mrm.geometry._threads import side_pool
    from mrm.geometry.discretize.voxels import voxelize_solid
    from mrm.geometry.polyhedra import Polyhedron

    runs = label_runs_3d(vs.mask, 6)
    if runs.n_labels != 1 or runs.n_bg != 1 or int(euler_per_label(runs)[1]) != 1:
        return None  # not one component without cavity or tunnel, as a convex solid is
    gauss = model == "gauss"
    hull = _hull(runs)
    if hull is None:
        return None
    found = convex_r(hull, vs.origin) if gauss else convex_cover_r(hull, vs.mask, vs.origin, model)
    if found is None:
        return None
    v, t, proven, valid = found
    # Under gauss the border check (the supercover of the surface, the costliest part) runs on R's worker
    # thread while this one validates P and discretizes it.
    pool = side_pool() if gauss else None
    border = pool.submit(_stays_near_a, v, t, vs) if pool is not None else None
    try:
        result = valid if valid is not None else Polyhedron(v, t)
        models = [] if proven else [model] if model != "standard" else ["standard", "supercover"]
        for m in models:
            if VoxelSet(*voxelize_solid(v, t, m, limit=None)) != vs:
                logger.debug("the convex hull's %s discretization is not A: A is not digitally convex", m)
                return None
    except ValueError as e:  # InvalidGeometryError: the proposed hull is not a valid polyhedron
        logger.warning("the convex hull's R is refused (%s): %d voxels, model %s", e, vs.count, model)
        return None
    finally:
        near = border.result() if border is not None else None  # waits on a refusal too: nothing left over
    if gauss:
        if near is None:
            near = _stays_near_a(v, t, vs)
        if not near:
            logger.debug("the grown hull leaves the border voxels' cubes")
            return None
    return ConvexR(result, surfel_count(runs), int(hull.normals.shape[0]))


def _stays_near_a(v: FloatArray, t: Int64Array, vs: VoxelSet) -> bool:
    # Whether every cube the triangles meet (their exact supercover) has a voxel of A in its 3×3×3 block.
    # The cubes P meets beyond them lie in its interior: their centres are in D(P) = A.
    from mrm.geometry.discretize.voxels import voxelize_triangles

    cover, at = voxelize_triangles(v, t, "supercover", limit=None)
    shift = np.asarray(vs.origin, np.int64) - np.asarray(at, np.int64)
    return bool(_near_a(cover, vs.mask, shift))


class _Hull(NamedTuple):
    # conv(A) in A's box (array indices): its corners, its faces' corners (counter-clockwise from outside,
    # face f's from face_ptr[f]), and each face's plane a·x = b (a primitive and outward, b integer).
    corners: Int64Array
    face_ptr: Int64Array
    face_corner: Int64Array
    normals: Int64Array
    offsets: Int64Array
    size: tuple[int, int, int]


def _hull(runs: Runs3D) -> _Hull | None:
    # conv(A) decided exactly, or None when A has a row of two runs or more, is flat, or the proposed hull is
    # not exactly a convex polyhedron.
    nz, ny, nx = runs.shape
    if max(runs.shape) > MAX_EXTENT:
        return None
    rs, re, ptr = runs.start, runs.end, runs.ptr
    per_row = np.diff(ptr)
    if per_row.size == 0 or per_row.max() > 1:
        return None  # a row (y, z) meets A in two runs: not digitally convex
    # conv(A) is the hull of the rows' ends; of those, only the corners of each slice's own hull can be its.
    ends = _slice_corners(rs, ptr, re, ny, nz)
    proposed = _propose_hull(ends)
    if proposed is None:
        return None
    faces = _exact_faces(*proposed)
    if faces is None:
        return None
    return _Hull(*faces, size=(nx, ny, nz))


def convex_r(
    hull: _Hull, origin: tuple[int, int, int]
) -> tuple[FloatArray, Int64Array, bool, Polyhedron | None] | None:
    """The grown convex hull P of A when A looks digitally convex, else None (module docstring).

    Parameters
    ----------
    hull : conv(A) (:func:`_hull`).
    origin : the world (x, y, z) of A's voxel at index (0, 0, 0).

    Returns
    -------
    vertices : float64 (n, 3), world coordinates, dyadic.
    triangles : int64 (m, 3), outward.
    proven : bool
        False: D(P) = A is the caller's to check.
    polyhedron : None
        P is the caller's to validate.
        Or None when no grown corner is a float64 number: the caller's checks decide the rest (D(P) = A is
        what proves A digitally convex).
    """
    size = hull.size
    pose = _corner_pose(hull.corners, size)
    perm, signs = ROTATIONS[pose]
    turned = turn_points(hull.corners, perm, signs, size)
    grown = _grow(turned, hull.normals, hull.offsets, perm, signs, size)
    if grown is None:
        return None
    triangles = _fans(turned, hull.face_ptr, hull.face_corner)
    back = turn_back_points(grown, perm, signs, size)
    return back + np.asarray(origin, np.float64), triangles, False, None


def convex_cover_r(
    hull: _Hull, mask: BoolArray, origin: tuple[int, int, int], model: str
) -> tuple[FloatArray, Int64Array, bool, Polyhedron | None] | None:
    """The covers' P of A when A looks digitally convex: conv(A)'s facets moved in, plus spikes; else None.

    The core: each facet a·x ≤ b of conv(A) becomes a·x ≤ b + ¾ − |a|₁/2. A centre q outside a digitally
    convex A has a·q ≥ b + 1 for some facet, and q's closed cube then has a·x ≥ b + 1 − |a|₁/2: the core
    meets no cube outside A. It may miss the cubes of a few voxels of A — the octahedron's six tips, which no
    convex P with the octahedron's symmetries can reach without touching an outside cube (it would hold the
    axis points (x, 0, 0), x > r − ½, and the triangle of three of them crosses the cube of (r − 1, 1, 1)).
    Each such voxel p gets a spike: the core's corner c nearest to p is cut off by a plane across the line
    c→p, and a pyramid stands on the cut, with its apex at (c + p)/2, inside p's cube. The octahedron comes
    back with 32 faces: its 8, each a hexagon, and four per tip.

    Parameters
    ----------
    hull : conv(A) (:func:`_hull`).
    mask : A's voxels (z, y, x).
    origin : the world (x, y, z) of A's voxel at index (0, 0, 0).
    model : ``"standard"`` or ``"supercover"``.

    Returns
    -------
    vertices : float64 (n, 3), world coordinates, dyadic.
    triangles : int64 (m, 3), outward.
    proven : bool
        Whether D(P) = A (and P ⊂ V(A)) is proven already (:func:`.snapped_core.snapped_cover_r`), so the
        caller need not discretize P again.
    polyhedron : Polyhedron or None
        P validated already (the snapped core), else None.
        Or None when conv(A) has more than ``FEW_FACETS`` facets, when
        the core has no volume or meets a cube outside A, when it misses more than ``MAX_SPIKES`` cubes of
        A, or when a corner is not a float64 number (a rational with another denominator than a power of
        two: rounding it would bend P's faces). The caller's checks decide the rest.
    """
    if hull.normals.shape[0] > FEW_FACETS:
        from mrm.geometry.reconstruct.snapped_core import snapped_cover_r

        return snapped_cover_r(hull, mask, origin, model, MAX_SPIKES)
    normals = [(int(a), int(b), int(c)) for a, b, c in hull.normals]
    moved = [
        Fraction(4 * int(b) + 3 - 2 * sum(map(abs, a)), 4) for a, b in zip(normals, hull.offsets, strict=True)
    ]
    lo = (Fraction(-1), Fraction(-1), Fraction(-1))
    hi = (Fraction(hull.size[0]), Fraction(hull.size[1]), Fraction(hull.size[2]))
    core = convex_polytope(normals, moved, lo, hi)
    if core is None:
        return None
    missing = _missed_voxels(core, mask, model)
    if missing is None or len(missing) > MAX_SPIKES:
        return None
    spikes = []
    for p in missing:
        spike = _spike(core.corners, p)
        if spike is None:
            return None
        spikes.append(spike)
    cut = cut_polytope(core, [u for u, _, _ in spikes], [d for _, d, _ in spikes], len(normals))
    if cut is None or len(cut.planes) != len(core.planes) + len(spikes):
        return None  # a cut took a whole face away, or two cuts met: the spikes are not apart
    v = _float_corners(cut.corners + [apex for _, _, apex in spikes])
    if v is None:
        return None
    flat = [f for plane, f in zip(cut.planes, cut.faces, strict=True) if plane < len(normals)]
    perm, signs = ROTATIONS[_corner_pose(hull.corners, hull.size)]
    triangles = [_fans(turn_points(v, perm, signs, hull.size), *_flat(flat))]
    for plane, f in zip(cut.planes, cut.faces, strict=True):
        if plane >= len(normals):  # a spike's base: a pyramid on it, each side f[k]→f[k+1] with the apex
            apex = len(cut.corners) + plane - len(normals)
            triangles.append(np.array([(f[k], f[(k + 1) % len(f)], apex) for k in range(len(f))], np.int64))
    return v + np.asarray(origin, np.float64), np.concatenate(triangles), False, None


def _missed_voxels(core: ConvexPolytope, mask: BoolArray, model: str) -> list[tuple[int, int, int]] | None:
    # The voxels (x, y, z) of A whose cubes the core misses in the model, or None when it meets one outside.
    from mrm.geometry.discretize.voxels import voxelize_solid

    v = _float_corners(core.corners)
    if v is None:
        return None
    face_ptr, face_corner = _flat(core.faces)
    got, at = voxelize_solid(v, _fans(v, face_ptr, face_corner), model, limit=None)
    nz, ny, nx = mask.shape
    ax, ay, az = at
    if (
        ax < 0
        or ay < 0
        or az < 0
        or az + got.shape[0] > nz
        or ay + got.shape[1] > ny
        or ax + got.shape[2] > nx
    ):
        return None
    inside = np.zeros_like(mask)
    inside[az : az + got.shape[0], ay : ay + got.shape[1], ax : ax + got.shape[2]] = got
    if np.any(inside & ~mask):
        return None
    k, j, i = np.nonzero(mask & ~inside)
    return [(int(x), int(y), int(z)) for x, y, z in zip(i, j, k, strict=True)]


def _float_corners(corners: list[Point]) -> FloatArray | None:
    # The corners as float64, or None when one is not a float64 number (rounding it would bend P's faces).
    if any(Fraction(float(x)) != x for p in corners for x in p):
        logger.debug("a corner of the covers' hull is not a float64 number: A takes the general way")
        return None
    return np.array(corners, np.float64)


def _flat(faces: list[list[int]]) -> tuple[Int64Array, Int64Array]:
    # The faces' corners in one array, face f's from ptr[f] to ptr[f + 1].
    ptr = np.cumsum([0] + [len(f) for f in faces]).astype(np.int64)
    return ptr, np.array([c for f in faces for c in f], np.int64)


def _spike(corners: list[Point], p: tuple[int, int, int]) -> tuple[Normal, Fraction, Point] | None:
    # The cut a·x ≤ d under the core's corner c nearest to p (the plane across c→p, a quarter of a·(p − c)
    # below c) and the apex (c + p)/2 of the pyramid on it; None when two corners are as near (the choice
    # would not follow the rotations of A) or the apex is not inside p's cube.
    dist = [sum((x - q) ** 2 for x, q in zip(c, p, strict=True)) for c in corners]
    best = min(dist)
    if dist.count(best) > 1:
        return None
    c = corners[dist.index(best)]
    step = [q - x for x, q in zip(c, p, strict=True)]
    scale = math.lcm(*(x.denominator for x in step))
    whole = [int(x * scale) for x in step]
    g = math.gcd(*whole)
    a = (whole[0] // g, whole[1] // g, whole[2] // g)
    rise = sum(ai * si for ai, si in zip(a, step, strict=True))  # a·(p − c) > 0
    d = sum(ai * ci for ai, ci in zip(a, c, strict=True)) - Fraction(rise) / 4
    apex = ((c[0] + p[0]) / 2, (c[1] + p[1]) / 2, (c[2] + p[2]) / 2)
    if max(abs(x - q) for x, q in zip(apex, p, strict=True)) >= Fraction(1, 2):
        return None
    return a, d, apex


@njit(cache=True)
def _near_a(cover: BoolArray, a: BoolArray, shift: Int64Array) -> bool:  # pragma: no cover - compiled
    # Whether every voxel of cover has a voxel of a in its 3×3×3 block; cover[k, j, i] is a[k − sz, j − sy,
    # i − sx] with (sx, sy, sz) = shift. The cover is a surface: its voxels are read from the flat array.
    _nz, ny, nx = cover.shape
    az, ay, ax = a.shape
    flat = cover.ravel()
    for n in range(flat.shape[0]):
        if not flat[n]:
            continue
        k, rest = divmod(n, ny * nx)
        j, i = divmod(rest, nx)
        ka, ja, ia = k - shift[2], j - shift[1], i - shift[0]
        found = False
        for dk in range(-1, 2):
            for dj in range(-1, 2):
                for di in range(-1, 2):
                    kk, jj, ii = ka + dk, ja + dj, ia + di
                    if 0 <= kk < az and 0 <= jj < ay and 0 <= ii < ax and a[kk, jj, ii]:
                        found = True
        if not found:
            return False
    return True


@njit(cache=True)
def _slice_corners(
    rs: npt.NDArray[np.int32], ptr: Int64Array, re: npt.NDArray[np.int32], ny: int, nz: int
) -> Int64Array:  # pragma: no cover - compiled
    # The corners of each slice z = k's convex hull, among its rows' two ends (x, y, z): the rows' left ends
    # (x as a function of y) on their lower convex chain and the right ends on their upper one, with exact
    # turns; an end strictly inside its slice's hull, or on a side, is no corner of conv(A) either.
    out = np.empty((2 * nz * ny, 3), np.int64)
    chain = np.empty(ny, np.int64)
    m = 0
    for k in range(nz):
        for side in range(2):
            h = 0
            for j in range(ny):
                r = k * ny + j
                if ptr[r + 1] == ptr[r]:
                    continue
                x = rs[ptr[r]] if side == 0 else re[ptr[r]]
                while h >= 2:
                    j0, j1 = chain[h - 2], chain[h - 1]
                    x0 = rs[ptr[k * ny + j0]] if side == 0 else re[ptr[k * ny + j0]]
                    x1 = rs[ptr[k * ny + j1]] if side == 0 else re[ptr[k * ny + j1]]
                    turn = _orient(j0, x0, j1, x1, j, x)  # in the (y, x) plane
                    if turn > 0 if side == 0 else turn < 0:
                        break
                    h -= 1
                chain[h] = j
                h += 1
            for s in range(h):
                j = chain[s]
                out[m, 0] = rs[ptr[k * ny + j]] if side == 0 else re[ptr[k * ny + j]]
                out[m, 1] = j
                out[m, 2] = k
                m += 1
    return out[:m].copy()


def _propose_hull(points: Int64Array) -> tuple[Int64Array, Int64Array] | None:
    # The hull's triangles (outward) by quickhull on the points, exactly; None when the points are coplanar.
    lifted = np.ones((points.shape[0], 4), np.int64)  # homogeneous (x, y, z, 1)
    lifted[:, :3] = points
    tri, ok = _quickhull(lifted)
    return (points, tri) if ok else None


@njit(cache=True, inline="always")
def _above(fn: Int64Array, fo: Int64Array, f: int, pts: Int64Array, q: int) -> int:  # pragma: no cover
    # How far point q lies above face f's plane, in units of its (unnormalized) normal; exact.
    h: int = fn[f, 0] * pts[q, 0] + fn[f, 1] * pts[q, 1] + fn[f, 2] * pts[q, 2] + fo[f] * pts[q, 3]
    return h


@njit(cache=True, inline="always")
def _minors(pts: Int64Array, a: int, b: int, c: int) -> tuple[int, int, int, int]:  # pragma: no cover
    # L with L·X = −det[Xa; Xb; Xc; X] for every homogeneous X: L_k = (−1)ᵏ times the minor of rows a, b, c
    # without column k. For points with w = 1, L = (n, −n·a), n = (b − a) × (c − a): X lies above the
    # triangle a b c (outward by n) iff L·X > 0, and with w > 0 the sign is the same as for X / w.
    return (
        _det3(pts, a, b, c, 1, 2, 3),
        -_det3(pts, a, b, c, 0, 2, 3),
        _det3(pts, a, b, c, 0, 1, 3),
        -_det3(pts, a, b, c, 0, 1, 2),
    )


@njit(cache=True, inline="always")
def _det3(pts: Int64Array, a: int, b: int, c: int, i: int, j: int, k: int) -> int:  # pragma: no cover
    # The determinant of rows a, b, c of pts restricted to columns i, j, k.
    d: int = (
        pts[a, i] * (pts[b, j] * pts[c, k] - pts[b, k] * pts[c, j])
        - pts[a, j] * (pts[b, i] * pts[c, k] - pts[b, k] * pts[c, i])
        + pts[a, k] * (pts[b, i] * pts[c, j] - pts[b, j] * pts[c, i])
    )
    return d


@njit(cache=True, inline="always")
def _before(pts: Int64Array, i: int, j: int) -> bool:  # pragma: no cover - compiled
    # Whether point i comes before point j in (x, y, z) / w order, exactly (w > 0).
    for k in range(3):
        a = pts[i, k] * pts[j, 3]
        b = pts[j, k] * pts[i, 3]
        if a != b:
            earlier: bool = a < b
            return earlier
    return False


@njit(cache=True, inline="always")
def _set_hull_plane(
    pts: Int64Array, ft: Int64Array, fn: Int64Array, fo: Int64Array, f: int
) -> None:  # pragma: no cover
    fn[f, 0], fn[f, 1], fn[f, 2], fo[f] = _minors(pts, ft[f, 0], ft[f, 1], ft[f, 2])


@njit(cache=True, inline="always")
def _assign(
    q: int,
    lo: int,
    hi: int,
    pts: Int64Array,
    fn: Int64Array,
    fo: Int64Array,
    nextp: Int64Array,
    head: Int64Array,
    far: Int64Array,
    fard: Int64Array,
) -> None:  # pragma: no cover - compiled
    # Point q goes to the outside list of the first face lo..hi−1 it lies strictly above (none: it is inside),
    # which keeps its farthest point.
    for f in range(lo, hi):
        h = _above(fn, fo, f, pts, q)
        if h > 0:
            nextp[q] = head[f]
            head[f] = q
            if h > fard[f]:
                fard[f], far[f] = h, q
            return


@njit(cache=True)
def _quickhull(pts: Int64Array) -> tuple[Int64Array, bool]:  # pragma: no cover - compiled
    # Quickhull (Barber, Dobkin & Huhdanpaa 1996) in integers on homogeneous points (x, y, z, w), w > 0 (the
    # point (x, y, z) / w): a point is outside a face when it lies strictly above its plane, so coplanar
    # points are never added and adjacent faces may be coplanar (merged later). Faces are triangles (a, b, c),
    # outward (:func:`_minors`); nb[f, e] is the face across edge e, from corner e to corner e + 1. Every
    # predicate is a 4 × 4 determinant: the caller keeps its terms inside int64 (coordinates below 2¹⁶ with
    # w = 1: products far inside; the dual points of :mod:`.snapped_core` are bounded there).
    n = pts.shape[0]
    i0 = 0
    i1 = 0
    for i in range(n):  # the first and last points in (x, y, z) / w order: two different points
        if _before(pts, i, i0):
            i0 = i
        if _before(pts, i1, i):
            i1 = i
    if i0 == i1:
        return np.empty((0, 3), np.int64), False
    i2, best = -1, 0
    for i in range(n):
        l0, l1, l2, l3 = _minors(pts, i0, i1, i)
        m = abs(l0) + abs(l1) + abs(l2) + abs(l3)  # 0 iff the three points are on one line
        if m > best:
            i2, best = i, m
    if i2 < 0:
        return np.empty((0, 3), np.int64), False
    nx, ny, nz, no = _minors(pts, i0, i1, i2)
    i3, best = -1, 0
    for i in range(n):
        d = nx * pts[i, 0] + ny * pts[i, 1] + nz * pts[i, 2] + no * pts[i, 3]
        if abs(d) > best:
            i3, best = i, abs(d)
    if i3 < 0:
        return np.empty((0, 3), np.int64), False
    d = nx * pts[i3, 0] + ny * pts[i3, 1] + nz * pts[i3, 2] + no * pts[i3, 3]
    if d > 0:  # p3 above (p0, p1, p2): swap p1 and p2 so that it lies below
        i1, i2 = i2, i1
    cap = 1024
    ft = np.empty((cap, 3), np.int64)
    nb = np.empty((cap, 3), np.int64)
    fn = np.empty((cap, 3), np.int64)
    fo = np.empty(cap, np.int64)
    alive = np.zeros(cap, np.bool_)
    head = np.full(cap, -1, np.int64)
    far = np.full(cap, -1, np.int64)
    fard = np.zeros(cap, np.int64)
    nextp = np.full(n, -1, np.int64)
    # The tetrahedron, outward (p3 lies below (p0, p1, p2) now).
    ft[0, 0], ft[0, 1], ft[0, 2] = i0, i1, i2
    ft[1, 0], ft[1, 1], ft[1, 2] = i0, i3, i1
    ft[2, 0], ft[2, 1], ft[2, 2] = i1, i3, i2
    ft[3, 0], ft[3, 1], ft[3, 2] = i2, i3, i0
    nf = 4
    for f in range(4):
        _set_hull_plane(pts, ft, fn, fo, f)
        alive[f] = True
    for f in range(4):
        for e in range(3):
            a, b = ft[f, e], ft[f, (e + 1) % 3]
            for g in range(4):
                for e2 in range(3):
                    if ft[g, e2] == b and ft[g, (e2 + 1) % 3] == a:
                        nb[f, e] = g
    for q in range(n):
        if q in (i0, i1, i2, i3):
            continue
        _assign(q, 0, 4, pts, fn, fo, nextp, head, far, fard)
    vis = np.full(cap, -1, np.int64)
    stack = np.empty(cap, np.int64)
    hz_u = np.empty(cap, np.int64)
    hz_v = np.empty(cap, np.int64)
    hz_f = np.empty(cap, np.int64)
    start = np.full(n, -1, np.int64)
    stop = np.full(n, -1, np.int64)
    f = 0
    it = 0
    while f < nf:
        if not alive[f] or head[f] < 0:
            f += 1
            continue
        it += 1
        p = far[f]
        # The faces p sees, by a walk from f; the edges from them to the faces it does not see: the horizon.
        n_vis = 0
        n_hz = 0
        stack[0] = f
        vis[f] = it
        top = 1
        seen = np.empty(0, np.int64)
        while top > 0:
            top -= 1
            g = stack[top]
            if n_vis + nf >= seen.shape[0]:
                seen = _grow1(seen, n_vis, 2 * (n_vis + nf) + 16)
            seen[n_vis] = g
            n_vis += 1
            for e in range(3):
                h = nb[g, e]
                if vis[h] == it:
                    continue
                if _above(fn, fo, h, pts, p) > 0:
                    vis[h] = it
                    if top >= stack.shape[0]:
                        stack = _grow1(stack, top, 2 * stack.shape[0])
                    stack[top] = h
                    top += 1
                else:
                    if n_hz >= hz_u.shape[0]:
                        hz_u = _grow1(hz_u, n_hz, 2 * hz_u.shape[0])
                        hz_v = _grow1(hz_v, n_hz, 2 * hz_v.shape[0])
                        hz_f = _grow1(hz_f, n_hz, 2 * hz_f.shape[0])
                    hz_u[n_hz], hz_v[n_hz], hz_f[n_hz] = ft[g, e], ft[g, (e + 1) % 3], h
                    n_hz += 1
        if nf + n_hz > cap:
            cap = 2 * (nf + n_hz)
            ft, nb, fn = _grow2(ft, nf, cap), _grow2(nb, nf, cap), _grow2(fn, nf, cap)
            fo, far, fard = _grow1(fo, nf, cap), _grow1(far, nf, cap), _grow1(fard, nf, cap)
            alive2 = np.zeros(cap, np.bool_)
            alive2[:nf] = alive[:nf]
            alive = alive2
            head2 = np.full(cap, -1, np.int64)
            head2[:nf] = head[:nf]
            head = head2
            vis2 = np.full(cap, -1, np.int64)
            vis2[:nf] = vis[:nf]
            vis = vis2
        first_new = nf
        for s in range(n_hz):
            u, v, h = hz_u[s], hz_v[s], hz_f[s]
            k = nf
            nf += 1
            ft[k, 0], ft[k, 1], ft[k, 2] = u, v, p
            _set_hull_plane(pts, ft, fn, fo, k)
            alive[k] = True
            head[k] = -1
            far[k] = -1
            fard[k] = 0
            nb[k, 0] = h
            for e2 in range(3):
                if ft[h, e2] == v and ft[h, (e2 + 1) % 3] == u:
                    nb[h, e2] = k
            start[u] = k
            stop[v] = k
        for k in range(first_new, nf):
            nb[k, 1] = start[ft[k, 1]]  # edge v → p: the new face whose horizon edge starts at v
            nb[k, 2] = stop[ft[k, 0]]  # edge p → u: the new face whose horizon edge ends at u
        # The points the visible faces held go to the first new face they lie above, or are inside now.
        for s in range(n_vis):
            g = seen[s]
            alive[g] = False
            q = head[g]
            while q >= 0:
                nq = nextp[q]
                if q != p:
                    _assign(q, first_new, nf, pts, fn, fo, nextp, head, far, fard)
                q = nq
            head[g] = -1
        f += 1
    m = 0
    for g in range(nf):
        if alive[g]:
            m += 1
    out = np.empty((m, 3), np.int64)
    m = 0
    for g in range(nf):
        if alive[g]:
            out[m] = ft[g]
            m += 1
    return out, True


@njit(cache=True, inline="always")
def _set_plane(
    pts: Int64Array, ft: Int64Array, fn: Int64Array, fo: Int64Array, f: int
) -> None:  # pragma: no cover
    a, b, c = ft[f, 0], ft[f, 1], ft[f, 2]
    ux, uy, uz = pts[b, 0] - pts[a, 0], pts[b, 1] - pts[a, 1], pts[b, 2] - pts[a, 2]
    wx, wy, wz = pts[c, 0] - pts[a, 0], pts[c, 1] - pts[a, 1], pts[c, 2] - pts[a, 2]
    fn[f, 0], fn[f, 1], fn[f, 2] = uy * wz - uz * wy, uz * wx - ux * wz, ux * wy - uy * wx
    fo[f] = fn[f, 0] * pts[a, 0] + fn[f, 1] * pts[a, 1] + fn[f, 2] * pts[a, 2]


def _exact_faces(
    v: Int64Array, t: Int64Array
) -> tuple[Int64Array, Int64Array, Int64Array, Int64Array, Int64Array] | None:
    # The proposed triangles' planes, grouped into faces, each face's corners in order: decided exactly.
    planes = _triangle_planes(v, t)
    real = np.flatnonzero(np.any(planes[:, :3] != 0, axis=1))  # collinear triangles (points on an edge) go
    pl = planes[real]
    order = np.lexsort((pl[:, 3], pl[:, 2], pl[:, 1], pl[:, 0]))
    pl = pl[order]
    new_face = np.ones(pl.shape[0], bool)
    new_face[1:] = np.any(pl[1:] != pl[:-1], axis=1)
    heads = np.flatnonzero(new_face)
    tri = np.ascontiguousarray(t[real[order]])
    gptr = np.append(heads, pl.shape[0]).astype(np.int64)
    normals = np.ascontiguousarray(pl[heads, :3])
    offsets = np.ascontiguousarray(pl[heads, 3])
    face_ptr, face_corner, ok = _face_corners(v, tri, gptr.astype(np.int64), normals)
    if not ok:
        return None
    used, local = np.unique(face_corner, return_inverse=True)
    if not _closed_and_convex(v, face_ptr, face_corner, normals, offsets, used.size):
        return None
    return v[used], face_ptr, local.astype(np.int64), normals, offsets


@njit(cache=True)
def _triangle_planes(v: Int64Array, t: Int64Array) -> Int64Array:  # pragma: no cover - compiled
    # Row i: the primitive outward normal (a, b, c) of triangle i and its offset a·p; zeros when flat.
    m = t.shape[0]
    fn = np.zeros((m, 3), np.int64)
    fo = np.zeros(m, np.int64)
    out = np.zeros((m, 4), np.int64)
    for i in range(m):
        _set_plane(v, t, fn, fo, i)
        _set_primitive(out, i, fn[i, 0], fn[i, 1], fn[i, 2])
        p = t[i, 0]
        out[i, 3] = out[i, 0] * v[p, 0] + out[i, 1] * v[p, 1] + out[i, 2] * v[p, 2]
    return out


@njit(cache=True)
def _face_corners(
    v: Int64Array, tri: Int64Array, gptr: Int64Array, normals: Int64Array
) -> tuple[Int64Array, Int64Array, bool]:  # pragma: no cover - compiled
    # For each face (the triangles gptr[f]..gptr[f+1] of one plane): its corners, counter-clockwise seen from
    # outside, by Andrew's monotone chain on the plane's projection along its largest normal component, with
    # exact turns; a point on a side is not a corner. ok is False when a face has fewer than three corners.
    nf = gptr.shape[0] - 1
    stamp = np.full(v.shape[0], -1, np.int64)
    face_ptr = np.zeros(nf + 1, np.int64)
    out = np.empty(3 * tri.shape[0], np.int64)
    n_out = 0
    ids = np.empty(3 * tri.shape[0], np.int64)
    chain = np.empty(3 * tri.shape[0] + 1, np.int64)
    for f in range(nf):
        n = 0
        for i in range(gptr[f], gptr[f + 1]):
            for s in range(3):
                w = tri[i, s]
                if stamp[w] != f:
                    stamp[w] = f
                    ids[n] = w
                    n += 1
        d = 0
        for s in range(1, 3):
            if abs(normals[f, s]) > abs(normals[f, d]):
                d = s
        du, dw = (d + 1) % 3, (d + 2) % 3
        pts = ids[:n]
        key = v[pts, du] * (1 << 20) + v[pts, dw]  # coordinates below 2¹⁶: the order of (u, w)
        pts = pts[np.argsort(key)]
        pu, pw = v[pts, du], v[pts, dw]
        h = 0
        low = 2
        for first, stop, step in ((0, n, 1), (n - 2, -1, -1)):  # the lower chain, then the upper one back
            for s in range(first, stop, step):  # chain holds indices into pts
                while h >= low:
                    a, b = chain[h - 2], chain[h - 1]
                    if _orient(pu[a], pw[a], pu[b], pw[b], pu[s], pw[s]) > 0:
                        break
                    h -= 1
                chain[h] = s
                h += 1
            low = h + 1  # the upper chain keeps the lower one
        h -= 1  # the first point, met again
        if h < 3:
            return face_ptr, out[:0], False
        # counter-clockwise in (u, w) is counter-clockwise about +e_d: reverse when the normal points to −e_d
        for s in range(h):
            out[n_out + s] = pts[chain[s]] if normals[f, d] > 0 else pts[chain[h - 1 - s]]
        n_out += h
        face_ptr[f + 1] = n_out
    return face_ptr, out[:n_out].copy(), True


def _closed_and_convex(
    v: Int64Array,
    face_ptr: Int64Array,
    face_corner: Int64Array,
    normals: Int64Array,
    offsets: Int64Array,
    n_corners: int,
) -> bool:
    # Every side u→v of a face is the side v→u of exactly one other face, the far corner of which lies
    # strictly below the first face's plane (a strictly convex edge); V − E + F = 2 (V: the n_corners).
    n_faces = face_ptr.size - 1
    lens = np.diff(face_ptr)
    face_of = np.repeat(np.arange(n_faces), lens)
    nxt = np.arange(face_corner.size) + 1
    ends = face_ptr[1:] - 1
    nxt[ends] = face_ptr[:-1]
    a, b = face_corner, face_corner[nxt]
    after = face_corner[nxt[nxt]]  # the corner after b in the same face
    n_v = int(face_corner.max()) + 1
    fwd = a * n_v + b
    rev = b * n_v + a
    order = np.argsort(fwd)
    if np.any(np.diff(fwd[order]) == 0):
        return False  # a side used twice in one direction
    at = np.searchsorted(fwd[order], rev)
    at[at >= fwd.size] = 0
    twin = order[at]
    if not np.array_equal(fwd[twin], rev):
        return False  # a side without its opposite: not closed
    # The twin face's corner after u (its side is b→a, so the corner after a there) is below this plane.
    far = after[twin]
    f = face_of
    lhs = np.einsum("ij,ij->i", normals[f], v[far])
    if np.any(lhs >= offsets[f]):
        return False
    return bool(n_corners - face_corner.size // 2 + n_faces == 2)


def _corner_pose(corners: Int64Array, size: tuple[int, int, int]) -> int:
    # The index in ROTATIONS of the turn whose box shape, then sorted corners, come first (a corner's key
    # packs its turned x, y, z, each below 2¹⁶ (MAX_EXTENT), into one int64: the same order).
    best: tuple[tuple[int, int, int], bytes] | None = None
    pick = 0
    for i, (perm, signs) in enumerate(ROTATIONS):
        p = turn_points(corners, perm, signs, size)
        key = np.sort((p[:, 0] << 32) | (p[:, 1] << 16) | p[:, 2])
        whole = ((size[perm[2]], size[perm[1]], size[perm[0]]), key.astype(">i8").tobytes())
        if best is None or whole < best:
            best, pick = whole, i
    return pick


def _grow(
    turned: Int64Array,
    normals: Int64Array,
    offsets: Int64Array,
    perm: tuple[int, int, int],
    signs: tuple[int, int, int],
    size: tuple[int, int, int],
) -> FloatArray | None:
    # v + (v − c)/2ᴷ in the turned frame. c is the centre of the corners' box when it lies strictly inside
    # (a symmetry of A fixes it, so a symmetric A gets a symmetric R: a box grows evenly on all sides), else
    # their mean rounded to the grid 2⁻ᵐ for the first m that does (the mean itself is inside: Q has
    # volume). 2ᴷ is the least power of two that moves no face out by more than ½ (the octahedron of radius
    # 2ⁿ gets |x| + |y| + |z| ≤ r + ½ exactly). The planes are in A's frame: the margins are read there.
    n = turned.shape[0]
    candidates = [(1, turned.min(axis=0) + turned.max(axis=0))]  # (m, 2ᵐ c)
    total = turned.sum(axis=0)
    candidates += [(m, np.floor_divide(2 * total * (1 << m) + n, 2 * n)) for m in range(24)]
    for m, c_m in candidates:
        here = turn_back_points(c_m[None, :].astype(np.float64) / (1 << m), perm, signs, size)[0]
        c_here = np.rint(here * (1 << m)).astype(np.int64)  # 2ᵐ c in A's frame, exact
        margin = offsets * (1 << m) - normals @ c_here  # 2ᵐ (b − a·c)
        if margin.min() >= 1:
            break
    else:
        return None
    # Each face moves out by 2⁻ᴷ (b − a·c) = margin / 2ᵇⁱᵍ (big = m + K), at most ½ and more than 0.
    big = (int(margin.max()) - 1).bit_length() + 1
    if int(np.abs(turned).max()).bit_length() + 1 + max(big, 0) > 52:
        return None  # the grown corners would not all be float64 numbers
    grown: FloatArray = turned + (turned * (1 << m) - c_m) / 2.0**big
    return grown


@njit(cache=True)
def _fans(
    turned: Int64Array | FloatArray, face_ptr: Int64Array, face_corner: Int64Array
) -> Int64Array:  # pragma: no cover
    # Each face as a fan from its corner that comes first in the turned frame (x, then y, then z).
    nf = face_ptr.shape[0] - 1
    out = np.empty((face_corner.shape[0] - 2 * nf, 3), np.int64)
    m = 0
    for f in range(nf):
        lo, hi = face_ptr[f], face_ptr[f + 1]
        s = lo
        for i in range(lo + 1, hi):
            a, b = face_corner[i], face_corner[s]
            if (turned[a, 0], turned[a, 1], turned[a, 2]) < (turned[b, 0], turned[b, 1], turned[b, 2]):
                s = i
        size = hi - lo
        for i in range(1, size - 1):
            out[m, 0] = face_corner[s]
            out[m, 1] = face_corner[lo + (s - lo + i) % size]
            out[m, 2] = face_corner[lo + (s - lo + i + 1) % size]
            m += 1
    return out
