"""Reading a capture into a ``FrameStore`` and writing a store back out, off the GUI thread.

``load_capture(store, stats, path, links, progress, cancel)`` decodes any python-can log
(ASC, BLF, TRC, CSV, candump .log, .db; ``bus.trace.replay`` with the node map saved beside
the capture) into the store's column chunks: a small first chunk so the first rows show at
once, then chunks of ``CHUNK_ROWS``. It reports ``progress(frames, permille, "")`` — the
permille from the reader's position in the file where the platform tells it (Linux), else 0
— and stops within a few thousand frames of ``cancel`` being set. ``save_store`` writes a
store as a python-can capture (by extension) or as decoded text (``.txt``).

Qt-free: it runs on a worker and is tested directly.
"""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from pdcp_studio.app.trace.store import (
    CHUNK_ROWS,
    FIRST_CHUNK_ROWS,
    ChunkBuilder,
    FrameStore,
    IdStats,
    line_head,
    who,
)

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


def load_capture(store: FrameStore, stats: IdStats, path: str | Path, links: dict[int, Any] | None,
                 progress: Progress, cancel: threading.Event) -> int:
    """Decode the capture at ``path`` into ``store`` (and ``stats``); returns the frames
    stored. Raises ``CaptureError`` naming the file when it cannot be read."""
    from pdcp_studio.bus.trace.decoder import FrameDecoder
    from pdcp_studio.bus.trace.frames import CHANNEL_DATA
    from pdcp_studio.bus.trace.nodemap import read_node_map
    from pdcp_studio.bus.trace.replay import replay

    decoder = FrameDecoder(dict(links or {}))
    node_map = read_node_map(path)
    if node_map is not None:
        decoder.load_node_map(node_map, f"{path}.nodemap.json")
    builder = ChunkBuilder(store.tables, decoder.channel_node_ids)
    add = builder.add
    size = FIRST_CHUNK_ROWS
    where = _position_probe(path)
    count = 0

    def flush() -> None:
        chunk = builder.take()
        stats.update(chunk)
        store.append(chunk)
        progress(store.end, where(), "")

    for frame in replay(path, decoder):
        add(frame.timestamp, frame.arbitration_id, frame.data,
            frame.head or line_head(frame.line), frame.direction == CHANNEL_DATA or None)
        count += 1
        if count % _YIELD_EVERY == 0:
            # Hand the interpreter to the window now and then: it waits for it to paint.
            time.sleep(0)
            if cancel.is_set():
                break
        if len(builder) >= size:
            flush()
            size = CHUNK_ROWS
    if len(builder):
        flush()
    progress(store.end, 1000, "")
    return count


def save_store(path: str | Path, store: FrameStore, links: dict[int, Any] | None = None) -> int:
    """Write every frame of ``store``: a python-can capture chosen by extension (.asc, .blf,
    .log, .csv, .trc — the bus monitor's Recorder, replaced only once complete, with the
    node map of ``links`` saved beside it), or decoded text for ``.txt``. Returns the count."""
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
    from pdcp_studio.bus.trace.decoder import FrameDecoder
    from pdcp_studio.bus.trace.recorder import Recorder  # python-can loads only here

    node_map = FrameDecoder(dict(links or {})).node_map
    written = 0
    with Recorder(path, node_map=node_map) as recorder:
        for _first, chunk in store.iter_chunks(first, first + count):
            ts, aid, dlc = chunk.ts.tolist(), chunk.aid.tolist(), chunk.dlc.tolist()
            data = chunk.data
            for k in range(len(ts)):
                recorder.write(aid[k], data[k, :min(dlc[k], 8)].tobytes(), ts[k])
            written += len(ts)
        if written != count:  # an opened capture closed meanwhile: keep the old file
            raise OSError(f"only {written:,} of {count:,} frames could be read back")
    return count


def stored_rows(store: FrameStore, indices: Any = None) -> list[Any]:
    """Frames of ``store`` as ``store.Frame`` tuples (all, or those at ``indices``)."""
    if indices is None:
        indices = range(store.base, store.end)
    return [store.frame(int(i)) for i in indices]
