"""Phase 4 of R: pruning, every vertex dropped whose neighbours one valid edge can join (:func:`prune_ring`).

One sweep of exact edge checks (:func:`._check.edge_ok`) that adds no point. :func:`._kernels.finish_all`
prunes every verified ring before merging it (:mod:`._merge`), a spliced ring (:mod:`._splice`) likewise,
and a ring that failed to verify once without the final check, since a redundant vertex (three in one piece
crossing) may be what failed. It needs the exact checks only, none of the merge-point search, hence a module
of its own.
"""

from __future__ import annotations

import numpy as np

from mrm.geometry._jit import njit
from mrm.geometry.reconstruct._check import edge_ok, verify_ring


@njit(cache=True)
def prune_ring(
    ix: np.ndarray,
    iy: np.ndarray,
    vt: np.ndarray,
    vs: np.ndarray,
    vl: np.ndarray,
    rect: np.ndarray,
    gp: np.ndarray,
    gq: np.ndarray,
    gdir: np.ndarray,
    sc: int,
    check: bool = True,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # pragma: no cover
    """Drop every vertex whose two neighbours can be joined by a valid edge (exact), in one sweep.

    With ``check``, the original ring is kept if the result does not verify; without, the pruned ring is
    returned as it is (used to repair a ring that failed: the caller verifies).
    """
    n = gdir.size
    m = ix.size
    keep = np.ones(m, np.bool_)
    left = m
    for i in range(m):
        if left <= 3:
            break
        p = (i - 1) % m
        while not keep[p]:
            p = (p - 1) % m
        q = (i + 1) % m
        while not keep[q]:
            q = (q + 1) % m
        tp = vt[p]
        tq = vt[q]
        if p > i:
            tp -= n  # p is in the previous lap
        if q < i:
            tq += n  # q is in the next lap
        if tq - tp >= n:
            continue
        if edge_ok(ix[p], iy[p], tp, ix[q], iy[q], tq, gp, gq, gdir, sc):
            keep[i] = False
            left -= 1
    if left == m:
        return ix, iy, vt, vs, vl
    ox = np.empty(left, np.int64)
    oy = np.empty(left, np.int64)
    ot = np.empty(left, np.int64)
    os_ = np.empty(left, np.int64)
    ol = np.empty(left, np.int64)
    j = 0
    for i in range(m):
        if keep[i]:
            ox[j] = ix[i]
            oy[j] = iy[i]
            ot[j] = vt[i]
            os_[j] = vs[i]
            ol[j] = vl[i]
            j += 1
    if not check:
        return ox, oy, ot, os_, ol
    bad = np.zeros(left, np.bool_)
    if verify_ring(ox, oy, ot, rect, gp, gq, gdir, sc, bad):
        return ox, oy, ot, os_, ol
    return ix, iy, vt, vs, vl
