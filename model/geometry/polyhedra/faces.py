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
from mrm.geometry.polyhedra.predicates import UNKNOWN, o3

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


__all__ = ["face_labels"]
