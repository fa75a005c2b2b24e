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
side. The required corners are the least set holding every corner the rectangles use (a fixed point: grown
from the empty set, pass after pass, until a pass adds none). Then a face's outline is split at exactly the
required corners on it, the same for both faces along an edge, and two rectangles of one face meeting along a
row line share their points there: no T-junction, every edge in exactly two triangles, every vertex in
Z + {¼, ¾}. A box is 12 triangles; blobs take about one triangle per surfel (marching cubes: two).

**The computation** builds neither the doubled grid (8 times the voxels) nor pass after pass. A seam is in
R(A) only if its core is, so all the squares of a plane have one sign: those of plane 2p + 1 (2p) are the
cells of voxel slice p doubled minus those of its intersection with slice p + 1 (p − 1) doubled, found row by
row from the runs of the mask along the rows. A run of squares repeated over consecutive rows is a *stack*.
Whatever is required, the rectangles use the corners of each stack's first and last runs (the ends of the
runs of the rows beyond, inside them, are corners of those rows' stacks, the runs of a row being a cell
apart). A rectangle stops inside a stack only at a required corner on its sides, and none lies there: at
such a corner the plane has two squares, on one side of a straight side, which leaves one down-set of the
cells around the corner up to symmetry (two cells in, or six): a straight crease with four squares, the
corner inside a run of the perpendicular plane along the crease and on no other square. So no rectangle
stops inside a stack (the passes end at the second), the required corners are the stacks' corners, and one
meshing gives the mesh. The corners are set in a bitmap (one bit per corner of the doubled grid: as many
bytes as the mask's box) and read out in the vertices' order; the triangles number 2 (vertices − 2 χ(R(A)))
by Euler's formula on the closed surface, χ(R(A)) known beforehand from the runs. The rest of the memory is
that of the mask's runs and of the surface.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt

from mrm.core.limits import check_pixels
from mrm.geometry._jit import leaf_njit, njit
from mrm.geometry.reconstruct._base import _grow1
from mrm.geometry.topology.labeling import _find, _union

FloatArray = npt.NDArray[np.float64]
Int64Array = npt.NDArray[np.int64]
Int32Array = npt.NDArray[np.int32]


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


#: For each axis a (0 = x, 1 = y, 2 = z) normal to a family of planes: the shifts of a corner's (plane, row,
#: column) indices in its packed key mz << 42 | my << 21 | mx, the plane's row and column axes (v, u) being
#: (z, y), (x, z) and (y, x), so that (u, v, a) is right-handed.
_SHIFTS = np.array([[0, 42, 21], [21, 0, 42], [42, 21, 0]], np.int64)


# ------------------------------------------------------------------------------------------- runs of the mask
#: ctz by de Bruijn multiplication: the index of the lowest set bit b of a word is _DEBRUIJN[(b · K) >> 58].
_DEBRUIJN_K = 0x022FDD63CC95386D
_DEBRUIJN = np.zeros(64, np.int64)
_DEBRUIJN[[((1 << i) * _DEBRUIJN_K % (1 << 64)) >> 58 for i in range(64)]] = np.arange(64)


@njit(cache=True)
def _x_runs(
    buf: npt.NDArray[np.uint8], fy: int, fx: int, k0: int, j0: int, i0: int, sz: int, sy: int, sx: int
) -> tuple[Int64Array, Int32Array, Int32Array]:  # pragma: no cover
    # The runs along x of the box [k0, k0 + sz) × [j0, j0 + sy) × [i0, i0 + sx) of a C-contiguous mask of rows
    # of fx bytes, fy rows a slice (buf: its bytes), the box padded by one empty voxel on each side: line
    # z · (sy + 2) + y holds the runs [s, e) of padded x numbered ptr[line] to ptr[line + 1] (excluded). The
    # bytes are read 8 at a time where aligned: a word equal to the last byte repeated is passed, otherwise
    # the bytes differing from the one before (the word xor itself shifted by a byte) are the runs' ends.
    words = buf[: 8 * (buf.size // 8)].view(np.uint64)
    ones = np.uint64(0x0101010101010101)
    mult = np.uint64(_DEBRUIJN_K)
    ny = sy + 2
    ptr = np.zeros((sz + 2) * ny + 1, np.int64)
    s = np.empty(1024, np.int32)
    e = np.empty(1024, np.int32)
    n = 0
    for z in range(sz):
        for y in range(sy):
            b0 = ((k0 + z) * fy + j0 + y) * fx + i0  # the row's first byte
            inside = False
            c = 0
            while c < sx:
                if ((b0 + c) & 7) == 0 and c + 8 <= sx:
                    w = words[(b0 + c) >> 3]
                    w |= w >> np.uint64(4)  # any non-zero byte to 1
                    w |= w >> np.uint64(2)
                    w |= w >> np.uint64(1)
                    w &= ones
                    t = w ^ ((w << np.uint64(8)) | np.uint64(inside))  # 1 where a byte differs from the last
                    while t:
                        low = t & (~t + np.uint64(1))
                        at = c + (_DEBRUIJN[np.int64((low * mult) >> np.uint64(58))] >> 3)
                        if not inside:
                            if n == s.size:
                                s = _grow1(s, n, 2 * s.size)
                                e = _grow1(e, n, 2 * e.size)
                            s[n] = at + 1
                        else:
                            e[n] = at + 1
                            n += 1
                        inside = not inside
                        t ^= low
                    c += 8
                    continue
                if bool(buf[b0 + c]) != inside:
                    if not inside:
                        if n == s.size:
                            s = _grow1(s, n, 2 * s.size)
                            e = _grow1(e, n, 2 * e.size)
                        s[n] = c + 1
                    else:
                        e[n] = c + 1
                        n += 1
                    inside = not inside
                c += 1
            if inside:
                e[n] = sx + 1
                n += 1
            ptr[(z + 1) * ny + y + 2] = n
    for k in range(1, ptr.size):  # the empty lines of the padding
        ptr[k] = max(ptr[k], ptr[k - 1])
    return ptr, s[:n], e[:n]


@leaf_njit(cache=True)
def _emit_diff(
    s: Int32Array,
    e: Int32Array,
    a0: int,
    a1: int,
    b0: int,
    b1: int,
    t: int,
    step: int,
    base: int,
    start: bool,
    fill: bool,
    count: Int64Array,
    cursor: Int64Array,
    out_s: Int32Array,
    out_e: Int32Array,
) -> None:  # pragma: no cover
    # Each voxel x of runs a0 .. a1 − 1 minus runs b0 .. b1 − 1 (one row) starts (or ends) at t a run of line
    # base + x · step: counted, or written.
    j = b0
    for i in range(a0, a1):
        cur = s[i]
        hi = e[i]
        while j < b1 and e[j] <= cur:
            j += 1
        k = j
        while cur < hi:
            nxt = hi
            if k < b1 and s[k] < hi:
                nxt = max(cur, s[k])  # the gap before run k of b
            for x in range(cur, nxt):
                line = base + x * step
                if not fill:
                    if start:
                        count[line + 1] += 1
                elif start:
                    out_s[cursor[line]] = t
                else:
                    out_e[cursor[line]] = t
                    cursor[line] += 1
            if nxt < hi:
                cur = e[k]
                k += 1
            else:
                cur = hi


@njit(cache=True)
def _cross_runs(
    ptr: Int64Array, s: Int32Array, e: Int32Array, nz: int, ny: int, nx: int, along_z: bool
) -> tuple[Int64Array, Int32Array, Int32Array]:  # pragma: no cover
    # From the runs along x of lines (z, y) (:func:`_x_runs`, padded sizes nz, ny, nx): the runs along y of
    # lines x · nz + z, or along z of lines y · nx + x. A run along y starts (ends) at y where voxel (x, y, z)
    # is in (out) and (x, y − 1, z) out (in): the voxels of one row's runs minus the previous row's.
    n_lines = ny * nx if along_z else nx * nz
    out = np.zeros(n_lines + 1, np.int64)
    cursor = np.empty(0, np.int64)
    out_s = np.empty(0, np.int32)
    out_e = np.empty(0, np.int32)
    for fill in (False, True):
        if fill:
            for k in range(n_lines):
                out[k + 1] += out[k]
            cursor = out[:-1].copy()
            out_s = np.empty(out[n_lines], np.int32)
            out_e = np.empty(out[n_lines], np.int32)
        n_outer, n_t = (ny, nz) if along_z else (nz, ny)
        for o in range(n_outer):
            for t in range(1, n_t):
                if along_z:
                    prev = (t - 1) * ny + o
                    cur = t * ny + o
                    step, base = 1, o * nx
                else:
                    prev = o * ny + t - 1
                    cur = o * ny + t
                    step, base = nz, o
                p0, p1, c0, c1 = ptr[prev], ptr[prev + 1], ptr[cur], ptr[cur + 1]
                if p0 == p1 and c0 == c1:
                    continue
                _emit_diff(s, e, c0, c1, p0, p1, t, step, base, True, fill, out, cursor, out_s, out_e)
                _emit_diff(s, e, p0, p1, c0, c1, t, step, base, False, fill, out, cursor, out_s, out_e)
    return out, out_s, out_e


# ------------------------------------------------------------------------------------ the boundary squares
#: Flags of a run of squares: the row below (above) has the same run.
_BELOW = 1
_ABOVE = 2


@leaf_njit(cache=True)
def _and(
    a_s: Int32Array,
    a_e: Int32Array,
    a0: int,
    a1: int,
    b_s: Int32Array,
    b_e: Int32Array,
    b0: int,
    b1: int,
    o_s: Int32Array,
    o_e: Int32Array,
    o0: int,
) -> int:  # pragma: no cover
    # The runs of (runs a0 .. a1 − 1 of a) ∩ (runs b0 .. b1 − 1 of b), written to o from o0; their end.
    n = o0
    i = a0
    j = b0
    while i < a1 and j < b1:
        lo = max(a_s[i], b_s[j])
        hi = min(a_e[i], b_e[j])
        if lo < hi:
            o_s[n] = lo
            o_e[n] = hi
            n += 1
        if a_e[i] < b_e[j]:
            i += 1
        else:
            j += 1
    return n


@leaf_njit(cache=True)
def _and_rows(
    a_s: Int32Array,
    a_e: Int32Array,
    aptr: Int64Array,
    a_row0: int,
    b_s: Int32Array,
    b_e: Int32Array,
    bptr: Int64Array,
    b_row0: int,
    n_rows: int,
    o_s: Int32Array,
    o_e: Int32Array,
    optr: Int64Array,
) -> None:  # pragma: no cover
    # Row q of o: row a_row0 + q of a ∩ row b_row0 + q of b, for q < n_rows (optr[0] = 0).
    optr[0] = 0
    for q in range(n_rows):
        a, b = a_row0 + q, b_row0 + q
        optr[q + 1] = _and(a_s, a_e, aptr[a], aptr[a + 1], b_s, b_e, bptr[b], bptr[b + 1], o_s, o_e, optr[q])


@leaf_njit(cache=True)
def _row_squares(
    f_s: Int32Array,
    f_e: Int32Array,
    f0: int,
    f1: int,
    h_s: Int32Array,
    h_e: Int32Array,
    h0: int,
    h1: int,
    d_s: Int32Array,
    d_e: Int32Array,
) -> int:  # pragma: no cover
    # The cell runs of D(F) \ D(H) (voxel runs f0 .. f1 − 1 of f and h0 .. h1 − 1 of h, H ⊆ F) into d;
    # their number.
    nd = 0
    j = h0
    for i in range(f0, f1):
        a = f_s[i]
        b = f_e[i]
        cur = 2 * a
        while j < h1 and h_s[j] < b:  # the runs of H inside this run of F
            if 2 * h_s[j] > cur:
                d_s[nd] = cur
                d_e[nd] = 2 * h_s[j]
                nd += 1
            cur = 2 * h_e[j] - 1
            j += 1
        if 2 * b - 1 > cur:
            d_s[nd] = cur
            d_e[nd] = 2 * b - 1
            nd += 1
    return nd


@njit(cache=True)
def _plane_squares(
    ls: Int32Array,
    le: Int32Array,
    lptr: Int64Array,
    line0: int,
    fo_s: Int32Array,
    fo_e: Int32Array,
    foptr: Int64Array,
    s_s: Int32Array,
    s_e: Int32Array,
    sptr: Int64Array,
    so_s: Int32Array,
    so_e: Int32Array,
    soptr: Int64Array,
    nv: int,
    d_s: Int32Array,
    d_e: Int32Array,
    rptr: Int64Array,
    row0: int,
    rc0: Int32Array,
    rc1: Int32Array,
    fl: npt.NDArray[np.uint8],
    n: int,
) -> tuple[Int32Array, Int32Array, npt.NDArray[np.uint8], int, int]:  # pragma: no cover
    # The squares of one plane, D(X) \ D(X ∩ Y) row by row, appended to the runs (rc0, rc1, fl) with the
    # rows' ends in rptr from row0: cell row 2q is voxel row q of X (lines line0 + q) minus row q of
    # S = X ∩ Y, cell row 2q + 1 row q of X's rows q and q + 1 together (fo) minus that of S's (so). Returns
    # the runs and, for X the lower slice, the plane's share of χ(R(A)): runs of X minus of S, even minus odd
    # rows.
    chi = 0
    prev0 = n  # the runs of the previous row
    prev1 = n
    for cv in range(2 * nv - 1):
        q = cv // 2
        if cv % 2 == 0:
            f0, f1, h0, h1 = lptr[line0 + q], lptr[line0 + q + 1], sptr[q], sptr[q + 1]
            nd = _row_squares(ls, le, f0, f1, s_s, s_e, h0, h1, d_s, d_e)
            chi += (f1 - f0) - (h1 - h0)
        else:
            f0, f1, h0, h1 = foptr[q], foptr[q + 1], soptr[q], soptr[q + 1]
            nd = _row_squares(fo_s, fo_e, f0, f1, so_s, so_e, h0, h1, d_s, d_e)
            chi -= (f1 - f0) - (h1 - h0)
        while n + nd > rc0.size:
            rc0 = _grow1(rc0, n, 2 * rc0.size)
            rc1 = _grow1(rc1, n, 2 * rc1.size)
            fl = _grow1(fl, n, 2 * fl.size)
        k = prev0
        for i in range(nd):
            rc0[n] = d_s[i]
            rc1[n] = d_e[i]
            fl[n] = 0
            while k < prev1 and rc0[k] < d_s[i]:
                k += 1
            if k < prev1 and rc0[k] == d_s[i] and rc1[k] == d_e[i]:
                fl[k] |= _ABOVE
                fl[n] = _BELOW
            n += 1
        prev0 = prev1
        prev1 = n
        rptr[row0 + cv + 1] = n
    return rc0, rc1, fl, n, chi


@njit(cache=True)
def _axis_squares(
    lptr: Int64Array,
    ls: Int32Array,
    le: Int32Array,
    na: int,
    nv: int,
    nu: int,
    rptr: Int64Array,
    row0: int,
    rc0: Int32Array,
    rc1: Int32Array,
    fl: npt.NDArray[np.uint8],
    n: int,
) -> tuple[Int32Array, Int32Array, npt.NDArray[np.uint8], int, int]:  # pragma: no cover
    # The boundary squares of the planes normal to one axis, as runs [rc0, rc1) of cell columns per row
    # (plane m, cell row r) = row row0 + m · (2 nv − 1) + r, with their flags fl (_BELOW, _ABOVE), from the
    # runs along u of the voxel lines p · nv + q (padded sizes na, nv, nu). Plane 2p + 1 separates core p
    # from seam (p, p + 1) and plane 2p + 2 seam (p, p + 1) from core p + 1; a seam is in R(A) only if its
    # core is, so their squares are the cells of the doubled slice p (p + 1) not in the doubled X_p ∩ X_p+1:
    # D(X) \ D(X ∩ Y), D doubling the runs [i0, i1) of voxels to cells [2 i0, 2 i1 − 1), with sign +1 (−1).
    # The rows of X ∩ Y, and those of each slice's and of X ∩ Y's consecutive rows together (the odd cell
    # rows), are made once for both planes. Also returns χ(R(A)) (see safety_net_3d).
    n_rows = 2 * nv - 1
    chi = 0
    most = 1  # the most runs in a slice
    for p in range(na):
        most = max(most, lptr[(p + 1) * nv] - lptr[p * nv])
    cap = 2 * most + nv
    fo_s = np.empty(cap, np.int32)  # the odd rows of slice p
    fo_e = np.empty(cap, np.int32)
    foptr = np.empty(nv, np.int64)
    fo2_s = np.empty(cap, np.int32)  # of slice p + 1
    fo2_e = np.empty(cap, np.int32)
    fo2ptr = np.empty(nv, np.int64)
    s_s = np.empty(cap, np.int32)  # the rows of S = X_p ∩ X_p+1
    s_e = np.empty(cap, np.int32)
    sptr = np.empty(nv + 1, np.int64)
    so_s = np.empty(2 * cap, np.int32)  # its odd rows
    so_e = np.empty(2 * cap, np.int32)
    soptr = np.empty(nv, np.int64)
    d_s = np.empty(nu + 1, np.int32)
    d_e = np.empty(nu + 1, np.int32)
    for cv in range(n_rows):  # plane 0: below the padding's first slice, no squares
        rptr[row0 + cv + 1] = n
    _and_rows(ls, le, lptr, 0, ls, le, lptr, 1, nv - 1, fo_s, fo_e, foptr)
    for p in range(na - 1):
        _and_rows(ls, le, lptr, (p + 1) * nv, ls, le, lptr, (p + 1) * nv + 1, nv - 1, fo2_s, fo2_e, fo2ptr)
        _and_rows(ls, le, lptr, p * nv, ls, le, lptr, (p + 1) * nv, nv, s_s, s_e, sptr)
        _and_rows(s_s, s_e, sptr, 0, s_s, s_e, sptr, 1, nv - 1, so_s, so_e, soptr)
        m = 2 * p + 1
        rc0, rc1, fl, n, c = _plane_squares(
            ls, le, lptr, p * nv, fo_s, fo_e, foptr, s_s, s_e, sptr, so_s, so_e, soptr, nv, d_s, d_e,
            rptr, row0 + m * n_rows, rc0, rc1, fl, n,
        )  # fmt: skip
        chi += c
        rc0, rc1, fl, n, c = _plane_squares(
            ls, le, lptr, (p + 1) * nv, fo2_s, fo2_e, fo2ptr, s_s, s_e, sptr, so_s, so_e, soptr, nv,
            d_s, d_e, rptr, row0 + (m + 1) * n_rows, rc0, rc1, fl, n,
        )  # fmt: skip
        fo_s, fo2_s = fo2_s, fo_s
        fo_e, fo2_e = fo2_e, fo_e
        foptr, fo2ptr = fo2ptr, foptr
    for cv in range(n_rows):  # the last plane, above the padding's last slice
        rptr[row0 + (2 * na - 1) * n_rows + cv + 1] = n
    return rc0, rc1, fl, n, chi


# -------------------------------------------------------------------------------------- the required corners
@leaf_njit(cache=True)
def _set(words: npt.NDArray[np.uint64], idx: int) -> bool:  # pragma: no cover
    # Set bit idx; True if it was clear.
    bit = np.uint64(1) << np.uint64(idx & 63)
    w = words[idx >> 6]
    if w & bit:
        return False
    words[idx >> 6] = w | bit
    return True


@njit(cache=True)
def _required(
    rptr: Int64Array, fl: npt.NDArray[np.uint8], rc0: Int32Array, rc1: Int32Array, dims: Int64Array
) -> Int64Array:  # pragma: no cover
    # The required corners, as packed keys mz << 42 | my << 21 | mx in increasing order: the corners of the
    # stacks' first and last runs (see the module's docstring), set in a bitmap of the corners of the doubled
    # grid, bit (mz · 2 ny + my) · 2 nx + mx, and read out in order.
    nx, ny, nz = dims[2, 2], dims[2, 1], dims[2, 0]
    w = 2 * nx
    wh = 2 * nx * 2 * ny
    words = np.zeros((wh * 2 * nz + 63) // 64, np.uint64)
    # for each axis, the strides of (plane, row line, column) in the bitmap
    strides = np.array([[1, wh, w], [w, 1, wh], [wh, w, 1]], np.int64)
    n = 0
    row0 = 0
    for a in range(3):
        na, nv = dims[a, 0], dims[a, 1]
        n_rows = 2 * nv - 1
        sp, sr, sc = strides[a, 0], strides[a, 1], strides[a, 2]
        for p in range(2 * na):
            for r in range(n_rows):
                row = row0 + p * n_rows + r
                for k in range(rptr[row], rptr[row + 1]):
                    if not fl[k] & _BELOW:  # the stack's first run: row line r
                        n += _set(words, p * sp + r * sr + rc0[k] * sc)
                        n += _set(words, p * sp + r * sr + rc1[k] * sc)
                    if not fl[k] & _ABOVE:  # its last: row line r + 1
                        n += _set(words, p * sp + (r + 1) * sr + rc0[k] * sc)
                        n += _set(words, p * sp + (r + 1) * sr + rc1[k] * sc)
        row0 += 2 * na * n_rows
    keys = np.empty(n, np.int64)
    n = 0
    mult = np.uint64(_DEBRUIJN_K)
    for wi in range(words.size):
        bits = words[wi]
        while bits:
            low = bits & (~bits + np.uint64(1))
            idx = wi * 64 + _DEBRUIJN[np.int64((low * mult) >> np.uint64(58))]
            keys[n] = ((idx // wh) << 42) | (((idx // w) % (2 * ny)) << 21) | (idx % w)
            n += 1
            bits ^= low
    return keys


# ------------------------------------------------------------------------------------------------- the mesh
@leaf_njit(cache=True)
def _run_at(rptr: Int64Array, rc0: Int32Array, rc1: Int32Array, row: int, c: int) -> int:  # pragma: no cover
    # The run of the row with rc0 <= c <= rc1 (corner c on it or at an end), or −1 (runs are a cell apart).
    lo = int(rptr[row])
    hi = int(rptr[row + 1])
    while lo < hi:
        mid = (lo + hi) // 2
        if rc0[mid] <= c:
            lo = mid + 1
        else:
            hi = mid
    k = lo - 1
    if k >= rptr[row] and c <= rc1[k]:
        return k
    return -1


@leaf_njit(cache=True)
def _lower(lu: Int32Array, lo: int, hi: int, c: int) -> int:  # pragma: no cover
    # The first index in lo .. hi − 1 with lu >= c (lu sorted), else hi.
    while lo < hi:
        mid = (lo + hi) // 2
        if lu[mid] < c:
            lo = mid + 1
        else:
            hi = mid
    return lo


@njit(cache=True)
def _mesh(
    rptr: Int64Array,
    rc0: Int32Array,
    rc1: Int32Array,
    fl: npt.NDArray[np.uint8],
    dims: Int64Array,
    shifts: Int64Array,
    keys: Int64Array,
    n_tri: int,
    lid: npt.NDArray[Any],
) -> tuple[Int64Array, Int64Array, int]:  # pragma: no cover
    # The triangles (vertex numbers: indices in the sorted required corners `keys`), their faces and the
    # number of faces; n_tri: the number of triangles expected (the arrays grow if it is short, and are cut
    # to what was made); lid: room for the vertex numbers (int32 when they fit). No required corner lies on a
    # stack's side inside it: the rectangles are the stacks.
    nk = keys.size
    mask21 = (1 << 21) - 1
    n_lines = 0
    widest = 1
    row0 = 0
    for a in range(3):
        na, nv = dims[a, 0], dims[a, 1]
        n_rows = 2 * nv - 1
        n_lines = max(n_lines, 2 * na * 2 * nv)
        for p in range(2 * na):
            widest = max(widest, rptr[row0 + (p + 1) * n_rows] - rptr[row0 + p * n_rows])
        row0 += 2 * na * n_rows
    # the required corners of each row line (plane, row line), by column: lp, lu, and their numbers lid
    lp = np.empty(n_lines + 2, np.int64)
    lu = np.empty(nk, np.int32)
    parent = np.empty(widest, np.int64)
    face_of = np.empty(widest, np.int64)
    tri = np.empty((max(n_tri, 1), 3), np.int64)
    face = np.empty(max(n_tri, 1), np.int64)
    nt = 0
    nf = 0
    row0 = 0
    for a in range(3):
        na, nv = dims[a, 0], dims[a, 1]
        n_rows = 2 * nv - 1
        sp, sr, sc = shifts[a, 0], shifts[a, 1], shifts[a, 2]
        # keys sorted by (z, y, x) are sorted by column within each row line of any axis
        lines = 2 * na * 2 * nv
        lp[: lines + 2] = 0
        for i in range(nk):
            line = ((keys[i] >> sp) & mask21) * 2 * nv + ((keys[i] >> sr) & mask21)
            lp[line + 1] += 1
        for line in range(lines):
            lp[line + 1] += lp[line]
        for i in range(nk):
            line = ((keys[i] >> sp) & mask21) * 2 * nv + ((keys[i] >> sr) & mask21)
            lu[lp[line]] = (keys[i] >> sc) & mask21
            lid[lp[line]] = i
            lp[line] += 1
        for line in range(lines, 0, -1):
            lp[line] = lp[line - 1]
        lp[0] = 0
        for p in range(2 * na):
            first = rptr[row0 + p * n_rows]
            last = rptr[row0 + (p + 1) * n_rows]
            if first == last:
                continue
            # faces: 4-connected squares, runs overlapping on adjacent rows, numbered by first run
            for k in range(first, last):
                parent[k - first] = k - first
            for r in range(1, n_rows):
                row = row0 + p * n_rows + r
                i = rptr[row - 1]
                j = rptr[row]
                while i < rptr[row] and j < rptr[row + 1]:
                    if rc0[i] < rc1[j] and rc0[j] < rc1[i]:
                        _union(parent, i - first, j - first)
                    if rc1[i] < rc1[j]:
                        i += 1
                    else:
                        j += 1
            for k in range(first, last):
                root = _find(parent, k - first)
                if root == k - first:
                    face_of[root] = nf
                    nf += 1
                else:
                    face_of[k - first] = face_of[root]
            sign = 1 if p % 2 == 1 else -1
            for r in range(n_rows):
                row = row0 + p * n_rows + r
                bl = p * 2 * nv + r
                # the required corners of row lines r and r + 1, walked along with the runs of row r
                kb = lp[bl]
                kt = lp[bl + 1]
                for k in range(rptr[row], rptr[row + 1]):
                    if fl[k] & _BELOW:
                        continue  # in the rectangle of a stack started below
                    c0 = rc0[k]
                    c1 = rc1[k]
                    # the bottom: the required corners c0 .. c1 of row line r (c0 and c1 among them)
                    while kb < lp[bl + 1] and lu[kb] < c0:
                        kb += 1
                    b0 = kb
                    while kb < lp[bl + 1] and lu[kb] < c1:
                        kb += 1
                    b1 = kb + 1
                    # the top: those of the row line above the stack's last run
                    if fl[k] & _ABOVE:
                        r1 = r + 1
                        kk = k
                        while fl[kk] & _ABOVE:
                            kk = _run_at(rptr, rc0, rc1, row + r1 - r, c0)
                            r1 += 1
                        tl = bl + r1 - r
                        t0 = _lower(lu, int(lp[tl]), int(lp[tl + 1]), c0)
                    else:
                        while kt < lp[bl + 2] and lu[kt] < c0:
                            kt += 1
                        tl = bl + 1
                        t0 = kt
                    t1 = t0
                    while t1 < lp[tl + 1] and lu[t1] < c1:
                        t1 += 1
                    t1 += 1
                    if nt + (b1 - b0 - 1) + (t1 - t0 - 1) > tri.shape[0]:  # n_tri short: never seen
                        grown = np.empty((2 * tri.shape[0] + (b1 - b0) + (t1 - t0), 3), np.int64)
                        grown[:nt] = tri[:nt]
                        tri = grown
                        grown_face = np.empty(tri.shape[0], np.int64)
                        grown_face[:nt] = face[:nt]
                        face = grown_face
                    f = face_of[k - first]
                    # the strip between the bottom (row line r) and top (row line r1) points
                    i = b0
                    j = t0
                    while i < b1 - 1 or j < t1 - 1:
                        v0 = lid[i]
                        if j == t1 - 1 or (i < b1 - 1 and lu[i + 1] <= lu[j + 1]):
                            v1 = lid[i + 1]
                            v2 = lid[j]
                            i += 1
                        else:
                            v1 = lid[j + 1]
                            v2 = lid[j]
                            j += 1
                        tri[nt, 0] = v0
                        if sign > 0:
                            tri[nt, 1] = v1
                            tri[nt, 2] = v2
                        else:
                            tri[nt, 1] = v2
                            tri[nt, 2] = v1
                        face[nt] = f
                        nt += 1
        row0 += 2 * na * n_rows
    if nt < tri.shape[0]:
        return tri[:nt].copy(), face[:nt].copy(), nf
    return tri, face, nf


@njit(cache=True)
def _vertices(keys: Int64Array, ox: int, oy: int, oz: int) -> FloatArray:  # pragma: no cover
    # Corner m is at (origin − 1) + (2m − 1)/4 on its axis (keys: mz << 42 | my << 21 | mx).
    v = np.empty((keys.size, 3), np.float64)
    mask21 = (1 << 21) - 1
    for i in range(keys.size):
        v[i, 0] = (2 * (keys[i] & mask21) - 1) / 4.0 + (ox - 1)
        v[i, 1] = (2 * ((keys[i] >> 21) & mask21) - 1) / 4.0 + (oy - 1)
        v[i, 2] = (2 * (keys[i] >> 42) - 1) / 4.0 + (oz - 1)
    return v


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
    k0, j0, i0 = int(ks[0]), int(js[0]), int(is_[0])
    sz, sy, sx = int(ks[-1]) + 1 - k0, int(js[-1]) + 1 - j0, int(is_[-1]) + 1 - i0
    ox, oy, oz = int(origin[0]) + i0, int(origin[1]) + j0, int(origin[2]) + k0
    nz, ny, nx = sz + 2, sy + 2, sx + 2  # the box padded by one empty voxel on each side
    check_pixels(8 * nz * ny * nx, limit, "the safety net's doubled grid")
    if 2 * max(nz, ny, nx) >= 1 << 21:
        raise ValueError("the safety net takes at most 2**20 voxels along each axis")
    if not m.flags.c_contiguous:
        m = np.ascontiguousarray(m[k0 : k0 + sz, j0 : j0 + sy, i0 : i0 + sx])
        k0 = j0 = i0 = 0
    # The doubled grid is never built: the runs of the mask along each axis give each plane's boundary
    # squares as runs per row; the rest works on those runs, the stacks' corners and the mesh.
    xptr, xs, xe = _x_runs(m.view(np.uint8).reshape(-1), m.shape[1], m.shape[2], k0, j0, i0, sz, sy, sx)
    yptr, ys, ye = _cross_runs(xptr, xs, xe, nz, ny, nx, False)
    zptr, zs, ze = _cross_runs(xptr, xs, xe, nz, ny, nx, True)
    dims = np.array([[nx, nz, ny], [ny, nx, nz], [nz, ny, nx]], np.int64)  # (plane, row, column) voxel axes
    rptr = np.zeros(sum(2 * int(d[0]) * (2 * int(d[1]) - 1) for d in dims) + 1, np.int64)
    rc0 = np.empty(1024, np.int32)
    rc1 = np.empty(1024, np.int32)
    fl = np.empty(1024, np.uint8)
    n = 0
    row0 = 0
    for (lptr, ls, le), d in zip(((yptr, ys, ye), (zptr, zs, ze), (xptr, xs, xe)), dims, strict=True):
        rc0, rc1, fl, n, chi = _axis_squares(
            lptr, ls, le, int(d[0]), int(d[1]), int(d[2]), rptr, row0, rc0, rc1, fl, n
        )
        row0 += 2 * int(d[0]) * (2 * int(d[1]) - 1)
    del xptr, xs, xe, yptr, ys, ye, zptr, zs, ze
    rc0, rc1, fl = rc0[:n].copy(), rc1[:n].copy(), fl[:n].copy()  # cut to size: kept through the meshing
    keys = _required(rptr, fl, rc0, rc1, dims)
    # The mesh is a closed surface, the boundary of the 3-manifold R(A): its triangles number
    # 2 (vertices − χ(∂R(A))) with χ(∂R(A)) = 2 χ(R(A)), and R(A) retracts onto A's cubical complex, whose χ
    # is, line by line of voxels along x, runs(L) − runs(L ∩ L_y+1) − runs(L ∩ L_z+1) + runs of the four.
    n_tri = 2 * (keys.size - 2 * chi)
    lid = np.empty(keys.size, np.int32 if keys.size < 1 << 31 else np.int64)
    triangles, face, n_faces = _mesh(rptr, rc0, rc1, fl, dims, _SHIFTS, keys, n_tri, lid)
    del lid, rptr, rc0, rc1, fl
    return SafetyNet3D(_vertices(keys, ox, oy, oz), triangles, face, int(n_faces))
