"""Numba labelling and crack tracing against scikit-image and a literal pure-Python tracer."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from skimage.measure import label as sk_label

from mrm.geometry.topology.cracks import fill_rings, trace_mask
from mrm.geometry.topology.labeling import label, label_regions, label_runs

DX = {0: 1, 1: 0, 2: -1, 3: 0}
DY = {0: 0, 1: 1, 2: 0, 3: -1}
LEFT = {0: (0, 0), 1: (-1, 0), 2: (-1, -1), 3: (0, -1)}
RIGHT = {0: (0, -1), 1: (0, 0), 2: (-1, 0), 3: (-1, -1)}


def boundary_linels(a: set[tuple[int, int]]) -> set[tuple[tuple[int, int], int]]:
    """Every (pointel, code) linel with a pixel of ``a`` on its left and a pixel not in ``a`` on its right."""
    out = set()
    for x, y in a:
        for (i, j), d in (((x, y), 0), ((x + 1, y), 1), ((x + 1, y + 1), 2), ((x, y + 1), 3)):
            rx, ry = RIGHT[d]
            if (i + rx, j + ry) not in a:
                out.add(((i, j), d))
    return out


def reference_rings(mask: np.ndarray) -> set[tuple[tuple[int, int], str]]:
    """The (4, 8) rings of a mask traced after docs/algorithms.md §2.5, each from its smallest (y, x)."""
    a = {(int(c), int(r)) for r, c in zip(*np.nonzero(mask), strict=True)}
    todo = boundary_linels(a)
    rings = set()
    while todo:
        (i, j), d = start = min(todo)
        walk = []
        while True:
            todo.discard(((i, j), d))
            walk.append(((i, j), d))
            i, j = i + DX[d], j + DY[d]
            fl = (i + LEFT[d][0], j + LEFT[d][1])
            fr = (i + RIGHT[d][0], j + RIGHT[d][1])
            if fl not in a:
                d = (d + 1) % 4
            elif fr in a:
                d = (d + 3) % 4
            if ((i, j), d) == start:
                break
        k = min(range(len(walk)), key=lambda t: (walk[t][0][1], walk[t][0][0]))
        walk = walk[k:] + walk[:k]
        rings.add((walk[0][0], "".join(str(d) for _, d in walk)))
    return rings


def our_rings(mask: np.ndarray) -> set[tuple[tuple[int, int], str]]:
    r = trace_mask(mask)
    codes = "".join(map(str, r.codes.tolist()))
    return {((int(r.sx[k]), int(r.sy[k])), codes[r.off[k] : r.off[k + 1]]) for k in range(r.sx.size)}


masks = arrays(bool, st.tuples(st.integers(0, 9), st.integers(0, 9)))


@st.composite
def noise(draw: st.DrawFn) -> np.ndarray:
    h, w = draw(st.integers(1, 48)), draw(st.integers(1, 48))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    return rng.random((h, w)) < draw(st.sampled_from([0.1, 0.3, 0.5, 0.55, 0.7, 0.95]))


@st.composite
def blocky(draw: st.DrawFn) -> np.ndarray:
    """Rows of long runs (lengths 1 … 40) in widths that are and are not multiples of 8, any non-zero byte."""
    h, w = draw(st.integers(1, 12)), draw(st.integers(1, 130))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    m = np.zeros((h, w), np.uint8)
    for r in range(h):
        c, on = 0, bool(rng.integers(2))
        while c < w:
            n = int(rng.integers(1, 41))
            if on:
                m[r, c : c + n] = draw(st.sampled_from([1, 1, 1, 255, 7]))
            c, on = c + n, not on
    return m


@settings(max_examples=300)
@given(blocky(), st.integers(0, 7))
def test_runs_are_the_maximal_non_zero_stretches_of_each_row(mask: np.ndarray, shift: int) -> None:
    # The run scan passes whole 8-byte words of background or of 1s at once: against a per-row reference,
    # also for a mask whose memory does not start on a word boundary.
    shifted = np.zeros(mask.size + shift, np.uint8)[shift:].reshape(mask.shape)
    shifted[:] = mask
    mask = shifted
    runs = label_runs(mask)
    for r in range(mask.shape[0]):
        d = np.diff(np.concatenate(([0], (mask[r] != 0).astype(np.int8), [0])))
        starts, ends = np.flatnonzero(d == 1), np.flatnonzero(d == -1) - 1
        a, b = runs.ptr[r], runs.ptr[r + 1]
        assert runs.start[a:b].tolist() == starts.tolist()
        assert runs.end[a:b].tolist() == ends.tolist()
    assert our_rings(mask) == reference_rings(mask != 0)


@settings(max_examples=300)
@given(st.one_of(masks, noise()), st.sampled_from([4, 8]))
def test_label_matches_skimage(mask: np.ndarray, connectivity: int) -> None:
    lab, n = label(mask, connectivity)
    sk = sk_label(mask, connectivity=1 if connectivity == 4 else 2)
    assert n == int(sk.max(initial=0))
    assert lab.dtype == np.int32 and np.array_equal(lab, sk)


@settings(max_examples=300)
@given(st.one_of(masks, noise()), st.sampled_from([4, 8]))
def test_background_components_match_skimage(mask: np.ndarray, connectivity: int) -> None:
    runs = label_runs(mask, connectivity)
    # The complement in the whole plane, with the dual connectivity: pad with background all round.
    sk = sk_label(np.pad(~mask, 1, constant_values=True), connectivity=2 if connectivity == 4 else 1)
    assert runs.n_bg == int(sk.max())
    outside = sk[0, 0]
    sizes = np.bincount(sk[1:-1, 1:-1].ravel(), minlength=sk.max() + 1)
    bounded = sorted(int(s) for k, s in enumerate(sizes) if k not in (0, outside))
    assert sorted(runs.bg_counts[1:].tolist()) == bounded


@settings(max_examples=300)
@given(st.one_of(masks, noise()))
def test_tracer_matches_literal_rule(mask: np.ndarray) -> None:
    assert our_rings(mask) == reference_rings(mask)


@settings(max_examples=150)
@given(st.one_of(masks, noise()))
def test_rings_partition_the_boundary_and_pair_components(mask: np.ndarray) -> None:
    r = trace_mask(mask)
    runs = r.runs
    # One ring per adjacent (object component, background component) pair: the adjacency graph is a tree.
    assert r.sx.size == runs.n_labels + runs.n_bg - 1
    a = {(int(c), int(rr)) for rr, c in zip(*np.nonzero(mask), strict=True)}
    walked = []
    obj = sk_label(mask, connectivity=1)
    pairs = set()
    for k in range(r.sx.size):
        i, j = int(r.sx[k]), int(r.sy[k])
        left_labels = set()
        for d in r.codes[r.off[k] : r.off[k + 1]].tolist():
            walked.append(((i, j), d))
            lx, ly = i + LEFT[d][0], j + LEFT[d][1]
            left_labels.add(int(obj[ly, lx]))
            i, j = i + DX[d], j + DY[d]
        assert (i, j) == (int(r.sx[k]), int(r.sy[k]))
        assert left_labels == {int(r.comp[k])}
        pairs.add((int(r.comp[k]), int(r.bg[k])))
        # Outer rings (area > 0) have the unbounded or an enclosing background on the right.
        assert (r.area2[k] > 0) == (codes_first(r, k) == 0)
    assert len(walked) == len(set(walked))
    assert set(walked) == boundary_linels(a)
    assert len(pairs) == r.sx.size


def codes_first(r: object, k: int) -> int:
    return int(r.codes[r.off[k]])  # type: ignore[attr-defined]


def test_fill_rings_of_nothing_and_open_rings() -> None:
    empty = np.zeros(0, np.int64)
    mask, _, _, problem = fill_rings(np.zeros(0, np.uint8), np.zeros(1, np.int64), empty, empty)
    assert mask.shape == (0, 0) and problem == ""
    _, _, _, problem = fill_rings(np.array([0, 1], np.uint8), np.array([0, 2]), np.array([0]), np.array([0]))
    assert "back to its start" in problem


@pytest.mark.parametrize("shape", [(0, 0), (0, 5), (5, 0)])
def test_degenerate_arrays(shape: tuple[int, int]) -> None:
    m = np.zeros(shape, bool)
    lab, n = label(m)
    assert n == 0 and lab.shape == shape
    r = trace_mask(m)
    assert r.sx.size == 0


def test_full_and_single_row_masks() -> None:
    assert our_rings(np.ones((3, 5), bool)) == {((0, 0), "0000011122222333")}
    assert our_rings(np.ones((1, 4), bool)) == {((0, 0), "0000122223")}
    r = trace_mask(np.array([[1, 0, 1, 1, 0, 1]], bool))
    assert r.sx.tolist() == [0, 2, 5] and r.comp.tolist() == [1, 2, 3]


@settings(max_examples=200)
@given(
    st.integers(0, 2**32 - 1),
    st.tuples(st.integers(0, 20), st.integers(0, 20)),
    st.sampled_from([2, 3, 6, 300]),
)
def test_label_regions_are_the_four_components_of_each_label(
    seed: int, shape: tuple[int, int], k: int
) -> None:
    # Against scikit-image, label by label: the regions' labels, sizes and first pixels, in raster order.
    labels = np.random.default_rng(seed).integers(0, k, size=shape).astype(np.int32)
    got = label_regions(labels)
    want = []
    for v in np.unique(labels[labels != 0]).tolist():
        comp = sk_label(labels == v, connectivity=1)
        for c in range(1, int(comp.max()) + 1):
            rows, cols = np.nonzero(comp == c)
            want.append((int(rows[0]), int(cols[0]), v, rows.size))
    want.sort()
    assert list(zip(got.first_row, got.first_col, got.label, got.pixels, strict=True)) == want
