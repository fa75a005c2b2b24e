"""Generators of hostile inputs for the issue 11 tests: every file is built in the test, none is stored."""

from __future__ import annotations

import io
import struct
import zlib
from collections.abc import Callable, Iterator

import numpy as np

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def chunk(ctype: bytes, data: bytes) -> bytes:
    """One PNG chunk with its length and CRC."""
    return struct.pack(">I", len(data)) + ctype + data + struct.pack(">I", zlib.crc32(ctype + data))


def png(
    width: int,
    height: int,
    *,
    color: int = 0,
    depth: int = 8,
    row: Callable[[int], bytes] | None = None,
    palette: bytes | None = None,
    trns: bytes | None = None,
    text: dict[str, str] | None = None,
    rows_stored: int | None = None,
    level: int = 6,
    iend: bool = True,
) -> bytes:
    """A PNG built chunk by chunk; ``row(r)`` gives the unfiltered bytes of image row r (default zeros).

    ``rows_stored`` < height writes a complete zlib stream that holds only that many rows (the "4 of its 8
    rows" file); the rows are streamed through zlib, so a 14000² image costs a few MB to build.
    """
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[color]
    stride = (width * channels * depth + 7) // 8
    zero = bytes(stride)
    comp = zlib.compressobj(level)
    parts: list[bytes] = []
    n = height if rows_stored is None else rows_stored
    for r in range(n):
        parts.append(comp.compress(b"\x00" + (row(r) if row is not None else zero)))
    parts.append(comp.flush())
    out = [PNG_SIGNATURE, chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, depth, color, 0, 0, 0))]
    if palette is not None:
        out.append(chunk(b"PLTE", palette))
    if trns is not None:
        out.append(chunk(b"tRNS", trns))
    for k, v in (text or {}).items():
        out.append(chunk(b"tEXt", k.encode("latin-1") + b"\0" + v.encode("latin-1")))
    out.append(chunk(b"IDAT", b"".join(parts)))
    if iend:
        out.append(chunk(b"IEND", b""))
    return b"".join(out)


def npy_header(shape: object, descr: str = "|b1") -> bytes:
    """A .npy version 1.0 header claiming any shape (negative, absurd) without the data to match."""
    header = f"{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape!r}, }}".encode("latin-1")
    pad = 64 - (10 + len(header) + 1) % 64
    header += b" " * pad + b"\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header


def npz(members: dict[str, bytes]) -> bytes:
    """A zip archive of raw .npy members (deflated)."""
    import zipfile

    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
        for name, data in members.items():
            zf.writestr(f"{name}.npy", data)
    return buf.getvalue()


def npy(a: np.ndarray) -> bytes:
    buf = io.BytesIO()
    np.save(buf, a, allow_pickle=False)
    return buf.getvalue()


def deep_wkt(levels: int) -> str:
    """``GEOMETRYCOLLECTION (`` nested ``levels`` deep around one point."""
    return "GEOMETRYCOLLECTION (" * levels + "POINT (1 1)" + ")" * levels + "\n"


def deep_geojson(levels: int) -> str:
    """A GeometryCollection nested ``levels`` deep around one point."""
    inner = '{"type": "Point", "coordinates": [1, 1]}'
    return '{"type": "GeometryCollection", "geometries": [' * levels + inner + "]}" * levels


def checkerboard(n: int) -> np.ndarray:
    """An n × n checkerboard mask: the longest boundary n² pixels can have."""
    return np.add.outer(np.arange(n), np.arange(n)) % 2 == 0


def rows_of(mask: np.ndarray) -> Iterator[bytes]:
    for r in mask:
        yield bytes(r.astype(np.uint8))
