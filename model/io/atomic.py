"""Atomic file writes: a file is either left as it was or replaced by the complete new content.

The data goes to a temporary file in the destination's directory (so the final rename never crosses file
systems), is flushed and fsynced, and then ``os.replace``s the destination in one step; the directory is
fsynced too so the rename survives a crash. If anything fails before the rename the temporary file is
removed and the destination is untouched — no half-written file is ever left under the real name.

Several files that only make sense together — a PNG and its world file and ``.prj``, the three parts of a
co-refinement — are one **output set** (:func:`atomic_file_set`, ADR 0049): inside its block every
:func:`atomic_open` writes its temporary file but defers the rename; when the block ends, every member is
renamed into place, or, on any failure, none is and the old set is left as it was.
"""

from __future__ import annotations

import contextlib
import contextvars
import errno
import logging
import os
import re
import secrets
import stat
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, Any

log = logging.getLogger(__name__)

#: Open modes accepted by :func:`atomic_open`.
_MODES = ("wb", "w")


#: Temporary files left by an older version (no pid in the name) are removed once this many seconds old.
_LEGACY_TEMP_AGE = 600.0


def _temp_pattern(target: Path) -> re.Pattern[str]:
    """Our temporary files beside ``target``: ``.name.<pid>-<hex>.tmp`` (``.name.<hex>.tmp`` before)."""
    return re.compile(rf"\.{re.escape(target.name)}\.(?:(\d{{1,10}})-)?[0-9a-f]{{8}}\.tmp")


def _pid_alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    if os.name != "posix":
        return True  # cannot tell: keep the file
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, OSError):
        return True
    return True


def remove_stale_temps(target: Path) -> int:
    """Delete temporary files of our own pattern beside ``target`` whose writer is gone; returns how many.

    A save killed between creating its temporary file and renaming it leaves the file behind (issue 11:
    14 files, 19.5 MB after 80 kills); the next save of the same file removes them. A temporary file of a
    process still running (another window saving the same project) is left alone. Only regular files
    are removed, never what a symbolic link points to.
    """
    pattern = _temp_pattern(target)
    removed = 0
    try:
        entries = list(os.scandir(target.parent))
    except OSError:
        return 0
    now = time.time()
    for entry in entries:
        m = pattern.fullmatch(entry.name)
        if m is None:
            continue
        try:
            st = entry.stat(follow_symlinks=False)
            if not stat.S_ISREG(st.st_mode):
                continue
            if hasattr(os, "getuid") and st.st_uid != os.getuid():
                continue  # someone else's file: not ours to delete
            if m.group(1) is not None:
                if _pid_alive(int(m.group(1))):
                    continue
            elif now - st.st_mtime < _LEGACY_TEMP_AGE:
                continue
            os.unlink(entry.path)
            removed += 1
        except OSError:
            continue
    return removed


def _temp_path(target: Path) -> tuple[Path, int]:
    """Create and open a fresh temporary file beside ``target``; return its path and descriptor."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0)
    flags |= getattr(os, "O_NOFOLLOW", 0)
    for _ in range(100):
        tmp = target.with_name(f".{target.name}.{os.getpid()}-{secrets.token_hex(4)}.tmp")
        try:
            # 0o666 filtered by the umask, like a file created by open(): a new file gets the usual mode.
            return tmp, os.open(tmp, flags, 0o666)
        except FileExistsError:
            continue
    raise FileExistsError(f"cannot create a temporary file beside {target}")


def _fsync_directory(directory: Path) -> None:
    if os.name != "posix":
        return
    with contextlib.suppress(OSError):
        fd = os.open(directory, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


@contextlib.contextmanager
def atomic_open(
    path: str | os.PathLike[str], mode: str = "wb", *, follow_symlinks: bool = True
) -> Iterator[IO[Any]]:
    """Open ``path`` for writing so that it is replaced atomically when the ``with`` block succeeds.

    Parameters
    ----------
    path : str or path-like
        The destination. A symbolic link is followed: its target is replaced, the link stays.
    mode : {"wb", "w"}
        Binary, or text in UTF-8 with Unix line ends.
    follow_symlinks : bool
        False for files this program owns (autosave side files): a symbolic link found at ``path`` is
        replaced by the file itself and what it points to is never written.

    Yields
    ------
    file object
        Write to it inside the block. If the block raises, the destination is left untouched.

    Notes
    -----
    When the destination exists its permission bits are kept.
    """
    if mode not in _MODES:
        raise ValueError(f"atomic_open mode must be one of {_MODES}, got {mode!r}")
    if follow_symlinks:
        target = Path(os.path.realpath(os.fspath(path)))
    else:
        given = Path(os.path.abspath(os.fspath(path)))
        target = Path(os.path.realpath(given.parent)) / given.name
    # Check here so the error names the user's path, not the temporary file.
    if not target.is_symlink() and target.is_dir():
        raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), os.fspath(path))
    if not target.parent.is_dir():
        raise FileNotFoundError(errno.ENOENT, "No such directory", os.fspath(target.parent))
    remove_stale_temps(target)
    tmp, fd = _temp_path(target)
    try:
        with contextlib.suppress(FileNotFoundError):
            st = os.lstat(target)
            if stat.S_ISLNK(st.st_mode):
                raise FileNotFoundError  # a link we replace: a new file gets the usual mode
            mode_bits = st.st_mode & 0o7777
            if hasattr(os, "fchmod"):
                os.fchmod(fd, mode_bits)
        fh: IO[Any] = (
            os.fdopen(fd, mode, encoding="utf-8", newline="\n") if mode == "w" else os.fdopen(fd, mode)
        )
    except BaseException:
        os.close(fd)
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    pending = _CURRENT_SET.get()
    try:
        with fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())
        if pending is not None:
            pending.add(tmp, target)  # renamed with the other members when the set's block ends
            return
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    _fsync_directory(target.parent)


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes, *, follow_symlinks: bool = True) -> None:
    """Write ``data`` to ``path`` atomically (see :func:`atomic_open`)."""
    with atomic_open(path, "wb", follow_symlinks=follow_symlinks) as fh:
        fh.write(data)


def atomic_write_text(path: str | os.PathLike[str], text: str) -> None:
    """Write ``text`` to ``path`` atomically, in UTF-8 (see :func:`atomic_open`)."""
    with atomic_open(path, "w") as fh:
        fh.write(text)


# ---------------------------------------------------------------------------------------------- output sets
@dataclass
class _Member:
    """One file of an output set: its temporary file (None: the file is to be removed) and destination."""

    target: Path
    tmp: Path | None
    backup: Path | None = None
    done: bool = False


@dataclass
class FileSet:
    """The files of an output set being written (see :func:`atomic_file_set`)."""

    members: list[_Member] = field(default_factory=list)

    def add(self, tmp: Path, target: Path) -> None:
        """A member written to ``tmp``, to replace ``target`` when the set is committed."""
        for m in self.members:
            if m.target == target:  # written twice: the later content wins
                if m.tmp is not None:
                    with contextlib.suppress(OSError):
                        os.unlink(m.tmp)
                m.tmp = tmp
                return
        self.members.append(_Member(target, tmp))

    def remove(self, path: str | os.PathLike[str]) -> None:
        """Remove ``path`` (a stale member of the old set, e.g. its ``.prj``) when the set is committed.

        Only a regular file or a symbolic link is removed, and only if the whole set is written.
        """
        target = Path(os.path.abspath(os.fspath(path)))
        if any(m.target == target for m in self.members):
            return
        with contextlib.suppress(OSError):
            if stat.S_ISREG(os.lstat(target).st_mode) or target.is_symlink():
                self.members.append(_Member(target, None))

    def discard(self) -> None:
        """Remove every temporary file written so far (the destinations were never touched)."""
        for m in self.members:
            if m.tmp is not None:
                with contextlib.suppress(OSError):
                    os.unlink(m.tmp)

    def commit(self) -> None:
        """Put every member in place, or none: on a failure the old set is restored and the error raised.

        1. Each existing destination gets a backup (a hard link, else a copy) beside it; a failure here
           touches no destination.
        2. The members are renamed (or removed) in order.
        3. If one of these fails, the members already in place are rolled back from their backups (a new
           file is removed), in reverse order.
        4. The backups are removed.
        """
        try:
            for m in self.members:
                m.backup = _backup(m.target)
        except BaseException:
            self._drop_backups()
            self.discard()
            raise
        try:
            for m in self.members:
                if m.tmp is None:
                    os.unlink(m.target)
                else:
                    os.replace(m.tmp, m.target)
                m.done = True
        except BaseException:
            kept = self._roll_back()
            self.discard()
            if kept:
                log.error("could not restore %s; the previous content is kept in %s", *kept[0])
            raise
        self._drop_backups()
        for d in {m.target.parent for m in self.members}:
            _fsync_directory(d)

    def _roll_back(self) -> list[tuple[Path, Path]]:
        """Undo the members put in place; returns (destination, backup) pairs that could not be restored."""
        kept: list[tuple[Path, Path]] = []
        for m in reversed(self.members):
            if not m.done:
                continue
            try:
                if m.backup is not None:
                    os.replace(m.backup, m.target)
                    m.backup = None
                else:
                    os.unlink(m.target)  # a new file of the set: the old set did not have it
            except OSError:
                if m.backup is not None:
                    kept.append((m.target, m.backup))
                    m.backup = None  # left in place: the only copy of the old content
        self._drop_backups()
        return kept

    def _drop_backups(self) -> None:
        for m in self.members:
            if m.backup is not None:
                with contextlib.suppress(OSError):
                    os.unlink(m.backup)
                m.backup = None


def _backup(target: Path) -> Path | None:
    """A second name for ``target``'s current content (None when there is no file): a hard link, else a copy.

    The name is one of our temporary names, so a backup left by a process that died is cleaned up by
    :func:`remove_stale_temps` like any temporary file.
    """
    try:
        st = os.lstat(target)
    except FileNotFoundError:
        return None
    for _ in range(100):
        backup = target.with_name(f".{target.name}.{os.getpid()}-{secrets.token_hex(4)}.tmp")
        try:
            os.link(target, backup, follow_symlinks=False)
            return backup
        except FileExistsError:
            continue
        except OSError:
            break  # no hard links here (some network and FAT file systems): copy instead
    if stat.S_ISLNK(st.st_mode):
        backup, fd = _temp_path(target)
        os.close(fd)
        os.unlink(backup)
        os.symlink(os.readlink(target), backup)
        return backup
    backup, fd = _temp_path(target)
    try:
        with os.fdopen(fd, "wb") as out, open(target, "rb") as src:
            while chunk := src.read(1 << 20):
                out.write(chunk)
            out.flush()
            os.fsync(out.fileno())
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(backup)
        raise
    return backup


_CURRENT_SET: contextvars.ContextVar[FileSet | None] = contextvars.ContextVar("_CURRENT_SET", default=None)


@contextlib.contextmanager
def atomic_file_set() -> Iterator[FileSet]:
    """Write several files as one output set: all of them are replaced, or none (ADR 0049).

    Inside the block, every :func:`atomic_open` (and so every writer of :mod:`mrm.io`) writes and fsyncs its
    temporary file but does not rename it; :meth:`FileSet.remove` names stale members to delete. When the
    block ends without an error, :meth:`FileSet.commit` puts them all in place; if the block raises (a full
    disk while writing the third part), every temporary file is removed and the old set stays byte for byte.

    Yields
    ------
    FileSet
        The set being written. A set opened inside another one joins it.

    Examples
    --------
    >>> with atomic_file_set():  # doctest: +SKIP
    ...     write_pixels(ps, "out.png")
    ...     write_world_file("out.png", georef)
    """
    outer = _CURRENT_SET.get()
    if outer is not None:
        yield outer
        return
    fs = FileSet()
    token = _CURRENT_SET.set(fs)
    try:
        yield fs
    except BaseException:
        fs.discard()
        raise
    finally:
        _CURRENT_SET.reset(token)
    fs.commit()
