"""Writing a capture: python-can's writer for the target's format, a ``.partial`` file put
in place only when complete, rotation by size, and the node map saved beside each file.

python-can is imported inside the functions only, so importing this module is cheap.
"""

from __future__ import annotations

import contextlib
import copy
import os
from pathlib import Path
from typing import Any

from pdcp_studio.bus.trace.files.capture import PARTIAL_SUFFIX, CaptureError, CaptureWriteError
from pdcp_studio.bus.trace.files.nodemap import write_node_map

#: Largest channel number the log formats carry (BLF stores a u16; 255 is plenty for CAN).
MAX_LOG_CHANNEL = 255
#: Frame kinds python-can 4.6's writers cannot keep, by target format: the TRC writer drops
#: error, remote and CAN FD frames (a warning in its log, nothing else); the CSV and SQLite
#: writers drop the FD flag (the frame would read back as a classical one, wrongly).
REFUSED_KINDS = {".trc": ("error frames", "remote frames", "CAN FD frames"),
                 ".csv": ("CAN FD frames",), ".db": ("CAN FD frames",)}


def frame_kind(msg: Any) -> str:
    """The kind of ``msg`` as ``REFUSED_KINDS`` names it ("" for a classical data frame)."""
    if msg.is_error_frame:
        return "error frames"
    if msg.is_fd:
        return "CAN FD frames"
    return "remote frames" if msg.is_remote_frame else ""


def _loggable(msg: Any, fallback: str | int | None) -> Any:
    """``msg`` with a channel every log format can store.

    python-can's writers turn a channel name into a number by its trailing digits, so a
    virtual channel such as ``pdcp-sim-8a81c7c786c490cb46c66be45734036`` becomes a number no
    BLF record can hold. Such channels are written as ``fallback`` instead (a copy: the
    frame is shared with other listeners).
    """
    from can.util import channel2int

    to_message = getattr(msg, "to_message", None)
    if to_message is not None:  # a BLF frame read without its can.Message
        msg = to_message()
    channel = msg.channel
    if channel is None or (isinstance(channel, int) and 0 <= channel <= MAX_LOG_CHANNEL):
        return msg
    number = channel2int(channel) if isinstance(channel, str) else None
    if number is not None and 0 <= number <= MAX_LOG_CHANNEL:
        return msg
    safe = copy.copy(msg)
    safe.channel = fallback
    return safe


def _writer_for(target: Path, file: Path) -> Any:
    """python-can's writer for ``target``'s format, writing to ``file`` (another name)."""
    import gzip

    from can.io.generic import BinaryIOMessageWriter
    from can.io.logger import _get_logger_for_suffix, _update_writer_plugins

    _update_writer_plugins()
    suffixes = [x.lower() for x in target.suffixes]
    if suffixes[-1:] == [".gz"]:
        real = suffixes[-2] if len(suffixes) >= 2 else ""
        if real in (".blf", ".db"):
            raise ValueError(f"the file type {real} is incompatible with gzip")
        cls = _get_logger_for_suffix(real)
        binary = issubclass(cls, BinaryIOMessageWriter)
        return cls(file=gzip.open(file, "wb" if binary else "wt"))  # type: ignore[arg-type]
    return _get_logger_for_suffix(suffixes[-1] if suffixes else "")(file=str(file))


def _fsync(path: Path) -> None:
    with contextlib.suppress(OSError):
        fd = os.open(path, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


class Recorder:
    """Writes frames to a capture; the format comes from the target's suffix (python-can).

    The frames go to ``<target>.partial`` and the target is replaced only when the capture
    is complete and closed (``close()``, or leaving the ``with`` block without an error):
    a capture that is killed, or fails on a full disk, leaves the previous target as it
    was and the partial one clearly named. Errors name the target. With ``rotate_bytes``
    the capture rotates as python-can's ``SizedRotatingLogger`` does (each finished part
    renamed with a timestamp and count). ``node_map`` (a callable returning the decoder's
    ``node_map()``) is saved beside every finished file, so a replay decodes it as it was.
    """

    def __init__(self, path: str | Path, channel: str | int | None = None, *,
                 rotate_bytes: int = 0, node_map: Any = None) -> None:
        self.path, self.channel, self.frames = Path(path), channel, 0
        self.partial = Path(str(self.path) + PARTIAL_SUFFIX)
        self.rotate_bytes, self.node_map = rotate_bytes, node_map
        self.parts: list[Path] = []  # finished rotated parts
        self._closed = False
        suffixes = [x.lower() for x in self.path.suffixes if x.lower() != ".gz"]
        #: Kinds this format cannot hold, and the frames of each not written.
        self.format = suffixes[-1] if suffixes else ""
        self.refused: tuple[str, ...] = REFUSED_KINDS.get(self.format, ())
        self.skipped: dict[str, int] = {}
        if self.path.is_dir():  # a failed write (exit 1), as for every file a command writes
            raise CaptureWriteError(self.path, "is a folder, not a capture file")
        try:
            self._writer = _writer_for(self.path, self.partial)
        except (ValueError, ImportError, NotImplementedError) as err:
            raise CaptureError(self.path, f"cannot write this capture: {err}") from err
        except OSError as err:
            raise CaptureWriteError(self.path, f"cannot write: {err.strerror or err}") from err
        if rotate_bytes and not callable(getattr(self._writer, "file_size", None)):
            self.abandon()
            with contextlib.suppress(OSError):
                self.partial.unlink()
            raise CaptureError(self.path, "this format cannot rotate (.asc, .blf, .csv, .log "
                               "and .trc can)")

    def write_message(self, msg: Any) -> None:
        if self.refused and (msg.is_error_frame or msg.is_remote_frame or msg.is_fd):
            kind = frame_kind(msg)
            if kind in self.refused:
                self.skipped[kind] = self.skipped.get(kind, 0) + 1
                return
        try:
            self._writer.on_message_received(_loggable(msg, self.channel))
            self.frames += 1
            if self.rotate_bytes and self.frames % 256 == 0:
                size = self._writer.file_size()
                if size is not None and size >= self.rotate_bytes:
                    self._rotate()
        except OSError as err:
            self._fail(err)

    def write(self, arbitration_id: int, data: bytes, timestamp: float | None = None) -> None:
        import time

        import can

        self.write_message(can.Message(
            timestamp=time.time() if timestamp is None else timestamp,
            arbitration_id=arbitration_id, data=bytes(data), is_extended_id=False,
            channel=self.channel))

    def not_written(self) -> str | None:
        """What was not written and why, in words (None: every frame was)."""
        if not self.skipped:
            return None
        total = sum(self.skipped.values())
        kinds = ", ".join(f"{n:,} {kind}" for kind, n in self.skipped.items())
        fmt = self.format.lstrip(".").upper()
        return (f"{total:,} of {total + self.frames:,} frames not written: python-can's "
                f"{fmt} writer cannot keep {kinds}")

    def _fail(self, err: OSError) -> None:
        with contextlib.suppress(Exception):
            self._writer.stop()
        self._closed = True
        raise CaptureWriteError(self.path, f"capture not written ({err.strerror or err}); the "
                           f"frames so far are in {self.partial.name}, the previous file is "
                           "unchanged") from err

    def _finish(self, target: Path) -> None:
        """Close the partial file and put it in place as ``target`` (with its node map)."""
        self._writer.stop()
        _fsync(self.partial)
        os.replace(self.partial, target)
        if self.node_map is not None:
            write_node_map(target, self.node_map())

    def _rotate(self) -> None:
        from datetime import datetime

        stem = self.path.name.split(".")[0]
        suffix = "".join(self.path.suffixes[-2:]) if self.path.suffix == ".gz" \
            else self.path.suffix
        part = self.path.with_name(
            f"{stem}_{datetime.now():%Y-%m-%dT%H%M%S}_#{len(self.parts) + 1:03}{suffix}")
        self._finish(part)
        self.parts.append(part)
        self._writer = _writer_for(self.path, self.partial)

    def close(self) -> None:
        if self._closed:
            return
        self._closed = True
        try:
            self._finish(self.path)
        except OSError as err:
            raise CaptureWriteError(self.path, f"capture not written ({err.strerror or err}); the "
                               f"frames are in {self.partial.name}, the previous file is "
                               "unchanged") from err

    def abandon(self) -> None:
        """Stop without replacing the target: the frames stay in the ``.partial`` file."""
        if not self._closed:
            self._closed = True
            with contextlib.suppress(Exception):
                self._writer.stop()

    def __enter__(self) -> Recorder:
        return self

    def __exit__(self, exc_type: object, *exc: object) -> None:
        if exc_type is None or exc_type in (KeyboardInterrupt, GeneratorExit):
            self.close()
        else:
            self.abandon()

