"""The functions of the curated library API (``import mrm``), as thin, documented wrappers.

Each function takes numpy arrays, :class:`~mrm.core.grids.PixelSet` / :class:`~mrm.core.grids.LabelMap`
objects and shapely geometries, and returns the same kinds: no Qt, no project, no file. Arrays given where a
pixel set is expected are **images** (row 0 at the top, as numpy, Pillow and matplotlib hold them) and go
through :meth:`PixelSet.from_image`, so a picture never comes out upside down.

The operations are the paper's (docs/design.md §5–§8); each wrapper calls the one implementation in
:mod:`mrm.ops` or :mod:`mrm.geometry` and adds nothing but the conversion of its inputs.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from mrm.core.errors import ParameterError
from mrm.core.grids import LabelMap, PixelSet, VoxelSet
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, PIXEL_COORDINATE_LIMIT
from mrm.core.models import DEFAULT_MODEL, Model
from mrm.core.numbers import read_pixel, value_text
from mrm.geometry.discretize import discretize as _discretize
from mrm.geometry.discretize.voxels import voxelize
from mrm.geometry.dss.segmentation import chain_points, greedy_segmentation, maximal_segments
from mrm.geometry.hausdorff import hausdorff_distance
from mrm.geometry.polyhedra import Polyhedron
from mrm.geometry.reconstruct import reconstruct as _reconstruct
from mrm.geometry.reconstruct.subdivision import reconstruct_label_map
from mrm.ops.boolean import euclidean_discrete_corefinement, euclidean_discrete_union
from mrm.ops.chain import chain_bound, parse_chain
from mrm.ops.registry import get_operation

__all__ = [
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


def as_pixels(obj: PixelSet | npt.ArrayLike) -> PixelSet:
    """A pixel set as it is; an array as an image (row 0 at the top, :meth:`PixelSet.from_image`)."""
    if isinstance(obj, PixelSet):
        return obj
    return PixelSet.from_image(obj)


def _as_object(obj: Any) -> Any:
    """A shapely geometry or pixel set as it is; an array as an image."""
    if isinstance(obj, PixelSet) or hasattr(obj, "geom_type"):
        return obj
    return PixelSet.from_image(obj)


def discretize(
    geom: Any, model: Model | str = DEFAULT_MODEL, *, limit: int | None = DEFAULT_PIXEL_LIMIT
) -> PixelSet | VoxelSet:
    """Return the exact discretization D(E) of a shapely geometry under ``model`` (docs/design.md §2).

    A :class:`~mrm.geometry.polyhedra.Polyhedron` is voxelized (:func:`mrm.voxelize`, §11) and gives a
    :class:`~mrm.core.grids.VoxelSet`.

    Parameters
    ----------
    geom : shapely geometry or Polyhedron
        Polygons, lines and points (any mix); coordinates are pixel units, pixel (x, y) is centred on (x, y).
    model : Model or str
    limit : int or None
        Largest bounding box (in pixels) of the result, checked before any work.

    Returns
    -------
    PixelSet

    Examples
    --------
    >>> from shapely.geometry import box
    >>> import mrm
    >>> # gauss takes the centres of [0, 3) × [0, 2): the crossing test is half-open (docs/design.md §2)
    >>> sorted(mrm.discretize(box(0, 0, 3, 2), "gauss"))
    [(0, 0), (0, 1), (1, 0), (1, 1), (2, 0), (2, 1)]
    """
    if isinstance(geom, Polyhedron):
        return voxelize(geom, model, limit=limit)
    return _discretize(geom, model, limit=limit)


def reconstruct(pixels: PixelSet | VoxelSet | npt.ArrayLike, model: Model | str = DEFAULT_MODEL) -> Any:
    """Return the reversible continuation R(A): a polygon (polyhedron) whose discretization is exactly A.

    Reference: docs/design.md §3, §11.

    Parameters
    ----------
    pixels : PixelSet, VoxelSet or array_like
        The pixel or voxel set, or an image (row 0 at the top; see :meth:`PixelSet.from_image`).
    model : Model or str

    Returns
    -------
    shapely Polygon or MultiPolygon, or Polyhedron for a voxel set
        ``discretize(reconstruct(A, m), m) == A`` for every A and model m (``voxelize`` in 3D).

    Examples
    --------
    >>> import numpy as np, mrm
    >>> img = np.zeros((5, 5), bool); img[1:4, 1:4] = True
    >>> poly = mrm.reconstruct(img, "gauss")
    >>> mrm.discretize(poly, "gauss") == mrm.PixelSet.from_image(img)
    True
    """
    if isinstance(pixels, VoxelSet):
        return _reconstruct(pixels, model)
    return _reconstruct(as_pixels(pixels), model)


def polygonize(
    labels: LabelMap | npt.ArrayLike, model: Model | str = Model.GAUSS, *, origin: tuple[int, int] = (0, 0)
) -> dict[int, Any]:
    """Reconstruct every label of a label map as a watertight subdivision: one polygon per label.

    Parameters
    ----------
    labels : LabelMap or array_like of int
        A label map, or an integer image (row 0 at the top); label 0 is the background.
    model : {"gauss"}
        The discretization every part reconstructs exactly under.
    origin : tuple of int
        For an image: the pixel of its bottom-left sample.

    Returns
    -------
    dict of int to Polygon or MultiPolygon
        ``{label: polygon}``; neighbouring parts share their edges exactly (no gap, no overlap).

    Examples
    --------
    >>> import numpy as np, mrm
    >>> parts = mrm.polygonize(np.array([[1, 1, 2], [1, 2, 2]]))
    >>> sorted(parts), parts[1].intersection(parts[2]).area
    ([1, 2], 0.0)
    """
    if not isinstance(labels, LabelMap):
        a = np.asarray(labels)
        if a.ndim != 2 or a.dtype.kind not in "iub":
            raise ParameterError(f"a label image must be a 2-D integer array, got {a.dtype} {a.shape}")
        at = read_pixel(origin, "origin", PIXEL_COORDINATE_LIMIT)
        labels = LabelMap(a[::-1].astype(np.int32), at)
    return reconstruct_label_map(labels, model)


def segment(
    chain: str | Sequence[int] | npt.ArrayLike,
    *,
    start: tuple[int, int] = (0, 0),
    mode: str = "greedy",
    closed: bool = False,
    adjacency: int = 4,
) -> list[Any]:
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


def _result_of(name: str, obj: Any, limit: int | None, *params: object) -> Any:
    """The result of the registry's one-object operation ``name`` (DSS_α, dR_θ,C, Sp_α) on ``obj``.

    An array is an image; ``params`` are the operation's parameters in the order its spec declares them.
    """
    spec = get_operation(name)
    values = dict(zip([s.name for s in spec.params.specs()], params, strict=False))
    return spec.outcome(_as_object(obj), spec.params.read(**values), limit=limit).result


def scale(
    obj: Any,
    alpha: object,
    center: object = None,
    model: Model | str = DEFAULT_MODEL,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> PixelSet:
    """Discrete smooth scaling DSS_α(A) = D(Sc_α(R(A))), computed exactly (paper §4).

    Parameters
    ----------
    obj : PixelSet, array_like image or shapely geometry
        A (a geometry E stands for D(E)).
    alpha : number
        α > 0; a float is read as the decimal it prints as (``0.2`` is 1/5), ``"1/3"`` and Fractions too.
    center : pair of numbers, optional
        The centre of the scaling (the origin by default).
    model : Model or str
    limit : int or None
        Largest result (pixels of its bounding box), estimated before the work.

    Returns
    -------
    PixelSet

    Examples
    --------
    >>> import mrm
    >>> # R_gauss of the 4×4 block is its voxels [-1/2, 7/2]²; doubled, [-1, 7]² holds the centres -1 … 6
    >>> # (the τ rule keeps the left and bottom sides, not the right and top ones): an 8×8 block
    >>> mrm.scale(mrm.PixelSet.box(0, 0, 3, 3), 2, model="gauss") == mrm.PixelSet.box(-1, -1, 6, 6)
    True
    """
    out: PixelSet = _result_of("dss", obj, limit, alpha, center, model)
    return out


def rotate(
    obj: Any,
    angle: object,
    center: object = None,
    model: Model | str = DEFAULT_MODEL,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> PixelSet:
    """Discrete rotation dR_θ,C(A) = D(rot_θ,C(R(A))) with an exact rational rotation (paper §4).

    Parameters
    ----------
    obj : PixelSet, array_like image or shapely geometry
    angle : number
        Degrees, counter-clockwise (y up).
    center : pair of numbers, optional
    model : Model or str
    limit : int or None

    Returns
    -------
    PixelSet

    Examples
    --------
    >>> import mrm
    >>> sorted(mrm.rotate(mrm.PixelSet.box(0, 0, 2, 0), 90, model="gauss"))
    [(0, 0), (0, 1), (0, 2)]
    """
    out: PixelSet = _result_of("discrete_rotation", obj, limit, angle, center, model)
    return out


def simplify(
    obj: Any,
    alpha: object,
    center: object = None,
    model: Model | str = DEFAULT_MODEL,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> Any:
    """Simplification Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))): E redrawn on a grid of voxel size 1/α (paper §5).

    Parameters
    ----------
    obj : shapely geometry, PixelSet or array_like image
        E (a pixel set A stands for R(A)).
    alpha : number
        α > 0.
    center : pair of numbers, optional
    model : Model or str
    limit : int or None

    Returns
    -------
    shapely Polygon or MultiPolygon

    Examples
    --------
    >>> from shapely.geometry import Point
    >>> import mrm
    >>> disc = Point(0, 0).buffer(10, 64)
    >>> len(mrm.simplify(disc, 0.25).exterior.coords) < len(disc.exterior.coords)
    True
    """
    return _result_of("simplify", obj, limit, alpha, center, model)


def union(
    first: Any, second: Any, model: Model | str = DEFAULT_MODEL, *, limit: int | None = DEFAULT_PIXEL_LIMIT
) -> Any:
    """Euclidean-discrete union EDu(E, E′) = R(D(E) ∪ D(E′)) (paper §6).

    Parameters
    ----------
    first, second : shapely geometry, PixelSet or array_like image
    model : Model or str
    limit : int or None

    Returns
    -------
    shapely Polygon or MultiPolygon

    Examples
    --------
    >>> from shapely.geometry import box
    >>> import mrm
    >>> u = mrm.union(box(0, 0, 2, 2), box(1, 1, 3, 3), "gauss")   # 2×2 blocks sharing pixel (1, 1)
    >>> len(mrm.discretize(u, "gauss"))
    7
    """
    return euclidean_discrete_union(_as_object(first), _as_object(second), model, limit=limit).result


def corefine(
    first: Any,
    second: Any,
    model: Model | str = DEFAULT_MODEL,
    alpha: object = None,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
) -> dict[str, Any]:
    """Euclidean-discrete co-refinement EDco(E, E′), or EDco_α with ``alpha`` (paper §6).

    Parameters
    ----------
    first, second : shapely geometry, PixelSet or array_like image
    model : Model or str
    alpha : number, optional
        The precision factor α > 0.
    limit : int or None

    Returns
    -------
    dict
        ``{"a_minus_b": …, "a_and_b": …, "b_minus_a": …}``, each a Polygon or MultiPolygon.

    Examples
    --------
    >>> from shapely.geometry import box
    >>> import mrm
    >>> parts = mrm.corefine(box(0, 0, 2, 2), box(1, 1, 3, 3), "gauss")
    >>> sorted(parts)
    ['a_and_b', 'a_minus_b', 'b_minus_a']
    """
    out = euclidean_discrete_corefinement(_as_object(first), _as_object(second), model, alpha, limit=limit)
    return dict(out.result)


def bound(
    chain: str | Sequence[Any], model: Model | str = DEFAULT_MODEL, *, exact_identities: bool = False
) -> Any:
    """Return the error bound of a chain of operations (docs/design.md §8), exactly.

    Parameters
    ----------
    chain : str or sequence of Link
        E.g. ``"DSS 5, DSS 2, DSS 0.5, DSS 0.2"`` (applied left to right), or links
        (:meth:`mrm.ops.chain.Link.of`: ``Link.of("dss", alpha=5)``).
    model : Model or str
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


def hausdorff(first: Any, second: Any, model: Model | str = DEFAULT_MODEL) -> Any:
    """Return the exact Hausdorff distance between two filled polygonal sets.

    Parameters
    ----------
    first, second : shapely Polygon / MultiPolygon, PixelSet or array_like image
        A pixel set (or image) stands for its continuation R(A) under ``model``.
    model : Model or str
        Only used for pixel inputs.

    Returns
    -------
    HausdorffDistance
        ``value`` (float nearest to the exact distance), ``squared`` (exact Fraction when rational),
        ``witness`` (a point where it is reached).

    Examples
    --------
    >>> from shapely.geometry import box
    >>> import mrm
    >>> mrm.hausdorff(box(0, 0, 1, 1), box(0, 0, 4, 1)).value
    3.0
    """
    a, b = (_as_object(x) for x in (first, second))
    a, b = (reconstruct(x, model) if isinstance(x, PixelSet) else x for x in (a, b))
    return hausdorff_distance(a, b)
