"""Pixel files: exact round trips, the orientation and origin conventions, thresholding, hostile input."""

from __future__ import annotations

import io
import os
import stat
import struct
import tempfile
import zipfile
import zlib
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from PIL import Image, PngImagePlugin
from skimage.filters import threshold_otsu

from mrm.core.errors import FileFormatError, ParameterError
from mrm.core.grids import LabelMap, PixelSet
from mrm.core.threshold import luminance, otsu_threshold
from mrm.io.atomic import atomic_open, atomic_write_bytes
from mrm.io.pixel_files import read_label_map, read_pixels, write_label_map, write_pixels

PIXEL_EXTS = [".png", ".pbm", ".pgm", ".npz"]


def ps_of(points) -> PixelSet:
    return PixelSet.from_points(sorted(points))


def as_set(ps: PixelSet) -> set[tuple[int, int]]:
    return {(int(x), int(y)) for x, y in ps.points()}


def png_with(arr: np.ndarray, origin: str | None = None, **save) -> bytes:
    im = Image.fromarray(arr)  # bool → "1", uint8 → "L", (h, w, 2) → "LA", (h, w, 3) → "RGB", uint16 → "I;16"
    info = PngImagePlugin.PngInfo()
    if origin is not None:
        info.add_text("mrm:origin", origin)
    buf = io.BytesIO()
    im.save(buf, format="PNG", pnginfo=info, **save)
    return buf.getvalue()


def png_chunks(data: bytes) -> list[tuple[bytes, bytes]]:
    out, pos = [], 8
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos : pos + 4])
        out.append((data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + n]))
        pos += 12 + n
    return out


def chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def write(path: Path, data: bytes) -> Path:
    path.write_bytes(data)
    return path


# ---------------------------------------------------------------------------------------------- round trips
# Every pixel of a file stays within the document's ±2^31 (mrm.core.limits), so it can be saved in a project.
coords = st.integers(-(2**31), 2**31 - 30)
point_sets = st.builds(
    lambda pts, dx, dy: {(x + dx, y + dy) for x, y in pts},
    st.sets(st.tuples(st.integers(0, 30), st.integers(0, 20)), max_size=80),
    coords,
    coords,
)


@pytest.mark.parametrize("ext", PIXEL_EXTS)
@settings(max_examples=40)
@given(pts=point_sets)
def test_write_then_read_gives_the_same_set(ext, pts):
    ps = ps_of(pts)
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / f"a{ext}"
        write_pixels(ps, p)
        back = read_pixels(p)
        assert back == ps
        assert as_set(back) == pts
        assert os.listdir(d) == [p.name]  # no temporary file left behind


@settings(max_examples=40)
@given(pts=point_sets)
def test_png_read_write_read_gives_identical_bytes(pts):
    with tempfile.TemporaryDirectory() as d:
        a, b = Path(d) / "a.png", Path(d) / "b.png"
        write_pixels(ps_of(pts), a)
        first = read_pixels(a)
        write_pixels(first, b)
        assert a.read_bytes() == b.read_bytes()
        second = read_pixels(b)
        assert np.array_equal(second.mask, first.mask) and second.origin == first.origin


def test_png_layout_row_zero_is_the_top_and_origin_is_bottom_left(tmp_path):
    # pixels (10, 20), (11, 20), (10, 22): 2 columns × 3 rows, bottom-left pixel (10, 20)
    ps = PixelSet.from_points([(10, 20), (11, 20), (10, 22)])
    p = tmp_path / "a.png"
    write_pixels(ps, p)
    data = p.read_bytes()
    chunks = png_chunks(data)
    ihdr = dict(chunks)[b"IHDR"]
    width, height, depth, colour = struct.unpack(">IIBB", ihdr[:10])
    assert (width, height, depth, colour) == (2, 3, 1, 0)  # a 1-bit grey PNG
    assert (b"tEXt", b"mrm:origin\x0010 20") in chunks
    with Image.open(p) as im:
        rows = np.array(im)
    assert rows.tolist() == [[True, False], [False, False], [True, True]]  # y = 22, 21, 20


def test_png_without_origin_chunk_starts_at_zero(tmp_path):
    # an image from elsewhere: 3 rows, row 0 on top, with background padding
    arr = np.array([[0, 0, 0, 0], [0, 255, 0, 0], [255, 0, 0, 0]], dtype=np.uint8)
    p = write(tmp_path / "x.png", png_with(arr))
    assert as_set(read_pixels(p)) == {(1, 1), (0, 0)}  # image row r → y = 2 − r
    # read → write keeps the place on the grid
    write_pixels(read_pixels(p), tmp_path / "y.png")
    assert read_pixels(tmp_path / "y.png") == read_pixels(p)


def test_png_with_origin_chunk_from_elsewhere(tmp_path):
    arr = np.zeros((4, 3), dtype=np.uint8)
    arr[3, 0] = 1  # bottom-left pixel of the image
    arr[0, 2] = 1  # top-right
    p = write(tmp_path / "x.png", png_with(arr, origin=" -5   7 "))
    assert as_set(read_pixels(p)) == {(-5, 7), (-3, 10)}


def test_uppercase_extension(tmp_path):
    ps = PixelSet.from_points([(1, 1)])
    write_pixels(ps, tmp_path / "A.PNG")
    assert read_pixels(tmp_path / "A.PNG") == ps


def test_empty_set_round_trips(tmp_path):
    for ext in PIXEL_EXTS:
        write_pixels(PixelSet.empty(), tmp_path / f"e{ext}")
        assert read_pixels(tmp_path / f"e{ext}").is_empty()


# ---------------------------------------------------------------------------------------------- Netpbm
def test_plain_and_raw_pbm_bit_one_is_in_the_set(tmp_path):
    expected = {(0, 1), (1, 0), (2, 0)}  # row 0 (top) is y = 1
    p1 = write(tmp_path / "a.pbm", b"P1\n# a comment\n3 2\n1 0 0\n0 1 1\n")
    p1_tight = write(tmp_path / "b.pbm", b"P1 3 2 100011")
    p4 = write(tmp_path / "c.pbm", b"P4\n3 2\n" + bytes([0b10000000, 0b01100000]))
    for p in (p1, p1_tight, p4):
        assert as_set(read_pixels(p)) == expected


def test_our_pbm_and_pgm_read_the_same_in_pillow(tmp_path):
    ps = PixelSet.from_points([(0, 0), (2, 0), (1, 2), (9, 1)])
    top_first = np.zeros((3, 10), dtype=bool)
    for x, y in as_set(ps):
        top_first[2 - y, x] = True
    write_pixels(ps, tmp_path / "a.pbm")
    write_pixels(ps, tmp_path / "a.pgm")
    assert (tmp_path / "a.pbm").read_bytes().startswith(b"P4\n")
    assert (tmp_path / "a.pgm").read_bytes().startswith(b"P5\n")
    with Image.open(tmp_path / "a.pbm") as im:
        # Pillow shows the PBM bit 1 as black (False)
        assert np.array_equal(np.array(im), ~top_first)
    with Image.open(tmp_path / "a.pgm") as im:
        assert np.array_equal(np.array(im), top_first.astype(np.uint8) * 255)


def test_pgm_non_zero_is_in_the_set_and_thresholds_use_raw_samples(tmp_path):
    p2 = write(tmp_path / "a.pgm", b"P2\n3 2\n3\n0 3 0\n3 3 0\n")  # binary: 0 and 3
    assert as_set(read_pixels(p2)) == {(1, 1), (0, 0), (1, 0)}
    grey = write(tmp_path / "b.pgm", b"P2\n4 1\n3\n0 1 2 3\n")
    assert as_set(read_pixels(grey, threshold=1)) == {(2, 0), (3, 0)}
    assert as_set(read_pixels(grey, threshold=2.5)) == {(3, 0)}
    # 16-bit raw samples, big-endian
    p5 = write(tmp_path / "c.pgm", b"P5\n3 1\n65535\n" + struct.pack(">3H", 0, 1, 40000))
    assert as_set(read_pixels(p5, threshold=0)) == {(1, 0), (2, 0)}
    assert as_set(read_pixels(p5, threshold=1)) == {(2, 0)}


def test_ppm_colour_goes_through_luminance(tmp_path):
    # red, green, blue, black: BT.601 luminances 76, 150, 29, 0, cut at Otsu's threshold (by definition)
    p6 = write(tmp_path / "a.pgm", b"P6\n4 1\n255\n" + bytes([255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0]))
    lum = np.array([76, 150, 29, 0])
    t = min(best_splits_by_definition(lum)[0])
    assert as_set(read_pixels(p6)) == {(int(x), 0) for x in np.flatnonzero(lum > t)}
    assert as_set(read_pixels(p6, threshold=28)) == {(0, 0), (1, 0), (2, 0)}
    p3 = write(tmp_path / "b.pbm", b"P3\n2 1\n255\n255 0 0  0 0 0\n")  # binary after luminance
    assert as_set(read_pixels(p3)) == {(0, 0)}


@pytest.mark.parametrize(
    ("data", "message"),
    [
        (b"", "not a Netpbm"),
        (b"P7\n3 2\n", "not a Netpbm"),
        (b"P4\n3", "truncated Netpbm header"),
        (b"P4\nx 2\n", "expected the width"),
        (b"P4\n3 2\n\x80", "truncated Netpbm file"),
        (b"P5\n3 2\n255\n\x00\x01", "truncated"),
        (b"P5\n2 1\n0\n\x00\x00", "maximum value"),
        (b"P5\n2 1\n70000\n\x00\x00\x00\x00", "maximum value"),
        (b"P5\n2 1\n3\n\x00\x07", "exceeds the maximum value"),
        (b"P2\n2 1\n3\n1 x\n", "decimal"),
        (b"P1\n2 1\n1 2\n", "0 and 1"),
        (b"P1\n3 1\n1 0", "truncated plain PBM"),
        (b"P4\n99999 99999\n", "more than the limit"),
        (b"P4\n9999999999 1\n", "absurd"),
        (b"P4\n#" + b"x" * 70000, "header longer"),
        (b"P4\n# mrm:origin 1.5 2\n1 1\n\x80", "malformed mrm:origin"),
    ],
)
def test_bad_netpbm_files(tmp_path, data, message):
    p = write(tmp_path / "bad.pbm", data)
    with pytest.raises(FileFormatError, match=message) as e:
        read_pixels(p, limit=10**8)
    assert "bad.pbm" in str(e.value)


# ---------------------------------------------------------------------------------------------- thresholds
def best_splits_by_definition(values: np.ndarray) -> tuple[set[int], Fraction]:
    """The thresholds t minimising the within-class sum of squares of {v ≤ t} / {v > t}, in Fractions."""
    vals = sorted(int(v) for v in values.ravel())
    present = sorted(set(vals))
    if len(present) == 1:
        return {present[0]}, Fraction(0)
    scores = {}
    for t in present[:-1]:
        total = Fraction(0)
        for cls in ([v for v in vals if v <= t], [v for v in vals if v > t]):
            mean = Fraction(sum(cls), len(cls))
            total += sum((v - mean) ** 2 for v in cls)
        scores[t] = total
    best = min(scores.values())
    return {t for t, s in scores.items() if s == best}, best


def between_class(values: np.ndarray, t: float) -> Fraction:
    vals = [int(v) for v in values.ravel()]
    c0 = [v for v in vals if v <= t]
    c1 = [v for v in vals if v > t]
    if not c0 or not c1:
        return Fraction(0)
    return Fraction(len(c0) * len(c1)) * (Fraction(sum(c0), len(c0)) - Fraction(sum(c1), len(c1))) ** 2


grey_images = st.one_of(
    st.lists(st.integers(0, 255), min_size=1, max_size=120),
    st.lists(st.sampled_from([0, 1, 2, 128, 254, 255]), min_size=1, max_size=60),
    st.builds(
        lambda lo, hi, n0, n1: [lo] * n0 + [hi] * n1 + [(lo + hi) // 2],
        st.integers(0, 100),
        st.integers(150, 255),
        st.integers(1, 30),
        st.integers(1, 30),
    ),
)


@settings(max_examples=150)
@given(grey_images)
def test_otsu_is_exact_and_agrees_with_skimage(values):
    img = np.array(values, dtype=np.uint8).reshape(1, -1)
    t = otsu_threshold(np.bincount(img.ravel()))
    best, _ = best_splits_by_definition(img)
    assert t == min(best)  # the exact optimum, smallest on ties
    sk = threshold_otsu(img)
    # skimage works in floats: it may pick another threshold only when the two splits tie exactly
    assert sk == t or between_class(img, float(sk)) == between_class(img, t)


def test_otsu_agrees_with_skimage_on_bimodal_images():
    rng = np.random.default_rng(7)
    for _ in range(20):
        n = int(rng.integers(200, 3000))
        a = np.concatenate(
            [rng.normal(rng.uniform(20, 100), 15, n), rng.normal(rng.uniform(140, 230), 20, n // 2)]
        )
        img = np.clip(a, 0, 255).astype(np.uint8).reshape(1, -1)
        assert otsu_threshold(np.bincount(img.ravel())) == threshold_otsu(img)


def test_luminance_matches_pillow():
    rng = np.random.default_rng(3)
    rgb = rng.integers(0, 256, size=(40, 50, 3), dtype=np.uint8)
    rgb[0, :8] = [
        [0, 0, 0],
        [255, 255, 255],
        [255, 0, 0],
        [0, 255, 0],
        [0, 0, 255],
        [1, 1, 1],
        [7, 7, 7],
        [128] * 3,
    ]
    expected = np.array(Image.fromarray(rgb).convert("L"))
    assert np.array_equal(luminance(rgb), expected)


def test_grey_png_is_cut_at_otsu(tmp_path):
    rng = np.random.default_rng(11)
    img = np.clip(
        np.where(rng.random((30, 40)) < 0.4, rng.normal(60, 20, (30, 40)), rng.normal(190, 25, (30, 40))),
        0,
        255,
    ).astype(np.uint8)
    p = write(tmp_path / "g.png", png_with(img))
    expected_rows = img > threshold_otsu(img)
    got = read_pixels(p)
    assert np.array_equal(got.to_array((0, 0, 39, 29)), expected_rows[::-1])
    # an explicit threshold: strictly brighter pixels are in the set
    got100 = read_pixels(p, threshold=100)
    assert np.array_equal(got100.to_array((0, 0, 39, 29)), (img > 100)[::-1])


def test_sixteen_bit_grey_png(tmp_path):
    rng = np.random.default_rng(5)
    img = np.where(
        rng.random((20, 30)) < 0.5, rng.integers(0, 20000, (20, 30)), rng.integers(30000, 65536, (20, 30))
    )
    img = img.astype(np.uint16)
    p = write(tmp_path / "g16.png", png_with(img))
    got = read_pixels(p)
    assert np.array_equal(got.to_array((0, 0, 29, 19)), (img > threshold_otsu(img))[::-1])
    got_t = read_pixels(p, threshold=25000)
    assert np.array_equal(got_t.to_array((0, 0, 29, 19)), (img > 25000)[::-1])


def test_binary_images_are_not_thresholded(tmp_path):
    # 0 and one other value, however dark: non-zero is in the set
    arr = np.array([[0, 3, 3], [0, 0, 3]], dtype=np.uint8)
    p = write(tmp_path / "b.png", png_with(arr))
    assert as_set(read_pixels(p)) == {(1, 1), (2, 1), (2, 0)}
    # a constant non-zero image is all in the set
    p2 = write(tmp_path / "c.png", png_with(np.full((2, 2), 9, dtype=np.uint8)))
    assert len(read_pixels(p2)) == 4
    # a 1-bit image ignores a threshold (it has no grey levels)
    p3 = write(tmp_path / "d.png", png_with(np.array([[True, False]])))
    assert as_set(read_pixels(p3, threshold=200)) == {(0, 0)}
    # an explicit threshold cuts a two-valued grey image too
    assert read_pixels(p, threshold=3).is_empty()


def test_colour_png_uses_luminance(tmp_path):
    rgb = np.zeros((2, 3, 3), dtype=np.uint8)
    rgb[0, 0] = (255, 0, 0)  # luminance 76
    rgb[1, 2] = (0, 0, 255)  # luminance 29
    rgb[1, 1] = (255, 255, 255)  # 255
    p = write(tmp_path / "c.png", png_with(rgb))
    # values {0, 29, 76, 255}: Otsu on the luminance image
    lum = np.array(Image.fromarray(rgb).convert("L"))
    expected = {(c, 1 - r) for r, c in zip(*np.nonzero(lum > threshold_otsu(lum)), strict=True)}
    assert as_set(read_pixels(p)) == expected
    assert as_set(read_pixels(p, threshold=50)) == {(0, 1), (1, 0)}


def test_alpha_transparent_is_background(tmp_path):
    # a black shape on a transparent layer: the shape is the set
    rgba = np.zeros((3, 3, 4), dtype=np.uint8)
    rgba[1, :, 3] = 255
    p = write(tmp_path / "a.png", png_with(rgba))
    assert as_set(read_pixels(p)) == {(0, 1), (1, 1), (2, 1)}
    # white but fully transparent pixels are background; opaque white is the set
    rgba2 = np.full((2, 2, 4), 255, dtype=np.uint8)
    rgba2[0, :, 3] = 0
    p2 = write(tmp_path / "b.png", png_with(rgba2))
    assert as_set(read_pixels(p2)) == {(0, 0), (1, 0)}
    # grey + alpha
    la = np.zeros((1, 3, 2), dtype=np.uint8)
    la[0, 0] = (200, 255)
    la[0, 1] = (200, 0)
    la[0, 2] = (10, 255)
    p3 = write(tmp_path / "c.png", png_with(la))
    assert as_set(read_pixels(p3)) == {(0, 0)}


def test_palette_png(tmp_path):
    im = Image.new("P", (3, 1))
    im.putpalette([0, 0, 0, 255, 255, 255] + [0] * 762)
    im.putdata([1, 0, 1])
    buf = io.BytesIO()
    im.save(buf, format="PNG")
    p = write(tmp_path / "p.png", buf.getvalue())
    assert as_set(read_pixels(p)) == {(0, 0), (2, 0)}


def test_bad_threshold(tmp_path):
    p = write(tmp_path / "g.png", png_with(np.arange(12, dtype=np.uint8).reshape(3, 4)))
    with pytest.raises(ParameterError):
        read_pixels(p, threshold=float("nan"))


# ---------------------------------------------------------------------------------------------- label maps
@pytest.mark.parametrize("top", [1, 255, 256, 65535])
@pytest.mark.parametrize("ext", [".png", ".npz"])
def test_label_map_round_trip(tmp_path, ext, top):
    labels = np.array([[0, 1, top], [2, 0, 0], [0, 0, 3]], dtype=np.int32)
    lm = LabelMap(labels, (-4, 9))
    p = tmp_path / f"l{ext}"
    write_label_map(lm, p)
    assert read_label_map(p) == lm
    if ext == ".png":
        with Image.open(p) as im:
            assert im.mode == ("L" if top <= 255 else "I;16")
            assert np.array(im)[0].tolist() == [0, 0, 3]  # the top row is y = 11


def test_label_map_npz_holds_large_labels_png_refuses(tmp_path):
    lm = LabelMap(np.array([[70000]], dtype=np.int32))
    write_label_map(lm, tmp_path / "l.npz")
    assert read_label_map(tmp_path / "l.npz") == lm
    with pytest.raises(ParameterError, match="npz"):
        write_label_map(lm, tmp_path / "l.png")
    assert not (tmp_path / "l.png").exists()


def test_label_map_from_colour_png_is_refused(tmp_path):
    p = write(tmp_path / "c.png", png_with(np.zeros((2, 2, 3), dtype=np.uint8)))
    with pytest.raises(FileFormatError, match="grey"):
        read_label_map(p)


def test_label_map_from_indexed_png_uses_indices(tmp_path):
    im = Image.new("P", (2, 1))
    im.putpalette([9, 9, 9] * 256)
    im.putdata([0, 7])
    buf = io.BytesIO()
    im.save(buf, format="PNG")
    p = write(tmp_path / "p.png", buf.getvalue())
    assert read_label_map(p).pixel_set(7) == PixelSet.from_points([(1, 0)])


# ---------------------------------------------------------------------------------------------- hostile files
def huge_png_header(width: int, height: int) -> bytes:
    ihdr = struct.pack(">IIBBBBB", width, height, 1, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IEND", b"")


def good_png() -> bytes:
    arr = np.zeros((20, 30), dtype=bool)
    arr[3:15, 5:25] = True
    arr[7, 7] = False
    return png_with(arr, origin="0 0")


def test_truncated_png_at_every_length(tmp_path):
    data = good_png()
    p = tmp_path / "t.png"
    for n in range(len(data)):  # any cut, even one that keeps all the pixel data
        p.write_bytes(data[:n])
        with pytest.raises(FileFormatError) as e:
            read_pixels(p)
        assert "t.png" in str(e.value)


def test_corrupt_png_data(tmp_path):
    data = bytearray(good_png())
    chunks = png_chunks(bytes(data))
    idat_at = bytes(data).index(b"IDAT")
    data[idat_at + 6] ^= 0xFF  # the CRC no longer matches
    p = write(tmp_path / "c.png", bytes(data))
    with pytest.raises(FileFormatError, match=r"c\.png"):
        read_pixels(p)
    # a consistent CRC over garbage compressed data
    body = b"\x78\x9c" + bytes(range(200))
    rebuilt = (
        b"\x89PNG\r\n\x1a\n"
        + b"".join(chunk(k, body if k == b"IDAT" else v) for k, v in chunks if k != b"IEND")
        + chunk(b"IEND", b"")
    )
    p2 = write(tmp_path / "z.png", rebuilt)
    with pytest.raises(FileFormatError, match=r"z\.png"):
        read_pixels(p2)


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (b"", "empty"),
        (b"hello, I am text\n", "text file"),
        (b"<svg xmlns='http://www.w3.org/2000/svg'/>", "text file"),
        (bytes(np.random.default_rng(1).integers(0, 256, 500, dtype=np.uint8)), "not a PNG"),
        (b"\xff\xd8\xff\xe0" + bytes(100), "JPEG"),
    ],
)
def test_not_a_png(tmp_path, content, message):
    p = write(tmp_path / "x.png", content)
    with pytest.raises(FileFormatError, match=message) as e:
        read_pixels(p)
    assert "x.png" in str(e.value)


@pytest.mark.parametrize(
    "origin", ["1.5 2", "abc", "1 2 3", "", "1", "0x10 5", "1_0 2", "99999999999999999 0"]
)
def test_bad_origin_chunk(tmp_path, origin):
    p = write(tmp_path / "o.png", png_with(np.ones((2, 2), dtype=np.uint8), origin=origin))
    with pytest.raises(FileFormatError, match=r"o\.png.*(mrm:origin|2\^31)"):
        read_pixels(p)


@pytest.mark.parametrize("origin", [f"{2**53} 0", f"{2**31 + 1} 0", f"0 {-(2**31) - 1}"])
def test_origin_beyond_the_document_limit_is_refused(tmp_path, origin):
    p = write(tmp_path / "o.png", png_with(np.ones((1, 1), dtype=np.uint8), origin=origin))
    with pytest.raises(FileFormatError, match="beyond ±2\\^31"):
        read_pixels(p)


def test_origin_at_the_document_limit_is_read(tmp_path):
    p = write(tmp_path / "o.png", png_with(np.ones((1, 1), dtype=np.uint8), origin=f"{2**31} {-(2**31)}"))
    assert read_pixels(p) == PixelSet.from_points([(2**31, -(2**31))])


def test_huge_dimensions_are_refused_before_decoding(tmp_path):
    p = write(tmp_path / "h.png", huge_png_header(100_000, 100_000))
    with pytest.raises(FileFormatError, match="more than the limit"):
        read_pixels(p)
    small = write(tmp_path / "s.png", good_png())
    with pytest.raises(FileFormatError, match="more than the limit of 100"):
        read_pixels(small, limit=100)
    assert read_pixels(small, limit=600).count > 0
    with pytest.raises(FileFormatError, match="more than the limit"):
        read_label_map(p)


def npz_bytes(**arrays) -> bytes:
    buf = io.BytesIO()
    np.savez(buf, **arrays)
    return buf.getvalue()


@pytest.mark.parametrize(
    ("arrays", "message"),
    [
        ({"mask": np.array([None, 1], dtype=object), "origin": np.zeros(2, np.int64)}, "Python objects"),
        ({"mask": np.ones((2, 2), np.uint8), "origin": np.zeros(2, np.int64)}, "boolean"),
        ({"mask": np.ones(4, bool), "origin": np.zeros(2, np.int64)}, "2-D"),
        ({"mask": np.ones((2, 2, 2), bool), "origin": np.zeros(2, np.int64)}, "2-D"),
        ({"mask": np.ones((2, 2), bool), "origin": np.zeros(2, np.float64)}, "two integers"),
        ({"mask": np.ones((2, 2), bool), "origin": np.zeros(3, np.int64)}, "two integers"),
        ({"mask": np.ones((2, 2), bool)}, "no 'origin'"),
        ({"labels": np.ones((2, 2), np.int32), "origin": np.zeros(2, np.int64)}, "no 'mask'"),
        ({"mask": np.ones((2, 2), bool), "origin": np.array([2**62, 0], np.int64)}, "2\\^31"),
    ],
)
def test_bad_npz_arrays(tmp_path, arrays, message):
    p = write(tmp_path / "n.npz", npz_bytes(**arrays))
    with pytest.raises(FileFormatError, match=message) as e:
        read_pixels(p)
    assert "n.npz" in str(e.value)


def test_npz_with_a_lying_header_is_refused_before_reading(tmp_path):
    header = {"descr": "|b1", "fortran_order": False, "shape": (10**6, 10**6)}
    npy = io.BytesIO()
    np.lib.format.write_array_header_1_0(npy, header)
    npy.write(b"\x01" * 10)
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as z:
        z.writestr("mask.npy", npy.getvalue())
        z.writestr("origin.npy", npz_member(np.zeros(2, np.int64)))
    p = write(tmp_path / "big.npz", buf.getvalue())
    with pytest.raises(FileFormatError, match="more than the limit"):
        read_pixels(p)
    # a header that promises more data than there is
    header["shape"] = (100, 100)
    npy = io.BytesIO()
    np.lib.format.write_array_header_1_0(npy, header)
    npy.write(b"\x01" * 10)
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as z:
        z.writestr("mask.npy", npy.getvalue())
        z.writestr("origin.npy", npz_member(np.zeros(2, np.int64)))
    p2 = write(tmp_path / "short.npz", buf.getvalue())
    with pytest.raises(FileFormatError, match="truncated"):
        read_pixels(p2)


def npz_member(a: np.ndarray) -> bytes:
    buf = io.BytesIO()
    np.save(buf, a)
    return buf.getvalue()


def test_corrupt_and_truncated_npz(tmp_path):
    ps = PixelSet.from_points([(0, 0), (5, 3)])
    write_pixels(ps, tmp_path / "a.npz")
    data = (tmp_path / "a.npz").read_bytes()
    for n in (0, 10, len(data) // 2, len(data) - 5):
        p = write(tmp_path / "t.npz", data[:n])
        with pytest.raises(FileFormatError, match=r"t\.npz"):
            read_pixels(p)
    write(tmp_path / "r.npz", bytes(np.random.default_rng(2).integers(0, 256, 300, dtype=np.uint8)))
    with pytest.raises(FileFormatError, match="not an NPZ"):
        read_pixels(tmp_path / "r.npz")


def test_unknown_extensions(tmp_path):
    with pytest.raises(FileFormatError, match=r"'\.jpg'"):
        write_pixels(PixelSet.empty(), tmp_path / "a.jpg")
    with pytest.raises(FileFormatError, match="no extension"):
        read_pixels(tmp_path / "noext")
    with pytest.raises(FileFormatError, match="label map"):
        read_label_map(tmp_path / "a.pbm")


def test_missing_file_and_directory_errors(tmp_path):
    with pytest.raises(FileNotFoundError):
        read_pixels(tmp_path / "missing.png")
    with pytest.raises(FileNotFoundError) as e:
        write_pixels(PixelSet.empty(), tmp_path / "no" / "such" / "dir.png")
    assert "such" in str(e.value.filename)
    (tmp_path / "d.png").mkdir()
    with pytest.raises(IsADirectoryError) as e2:
        write_pixels(PixelSet.empty(), tmp_path / "d.png")
    assert e2.value.filename.endswith("d.png")


# ---------------------------------------------------------------------------------------------- atomic writes
def test_failed_write_leaves_the_old_file_and_no_temporary(tmp_path):
    p = tmp_path / "keep.png"
    write_pixels(PixelSet.from_points([(1, 1)]), p)
    before = p.read_bytes()
    with pytest.raises(RuntimeError), atomic_open(p, "wb") as fh:
        fh.write(b"half a file")
        raise RuntimeError("disk on fire")
    assert p.read_bytes() == before
    assert sorted(os.listdir(tmp_path)) == ["keep.png"]
    with pytest.raises(ParameterError):
        write_label_map(LabelMap(np.array([[70000]])), tmp_path / "keep.png")
    assert p.read_bytes() == before


def test_atomic_write_replaces_keeps_mode_and_follows_symlinks(tmp_path):
    p = tmp_path / "f.bin"
    atomic_write_bytes(p, b"one")
    os.chmod(p, 0o640)
    atomic_write_bytes(p, b"two")
    assert p.read_bytes() == b"two"
    assert stat.S_IMODE(os.stat(p).st_mode) == 0o640
    link = tmp_path / "link.bin"
    link.symlink_to(p)
    atomic_write_bytes(link, b"three")
    assert link.is_symlink() and p.read_bytes() == b"three"
    with atomic_open(tmp_path / "t.txt", "w") as fh:
        fh.write("é\n")
    assert (tmp_path / "t.txt").read_bytes() == "é\n".encode()
    assert sorted(os.listdir(tmp_path)) == ["f.bin", "link.bin", "t.txt"]


def test_label_map_reads_a_grey_pgm_and_an_npz_without_origin(tmp_path):
    # One reader for the application's import and `mrm polygonize`: a PGM's grey values are the labels
    # (16-bit too), its origin comment places it; an NPZ holding `labels` alone sits at the origin.
    rows = np.array([[0, 0, 300], [7, 7, 0]], dtype=">u2")  # row 0 is the top row
    p = tmp_path / "l.pgm"
    p.write_bytes(b"P5\n# mrm:origin -4 9\n3 2 65535\n" + rows.tobytes())
    assert read_label_map(p) == LabelMap(np.array([[7, 7, 0], [0, 0, 300]]), (-4, 9))
    plain = tmp_path / "plain.pgm"
    plain.write_bytes(b"P2 2 1 9 0 5")
    assert read_label_map(plain) == LabelMap(np.array([[0, 5]]), (0, 0))
    np.savez(tmp_path / "bare.npz", labels=np.array([[1, 0], [0, 2]], dtype=np.int16))
    assert read_label_map(tmp_path / "bare.npz") == LabelMap(np.array([[1, 0], [0, 2]]), (0, 0))
    (tmp_path / "bits.pgm").write_bytes(b"P4 8 1 \xff")  # a bitmap is not a label image
    with pytest.raises(FileFormatError, match="grey PGM"):
        read_label_map(tmp_path / "bits.pgm")
