"""Combinatorial checks of a triangle mesh: closed, edge-manifold, consistently oriented, manifold vertices.

Everything here depends on the vertex indices only (after the vertices have been checked distinct), so it is
exact by construction. Each check raises :class:`~mrm.core.errors.InvalidGeometryError` naming the first
offending edge (its two end points' coordinates, and the triangles on it) or vertex; "first" means the one
involving the lowest triangle index, so a message points at the same place as the file's order.

The twin table built here (for every half-edge 3·t + k, from ``triangles[t, k]`` to
``triangles[t, (k+1) % 3]``, the opposite half-edge of the neighbouring triangle) also gives the shells
(edge-connected components) and the faces.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mrm.core.errors import InvalidGeometryError
from mrm.geometry._jit import njit

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]


@njit(cache=True)
def components(n: int, a: Ints, b: Ints) -> tuple[int, Ints]:
    """Connected components of the graph on 0 … n−1 with edges a[i]–b[i] (union–find).

    Returns the number of components and every node's component, numbered in the order of their
    smallest node (so labels follow the input's order).
    """
    parent = np.arange(n)
    for e in range(a.shape[0]):
        x, y = a[e], b[e]
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        while parent[y] != y:
            parent[y] = parent[parent[y]]
            y = parent[y]
        if x != y:
            if x < y:
                parent[y] = x
            else:
                parent[x] = y
    labels = np.empty(n, np.int64)
    count = 0
    for i in range(n):
        r = i
        while parent[r] != r:
            r = parent[r]
        if r == i:
            labels[i] = count
            count += 1
        else:
            labels[i] = labels[r]  # r < i: the root is the smallest node, labelled already
    return count, labels


def fmt_point(p: Floats) -> str:
    """``(x, y, z)`` with every float in full (``repr``), so the user can find the vertex in the file."""
    return "(" + ", ".join(repr(float(c)) for c in p) + ")"


def _edge(vertices: Floats, u: int, v: int) -> str:
    return f"{fmt_point(vertices[u])}–{fmt_point(vertices[v])}"


def half_edges(triangles: Ints) -> tuple[Ints, Ints]:
    """Start and end vertex of every half-edge 3·t + k."""
    start = triangles.reshape(-1)
    end = triangles[:, [1, 2, 0]].reshape(-1)
    return start, end


def twin_half_edges(vertices: Floats, triangles: Ints) -> Ints:
    """For every half-edge the opposite one, after checking that the surface is a closed oriented 2-manifold.

    Raises
    ------
    InvalidGeometryError
        An edge in one triangle only (the surface is open), in three or more (non-manifold), or in two
        triangles that run along it in the same direction (inconsistent orientation).
    """
    m = triangles.shape[0]
    n = vertices.shape[0]
    start, end = half_edges(triangles)
    lo = np.minimum(start, end)
    hi = np.maximum(start, end)
    key = lo * np.int64(n) + hi
    order = np.argsort(key, kind="stable")  # stable: half-edges of one edge in triangle order
    k = key[order]
    first = np.flatnonzero(np.r_[True, k[1:] != k[:-1]])
    counts = np.diff(np.r_[first, k.size])
    tri_of = order // 3
    # The lowest triangle on each edge (the stable sort put it first in its group).
    group_min_tri = tri_of[first]

    def _first_bad(mask: npt.NDArray[np.bool_]) -> int:
        bad = np.flatnonzero(mask)
        return int(bad[np.argmin(group_min_tri[bad])])

    if (counts == 1).any():
        g = _first_bad(counts == 1)
        he = int(order[first[g]])
        raise InvalidGeometryError(
            f"the surface is open: edge {_edge(vertices, int(start[he]), int(end[he]))} belongs to triangle "
            f"{he // 3} only (every edge of a closed surface is in exactly two triangles)"
        )
    if (counts > 2).any():
        g = _first_bad(counts > 2)
        he = int(order[first[g]])
        tris = sorted(int(t) for t in tri_of[first[g] : first[g] + counts[g]])
        raise InvalidGeometryError(
            f"non-manifold edge {_edge(vertices, int(start[he]), int(end[he]))}: it belongs to "
            f"{len(tris)} triangles {tris[:6]}{'…' if len(tris) > 6 else ''} "
            "(a closed 2-manifold has two per edge)"
        )
    e1 = order[first]
    e2 = order[first + 1]
    same = start[e1] == start[e2]
    if same.any():
        g = _first_bad(same)
        he = int(e1[g])
        raise InvalidGeometryError(
            f"inconsistent orientation: triangles {int(e1[g]) // 3} and {int(e2[g]) // 3} both run along "
            f"edge {_edge(vertices, int(start[he]), int(end[he]))} in the same direction (neighbours must "
            "traverse a shared edge in opposite directions; flip one, or use repair())"
        )
    twin = np.empty(3 * m, np.int64)
    twin[e1] = e2
    twin[e2] = e1
    return twin


def check_vertex_fans(vertices: Floats, triangles: Ints, twin: Ints) -> None:
    """Refuse a vertex whose triangles form several fans (two sheets touching at a point).

    The corners around a vertex are linked across the edges at it; on a manifold they form one cycle.
    """
    m = triangles.shape[0]
    n = vertices.shape[0]
    he = np.arange(3 * m, dtype=np.int64)
    # Half-edge 3t+k starts at the corner 3t+k; its twin 3t'+k' ends there, so the corner of t' at the same
    # vertex is 3t' + (k'+1) % 3.
    tw = twin[he]
    other = 3 * (tw // 3) + (tw % 3 + 1) % 3
    ncomp, labels = components(3 * m, he, other)
    if ncomp == n:
        return
    corner_vertex = triangles.reshape(-1)
    pairs = np.unique(np.stack([corner_vertex, labels.astype(np.int64)], axis=1), axis=0)
    fans = np.bincount(pairs[:, 0], minlength=n)
    bad = np.flatnonzero(fans > 1)
    # The offending vertex of the lowest triangle.
    tri_of_vertex = np.full(n, m, np.int64)
    np.minimum.at(tri_of_vertex, corner_vertex, np.arange(3 * m, dtype=np.int64) // 3)
    vtx = int(bad[np.argmin(tri_of_vertex[bad])])
    raise InvalidGeometryError(
        f"non-manifold vertex {fmt_point(vertices[vtx])}: the triangles around it form {int(fans[vtx])} "
        f"separate fans (first at triangle {int(tri_of_vertex[vtx])}); the surface touches itself there"
    )


def shells(triangles: Ints, twin: Ints) -> tuple[int, Ints]:
    """Number of shells (edge-connected components of triangles) and the shell of every triangle."""
    m = triangles.shape[0]
    if m == 0:
        return 0, np.zeros(0, np.int64)
    a = np.arange(3 * m, dtype=np.int64) // 3
    b = twin // 3
    n, labels = components(m, a, b)
    return int(n), labels


__all__ = ["check_vertex_fans", "components", "fmt_point", "half_edges", "shells", "twin_half_edges"]
