"""Exact discretization D of polygons with rational vertices.

Reference: the image of a similarity, docs/design.md §2 and §8.

:func:`mrm.geometry.discretize.discretize` is exact for float64 input. The image of a polygon under an
exact similarity (``Sc_1/5``, a rational rotation) has rational vertices that are not float64 values; rounding
them first could move a vertex across a pixel side. Three exact paths, all giving the pixels of the
definitions (docs/algorithms.md §1.7):

* every coordinate a float64: ``discretize`` itself;
* the integer definitions of :mod:`mrm.geometry.discretize.rational_kernels` — coordinates scaled by ``2L``
(L the
  common denominator) so that vertices, pixel centres (multiples of ``G = 2L``) and pixel sides (odd
  multiples of ``L``) are integers; compiled on int64 when that cannot overflow, else on Python integers;
* :func:`filtered_image` for a float64 polygon under a similarity whose image does not fit int64 (a
  rotation): float64 arithmetic with a proven error bound decides almost every pixel in compiled kernels,
  and the integer definitions decide the edges with a near-tie.

:func:`discretize_exact` takes an :class:`~mrm.geometry.discretize.exact_shape.ExactShape` (the first two
paths);
:func:`discretize_image` takes a float64 polygon and an exact similarity (the fastest path that applies).
"""

from __future__ import annotations

import logging
import math
from fractions import Fraction
from typing import Any

import numpy as np
import shapely

from mrm.core.grids import Box, PixelSet, box_area
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, check_pixels
from mrm.core.models import Model
from mrm.core.progress import ProgressLike
from mrm.geometry.discretize import discretize
from mrm.geometry.discretize.exact import check_coordinate_range
from mrm.geometry.discretize.exact_shape import ExactShape, pixel_box
from mrm.geometry.discretize.rational_kernels import (
    discretize_integer_edges,
    filtered_crossings,
    filtered_spans,
    filtered_walks,
    fits_int64,
    integer_crossings,
    integer_walks,
)

log = logging.getLogger(__name__)

IntEdge = tuple[int, int, int, int]


def _tick(progress: ProgressLike | None, fraction: float | None, message: str | None = None) -> None:
    if progress is not None:
        progress.update(fraction, message)


def discretize_exact(
    shape: ExactShape,
    model: str = "standard",
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
    what: str = "discretization",
    force_integer: bool = False,
    compiled: bool = True,
) -> PixelSet:
    """Return D(shape) exactly for polygons with rational vertices.

    Parameters
    ----------
    shape : ExactShape
        Valid polygons (holes allowed; the pieces of a multipolygon with disjoint interiors), e.g. the exact
        image of a valid polygon under a similarity.
    model : {"standard", "supercover", "gauss"}
        The discretization model (docs/design.md §2).
    limit : int or None
        Largest bounding box (in pixels) allowed for the result; checked before anything is allocated.
    progress : object with ``update(fraction, message)``, optional
        Called now and then; the ``Cancelled`` it raises propagates.
    what : str
        How the size-limit message names the result.
    force_integer : bool
        Use the integer path even when the coordinates are float64 values (for tests).
    compiled : bool
        Let the integer path use the compiled int64 kernels when no overflow is possible (False: the Python
        integers everywhere, for tests comparing the two).

    Returns
    -------
    PixelSet
        The pixels whose kernel meets the polygons.

    Raises
    ------
    ParameterError
        Unknown model.
    SizeLimitError
        The result's bounding box would exceed ``limit`` pixels.
    """
    model = Model.parse(model)
    box = pixel_box(shape.bounds(), "supercover" if model == "supercover" else "standard")
    if box is None:
        return PixelSet.empty()
    check_pixels(box_area(box), limit, what)
    _tick(progress, None, "discretizing")
    if not force_integer and shape.is_float_exact():
        geom = shape.to_geometry()
        # Float64 coordinates within the range D's float kernels take: D itself. A scaled shape may leave it
        # (α = 1/4 of a valid triangle with legs 3·2⁻⁴⁰⁰, below MIN_ABS_COORD) where its input did not; the
        # exact paths below take any rational, so the result exists and is computed, never refused.
        if check_coordinate_range(shapely.get_coordinates(geom).reshape(-1)) is None:
            result = discretize(geom, model, limit=limit)
            _tick(progress, None)
            return result
    if not force_integer:
        # Coordinates that are not float64 values (a rotation's): the float filter, exact by its bound.
        filtered = filtered_exact(shape, model, limit=limit)
        if filtered is not None:
            _tick(progress, None)
            return filtered
    return _integer_path(shape, model, box, progress, compiled)


# --------------------------------------------------------------------------------------------- integer path
def _integer_edges(shape: ExactShape) -> tuple[list[IntEdge], int]:
    """Every polygon edge scaled by 2L to integers, and G = 2L (the pixel spacing in those units)."""
    den = 1
    for c in shape.coordinates():
        den = math.lcm(den, c.denominator)
    g = 2 * den
    edges: list[IntEdge] = []
    for poly in shape.polygons:
        for ring in poly:
            pts = [(x.numerator * (g // x.denominator), y.numerator * (g // y.denominator)) for x, y in ring]
            n = len(pts)
            for k in range(n):
                ax, ay = pts[k]
                bx, by = pts[(k + 1) % n]
                if ax != bx or ay != by:
                    edges.append((ax, ay, bx, by))
    return edges, g


def _integer_path(
    shape: ExactShape, model: str, box: Box, progress: ProgressLike | None, compiled: bool = True
) -> PixelSet:
    edges, g = _integer_edges(shape)
    return integer_discretization(edges, g, model, box, progress, compiled)


def integer_discretization(
    edges: list[IntEdge], g: int, model: str, box: Box, progress: ProgressLike | None, compiled: bool = True
) -> PixelSet:
    """D of integer edges on the grid of spacing ``g`` (:mod:`mrm.geometry.discretize.rational_kernels`).

    The definitions run compiled on int64 when no overflow is possible (and ``compiled``), else on Python
    integers; ``progress`` is told when the work starts and ends.
    """
    _tick(progress, 0.0)
    mask = discretize_integer_edges(edges, g, box, model, compiled=compiled)
    _tick(progress, 1.0)
    return PixelSet.taking_over(mask, (box[0], box[1]))


# --------------------------------------------------------------------------------------- similarity images
def discretize_image(
    geom: Any,
    sim: Any,
    model: str,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    what: str = "discretization",
    valid: bool = False,
) -> PixelSet | None:
    """D(T(E)) for a float64 polygon E and an exact similarity T, without a Fraction per vertex.

    A scaling-or-translation: every float64 coordinate is ``X/2^k`` with an integer X; the image under
    ``v ↦ (p/q)·v + t`` is then ``X'/D`` over one common denominator ``D``, computed with int64 numpy
    arithmetic once the magnitudes are checked, and discretized by the compiled exact kernels
    (:mod:`mrm.geometry.discretize.rational_kernels`). A rotation, or an image beyond int64: the float filter
    (:func:`filtered_image`). Returns None where neither applies (non-finite input, magnitudes beyond
    2⁴⁰): the caller then takes :func:`discretize_exact`, which gives the same pixels.

    ``valid=True`` says E is known valid (R's output, docs/design.md §3 item 1): where T(E) is computed
    exactly in float64, it is then valid too (a similarity maps a simple ring to a simple ring and keeps holes
    inside their shell), and D skips its own validity check (a third of its time on a 1024² object).
    """
    import shapely
    from shapely.geometry import MultiPolygon, Polygon

    if not isinstance(geom, Polygon | MultiPolygon):
        return None
    if geom.is_empty:
        return PixelSet.empty()
    rings = shapely.get_rings(shapely.get_parts(geom))
    coords, index = shapely.get_coordinates(rings, return_index=True)
    if not coords.size:
        return PixelSet.empty()
    if not np.isfinite(coords).all():
        return None
    if sim.b != 0:
        return filtered_image(coords, index, sim, model, limit=limit)
    a = Fraction(sim.a)
    if (
        sim.tx == 0
        and sim.ty == 0
        and a.numerator & (a.numerator - 1) == 0
        and a.denominator & (a.denominator - 1) == 0
    ):
        # A scaling about the origin by a power of two: the float64 image is exact when neither the input nor
        # the image leaves the range of D's float kernels (no underflow); else the exact paths below.
        values = coords * float(a)
        if (
            check_coordinate_range(coords.reshape(-1)) is None
            and check_coordinate_range(values.reshape(-1)) is None
        ):
            image = shapely.set_coordinates(shapely.get_parts(geom).copy(), values)
            whole = image[0] if len(image) == 1 else MultiPolygon(list(image))
            return discretize(whole, model, limit=limit, check_validity=not valid)
    k = _denominator_exponent(coords)
    if k > 900:
        return filtered_image(coords, index, sim, model, limit=limit)
    scaled = coords * float(2**k)
    if np.abs(scaled).max(initial=0.0) >= 2.0**62:
        return filtered_image(coords, index, sim, model, limit=limit)
    xs = scaled.astype(np.int64)
    tx, ty = Fraction(sim.tx), Fraction(sim.ty)
    base = a.denominator << k
    d = math.lcm(base, tx.denominator, ty.denominator)
    ma = a.numerator * (d // base)
    t_x, t_y = tx.numerator * (d // tx.denominator), ty.numerator * (d // ty.denominator)
    big = abs(ma) * int(np.abs(xs).max(initial=0)) + max(abs(t_x), abs(t_y))
    g = 2 * d
    if not fits_int64(2 * big, g) or 2 * big >= 2**62:
        return filtered_image(coords, index, sim, model, limit=limit)
    img = np.empty_like(xs)
    img[:, 0] = 2 * (ma * xs[:, 0] + t_x)
    img[:, 1] = 2 * (ma * xs[:, 1] + t_y)
    if d & (d - 1) == 0 and big < 2**52:
        # Every image coordinate is a float64 (a dyadic over a power-of-two denominator): the compiled float
        # discretization is exact on it, and faster than the integer kernels.

        values = (img // 2).astype(np.float64) / float(d)
        if check_coordinate_range(values.reshape(-1)) is None:  # else the integer kernels below
            image = shapely.set_coordinates(shapely.get_parts(geom).copy(), values)
            whole = image[0] if len(image) == 1 else MultiPolygon(list(image))
            return discretize(whole, model, limit=limit, check_validity=not valid)
    # Edges: consecutive vertices of each closed ring (the closing point repeats the first).
    same = index[1:] == index[:-1]
    e = np.concatenate([img[:-1][same], img[1:][same]], axis=1)
    e = e[(e[:, 0] != e[:, 2]) | (e[:, 1] != e[:, 3])]
    lo, hi = img.min(axis=0), img.max(axis=0)
    bounds = (
        Fraction(int(lo[0]), g),
        Fraction(int(lo[1]), g),
        Fraction(int(hi[0]), g),
        Fraction(int(hi[1]), g),
    )
    box = pixel_box(bounds, "supercover" if model == "supercover" else "standard")
    assert box is not None
    check_pixels(box_area(box), limit, what)
    mask = discretize_integer_edges(e, g, box, model)
    return PixelSet.taking_over(mask, (box[0], box[1]))


#: The float-filtered path works on coordinates below this magnitude (far beyond the limits of
#: mrm.core.limits,
#: ±2³¹): every rounding bound below is then far above the subnormal range and far below overflow.
_FILTER_MAGNITUDE = 2.0**40
_U = 2.0**-53


def filtered_image(
    coords: np.ndarray, index: np.ndarray, sim: Any, model: str, *, limit: int | None = DEFAULT_PIXEL_LIMIT
) -> PixelSet | None:
    """D(T(E)) for the rings of a float64 polygon E (``coords`` with shapely's ring ``index``), exactly.

    The image is computed in float64 with a proven bound ``delta`` on the error of every coordinate, the
    compiled kernels of :mod:`mrm.geometry.discretize.rational_kernels` decide every crossing and edge pixel
    the
    float data decide for every polygon within ``delta``, and the edges with a near-tie are decided from
    their exact image (Fractions, then the integer definitions of this module): the pixels of the integer
    path, at the cost of the float one. Returns None (the caller takes the exact path) for magnitudes
    beyond ``2⁴⁰`` or a box beyond ``limit``.

    Error bound: ``X' = fl(fl(fl(c'·x) − fl(s'·y)) + t'_x)`` with ``c' = fl(c)``, ``s' = fl(s)``,
    ``t' = fl(t)`` (each correctly rounded, relative error ≤ u = 2⁻⁵³) has
    ``|X − X'| ≤ 4.01·u·(|c|·|x| + |s|·|y| + |t_x|)`` (at most four roundings on each term); products
    that underflow lose at most 2⁻¹⁰⁷⁴ each. ``delta = 16·u·max(…) + 2⁻¹⁰⁰⁰`` keeps a factor 2 of slack
    (with |c| ≤ (1 + u)|c'|), which the kernels' own bounds rely on.
    """
    cf, sf, txf, tyf = float(sim.a), float(sim.b), float(sim.tx), float(sim.ty)
    if max(abs(cf), abs(sf), abs(txf), abs(tyf)) >= _FILTER_MAGNITUDE:
        return None
    x = np.ascontiguousarray(coords[:, 0], dtype=np.float64)
    y = np.ascontiguousarray(coords[:, 1], dtype=np.float64)
    if np.abs(coords).max(initial=0.0) >= _FILTER_MAGNITUDE:
        return None
    ix = (cf * x - sf * y) + txf
    iy = (sf * x + cf * y) + tyf
    magnitude = float(max(np.abs(ix).max(initial=0.0), np.abs(iy).max(initial=0.0)))
    if not magnitude < _FILTER_MAGNITUDE:
        return None
    spread = (abs(cf) + abs(sf)) * (np.abs(x) + np.abs(y)) + (abs(txf) + abs(tyf))
    delta = 16.0 * _U * float(spread.max(initial=0.0)) + 2.0**-1000
    # Edges: consecutive vertices of each closed ring; an edge of two equal input points has one exact
    # image point (T is injective) and is skipped, as the integer path skips zero-length edges.
    first = np.flatnonzero(index[1:] == index[:-1])
    second = first + 1
    keep = (x[first] != x[second]) | (y[first] != y[second])

    def exact_point(v: int) -> tuple[Fraction, Fraction]:
        p: tuple[Fraction, Fraction] = sim((Fraction(float(x[v])), Fraction(float(y[v]))))
        return p

    return _filtered(ix, iy, first[keep], second[keep], delta, magnitude, exact_point, model, limit)


def filtered_exact(
    shape: ExactShape, model: str, *, limit: int | None = DEFAULT_PIXEL_LIMIT
) -> PixelSet | None:
    """D(shape) for rational polygons by the float filter of :func:`filtered_image` (None: not applicable).

    Each coordinate is rounded once to the nearest float64 (``Fraction.__float__`` is correctly rounded:
    ``|X − X'| ≤ u·|X|``, u = 2⁻⁵³, or 2⁻¹⁰⁷⁵ in the subnormal range); ``delta = 4·u·max|X| + 2⁻¹⁰⁰⁰``
    keeps the factor 2 of slack the kernels rely on. The edges with a near-tie are decided from the exact
    coordinates by the integer definitions.
    """
    pts: list[tuple[Fraction, ...]] = []
    first: list[int] = []
    second: list[int] = []
    for poly in shape.polygons:
        for ring in poly:
            start, n = len(pts), len(ring)
            pts.extend(ring)
            for k in range(n):
                if ring[k] != ring[(k + 1) % n]:  # the integer path skips zero-length edges too
                    first.append(start + k)
                    second.append(start + (k + 1) % n)
    if not pts:
        return PixelSet.empty()
    try:
        ix = np.array([float(p[0]) for p in pts], dtype=np.float64)
        iy = np.array([float(p[1]) for p in pts], dtype=np.float64)
    except OverflowError:
        return None
    magnitude = float(max(np.abs(ix).max(), np.abs(iy).max()))
    if not magnitude < _FILTER_MAGNITUDE:
        return None
    delta = 4.0 * _U * magnitude + 2.0**-1000
    return _filtered(
        ix,
        iy,
        np.array(first, dtype=np.int64),
        np.array(second, dtype=np.int64),
        delta,
        magnitude,
        lambda v: pts[v],
        model,
        limit,
    )


def _filtered(
    ix: np.ndarray,
    iy: np.ndarray,
    first: np.ndarray,
    second: np.ndarray,
    delta: float,
    magnitude: float,
    exact_point: Any,
    model: str,
    limit: int | None,
) -> PixelSet | None:
    """The float-filtered discretization of the edges ``first[k] → second[k]``.

    The float vertices ``(ix, iy)`` are each within ``delta`` of the exact vertex ``exact_point(v)``;
    ``magnitude`` bounds their coordinates.
    """
    ax, ay, bx, by = ix[first], iy[first], ix[second], iy[second]
    # A box holding every pixel D can contain (cells of the bounds, grown by one pixel for delta < 1).
    x0 = int(np.floor(ix.min() - 0.5)) - 1
    y0 = int(np.floor(iy.min() - 0.5)) - 1
    x1 = int(np.ceil(ix.max() + 0.5)) + 1
    y1 = int(np.ceil(iy.max() + 0.5)) + 1
    if limit is not None and box_area((x0, y0, x1, y1)) > limit:
        return None  # the exact path checks the exact box (this one is a few pixels larger)

    def exact_edges(ks: np.ndarray) -> tuple[list[IntEdge], int]:
        """The exact edges ``ks`` as integers on one grid G = 2L (L: their common denominator)."""
        pts = [exact_point(int(v)) for k in ks for v in (first[k], second[k])]
        den = math.lcm(*(c.denominator for p in pts for c in p))
        g = 2 * den
        ints = [(int(px * g), int(py * g)) for px, py in pts]
        return [(*ints[2 * t], *ints[2 * t + 1]) for t in range(len(ks))], g

    rows, xs, ok = filtered_crossings(ax, ay, bx, by, delta, x0, x1)
    doubtful = np.flatnonzero(~ok)
    if doubtful.size:
        edges, g = exact_edges(doubtful)
        more_rows, more_xs = integer_crossings(edges, g, x0, x1)
        rows, xs = np.concatenate([rows, more_rows]), np.concatenate([xs, more_xs])
    mask = np.zeros((y1 - y0 + 1, x1 - x0 + 1), dtype=bool)
    filtered_spans(mask, rows, xs, x0, y0)
    if model != "gauss":
        filtered_walks(mask, ax, ay, bx, by, ok, delta, magnitude, x0, y0)
        doubtful = np.flatnonzero(~ok)
        if doubtful.size:
            edges, g = exact_edges(doubtful)
            integer_walks(mask, edges, g, x0, y0, model == "standard")
    if log.isEnabledFor(logging.DEBUG):
        log.debug("filtered discretization: %d edges, %d decided exactly", len(ok), int((~ok).sum()))
    return PixelSet.taking_over(mask, (x0, y0))


def _denominator_exponent(values: np.ndarray) -> int:
    """The smallest k ≥ 0 such that every float64 value times 2^k is an integer."""
    v = values.ravel()
    v = v[v != 0]
    if not v.size:
        return 0
    m, e = np.frexp(v)  # v = m·2^e, 0.5 ≤ |m| < 1, m a 53-bit fraction
    mant = np.abs(m * 2.0**53).astype(np.int64)
    low = mant & -mant  # the lowest set bit: 2^(trailing zeros)
    tz = np.log2(low.astype(np.float64)).astype(np.int64)  # exact: powers of two
    return int(max(0, int((53 - e - tz).max())))
