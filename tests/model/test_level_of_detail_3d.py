"""Coarser levels of a voxel set for the 3D views: max pooling, their surfels, the level within a budget."""

from __future__ import annotations

import numpy as np
import pytest

from mrm.geometry.topology.labeling_3d import label_runs_3d, surfel_count
from mrm.geometry.topology.level_of_detail import boundary_surfels, coarse_level, pool_voxels, surfel_total
from mrm.geometry.topology.surfels import surfels_of


def _ball(r: int) -> np.ndarray:
    z, y, x = np.mgrid[-r : r + 1, -r : r + 1, -r : r + 1]
    return x * x + y * y + z * z <= r * r


def test_pooling_covers_every_voxel_and_adds_none_outside_the_blocks_of_the_set() -> None:
    rng = np.random.default_rng(3)
    m = rng.random((11, 7, 9)) < 0.05  # sizes not multiples of the factor: ragged last blocks
    for f in (1, 2, 3, 4, 20):
        p = pool_voxels(m, f)
        assert p.shape == tuple(-(-s // f) for s in m.shape)
        k, j, i = np.nonzero(m)
        assert p[k // f, j // f, i // f].all()  # the coarse set covers the fine one
        # a coarse voxel is set only when its block holds a voxel
        blocks = {(a // f, b // f, c // f) for a, b, c in zip(k, j, i, strict=True)}
        assert {tuple(map(int, t)) for t in np.argwhere(p)} == blocks


def test_the_surfels_of_a_mask_are_those_of_the_region_representation() -> None:
    rng = np.random.default_rng(5)
    m = rng.random((6, 8, 7)) < 0.4
    voxels, dirs = boundary_surfels(m)
    s = surfels_of(label_runs_3d(m.astype(np.uint8), 6))
    assert sorted(zip(map(tuple, voxels.tolist()), dirs.tolist(), strict=True)) == sorted(
        zip(map(tuple, s.voxel.tolist()), s.direction.tolist(), strict=True)
    )
    assert surfel_total(m) == len(dirs) == surfel_count(label_runs_3d(m.astype(np.uint8), 6))


def test_a_big_ball_is_drawn_at_the_finest_level_within_the_budget() -> None:
    m = _ball(60)  # 121³, about 67,000 surfels
    n = surfel_total(m)
    f, p = coarse_level(m, n)
    assert f == 1 and p.shape == m.shape  # within the budget: the set itself
    f, p = coarse_level(m, 10_000, n_surfels=n)
    assert f > 1 and surfel_total(p) <= 10_000
    assert surfel_total(pool_voxels(m, f - 1)) > 10_000 or f == 2  # the finest that fits
    assert p.sum() * f**3 >= m.sum()  # it still covers the ball
    f, p = coarse_level(m, 6)  # a budget of one cube: the whole ball in one block
    assert surfel_total(p) <= 6


def test_bad_factors_and_budgets_are_refused() -> None:
    with pytest.raises(ValueError):
        pool_voxels(np.ones((2, 2, 2), bool), 0)
    with pytest.raises(ValueError):
        coarse_level(np.ones((2, 2, 2), bool), 0)
    with pytest.raises(ValueError):
        boundary_surfels(np.ones((2, 2), bool))
