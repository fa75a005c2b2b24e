"""Voxel files (docs/design.md §11): every format reads back what was written, and hostile files are refused
with one clear line before anything large is decoded."""

from __future__ import annotations

import gzip
import os

import nibabel as nib
import numpy as np
import pytest
import tifffile
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mrm.core.errors import FileFormatError
from mrm.core.grids import LabelVolume, VoxelSet
from mrm.io.voxel_files import (
    is_volume_file,
    read_label_volume,
    read_volume,
    read_voxels,
    write_label_volume,
    write_voxels,
)

FORMATS = (".npz", ".tif", ".nii", ".nii.gz")
coord = st.integers(-5, 5)
voxels = st.sets(st.tuples(coord, coord, coord), max_size=30)


def vs_of(pts) -> VoxelSet:
    return VoxelSet.from_points(sorted(pts)) if pts else VoxelSet.empty()


@pytest.mark.parametrize("ext", FORMATS)
@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    pts=voxels, shift=st.tuples(st.integers(-1000, 1000), st.integers(-1000, 1000), st.integers(-1000, 1000))
)
def test_a_voxel_set_reads_back_equal_from_every_format(tmp_path, ext, pts, shift):
    vs = vs_of(pts).translate(*shift)
    path = tmp_path / f"v{ext}"
    write_voxels(vs, path)
    assert read_voxels(path) == vs
    assert is_volume_file(path)


@pytest.mark.parametrize("ext", FORMATS)
def test_a_label_volume_reads_back_equal_from_every_format(tmp_path, ext):
    rng = np.random.default_rng(3)
    labels = rng.integers(0, 300, size=(4, 5, 6)).astype(np.int32)
    lv = LabelVolume(labels, (7, -8, 9))
    path = tmp_path / f"l{ext}"
    write_label_volume(lv, path)
    assert read_label_volume(path) == lv


def test_a_tiff_stack_is_slices_from_the_bottom_with_row_zero_at_the_top(tmp_path):
    # Written by another program: page 0 is z = 0; the top row of a page is the highest y.
    stack = np.zeros((2, 3, 4), dtype=np.uint8)
    stack[1, 0, 3] = 255  # page 1, top row, last column
    path = tmp_path / "stack.tif"
    tifffile.imwrite(path, stack, photometric="minisblack")
    assert set(map(tuple, read_voxels(path).points().tolist())) == {(3, 2, 1)}


def test_a_nifti_affine_is_kept_as_the_placement_and_whole_voxel_moves_are_the_origin(tmp_path):
    data = np.zeros((3, 4, 5), dtype=np.uint8)  # NIfTI order: (i, j, k) = (x, y, z)
    data[2, 1, 0] = 1
    scaled = np.diag([0.5, 0.5, 2.0, 1.0])
    scaled[:3, 3] = (10.0, 20.0, 30.0)
    nib.save(nib.Nifti1Image(data, scaled), tmp_path / "mm.nii.gz")
    vol = read_volume(tmp_path / "mm.nii.gz")
    assert set(map(tuple, vol.value.points().tolist())) == {(2, 1, 0)}
    assert vol.affine is not None and np.array_equal(vol.affine, scaled)
    moved = np.eye(4)
    moved[:3, 3] = (4, -5, 6)
    nib.save(nib.Nifti1Image(data, moved), tmp_path / "moved.nii")
    vol = read_volume(tmp_path / "moved.nii")
    assert vol.affine is None and set(map(tuple, vol.value.points().tolist())) == {(6, -4, 6)}
    # and the placement goes back out with the voxels
    write_voxels(vol.value, tmp_path / "back.nii", affine=scaled)
    again = read_volume(tmp_path / "back.nii")
    assert np.allclose(again.affine @ [0, 0, 0, 1], scaled @ [6, -4, 6, 1])


def test_a_grey_volume_asks_for_a_threshold_or_labels(tmp_path):
    grey = np.arange(60, dtype=np.uint8).reshape(3, 4, 5)
    tifffile.imwrite(tmp_path / "grey.tif", grey, photometric="minisblack")
    with pytest.raises(FileFormatError, match=r"threshold.*label volume"):
        read_voxels(tmp_path / "grey.tif")
    assert len(read_voxels(tmp_path / "grey.tif", threshold=29.5)) == 30
    assert read_label_volume(tmp_path / "grey.tif").label_values() == list(range(1, 60))


def test_a_four_dimensional_nifti_is_refused_with_its_volume_count(tmp_path):
    nib.save(nib.Nifti1Image(np.zeros((3, 3, 3, 7), dtype=np.uint8), np.eye(4)), tmp_path / "series.nii")
    with pytest.raises(FileFormatError, match="series of 7 volumes"):
        read_voxels(tmp_path / "series.nii")


def test_a_nifti_declaring_far_more_voxels_than_it_holds_is_refused_from_its_header(tmp_path):
    header = nib.Nifti1Header()
    header.set_data_dtype(np.uint8)
    header.set_data_shape((4000, 4000, 4000))
    raw = header.binaryblock + b"\x00" * 4 + b"\x00" * 1000
    (tmp_path / "bomb.nii.gz").write_bytes(gzip.compress(raw))
    with pytest.raises(FileFormatError, match="64,000,000,000 voxels"):
        read_voxels(tmp_path / "bomb.nii.gz")
    header.set_data_shape((10, 10, 10))
    (tmp_path / "short.nii").write_bytes(header.binaryblock + b"\x00" * 4 + b"\x01" * 10)
    with pytest.raises(FileFormatError, match="truncated"):
        read_voxels(tmp_path / "short.nii")


def test_a_tiff_declaring_huge_pages_is_refused_before_decoding(tmp_path):
    path = tmp_path / "bomb.tif"
    tifffile.imwrite(path, np.ones((3, 4, 4), dtype=np.uint8), photometric="minisblack", compression="zlib")
    with tifffile.TiffFile(path, mode="r+b") as tif:
        for page in tif.pages:
            page.tags["ImageWidth"].overwrite(65535)
            page.tags["ImageLength"].overwrite(65535)
    with pytest.raises(FileFormatError, match="more than the limit"):
        read_voxels(path)


@pytest.mark.parametrize(
    "content, message",
    [
        (b"", "not a TIFF"),
        (b"P4\n1 1\n\x00", "not a TIFF"),
        (b"II*\x00garbage", "TIFF holds no image|unreadable TIFF"),
    ],
)
def test_corrupt_tiffs_get_one_line(tmp_path, content, message):
    (tmp_path / "x.tif").write_bytes(content)
    with pytest.raises(FileFormatError, match=message):
        read_voxels(tmp_path / "x.tif")


def test_a_fifo_named_like_a_volume_is_refused_without_waiting(tmp_path):
    fifo = tmp_path / "pipe.nii"
    os.mkfifo(fifo)
    with pytest.raises(FileFormatError, match="named pipe"):
        read_voxels(fifo)


def test_a_two_dimensional_npz_is_not_a_volume_and_says_so(tmp_path):
    np.savez(tmp_path / "flat.npz", mask=np.ones((2, 2), dtype=bool), origin=np.zeros(2, dtype=np.int64))
    assert not is_volume_file(tmp_path / "flat.npz")
    with pytest.raises(FileFormatError, match="3-D boolean"):
        read_voxels(tmp_path / "flat.npz")


def test_a_write_that_fails_leaves_the_old_file(tmp_path):
    path = tmp_path / "keep.npz"
    write_voxels(VoxelSet.from_points([(0, 0, 0)]), path)
    before = path.read_bytes()
    with pytest.raises(FileFormatError):
        write_voxels(VoxelSet.from_points([(1, 1, 1)]), tmp_path / "keep.obj")
    assert path.read_bytes() == before


def test_a_volume_placed_beyond_the_documents_coordinates_is_refused(tmp_path):
    np.savez(
        tmp_path / "far.npz",
        mask=np.ones((1, 1, 2), dtype=bool),
        origin=np.array([2**31, 0, 0], dtype=np.int64),  # its second voxel is at x = 2^31 + 1
    )
    with pytest.raises(FileFormatError, match=r"origin \(2147483648, 0, 0\) puts voxels beyond"):
        read_voxels(tmp_path / "far.npz")
