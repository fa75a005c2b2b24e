"""The incremental arithmetic DSS recognizer against a brute-force definition of digital straight segments."""

from __future__ import annotations

from math import gcd

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.geometry.dss import ArithmeticalDSS, Segment, recognize

STEPS4 = [(1, 0), (0, 1), (-1, 0), (0, -1)]
STEPS8 = [*STEPS4, (1, 1), (-1, 1), (-1, -1), (1, -1)]

_PAIRS: dict[int, np.ndarray] = {}


def _coprime_pairs(n: int) -> np.ndarray:
    if n not in _PAIRS:
        _PAIRS[n] = np.array(
            [(a, b) for a in range(-n, n + 1) for b in range(-n, n + 1) if gcd(a, b) == 1], dtype=np.int64
        )
    return _PAIRS[n]


def brute_dss(points, adjacency=4):
    """(a, b, mu, omega) of the minimal DSL holding the point sequence, oriented along it; None if not a DSS.

    Definition: a sequence of distinct points, consecutive ones adjacent, is a DSS iff some coprime (a, b) and
    mu put every remainder a·x − b·y in [mu, mu + omega), omega = |a| + |b| (standard) or max(|a|, |b|)
    (naive). Slopes of a DSS of n points have |a|, |b| <= n, so the search below is exhaustive.
    """
    pts = np.asarray(points, dtype=np.int64)
    n = len(pts)
    if len({tuple(p) for p in pts.tolist()}) != n:
        return None
    if n == 1:
        return (0, 0, 0, 1)
    ab = _coprime_pairs(n)
    r = ab[:, :1] * pts[None, :, 0] - ab[:, 1:] * pts[None, :, 1]
    w = np.abs(ab).sum(axis=1) if adjacency == 4 else np.abs(ab).max(axis=1)
    d = pts[-1] - pts[0]
    ok = (r.max(axis=1) - r.min(axis=1) < w) & (ab[:, 1] * d[0] + ab[:, 0] * d[1] > 0)
    if not ok.any():
        return None
    k = np.flatnonzero(ok)
    best = k[np.argmin(w[k])]
    assert np.sum(w[k] == w[best]) == 1, "minimal characteristics are unique"
    return (int(ab[best, 0]), int(ab[best, 1]), int(r[best].min()), int(w[best]))


def walk(start, steps):
    pts = [tuple(start)]
    for dx, dy in steps:
        pts.append((pts[-1][0] + dx, pts[-1][1] + dy))
    return pts


def paths(adjacency, max_len=24):
    """Random walks biased towards two step directions (so that long DSS occur), any step possible."""
    steps = STEPS4 if adjacency == 4 else STEPS8
    step = st.sampled_from(steps)
    biased = st.tuples(st.sampled_from(steps), st.sampled_from(steps)).flatmap(
        lambda pair: st.lists(
            st.one_of(st.sampled_from(pair), st.sampled_from(pair), st.sampled_from(pair), step),
            min_size=1,
            max_size=max_len,
        )
    )
    return st.tuples(st.tuples(st.integers(-50, 50), st.integers(-50, 50)), biased).map(lambda t: walk(*t))


def check_invariants(dss: ArithmeticalDSS, pts, adjacency):
    a, b, mu, omega = dss.characteristics()
    for p in pts:
        assert mu <= a * p[0] - b * p[1] < mu + omega
    assert tuple(pts[0]) == dss.F and tuple(pts[-1]) == dss.L
    for q in (dss.Uf, dss.Ul):
        assert q in pts and dss.remainder(q) == mu
    for q in (dss.Lf, dss.Ll):
        assert q in pts and dss.remainder(q) == mu + omega - 1
    idx = {p: i for i, p in enumerate(pts)}
    # first / last leaning points are the first / last points with that remainder
    ups = [i for i, p in enumerate(pts) if dss.remainder(p) == mu]
    lows = [i for i, p in enumerate(pts) if dss.remainder(p) == mu + omega - 1]
    assert (idx[dss.Uf], idx[dss.Ul]) == (ups[0], ups[-1])
    assert (idx[dss.Lf], idx[dss.Ll]) == (lows[0], lows[-1])
    if len(pts) > 1:
        expected_omega = abs(a) + abs(b) if adjacency == 4 else max(abs(a), abs(b))
        assert omega == expected_omega and gcd(a, b) == 1


@pytest.mark.parametrize("adjacency", [4, 8])
@settings(max_examples=1000)
@given(data=st.data())
def test_extend_front_agrees_with_brute_force(adjacency, data):
    pts = data.draw(paths(adjacency))
    dss = ArithmeticalDSS(pts[0], adjacency)
    check_invariants(dss, pts[:1], adjacency)
    for k in range(1, len(pts)):
        before = dss.copy()
        if not dss.extend_front(pts[k]):
            # the first rejected point makes the set non-DSS, and a rejection changes nothing
            assert brute_dss(pts[: k + 1], adjacency) is None
            assert dss == before
            return
        assert dss.characteristics() == brute_dss(pts[: k + 1], adjacency)
        check_invariants(dss, pts[: k + 1], adjacency)


@pytest.mark.parametrize("adjacency", [4, 8])
@settings(max_examples=500)
@given(data=st.data())
def test_extend_back_agrees_with_brute_force(adjacency, data):
    pts = data.draw(paths(adjacency))
    dss = ArithmeticalDSS(pts[-1], adjacency)
    for k in range(len(pts) - 2, -1, -1):
        if not dss.extend_back(pts[k]):
            assert brute_dss(pts[k:], adjacency) is None
            return
        assert dss.characteristics() == brute_dss(pts[k:], adjacency)
        check_invariants(dss, pts[k:], adjacency)


def _longest_prefix(pts, adjacency):
    dss = ArithmeticalDSS(pts[0], adjacency)
    k = 1
    while k < len(pts) and dss.extend_front(pts[k]):
        k += 1
    return dss, pts[:k]


def _same_segment(x: ArithmeticalDSS, y: ArithmeticalDSS) -> None:
    assert x.characteristics() == y.characteristics()
    assert (x.F, x.L) == (y.F, y.L)
    assert x.leaning_points() == y.leaning_points()


@pytest.mark.parametrize("adjacency", [4, 8])
@settings(max_examples=500)
@given(data=st.data())
def test_retract_equals_recognition_from_scratch(adjacency, data):
    pts = data.draw(paths(adjacency, max_len=30))
    full, seg = _longest_prefix(pts, adjacency)
    # remove from the back, one point at a time, down to one point
    dss = full.copy()
    for k in range(1, len(seg)):
        assert dss.retract_back()
        _same_segment(dss, recognize(seg[k:], adjacency))
        check_invariants(dss, seg[k:], adjacency)
    assert not dss.retract_back()
    # remove from the front
    dss = full.copy()
    for k in range(len(seg) - 1, 0, -1):
        assert dss.retract_front()
        _same_segment(dss, recognize(seg[:k], adjacency))
        check_invariants(dss, seg[:k], adjacency)
    assert not dss.retract_front()
    # and the retracted segment can grow again at the front exactly as a fresh one would
    if len(seg) > 2:
        dss = full.copy()
        dss.retract_back()
        dss.retract_back()
        fresh = recognize(seg[2:], adjacency)
        for q in pts[len(seg) : len(seg) + 3]:
            assert dss.extend_front(q) == fresh.extend_front(q)
            _same_segment(dss, fresh)


def test_hand_checked_standard_segment():
    # Points (0,0) (1,0) (2,0) (2,1) (3,1) (4,1): steps E, E, N, E, E. Try the direction (b, a) = (2, 1): the
    # remainders r = x − 2y are 0, 1, 2, 0, 1, 2, a window of width 3 = |a| + |b|, so (a, b, mu, omega) =
    # (1, 2, 0, 3); no coprime (a, b) with |a| + |b| < 3 fits (a horizontal or 45° line spreads them wider).
    # Upper leaning points (r = 0): (0,0) and (2,1); lower (r = 2): (2,0) and (4,1).
    dss = recognize([(0, 0), (1, 0), (2, 0), (2, 1), (3, 1), (4, 1)])
    assert dss is not None
    assert dss.characteristics() == (1, 2, 0, 3)
    assert (dss.Uf, dss.Ul, dss.Lf, dss.Ll) == ((0, 0), (2, 1), (2, 0), (4, 1))
    # The same path read backwards: (−a, −b), remainders negated (0, −1, −2), so mu = −2; the roles of the
    # upper and lower leaning points swap.
    back = recognize([(4, 1), (3, 1), (2, 1), (2, 0), (1, 0), (0, 0)])
    assert back is not None and back.characteristics() == (-1, -2, -2, 3)
    assert (back.Uf, back.Ul, back.Lf, back.Ll) == ((4, 1), (2, 0), (2, 1), (0, 0))
    # E, N, E, N is a 45° standard line: r = x − y in {0, 1}: a = b = 1, mu = 0, omega = 2.
    assert recognize([(0, 0), (1, 0), (1, 1), (2, 1), (2, 2)]).characteristics() == (1, 1, 0, 2)
    # A horizontal run: a = 0, b = 1, r = −y = −3 for every point: mu = −3, omega = 1.
    assert recognize([(5, 3), (6, 3), (7, 3)]).characteristics() == (0, 1, -3, 1)
    # E, E, N, N is not a DSS (a 1-pixel corner on both sides), nor is a step back.
    assert recognize([(0, 0), (1, 0), (2, 0), (2, 1), (2, 2)]) is None
    assert recognize([(0, 0), (1, 0), (0, 0)]) is None


def test_hand_checked_naive_segment():
    # 8-path (0,0) (1,0) (2,1) (3,1) (4,2): steps E, NE, E, NE: slope 1/2, r = x − 2y = 0, 1, 0, 1, 0;
    # naive omega = max(1, 2) = 2, mu = 0.
    dss = recognize([(0, 0), (1, 0), (2, 1), (3, 1), (4, 2)], adjacency=8)
    assert dss is not None and dss.characteristics() == (1, 2, 0, 2)
    # a diagonal: a = b = 1, r = 0, omega = 1
    assert recognize([(0, 0), (1, 1), (2, 2)], adjacency=8).characteristics() == (1, 1, 0, 1)
    # a 4-step corner is not an 8-DSS of distinct directions beyond the octant
    assert recognize([(0, 0), (1, 0), (1, 1), (1, 2), (2, 2)], adjacency=8) is None


def test_segment_median_line():
    s = Segment(0, 5, 1, 2, 0, 3, (0, 0), (2, 1), (2, 0), (4, 1))
    a, b, c = s.median_line
    assert (a, b, c) == (1, 2, 1)  # (lo + hi) / 2 = (0 + 2) / 2
    s2 = Segment(0, 4, 1, 1, 0, 2, (0, 0), (2, 2), (1, 0), (2, 1))
    assert s2.median_line[2] * 2 == 1
    assert s.as_list() == [0, 5, 1, 2, 0, 3] and s.length == 6


def test_bad_adjacency():
    with pytest.raises(ValueError):
        ArithmeticalDSS((0, 0), 6)  # type: ignore[arg-type]
