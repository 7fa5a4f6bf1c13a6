"""An opened capture's frames and texts in temporary files: memory flat whatever its length.

A capture of an hour of a busy bus holds ~30 million frames; even at 28 bytes a frame its
columns would need ~1 GB of memory. ``FileFrameStore`` keeps them in a temporary file instead
(one packed record per frame, appended chunk by chunk) and reads back only what is asked for:
a record per row on screen, one chunk at a time for filters, search and statistics. Its
decoded texts live in a ``FileTexts`` beside it: distinct texts appended to a file, with only
a bounded window of recent ones in memory (to share a number between repeats) and a bounded
cache for reading. The folder is removed by ``close()`` (or when the store is collected).

Both are used like ``store.FrameStore`` and ``Interner``: one thread appends, any
thread reads. No Qt here (tested directly).
"""

from __future__ import annotations

import os
import shutil
import tempfile
import threading
import weakref
from collections import OrderedDict
from collections.abc import Iterator
from itertools import pairwise

import numpy as np

from pdcp_studio.app.trace.store import F_REMOTE, Chunk, Frame, FrameStore, Tables

#: One frame on disk (packed, 28 bytes), the fields of ``store.Chunk``.
RECORD = np.dtype([("ts", "<f8"), ("aid", "<u4"), ("dlc", "u1"), ("data", "u1", (8,)),
                   ("func", "<u2"), ("text", "<u4"), ("flags", "u1")])
#: Recently used distinct texts remembered to number their repeats alike (a text unused for
#: longer gets a new number when it comes back: the table grows on disk, never in memory).
#: ~250 bytes each: 16,384 of them ~4 MB (65,536 held ~16 MB by 5,000,000 frames).
RECENT_TEXTS = 1 << 14
#: Texts kept in memory for reading (rows on screen, statistics on screen).
CACHED_TEXTS = 1 << 12
#: Rows read at once for painting (a screenful or two).
PREFETCH_ROWS = 512
_TEXT_BATCH = 4096
#: Searched a block at a time: a block's lines as strings (decoded, lower-cased, split; two
#: bytes a character once a text has an arrow) take ~9× the block's bytes: 1 MB blocks added
#: 11 MB to the peak of a search through a 5,000,000-frame capture.
_SCAN_BYTES = 1 << 18


class _File:
    """A file opened for reading and appending at offsets, closed once, under a lock."""

    def __init__(self, path: str) -> None:
        self.fd: int | None = os.open(path, os.O_RDWR | os.O_CREAT | os.O_EXCL, 0o600)
        self.lock = threading.Lock()

    def write(self, data: bytes, offset: int) -> bool:
        view = memoryview(data)
        with self.lock:
            if self.fd is None:
                return False
            while view:
                done = os.pwrite(self.fd, view, offset)
                view, offset = view[done:], offset + done
        return True

    def read(self, size: int, offset: int) -> bytes:
        with self.lock:
            if self.fd is None:
                return b""  # closed: a reader still running finds nothing more
            return os.pread(self.fd, size, offset)

    def truncate(self) -> None:
        with self.lock:
            if self.fd is not None:
                os.ftruncate(self.fd, 0)

    def close(self) -> None:
        with self.lock:
            if self.fd is not None:
                os.close(self.fd)
                self.fd = None


class FileTexts:
    """Distinct decoded texts numbered in order of arrival, kept in a file (see module doc).

    Number ``i``'s text is line ``i`` of ``texts.txt`` (newlines in a text become spaces);
    ``offsets.bin`` holds where each line starts. The newest texts wait in memory and are
    written a batch at a time.
    """

    def __init__(self, directory: str) -> None:
        self.folder = directory
        self._heap = _File(os.path.join(directory, "texts.txt"))
        self._offsets = _File(os.path.join(directory, "offsets.bin"))
        self._lock = threading.Lock()
        # writer only: text → number, oldest first (an OrderedDict drops its oldest in O(1))
        self._recent: OrderedDict[str, int] = OrderedDict({"": 0})
        self._cache: OrderedDict[int, str] = OrderedDict()
        self._written = 0  # numbers below this are in the files
        self._heap_size = 0
        self._tail: list[str] = [""]  # numbers _written … len-1, not yet written
        self._count = 1

    def add(self, text: str) -> int:
        recent = self._recent
        found = recent.get(text)
        if found is not None:
            recent.move_to_end(text)  # in use: kept (the oldest unused go first)
            return found
        if "\n" in text:
            text = text.replace("\n", " ")
        with self._lock:
            n = self._count
            self._tail.append(text)
            self._count += 1
            if len(self._tail) >= _TEXT_BATCH:
                self._flush()
        recent[text] = n
        if len(recent) > RECENT_TEXTS:
            recent.popitem(last=False)
        return n

    def _flush(self) -> None:
        """Write the waiting texts (the lock held)."""
        if not self._tail:
            return
        encoded = [t.encode("utf-8") + b"\n" for t in self._tail]
        sizes = np.fromiter((len(e) for e in encoded), dtype=np.int64, count=len(encoded))
        starts = self._heap_size + np.concatenate(([0], np.cumsum(sizes)[:-1]))
        self._heap.write(b"".join(encoded), self._heap_size)
        self._offsets.write(starts.astype("<u8").tobytes(), self._written * 8)
        self._heap_size += int(sizes.sum())
        self._written += len(self._tail)
        self._tail = []

    def __len__(self) -> int:
        return self._count

    def __getitem__(self, i: int) -> str:
        with self._lock:
            if i >= self._written:
                return self._tail[i - self._written]
            cached = self._cache.get(i)
            if cached is not None:
                self._cache.move_to_end(i)
                return cached
            if i < 0:
                raise IndexError(i)
            if i + 1 < self._written:
                lo, hi = np.frombuffer(self._offsets.read(16, i * 8), dtype="<u8").tolist()
            else:
                lo = int(np.frombuffer(self._offsets.read(8, i * 8), dtype="<u8")[0])
                hi = self._heap_size
            text = self._heap.read(hi - lo, lo)[:-1].decode("utf-8", "replace")
            self._cache[i] = text
            if len(self._cache) > CACHED_TEXTS:
                self._cache.popitem(last=False)
            return text

    def matching(self, needle: str) -> np.ndarray:
        """Which texts contain ``needle`` (lower case): a mask by number, read a block at a
        time from the file."""
        with self._lock:
            self._flush()
            written, size = self._written, self._heap_size
        mask = np.zeros(written, dtype=bool)
        number, offset, rest = 0, 0, b""
        while offset < size:
            read = self._heap.read(min(_SCAN_BYTES, size - offset), offset)
            if not read:
                break
            block = rest + read
            offset += len(block) - len(rest)
            cut = block.rfind(b"\n") + 1
            block, rest = block[:cut], block[cut:]
            lines = block.decode("utf-8", "replace").lower().split("\n")[:-1]
            hits = np.fromiter((needle in s for s in lines), dtype=bool, count=len(lines))
            mask[number:number + len(lines)] = hits
            number += len(lines)
        return mask

    def close(self) -> None:
        self._heap.close()
        self._offsets.close()


def _remove(frames: _File, texts: FileTexts, directory: str) -> None:
    frames.close()
    texts.close()
    shutil.rmtree(directory, ignore_errors=True)


class _ChunkList:
    """``store.chunks`` of a file store: read one at a time when iterated."""

    def __init__(self, store: FileFrameStore) -> None:
        self._store = store

    def __len__(self) -> int:
        return len(self._store.starts)

    def __iter__(self) -> Iterator[Chunk]:
        return (chunk for _, chunk in self._store.iter_chunks())


class FileFrameStore(FrameStore):
    """A ``FrameStore`` whose frames are in a temporary file (see the module doc).

    ``directory`` is where its folder is made (the system's temporary folder by default);
    ``path`` is the frames' file. Not a ring: frames are only appended (or all cleared).
    """

    def __init__(self, directory: str | None = None) -> None:
        self.folder = tempfile.mkdtemp(prefix="pdcp-capture-", dir=directory)
        self.path = os.path.join(self.folder, "frames.bin")
        self._file = _File(self.path)
        texts = FileTexts(self.folder)
        super().__init__(Tables(texts))
        self._row0 = 0  # the row at the file's start
        self._block: tuple[int, np.ndarray] | None = None  # rows read ahead for painting
        self._first_ts: float | None = None
        self._parent: FileFrameStore | None = None
        self._remove = weakref.finalize(self, _remove, self._file, texts, self.folder)

    @property  # type: ignore[override]
    def chunks(self) -> _ChunkList:
        return _ChunkList(self)

    @chunks.setter
    def chunks(self, _value: object) -> None:
        """The base class's list is not used: chunks are read from the file."""

    def append(self, chunk: Chunk | None) -> None:
        if chunk is None or not len(chunk):
            return
        rec = np.empty(len(chunk), dtype=RECORD)
        for name, column in zip(RECORD.names or (), chunk, strict=True):
            rec[name] = column
        if not self._file.write(rec.tobytes(), (self.end - self._row0) * RECORD.itemsize):
            return  # closed meanwhile: nothing more is kept
        if self._first_ts is None:
            self._first_ts = float(chunk.ts[0])
        self.starts.append(self.end)
        self.end += len(chunk)

    def clear(self) -> None:
        self._block = None
        self.starts = []
        self.base = self._row0 = self.end
        self._first_ts = None
        self._file.truncate()

    def snapshot(self) -> FileFrameStore:
        """A frozen view sharing the file (which stays until the view is dropped too)."""
        copy = object.__new__(FileFrameStore)
        copy.__dict__.update(self.__dict__)
        copy.starts = list(self.starts)
        copy._parent = self
        return copy

    def close(self) -> None:
        """Remove the files now (a reader still running then finds no more frames)."""
        self._remove()

    def _records(self, start: int, stop: int) -> np.ndarray:
        size = RECORD.itemsize
        data = self._file.read((stop - start) * size, (start - self._row0) * size)
        return np.frombuffer(data, dtype=RECORD, count=len(data) // size)

    def _record(self, index: int) -> np.void:
        if not self.base <= index < self.end:
            raise IndexError(index)
        block = self._block
        if block is not None and block[0] <= index < block[0] + len(block[1]):
            cached: np.void = block[1][index - block[0]]
            return cached
        rec = self._records(index, index + 1)
        if not len(rec):
            raise IndexError(index)
        first: np.void = rec[0]
        return first

    def prefetch(self, start: int, stop: int) -> None:
        """Read frames ``start … stop-1`` at once for the rows about to be painted (up to
        ``PREFETCH_ROWS``). Each read lets another thread take the interpreter, and getting
        it back waits for that thread's turn: a read per row made a repaint of 30 rows wait
        up to 30 turns while a capture loads."""
        start, stop = max(start, self.base), min(stop, self.end)
        if 0 < stop - start <= PREFETCH_ROWS:  # (filtered rows far apart: read one by one)
            self._block = (start, self._records(start, stop))

    def frame(self, index: int) -> Frame:
        r = self._record(index)
        n, flags = int(r["dlc"]), int(r["flags"])
        data = b"" if flags & F_REMOTE else r["data"][:min(n, 8)].tobytes()
        return Frame(index, float(r["ts"]), int(r["aid"]), data,
                     self.tables.functions[int(r["func"])], self.tables.texts[int(r["text"])],
                     flags, n)

    def timestamp(self, index: int) -> float:
        return float(self._record(index)["ts"])

    def first_time(self) -> float | None:
        return self._first_ts

    def iter_chunks(self, start: int | None = None,
                    stop: int | None = None) -> Iterator[tuple[int, Chunk]]:
        start = self.base if start is None else max(start, self.base)
        stop = self.end if stop is None else min(stop, self.end)
        bounds = [*self.starts, self.end]
        for first, last in pairwise(bounds):
            if last <= start or first >= stop:
                continue
            lo, hi = max(start, first), min(stop, last)
            rec = self._records(lo, hi)
            yield lo, Chunk(rec["ts"], rec["aid"], rec["dlc"], rec["data"], rec["func"],
                            rec["text"], rec["flags"])
