"""The trivial reversible continuations, exact.

Reference: docs/design.md §3, item 7; docs/algorithms.md §3.5 "Fallback R0".

* :func:`eroded_net` — R0(A) = V(A) ⊖ [−¼, ¼]²: every crack ring offset inward by a quarter pixel. Each pixel
  keeps its core, the boundary stays a quarter pixel inside V(A) and away from every outside pixel, and
  pixels touching only at a corner come apart: D(R0(A)) = A under all three models, with the (4, 8)
  topology. One vertex per corner of the crack boundary.
* :func:`staircase` — V(A) itself, the ``gauss`` safety net (its boundary runs along pixel sides, so the
  cover models would add the outside neighbours). Where the crack boundary passes a pointel twice (two
  pixels of A touching only at a corner) each pixel's corner is cut by a quarter pixel, so that the rings
  stay simple and the parts keep the (4, 8) topology.

Both are built directly from the crack chains with integer arithmetic (coordinates are multiples of ¼).
:mod:`mrm.geometry.reconstruct` never returns them whole: it splices R0 into a ring only where its own
ring fails the exact check.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.grids import PixelSet
from mrm.reps.region import CrackChain, region_of

FloatArray = npt.NDArray[np.float64]

_STEP = np.array([[1, 0], [0, 1], [-1, 0], [0, -1]], dtype=np.int64)
_LEFT = np.roll(_STEP, -1, axis=0)  # the left normal of each step


def _turns(chain: CrackChain) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    # Pointels (n, 2) where the chain turns, with the codes before and after the turn.
    codes = chain.code_array().astype(np.int64)
    pts = chain.points()[:-1]
    prev = np.roll(codes, 1)
    turn = codes != prev
    return pts[turn], prev[turn], codes[turn]


def net_ring(chain: CrackChain) -> FloatArray:
    """The closed crack chain offset inward (to its left) by a quarter pixel: one vertex per turn.

    Returns
    -------
    ndarray of float64, shape (k, 2)
        The ring's vertices (not repeated at the end), in the chain's direction.
    """
    pts, prev, cur = _turns(chain)
    q = 4 * pts - 2 + _LEFT[prev] + _LEFT[cur]  # quarter-pixel units
    return q / 4.0


def staircase_ring(chain: CrackChain, pinched: set[tuple[int, int]] | None = None) -> FloatArray:
    """The crack chain as a polygon ring (its turning pointels).

    The corners at ``pinched`` pointels are cut by a quarter pixel on each side.
    """
    pts, prev, cur = _turns(chain)
    out: list[FloatArray] = []
    base = pts - 0.5
    if not pinched:
        return base.astype(np.float64)
    for k in range(pts.shape[0]):
        p = (int(pts[k, 0]), int(pts[k, 1]))
        if p in pinched:
            out.append(base[k] - 0.25 * _STEP[prev[k]])
            out.append(base[k] + 0.25 * _STEP[cur[k]])
        else:
            out.append(base[k].astype(np.float64))
    return np.array(out, dtype=np.float64)


def _assemble(rings: Sequence[tuple[FloatArray, list[FloatArray]]]) -> Polygon | MultiPolygon:
    polys = [Polygon(shell, holes) for shell, holes in rings]
    if not polys:
        return Polygon()
    if len(polys) == 1:
        return polys[0]
    return MultiPolygon(polys)


def eroded_net(ps: PixelSet) -> Polygon | MultiPolygon:
    """R0(A): V(A) eroded by a quarter pixel, one polygon per 4-component, one hole per hole."""
    region = region_of(ps)
    return _assemble(
        [(net_ring(c.outer), [net_ring(h.boundary) for h in c.holes]) for c in region.components]
    )


def staircase(ps: PixelSet) -> Polygon | MultiPolygon:
    """V(A) as polygons (the crack rings), corners cut where two rings or one ring meet at a pointel."""
    region = region_of(ps)
    seen: Counter[tuple[int, int]] = Counter()
    for ch in region.boundary_chains:
        pts, _prev, _cur = _turns(ch)
        seen.update(map(tuple, pts.tolist()))
    pinched = {p for p, n in seen.items() if n > 1}
    return _assemble(
        [
            (staircase_ring(c.outer, pinched), [staircase_ring(h.boundary, pinched) for h in c.holes])
            for c in region.components
        ]
    )


def safety_net(ps: PixelSet, model: str = "standard") -> Polygon | MultiPolygon:
    """The trivial continuation of a model: :func:`staircase` for ``gauss``, :func:`eroded_net` otherwise."""
    if model == "gauss":
        return staircase(ps)
    return eroded_net(ps)
