"""Triangle meshes for the 3D views, made from the model's representations (numpy only, no Qt, no OpenGL).

A voxel (x, y, z) is the unit cube centred on (x, y, z) (docs/design.md §11), so a surfel — the face of a
voxel of A towards a voxel outside A — is the unit square at the voxel centre plus half its outward normal.
Each surfel becomes two triangles wound counter-clockwise seen from outside, so that the views' lighting
shades the outside. Vertices are not shared between surfels: every triangle keeps the flat colour of its
surfel, segment or face, which is what the views show.

These functions run on a worker for big objects (:meth:`View3D.prepared`); they touch each surfel a constant
number of times, in numpy.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mrm.geometry.topology.surfels import DIRS
from mrm.views.palette import COMPONENT_COLOURS

Floats = npt.NDArray[np.float32]
Ints = npt.NDArray[np.int32]

# For the normal of each surfel direction, two unit vectors u, w with u × w = the normal: the square's
# corners c + (∓u ∓ w)/2 taken in the order below run counter-clockwise seen from outside.
_U = np.array([[0, 1, 0], [0, 0, 1], [0, 0, 1], [1, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float64)
_W = np.array([[0, 0, 1], [0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 1, 0], [1, 0, 0]], dtype=np.float64)
_CORNERS = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], dtype=np.float64) / 2
_QUAD = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int32)

assert np.array_equal(np.cross(_U, _W), DIRS), "each (u, w) must turn counter-clockwise about its normal"


def surfel_mesh(voxels: npt.ArrayLike, directions: npt.ArrayLike) -> tuple[Floats, Ints]:
    """The two triangles of each surfel.

    Parameters
    ----------
    voxels : int array (n, 3)
        The (x, y, z) voxel of A each surfel belongs to.
    directions : int array (n,)
        The index in :data:`~mrm.geometry.topology.surfels.DIRS` of each surfel's outward normal.

    Returns
    -------
    vertices : float32 (4n, 3)
        The four corners of surfel i are rows 4i … 4i + 3.
    triangles : int32 (2n, 3)
        Triangles 2i and 2i + 1 cover surfel i, counter-clockwise seen from outside.
    """
    v = np.asarray(voxels, dtype=np.float64).reshape(-1, 3)
    d = np.asarray(directions, dtype=np.intp).reshape(-1)
    n = d.size
    centre = v + DIRS[d] / 2.0
    corners = (
        centre[:, None, :]
        + _CORNERS[None, :, 0, None] * _U[d][:, None, :]
        + _CORNERS[None, :, 1, None] * _W[d][:, None, :]
    )
    triangles = (np.arange(n, dtype=np.int32)[:, None, None] * 4 + _QUAD[None]).reshape(-1, 3)
    return corners.reshape(-1, 3).astype(np.float32), triangles


def face_edges(vertices: npt.ArrayLike, triangles: npt.ArrayLike, face_of_triangle: npt.ArrayLike) -> Floats:
    """The edges between two different faces of a triangulated polyhedron, as line-segment end points.

    An edge of a triangle is drawn when the triangles on its two sides belong to different faces (or when it
    has one side only): the polygon outlines of the faces, without the diagonals of their triangulation.

    Returns
    -------
    float32 (2m, 3)
        Rows 2k and 2k + 1 are the ends of edge k.
    """
    verts = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    tri = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    face = np.asarray(face_of_triangle, dtype=np.int64).reshape(-1)
    if tri.size == 0:
        return np.zeros((0, 3), np.float32)
    edges = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    faces = np.concatenate([face, face, face])
    edges.sort(axis=1)
    order = np.lexsort((faces, edges[:, 1], edges[:, 0]))
    edges, faces = edges[order], faces[order]
    same_edge_as_next = np.all(edges[1:] == edges[:-1], axis=1)
    # One row per edge: a run's first, kept when its sides lie on two faces (or it has one side).
    start = np.ones(len(edges), bool)
    start[1:] = ~same_edge_as_next
    run = np.cumsum(start) - 1
    n_runs = int(run[-1]) + 1
    fmin = np.full(n_runs, np.iinfo(np.int64).max)
    fmax = np.full(n_runs, np.iinfo(np.int64).min)
    np.minimum.at(fmin, run, faces)
    np.maximum.at(fmax, run, faces)
    count = np.bincount(run, minlength=n_runs)
    keep = (fmin != fmax) | (count == 1)
    first = edges[start][keep]
    return verts[first.reshape(-1)].astype(np.float32)


#: The region view's component colours, as the plane region view's (:data:`COMPONENT_COLOURS`), without the
#: red that marks cavity surfaces here.
CAVITY_COLOUR = "#e15759"
COMPONENT_COLOURS_3D = tuple(c for c in COMPONENT_COLOURS if c != CAVITY_COLOUR)

#: The analytical view's plane segment colours: the same palette and two more, so neighbours rarely share one.
SEGMENT_COLOURS_3D = (*COMPONENT_COLOURS, "#86bcb6", "#d37295")


def rgba(colour: str, alpha: float = 1.0) -> tuple[float, float, float, float]:
    """``#rrggbb`` as float RGBA in [0, 1]."""
    c = colour.lstrip("#")
    return (int(c[0:2], 16) / 255, int(c[2:4], 16) / 255, int(c[4:6], 16) / 255, float(alpha))


def palette_colours(index: npt.ArrayLike, palette: tuple[str, ...], repeat: int = 2) -> Floats:
    """RGBA rows for each index (``index mod len(palette)``), each repeated ``repeat`` times (triangles)."""
    table = np.array([rgba(c) for c in palette], dtype=np.float32)
    idx = np.asarray(index, dtype=np.int64).reshape(-1) % len(palette)
    return np.repeat(table[idx], repeat, axis=0)


def segment_colour_indices(
    segment_of: npt.ArrayLike, neighbours: npt.ArrayLike | None = None
) -> npt.NDArray[np.int64]:
    """A palette index per segment such that segments sharing a surfel edge differ where the palette allows.

    Greedy colouring in segment order: each segment takes the first colour none of its already-coloured
    neighbours has (a planar-like adjacency rarely needs more than the 12 colours).
    """
    seg = np.asarray(segment_of, dtype=np.int64).reshape(-1)
    n_seg = int(seg.max()) + 1 if seg.size else 0
    if neighbours is None or n_seg == 0:
        return np.arange(n_seg, dtype=np.int64)
    nb = np.asarray(neighbours, dtype=np.int64).reshape(seg.size, -1)
    a = np.repeat(seg, nb.shape[1])
    b = seg[nb.reshape(-1)]
    pairs = np.unique(np.stack([a, b], axis=1)[a != b], axis=0)
    start = np.searchsorted(pairs[:, 0], np.arange(n_seg + 1))
    colours = np.full(n_seg, -1, np.int64)
    k = len(SEGMENT_COLOURS_3D)
    for s in range(n_seg):
        used = colours[pairs[start[s] : start[s + 1], 1]]
        free = np.setdiff1d(np.arange(k), used[used >= 0], assume_unique=False)
        colours[s] = int(free[0]) if free.size else s % k
    return colours
