"""Reading a capture: python-can's readers for every log format it knows (ASC, CSV,
candump .log, TRC, SQLite .db, gzipped ones too), the monitor's own reader for BLF
(``blf.py``), and the errors that name the file.

python-can is imported inside the functions only, so importing this module is cheap.
"""

from __future__ import annotations

from collections.abc import Callable, Generator, Iterator
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


def _checked_capture(path: str | Path) -> Path:
    """``path`` if it may be a capture; CaptureError naming it if not."""
    path = Path(path)
    if path.is_dir():
        raise CaptureError(path, "is a folder, not a capture file")
    if not path.is_file():
        raise CaptureError(path, "no such file")
    if path.name.endswith(PARTIAL_SUFFIX):
        raise CaptureError(path, "an interrupted capture (never completed, it may end "
                           "anywhere); rename it to read what it holds")
    return path


def _unreadable(path: Path, err: Exception) -> CaptureError:
    reason = str(err) or type(err).__name__
    return CaptureError(path, f"not a readable capture ({reason})")


def read_capture(path: str | Path, *, plain_frames: bool = False) -> Iterator[Any]:
    """The ``can.Message`` frames of a capture; CaptureError (naming the file) if unreadable.

    ``plain_frames``: a BLF capture's classical 11-bit data frames may come as
    ``blf.PlainFrame`` (the same attributes, ``to_message()`` for the message itself),
    read in a third of the time.
    """
    import can

    if plain_frames and _fast_blf(path):
        for batch in _blf_batches(path):
            yield from batch
        return
    path = _checked_capture(path)
    # ASC stores times relative to its header; ask for absolute ones like the other formats.
    kwargs = {"relative_timestamp": False} if ".asc" in path.suffixes[-2:] else {}
    try:
        with can.LogReader(str(path), **kwargs) as reader:
            yield from reader
    except CaptureError:
        raise
    except Exception as err:  # readers raise anything from struct.error to sqlite3 errors
        raise _unreadable(path, err) from err


def _fast_blf(path: str | Path) -> bool:
    """Whether ``path`` is a BLF capture the monitor's own reader reads."""
    if Path(path).suffix.lower() != ".blf":
        return False
    from pdcp_studio.bus.trace.blf import COMPATIBLE

    return COMPATIBLE


def _blf_batches(path: str | Path) -> Generator[list[Any], None, None]:
    """A BLF capture's frames (``PlainFrame`` or ``can.Message``), a list per container."""
    from pdcp_studio.bus.trace.blf import FastBLFReader

    path = _checked_capture(path)
    try:
        with FastBLFReader(path) as reader:
            yield from reader.batches()
    except Exception as err:
        raise _unreadable(path, err) from err


def open_capture(path: str | Path, *,
                 plain_frames: bool = False) -> tuple[Iterator[Any], Callable[[], None]]:
    """``read_capture``'s frames and how to close the capture early. A BLF capture read
    with ``plain_frames`` comes a container at a time, flattened in C: nothing of ours is
    resumed per frame between the reader and the loop that takes them."""
    import itertools

    if plain_frames and _fast_blf(path):
        batches = _blf_batches(path)
        return itertools.chain.from_iterable(batches), batches.close
    frames = read_capture(path)
    return frames, frames.close  # type: ignore[attr-defined]

