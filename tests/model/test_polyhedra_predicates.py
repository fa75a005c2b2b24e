"""The exact orientation predicates of mrm.geometry.polyhedra against a Fraction reference.

Adversarial inputs: exactly coplanar and collinear points (the filter must hand them to the exact stages),
near-degenerate ones (a coplanar point nudged by one ulp), large and tiny magnitudes (inside and outside the
compiled stages' range, where the Fraction path decides), and points far from the origin with tiny
differences.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.geometry.polyhedra.predicates import (
    UNKNOWN,
    o2,
    o3,
    orient2d,
    orient2d_sign,
    orient3d,
    orient3d_sign,
)
from tests.oracles import polyhedra_reference as ref

MAGNITUDES = (1.0, 2.0**-30, 2.0**30, 2.0**-190, 2.0**190, 2.0**-250, 2.0**250, 1e-310, 1e300)


@st.composite
def coordinate(draw: st.DrawFn) -> float:
    kind = draw(st.sampled_from(("int", "half", "float", "big")))
    if kind == "int":
        return float(draw(st.integers(-8, 8)))
    if kind == "half":
        return draw(st.integers(-16, 16)) / 4.0
    if kind == "float":
        return draw(st.floats(-10, 10, allow_nan=False))
    return draw(st.floats(-1e300, 1e300, allow_nan=False, allow_infinity=False))


@st.composite
def points(draw: st.DrawFn, n: int) -> np.ndarray:
    """n points, often degenerate: later ones on the affine hull of the first ones, maybe nudged by an ulp."""
    scale = draw(st.sampled_from(MAGNITUDES))
    offset = draw(st.sampled_from((0.0, 0.0, 1.0, 1e6, -(2.0**40))))
    pts = [[draw(coordinate()) for _ in range(3)] for _ in range(min(n, 3))]
    while len(pts) < n:
        mode = draw(st.sampled_from(("free", "hull", "hull", "nudged", "collinear")))
        if mode == "free":
            pts.append([draw(coordinate()) for _ in range(3)])
            continue
        s = draw(st.integers(-3, 3)) / 2.0
        t = draw(st.integers(-3, 3)) / 2.0 if mode != "collinear" else 0.0
        a, b, c = (np.array(p) for p in pts[:3])
        p = a + s * (b - a) + t * (c - a)
        if mode == "nudged":
            k = draw(st.integers(0, 2))
            p[k] = math.nextafter(p[k], math.inf if draw(st.booleans()) else -math.inf)
        pts.append([float(x) for x in p])
    with np.errstate(over="ignore"):
        arr = np.array(pts, dtype=np.float64) * scale + offset
    # Scaling can overflow; the predicates are defined on finite inputs only.
    arr[~np.isfinite(arr)] = 0.0
    return arr


@settings(max_examples=400)
@given(points(4))
def test_orient3d_is_exact(p: np.ndarray) -> None:
    expected = ref.orient3d(p[0], p[1], p[2], p[3])
    assert orient3d_sign(p[0], p[1], p[2], p[3]) == expected
    assert o3(p, 0, 1, 2, 3) == expected  # the by-index form called from Python
    compiled = orient3d(p[0], p[1], p[2], p[3])
    assert compiled in (expected, UNKNOWN)
    in_range = np.all((p == 0) | ((np.abs(p) >= 2.0**-200) & (np.abs(p) <= 2.0**200)))
    if in_range:
        assert compiled == expected


@settings(max_examples=400)
@given(points(3), st.sampled_from(((0, 1), (1, 2), (2, 0), (1, 0))))
def test_orient2d_is_exact(p: np.ndarray, axes: tuple[int, int]) -> None:
    i, j = axes
    expected = ref.orient2d(p[0], p[1], p[2], i, j)
    assert orient2d_sign(p[0], p[1], p[2], i, j) == expected
    assert o2(p, 0, 1, 2, i, j) == expected
    assert orient2d(p[0], p[1], p[2], i, j) in (expected, UNKNOWN)


def test_the_compiled_index_form_agrees_on_ties() -> None:
    # Exactly coplanar points with short coordinates (the exact-difference stage), one ulp off the plane
    # (the filter cannot decide: the expansions do), and huge ones (the Fraction path).
    from mrm.geometry.polyhedra.faces import _coplanar_edges  # a kernel calling o3 compiled

    v = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]])
    t = np.array([[0, 1, 2], [1, 3, 2]])
    twin = np.array([-1, 5, -1, -1, -1, 1])
    assert _coplanar_edges(v, t, twin)[1] == 1
    v[3, 2] = 2.0**-60
    assert _coplanar_edges(v, t, twin)[1] == 0
    assert ref.orient3d(v[0], v[1], v[2], v[3]) == 1


def test_sign_conventions() -> None:
    a, b, c, d = np.eye(4, 3)[[3, 0, 1, 2]]  # origin, x, y, z
    assert orient3d_sign(a, b, c, d) == 1  # d above the counter-clockwise triangle a b c
    assert orient3d_sign(a, c, b, d) == -1
    assert orient2d_sign(a, b, c, 0, 1) == 1


_RANGE = st.one_of(
    st.floats(2.0**-200, 2.0**200),
    st.floats(-(2.0**200), -(2.0**-200)),
    st.just(0.0),
    st.integers(-(2**53), 2**53).map(float),
)


@settings(max_examples=300)
@given(_RANGE, _RANGE, _RANGE)
def test_exact_triple_products(a: float, b: float, c: float) -> None:
    # The expansion stage's building block: four doubles whose sum is a·b·c exactly (Dekker's products).
    from fractions import Fraction

    from mrm.geometry.polyhedra.predicates import _push_triple

    buf = np.zeros(4)
    assert _push_triple(buf, 0, -1.0, a, b, c) == 4
    assert sum(Fraction(x) for x in buf.tolist()) == -Fraction(a) * Fraction(b) * Fraction(c)


@settings(max_examples=300)
@given(st.lists(_RANGE, min_size=1, max_size=40))
def test_exact_sign_of_a_sum(terms: list[float]) -> None:
    from fractions import Fraction

    from mrm.geometry.polyhedra.predicates import _sign_of_sum

    # Cancelling pairs make the exact sum tiny or zero: the case the expansion exists for.
    terms = terms + [-x for x in terms[: len(terms) // 2]] + [2.0**-1000 if len(terms) % 3 else 0.0]
    total = sum(Fraction(x) for x in terms)
    assert _sign_of_sum(np.array(terms), len(terms)) == (total > 0) - (total < 0)
