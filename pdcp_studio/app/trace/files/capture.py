"""Reading a capture into a ``FrameStore`` and writing a store back out, off the GUI thread.

``load_capture(store, stats, path, progress, cancel)`` decodes any capture the one reader
reads (``bus.trace.files.replay``: the format by content, the capture's own node map — saved
beside it or learned from its traffic — and its verdict) into the store's column chunks: a
small first chunk so the first rows show at once, then chunks of ``CHUNK_ROWS``; it returns
a ``CaptureVerdict``. It reports ``progress(frames, permille, "")`` — the
permille from the reader's position in the file where the platform tells it (Linux), else 0
— and stops at its next read of the file once ``cancel`` is set. ``save_store`` writes a
store as a python-can capture (by extension) or as decoded text (``.txt``).

Qt-free: it runs on a worker and is tested directly.
"""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pdcp_studio.app.trace.store import (
    CHUNK_ROWS,
    F_ERROR,
    F_EXTENDED,
    F_FD,
    F_PLAIN,
    F_REMOTE,
    FIRST_CHUNK_ROWS,
    ChunkBuilder,
    FrameStore,
    IdStats,
    line_head,
    message_kind,
    who,
)
from pdcp_studio.errors import PdcpError

Progress = Callable[[int, int, str], None]
_YIELD_EVERY = 256


def _position_probe(path: str | Path) -> Callable[[], int]:
    """A function giving how far (‰) the process has read ``path``, 0 where unknown."""
    target = os.path.realpath(path)
    try:
        size = os.path.getsize(target)
    except OSError:
        size = 0
    fds = "/proc/self/fd"
    found: dict[str, int] = {}

    def probe() -> int:
        if not size or not os.path.isdir(fds):
            return 0
        fd = found.get("fd")
        try:
            if fd is None or os.readlink(f"{fds}/{fd}") != target:
                fd = next((int(n) for n in os.listdir(fds)
                           if _link(f"{fds}/{n}") == target), None)
                if fd is None:
                    return 0
                found["fd"] = fd
            return min(1000, os.lseek(fd, 0, os.SEEK_CUR) * 1000 // size)
        except OSError:
            found.pop("fd", None)
            return 0

    return probe


def _link(path: str) -> str:
    try:
        return os.readlink(path)
    except OSError:
        return ""


@dataclass(frozen=True)
class NodeMapNote:
    """Where an opened capture's node map came from (the banner says it in words):
    ``source`` is ``file`` (``path``, the capture's ``.nodemap.json``), ``set-up`` (the
    capture's own bind answers and writes), ``inferred`` (from its traffic) or ``none``."""

    source: str
    devices: int = 0
    channels: int = 0
    path: str = ""


@dataclass(frozen=True)
class CaptureVerdict:
    """What an opened capture is: ``verdict`` ``pdcp`` / ``not-pdcp`` / ``empty`` (the
    CLI's words), its format in words, its node map, the frames read, and where it was cut
    (``damage``, the reader's "FILE: line N: …") or that the reading was stopped."""

    verdict: str
    format_name: str
    node_map: NodeMapNote | None
    frames: int = 0
    damage: str | None = None
    cancelled: bool = False
    #: The node map the capture was decoded with (``FrameDecoder.node_map()``; None for a
    #: foreign capture): saved beside it when it is saved again.
    node_map_json: Any = field(default=None, compare=False, repr=False)


class LoadState:
    """What the loading worker has learned so far, read by the window as it reports
    progress (each attribute replaced whole: no lock needed)."""

    def __init__(self) -> None:
        self.verdict: CaptureVerdict | None = None


def node_map_note(decoder: Any, source: str | None) -> NodeMapNote | None:
    """The evidence behind ``decoder``'s node map, as ``replay.node_map_words`` says it in
    the CLI; None for a foreign capture."""
    if decoder.foreign:
        return None
    if source is not None:
        return NodeMapNote("file", path=source)
    from pdcp_studio.bus.trace.knowledge import INFERRED

    inferred = sum(1 for owner in decoder.outputs.values() if owner == INFERRED)
    set_up = len(decoder.outputs) - inferred
    if inferred and decoder.learner is not None:
        return NodeMapNote("inferred", len(decoder.learner.devices | set(decoder.devices)),
                           inferred + set_up)
    if decoder.devices or set_up:
        return NodeMapNote("set-up", len(decoder.devices), set_up)
    return NodeMapNote("none")


def refuse_stream(path: str | Path) -> None:
    """CaptureError for a pipe or a device: opening a FIFO waits for its writer, which no
    Stop button can interrupt (the CLI reads one as a stream: ``monitor --replay``)."""
    import stat

    from pdcp_studio.bus.trace.files.capture import CaptureError

    try:
        mode = os.stat(path).st_mode
    except OSError:
        return  # the reader says why, in its words
    if not stat.S_ISREG(mode) and not stat.S_ISDIR(mode):
        raise CaptureError(path, "a pipe or a device, not a capture file (the app opens "
                           "files; read a pipe with pdcp-studio monitor --replay)")


def load_capture(store: FrameStore, stats: IdStats, path: str | Path, progress: Progress,
                 cancel: threading.Event, state: LoadState | None = None) -> CaptureVerdict:
    """Decode the capture at ``path`` into ``store`` (and ``stats``) with its own node map
    (the one saved beside it, else what its traffic teaches: ``bus.trace.files.replay``), never a
    live session's; returns what it is. A foreign capture's frames are stored as plain CAN
    (``F_PLAIN``), and every frame keeps its kind (error, remote, extended, FD). Raises
    ``CaptureError`` naming the file (and line or offset) when it cannot be read at all; a
    capture damaged later gives its frames up to the cut (``damage``)."""
    from pdcp_studio.bus.trace.files.blf import PlainFrame
    from pdcp_studio.bus.trace.files.reader import ReadCancelled
    from pdcp_studio.bus.trace.files.replay import CaptureReplay
    from pdcp_studio.bus.trace.frames import CHANNEL_DATA

    state = state if state is not None else LoadState()
    refuse_stream(path)
    try:
        opened = CaptureReplay(path, cancel=cancel)
    except ReadCancelled:
        state.verdict = CaptureVerdict("empty", "", None, cancelled=True)
        return state.verdict
    decoder = opened.decoder
    reader = opened.reader
    foreign = decoder.foreign
    source = opened.node_map_source
    state.verdict = CaptureVerdict("not-pdcp" if foreign else "pdcp" if reader.frames
                                   else "empty", reader.format_name,
                                   node_map_note(decoder, source))
    builder = ChunkBuilder(store.tables, decoder.channel_node_ids)
    add = builder.add
    decode = decoder.decode_message
    size = FIRST_CHUNK_ROWS
    where = _position_probe(path)
    count = 0
    cancelled = False

    def flush() -> None:
        chunk = builder.take()
        stats.update(chunk)
        store.append(chunk)
        progress(store.end, where(), "")

    try:
        for msg in opened.frames:
            kind = 0 if type(msg) is PlainFrame else message_kind(msg)
            if foreign:
                add(msg.timestamp or 0.0, msg.arbitration_id, bytes(msg.data), "",
                    kind=kind | F_PLAIN, dlc=msg.dlc)
            else:
                frame = decode(msg)
                if kind:
                    add(frame.timestamp, frame.arbitration_id, frame.data,
                        f"DLC {msg.dlc}" if kind & F_REMOTE else "", kind=kind, dlc=msg.dlc)
                else:
                    add(frame.timestamp, frame.arbitration_id, frame.data,
                        frame.head or line_head(frame.line),
                        frame.direction == CHANNEL_DATA or None, function=frame.function)
            count += 1
            if count % _YIELD_EVERY == 0:
                # Hand the interpreter to the window now and then: it waits for it to paint.
                time.sleep(0)
                if cancel.is_set():
                    cancelled = True
                    break
            if len(builder) >= size:
                flush()
                size = CHUNK_ROWS
    except ReadCancelled:
        cancelled = True
    finally:
        opened.close()
    if len(builder):
        flush()
    progress(store.end, 1000, "")
    verdict = "not-pdcp" if foreign else decoder.stats.verdict_word() if count else "empty"
    state.verdict = CaptureVerdict(verdict, reader.format_name,
                                   node_map_note(decoder, source) if count else None,
                                   count, reader.damage if reader.truncated else None,
                                   cancelled, None if foreign else decoder.node_map())
    return state.verdict


class PartlySaved(PdcpError):
    """A capture was written without some of its frames (a kind its format cannot keep, or
    CAN FD data beyond the 8 bytes the trace keeps): how many and why."""


def save_store(path: str | Path, store: FrameStore, links: dict[int, Any] | None = None, *,
               node_map: Any = None) -> int:
    """Write every frame of ``store``: a python-can capture chosen by extension (.asc, .blf,
    .log, .csv, .trc — the bus monitor's Recorder, replaced only once complete, with the
    node map saved beside it: ``node_map`` (an opened capture's own, JSON) or that of
    ``links`` (the live session's); neither: none), or decoded text for ``.txt``. Each
    frame keeps its kind (extended, remote, error, FD). Returns the count; raises
    ``PartlySaved`` once the file is written when some frames could not be (the format
    cannot keep their kind, or an FD frame's data is longer than the 8 bytes the trace
    keeps)."""
    from pdcp_studio.app.trace.model import decoded_fields

    path = Path(path)
    first, count = store.base, len(store)
    if path.suffix.lower() == ".txt":
        t0 = store.first_time() or 0.0
        with open(path, "w", encoding="utf-8") as out:
            for index in range(first, first + count):
                f = store.frame(index)
                out.write(f"{f.timestamp - t0:12.6f}  0x{f.arbitration_id:03X}  "
                          f"{who(f.arbitration_id, f.flags):9}  "
                          f"{f.data.hex(' ').upper():23}  {f.function}  "
                          f"{decoded_fields(store.text(f))}".rstrip() + "\n")
        return count
    import can

    from pdcp_studio.bus.trace.decoder import FrameDecoder
    from pdcp_studio.bus.trace.files.recorder import Recorder  # python-can loads only here

    saved_map = ((lambda: node_map) if node_map is not None
                 else None if links is None else FrameDecoder(dict(links)).node_map)
    written = cut = 0
    kinds = F_EXTENDED | F_REMOTE | F_ERROR | F_FD
    with Recorder(path, node_map=saved_map) as recorder:
        for _first, chunk in store.iter_chunks(first, first + count):
            ts, aid, dlc = chunk.ts.tolist(), chunk.aid.tolist(), chunk.dlc.tolist()
            flags = chunk.flags.tolist()
            data = chunk.data
            for k in range(len(ts)):
                f = flags[k]
                if not f & kinds:
                    recorder.write(aid[k], data[k, :min(dlc[k], 8)].tobytes(), ts[k])
                elif f & F_FD and dlc[k] > 8:
                    cut += 1  # its data beyond 8 bytes is not in the trace
                else:
                    remote = bool(f & F_REMOTE)
                    recorder.write_message(can.Message(
                        timestamp=ts[k], arbitration_id=aid[k],
                        is_extended_id=bool(f & F_EXTENDED), is_remote_frame=remote,
                        is_error_frame=bool(f & F_ERROR), is_fd=bool(f & F_FD), dlc=dlc[k],
                        data=b"" if remote else data[k, :min(dlc[k], 8)].tobytes()))
            written += len(ts)
        if written != count:  # an opened capture closed meanwhile: keep the old file
            raise OSError(f"only {written:,} of {count:,} frames could be read back")
    missing = recorder.not_written()
    if cut:
        words = (f"{cut:,} CAN FD frames longer than 8 bytes not written: the trace keeps "
                 "8 data bytes a frame (save from the capture file itself)")
        missing = f"{missing}; {words}" if missing else words
    if missing:
        raise PartlySaved(f"the file was written without some frames: {missing}")
    return count


def stored_rows(store: FrameStore, indices: Any = None) -> list[Any]:
    """Frames of ``store`` as ``store.Frame`` tuples (all, or those at ``indices``)."""
    if indices is None:
        indices = range(store.base, store.end)
    return [store.frame(int(i)) for i in indices]
