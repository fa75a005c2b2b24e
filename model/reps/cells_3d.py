"""Cells of a label volume: regions, 2-cells, 1-cells, 0-cells and the region adjacency graph.

Reference: docs/design.md §11 (region representation, label volumes); the 2D counterpart is
:mod:`mrm.reps.cells`. The space outside the label array carries label 0 (background), and 0 counts as a
label like any other.

- A **region** is a 6-connected component of equal non-zero labels.
- A boundary square separates two 6-adjacent voxels with different labels. A **1-cell** is a maximal set of
  *junction* linels (unit edges around which three or four of the four squares are boundary squares: three or
  more labels meet there, or two meet diagonally) joined at pointels where exactly two junction linels with
  the same labels meet; it is closed when it meets no 0-cell.
- A **0-cell** is a pointel where the junction linels do not simply pass through: one, three or more of them
  meet there, or two with different labels.
- A **2-cell** is a maximal patch of boundary squares between the same two labels, joined across linels
  around which exactly two squares are boundary squares (so a 2-cell never crosses a 1-cell). Each square is
  oriented from the voxel with the larger label towards the smaller one (outward from a labelled region next
  to the background).
- The **adjacency** graph links two labels whose voxels are 6-adjacent.

Points are in world coordinates: voxel (x, y, z) is ``labels[z − z0, y − y0, x − x0]``; linel (b, x, y, z)
runs along axis b (0 = x, 1 = y, 2 = z) through the corner shared by voxels (x, y, z), +e_c, +e_d and
+e_c + e_d ((b, c, d) cyclic), from coordinate p_b − ½ to p_b + ½ on its axis; pointel (x, y, z) is the corner
(x + ½, y + ½, z + ½).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from mrm.core.limits import check_pixels
from mrm.geometry.topology.cells_3d import boundary_cells, label_regions_3d
from mrm.reps.region_3d import Origin3, Region3D, region_3d_of

IntArray = npt.NDArray[np.int64]
_AXIS = np.eye(3, dtype=np.int64)


@dataclass(frozen=True, slots=True)
class LabelRegion3D:
    """A region: a 6-connected component of one non-zero label, with its first voxel in raster order."""

    label: int
    voxels: int
    first: tuple[int, int, int]


@dataclass(frozen=True, slots=True)
class TwoCell:
    """A maximal patch of boundary squares between two labels.

    Attributes
    ----------
    high, low : int
        The labels on each side; ``high > low``.
    voxels : ndarray of int64, shape (n, 3)
        For each square, the (x, y, z) of its voxel with label ``high``.
    directions : ndarray of uint8, shape (n,)
        The index in :data:`mrm.geometry.topology.surfels.DIRS` of the normal pointing to the ``low`` voxel.
    """

    high: int
    low: int
    voxels: IntArray = field(repr=False, compare=False)
    directions: npt.NDArray[np.uint8] = field(repr=False, compare=False)

    def __len__(self) -> int:
        return int(self.directions.size)


@dataclass(frozen=True, slots=True)
class OneCell3D:
    """A maximal chain of junction linels with the same labels around them.

    Attributes
    ----------
    labels : tuple of int
        The distinct labels around its linels, sorted.
    linels : ndarray of int64, shape (n, 4)
        (axis, x, y, z) of each linel, in raster order of (z, y, x) then axis.
    closed : bool
        True when it meets no 0-cell (a loop).
    """

    labels: tuple[int, ...]
    linels: IntArray = field(repr=False, compare=False)
    closed: bool


@dataclass(frozen=True, slots=True)
class ZeroCell3D:
    """A pointel where 1-cells meet or end: the corner (x + ½, y + ½, z + ½), and the labels around it."""

    point: tuple[int, int, int]
    labels: tuple[int, ...]


@dataclass(frozen=True, slots=True)
class Cells3D:
    """The cell decomposition of a label volume (:func:`cells_3d_of`).

    Attributes
    ----------
    regions : tuple of LabelRegion3D
        In raster order (z, y, x) of their first voxel.
    two_cells : tuple of TwoCell
        In raster order of their first square.
    one_cells : tuple of OneCell3D
        In raster order of their first linel.
    zero_cells : tuple of ZeroCell3D
        Sorted by (z, y, x).
    adjacency : tuple of (int, int)
        The sorted pairs (a, b), a < b, of 6-adjacent labels (0 included).
    """

    regions: tuple[LabelRegion3D, ...]
    two_cells: tuple[TwoCell, ...]
    one_cells: tuple[OneCell3D, ...]
    zero_cells: tuple[ZeroCell3D, ...]
    adjacency: tuple[tuple[int, int], ...]

    def neighbours(self, label: int) -> tuple[int, ...]:
        """The labels adjacent to ``label``, sorted."""
        return tuple(sorted({b if a == label else a for a, b in self.adjacency if label in (a, b)}))


def _find(parent: list[int], a: int) -> int:
    while parent[a] != a:
        parent[a] = parent[parent[a]]
        a = parent[a]
    return a


def cells_3d_of(labels: npt.ArrayLike, origin: Origin3 = (0, 0, 0), limit: int | None = None) -> Cells3D:
    """Split the boundaries of a label volume into 2-, 1- and 0-cells, and build its adjacency graph.

    Parameters
    ----------
    labels : array_like of int, shape (nz, ny, nx)
        The label volume; label 0 (and everything outside the array) is the background.
    origin : tuple of int
        (x0, y0, z0).
    limit : int, optional
        Refuse a volume of more voxels than this (:func:`mrm.core.limits.check_pixels`).

    Returns
    -------
    Cells3D
        See the module docstring for the definitions.
    """
    lab = np.asarray(labels)
    if lab.ndim != 3:
        raise ValueError(f"a label volume must be 3-D, got shape {lab.shape}")
    check_pixels(int(lab.size), limit, "the label volume")
    if lab.size == 0:
        return Cells3D((), (), (), (), ())
    lab = np.ascontiguousarray(lab, dtype=np.int32)
    o = np.array(origin, np.int64)
    _nz, ny, nx = lab.shape
    rl, rv, rf = label_regions_3d(lab)
    regions = tuple(
        LabelRegion3D(
            int(a),
            int(n),
            (int(f % nx) + int(o[0]), int(f // nx % ny) + int(o[1]), int(f // (nx * ny)) + int(o[2])),
        )
        for a, n, f in zip(rl.tolist(), rv.tolist(), rf.tolist(), strict=True)
    )
    bc = boundary_cells(lab)
    pad = np.pad(lab, 1)
    shift = o - 1  # padded index → world
    # ---- 2-cells
    axis = bc.squares[:, 0]
    v = bc.squares[:, 1:]
    w = v + _AXIS[axis]
    la = pad[v[:, 2], v[:, 1], v[:, 0]].astype(np.int64)
    lb = pad[w[:, 2], w[:, 1], w[:, 0]].astype(np.int64)
    a_high = la > lb
    high_vox = np.where(a_high[:, None], v, w) + shift
    direction = (2 * axis + np.where(a_high, 0, 1)).astype(np.uint8)
    order = np.argsort(bc.patch, kind="stable")
    bounds = np.searchsorted(bc.patch[order], np.arange(bc.n_patches + 1))
    two = []
    for t in range(bc.n_patches):
        idx = order[bounds[t] : bounds[t + 1]]
        s0 = idx[0]
        two.append(TwoCell(int(max(la[s0], lb[s0])), int(min(la[s0], lb[s0])), high_vox[idx], direction[idx]))
    pairs = np.unique(np.minimum(la, lb) << 32 | np.maximum(la, lb)) if la.size else np.zeros(0, np.int64)
    adjacency = tuple((int(p >> 32), int(p & 0xFFFFFFFF)) for p in pairs.tolist())
    # ---- 1-cells and 0-cells from the junction linels
    jl = bc.linels
    m = len(jl)
    sets = [tuple(sorted(set(r))) for r in bc.linel_labels.tolist()]
    ends: dict[tuple[int, int, int], list[int]] = {}
    for t, (b, i, j, k) in enumerate(jl.tolist()):
        q = (i, j, k)
        lo = (i - (b == 0), j - (b == 1), k - (b == 2))
        ends.setdefault(lo, []).append(t)
        ends.setdefault(q, []).append(t)
    parent = list(range(m))
    zero_points = []
    for q, ts in ends.items():
        if len(ts) == 2 and sets[ts[0]] == sets[ts[1]]:
            ra, rb = _find(parent, ts[0]), _find(parent, ts[1])
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
        else:
            zero_points.append(q)
    on_zero = set(zero_points)
    groups: dict[int, list[int]] = {}
    for t in range(m):
        groups.setdefault(_find(parent, t), []).append(t)
    one = []
    for root in sorted(groups):  # roots are the first linel of each group (the smaller index stays the root)
        ts = groups[root]
        closed = not any(
            p in on_zero
            for t in ts
            for p in (
                (
                    int(jl[t, 1]) - (jl[t, 0] == 0),
                    int(jl[t, 2]) - (jl[t, 0] == 1),
                    int(jl[t, 3]) - (jl[t, 0] == 2),
                ),
                (int(jl[t, 1]), int(jl[t, 2]), int(jl[t, 3])),
            )
        )
        rows = jl[ts].copy()
        rows[:, 1:] += shift
        one.append(OneCell3D(sets[root], rows, closed))
    zero = []
    for q in sorted(zero_points, key=lambda p: (p[2], p[1], p[0])):
        i, j, k = q
        around = pad[k : k + 2, j : j + 2, i : i + 2]
        zero.append(
            ZeroCell3D(
                (i + int(shift[0]), j + int(shift[1]), k + int(shift[2])),
                tuple(int(x) for x in np.unique(around)),
            )
        )
    return Cells3D(regions, tuple(two), tuple(one), tuple(zero), adjacency)


def region_3d_of_labels(labels: npt.ArrayLike, origin: Origin3 = (0, 0, 0)) -> dict[int, Region3D]:
    """Return the region representation of each non-zero label of a label volume, by increasing label."""
    lab = np.asarray(labels)
    if lab.ndim != 3:
        raise ValueError(f"a label volume must be 3-D, got shape {lab.shape}")
    return {int(v): region_3d_of(lab == v, origin) for v in np.unique(lab).tolist() if v != 0}
