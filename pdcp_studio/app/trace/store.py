"""Frames in compact columns: the trace's memory for live frames and opened captures.

A busy bus brings ~8,000 frames a second and a capture can hold millions: one Python object
per frame (or one table item) would not fit and would stall the window. Frames are kept as
numpy columns in chunks (time, identifier, length, 8 data bytes, function, decoded text as an
index into a table of distinct texts, flags) — about 30 bytes a frame — and rows are
numbered absolutely (0 = the first frame ever stored), so a live ring that drops its oldest
chunks keeps the numbers of the rest.

This is the in-memory store (the live ring, bounded by its capacity); an opened capture goes
to ``trace_disk.FileFrameStore``, the same interface with the columns in a temporary file
(``iter_chunks`` reads them a chunk at a time). Filtering and search are vectorised over the
columns (``FrameStore.select``): the text needle is tried once on each distinct text (a mask
by text number), then matched by index. Nothing here imports Qt,
so the worker threads that load captures and filter them use it directly.

Public API: ``TraceFilter``, ``FrameStore``, ``ChunkBuilder``, ``IdStats`` (``StatRows``),
``line_head(line)``, ``who(aid, flags)``, ``CHANNEL_DATA``.
"""

from __future__ import annotations

import threading
from bisect import bisect_right
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import TYPE_CHECKING, Any, NamedTuple, overload

import numpy as np

from pdcp_studio.protocol.codes import FunctionCode

if TYPE_CHECKING:
    from pdcp_studio.app.trace.disk import FileTexts

CHANNEL_DATA = "Channel data"
#: Rows per chunk of an opened capture (the first chunk is small so rows show at once).
CHUNK_ROWS = 65_536
FIRST_CHUNK_ROWS = 500
#: Distinct decoded texts kept; beyond, a frame's text is re-made from its fields.
TEXT_LIMIT = 1 << 20
F_HEX = 1  # the decoded text goes on with the data bytes in hex
F_CHANNEL = 2  # channel data of an output
F_EXTENDED = 4
F_REMOTE = 8  # a remote frame: its DLC is in the length column, it carries no data
F_ERROR = 16
F_FD = 32
F_PLAIN = 64  # not PDCP's (a foreign capture's frame): shown as plain CAN, no PDCP names
#: Frames that are no PDCP message whatever the bus: shown as the kind of frame they are.
ODD_KINDS = F_EXTENDED | F_REMOTE | F_ERROR | F_FD
_MODE_BIT = 0x100
#: A decoded line that names no PDCP message says one of these after its sender
#: (``bus.trace.frames``): its Function column says so too, never its first byte's name.
_NOT_MESSAGES = ("undecodable", "unattributed", "not PDCP")


def _no_message(head: str) -> str | None:
    """Which of ``_NOT_MESSAGES`` a decoded line (without its time) is, if any."""
    lead = head[:40]  # priority, sender and function; not the fields
    for word in _NOT_MESSAGES:
        if word in lead:
            return word
    return None

#: The kinds that key an identifier's statistics apart (bits above its 32).
_KIND_KEY = F_EXTENDED | F_ERROR


class Interner:
    """Distinct strings numbered in order of arrival (append-only, safe to read anywhere)."""

    def __init__(self, limit: int = TEXT_LIMIT) -> None:
        self.values: list[str] = [""]
        self._index: dict[str, int] = {"": 0}
        self._lower: list[str] = [""]
        self.limit = limit
        self._lock = threading.Lock()

    def add(self, text: str) -> int:
        found = self._index.get(text)
        if found is not None:
            return found
        with self._lock:
            found = self._index.get(text)
            if found is not None:
                return found
            if len(self.values) >= self.limit:
                return 0
            self.values.append(text)
            self._lower.append(text.lower())
            self._index[text] = n = len(self.values) - 1
            return n

    def __getitem__(self, i: int) -> str:
        return self.values[i]

    def __len__(self) -> int:
        return len(self.values)

    def matching(self, needle: str) -> np.ndarray:
        """Which strings contain ``needle`` (lower case): a mask indexed by string number."""
        lower = self._lower[:len(self.values)]
        return np.fromiter((needle in s for s in lower), dtype=bool, count=len(lower))

    def close(self) -> None:
        """Nothing to release (the file-backed table removes its files)."""


class Tables:
    """The string tables a store's columns point into: functions and decoded texts
    (``texts`` may be a ``FileTexts``, on disk, for an opened capture)."""

    def __init__(self, texts: Interner | FileTexts | None = None) -> None:
        self.functions = Interner()
        self.texts = texts if texts is not None else Interner()
        by_byte = []
        for b in range(256):
            try:
                name = FunctionCode(b).title
            except ValueError:
                name = f"0x{b:02X}"
            by_byte.append(self.functions.add(name))
        self.function_by_byte = by_byte
        self.channel_data = self.functions.add(CHANNEL_DATA)


class Chunk(NamedTuple):
    """Columns of consecutive frames (equal lengths)."""

    ts: np.ndarray  # float64 seconds
    aid: np.ndarray  # uint32 arbitration ID
    dlc: np.ndarray  # uint8 data length
    data: np.ndarray  # uint8 (n, 8)
    func: np.ndarray  # uint16 into Tables.functions
    text: np.ndarray  # uint32 into Tables.texts
    flags: np.ndarray  # uint8 F_*

    def __len__(self) -> int:
        return len(self.ts)


class Frame(NamedTuple):
    """One stored frame, made on demand for the rows on screen."""

    index: int  # type: ignore[assignment]  # the absolute row; shadows tuple.index on purpose
    timestamp: float
    arbitration_id: int
    data: bytes
    function: str
    text: str  # the decoded line without its time
    flags: int
    dlc: int = 0  # the frame's DLC (a remote frame's, though it carries no data)

    @property
    def node(self) -> int:
        return self.arbitration_id & 0xFF

    @property
    def who(self) -> str:
        return who(self.arbitration_id, self.flags)


def who(aid: int, flags: int) -> str:
    """Who sent the frame to whom, as the trace's Node column shows it (nobody PDCP knows
    for a plain CAN frame, an extended, error, remote or FD one)."""
    if flags & (F_PLAIN | ODD_KINDS) or aid > 0x7FF:
        return ""
    node = aid & 0xFF
    if flags & F_CHANNEL:
        return f"#{node} data"
    if aid & _MODE_BIT:
        return f"BA→#{node}" if node else "BA→all"
    return f"#{node}→BA"


#: The kinds of frame, as the Kind column and a plain frame's Function column name them.
KIND_WORDS = {F_ERROR: "error frame", F_REMOTE: "remote frame", F_FD: "FD frame",
              F_EXTENDED: "extended frame"}


def kind_word(flags: int) -> str:
    """What kind of CAN frame ``flags`` say ("data frame", "remote frame", …)."""
    for bit, word in KIND_WORDS.items():
        if flags & bit:
            return word
    return "data frame"


def message_kind(msg: Any) -> int:
    """The kind flags of a python-can frame (``can.Message`` or anything with its fields)."""
    return ((F_EXTENDED if msg.is_extended_id else 0) | (F_REMOTE if msg.is_remote_frame else 0)
            | (F_ERROR if msg.is_error_frame else 0) | (F_FD if msg.is_fd else 0))


def line_head(line: str) -> str:
    """A decoded line without its leading time (``DecodedFrame.line`` starts with it)."""
    stripped = line.lstrip()
    first, _, rest = stripped.partition(" ")
    try:
        float(first)
    except ValueError:
        return line
    return rest.lstrip()


class ChunkBuilder:
    """Collects frames and hands them out as a ``Chunk`` (one Python step per frame)."""

    def __init__(self, tables: Tables, channel_nodes: Iterable[int] = ()) -> None:
        self.tables = tables
        self.channel_nodes = set(channel_nodes)
        self._clear()

    def _clear(self) -> None:
        self._ts: list[float] = []
        self._aid: list[int] = []
        self._dlc: list[int] = []
        self._data = bytearray()
        self._func: list[int] = []
        self._text: list[int] = []
        self._flags: list[int] = []

    def __len__(self) -> int:
        return len(self._ts)

    def add(self, timestamp: float, aid: int, data: bytes, head: str,
            channel: bool | None = None, *, function: str | None = None, kind: int = 0,
            dlc: int | None = None) -> None:
        """One frame; ``head`` is its decoded line without the time; ``channel`` whether it
        is channel data (None: from the known output nodes or the text); ``function`` the
        decoder's name for it (None: from its first byte); ``kind`` its ``F_*`` kind flags
        (``message_kind``, ``F_PLAIN``); ``dlc`` a remote frame's DLC."""
        node = aid & 0xFF
        flags = kind | (F_EXTENDED if aid > 0x7FF else 0)
        if flags & (F_PLAIN | ODD_KINDS):
            channel = False
            func = self.tables.functions.add(function or kind_word(flags))
        elif channel is None:
            channel = not aid & _MODE_BIT and (node in self.channel_nodes or CHANNEL_DATA in head)
        if channel:
            flags |= F_CHANNEL
            func = self.tables.channel_data
            if node not in self.channel_nodes:
                self.channel_nodes.add(node)
        elif flags & (F_PLAIN | ODD_KINDS):
            pass  # named above
        elif function is not None:
            func = self.tables.functions.add(function)
        elif (word := _no_message(head)) is not None:  # never its first byte's name
            func = self.tables.functions.add(word)
        elif data:
            func = self.tables.function_by_byte[data[0]]
        else:
            func = 0
        n = len(data)
        if n > 8:
            data = data[:8]
        if n:
            hexed = data.hex(" ").upper()
            if head.endswith(hexed):
                head = head[:-len(hexed)].rstrip()
                flags |= F_HEX
        self._ts.append(timestamp)
        self._aid.append(aid)
        self._dlc.append(min(n if dlc is None or not flags & F_REMOTE else dlc, 255))
        self._data += data.ljust(8, b"\0")
        self._func.append(func)
        self._text.append(self.tables.texts.add(head))
        self._flags.append(flags)

    def take(self) -> Chunk | None:
        """The frames added since the last take, as columns (None if there are none)."""
        if not self._ts:
            return None
        n = len(self._ts)
        chunk = Chunk(np.array(self._ts, dtype=np.float64), np.array(self._aid, dtype=np.uint32),
                      np.array(self._dlc, dtype=np.uint8),
                      np.frombuffer(bytes(self._data), dtype=np.uint8).reshape(n, 8),
                      np.array(self._func, dtype=np.uint16), np.array(self._text, dtype=np.uint32),
                      np.array(self._flags, dtype=np.uint8))
        self._clear()
        return chunk


class TraceFilter(NamedTuple):
    """What the trace shows: a text or ID needle, a function name, a node.

    ``node`` None is any node; 0 is a broadcast (frames from the bus arbiter to all).
    The text matches the decoded text, the function name, the identifier written as
    ``0x…`` and the data bytes written in hex (``0A 1B`` or ``0a1b``), all case-insensitive.
    """

    text: str = ""
    function: str = ""
    node: int | None = None

    def __bool__(self) -> bool:
        return bool(self.text or self.function or self.node is not None)


class _Needle(NamedTuple):
    texts: np.ndarray  # mask by text number
    functions: np.ndarray  # mask by function number
    ident: int | None
    data: bytes | None


def _needle(tables: Tables, text: str) -> _Needle:
    low = text.strip().lower()
    ident = None
    if low.startswith("0x"):
        try:
            ident = int(low, 16)
        except ValueError:
            ident = None
    data = None
    compact = low.replace(" ", "")
    if compact and len(compact) % 2 == 0:
        try:
            data = bytes.fromhex(compact)
        except ValueError:
            data = None
    return _Needle(tables.texts.matching(low), tables.functions.matching(low), ident, data)


def _has_bytes(chunk: Chunk, needle: bytes) -> np.ndarray:
    """Rows whose data contains ``needle`` (within their length)."""
    n, k = len(chunk), len(needle)
    found = np.zeros(n, dtype=bool)
    if k > 8:
        return found
    for start in range(0, 9 - k):
        hit = (chunk.dlc >= start + k) & (chunk.flags & F_REMOTE == 0)
        for j, b in enumerate(needle):
            hit &= chunk.data[:, start + j] == b
        found |= hit
    return found


def _masked(mask: np.ndarray, numbers: np.ndarray) -> np.ndarray:
    """``mask[numbers]``, with numbers past the mask's end (added since) False."""
    if len(numbers) and int(numbers.max()) >= len(mask):
        mask = np.concatenate((mask, np.zeros(int(numbers.max()) + 1 - len(mask), dtype=bool)))
    masked: np.ndarray = mask[numbers]
    return masked


class FrameStore:
    """Frames in chunks with absolute row numbers ``base … end-1``.

    ``max_rows`` makes it a ring: whole chunks are dropped from the front once more than
    that many rows are kept. One thread appends; any thread reads (``end`` is set last).
    """

    def __init__(self, tables: Tables | None = None, max_rows: int | None = None) -> None:
        self.tables = tables or Tables()
        self.max_rows = max_rows
        self.chunks: list[Chunk] = []
        self.starts: list[int] = []
        self.base = 0
        self.end = 0

    def __len__(self) -> int:
        return self.end - self.base

    def append(self, chunk: Chunk | None) -> None:
        if chunk is None or not len(chunk):
            return
        self.chunks.append(chunk)
        self.starts.append(self.end)
        self.end += len(chunk)
        if self.max_rows is not None:
            while len(self.chunks) > 1 and self.end - self.starts[1] >= self.max_rows:
                self.chunks.pop(0)
                self.starts.pop(0)
                self.base = self.starts[0]
            over = self.end - self.base - self.max_rows
            if over > 0:  # trim the oldest chunk to exactly ``max_rows`` (a view)
                self.chunks[0] = Chunk(*(c[over:] for c in self.chunks[0]))
                self.starts[0] += over
                self.base = self.starts[0]

    def clear(self) -> None:
        """Drop every frame (row numbers go on from where they were)."""
        self.chunks, self.starts = [], []
        self.base = self.end

    def snapshot(self) -> FrameStore:
        """A frozen copy sharing the chunks (a paused view keeps what it shows)."""
        copy = FrameStore(self.tables)
        end = self.end
        copy.chunks, copy.starts = list(self.chunks), list(self.starts)
        while copy.starts and copy.starts[-1] >= end:  # appended while copying
            copy.chunks.pop()
            copy.starts.pop()
        copy.base, copy.end = (copy.starts[0] if copy.starts else end), end
        return copy

    def _locate(self, index: int) -> tuple[Chunk, int]:
        i = bisect_right(self.starts, index) - 1
        if i < 0 or not self.base <= index < self.end:
            raise IndexError(index)
        return self.chunks[i], index - self.starts[i]

    def frame(self, index: int) -> Frame:
        chunk, k = self._locate(index)
        n, flags = int(chunk.dlc[k]), int(chunk.flags[k])
        data = b"" if flags & F_REMOTE else chunk.data[k, :min(n, 8)].tobytes()
        return Frame(index, float(chunk.ts[k]), int(chunk.aid[k]), data,
                     self.tables.functions[int(chunk.func[k])],
                     self.tables.texts[int(chunk.text[k])], flags, n)

    def timestamp(self, index: int) -> float:
        chunk, k = self._locate(index)
        return float(chunk.ts[k])

    def first_time(self) -> float | None:
        return float(self.chunks[0].ts[0]) if self.chunks else None

    def text(self, frame: Frame) -> str:
        """The decoded text of ``frame`` as shown (the data bytes put back)."""
        if frame.flags & F_HEX:
            hexed = frame.data.hex(" ").upper()
            return f"{frame.text}  {hexed}" if frame.text else hexed
        return frame.text

    def iter_chunks(self, start: int | None = None,
                    stop: int | None = None) -> Iterator[tuple[int, Chunk]]:
        """``(first row, columns)`` of the stored frames in ``start … stop-1``, chunk by
        chunk (the chunks held when called; safe while another thread appends)."""
        start = self.base if start is None else max(start, self.base)
        stop = self.end if stop is None else min(stop, self.end)
        for chunk, first in zip(list(self.chunks), list(self.starts), strict=False):
            last = first + len(chunk)
            if last <= start or first >= stop:
                continue
            lo, hi = max(start, first) - first, min(stop, last) - first
            yield first + lo, (chunk if (lo, hi) == (0, len(chunk))
                               else Chunk(*(c[lo:hi] for c in chunk)))

    def prefetch(self, start: int, stop: int) -> None:
        """Make frames ``start … stop-1`` quick to read (in memory already: nothing to do;
        see ``trace_disk``)."""

    def close(self) -> None:
        """Release what the store holds outside memory (nothing here; see ``trace_disk``)."""

    def select(self, flt: TraceFilter, start: int | None = None, stop: int | None = None,
               cancel: threading.Event | None = None,
               progress: Callable[[int, int], None] | None = None) -> np.ndarray:
        """Absolute indices of the rows in ``start … stop-1`` that pass ``flt`` (sorted)."""
        start = self.base if start is None else max(start, self.base)
        stop = self.end if stop is None else min(stop, self.end)
        tables = self.tables
        needle = _needle(tables, flt.text) if flt.text else None
        function = tables.functions._index.get(flt.function, -1) if flt.function else None
        out: list[np.ndarray] = []
        for first, part in self.iter_chunks(start, stop):
            if cancel is not None and cancel.is_set():
                break
            mask = np.ones(len(part), dtype=bool)
            if flt.node is not None:
                mask &= (part.aid & 0xFF) == flt.node
                if flt.node == 0:
                    mask &= (part.aid & _MODE_BIT) != 0
            if function is not None:
                mask &= part.func == function
            if needle is not None:
                hit = _masked(needle.texts, part.text) | _masked(needle.functions, part.func)
                if needle.ident is not None:
                    hit |= part.aid == needle.ident
                if needle.data is not None:
                    hit |= _has_bytes(part, needle.data)
                mask &= hit
            out.append(np.flatnonzero(mask) + first)
            if progress is not None:
                progress(first + len(part) - start, stop - start)
        if not out:
            return np.zeros(0, dtype=np.int64)
        return np.concatenate(out).astype(np.int64, copy=False)


class IdStat(NamedTuple):
    """Per-identifier statistics as the statistics view shows them."""

    arbitration_id: int
    count: int  # type: ignore[assignment]  # frames seen; shadows tuple.count on purpose
    period_s: float | None  # mean period
    last_period_s: float | None
    last_time: float
    last_data: bytes
    function: str
    text: str
    flags: int = 0  # the last frame's F_* (extended, error: told apart from standard IDs)


class IdStats:
    """Count, first/last time, last data and meaning per identifier, updated per chunk
    (vectorised); bounded by the identifiers a bus can use.

    A loading worker updates while the window reads: each entry is replaced whole (one dict
    store), so a reader needs no lock to see a consistent entry, and the statistics view
    asks only for the rows it paints (``view()``): refreshing 4,096 identifiers twice a
    second on the GUI thread made ~12,000 objects each time, stalled it 20-120 ms and fed
    the cyclic collector's full collections (benchmarks/gui.py, capture case)."""

    def __init__(self, tables: Tables, limit: int = 4096) -> None:
        self.tables = tables
        self.limit = limit
        #: aid → [count, first ts, last ts, previous ts, data, text index, func, flags]
        self.entries: dict[int, list[Any]] = {}
        self.others = 0
        self.frames = 0
        self._sorted: list[int] | None = []  # the identifiers in order; None: re-sort
        self._lock = threading.Lock()  # a loading worker updates, the window reads

    def clear(self) -> None:
        with self._lock:
            self.entries.clear()
            self._sorted = []
            self.others = self.frames = 0

    def update(self, chunk: Chunk | None) -> None:
        if chunk is None or not len(chunk):
            return
        # Vectorised per chunk (a stable sort groups each identifier's frames in order).
        # Extended and error frames are keyed apart from the standard identifier they share
        # a number with (``_KIND_KEY``): 0x123 and 0x00000123 are two rows.
        aids = chunk.aid.astype(np.int64)
        kinds = chunk.flags & _KIND_KEY
        if kinds.any():
            aids |= kinds.astype(np.int64) << 32
        n = len(aids)
        order = np.argsort(aids, kind="stable")
        grouped = aids[order]
        starts = np.concatenate(([0], np.flatnonzero(np.diff(grouped)) + 1))
        ends = np.concatenate((starts[1:], [n]))
        counts = (ends - starts).tolist()
        first = order[starts]
        last = order[ends - 1]
        prev = order[np.maximum(ends - 2, starts)]
        ts = chunk.ts
        rows = zip(grouped[starts].tolist(), counts, ts[first].tolist(), ts[last].tolist(),
                   ts[prev].tolist(), strict=True)
        dlc, data, text, func, flags = (chunk.dlc[last].tolist(), chunk.data[last],
                                        chunk.text[last].tolist(), chunk.func[last].tolist(),
                                        chunk.flags[last].tolist())
        # One thread updates. Each entry is replaced by one dict store, which a reader sees
        # whole, so the merge needs no lock: held through it (up to 4,096 identifiers a
        # chunk), the lock kept the window's statistics refresh waiting for the loading
        # thread's turns at the interpreter.
        entries = self.entries
        others, new_ids = 0, False
        for j, (aid, c, t_first, t_last, t_prev) in enumerate(rows):
            e = entries.get(aid)
            last_data = (b"" if flags[j] & F_REMOTE
                         else data[j, :min(dlc[j], 8)].tobytes())
            if e is None:
                if len(entries) >= self.limit:
                    others += c
                    continue
                entries[aid] = [c, t_first, t_last, t_prev if c > 1 else None, last_data,
                                text[j], func[j], flags[j]]
                new_ids = True
            else:
                entries[aid] = [e[0] + c, e[1], t_last, t_prev if c > 1 else e[2],
                                last_data, text[j], func[j], flags[j]]
        with self._lock:
            self.frames += n
            self.others += others
            if new_ids:
                self._sorted = None

    def ids(self) -> list[int]:
        """The identifiers seen (safe while a worker updates)."""
        with self._lock:
            return list(self.entries)

    def sorted_ids(self) -> list[int]:
        """The identifiers seen, in order (sorted again only when new ones came)."""
        with self._lock:
            if self._sorted is None:
                self._sorted = sorted(self.entries)
            return self._sorted

    def row(self, aid: int) -> IdStat:
        """The statistics of identifier ``aid`` (KeyError if it was not seen)."""
        count, first, last, prev, data, text, func, flags = self.entries[aid]
        aid &= 0xFFFFFFFF
        head = self.tables.texts[text]
        if flags & F_HEX:
            hexed = data.hex(" ").upper()
            head = f"{head}  {hexed}" if head else hexed
        return IdStat(aid, count, (last - first) / (count - 1) if count > 1 else None,
                      None if prev is None else last - prev, last, data,
                      self.tables.functions[func], head, flags)

    def view(self) -> StatRows:
        """The rows by identifier, each made when asked for (see the class doc)."""
        return StatRows(self, self.sorted_ids())

    def rows(self) -> list[IdStat]:
        """Every identifier seen, by identifier."""
        return list(self.view())


class StatRows(Sequence[IdStat]):
    """``IdStats`` rows by identifier: the identifiers fixed when made, each row's figures
    read when it is asked for (the statistics view asks for the rows it paints)."""

    def __init__(self, stats: IdStats, ids: list[int]) -> None:
        self.stats = stats
        self.ids = ids

    def __len__(self) -> int:
        return len(self.ids)

    @overload
    def __getitem__(self, i: int) -> IdStat: ...

    @overload
    def __getitem__(self, i: slice) -> list[IdStat]: ...

    def __getitem__(self, i: int | slice) -> IdStat | list[IdStat]:
        if isinstance(i, slice):
            return [self.stats.row(aid) for aid in self.ids[i]]
        return self.stats.row(self.ids[i])
