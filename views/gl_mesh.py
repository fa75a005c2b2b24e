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


def surfel_mesh(
    voxels: npt.ArrayLike,
    directions: npt.ArrayLike,
    scale: float = 1.0,
    offset: npt.ArrayLike = (0.0, 0.0, 0.0),
) -> tuple[Floats, Ints]:
    """The two triangles of each surfel.

    Parameters
    ----------
    voxels : int array (n, 3)
        The (x, y, z) voxel of A each surfel belongs to.
    directions : int array (n,)
        The index in :data:`~mrm.geometry.topology.surfels.DIRS` of each surfel's outward normal.
    scale, offset :
        Voxel v is the cube of side ``scale`` centred on ``offset + scale * v`` (a coarser level's blocks,
        :mod:`mrm.geometry.topology.level_of_detail`); by default the unit voxels themselves.

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
    centre = np.asarray(offset, np.float64) + scale * (v + DIRS[d] / 2.0)
    corners = centre[:, None, :] + scale * (
        _CORNERS[None, :, 0, None] * _U[d][:, None, :] + _CORNERS[None, :, 1, None] * _W[d][:, None, :]
    )
    triangles = (np.arange(n, dtype=np.int32)[:, None, None] * 4 + _QUAD[None]).reshape(-1, 3)
    return corners.reshape(-1, 3).astype(np.float32), triangles


def surfel_arrays(
    voxels: npt.ArrayLike,
    directions: npt.ArrayLike,
    colours: npt.ArrayLike,
    scale: float = 1.0,
    offset: npt.ArrayLike = (0.0, 0.0, 0.0),
) -> dict[str, npt.NDArray[np.generic]]:
    """The arrays an OpenGL mesh item draws surfels from, ready to upload (made on a worker).

    pyqtgraph's ``GLMeshItem`` with ``smooth=False`` builds per-face copies of vertices, normals and colours
    when it first paints, on the GUI thread; these are the arrays it would end with, built here instead. The
    four corners of a surfel are not shared with other surfels, so per-vertex normals and colours are the
    surfel's own and the mesh draws flat.

    Parameters
    ----------
    voxels, directions, scale, offset :
        As :func:`surfel_mesh`.
    colours : uint8 (n, 4)
        The RGBA colour of each surfel.

    Returns
    -------
    dict
        ``vertices`` float32 (4n, 3), ``normals`` float32 (4n, 3), ``colours`` uint8 (4n, 4) and ``faces``
        uint32 (2n, 3), with ``box`` the box of the vertices (None when there are none).
    """
    vertices, triangles = surfel_mesh(voxels, directions, scale, offset)
    d = np.asarray(directions, dtype=np.intp).reshape(-1)
    normals = np.repeat(DIRS[d].astype(np.float32), 4, axis=0)
    rgba8 = np.repeat(np.asarray(colours, np.uint8).reshape(-1, 4), 4, axis=0)
    return with_box(
        {"vertices": vertices, "normals": normals, "colours": rgba8, "faces": triangles.astype(np.uint32)}
    )


def triangle_arrays(
    vertices: npt.ArrayLike, triangles: npt.ArrayLike, colours: npt.ArrayLike
) -> dict[str, npt.NDArray[np.generic]]:
    """Flat-shaded arrays of a triangle mesh (each triangle its own three vertices, its normal and colour).

    ``colours`` is uint8 (m, 4), one RGBA per triangle; the result is as :func:`surfel_arrays`'.
    """
    v = np.asarray(vertices, np.float64).reshape(-1, 3)
    t = np.asarray(triangles, np.int64).reshape(-1, 3)
    corners = v[t]  # (m, 3, 3)
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    length = np.linalg.norm(normal, axis=1, keepdims=True)
    normal = np.divide(normal, length, out=np.zeros_like(normal), where=length > 0)
    return with_box(
        {
            "vertices": corners.reshape(-1, 3).astype(np.float32),
            "normals": np.repeat(normal.astype(np.float32), 3, axis=0),
            "colours": np.repeat(np.asarray(colours, np.uint8).reshape(-1, 4), 3, axis=0),
            "faces": np.arange(3 * len(t), dtype=np.uint32).reshape(-1, 3),
        }
    )


def with_box(data: dict[str, npt.NDArray[np.generic]]) -> dict[str, npt.NDArray[np.generic]]:
    """``data`` with ``box``, the (lo, hi) corners of its ``vertices`` (None when empty)."""
    v = data["vertices"]
    data["box"] = (tuple(map(float, v.min(axis=0))), tuple(map(float, v.max(axis=0)))) if v.size else None  # type: ignore[assignment]
    return data


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


def rgba8(colour: str) -> npt.NDArray[np.uint8]:
    """``#rrggbb`` as an opaque uint8 RGBA row."""
    return np.array([round(c * 255) for c in rgba(colour)], np.uint8)


def palette_rgba8(index: npt.ArrayLike, palette: tuple[str, ...]) -> npt.NDArray[np.uint8]:
    """One uint8 RGBA row per index (``index mod len(palette)``)."""
    table = np.array([rgba8(c) for c in palette], dtype=np.uint8)
    return table[np.asarray(index, dtype=np.int64).reshape(-1) % len(palette)]


def colours_by_block(
    fine_blocks: npt.ArrayLike,
    fine_directions: npt.ArrayLike,
    fine_colours: npt.ArrayLike,
    blocks: npt.ArrayLike,
    directions: npt.ArrayLike,
    shape: tuple[int, ...],
) -> npt.NDArray[np.uint8]:
    """Colours of a coarser level's surfels taken from the fine surfels they stand for.

    A coarse surfel (block B, direction d) takes the colour of a fine surfel facing d whose voxel lies in
    block B (the last in sort order); one with none (the pooled surface moved outward by a block) is grey.

    Parameters
    ----------
    fine_blocks : int (m, 3)
        The (I, J, K) block of each fine surfel's voxel.
    fine_directions, fine_colours :
        Its direction and uint8 RGBA colour.
    blocks, directions :
        The coarse surfels (:func:`mrm.geometry.topology.level_of_detail.boundary_surfels`).
    shape :
        The pooled mask's (nz, ny, nx).
    """
    _nz, ny, nx = (int(v) for v in shape)

    def key(b: npt.ArrayLike, d: npt.ArrayLike) -> npt.NDArray[np.int64]:
        v = np.asarray(b, np.int64).reshape(-1, 3)
        return ((v[:, 2] * ny + v[:, 1]) * nx + v[:, 0]) * 6 + np.asarray(d, np.int64).reshape(-1)

    fine = key(fine_blocks, fine_directions)
    colours = np.asarray(fine_colours, np.uint8).reshape(-1, 4)
    order = np.argsort(fine, kind="stable")
    fine = fine[order]
    want = key(blocks, directions)
    out = np.tile(rgba8("#9a9a9a"), (want.size, 1))
    if fine.size:
        at = np.clip(np.searchsorted(fine, want, side="right") - 1, 0, fine.size - 1)
        hit = fine[at] == want
        out[hit] = colours[order[at[hit]]]
    return out


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
    # unique pairs as one int64 key each: numpy sorts integers without the GIL, rows (axis=0) with it
    from mrm.geometry.topology.colouring import greedy_colouring

    keep = a != b
    return greedy_colouring(n_seg, np.stack([a[keep], b[keep]], axis=1), len(SEGMENT_COLOURS_3D))


def difference_arrays(
    light: object, dark: object, light_rgb: tuple[int, int, int], dark_rgb: tuple[int, int, int]
) -> dict[str, npt.NDArray[np.generic]]:
    """The surfels of the voxels only in a result (``light``) and only in the direct result (``dark``).

    ``light`` and ``dark`` are voxel sets (the paper's light and dark grey of Fig. 12, in 3D).
    """
    parts = []
    for vs, rgb in ((light, light_rgb), (dark, dark_rgb)):
        if not vs.is_empty():  # type: ignore[attr-defined]
            from mrm.geometry.topology.level_of_detail import boundary_surfels

            v, d = boundary_surfels(vs.mask)  # type: ignore[attr-defined]
            v = v + np.asarray(vs.origin, np.int64)  # type: ignore[attr-defined]  # array indices → voxels
            parts.append((v, d, np.tile(np.array([*rgb, 255], np.uint8), (len(d), 1))))
    if not parts:
        return surfel_arrays(np.zeros((0, 3)), np.zeros(0, np.uint8), np.zeros((0, 4), np.uint8))
    v = np.concatenate([p[0] for p in parts])
    d = np.concatenate([p[1] for p in parts])
    c = np.concatenate([p[2] for p in parts])
    return surfel_arrays(v, d, c)


#: Plane segments whose normals are drawn at most (the biggest first): a view crowded with lines shows
#: nothing.
MAX_NORMALS = 300


def segment_normals(segmentation: object, count: int = MAX_NORMALS) -> Floats:
    """A line along a normal of each of the ``count`` biggest digital plane segments.

    The normal drawn is the mean of the unit extreme rays of the segment's preimage (the cone of the normals
    that separate its voxels from those outside,
    :class:`~mrm.geometry.planes.segmentation.PlaneSegmentation`): a convex combination of them, so a
    normal of the preimage, and the axis itself for a one-surfel segment.
    It is read from the segmentation's integer rays in numpy: the chosen plane of each segment (exact
    rational arithmetic, about 1 ms each in Python) would hold the GIL the window paints with.

    Each line starts at the centre of its segment's surfels (the mean of their centres: the voxel plus half
    the outward direction) and runs outward for ``0.3·√(surfels)`` voxels, at least 1 and at most 6.

    Parameters
    ----------
    segmentation : mrm.geometry.planes.segmentation.PlaneSegmentation
        The segments of a voxel set's surfaces.
    count : int
        The number of segments drawn (the biggest ones).

    Returns
    -------
    float32 (2k, 3)
        The two ends of each line, for a ``GLLinePlotItem`` in ``lines`` mode.
    """
    ptr = np.asarray(segmentation.member_ptr, np.int64)  # type: ignore[attr-defined]
    sizes = np.diff(ptr)
    if sizes.size == 0 or count <= 0:
        return np.zeros((0, 3), np.float32)
    n_seg = sizes.size
    seg_of = np.asarray(segmentation.segment_of, np.int64)  # type: ignore[attr-defined]
    direction = np.asarray(segmentation.direction, np.intp)  # type: ignore[attr-defined]
    centres = np.asarray(segmentation.voxel, np.float64) + DIRS[direction] / 2.0  # type: ignore[attr-defined]
    start = np.stack([np.bincount(seg_of, centres[:, i], n_seg) for i in range(3)], axis=1)
    start /= np.maximum(sizes, 1)[:, None]
    # a one-surfel segment (no rays): its own direction; otherwise the mean of its unit extreme rays
    members = np.asarray(segmentation.members, np.int64)  # type: ignore[attr-defined]
    normal = DIRS[direction[members[ptr[:-1]]]].astype(np.float64)
    rays = np.asarray(segmentation.rays, np.float64).reshape(-1, 3)  # type: ignore[attr-defined]
    ray_ptr = np.asarray(segmentation.ray_ptr, np.int64)  # type: ignore[attr-defined]
    counts = np.diff(ray_ptr)
    if rays.size:
        unit = rays / np.linalg.norm(rays, axis=1)[:, None]
        owner = np.repeat(np.arange(n_seg), counts)
        summed = np.stack([np.bincount(owner, unit[:, i], n_seg) for i in range(3)], axis=1)
        normal = np.where((counts > 0)[:, None], summed, normal)
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    biggest = np.argsort(-sizes, kind="stable")[:count]
    length = np.clip(0.3 * np.sqrt(sizes[biggest].astype(np.float64)), 1.0, 6.0)
    ends = np.empty((biggest.size, 2, 3), np.float64)
    ends[:, 0] = start[biggest]
    ends[:, 1] = start[biggest] + length[:, None] * normal[biggest]
    return ends.reshape(-1, 3).astype(np.float32)


def cut_away(
    voxels: npt.ArrayLike,
    directions: npt.ArrayLike,
    colours: npt.ArrayLike,
    labels: npt.ArrayLike,
    origin: tuple[int, int, int],
    top: int,
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.uint8], npt.NDArray[np.uint8]]:
    """The surfels of a voxel set cut by the plane above layer z = ``top``, and the cut's faces.

    What is drawn is the part z ≤ ``top``: the surfels of voxels above it go, and each voxel of the top layer
    whose upper neighbour was in the set gets the face it now shows upward, in its component's colour,
    darkened. The cavities the plane crosses open: their walls below it (red in the region view) show.

    Parameters
    ----------
    voxels, directions, colours :
        The surfels (voxel (n, 3) in the coordinates of ``labels``' voxels, direction index, RGBA uint8).
    labels, origin :
        The voxel set's components: ``labels[k, j, i]`` is the component label (1…n, 0 outside the set) of
        voxel origin + (i, j, k).
    top : int
        The highest layer kept.

    Returns
    -------
    voxels, directions, colours
        The surfels drawn.
    """
    v = np.asarray(voxels, np.int64).reshape(-1, 3)
    keep = v[:, 2] <= top
    lab_volume = np.asarray(labels)
    m = lab_volume > 0
    k = top - origin[2]
    up = int(np.flatnonzero((DIRS == (0, 0, 1)).all(axis=1))[0])  # the +z direction's index
    if 0 <= k < m.shape[0] - 1:
        jj, ii = np.nonzero(m[k] & m[k + 1])
        cap = np.stack([ii + origin[0], jj + origin[1], np.full(ii.size, top)], axis=1).astype(np.int64)
        lab = lab_volume[k, jj, ii].astype(np.int64)
        cap_colours = palette_rgba8(lab - 1, COMPONENT_COLOURS_3D)
        cap_colours[:, :3] = (cap_colours[:, :3] * 0.75).astype(np.uint8)  # a cut face reads darker
    else:
        cap = np.zeros((0, 3), np.int64)
        cap_colours = np.zeros((0, 4), np.uint8)
    return (
        np.concatenate([v[keep], cap]),
        np.concatenate([np.asarray(directions, np.uint8).reshape(-1)[keep], np.full(len(cap), up, np.uint8)]),
        np.concatenate([np.asarray(colours, np.uint8).reshape(-1, 4)[keep], cap_colours]),
    )
