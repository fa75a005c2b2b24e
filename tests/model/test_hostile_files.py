"""Issue 11, classes 2–5 and 8: hostile files are refused with a message, in bounded memory and time.

Every hostile file is generated here (tests/model/hostile.py); memory is measured with tracemalloc (numpy
reports its buffers to it) or, for whole-process peaks, in a child process with its own ``VmHWM`` (not
``ru_maxrss``, which on Linux keeps the peak of the forking parent across exec: the whole test run's).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
import tracemalloc
import warnings
from pathlib import Path

import hostile
import numpy as np
import pytest
from PIL import Image

import mrm.core.limits as limits
from mrm.core.errors import FileFormatError, LimitError, MRMError
from mrm.core.grids import PixelSet
from mrm.core.threshold import binarize, grey_of
from mrm.document import Document
from mrm.document.commands import AddObject
from mrm.io.imports import import_file
from mrm.io.pixel_files import read_label_map, read_pixels
from mrm.io.project import dumps, parse_project, read_project, save_project
from mrm.io.vector_files import read_geometries
from mrm.ops.provenance import Provenance

HERE = Path(__file__).parent


def peak_of(fn):
    """(result or exception, peak bytes traced) of ``fn()``."""
    tracemalloc.start()
    try:
        try:
            out = fn()
        except Exception as e:
            out = e
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return out, peak


# ---------------------------------------------------------------------------------------------- class 2
def test_a_lone_surrogate_feature_name_is_cleaned_on_import_and_the_document_saves(tmp_path):
    p = tmp_path / "s.geojson"
    feats = [
        {
            "type": "Feature",
            "properties": {"name": "\ud800"},
            "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]},
        },
        {
            "type": "Feature",
            "properties": {"name": "x" * 20_000},
            "geometry": {"type": "Polygon", "coordinates": [[[5, 5], [6, 5], [6, 6], [5, 5]]]},
        },
    ]
    p.write_text(json.dumps({"type": "FeatureCollection", "features": feats}))  # json escapes "\ud800"
    doc = Document()
    ids = import_file(doc, p)
    assert doc.get(ids[0]).name == "\ufffd"
    assert len(doc.get(ids[1]).name) == limits.MAX_NAME_CHARS and doc.get(ids[1]).name.endswith("…")
    save_project(doc, tmp_path / "s.mrm")
    assert [o.name for o in read_project(tmp_path / "s.mrm").objects] == [o.name for o in doc.objects]


def test_lone_surrogates_in_a_project_file_are_cleaned_on_load():
    doc = Document()
    prov = Provenance("OPNAME", {"KEY": "VALUE"}, ())
    doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 1, 1), "NAME", provenance=prov)))
    data = dumps(doc)
    for word, hostile_text in (
        (b"NAME", b"a\\ud800b"),
        (b"OPNAME", b"op\\udc80"),
        (b"KEY", b"\\udfff"),
        (b"VALUE", b"\\ud800"),
    ):
        data = data.replace(b'"' + word + b'"', b'"' + hostile_text + b'"')
    proj = parse_project(data, "p.mrm")
    o = proj.objects[0]
    assert (o.name, o.provenance.operation, dict(o.provenance.params)) == (
        "a\ufffdb",
        "op\ufffd",
        {"\ufffd": "\ufffd"},
    )
    back = proj.to_document()
    assert parse_project(dumps(back), "q.mrm").objects == list(back.objects)


def test_an_undecodable_file_name_gives_a_savable_object_name(tmp_path):
    raw = os.fsencode(tmp_path) + b"/caf\xe9.png"
    Image.fromarray(np.ones((2, 2), np.uint8) * 255).save(os.fsdecode(raw))
    doc = Document()
    ids = import_file(doc, os.fsdecode(raw))
    assert doc.get(ids[0]).name == "caf\ufffd"
    dumps(doc)


# ---------------------------------------------------------------------------------------------- class 3
@pytest.mark.parametrize("levels", [33, 1_000, 20_000])
def test_deeply_nested_wkt_is_refused_before_geos(tmp_path, levels):
    p = tmp_path / "deep.wkt"
    p.write_text(hostile.deep_wkt(levels))
    t = time.perf_counter()
    with pytest.raises(FileFormatError, match=f"nests parentheses {levels + 1:,} deep, more than the 32"):
        read_geometries(p)
    assert time.perf_counter() - t < 5


def test_nesting_at_the_limit_is_read(tmp_path):
    p = tmp_path / "ok.wkt"
    p.write_text(hostile.deep_wkt(31))  # 31 collections + the point's parentheses = 32
    ((_, g),) = read_geometries(p)
    assert g.geom_type == "GeometryCollection"


@pytest.mark.parametrize("levels", [33, 900, 5_000])
def test_deeply_nested_geojson_is_a_message(tmp_path, levels):
    p = tmp_path / "deep.geojson"
    p.write_text(hostile.deep_geojson(levels))
    with pytest.raises(FileFormatError, match="nested"):
        read_geometries(p)


def test_wkt_with_nan_gives_the_message_without_a_warning(tmp_path):
    p = tmp_path / "n.wkt"
    p.write_text("POLYGON ((0 0, nan 0, 1 1, 0 0))\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any library warning fails the test
        with pytest.raises(MRMError, match=r"coordinates must be finite numbers, found \(nan, 0\.0\)"):
            read_geometries(p)


def test_too_many_positions_are_refused_before_geos(tmp_path, monkeypatch):
    monkeypatch.setattr("mrm.io.vector_files.MAX_OBJECT_VERTICES", 100)
    p = tmp_path / "big.wkt"
    p.write_text("LINESTRING (" + ", ".join(f"{i} 0" for i in range(101)) + ")\n")
    with pytest.raises(FileFormatError, match="more than the limit of 100"):
        read_geometries(p)


# ---------------------------------------------------------------------------------------------- class 4
@pytest.mark.parametrize("shape", [(-1, 1000), (-1, 5), (5, -1), (-(2**40), -(2**40)), (2**62, 2**62)])
def test_npz_with_negative_or_absurd_dimensions_is_refused_before_decompression(tmp_path, shape):
    # A header claiming the shape, followed by 6 MB of zeros that must never be inflated.
    data = hostile.npz(
        {"mask": hostile.npy_header(shape) + bytes(6_000_000), "origin": hostile.npy(np.zeros(2, np.int64))}
    )
    p = tmp_path / "n.npz"
    p.write_bytes(data)
    out, peak = peak_of(lambda: read_pixels(p))
    assert isinstance(out, FileFormatError) and "'mask'" in str(out)
    assert ("invalid shape" in str(out)) or ("more than the limit" in str(out))
    assert peak < 2_000_000 + len(data)


def test_npz_of_an_unsupported_zip_version_is_a_message(tmp_path):
    # Found by random fuzzing: zipfile raises NotImplementedError("zip file version 9.6").
    data = bytearray(
        hostile.npz(
            {"mask": hostile.npy(np.ones((2, 2), bool)), "origin": hostile.npy(np.zeros(2, np.int64))}
        )
    )
    central = data.rindex(b"PK\x01\x02")
    data[central + 6] = 96  # "version needed to extract" of the first central directory entry
    p = tmp_path / "v.npz"
    p.write_bytes(bytes(data))
    with pytest.raises(FileFormatError, match=r"v\.npz: unreadable NPZ archive: zip file version 9\.6"):
        read_pixels(p)


def test_npz_wide_dtypes_are_refused_before_reading(tmp_path):
    data = hostile.npz(
        {"mask": hostile.npy_header((10_000, 10_000), "<c16"), "origin": hostile.npy(np.zeros(2, np.int64))}
    )
    p = tmp_path / "c.npz"
    p.write_bytes(data)
    with pytest.raises(FileFormatError, match="must be a 2-D boolean array"):
        read_pixels(p)


MODES = [  # (colour type, depth, bytes of one pixel): every Pillow road that used to widen to int64
    (6, 8, 4),
    (6, 16, 8),
    (2, 8, 3),
    (4, 8, 2),
    (0, 16, 2),
    (3, 8, 1),
]


@pytest.mark.parametrize(("color", "depth", "bpp"), MODES)
def test_png_decoding_takes_about_one_byte_per_pixel(tmp_path, color, depth, bpp):
    n = 3000  # 9 M pixels: 4-byte decoding would be 36 MB, int64 colour arrays 200 MB and more
    pal = bytes(range(256)) * 3 if color == 3 else None
    data = hostile.png(
        n,
        n,
        color=color,
        depth=depth,
        palette=pal,
        level=1,
        row=(lambda r: bytes([r % 251]) * (n * bpp)) if color in (0, 3) else None,
    )
    p = tmp_path / "m.png"
    p.write_bytes(data)
    out, peak = peak_of(lambda: read_pixels(p))
    assert isinstance(out, PixelSet), out
    assert peak < n * n * 1.2 + 24e6, f"{peak / 1e6:.0f} MB for {n * n / 1e6:.0f} M pixels"


@pytest.mark.parametrize(
    ("mode", "make"),
    [
        ("RGBA", lambda rng, s: rng.integers(0, 256, (*s, 4), dtype=np.uint8)),
        (
            "RGBA",
            lambda rng, s: np.dstack(
                [np.full(s, 200, np.uint8)] * 3 + [rng.integers(0, 2, s, dtype=np.uint8) * 255]
            ),
        ),
        ("RGB", lambda rng, s: rng.integers(0, 256, (*s, 3), dtype=np.uint8)),
        ("LA", lambda rng, s: rng.integers(0, 256, (*s, 2), dtype=np.uint8)),
        ("L", lambda rng, s: rng.integers(0, 256, s, dtype=np.uint8)),
        ("I;16", lambda rng, s: rng.integers(0, 65536, s, dtype=np.uint16)),
        ("1", lambda rng, s: rng.integers(0, 2, s, dtype=np.uint8).astype(bool)),
        ("P", lambda rng, s: rng.integers(0, 7, s, dtype=np.uint8)),
    ],
)
@pytest.mark.parametrize("seed", range(4))
def test_streamed_png_matches_the_documented_rules_applied_to_pillows_decoding(tmp_path, mode, make, seed):
    rng = np.random.default_rng(seed)
    shape = (int(rng.integers(1, 40)), int(rng.integers(1, 40)))
    a = make(rng, shape)
    im = Image.fromarray(a)
    if mode == "P":
        im = Image.fromarray(a, mode="P")
        im.putpalette([int(v) for v in rng.integers(0, 256, 768)])
        im.info["transparency"] = bytes(int(v) for v in rng.integers(0, 256, 7))
    p = tmp_path / "x.png"
    im.save(p, optimize=bool(seed % 2))
    # The reference: Pillow's full decoding, then grey_of and binarize as mrm.core.threshold documents them.
    ref = Image.open(p)
    ref.load()
    if ref.mode == "1":
        rows = np.array(ref, dtype=bool)
    elif ref.mode in ("P", "PA"):
        rgba = np.array(ref.convert("RGBA"))
        rows = binarize(grey_of(rgba[..., :3], alpha=rgba[..., 3]))
    elif ref.mode == "LA":
        la = np.array(ref)
        rows = binarize(grey_of(la[..., 0], alpha=la[..., 1]))
    elif ref.mode == "RGBA":
        rgba = np.array(ref)
        rows = binarize(grey_of(rgba[..., :3], alpha=rgba[..., 3]))
    elif ref.mode == "RGB":
        rows = binarize(grey_of(np.array(ref)))
    else:
        rows = binarize(np.array(ref))
    assert read_pixels(p) == PixelSet(rows[::-1])


def test_a_14000_squared_all_zero_rgba_png_stays_far_under_1_gb(tmp_path):
    p = tmp_path / "z.png"
    p.write_bytes(hostile.png(14000, 14000, color=6, level=1))
    assert p.stat().st_size < 10_000_000
    code = (
        "import sys, time; from mrm.io.pixel_files import read_pixels; t = time.perf_counter(); "
        "ps = read_pixels(sys.argv[1]); "
        "hwm = [l.split()[1] for l in open('/proc/self/status') if l.startswith('VmHWM:')][0]; "
        "print(ps.count, hwm, time.perf_counter() - t)"
    )
    out = subprocess.run([sys.executable, "-c", code, str(p)], capture_output=True, text=True, check=True)
    count, rss_kb, seconds = out.stdout.split()
    assert int(count) == 0
    assert int(rss_kb) < 1_000_000, f"peak RSS {int(rss_kb) / 1024:.0f} MB"
    print(f"14000² RGBA: peak {int(rss_kb) / 1024:.0f} MB, {float(seconds):.1f} s")


def test_reconstruct_of_a_checkerboard_is_refused_before_work():
    from mrm.geometry.reconstruct import reconstruct

    ps = PixelSet(hostile.checkerboard(2048))
    t = time.perf_counter()
    with pytest.raises(LimitError, match="boundary of 8,388,608 pixel edges, more than the 2,000,000"):
        reconstruct(ps, "standard")  # R's one entry point applies its limit, for every caller
    assert time.perf_counter() - t < 5


def test_boundary_length_matches_a_direct_count():
    rng = np.random.default_rng(1)
    for _ in range(30):
        m = rng.random((int(rng.integers(1, 40)), int(rng.integers(1, 40)))) < 0.5
        padded = np.pad(m, 1)
        direct = sum(
            int(padded[r, c] != padded[r, c + 1])
            for r in range(padded.shape[0])
            for c in range(padded.shape[1] - 1)
        ) + sum(
            int(padded[r, c] != padded[r + 1, c])
            for r in range(padded.shape[0] - 1)
            for c in range(padded.shape[1])
        )
        assert limits.crack_steps(m, rows_per_strip=7) == direct


def test_export_of_a_checkerboard_object_is_refused_with_a_message_and_nothing_written(tmp_path, monkeypatch):
    from mrm.io.export import export_object

    doc = Document()
    o = doc.make_object(PixelSet(hostile.checkerboard(2048)), "cb")
    doc.push(AddObject(o))
    for ext, rep in ((".svg", None), (".geojson", None), (".svg", "both")):
        out = tmp_path / f"cb{ext}"
        with pytest.raises(LimitError, match="boundary"):
            export_object(doc, o.id, out, rep=rep)
        assert not out.exists() and not list(tmp_path.glob(".*.tmp"))
    # Its pixels as an SVG picture: 2 M rectangles of about 80 bytes, over a 100 MB output limit.
    monkeypatch.setattr(limits, "MAX_OUTPUT_BYTES", 100 << 20)
    big = tmp_path / "px.svg"
    with pytest.raises(LimitError, match="about 160 MB, more than the limit of 100 MB"):
        export_object(doc, o.id, big, rep="discrete")
    assert not big.exists()


# ---------------------------------------------------------------------------------------------- class 5
def test_200000_provenance_keys_are_refused_fast():
    doc = Document()
    doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 1, 1), "a", provenance=Provenance("op", {"x": 0}))))
    params = json.dumps({f"k{i}": i for i in range(200_000)}).encode()
    data = dumps(doc).replace(b'{"x": 0}', params)
    assert params in data
    t = time.perf_counter()
    with pytest.raises(FileFormatError, match="larger than 1,000,000 characters"):
        parse_project(data, "p.mrm")
    assert time.perf_counter() - t < 5


@pytest.mark.parametrize("n", [10_000, 40_000])
def test_project_validation_is_linear_in_the_number_of_keys(n):
    # Keys that pass the size check: the unknown-key check itself must not be quadratic.
    doc = Document()
    doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 1, 1), "a", provenance=Provenance("op", {"x": 0}))))
    params = json.dumps({str(i): 0 for i in range(n)}).encode()
    data = dumps(doc).replace(b'{"x": 0}', params)
    t = time.perf_counter()
    proj = parse_project(data, "p.mrm")
    assert len(proj.objects[0].provenance.params) == n
    assert time.perf_counter() - t < 3


def test_a_chain_of_14000_steps_is_refused_up_front(monkeypatch):
    from mrm.ops.chain import Link, chain_bound, parse_chain

    steps = parse_chain(", ".join(["DSS 1.25", "DSS 0.8"] * 7000))
    made = []
    original = Link.bound_step
    monkeypatch.setattr(Link, "bound_step", lambda self, n=2: made.append(1) or original(self, n))
    with pytest.raises(LimitError, match="14,000 steps, more than the limit of 256"):
        chain_bound(steps, "standard")
    assert not made  # refused before any step's exact arithmetic (a timing here flaked under load)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this system")
@pytest.mark.parametrize("fname", ["x.png", "x.npz", "x.pbm", "x.geojson", "x.wkt", "x.mrm"])
def test_a_fifo_is_refused_at_once(tmp_path, fname):
    p = tmp_path / fname
    os.mkfifo(p)
    t = time.perf_counter()
    with pytest.raises(FileFormatError, match="named pipe"):
        if fname.endswith(".mrm"):
            read_project(p)
        elif fname.endswith((".geojson", ".wkt")):
            read_geometries(p)
        else:
            read_pixels(p)
    assert time.perf_counter() - t < 2


# ---------------------------------------------------------------------------------------------- class 8
def test_a_png_holding_4_of_its_8_rows_is_refused(tmp_path):
    p = tmp_path / "half.png"
    p.write_bytes(hostile.png(8, 8, row=lambda r: bytes([255] * 8), rows_stored=4))
    with pytest.raises(FileFormatError, match="holds 4 of its 8 rows"):
        read_pixels(p)


def test_label_maps_are_bounded_by_their_own_limit(tmp_path):
    n = 8000  # 64 M pixels > 50 M: refused from the header, before decoding
    p = tmp_path / "l.png"
    p.write_bytes(hostile.png(n, n, level=1))
    with pytest.raises(FileFormatError, match="more than the limit of 50,000,000"):
        read_label_map(p)
