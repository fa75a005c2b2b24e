"""Polygonize a label volume: one closed mesh per region, common faces shared exactly (watertight).

The 3D counterpart of :mod:`.polygonize` (docs/design.md §11, docs/polygonize-3d.md, ADR 0065). A *region* is
a 6-connected component of the voxels of one non-zero label (label 0 is the background). The result is one
closed, outward-oriented triangle mesh per region, all on one vertex list:

* D_gauss(mesh of a region) = the region's voxels exactly, so a centre-rule voxelizer burns the meshes with
  their labels back to the label volume;
* a face between two regions is triangulated once; both meshes use those triangles, one of them reversed
  (the same vertices): no gap, no overlap, no T-junction;
* every coordinate is a multiple of ¼, exact in float64; the output is deterministic and translating the
  volume by an integer vector translates every mesh exactly.

**Construction** — the *interface complex*, made a 2-manifold per region. Every voxel is cut into 4 × 4 × 4
quarter cells; each belongs to its voxel's region except a few edge and corner cells at *pinches* (a region
meeting itself only along a linel or at a pointel, where its staircase boundary is not a 2-manifold), which
take a neighbouring voxel's region by the linel rule and the pointel table of :mod:`._label_corners` (which
says why every region's boundary is then a 2-manifold; the table is checked exhaustively in the tests). The
eight core cells of a voxel (the cube [p − ¼, p + ¼]³ around its centre) never move, and no other cell's
closure holds a centre, so every centre is strictly inside its own region's solid and outside every other:
D_gauss gives each region exactly its voxels. Region boundaries are then

1. the unit squares between voxels of different regions that no pinch touches (*intact* squares), merged per
   plane, per ordered pair of regions, into maximal rectangles by a greedy sweep (rows, then columns);
2. the quarter squares between quarter cells of different regions near the pinches (*fine* squares);

and every vertex of the complex lying on a rectangle's side becomes a vertex of that rectangle (no
T-junction). A rectangle is triangulated as a fan from a corner whose two sides hold no such vertex, else
from its centre; it is triangulated once and its triangles are used by the region below it as they are and
by the region above it reversed. Only ``gauss`` is accepted: under a cover model two regions sharing a face
would both claim the voxels along it (a :class:`ParameterError` says so), as in 2D.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from mrm.core.errors import ParameterError
from mrm.core.grids import LabelVolume
from mrm.core.limits import PIXEL_COORDINATE_LIMIT
from mrm.core.models import Model
from mrm.core.numbers import read_pixel
from mrm.geometry._jit import njit
from mrm.geometry.reconstruct._label_corners import linel_source, table
from mrm.geometry.topology.cells_3d import region_map_3d

logger = logging.getLogger(__name__)

Floats = npt.NDArray[np.float64]
Int64Array = npt.NDArray[np.int64]
Int32Array = npt.NDArray[np.int32]
UInt8Array = npt.NDArray[np.uint8]

#: Bits of one coordinate in a vertex key (in eighths) or a face key (in quarters, with its axis): a volume
#: side of up to 2^17 voxels.
_BITS = 20
_MASK = (1 << _BITS) - 1


@dataclass(frozen=True)
class RegionMesh:
    """One region of a label volume and its closed mesh.

    Attributes
    ----------
    label : int
        The region's label (non-zero).
    voxels : int
        Its number of voxels.
    triangles : ndarray of int64, shape (m, 3)
        Its boundary, indices into the ``vertices`` of :class:`LabelMeshes`, counter-clockwise seen from
        outside.
    """

    label: int
    voxels: int
    triangles: Int64Array = field(repr=False)


@dataclass(frozen=True)
class LabelMeshes:
    """The meshes of every region of a label volume, on one shared vertex list (:func:`mrm.polygonize`).

    Attributes
    ----------
    vertices : ndarray of float64, shape (n, 3)
        (x, y, z), multiples of ¼; every vertex is used by some region's mesh.
    regions : list of RegionMesh
        By increasing label, then by the raster order (z, y, x) of the region's first voxel.
    surfels : int
        The unit squares between voxels of different regions, or of a region and the background.
    """

    vertices: Floats = field(repr=False)
    regions: list[RegionMesh]
    surfels: int

    @property
    def n_triangles(self) -> int:
        """The triangles of all regions' meshes (a shared face's triangles counted once per side)."""
        return sum(int(r.triangles.shape[0]) for r in self.regions)

    def mesh(self, i: int) -> tuple[Floats, Int64Array]:
        """Region ``i``'s mesh on its own vertices: (vertices (k, 3), triangles (m, 3))."""
        used, triangles = _unique(self.regions[i].triangles)
        return self.vertices[used], triangles

    def polyhedron(self, i: int) -> object:
        """Region ``i``'s mesh as a :class:`~mrm.geometry.polyhedra.Polyhedron` (validated exactly)."""
        from mrm.geometry.polyhedra import Polyhedron

        v, t = self.mesh(i)
        return Polyhedron(v, t, limit=None)

    def polygons(self) -> list[tuple[Int64Array, Int64Array]]:
        """Each region's surface as polygons (ptr, indices into ``vertices``), as mesh files hold them.

        As :attr:`~mrm.geometry.polyhedra.Polyhedron.polygons`, with a face cut where the region on its
        other side changes: a face between two regions is then the same polygon in both, reversed (the
        same corners, every vertex on its boundary kept), so the files stay watertight without
        T-junctions. A vertex inside such a face is in no polygon of either.
        """
        from mrm.geometry.polyhedra.faces import face_labels, face_polygons, split_faces
        from mrm.geometry.polyhedra.manifold import twin_half_edges

        # Each region's mesh is a valid polyhedron by construction (the tests validate it): only its
        # half-edges' twins are needed here, not a second validation (whose pair search would cost several
        # times the polygonization).
        other = _other_sides(self.regions)
        out = []
        for i, r in enumerate(self.regions):
            used, t = _unique(r.triangles)
            v = self.vertices[used]
            twin = twin_half_edges(v, t)
            n, labels = split_faces(face_labels(v, t, twin)[1], twin, other[i])
            ptr, idx = face_polygons(v, t, twin, labels, n)
            out.append((ptr, used[idx]))
        return out


#: Bits per vertex index when a triangle's three are packed into one int64 (below 2²¹ vertices).
_PACK_BITS = 21


def _other_sides(regions: list[RegionMesh]) -> list[Int64Array]:
    # For each region, the region on the other side of each of its triangles (its index in regions), or −1
    # for the background: a face between two regions is the same triangles in both, reversed.
    tris = np.concatenate([r.triangles for r in regions]) if regions else np.zeros((0, 3), np.int64)
    owner = np.repeat(np.arange(len(regions)), [r.triangles.shape[0] for r in regions])
    key = np.sort(tris, axis=1)
    b = _PACK_BITS
    if tris.size and int(key.max()) < 1 << b:  # one int64 per triangle: a sort of it is several times faster
        packed = (key[:, 0] << (2 * b)) | (key[:, 1] << b) | key[:, 2]
        order = np.argsort(packed, kind="stable")
        sorted_key = packed[order]
        pair = np.flatnonzero(sorted_key[1:] == sorted_key[:-1])
    else:  # a shared triangle's two sides end up adjacent
        order = np.lexsort((key[:, 2], key[:, 1], key[:, 0]))
        k = key[order]
        pair = np.flatnonzero(np.all(k[1:] == k[:-1], axis=1))
    a, c = order[pair], order[pair + 1]
    other = np.full(tris.shape[0], -1, np.int64)
    other[a], other[c] = owner[c], owner[a]
    bounds = np.cumsum([0] + [r.triangles.shape[0] for r in regions])
    return [other[bounds[k] : bounds[k + 1]] for k in range(len(regions))]


# --------------------------------------------------------------------------------------------- kernels
@njit(cache=True)
def _pattern_key(vals: Int64Array, ids: Int64Array) -> tuple[int, int]:  # pragma: no cover
    # _label_corners.pattern_key of the eight regions around a pointel, and how many distinct ones there are.
    nb = 0
    key = 0
    bgb = -1
    for p in range(8):
        r = vals[p]
        blk = -1
        for t in range(nb):
            if ids[t] == r:
                blk = t
                break
        if blk < 0:
            ids[nb] = r
            blk = nb
            nb += 1
            if r == 0:
                bgb = blk
        key += blk << (3 * p)
    return key + ((bgb + 1) << 24), nb


@njit(cache=True)
def _find_key(keys: Int64Array, key: int) -> int:  # pragma: no cover
    # The index of key in the sorted keys, or −1.
    lo = np.searchsorted(keys, key)
    if lo < keys.size and keys[lo] == key:
        return int(lo)
    return -1


@njit(cache=True)
def _pointel_values(reg: Int32Array, x: int, y: int, z: int, vals: Int64Array) -> None:  # pragma: no cover
    # The regions of the voxels (x, y, z) + (dx, dy, dz), at position dx + 2·dy + 4·dz.
    for p in range(8):
        vals[p] = reg[z + (p >> 2 & 1), y + (p >> 1 & 1), x + (p & 1)]


@njit(cache=True)
def _cell_region(
    reg: Int32Array, keys: Int64Array, entries: UInt8Array, a: Int64Array, s: Int64Array
) -> int:  # pragma: no cover
    # The region of the quarter cell with quarter-grid coordinates a = (x, y, z) (cell [a, a + 1] per axis,
    # voxel a >> 2). s is scratch of 25 int64.
    nout = 0
    inner = 0
    for ax in range(3):
        r = a[ax] & 3
        s[ax] = a[ax] >> 2  # the voxel
        if r == 3:
            s[3 + ax] = s[ax]  # the pointel (or linel) index: between voxel s and s + 1
            s[6 + ax] = 0  # the cell's voxel is the low one
            nout += 1
        elif r == 0:
            s[3 + ax] = s[ax] - 1
            s[6 + ax] = 1
            nout += 1
        else:
            inner = ax
    if nout < 2:
        return int(reg[s[2], s[1], s[0]])
    vals = s[9:17]
    ids = s[17:25]
    if nout == 3:
        _pointel_values(reg, s[3], s[4], s[5], vals)
        key, nb = _pattern_key(vals, ids)
        pos = s[6] + 2 * s[7] + 4 * s[8]
        if nb == 1:
            return int(vals[pos])
        e = _find_key(keys, key)
        if e < 0:
            return int(vals[pos])
        return int(vals[entries[e, pos]])
    b = inner
    c = (b + 1) % 3
    d = (b + 2) % 3
    g = s[9:13]
    for q in range(4):
        s[13 + b] = s[b]
        s[13 + c] = s[3 + c] + (q & 1)
        s[13 + d] = s[3 + d] + (q >> 1)
        g[q] = reg[s[15], s[14], s[13]]
    q = s[6 + c] + 2 * s[6 + d]
    return int(g[linel_source(g[0], g[1], g[2], g[3], 0, q)])


@njit(cache=True)
def _is_pinch(g0: int, g1: int, g2: int, g3: int) -> bool:  # pragma: no cover
    return linel_source(g0, g1, g2, g3, 0, 0) != 0 or linel_source(g0, g1, g2, g3, 0, 1) != 1


@njit(cache=True)
def _specials(reg: Int32Array, keys: Int64Array) -> tuple[Int64Array, Int64Array]:  # pragma: no cover
    # The pointels whose table entry is not the identity, (x, y, z) of their low voxel, and the pinch linels,
    # (axis b, x, y, z) with the linel's low voxel across it and its voxel along it.
    nz, ny, nx = reg.shape
    pts = np.empty((64, 3), np.int64)
    npt_ = 0
    vals = np.empty(8, np.int64)
    ids = np.empty(8, np.int64)
    for z in range(nz - 1):
        for y in range(ny - 1):
            for x in range(nx - 1):
                r0 = reg[z, y, x]
                same = True
                for p in range(1, 8):
                    if reg[z + (p >> 2 & 1), y + (p >> 1 & 1), x + (p & 1)] != r0:
                        same = False
                        break
                if same:
                    continue
                _pointel_values(reg, x, y, z, vals)
                key, _ = _pattern_key(vals, ids)
                if _find_key(keys, key) < 0:
                    continue
                if npt_ == pts.shape[0]:
                    grown = np.empty((2 * npt_, 3), np.int64)
                    grown[:npt_] = pts
                    pts = grown
                pts[npt_, 0] = x
                pts[npt_, 1] = y
                pts[npt_, 2] = z
                npt_ += 1
    lin = np.empty((64, 4), np.int64)
    nl = 0
    for z in range(nz):
        for y in range(ny):
            for x in range(nx):
                for b in range(3):
                    # the four voxels around the linel along b through the corner of (x, y, z) toward +c, +d
                    if b == 0:
                        if y + 1 >= ny or z + 1 >= nz:
                            continue
                        g0 = reg[z, y, x]
                        g1 = reg[z, y + 1, x]
                        g2 = reg[z + 1, y, x]
                        g3 = reg[z + 1, y + 1, x]
                    elif b == 1:
                        if z + 1 >= nz or x + 1 >= nx:
                            continue
                        g0 = reg[z, y, x]
                        g1 = reg[z + 1, y, x]
                        g2 = reg[z, y, x + 1]
                        g3 = reg[z + 1, y, x + 1]
                    else:
                        if x + 1 >= nx or y + 1 >= ny:
                            continue
                        g0 = reg[z, y, x]
                        g1 = reg[z, y, x + 1]
                        g2 = reg[z, y + 1, x]
                        g3 = reg[z, y + 1, x + 1]
                    if g0 == g1 and g0 == g2 and g0 == g3:
                        continue
                    if not _is_pinch(g0, g1, g2, g3):
                        continue
                    if nl == lin.shape[0]:
                        grown2 = np.empty((2 * nl, 4), np.int64)
                        grown2[:nl] = lin
                        lin = grown2
                    lin[nl, 0] = b
                    lin[nl, 1] = x
                    lin[nl, 2] = y
                    lin[nl, 3] = z
                    nl += 1
    return pts[:npt_], lin[:nl]


@njit(cache=True)
def _mark_bad(bad: UInt8Array, pts: Int64Array, lin: Int64Array) -> None:  # pragma: no cover
    # Bit n of bad[z, y, x]: the unit square between voxel (x, y, z) and its neighbour along axis n touches a
    # special pointel or a pinch linel (its cells may have moved: it is cut into quarter squares).
    v = np.empty(3, np.int64)
    for t in range(pts.shape[0]):
        for n in range(3):
            c = (n + 1) % 3
            d = (n + 2) % 3
            for q in range(4):
                v[n] = pts[t, n]
                v[c] = pts[t, c] + (q & 1)
                v[d] = pts[t, d] + (q >> 1)
                bad[v[2], v[1], v[0]] |= 1 << n
    for t in range(lin.shape[0]):
        b = lin[t, 0]
        c = (b + 1) % 3
        d = (b + 2) % 3
        for side in range(2):
            # the squares across c (between the two voxels along c), at d and d + 1, and across d
            v[b] = lin[t, 1 + b]
            v[c] = lin[t, 1 + c]
            v[d] = lin[t, 1 + d] + side
            bad[v[2], v[1], v[0]] |= 1 << c
            v[c] = lin[t, 1 + c] + side
            v[d] = lin[t, 1 + d]
            bad[v[2], v[1], v[0]] |= 1 << d


@njit(cache=True)
def _face_key(n: int, x: int, y: int, z: int) -> int:  # pragma: no cover
    # The quarter square between cell (x, y, z) and its neighbour along n.
    return (((n << _BITS | x) << _BITS | y) << _BITS) | z


@njit(cache=True)
def _fine_candidates(bad: UInt8Array, pts: Int64Array, lin: Int64Array) -> Int64Array:  # pragma: no cover
    # Every quarter square that may lie between cells of different regions and is not in an intact square: the
    # 16 of each cut square, and those inside the neighbourhood of each special pointel and pinch linel.
    nz, ny, nx = bad.shape
    nb = 0
    for z in range(nz):
        for y in range(ny):
            for x in range(nx):
                m = bad[z, y, x]
                nb += (m & 1) + (m >> 1 & 1) + (m >> 2 & 1)
    out = np.empty(16 * nb + 144 * pts.shape[0] + 160 * lin.shape[0], np.int64)
    k = 0
    v = np.empty(3, np.int64)
    for z in range(nz):
        for y in range(ny):
            for x in range(nx):
                m = bad[z, y, x]
                if m == 0:
                    continue
                for n in range(3):
                    if not (m >> n & 1):
                        continue
                    c = (n + 1) % 3
                    d = (n + 2) % 3
                    for du in range(4):
                        for dv in range(4):
                            v[0] = 4 * x
                            v[1] = 4 * y
                            v[2] = 4 * z
                            v[n] += 3  # the last cell of the low voxel
                            v[c] += du
                            v[d] += dv
                            out[k] = _face_key(n, v[0], v[1], v[2])
                            k += 1
    for t in range(pts.shape[0]):
        # cells 4p + 2 … 4p + 5 per axis around the pointel at 4p + 4; faces between two of them
        for n in range(3):
            c = (n + 1) % 3
            d = (n + 2) % 3
            for a in range(3):
                for du in range(4):
                    for dv in range(4):
                        v[n] = 4 * pts[t, n] + 2 + a
                        v[c] = 4 * pts[t, c] + 2 + du
                        v[d] = 4 * pts[t, d] + 2 + dv
                        out[k] = _face_key(n, v[0], v[1], v[2])
                        k += 1
    for t in range(lin.shape[0]):
        b = lin[t, 0]
        c = (b + 1) % 3
        d = (b + 2) % 3
        for a in range(4):  # along the linel: the four cells of its voxel
            for du in range(4):
                for dv in range(4):
                    v[b] = 4 * lin[t, 1 + b] + a
                    v[c] = 4 * lin[t, 1 + c] + 2 + du
                    v[d] = 4 * lin[t, 1 + d] + 2 + dv
                    if du < 3:
                        out[k] = _face_key(c, v[0], v[1], v[2])
                        k += 1
                    if dv < 3:
                        out[k] = _face_key(d, v[0], v[1], v[2])
                        k += 1
                    if a < 3:
                        out[k] = _face_key(b, v[0], v[1], v[2])
                        k += 1
    return out[:k]


@njit(cache=True)
def _fine_faces(
    faces: Int64Array, reg: Int32Array, keys: Int64Array, entries: UInt8Array
) -> tuple[Int64Array, Int64Array]:  # pragma: no cover
    # The candidate quarter squares between cells of different regions, as rectangles (n, w, u0, v0, u1, v1)
    # in quarter units (u along c = n + 1, v along d = n + 2), with (region below, region above).
    m = faces.size
    rect = np.empty((m, 6), np.int64)
    pair = np.empty((m, 2), np.int64)
    a = np.empty(3, np.int64)
    s = np.empty(25, np.int64)
    k = 0
    for t in range(m):
        f = faces[t]
        z = f & _MASK
        y = (f >> _BITS) & _MASK
        x = (f >> (2 * _BITS)) & _MASK
        n = f >> (3 * _BITS)
        a[0] = x
        a[1] = y
        a[2] = z
        lo = _cell_region(reg, keys, entries, a, s)
        a[n] += 1
        hi = _cell_region(reg, keys, entries, a, s)
        if lo == hi:
            continue
        c = (n + 1) % 3
        d = (n + 2) % 3
        rect[k, 0] = n
        rect[k, 1] = a[n]
        rect[k, 2] = a[c]
        rect[k, 3] = a[d]
        rect[k, 4] = a[c] + 1
        rect[k, 5] = a[d] + 1
        pair[k, 0] = lo
        pair[k, 1] = hi
        k += 1
    return rect[:k], pair[:k]


@njit(cache=True)
def _rectangles(reg: Int32Array, bad: UInt8Array) -> tuple[Int64Array, Int64Array, int]:  # pragma: no cover
    # Intact unit squares merged per plane and per (region below, region above) into maximal rectangles: a run
    # along v, extended along u while the next row holds the same run. Quarter units, as _fine_faces; also the
    # number of all unit squares between different regions (the surfels).
    nz, ny, nx = reg.shape
    dims = np.array([nx, ny, nz], np.int64)
    rect = np.empty((1024, 6), np.int64)
    pair = np.empty((1024, 2), np.int64)
    k = 0
    surfels = 0
    v = np.empty(3, np.int64)
    for n in range(3):
        c = (n + 1) % 3
        d = (n + 2) % 3
        nu = dims[c]
        nv = dims[d]
        lo = np.zeros((nu, nv), np.int64)
        hi = np.zeros((nu, nv), np.int64)
        ok = np.zeros((nu, nv), np.uint8)
        for w in range(dims[n] - 1):
            for u in range(nu):
                for vv in range(nv):
                    v[n] = w
                    v[c] = u
                    v[d] = vv
                    r0 = reg[v[2], v[1], v[0]]
                    v[n] = w + 1
                    r1 = reg[v[2], v[1], v[0]]
                    lo[u, vv] = r0
                    hi[u, vv] = r1
                    ok[u, vv] = 0
                    if r0 != r1:
                        surfels += 1
                        v[n] = w
                        if not (bad[v[2], v[1], v[0]] >> n & 1):
                            ok[u, vv] = 1
            for u in range(nu):
                for vv in range(nv):
                    if not ok[u, vv]:
                        continue
                    a0 = lo[u, vv]
                    a1 = hi[u, vv]
                    v1 = vv + 1
                    while v1 < nv and ok[u, v1] and lo[u, v1] == a0 and hi[u, v1] == a1:
                        v1 += 1
                    u1 = u + 1
                    while u1 < nu:
                        same = True
                        for t in range(vv, v1):
                            if not ok[u1, t] or lo[u1, t] != a0 or hi[u1, t] != a1:
                                same = False
                                break
                        if not same:
                            break
                        u1 += 1
                    for uu in range(u, u1):
                        for t in range(vv, v1):
                            ok[uu, t] = 0
                    if k == rect.shape[0]:
                        r2 = np.empty((2 * k, 6), np.int64)
                        r2[:k] = rect
                        rect = r2
                        p2 = np.empty((2 * k, 2), np.int64)
                        p2[:k] = pair
                        pair = p2
                    rect[k, 0] = n
                    rect[k, 1] = 4 * w + 4
                    rect[k, 2] = 4 * u
                    rect[k, 3] = 4 * vv
                    rect[k, 4] = 4 * u1
                    rect[k, 5] = 4 * v1
                    pair[k, 0] = a0
                    pair[k, 1] = a1
                    k += 1
    return rect[:k], pair[:k], surfels


@njit(cache=True)
def _point_key(n: int, w: int, u: int, v: int) -> int:  # pragma: no cover
    # The key (x << 2B | y << B | z) of the point at w along n, u along n + 1, v along n + 2, in eighths: the
    # quarter grid doubled, so that a rectangle's centre has a key too.
    p0 = w if n == 0 else (v if n == 1 else u)
    p1 = u if n == 0 else (w if n == 1 else v)
    p2 = v if n == 0 else (u if n == 1 else w)
    return ((p0 << _BITS | p1) << _BITS) | p2


@njit(cache=True)
def _corner_keys(rect: Int64Array) -> Int64Array:  # pragma: no cover
    out = np.empty(4 * rect.shape[0], np.int64)
    for t in range(rect.shape[0]):
        n, w, u0, v0, u1, v1 = (
            rect[t, 0],
            2 * rect[t, 1],
            2 * rect[t, 2],
            2 * rect[t, 3],
            2 * rect[t, 4],
            2 * rect[t, 5],
        )
        out[4 * t] = _point_key(n, w, u0, v0)
        out[4 * t + 1] = _point_key(n, w, u1, v0)
        out[4 * t + 2] = _point_key(n, w, u1, v1)
        out[4 * t + 3] = _point_key(n, w, u0, v1)
    return out


@njit(cache=True)
def _triangulate(
    rect: Int64Array, points: Int64Array
) -> tuple[Int64Array, Int64Array, Int64Array]:  # pragma: no cover
    # Each rectangle with every complex vertex on its sides (points: the sorted keys of all corners), as a fan
    # counter-clockwise seen from +n: from a corner whose two sides hold no other vertex, else from the
    # centre. Quarter coordinates in; triangles index the points, then the centres (their keys are returned).
    m = rect.shape[0]
    tri = np.empty((2 * m + 16, 3), np.int64)
    owner = np.empty(2 * m + 16, np.int64)
    ring = np.empty(64, np.int64)
    extra = np.zeros(4, np.int64)
    start = np.empty(4, np.int64)
    centres = np.empty(64, np.int64)
    nc = 0
    k = 0
    for t in range(m):
        n, w, u0, v0, u1, v1 = (
            rect[t, 0],
            2 * rect[t, 1],
            2 * rect[t, 2],
            2 * rect[t, 3],
            2 * rect[t, 4],
            2 * rect[t, 5],
        )
        need = u1 - u0 + v1 - v0 + 1
        if ring.size < need:
            ring = np.empty(2 * need, np.int64)
        r = 0
        extra[:] = 0
        # side 0: (u0, v0) -> (u1, v0); side 1: -> (u1, v1); side 2: -> (u0, v1); side 3: -> (u0, v0). Each
        # side starts at its corner, then takes every vertex of the complex on it (no T-junction).
        for side in range(4):
            start[side] = r
            cu = u1 if side == 1 or side == 2 else u0
            cv = v1 if side >= 2 else v0
            du = 2 if side == 0 else (-2 if side == 2 else 0)
            dv = 2 if side == 1 else (-2 if side == 3 else 0)
            steps = ((u1 - u0) if du != 0 else (v1 - v0)) // 2
            ring[r] = _find_key(points, _point_key(n, w, cu, cv))
            r += 1
            for step in range(1, steps):
                at = _find_key(points, _point_key(n, w, cu + step * du, cv + step * dv))
                if at >= 0:
                    ring[r] = at
                    r += 1
                    extra[side] += 1
        apex = -1
        for corner in range(4):
            if extra[corner] == 0 and extra[(corner + 3) % 4] == 0:
                apex = corner
                break
        count = r - 2 if apex >= 0 else r
        if k + count > tri.shape[0]:
            size = 2 * (k + count)
            t2 = np.empty((size, 3), np.int64)
            t2[:k] = tri[:k]
            tri = t2
            o2 = np.empty(size, np.int64)
            o2[:k] = owner[:k]
            owner = o2
        if apex >= 0:
            a = start[apex]
            for i in range(1, r - 1):
                tri[k, 0] = ring[a]
                tri[k, 1] = ring[(a + i) % r]
                tri[k, 2] = ring[(a + i + 1) % r]
                owner[k] = t
                k += 1
        else:
            if nc == centres.size:
                c2 = np.empty(2 * nc, np.int64)
                c2[:nc] = centres
                centres = c2
            centres[nc] = _point_key(n, w, (u0 + u1) >> 1, (v0 + v1) >> 1)  # an eighth point at worst
            centre = points.size + nc
            nc += 1
            for i in range(r):
                tri[k, 0] = centre
                tri[k, 1] = ring[i]
                tri[k, 2] = ring[(i + 1) % r]
                owner[k] = t
                k += 1
    return tri[:k], owner[:k], centres[:nc]


# ------------------------------------------------------------------------------------------- the function
def _unique(a: Int64Array) -> tuple[Int64Array, Int64Array]:
    """The sorted distinct values of ``a`` and the index of each element among them.

    (numpy 2's ``np.unique`` takes seconds on a few million int64 where a sort takes a tenth of one.)
    """
    flat = a.reshape(-1)
    order = np.argsort(flat, kind="stable")
    s = flat[order]
    first = np.empty(s.size, np.bool_)
    first[:1] = True
    np.not_equal(s[1:], s[:-1], out=first[1:])
    inverse = np.empty(s.size, np.int64)
    inverse[order] = np.cumsum(first) - 1
    return s[first], inverse.reshape(a.shape)


def _runs(starts: npt.NDArray[np.bool_]) -> Int64Array:
    """The index of each run's first element, from a flag per element saying where a run starts."""
    return np.flatnonzero(starts)


def _merge_squares(rect: Int64Array, pair: Int64Array) -> tuple[Int64Array, Int64Array]:
    """Quarter squares of one plane and ordered pair merged: runs along v, then equal runs stacked along u."""
    if rect.shape[0] == 0:
        return rect, pair
    n, w, u, v = rect[:, 0], rect[:, 1], rect[:, 2], rect[:, 3]
    lo, hi = pair[:, 0], pair[:, 1]
    order = np.lexsort((v, u, hi, lo, w, n))
    n, w, u, v, lo, hi = n[order], w[order], u[order], v[order], lo[order], hi[order]
    same = (n[1:] == n[:-1]) & (w[1:] == w[:-1]) & (lo[1:] == lo[:-1]) & (hi[1:] == hi[:-1])
    first = _runs(np.r_[True, ~(same & (u[1:] == u[:-1]) & (v[1:] == v[:-1] + 1))])
    last = np.r_[first[1:], n.size] - 1
    n, w, u, lo, hi = n[first], w[first], u[first], lo[first], hi[first]
    v0, v1 = v[first], v[last] + 1
    order = np.lexsort((u, v1, v0, hi, lo, w, n))
    n, w, u, v0, v1, lo, hi = (x[order] for x in (n, w, u, v0, v1, lo, hi))
    same = (n[1:] == n[:-1]) & (w[1:] == w[:-1]) & (lo[1:] == lo[:-1]) & (hi[1:] == hi[:-1])
    same &= (v0[1:] == v0[:-1]) & (v1[1:] == v1[:-1]) & (u[1:] == u[:-1] + 1)
    first = _runs(np.r_[True, ~same])
    last = np.r_[first[1:], n.size] - 1
    merged = np.stack([n[first], w[first], u[first], v0[first], u[last] + 1, v1[first]], axis=1)
    return merged, np.stack([lo[first], hi[first]], axis=1)


def _as_volume(labels: LabelVolume | npt.ArrayLike, origin: tuple[int, int, int]) -> LabelVolume:
    if isinstance(labels, LabelVolume):
        return labels
    a = np.asarray(labels)
    if a.ndim != 3 or a.dtype.kind not in "iub":
        raise ParameterError(f"labels must be a 3-D integer array, not {a.dtype} of shape {a.shape}")
    if a.size and int(a.min()) < 0:
        raise ParameterError("labels must be non-negative (0 is the background)")
    try:
        return LabelVolume(a, read_pixel(origin, "origin", PIXEL_COORDINATE_LIMIT, 3))
    except ValueError as e:
        raise ParameterError(str(e)) from None


def polygonize_volume(
    labels: LabelVolume | npt.ArrayLike, origin: tuple[int, int, int] = (0, 0, 0), model: str = "gauss"
) -> LabelMeshes:
    """Return one closed mesh per region (6-connected component of one non-zero label) of a label volume.

    Parameters
    ----------
    labels : LabelVolume or array_like of int, shape (nz, ny, nx)
        The label volume: ``labels[k, j, i]`` is the label of voxel (x0 + i, y0 + j, z0 + k); 0 is the
        background.
    origin : (int, int, int)
        (x0, y0, z0) of an array (ignored for a LabelVolume, which has its own).
    model : str
        Only ``"gauss"``: the one model under which meshes sharing their faces give the labels back.

    Returns
    -------
    LabelMeshes
        The meshes on one vertex list: each a closed 2-manifold, outward oriented, with D_gauss = the region's
        voxels; a face between two regions is the same triangles in both meshes, reversed.

    Raises
    ------
    ParameterError
        For a model other than ``gauss``, or an array that is not a 3-D array of non-negative integers.

    Examples
    --------
    >>> import numpy as np
    >>> lab = np.zeros((1, 1, 2), np.int32); lab[0, 0] = [1, 2]   # two voxels side by side
    >>> out = polygonize_volume(lab)
    >>> [(r.label, r.voxels, len(r.triangles)) for r in out.regions]
    [(1, 1, 12), (2, 1, 12)]
    """
    if Model.parse(model).is_cover:
        raise ParameterError(
            f"polygonize needs the gauss model, not {model!r}: under a cover model two regions sharing a "
            "face would both claim the voxels along it (use 'mrm reconstruct' per label instead)"
        )
    lv = _as_volume(labels, origin)
    if lv.is_empty():
        return LabelMeshes(np.zeros((0, 3)), [], 0)
    # Two voxels of background around: every cell looked at near a pinch then has its pointels in the array.
    lab = np.pad(np.ascontiguousarray(lv.labels, dtype=np.int32), 2)
    if 8 * max(lab.shape) + 8 > _MASK:
        raise ParameterError(f"a label volume side may hold at most {(_MASK - 8) // 8 - 2:,} voxels")
    reg, label, voxels, _first = region_map_3d(lab)
    # Indexed by region number (0: the background).
    region_label = np.concatenate((np.zeros(1, np.int64), label))
    region_voxels = np.concatenate((np.zeros(1, np.int64), voxels))
    keys, entries = table()
    pts, lin = _specials(reg, keys)
    bad = np.zeros(reg.shape, np.uint8)
    _mark_bad(bad, pts, lin)
    coarse, coarse_pair, surfels = _rectangles(reg, bad)
    candidates, _ = _unique(_fine_candidates(bad, pts, lin))
    fine, fine_pair = _merge_squares(*_fine_faces(candidates, reg, keys, entries))
    rect = np.concatenate([coarse, fine])
    pair = np.concatenate([coarse_pair, fine_pair])
    points, _ = _unique(_corner_keys(rect))
    tri, owner, centres = _triangulate(rect, points)
    lo, hi = pair[owner, 0], pair[owner, 1]
    # Below the face the region's outward normal is +n (the fan's orientation); above it, the same reversed.
    all_tri = np.concatenate([tri[lo != 0], tri[hi != 0][:, ::-1]])
    all_owner = np.concatenate([lo[lo != 0], hi[hi != 0]])
    vkeys = np.concatenate([points, centres])
    x0, y0, z0 = lv.origin
    eighths = np.stack([vkeys >> (2 * _BITS), (vkeys >> _BITS) & _MASK, vkeys & _MASK], axis=1)
    # Eighth coordinate e of the padded array is (e − 20) / 8 from the first voxel's centre: exact in float64.
    vertices = (eighths - 20).astype(np.float64) / 8.0 + np.array([x0, y0, z0], np.float64)
    order = np.argsort(all_owner, kind="stable")
    all_tri, all_owner = all_tri[order], all_owner[order]
    bounds = np.searchsorted(all_owner, np.arange(1, region_label.size + 1))
    meshes = [
        RegionMesh(int(region_label[r]), int(region_voxels[r]), all_tri[bounds[r - 1] : bounds[r]])
        for r in range(1, region_label.size)
    ]
    meshes.sort(key=lambda m: m.label)  # stable: raster order within a label
    logger.debug(
        "polygonized %d regions: %d surfels, %d special pointels, %d pinch linels, %d rectangles, %d quarter "
        "squares, %d triangles",
        len(meshes), surfels, len(pts), len(lin), len(coarse), len(fine), all_tri.shape[0],
    )  # fmt: skip
    return LabelMeshes(vertices, meshes, surfels)
