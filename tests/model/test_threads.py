"""The geometry's worker threads (mrm.geometry._threads) and the discretization's marking shared by them."""

from __future__ import annotations

import threading

import numpy as np
import pytest

import mrm.geometry._threads as th
import mrm.geometry.discretize.voxels as voxels
from tests.model.test_snapped_core_3d import random_hull


def test_shared_work_comes_back_in_order_on_several_threads(monkeypatch):
    monkeypatch.setenv("MRM_THREADS", "2")
    names = set()

    def work(i: int) -> int:
        names.add(threading.current_thread().name)
        threading.Event().wait(0.002)  # long enough for the helper to take some
        return i * i

    assert th.share_out(work, 40) == [i * i for i in range(40)]
    assert len(names) == 2


def test_one_thread_does_all_the_work_itself(monkeypatch):
    monkeypatch.setenv("MRM_THREADS", "1")
    names = set()

    def work(i: int) -> int:
        names.add(threading.current_thread().name)
        return -i

    assert th.share_out(work, 5) == [0, -1, -2, -3, -4]
    assert names == {threading.current_thread().name}


def test_an_error_in_a_share_reaches_the_caller(monkeypatch):
    monkeypatch.setenv("MRM_THREADS", "2")

    def work(i: int) -> int:
        if i == 7:
            raise ValueError("chunk 7")
        return i

    with pytest.raises(ValueError, match="chunk 7"):
        th.share_out(work, 12)


def test_sharing_from_inside_a_busy_pool_does_not_wait_for_it(monkeypatch):
    # Every worker of the pool runs a task that shares out its own work: none may wait for a helper that
    # cannot start (the helpers that never started are cancelled).
    monkeypatch.setenv("MRM_THREADS", "2")
    pool = th.side_pool()
    assert pool is not None
    release = threading.Event()

    def nested(k: int) -> list[int]:
        release.wait(5)
        return th.share_out(lambda i: i + k, 6)

    futures = [pool.submit(nested, k) for k in range(th.MAX_THREADS)]
    release.set()
    expected = [[i + k for i in range(6)] for k in range(th.MAX_THREADS)]
    assert [f.result(timeout=20) for f in futures] == expected


@pytest.mark.parametrize("model", ["standard", "supercover"])
def test_a_mesh_marked_in_chunks_on_two_threads_is_marked_as_on_one(model, monkeypatch):
    # The covers' marking shares its triangles between threads in chunks: the same voxels, exactly.
    rng = np.random.default_rng(5)
    q, tris = random_hull(rng.integers(-300, 300, (400, 3)))
    v = q / 16.0
    monkeypatch.setenv("MRM_THREADS", "1")
    one = voxels.voxelize_solid(v, tris, model, limit=None)
    surface = voxels.voxelize_triangles(v, tris, model, limit=None)
    monkeypatch.setenv("MRM_THREADS", "2")
    monkeypatch.setattr(voxels, "MARK_CHUNK", 4)
    assert tris.shape[0] > 20 * 4
    two = voxels.voxelize_solid(v, tris, model, limit=None)
    assert two[1] == one[1] and np.array_equal(two[0], one[0])
    again = voxels.voxelize_triangles(v, tris, model, limit=None)
    assert again[1] == surface[1] and np.array_equal(again[0], surface[0])
