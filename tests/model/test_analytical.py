"""The analytical representation: boundary chains of regions cut into DSS, with preimages and lines."""

from __future__ import annotations

import itertools
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.grids import PixelSet
from mrm.geometry.dss.preimage import median_parameters
from mrm.geometry.dss.segmentation import chain_points, greedy_segmentation, maximal_segments
from mrm.reps.analytical import Analytical, analytical_of
from mrm.reps.region import CrackChain, region_of


def pixel_sets(max_side=9):
    return st.sets(
        st.tuples(st.integers(0, max_side), st.integers(0, max_side)), min_size=1, max_size=50
    ).map(PixelSet.from_points)


@pytest.mark.parametrize("mode", ["greedy", "maximal"])
@settings(max_examples=120)
@given(ps=pixel_sets())
def test_every_chain_is_segmented_like_the_free_function(ps, mode):
    region = region_of(ps)
    rep = analytical_of(region, mode=mode)
    assert isinstance(rep, Analytical) and rep.mode == mode
    chains = region.boundary_chains
    assert len(rep.chains) == len(chains)
    segment = greedy_segmentation if mode == "greedy" else maximal_segments
    total = 0
    for cs, ch in zip(rep.chains, chains, strict=True):
        assert (cs.start, cs.codes) == (ch.start, ch.codes)
        expected = segment(ch.points(), closed=True)
        assert cs.segments == tuple(expected)
        total += len(expected)
        if mode == "greedy":
            # one pass around the chain: starts at point 0, ends back on it, consecutive ones share points
            assert cs.segments[0].first == 0 and cs.segments[-1].last == len(ch.codes)
            assert all(s.last == t.first for s, t in itertools.pairwise(cs.segments))
    assert rep.n_segments == total == len(rep.segments)
    # components and holes are tagged
    tags = [(c.component, c.hole) for c in rep.chains]
    assert [t for t in tags if not t[1]] == [(comp.label, False) for comp in region.components]
    assert sum(t[1] for t in tags) == region.n_holes


def test_ring_with_hole():
    # a 3 × 3 ring: outer chain (12 linels, counter-clockwise) and hole chain (4 linels, clockwise)
    ring = PixelSet.from_points([(x, y) for x in range(3) for y in range(3) if (x, y) != (1, 1)])
    rep = analytical_of(region_of(ring))
    outer, hole = rep.chains
    assert not outer.hole and hole.hole and outer.component == hole.component == 1
    assert outer.segments == tuple(greedy_segmentation(chain_points((0, 0), "000111222333"), closed=True))
    # the hole: the unit square around pixel (1, 1), clockwise from its lowest-leftmost pointel (1, 1)
    assert (hole.start, hole.codes) == ((1, 1), "1032")
    # N then E from (1,1): direction (1, 1), r = x − y is 0, −1, 0 on (1,1) (1,2) (2,2): mu = −1, omega = 2;
    # then S W from (2,2) back to (1,1): direction (−1, −1), r = −x + y is 0, −1, 0 again.
    assert [s.as_list() for s in hole.segments] == [[0, 2, 1, 1, -1, 2], [2, 4, -1, -1, -1, 2]]
    assert rep.n_segments == len(outer) + len(hole) == len(rep.segments)


def test_lines_and_preimages():
    c7, c9 = Fraction(1, 7), Fraction(2, 9)
    disk = PixelSet.from_points(
        [(x, y) for x in range(-9, 10) for y in range(-9, 10) if (x - c7) ** 2 + (y - c9) ** 2 <= 64]
    )
    for mode in ("greedy", "maximal"):
        rep = analytical_of(region_of(disk), mode=mode)
        (chain,) = rep.chains
        for k, seg in enumerate(chain.segments):
            pts = chain.segment_points(k)
            assert len(pts) == seg.length
            a, b, c = chain.line(k)
            assert (a, b, c) == seg.median_line
            # pointel coordinates: every pointel within (omega − 1)/2 of the median line
            for i, j in pts.tolist():
                assert abs(a * i - b * j - c) <= Fraction(seg.omega - 1, 2)
            # plane coordinates: pointel (i, j) is (i − ½, j − ½); the residuals are the same
            ae, be, ce = chain.euclidean_line(k)
            for i, j in pts.tolist():
                x, y = Fraction(2 * i - 1, 2), Fraction(2 * j - 1, 2)
                assert ae * x - be * y - ce == a * i - b * j - c
            pre = chain.preimage(k)
            assert pre is chain.preimage(k)  # cached
            assert pre.count == seg.length and pre.contains_open(*median_parameters(seg))


def test_dgtal_counts_through_the_region():
    # docs/algorithms.md §5.1: off-centre disk r = 100, pointel contour: maximal 108 (whatever the start),
    # greedy 44 from DGtal's start; from the region's canonical start the greedy count may differ by one.
    cx, cy, r = Fraction(1, 7), Fraction(2, 9), 100
    ps = PixelSet.from_points(
        [(x, y) for y in range(-101, 102) for x in range(-101, 102) if (x - cx) ** 2 + (y - cy) ** 2 <= r * r]
    )
    assert len(ps) == 31417  # DGtal's pixel count
    region = region_of(ps)
    assert abs(analytical_of(region).n_segments - 44) <= 1
    assert analytical_of(region, mode="maximal").n_segments == 108


def test_chains_without_a_region_and_errors():
    sq = [((0, 0), "0123"), CrackChain((5, 5), "00112233")]
    rep = analytical_of(sq)
    assert [len(c) for c in rep.chains] == [2, 3] and rep.chains[1].component == 0
    assert analytical_of([]).n_segments == 0
    assert analytical_of(region_of(PixelSet.empty())).n_segments == 0
    with pytest.raises(ParameterError):
        analytical_of(sq, mode="best")  # type: ignore[arg-type]
    with pytest.raises(InvalidGeometryError):
        analytical_of([((0, 0), "0011")])  # not closed
    with pytest.raises(InvalidGeometryError):
        analytical_of([((0, 0), "")])
    with pytest.raises(InvalidGeometryError):
        analytical_of([((0, 0), "01x3")])
