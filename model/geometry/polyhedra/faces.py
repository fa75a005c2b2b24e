"""Faces of a polyhedron: the maximal sets of edge-adjacent triangles that are exactly coplanar (§11).

Two triangles across an edge are coplanar when the far vertex of one lies exactly in the plane of the other
(:func:`~mrm.geometry.polyhedra.predicates.o3` = 0); on a valid polyhedron they then face the same
way (they do not overlap), so a face is a planar polygon, possibly with holes, of one orientation.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import njit
from mrm.geometry.polyhedra.manifold import components
from mrm.geometry.polyhedra.predicates import UNKNOWN, o2, o3

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]


@njit(cache=True)
def _coplanar_edges(v: Floats, t: Ints, twin: Ints) -> Ints:
    """Per half-edge: 1 if the triangles across it are coplanar, 0 if not, UNKNOWN if undecided."""
    out = np.zeros(twin.shape[0], np.int64)
    for he in range(twin.shape[0]):
        tw = twin[he]
        if tw < he:
            continue
        f, g = he // 3, tw // 3
        q = t[g, (tw % 3 + 2) % 3]
        s = o3(v, t[f, 0], t[f, 1], t[f, 2], q)
        out[he] = UNKNOWN if s == UNKNOWN else (1 if s == 0 else 0)
    return out


def face_labels(vertices: Floats, triangles: Ints, twin: Ints) -> tuple[int, Ints]:
    """Number of faces and the face of every triangle (numbered in the order of their first triangle)."""
    m = triangles.shape[0]
    if m == 0:
        return 0, np.zeros(0, np.int64)
    flags = _coplanar_edges(vertices, triangles, twin)
    for he in np.flatnonzero(flags == UNKNOWN).tolist():
        tw = int(twin[he])
        f, g = he // 3, tw // 3
        q = int(triangles[g, (tw % 3 + 2) % 3])
        a, b, c = (int(x) for x in triangles[f])
        flags[he] = 1 if o3(vertices, a, b, c, q) == 0 else 0
    coplanar = np.flatnonzero(flags == 1)
    n, labels = components(m, coplanar // 3, twin[coplanar] // 3)  # numbered by first triangle
    return int(n), labels


@njit(cache=True)
def _face_polygons(
    v: Floats, t: Ints, twin: Ints, labels: Ints, n_faces: int
) -> tuple[Ints, Ints]:  # pragma: no cover - compiled
    """The polygons of :func:`face_polygons`, as a CSR list (ptr, vertex indices)."""
    m = t.shape[0]
    # the boundary half-edges of each face (across them lies another face), grouped by face
    count = np.zeros(n_faces + 1, np.int64)
    for he in range(3 * m):
        if labels[twin[he] // 3] != labels[he // 3]:
            count[labels[he // 3] + 1] += 1
    start = np.cumsum(count)
    edges = np.empty(start[n_faces], np.int64)
    fill = start[:n_faces].copy()
    for he in range(3 * m):
        f = labels[he // 3]
        if labels[twin[he] // 3] != f:
            edges[fill[f]] = he
            fill[f] += 1
    tri_count = np.zeros(n_faces + 1, np.int64)
    for i in range(m):
        tri_count[labels[i] + 1] += 1
    tri_start = np.cumsum(tri_count)
    tri_of = np.empty(m, np.int64)
    tfill = tri_start[:n_faces].copy()
    for i in range(m):
        tri_of[tfill[labels[i]]] = i
        tfill[labels[i]] += 1
    ptr = np.zeros(m + n_faces + 1, np.int64)  # at most one polygon per triangle
    out = np.empty(3 * m, np.int64)
    n_poly = 0
    n_out = 0
    after = np.full(v.shape[0], -1, np.int64)  # the next corner along the face's boundary, per corner
    loop = np.empty(start[n_faces] + 1, np.int64)
    turn = np.empty(start[n_faces] + 1, np.int64)
    for f in range(n_faces):
        lo, hi = start[f], start[f + 1]
        k = hi - lo
        ok = k >= 3
        for s in range(lo, hi):  # one outgoing boundary edge per corner, or the face is pinched
            he = edges[s]
            a = t[he // 3, he % 3]
            if after[a] != -1:
                ok = False
            after[a] = t[he // 3, (he % 3 + 1) % 3]
        if ok:  # a single loop through all of them, or the face has holes
            first = t[edges[lo] // 3, edges[lo] % 3]
            x = first
            n = 0
            while n <= k:
                loop[n] = x
                n += 1
                x = after[x]
                if x == first or x == -1:
                    break
            ok = x == first and n == k
        if ok:  # convex: no right turn on the projection along the normal's largest axis
            tri = tri_of[tri_start[f]]
            a, b, c = t[tri, 0], t[tri, 1], t[tri, 2]
            d = 0
            best = -1.0
            for ax in range(3):
                nx = abs(
                    (v[b, (ax + 1) % 3] - v[a, (ax + 1) % 3]) * (v[c, (ax + 2) % 3] - v[a, (ax + 2) % 3])
                    - (v[b, (ax + 2) % 3] - v[a, (ax + 2) % 3]) * (v[c, (ax + 1) % 3] - v[a, (ax + 1) % 3])
                )
                if nx > best:
                    best, d = nx, ax
            sign = o2(v, a, b, c, (d + 1) % 3, (d + 2) % 3)
            if sign == 0 or sign == UNKNOWN:
                ok = False
            for i in range(k):
                if not ok:
                    break
                o = o2(v, loop[(i - 1) % k], loop[i], loop[(i + 1) % k], (d + 1) % 3, (d + 2) % 3)
                if o == UNKNOWN or o * sign < 0:
                    ok = False
                turn[i] = o
        first_corner = -1
        if ok:  # a fan from a vertex whose two neighbours are corners (not straight) has no flat triangle
            for i in range(k):
                if turn[(i - 1) % k] != 0 and turn[(i + 1) % k] != 0:
                    first_corner = i
                    break
        for s in range(lo, hi):
            he = edges[s]
            after[t[he // 3, he % 3]] = -1
        if first_corner >= 0:
            for i in range(k):
                out[n_out] = loop[(first_corner + i) % k]
                n_out += 1
            n_poly += 1
            ptr[n_poly] = n_out
        else:
            for j in range(tri_start[f], tri_start[f + 1]):
                for e in range(3):
                    out[n_out] = t[tri_of[j], e]
                    n_out += 1
                n_poly += 1
                ptr[n_poly] = n_out
    return ptr[: n_poly + 1].copy(), out[:n_out].copy()


def split_faces(labels: Ints, twin: Ints, groups: Ints) -> tuple[int, Ints]:
    """Faces cut where ``groups`` (one value per triangle) changes: (number of faces, face of each triangle).

    Two triangles across an edge stay in one face when they were (``labels``) and their groups are equal.
    """
    tri = np.arange(twin.shape[0]) // 3
    across = twin // 3
    same = (labels[tri] == labels[across]) & (groups[tri] == groups[across])
    n, out = components(labels.shape[0], tri[same], across[same])
    return int(n), out


def face_polygons(
    vertices: Floats, triangles: Ints, twin: Ints, labels: Ints, n_faces: int
) -> tuple[Ints, Ints]:
    """The surface as polygons: one per face, or the face's triangles when it cannot be one polygon.

    A face is one polygon when its boundary is a single loop (no hole, no corner met twice), it is convex
    (no right turn, decided exactly) and it has a vertex whose two neighbours along the loop are corners
    (not straight): the polygon starts there. The fan of triangles from the first vertex — what OBJ, OFF and
    PLY readers make of a polygon — then has no flat triangle (a line through that vertex holds no side
    other than its own two) and covers the face exactly. The vertices run counter-clockwise seen from
    outside, every boundary vertex kept (the neighbouring faces share them). Other faces are written as
    their triangles.

    Returns
    -------
    ptr : ndarray of int64, shape (n + 1,)
        Polygon k is ``indices[ptr[k]:ptr[k + 1]]``.
    indices : ndarray of int64
        Vertex indices.
    """
    if triangles.shape[0] == 0:
        return np.zeros(1, np.int64), np.zeros(0, np.int64)
    return _face_polygons(vertices, triangles, twin, labels, n_faces)


__all__ = ["face_labels", "face_polygons", "split_faces"]
