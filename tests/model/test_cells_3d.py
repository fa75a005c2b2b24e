"""Cells of label volumes: regions, 2-cells, 1-cells, 0-cells, adjacency (docs/design.md §11).

Checked against a plain-Python enumeration of the squares and linels of the padded volume, and the regions
against ``scipy.ndimage.label``.
"""

from __future__ import annotations

import itertools

import numpy as np
import scipy.ndimage as ndi
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.geometry.topology.surfels import DIRS
from mrm.reps.cells_3d import cells_3d_of, region_3d_of_labels

ORIGIN = (4, -2, 9)
E = [(1, 0, 0), (0, 1, 0), (0, 0, 1)]


def _add(p: tuple[int, ...], q: tuple[int, ...]) -> tuple[int, int, int]:
    return (p[0] + q[0], p[1] + q[1], p[2] + q[2])


class Brute:
    """Squares, linels, patches and junctions of a label volume, by enumeration (world coordinates)."""

    def __init__(self, lab: np.ndarray) -> None:
        nz, ny, nx = lab.shape
        x0, y0, z0 = ORIGIN

        def at(p: tuple[int, int, int]) -> int:
            i, j, k = p[0] - x0, p[1] - y0, p[2] - z0
            return int(lab[k, j, i]) if 0 <= i < nx and 0 <= j < ny and 0 <= k < nz else 0

        self.at = at
        box = list(
            itertools.product(
                range(x0 - 1, x0 + nx + 1), range(y0 - 1, y0 + ny + 1), range(z0 - 1, z0 + nz + 1)
            )
        )
        # square (n, v): between v and v + e_n
        self.squares = {(n, v) for v in box for n in range(3) if at(v) != at(_add(v, E[n]))}
        parent = {s: s for s in self.squares}

        def find(s: tuple) -> tuple:  # type: ignore[type-arg]
            while parent[s] != s:
                s = parent[s]
            return s

        self.junction: dict[tuple[int, tuple[int, int, int]], tuple[int, ...]] = {}
        for p in box:
            for b in range(3):
                c, d = (b + 1) % 3, (b + 2) % 3
                around = [(c, p), (d, _add(p, E[c])), (c, _add(p, E[d])), (d, p)]
                on = [s for s in around if s in self.squares]
                if len(on) == 2:
                    parent[find(on[0])] = find(on[1])
                elif len(on) >= 3:
                    vox = [p, _add(p, E[c]), _add(_add(p, E[c]), E[d]), _add(p, E[d])]
                    self.junction[(b, p)] = tuple(sorted({at(v) for v in vox}))
        groups: dict[tuple, set] = {}  # type: ignore[type-arg]
        for s in self.squares:
            groups.setdefault(find(s), set()).add(s)
        self.patches = {frozenset(g) for g in groups.values()}


def check(lab: np.ndarray) -> None:
    cells = cells_3d_of(lab, ORIGIN)
    ref = Brute(lab)
    # 2-cells: the same partition of the boundary squares, each between its two labels, oriented high → low
    got = set()
    for t in cells.two_cells:
        assert t.high > t.low
        squares = set()
        for v, d in zip(t.voxels.tolist(), t.directions.tolist(), strict=True):
            w = _add(tuple(v), tuple(DIRS[d].tolist()))
            assert ref.at(tuple(v)) == t.high and ref.at(w) == t.low  # type: ignore[arg-type]
            n = d // 2
            squares.add((n, tuple(v) if d % 2 == 0 else w))
        assert len(squares) == len(t)
        got.add(frozenset(squares))
    assert got == ref.patches
    # adjacency
    pairs = {tuple(sorted((ref.at(v), ref.at(_add(v, E[n]))))) for n, v in ref.squares}
    assert set(cells.adjacency) == pairs and list(cells.adjacency) == sorted(cells.adjacency)
    # 1-cells: the junction linels, each cell with one label set; 0-cells where chains do not pass through
    linels = {}
    for o in cells.one_cells:
        for b, x, y, z in o.linels.tolist():
            assert (b, (x, y, z)) not in linels
            linels[(b, (x, y, z))] = o
            assert ref.junction[(b, (x, y, z))] == o.labels
    assert set(linels) == set(ref.junction)
    ends: dict[tuple[int, int, int], list[tuple[int, tuple[int, int, int]]]] = {}
    for b, p in ref.junction:
        ends.setdefault(p, []).append((b, p))
        ends.setdefault(_add(p, tuple(-e for e in E[b])), []).append((b, p))
    zeros = {q for q, ls in ends.items() if len(ls) != 2 or ref.junction[ls[0]] != ref.junction[ls[1]]}
    assert {z.point for z in cells.zero_cells} == zeros
    for q, ls in ends.items():
        if q not in zeros:
            assert linels[ls[0]] is linels[ls[1]]
    for o in cells.one_cells:
        assert o.closed == (not any(q in zeros for q, ls in ends.items() for lk in ls if linels[lk] is o))
    # regions: scipy, per label
    expected = sorted(
        (int(np.flatnonzero((comp == c).ravel())[0]), int(v))
        for v in np.unique(lab)
        if v != 0
        for comp, n in [ndi.label(lab == v, ndi.generate_binary_structure(3, 1))]
        for c in range(1, n + 1)
    )
    _nz, ny, nx = lab.shape
    got_regions = [
        ((r.first[2] - ORIGIN[2]) * ny * nx + (r.first[1] - ORIGIN[1]) * nx + r.first[0] - ORIGIN[0], r.label)
        for r in cells.regions
    ]
    assert got_regions == expected
    for r in cells.regions:
        assert r.voxels > 0


def test_two_blocks_side_by_side() -> None:
    lab = np.zeros((2, 2, 4), np.int32)
    lab[:, :, :2] = 1
    lab[:, :, 2:] = 2
    check(lab)
    cells = cells_3d_of(lab, ORIGIN)
    assert [(t.high, t.low, len(t)) for t in cells.two_cells] == [(1, 0, 20), (2, 0, 20), (2, 1, 4)]
    assert [(o.labels, len(o.linels), o.closed) for o in cells.one_cells] == [((0, 1, 2), 8, True)]
    assert cells.zero_cells == () and cells.adjacency == ((0, 1), (0, 2), (1, 2))
    assert cells.neighbours(1) == (0, 2)


def test_four_columns_meet_along_a_line_ending_in_two_zero_cells() -> None:
    lab = np.zeros((2, 2, 2), np.int32)
    lab[:, 0, 0], lab[:, 0, 1], lab[:, 1, 0], lab[:, 1, 1] = 1, 2, 3, 4
    check(lab)
    cells = cells_3d_of(lab, (0, 0, 0))
    assert [z.point for z in cells.zero_cells] == [(0, 0, -1), (0, 0, 1)]
    assert all(z.labels == (0, 1, 2, 3, 4) for z in cells.zero_cells)
    assert next(o for o in cells.one_cells if o.labels == (1, 2, 3, 4)).linels.shape == (2, 4)


def test_diagonal_pinch_of_two_labels_is_a_junction() -> None:
    lab = np.zeros((1, 2, 2), np.int32)
    lab[0, 0, 0] = lab[0, 1, 1] = 1
    lab[0, 0, 1] = lab[0, 1, 0] = 2
    check(lab)


def test_region_per_label() -> None:
    lab = np.zeros((3, 3, 3), np.int32)
    lab[0, 0, 0] = lab[2, 2, 2] = 5
    lab[1] = 7
    regs = region_3d_of_labels(lab, ORIGIN)
    assert sorted(regs) == [5, 7]
    assert regs[5].n_components == 2 and regs[7].n_components == 1


@settings(max_examples=40)
@given(
    st.integers(0, 2**32 - 1),
    st.tuples(st.integers(1, 4), st.integers(1, 4), st.integers(1, 4)),
    st.integers(1, 4),
)
def test_random_label_volumes(seed: int, shape: tuple[int, int, int], n: int) -> None:
    lab = np.random.default_rng(seed).integers(0, n + 1, shape).astype(np.int32)
    check(lab)
