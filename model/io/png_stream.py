"""A streaming PNG reader for pixel sets: one byte per pixel of the image, whatever its colour type.

Pillow decodes a whole image into its own buffer — four bytes per pixel for grey+alpha, RGB, RGBA and
paletted images, and numpy conversions then widened that to int64 arrays (a 762 KB all-zero RGBA PNG of
14000² peaked at 9 GB). This reader parses the chunks itself, inflates the image data with a bounded
``zlib`` stream a strip of rows at a time, undoes the row filters (a numba kernel) and turns each strip into
the grey values of :mod:`mrm.core.threshold` at once. The only full-size array is the boolean result.

The thresholding rules need the whole image (Otsu's histogram; whether the visible pixels share one colour),
so the image data is read twice: a first pass gathers the histograms, the second writes the mask. The
result is exactly what the Pillow path gave: same luminance, same alpha rules, same scaling of 2- and 4-bit
grey (×85, ×17), same use of the high byte of 16-bit colour samples, palette transparency applied.

Every structural problem is a :class:`~mrm.core.errors.FileFormatError`: bad CRC, missing or truncated chunks,
image data that ends before the last row (rows are never filled in blank) or holds more than the image,
unknown filter types. Interlaced (Adam7) images are left to Pillow by the caller.
"""

from __future__ import annotations

import zlib
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any, BinaryIO

import numpy as np
import numpy.typing as npt

from mrm.core.errors import FileFormatError
from mrm.core.threshold import _otsu_sparse
from mrm.geometry._jit import njit

#: Channels per colour type.
_CHANNELS = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}
_DEPTHS = {0: (1, 2, 4, 8, 16), 2: (8, 16), 3: (1, 2, 4, 8), 4: (8, 16), 6: (8, 16)}
#: Largest chunk accepted (the PNG limit is 2³¹ − 1; text chunks are kept far smaller).
_MAX_TEXT = 1 << 20
#: Pixels per strip: the temporaries of one strip stay at a few tens of MB.
_STRIP_PIXELS = 1 << 18
_LUMA = (19595, 38470, 7471)


@dataclass
class PngInfo:
    """What the chunks before the image data say."""

    width: int = 0
    height: int = 0
    depth: int = 0
    color: int = 0
    interlace: int = 0
    palette: npt.NDArray[np.uint8] | None = None
    trns: bytes | None = None
    text: dict[str, str] = field(default_factory=dict)
    #: File offset of the first IDAT chunk's length field.
    idat_offset: int = -1


def _read_exact(fh: BinaryIO, n: int, name: str, what: str) -> bytes:
    data = fh.read(n)
    if len(data) < n:
        raise FileFormatError(f"{name}: truncated PNG: the file ends inside {what}")
    return data


def _chunks(fh: BinaryIO, name: str) -> Iterator[tuple[bytes, int, int]]:
    """(type, length, offset of its length field) of each chunk; the caller reads or skips the data."""
    while True:
        pos = fh.tell()
        head = fh.read(8)
        if len(head) < 8:
            raise FileFormatError(f"{name}: truncated PNG: the file ends before its IEND chunk")
        length = int.from_bytes(head[:4], "big")
        ctype = head[4:8]
        if length > 0x7FFFFFFF or not ctype.isalpha():
            raise FileFormatError(f"{name}: corrupt PNG: malformed chunk header at byte {pos}")
        yield ctype, length, pos


def _read_chunk_data(fh: BinaryIO, ctype: bytes, length: int, name: str) -> bytes:
    data = _read_exact(fh, length, name, f"the {ctype.decode('ascii')} chunk")
    crc = _read_exact(fh, 4, name, f"the {ctype.decode('ascii')} chunk")
    if zlib.crc32(data, zlib.crc32(ctype)) != int.from_bytes(crc, "big"):
        raise FileFormatError(f"{name}: corrupt PNG: bad checksum (CRC) in the {ctype.decode('ascii')} chunk")
    return data


def _inflate_text(data: bytes, name: str) -> bytes:
    d = zlib.decompressobj()
    try:
        out = d.decompress(data, _MAX_TEXT)
    except zlib.error as e:
        raise FileFormatError(f"{name}: corrupt PNG: compressed text chunk: {e}") from None
    if d.unconsumed_tail:
        raise FileFormatError(f"{name}: a PNG text chunk holds more than {_MAX_TEXT:,} bytes")
    return out


def _text_chunk(ctype: bytes, data: bytes, name: str) -> tuple[str, str] | None:
    key, sep, rest = data.partition(b"\0")
    if not sep:
        return None
    k = key.decode("latin-1")
    if ctype == b"tEXt":
        return k, rest.decode("latin-1")
    if ctype == b"zTXt":
        return k, _inflate_text(rest[1:], name).decode("latin-1")
    # iTXt: compression flag, method, language tag \0, translated keyword \0, text (UTF-8)
    if len(rest) < 2:
        return None
    flag = rest[0]
    _, _, rest2 = rest[2:].partition(b"\0")
    _, _, text = rest2.partition(b"\0")
    raw = _inflate_text(text, name) if flag else text
    return k, raw.decode("utf-8", "replace")


def read_header(fh: BinaryIO, name: str) -> PngInfo:
    """Parse the chunks up to the first IDAT (signature already checked by the caller, fh at byte 8).

    Text chunks after the image data are read as well by :func:`read_trailer`.
    """
    info = PngInfo()
    first = True
    for ctype, length, pos in _chunks(fh, name):
        if first:
            if ctype != b"IHDR" or length != 13:
                raise FileFormatError(f"{name}: corrupt PNG: the header (IHDR) is missing or truncated")
            first = False
        if ctype == b"IDAT":
            info.idat_offset = pos
            fh.seek(pos)
            break
        if ctype == b"IEND":
            raise FileFormatError(f"{name}: corrupt PNG: no image data (IDAT) before IEND")
        data = _read_chunk_data(fh, ctype, length, name)
        if ctype == b"IHDR":
            w, h = int.from_bytes(data[0:4], "big"), int.from_bytes(data[4:8], "big")
            depth, color, comp, filt, inter = data[8], data[9], data[10], data[11], data[12]
            if color not in _CHANNELS or depth not in _DEPTHS[color] or comp or filt or inter > 1:
                raise FileFormatError(
                    f"{name}: corrupt PNG: unsupported header (bit depth {depth}, colour type {color})"
                )
            if w == 0 or h == 0:
                raise FileFormatError(f"{name}: corrupt PNG: the image is {w}×{h} pixels")
            info.width, info.height, info.depth, info.color, info.interlace = w, h, depth, color, inter
        elif ctype == b"PLTE":
            if length % 3 or length > 768:
                raise FileFormatError(f"{name}: corrupt PNG: palette of {length} bytes")
            info.palette = np.frombuffer(data, dtype=np.uint8).reshape(-1, 3)
        elif ctype == b"tRNS":
            info.trns = data
        elif ctype in (b"tEXt", b"zTXt", b"iTXt"):
            kv = _text_chunk(ctype, data, name)
            if kv is not None:
                info.text.setdefault(*kv)
    if info.color == 3 and info.palette is None:
        raise FileFormatError(f"{name}: corrupt PNG: a paletted image without a palette (PLTE)")
    return info


def _idat_stream(fh: BinaryIO, info: PngInfo, name: str, text: dict[str, str] | None) -> Iterator[bytes]:
    """The compressed image data, chunk by chunk (CRCs checked), then the chunks up to IEND."""
    fh.seek(info.idat_offset)
    in_idat = True
    for ctype, length, _ in _chunks(fh, name):
        if ctype == b"IDAT":
            if not in_idat:
                raise FileFormatError(f"{name}: corrupt PNG: the image data (IDAT) is not contiguous")
            crc = zlib.crc32(ctype)
            left = length
            while left:
                piece = _read_exact(fh, min(left, 1 << 20), name, "the image data")
                crc = zlib.crc32(piece, crc)
                left -= len(piece)
                yield piece
            if crc != int.from_bytes(_read_exact(fh, 4, name, "the image data"), "big"):
                raise FileFormatError(f"{name}: corrupt PNG: bad checksum (CRC) in the image data")
            continue
        in_idat = False
        data = _read_chunk_data(fh, ctype, length, name)
        if ctype == b"IEND":
            return
        if text is not None and ctype in (b"tEXt", b"zTXt", b"iTXt"):
            kv = _text_chunk(ctype, data, name)
            if kv is not None:
                text.setdefault(*kv)


@njit(cache=True)
def _unfilter(raw: Any, nrows: int, stride: int, bpp: int, prev: Any, out: Any) -> int:  # pragma: no cover
    """Undo the PNG row filters of ``nrows`` rows (each a filter byte and ``stride`` bytes) into ``out``.

    ``prev`` is the row above the first one (zeros for the top row) and becomes the last row. Returns -1, or
    the index of a row with an unknown filter type.
    """
    for r in range(nrows):
        base = r * (stride + 1) + 1
        f = raw[base - 1]
        if f > 4:
            return r
        # One loop per filter type, so the inner loops carry no branch on it.
        if f == 0:
            for i in range(stride):
                out[r, i] = raw[base + i]
        elif f == 1:
            for i in range(stride):
                a = out[r, i - bpp] if i >= bpp else 0
                out[r, i] = (raw[base + i] + a) & 0xFF
        elif f == 2:
            for i in range(stride):
                out[r, i] = (raw[base + i] + prev[i]) & 0xFF
        elif f == 3:
            for i in range(stride):
                a = np.int32(out[r, i - bpp]) if i >= bpp else np.int32(0)
                out[r, i] = (np.int32(raw[base + i]) + (a + np.int32(prev[i])) // 2) & 0xFF
        else:
            for i in range(stride):
                a = np.int32(out[r, i - bpp]) if i >= bpp else np.int32(0)
                b = np.int32(prev[i])
                c = np.int32(prev[i - bpp]) if i >= bpp else np.int32(0)
                p = a + b - c
                pa = abs(p - a)
                pb = abs(p - b)
                pc = abs(p - c)
                if pa <= pb and pa <= pc:
                    pred = a
                elif pb <= pc:
                    pred = b
                else:
                    pred = c
                out[r, i] = (np.int32(raw[base + i]) + pred) & 0xFF
        for i in range(stride):
            prev[i] = out[r, i]
    return -1


def _strips(fh: BinaryIO, info: PngInfo, name: str, text: dict[str, str] | None) -> Iterator[Any]:
    """The unfiltered rows of the image, a strip (rows, stride) of uint8 at a time, top row first."""
    w, h = info.width, info.height
    bits = _CHANNELS[info.color] * info.depth
    stride = (w * bits + 7) // 8
    bpp = max(1, bits // 8)
    rows_per = max(1, min(h, _STRIP_PIXELS // max(1, w)))
    prev = np.zeros(stride, dtype=np.uint8)
    d = zlib.decompressobj()
    pending = bytearray()
    done_rows = 0
    src = _idat_stream(fh, info, name, text)
    exhausted = False
    while done_rows < h:
        n = min(rows_per, h - done_rows)
        need = n * (stride + 1)
        while len(pending) < need and not exhausted:
            if d.unconsumed_tail:
                chunk = d.unconsumed_tail
            else:
                nxt = next(src, None)
                if nxt is None:
                    exhausted = True
                    break
                chunk = nxt
            try:
                pending += d.decompress(chunk, need - len(pending) + 65536)
            except zlib.error as e:
                raise FileFormatError(f"{name}: corrupt PNG: cannot inflate the image data: {e}") from None
            if d.eof:
                exhausted = True
        if len(pending) < need:
            got = done_rows + len(pending) // (stride + 1)
            raise FileFormatError(
                f"{name}: truncated PNG: the image data holds {got} of its {h} rows; refusing to fill the "
                "rest with blank rows"
            )
        raw = np.frombuffer(bytes(pending[:need]), dtype=np.uint8)
        del pending[:need]
        out = np.empty((n, stride), dtype=np.uint8)
        bad = _unfilter(raw, n, stride, bpp, prev, out)
        if bad >= 0:
            raise FileFormatError(f"{name}: corrupt PNG: unknown filter type in row {done_rows + bad}")
        done_rows += n
        yield out
    # Data after the last row is ignored, as every decoder does; the chunks up to IEND are still read, so
    # their checksums are verified and a file cut before IEND is refused.
    for _ in src:
        pass


@njit(cache=True)
def _lum_alpha(  # pragma: no cover - compiled
    strip: Any,
    w: int,
    ch: int,
    step: int,
    grey16: bool,
    table: bool,
    lum_tab: Any,
    alpha_tab: Any,
    lum: Any,
    alpha: Any,
) -> None:
    """Grey value (BT.601 luminance) and alpha of every pixel of a strip, in one pass.

    Channel c of pixel i is at byte (i·ch + c)·step of a row: step 2 for 16-bit samples, of which the
    high byte is used for colour (as Pillow does) and both bytes for grey (``grey16``). With ``table`` the
    single channel is an index into ``lum_tab``/``alpha_tab`` (palettes, scaled 2- and 4-bit grey).
    """
    n = strip.shape[0]
    for r in range(n):
        row = strip[r]
        for i in range(w):
            o = i * ch * step
            if table:
                v = row[o]
                lum[r, i] = lum_tab[v]
                alpha[r, i] = alpha_tab[v]
            elif ch == 1:
                if grey16:
                    lum[r, i] = np.int32(row[o]) * 256 + np.int32(row[o + 1])
                else:
                    lum[r, i] = row[o]
                alpha[r, i] = 255
            elif ch == 2:
                lum[r, i] = row[o]
                alpha[r, i] = row[o + step]
            else:
                rr = np.int64(row[o])
                gg = np.int64(row[o + step])
                bb = np.int64(row[o + 2 * step])
                lum[r, i] = np.int32((19595 * rr + 38470 * gg + 7471 * bb + 32768) >> 16)
                alpha[r, i] = row[o + 3 * step] if ch == 4 else 255


def _tables(info: PngInfo) -> tuple[Any, Any] | None:
    """(luminance, alpha) per sample value for palettes and scaled low-depth grey; None otherwise."""
    if info.color == 3:
        pal = np.zeros((256, 3), dtype=np.int64)
        assert info.palette is not None
        pal[: len(info.palette)] = info.palette
        lum = ((_LUMA[0] * pal[:, 0] + _LUMA[1] * pal[:, 1] + _LUMA[2] * pal[:, 2] + 32768) >> 16).astype(
            np.int32
        )
        alpha = np.full(256, 255, dtype=np.int32)
        if info.trns is not None:
            t = np.frombuffer(info.trns[:256], dtype=np.uint8)
            alpha[: len(t)] = t
        return lum, alpha
    if info.color == 0 and info.depth in (2, 4):  # Pillow's L;2 and L;4 scale the samples to 0–255
        return (np.arange(256, dtype=np.int32) * (85 if info.depth == 2 else 17)), np.full(
            256, 255, dtype=np.int32
        )
    return None


def _samples(strip: Any, info: PngInfo, tables: tuple[Any, Any] | None) -> tuple[Any, Any | None, bool]:
    """(grey L, alpha or None, is_bitmap) of a strip of unfiltered rows, as Pillow's modes give them."""
    w, depth, color = info.width, info.depth, info.color
    n = strip.shape[0]
    if depth < 8:
        if depth == 1:
            vals = np.unpackbits(strip, axis=1)[:, :w]
        else:
            shifts = np.arange(8 - depth, -1, -depth, dtype=np.uint8)
            vals = ((strip[:, :, None] >> shifts) & ((1 << depth) - 1)).reshape(n, -1)[:, :w]
        if color == 0 and depth == 1:
            return vals.astype(bool), None, True
        strip, ch, step = np.ascontiguousarray(vals, dtype=np.uint8), 1, 1
    else:
        ch, step = _CHANNELS[color], depth // 8
    lum = np.empty((n, w), dtype=np.int32)
    alpha = np.empty((n, w), dtype=np.int32)
    lt, at = tables if tables is not None else (np.zeros(1, np.int32), np.zeros(1, np.int32))
    _lum_alpha(strip, w, ch, step, color == 0 and depth == 16, tables is not None, lt, at, lum, alpha)
    return lum, (alpha if color in (3, 4, 6) else None), False


def read_png_mask(
    fh: BinaryIO, name: str, threshold: float | None, check_threshold: Any
) -> tuple[npt.NDArray[np.bool_], dict[str, str]]:
    """Decode a non-interlaced PNG (fh just after the signature) into its mask, rows bottom first.

    Returns
    -------
    mask : ndarray of bool, shape (height, width)
        ``mask[row]`` is image row ``height − 1 − row`` (row 0 = lowest y), the pixel set's layout.
    text : dict
        The text chunks (keyword → text), for the origin.
    """
    info = read_header(fh, name)
    if info.interlace:
        raise ValueError("interlaced PNG: use the Pillow path")
    text = dict(info.text)
    h, w = info.height, info.width
    has_alpha = info.color in (3, 4, 6)
    t = None if threshold is None else check_threshold(threshold)
    tables = _tables(info)
    # Pass 1 (skipped when nothing global is needed): histograms and the visible-colour test.
    use_alpha_as_grey = False
    zero_image = False
    bitmap = info.color == 0 and info.depth == 1
    if not bitmap and (t is None or has_alpha):
        hist_plain = np.zeros(65536, dtype=np.int64)
        hist_alpha = np.zeros(256, dtype=np.int64)
        hist_comp = np.zeros(256, dtype=np.int64)
        lo, hi, visible = None, None, False
        for strip in _strips(fh, info, name, text):
            lum, alpha, _ = _samples(strip, info, tables)
            if alpha is None:
                hist_plain += np.bincount(lum.ravel(), minlength=65536)
                continue
            vis = alpha > 0
            if vis.any():
                shown = lum[vis]
                smin, smax = int(shown.min()), int(shown.max())
                lo = smin if lo is None else min(lo, smin)
                hi = smax if hi is None else max(hi, smax)
                visible = True
            hist_alpha += np.bincount(alpha.ravel(), minlength=256)
            hist_comp += np.bincount(((lum * alpha + 127) // 255).ravel(), minlength=256)
        if has_alpha:
            if not visible:
                zero_image = True
                hist = np.zeros(1, dtype=np.int64)
                hist[0] = h * w
            elif lo == hi:
                use_alpha_as_grey = True
                hist = hist_alpha
            else:
                hist = hist_comp
        else:
            hist = hist_plain
        if t is None:
            occupied = np.flatnonzero(hist)
            vals = [int(v) for v in occupied]
            counts = [int(c) for c in hist[occupied]]
            binary = len(vals) <= 1 or (len(vals) == 2 and vals[0] == 0)
            t = 0.0 if binary else float(_otsu_sparse(vals, counts))
            # binary: "non-zero is in the set", which is "value > 0" for non-negative values
        fh.seek(info.idat_offset)
    mask = np.empty((h, w), dtype=bool)
    row = 0
    for strip in _strips(fh, info, name, text):
        lum, alpha, is_bitmap = _samples(strip, info, tables)
        n = lum.shape[0]
        if is_bitmap:
            part = lum
        elif zero_image:
            part = np.zeros(lum.shape, dtype=bool) if t is None or t >= 0 else np.ones(lum.shape, dtype=bool)
        elif alpha is None:
            part = lum > t
        elif use_alpha_as_grey:
            part = alpha > t
        else:
            part = (lum * alpha + 127) // 255 > t
        # Image row r is y = y0 + h − 1 − r: write the strip upside down at the top of what is left.
        mask[h - row - n : h - row] = part[::-1]
        row += n
    return mask, text


__all__ = ["PngInfo", "read_header", "read_png_mask"]
