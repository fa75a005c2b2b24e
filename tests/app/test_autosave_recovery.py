"""Issue 11 through the window: a failing autosave is shown and retried; an orphan's recorded path is shown
but never becomes the recovered document's path."""

from __future__ import annotations

import os
import subprocess
import sys

from mrm.core.grids import PixelSet
from mrm.document import Document
from mrm.document.commands import AddObject, RenameObject
from mrm.io import autosave
from mrm.io.project import dumps
from tests.app.helpers import answer_dialog


def test_a_failing_autosave_is_shown_in_the_status_bar_and_retried(make_window, monkeypatch):
    win = make_window()
    win.doc.push(AddObject(win.doc.make_object(PixelSet.box(0, 0, 3, 3), "sq")))
    real = autosave.dumps

    def failing(*a, **k):  # the lone surrogate, whatever the content
        raise UnicodeEncodeError("utf-8", "\ud800", 0, 1, "surrogates not allowed")

    monkeypatch.setattr(autosave, "dumps", failing)
    win.files.autosaver.interval = 0.0
    win.files.autosave_tick()  # must not raise out of the timer slot
    assert win.status.currentMessage().startswith("Autosave failed, will retry: 'utf-8' codec")
    assert not win.files.autosaver.path.exists()
    monkeypatch.setattr(autosave, "dumps", real)
    monkeypatch.setattr(autosave, "RETRY_SECONDS", 0.0)
    win.doc.push(RenameObject(win.doc.objects[0].id, "renamed"))
    win.files.autosaver._retry_at = 0.0  # the retry is due
    win.files.autosave_tick()
    assert win.files.autosaver.path.is_file() and win.files.autosaver.failures == 0


def test_an_orphans_recorded_path_is_shown_not_adopted(make_window, qtbot, autosave_dir, tmp_path):
    victim = tmp_path / "precious.mrm"
    victim.write_bytes(b"precious")
    doc = Document()
    doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 2, 2), "orphaned work")))
    dead = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True
    )
    autosave_dir.mkdir(parents=True, exist_ok=True)
    orphan = autosave_dir / f"untitled-{int(dead.stdout)}-cafe.mrm.autosave"
    orphan.write_bytes(dumps(doc, autosave={"project": str(victim), "saved_at": "2026-01-01T00:00:00+00:00"}))
    (autosave_dir / "untitled-99999999999999999999-x.mrm.autosave").write_bytes(b"junk")
    win = make_window()
    texts = answer_dialog(qtbot, "recoveryDialog", "Recover")
    assert win.files.check_orphans()
    assert str(victim) in texts[0]
    assert [o.name for o in win.doc.objects] == ["orphaned work"]
    assert win.doc.path is None and win.doc.is_modified  # Save will ask where to write
    assert victim.read_bytes() == b"precious"


def test_two_windows_on_one_project_never_lose_each_others_edits(make_window, qtbot, tmp_path, monkeypatch):
    """Issue 32, class 7: B's autosave and B's save leave A's autosave alone; A's crash is recovered."""
    from mrm.io.project import save_project

    path = tmp_path / "shared.mrm"
    doc = Document()
    doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 4, 4), "start")))
    save_project(doc, path)
    a, b = make_window(), make_window()
    offered: list[object] = []
    monkeypatch.setattr(b.files, "offer_recovery", lambda rec, *_: offered.append(rec) or False)
    assert a.files.open(path, ask=False)
    a.doc.push(RenameObject(a.doc.objects[0].id, "edited in A"))
    a.files.autosaver.interval = 0.0
    a.files.autosave_tick()
    assert b.files.open(path, ask=False)
    assert offered == []  # A is open: its autosave is no crash to recover from
    b.doc.push(RenameObject(b.doc.objects[0].id, "edited in B"))
    b.files.autosaver.interval = 0.0
    b.files.autosave_tick()  # B's autosave after A's
    assert b.files.save()  # B saves its own edits
    side_a = a.files.autosaver.path
    assert side_a.is_file() and b"edited in A" in side_a.read_bytes()
    a.close_now(discard_autosave=False)  # A crashes with its edits unsaved

    c = make_window()
    texts = answer_dialog(qtbot, "recoveryDialog", "Recover")
    assert c.files.open(path, ask=False)
    assert "shared.mrm" in texts[0]
    assert [o.name for o in c.doc.objects] == ["edited in A"] and c.doc.is_modified
    assert not side_a.exists()  # recovered: now in C's own autosave


def test_every_untitled_orphan_is_offered_in_turn(make_window, qtbot, autosave_dir):
    """Two crashed windows left two untitled autosaves: the second is offered after "Later" on the first."""
    from PySide6 import QtWidgets

    from tests.app.helpers import _when_modal

    dead = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True
    )
    for k, name in enumerate(("older work", "newer work")):
        doc = Document()
        doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 2, 2), name)))
        orphan = autosave_dir / f"untitled-{int(dead.stdout)}-{k}.mrm.autosave"
        orphan.write_bytes(dumps(doc))
        os.utime(orphan, (1_000_000 + k, 1_000_000 + k))
    seen: list[str] = []

    def click(w: QtWidgets.QMessageBox, text: str) -> None:
        seen.append(w.text())
        next(b for b in w.buttons() if b.text().replace("&", "") == text).click()

    def second(w: QtWidgets.QMessageBox) -> None:
        if "2 of 2" not in w.text():  # still the first box, closing
            _when_modal(QtWidgets.QMessageBox, "recoveryDialog", second)
            return
        click(w, "Recover")

    def first(w: QtWidgets.QMessageBox) -> None:
        click(w, "Later")
        _when_modal(QtWidgets.QMessageBox, "recoveryDialog", second)

    win = make_window()
    _when_modal(QtWidgets.QMessageBox, "recoveryDialog", first)
    assert win.files.check_orphans()
    assert "1 of 2" in seen[0] and "2 of 2" in seen[-1]
    assert [o.name for o in win.doc.objects] == ["older work"]  # newest first: the older one came second
    assert (autosave_dir / f"untitled-{int(dead.stdout)}-1.mrm.autosave").exists()  # "Later": kept
