"""Atomic file replacement: a reader sees the old file or the new one, never half of either.

A stored configuration, a system file or the arbitrator's memory must survive a crash or
a full disk in the middle of a save. So the data goes to a temporary file in the *same
directory* (``os.replace`` is only atomic within one file system), is flushed and fsynced,
then renamed over the target; finally the directory is fsynced so the rename itself is
durable (where the platform allows opening a directory — not on Windows). On any failure,
including KeyboardInterrupt, the temporary file is removed and the old file is untouched.

Decisions:
- Errors name the file asked for, never the temporary one: every ``OSError`` is raised again
  as the same kind (``PermissionError``, ``FileNotFoundError``, ENOSPC …) with the target as
  its ``filename``, so "No space left on device: 'capture.asc'" says which file was lost.
- Temporary files are ``.<target name>.<pid>.<8 hex digits>.tmp``. One left behind by a
  killed writer (``kill -9``, power cut) is removed by the next write of the same target when
  it is ours beyond doubt: our name pattern, and its writer process is gone (or it has not been
  touched for ``STALE_TEMP_S``). Another program's files, and a live writer's, are left alone.
- A symlink target is followed: the file it points to is replaced, the link is kept.
- Only a regular file (or a new path) is replaced: a device node (``-o /dev/null``), a FIFO,
  a socket or a folder is refused in words (``NotARegularFile`` / ``IsADirectoryError``), so
  a write as root cannot turn ``/dev/null`` into a file; a symlink loop is refused too.
- An existing file's permission bits are kept; a new file gets the usual ``0o666 & ~umask``.
- Text is written exactly as given (no newline translation), encoded as UTF-8 by default.
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import secrets
import stat
import time
from pathlib import Path

from pdcp_studio.storage.regular_file import refusal

# Temporary names: ".<target name>.<pid>.<8 hex digits>.tmp", hidden on POSIX.
_TEMP_SUFFIX = ".tmp"
_TEMP_ATTEMPTS = 100
_OPEN_FLAGS = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
#: A temporary file untouched this long is stale even if its pid is alive (pid reuse, another
#: host on a shared folder); earlier versions' names (no pid) go stale after this too.
STALE_TEMP_S = 3600.0


def _temp_pattern(name: str) -> re.Pattern[str]:
    """Our temporary files for target ``name``: group 1 is the writer's pid (None: old name)."""
    return re.compile(rf"\.{re.escape(name)}\.(?:(\d+)\.)?[0-9a-f]{{8}}{re.escape(_TEMP_SUFFIX)}")


def _pid_alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError, OverflowError):
        return True  # someone else's live process, or we cannot tell: keep the file
    return True


def remove_stale_temps(target: Path, now: float | None = None) -> list[Path]:
    """Remove temporary files a killed writer left next to ``target``; returns them.

    Only files matching our pattern for this very target, whose writer is gone or which have
    not been touched for ``STALE_TEMP_S``. Never raises: cleaning up is a courtesy.
    """
    now = time.time() if now is None else now
    pattern = _temp_pattern(target.name)
    removed: list[Path] = []
    try:
        entries = list(os.scandir(target.parent))
    except OSError:
        return removed
    for entry in entries:
        match = pattern.fullmatch(entry.name)
        if match is None:
            continue
        try:
            info = entry.stat(follow_symlinks=False)
            if not stat.S_ISREG(info.st_mode):
                continue
            pid = match.group(1)
            old = now - info.st_mtime > STALE_TEMP_S
            if old or (pid is not None and not _pid_alive(int(pid))):
                os.unlink(entry.path)
                removed.append(Path(entry.path))
        except OSError:
            continue
    return removed


def _open_temp(directory: Path, name: str) -> tuple[int, Path]:
    """Create a fresh temporary file next to the target (O_EXCL, so never someone else's)."""
    for _ in range(_TEMP_ATTEMPTS):
        temp = directory / f".{name}.{os.getpid()}.{secrets.token_hex(4)}{_TEMP_SUFFIX}"
        try:
            return os.open(temp, _OPEN_FLAGS, 0o666), temp
        except FileExistsError:
            continue
    raise FileExistsError(errno.EEXIST, "could not create a temporary file next to it")


def _naming(err: OSError, path: str | os.PathLike[str]) -> OSError:
    """The same kind of error, naming the file asked for (not the temporary file)."""
    if err.errno is None:
        return err
    return OSError(err.errno, err.strerror or os.strerror(err.errno), os.fspath(path))


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
    """Replace ``path`` with ``data`` atomically and durably (see the module docstring).

    An OSError names ``path`` as given, whatever step failed; the previous file is untouched.
    """
    target = Path(os.path.realpath(path))
    try:
        mode: int | None = os.stat(target).st_mode
    except FileNotFoundError:
        mode = None  # a new file (or a link to one not made yet)
    except OSError as err:  # a symlink loop, a folder we may not look into
        raise _naming(err, path) from None
    if mode is not None and not stat.S_ISREG(mode):
        # A folder (else the error would name the temporary file), a device node such as
        # /dev/null, a FIFO, a socket: never replaced by a regular file.
        raise refusal(path, mode, "replace")
    directory = target.parent
    remove_stale_temps(target)
    try:
        fd, temp = _open_temp(directory, target.name)
    except OSError as err:
        raise _naming(err, path) from None
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        with contextlib.suppress(FileNotFoundError):
            os.chmod(temp, stat.S_IMODE(os.stat(target).st_mode))
        os.replace(temp, target)
    except BaseException as err:
        with contextlib.suppress(OSError):
            os.unlink(temp)
        if isinstance(err, OSError):
            raise _naming(err, path) from None
        raise
    _fsync_directory(directory)


def atomic_write_text(
    path: str | os.PathLike[str], text: str, encoding: str = "utf-8"
) -> None:
    """Replace ``path`` with ``text`` atomically; no newline translation happens."""
    atomic_write_bytes(path, text.encode(encoding))
