"""Cells of label maps: 1-cells, 0-cells and adjacency against brute-force scans of the definitions."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from mrm.core.grids import LabelMap, PixelSet
from mrm.reps.cells import Cells, OneCell, ZeroCell, cells_of, region_of_labels
from mrm.reps.region import CrackChain, fill, region_of


def padded(lm: LabelMap) -> tuple[np.ndarray, int, int]:
    """The label array with a ring of 0 around it, and the world pixel of padded[0, 0]."""
    x0, y0 = lm.origin
    return np.pad(lm.labels, 1), x0 - 1, y0 - 1


def linel_key(i: int, j: int, code: str) -> tuple[str, int, int]:
    """An unoriented name for the linel leaving pointel (i, j) with ``code``."""
    return {
        "0": ("h", i, j),
        "2": ("h", i - 1, j),
        "1": ("v", i, j),
        "3": ("v", i, j - 1),
    }[code]


def brute_force(lm: LabelMap) -> tuple[dict, set, set]:
    """Boundary linels {key: {labels}}, pointels with ≥ 3 labels or a 2-label diagonal, and adjacent pairs."""
    p, px, py = padded(lm)
    linels, zero, adj = {}, set(), set()
    h, w = p.shape
    for r in range(h):
        for c in range(w):
            if r > 0 and p[r, c] != p[r - 1, c]:  # bottom edge of pixel (c, r): from pointel (c, r) East
                linels[("h", c + px, r + py)] = {int(p[r, c]), int(p[r - 1, c])}
            if c > 0 and p[r, c] != p[r, c - 1]:  # left edge: from pointel (c, r) North
                linels[("v", c + px, r + py)] = {int(p[r, c]), int(p[r, c - 1])}
            if r > 0 and c > 0:
                bl, br, tl, tr = p[r - 1, c - 1], p[r - 1, c], p[r, c - 1], p[r, c]
                if len({bl, br, tl, tr}) >= 3 or (bl == tr and br == tl and bl != br):
                    zero.add((c + px, r + py))
    for labels in linels.values():
        adj.add(tuple(sorted(labels)))
    return linels, zero, adj


def label_at(lm: LabelMap, pts: np.ndarray) -> list[int]:
    p, px, py = padded(lm)
    out = []
    for x, y in pts.tolist():
        r, c = y - py, x - px
        out.append(int(p[r, c]) if 0 <= r < p.shape[0] and 0 <= c < p.shape[1] else 0)
    return out


def check_cells(lm: LabelMap) -> Cells:
    cells = cells_of(lm)
    linels, zero, adj = brute_force(lm)
    assert {z.point for z in cells.zero_cells} == zero
    assert [z.point for z in cells.zero_cells] == sorted(zero, key=lambda q: (q[1], q[0]))
    for z in cells.zero_cells:
        i, j = z.point
        around = label_at(lm, np.array([[i - 1, j - 1], [i, j - 1], [i - 1, j], [i, j]]))
        assert z.labels == tuple(sorted(set(around)))
    assert set(cells.adjacency) == adj and list(cells.adjacency) == sorted(adj)
    walked = []
    for oc in cells.one_cells:
        ch = oc.chain
        assert oc.left > oc.right and len(ch) > 0
        assert set(label_at(lm, ch.left_pixels())) == {oc.left}
        assert set(label_at(lm, ch.right_pixels())) == {oc.right}
        pts = [tuple(q) for q in ch.points().tolist()]
        walked += [linel_key(i, j, c) for (i, j), c in zip(pts, ch.codes, strict=False)]
        # Maximal: only the ends may be 0-cells, and an open cell ends at 0-cells on both sides.
        assert not any(q in zero for q in pts[1:-1])
        if pts[0] in zero:
            assert pts[-1] in zero
        else:  # a closed loop with no 0-cell, from its lowest-leftmost pointel
            assert ch.is_closed() and not any(q in zero for q in pts)
            assert ch.start == min(pts, key=lambda q: (q[1], q[0]))
    # The 1-cells partition the boundary linels.
    assert len(walked) == len(set(walked)) and set(walked) == set(linels)
    keys = [(oc.chain.start[1], oc.chain.start[0], oc.chain.codes[0]) for oc in cells.one_cells]
    assert keys == sorted(keys)
    return cells


@st.composite
def label_maps(draw: st.DrawFn, max_side: int = 24) -> LabelMap:
    h, w = draw(st.integers(1, max_side)), draw(st.integers(1, max_side))
    n = draw(st.integers(1, 6))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    k = draw(st.integers(1, 4))
    coarse = rng.integers(0, n + 1, (-(-h // k), -(-w // k)))
    lab = np.kron(coarse, np.ones((k, k), np.int64))[:h, :w]
    noise = rng.random((h, w)) < draw(st.sampled_from([0.0, 0.05, 0.3]))
    lab[noise] = rng.integers(0, n + 1, int(noise.sum()))
    return LabelMap(lab, draw(st.tuples(st.integers(-20, 20), st.integers(-20, 20))))


@settings(max_examples=200)
@given(label_maps())
def test_cells_of_random_label_maps(lm: LabelMap) -> None:
    check_cells(lm)


@settings(max_examples=200)
@given(arrays(np.int32, st.tuples(st.integers(1, 6), st.integers(1, 6)), elements=st.integers(0, 3)))
def test_cells_of_small_label_maps(lab: np.ndarray) -> None:
    check_cells(LabelMap(lab))


@settings(max_examples=40)
@given(label_maps(max_side=16))
def test_region_of_labels(lm: LabelMap) -> None:
    regions = region_of_labels(lm)
    assert sorted(regions) == lm.label_values()
    for v, reg in regions.items():
        assert fill(reg) == lm.pixel_set(v)
        assert reg == region_of(lm.pixel_set(v))


def test_empty_label_map() -> None:
    lm = LabelMap(np.zeros((3, 3), np.int32))
    assert cells_of(lm) == Cells((), (), ())
    assert region_of_labels(lm) == {}


def test_single_label_is_one_closed_cell() -> None:
    lm = LabelMap(np.full((2, 3), 7), (4, -1))
    cells = check_cells(lm)
    assert cells.zero_cells == ()
    assert cells.one_cells == (OneCell(7, 0, CrackChain((4, -1), "0001122233")),)
    assert cells.adjacency == ((0, 7),) and cells.neighbours(7) == (0,)


def test_two_labels_side_by_side() -> None:
    lm = LabelMap(np.array([[1, 2]]))
    cells = check_cells(lm)
    # Labels 1, 2 and the background meet at the two ends of the shared linel.
    assert [z.point for z in cells.zero_cells] == [(1, 0), (1, 1)]
    assert all(z.labels == (0, 1, 2) for z in cells.zero_cells)
    assert OneCell(2, 1, CrackChain((1, 1), "3")) in cells.one_cells  # label 2 (East) on the left
    assert len(cells.one_cells) == 3
    assert cells.adjacency == ((0, 1), (0, 2), (1, 2))


def test_two_label_checkerboard_pinches_are_zero_cells() -> None:
    lm = LabelMap(np.array([[1, 2], [2, 1]]))
    cells = check_cells(lm)
    centre = ZeroCell((1, 1), (1, 2))
    assert centre in cells.zero_cells
    # Every inner linel ends at the pinch: four 1-cells of length 1 between labels 1 and 2.
    inner = [oc for oc in cells.one_cells if (oc.left, oc.right) == (2, 1)]
    assert len(inner) == 4 and all(len(oc.chain) == 1 for oc in inner)


def test_nested_labels_give_closed_cells() -> None:
    lab = np.ones((5, 5), np.int32)
    lab[1:4, 1:4] = 2
    lab[2, 2] = 3
    cells = check_cells(LabelMap(lab))
    assert cells.zero_cells == ()
    assert [(oc.left, oc.right, oc.chain.start, oc.chain.is_closed()) for oc in cells.one_cells] == [
        (1, 0, (0, 0), True),
        (2, 1, (1, 1), True),
        (3, 2, (2, 2), True),
    ]
    assert cells.adjacency == ((0, 1), (1, 2), (2, 3))


def test_cells_follow_label_pixels_not_regions() -> None:
    # One label in two 4-components touching a second label: cells are per label pair, not per component.
    lm = LabelMap.from_pixel_sets([PixelSet.from_points([(0, 0), (2, 0)]), PixelSet.from_points([(1, 0)])])
    cells = check_cells(lm)
    assert cells.adjacency == ((0, 1), (0, 2), (1, 2))
    assert len([oc for oc in cells.one_cells if (oc.left, oc.right) == (2, 1)]) == 2


def test_region_of_labels_with_huge_label_values() -> None:
    big = 2**31 - 1
    lm = LabelMap(np.array([[0, big, big], [5, 0, big]]), (10, 20))  # row 0 is y = 20
    regions = region_of_labels(lm)
    assert sorted(regions) == [5, big]
    assert fill(regions[big]) == PixelSet.from_points([(11, 20), (12, 20), (12, 21)])
    assert regions[5].components[0].outer == CrackChain((10, 21), "0123")
    cells = check_cells(lm)
    assert cells.adjacency == ((0, 5), (0, big))
