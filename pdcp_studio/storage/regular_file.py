"""Files that are what they claim: a path read or replaced must be a regular file.

Opening a FIFO for reading waits for a writer that may never come, a terminal or a serial
port can block or change state when opened, and ``/dev/zero`` never ends. So every path
PDCP Studio reads or replaces is checked with ``os.stat`` first, and opened with
``O_NONBLOCK`` (and ``O_NOCTTY``) so that a path swapped for a FIFO between the check and
the open cannot hang the reader either; the opened descriptor is checked again with
``fstat``. Standard input is asked for by name (``-``), never through ``/dev/stdin``.

The refusal is :class:`NotARegularFile`, an ``OSError`` naming the file, whose text says
what the path is ("a FIFO (named pipe), not a regular file"): every reader already turns an
``OSError`` into "FILE: cannot read: …" and every writer into "FILE: …".
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
from typing import BinaryIO

# Not on Windows, where neither FIFOs nor device paths open like this.
_NONBLOCK = getattr(os, "O_NONBLOCK", 0)
_NOCTTY = getattr(os, "O_NOCTTY", 0)
_BINARY = getattr(os, "O_BINARY", 0)


class NotARegularFile(OSError):
    """A path that is a FIFO, a device or a socket where a regular file is needed."""


def kind(mode: int) -> str:
    """What a file of this ``st_mode`` is, in words ("a FIFO (named pipe)")."""
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISCHR(mode):
        return "a character device"
    if stat.S_ISBLK(mode):
        return "a block device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    if stat.S_ISDIR(mode):
        return "a folder"
    return "not a regular file"


def refusal(path: str | os.PathLike[str], mode: int, doing: str = "read") -> OSError:
    """The error for ``path`` of ``mode`` (a folder stays IsADirectoryError)."""
    name = os.fspath(path)
    if stat.S_ISDIR(mode):
        return IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), name)
    if doing == "read":
        hint = " (give - for standard input)" if stat.S_ISFIFO(mode) else ""
    else:
        hint = f"; refused to {doing} it"
    return NotARegularFile(errno.EINVAL, f"is {kind(mode)}, not a regular file{hint}", name)


def check_regular(path: str | os.PathLike[str], doing: str = "read") -> None:
    """Raise the refusal unless ``path`` (symlinks followed) is a regular file.

    A path that does not exist raises FileNotFoundError, as ``open`` would.
    """
    mode = os.stat(path).st_mode
    if not stat.S_ISREG(mode):
        raise refusal(path, mode, doing)


def open_regular_fd(path: str | os.PathLike[str]) -> int:
    """A read-only descriptor of the regular file ``path``; never blocks on a FIFO."""
    check_regular(path)
    fd = os.open(path, os.O_RDONLY | _NONBLOCK | _NOCTTY | _BINARY)
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):  # swapped between the check and the open
            raise refusal(path, mode)
        if _NONBLOCK:
            import fcntl

            with contextlib.suppress(OSError):
                fcntl.fcntl(fd, fcntl.F_SETFL, fcntl.fcntl(fd, fcntl.F_GETFL) & ~_NONBLOCK)
    except BaseException:
        os.close(fd)
        raise
    return fd


def open_regular(path: str | os.PathLike[str]) -> BinaryIO:
    """``open(path, "rb")`` for a regular file only (see the module docstring)."""
    return os.fdopen(open_regular_fd(path), "rb")
