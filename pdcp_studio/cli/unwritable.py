"""Why a file could not be written, when the writer gave no reason (Qt's ``QImage.save``
returns only False): the same plain words as every command's failed write
(``cli.main.os_error_text``), found by trying the folder without leaving anything there."""

from __future__ import annotations

import errno
import os
import tempfile

from pdcp_studio.cli.main import os_error_text


def why_not_written(path: str | os.PathLike[str]) -> str:
    """``PATH: reason`` — the file asked for, never a temporary one (contracts §2)."""
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
