"""Autosave to a side file, and recovery on the next start (the model side: write, detect, restore).

While a document has unsaved edits, :class:`Autosaver` writes it — a complete project file with an extra
``"autosave"`` record — to a side file, after ``every_edits`` edits or ``interval`` seconds, whichever comes
first. The GUI calls :meth:`Autosaver.tick` from a timer; nothing here starts threads or timers.

* A saved project ``dir/name.mrm`` autosaves to ``dir/.name.mrm.<pid>-<token>.autosave`` (hidden, beside it).
* An untitled document autosaves to ``<data dir>/autosave/untitled-<pid>-<token>.mrm.autosave``.

Each :class:`Autosaver` — each window, in any process — is one **writer** with a side file of its own
(``<pid>-<token>``, ADR 0049): two windows on one project never overwrite each other's autosave, and a save
removes only the saving window's side file, so the other window's edits stay recoverable (issue 32).

On the next start, :func:`find_recoveries` (for a project being opened) and :func:`find_orphans` (untitled
documents) return a :class:`Recovery` for every side file whose writer is gone — its process has exited,
or, in this process, its autosaver was closed without discarding it; a live writer's side file is never
offered. :meth:`Recovery.restore` gives the recovered document — marked modified, since its edits are in
no saved file — and :meth:`Recovery.discard` deletes the side file. Saving the project or undoing back to
its saved state removes the writer's own side file. The side file of older versions (``.name.mrm.autosave``,
shared by every window) is still found, when it is newer than the project.

What is found on start-up is not trusted (ADR 0015): any file name in the autosave folder is tolerated, an
orphan's recorded project path is only shown, never adopted (the recovered document is untitled, so Save
asks where to write), and side files are written without following a symbolic link planted at their name.
An autosave that fails (disk full, read-only folder) is reported through ``on_error`` and retried; it never
raises out of :meth:`Autosaver.tick`.
"""

from __future__ import annotations

import contextlib
import logging
import os
import re
import secrets
import stat
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

from mrm.document import Changes, Document
from mrm.io.atomic import atomic_write_bytes
from mrm.io.project import dumps, read_project

SUFFIX = ".autosave"
#: Seconds before a failed autosave is tried again.
RETRY_SECONDS = 15.0
#: Untitled side files: ``untitled-<pid>-<token>.mrm.autosave``.
_ORPHAN = re.compile(r"untitled-([0-9]{1,10})-([0-9A-Za-z]{1,64})\.mrm" + re.escape(SUFFIX))
#: The writers (``<pid>-<token>``) of this process whose autosaver is open: their side files are not orphans.
_LIVE_WRITERS: set[str] = set()
#: Largest process id of any system we run on (Linux's pid_max is at most 2^22).
_MAX_PID = 2**31 - 1

log = logging.getLogger(__name__)


def default_directory() -> Path:
    """Where untitled documents autosave: the user's data directory for MR Modeler."""
    if sys.platform == "win32":
        base = Path(os.environ.get("LOCALAPPDATA", Path.home() / "AppData" / "Local"))
    elif sys.platform == "darwin":
        base = Path.home() / "Library" / "Application Support"
    else:
        base = Path(os.environ.get("XDG_DATA_HOME", Path.home() / ".local" / "share"))
    return base / "mr-modeler" / "autosave"


def side_file(project: Path, writer: str | None = None) -> Path:
    """The autosave side file of a saved project written by ``writer`` (``<pid>-<token>``).

    Without ``writer``: the one side file older versions shared between every window (still recovered).
    """
    if writer is None:
        return project.with_name(f".{project.name}{SUFFIX}")
    return project.with_name(f".{project.name}.{writer}{SUFFIX}")


def _side_pattern(project: Path) -> re.Pattern[str]:
    """The per-writer side files of ``project``: ``.name.mrm.<pid>-<token>.autosave``."""
    return re.compile(rf"\.{re.escape(project.name)}\.([0-9]{{1,10}})-([0-9a-f]{{8}}){re.escape(SUFFIX)}")


@dataclass(frozen=True)
class Recovery:
    """An autosave side file found on start-up.

    Attributes
    ----------
    path : Path
        The side file.
    project : Path or None
        The project it belongs to: the project being opened, for the side file beside it; None for an
        orphan (an untitled document), whatever its record says.
    saved_at : str
        When it was written (ISO 8601, UTC).
    recorded : Path or None
        The project path written in the side file's record — shown to the user, never used as the
        recovered document's path (a planted or stale record must not make Save overwrite what it names).
    """

    path: Path
    project: Path | None
    saved_at: str
    recorded: Path | None = None

    def restore(self) -> Document:
        """Load the autosaved document: its path is :attr:`project` (None for an orphan), marked modified.

        Raises :class:`~mrm.core.errors.FileFormatError` if the side file is damaged (offer :meth:`discard`).
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
    recorded = Path(project) if isinstance(project, str) and project else None
    return Recovery(path, None, str(info.get("saved_at", "")), recorded)


def find_recoveries(project: str | os.PathLike[str]) -> list[Recovery]:
    """Every autosave of ``project`` left by a writer that is gone, newest first.

    A per-writer side file exists only while its writer has edits that are in no saved file (its own save
    removes it), so it is offered whatever its age: another window may have saved the project since, with
    other edits. The shared side file of older versions is offered only when newer than the project (older,
    it is left over from before a later save). A side file of a live writer (another window still open) is
    never offered.
    """
    p = Path(project)
    try:
        project_mtime: float | None = p.stat().st_mtime
    except OSError:
        project_mtime = None
    pattern = _side_pattern(p)
    found: list[tuple[float, Recovery]] = []
    try:
        entries = list(os.scandir(p.parent))
    except OSError:
        entries = []
    legacy = side_file(p).name
    for entry in entries:
        try:
            m = pattern.fullmatch(entry.name)
            if m is None and entry.name != legacy:
                continue
            st = entry.stat(follow_symlinks=False)
            if not stat.S_ISREG(st.st_mode):
                continue
            if m is None:
                if project_mtime is not None and project_mtime > st.st_mtime:
                    continue
            elif _writer_alive(int(m.group(1)), m.group(2)):
                continue
            rec = _record(Path(entry.path))
        except Exception as e:  # whatever is beside the project, opening it never fails
            log.warning("skipping %r beside %s: %s", entry.name, p.name, e)
            continue
        if rec is not None:
            found.append((st.st_mtime, Recovery(rec.path, p, rec.saved_at, rec.recorded)))
    return [r for _, r in sorted(found, key=lambda t: -t[0])]


def find_recovery(project: str | os.PathLike[str]) -> Recovery | None:
    """The newest of :func:`find_recoveries` (None when there is none)."""
    found = find_recoveries(project)
    return found[0] if found else None


def _pid_alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    if sys.platform == "win32":  # os.kill(pid, 0) would terminate the process on Windows
        return False
    if not 0 < pid <= _MAX_PID:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    except (OverflowError, ValueError, OSError):
        return False
    return True


def _writer_alive(pid: int, token: str) -> bool:
    """Whether the writer ``<pid>-<token>`` may still be writing: in this process, its autosaver is open."""
    if pid == os.getpid():
        return f"{pid}-{token}" in _LIVE_WRITERS
    return _pid_alive(pid)


def find_orphans(directory: str | os.PathLike[str] | None = None) -> list[Recovery]:
    """Autosaves of untitled documents whose writer is gone (see :func:`find_recoveries`), newest first."""
    d = Path(directory) if directory is not None else default_directory()
    try:
        if not d.is_dir():
            return []
        names = os.listdir(d)
    except OSError:
        return []
    found: list[tuple[float, Recovery]] = []
    for fname in names:
        if not fname.endswith(SUFFIX):
            continue
        # Whatever else is in the folder (junk names, huge "pids", links, folders) is skipped, never fatal.
        try:
            m = _ORPHAN.fullmatch(fname)
            if m is None:
                continue
            f = d / fname
            st = os.lstat(f)
            if not stat.S_ISREG(st.st_mode):
                continue
            if _writer_alive(int(m.group(1)), m.group(2)):
                continue
            rec = _record(f)
        except Exception as e:
            log.warning("skipping %r in the autosave folder: %s", fname, e)
            continue
        if rec is not None:
            found.append((st.st_mtime, rec))
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
    on_error : callable, optional
        ``on_error(message)`` after a failed autosave (the GUI shows it); the write is retried after
        :data:`RETRY_SECONDS`. Failures are logged in any case.
    """

    def __init__(
        self,
        doc: Document,
        *,
        interval: float = 120.0,
        every_edits: int = 50,
        directory: str | os.PathLike[str] | None = None,
        clock: Callable[[], float] = time.monotonic,
        on_error: Callable[[str], None] | None = None,
    ) -> None:
        self.doc = doc
        self.interval = float(interval)
        self.every_edits = int(every_edits)
        self.directory = Path(directory) if directory is not None else default_directory()
        self.clock = clock
        #: This autosaver's writer id, ``<pid>-<token>``: its side files carry it.
        self.writer = f"{os.getpid()}-{secrets.token_hex(4)}"
        _LIVE_WRITERS.add(self.writer)
        self._token = f"untitled-{self.writer}.mrm{SUFFIX}"
        self.edits = 1 if doc.is_modified else 0  # edits made before the autosaver started count too
        self._since = clock()
        self._written: Path | None = None
        self.on_error = on_error
        #: The message of the last failed autosave (None after a success).
        self.last_error: str | None = None
        #: Consecutive failed autosaves.
        self.failures = 0
        self._retry_at: float | None = None
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
            return side_file(Path(self.doc.path), self.writer)
        return self.directory / self._token

    def due(self, now: float | None = None) -> bool:
        """True when unsaved edits should be autosaved now."""
        if not self.doc.is_modified or self.edits == 0:
            return False
        t = self.clock() if now is None else now
        if self._retry_at is not None:
            return t >= self._retry_at
        return self.edits >= self.every_edits or t - self._since >= self.interval

    def tick(self, now: float | None = None) -> Path | None:
        """Autosave if due (returns the side file written); drop the side file once the document is clean.

        Never raises: a failed write is logged, reported to ``on_error`` and retried after
        :data:`RETRY_SECONDS` (the edits stay pending), so crash recovery is never silently switched off.
        """
        if not self.doc.is_modified:
            with contextlib.suppress(OSError):
                self.discard()
            self.edits = 0
            self._retry_at = None
            return None
        if not self.due(now):
            return None
        try:
            return self.write_now()
        except Exception as e:  # every failure, not only OSError: a timer callback must never raise
            self.failures += 1
            self.last_error = _describe(e)
            t = self.clock() if now is None else now
            self._retry_at = t + RETRY_SECONDS
            log.warning("autosave to %s failed (%d in a row): %s", self.path, self.failures, self.last_error)
            if self.on_error is not None:
                try:
                    self.on_error(f"Autosave failed, will retry: {self.last_error}")
                except Exception:
                    log.exception("the autosave error handler failed")
            return None

    def write_now(self) -> Path:
        """Write the side file at once (atomically) and reset the counters."""
        target, write = self.prepare_write()
        write()
        self.written(target, self.edits)
        return target

    def prepare_write(self) -> tuple[Path, Callable[[], None]]:
        """The side file and a callable writing the document as it is now to it.

        The callable holds a snapshot (the objects are immutable values), so it may run on another thread
        while the document changes; report its outcome with :meth:`written` or :meth:`write_failed`.
        """
        from types import SimpleNamespace

        target = self.path
        if self._written is not None and self._written != target:
            self.discard()  # the document was saved under another name
        doc = self.doc
        snap = SimpleNamespace(settings=doc.settings, selection=doc.selection, objects=doc.objects)
        record = {
            "project": str(doc.path) if doc.path is not None else None,
            "saved_at": datetime.now(UTC).isoformat(timespec="seconds"),
        }

        def write() -> None:
            target.parent.mkdir(parents=True, exist_ok=True)
            # Never follow a link planted at the side file's name: it is replaced, its target left alone.
            atomic_write_bytes(target, dumps(snap, autosave=record), follow_symlinks=False)  # type: ignore[arg-type]

        return target, write

    def written(self, target: Path, edits: int) -> None:
        """A write of :meth:`prepare_write` succeeded; ``edits`` were pending when it was prepared."""
        self._written = target
        self.failures = 0
        self.last_error = None
        self._retry_at = None
        self.edits = max(0, self.edits - edits)  # edits made while it was written stay pending
        self._since = self.clock()

    def write_failed(self, e: BaseException) -> None:
        """A write of :meth:`prepare_write` failed: reported to ``on_error`` and retried later."""
        self.failures += 1
        self.last_error = _describe(e)
        self._retry_at = self.clock() + RETRY_SECONDS
        log.warning("autosave to %s failed (%d in a row): %s", self.path, self.failures, self.last_error)
        if self.on_error is not None:
            try:
                self.on_error(f"Autosave failed, will retry: {self.last_error}")
            except Exception:
                log.exception("the autosave error handler failed")

    def discard(self) -> None:
        """Delete the side file written by this autosaver, if any (after a save, or on a clean close)."""
        if self._written is not None:
            with contextlib.suppress(FileNotFoundError):
                self._written.unlink()
            self._written = None

    def close(self) -> None:
        """Stop watching the document (the side file stays, for recovery, unless discarded).

        From now on the side file is an orphan: a window opening the project (or started later) offers it.
        """
        self._unsubscribe()
        _LIVE_WRITERS.discard(self.writer)


def _describe(e: BaseException) -> str:
    if isinstance(e, OSError):
        where = getattr(e, "filename", None)
        return f"{where}: {e.strerror or e}" if where else str(e.strerror or e)
    return str(e) or type(e).__name__
