"""The exact discretization D of Euclidean geometry into voxels, in three models (docs/design.md §11).

The 3D counterpart of :func:`mrm.geometry.discretize.discretize`: a kernel K(p) ⊂ V(p) is fixed for each
voxel p ∈ Z³ and D(E) = { p : E ∩ K(p) ≠ ∅ }, τ = (ε, ε², ε³), ε → 0⁺.

============== ================================================= ============================================
model          K(p)                                              reads
============== ================================================= ============================================
``standard``   the open unit cube int V(p), shifted by τ         Andres' standard model; a point goes to the
                                                                 voxel whose cell (p − ½, p + ½]³ holds it
``supercover`` the closed unit cube V(p)                         every voxel the closed set touches
``gauss``      the single point p + τ                            voxel-centre sampling with a tie rule
============== ================================================= ============================================

How each is computed (the kernels are in :mod:`._kernels3d`):

* gauss of a solid: { p : p + τ ∈ P }, a parity scanline along +x with exact crossings;
* standard / supercover of a solid: gauss(P) ∪ D(∂P), D of the triangles by an exact separating-axis test
  (if K(p) meets P but no triangle, the connected K(p) lies inside P and so does p + τ);
* triangles, segments and points (no interior): D of each, by the same test (segments and points are
  degenerate triangles). Under ``gauss`` they discretize to nothing: no p + τ lies on a plane for all small ε.

The image of a polyhedron under a rational affine map (DSS_α with α = 1/5, a quarter turn), whose vertices
are not float64, is voxelized exactly by :func:`mrm.geometry.discretize.voxel_images.voxelize_image`.

Every decision is exact for float64 input: a float filter decides the easy cases, floating-point expansions
the rest, or plain float arithmetic when it is provably exact for the whole input (snapped coordinates).
Nothing uses an epsilon.

Input rules (InvalidGeometryError otherwise): vertices an (n, 3) array of finite floats with |v| ≤ 2^51 and
v = 0 or |v| ≥ 2^-250 (the exact 3×3 determinants must neither overflow nor underflow); triangles an (m, 3)
integer array of vertex indices. A solid must be a valid closed polyhedron (closed 2-manifold, outward,
without self-intersection; several shells and cavities allowed): its validity is decided by the polyhedra
module, not here; on an invalid mesh the parity rule still gives a well-defined but meaningless set.
Results are plain ``(mask, origin)`` pairs: a bool array mask[k, j, i] for voxel (x0 + i, y0 + j, z0 + k),
cropped to the bounding box (empty: shape (0, 0, 0), origin (0, 0, 0)).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.grids import VoxelSet
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, DEFAULT_VOXEL_LIMIT, check_pixels
from mrm.core.models import Model
from mrm.geometry._threads import share_out
from mrm.geometry.discretize import _kernels3d as _k3
from mrm.geometry.discretize.exact import EXACT_UNITS_3D, MAX_ABS_COORD, float_predicates_are_exact

__all__ = [
    "MAX_GRID_STEP",
    "MIN_ABS_COORD_3D",
    "estimate_voxels",
    "voxelization_box",
    "voxelize",
    "voxelize_points",
    "voxelize_segments",
    "voxelize_solid",
    "voxelize_triangles",
]

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]
Mask = npt.NDArray[np.bool_]
Origin = tuple[int, int, int]
Box3 = tuple[int, int, int, int, int, int]

#: Smallest supported non-zero |coordinate| in 3D: products of three differences must stay above the
#: subnormal range (see :mod:`._kernels3d`).
MIN_ABS_COORD_3D = 2.0**-250

#: Largest grid step of :func:`voxelize_solid`: with |coordinates| ≤ 2^51 the grid numbers the kernels use
#: (step·p and step·p ± step/2 within two voxels of the data) stay below 2^52, exact half-integers.
MAX_GRID_STEP = 2**49

#: Triangles per chunk of the covers' marking, which the geometry's threads share (mrm.geometry._threads):
#: about 8 ms of work on the snapped core of a 256³ ball, so a big mesh splits and a small one does not.
MARK_CHUNK = 2048


# --------------------------------------------------------------------------------------- public API
def voxelize(solid: object, model: str = "standard", *, limit: int | None = DEFAULT_VOXEL_LIMIT) -> VoxelSet:
    """D(P) of a polyhedron as a :class:`~mrm.core.grids.VoxelSet`: the typed entry point of 3D D.

    Parameters
    ----------
    solid : Polyhedron
        A validated solid (:class:`mrm.geometry.polyhedra.Polyhedron`; validity is what makes the parity
        rule mean "inside").
    model : {"standard", "supercover", "gauss"}
        The kernel (docs/design.md §11).
    limit : int or None
        Largest bounding box of the result, in voxels (default
        :data:`~mrm.core.limits.DEFAULT_VOXEL_LIMIT`); None for none. Checked before any array is made.

    Returns
    -------
    VoxelSet

    Examples
    --------
    >>> import mrm, numpy as np
    >>> v = np.array([[2, 0, 0], [-2, 0, 0], [0, 2, 0], [0, -2, 0], [0, 0, 2], [0, 0, -2]], dtype=float)
    >>> t = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
    >>> # the 7 centres with |x| + |y| + |z| ≤ 1, and the 5 of the 18 boundary centres that τ moves inside
    >>> len(mrm.voxelize(mrm.Polyhedron(v, t), "gauss"))
    12
    """
    from mrm.geometry.polyhedra import Polyhedron  # the value's module builds on the predicates here

    if not isinstance(solid, Polyhedron):
        raise InvalidGeometryError(f"voxelize takes a Polyhedron, got {type(solid).__name__}")
    mask, origin = voxelize_solid(solid.vertices, solid.triangles, model, limit=limit)
    return VoxelSet.taking_over(mask, origin)


def voxelize_solid(
    vertices: npt.ArrayLike,
    triangles: npt.ArrayLike,
    model: str = "standard",
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    step: int = 1,
) -> tuple[Mask, Origin]:
    """Return the exact discretization D(P) of the closed solid P bounded by a triangle mesh.

    Parameters
    ----------
    vertices : array_like, shape (n, 3)
        float64 vertex coordinates (x, y, z).
    triangles : array_like, shape (m, 3)
        Vertex indices of the boundary triangles, outward (counter-clockwise seen from outside). Several
        shells and cavities (inner shells, oriented inward) are allowed; the mesh must be a valid
        polyhedron.
    model : {"standard", "supercover", "gauss"}
        The kernel: shifted open cube, closed cube, or shifted centre.
    limit : int or None
        Largest bounding-box size (in voxels) allowed for the result; None for no limit. Checked before any
        voxel array is allocated.
    step : int
        The grid step N, a positive integer up to :data:`MAX_GRID_STEP`: voxel p is the cube of side N
        centred on N·p, with kernel N·K(p). The result is D(P / N) exactly, computed without dividing P (whose
        vertices divided by an odd N would not be float64 numbers); 1 is the unit grid.

    Returns
    -------
    mask : ndarray of bool, shape (nz, ny, nx)
        mask[k, j, i] is True when voxel (x0 + i, y0 + j, z0 + k) is in D(P); cropped to the bounding box.
    origin : tuple of int
        (x0, y0, z0).

    Raises
    ------
    ParameterError
        Unknown model, bad limit or bad step.
    InvalidGeometryError
        Malformed arrays, a triangle index out of range, or a coordinate out of the supported range.
    SizeLimitError
        The result's bounding box would exceed ``limit`` voxels.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [0, 0, 2]], dtype=float)
    >>> t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    >>> mask, origin = voxelize_solid(v, t, "gauss")
    >>> int(mask.sum()), origin
    (4, (0, 0, 0))
    """
    return _run(vertices, triangles, Model.parse(model), True, limit, step=step)


def voxelize_triangles(
    vertices: npt.ArrayLike,
    triangles: npt.ArrayLike,
    model: str = "standard",
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> tuple[Mask, Origin]:
    """Return D(T) for the union T of closed triangles (a surface, no interior): ``(mask, origin)``.

    Same parameters as :func:`voxelize_solid`; the triangles need not form a closed surface and may be
    degenerate (a zero-area triangle is its segment or point). Under ``"gauss"`` the result is empty.
    """
    return _run(vertices, triangles, Model.parse(model), False, limit)


def voxelize_segments(
    starts: npt.ArrayLike,
    ends: npt.ArrayLike,
    model: str = "standard",
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> tuple[Mask, Origin]:
    """Return D(S) for the union S of the closed segments [starts[k], ends[k]]: ``(mask, origin)``.

    Parameters
    ----------
    starts, ends : array_like, shape (m, 3)
        End points of the segments (a segment with equal ends is a point).
    model, limit
        As in :func:`voxelize_solid`. Under ``"gauss"`` the result is empty.
    """
    a = _as_points(starts, "segment starts")
    b = _as_points(ends, "segment ends")
    if a.shape != b.shape:
        raise InvalidGeometryError(f"segment starts {a.shape} and ends {b.shape} must have the same shape")
    m = a.shape[0]
    tris = np.c_[np.arange(m), np.arange(m, 2 * m), np.arange(m, 2 * m)].astype(np.int64)
    return _run(np.concatenate([a, b]), tris, Model.parse(model), False, limit)


def voxelize_points(
    points: npt.ArrayLike, model: str = "standard", *, limit: int | None = DEFAULT_PIXEL_LIMIT
) -> tuple[Mask, Origin]:
    """Return D of a set of points: their cells (standard), every closed cube holding one (supercover).

    Parameters
    ----------
    points : array_like, shape (m, 3)
    model, limit
        As in :func:`voxelize_solid`. Under ``"gauss"`` the result is empty.
    """
    p = _as_points(points, "points")
    idx = np.arange(p.shape[0], dtype=np.int64)
    return _run(p, np.c_[idx, idx, idx], Model.parse(model), False, limit)


def voxelization_box(
    vertices: npt.ArrayLike, triangles: npt.ArrayLike, model: str = "standard"
) -> Box3 | None:
    """Return the voxel box (xmin, ymin, zmin, xmax, ymax, zmax) that holds D, or None without triangles.

    Tight for ``"standard"`` and ``"supercover"`` (the extreme vertices' cells are reached); for ``"gauss"``
    the voxels p whose p + τ lies in the vertices' extent (⌈min⌉ ≤ p ≤ ⌈max⌉ − 1), which hold the result
    (None when there are none).
    """
    _, t, used = _validate(vertices, triangles)
    return _box(used, t, Model.parse(model), 1)


def estimate_voxels(vertices: npt.ArrayLike, triangles: npt.ArrayLike, model: str = "supercover") -> int:
    """Return the number of voxels of :func:`voxelization_box` (an upper bound for any model by default)."""
    return _volume(voxelization_box(vertices, triangles, model))


# ------------------------------------------------------------------------------------------- checks
def _as_points(values: npt.ArrayLike, what: str) -> Floats:
    try:
        arr = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InvalidGeometryError(f"{what}: expected an (n, 3) array of numbers ({exc})") from None
    if arr.size == 0:
        return np.zeros((0, 3), dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise InvalidGeometryError(f"{what}: expected an (n, 3) array of coordinates, got shape {arr.shape}")
    return np.ascontiguousarray(arr)


def _used(v: Floats, t: Ints) -> Floats:
    """The vertices the triangles refer to, each once: their coordinates decide the box and the arithmetic.

    Usually all of them (a closed mesh): one bincount tells, instead of gathering three rows per triangle.
    """
    if t.shape[0] * 3 >= v.shape[0] and bool(np.bincount(t.reshape(-1), minlength=v.shape[0]).all()):
        return v
    return v[np.unique(t)]


def _validate(vertices: npt.ArrayLike, triangles: npt.ArrayLike) -> tuple[Floats, Ints, Floats]:
    """Check the arrays and the referenced vertices' coordinates: (vertices, triangles, :func:`_used`)."""
    v = _as_points(vertices, "vertices")
    try:
        t = np.asarray(triangles)
    except (TypeError, ValueError) as exc:  # pragma: no cover - numpy accepts nearly anything
        raise InvalidGeometryError(f"triangles: expected an (m, 3) integer array ({exc})") from None
    if t.size == 0:
        return v, np.zeros((0, 3), dtype=np.int64), v[:0]
    if t.ndim != 2 or t.shape[1] != 3 or not (np.issubdtype(t.dtype, np.integer)):
        raise InvalidGeometryError(
            f"triangles: expected an (m, 3) array of integer vertex indices, got shape {t.shape} of {t.dtype}"
        )
    t = np.ascontiguousarray(t, dtype=np.int64)
    lo, hi = int(t.min()), int(t.max())
    if lo < 0 or hi >= v.shape[0]:
        bad = int(np.flatnonzero(((t < 0) | (t >= v.shape[0])).any(axis=1))[0])
        raise InvalidGeometryError(
            f"triangle {bad} {t[bad].tolist()} refers to a vertex that does not exist "
            f"(there are {v.shape[0]} vertices)"
        )
    used = _used(v, t)
    a = np.abs(used)
    bad_mask = ~np.isfinite(used) | (a > MAX_ABS_COORD) | ((a < MIN_ABS_COORD_3D) & (a != 0.0))
    if bad_mask.any():
        row = int(np.flatnonzero(bad_mask.any(axis=1))[0])
        x, y, z = (float(u) for u in used[row])
        raise InvalidGeometryError(
            f"a vertex ({x!r}, {y!r}, {z!r}) has a coordinate outside the supported range: coordinates "
            "must be "
            f"finite, at most 2^51 ≈ {MAX_ABS_COORD:.3g} in absolute value, and 0 or at least 2^-250 "
            "(exact determinants must neither overflow nor underflow); repair, translate or rescale the mesh"
        )
    return v, t, used


# -------------------------------------------------------------------------------------------- boxes
def _volume(box: Box3 | None) -> int:
    if box is None:
        return 0
    x0, y0, z0, x1, y1, z1 = box
    return (x1 - x0 + 1) * (y1 - y0 + 1) * (z1 - z0 + 1)


def _ceil_step(u: Floats, step: int) -> Ints:
    """⌈u / step⌉ exactly: the float quotient is off by less than one, k·step is an exact integer float."""
    k = np.ceil(u / step)
    k = k + (k * step < u) - ((k - 1) * step >= u)
    return k.astype(np.int64)


def _cell_step(u: Floats, step: int) -> Ints:
    """The cell index k with u ∈ (k·step − step/2, k·step + step/2], exactly.

    An estimate off by at most one, corrected by exact comparisons (k·step ± step/2 are integers or
    half-integers below 2^52, exact floats).
    """
    half = 0.5 * step
    k = np.ceil((u - half) / step)
    k = k + (u > k * step + half) - (u <= k * step - half)
    return k.astype(np.int64)


def _box(used: Floats, t: Ints, model: Model, step: int) -> Box3 | None:
    """The voxel box of D on the grid of ``step``, from ``used``, the vertices that ``t`` refers to."""
    if t.shape[0] == 0:
        return None
    # column by column: numpy reduces an (n, 3) array along axis 0 several times slower
    lo = np.array([used[:, d].min() for d in range(3)])
    hi = np.array([used[:, d].max() for d in range(3)])
    # Voxel p spans step·p ± step/2 (an integer or a half-integer, exact); its cell on an axis is
    # (step·p − step/2, step·p + step/2]. The closed upper end adds one voxel when the maximum is on a grid
    # plane.
    if model is Model.GAUSS:
        # step·(p + τ) within the extent: lo ≤ step·p and step·p < hi on each axis, ⌈lo / step⌉ ≤ p ≤
        # ⌈hi / step⌉ − 1.
        c_lo = _ceil_step(lo, step)
        c_hi = _ceil_step(hi, step) - 1
        if (c_hi < c_lo).any():
            return None
    else:
        c_lo = _cell_step(lo, step)
        c_hi = _cell_step(hi, step)
    if model is Model.SUPERCOVER:
        c_hi = c_hi + (hi == c_hi * step + 0.5 * step)
    return (int(c_lo[0]), int(c_lo[1]), int(c_lo[2]), int(c_hi[0]), int(c_hi[1]), int(c_hi[2]))


# ---------------------------------------------------------------------------------------- computing
def _empty() -> tuple[Mask, Origin]:
    return np.zeros((0, 0, 0), dtype=bool), (0, 0, 0)


def _run(
    vertices: npt.ArrayLike,
    triangles: npt.ArrayLike,
    model: Model,
    solid: bool,
    limit: int | None,
    exact_mode: bool | None = None,
    step: int = 1,
) -> tuple[Mask, Origin]:
    """Validate, allocate the box and run the kernels on the grid of ``step``.

    ``exact_mode``: force/forbid plain float (tests).
    """
    if isinstance(step, bool) or not isinstance(step, int | np.integer) or not 1 <= step <= MAX_GRID_STEP:
        raise ParameterError(f"the grid step must be an integer from 1 to 2^49, got {step!r}")
    step = int(step)
    v, t, used = _validate(vertices, triangles)
    gauss = model is Model.GAUSS
    if gauss and not solid:
        return _empty()
    box = _box(used, t, model, step)
    if box is None:
        return _empty()
    check_pixels(_volume(box), limit, "voxelization")
    if exact_mode is None:
        exact_mode = float_predicates_are_exact(used.reshape(-1), EXACT_UNITS_3D, step=step)
    x0, y0, z0, x1, y1, z1 = box
    mask = np.zeros((z1 - z0 + 1, y1 - y0 + 1, x1 - x0 + 1), dtype=bool)
    vx = np.ascontiguousarray(v[:, 0])
    vy = np.ascontiguousarray(v[:, 1])
    vz = np.ascontiguousarray(v[:, 2])
    scratch = np.zeros(_k3.SCRATCH3_SIZE, dtype=np.float64)
    big = np.iinfo(np.int64).max
    ext = np.array([big, big, big, -big, -big, -big], dtype=np.int64)
    bad = 0
    if solid:
        bad += _k3.fill_parity(mask, x0, y0, z0, vx, vy, vz, t, exact_mode, scratch, ext, float(step))
    if not gauss:
        supercover = model is Model.SUPERCOVER

        def mark(i: int) -> int:
            # One chunk of triangles; the threads share the mask (each only sets voxels, the same way).
            part = t[i * MARK_CHUNK : (i + 1) * MARK_CHUNK]
            own = np.zeros(_k3.SCRATCH3_SIZE, dtype=np.float64)
            w = float(step)
            return int(_k3.mark_triangles(mask, x0, y0, z0, vx, vy, vz, part, supercover, exact_mode, own, w))

        bad += sum(share_out(mark, -(-t.shape[0] // MARK_CHUNK)))
    if bad:  # pragma: no cover - the boxes above are proven to hold every voxel
        raise RuntimeError(f"internal error: {bad} voxels fell outside the voxelization box {box}")
    if gauss:
        if ext[0] > ext[3]:
            return _empty()
        g = tuple(int(u) for u in ext)
        if g != (x0, y0, z0, x1, y1, z1):
            # Crop in place (a copy would double the peak memory): move the kept rows to the front of the
            # buffer, then shrink it.
            shape = (g[5] - g[2] + 1, g[4] - g[1] + 1, g[3] - g[0] + 1)
            _k3.crop_in_place(mask, g[0] - x0, g[1] - y0, g[2] - z0, shape[2], shape[1], shape[0])
            mask.resize(shape, refcheck=False)
            x0, y0, z0 = g[0], g[1], g[2]
    return mask, (x0, y0, z0)
