"""A small, strict Netpbm codec (PBM, PGM, PPM; plain and raw) that keeps sample values exact.

Written here rather than through Pillow because Pillow rescales PGM samples to 0–255 or 0–65535 and inverts
PBM bits, and because a hostile header must be refused *before* any pixel memory is allocated.

Reading gives the raw samples: for PBM the bits as stored (True = 1 = black), for PGM/PPM the integers
0…maxval. Header comments are kept, so the ``# mrm:origin x0 y0`` comment written by :func:`encode_pbm`
and :func:`encode_pgm` can be found again.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import BinaryIO

import numpy as np
import numpy.typing as npt

from mrm.core.errors import FileFormatError

#: The longest header read (magic, comments, sizes); real headers are a few dozen bytes.
HEADER_LIMIT = 64 * 1024
#: Plain (ASCII) PGM/PPM files are slow to parse and enormous; bigger ones should be converted to raw (P5/P6).
PLAIN_SAMPLE_LIMIT = 1 << 22

_WHITESPACE = b" \t\n\v\f\r"
_MAGICS = {
    b"P1": (1, True),
    b"P2": (1, False),
    b"P3": (3, False),
    b"P4": (1, True),
    b"P5": (1, False),
    b"P6": (3, False),
}


@dataclass(frozen=True)
class NetpbmImage:
    """A decoded Netpbm image.

    Attributes
    ----------
    magic : str
        "P1" … "P6".
    samples : ndarray
        (rows, cols) for PBM (bool, True = bit 1) and PGM (integers), (rows, cols, 3) for PPM; row 0 is the
        top row of the picture.
    maxval : int
        The largest sample value (1 for PBM).
    comments : list of str
        The header comments, without the leading "#" and surrounding blanks.
    """

    magic: str
    samples: npt.NDArray[np.generic]
    maxval: int
    comments: list[str] = field(default_factory=list)


class _Header:
    """Cursor over the header bytes with the Netpbm token rules (blanks and # comments between tokens)."""

    def __init__(self, buf: bytes, name: str, complete: bool) -> None:
        self.buf, self.name, self.complete, self.pos = buf, name, complete, 2
        self.comments: list[str] = []

    def _fail(self, what: str) -> FileFormatError:
        if self.pos >= len(self.buf) and not self.complete:
            return FileFormatError(f"{self.name}: Netpbm header longer than {HEADER_LIMIT} bytes")
        if self.pos >= len(self.buf):
            return FileFormatError(f"{self.name}: truncated Netpbm header (the file ends before {what})")
        return FileFormatError(f"{self.name}: malformed Netpbm header at byte {self.pos}: expected {what}")

    def _skip_blanks_and_comments(self) -> None:
        buf = self.buf
        while self.pos < len(buf):
            c = buf[self.pos : self.pos + 1]
            if c in _WHITESPACE:
                self.pos += 1
            elif c == b"#":
                m = re.compile(rb"[\r\n]").search(buf, self.pos)
                end = m.start() if m else len(buf)
                if m is None and not self.complete:
                    raise FileFormatError(f"{self.name}: Netpbm header longer than {HEADER_LIMIT} bytes")
                self.comments.append(buf[self.pos + 1 : end].decode("latin-1").strip())
                self.pos = end
            else:
                return

    def number(self, what: str) -> int:
        self._skip_blanks_and_comments()
        m = re.compile(rb"[0-9]+").match(self.buf, self.pos)
        if m is None:
            raise self._fail(what)
        if m.end() == len(self.buf) and not self.complete:
            raise self._fail(what)
        if len(m.group()) > 9:
            raise FileFormatError(f"{self.name}: absurd {what} in the Netpbm header ({m.group().decode()})")
        self.pos = m.end()
        return int(m.group())


def read_netpbm(fh: BinaryIO, name: str, limit: int) -> NetpbmImage:
    """Decode the first image of a Netpbm file.

    Parameters
    ----------
    fh : binary file
        Positioned at the start of the file.
    name : str
        The file name, for messages.
    limit : int
        The largest accepted width × height; larger images are refused from the header alone.

    Raises
    ------
    FileFormatError
        Not a Netpbm file, malformed or truncated header or raster, samples above maxval, too large.
    """
    head = fh.read(HEADER_LIMIT)
    magic = head[:2]
    if magic not in _MAGICS:
        raise FileFormatError(f"{name}: not a Netpbm (PBM/PGM/PPM) file: it does not start with P1 … P6")
    channels, is_bitmap = _MAGICS[magic]
    hdr = _Header(head, name, complete=len(head) < HEADER_LIMIT)
    width = hdr.number("the width")
    height = hdr.number("the height")
    maxval = 1 if is_bitmap else hdr.number("the maximum value")
    if not is_bitmap and not 1 <= maxval <= 65535:
        raise FileFormatError(f"{name}: Netpbm maximum value {maxval} is outside 1…65535")
    if width * height > limit:
        raise FileFormatError(
            f"{name}: the image is {width}×{height} = {width * height:,} pixels, "
            f"more than the limit of {limit:,}"
        )
    n = width * height * channels
    plain = magic in (b"P1", b"P2", b"P3")
    if plain:
        samples = _read_plain(magic, head[hdr.pos :], fh, name, n, is_bitmap)
    else:
        # Exactly one blank separates the header from the raster.
        if hdr.pos >= len(head) or head[hdr.pos : hdr.pos + 1] not in _WHITESPACE:
            raise FileFormatError(f"{name}: truncated Netpbm header (no blank before the pixel data)")
        rest = head[hdr.pos + 1 :]
        samples = _read_raw(magic, rest, fh, name, width, height, channels, maxval)
    if not is_bitmap and samples.size and int(samples.max()) > maxval:
        raise FileFormatError(
            f"{name}: a sample value {int(samples.max())} exceeds the maximum value {maxval}"
        )
    shape = (height, width) if channels == 1 else (height, width, channels)
    return NetpbmImage(magic.decode(), samples.reshape(shape), maxval, hdr.comments)


def _read_at_most(fh: BinaryIO, n: int) -> bytes:
    """Read up to ``n`` bytes in chunks, so a header that lies about the size costs no huge allocation."""
    chunks: list[bytes] = []
    while n > 0:
        chunk = fh.read(min(n, 1 << 24))
        if not chunk:
            break
        chunks.append(chunk)
        n -= len(chunk)
    return b"".join(chunks)


def _read_raw(
    magic: bytes,
    rest: bytes,
    fh: BinaryIO,
    name: str,
    width: int,
    height: int,
    channels: int,
    maxval: int,
) -> npt.NDArray[np.generic]:
    if magic == b"P4":
        row_bytes = (width + 7) // 8
        need = row_bytes * height
    else:
        bps = 1 if maxval < 256 else 2
        need = width * height * channels * bps
    data = rest[:need]
    if len(data) < need:
        data += _read_at_most(fh, need - len(data))
    if len(data) < need:
        raise FileFormatError(
            f"{name}: truncated Netpbm file: {need:,} bytes of pixel data expected, {len(data):,} found"
        )
    if magic == b"P4":
        packed = np.frombuffer(data, dtype=np.uint8).reshape(height, row_bytes)
        return np.unpackbits(packed, axis=1)[:, :width].astype(bool)
    return np.frombuffer(data, dtype=np.uint8 if maxval < 256 else ">u2").astype(
        np.uint8 if maxval < 256 else np.uint16
    )


def _read_plain(
    magic: bytes, rest: bytes, fh: BinaryIO, name: str, n: int, is_bitmap: bool
) -> npt.NDArray[np.generic]:
    if n > PLAIN_SAMPLE_LIMIT and not is_bitmap:
        raise FileFormatError(
            f"{name}: plain (ASCII) Netpbm images of more than {PLAIN_SAMPLE_LIMIT:,} samples are not read; "
            "convert it to the raw format (P4/P5/P6)"
        )
    # Each sample takes at least one byte (two for P2/P3 with their separators); read no more than needed.
    # A sample takes at most 6 bytes ("65535 "); comments aside, nothing beyond that is needed.
    text = rest + _read_at_most(fh, max(0, (2 if is_bitmap else 6) * n + HEADER_LIMIT - len(rest)))
    text = re.sub(rb"#[^\r\n]*", b"", text)
    if is_bitmap:
        chars = np.frombuffer(text, dtype=np.uint8)
        chars = chars[~np.isin(chars, np.frombuffer(_WHITESPACE, dtype=np.uint8))][:n]
        if chars.size < n:
            raise FileFormatError(f"{name}: truncated plain PBM: {n:,} pixels expected, {chars.size:,} found")
        if not np.all((chars == ord("0")) | (chars == ord("1"))):
            raise FileFormatError(f"{name}: a plain PBM raster may hold only the digits 0 and 1")
        bits: npt.NDArray[np.bool_] = chars == ord("1")
        return bits
    tokens = text.split(maxsplit=n)[:n]
    if len(tokens) < n:
        raise FileFormatError(
            f"{name}: truncated plain Netpbm file: {n:,} samples expected, {len(tokens):,} found"
        )
    if not all(t.isdigit() and len(t) <= 5 for t in tokens):
        raise FileFormatError(f"{name}: a plain Netpbm raster may hold only decimal samples 0…65535")
    return np.array([int(t) for t in tokens], dtype=np.int64)


def _header(magic: bytes, width: int, height: int, origin: tuple[int, int], maxval: int | None) -> bytes:
    lines = [magic, f"# mrm:origin {origin[0]} {origin[1]}".encode(), f"{width} {height}".encode()]
    if maxval is not None:
        lines.append(str(maxval).encode())
    return b"\n".join(lines) + b"\n"


def encode_pbm(rows: npt.NDArray[np.bool_], origin: tuple[int, int]) -> bytes:
    """Return a raw PBM (P4) of ``rows`` (top row first; True = bit 1) with an ``mrm:origin`` comment."""
    h, w = rows.shape
    return _header(b"P4", w, h, origin, None) + np.packbits(rows, axis=1).tobytes()


def encode_pgm(rows: npt.NDArray[np.bool_], origin: tuple[int, int]) -> bytes:
    """Return a raw 8-bit PGM (P5) of ``rows`` (top row first; True = 255, False = 0), with ``mrm:origin``."""
    h, w = rows.shape
    return _header(b"P5", w, h, origin, 255) + (rows.astype(np.uint8) * 255).tobytes()
