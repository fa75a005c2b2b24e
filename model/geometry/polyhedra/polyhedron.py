"""The Euclidean solid value of MR Modeler's 3-D side: an immutable, exactly validated polyhedron (§11).

A :class:`Polyhedron` is given by its boundary: float64 vertices (n, 3) and int64 triangles (m, 3),
counter-clockwise seen from outside. Construction validates exactly (:func:`.validation.validate`) and
refuses anything that does not bound a solid; a repair is applied only when asked (:func:`.repair.repair`).
The arrays are read-only, so a value cannot change after it has been checked.
"""

from __future__ import annotations

import math
from functools import cached_property
from typing import Any

import numpy as np
import numpy.typing as npt

from mrm.core.errors import InvalidGeometryError
from mrm.geometry.polyhedra.faces import face_labels, face_polygons, split_faces
from mrm.geometry.polyhedra.validation import MAX_TRIANGLES, Topology, as_arrays, validate

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]


def _read_only(a: npt.NDArray[Any]) -> npt.NDArray[Any]:
    a.setflags(write=False)
    return a


class Polyhedron:
    """A solid bounded by a closed, oriented, non-self-intersecting triangle mesh (one or more shells).

    Parameters
    ----------
    vertices : array_like, shape (n, 3)
        Finite coordinates, converted to float64; every vertex used by a triangle, no two equal.
    triangles : array_like of int, shape (m, 3)
        Vertex indices, counter-clockwise seen from outside (inner shells, the cavities' boundaries, face
        into the cavity). No triangle is flat.
    limit : int or None
        Most triangles accepted (default :data:`~.validation.MAX_TRIANGLES`); None for no limit.

    Raises
    ------
    InvalidGeometryError
        If the mesh does not bound a solid; the message says where (first offending vertex, triangle, edge
        or pair of triangles). Nothing is repaired silently: see :func:`mrm.geometry.polyhedra.repair`.

    Notes
    -----
    The empty polyhedron (no vertex, no triangle) is valid: it is R(∅). Two polyhedra are equal when they
    have the same vertices and the same oriented triangles, whatever their order and each triangle's
    starting vertex.
    """

    __slots__ = ("__dict__", "_topology", "_triangles", "_vertices")

    #: A solid of space (``mrm.core.grids.dimension_of`` reads it).
    ndim = 3

    def __init__(self, vertices: object, triangles: object, *, limit: int | None = MAX_TRIANGLES) -> None:
        v, t = as_arrays(vertices, triangles, limit)
        self._topology: Topology = validate(v, t)
        self._vertices: Floats = _read_only(v)
        self._triangles: Ints = _read_only(t)

    @classmethod
    def _trusted(cls, vertices: Floats, triangles: Ints, topology: Topology) -> Polyhedron:
        """A polyhedron from arrays already known valid with ``topology`` (an exact image of a valid one)."""
        p = cls.__new__(cls)
        p._vertices = _read_only(vertices)
        p._triangles = _read_only(triangles)
        p._topology = topology
        return p

    @classmethod
    def empty(cls) -> Polyhedron:
        """The empty solid (no vertex, no triangle)."""
        return cls(np.zeros((0, 3)), np.zeros((0, 3), np.int64))

    # ------------------------------------------------------------------------------------------ arrays
    @property
    def vertices(self) -> Floats:
        """The vertices, float64 (n, 3), read-only."""
        return self._vertices

    @property
    def triangles(self) -> Ints:
        """The triangles, int64 (m, 3) indices into :attr:`vertices`, outward, read-only."""
        return self._triangles

    @property
    def n_vertices(self) -> int:
        """Number of vertices (all of them used by triangles)."""
        return int(self._vertices.shape[0])

    @property
    def n_triangles(self) -> int:
        """Number of triangles."""
        return int(self._triangles.shape[0])

    @property
    def is_empty(self) -> bool:
        """True for the empty solid."""
        return self.n_triangles == 0

    # ------------------------------------------------------------------------------------------ measures
    @property
    def n_shells(self) -> int:
        """Number of shells (edge-connected closed surfaces: outer boundaries and cavities)."""
        return self._topology.n_shells

    @property
    def shell_of_triangle(self) -> Ints:
        """The shell (0 … n_shells − 1) of every triangle, read-only."""
        return _read_only(self._topology.shell.copy())

    @cached_property
    def _faces(self) -> tuple[int, Ints]:
        n, labels = face_labels(self._vertices, self._triangles, self._topology.twin)
        return n, _read_only(labels)

    @property
    def n_faces(self) -> int:
        """Number of faces: maximal sets of edge-adjacent, exactly coplanar triangles."""
        return self._faces[0]

    @property
    def face_of_triangle(self) -> Ints:
        """The face (0 … n_faces − 1, numbered by first triangle) of every triangle, read-only."""
        return self._faces[1]

    @cached_property
    def polygons(self) -> tuple[Ints, Ints]:
        """The surface as polygons, one per face where a polygon can hold it, as (ptr, indices).

        Polygon k is ``indices[ptr[k]:ptr[k + 1]]``, counter-clockwise seen from outside, starting at a vertex
        from which the fan of triangles (how mesh files' polygons are read back) covers the face exactly.
        A face with a hole, a corner met twice, a right turn, or no vertex between two corners (where the fan
        starts) is given as its triangles (``mrm.geometry.polyhedra.faces.face_polygons``). A vertex inside a
        face is in no polygon (a file of these polygons leaves it out). Read-only.
        """
        ptr, idx = self.polygons_within(None)
        return _read_only(ptr), _read_only(idx)

    def polygons_within(self, groups: Ints | None) -> tuple[Ints, Ints]:
        """:attr:`polygons` with each face also cut where ``groups`` (one value per triangle) changes.

        A label mesh cuts its faces where the region on their other side changes, so that a face between
        two regions is the same polygon in both (``LabelMeshes.polygons``).
        """
        n, labels = self._faces
        if groups is not None:
            n, labels = split_faces(labels, self._topology.twin, groups)
        return face_polygons(self._vertices, self._triangles, self._topology.twin, labels, n)

    @property
    def bbox(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """((xmin, ymin, zmin), (xmax, ymax, zmax)); raises ValueError when empty."""
        if self.is_empty:
            raise ValueError("the empty polyhedron has no bounding box")
        lo = self._vertices.min(axis=0)
        hi = self._vertices.max(axis=0)
        return (
            (float(lo[0]), float(lo[1]), float(lo[2])),
            (float(hi[0]), float(hi[1]), float(hi[2])),
        )

    @cached_property
    def signed_volume(self) -> float:
        """The enclosed volume (positive for a valid solid), correctly rounded from the exact float64 data.

        Σ det[a, b, c] / 6 over the triangles: each determinant is rounded once, then summed with
        ``math.fsum``; close to the exact value, whose sign validation has already checked.
        """
        if self.is_empty:
            return 0.0
        c = self._vertices[self._triangles]
        with np.errstate(over="ignore", invalid="ignore"):  # coordinates near 1e308: ±inf or nan, said so
            det = np.einsum("ij,ij->i", c[:, 0], np.cross(c[:, 1], c[:, 2]))
        return math.fsum(det.tolist()) / 6.0

    # ------------------------------------------------------------------------------------------ transforms
    def translate(self, offset: object) -> Polyhedron:
        """The same solid moved by ``offset`` (three numbers, integers or floats).

        When every moved coordinate is exact (always for integer offsets within float64's integer range on
        coordinates with few bits) the result is valid by construction; otherwise the rounded copy is
        validated again and may be refused (rounding can make nearby sheets touch).

        Raises
        ------
        InvalidGeometryError
            For a non-finite offset, or a rounded result that is no longer a valid polyhedron.
        """
        d = np.array(offset, dtype=np.float64).reshape(-1)
        if d.shape != (3,) or not np.isfinite(d).all():
            raise InvalidGeometryError(f"a translation is three finite numbers, got {offset!r}")
        if self.is_empty:
            return self
        w = self._vertices + d
        # Two-sum's error term: zero everywhere means w = vertices + d exactly.
        bv = w - self._vertices
        err = (self._vertices - (w - bv)) + (d - bv)
        if np.isfinite(w).all() and not err.any():
            return Polyhedron._trusted(w, self._triangles.copy(), self._topology)
        return Polyhedron(w, self._triangles)

    def affine(self, linear: object, offset: object = (0.0, 0.0, 0.0)) -> Polyhedron:
        """The solid mapped by v ↦ linear · v + offset (a move, a scaling, a rotation or any invertible map).

        The image of a valid solid under an invertible affine map is a valid solid; its vertices are rounded
        to float64, so the result is validated again and may be refused (rounding can make nearby sheets
        touch). A map that reverses orientation (negative determinant) has its triangles turned back, so
        that they face outwards.

        Parameters
        ----------
        linear : 3 × 3 numbers
        offset : three numbers

        Raises
        ------
        InvalidGeometryError
            For non-finite or singular maps, or a rounded result that is no longer a valid polyhedron.
        """
        m = np.array(linear, dtype=np.float64)
        d = np.array(offset, dtype=np.float64).reshape(-1)
        if m.shape != (3, 3) or d.shape != (3,) or not (np.isfinite(m).all() and np.isfinite(d).all()):
            raise InvalidGeometryError("an affine map is a 3 × 3 matrix and three numbers, all finite")
        det = float(np.linalg.det(m))
        if not math.isfinite(det) or det == 0.0:
            # a nearly flat map passes here: the result's validation below decides whether it is a solid
            raise InvalidGeometryError("the map flattens the solid (its determinant is 0)")
        if self.is_empty:
            return self
        with np.errstate(over="ignore", invalid="ignore"):
            w = self._vertices @ m.T + d
        if not np.isfinite(w).all():
            raise InvalidGeometryError("the mapped vertices overflow float64")
        t = self._triangles if det > 0 else self._triangles[:, ::-1]
        return Polyhedron(w, np.ascontiguousarray(t))

    # ------------------------------------------------------------------------------------------ equality
    @cached_property
    def _canonical(self) -> tuple[bytes, bytes]:
        v, t = self._vertices, self._triangles
        order = np.lexsort((v[:, 2], v[:, 1], v[:, 0]))
        rank = np.empty_like(order)
        rank[order] = np.arange(order.size)
        tt = rank[t]
        # Rotate each triangle so its least vertex comes first (keeps the orientation), then sort them.
        k = np.argmin(tt, axis=1)
        rows = np.arange(tt.shape[0])
        tt = np.stack([tt[rows, k], tt[rows, (k + 1) % 3], tt[rows, (k + 2) % 3]], axis=1)
        tt = tt[np.lexsort((tt[:, 2], tt[:, 1], tt[:, 0]))]
        return (v[order] + 0.0).tobytes(), tt.astype(np.int64).tobytes()

    def canonical_bytes(self) -> tuple[bytes, bytes]:
        """The vertices and triangles in a canonical order, as bytes: equal for equal solids."""
        return self._canonical

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Polyhedron):
            return NotImplemented
        return self._canonical == other._canonical

    def __hash__(self) -> int:
        return hash(self._canonical)

    def __repr__(self) -> str:
        return (
            f"Polyhedron({self.n_vertices} vertices, {self.n_triangles} triangles, {self.n_shells} shell"
            f"{'s' if self.n_shells != 1 else ''})"
        )

    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:
        return (_rebuild, (np.array(self._vertices), np.array(self._triangles)))


def _rebuild(vertices: Floats, triangles: Ints) -> Polyhedron:
    """Unpickling: validated again (a pickle is input like any other)."""
    return Polyhedron(vertices, triangles, limit=None)


__all__ = ["Polyhedron"]
