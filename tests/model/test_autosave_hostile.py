"""Issue 11, classes 2 and 6: autosave failures are reported and retried; what recovery finds is not trusted;
interrupted saves leave nothing behind for long."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from mrm.core.errors import FileFormatError
from mrm.core.grids import PixelSet
from mrm.document import Document
from mrm.document.commands import AddObject, RenameObject
from mrm.io import autosave
from mrm.io.atomic import atomic_write_bytes, remove_stale_temps
from mrm.io.autosave import Autosaver, find_orphans, find_recovery, side_file
from mrm.io.project import dumps, save_project


class Clock:
    def __init__(self) -> None:
        self.t = 0.0

    def __call__(self) -> float:
        return self.t


def edited_doc() -> Document:
    doc = Document()
    doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 2, 2), "a")))
    return doc


def dead_pid() -> int:
    p = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True
    )
    return int(p.stdout)


# ---------------------------------------------------------------------------------------------- class 2
def test_a_failing_autosave_is_reported_retried_and_never_raises(tmp_path, monkeypatch):
    doc = edited_doc()
    clock = Clock()
    messages: list[str] = []
    saver = Autosaver(doc, interval=10, directory=tmp_path / "as", clock=clock, on_error=messages.append)
    calls = {"n": 0}
    real = autosave.dumps if hasattr(autosave, "dumps") else dumps

    def failing(*a, **k):
        calls["n"] += 1
        if calls["n"] <= 2:
            raise UnicodeEncodeError("utf-8", "\ud800", 0, 1, "surrogates not allowed")
        return real(*a, **k)

    monkeypatch.setattr(autosave, "dumps", failing)
    clock.t = 11
    assert saver.tick() is None  # no exception out of the timer's callback
    assert messages == [
        "Autosave failed, will retry: 'utf-8' codec can't encode character '\\ud800' in position 0: "
        "surrogates not allowed"
    ]
    assert saver.failures == 1 and saver.last_error is not None
    clock.t = 12
    assert saver.tick() is None and calls["n"] == 1  # waits RETRY_SECONDS before trying again
    clock.t = 11 + autosave.RETRY_SECONDS
    assert saver.tick() is None and calls["n"] == 2 and len(messages) == 2
    clock.t += autosave.RETRY_SECONDS
    written = saver.tick()
    assert written is not None and written.exists() and saver.failures == 0 and saver.last_error is None


def test_an_os_error_while_autosaving_is_reported(tmp_path):
    doc = edited_doc()
    blocker = tmp_path / "file"
    blocker.write_text("x")
    messages: list[str] = []
    saver = Autosaver(
        doc, interval=0, directory=blocker / "sub", on_error=messages.append
    )  # a path through a file
    assert saver.tick() is None
    assert len(messages) == 1 and "Autosave failed, will retry" in messages[0]


# ---------------------------------------------------------------------------------------------- class 6
JUNK = [
    "untitled-99999999999999999999-x.mrm.autosave",
    "untitled--x.mrm.autosave",
    "untitled-12-.mrm.autosave",
    "untitled-abc-x.mrm.autosave",
    "untitled-0-x.mrm.autosave",
    "untitled-1e9-x.mrm.autosave",
    "untitled-\u0661\u0662-x.mrm.autosave",  # Arabic-Indic digits pass str.isdigit()
    ".mrm.autosave",
    "untitled-4-x.mrm.autosave.tmp",
]


def test_junk_names_in_the_autosave_folder_never_fail_a_start(tmp_path):
    d = tmp_path / "as"
    d.mkdir()
    for name in JUNK:
        (d / name).write_bytes(b"not a project")
    (d / "untitled-7-dir.mrm.autosave").mkdir()
    (d / "untitled-8-link.mrm.autosave").symlink_to(tmp_path / "nowhere")
    found = find_orphans(d)
    # Junk is skipped; a file of our pattern whose pid cannot be alive is offered (damaged: discardable).
    assert [r.path.name for r in found] == ["untitled-0-x.mrm.autosave"]
    assert all(r.project is None for r in found)


def test_an_orphans_recorded_path_is_offered_never_adopted(tmp_path):
    victim = tmp_path / "precious.mrm"
    victim.write_bytes(b"precious data")
    d = tmp_path / "as"
    d.mkdir()
    doc = edited_doc()
    data = dumps(doc, autosave={"project": str(victim), "saved_at": "2026-01-01T00:00:00+00:00"})
    orphan = d / f"untitled-{dead_pid()}-cafe.mrm.autosave"
    orphan.write_bytes(data)
    (rec,) = find_orphans(d)
    assert rec.project is None and rec.recorded == victim
    restored = rec.restore()
    assert restored.path is None and restored.is_modified  # Save asks where to write
    assert victim.read_bytes() == b"precious data"


def test_recovery_of_an_opened_project_uses_the_project_being_opened_not_the_record(tmp_path):
    proj = tmp_path / "p.mrm"
    doc = edited_doc()
    save_project(doc, proj)
    elsewhere = tmp_path / "elsewhere.mrm"
    side = side_file(proj)
    side.write_bytes(dumps(doc, autosave={"project": str(elsewhere), "saved_at": "x"}))
    os.utime(side, (proj.stat().st_mtime + 10,) * 2)
    rec = find_recovery(proj)
    assert rec is not None and rec.project == proj and rec.recorded == elsewhere
    assert rec.restore().path == proj


def test_autosave_never_follows_a_planted_symlink(tmp_path):
    proj = tmp_path / "name.mrm"
    doc = edited_doc()
    save_project(doc, proj)
    target = tmp_path / "victim.txt"
    target.write_bytes(b"keep me")
    saver = Autosaver(doc, interval=0)
    side_file(proj, saver.writer).symlink_to(target)
    doc.push(RenameObject(doc.objects[0].id, "b"))
    written = saver.tick()
    assert written == side_file(proj, saver.writer)
    assert target.read_bytes() == b"keep me"
    assert not written.is_symlink() and b'"b"' in written.read_bytes()


def test_stale_temporary_files_of_our_pattern_are_removed_on_the_next_save(tmp_path):
    proj = tmp_path / "proj.mrm"
    dead = dead_pid()
    stale = [tmp_path / f".proj.mrm.{dead}-{k:08x}.tmp" for k in range(14)]
    for p in stale:
        p.write_bytes(b"x" * 1000)
    legacy_old = tmp_path / ".proj.mrm.deadbeef.tmp"
    legacy_old.write_bytes(b"old")
    os.utime(legacy_old, (1, 1))
    legacy_new = tmp_path / ".proj.mrm.0badf00d.tmp"  # may be another process's save in progress
    legacy_new.write_bytes(b"new")
    alive = tmp_path / f".proj.mrm.{os.getpid()}-0000abcd.tmp"  # ours, in progress
    alive.write_bytes(b"live")
    other = tmp_path / ".other.mrm.deadbeef.tmp"
    other.write_bytes(b"other")
    os.utime(other, (1, 1))
    target = tmp_path / "victim"
    target.write_bytes(b"v")
    link = tmp_path / f".proj.mrm.{dead}-00000fff.tmp"
    link.symlink_to(target)
    atomic_write_bytes(proj, b"data")
    left = sorted(p.name for p in tmp_path.iterdir())
    assert left == sorted(["proj.mrm", legacy_new.name, alive.name, other.name, "victim", link.name])
    assert target.read_bytes() == b"v"
    assert remove_stale_temps(proj) == 0


def test_temporary_files_left_by_killed_saves_are_cleaned_by_the_next_save(tmp_path):
    proj = tmp_path / "k.mrm"
    code = (
        "import os, sys; from mrm.io import atomic; cm = atomic.atomic_open(sys.argv[1]); "
        "fh = cm.__enter__(); fh.write(b'half'); fh.flush(); os._exit(9)"
    )
    for _ in range(5):
        subprocess.run([sys.executable, "-c", code, str(proj)], check=False)
        # Each interrupted save removed the one before it: one stale file at most, never a growing pile.
        assert len(list(tmp_path.glob(".k.mrm.*.tmp"))) == 1 and not proj.exists()
    save_project(edited_doc(), proj)
    assert list(tmp_path.glob(".k.mrm.*.tmp")) == []
    assert Path(proj).read_bytes().startswith(b"{")


@pytest.mark.parametrize("name", JUNK)
def test_every_junk_name_alone_is_harmless(tmp_path, name):
    d = tmp_path / "as"
    d.mkdir()
    (d / name).write_bytes(b"\x00\xff junk")
    for rec in find_orphans(d):
        assert rec.project is None
        with pytest.raises(FileFormatError, match=r"not an MR Modeler project|not UTF-8|empty"):
            rec.restore()


# ------------------------------------------------------------------------------------------ issue 32, class 7
def opened(project: Path) -> Document:
    from mrm.io.project import load_project

    return load_project(project)


def test_two_writers_on_one_project_keep_their_own_autosaves(tmp_path):
    proj = tmp_path / "shared.mrm"
    save_project(edited_doc(), proj)
    doc_a, doc_b = opened(proj), opened(proj)
    saver_a = Autosaver(doc_a, interval=0)
    saver_b = Autosaver(doc_b, interval=0)
    doc_a.push(RenameObject(doc_a.ids[0], "edited in A"))
    doc_b.push(RenameObject(doc_b.ids[0], "edited in B"))
    side_a, side_b = saver_a.tick(), saver_b.tick()  # B's autosave comes last
    assert side_a is not None and side_b is not None and side_a != side_b
    assert b"edited in A" in side_a.read_bytes()
    save_project(doc_b, proj)  # B saves its edits, and drops its own side file only
    saver_b.tick()
    assert not side_b.exists() and side_a.exists()
    assert find_recovery(proj) is None  # A is still open: its autosave is not an orphan
    saver_a.close()  # A crashes
    (rec,) = autosave.find_recoveries(proj)
    assert rec.project == proj and [o.name for o in rec.restore().objects] == ["edited in A"]


WRITER = """
import os, sys
from mrm.document.commands import RenameObject
from mrm.io.autosave import Autosaver
from mrm.io.project import load_project
doc = load_project(sys.argv[1])
doc.push(RenameObject(doc.ids[0], sys.argv[2]))
Autosaver(doc, interval=0).tick()
print("written", flush=True)
if sys.argv[3] == "crash":
    os._exit(9)
sys.stdin.read()  # alive until the test closes our stdin
"""


def test_every_crashed_process_is_offered_and_a_live_one_is_not(tmp_path):
    proj = tmp_path / "p.mrm"
    save_project(edited_doc(), proj)
    for name in ("first crash", "second crash"):
        subprocess.run([sys.executable, "-c", WRITER, str(proj), name, "crash"], check=False)
    live = subprocess.Popen(
        [sys.executable, "-c", WRITER, str(proj), "still open", "wait"],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert live.stdout is not None and live.stdout.readline().strip() == "written"
        assert len(list(tmp_path.glob(".p.mrm.*.autosave"))) == 3  # one side file per writer
        found = autosave.find_recoveries(proj)
        names = sorted(rec.restore().objects[0].name for rec in found)
        assert names == ["first crash", "second crash"]  # every orphan; the live writer's is not one
    finally:
        live.communicate("")
    names = sorted(rec.restore().objects[0].name for rec in autosave.find_recoveries(proj))
    assert names == ["first crash", "second crash", "still open"]  # exited without discarding


def test_a_legacy_shared_side_file_is_still_recovered(tmp_path):
    proj = tmp_path / "old.mrm"
    doc = edited_doc()
    save_project(doc, proj)
    legacy = side_file(proj)
    assert legacy.name == ".old.mrm.autosave"
    legacy.write_bytes(dumps(doc, autosave={"project": str(proj), "saved_at": "x"}))
    os.utime(legacy, (proj.stat().st_mtime + 10,) * 2)
    (rec,) = autosave.find_recoveries(proj)
    assert rec.path == legacy
