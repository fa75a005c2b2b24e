"""The functions of the curated library API (``import mrm``), as thin, documented wrappers.

Each function takes numpy arrays, :class:`~mrm.core.grids.PixelSet` / :class:`~mrm.core.grids.LabelMap`
objects and Euclidean geometries, and returns the same kinds: no Qt, no project, no file. Arrays given where
a pixel set is expected are **images** (row 0 at the top, as numpy, Pillow and matplotlib hold them) and go
through :meth:`PixelSet.from_image <mrm.core.grids.PixelSet.from_image>`, so a picture never comes out
upside down; a NaN or infinite sample is refused.

**Geometries** are shapely geometries, GeoJSON mappings (a geometry, a ``Feature`` or a ``FeatureCollection``)
or any object with ``__geo_interface__`` (GeoPandas, Fiona, …): :func:`mrm.io.geo_interface.as_geometry`.

**Vectorized forms**, as in shapely 2 (docs/adr/0053): where a function takes one geometry, pixel set or
image, it also takes a *batch*: a ``list`` or ``tuple`` whose items are all such values (2-D arrays,
pixel sets, label maps, geometries, GeoJSON mappings), or a numpy array of ``dtype=object``. The result is
then a numpy ``object`` array of the element-wise results, of the batch's shape (a list or tuple gives a 1-D
array). Two-argument functions broadcast their arguments as numpy does. A plain 3-D numeric array is **never**
a batch: it stays one value (an H×W×3 colour image; voxels are a :class:`~mrm.core.grids.VoxelSet`); pass a
stack of masks ``a`` of shape (N, H, W) as ``list(a)``. A nested list of numbers is one image, as before.

The operations are the paper's (docs/design.md §5–§8); each wrapper calls the one implementation in
:mod:`mrm.ops` or :mod:`mrm.geometry` and adds nothing but the conversion of its inputs and outputs.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import TYPE_CHECKING, Any, Literal, TypeAlias, TypeVar, cast, overload

import numpy as np
import numpy.typing as npt
from shapely.geometry import MultiPolygon, Polygon
from shapely.geometry.base import BaseGeometry

from mrm.core.errors import FileFormatError, MRMError, NotApplicableError, ParameterError
from mrm.core.georef import GeoRef
from mrm.core.grids import LabelMap, LabelVolume, PixelSet, VoxelSet
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, PIXEL_COORDINATE_LIMIT
from mrm.core.models import DEFAULT_MODEL, Model
from mrm.core.numbers import read_pixel, value_text
from mrm.geometry.discretize import discretize as _discretize
from mrm.geometry.discretize.voxels import voxelize
from mrm.geometry.dss import Segment
from mrm.geometry.dss.segmentation import chain_points, greedy_segmentation, maximal_segments
from mrm.geometry.hausdorff import HausdorffDistance, hausdorff_distance
from mrm.geometry.hausdorff.bounds import BoundResult
from mrm.geometry.polyhedra import Polyhedron
from mrm.geometry.reconstruct import reconstruct as _reconstruct
from mrm.geometry.reconstruct.subdivision import reconstruct_label_map
from mrm.io.geo_interface import GeoInterface, GeometryLike, as_geometry, is_geometry_like
from mrm.ops.boolean import euclidean_discrete_corefinement, euclidean_discrete_union
from mrm.ops.chain import Link, chain_bound, parse_chain
from mrm.ops.registry import THREE_D, get_operation

if TYPE_CHECKING:  # the 3D label meshes' module loads the 3D kernels: imported when used
    from mrm.geometry.reconstruct.polygonize_3d import LabelMeshes

__all__ = [
    "Batch",
    "BoundResult",
    "GeoInterface",
    "GeometryLike",
    "HausdorffDistance",
    "Image",
    "ModelLike",
    "ModelName",
    "ObjectArray",
    "Polygonal",
    "Segment",
    "Shape",
    "TransformLike",
    "bound",
    "corefine",
    "discretize",
    "hausdorff",
    "polygonize",
    "reconstruct",
    "rotate",
    "scale",
    "segment",
    "simplify",
    "union",
]

#: The names of the discretization models (docs/design.md §2), as a type checker sees them.
ModelName: TypeAlias = Literal["standard", "supercover", "gauss"]
#: A discretization model: a :class:`~mrm.core.models.Model` or its name.
ModelLike: TypeAlias = Model | ModelName
#: What a reconstruction gives in 2-D.
Polygonal: TypeAlias = Polygon | MultiPolygon
#: An image as numpy holds it (row 0 at the top): booleans, integers or floats in [0, 1], or nested lists.
Image: TypeAlias = (
    npt.NDArray[np.bool_] | npt.NDArray[np.integer] | npt.NDArray[np.floating] | Sequence[Sequence[float]]
)
#: One 2-D value of the paper's operations: a pixel set, an image or a Euclidean geometry.
Shape: TypeAlias = PixelSet | Image | GeometryLike
#: Many values at once: a list or tuple of values, or a numpy array of ``dtype=object`` (module docstring).
Batch: TypeAlias = (
    Sequence[PixelSet | VoxelSet | LabelMap | Polyhedron | GeometryLike | npt.NDArray[np.generic]]
    | npt.NDArray[np.object_]
)
#: The results of a batch: a numpy array of ``dtype=object``, of the batch's shape.
ObjectArray: TypeAlias = npt.NDArray[np.object_]
#: Where an image lies: GDAL's / rasterio's affine ``(a, b, c, d, e, f)`` (an ``affine.Affine`` too), or a
#: :class:`~mrm.core.georef.GeoRef` (needed for a pixel set or label map, which have no rows of their own).
TransformLike: TypeAlias = GeoRef | Sequence[float]

_R = TypeVar("_R")


# ---------------------------------------------------------------------------------------------- inputs
def as_pixels(obj: PixelSet | Image) -> PixelSet:
    """A pixel set as it is; an array as an image (row 0 at the top, :meth:`PixelSet.from_image`)."""
    if isinstance(obj, PixelSet):
        return obj
    return PixelSet.from_image(obj)


def _as_object(obj: object, *, solids: bool = False) -> PixelSet | BaseGeometry | VoxelSet | Polyhedron:
    """A value of the paper's operations as they take it: GeoJSON as shapely's, an array as an image.

    Pixel sets and shapely geometries stay as they are; voxel sets and polyhedra too for the operations that
    take 3D objects (``solids``: DSS_α and dR). Otherwise a voxel set, polyhedron or label map is refused.
    """
    if solids and isinstance(obj, VoxelSet | Polyhedron):
        return obj
    if isinstance(obj, VoxelSet | Polyhedron | LabelMap):
        raise NotApplicableError(
            f"this operation takes a pixel set, an image or a 2-D geometry, not a {type(obj).__name__}; "
            "the library's 3-D functions are mrm.voxelize and mrm.reconstruct"
            if not isinstance(obj, LabelMap)
            else "a label map is no input of the paper's operations: take one label with lm.pixel_set(label)"
        )
    if isinstance(obj, PixelSet | BaseGeometry):
        return obj
    if is_geometry_like(obj):
        return as_geometry(obj)
    return PixelSet.from_image(obj)  # type: ignore[arg-type]  # what is left is an image


def _is_item(x: object) -> bool:
    """Whether ``x`` can be one element of a batch (a value, not a number or a row of numbers)."""
    return isinstance(x, np.ndarray | PixelSet | VoxelSet | LabelMap | Polyhedron) or is_geometry_like(x)


def _is_batch(obj: object) -> bool:
    """The batch signal (module docstring): an object array, or a list/tuple of values (not of numbers)."""
    if isinstance(obj, np.ndarray):
        return bool(obj.dtype == np.object_)
    if isinstance(obj, list | tuple):
        return all(_is_item(x) for x in obj)
    return False


def _objects(obj: object) -> ObjectArray:
    """The batch ``obj`` as an object array, or a 0-d object array holding the one value ``obj``."""
    if isinstance(obj, np.ndarray) and obj.dtype == np.object_:
        return obj
    if _is_batch(obj):
        items = list(obj)  # type: ignore[call-overload]  # a list or tuple (_is_batch)
        out = np.empty(len(items), dtype=object)
        for i, x in enumerate(items):  # one by one: np.array would stack equal-shaped images into 3-D
            out[i] = x
        return out
    one = np.empty((), dtype=object)
    one[()] = obj
    return one


def _map(func: Callable[..., _R], *args: object) -> ObjectArray:
    """``func`` applied element-wise over broadcast batches, into an object array (module docstring)."""
    arrays = [_objects(a) for a in args]
    try:
        it = np.broadcast(*arrays)
    except ValueError as e:
        shapes = " and ".join(str(a.shape) for a in arrays)
        raise ParameterError(f"batches of shapes {shapes} do not broadcast together") from e
    out = np.empty(it.shape, dtype=object)
    for index, items in zip(np.ndindex(*it.shape), it, strict=True):
        try:
            out[index] = func(*items)
        except MRMError as e:
            e.add_note(f"in item {index} of the batch")
            raise
    return out


def _georef(transform: TransformLike, shape: tuple[int, int] | None, origin: tuple[int, int]) -> GeoRef:
    """The :class:`GeoRef` of an image of ``shape`` (rows, columns) under ``transform`` (rasterio's order).

    A GeoRef is taken as it is; ``None`` for ``shape`` means the input has no rows (a pixel set, a label map),
    which needs a GeoRef.
    """
    if isinstance(transform, GeoRef):
        return transform
    if shape is None:
        raise ParameterError(
            "transform= as six numbers places an image's rows; a pixel set or label map has none: "
            "give the image array, or a GeoRef (mrm.io.georef.read_georef)"
        )
    try:
        t = [float(v) for v in transform]
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(
            "transform must be an Affine, six numbers (a, b, c, d, e, f) or a GeoRef, "
            f"got {value_text(transform)}"
        ) from None
    if len(t) == 9 and t[6:] == [0.0, 0.0, 1.0]:  # affine.Affine is the 3×3 matrix, its last row (0, 0, 1)
        t = t[:6]
    if len(t) != 6:
        raise ParameterError(
            f"transform must be an Affine or six numbers (a, b, c, d, e, f), got {len(t)} numbers; "
            "for GDAL's geotransform (c, a, b, f, d, e) use affine.Affine.from_gdal(*gt)"
        )
    h, w = shape
    if h < 1 or w < 1:
        raise ParameterError(f"an image of {w}×{h} pixels holds nothing to place")
    try:
        return GeoRef((t[0], t[1], t[2], t[3], t[4], t[5]), w, h, None, origin)
    except FileFormatError as e:  # GeoRef's wording is for files; here it is an argument
        raise ParameterError(f"transform: {e}") from None


def _image_shape(obj: object) -> tuple[int, int] | None:
    """(rows, columns) of an image argument; None for a pixel set, a label map or a geometry."""
    if isinstance(obj, PixelSet | VoxelSet | LabelMap | BaseGeometry) or is_geometry_like(obj):
        return None
    a = np.asarray(obj)
    return (int(a.shape[0]), int(a.shape[1])) if a.ndim >= 2 else None


# ---------------------------------------------------------------------------------------------- functions
@overload
def discretize(geom: GeometryLike, model: ModelLike = ..., *, limit: int | None = ...) -> PixelSet: ...
@overload
def discretize(geom: Polyhedron, model: ModelLike = ..., *, limit: int | None = ...) -> VoxelSet: ...
@overload
def discretize(geom: Batch, model: ModelLike = ..., *, limit: int | None = ...) -> ObjectArray: ...
def discretize(
    geom: GeometryLike | Polyhedron | Batch,
    model: ModelLike = DEFAULT_MODEL,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> PixelSet | VoxelSet | ObjectArray:
    """Return the exact discretization D(E) of a Euclidean geometry under ``model`` (docs/design.md §2).

    A :class:`~mrm.geometry.polyhedra.Polyhedron` is voxelized (:func:`mrm.voxelize`, §11) and gives a
    :class:`~mrm.core.grids.VoxelSet`.

    Parameters
    ----------
    geom : shapely geometry, GeoJSON mapping, ``__geo_interface__`` object, Polyhedron, or a batch of them
        Polygons, lines and points (any mix); coordinates are pixel units, pixel (x, y) is centred on (x, y).
    model : Model or {"standard", "supercover", "gauss"}
    limit : int or None
        Largest bounding box (in pixels) of each result, checked before any work.

    Returns
    -------
    PixelSet, VoxelSet, or numpy.ndarray of them for a batch

    Examples
    --------
    >>> from shapely.geometry import box
    >>> import mrm
    >>> # gauss takes the centres of [0, 3) × [0, 2): the crossing test is half-open (docs/design.md §2)
    >>> sorted(mrm.discretize(box(0, 0, 3, 2), "gauss"))
    [(0, 0), (0, 1), (1, 0), (1, 1), (2, 0), (2, 1)]
    >>> # a GeoJSON dict, and a batch: a list in, an object array out
    >>> len(mrm.discretize({"type": "Point", "coordinates": [2, 5]}))
    1
    >>> [len(ps) for ps in mrm.discretize([box(0, 0, 1, 1), box(0, 0, 3, 2)], "gauss")]
    [1, 6]
    """
    if _is_batch(geom):
        return _map(lambda g: discretize(g, model, limit=limit), geom)
    if isinstance(geom, Polyhedron):
        return voxelize(geom, model, limit=limit)
    return _discretize(as_geometry(geom), model, limit=limit)


@overload
def reconstruct(
    pixels: PixelSet | Image, model: ModelLike = ..., *, transform: TransformLike | None = ...
) -> Polygonal: ...
@overload
def reconstruct(pixels: VoxelSet, model: ModelLike = ..., *, transform: None = ...) -> Polyhedron: ...
@overload
def reconstruct(
    pixels: Batch, model: ModelLike = ..., *, transform: TransformLike | None = ...
) -> ObjectArray: ...
def reconstruct(
    pixels: PixelSet | VoxelSet | Image | Batch,
    model: ModelLike = DEFAULT_MODEL,
    *,
    transform: TransformLike | None = None,
) -> Polygonal | Polyhedron | ObjectArray:
    """Return the reversible continuation R(A): a polygon (polyhedron) whose discretization is exactly A.

    Reference: docs/design.md §3, §11.

    Parameters
    ----------
    pixels : PixelSet, VoxelSet, array_like image, or a batch of them (a stack of masks: ``list(stack)``)
        The pixel or voxel set, or an image (row 0 at the top; see :meth:`PixelSet.from_image`).
    model : Model or {"standard", "supercover", "gauss"}
    transform : affine.Affine, tuple of 6 float or GeoRef, optional
        Where the image lies, as rasterio's ``transform=`` (``X = a·col + b·row + c``, ``Y = d·col + e·row +
        f``, (col, row) = (0, 0) the top-left corner of the image): the polygon is returned in these world
        coordinates, placed as ``rasterio.features.shapes(image, transform=transform)`` places the pixels'
        outlines. A pixel set needs a :class:`~mrm.core.georef.GeoRef`.

    Returns
    -------
    shapely.geometry.Polygon or shapely.geometry.MultiPolygon, Polyhedron, or numpy.ndarray of them
        ``discretize(reconstruct(A, m), m) == A`` for every A and model m (``voxelize`` in 3D), in grid
        coordinates (without ``transform``).

    Examples
    --------
    >>> import numpy as np, mrm
    >>> img = np.zeros((5, 5), bool); img[1:4, 1:4] = True
    >>> poly = mrm.reconstruct(img, "gauss")
    >>> mrm.discretize(poly, "gauss") == mrm.PixelSet.from_image(img)
    True
    >>> # 10 m pixels, the image's top-left corner at (500000, 4200050): the 3×3 block's world outline
    >>> mrm.reconstruct(img, "gauss", transform=(10, 0, 500000, 0, -10, 4200050)).bounds
    (500010.0, 4200010.0, 500040.0, 4200040.0)
    >>> # a stack of masks is a list of 2-D arrays (a 3-D array is not a batch)
    >>> [p.area for p in mrm.reconstruct([img, img[:, :3]], "gauss")]
    [9.0, 6.0]
    """
    if _is_batch(pixels):
        return _map(lambda a: reconstruct(a, model, transform=transform), pixels)
    if isinstance(pixels, VoxelSet):
        if transform is not None:
            raise ParameterError("transform= places a 2-D image; a voxel set has no raster transform here")
        return _reconstruct(pixels, model)
    if transform is None:
        return _reconstruct(as_pixels(pixels), model)  # type: ignore[arg-type]  # not a batch
    georef = _georef(transform, _image_shape(pixels), (0, 0))
    poly: Polygonal = georef.raster_to_world(_reconstruct(as_pixels(pixels), model))  # type: ignore[arg-type]
    return poly


@overload
def polygonize(
    labels: LabelVolume,
    model: ModelLike = ...,
    *,
    origin: tuple[int, int, int] = ...,
    transform: None = ...,
) -> LabelMeshes: ...
@overload
def polygonize(
    labels: LabelMap | Image,
    model: ModelLike = ...,
    *,
    origin: tuple[int, int] = ...,
    transform: TransformLike | None = ...,
) -> dict[int, Polygonal]: ...
@overload
def polygonize(
    labels: Batch,
    model: ModelLike = ...,
    *,
    origin: tuple[int, int] = ...,
    transform: TransformLike | None = ...,
) -> ObjectArray: ...
def polygonize(
    labels: LabelMap | LabelVolume | Image | Batch,
    model: ModelLike = Model.GAUSS,
    *,
    origin: tuple[int, int] | tuple[int, int, int] = (0, 0),
    transform: TransformLike | None = None,
) -> dict[int, Polygonal] | LabelMeshes | ObjectArray:
    """Reconstruct every label of a label map as a watertight subdivision: one polygon per label.

    A label volume (3-D) gives one closed mesh per region (6-connected part of one label), on one shared
    vertex list: neighbouring regions share their common faces exactly, and each burns back to its voxels
    under ``gauss`` (docs/design.md §11).

    Parameters
    ----------
    labels : LabelMap, LabelVolume, array_like of int, or a batch of them
        A label map, or an integer image (row 0 at the top); or a label volume, or a 3-D integer array
        ``labels[k, j, i]`` (voxel (x0 + i, y0 + j, z0 + k)). Label 0 is the background.
    model : {"gauss"}
        The discretization every part reconstructs exactly under.
    origin : tuple of int
        For an image: the pixel of its bottom-left sample; for a 3-D array: the voxel (x0, y0, z0) of
        ``labels[0, 0, 0]``.
    transform : affine.Affine, tuple of 6 float or GeoRef, optional
        Where the image lies (rasterio's ``transform=``, see :func:`reconstruct`): the polygons are returned
        in world coordinates, each pixel corner exactly where ``rasterio.features.shapes`` puts it. A label
        map needs a :class:`~mrm.core.georef.GeoRef`.

    Returns
    -------
    dict of int to shapely.geometry.Polygon or shapely.geometry.MultiPolygon, LabelMeshes, or numpy.ndarray
        ``{label: polygon}``; neighbouring parts share their edges exactly (no gap, no overlap). For a label
        volume, the meshes (:class:`~mrm.geometry.reconstruct.polygonize_3d.LabelMeshes`: ``regions``, each
        with its ``label``, ``voxels`` and ``triangles``, and ``polyhedron(i)``). A batch gives an array of
        them.

    Examples
    --------
    >>> import numpy as np, mrm
    >>> parts = mrm.polygonize(np.array([[1, 1, 2], [1, 2, 2]]))
    >>> sorted(parts), parts[1].intersection(parts[2]).area
    ([1, 2], 0.0)
    >>> # half-metre pixels whose top-left corner is at (100, 200)
    >>> world = mrm.polygonize(np.array([[1, 1, 2], [1, 2, 2]]), transform=(0.5, 0, 100, 0, -0.5, 200))
    >>> world[2].bounds
    (100.5, 199.0, 101.5, 200.0)
    >>> # in 3D: two labels side by side, each a closed mesh; the square between them is in both
    >>> meshes = mrm.polygonize(np.array([[[1, 2]]]))
    >>> [(r.label, r.voxels, r.triangles.shape[0]) for r in meshes.regions]
    [(1, 1, 12), (2, 1, 12)]
    """
    if _is_batch(labels):
        # each item picks its own overload (2-D or 3-D) at run time
        return _map(
            lambda a: polygonize(a, model, origin=cast(Any, origin), transform=cast(Any, transform)), labels
        )
    if isinstance(labels, LabelVolume) or (
        not isinstance(labels, LabelMap) and np.ndim(cast(Any, labels)) == 3
    ):
        if transform is not None:
            raise ParameterError("transform= places a 2-D image; a label volume has no raster transform here")
        from mrm.geometry.reconstruct.polygonize_3d import polygonize_volume

        if len(origin) == 2 and tuple(origin) != (0, 0):
            raise ParameterError(f"a label volume's origin is a voxel (x0, y0, z0), got {origin!r}")
        corner = (0, 0, 0) if len(origin) == 2 else origin
        x0, y0, z0 = (int(c) for c in corner)
        return polygonize_volume(cast(Any, labels), (x0, y0, z0), model)
    at = read_pixel(origin, "origin", PIXEL_COORDINATE_LIMIT)
    shape = None
    if not isinstance(labels, LabelMap):
        a = np.asarray(labels)
        if a.ndim != 2 or a.dtype.kind not in "iub":
            raise ParameterError(f"a label image must be a 2-D integer array, got {a.dtype} {a.shape}")
        shape = (int(a.shape[0]), int(a.shape[1]))
        labels = LabelMap(a[::-1].astype(np.int32), at)
    parts = reconstruct_label_map(labels, model)
    if transform is None:
        return parts
    georef = _georef(transform, shape, (at[0], at[1]))
    return {v: georef.raster_to_world(p) for v, p in parts.items()}


def segment(
    chain: str | Sequence[int] | npt.ArrayLike,
    *,
    start: tuple[int, int] = (0, 0),
    mode: Literal["greedy", "maximal"] = "greedy",
    closed: bool = False,
    adjacency: Literal[4, 8] = 4,
) -> list[Segment]:
    """Cut a digital curve into digital straight segments (DGtal's greedy or maximal segmentation).

    Parameters
    ----------
    chain : str of Freeman codes, or array_like of int, shape (n, 2)
        Freeman codes (0 = E, 1 = N, 2 = W, 3 = S) from ``start``, or the points of the curve.
    start : tuple of int
        The first point, for Freeman codes.
    mode : {"greedy", "maximal"}
    closed : bool
        Read the curve as closed.
    adjacency : {4, 8}
        4: standard (4-connected) segments; 8: naive (8-connected) ones.

    Returns
    -------
    list of Segment
        ``first``, ``last`` (indices of points), ``a``, ``b``, ``mu``, ``omega``: μ ≤ a·x − b·y < μ + ω.

    Examples
    --------
    >>> import mrm
    >>> # E E N repeated: one segment of direction (2, 1), 0 ≤ x − 2y < 3 on its nine points
    >>> [s.as_list() for s in mrm.segment("00100100")]
    [[0, 8, 1, 2, 0, 3]]
    """
    if not isinstance(closed, bool | np.bool_):
        raise ParameterError(f"closed must be True or False, got {value_text(closed)}")
    if isinstance(adjacency, bool) or adjacency not in (4, 8):
        raise ParameterError(f"adjacency must be 4 or 8, got {value_text(adjacency)}")
    if isinstance(chain, str):
        bad = chain.translate(str.maketrans("", "", "0123"))
        if bad:
            raise ParameterError(f"Freeman codes are 0-3 (0=E 1=N 2=W 3=S), got {bad[0]!r}")
        pts = chain_points(read_pixel(start, "start", PIXEL_COORDINATE_LIMIT), chain)
    else:
        pts = np.asarray(chain, dtype=np.int64)
    if mode == "greedy":
        return list(greedy_segmentation(pts, closed=closed, adjacency=adjacency))
    if mode == "maximal":
        return list(maximal_segments(pts, closed=closed, adjacency=adjacency))
    raise ParameterError(f"mode must be 'greedy' or 'maximal', got {value_text(mode)}")


#: A number as the operations read it: a float is the decimal it prints as, ``"1/3"`` and Fractions exactly.
Number: TypeAlias = int | float | Fraction | str


def _result_of(name: str, obj: object, limit: int | None, *params: object) -> object:
    """The result of the registry's one-object operation ``name`` (DSS_α, dR_θ,C, Sp_α) on ``obj``.

    An array is an image; ``params`` are the operation's parameters in the order its spec declares them.
    """
    spec = get_operation(name)
    values = dict(zip([s.name for s in spec.params.specs()], params, strict=False))
    value = _as_object(obj, solids=spec.name in THREE_D)
    result: object = spec.outcome(value, spec.params.read(**values), limit=limit).result
    return result


@overload
def scale(
    obj: VoxelSet | Polyhedron,
    alpha: Number,
    center: tuple[Number, Number, Number] | None = ...,
    model: ModelLike = ...,
    *,
    limit: int | None = ...,
) -> VoxelSet: ...
@overload
def scale(
    obj: Shape,
    alpha: Number,
    center: tuple[Number, Number] | None = ...,
    model: ModelLike = ...,
    *,
    limit: int | None = ...,
) -> PixelSet: ...
@overload
def scale(
    obj: Batch,
    alpha: Number,
    center: tuple[Number, Number] | None = ...,
    model: ModelLike = ...,
    *,
    limit: int | None = ...,
) -> ObjectArray: ...
def scale(
    obj: Shape | VoxelSet | Polyhedron | Batch,
    alpha: Number,
    center: tuple[Number, Number] | tuple[Number, Number, Number] | None = None,
    model: ModelLike = DEFAULT_MODEL,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> PixelSet | VoxelSet | ObjectArray:
    """Discrete smooth scaling DSS_α(A) = D(Sc_α(R(A))), computed exactly (paper §4).

    Parameters
    ----------
    obj : PixelSet, VoxelSet, array_like image, geometry, Polyhedron, or a batch of them
        A (a geometry E stands for D(E), a polyhedron P for D(P)).
    alpha : number
        α > 0; a float is read as the decimal it prints as (``0.2`` is 1/5), ``"1/3"`` and Fractions too.
    center : two (three for a 3D object) numbers, optional
        The centre of the scaling (the origin by default).
    model : Model or {"standard", "supercover", "gauss"}
    limit : int or None
        Largest result (pixels or voxels of its bounding box), estimated before the work.

    Returns
    -------
    PixelSet (VoxelSet for a 3D object), or numpy.ndarray of them for a batch

    Examples
    --------
    >>> import mrm
    >>> # R_gauss of the 4×4 block is its voxels [-1/2, 7/2]²; doubled, [-1, 7]² holds the centres -1 … 6
    >>> # (the τ rule keeps the left and bottom sides, not the right and top ones): an 8×8 block
    >>> mrm.scale(mrm.PixelSet.box(0, 0, 3, 3), 2, model="gauss") == mrm.PixelSet.box(-1, -1, 6, 6)
    True
    >>> # in 3D R_gauss of the 4×4×4 block is its hull grown about its centre: [-3/8, 27/8]³; doubled,
    >>> # [-3/4, 27/4]³ holds the centres 0 … 6
    >>> cube = mrm.VoxelSet.box(0, 0, 0, 3, 3, 3)
    >>> mrm.scale(cube, 2, model="gauss") == mrm.VoxelSet.box(0, 0, 0, 6, 6, 6)
    True
    """
    if _is_batch(obj):
        return _map(lambda o: scale(o, alpha, center, model, limit=limit), obj)
    out = _result_of("dss", obj, limit, alpha, center, model)
    assert isinstance(out, PixelSet | VoxelSet)
    return out


@overload
def rotate(
    obj: VoxelSet | Polyhedron,
    angle: Number,
    center: tuple[Number, Number, Number] | None = ...,
    model: ModelLike = ...,
    *,
    axis: tuple[Number, Number, Number] | None = ...,
    limit: int | None = ...,
) -> VoxelSet: ...
@overload
def rotate(
    obj: Shape,
    angle: Number,
    center: tuple[Number, Number] | None = ...,
    model: ModelLike = ...,
    *,
    axis: tuple[Number, Number, Number] | None = ...,
    limit: int | None = ...,
) -> PixelSet: ...
@overload
def rotate(
    obj: Batch,
    angle: Number,
    center: tuple[Number, Number] | None = ...,
    model: ModelLike = ...,
    *,
    axis: tuple[Number, Number, Number] | None = ...,
    limit: int | None = ...,
) -> ObjectArray: ...
def rotate(
    obj: Shape | VoxelSet | Polyhedron | Batch,
    angle: Number,
    center: tuple[Number, Number] | tuple[Number, Number, Number] | None = None,
    model: ModelLike = DEFAULT_MODEL,
    *,
    axis: tuple[Number, Number, Number] | None = None,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> PixelSet | VoxelSet | ObjectArray:
    """Discrete rotation dR_θ,C(A) = D(rot_θ,C(R(A))) with an exact rational rotation (paper §4).

    Parameters
    ----------
    obj : PixelSet, VoxelSet, array_like image, geometry, Polyhedron, or a batch of them
    angle : number
        Degrees, counter-clockwise (y up; seen from the axis's tip in 3D).
    center : two (three for a 3D object) numbers, optional
    model : Model or {"standard", "supercover", "gauss"}
    axis : three numbers, optional
        3D only: the axis (z by default). Quarter turns about x, y or z are exact; other rotations apply the
        axis-angle matrix rounded to multiples of 2⁻³⁰, exactly (docs/adr/0060).
    limit : int or None

    Returns
    -------
    PixelSet (VoxelSet for a 3D object), or numpy.ndarray of them for a batch

    Examples
    --------
    >>> import mrm
    >>> sorted(mrm.rotate(mrm.PixelSet.box(0, 0, 2, 0), 90, model="gauss"))
    [(0, 0), (0, 1), (0, 2)]
    """
    if _is_batch(obj):
        return _map(lambda o: rotate(o, angle, center, model, axis=axis, limit=limit), obj)
    out = _result_of("discrete_rotation", obj, limit, angle, center, model, axis)
    assert isinstance(out, PixelSet | VoxelSet)
    return out


@overload
def simplify(
    obj: VoxelSet | Polyhedron,
    alpha: Number,
    center: tuple[Number, Number, Number] | None = ...,
    model: ModelLike = ...,
    *,
    limit: int | None = ...,
) -> Polyhedron: ...
@overload
def simplify(
    obj: Shape,
    alpha: Number,
    center: tuple[Number, Number] | None = ...,
    model: ModelLike = ...,
    *,
    limit: int | None = ...,
) -> Polygonal: ...
@overload
def simplify(
    obj: Batch,
    alpha: Number,
    center: tuple[Number, Number] | None = ...,
    model: ModelLike = ...,
    *,
    limit: int | None = ...,
) -> ObjectArray: ...
def simplify(
    obj: Shape | VoxelSet | Polyhedron | Batch,
    alpha: Number,
    center: tuple[Number, Number] | tuple[Number, Number, Number] | None = None,
    model: ModelLike = DEFAULT_MODEL,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> Polygonal | Polyhedron | ObjectArray:
    """Simplification Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))): E redrawn on a grid of voxel size 1/α (paper §5).

    Parameters
    ----------
    obj : geometry, PixelSet, array_like image, Polyhedron, VoxelSet, or a batch of them
        E (a pixel or voxel set A stands for R(A)).
    alpha : number
        α > 0.
    center : two (three for a 3D object) numbers, optional
    model : Model or {"standard", "supercover", "gauss"}
    limit : int or None

    Returns
    -------
    shapely.geometry.Polygon or shapely.geometry.MultiPolygon (a Polyhedron for a 3D object), or
    numpy.ndarray of them

    Examples
    --------
    >>> from shapely.geometry import Point
    >>> import mrm
    >>> disc = Point(0, 0).buffer(10, 64)
    >>> len(mrm.simplify(disc, 0.25).exterior.coords) < len(disc.exterior.coords)
    True
    """
    if _is_batch(obj):
        # Any: each item takes the centre of its own dimension (too many overload unions for mypy to try)
        return _map(lambda o: simplify(o, alpha, cast(Any, center), model, limit=limit), obj)
    out = _result_of("simplify", obj, limit, alpha, center, model)
    assert isinstance(out, Polyhedron | Polygon | MultiPolygon)
    return out


@overload
def union(
    first: VoxelSet | Polyhedron,
    second: VoxelSet | Polyhedron,
    model: ModelLike = ...,
    *,
    limit: int | None = ...,
) -> Polyhedron: ...
@overload
def union(first: Shape, second: Shape, model: ModelLike = ..., *, limit: int | None = ...) -> Polygonal: ...
@overload
def union(
    first: Shape | Batch, second: Batch, model: ModelLike = ..., *, limit: int | None = ...
) -> ObjectArray: ...
@overload
def union(
    first: Batch, second: Shape | Batch, model: ModelLike = ..., *, limit: int | None = ...
) -> ObjectArray: ...
def union(
    first: Shape | VoxelSet | Polyhedron | Batch,
    second: Shape | VoxelSet | Polyhedron | Batch,
    model: ModelLike = DEFAULT_MODEL,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> Polygonal | Polyhedron | ObjectArray:
    """Euclidean-discrete union EDu(E, E′) = R(D(E) ∪ D(E′)) (paper §6).

    Parameters
    ----------
    first, second : geometry, PixelSet, array_like image, or batches of them (broadcast together)
        Or two 3D objects (Polyhedron, VoxelSet): the union is then a polyhedron.
    model : Model or {"standard", "supercover", "gauss"}
    limit : int or None

    Returns
    -------
    shapely.geometry.Polygon or shapely.geometry.MultiPolygon (a Polyhedron for 3D objects), or
    numpy.ndarray of them

    Examples
    --------
    >>> from shapely.geometry import box
    >>> import mrm
    >>> u = mrm.union(box(0, 0, 2, 2), box(1, 1, 3, 3), "gauss")   # 2×2 blocks sharing pixel (1, 1)
    >>> len(mrm.discretize(u, "gauss"))
    7
    """
    if _is_batch(first) or _is_batch(second):
        return _map(lambda a, b: union(a, b, model, limit=limit), first, second)
    out: Polygonal | Polyhedron = euclidean_discrete_union(
        _as_object(first, solids=True), _as_object(second, solids=True), model, limit=limit
    ).result
    return out


@overload
def corefine(
    first: VoxelSet | Polyhedron,
    second: VoxelSet | Polyhedron,
    model: ModelLike = ...,
    alpha: Number | None = ...,
    *,
    limit: int | None = ...,
) -> dict[str, Polyhedron]: ...
@overload
def corefine(
    first: Shape,
    second: Shape,
    model: ModelLike = ...,
    alpha: Number | None = ...,
    *,
    limit: int | None = ...,
) -> dict[str, Polygonal]: ...
@overload
def corefine(
    first: Shape | Batch,
    second: Batch,
    model: ModelLike = ...,
    alpha: Number | None = ...,
    *,
    limit: int | None = ...,
) -> ObjectArray: ...
@overload
def corefine(
    first: Batch,
    second: Shape | Batch,
    model: ModelLike = ...,
    alpha: Number | None = ...,
    *,
    limit: int | None = ...,
) -> ObjectArray: ...
def corefine(
    first: Shape | VoxelSet | Polyhedron | Batch,
    second: Shape | VoxelSet | Polyhedron | Batch,
    model: ModelLike = DEFAULT_MODEL,
    alpha: Number | None = None,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> dict[str, Polygonal] | dict[str, Polyhedron] | ObjectArray:
    """Euclidean-discrete co-refinement EDco(E, E′), or EDco_α with ``alpha`` (paper §6).

    Parameters
    ----------
    first, second : geometry, PixelSet, array_like image, or batches of them (broadcast together)
        Or two 3D objects (Polyhedron, VoxelSet): the parts are then polyhedra.
    model : Model or {"standard", "supercover", "gauss"}
    alpha : number, optional
        The precision factor α > 0.
    limit : int or None

    Returns
    -------
    dict, or numpy.ndarray of dict
        ``{"a_minus_b": …, "a_and_b": …, "b_minus_a": …}``, each a Polygon or MultiPolygon (a Polyhedron
        for 3D objects).

    Examples
    --------
    >>> from shapely.geometry import box
    >>> import mrm
    >>> parts = mrm.corefine(box(0, 0, 2, 2), box(1, 1, 3, 3), "gauss")
    >>> sorted(parts)
    ['a_and_b', 'a_minus_b', 'b_minus_a']
    """
    if _is_batch(first) or _is_batch(second):
        return _map(lambda a, b: corefine(a, b, model, alpha, limit=limit), first, second)
    a, b = _as_object(first, solids=True), _as_object(second, solids=True)
    return dict(euclidean_discrete_corefinement(a, b, model, alpha, limit=limit).result)


def bound(
    chain: str | Sequence[Link], model: ModelLike = DEFAULT_MODEL, *, exact_identities: bool = False
) -> BoundResult:
    """Return the error bound of a chain of operations (docs/design.md §8), exactly.

    Parameters
    ----------
    chain : str or sequence of Link
        E.g. ``"DSS 5, DSS 2, DSS 0.5, DSS 0.2"`` (applied left to right), or links
        (:meth:`Link.of <mrm.ops.chain.Link.of>`: ``Link.of("dss", alpha=5)``).
    model : Model or {"standard", "supercover", "gauss"}
    exact_identities : bool
        Merge round trips separated by an exact identity.

    Returns
    -------
    BoundResult
        ``bound`` (float or None), ``coefficient`` (Fraction, of √n), ``formula``, ``guarantee``.

    Examples
    --------
    >>> import mrm
    >>> b = mrm.bound("DSS 5, DSS 2, DSS 0.5, DSS 0.2")
    >>> b.coefficient, round(b.bound, 4)
    (Fraction(1, 2), 0.7071)
    """
    links = parse_chain(chain) if isinstance(chain, str) else list(chain)
    return chain_bound(links, model, exact_identities=exact_identities)


@overload
def hausdorff(first: Shape, second: Shape, model: ModelLike = ...) -> HausdorffDistance: ...
@overload
def hausdorff(first: Shape | Batch, second: Batch, model: ModelLike = ...) -> ObjectArray: ...
@overload
def hausdorff(first: Batch, second: Shape | Batch, model: ModelLike = ...) -> ObjectArray: ...
def hausdorff(
    first: Shape | Batch, second: Shape | Batch, model: ModelLike = DEFAULT_MODEL
) -> HausdorffDistance | ObjectArray:
    """Return the exact Hausdorff distance between two filled polygonal sets.

    Parameters
    ----------
    first, second : geometry, PixelSet, array_like image, or batches of them (broadcast together)
        A pixel set (or image) stands for its continuation R(A) under ``model``.
    model : Model or {"standard", "supercover", "gauss"}
        Only used for pixel inputs.

    Returns
    -------
    HausdorffDistance, or numpy.ndarray of them
        ``value`` (float nearest to the exact distance), ``squared`` (exact Fraction when rational),
        ``witness`` (a point where it is reached).

    Examples
    --------
    >>> from shapely.geometry import box
    >>> import mrm
    >>> mrm.hausdorff(box(0, 0, 1, 1), box(0, 0, 4, 1)).value
    3.0
    >>> # one polygon against three: broadcast as numpy does
    >>> [d.value for d in mrm.hausdorff(box(0, 0, 1, 1), [box(0, 0, 1, 1), box(0, 0, 2, 1), box(0, 0, 4, 1)])]
    [0.0, 1.0, 3.0]
    """
    if _is_batch(first) or _is_batch(second):
        return _map(lambda a, b: hausdorff(a, b, model), first, second)
    a, b = (_as_object(x) for x in (first, second))
    a, b = (_reconstruct(x, model) if isinstance(x, PixelSet) else x for x in (a, b))
    return hausdorff_distance(a, b)
