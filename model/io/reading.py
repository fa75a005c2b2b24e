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


def describe_content(head: bytes) -> str:
    """A hint of what a file that is not the expected format holds."""
    if head.startswith(b"\x89PNG\r\n\x1a\n"):
        return "it is a PNG"
    if head[:2] in (b"P1", b"P2", b"P3", b"P4", b"P5", b"P6"):
        return "it looks like a Netpbm image"
    if head.startswith(b"PK\x03\x04"):
        return "it is a zip archive"
    if head[:3] == b"\xff\xd8\xff":
        return "it is a JPEG"
    if head.startswith((b"GIF87a", b"GIF89a")):
        return "it is a GIF"
    if head.startswith((b"II*\x00", b"MM\x00*")):
        return "it is a TIFF"
    if not head:
        return "the file is empty"
    try:
        head.decode("utf-8")
    except UnicodeDecodeError:
        return "its content is not recognised"
    return "it is a text file"


__all__ = ["describe_content", "open_regular", "read_regular"]
