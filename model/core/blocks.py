"""Grid sets on a grid k times coarser: k-block OR-pooling and k-sampling, in any dimension.

Two exact reductions of a grid set A, used by DSS_1/k of a pixel or voxel set when the grids are aligned
(:func:`mrm.ops.outcome.scaling_by_pixels`). Cell c of the coarse grid stands for
the block of k^n cells of A's grid ``k·c + s + [0, k − 1]^n`` (``s`` its first cell for c = 0); the
reductions are

* :func:`or_pool`: ``{c : A meets the block of c}``;
* :func:`sample`: ``{c : k·c + s ∈ A}``.

Neither pads A to whole blocks nor makes a k^n array: pooling ORs along one axis at a time (the first, a
contiguous one, shrinks A k times before the others are read), with k slice ORs for small k and
``ufunc.reduceat`` beyond :data:`_POOL_SLICES_MAX_K` (α = 10⁻⁶ on one pixel must not make a 10⁶ × 10⁶ array).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, TypeVar

import numpy as np
import numpy.typing as npt

from mrm.core.grids import GridSet

__all__ = ["or_pool", "sample"]

_G = TypeVar("_G", bound="GridSet[Any, Any]")

#: Largest block side k pooled by k slice ORs; beyond it, ufunc.reduceat (k Python steps would dominate).
_POOL_SLICES_MAX_K = 32

BoolArray = npt.NDArray[np.bool_]


def sample(gs: _G, k: int, start: Sequence[int]) -> _G:
    """``{c : k·c + start ∈ gs}``: the cells of ``gs`` congruent to ``start`` modulo k, on the coarse grid.

    Parameters
    ----------
    gs : PixelSet or VoxelSet (any GridSet)
    k : int
        The block side, at least 1.
    start : sequence of int
        The cell of ``gs``'s grid that coarse cell 0 stands for, in coordinate order (x, y[, z]).
    """
    if gs.is_empty():
        return gs
    origin = gs.origin
    n = len(origin)
    # the mask's axes are in reverse coordinate order
    first = [(start[d] - origin[d]) % k for d in range(n)]
    sub = np.ascontiguousarray(gs.mask[tuple(slice(first[d], None, k) for d in reversed(range(n)))])
    return type(gs)(sub, tuple((origin[d] + first[d] - start[d]) // k for d in range(n)))


def or_pool(gs: _G, k: int, start: Sequence[int]) -> _G:
    """``{c : gs meets the block k·c + start + [0, k − 1]^n}``: a k-block OR-pooling of ``gs``.

    Parameters
    ----------
    gs : PixelSet or VoxelSet (any GridSet)
    k : int
        The block side, at least 1.
    start : sequence of int
        The first cell of coarse cell 0's block, in coordinate order (x, y[, z]).
    """
    if gs.is_empty():
        return gs
    if k == 1:
        return gs.translate(*(-int(v) for v in start))
    origin = gs.origin
    n = len(origin)
    coarse = [(origin[d] - start[d]) // k for d in range(n)]
    offsets = [(origin[d] - start[d]) - k * coarse[d] for d in range(n)]  # 0 ≤ offset < k
    out: BoolArray = gs.mask
    # Mask axis a holds coordinate n − 1 − a. The first axis (z, or the rows) first: its blocks are
    # contiguous, and what the later axes read is already k times smaller.
    for axis in range(n):
        out = _pool_axis(out, axis, k, offsets[n - 1 - axis])
    return type(gs)(out, tuple(coarse))


def _block_starts(m: int, offset: int, k: int) -> npt.NDArray[np.intp]:
    """Where the blocks of ``k`` cells start in ``range(m)`` when the first has ``offset`` cells before 0.

    0, then k − offset, 2k − offset, … below m (0 ≤ offset < k): ⌈(m + offset)/k⌉ blocks.
    """
    return np.concatenate(([0], np.arange(k - offset, m, k))).astype(np.intp)


def _pool_axis(a: BoolArray, axis: int, k: int, offset: int) -> BoolArray:
    """OR the blocks of ``k`` entries of ``a`` along ``axis``, the first block having ``offset`` before 0."""
    m = a.shape[axis]
    if k > _POOL_SLICES_MAX_K:
        return np.logical_or.reduceat(a, _block_starts(m, offset, k), axis=axis)
    blocks = -(-(m + offset) // k)
    shape = list(a.shape)
    shape[axis] = blocks
    out = np.zeros(shape, dtype=bool)

    def take(lo: int, hi: int) -> tuple[slice, ...]:
        return (slice(None),) * axis + (slice(lo, hi),)

    # The whole blocks, a view of a split into (…, blocks, k, …) (splitting an axis never copies): k slice
    # ORs, ten times faster than .any(axis) and than ufunc.reduceat for small k.
    head = min((k - offset) % k, m)  # the cells of a partial first block
    whole = (m - head) // k
    b0 = 1 if head else 0
    if whole:
        mid = a[take(head, head + whole * k)]
        split = mid.reshape((*a.shape[:axis], whole, k, *a.shape[axis + 1 :]))
        cells = np.moveaxis(split, axis + 1, 0)  # cells[i]: the i-th cell of every block (a view)
        dst = out[take(b0, b0 + whole)]
        np.copyto(dst, cells[0])
        for i in range(1, k):
            dst |= cells[i]
    if head:
        np.any(a[take(0, head)], axis=axis, out=out[take(0, 1)].squeeze(axis))
    tail = m - head - whole * k
    if tail > 0:
        np.any(a[take(m - tail, m)], axis=axis, out=out[take(blocks - 1, blocks)].squeeze(axis))
    return out
