"""Repairing a triangle mesh into a polyhedron's boundary — only when the user asks (docs/design.md §6, §11).

:class:`~.polyhedron.Polyhedron` never changes its input: an invalid mesh is refused with where it is wrong.
:func:`repair` is the explicit next step, the one a "Repair" button or ``--repair`` runs, and it says what it
changed. It does the safe, exact things: merge vertices at exactly the same point, drop triangles that repeat
a vertex or are exactly flat, drop repeated triangles and unused vertices, and orient every shell
consistently and outward (trimesh's ``fix_winding`` and ``fix_normals``). It does not close holes or
resolve self-intersections: the result is validated again when it becomes a Polyhedron.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from mrm.core.errors import InvalidGeometryError
from mrm.geometry.polyhedra.manifold import check_vertex_fans, shells, twin_half_edges
from mrm.geometry.polyhedra.predicates import UNKNOWN, o2
from mrm.geometry.polyhedra.self_intersection import first_intersecting_pair
from mrm.geometry.polyhedra.shells import shell_windings, volume_signs
from mrm.geometry.polyhedra.validation import MAX_TRIANGLES, _flat_triangles, as_arrays

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]


def _plural(n: int, what: str) -> str:
    many = what[:-1] + "ices" if what.endswith("ex") else what + "s"
    return f"{n:,} {what if n == 1 else many}"


def repair(
    vertices: object, triangles: object, *, limit: int | None = MAX_TRIANGLES
) -> tuple[Floats, Ints, list[str]]:
    """A cleaned copy of a mesh and what was changed; the input is never modified.

    Parameters
    ----------
    vertices : array_like, shape (n, 3)
    triangles : array_like of int, shape (m, 3)
    limit : int or None
        Most triangles accepted.

    Returns
    -------
    vertices : ndarray, float64 (n', 3)
    triangles : ndarray, int64 (m', 3)
    changes : list of str
        One line per kind of change made (empty when nothing needed changing).

    Raises
    ------
    InvalidGeometryError
        For malformed arrays or non-finite coordinates (nothing sensible to repair).
    """
    import trimesh  # imported here: only a repair needs it

    v, t = as_arrays(vertices, triangles, limit)
    changes: list[str] = []
    if not np.isfinite(v).all():
        raise InvalidGeometryError(
            "vertices with NaN or infinite coordinates cannot be repaired; remove them"
        )
    # Exact merge: the same float64 values (0.0 and -0.0 alike), never a tolerance.
    # Kept in the order of first occurrence, so a mesh without duplicates keeps its numbering.
    _, first_of, inverse = np.unique(v + 0.0, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first_of, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    if first_of.size < v.shape[0]:
        changes.append(f"merged {_plural(v.shape[0] - first_of.size, 'duplicate vertex')}")
    t = rank[inverse.reshape(-1)][t].astype(np.int64)
    v = np.ascontiguousarray(v[first_of[order]])
    rep = (t[:, 0] == t[:, 1]) | (t[:, 1] == t[:, 2]) | (t[:, 2] == t[:, 0])
    keep = ~rep
    flat = np.zeros(t.shape[0], bool)
    if keep.any():
        idx = np.flatnonzero(keep)
        f = _flat_triangles(v, t[idx])
        for i in np.flatnonzero(f == UNKNOWN).tolist():
            a, b, c = (int(x) for x in t[idx[i]])
            f[i] = int(all(o2(v, a, b, c, (k + 1) % 3, (k + 2) % 3) == 0 for k in range(3)))
        flat[idx] = f == 1
    dropped = int(rep.sum() + flat.sum())
    if dropped:
        changes.append(f"dropped {_plural(dropped, 'zero-area triangle')}")
    t = t[keep & ~flat]
    # Repeated triangles (the same three vertices, in any order).
    key = np.sort(t, axis=1)
    _, first = np.unique(key, axis=0, return_index=True)
    if first.size < t.shape[0]:
        changes.append(f"dropped {_plural(t.shape[0] - first.size, 'repeated triangle')}")
        t = t[np.sort(first)]
    used = np.zeros(v.shape[0], bool)
    used[t.reshape(-1)] = True
    if not used.all():
        changes.append(f"dropped {_plural(int((~used).sum()), 'unused vertex')}")
        remap = np.cumsum(used) - 1
        v = v[used]
        t = remap[t]
    if t.shape[0]:
        t = _orient(v, t, changes, trimesh)
    return np.ascontiguousarray(v, dtype=np.float64), np.ascontiguousarray(t, dtype=np.int64), changes


def _orient(v: Floats, t: Ints, changes: list[str], trimesh: Any) -> Ints:
    """Consistent winding per shell (trimesh), then each shell outward or, for a cavity, inward (exact)."""
    mesh = trimesh.Trimesh(vertices=v.copy(), faces=t.copy(), process=False, validate=False)
    trimesh.repair.fix_winding(mesh)
    if not np.array_equal(np.asarray(mesh.vertices), v):  # trimesh must never move a vertex
        raise AssertionError("trimesh changed vertex coordinates during repair")
    after = np.ascontiguousarray(mesh.faces, dtype=np.int64)
    try:
        twin = twin_half_edges(v, after)
        check_vertex_fans(v, after, twin)
        if first_intersecting_pair(v, after) is None:
            n, shell = shells(after, twin)
            signs = volume_signs(v, after, shell, n)
            # All shells outward first: the winding number at a shell is then its nesting depth, and the
            # shells at odd depths (cavities) are turned inward.
            neg = np.isin(shell, np.flatnonzero(signs < 0))
            after[neg] = after[neg][:, ::-1]
            _, _, depth = shell_windings(v, after, shell, n)
            odd = np.isin(shell, np.flatnonzero(depth % 2 == 1))
            after[odd] = after[odd][:, ::-1]
    except InvalidGeometryError:
        pass  # open, non-manifold or self-intersecting: left to the validation's message
    reversed_ = int((after != t).any(axis=1).sum())
    if reversed_:
        changes.append(
            f"reversed {_plural(reversed_, 'triangle')} to orient every shell outward (cavities inward)"
        )
    return after


__all__ = ["repair"]
