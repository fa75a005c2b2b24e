"""Polygonize a label map: one polygon per region, shared boundaries shared exactly (watertight).

A *region* is a 4-connected component of the pixels of one non-zero label (label 0 is the background,
docs/design.md §1). :func:`polygonize` returns one :class:`Region` per region, built from the joint ``gauss``
reconstruction of the label map (:mod:`mrm.geometry.reconstruct.subdivision`, ADR 0004):

* D_gauss(region polygon) = the region's pixels exactly, so any centre-rule rasterizer (GDAL's
  ``rasterize``, PIL, scikit-image) burns the polygons with their labels back to the label image;
* a boundary between two regions is one polyline used by both (the same float64 vertices, in opposite
  directions): no gap, no overlap, no sliver;
* dyadic float64 coordinates; the same input always gives the same output, and translating the label map by
  an integer vector translates every polygon exactly.

Only ``gauss`` admits such a coverage: under a cover model a polygon's discretization adds the pixels its
boundary crosses, so two regions sharing an edge would both claim them (a :class:`ParameterError` says so).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import shapely
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import ParameterError
from mrm.core.grids import LabelMap
from mrm.core.limits import PIXEL_COORDINATE_LIMIT
from mrm.core.models import Model
from mrm.core.numbers import read_pixel
from mrm.geometry.discretize import discretize
from mrm.geometry.reconstruct.subdivision import subdivide
from mrm.geometry.topology.labeling import label_regions

logger = logging.getLogger(__name__)


@dataclass(frozen=True)
class Region:
    """One region of a label map and its polygon.

    Attributes
    ----------
    label : int
        The region's label (non-zero).
    pixels : int
        Its number of pixels.
    geometry : Polygon
        Its polygon, holes included: D_gauss(geometry) is exactly the region's pixels.
    """

    label: int
    pixels: int
    geometry: Polygon


def polygonize(
    labels: LabelMap | npt.ArrayLike, origin: tuple[int, int] = (0, 0), model: str = "gauss"
) -> list[Region]:
    """Return one polygon per region (4-connected component of one non-zero label) of a label map.

    Parameters
    ----------
    labels : LabelMap or array_like of int, shape (rows, cols)
        The label map; an array is read with row 0 as the lowest y (docs/design.md §1), placed at ``origin``.
    origin : (int, int)
        The plane coordinates of the array's element [0, 0] (ignored for a LabelMap, which has its own).
    model : str
        Only ``"gauss"``: the one model under which a watertight coverage gives the labels back.

    Returns
    -------
    list of Region
        By increasing label, then by the region's lowest (y, x) pixel.

    Raises
    ------
    ParameterError
        For a model other than ``gauss``, or an array that is not a 2-D integer array.
    """
    if Model.parse(model).is_cover:
        raise ParameterError(
            f"polygonize needs the gauss model, not {model!r}: under a cover model two regions sharing a "
            "boundary would both claim the pixels along it (use 'mrm reconstruct' per label instead)"
        )
    if isinstance(labels, LabelMap):
        lm = labels
    else:
        a = np.asarray(labels)
        if a.ndim != 2 or a.dtype.kind not in "iub":
            raise ParameterError(f"labels must be a 2-D integer array, not {a.dtype} of shape {a.shape}")
        try:
            lm = LabelMap(a, read_pixel(origin, "origin", PIXEL_COORDINATE_LIMIT))
        except ValueError as e:
            raise ParameterError(str(e)) from None
    reg = label_regions(lm.labels)
    sd = subdivide(lm, "gauss", regions=reg)  # its cost is checked first, from these regions
    # The subdivision gives one polygon per region, D_gauss of it exactly the region's pixels (its contract,
    # proven and tested in mrm.geometry.reconstruct.subdivision): a polygon is the region whose first pixel's
    # centre it holds, and the labelling gives each region's size and order.
    x0, y0 = lm.origin
    # Each label's regions in the output order, grouped once (a search per label was quadratic in labels).
    order = np.argsort(reg.label, kind="stable")
    starts = np.searchsorted(reg.label[order], np.asarray(list(sd.parts), dtype=np.int64))
    ends = np.searchsorted(reg.label[order], np.asarray(list(sd.parts), dtype=np.int64), side="right")
    out: list[Region] = []
    for (label, geom), a, b in zip(sd.parts.items(), starts.tolist(), ends.tolist(), strict=True):
        polys = list(geom.geoms) if isinstance(geom, MultiPolygon) else ([geom] if not geom.is_empty else [])
        mine = order[a:b]  # this label's regions, in the output order
        centres = shapely.points(x0 + reg.first_col[mine], y0 + reg.first_row[mine])
        which, poly = shapely.STRtree(polys).query(centres, predicate="within")
        if which.size != mine.size or np.unique(poly).size != len(polys) or len(polys) != mine.size:
            logger.error(
                "label %d: %d polygons for %d regions; counting them exactly", label, len(polys), mine.size
            )
            out.extend(_regions_by_discretization(int(label), polys))
            continue
        by_region = np.empty(mine.size, np.int64)
        by_region[which] = poly
        out.extend(
            Region(int(label), int(reg.pixels[r]), polys[p]) for r, p in zip(mine, by_region, strict=True)
        )
    logger.debug("polygonized %d regions of %d labels", len(out), len(sd.parts))
    return out


def _regions_by_discretization(label: int, polys: list[Polygon]) -> list[Region]:
    # Each polygon's pixels by the exact discretization (slow: one D per polygon), in region order.
    regions = []
    for p in polys:
        ps = discretize(p, "gauss", limit=None)
        first = ps.points()
        key = (int(first[:, 1].min()), int(first[first[:, 1] == first[:, 1].min(), 0].min()))
        regions.append((key, Region(label, len(ps), p)))
    return [r for _k, r in sorted(regions, key=lambda kr: kr[0])]
