"""Greedy segmentation, maximal segments, reach tables and windows against brute force and DGtal's counts."""

from __future__ import annotations

import itertools
from fractions import Fraction
from math import gcd

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import InvalidGeometryError
from mrm.geometry.dss import recognize
from mrm.geometry.dss.segmentation import (
    chain_points,
    dss_of_window,
    greedy_segmentation,
    maximal_segments,
    standard_dss_reach,
    standard_dss_reach_table,
)

STEPS4 = [(1, 0), (0, 1), (-1, 0), (0, -1)]
STEPS8 = [*STEPS4, (1, 1), (-1, 1), (-1, -1), (1, -1)]


# ----------------------------------------------------------------------------------------------- oracles
def is_dss_brute(points, adjacency=4) -> bool:
    """A sequence of distinct points is a DSS iff some coprime (a, b) fits all a·x − b·y in a window of width
    omega = |a| + |b| (standard) or max(|a|, |b|) (naive); |a|, |b| <= n suffices for n points."""
    pts = np.asarray(points, dtype=np.int64)
    n = len(pts)
    if len({tuple(p) for p in pts.tolist()}) != n:
        return False
    if n <= 2:
        return True
    ab = np.array([(a, b) for a in range(-n, n + 1) for b in range(0, n + 1) if gcd(a, b) == 1])
    r = ab[:, :1] * pts[None, :, 0] - ab[:, 1:] * pts[None, :, 1]
    w = np.abs(ab).sum(axis=1) if adjacency == 4 else np.abs(ab).max(axis=1)
    return bool(np.any(r.max(axis=1) - r.min(axis=1) < w))


def cyc(pts, i, j):
    m = len(pts)
    return [tuple(pts[k % m]) for k in range(i, j + 1)]


def brute_greedy(pts, adjacency, last_index):
    """Recognize each maximal prefix from scratch; the next segment starts on the previous end point."""
    m = len(pts)
    out = []
    s = 0
    while True:
        e = s
        while e < last_index and recognize(cyc(pts, s, e + 1), adjacency) is not None:
            e += 1
        dss = recognize(cyc(pts, s, e), adjacency)
        out.append((s, e, *dss.characteristics()))
        if e >= last_index:
            return out
        s = e
    _ = m


def brute_maximal(pts, adjacency, closed):
    """Every window that is a DSS and stays one neither with the previous nor with the next point added."""
    m = len(pts)
    out = []
    starts = range(m)
    for i in starts:
        maxlen = m if closed else m - i
        for length in range(1, maxlen + 1):
            j = i + length - 1
            if not is_dss_brute(cyc(pts, i, j), adjacency):
                break
            ext_front = (closed and length < m) or (not closed and j + 1 < m)
            ext_back = (closed and length < m) or (not closed and i > 0)
            if ext_front and is_dss_brute(cyc(pts, i, j + 1), adjacency):
                continue
            if ext_back and is_dss_brute(cyc(pts, i - 1, j), adjacency):
                continue
            out.append((i, j))
    return sorted(out)


# ----------------------------------------------------------------------------------------------- inputs
def walk(start, steps):
    pts = [tuple(start)]
    for dx, dy in steps:
        pts.append((pts[-1][0] + dx, pts[-1][1] + dy))
    return pts


def open_chains(adjacency, max_len=40):
    steps = STEPS4 if adjacency == 4 else STEPS8
    step = st.sampled_from(steps)

    def biased(pair):
        favoured = st.sampled_from(pair)
        return st.lists(st.one_of(favoured, favoured, favoured, favoured, step), min_size=0, max_size=max_len)

    seqs = st.tuples(st.sampled_from(steps), st.sampled_from(steps)).flatmap(biased)
    pts = st.tuples(st.tuples(st.integers(-9, 9), st.integers(-9, 9)), seqs).map(lambda t: walk(*t))
    # the recognizer needs distinct consecutive points
    return pts.filter(lambda p: all(p[k] != p[k + 1] for k in range(len(p) - 1)))


@st.composite
def closed_chains(draw, max_half=14):
    """Closed 4-paths: random E/N staircases closed by random W/S staircases, or random blob contours."""
    kind = draw(st.integers(0, 2))
    if kind < 2:
        e = draw(st.integers(0, max_half))
        n = draw(st.integers(0 if e else 1, max_half))
        out = draw(st.permutations([0] * e + [1] * n))
        back = draw(st.permutations([2] * e + [3] * n))
        codes = list(out) + list(back)
        if kind == 1:  # rotate which part comes first and the start point
            k = draw(st.integers(0, len(codes) - 1))
            codes = codes[k:] + codes[:k]
    else:
        cells = draw(st.sets(st.tuples(st.integers(0, 5), st.integers(0, 5)), min_size=1, max_size=20))
        codes = contour_codes(largest_component(cells))
    start = draw(st.tuples(st.integers(-20, 20), st.integers(-20, 20)))
    return chain_points(start, "".join(map(str, codes)))


def largest_component(cells):
    cells = set(cells)
    best: set = set()
    while cells:
        seed = cells.pop()
        comp = {seed}
        todo = [seed]
        while todo:
            x, y = todo.pop()
            for dx, dy in STEPS4:
                q = (x + dx, y + dy)
                if q in cells:
                    cells.remove(q)
                    comp.add(q)
                    todo.append(q)
        if len(comp) > len(best):
            best = comp
    return best


_LEFT = {0: (0, 0), 1: (-1, 0), 2: (-1, -1), 3: (0, -1)}
_RIGHT = {0: (0, -1), 1: (0, 0), 2: (-1, 0), 3: (-1, -1)}
_D = STEPS4


def contour(pixels):
    """Outer crack contour of a 4-connected pixel set, object on the left, from its lowest-leftmost pointel.

    Pointel (i, j) is the lower-left corner of pixel (i, j). At each pointel look at the pixels ahead: turn
    left when the front-left one is outside, right when the front-right one is inside, else go straight
    (4-connected object, 8-connected background).
    """
    y0 = min(y for _, y in pixels)
    x0 = min(x for x, y in pixels if y == y0)
    p, c, codes = (x0, y0), 0, []
    while True:
        codes.append(c)
        p = (p[0] + _D[c][0], p[1] + _D[c][1])
        fl = (p[0] + _LEFT[c][0], p[1] + _LEFT[c][1])
        fr = (p[0] + _RIGHT[c][0], p[1] + _RIGHT[c][1])
        if fl not in pixels:
            c = (c + 1) % 4
        elif fr in pixels:
            c = (c + 3) % 4
        if p == (x0, y0) and c == 0:
            return (x0, y0), codes


def contour_codes(pixels):
    return contour(pixels)[1]


def gauss_disk(r, cx, cy):
    """Exact Gauss digitization: pixel (x, y) is in iff (x − cx)² + (y − cy)² <= r² (Fractions)."""
    out = set()
    for y in range(-r - 2, r + 3):
        dy2 = (y - cy) ** 2
        for x in range(-r - 2, r + 3):
            if (x - cx) ** 2 + dy2 <= r * r:
                out.add((x, y))
    return out


# ----------------------------------------------------------------------------------------------- chain_points
def test_chain_points():
    pts = chain_points((2, -1), "0123")
    assert pts.dtype == np.int64
    assert pts.tolist() == [[2, -1], [3, -1], [3, 0], [2, 0], [2, -1]]
    assert chain_points((0, 0), [0, 0, 1]).tolist() == [[0, 0], [1, 0], [2, 0], [2, 1]]
    assert chain_points((5, 5), "").tolist() == [[5, 5]]
    for bad in ("014", "0a", "0 1", "é"):
        with pytest.raises(InvalidGeometryError):
            chain_points((0, 0), bad)


def test_invalid_chains_are_refused():
    with pytest.raises(InvalidGeometryError):
        greedy_segmentation([(0, 0), (1, 1)])  # diagonal step in a 4-chain
    with pytest.raises(InvalidGeometryError):
        greedy_segmentation([(0, 0), (0, 0), (1, 0)])  # repeated point
    with pytest.raises(InvalidGeometryError):
        maximal_segments([(0, 0), (1, 0), (2, 0)], closed=True)  # 2 → 0 is not a step
    with pytest.raises(InvalidGeometryError):
        greedy_segmentation([(0.5, 0), (1.5, 0)])
    with pytest.raises(InvalidGeometryError):
        greedy_segmentation(np.zeros((0, 2), dtype=np.int64))
    assert len(greedy_segmentation([(0.0, 0.0), (1.0, 0.0), (2.0, 1.0)], adjacency=8)) == 1


# ----------------------------------------------------------------------------------------------- greedy
def test_greedy_hand_checked():
    # E E N E E N E E N N: the first 9 steps (points 0..9) are the slope-1/2 pattern EEN repeated
    # (r = x − 2y in {0, 1, 2}: a=1, b=2, mu=0, omega=3); the 10th step N would give two N in a row, which no
    # slope of this staircase allows, so the segment stops at point 9 and the last one is the vertical step
    # pair N N from (6, 2) (a = 1, b = 0: r = x = 6 for both points, mu = 6, omega = 1).
    segs = greedy_segmentation(chain_points((0, 0), "0010010011"))
    assert [s.as_list() for s in segs] == [[0, 9, 1, 2, 0, 3], [9, 10, 1, 0, 6, 1]]
    # A unit square read as closed: points (0,0) (1,0) (1,1) (0,1). [0, 2] = E N is the 45° pattern
    # (a = b = 1, r = x − y in {0, 1, 0}: mu = 0, omega = 2); adding W is a third direction. The next
    # segment starts on point 2 = (1, 1): W then S, direction (−1, −1), so a = b = −1 and r = −x + y is
    # 0, 1, 0 on (1,1) (0,1) (0,0): mu = 0, omega = 2 — it ends on point 4 = point 0 with closed_end="wrap".
    # DGtal's "truncate" stops at point 3 = (0, 1): the single step W, a = 0, b = −1, r = y = 1: mu = 1,
    # omega = 1.
    sq = chain_points((0, 0), "0123")
    wrap = [s.as_list() for s in greedy_segmentation(sq, closed=True)]
    assert wrap == [[0, 2, 1, 1, 0, 2], [2, 4, -1, -1, 0, 2]]
    trunc = [s.as_list() for s in greedy_segmentation(sq, closed=True, closed_end="truncate")]
    assert trunc == [[0, 2, 1, 1, 0, 2], [2, 3, 0, -1, 1, 1]]


@pytest.mark.parametrize("adjacency", [4, 8])
@settings(max_examples=500)
@given(data=st.data())
def test_greedy_open_agrees_with_brute_force(adjacency, data):
    pts = data.draw(open_chains(adjacency))
    segs = greedy_segmentation(np.array(pts), adjacency=adjacency)
    got = [tuple(s.as_list()) for s in segs]
    assert got == brute_greedy(pts, adjacency, len(pts) - 1)
    assert segs[0].first == 0 and segs[-1].last == len(pts) - 1
    for s, t in itertools.pairwise(segs):
        assert s.last == t.first
    for s in segs:
        assert is_dss_brute(pts[s.first : s.last + 1], adjacency)
        # the numba kernel's leaning points are the pure-Python recognizer's
        ref = recognize(pts[s.first : s.last + 1], adjacency)
        assert (s.uf, s.ul, s.lf, s.ll) == ref.leaning_points()
        if s.last + 1 < len(pts):
            assert not is_dss_brute(pts[s.first : s.last + 2], adjacency)


@settings(max_examples=300)
@given(pts=closed_chains())
def test_greedy_closed_agrees_with_brute_force(pts):
    cyc_pts = [tuple(p) for p in pts[:-1].tolist()]
    m = len(cyc_pts)
    for closed_end, last in (("wrap", m), ("truncate", m - 1)):
        got = [tuple(s.as_list()) for s in greedy_segmentation(pts, closed=True, closed_end=closed_end)]
        assert got == brute_greedy(cyc_pts, 4, last)
        assert got[0][0] == 0 and got[-1][1] == last


# ----------------------------------------------------------------------------------------------- maximal
@pytest.mark.parametrize("adjacency", [4, 8])
@settings(max_examples=200)
@given(data=st.data())
def test_maximal_open_agrees_with_brute_force(adjacency, data):
    pts = data.draw(open_chains(adjacency, max_len=25))
    segs = maximal_segments(np.array(pts), adjacency=adjacency)
    assert [(s.first, s.last) for s in segs] == brute_maximal(pts, adjacency, closed=False)
    # they cover the chain, and each carries the characteristics of its window
    covered = set()
    for s in segs:
        covered.update(range(s.first, s.last + 1))
        assert (s.a, s.b, s.mu, s.omega) == recognize(pts[s.first : s.last + 1], adjacency).characteristics()
    assert covered == set(range(len(pts)))


@settings(max_examples=200)
@given(pts=closed_chains(max_half=9))
def test_maximal_closed_agrees_with_brute_force(pts):
    cyc_pts = [tuple(p) for p in pts[:-1].tolist()]
    m = len(cyc_pts)
    segs = maximal_segments(pts, closed=True)
    got = [(s.first, s.last) for s in segs]
    assert got == brute_maximal(cyc_pts, 4, closed=True)
    for s in segs:
        assert 0 <= s.first < m and s.first <= s.last <= s.first + m - 1
        assert (s.a, s.b, s.mu, s.omega) == recognize(cyc(cyc_pts, s.first, s.last)).characteristics()
    covered = {k % m for s in segs for k in range(s.first, s.last + 1)}
    assert covered == set(range(m))


def test_maximal_small_closed_chains():
    # two points going back and forth: each one-step window is maximal
    assert [(s.first, s.last) for s in maximal_segments([(0, 0), (1, 0)], closed=True)] == [(0, 1), (1, 2)]
    assert [(s.first, s.last) for s in maximal_segments([(3, 4)], closed=True)] == [(0, 0)]
    assert [(s.first, s.last) for s in maximal_segments([(3, 4)])] == [(0, 0)]
    assert [s.as_list() for s in greedy_segmentation([(3, 4)], closed=True)] == [[0, 0, 0, 0, 0, 1]]


# ------------------------------------------------------------------------------------------- reach / windows
@settings(max_examples=200)
@given(pts=closed_chains())
def test_reach_closed_agrees_with_brute_force(pts):
    cyc_pts = [tuple(p) for p in pts[:-1].tolist()]
    m = len(cyc_pts)
    reach, params = standard_dss_reach_table(pts, closed=True)
    assert np.array_equal(reach, standard_dss_reach(pts, closed=True))
    for i in range(m):
        j = i
        while j < i + m - 1 and is_dss_brute(cyc(cyc_pts, i, j + 1)):
            j += 1
        assert reach[i] == j
        dss = recognize(cyc(cyc_pts, i, j))
        assert tuple(params[i]) == dss.characteristics()
        # the median line a·x − b·y = mu + (omega − 1)/2 is within (omega − 1)/2 of every remainder
        a, b, mu, omega = params[i]
        c = Fraction(2 * mu + omega - 1, 2)
        assert all(abs(a * x - b * y - c) <= Fraction(omega - 1, 2) for x, y in cyc(cyc_pts, i, j))
        seg = dss_of_window(pts, i, j, closed=True)
        assert (seg.first, seg.last, seg.a, seg.b, seg.mu, seg.omega) == (i, j, a, b, mu, omega)


@settings(max_examples=200)
@given(pts=open_chains(4))
def test_reach_open_agrees_with_brute_force(pts):
    reach = standard_dss_reach(np.array(pts))
    for i in range(len(pts)):
        j = i
        while j + 1 < len(pts) and is_dss_brute(pts[i : j + 2]):
            j += 1
        assert reach[i] == j


def test_dss_of_window_errors():
    path = [(0, 0), (1, 0), (2, 0), (2, 1), (1, 1), (0, 1)]
    with pytest.raises(ValueError):
        dss_of_window(path, 4, 7, closed=True)  # W S E turns twice: not a DSS
    with pytest.raises(ValueError):
        dss_of_window(path, 3, 2)
    with pytest.raises(ValueError):
        dss_of_window(path, 0, 6)  # past the end of an open chain
    with pytest.raises(ValueError):
        dss_of_window(path, 0, 6, closed=True)  # more than m points
    seg = dss_of_window(path, 5, 8, closed=True)  # (0,1) (0,0) (1,0) (2,0): S E E
    assert (seg.first, seg.last) == (5, 8)
    assert (seg.a, seg.b, seg.mu, seg.omega) == recognize([(0, 1), (0, 0), (1, 0), (2, 0)]).characteristics()


# --------------------------------------------------------------------------------------------- DGtal anchors
def _disk_chain(r, cx, cy):
    start, codes = contour(gauss_disk(r, cx, cy))
    return chain_points(start, "".join(map(str, codes)))


@pytest.mark.parametrize(
    ("r", "centre", "n_linels", "dgtal_greedy", "dgtal_maximal"),
    [
        (5, (Fraction(1, 7), Fraction(2, 9)), 40, 7, 15),
        (20, (Fraction(1, 7), Fraction(2, 9)), 160, 15, 38),
        (100, (Fraction(1, 7), Fraction(2, 9)), 800, 44, 108),
        (10, (0, 0), 84, 12, 32),
        (50, (0, 0), 404, 24, 72),
        (100, (0, 0), 804, 48, 112),
    ],
)
def test_dgtal_disk_counts(r, centre, n_linels, dgtal_greedy, dgtal_maximal):
    """docs/algorithms.md §5.1: DGtal's counts on the pointel contour of Gauss-digitized disks.

    The maximal-segment count does not depend on where the contour starts or which way it runs: it must equal
    DGtal's exactly. The greedy count does; DGtal starts at the first boundary element its search finds, which
    we cannot reproduce, so from our canonical start the count must be within 1 of DGtal's, and DGtal's count
    must be what some start (in one of the two directions) gives.
    """
    pts = _disk_chain(r, *centre)
    assert len(pts) - 1 == n_linels
    assert len(maximal_segments(pts, closed=True)) == dgtal_maximal
    assert len(maximal_segments(pts[::-1], closed=True)) == dgtal_maximal
    assert abs(len(greedy_segmentation(pts, closed=True)) - dgtal_greedy) <= 1
    ring = pts[:-1]
    counts = {
        len(greedy_segmentation(np.roll(q, -s, axis=0), closed=True, closed_end=end))
        for q in (ring, ring[::-1])
        for s in range(0, len(ring), 7)
        for end in ("wrap", "truncate")
    }
    assert dgtal_greedy in counts
    assert max(counts) - min(counts) <= 2


# ----------------------------------------------------------------------------------------------- mrm segment
def _cli(capsys, *argv):
    import json

    from mrm.cli import run_cli

    code = run_cli(["segment", *argv])
    out, err = capsys.readouterr()
    return code, (json.loads(out) if code == 0 and "--json" in argv else out), err


def test_cli_segment_json(capsys):
    code, out, err = _cli(capsys, "--chain", "0,0,0010010011", "--json")
    assert code == 0 and err == ""
    # the hand-checked example of test_greedy_hand_checked
    assert out["segments"] == [[0, 9, 1, 2, 0, 3], [9, 10, 1, 0, 6, 1]]
    assert out["count"] == 2 and out["points"] == 11 and out["closed"] is False and out["mode"] == "greedy"
    assert out["leaning_points"][1] == [[6, 3], [6, 4], [6, 3], [6, 4]]
    code, out, _ = _cli(capsys, "--chain", "0,0,0123", "--closed", "--json")
    assert code == 0 and out["segments"] == [[0, 2, 1, 1, 0, 2], [2, 4, -1, -1, 0, 2]]
    code, out, _ = _cli(capsys, "--chain", "0,0,0123", "--closed", "--closed-end", "truncate", "--json")
    assert code == 0 and out["segments"][-1][:2] == [2, 3]
    code, out, _ = _cli(capsys, "--chain", " 3 , -2 , 0123", "--closed", "--mode", "maximal", "--json")
    pts = chain_points((3, -2), "0123")
    assert out["segments"] == [s.as_list() for s in maximal_segments(pts, closed=True)]
    assert len(out["segments"]) == 4  # each pair of sides of the unit square
    code, out, _ = _cli(capsys, "--chain", "0,0,0000", "--adjacency", "8", "--json")
    assert out["segments"] == [[0, 4, 0, 1, 0, 1]]
    code, out, _ = _cli(capsys, "--chain", "5,5,", "--json")
    assert out["segments"] == [[0, 0, 0, 0, 0, 1]] and out["points"] == 1


def test_cli_segment_table(capsys):
    code, out, _ = _cli(capsys, "--chain", "0,0,0010010011")
    assert code == 0
    lines = out.splitlines()
    assert "2 greedy standard (4-connected) segments" in lines[0]
    assert lines[1].split()[:6] == ["first", "last", "a", "b", "mu", "omega"]
    assert lines[2].split()[:6] == ["0", "9", "1", "2", "0", "3"]


@pytest.mark.parametrize(
    ("chain", "extra", "message"),
    [
        ("0,0,0140", (), "Freeman"),
        ("0,0,01a", (), "Freeman"),
        ("x,0,01", (), "integers"),
        ("0.5,0,01", (), "integers"),
        ("0,0", (), "X,Y,CODES"),
        ("0,0,01,2", (), "X,Y,CODES"),
        ("0,0,0011", ("--closed",), "not back at its start"),
    ],
)
def test_cli_segment_bad_chain(capsys, chain, extra, message):
    code, out, err = _cli(capsys, "--chain", chain, *extra, "--json")
    assert code == 2 and out == ""
    assert err.startswith("mrm segment: error: ") and message in err and "Traceback" not in err


def test_cli_segment_bad_options(capsys):
    from mrm.cli import run_cli

    for argv in (
        ["segment", "--chain", "0,0,01", "--adjacency", "6"],
        ["segment"],
        ["segment", "--chain", "0,0,01", "--mode", "x"],
    ):
        with pytest.raises(SystemExit) as exc:
            run_cli(argv)
        assert exc.value.code == 2
    capsys.readouterr()
