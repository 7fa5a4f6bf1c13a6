"""One reader for every capture, the CLI's and the app's: the format told by the content
(magic bytes, header lines), never by the extension; python-can's readers where they serve;
damage read up to the cut and said; bounded memory whatever the input.

``CaptureReader(path, cancel=None)`` opens a capture (a file, a FIFO read as a stream,
gzipped or not) and iterates its frames (``can.Message``; BLF's classical 11-bit data frames as
``blf.PlainFrame`` when ``plain_frames``). It never raises once it has started yielding:
damage after the first frame ends the iteration, sets ``truncated`` and says where in
``damage`` ("FILE: line N: …" for text formats, "FILE: offset N: …" for binary ones). What
cannot be read at all (no known format, damage before any frame, a missing extra) raises
``CaptureError`` with the same words. An empty file (or a capture with no frame) has the
format ``empty``.

``cancel`` (an event, the app's Stop button) makes the next read of the file raise
``ReadCancelled``; text is then read in smaller chunks, so a Stop is heard within ~0.1 s.

Bounds: text is read a chunk at a time, a line longer than ``MAX_LINE`` (no capture format
writes one) is damage; a BLF object larger than ``MAX_OBJECT`` is damage; so a 2 GB file
without newlines, or of NUL bytes, is refused after its first bytes. Text is UTF-8, and a
line that is not (a comment written by a Windows tool) is read as cp1252.

python-can is imported inside the functions only.
"""

from __future__ import annotations

import itertools
import os
import re
import stat
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import IO, Any, Protocol

from pdcp_studio.bus.trace.files.capture import PARTIAL_SUFFIX, CaptureError

#: Bytes read to tell the format.
SNIFF_BYTES = 1 << 16
#: Text is read this much at a time.
CHUNK_BYTES = 1 << 20
#: … and this much when the caller may cancel: a chunk of short lines (comments, blank
#: lines) takes python-can ~5 µs a line, so a Stop is seen within ~0.1 s.
CANCELLABLE_CHUNK_BYTES = 1 << 16
#: No line of a capture is longer (an ASC CAN FD frame with 64 bytes is about 300).
MAX_LINE = 1 << 16
#: No BLF object is larger (python-can and Vector write containers of about 128 KiB).
MAX_OBJECT = 1 << 24
#: Formats by content (``FORMATS[name]`` is what the messages call it).
FORMATS = {"asc": "Vector ASC", "blf": "Vector BLF", "trc": "PEAK TRC", "csv": "python-can CSV",
           "log": "candump log", "db": "python-can SQLite", "mf4": "ASAM MDF4",
           "empty": "empty"}
_GZIP = b"\x1f\x8b"
_TEXT_FORMATS = ("asc", "trc", "csv", "log")


def sniff(head: bytes) -> str | None:
    """The capture format of a file starting with ``head``; None when it is none we read
    (``empty`` for no bytes at all)."""
    if not head.strip(b" \t\r\n"):
        return "empty"
    if head.startswith(b"LOGG"):
        return "blf"
    if head.startswith(b"SQLite format 3\x00"):
        return "db"
    if head.startswith((b"MDF     ", b"UnFinMF ")):
        return "mf4"
    if b"\x00" in head[:4096]:
        return None  # text captures hold no NUL byte
    text = head.decode("latin-1")
    for raw in text.splitlines()[:50]:
        line = raw.strip()
        if not line:
            continue
        low = line.lower()
        if low.startswith(";"):
            return "trc"
        if low.startswith(("date ", "base ", "begin triggerblock", "internal events logged",
                           "// version", "no internal events logged")):
            return "asc"
        if low.startswith("timestamp,arbitration_id"):
            return "csv"
        if low.startswith("(") and ")" in low and "#" in low:
            return "log"
        if low.startswith("//"):
            continue  # an ASC comment before its header
        return None
    return None


class _Stream:
    """A binary stream: the bytes already read to sniff it, then the rest of ``raw``.

    ``read(n)`` refuses an ``n`` above ``limit`` and fails on a short read of an object
    (``strict``): where a capture declares more than the file holds, it was cut."""

    def __init__(self, head: bytes, raw: Any, limit: int = MAX_OBJECT) -> None:
        self._head, self._raw, self.limit = head, raw, limit
        self.offset = 0  # bytes handed out
        self.strict = False
        self._cut = False  # the gzip stream ended early while its head was read

    def read(self, n: int = -1) -> bytes:
        if n is None or n < 0:
            n = self.limit + 1
        if n > self.limit:
            raise _Damage(self.offset, f"an object of {n:,} bytes (larger than any valid one: "
                          "damaged?)")
        head = self._head
        if head:
            part, self._head = head[:n], head[n:]
            if len(part) < n:
                try:
                    part += self._read_raw(n - len(part))
                except _Damage:
                    self._cut = True  # what was read first comes now, the cut next
        else:
            part = self._read_raw(n)
        if self.strict and 0 < len(part) < n and n >= 4:
            raise _Damage(self.offset + len(part), f"the file ends inside an object of "
                          f"{n:,} bytes (cut short)")
        self.offset += len(part)
        return part

    def _read_raw(self, n: int) -> bytes:
        if self._cut:
            raise _Damage(self.offset, "the gzip stream ends early (cut short)")
        try:
            return bytes(self._raw.read(n))
        except EOFError:
            raise _Damage(self.offset, "the gzip stream ends early (cut short)") from None

    def tell(self) -> int:
        return self.offset

    @property
    def closed(self) -> bool:
        return bool(getattr(self._raw, "closed", False))

    def close(self) -> None:
        self._raw.close()


class ReadCancelled(BaseException):
    """The caller's ``cancel`` was set while the capture was read (a BaseException, as
    KeyboardInterrupt: python-can's readers turn any ``Exception`` into damage)."""


class _Event(Protocol):
    def is_set(self) -> bool: ...


class _Cancellable:
    """A file whose every read first checks the caller's ``cancel`` (a stop button): a
    capture of a few frames among gigabytes of other lines stops as soon as it is asked to,
    not at the next frame."""

    def __init__(self, raw: Any, cancel: _Event) -> None:
        self._raw, self._cancel = raw, cancel

    def read(self, n: int = -1) -> bytes:
        if self._cancel.is_set():
            raise ReadCancelled()
        data: bytes = self._raw.read(n)
        return data

    @property
    def closed(self) -> bool:
        return bool(self._raw.closed)

    def close(self) -> None:
        self._raw.close()


class _Damage(Exception):
    """Where a capture is damaged (a line number or a byte offset) and why."""

    def __init__(self, where: int, reason: str, line: bool = False) -> None:
        super().__init__(reason)
        self.where, self.reason, self.line = where, reason, line


def _decode(raw: bytes) -> str:
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        # A line of another encoding (a Windows tool's comment): each line on its own.
        return "\n".join(_decode_line(x) for x in raw.split(b"\n"))


def _decode_line(raw: bytes) -> str:
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        return raw.decode("cp1252", errors="replace")


class _Lines:
    """A text file as python-can's text readers read it (``for line in file``,
    ``readline()``), a chunk at a time, each line numbered (``line``) and bounded."""

    def __init__(self, stream: _Stream, fix: Callable[[str], str] | None = None,
                 chunk: int = CHUNK_BYTES) -> None:
        self._stream, self._fix, self._chunk = stream, fix, chunk
        self.line = 0  # the number of the line handed out last
        self.ended_mid_line = False
        self._lines = self._generate()

    def _generate(self) -> Iterator[str]:
        read = self._stream.read
        rest = b""
        number = 0
        first = True
        while True:
            chunk = read(self._chunk)
            if not chunk:
                break
            block = rest + chunk
            cut = block.rfind(b"\n") + 1
            rest = block[cut:]
            raw_lines = block[:cut - 1].split(b"\n") if cut else []
            long = None
            if raw_lines and max(map(len, raw_lines)) > MAX_LINE:
                long = next(k for k, x in enumerate(raw_lines) if len(x) > MAX_LINE)
                raw_lines = raw_lines[:long]
            elif len(rest) > MAX_LINE:
                long = len(raw_lines)
            if raw_lines:
                lines = _decode(b"\n".join(raw_lines)).split("\n")
                if first and self._fix is not None:
                    lines = [self._fix(x) for x in lines]
                first = False
                for self.line, text in enumerate(lines, number + 1):
                    yield text + "\n"
                number += len(lines)
            if long is not None:  # the lines before it were read
                raise _Damage(number + 1, f"a line longer than {MAX_LINE:,} bytes (no "
                              "capture has one)", line=True)
        if rest:
            self.ended_mid_line = True
            self.line = number + 1
            yield _decode_line(rest)

    def __iter__(self) -> Iterator[str]:
        return self._lines

    def __next__(self) -> str:
        return next(self._lines)

    def readline(self) -> str:
        return next(self._lines, "")

    def close(self) -> None:
        self._stream.close()

    @property
    def closed(self) -> bool:
        return self._stream.closed


def _trc_version_fix(line: str) -> str:
    """TRC 2.2 and 3.0 keep 2.1's columns (``$COLUMNS`` names them): read them as 2.1."""
    if line.startswith(";$FILEVERSION="):
        version = line.split("=", 1)[1].strip()
        if version in ("2.2", "3.0"):
            return ";$FILEVERSION=2.1"
    return line


def _trc_reader(lines: _Lines) -> Any:
    """python-can's TRC reader, with the error frames (``ER``) of versions 2.x kept."""
    import can

    class TRCReader(can.TRCReader):
        def _parse_cols_v2_x(self, cols: tuple[str, ...]) -> Any:
            if cols[self.columns["T"]] == "ER":
                bus = self.columns.get("B")
                return can.Message(
                    timestamp=float(cols[self.columns["O"]]) / 1000 + self._start_time,
                    is_error_frame=True, channel=int(cols[bus]) if bus is not None else 1)
            return super()._parse_cols_v2_x(cols)

    file: Any = lines  # a text file as python-can reads one
    return TRCReader(file)


class CaptureReader:
    """A capture's frames, its format and whether it was read to its end.

    ``format``: a key of ``FORMATS``. ``truncated``: damage ended the reading early;
    ``damage`` says where and why, naming the file. ``frames``: how many were yielded.
    """

    def __init__(self, path: str | Path, *, plain_frames: bool = False,
                 cancel: _Event | None = None) -> None:
        self.path = Path(path)
        self.name = str(path)
        self.truncated = False
        self.damage: str | None = None
        self.frames = 0
        self._plain = plain_frames
        self._closers: list[Callable[[], None]] = []
        self._cancel = cancel
        raw: Any = self._open()
        if cancel is not None:
            raw = _Cancellable(raw, cancel)
        try:
            head = _read_head(raw)
            self.gzipped = head.startswith(_GZIP)
            stream = _Stream(head, raw)
            if self.gzipped:
                import gzip

                fileobj: Any = stream
                inner = gzip.GzipFile(fileobj=fileobj)
                try:
                    head = _read_head(inner)
                except OSError as err:
                    raise CaptureError(self.path, f"not a readable gzip file ({err})") from None
                stream = _Stream(head, inner)
            fmt = sniff(head)
            if fmt is None:
                known = ", ".join(v for k, v in FORMATS.items() if k != "empty")
                raise CaptureError(self.path, "not a readable capture: its content is in "
                                   f"none of the formats PDCP Studio reads ({known})")
            self.format = fmt
            self._stream = stream
            if fmt == "empty":
                self._iter: Iterator[Any] = iter(())
            elif fmt == "blf":  # a container's frames at a time, flattened in C
                self._iter = itertools.chain.from_iterable(self._blf(stream))
            else:
                self._iter = self._frames(stream)
        except BaseException:
            raw.close()
            raise

    # -- opening ----------------------------------------------------------------------------

    def _open(self) -> IO[bytes]:
        path = self.path
        if path.name.endswith(PARTIAL_SUFFIX):
            raise CaptureError(path, "an interrupted capture (never completed, it may end "
                               "anywhere); rename it to read what it holds")
        try:
            mode = os.stat(path).st_mode
        except FileNotFoundError:
            raise CaptureError(path, "no such file") from None
        except OSError as err:
            raise CaptureError(path, f"cannot be read ({err.strerror or err})") from None
        if stat.S_ISDIR(mode):
            raise CaptureError(path, "is a folder, not a capture file")
        self.is_stream = not stat.S_ISREG(mode)
        if self.is_stream and not stat.S_ISFIFO(mode) and not stat.S_ISCHR(mode):
            raise CaptureError(path, "is neither a file nor a pipe")
        try:
            return open(path, "rb")  # closed by close()
        except OSError as err:
            raise CaptureError(path, f"cannot be read ({err.strerror or err})") from None

    def _python_can_reader(self, stream: _Stream) -> tuple[Any, _Lines | None]:
        import can

        fmt = self.format
        if fmt in _TEXT_FORMATS:
            lines = _Lines(stream, _trc_version_fix if fmt == "trc" else None,
                           CHUNK_BYTES if self._cancel is None else CANCELLABLE_CHUNK_BYTES)
            file: Any = lines  # a text file as python-can reads one
            if fmt == "asc":
                from pdcp_studio.bus.trace.files.asc import QuickASCReader

                return QuickASCReader(file, relative_timestamp=False), lines
            if fmt == "trc":
                return _trc_reader(lines), lines
            if fmt == "csv":
                return can.CSVReader(file), lines
            return can.CanutilsLogReader(file), lines
        if self.is_stream or self.gzipped:
            raise CaptureError(self.path, f"a {FORMATS[fmt]} capture cannot be read from a "
                               "pipe or a gzip file (save it as a plain file first)")
        if fmt == "db":
            stream.close()
            return can.SqliteReader(str(self.path)), None
        # mf4
        import importlib.util

        if importlib.util.find_spec("asammdf") is None:
            raise CaptureError(self.path, "an MF4 capture: reading it needs python-can's mf4 "
                               "extra, which is not installed (pip install 'python-can[mf4]')")
        stream.close()
        from can.io.mf4 import MF4Reader

        return MF4Reader(str(self.path)), None

    # -- reading ----------------------------------------------------------------------------

    def _frames(self, stream: _Stream) -> Iterator[Any]:
        reader, lines = self._python_can_reader(stream)
        self._closers.append(reader.stop)
        try:
            if lines is None:
                for msg in reader:
                    self.frames += 1
                    yield msg
                return
            for msg in reader:
                data = msg.data
                if len(data) < (msg.dlc if msg.is_fd else min(msg.dlc, 8)) \
                        and not msg.is_remote_frame and not msg.is_error_frame:
                    raise _Damage(lines.line, f"a frame cut short: DLC {msg.dlc} with "
                                  f"{len(data)} data bytes", line=True)
                self.frames += 1
                yield msg
            if lines.ended_mid_line and self.format == "asc":
                raise _Damage(lines.line, "the file ends in the middle of a line (cut short?)",
                              line=True)
        except _Damage as err:
            if not err.line and lines is not None:  # a gzip stream cut inside a line
                err = _Damage(lines.line + 1, err.reason, line=True)
            self._damaged(err)
        except (EOFError, OSError) as err:  # a gzip stream cut short
            self._damaged(_Damage(lines.line if lines else 0, str(err), line=lines is not None))
        except Exception as err:  # python-can's readers raise anything on bad input
            if lines is None:
                self._damaged(_Damage(stream.offset, str(err) or type(err).__name__))
            elif lines.ended_mid_line:
                self._damaged(_Damage(lines.line, "the file ends in the middle of a line "
                                      "(cut short?)", line=True))
            else:
                self._damaged(_Damage(lines.line, "not a frame python-can's "
                                      f"{FORMATS[self.format]} reader can read "
                                      f"({type(err).__name__}: {err})", line=True))

    def _blf(self, stream: _Stream) -> Iterator[list[Any]]:
        """The frames of a BLF capture, a list per container."""
        import struct
        import zlib

        from pdcp_studio.bus.trace.files.blf import COMPATIBLE, FastBLFReader

        try:
            import can

            file: Any = stream
            reader: Any = FastBLFReader(file) if COMPATIBLE else can.BLFReader(file)
        except Exception as err:
            self._damaged(_Damage(stream.offset, f"no BLF header ({err or type(err).__name__})"))
            return
        self._closers.append(reader.stop)
        stream.strict = True
        try:
            if COMPATIBLE:
                for batch in reader.batches():
                    self.frames += len(batch)
                    if not self._plain:
                        batch = [m.to_message() if hasattr(m, "to_message") else m
                                 for m in batch]
                    yield batch
            else:
                for msg in reader:
                    self.frames += 1
                    yield [msg]
            tail = getattr(reader, "_tail", b"")
            if len(tail) >= 16:
                raise _Damage(stream.offset, "the file ends inside an object (cut short)")
            declared = getattr(reader, "file_size", 0)
            if not self.is_stream and not self.gzipped and declared > stream.offset + 4:
                raise _Damage(stream.offset, f"the file ends at byte {stream.offset:,} of the "
                              f"{declared:,} its header declares (cut short)")
        except _Damage as err:
            self._damaged(err)
        except (can.io.blf.BLFParseError, struct.error, zlib.error, ValueError) as err:
            reason = re.sub(r" \(before byte \d+\)$", "", str(err)) or type(err).__name__
            self._damaged(_Damage(stream.offset, f"damaged ({reason})"))

    def _damaged(self, err: _Damage) -> None:
        where = f"line {err.where}" if err.line else f"offset {err.where}"
        self.damage = f"{self.name}: {where}: {err.reason}"
        if not self.frames:
            raise CaptureError(self.path, f"{where}: {err.reason}")
        self.truncated = True

    @property
    def format_name(self) -> str:
        """The format in words ("Vector ASC", …; "gzipped" said)."""
        return FORMATS[self.format] + (", gzipped" if self.gzipped else "")

    # -- the iterator -------------------------------------------------------------------------

    def __iter__(self) -> Iterator[Any]:
        return self._iter

    def close(self) -> None:
        closer = getattr(self._iter, "close", None)
        if closer is not None:
            closer()
        for stop in self._closers:
            try:
                stop()
            except Exception:  # closing what failed must not fail again
                pass
        try:
            self._stream.close()
        except Exception:
            pass

    def __enter__(self) -> CaptureReader:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _read_head(raw: Any) -> bytes:
    """Up to ``SNIFF_BYTES`` from the start (a pipe may hand them over in pieces; a gzip
    stream cut short gives what it holds, its next read says it was cut)."""
    parts: list[bytes] = []
    size = 0
    while size < SNIFF_BYTES:
        try:
            part = raw.read(min(SNIFF_BYTES - size, 4096))
        except EOFError:
            raw.read = _cut_short
            break
        if not part:
            break
        parts.append(part)
        size += len(part)
    return b"".join(parts)


def _cut_short(n: int = -1) -> bytes:
    """A gzip stream's ``read`` once it was found cut short."""
    raise EOFError("Compressed file ended before the end-of-stream marker was reached")
