"""VoxelSet and LabelVolume: the grid-set value of docs/design.md §11, checked against Python sets of points.

The reference is a plain ``set`` of integer triples: whatever a voxel set does must agree with it, whatever
the extent of the arrays it was built from.
"""

from __future__ import annotations

import pickle

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import SizeLimitError
from mrm.core.grids import LabelVolume, PixelSet, VoxelSet

coord = st.integers(-6, 6)
point = st.tuples(coord, coord, coord)
points = st.sets(point, max_size=40)


def vs_of(pts: set[tuple[int, int, int]]) -> VoxelSet:
    return VoxelSet.from_points(sorted(pts)) if pts else VoxelSet.empty()


def as_set(vs: VoxelSet) -> set[tuple[int, int, int]]:
    return {tuple(int(v) for v in p) for p in vs.points()}


@given(points, st.tuples(st.integers(0, 3), st.integers(0, 3), st.integers(0, 3)))
def test_a_mask_with_margins_is_the_same_set_as_its_points(pts, pad):
    # Built from a padded array placed anywhere: same points, same canonical value, same hash.
    a = vs_of(pts)
    if pts:
        lo = np.min(np.array(sorted(pts)), axis=0) - np.array(pad)
        hi = np.max(np.array(sorted(pts)), axis=0) + 2
        m = np.zeros(tuple((hi - lo)[::-1]), dtype=bool)
        for x, y, z in pts:
            m[z - lo[2], y - lo[1], x - lo[0]] = True
        b = VoxelSet(m, tuple(int(v) for v in lo))
    else:
        b = VoxelSet(np.zeros((2, 3, 1), dtype=bool), (5, 5, 5))
    assert as_set(a) == pts == as_set(b)
    assert a == b and hash(a) == hash(b)
    assert len(a) == len(pts)
    assert all(p in a for p in pts)
    assert (7, 7, 7) not in a and (0.5, 0, 0) not in a and (0, 0) not in a


@given(points, points)
def test_set_algebra_agrees_with_python_sets(p, q):
    a, b = vs_of(p), vs_of(q)
    assert as_set(a | b) == p | q
    assert as_set(a & b) == p & q
    assert as_set(a - b) == p - q
    assert as_set(a ^ b) == p ^ q
    assert a.issubset(a | b)


@given(points, point)
def test_translation_moves_every_voxel(p, t):
    moved = vs_of(p).translate(*t)
    assert as_set(moved) == {(x + t[0], y + t[1], z + t[2]) for x, y, z in p}


@given(points, st.integers(0, 3), st.sampled_from([0, 1, 2]), point)
def test_quarter_turns_follow_the_right_hand_rule(p, k, axis, c):
    def turn(v: tuple[int, int, int]) -> tuple[int, int, int]:
        w = [v[0] - c[0], v[1] - c[1], v[2] - c[2]]
        a, b = [(1, 2), (2, 0), (0, 1)][axis]
        for _ in range(k):
            w[a], w[b] = -w[b], w[a]
        return (w[0] + c[0], w[1] + c[1], w[2] + c[2])

    assert as_set(vs_of(p).rotate90(k, axis=axis, center=c)) == {turn(v) for v in p}


def test_a_quarter_turn_about_z_takes_x_to_y():
    # The right-hand rule, stated once without the code's table: x → y about z, y → z about x, z → x about y.
    assert as_set(VoxelSet.from_points([(1, 0, 0)]).rotate90(1, axis=2)) == {(0, 1, 0)}
    assert as_set(VoxelSet.from_points([(0, 1, 0)]).rotate90(1, axis=0)) == {(0, 0, 1)}
    assert as_set(VoxelSet.from_points([(0, 0, 1)]).rotate90(1, axis=1)) == {(1, 0, 0)}


@given(points, st.tuples(coord, coord, coord, coord, coord, coord))
def test_crop_and_complement_keep_the_points_of_the_box(p, b):
    box = (*(min(b[d], b[3 + d]) for d in range(3)), *(max(b[d], b[3 + d]) for d in range(3)))
    inside = {v for v in p if all(box[d] <= v[d] <= box[3 + d] for d in range(3))}
    a = vs_of(p)
    assert as_set(a.crop(box)) == inside
    full = {
        (x, y, z)
        for x in range(box[0], box[3] + 1)
        for y in range(box[1], box[4] + 1)
        for z in range(box[2], box[5] + 1)
    }
    assert as_set(a.complement(box)) == full - inside
    assert as_set(VoxelSet.box(*box)) == full


@given(points)
def test_pickling_gives_the_same_frozen_set(p):
    a = vs_of(p)
    for protocol in (2, 5):
        b = pickle.loads(pickle.dumps(a, protocol=protocol))
        assert b == a and isinstance(b, VoxelSet)
        assert not b.mask.flags.writeable


def test_a_voxel_set_is_immutable_and_never_equal_to_a_pixel_set():
    a = VoxelSet.from_points([(0, 0, 0), (1, 2, 3)])
    with pytest.raises(ValueError):
        a.mask[0, 0, 0] = False
    assert a.bbox == (0, 0, 0, 1, 2, 3)
    assert a.shape == (4, 3, 2)  # (nz, ny, nx)
    assert a != PixelSet.from_points([(0, 0)])
    with pytest.raises(ValueError, match="3-D"):
        VoxelSet(np.ones((2, 2), dtype=bool))


def test_the_union_of_far_apart_voxel_sets_is_refused_in_voxels_before_allocating():
    a = VoxelSet.from_points([(0, 0, 0)])
    b = VoxelSet.from_points([(2000, 2000, 2000)])
    with pytest.raises(SizeLimitError, match="voxels"):
        a | b


@settings(max_examples=50)
@given(st.lists(points, max_size=4))
def test_a_label_volume_gives_back_its_disjoint_parts(parts):
    seen: set[tuple[int, int, int]] = set()
    disjoint = []
    for p in parts:
        disjoint.append(p - seen)
        seen |= p
    lv = LabelVolume.from_sets(vs_of(p) for p in disjoint)
    for i, p in enumerate(disjoint, start=1):
        assert as_set(lv.voxel_set(i)) == p
        assert all(lv.label_at(v) == i for v in p)
    assert as_set(lv.support()) == seen
    assert pickle.loads(pickle.dumps(lv)) == lv
