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


# ---------------------------------------------------------------------------------------------- TIFF
_SAMPLE_FORMATS = {"u": 1, "i": 2, "f": 3, "c": 6}


def tiff(
    width: int,
    height: int,
    *,
    dtype: str = "uint8",
    rows_per_strip: int | None = None,
    fill: int = 0,
    level: int = 9,
    geo: tuple[float, float, float, float] | None = None,
) -> bytes:
    """A little-endian TIFF of one band built by hand, every strip deflated and stored once.

    All strips point at the same compressed bytes (a strip of samples ``fill``), so a raster of 14000² complex
    samples (3 GB decoded) is a file of a few KB. ``geo`` = (pixel width, pixel height, X, Y of the top-left
    corner) adds GeoTIFF's ModelPixelScale and ModelTiepoint tags.
    """
    dt = np.dtype(dtype)
    rows = height if rows_per_strip is None else min(rows_per_strip, height)
    nstrips = -(-height // rows)
    blob = zlib.compress(np.full(rows * width, fill, dtype=dt).tobytes(), level)
    last_rows = height - (nstrips - 1) * rows  # a shorter last strip gets its own bytes
    last = blob if last_rows == rows else zlib.compress(np.full(last_rows * width, fill, dt).tobytes(), level)
    entries: list[tuple[int, int, list[float]]] = [  # (tag, type, values); 3 SHORT, 4 LONG, 12 DOUBLE
        (256, 4, [width]),
        (257, 4, [height]),
        (258, 3, [8 * dt.itemsize]),
        (259, 3, [8]),  # deflate
        (262, 3, [1]),  # min-is-black
        (273, 4, [0] * nstrips),  # strip offsets, filled in below
        (277, 3, [1]),
        (278, 4, [rows]),
        (279, 4, [len(blob)] * (nstrips - 1) + [len(last)]),
        (284, 3, [1]),
        (339, 3, [_SAMPLE_FORMATS[dt.kind]]),
    ]
    if geo is not None:
        sx, sy, x, y = geo
        entries += [(33550, 12, [sx, sy, 0.0]), (33922, 12, [0.0, 0.0, 0.0, x, y, 0.0])]
    ifd_size = 2 + 12 * len(entries) + 4
    extra = bytearray()
    base = 8 + ifd_size
    data_offset = base + sum(
        len(v) * {3: 2, 4: 4, 12: 8}[t] for _, t, v in entries if len(v) * {3: 2, 4: 4, 12: 8}[t] > 4
    )
    last_offset = data_offset + (len(blob) if last is not blob else 0)
    entries[5] = (273, 4, [data_offset] * (nstrips - 1) + [last_offset])
    ifd = struct.pack("<H", len(entries))
    for tag, typ, vals in entries:
        fmt = {3: "H", 4: "I", 12: "d"}[typ]
        raw = struct.pack(f"<{len(vals)}{fmt}", *vals)
        if len(raw) <= 4:
            ifd += struct.pack("<HHI", tag, typ, len(vals)) + raw.ljust(4, b"\0")
        else:
            ifd += struct.pack("<HHII", tag, typ, len(vals), base + len(extra))
            extra += raw
    ifd += struct.pack("<I", 0)
    return b"II*\0" + struct.pack("<I", 8) + ifd + bytes(extra) + blob + (last if last is not blob else b"")


def vrt(target: str, width: int = 16, height: int = 16) -> str:
    """A GDAL VRT (XML) reading ``target`` as raw bytes: what a hostile ``.tif`` may hold instead."""
    return (
        f'<VRTDataset rasterXSize="{width}" rasterYSize="{height}">\n'
        '  <VRTRasterBand dataType="Byte" band="1" subClass="VRTRawRasterBand">\n'
        f'    <SourceFilename relativetoVRT="0">{target}</SourceFilename>\n'
        f"    <ImageOffset>0</ImageOffset><PixelOffset>1</PixelOffset><LineOffset>{width}</LineOffset>\n"
        "  </VRTRasterBand>\n"
        "</VRTDataset>\n"
    )
