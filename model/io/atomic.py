"""Atomic file writes: a file is either left as it was or replaced by the complete new content.

The data goes to a temporary file in the destination's directory (so the final rename never crosses file
systems), is flushed and fsynced, and then ``os.replace``s the destination in one step; the directory is
fsynced too so the rename survives a crash. If anything fails before the rename the temporary file is
removed and the destination is untouched — no half-written file is ever left under the real name.
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import secrets
import stat
import time
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

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
    try:
        with fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())
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
