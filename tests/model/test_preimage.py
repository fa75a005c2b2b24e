"""Preimages of standard DSS: exact polygons in (u, w) line space, checked against the definition."""

from __future__ import annotations

from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.geometry.dss import recognize
from mrm.geometry.dss.preimage import (
    Preimage,
    frame_of,
    median_parameters,
    preimage_of,
    segment_preimage,
    standard_contains,
)
from mrm.geometry.dss.segmentation import chain_points, greedy_segmentation, maximal_segments

HALF = Fraction(1, 2)


def meets_all(points, frame, u, w, strict):
    """Definition: the line u·x' − (1 − u)·y' = w (frame coordinates) meets every open / closed square."""
    if not 0 <= u <= 1:
        return False
    for x, y in points:
        xf, yf = frame[0] * x, frame[1] * y
        d = abs(u * xf - (1 - u) * yf - w)
        if d > HALF or (strict and d == HALF):
            return False
    return True


def random_param(data, lo, hi):
    den = data.draw(st.sampled_from([1, 2, 3, 4, 6, 8, 12, 16, 97]))
    u = Fraction(data.draw(st.integers(0, den)), den)
    wn = data.draw(st.integers(int(lo * den * 4) - 8, int(hi * den * 4) + 8))
    return u, Fraction(wn, 4 * den)


def staircase(codes, start=(0, 0)):
    return [tuple(p) for p in chain_points(start, codes).tolist()]


def test_two_pixels_by_hand():
    # Pixels (0,0) and (1,0), frame (1,1): (0,0) gives −½ ≤ w ≤ ½, (1,0) gives u − ½ ≤ w ≤ u + ½; with
    # 0 ≤ u ≤ 1 that is the triangle (0, −½), (1, ½), (0, ½): from horizontal lines (u = 0) through the
    # shared edge's neighbourhood to the vertical line x = ½ (u = 1, w = ½), which only touches the squares.
    pre = Preimage((1, 1), [(0, 0), (1, 0)])
    assert pre.vertices == [(0, -HALF), (1, HALF), (0, HALF)]
    assert pre.contains_open(0, 0)  # y = 0, the median line, on the chart side u = 0
    assert not pre.contains_open(1, HALF)  # x = ½ only touches both squares
    assert pre.contains(1, HALF)
    assert not pre.contains_open(0, HALF)  # y = ½: the top edges
    assert pre.contains_open(HALF, Fraction(1, 4))  # the 45° line x − y = ½ crosses both squares


def test_unit_staircase_by_hand():
    # (0,0) (1,0) (1,1), frame (1,1). Constraints: −½ ≤ w ≤ ½ from (0,0); u − ½ ≤ w ≤ u + ½ from (1,0);
    # 2u − 3/2 ≤ w ≤ 2u − ½ from (1,1). On 0 ≤ u ≤ 1 the binding lower bound is u − ½ and the upper one
    # min(2u − ½, ½): the triangle (0, −½), (1, ½), (½, ½). The only horizontal line left, y = ½ (u = 0,
    # w = −½), merely runs along the squares' edges; the open preimage holds directions strictly between
    # horizontal and vertical.
    pts = [(0, 0), (1, 0), (1, 1)]
    pre = Preimage((1, 1), pts)
    assert set(pre.vertices) == {(0, -HALF), (1, HALF), (HALF, HALF)}
    assert recognize(pts).characteristics() == (1, 1, 0, 2)
    # the median line x − y = ½ → u = ½, w = ¼, strictly inside
    seg = greedy_segmentation(pts)[0]
    assert median_parameters(seg) == (HALF, Fraction(1, 4))
    assert pre.contains_open(HALF, Fraction(1, 4))
    assert not pre.contains_open(0, -HALF) and pre.contains(0, -HALF)


def test_empty_and_degenerate():
    # E E N N is not a DSS: no line crosses all open squares
    pts = staircase("0011")
    pre = Preimage((1, 1), pts)
    assert not pre.has_interior
    assert not any(pre.contains_open(u, w) for u, w in pre.vertices)
    # pixels far apart: empty
    far = Preimage((1, 1), [(0, 0), (0, 5), (5, 0)])
    assert far.is_empty and not far.contains(0, 0)
    # no pixel yet: the whole chart
    whole = Preimage()
    assert whole.contains(HALF, 1000) and not whole.contains(2, 0) and not whole.is_empty
    with pytest.raises(ValueError):
        Preimage((0, 1))


@st.composite
def quadrant_paths(draw):
    """Random E/N staircases mapped to a random quadrant, biased towards digital straight lines."""
    n = draw(st.integers(1, 30))
    if draw(st.booleans()):
        # a digital straight line: steps of the standard line of slope p/q from a random intercept
        q = draw(st.integers(1, 7))
        p = draw(st.integers(0, 7))
        mu = draw(st.integers(0, p + q - 1))
        codes, x, y = [], 0, 0
        for _ in range(n):
            # standard DSL p·x − q·y in [−mu, −mu + p + q): step E if it stays inside, else N
            if p * (x + 1) - q * y < -mu + p + q:
                codes.append("0")
                x += 1
            else:
                codes.append("1")
                y += 1
        codes = "".join(codes)
    else:
        codes = "".join(draw(st.lists(st.sampled_from("01"), min_size=n, max_size=n)))
    sx, sy = draw(st.sampled_from([(1, 1), (-1, 1), (1, -1), (-1, -1)]))
    ox, oy = draw(st.integers(-20, 20)), draw(st.integers(-20, 20))
    pts = [(ox + sx * x, oy + sy * y) for x, y in staircase(codes)]
    return pts, (sx, sy)


@settings(max_examples=250)
@given(data=st.data())
def test_polygon_matches_definition(data):
    pts, frame = data.draw(quadrant_paths())
    pre = Preimage(frame, pts)
    # a path stepping into one quadrant is a standard DSS iff some line crosses all its open squares
    assert pre.has_interior == (recognize(pts) is not None)
    # vertices satisfy the closed constraints; random parameter points agree with the definition
    for u, w in pre.vertices:
        assert meets_all(pts, frame, u, w, strict=False)
    ws = [w for _, w in pre.vertices] or [0]
    for _ in range(12):
        u, w = random_param(data, min(ws), max(ws))
        assert pre.contains(u, w) == meets_all(pts, frame, u, w, strict=False)
        assert pre.contains_open(u, w) == meets_all(pts, frame, u, w, strict=True)
        A, B, C = pre.line(u, w)
        if pre.contains_open(u, w):
            assert standard_contains(pts, A, B, C)
        if standard_contains(pts, A, B, C):
            assert pre.contains(u, w)
    # adding the pixels in another order gives the same polygon
    shuffled = data.draw(st.permutations(pts))
    again = Preimage(frame, shuffled)
    assert set(again.vertices) == set(pre.vertices)


@settings(max_examples=300)
@given(data=st.data())
def test_median_line_in_open_preimage(data):
    pts, _ = data.draw(quadrant_paths())
    for seg in maximal_segments(pts) + greedy_segmentation(pts):
        if seg.first == seg.last:
            continue
        window = pts[seg.first : seg.last + 1]
        pre = segment_preimage(pts, seg)
        assert pre.frame == frame_of(seg.a, seg.b)
        u, w = median_parameters(seg)
        assert pre.contains_open(u, w)
        assert meets_all(window, pre.frame, u, w, strict=True)
        a, b, c = seg.median_line
        assert standard_contains(window, a, -b, c)
        # at most 4 vertices off the chart's sides (Dorst & Smeulders), a handful in all
        assert len([v for v in pre.vertices if 0 < v[0] < 1]) <= 4


def test_median_line_on_disk_segments():
    # every greedy and maximal segment of a closed contour, all four quadrants
    cx, cy, r = Fraction(1, 7), Fraction(2, 9), 12
    disk = {(x, y) for x in range(-14, 15) for y in range(-14, 15) if (x - cx) ** 2 + (y - cy) ** 2 <= r * r}
    # its pointel contour, convex row by row: E along the bottom, up the right side, W along the top, down
    rows = {y: (min(x for x, yy in disk if yy == y), max(x for x, yy in disk if yy == y)) for _, y in disk}
    y0, y1 = min(rows), max(rows)
    codes, x = "0" * (rows[y0][1] + 1 - rows[y0][0]), rows[y0][1] + 1
    for y in range(y0 + 1, y1 + 1):
        codes += "1" + ("0" * (rows[y][1] + 1 - x) if rows[y][1] + 1 > x else "2" * (x - rows[y][1] - 1))
        x = rows[y][1] + 1
    codes += "1" + "2" * (x - rows[y1][0])
    x = rows[y1][0]
    for y in range(y1 - 1, y0 - 1, -1):
        codes += "3" + ("2" * (x - rows[y][0]) if x > rows[y][0] else "0" * (rows[y][0] - x))
        x = rows[y][0]
    pts = chain_points((rows[y0][0], y0), codes + "3")
    assert (pts[0] == pts[-1]).all()
    ring = [tuple(p) for p in pts[:-1].tolist()]
    segs = greedy_segmentation(pts, closed=True) + maximal_segments(pts, closed=True)
    frames = set()
    for seg in segs:
        pre = segment_preimage(ring, seg)
        frames.add(pre.frame)
        assert pre.has_interior
        assert pre.contains_open(*median_parameters(seg))
    assert frames == {(1, 1), (-1, 1), (1, -1), (-1, -1)}


def test_parameters_of_and_line_round_trip():
    pre = preimage_of([(0, 0), (-1, 0), (-1, 1), (-2, 1)], a=1, b=-2)  # direction (−2, 1): frame (−1, 1)
    assert pre.frame == (-1, 1)
    u, w = pre.parameters_of(1, -2, Fraction(1, 2))
    A, B, C = pre.line(u, w)
    # the same line: proportional to x + 2y = ½
    assert A / 1 == B / 2 == C / Fraction(1, 2)
    with pytest.raises(ValueError):
        pre.parameters_of(1, 2, 0)  # direction (2, 1) is in another quadrant
    with pytest.raises(ValueError):
        standard_contains([(0, 0)], 0, 0, 1)


def test_standard_contains_tie_rule():
    # the line y = ½ lies on the top edge of pixel (0, 0): the standard model gives it to the pixel below
    assert standard_contains([(0, 0)], 0, 1, HALF)
    assert not standard_contains([(0, 1)], 0, 1, HALF)
    # vertical line x = ½: to the pixel on its left; the orientation of (A, B, C) does not matter
    assert standard_contains([(0, 0)], 1, 0, HALF) and standard_contains([(0, 0)], -1, 0, -HALF)
    assert not standard_contains([(1, 0)], -1, 0, -HALF)
