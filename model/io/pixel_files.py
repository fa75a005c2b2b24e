"""Pixel sets and label maps in image files that keep their place on the grid (docs/design.md §1, §9).

Formats, chosen by the file extension:

``.png``
    Read: any PNG (Pillow). Written: a 1-bit PNG (label maps: 8- or 16-bit grey). Row 0 is the top row:
    image row r of an H-row image is y = y0 + H − 1 − r. A ``tEXt`` chunk ``mrm:origin`` = ``"x0 y0"`` holds
    the coordinates of the bottom-left pixel (column 0, last row); without it the origin is (0, 0).
``.pbm``, ``.pgm`` (Netpbm; P1–P6 are all read, whatever the extension)
    Written: raw PBM (P4) and raw 8-bit PGM (P5) with a ``# mrm:origin x0 y0`` header comment.
    **The stored sample decides, not the colour shown**: non-zero is in the set. For PBM that is the bit 1,
    which viewers draw black (the PBM convention: 1 = ink), so a bitmap drawn black on white reads as the
    black shape. For PGM it is any value > 0, which viewers draw bright, as for PNG — a mask saved as
    0/255 (or 0/1) reads back unchanged. A picture with a dark object on a bright background therefore
    reads inverted from a PGM or PNG (invert it, or export it as PBM).
``.npz``
    ``mask`` (bool, [row, col], y growing with the row — the in-memory layout) and ``origin`` (int64 x0, y0);
    label maps store ``labels`` (int32) instead of ``mask``. Nothing is ever unpickled.

Grey and colour images are thresholded on import as :mod:`mrm.core.threshold` describes (pixels **brighter
than** the threshold are in the set; Otsu's threshold by default; binary images and 1-bit images keep their
non-zero pixels). Every file this module writes reads back as an equal object, and a PNG written here gives
the same bytes when read and written again. Writes are atomic (:mod:`mrm.io.atomic`).
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import warnings
from pathlib import Path
from typing import Any, BinaryIO

import numpy as np
import numpy.typing as npt
from PIL import Image, PngImagePlugin, UnidentifiedImageError

from mrm.core import limits
from mrm.core.errors import FileFormatError, ParameterError
from mrm.core.grids import LabelMap, PixelSet
from mrm.core.limits import DEFAULT_PIXEL_LIMIT
from mrm.core.threshold import _check_threshold, binarize, grey_of
from mrm.io.atomic import atomic_write_bytes
from mrm.io.netpbm import encode_pbm, encode_pgm, read_netpbm
from mrm.io.npz_arrays import npz_bytes, npz_origin, read_npz_arrays
from mrm.io.png_stream import read_png_mask
from mrm.io.reading import describe_content, open_regular

PathLike = str | os.PathLike[str]

#: Extensions read and written by :func:`read_pixels` / :func:`write_pixels`.
PIXEL_EXTENSIONS = (".png", ".pbm", ".pgm", ".npz", ".tif", ".tiff")  # GeoTIFF: mrm.io.georef
#: Extensions written by :func:`write_label_map`.
LABEL_EXTENSIONS = (".png", ".npz")
#: Extensions read by :func:`read_label_map` (the GUI's import and ``mrm polygonize``).
LABEL_READ_EXTENSIONS = (".png", ".pgm", ".npz")
#: The PNG text chunk keyword (and Netpbm comment) holding the origin.
ORIGIN_KEY = "mrm:origin"

_PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
_PNG_IEND = b"\x00\x00\x00\x00IEND\xaeB`\x82"  # the whole (empty) IEND chunk with its CRC

# Pillow refuses images above 2 × MAX_IMAGE_PIXELS while opening them; our own limit (checked from the
# header, before decoding) is the one that should speak, so Pillow's must not be lower.
if Image.MAX_IMAGE_PIXELS is not None and Image.MAX_IMAGE_PIXELS < DEFAULT_PIXEL_LIMIT:
    Image.MAX_IMAGE_PIXELS = DEFAULT_PIXEL_LIMIT


# ---------------------------------------------------------------------------------------------- helpers
def _name(path: PathLike) -> str:
    return os.fspath(path)


def _extension(path: PathLike, allowed: tuple[str, ...], what: str) -> str:
    ext = Path(path).suffix.lower()
    if ext not in allowed:
        shown = f"'{ext}'" if ext else "no extension"
        raise FileFormatError(
            f"{_name(path)}: {shown} is not a {what} file type; "
            f"use {', '.join(allowed[:-1])} or {allowed[-1]}"
        )
    return ext


def parse_origin(text: str, name: str) -> tuple[int, int]:
    """Parse the ``"x0 y0"`` origin text of a PNG chunk or Netpbm comment.

    Raises
    ------
    FileFormatError
        Unless the text is two decimal integers within ±2⁵³ separated by blanks.
    """
    m = re.fullmatch(r"\s*([+-]?[0-9]{1,16})\s+([+-]?[0-9]{1,16})\s*", text)
    if m is None:
        shown = text if len(text) <= 40 else text[:40] + "…"
        raise FileFormatError(f"{name}: malformed {ORIGIN_KEY} {shown!r}: expected two integers 'x0 y0'")
    x0, y0 = int(m.group(1)), int(m.group(2))
    return x0, y0


def check_file_extent(origin: tuple[int, ...], shape: tuple[int, ...], name: str) -> None:
    """Refuse a file's grid whose points would lie beyond the document's coordinates (mrm.core.limits).

    ``origin`` in coordinate order, ``shape`` in array order; two coordinates are pixels, three voxels (the
    voxel files use it too).
    """
    n = len(origin)
    lim = limits.PIXEL_COORDINATE_LIMIT
    if all(shape[:n]) and (
        min(origin) < -lim or max(int(origin[d]) + int(shape[n - 1 - d]) - 1 for d in range(n)) > lim
    ):
        unit = "pixels" if n == 2 else "voxels"
        shown = ", ".join(str(v) for v in origin)
        raise FileFormatError(
            f"{name}: origin ({shown}) puts {unit} beyond ±2^31, the coordinates a document can hold"
        )


def _check_size(width: int, height: int, limit: int, name: str) -> None:
    if width * height > limit:
        raise FileFormatError(
            f"{name}: the image is {width}×{height} = {width * height:,} pixels, "
            f"more than the limit of {limit:,}"
        )


def _rows_to_pixels(rows: npt.NDArray[Any], origin: tuple[int, int], name: str) -> PixelSet:
    """Image rows (top first) → pixel set; image row r is y = y0 + H − 1 − r."""
    check_file_extent(origin, rows.shape, name)
    return PixelSet(rows[::-1], origin)


def _pixels_to_rows(ps: PixelSet) -> tuple[npt.NDArray[np.bool_], tuple[int, int]]:
    """Pixel set → image rows (top first) and origin; the empty set is one background pixel at (0, 0)."""
    if ps.is_empty():
        return np.zeros((1, 1), dtype=bool), (0, 0)
    return np.ascontiguousarray(ps.mask[::-1]), ps.origin


# ---------------------------------------------------------------------------------------------- PNG
def _open_png(fh: BinaryIO, name: str, limit: int) -> tuple[Image.Image, tuple[int, int]]:
    """Open and decode a PNG, refusing huge ones from the IHDR chunk before anything is decoded."""
    head = fh.read(24)
    if not head.startswith(_PNG_SIGNATURE):
        raise FileFormatError(f"{name}: not a PNG image ({describe_content(head)})")
    if len(head) < 24 or head[12:16] != b"IHDR":
        raise FileFormatError(f"{name}: corrupt PNG: the header (IHDR) is missing or truncated")
    _check_size(int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big"), limit, name)
    data = head + fh.read()
    # Pillow stops reading once the image data is complete, so a file cut in the last CRC or before IEND
    # would pass unnoticed; a truncated file is refused even when its pixels happen to be all there.
    if _PNG_IEND not in data:
        raise FileFormatError(f"{name}: truncated PNG: the file ends before its IEND chunk")
    # Pillow warns about images above MAX_IMAGE_PIXELS (raised to our default limit at import); silence it
    # only for a caller who raised the limit, as catch_warnings changes global state (not thread-safe).
    quiet = Image.MAX_IMAGE_PIXELS is not None and limit > Image.MAX_IMAGE_PIXELS
    try:
        with warnings.catch_warnings() if quiet else contextlib.nullcontext():
            if quiet:
                warnings.simplefilter("ignore", Image.DecompressionBombWarning)
            im = Image.open(io.BytesIO(data), formats=["PNG"])
            im.load()
            text = dict(getattr(im, "text", {}) or {})
    except Image.DecompressionBombError as e:
        raise FileFormatError(f"{name}: the image is too large to decode ({e})") from None
    except UnidentifiedImageError:
        raise FileFormatError(f"{name}: not a readable PNG image") from None
    except MemoryError:
        raise FileFormatError(f"{name}: not enough memory to decode this PNG") from None
    except Exception as e:  # Pillow raises many types (OSError, SyntaxError, ValueError, zlib.error …)
        raise FileFormatError(f"{name}: corrupt or truncated PNG: {e}") from None
    origin = (0, 0)
    if ORIGIN_KEY in text:
        origin = parse_origin(str(text[ORIGIN_KEY]), name)
    return im, origin


def _png_grey(im: Image.Image, name: str) -> tuple[npt.NDArray[Any], bool]:
    """Return (samples, is_bitmap): a bool array for 1-bit images, else the integer grey image."""
    mode = im.mode
    if mode == "1":
        return np.array(im, dtype=bool), True
    if mode in ("L", "I", "I;16", "I;16B", "I;16L", "I;16N"):
        a = np.array(im)
        if a.dtype.kind not in "iu" or (a.size and int(a.min()) < 0):
            raise FileFormatError(f"{name}: unsupported grey PNG samples ({a.dtype})")
        return a, False
    if mode in ("P", "PA"):
        im, mode = im.convert("RGBA"), "RGBA"
    if mode == "LA":
        a = np.array(im)
        return grey_of(a[..., 0], alpha=a[..., 1]), False
    if mode == "RGB":
        return grey_of(np.array(im)), False
    if mode == "RGBA":
        a = np.array(im)
        return grey_of(a[..., :3], alpha=a[..., 3]), False
    raise FileFormatError(f"{name}: unsupported PNG colour mode {mode!r}")


#: Interlaced PNGs go through Pillow, which decodes the whole image at up to 4 bytes per pixel and whose
#: grey conversion takes several int64 arrays: they are read up to this size (a few hundred MB at worst).
PILLOW_PNG_PIXELS = 10_000_000


def _read_png_pixels(fh: BinaryIO, name: str, limit: int, threshold: float | None) -> PixelSet:
    """A PNG's pixel set, decoded by :mod:`mrm.io.png_stream` at one byte per pixel (ADR 0010)."""
    head = fh.read(29)
    if not head.startswith(_PNG_SIGNATURE):
        raise FileFormatError(f"{name}: not a PNG image ({describe_content(head)})")
    if len(head) < 29 or head[12:16] != b"IHDR":
        raise FileFormatError(f"{name}: corrupt PNG: the header (IHDR) is missing or truncated")
    width, height = int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")
    _check_size(width, height, limit, name)
    if threshold is not None:
        _check_threshold(threshold)
    if head[28] == 1:  # Adam7 interlacing: rows are not stored in order; Pillow, within a bound
        if width * height > PILLOW_PNG_PIXELS:
            raise FileFormatError(
                f"{name}: an interlaced PNG of {width}×{height} pixels is more than the "
                f"{PILLOW_PNG_PIXELS:,} read in that form; save it without interlacing"
            )
        fh.seek(0)
        im, origin = _open_png(fh, name, limit)
        samples, is_bitmap = _png_grey(im, name)
        rows = samples if is_bitmap else binarize(samples, threshold)
        return _rows_to_pixels(rows, origin, name)
    fh.seek(8)
    mask, text = read_png_mask(fh, name, threshold, _check_threshold)
    origin = parse_origin(text[ORIGIN_KEY], name) if ORIGIN_KEY in text else (0, 0)
    check_file_extent(origin, mask.shape, name)
    return _owned_pixel_set(mask, origin)


def _owned_pixel_set(mask: npt.NDArray[np.bool_], origin: tuple[int, int]) -> PixelSet:
    """A pixel set taking over a freshly decoded mask (bottom row first) without a second full copy."""
    return PixelSet.taking_over(mask, origin)


def _png_bytes(im: Image.Image, origin: tuple[int, int]) -> bytes:
    info = PngImagePlugin.PngInfo()
    info.add_text(ORIGIN_KEY, f"{origin[0]} {origin[1]}")
    buf = io.BytesIO()
    im.save(buf, format="PNG", pnginfo=info)
    return buf.getvalue()


# ---------------------------------------------------------------------------------------------- pixel sets
def read_pixels(
    path: PathLike, *, threshold: float | None = None, limit: int = DEFAULT_PIXEL_LIMIT
) -> PixelSet:
    """Read a pixel set from a .png, .pbm, .pgm or .npz file.

    Parameters
    ----------
    path : str or path-like
        The file; its extension chooses the format (see the module notes).
    threshold : float, optional
        For grey and colour images: pixels whose (luminance) value is greater than it are in the set. By
        default binary images keep their non-zero pixels and other images are cut at Otsu's threshold. Values
        are the stored samples (0–255 for 8-bit PNG, 0–65535 for 16-bit, 0–maxval for Netpbm). Ignored for
        1-bit images and .npz files.
    limit : int
        Images with more pixels (width × height) are refused from their header, before decoding.

    Returns
    -------
    PixelSet

    Raises
    ------
    FileFormatError
        Unknown extension, or a file that is corrupt, truncated, of another type, too large, or has a
        malformed origin.
    FileNotFoundError, IsADirectoryError, PermissionError
        As ``open`` does.
    ParameterError
        A non-finite threshold.
    """
    name = _name(path)
    ext = _extension(path, PIXEL_EXTENSIONS, "pixel")
    if ext in (".tif", ".tiff"):  # GeoTIFF (the geo extra)
        # A local import: mrm.io.georef builds on this module (it reads rasters through read_pixels), and a
        # .tif is georeferenced by nature.
        from mrm.io.georef import read_pixels_tif

        open_regular(path, name).close()  # a FIFO or device is refused before rasterio opens it
        return read_pixels_tif(path, threshold=threshold, limit=limit)
    with open_regular(path, name) as fh:  # a FIFO or device is refused, never waited on
        if ext == ".png":
            return _read_png_pixels(fh, name, limit, threshold)
        if ext in (".pbm", ".pgm"):
            img = read_netpbm(fh, name, limit)
            origin = _netpbm_origin(img.comments, name)
            if img.samples.dtype == np.bool_:
                rows = img.samples
            else:
                grey = grey_of(img.samples) if img.samples.ndim == 3 else img.samples
                rows = binarize(grey, threshold)
            return _rows_to_pixels(rows, origin, name)
        arrays = read_npz_arrays(fh, name, ("mask", "origin"), limit, ndim=2)
    mask, origin_arr = arrays["mask"], arrays["origin"]
    if mask.ndim != 2 or mask.dtype != np.bool_:
        raise FileFormatError(
            f"{name}: 'mask' must be a 2-D boolean array, found dtype {mask.dtype} and shape {mask.shape}"
        )
    x0, y0 = npz_origin(origin_arr, name, 2)
    origin = (x0, y0)
    check_file_extent(origin, mask.shape, name)
    return PixelSet(mask, origin)


def _netpbm_origin(comments: list[str], name: str) -> tuple[int, int]:
    for c in comments:
        if c.startswith(ORIGIN_KEY):
            return parse_origin(c[len(ORIGIN_KEY) :], name)
    return (0, 0)


def write_pixels(ps: PixelSet, path: PathLike) -> None:
    """Write a pixel set to a .png (1-bit), .pbm (P4), .pgm (P5) or .npz file, atomically.

    The file covers the set's bounding box and records its origin, so :func:`read_pixels` gives back an equal
    set. The empty set is written as one background pixel (origin (0, 0)), which reads back empty.

    Raises
    ------
    FileFormatError
        For an extension that is not a pixel file type.
    LimitError, SizeLimitError
        For a set with pixels beyond ±2³¹ or a box over the pixel limit (:mod:`mrm.core.limits`).
    """
    ext = _extension(path, PIXEL_EXTENSIONS, "pixel")
    # What this module writes it reads back: pixels beyond the document's coordinates are refused here too.
    limits.check_pixel_extent(ps.origin, ps.shape, f"{_name(path)}: the pixel set")
    if ext in (".tif", ".tiff"):  # GeoTIFF (the geo extra)
        from mrm.io.georef import write_pixels_tif  # local: mrm.io.georef builds on this module

        write_pixels_tif(ps, path)
        return
    if ext == ".npz":
        data = npz_bytes(mask=np.asarray(ps.mask), origin=np.array(ps.origin, dtype=np.int64))
    else:
        rows, origin = _pixels_to_rows(ps)
        if ext == ".png":
            data = _png_bytes(Image.fromarray(rows), origin)
        elif ext == ".pbm":
            data = encode_pbm(rows, origin)
        else:
            data = encode_pgm(rows, origin)
    atomic_write_bytes(path, data)


# ---------------------------------------------------------------------------------------------- label maps
def read_label_map(path: PathLike, *, limit: int = limits.MAX_LABEL_PIXELS) -> LabelMap:
    """Read a label map from a grey or indexed .png, a grey .pgm or an .npz (``labels``, optional ``origin``).

    A PNG's grey value (8 or 16 bits) or palette index, or a PGM's grey value (P2 or P5), is the label; 0 is
    the background. Row 0 of the image is the top row and the ``mrm:origin`` chunk (PNG) or comment (PGM)
    gives the bottom-left pixel, as for pixel sets; without one, and for an .npz without ``origin``, the
    map is placed at the origin.

    Raises
    ------
    FileFormatError
        Unknown extension; a corrupt, truncated, colour or too large image; bad arrays in the .npz.
    """
    name = _name(path)
    ext = _extension(path, LABEL_READ_EXTENSIONS, "label map")
    with open_regular(path, name) as fh:  # a FIFO or device is refused, never waited on
        if ext == ".pgm":
            img = read_netpbm(fh, name, limit)
            if img.magic not in ("P2", "P5"):
                raise FileFormatError(f"{name}: a label map must be a grey PGM (P2 or P5), not {img.magic}")
            labels, origin = img.samples[::-1], _netpbm_origin(img.comments, name)
        elif ext == ".png":
            im, origin = _open_png(fh, name, limit)
            if im.mode not in ("1", "L", "P", "I", "I;16", "I;16B", "I;16L", "I;16N"):
                raise FileFormatError(
                    f"{name}: a label map PNG must be grey (8 or 16 bits) or indexed, not {im.mode!r}"
                )
            rows = np.array(im)
            if rows.dtype == np.bool_:
                rows = rows.astype(np.uint8)
            labels = rows[::-1]
        else:
            arrays = read_npz_arrays(fh, name, ("labels", "origin"), limit, ndim=2, optional=("origin",))
            labels = arrays["labels"]
            if labels.ndim != 2 or labels.dtype.kind not in "iu":
                raise FileFormatError(
                    f"{name}: 'labels' must be a 2-D integer array, found dtype {labels.dtype} "
                    f"and shape {labels.shape}"
                )
            x0, y0 = npz_origin(arrays["origin"], name, 2) if "origin" in arrays else (0, 0)
            origin = (x0, y0)
    check_file_extent(origin, labels.shape, name)
    try:
        return LabelMap(labels, origin)
    except ValueError as e:
        raise FileFormatError(f"{name}: {e}") from None


def write_label_map(lm: LabelMap, path: PathLike) -> None:
    """Write a label map to a .png (8-bit grey up to label 255, else 16-bit) or an .npz file, atomically.

    Raises
    ------
    FileFormatError
        For an extension that is not a label map file type.
    ParameterError
        For a PNG when a label exceeds 65535 (use .npz).
    """
    ext = _extension(path, LABEL_EXTENSIONS, "label map")
    if ext == ".npz":
        data = npz_bytes(labels=np.asarray(lm.labels), origin=np.array(lm.origin, dtype=np.int64))
    else:
        if lm.shape[0] == 0:
            rows: npt.NDArray[Any] = np.zeros((1, 1), dtype=np.uint8)
            origin = (0, 0)
        else:
            top = int(lm.labels.max())
            if top > 65535:
                raise ParameterError(
                    f"{_name(path)}: label {top} does not fit in a PNG (at most 65535); "
                    "save the label map as .npz"
                )
            rows = np.ascontiguousarray(lm.labels[::-1]).astype(np.uint8 if top <= 255 else np.uint16)
            origin = lm.origin
        data = _png_bytes(Image.fromarray(rows), origin)
    atomic_write_bytes(path, data)


__all__ = [
    "LABEL_EXTENSIONS",
    "LABEL_READ_EXTENSIONS",
    "PIXEL_EXTENSIONS",
    "parse_origin",
    "read_label_map",
    "read_pixels",
    "write_label_map",
    "write_pixels",
]
