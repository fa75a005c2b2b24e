"""Autosave to a side file, and recovery on the next start (the model side: write, detect, restore).

While a document has unsaved edits, :class:`Autosaver` writes it — a complete project file with an extra
``"autosave"`` record — to a side file, after ``every_edits`` edits or ``interval`` seconds, whichever comes
first. The GUI calls :meth:`Autosaver.tick` from a timer; nothing here starts threads or timers.

* A saved project ``dir/name.mrm`` autosaves to ``dir/.name.mrm.autosave`` (hidden, beside it).
* An untitled document autosaves to ``<data dir>/autosave/untitled-<pid>-<token>.mrm.autosave``.

On the next start, :func:`find_recovery` (for a project being opened) and :func:`find_orphans` (untitled
documents of processes that are gone) return :class:`Recovery` records; :meth:`Recovery.restore` gives the
recovered document — marked modified, since its edits are in no saved file — and :meth:`Recovery.discard`
deletes the side file. Saving the project or undoing back to its saved state removes the side file.
"""

from __future__ import annotations

import contextlib
import os
import secrets
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

from mrm.document import Changes, Document
from mrm.io.project import dumps, read_project

SUFFIX = ".autosave"


def default_directory() -> Path:
    """Where untitled documents autosave: the user's data directory for MR Modeler."""
    if sys.platform == "win32":
        base = Path(os.environ.get("LOCALAPPDATA", Path.home() / "AppData" / "Local"))
    elif sys.platform == "darwin":
        base = Path.home() / "Library" / "Application Support"
    else:
        base = Path(os.environ.get("XDG_DATA_HOME", Path.home() / ".local" / "share"))
    return base / "mr-modeler" / "autosave"


def side_file(project: Path) -> Path:
    """The autosave side file of a saved project."""
    return project.with_name(f".{project.name}{SUFFIX}")


@dataclass(frozen=True)
class Recovery:
    """An autosave side file found on start-up.

    Attributes
    ----------
    path : Path
        The side file.
    project : Path or None
        The project it belongs to (None for an untitled document).
    saved_at : str
        When it was written (ISO 8601, UTC).
    """

    path: Path
    project: Path | None
    saved_at: str

    def restore(self) -> Document:
        """Load the autosaved document: its path is the original project's, and it is marked modified.

        Raises :class:`~mrm.errors.FileFormatError` if the side file is damaged (offer :meth:`discard`).
        """
        return read_project(self.path).to_document(self.project, clean=False)

    def discard(self) -> None:
        """Delete the side file."""
        with contextlib.suppress(FileNotFoundError):
            self.path.unlink()


def _record(path: Path) -> Recovery | None:
    try:
        proj = read_project(path)
    except Exception:  # a damaged side file is still offered, so the user can choose to discard it
        return Recovery(path, None, "")
    info = proj.autosave or {}
    project = info.get("project")
    return Recovery(path, Path(project) if project else None, str(info.get("saved_at", "")))


def find_recovery(project: str | os.PathLike[str]) -> Recovery | None:
    """The autosave of ``project`` if it is newer than the project file (else None).

    A side file older than the project is left over from before a later save, so it is ignored.
    """
    p = Path(project)
    side = side_file(p)
    try:
        side_mtime = side.stat().st_mtime
    except FileNotFoundError:
        return None
    with contextlib.suppress(FileNotFoundError):
        if p.stat().st_mtime > side_mtime:
            return None
    rec = _record(side)
    return None if rec is None else Recovery(rec.path, p, rec.saved_at)


def _pid_alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    if sys.platform == "win32":  # os.kill(pid, 0) would terminate the process on Windows
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def find_orphans(directory: str | os.PathLike[str] | None = None) -> list[Recovery]:
    """Autosaves of untitled documents whose process is no longer running, newest first."""
    d = Path(directory) if directory is not None else default_directory()
    if not d.is_dir():
        return []
    found: list[tuple[float, Recovery]] = []
    for f in d.glob(f"untitled-*.mrm{SUFFIX}"):
        parts = f.name.split("-")
        pid = int(parts[1]) if len(parts) > 2 and parts[1].isdigit() else -1
        if pid >= 0 and _pid_alive(pid):
            continue
        rec = _record(f)
        if rec is not None:
            with contextlib.suppress(FileNotFoundError):
                found.append((f.stat().st_mtime, rec))
    return [r for _, r in sorted(found, key=lambda t: -t[0])]


class Autosaver:
    """Write a document's autosave side file at an interval and after a number of edits.

    Parameters
    ----------
    doc : Document
        The document to watch.
    interval : float
        Seconds after which pending edits are autosaved.
    every_edits : int
        Number of edits after which they are autosaved without waiting for the interval.
    directory : path, optional
        Where untitled documents autosave (default :func:`default_directory`).
    clock : callable
        Monotonic time source (tests pass a fake one).
    """

    def __init__(
        self,
        doc: Document,
        *,
        interval: float = 120.0,
        every_edits: int = 50,
        directory: str | os.PathLike[str] | None = None,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.doc = doc
        self.interval = float(interval)
        self.every_edits = int(every_edits)
        self.directory = Path(directory) if directory is not None else default_directory()
        self.clock = clock
        self._token = f"untitled-{os.getpid()}-{secrets.token_hex(4)}.mrm{SUFFIX}"
        self.edits = 1 if doc.is_modified else 0  # edits made before the autosaver started count too
        self._since = clock()
        self._written: Path | None = None
        self._unsubscribe = doc.subscribe(self._on_change)

    def _on_change(self, ch: Changes) -> None:
        if ch.inserted or ch.removed or ch.changed or ch.reordered or ch.settings or ch.reset:
            if self.edits == 0:
                self._since = self.clock()
            self.edits += 1

    @property
    def path(self) -> Path:
        """Where the side file of the document currently goes."""
        if self.doc.path is not None:
            return side_file(Path(self.doc.path))
        return self.directory / self._token

    def due(self, now: float | None = None) -> bool:
        """True when unsaved edits should be autosaved now."""
        if not self.doc.is_modified or self.edits == 0:
            return False
        t = self.clock() if now is None else now
        return self.edits >= self.every_edits or t - self._since >= self.interval

    def tick(self, now: float | None = None) -> Path | None:
        """Autosave if due (returns the side file written); drop the side file once the document is clean."""
        if not self.doc.is_modified:
            self.discard()
            self.edits = 0
            return None
        if self.due(now):
            return self.write_now()
        return None

    def write_now(self) -> Path:
        """Write the side file at once (atomically) and reset the counters."""
        from mrm.io.atomic import atomic_write_bytes

        target = self.path
        if self._written is not None and self._written != target:
            self.discard()  # the document was saved under another name
        target.parent.mkdir(parents=True, exist_ok=True)
        record = {
            "project": str(self.doc.path) if self.doc.path is not None else None,
            "saved_at": datetime.now(UTC).isoformat(timespec="seconds"),
        }
        atomic_write_bytes(target, dumps(self.doc, autosave=record))
        self._written = target
        self.edits = 0
        self._since = self.clock()
        return target

    def discard(self) -> None:
        """Delete the side file written by this autosaver, if any (after a save, or on a clean close)."""
        if self._written is not None:
            with contextlib.suppress(FileNotFoundError):
                self._written.unlink()
            self._written = None

    def close(self) -> None:
        """Stop watching the document (the side file stays, for recovery, unless discarded)."""
        self._unsubscribe()
