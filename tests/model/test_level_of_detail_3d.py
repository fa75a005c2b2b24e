"""Coarser levels of a voxel set for the 3D views: max pooling, their surfels, the level within a budget."""

from __future__ import annotations

import numpy as np
import pytest

from mrm.geometry.topology.labeling_3d import label_runs_3d, surfel_count
from mrm.geometry.topology.level_of_detail import (
    boundary_surfels,
    cluster_vertices,
    coarse_level,
    coarse_mesh,
    pool_voxels,
    surfel_total,
)
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


def _uv_sphere(r: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """A closed sphere of 2·n·(n−1) triangles wound counter-clockwise seen from outside."""
    theta = np.linspace(0, np.pi, n + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, 2 * n, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    ring = np.stack([r * np.sin(t) * np.cos(p), r * np.sin(t) * np.sin(p), r * np.cos(t)], -1).reshape(-1, 3)
    v = np.vstack([[0, 0, r], ring, [0, 0, -r]])
    m = 2 * n
    tris = [[0, 1 + j, 1 + (j + 1) % m] for j in range(m)]
    for i in range(n - 2):
        for j in range(m):
            a, b = 1 + i * m + j, 1 + i * m + (j + 1) % m
            tris += [[a, a + m, b + m], [a, b + m, b]]
    last = len(v) - 1
    tris += [[last, 1 + (n - 2) * m + (j + 1) % m, 1 + (n - 2) * m + j] for j in range(m)]
    return v, np.array(tris)


def test_a_fine_mesh_is_clustered_within_a_triangle_budget_and_keeps_its_shape() -> None:
    v, t = _uv_sphere(50.0, 200)  # 79,600 triangles
    normal = np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]])
    assert (np.einsum("ij,ij->i", normal, v[t].mean(axis=1)) > 0).all()  # outward, as a polyhedron's
    cell, cv, ct, kept = coarse_mesh(v, t, 5000)
    assert cell > 0 and 0 < len(ct) <= 5000 and len(kept) == len(ct) and kept.max() < len(t)
    # every vertex stays near the sphere, and the triangles still face outward
    assert np.abs(np.linalg.norm(cv[np.unique(ct)], axis=1) - 50.0).max() <= cell * np.sqrt(3)
    n = np.cross(cv[ct[:, 1]] - cv[ct[:, 0]], cv[ct[:, 2]] - cv[ct[:, 0]])
    assert np.mean(np.einsum("ij,ij->i", n, cv[ct].mean(axis=1)) > 0) > 0.95
    # within the budget: the mesh itself
    cell, cv, ct, kept = coarse_mesh(v, t, len(t))
    assert cell == 0 and np.array_equal(ct, t) and np.array_equal(kept, np.arange(len(t)))
    with pytest.raises(ValueError):
        cluster_vertices(v, t, 0.0)
