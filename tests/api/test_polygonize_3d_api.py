"""mrm.polygonize on 3-D label volumes (docs/design.md §11: the existing functions accept 3D values)."""

from __future__ import annotations

import numpy as np
import pytest

import mrm
from mrm.core.errors import ParameterError


def labels_3d(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.integers(0, 4, (4, 5, 6))


@pytest.mark.parametrize("seed", range(3))
def test_each_region_of_a_label_array_burns_back_to_its_voxels_at_its_origin(seed):
    labels = labels_3d(seed)
    meshes = mrm.polygonize(labels, origin=(10, -3, 7))
    assert sum(r.voxels for r in meshes.regions) == np.count_nonzero(labels)
    union = {}
    for i, region in enumerate(meshes.regions):
        got = mrm.voxelize(meshes.polyhedron(i), "gauss")
        assert len(got) == region.voxels
        for x, y, z in got.points():
            assert labels[z - 7, y + 3, x - 10] == region.label  # its voxels, where the array puts them
            union[(x, y, z)] = region.label
    assert len(union) == np.count_nonzero(labels)  # the regions cover the labels once


def test_a_label_volume_and_its_array_give_the_same_meshes():
    vs = mrm.VoxelSet.box(0, 0, 0, 1, 1, 1)
    lv = mrm.LabelVolume.from_sets([vs, vs.translate(2, 0, 0)])
    by_volume = mrm.polygonize(lv)
    by_array = mrm.polygonize(lv.labels, origin=lv.origin)
    assert [(r.label, r.voxels) for r in by_volume.regions] == [(1, 8), (2, 8)]
    assert np.array_equal(by_volume.vertices, by_array.vertices)


def test_a_batch_mixes_label_maps_and_volumes():
    out = mrm.polygonize([np.array([[[1, 2]]]), np.array([[1, 2]])])
    assert [r.label for r in out[0].regions] == [1, 2]
    assert sorted(out[1]) == [1, 2]


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"transform": (1, 0, 0, 0, -1, 0)}, "no raster transform"),
        ({"origin": (5, 5)}, "voxel"),
        ({"model": "standard"}, "gauss"),
    ],
)
def test_what_a_label_volume_cannot_take_is_refused_clearly(kwargs, message):
    with pytest.raises(ParameterError, match=message):
        mrm.polygonize(np.array([[[1, 2]]]), **kwargs)
