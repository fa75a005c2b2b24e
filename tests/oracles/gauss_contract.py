"""The containment item of docs/design.md §3 for ``gauss`` (item 2), checked exactly with the project's exact
D.

R_gauss(A) need not lie inside V(A). Its boundary must

* separate the centres of A from every other centre strictly — no centre on ∂R(A). With D_gauss(R) = A this
  is checked by also turning R(A) by 180° about a pixel centre: a centre on the relative interior of an
  edge is decided by the perturbation τ, and τ and −τ cannot both point into R (or both out of it), so one of
  the two discretizations would differ; at a vertex, "neither inward" or "both inward" already breaks one of
  them;
* stay within the voxels of the border pixels on either side (pixels of A 8-adjacent to the complement, and
  pixels of the complement 8-adjacent to A): the supercover of ∂R(A) — every pixel whose closed square meets
  the boundary — must hold border pixels only. (That is slightly stronger than the contract, which would
  also allow the boundary on a side shared with a non-border pixel; R never goes there.)
"""

from __future__ import annotations

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.grids import PixelSet
from mrm.geometry.discretize import discretize


def border_pixels(ps: PixelSet) -> PixelSet:
    """Pixels of A 8-adjacent to the complement, and pixels of the complement 8-adjacent to A."""
    m = np.pad(ps.mask, 2)
    h, w = m.shape
    dil = np.zeros_like(m)
    ero = np.ones_like(m)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            sh = np.zeros_like(m)
            sh[max(dy, 0) : h + min(dy, 0), max(dx, 0) : w + min(dx, 0)] = m[
                max(-dy, 0) : h + min(-dy, 0), max(-dx, 0) : w + min(-dx, 0)
            ]
            dil |= sh
            ero &= sh
    x0, y0 = ps.origin
    return PixelSet(dil & ~ero, (x0 - 2, y0 - 2))


def half_turn(geom: Polygon | MultiPolygon, c: tuple[int, int]) -> Polygon | MultiPolygon:
    """The geometry turned by 180° about the point c, exactly."""
    return shapely.transform(geom, lambda xy: np.array([2 * c[0], 2 * c[1]], dtype=np.float64) - xy)


def check_gauss_containment(geom: Polygon | MultiPolygon, ps: PixelSet) -> None:
    """Assert docs/design.md §3 item 2 for ``gauss`` (and D_gauss(R) = A, which it relies on)."""
    assert discretize(geom, "gauss") == ps
    c = (ps.origin[0], ps.origin[1])
    assert discretize(half_turn(geom, c), "gauss") == ps.rotate90(2, c)
    touched = discretize(geom.boundary, "supercover")
    assert touched.issubset(border_pixels(ps)), "the boundary leaves the border pixels' voxels"
