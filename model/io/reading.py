"""Opening input files: only regular files are read, and never more than a limit (issue 11, ADR 0010).

A FIFO, a character device or a socket named ``x.png`` would block a reader forever or feed it without
end; :func:`open_regular` opens without blocking, checks the kind of file it got (on the descriptor, so no
rename can slip in between) and refuses anything but a regular file with a :class:`FileFormatError`.
"""

from __future__ import annotations

import errno
import os
import stat
from typing import BinaryIO

from mrm.core.errors import FileFormatError

PathLike = str | os.PathLike[str]

_KINDS = (
    (stat.S_ISFIFO, "a named pipe (FIFO)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


def _kind(mode: int) -> str:
    return next((what for test, what in _KINDS if test(mode)), "not a regular file")


def open_regular(path: PathLike, name: str | None = None) -> BinaryIO:
    """Open ``path`` for binary reading if it is a regular file (symbolic links to one are fine).

    Raises
    ------
    FileFormatError
        For a FIFO, device or socket (checked before anything is read, without blocking).
    IsADirectoryError
        For a folder.
    OSError
        As ``open`` does (missing file, permission, …).
    """
    shown = os.fspath(path) if name is None else name
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0)
    flags |= getattr(os, "O_CLOEXEC", 0)
    fd = os.open(path, flags)
    try:
        st = os.fstat(fd)
        if stat.S_ISDIR(st.st_mode):
            raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), shown)
        if not stat.S_ISREG(st.st_mode):
            raise FileFormatError(f"{shown}: is {_kind(st.st_mode)}, not a regular file; only files are read")
        if hasattr(os, "set_blocking"):
            os.set_blocking(fd, True)
        fh = os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise
    return fh


def read_regular(path: PathLike, max_bytes: int, what: str, name: str | None = None) -> bytes:
    """The whole content of a regular file of at most ``max_bytes`` bytes (else FileFormatError)."""
    shown = os.fspath(path) if name is None else name
    with open_regular(path, shown) as fh:
        size = os.fstat(fh.fileno()).st_size
        if size > max_bytes:
            raise FileFormatError(
                f"{shown}: the file is {size:,} bytes, more than the {max_bytes:,} accepted for {what}"
            )
        data = fh.read(max_bytes + 1)
    if len(data) > max_bytes:  # it grew while we read it
        raise FileFormatError(f"{shown}: the file is larger than the {max_bytes:,} bytes accepted for {what}")
    return data


__all__ = ["open_regular", "read_regular"]
