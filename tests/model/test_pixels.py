"""PixelSet and LabelMap against Python sets of (x, y) tuples, the obviously-correct reference."""

from __future__ import annotations

import pickle

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import SizeLimitError
from mrm.core.grids import LabelMap, PixelSet

# ---------------------------------------------------------------------------------------------- strategies
coord = st.integers(-12, 12)
point = st.tuples(coord, coord)
# Small dense sets, plus sets with a few far-apart points (adversarial extents). Every set lies within
# ±200 of the origin; ``shift`` moves all the sets of one example by the same (possibly huge) vector, so the
# joint boxes of binary operations stay small while the coordinates go far from 0.
local_sets = st.one_of(
    st.sets(point, max_size=40),
    st.sets(st.tuples(st.integers(-3, 3), st.integers(-3, 3)), max_size=49),
    st.sets(st.tuples(st.integers(-200, 200), st.integers(-200, 200)), max_size=5),
)
shifts = st.one_of(st.just((0, 0)), st.tuples(st.integers(-(10**12), 10**12), st.integers(-(10**12), 10**12)))


def moved(pts: set[tuple[int, int]], shift: tuple[int, int]) -> set[tuple[int, int]]:
    return {(x + shift[0], y + shift[1]) for x, y in pts}


point_sets = st.builds(moved, local_sets, shifts)
boxes = st.tuples(st.integers(-15, 15), st.integers(-15, 15), st.integers(-15, 15), st.integers(-15, 15))


def ps_of(points: set[tuple[int, int]]) -> PixelSet:
    return PixelSet.from_points(sorted(points))


def as_set(ps: PixelSet) -> set[tuple[int, int]]:
    return {(int(x), int(y)) for x, y in ps.points()}


def box_points(box: tuple[int, int, int, int]) -> set[tuple[int, int]]:
    xmin, ymin, xmax, ymax = box
    return {(x, y) for x in range(xmin, xmax + 1) for y in range(ymin, ymax + 1)}


def rot_ref(points: set[tuple[int, int]], k: int, c: tuple[int, int]) -> set[tuple[int, int]]:
    """Rotation by k·90° counter-clockwise about c, by complex multiplication with i**k."""
    out = set()
    for x, y in points:
        z = complex(x - c[0], y - c[1]) * (1j**k)
        out.add((round(z.real) + c[0], round(z.imag) + c[1]))
    return out


# ---------------------------------------------------------------------------------------------- content
@given(point_sets)
def test_content_matches_the_points(pts):
    ps = ps_of(pts)
    assert as_set(ps) == pts
    assert len(ps) == ps.count == len(pts)
    assert ps.is_empty() == (not pts) == (not ps)
    got = [tuple(p) for p in ps.points().tolist()]
    assert got == sorted(pts, key=lambda p: (p[1], p[0]))
    assert ps.points().dtype == np.int64
    for p in pts:
        assert p in ps
        assert (p[0] + 0.5, p[1]) not in ps
    if pts:
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        assert ps.bbox == (min(xs), min(ys), max(xs), max(ys))
        assert ps.origin == (min(xs), min(ys))
        assert ps.shape == (max(ys) - min(ys) + 1, max(xs) - min(xs) + 1)
        # canonical: the mask touches all four sides of its array
        m = ps.mask
        assert m[0].any() and m[-1].any() and m[:, 0].any() and m[:, -1].any()
    else:
        assert ps.bbox is None and ps.origin == (0, 0) and ps.shape == (0, 0)


@given(local_sets, boxes)
def test_to_array_is_the_box_indicator(pts, box):
    ps = ps_of(pts)
    a = ps.to_array(box)
    xmin, ymin, xmax, ymax = box
    assert a.shape == (max(0, ymax - ymin + 1), max(0, xmax - xmin + 1))
    assert a.flags.writeable
    expected = {(x, y) for x, y in box_points(box) if (x, y) in pts}
    got = {(xmin + int(c), ymin + int(r)) for r, c in zip(*np.nonzero(a), strict=True)}
    assert got == expected


def test_membership_of_odd_keys():
    ps = PixelSet.from_points([(1, 2)])
    assert (1, 2) in ps and (1.0, 2.0) in ps and (np.int64(1), np.int32(2)) in ps
    assert (1.5, 2) not in ps
    assert (float("nan"), 2) not in ps and (float("inf"), 2) not in ps
    assert "12" not in ps and (1, 2, 3) not in ps and ("a", 2) not in ps and [1, 2] not in ps
    assert (0, 0) not in PixelSet.empty()


def test_from_points_refuses_non_integers():
    with pytest.raises(ValueError, match="integers"):
        PixelSet.from_points([(0.5, 1.0)])
    assert PixelSet.from_points(np.array([[2.0, 3.0]])) == PixelSet.from_points([(2, 3)])
    assert PixelSet.from_points([]) == PixelSet.empty()
    assert PixelSet.from_points(np.zeros((0, 2), dtype=np.int64)).is_empty()


def test_box_constructor():
    assert as_set(PixelSet.box(-1, 2, 1, 3)) == box_points((-1, 2, 1, 3))
    assert PixelSet.box(3, 0, 2, 5).is_empty()


# ---------------------------------------------------------------------------------------------- set algebra
@given(local_sets, local_sets, shifts)
def test_set_algebra_matches_python_sets(a, b, shift):
    a, b = moved(a, shift), moved(b, shift)
    pa, pb = ps_of(a), ps_of(b)
    assert as_set(pa | pb) == a | b
    assert as_set(pa & pb) == a & b
    assert as_set(pa - pb) == a - b
    assert as_set(pa ^ pb) == a ^ b
    assert pa.union(pb) == ps_of(a | b)
    assert pa.intersection(pb) == ps_of(a & b)
    assert pa.difference(pb) == ps_of(a - b)
    assert pa.symmetric_difference(pb) == ps_of(a ^ b)
    assert pa.issubset(pb) == (a <= b)
    assert (pa | pb).issubset(pa | pb)


@settings(max_examples=60)
@given(local_sets, local_sets, local_sets)
def test_set_algebra_laws(a, b, c):
    pa, pb, pc = ps_of(a), ps_of(b), ps_of(c)
    assert (pa | pb) | pc == pa | (pb | pc)
    assert pa & (pb | pc) == (pa & pb) | (pa & pc)
    assert pa - (pb | pc) == (pa - pb) & (pa - pc)


@given(local_sets, boxes)
def test_complement_within_a_box(pts, box):
    ps = ps_of(pts)
    assert as_set(ps.complement(box)) == box_points(box) - pts


@given(local_sets, boxes)
def test_crop(pts, box):
    assert as_set(ps_of(pts).crop(box)) == pts & box_points(box)


def test_far_apart_sets():
    near = PixelSet.from_points([(0, 0), (1, 1)])
    far = PixelSet.from_points([(10**9, 10**9)])
    # results that fit are computed without touching the joint box ...
    assert (near & far).is_empty()
    assert near - far == near
    assert not near.issubset(far)
    assert as_set(near.crop((-(10**15), -(10**15), 10**15, 10**15))) == {(0, 0), (1, 1)}
    # ... and a union that would need a 10^18-pixel mask is refused before anything is allocated
    with pytest.raises(SizeLimitError):
        near | far
    with pytest.raises(SizeLimitError):
        near ^ far


# ---------------------------------------------------------------------------------------------- geometry
@given(point_sets, st.integers(-(10**9), 10**9), st.integers(-(10**9), 10**9))
def test_translate(pts, dx, dy):
    ps = ps_of(pts)
    moved = ps.translate(dx, dy)
    assert as_set(moved) == {(x + dx, y + dy) for x, y in pts}
    assert moved.translate(-dx, -dy) == ps


@given(point_sets, st.integers(-50, 50), st.integers(-50, 50))
def test_the_pixel_count_is_the_number_of_pixels_however_the_set_was_made(pts, dx, dy):
    """The count is kept once computed (the set is immutable): it stays right through every way of making
    a set from another."""
    ps = ps_of(pts)
    assert ps.count == len(pts)  # counted, then kept
    made = (
        ps.translate(dx, dy),
        pickle.loads(pickle.dumps(ps)),
        PixelSet.taking_over(np.array(ps.mask), ps.origin),
        ps.union(ps.translate(dx, dy)),
        ps.rotate90(1),
    )
    expected = (len(pts), len(pts), len(pts), len(pts | {(x + dx, y + dy) for x, y in pts}), len(pts))
    assert [m.count for m in made] == list(expected)


@given(point_sets, st.integers(-6, 6), point)
def test_rotate90_matches_complex_rotation(pts, k, center):
    ps = ps_of(pts)
    assert as_set(ps.rotate90(k, center)) == rot_ref(pts, k % 4, center)


@given(point_sets, st.integers(1, 4), point)
def test_rotate90_composes_to_identity(pts, k, center):
    ps = ps_of(pts)
    assert ps.rotate90(k, center).rotate90(4 - k, center) == ps
    r = ps
    for _ in range(4):
        r = r.rotate90(1, center)
    assert r == ps
    assert ps.rotate90(-1, center) == ps.rotate90(3, center)
    assert ps.rotate90(2, center) == ps.rotate90(1, center).rotate90(1, center)


def test_rotate90_example():
    # (1, 0) about (0, 0): a quarter turn counter-clockwise (y up) goes to (0, 1), then (-1, 0), then (0, -1).
    ps = PixelSet.from_points([(1, 0)])
    assert as_set(ps.rotate90(1)) == {(0, 1)}
    assert as_set(ps.rotate90(2)) == {(-1, 0)}
    assert as_set(ps.rotate90(3)) == {(0, -1)}
    assert as_set(PixelSet.from_points([(3, 2)]).rotate90(1, (2, 2))) == {(2, 3)}


@given(point_sets, st.integers(-20, 20))
def test_flips(pts, axis):
    ps = ps_of(pts)
    fx, fy = ps.flip_x(axis), ps.flip_y(axis)
    assert as_set(fx) == {(2 * axis - x, y) for x, y in pts}
    assert as_set(fy) == {(x, 2 * axis - y) for x, y in pts}
    assert fx.flip_x(axis) == ps and fy.flip_y(axis) == ps
    # two perpendicular mirrors through c make a half turn about c
    assert ps.flip_x(axis).flip_y(axis) == ps.rotate90(2, (axis, axis))


# ------------------------------------------------------------------------------------------ equality, hashing
@given(
    point_sets,
    st.integers(0, 4),
    st.integers(0, 4),
    st.integers(0, 4),
    st.integers(0, 4),
    st.sampled_from([bool, np.uint8, np.int32]),
)
def test_equality_ignores_padding_and_dtype(pts, top, bottom, left, right, dtype):
    ps = ps_of(pts)
    h, w = ps.shape
    padded = np.zeros((h + top + bottom, w + left + right), dtype=dtype)
    padded[bottom : bottom + h, left : left + w] = ps.mask
    x0, y0 = ps.origin
    other = PixelSet(padded, (x0 - left, y0 - bottom))
    assert other == ps
    assert hash(other) == hash(ps)
    assert other.origin == ps.origin and other.shape == ps.shape
    assert np.array_equal(other.mask, ps.mask)
    assert len({ps, other, ps_of(set(pts))}) == 1


@given(local_sets, local_sets)
def test_hash_consistent_with_equality(a, b):
    pa, pb = ps_of(a), ps_of(b)
    assert (pa == pb) == (a == b)
    if a == b:
        assert hash(pa) == hash(pb)
    # the same set built by algebra from pieces
    rebuilt = (pa & pb) | (pa - pb)
    assert rebuilt == pa and hash(rebuilt) == hash(pa)
    assert pa != frozenset(a) and pa != None  # noqa: E711 - comparing to foreign types is False


def test_empty_sets_are_equal_whatever_their_array():
    e1 = PixelSet(np.zeros((3, 5), dtype=bool), (7, -2))
    assert e1 == PixelSet.empty() == PixelSet.from_points([]) and hash(e1) == hash(PixelSet.empty())
    assert e1.origin == (0, 0)


# ---------------------------------------------------------------------------------------------- immutability
def test_mask_is_read_only_and_cannot_be_made_writable():
    ps = PixelSet.box(0, 0, 2, 2)
    with pytest.raises(ValueError):
        ps.mask[0, 0] = False
    with pytest.raises(ValueError):
        ps.mask.flags.writeable = True
    assert len(ps) == 9


def test_caller_arrays_are_not_aliased():
    a = np.ones((2, 3), dtype=bool)
    ps = PixelSet(a)
    h = hash(ps)
    a[:] = False
    assert len(ps) == 6 and hash(ps) == h
    # a read-only *view* of a writable array must be copied too
    b = np.ones((2, 2), dtype=bool)
    v = b.view()
    v.flags.writeable = False
    ps2 = PixelSet(v)
    b[0, 0] = False
    assert len(ps2) == 4
    # to_array hands out a copy
    arr = ps.to_array((0, 0, 2, 1))
    arr[:] = False
    assert len(ps) == 6


@given(point_sets, st.integers(-5, 5), st.integers(-5, 5))
def test_operations_return_new_frozen_sets(pts, dx, dy):
    ps = ps_of(pts)
    before = as_set(ps)
    results = [ps.translate(dx, dy), ps.rotate90(1), ps.flip_x(), ps | ps, ps.crop((-3, -3, 3, 3))]
    for r in results:
        assert not r.mask.flags.writeable
    assert as_set(ps) == before


def test_pickle_round_trip_keeps_value_and_immutability():
    ps = PixelSet.from_points([(0, 0), (3, -4)])
    hash(ps)
    back = pickle.loads(pickle.dumps(ps))
    assert back == ps and hash(back) == hash(ps)
    assert not back.mask.flags.writeable
    lm = LabelMap([[0, 2], [1, 0]], (5, 6))
    lback = pickle.loads(pickle.dumps(lm))
    assert lback == lm and not lback.labels.flags.writeable


# ---------------------------------------------------------------------------------------------- label maps
labelings = st.dictionaries(point, st.integers(1, 4), max_size=40)


@given(labelings)
def test_label_map_from_pixel_sets(labeling):
    parts = [ps_of({p for p, v in labeling.items() if v == k}) for k in range(1, 5)]
    lm = LabelMap.from_pixel_sets(parts)
    for k in range(1, 5):
        assert as_set(lm.pixel_set(k)) == {p for p, v in labeling.items() if v == k}
    assert lm.label_values() == sorted(set(labeling.values()))
    assert as_set(lm.support()) == set(labeling)
    assert lm.labels.dtype == np.int32
    assert not lm.labels.flags.writeable
    with pytest.raises(ValueError):
        lm.labels[...] = 0


@given(labelings, st.integers(0, 3), st.integers(0, 3))
def test_label_map_equality_ignores_padding(labeling, pad_lo, pad_hi):
    parts = [ps_of({p for p, v in labeling.items() if v == k}) for k in range(1, 5)]
    lm = LabelMap.from_pixel_sets(parts)
    h, w = lm.shape
    big = np.zeros((h + pad_lo + pad_hi, w + pad_lo + pad_hi), dtype=np.int64)
    big[pad_lo : pad_lo + h, pad_lo : pad_lo + w] = lm.labels
    other = LabelMap(big, (lm.origin[0] - pad_lo, lm.origin[1] - pad_lo))
    assert other == lm and hash(other) == hash(lm)


def test_label_map_refuses_overlapping_sets():
    a = PixelSet.from_points([(0, 0), (1, 0)])
    b = PixelSet.from_points([(1, 0), (5, 5)])
    with pytest.raises(ValueError, match="disjoint"):
        LabelMap.from_pixel_sets([a, b])


def test_label_map_refuses_bad_labels():
    with pytest.raises(ValueError):
        LabelMap(np.array([[-1, 0]]))
    with pytest.raises(ValueError):
        LabelMap(np.array([[2**31, 0]], dtype=np.int64))
    with pytest.raises(ValueError, match="integers"):
        LabelMap(np.array([[1.5, 0.0]]))
    with pytest.raises(ValueError):
        LabelMap(np.zeros(3, dtype=np.int32))


def test_label_map_does_not_alias_the_callers_array():
    a = np.array([[1, 0], [0, 2]], dtype=np.int32)
    lm = LabelMap(a)
    a[0, 0] = 7
    assert lm.label_values() == [1, 2]
    assert LabelMap.from_pixel_sets([]) == LabelMap(np.zeros((2, 2), dtype=np.int32))


@given(st.lists(st.sets(point, max_size=12), min_size=1, max_size=4))
def test_label_map_from_pixel_sets_refuses_exactly_the_overlapping_sets(sets):
    overlap = any(a & b for i, a in enumerate(sets) for b in sets[i + 1 :])
    if overlap:
        with pytest.raises(ValueError, match="disjoint"):
            LabelMap.from_pixel_sets([ps_of(s) for s in sets])
        return
    lm = LabelMap.from_pixel_sets([ps_of(s) for s in sets])
    for k, s in enumerate(sets, start=1):
        assert as_set(lm.pixel_set(k)) == s


# ---------------------------------------------------------------------------------------------- taking over
@given(
    st.lists(st.lists(st.booleans(), min_size=6, max_size=6), min_size=1, max_size=6),
    st.tuples(st.integers(-(10**9), 10**9), st.integers(-(10**9), 10**9)),
    st.sampled_from(["fresh", "view", "fortran", "uint8"]),
)
def test_taking_over_is_the_constructor(rows, origin, kind):
    """PixelSet.taking_over(m, o) is the set PixelSet(m, o), for canonical, padded, empty, viewed masks."""
    base = np.array(rows, dtype=bool)
    expected = PixelSet(base.copy(), origin)
    if kind == "fresh":
        mask = base.copy()
    elif kind == "view":
        mask = np.zeros((base.shape[0] + 2, base.shape[1] + 2), dtype=bool)
        mask[1:-1, 1:-1] = base
        mask = mask[1:-1, 1:-1]
    elif kind == "fortran":
        mask = np.asfortranarray(base)
    else:
        mask = base.astype(np.uint8)
    got = PixelSet.taking_over(mask, origin)
    assert got == expected and got.origin == expected.origin and got.mask.shape == expected.mask.shape
    assert hash(got) == hash(expected)
    assert not got.mask.flags.writeable
    with pytest.raises(ValueError):
        got.mask.flags.writeable = True


def test_taking_over_freezes_a_canonical_mask_in_place():
    """A fresh canonical mask is not copied (the point of taking_over); a padded one is cropped."""
    mask = np.ones((3, 4), dtype=bool)
    ps = PixelSet.taking_over(mask, (5, -2))
    assert np.shares_memory(ps.mask, mask) and not mask.flags.writeable
    assert ps == PixelSet.box(5, -2, 8, 0)
    padded = np.zeros((5, 6), dtype=bool)
    padded[1:4, 1:5] = True
    assert PixelSet.taking_over(padded, (4, -3)) == PixelSet.box(5, -2, 8, 0)
    assert PixelSet.taking_over(np.zeros((2, 2), dtype=bool), (7, 7)) == PixelSet.empty()
