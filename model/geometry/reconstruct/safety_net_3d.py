"""The trivial reversible continuation in 3D: V(A) eroded by ¼ in the max norm, as a closed triangle mesh.

Reference: docs/design.md §11, "Continuation R in 3D", item 7; the 2D counterpart is :mod:`.safety_net`.

**The cells.** On the *doubled grid* cell 2p is the core [p − ¼, p + ¼] of voxel p along an axis and cell
2p + 1 the seam [p + ¼, p + ¾] between voxels p and p + 1; a cell of Z³ is the product of one interval per
axis (a core, a face seam, an edge seam or a corner seam) and touches the 1, 2, 4 or 8 voxels of the
product. R(A) is the union of the closed cells whose voxels are all in A: V(A) eroded by ¼ in the max norm.
Cell c spans [c/2 − ¼, c/2 + ¼] on each axis, so R(A) is a union of cubes of side ½ and every vertex of it has
coordinates in Z + {¼, ¾} (exact in float64).

**Why it is a valid solid with the (6, 26) topology.** Around any corner of the doubled grid each axis has
one core-like and one seam-like cell, and a cell touching a subset of another's voxels is in R(A) whenever the
other is, so the cells of R(A) around a corner form a down-set of {0, 1}³: they and the cells outside are both
face-connected around the corner, and R(A)'s boundary is a 2-manifold there (no edge or corner where two
cubes meet alone). Voxels of A meeting only along an edge or at a corner touch seams that also touch a voxel
outside A, so their cores stay apart: the shells of R(A) are the 6-components of A, its inner shells the
cavities (bounded 26-components of the complement), and R(A) retracts onto the cubical complex of A (its
Euler characteristic, hence each shell's genus is its component's tunnels).

**D(R(A)) = A in the three models.** Each core holds its voxel's centre in its interior, and a seam touches
only the two, four or eight voxels it lies between, each in A, so R(A) ⊂ V(A) meets V(p) only for p ∈ A and
holds every centre of A with a neighbourhood: gauss (the centres in R(A)), standard (int V(p) + τ meets R(A))
and supercover (V(p) meets R(A)) all give A.

**The mesh.** The boundary squares between a cell of R(A) and one outside are grouped by plane and outward
normal; a **face** is a 4-connected set of them (a maximal set of coplanar edge-adjacent squares). Each face
is cut into rectangles: a run of a row of squares, extended over the following rows with the same run while
no *required* corner lies on its sides. A rectangle is triangulated as a strip between the points of its
bottom and top sides that are its corners, required corners, or corners of the runs of the row on the other
side. The required corners start empty and grow to every corner the rectangles use, until a pass adds none
(a fixed point: the set only grows, within a finite grid). Then a face's outline is split at exactly the
required corners on it, the same for both faces along an edge, and two rectangles of one face meeting along a
row line share their points there: no T-junction, every edge in exactly two triangles, every vertex in
Z + {¼, ¾}. A box is 12 triangles; blobs take about one triangle per surfel (marching cubes: two).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from mrm.core.limits import check_pixels
from mrm.geometry._jit import njit
from mrm.geometry.topology.labeling import _find, _union

FloatArray = npt.NDArray[np.float64]
Int64Array = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]


class SafetyNet3D(NamedTuple):
    """R(A) as a closed, outward-oriented triangle mesh (:func:`safety_net_3d`).

    Attributes
    ----------
    vertices : float64 (n, 3), (x, y, z), each in Z + {¼, ¾}, sorted by (z, y, x).
    triangles : int64 (m, 3), counter-clockwise seen from outside.
    face : int64 (m,), the face of each triangle (0 .. n_faces − 1).
    n_faces : int
        The number of faces (maximal sets of coplanar edge-adjacent triangles).
    """

    vertices: FloatArray
    triangles: Int64Array
    face: Int64Array
    n_faces: int


def _doubled(a: BoolArray, axis: int) -> BoolArray:
    # Cells 2p (core: voxel p) and 2p + 1 (seam: voxels p and p + 1) along one axis.
    n = a.shape[axis]
    shape = list(a.shape)
    shape[axis] = 2 * n - 1
    out = np.empty(shape, bool)
    idx: list[slice] = [slice(None)] * a.ndim
    idx[axis] = slice(0, None, 2)
    out[tuple(idx)] = a
    lo: list[slice] = [slice(None)] * a.ndim
    hi: list[slice] = [slice(None)] * a.ndim
    lo[axis] = slice(0, n - 1)
    hi[axis] = slice(1, n)
    idx[axis] = slice(1, None, 2)
    out[tuple(idx)] = a[tuple(lo)] & a[tuple(hi)]
    return out


@njit(cache=True)
def _run_end(bd: npt.NDArray[np.int8], p: int, r: int, u: int, sign: int) -> bool:  # pragma: no cover
    # True when the squares of the given sign in row r (of plane p) start or stop at corner u (beyond: none).
    R, C = bd.shape[1], bd.shape[2]
    if r < 0 or r >= R:
        return False
    a = u >= 1 and bd[p, r, u - 1] == sign
    b = u < C and bd[p, r, u] == sign
    return bool(a != b)


@njit(cache=True)
def _same_run(
    bd: npt.NDArray[np.int8], p: int, r: int, c0: int, c1: int, sign: int
) -> bool:  # pragma: no cover
    # True when row r has a run of the given sign covering exactly the squares c0 .. c1 − 1.
    C = bd.shape[2]
    if c0 > 0 and bd[p, r, c0 - 1] == sign:
        return False
    if c1 < C and bd[p, r, c1] == sign:
        return False
    for c in range(c0, c1):  # noqa: SIM110 (a plain loop: no generator in a numba kernel)
        if bd[p, r, c] != sign:
            return False
    return True


@njit(cache=True)
def _plane_mesh(
    bd: npt.NDArray[np.int8], req: npt.NDArray[np.uint8]
) -> tuple[Int64Array, Int64Array, int]:  # pragma: no cover
    # bd (P, R, C): +1 / −1 for a boundary square of outward normal +axis / −axis in plane p, row v, column u;
    # req (P, R + 1, C + 1): the corners that must be vertices. Returns the triangles as corner triples
    # (plane, v, u) (int64 (m, 3, 3)), their faces, and the number of faces.
    P, R, C = bd.shape
    # Faces are 4-connected squares of one sign in one plane, labelled plane by plane (memory for one plane).
    parent = np.empty(R * C, np.int64)
    face_of = np.empty(R * C, np.int64)
    covered = np.zeros(R * C, np.uint8)
    nf = 0
    cap = 64
    tri = np.empty((cap, 3, 3), np.int64)
    tface = np.empty(cap, np.int64)
    nt = 0
    bot = np.empty(C + 1, np.int64)
    top = np.empty(C + 1, np.int64)
    for p in range(P):
        plane = bd[p]
        for k in range(R * C):
            parent[k] = k
            covered[k] = 0
        for r in range(R):
            for c in range(C):
                sq = plane[r, c]
                if sq == 0:
                    continue
                k = r * C + c
                if c > 0 and plane[r, c - 1] == sq:
                    _union(parent, k - 1, k)
                if r > 0 and plane[r - 1, c] == sq:
                    _union(parent, k - C, k)
        for k in range(R * C):
            if plane[k // C, k % C] != 0:
                root = _find(parent, k)
                if root == k:
                    face_of[k] = nf
                    nf += 1
                else:
                    face_of[k] = face_of[root]
        for sign in (1, -1):
            for r in range(R):
                row = plane[r]
                c = 0
                while c < C:
                    if row[c] != sign:
                        c += 1
                        continue
                    c0 = c
                    while c < C and row[c] == sign:
                        c += 1
                    c1 = c  # the run covers columns c0 .. c1 − 1: corners c0 .. c1
                    if covered[r * C + c0]:
                        continue  # in a rectangle started below
                    # the rectangle: the following rows with the same run, no required corner on its sides
                    r1 = r + 1  # its top row line
                    while (
                        r1 < R
                        and not req[p, r1, c0]
                        and not req[p, r1, c1]
                        and _same_run(bd, p, r1, c0, c1, sign)
                    ):
                        covered[r1 * C + c0] = 1
                        r1 += 1
                    nb = 0
                    nt_top = 0
                    for u in range(c0, c1 + 1):
                        # a corner, a required corner, or a corner of a run of the row on the other side
                        if u in (c0, c1) or req[p, r, u] or _run_end(bd, p, r - 1, u, sign):
                            bot[nb] = u
                            nb += 1
                        if u in (c0, c1) or req[p, r1, u] or _run_end(bd, p, r1, u, sign):
                            top[nt_top] = u
                            nt_top += 1
                    f = face_of[r * C + c0]
                    # the strip between the bottom (row line r) and top (row line r1) points
                    i = 0
                    j = 0
                    while i < nb - 1 or j < nt_top - 1:
                        if nt + 1 > cap:
                            cap *= 2
                            t2 = np.empty((cap, 3, 3), np.int64)
                            t2[:nt] = tri[:nt]
                            tri = t2
                            f2 = np.empty(cap, np.int64)
                            f2[:nt] = tface[:nt]
                            tface = f2
                        adv_bottom = j == nt_top - 1 or (i < nb - 1 and bot[i + 1] <= top[j + 1])
                        # corners as (plane, v, u); counter-clockwise in (u, v) for sign +1
                        tri[nt, 0, 0] = p
                        tri[nt, 0, 1] = r
                        tri[nt, 0, 2] = bot[i]
                        if adv_bottom:
                            tri[nt, 1, 0] = p
                            tri[nt, 1, 1] = r
                            tri[nt, 1, 2] = bot[i + 1]
                            tri[nt, 2, 0] = p
                            tri[nt, 2, 1] = r1
                            tri[nt, 2, 2] = top[j]
                            i += 1
                        else:
                            tri[nt, 1, 0] = p
                            tri[nt, 1, 1] = r1
                            tri[nt, 1, 2] = top[j + 1]
                            tri[nt, 2, 0] = p
                            tri[nt, 2, 1] = r1
                            tri[nt, 2, 2] = top[j]
                            j += 1
                        if sign < 0:
                            for a in range(3):
                                t = tri[nt, 1, a]
                                tri[nt, 1, a] = tri[nt, 2, a]
                                tri[nt, 2, a] = t
                        tface[nt] = f
                        nt += 1
    return tri[:nt], tface[:nt], nf


#: For each axis a (0 = x, 1 = y, 2 = z): the transpose of a (z, y, x) array to (a, v, u) with (u, v, a)
#: right-handed, and for each of (plane, v, u) the index in (x, y, z) it stands for.
_LAYOUT = (((2, 0, 1), (0, 2, 1)), ((1, 2, 0), (1, 0, 2)), ((0, 1, 2), (2, 1, 0)))


def safety_net_3d(
    mask: npt.ArrayLike, origin: tuple[int, int, int] = (0, 0, 0), limit: int | None = None
) -> SafetyNet3D:
    """R(A) = V(A) eroded by ¼ in the max norm, as a closed outward triangle mesh with its faces.

    Parameters
    ----------
    mask : array_like of bool, shape (nz, ny, nx)
        The voxel set A; ``mask[k, j, i]`` is voxel (x0 + i, y0 + j, z0 + k).
    origin : tuple of int
        (x0, y0, z0).
    limit : int, optional
        Refuse a set whose doubled grid would hold more cells than this, before allocating it.

    Returns
    -------
    SafetyNet3D
        Empty arrays for the empty set.
    """
    m = np.asarray(mask).astype(bool, copy=False)
    if m.ndim != 3:
        raise ValueError(f"a voxel mask must be 3-D, got shape {m.shape}")
    empty = SafetyNet3D(np.zeros((0, 3)), np.zeros((0, 3), np.int64), np.zeros(0, np.int64), 0)
    if not m.any():
        return empty
    ks, js, is_ = (np.flatnonzero(m.any(axis=a)) for a in ((1, 2), (0, 2), (0, 1)))
    m = m[ks[0] : ks[-1] + 1, js[0] : js[-1] + 1, is_[0] : is_[-1] + 1]
    ox, oy, oz = int(origin[0]) + int(is_[0]), int(origin[1]) + int(js[0]), int(origin[2]) + int(ks[0])
    nz, ny, nx = (s + 2 for s in m.shape)
    check_pixels(8 * nz * ny * nx, limit, "the safety net's doubled grid")
    if 2 * max(nz, ny, nx) >= 1 << 21:
        raise ValueError("the safety net takes at most 2**20 voxels along each axis")
    a = np.pad(m, 1)
    s = _doubled(_doubled(_doubled(a, 0), 1), 2)  # cells, (2nz − 1, 2ny − 1, 2nx − 1)
    # The required corners grow until every corner the rectangles use is required (a fixed point): then a
    # face's outline is split at exactly the required corners on it, the same for both faces along an edge.
    req = np.zeros((2 * nz, 2 * ny, 2 * nx), np.uint8)  # corners (mz, my, mx)
    bds = []
    for axis in range(3):
        perm, _ = _LAYOUT[axis]
        st = np.ascontiguousarray(s.transpose(perm))
        sa = np.pad(st, ((1, 1), (0, 0), (0, 0)))
        # plane m lies between cells m − 1 (sa[m]) and m (sa[m + 1])
        bds.append(np.ascontiguousarray(sa[:-1].astype(np.int8) - sa[1:].astype(np.int8)))
    while True:
        tris = []
        faces = []
        nf_total = 0
        for axis in range(3):
            perm, to_xyz = _LAYOUT[axis]
            t, f, nf = _plane_mesh(bds[axis], np.ascontiguousarray(req.transpose(perm)))
            xyz = np.empty_like(t)
            for k in range(3):
                xyz[:, :, to_xyz[k]] = t[:, :, k]
            tris.append(xyz)
            faces.append(f + nf_total)
            nf_total += int(nf)
        used = np.concatenate(tris).reshape(-1, 3)
        if bool(np.all(req[used[:, 2], used[:, 1], used[:, 0]])):
            break
        req[used[:, 2], used[:, 1], used[:, 0]] = 1
    corners = np.concatenate(tris).reshape(-1, 3)  # (mx, my, mz) corner indices
    # Sort vertices by (z, y, x): pack the corner indices (each at most 2·(n + 2) < 2**21, checked above).
    key = (corners[:, 2] << 42) | (corners[:, 1] << 21) | corners[:, 0]
    uniq, inverse = np.unique(key, return_inverse=True)
    cm = np.stack([uniq & ((1 << 21) - 1), (uniq >> 21) & ((1 << 21) - 1), uniq >> 42], axis=1)
    # corner m is at (origin − 1) + (2m − 1)/4 on its axis
    base = np.array([ox - 1, oy - 1, oz - 1], np.float64)
    vertices = base + (2 * cm - 1).astype(np.float64) / 4.0
    triangles = inverse.reshape(-1, 3).astype(np.int64)
    return SafetyNet3D(vertices, triangles, np.concatenate(faces), nf_total)
