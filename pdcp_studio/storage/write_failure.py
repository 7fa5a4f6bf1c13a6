"""A file that could not be written or read, in plain words: the file asked for (never a
temporary one, contracts §2) and why — "the folder X does not exist", not "[Errno 2] …".

``os_error_text`` is what every command prints for an operating-system failure
(``cli.main``); ``why_not_written`` finds the reason where the writer gives none (Qt's
``QImage.save`` returns only False, for ``gui --screenshot``) by trying the folder, leaving
nothing there. Below the app and the CLI so both use the same words.
"""

from __future__ import annotations

import errno
import os
import tempfile


def os_error_text(err: OSError) -> str:
    """An operating-system failure in words that name the file and, for a path that
    cannot exist, the folder that is missing (not "[Errno 2] …")."""
    if not err.filename:
        return str(err)
    name = os.fsdecode(err.filename)
    why = err.strerror or str(err)
    parent = os.path.dirname(os.path.abspath(name))
    if err.errno == errno.ENOENT and not os.path.isdir(parent):
        why = f"the folder {parent} does not exist"
    elif err.errno == errno.ENOTDIR:
        why = "a part of the path is a file, not a folder"
    elif err.errno == errno.EISDIR:
        why = "is a folder, not a file"
    return f"{name}: {why}"


def why_not_written(path: str | os.PathLike[str]) -> str:
    """``PATH: reason`` for a write to ``path`` that failed without saying why."""
    name = os.fspath(path)
    if os.path.isdir(name):
        return os_error_text(IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), name))
    folder = os.path.dirname(os.path.abspath(name))
    try:
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as err:  # the folder is missing, read-only, full …: its reason, our name
        code = err.errno if err.errno is not None else errno.EIO
        return os_error_text(OSError(code, err.strerror or os.strerror(code), name))
    if os.path.exists(name) and not os.access(name, os.W_OK):
        return os_error_text(PermissionError(errno.EACCES, os.strerror(errno.EACCES), name))
    return f"{name}: could not be written there (is the disk full?)"
