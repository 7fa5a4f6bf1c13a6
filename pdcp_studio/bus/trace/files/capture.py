"""Reading a capture (``reader.py`` tells the format by content and reads it), and the
errors that name the file.

python-can is imported inside the functions only, so importing this module is cheap.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from pdcp_studio.errors import PdcpError

#: Capture formats python-can 4.6 both writes and reads without extra packages (``.gz`` too).
CAPTURE_SUFFIXES = (".asc", ".blf", ".csv", ".log", ".trc", ".db")
#: A capture being written (or interrupted) is named ``<capture>`` + this suffix.
PARTIAL_SUFFIX = ".partial"


class CaptureError(PdcpError):
    """A capture file cannot be read or written; names the file and why."""

    def __init__(self, path: str | Path, reason: str) -> None:
        self.path, self.reason = str(path), reason
        super().__init__(f"{path}: {reason}")


class CaptureWriteError(CaptureError):
    """A capture could not be written (full disk, …): a failure (exit 1), not bad input."""


def read_capture(path: str | Path, *, plain_frames: bool = False) -> Iterator[Any]:
    """The frames of a capture, read by its content (``reader.CaptureReader``); a capture
    damaged after its first frames gives them and then raises CaptureError saying where.

    ``plain_frames``: a BLF capture's classical 11-bit data frames may come as
    ``blf.PlainFrame`` (the same attributes, ``to_message()`` for the message itself).
    """
    from pdcp_studio.bus.trace.files.reader import CaptureReader

    with CaptureReader(path, plain_frames=plain_frames) as reader:
        yield from reader
        if reader.damage is not None:
            raise CaptureError(path, reader.damage.split(": ", 1)[1])


def open_capture(path: str | Path, *,
                 plain_frames: bool = False) -> tuple[Iterator[Any], Callable[[], None]]:
    """A capture's frames and how to close it early (``CaptureReader`` for its damage)."""
    from pdcp_studio.bus.trace.files.reader import CaptureReader

    reader = CaptureReader(path, plain_frames=plain_frames)
    return iter(reader), reader.close
