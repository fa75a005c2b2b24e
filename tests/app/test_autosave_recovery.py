"""Issue 11 through the window: a failing autosave is shown and retried; an orphan's recorded path is shown
but never becomes the recovered document's path."""

from __future__ import annotations

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
