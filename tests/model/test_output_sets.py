"""Issue 32, class 6: an output set (a PNG + world file + .prj, the parts of a co-refinement) is replaced as a
whole or not at all — a full disk or a failing rename midway leaves the old set byte for byte, no temporary
file behind."""

from __future__ import annotations

import errno
import os
from pathlib import Path

import pytest
import shapely

import mrm.io.atomic as atomic
from mrm.cli import run_cli
from mrm.core.georef import GeoRef
from mrm.core.grids import PixelSet
from mrm.io.atomic import atomic_file_set, atomic_write_bytes
from mrm.io.georef import read_georef, write_georeferenced
from mrm.io.pixel_files import read_pixels

OLD = GeoRef((10.0, 0.0, 500000.0, 0.0, -10.0, 4000000.0), 8, 8, "EPSG:32633")
NEW = GeoRef((2.0, 0.0, 100.0, 0.0, -2.0, 900.0), 8, 8, "EPSG:32633")


def snapshot(folder: Path) -> dict[str, bytes]:
    """Every file of ``folder`` (hidden temporary files included) and its bytes."""
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir()) if p.is_file()}


def fail_nth_write(monkeypatch, n: int) -> None:
    """The n-th file written through an atomic write gets half its bytes, then ENOSPC."""
    real_fdopen = os.fdopen
    count = {"opened": 0}

    class DiskFull:
        def __init__(self, fh):
            self.fh = fh

        def write(self, data):
            self.fh.write(data[: len(data) // 2])
            raise OSError(errno.ENOSPC, "No space left on device")

        def __getattr__(self, name):
            return getattr(self.fh, name)

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            return self.fh.__exit__(*exc)

    def fdopen(fd, mode="r", *a, **k):
        fh = real_fdopen(fd, mode, *a, **k)
        if "w" not in mode:
            return fh  # an input being read
        count["opened"] += 1
        return DiskFull(fh) if count["opened"] == n else fh

    monkeypatch.setattr(atomic.os, "fdopen", fdopen)


def fail_nth_rename(monkeypatch, n: int) -> None:
    """The n-th ``os.replace`` raises (EIO: the rename itself fails midway through the set)."""
    real = os.replace
    count = {"renames": 0}

    def replace(src, dst):
        count["renames"] += 1
        if count["renames"] == n:
            raise OSError(errno.EIO, "Input/output error")
        return real(src, dst)

    monkeypatch.setattr(atomic.os, "replace", replace)


@pytest.fixture
def old_png_set(tmp_path: Path) -> Path:
    out = tmp_path / "out.png"
    write_georeferenced(PixelSet.box(0, 0, 7, 7), out, OLD)
    # the CRS twice: in the PAM file GDAL reads, and in the .prj older MR Modeler and some tools read
    assert {p.name for p in tmp_path.iterdir()} == {"out.png", "out.pgw", "out.prj", "out.png.aux.xml"}
    return out


@pytest.mark.parametrize("member", [1, 2, 3, 4])
def test_a_full_disk_while_exporting_a_georeferenced_png_keeps_the_old_set(old_png_set, monkeypatch, member):
    before = snapshot(old_png_set.parent)
    fail_nth_write(monkeypatch, member)  # the PNG, the world file, the .prj, the .aux.xml, in some order
    with pytest.raises(OSError) as e:
        write_georeferenced(PixelSet.box(2, 2, 4, 5), old_png_set, NEW)
    monkeypatch.undo()
    assert e.value.errno == errno.ENOSPC
    assert snapshot(old_png_set.parent) == before  # byte-identical, and no temporary file left
    assert read_georef(old_png_set).transform == OLD.transform


@pytest.mark.parametrize("rename", [2, 3, 4])
def test_a_rename_failing_midway_rolls_the_set_back(old_png_set, monkeypatch, rename):
    before = snapshot(old_png_set.parent)
    fail_nth_rename(monkeypatch, rename)
    with pytest.raises(OSError):
        write_georeferenced(PixelSet.box(2, 2, 4, 5), old_png_set, NEW)
    monkeypatch.undo()
    assert snapshot(old_png_set.parent) == before


def test_a_new_set_replaces_the_whole_old_one_and_a_stale_prj_goes(old_png_set):
    no_crs = GeoRef(NEW.transform, NEW.width, NEW.height, None)
    write_georeferenced(PixelSet.box(2, 2, 4, 5), old_png_set, no_crs)
    # Without removal the old .prj and .aux.xml would give the new picture a CRS it does not have.
    assert {p.name for p in old_png_set.parent.iterdir()} == {"out.png", "out.pgw"}
    g = read_georef(old_png_set)
    assert g is not None and g.transform == NEW.transform and g.crs is None
    assert len(read_pixels(old_png_set)) == len(PixelSet.box(2, 2, 4, 5))


def test_a_new_geotiff_is_not_placed_by_an_old_aux_xml(tmp_path, monkeypatch):
    out = tmp_path / "out.tif"
    write_georeferenced(PixelSet.box(0, 0, 7, 7), out, OLD)
    # What a GIS leaves beside a GeoTIFF it re-referenced: GDAL reads it before the file's own transform.
    aux = tmp_path / "out.tif.aux.xml"
    aux.write_text("<PAMDataset><GeoTransform>1, 1, 0, 1, 0, -1</GeoTransform></PAMDataset>")
    before = snapshot(tmp_path)
    fail_nth_write(monkeypatch, 1)
    with pytest.raises(OSError):
        write_georeferenced(PixelSet.box(2, 2, 4, 5), out, NEW)
    monkeypatch.undo()
    assert snapshot(tmp_path) == before  # the old set, its .aux.xml included, as it was
    write_georeferenced(PixelSet.box(2, 2, 4, 5), out, NEW)
    assert not aux.exists() and read_georef(out).transform == NEW.transform


def test_a_failed_set_on_a_new_name_leaves_nothing(tmp_path, monkeypatch):
    fail_nth_rename(monkeypatch, 2)
    with pytest.raises(OSError):
        write_georeferenced(PixelSet.box(0, 0, 3, 3), tmp_path / "new.png", NEW)
    monkeypatch.undo()
    assert list(tmp_path.iterdir()) == []


def test_an_error_inside_the_set_writes_nothing(tmp_path):
    (tmp_path / "a").write_bytes(b"old a")
    with pytest.raises(RuntimeError), atomic_file_set():
        atomic_write_bytes(tmp_path / "a", b"new a")
        atomic_write_bytes(tmp_path / "b", b"new b")
        raise RuntimeError("the third part could not be computed")
    assert snapshot(tmp_path) == {"a": b"old a"}


def test_without_hard_links_the_backups_are_copies(tmp_path, monkeypatch):
    for name in "ab":
        (tmp_path / name).write_bytes(b"old " + name.encode())

    def no_links(*a, **k):
        raise OSError(errno.EPERM, "Operation not permitted")

    monkeypatch.setattr(atomic.os, "link", no_links)
    fail_nth_rename(monkeypatch, 2)
    with pytest.raises(OSError), atomic_file_set():
        atomic_write_bytes(tmp_path / "a", b"new a")
        atomic_write_bytes(tmp_path / "b", b"new b")
    monkeypatch.undo()
    assert snapshot(tmp_path) == {"a": b"old a", "b": b"old b"}


# ---------------------------------------------------------------------------------------------- corefine
TRIANGLE = shapely.Polygon([(0, 0), (9, 1), (2, 7)])
SQUARE = shapely.box(4, -1, 11, 5)
OTHER = shapely.box(-3, -3, 1, 2)


@pytest.mark.parametrize(("ext", "member"), [(".wkt", 3), (".wkt", 2), ("", 3), (".svg", 2)])
def test_corefine_after_a_full_disk_keeps_the_three_old_parts(tmp_path, capsys, monkeypatch, ext, member):
    a, b, c = (tmp_path / n for n in ("a.wkt", "b.wkt", "c.wkt"))
    a.write_text(TRIANGLE.wkt)
    b.write_text(SQUARE.wkt)
    c.write_text(OTHER.wkt)
    out = tmp_path / "out" / f"parts{ext}"
    out.parent.mkdir()
    assert run_cli(["corefine", str(a), str(b), "-o", str(out), "--no-measure"]) == 0
    before = snapshot(out.parent)
    assert len(before) == 3
    capsys.readouterr()
    fail_nth_write(monkeypatch, member)
    code = run_cli(["corefine", str(a), str(c), "-o", str(out), "--no-measure"])
    monkeypatch.undo()
    err = capsys.readouterr().err
    assert code == 2 and "No space left on device" in err and "Traceback" not in err
    assert snapshot(out.parent) == before
