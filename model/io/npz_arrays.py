"""The .npz archives of pixel and voxel files: arrays read header first, never unpickled (ADR 0010).

One reader for both dimensions: a pixel file holds a 2-D ``mask`` (or ``labels``) and two ``origin``
integers, a voxel file a 3-D one and three (docs/design.md §1, §11). Each array's header (dtype, shape) is
checked against its role and the limits before a byte of its data is read.
"""

from __future__ import annotations

import io
import zipfile
from typing import IO, Any, BinaryIO

import numpy as np
import numpy.typing as npt

from mrm.core import limits
from mrm.core.errors import FileFormatError
from mrm.io.reading import describe_content

_COUNT = {2: "two", 3: "three"}
_ORIGIN = {2: "(x0, y0)", 3: "(x0, y0, z0)"}
#: Most bytes of a mask (one byte per point) and of int32 labels, per dimension.
_MASK_BYTES = {2: limits.MAX_OBJECT_PIXELS, 3: limits.DEFAULT_VOXEL_LIMIT}
_LABEL_BYTES = {2: 4 * limits.MAX_LABEL_PIXELS, 3: 4 * limits.MAX_LABEL_VOXELS}


def _role(key: str, ndim: int) -> tuple[str, int, int, str]:
    """Per NPZ array: the dtype kinds accepted, its dimensions, the most bytes read and how to say it."""
    if key == "mask":
        return ("b", ndim, _MASK_BYTES[ndim], f"a {ndim}-D boolean array")
    if key == "labels":
        return ("iu", ndim, _LABEL_BYTES[ndim], f"a {ndim}-D integer array")
    return ("iu", 1, 64, f"{_COUNT[ndim]} integers {_ORIGIN[ndim]}")


def read_npz_arrays(
    fh: BinaryIO,
    name: str,
    keys: tuple[str, ...],
    limit: int,
    *,
    ndim: int,
    optional: tuple[str, ...] = (),
) -> dict[str, npt.NDArray[Any]]:
    """Read the named arrays of an .npz, checking each header before its data and never unpickling.

    Parameters
    ----------
    fh : binary file
        The open archive (:func:`mrm.io.reading.open_regular`).
    name : str
        The file's name, for messages.
    keys : tuple of str
        The arrays to read, among ``mask``, ``labels`` and ``origin``.
    limit : int
        The most elements of one array.
    ndim : int
        2 for pixel sets and label maps, 3 for voxel sets and label volumes: the masks and labels must have
        this many dimensions and the origin this many coordinates.
    optional : tuple of str
        Keys the archive may lack: left out of the result instead of refused.
    """
    try:
        zf = zipfile.ZipFile(fh)
    except (zipfile.BadZipFile, OSError, ValueError, EOFError):
        head = (fh.seek(0), fh.read(16))[1]
        raise FileFormatError(f"{name}: not an NPZ archive ({describe_content(head)})") from None
    except Exception as e:  # NotImplementedError for a "zip file version 9.6", RuntimeError, …
        raise FileFormatError(f"{name}: unreadable NPZ archive: {e}") from None
    out: dict[str, npt.NDArray[Any]] = {}
    with zf:
        members = set(zf.namelist())
        for key in keys:
            member = f"{key}.npy"
            if member not in members:
                if key in optional:
                    continue
                found = ", ".join(sorted(m.removesuffix(".npy") for m in members)) or "nothing"
                raise FileFormatError(f"{name}: the NPZ archive has no '{key}' array (it holds: {found})")
            try:
                with zf.open(member) as m:
                    out[key] = _read_npy(m, f"{name}: '{key}'", limit, _role(key, ndim))
            except FileFormatError:
                raise
            except MemoryError:
                raise FileFormatError(f"{name}: not enough memory to read '{key}'") from None
            except Exception as e:  # zipfile/zlib errors: bad CRC, truncated or corrupt compressed data
                raise FileFormatError(f"{name}: corrupt NPZ member '{key}': {e}") from None
    return out


def _read_npy(
    m: IO[bytes],
    what: str,
    limit: int,
    role: tuple[str, int, int, str] = ("biu", 2, limits.MAX_OBJECT_PIXELS, "a 2-D array"),
) -> npt.NDArray[Any]:
    kinds, ndim, max_bytes, desc = role
    fmt = np.lib.format
    try:
        version = fmt.read_magic(m)
        if version == (1, 0):
            shape, fortran, dtype = fmt.read_array_header_1_0(m)
        elif version == (2, 0):
            shape, fortran, dtype = fmt.read_array_header_2_0(m)
        else:
            raise FileFormatError(f"{what}: unsupported .npy format version {version}")
    except FileFormatError:
        raise
    except Exception as e:
        raise FileFormatError(f"{what}: malformed .npy header ({e})") from None
    if dtype.hasobject:
        raise FileFormatError(f"{what} holds Python objects (pickled data), which are never loaded")
    # The dtype and every dimension are checked before anything is read: (-1, 1000) must not pass as a
    # small array (reading a negative byte count would decompress the whole member).
    if not isinstance(shape, tuple) or any(
        not isinstance(d, int) or isinstance(d, bool) or d < 0 for d in shape
    ):
        raise FileFormatError(f"{what} has the invalid shape {shape!r:.80}")
    if dtype.kind not in kinds or dtype.itemsize > 8 or len(shape) != ndim:
        raise FileFormatError(f"{what} must be {desc}, found dtype {dtype} and shape {shape!r:.80}")
    count = int(np.prod(shape, dtype=object)) if shape else 1
    if count > limit:
        raise FileFormatError(f"{what} has {count:,} elements, more than the limit of {limit:,}")
    nbytes = count * dtype.itemsize
    if nbytes > max_bytes:
        raise FileFormatError(
            f"{what} holds {nbytes:,} bytes ({count:,} × {dtype}), more than the {max_bytes:,} accepted"
        )
    data = m.read(nbytes)
    if len(data) < nbytes:
        raise FileFormatError(f"{what} is truncated: {nbytes:,} bytes expected, {len(data):,} found")
    if m.read(1):
        raise FileFormatError(f"{what} has unexpected data after the array")
    return np.frombuffer(data, dtype=dtype).reshape(shape, order="F" if fortran else "C")


def npz_origin(a: npt.NDArray[Any], name: str, ndim: int) -> tuple[int, ...]:
    """The origin stored in an .npz: ``ndim`` integers (x0, y0[, z0])."""
    if a.shape != (ndim,) or a.dtype.kind not in "iu":
        raise FileFormatError(
            f"{name}: 'origin' must be {_COUNT[ndim]} integers {_ORIGIN[ndim]}, found dtype {a.dtype} "
            f"and shape {a.shape}"
        )
    return tuple(int(v) for v in a)


def npz_bytes(**arrays: npt.NDArray[Any]) -> bytes:
    """The bytes of a compressed .npz holding ``arrays`` (never pickled)."""
    buf = io.BytesIO()
    np.savez_compressed(buf, allow_pickle=False, **arrays)
    return buf.getvalue()


__all__ = ["npz_bytes", "npz_origin", "read_npz_arrays"]
