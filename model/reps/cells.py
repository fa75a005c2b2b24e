"""Cells of a label map: 0-cells, 1-cells and the region adjacency graph (docs/design.md §4).

The plane outside the label array carries label 0 (background), and 0 counts as a label like any other.

- A boundary linel separates two 4-adjacent pixels with different labels.
- A **0-cell** is a pointel where three or more boundary linels meet. That is every pointel where three or
  four labels meet, and also the pointel where only two labels meet *diagonally* (a 2×2 checkerboard
  ``a b / b a``): there the boundary between the two labels pinches to a point, exactly like at a junction,
  so it is a 0-cell too. A pointel where two labels meet any other way has two boundary linels and lies
  inside a 1-cell.
- A **1-cell** is a maximal chain of boundary linels between the same two labels that does not pass through
  a 0-cell. It is oriented with the larger label on its left (so a labelled region next to the background
  has it on the left, counter-clockwise like an outer boundary). An open 1-cell runs from a 0-cell to a
  0-cell (possibly the same one); a loop with no 0-cell on it is one closed 1-cell, starting at its
  lowest-leftmost pointel.
- The **adjacency** graph links two labels whose pixels are 4-adjacent (share a linel).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mrm.core import limits
from mrm.core.errors import LimitError
from mrm.core.gc_pause import paused_gc
from mrm.core.grids import LabelMap, PixelSet
from mrm.geometry.topology.cracks import trace_cells
from mrm.geometry.topology.labeling import group_by_label
from mrm.reps.region import CrackChain, Region, region_of


@dataclass(frozen=True, slots=True)
class ZeroCell:
    """A pointel where boundaries meet.

    Attributes
    ----------
    point : tuple of int
        The pointel (i, j), the Euclidean point (i − ½, j − ½).
    labels : tuple of int
        The distinct labels of the four pixels around it, sorted (2 for a two-label diagonal pinch).
    """

    point: tuple[int, int]
    labels: tuple[int, ...]


@dataclass(frozen=True, slots=True)
class OneCell:
    """A maximal boundary chain between two labels.

    Attributes
    ----------
    left, right : int
        The labels on each side; ``left > right``.
    chain : CrackChain
        The linels, with ``left`` on the left. Closed (``chain.is_closed()``) when it meets no 0-cell.
    """

    left: int
    right: int
    chain: CrackChain


@dataclass(frozen=True, slots=True)
class Cells:
    """The cell decomposition of a label map's boundaries.

    Attributes
    ----------
    one_cells : tuple of OneCell
        Sorted by the start pointel (y then x) and then the first code.
    zero_cells : tuple of ZeroCell
        Sorted by (y, x).
    adjacency : tuple of (int, int)
        The sorted pairs (a, b), a < b, of 4-adjacent labels (0 included).
    """

    one_cells: tuple[OneCell, ...]
    zero_cells: tuple[ZeroCell, ...]
    adjacency: tuple[tuple[int, int], ...]

    def neighbours(self, label: int) -> tuple[int, ...]:
        """The labels adjacent to ``label``, sorted."""
        return tuple(sorted({b if a == label else a for a, b in self.adjacency if label in (a, b)}))


def cells_of(lm: LabelMap) -> Cells:
    """Split the boundaries of a label map into 0-cells and 1-cells, and build its adjacency graph.

    Parameters
    ----------
    lm : LabelMap
        The label map; label 0 (and everything outside the array) is the background.

    Returns
    -------
    Cells
        See the module docstring for the definitions.
    """
    lab = lm.labels
    if lab.size == 0:
        return Cells((), (), ())
    x0, y0 = lm.origin
    cc = trace_cells(lab)
    # 0-cells, with the labels around them (read from the padded array: pointel (i, j) of the array is the
    # lower-left corner of padded pixel (i + 1, j + 1)).
    pad = np.pad(lab, 1)
    zi, zj = cc.zx + 1, cc.zy + 1
    around = np.stack([pad[zj - 1, zi - 1], pad[zj - 1, zi], pad[zj, zi - 1], pad[zj, zi]], axis=1)
    around.sort(axis=1)
    distinct = np.ones(around.shape, bool)
    distinct[:, 1:] = around[:, 1:] != around[:, :-1]
    # 1-cells in canonical order: by start (y, x), then first code.
    n = cc.sx.size
    first_code = cc.codes[cc.off[:-1]] if n else np.zeros(0, np.uint8)
    order = np.lexsort((first_code, cc.sx, cc.sy)).tolist()
    text = (cc.codes + np.uint8(48)).tobytes().decode("ascii")
    off = cc.off.tolist()
    sx = (cc.sx + x0).tolist()
    sy = (cc.sy + y0).tolist()
    left = cc.left.tolist()
    right = cc.right.tolist()
    chain = CrackChain._trusted
    with paused_gc():
        zero = tuple(
            ZeroCell((x, y), tuple(v for v, keep in zip(a, d, strict=True) if keep))
            for x, y, a, d in zip(
                (cc.zx + x0).tolist(), (cc.zy + y0).tolist(), around.tolist(), distinct.tolist(), strict=True
            )
        )
        ones = tuple(
            OneCell(left[k], right[k], chain((sx[k], sy[k]), text[off[k] : off[k + 1]])) for k in order
        )
    pairs = np.unique(cc.right.astype(np.int64) << 32 | cc.left.astype(np.int64))
    adjacency = tuple((int(p >> 32), int(p & 0xFFFFFFFF)) for p in pairs)
    return Cells(ones, zero, adjacency)


def region_of_labels(lm: LabelMap) -> dict[int, Region]:
    """Return the region representation of each non-zero label of a label map.

    Parameters
    ----------
    lm : LabelMap
        The label map.

    Returns
    -------
    dict
        ``{label: region_of(pixels of that label)}`` for every non-zero label, in increasing order.
    """
    lab = lm.labels
    if lab.size == 0:
        return {}
    x0, y0 = lm.origin
    w = lab.shape[1]
    out: dict[int, Region] = {}
    for v, idx in zip(*group_by_label(lab), strict=True):
        if v == 0:
            continue
        rows, cols = idx // w, idx % w
        r0, c0 = int(rows[0]), int(cols.min())  # indices are increasing: rows[0] is the lowest row
        m = np.zeros((int(rows[-1]) - r0 + 1, int(cols.max()) - c0 + 1), dtype=bool)
        m[rows - r0, cols - c0] = True
        out[v] = region_of(PixelSet(m, (x0 + c0, y0 + r0)))
    return out


@dataclass(frozen=True, slots=True)
class CellCounts:
    """How many cells a label map has (what :func:`cells_of` would list), and its regions.

    Attributes
    ----------
    regions : int
        4-connected components of one non-zero label.
    one_cells, zero_cells, adjacencies : int
        ``len(cells_of(lm).one_cells)``, ``len(….zero_cells)``, ``len(….adjacency)``.
    """

    regions: int
    one_cells: int
    zero_cells: int
    adjacencies: int


def cell_counts(lm: LabelMap, budget: int | None = None) -> CellCounts:
    """Count the regions and cells of a label map without building them (a summary, ``mrm info``).

    :func:`cells_of` makes a Python object per cell — gigabytes for a 2000² checkerboard of 8·10⁶ 1-cells,
    held in a 38 KB project. This counts with arrays, a few dozen bytes a pixel:

    * a pointel is a 0-cell where three or four boundary linels meet (a diagonal pinch has four);
    * each open 1-cell has its two ends at 0-cells: their number is half the linels at 0-cells;
    * a closed 1-cell is a loop of boundary linels through no 0-cell: on the doubled grid (pointels, linels
      and pixels as cells), the 4-connected components of boundary linels and the pointels of two boundary
      linels that touch no 0-cell.

    Parameters
    ----------
    lm : LabelMap
    budget : int, optional
        Bytes the counting may take (estimated from the pixels and boundary linels before the work).

    Raises
    ------
    LimitError
        When the estimate exceeds ``budget``.
    """
    from mrm.geometry.topology.labeling import label, label_regions

    lab = lm.labels
    if lab.size == 0:
        return CellCounts(0, 0, 0, 0)
    h, w = lab.shape
    if budget is not None and limits.LABEL_COUNT_BYTES_PER_PIXEL * lab.size > budget:
        # The pixels alone are over the budget: refused before the padded copy and the linel masks below
        # (210 MB for a 6614² map, more than the summary it would spare).
        raise LimitError(
            f"counting the cells of a {w}×{h} label map would take more than "
            f"{(limits.LABEL_COUNT_BYTES_PER_PIXEL * lab.size) >> 20} MB, more than {budget >> 20} MB"
        )
    p = np.pad(lab, 1)  # the background around the array
    dv = p[:, 1:] != p[:, :-1]  # (h+2, w+1): the linel between p[r, c] and p[r, c+1]
    dh = p[1:, :] != p[:-1, :]  # (h+1, w+2): the linel between p[r, c] and p[r+1, c]
    if budget is not None:
        linels = int(np.count_nonzero(dv)) + int(np.count_nonzero(dh))
        cost = limits.LABEL_COUNT_BYTES_PER_PIXEL * lab.size + limits.LABEL_COUNT_BYTES_PER_LINEL * linels
        if cost > budget:
            raise LimitError(
                f"counting the cells of a {w}×{h} label map with {linels} boundary linels would take about "
                f"{cost >> 20} MB, more than {budget >> 20} MB"
            )
    regions = len(label_regions(lab).label)
    pairs = np.unique(
        np.concatenate(
            [
                _pair_codes(p[:, 1:][dv], p[:, :-1][dv]),
                _pair_codes(p[1:, :][dh], p[:-1, :][dh]),
            ]
        )
    )
    # Pointel (i, j), 0 ≤ i ≤ h, 0 ≤ j ≤ w: the corner between rows i, i+1 and columns j, j+1 of p.
    deg = dv[:-1, :].astype(np.uint8) + dv[1:, :] + dh[:, :-1] + dh[:, 1:]
    zero = deg >= 3
    open_cells = int(deg[zero].sum(dtype=np.int64)) // 2
    # The doubled grid: pointel (i, j) at (2i, 2j); the vertical linel between p[r, c] and p[r, c+1] joins
    # pointels (r-1, c) and (r, c), at (2r-1, 2c); the horizontal one between p[r, c] and p[r+1, c] joins
    # (r, c-1) and (r, c), at (2r, 2c-1). 0-cells are left out, so the chains end next to them.
    g = np.zeros((2 * h + 1, 2 * w + 1), dtype=np.uint8)
    g[::2, ::2] = deg == 2
    g[1::2, ::2] = dv[1 : h + 1, :]
    g[::2, 1::2] = dh[:, 1 : w + 1]
    chains, n = label(g, connectivity=4)
    del g
    near = np.zeros(chains.shape, dtype=bool)  # the linels at a 0-cell
    zi, zj = np.nonzero(zero)
    for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1)):
        i, j = 2 * zi + di, 2 * zj + dj
        ok = (i >= 0) & (i <= 2 * h) & (j >= 0) & (j <= 2 * w)
        near[i[ok], j[ok]] = True
    touching = np.unique(chains[near])
    loops = n - int(np.count_nonzero(touching))
    return CellCounts(regions, open_cells + loops, int(np.count_nonzero(zero)), len(pairs))


def _pair_codes(a: npt.NDArray[np.int32], b: npt.NDArray[np.int32]) -> npt.NDArray[np.int64]:
    """One int64 per unordered pair of labels (labels are non-negative int32)."""
    lo, hi = np.minimum(a, b).astype(np.int64), np.maximum(a, b).astype(np.int64)
    codes: npt.NDArray[np.int64] = (lo << 32) | hi
    return codes
