"""Atomic file replacement: a reader sees the old file or the new one, never half of either.

A stored configuration, a system file or the arbitrator's memory must survive a crash or
a full disk in the middle of a save. So the data goes to a temporary file in the *same
directory* (``os.replace`` is only atomic within one file system), is flushed and fsynced,
then renamed over the target; finally the directory is fsynced so the rename itself is
durable (where the platform allows opening a directory — not on Windows). On any failure,
including KeyboardInterrupt, the temporary file is removed and the old file is untouched.

Decisions:
- A symlink target is followed: the file it points to is replaced, the link is kept.
- An existing file's permission bits are kept; a new file gets the usual ``0o666 & ~umask``.
- Text is written exactly as given (no newline translation), encoded as UTF-8 by default.
"""

from __future__ import annotations

import contextlib
import errno
import os
import secrets
import stat
from pathlib import Path

# Temporary names: ".<target name>.<8 hex digits>.tmp", hidden on POSIX.
_TEMP_SUFFIX = ".tmp"
_TEMP_ATTEMPTS = 100
_OPEN_FLAGS = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)


def _open_temp(directory: Path, name: str) -> tuple[int, Path]:
    """Create a fresh temporary file next to the target (O_EXCL, so never someone else's)."""
    for _ in range(_TEMP_ATTEMPTS):
        temp = directory / f".{name}.{secrets.token_hex(4)}{_TEMP_SUFFIX}"
        try:
            return os.open(temp, _OPEN_FLAGS, 0o666), temp
        except FileExistsError:
            continue
    raise FileExistsError(f"could not create a temporary file in {directory}")


def _fsync_directory(directory: Path) -> None:
    """Make the rename durable; silently skipped where directories cannot be opened."""
    try:
        fd = os.open(directory, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        with contextlib.suppress(OSError):
            os.fsync(fd)
    finally:
        os.close(fd)


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> None:
    """Replace ``path`` with ``data`` atomically and durably (see the module docstring)."""
    target = Path(os.path.realpath(path))
    if target.is_dir():  # else the error would name the temporary file, not the target
        raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), os.fspath(path))
    directory = target.parent
    fd, temp = _open_temp(directory, target.name)
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        with contextlib.suppress(FileNotFoundError):
            os.chmod(temp, stat.S_IMODE(os.stat(target).st_mode))
        os.replace(temp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temp)
        raise
    _fsync_directory(directory)


def atomic_write_text(
    path: str | os.PathLike[str], text: str, encoding: str = "utf-8"
) -> None:
    """Replace ``path`` with ``text`` atomically; no newline translation happens."""
    atomic_write_bytes(path, text.encode(encoding))
