"""Voxel sets and label volumes in files that keep their place on the grid (docs/design.md §11).

Formats, chosen by the file extension:

``.npz``
    ``mask`` (3-D bool, ``[k, j, i]`` = ``[z, y, x]``, the in-memory layout) and ``origin`` (int64 x0, y0,
    z0); label volumes store ``labels`` (int32) instead of ``mask``. Nothing is ever unpickled
    (:mod:`mrm.io.npz_arrays`, shared with pixel files).
``.tif``, ``.tiff`` (a multi-page TIFF, :mod:`tifffile`)
    Page k is the slice z = z0 + k; within a page row 0 is the top row, as in every image: row r of an
    H-row page is y = y0 + H − 1 − r, column c is x = x0 + c. The origin is kept in the TIFF's JSON
    description (``mrm:origin``); without it the volume is placed at the origin. Masks are written as
    8-bit pages of 0 and 255.
``.nii``, ``.nii.gz`` (NIfTI-1, :mod:`nibabel`)
    The data array's index (i, j, k) is voxel (x0 + i, y0 + j, z0 + k). The file's affine (voxel index →
    world millimetres) is the volume's **placement**, kept beside the voxels as a GeoTIFF's transform is
    kept in 2D; an affine that only moves by whole voxels is folded into the origin instead, so a volume
    written here reads back equal.

Reading refuses, before anything is decoded: files of other kinds, volumes whose declared size exceeds the
limits (whatever their compressed size), 4-D NIfTI series, colour stacks, and grey or label volumes where a
mask is expected unless a threshold is given (:func:`read_voxels` says which choices there are). Writes are
atomic (:mod:`mrm.io.atomic`).
"""

from __future__ import annotations

import gzip
import io
import logging
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from mrm.core import limits
from mrm.core.errors import FileFormatError
from mrm.core.grids import LabelVolume, VoxelSet
from mrm.core.threshold import _check_threshold
from mrm.io.atomic import atomic_write_bytes
from mrm.io.npz_arrays import npz_bytes, npz_origin, read_npz_arrays
from mrm.io.pixel_files import check_file_extent
from mrm.io.reading import describe_content, open_regular

log = logging.getLogger(__name__)

PathLike = str | os.PathLike[str]

#: Extensions of voxel files, read and written by :func:`read_voxels` / :func:`write_voxels` and the
#: label-volume functions.
VOXEL_EXTENSIONS = (".npz", ".tif", ".tiff", ".nii", ".nii.gz")
#: The key of the origin in a TIFF's JSON description.
ORIGIN_KEY = "mrm:origin"

Affine = npt.NDArray[np.float64]
#: Where a NIfTI's data may start at the latest (its header and extensions before it).
_MAX_NIFTI_OFFSET = 1 << 20


@dataclass(frozen=True)
class Volume:
    """What a voxel file holds: the voxels (or labels) and, for NIfTI, the placement in the world.

    Attributes
    ----------
    value : VoxelSet or LabelVolume
        The voxels, at their grid coordinates.
    affine : numpy.ndarray of shape (4, 4), or None
        The map from voxel coordinates (x, y, z, 1) to world coordinates; None when the file has none beyond
        whole-voxel moves (those are the origin).
    """

    value: VoxelSet | LabelVolume
    affine: Affine | None = None


# ---------------------------------------------------------------------------------------------- helpers
def _extension(path: PathLike) -> str:
    name = Path(path).name.lower()
    if name.endswith(".nii.gz"):
        return ".nii.gz"
    ext = Path(path).suffix.lower()
    if ext not in VOXEL_EXTENSIONS:
        shown = f"'{ext}'" if ext else "no extension"
        raise FileFormatError(
            f"{os.fspath(path)}: {shown} is not a voxel file type; use .npz, .tif, .tiff, .nii or .nii.gz"
        )
    return ext


def _check_count(shape: tuple[int, ...], itemsize: int, limit: int, name: str) -> None:
    """Refuse a volume whose declared size exceeds ``limit`` voxels (or its bytes), before reading it."""
    count = 1
    for d in shape:
        count *= int(d)
    if count > limit:
        dims = " × ".join(str(int(d)) for d in shape)
        raise FileFormatError(
            f"{name}: the volume is {dims} = {count:,} voxels, more than the limit of {limit:,}"
        )
    if count * itemsize > 8 * limits.DEFAULT_VOXEL_LIMIT:
        raise FileFormatError(f"{name}: the volume would take {count * itemsize:,} bytes in memory")


def _as_mask(data: npt.NDArray[Any], threshold: float | None, name: str) -> npt.NDArray[np.bool_]:
    """A binary volume's non-zero voxels, or those above ``threshold`` (a grey one without it: refused)."""
    if data.dtype == np.bool_:
        return data
    if data.dtype.kind not in "iuf":
        raise FileFormatError(f"{name}: voxels of type {data.dtype} are not numbers")
    if threshold is not None:
        above: npt.NDArray[np.bool_] = np.asarray(data > threshold)  # NaN is never above it: background
        return above
    if data.dtype.kind == "f" and bool(np.isnan(data).any()):
        raise FileFormatError(
            f"{name}: the volume holds NaN values; give a threshold to say which voxels are in"
        )
    top = data.max() if data.size else 0
    nz: npt.NDArray[np.bool_] = np.asarray(data != 0)
    if data.size and (data.min() < 0 or np.count_nonzero(nz & (data != top))):
        raise FileFormatError(
            f"{name}: the volume holds more than two values (grey levels or labels), so it is not a mask; "
            "give a threshold (--threshold T: voxels above T are in) or read it as a label volume "
            "(mrm polygonize)"
        )
    return nz


def _read_bounded(path: PathLike, name: str) -> bytes:
    """The bytes of a regular file of at most :data:`~mrm.core.limits.MAX_FILE_BYTES` (compressed data)."""
    with open_regular(path, name) as fh:
        raw = fh.read(limits.MAX_FILE_BYTES + 1)
    if len(raw) > limits.MAX_FILE_BYTES:
        raise FileFormatError(f"{name}: the file is larger than {limits.MAX_FILE_BYTES:,} bytes")
    return raw


# ---------------------------------------------------------------------------------------------- TIFF
def _read_tiff(path: PathLike, name: str, limit: int) -> tuple[npt.NDArray[Any], tuple[int, int, int]]:
    """The (z, y, x) array of a multi-page TIFF (y already turned to grow with the index) and its origin."""
    import tifffile  # only when a TIFF is read: it is not needed for anything else

    raw = _read_bounded(path, name)
    if raw[:4] not in (b"II*\x00", b"MM\x00*", b"II+\x00", b"MM\x00+"):
        raise FileFormatError(f"{name}: not a TIFF ({describe_content(raw[:16])})")
    try:
        with tifffile.TiffFile(io.BytesIO(raw)) as tif:
            series = tif.series
            if not series:
                raise FileFormatError(f"{name}: the TIFF holds no image")
            s = series[0]
            shape = tuple(int(d) for d in s.shape)
            if len(series) > 1:
                raise FileFormatError(
                    f"{name}: the TIFF holds {len(series)} image series of different shapes; a voxel "
                    "file holds one stack of equal slices"
                )
            if len(shape) == 2:
                raise FileFormatError(f"{name}: the TIFF holds one image, not a stack: read it as pixels")
            if len(shape) != 3 or s.axes[-1] == "S":
                raise FileFormatError(
                    f"{name}: the TIFF's stack has shape {shape} (axes {s.axes}); a voxel file holds "
                    "slices of one grey channel (colour stacks are not masks)"
                )
            _check_count(shape, np.dtype(s.dtype).itemsize, limit, name)
            meta = tif.shaped_metadata[0] if tif.shaped_metadata else {}
            data = s.asarray()
    except FileFormatError:
        raise
    except MemoryError:
        raise FileFormatError(f"{name}: not enough memory to read the TIFF") from None
    except Exception as e:  # tifffile's TiffFileError, zlib/codec errors, truncated strips
        raise FileFormatError(f"{name}: unreadable TIFF: {e}") from None
    origin = _origin_of(meta.get(ORIGIN_KEY) if isinstance(meta, dict) else None, name)
    return np.ascontiguousarray(data[:, ::-1, :]), origin


def _origin_of(value: Any, name: str) -> tuple[int, int, int]:
    if value is None:
        return (0, 0, 0)
    if (
        not isinstance(value, list)
        or len(value) != 3
        or not all(isinstance(v, int) and not isinstance(v, bool) for v in value)
    ):
        raise FileFormatError(f"{name}: malformed {ORIGIN_KEY} {value!r:.60}: expected three integers")
    return (int(value[0]), int(value[1]), int(value[2]))


def _tiff_bytes(data: npt.NDArray[Any], origin: tuple[int, int, int]) -> bytes:
    import tifffile

    buf = io.BytesIO()
    # Slices written top row first, as every image; deflate keeps masks and labels small.
    tifffile.imwrite(
        buf,
        np.ascontiguousarray(data[:, ::-1, :]),
        photometric="minisblack",
        metadata={ORIGIN_KEY: list(origin)},
        compression="zlib",
    )
    return buf.getvalue()


# ---------------------------------------------------------------------------------------------- NIfTI
def _read_nifti(path: PathLike, name: str, ext: str, limit: int) -> tuple[npt.NDArray[Any], Affine]:
    """The (z, y, x) array of a NIfTI-1 file and its affine (voxel index → world)."""
    import nibabel as nib  # only when a NIfTI is read

    raw = _read_bounded(path, name)
    stream: io.IOBase = io.BytesIO(raw)
    if ext == ".nii.gz":
        if raw[:2] != b"\x1f\x8b":
            raise FileFormatError(f"{name}: not a gzip-compressed NIfTI ({describe_content(raw[:16])})")
        stream = gzip.GzipFile(fileobj=io.BytesIO(raw))
    try:
        header = nib.Nifti1Header.from_fileobj(stream, check=True)  # type: ignore[no-untyped-call]
    except Exception as e:  # HeaderDataError, wrong sizeof_hdr, truncated gzip, …
        raise FileFormatError(f"{name}: not a NIfTI-1 file ({e})") from None
    shape = tuple(int(d) for d in header.get_data_shape())
    if len(shape) == 4 and shape[3] == 1:
        shape = shape[:3]
    if len(shape) == 4:
        raise FileFormatError(
            f"{name}: the NIfTI holds a series of {shape[3]} volumes (4-D); a voxel file holds one volume — "
            "extract the one you want first"
        )
    if len(shape) != 3:
        raise FileFormatError(f"{name}: the NIfTI's data has {len(shape)} dimensions; a volume has 3")
    dtype = header.get_data_dtype()
    if dtype.kind not in "biuf" or dtype.fields is not None:
        raise FileFormatError(
            f"{name}: NIfTI voxels of type {dtype} (colour or complex) are not a mask or labels"
        )
    _check_count(shape, dtype.itemsize, limit, name)
    offset = int(header.get_data_offset())
    if offset > _MAX_NIFTI_OFFSET:
        raise FileFormatError(
            f"{name}: the NIfTI's data starts {offset:,} bytes in (its header extensions are too large)"
        )
    # Never more than the header says: a gzip bomb decompresses only as far as the declared data.
    wanted = max(offset, 352) + int(np.prod(shape, dtype=np.int64)) * dtype.itemsize
    try:
        stream.seek(0)
        blob = stream.read(wanted)
        if len(blob) < wanted:
            raise FileFormatError(
                f"{name}: the NIfTI is truncated: {wanted:,} bytes expected, {len(blob):,} found"
            )
        img = nib.Nifti1Image.from_bytes(blob)
        data = np.asarray(img.dataobj).reshape(shape, order="F")
        affine = np.asarray(img.affine, dtype=np.float64)
    except FileFormatError:
        raise
    except MemoryError:
        raise FileFormatError(f"{name}: not enough memory to read the NIfTI") from None
    except Exception as e:  # bad offsets, gzip errors
        raise FileFormatError(f"{name}: unreadable NIfTI data: {e}") from None
    if not np.isfinite(affine).all():
        raise FileFormatError(f"{name}: the NIfTI's affine holds non-finite numbers")
    return np.ascontiguousarray(data.transpose(2, 1, 0)), affine


def _split_affine(affine: Affine) -> tuple[tuple[int, int, int], Affine | None]:
    """An affine that only moves by whole voxels is an origin; any other one is kept as the placement."""
    linear, t = affine[:3, :3], affine[:3, 3]
    if (
        np.array_equal(linear, np.eye(3))
        and np.array_equal(affine[3], [0, 0, 0, 1])
        and np.array_equal(t, np.round(t))
        and bool(np.all(np.abs(t) <= limits.PIXEL_COORDINATE_LIMIT))
    ):
        return (int(t[0]), int(t[1]), int(t[2])), None
    return (0, 0, 0), affine


def _nifti_bytes(
    data: npt.NDArray[Any], origin: tuple[int, int, int], affine: Affine | None, gz: bool
) -> bytes:
    import nibabel as nib

    move = np.eye(4)
    move[:3, 3] = origin
    placed = move if affine is None else np.asarray(affine, dtype=np.float64) @ move
    img = nib.Nifti1Image(np.asfortranarray(data.transpose(2, 1, 0)), placed)  # type: ignore[no-untyped-call]
    raw: bytes = img.to_bytes()
    # mtime=0: the same volume gives the same bytes
    return gzip.compress(raw, mtime=0) if gz else raw


# ---------------------------------------------------------------------------------------------- reading
def _read_array(
    path: PathLike, key: str, limit: int
) -> tuple[npt.NDArray[Any], tuple[int, ...], Affine | None]:
    name = os.fspath(path)
    ext = _extension(path)
    affine: Affine | None = None
    if ext == ".npz":
        with open_regular(path, name) as fh:
            arrays = read_npz_arrays(fh, name, (key, "origin"), limit, ndim=3, optional=("origin",))
        data = arrays[key]
        origin = npz_origin(arrays["origin"], name, 3) if "origin" in arrays else (0, 0, 0)
    elif ext in (".tif", ".tiff"):
        data, origin = _read_tiff(path, name, limit)
    else:
        data, file_affine = _read_nifti(path, name, ext, limit)
        origin, affine = _split_affine(file_affine)
    check_file_extent(origin, data.shape, name)
    return data, origin, affine


def read_volume(
    path: PathLike, *, threshold: float | None = None, labels: bool = False, limit: int | None = None
) -> Volume:
    """Read a voxel set (or, with ``labels=True``, a label volume) and its placement from a voxel file.

    Parameters
    ----------
    path : str or path-like
        A ``.npz``, multi-page ``.tif``/``.tiff``, ``.nii`` or ``.nii.gz`` file (see the module notes).
    threshold : float, optional
        Voxels whose value is greater than it are in the set. Without it a volume must be binary (0 and one
        other value); a grey or label volume is refused with a message that names both choices.
    labels : bool
        Read the values as labels (non-negative integers, 0 = background) instead of a mask.
    limit : int, optional
        The most voxels of the volume's box (default :data:`~mrm.core.limits.DEFAULT_VOXEL_LIMIT`, and
        :data:`~mrm.core.limits.MAX_LABEL_VOXELS` for labels), checked from the header before decoding.

    Returns
    -------
    Volume

    Raises
    ------
    FileFormatError
        Unknown extension; a corrupt, truncated, hostile, 4-D, colour or too large file; a grey volume where
        a mask is expected.
    ParameterError
        A non-finite threshold.
    """
    if threshold is not None:
        threshold = _check_threshold(threshold)
    name = os.fspath(path)
    if labels:
        data, origin, affine = _read_array(
            path, "labels", limits.MAX_LABEL_VOXELS if limit is None else limit
        )
        if data.dtype.kind not in "biu" or (
            data.size and (data.min() < 0 or data.max() > np.iinfo(np.int32).max)
        ):
            raise FileFormatError(
                f"{name}: labels must be non-negative 32-bit integers, found {data.dtype} values"
            )
        return Volume(LabelVolume(data, origin), affine)
    data, origin, affine = _read_array(path, "mask", limits.DEFAULT_VOXEL_LIMIT if limit is None else limit)
    return Volume(VoxelSet(_as_mask(data, threshold, name), origin), affine)


def read_voxels(path: PathLike, *, threshold: float | None = None, limit: int | None = None) -> VoxelSet:
    """Read a voxel set from a voxel file (:func:`read_volume` without the placement).

    Examples
    --------
    >>> import mrm, numpy as np, tempfile, os
    >>> ball = mrm.VoxelSet.from_points([(x, y, z) for x in range(-2, 3) for y in range(-2, 3)
    ...                                  for z in range(-2, 3) if x * x + y * y + z * z <= 4])
    >>> path = os.path.join(tempfile.mkdtemp(), "ball.npz")
    >>> mrm.write_voxels(ball, path)
    >>> mrm.read_voxels(path) == ball
    True
    """
    value = read_volume(path, threshold=threshold, limit=limit).value
    assert isinstance(value, VoxelSet)
    return value


def read_label_volume(path: PathLike, *, limit: int | None = None) -> LabelVolume:
    """Read a label volume (non-negative integers, 0 = background) from a voxel file."""
    value = read_volume(path, labels=True, limit=limit).value
    assert isinstance(value, LabelVolume)
    return value


# ---------------------------------------------------------------------------------------------- writing
def _write(
    path: PathLike, key: str, data: npt.NDArray[Any], origin: tuple[int, int, int], affine: Affine | None
) -> None:
    ext = _extension(path)
    if ext == ".npz":
        blob = npz_bytes(**{key: data, "origin": np.array(origin, dtype=np.int64)})
    elif ext in (".tif", ".tiff"):
        blob = _tiff_bytes(data, origin)
    else:
        blob = _nifti_bytes(data, origin, affine, ext == ".nii.gz")
    if affine is not None and ext not in (".nii", ".nii.gz"):
        log.warning(
            "%s keeps no placement: the volume's affine is not written (use .nii or .nii.gz)", os.fspath(path)
        )
    atomic_write_bytes(path, blob)


def write_voxels(vs: VoxelSet, path: PathLike, *, affine: Affine | None = None) -> None:
    """Write a voxel set to a ``.npz``, multi-page ``.tif`` or NIfTI file, atomically; it reads back equal.

    ``affine`` (NIfTI only) is the placement to keep (see :class:`Volume`). The empty set is written as one
    background voxel at the origin, which reads back empty.

    Raises
    ------
    FileFormatError
        For an extension that is not a voxel file type.
    """
    if vs.is_empty():
        data: npt.NDArray[Any] = np.zeros((1, 1, 1), dtype=bool)
        origin = (0, 0, 0)
    else:
        data, origin = np.asarray(vs.mask), vs.origin
    ext = _extension(path)
    if ext != ".npz":
        data = data.astype(np.uint8) * np.uint8(255)  # viewers show 0/255 stacks; any non-zero reads back in
    _write(path, "mask", data, origin, affine)


def write_label_volume(lv: LabelVolume, path: PathLike, *, affine: Affine | None = None) -> None:
    """Write a label volume to a ``.npz``, multi-page ``.tif`` or NIfTI file, atomically; it reads back equal.

    Raises
    ------
    FileFormatError
        For an extension that is not a voxel file type.
    ParameterError
        Never for these formats (every int32 label fits); kept for symmetry with 2D label maps.
    """
    if lv.is_empty():
        data: npt.NDArray[Any] = np.zeros((1, 1, 1), dtype=np.int32)
        origin = (0, 0, 0)
    else:
        data, origin = np.asarray(lv.labels), lv.origin
    if data.size and int(data.max()) <= 65535 and _extension(path) in (".tif", ".tiff"):
        data = data.astype(np.uint16 if int(data.max()) > 255 else np.uint8)
    _write(path, "labels", data, origin, affine)


def is_volume_file(path: PathLike) -> bool:
    """True when ``path`` names a voxel file by its extension and, for ``.npz``/``.tif``, by what it holds.

    Decides from headers only (a 3-D ``mask``/``labels`` array, a TIFF with more than one page), so that
    ``mrm info`` can take 2D and 3D files alike.
    """
    ext = Path(path).name.lower()
    if ext.endswith((".nii", ".nii.gz")):
        return True
    name = os.fspath(path)
    if ext.endswith(".npz"):
        import zipfile

        try:
            with open_regular(path, name) as fh, zipfile.ZipFile(fh) as zf:
                for member in ("mask.npy", "labels.npy"):
                    if member in zf.namelist():
                        with zf.open(member) as m:
                            fmt = np.lib.format
                            version = fmt.read_magic(m)
                            read = (
                                fmt.read_array_header_1_0 if version == (1, 0) else fmt.read_array_header_2_0
                            )
                            shape = read(m)[0]
                            return len(shape) == 3
        except (OSError, ValueError, FileFormatError, zipfile.BadZipFile):
            return False
        return False
    if ext.endswith((".tif", ".tiff")):
        import tifffile

        try:
            open_regular(path, name).close()  # a FIFO or device is refused before tifffile opens it
            with tifffile.TiffFile(name) as tif:
                return bool(tif.series) and len(tif.series[0].shape) == 3 and tif.series[0].axes[-1] != "S"
        except Exception:  # not a readable TIFF: the 2D reader will say why
            return False
    return False


__all__ = [
    "VOXEL_EXTENSIONS",
    "Volume",
    "is_volume_file",
    "read_label_volume",
    "read_volume",
    "read_voxels",
    "write_label_volume",
    "write_voxels",
]
