"""The exact validity check of a polyhedron's boundary (docs/design.md §11), in the order users fix things.

1. arrays: vertices (n, 3) finite float64, triangles (m, 3) integer indices into them, within the limit;
2. every vertex used and no two at the same point (merging them is :func:`~.repair.repair`'s job);
3. no flat triangle (zero area: its three vertices exactly collinear);
4. a closed 2-manifold, consistently oriented (:mod:`.manifold`);
5. no self-intersection (:mod:`.self_intersection`);
6. every shell oriented as its nesting requires, so the volume is positive (:mod:`.shells`).

Each failure raises :class:`~mrm.core.errors.InvalidGeometryError` (a ValueError) saying where: the vertex,
the triangle, the first offending edge with its end points' coordinates, or the first pair of triangles.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mrm.core.errors import InvalidGeometryError
from mrm.core.limits import MAX_OBJECT_TRIANGLES
from mrm.geometry._jit import njit
from mrm.geometry.polyhedra.manifold import check_vertex_fans, fmt_point, shells, twin_half_edges
from mrm.geometry.polyhedra.predicates import UNKNOWN, o2
from mrm.geometry.polyhedra.self_intersection import first_intersecting_pair
from mrm.geometry.polyhedra.shells import check_shells

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

#: Default limit on the number of triangles of a polyhedron (a 512³ surface is a few million): the one
#: declared in :mod:`mrm.core.limits`.
MAX_TRIANGLES = MAX_OBJECT_TRIANGLES


@dataclass(frozen=True)
class Topology:
    """What validation learnt on the way: the twin of every half-edge and the shell of every triangle."""

    twin: Ints
    shell: Ints
    n_shells: int


def as_arrays(vertices: object, triangles: object, limit: int | None = MAX_TRIANGLES) -> tuple[Floats, Ints]:
    """C-contiguous float64 (n, 3) and int64 (m, 3) copies of the inputs, or InvalidGeometryError."""
    try:
        v = np.array(vertices, dtype=np.float64, copy=True, order="C")
    except (TypeError, ValueError) as e:
        raise InvalidGeometryError(f"vertices must be an (n, 3) array of numbers: {e}") from None
    t_in = np.asarray(triangles)
    if t_in.size == 0:
        t_in = t_in.reshape(0, 3).astype(np.int64)
    if t_in.dtype == np.bool_ or not np.issubdtype(t_in.dtype, np.integer):
        raise InvalidGeometryError(f"triangles must be an (m, 3) array of integer indices, not {t_in.dtype}")
    if v.size == 0:
        v = v.reshape(0, 3)
    if v.ndim != 2 or v.shape[1] != 3:
        raise InvalidGeometryError(f"vertices must have shape (n, 3), not {v.shape}")
    if t_in.ndim != 2 or t_in.shape[1] != 3:
        raise InvalidGeometryError(f"triangles must have shape (m, 3), not {t_in.shape}")
    if limit is not None and t_in.shape[0] > limit:
        raise InvalidGeometryError(
            f"the mesh has {t_in.shape[0]:,} triangles, more than the limit of {limit:,}"
        )
    if t_in.size and (int(t_in.min()) < 0 or int(t_in.max()) >= v.shape[0]):
        bad = int(np.flatnonzero(((t_in < 0) | (t_in >= v.shape[0])).any(axis=1))[0])
        raise InvalidGeometryError(
            f"triangle {bad} refers to vertex {[int(x) for x in t_in[bad]]}, "
            f"but there are {v.shape[0]} vertices"
        )
    return v, np.array(t_in, dtype=np.int64, copy=True, order="C")


@njit(cache=True)
def _flat_triangles(v: Floats, t: Ints) -> Ints:
    """Per triangle: 1 if flat (all three projected orientations zero), 0 if not, UNKNOWN if undecided."""
    out = np.zeros(t.shape[0], np.int64)
    for f in range(t.shape[0]):
        flat = 1
        for k in range(3):
            s = o2(v, t[f, 0], t[f, 1], t[f, 2], (k + 1) % 3, (k + 2) % 3)
            if s == UNKNOWN:
                flat = UNKNOWN
            elif s != 0:
                flat = 0
                break
        out[f] = flat
    return out


def _check_points(v: Floats, t: Ints) -> None:
    bad = ~np.isfinite(v).all(axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise InvalidGeometryError(
            f"vertex {i} has a coordinate that is not a finite number: {fmt_point(v[i])}"
        )
    used = np.zeros(v.shape[0], bool)
    used[t.reshape(-1)] = True
    if not used.all():
        i = int(np.flatnonzero(~used)[0])
        raise InvalidGeometryError(
            f"vertex {i} {fmt_point(v[i])} belongs to no triangle (drop it, or use repair())"
        )
    # -0.0 and 0.0 are the same point: compare the values, not the bits. A lexicographic sort puts equal
    # points side by side (np.unique(axis=0) does the same, several times slower).
    w = v + 0.0
    order = np.lexsort((w[:, 2], w[:, 1], w[:, 0]))
    s = w[order]
    same = (s[1:] == s[:-1]).all(axis=1)
    if same.any():
        k = np.flatnonzero(same)
        pairs = np.sort(np.stack([order[k], order[k + 1]], axis=1), axis=1)
        i, j = (int(x) for x in pairs[np.lexsort((pairs[:, 0], pairs[:, 1]))[0]])
        raise InvalidGeometryError(
            f"vertices {i} and {j} are both at {fmt_point(v[i])}: a point must be one vertex shared by its "
            "triangles (merge them with repair())"
        )


def _check_triangles(v: Floats, t: Ints) -> None:
    rep = (t[:, 0] == t[:, 1]) | (t[:, 1] == t[:, 2]) | (t[:, 2] == t[:, 0])
    if rep.any():
        f = int(np.flatnonzero(rep)[0])
        raise InvalidGeometryError(
            f"triangle {f} has zero area: it repeats a vertex ({[int(x) for x in t[f]]}, at "
            f"{', '.join(fmt_point(v[x]) for x in t[f])})"
        )
    flat = _flat_triangles(v, t)
    for f in np.flatnonzero(flat == UNKNOWN).tolist():
        a, b, c = (int(x) for x in t[f])
        flat[f] = int(all(o2(v, a, b, c, (k + 1) % 3, (k + 2) % 3) == 0 for k in range(3)))
    if (flat == 1).any():
        f = int(np.flatnonzero(flat == 1)[0])
        raise InvalidGeometryError(
            f"triangle {f} has zero area: its vertices {', '.join(fmt_point(v[x]) for x in t[f])} are "
            "collinear (drop it with repair())"
        )


def validate(vertices: Floats, triangles: Ints, *, pairs: bool = True) -> Topology:
    """Check exactly that the mesh bounds a solid (see the module docstring); return its topology.

    Parameters
    ----------
    vertices : ndarray, float64, shape (n, 3)
    triangles : ndarray, int64, shape (m, 3)
        Outward oriented (counter-clockwise seen from outside). Both as returned by :func:`as_arrays`.
    pairs : bool
        False skips the search for triangles that meet improperly (the costliest check), for a caller that
        has proven it otherwise: a mesh changed locally from a valid one, the changed triangles tested
        against their neighbours (``mrm.geometry.reconstruct.snapped_core``).

    Raises
    ------
    InvalidGeometryError
        With where the mesh is wrong (vertex, triangle, edge or pair of triangles).
    """
    v, t = vertices, triangles
    if t.shape[0] == 0:
        if v.shape[0]:
            raise InvalidGeometryError(f"{v.shape[0]} vertices but no triangle: a polyhedron needs a surface")
        return Topology(np.zeros(0, np.int64), np.zeros(0, np.int64), 0)
    _check_points(v, t)
    _check_triangles(v, t)
    twin = twin_half_edges(v, t)
    check_vertex_fans(v, t, twin)
    pair = first_intersecting_pair(v, t) if pairs else None
    if pair is not None:
        a, b = pair
        raise InvalidGeometryError(
            f"the surface intersects itself: triangles {a} {_corners(v, t, a)} and {b} {_corners(v, t, b)} "
            "meet beyond their common vertices and edges"
        )
    n_shells, shell = shells(t, twin)
    check_shells(v, t, shell, n_shells)
    return Topology(twin, shell, n_shells)


def _corners(v: Floats, t: Ints, f: int) -> str:
    return "[" + ", ".join(fmt_point(v[x]) for x in t[f]) + "]"


__all__ = ["MAX_TRIANGLES", "Topology", "as_arrays", "validate"]
