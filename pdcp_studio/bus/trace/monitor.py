"""The bus monitor: every CAN frame as one readable line, captures in python-can's log formats.

``FrameDecoder`` keeps what a listener can learn from the traffic — which node IDs are devices
(bind responses, VID/PID/serial reads), which are output channels (Channel Node Id writes and
reads) and which inputs listen to them (Source's Node Ids) — so that parameter names fit the
channel's direction and a data frame names its link. A frame that does not decode becomes an
"undecodable: <reason>" line and is counted; the decoder never raises on bus input. It is not
thread-safe: one consumer (a session thread or a GUI timer) feeds it.

python-can is imported inside the capture functions only, so importing this module is cheap.
"""

from __future__ import annotations

import contextlib
import copy
import json
import os
from collections import Counter
from collections.abc import Callable, Generator, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

from pdcp_studio.bus.trace.bustime import BusTimeMeter
from pdcp_studio.errors import FrameError, PdcpError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.protocol import messages as M
from pdcp_studio.protocol.bulk import BulkReassembler, packet_count
from pdcp_studio.protocol.codes import FunctionCode, ResponseCode
from pdcp_studio.protocol.identifier import Mode

TO_BA, FROM_BA, CHANNEL_DATA = "device→BA", "BA→device", "channel data"
UNDECODABLE = "undecodable"
UNATTRIBUTED = "unattributed"
#: node ID → (output channel, the inputs linked to it); the caller may keep updating it.
LinkMap = Mapping[int, tuple[ChannelRef, Sequence[ChannelRef]]]
#: Capture formats python-can 4.6 both writes and reads without extra packages (``.gz`` too).
CAPTURE_SUFFIXES = (".asc", ".blf", ".csv", ".log", ".trc", ".db")
_FAILURE = ResponseCode.FAILURE.title
_BEACON, _BULK_DATA = int(FunctionCode.BEACON), int(FunctionCode.BULK_DATA)
_DEVICE, _ARBITRATOR = Mode.DEVICE, Mode.ARBITRATOR
_NO_SOURCE = (0, 0xFF)  # a Source's Node Ids byte that means "not connected"
#: Per-ID statistics key extended identifiers above every base one.
EXTENDED_KEY = 1 << 29
NOT_PDCP = "not PDCP"
#: Frames a capture needs, none of them PDCP's, before it is called ``not PDCP``.
NOT_PDCP_MIN_FRAMES = 20
#: Decoded messages and descriptions kept for frames seen again (cleared when full).
CACHE_SIZE = 8192
NODE_MAP_FORMAT = "pdcp-studio-node-map/1"
#: A capture's node map is saved beside it as ``<capture>`` + this suffix.
NODE_MAP_SUFFIX = ".nodemap.json"
#: A capture being written (or interrupted) is named ``<capture>`` + this suffix.
PARTIAL_SUFFIX = ".partial"


class CaptureError(PdcpError):
    """A capture file cannot be read or written; names the file and why."""

    def __init__(self, path: str | Path, reason: str) -> None:
        self.path, self.reason = str(path), reason
        super().__init__(f"{path}: {reason}")


#: Messages the decoder follows (``_track``) every time they are seen: each starts or ends
#: a bulk transfer. Seen again while the decoder knows what it knew (same ``version``), the
#: other parameter messages teach nothing new — what they taught the first time did not
#: change what it knows, or the version would have moved on.
_LEARNING = (M.ConfigureGetBulkResponse, M.ConfigureSetBulk, M.ConfigureSetBulkResponse)
#: Messages whose line depends on more than what the decoder learned (bulk packets follow a
#: transfer) or that teach it something every time (binds): never described from a cache.
_UNCACHED = (M.BulkData, M.BindRequest, M.BindResponse)
_new_frame = tuple.__new__  # builds a DecodedFrame from a full tuple, skipping __new__'s keywords


class CaptureWriteError(CaptureError):
    """A capture could not be written (full disk, …): a failure (exit 1), not bad input."""


class DecodedFrame(NamedTuple):
    """One frame as the monitor shows it; ``line`` is the text, ``as_json()`` the record.

    A named tuple: immutable, and cheap to build for every frame of a saturated bus.
    """

    timestamp: float
    time: float  # seconds since the decoder's first frame
    arbitration_id: int
    data: bytes
    direction: str  # TO_BA, FROM_BA, CHANNEL_DATA or "" when the identifier is not PDCP's
    priority: int | None
    node_id: int | None
    function: str  # a function title, "Channel data" or UNDECODABLE
    fields: str
    error: str | None = None  # why it is undecodable, or a bulk-transfer fault
    response: str | None = None  # the response code's name
    link: tuple[ChannelRef | str, tuple[ChannelRef | str, ...]] | None = None
    message: Any = None
    #: The line without its time, when the decoder composed it already.
    head: str = ""

    @property
    def who(self) -> str:
        if self.node_id is None:
            return f"0x{self.arbitration_id:03X}"
        if self.direction == FROM_BA:
            return "BA→all" if self.node_id == 0 else f"BA→#{self.node_id}"
        return f"#{self.node_id} data" if self.direction == CHANNEL_DATA else f"#{self.node_id}→BA"

    @property
    def line(self) -> str:
        return f"{self.time:11.6f}  {self.head or self.text_head}"

    @property
    def text_head(self) -> str:
        """The line after its time."""
        prio = "P?" if self.priority is None else f"P{self.priority}"
        text = f"{prio}  {self.who} {self.function}"
        return f"{text}  {self.fields}" if self.fields else text

    def __str__(self) -> str:
        return self.line

    def as_json(self) -> dict[str, Any]:
        def ref(r: ChannelRef | str) -> Any:
            return r.as_json() if isinstance(r, ChannelRef) else r

        link = None if self.link is None else {
            "output": ref(self.link[0]), "inputs": [ref(r) for r in self.link[1]]}
        return {"timestamp": self.timestamp, "time": round(self.time, 6),
                "arbitration_id": self.arbitration_id, "data": self.data.hex(),
                "direction": self.direction, "priority": self.priority,
                "node_id": self.node_id, "function": self.function, "fields": self.fields,
                "response": self.response, "error": self.error, "link": link,
                "text": self.line}


#: Identifiers the per-ID statistics follow one by one; frames of any others are counted
#: together (a base bus has 2,048 identifiers, extended frames could bring 2^29).
MAX_TRACKED_IDS = 4096


@dataclass
class MonitorStats:
    """Frames by function and by identifier, errors, and the bus time they took.

    Every structure is bounded whatever the number of frames: counters by function name
    (a fixed vocabulary plus one entry per undecodable reason kind), per-ID entries up to
    ``MAX_TRACKED_IDS`` (``other_ids`` counts the rest).
    """

    frames: int = 0
    by_function: Counter[str] = field(default_factory=Counter)
    undecodable: int = 0
    failures: int = 0  # responses with code 0 (failure)
    bulk_errors: int = 0
    meter: BusTimeMeter = field(default_factory=BusTimeMeter)
    #: arbitration ID (extended ones + 0x20000000) → [count, first time, last time, last data]
    by_id: dict[int, list[Any]] = field(default_factory=dict)
    other_ids: int = 0
    #: Frames that fit PDCP in context (a response to its request, a completed bulk packet,
    #: channel data of a known output): what tells a PDCP bus from another one.
    in_context: int = 0

    @property
    def errors(self) -> int:
        return self.undecodable + self.failures + self.bulk_errors

    def note_id(self, key: int, timestamp: float, data: bytes) -> None:
        entry = self.by_id.get(key)
        if entry is not None:
            entry[0] += 1
            entry[2] = timestamp
            entry[3] = data
        elif len(self.by_id) < MAX_TRACKED_IDS:
            self.by_id[key] = [1, timestamp, timestamp, data]
        else:
            self.other_ids += 1

    def id_stats(self) -> list[dict[str, Any]]:
        """Per identifier: count, mean period in seconds (None below two frames), last data."""
        rows = []
        for key, (count, first, last, data) in sorted(self.by_id.items()):
            extended = key >= EXTENDED_KEY
            rows.append({"arbitration_id": key - EXTENDED_KEY if extended else key,
                         "extended": extended, "count": count,
                         "period_s": (last - first) / (count - 1) if count > 1 else None,
                         "last_data": data.hex()})
        return rows

    def verdict(self) -> str | None:
        """``not PDCP`` when plenty of frames came and none of them fitted PDCP in context."""
        nothing_decoded = 0 < self.frames == self.undecodable  # a short foreign capture
        if self.by_function.get(NOT_PDCP) or (self.in_context == 0 and (
                self.frames >= NOT_PDCP_MIN_FRAMES or nothing_decoded)):
            return NOT_PDCP
        return None

    def as_json(self, elapsed_s: float | None = None) -> dict[str, Any]:
        return {"frames": self.frames, "by_function": dict(self.by_function.most_common()),
                "undecodable": self.undecodable, "failures": self.failures,
                "bulk_errors": self.bulk_errors, "bus_time_us": round(self.meter.bus_time_us, 1),
                "bus_load": self.meter.load(elapsed_s), "verdict": self.verdict(),
                "ids": self.id_stats(), "other_ids": self.other_ids}

    def summary(self, elapsed_s: float | None = None, top_ids: int = 12) -> str:
        load = self.meter.load(elapsed_s)
        span = self.meter.span_s if elapsed_s is None else elapsed_s
        if self.verdict() == NOT_PDCP:
            head = (f"{self.frames} frames, {NOT_PDCP}: no frame fits PDCP's protocol "
                    "(a capture of another bus?), so none is counted as an error")
        else:
            head = (f"{self.frames} frames, {self.errors} errors ({self.undecodable} "
                    f"undecodable, {self.failures} failure responses, {self.bulk_errors} "
                    "bulk faults)")
        lines = [head, f"bus time {self.meter.bus_time_us / 1000:.3f} ms over {span:.3f} s"
                 + ("" if load is None else f" (bus load {100 * load:.2f} %)")]
        lines += [f"  {n:7d}  {name}" for name, n in self.by_function.most_common()]
        busiest = sorted(self.id_stats(), key=lambda r: -r["count"])[:top_ids]
        if busiest:
            lines.append(f"busiest of {len(self.by_id)} identifiers"
                         + (f" (+{self.other_ids} frames of others)" if self.other_ids else "")
                         + ": count, mean period, last data")
        for row in busiest:
            ident = (f"{row['arbitration_id']:08X}" if row["extended"]
                     else f"{row['arbitration_id']:03X}")
            period = ("-" if row["period_s"] is None
                      else f"{row['period_s'] * 1000:.3f} ms")
            lines.append(f"  {ident:>8}  {row['count']:7d}  {period:>12}  "
                         f"{row['last_data'].upper() or '(empty)'}")
        return "\n".join(lines)


class FrameDecoder:
    """Turns frames into ``DecodedFrame`` lines, learning the bus as it goes.

    ``links`` is an optional caller-owned mapping node ID → (output, [inputs]); it wins over
    what the decoder learned, and the caller may update it at any time.
    """

    def __init__(self, links: LinkMap | None = None, *, passive: bool = False) -> None:
        self.links: LinkMap = links if links is not None else {}
        #: A monitor that joined a running bus: frames from nodes it has not seen bind and
        #: that fit no function are "unattributed" (likely channel data), not errors.
        self.passive = passive
        #: Set when the traffic is known not to be PDCP's: frames are shown raw, no errors.
        self.foreign = False
        #: Show a frame as a PDCP message only when it fits in context (``_fits``): a
        #: request to or from a known device, a response to its request. Other frames that
        #: parse are "unattributed" (the stray frames of another bus in a capture or on a
        #: shared bus), not commands. Off, every frame that parses is shown as what it
        #: parses to (a simulated bus, a test).
        self.context_checked = False
        #: Count bus time (off for a decoder that only probes a capture).
        self.meter_on = True
        self.stats = MonitorStats()
        self.devices: dict[int, DeviceKey] = {}  # device node ID → identity
        self.outputs: dict[int, tuple[int, int]] = {}  # channel node → (device node, index)
        self.inputs: dict[int, set[tuple[int, int]]] = {}  # channel node → {(device node, index)}
        self.directions: dict[tuple[int, int], Direction] = {}
        self.bulk_values: dict[tuple[int, int, int], bytes] = {}  # (node, chan, param) → value
        self._partial: dict[int, dict[str, int]] = {}
        self._bulk: dict[tuple[int, Mode], tuple[int, int, BulkReassembler]] = {}  # param, chan
        self._t0: float | None = None
        # Caches for a saturated bus: decoded messages (or the reason they do not decode) by
        # frame; the link and its text by channel node, valid while ``_version`` (bumped by
        # every change to what was learned) and the caller's entry are the same.
        self._messages: dict[tuple[int, bytes], Any] = {}
        self._described: dict[tuple[int, bytes], tuple[Any, ...]] = {}
        self._link_cache: dict[int, tuple[Any, ...]] = {}
        self._version = 0
        # Requests seen and not yet answered: (node, response code) → count (bounded).
        self._pending: dict[tuple[int, int], int] = {}
        #: Device node IDs heard beaconing or answering (at most 254).
        self.heard: set[int] = set()
        self._beaconed: set[int] = set()

    def _changed(self) -> None:
        """What was learned changed: cached link texts are stale."""
        self._version += 1

    @property
    def version(self) -> int:
        """Bumped by every change to what the decoder knows (texts cached under an older
        version are stale)."""
        return self._version

    @property
    def t0(self) -> float | None:
        """The timestamp of the first frame (``time`` counts from it)."""
        return self._t0

    def relearn(self) -> None:
        """The caller changed its link map: forget the texts cached from it."""
        self._changed()

    def channel_texts(self, arbitration_id: int) -> tuple[Any, str, str] | None:
        """For an identifier just decoded as channel data of a known output: its link, the
        fields and the line before the data bytes — the same for every frame of that
        identifier while ``version`` stays."""
        cached = self._link_cache.get(arbitration_id)
        if cached is None or cached[0] != self._version:
            return None
        return cached[2], cached[3], cached[4]

    def repeatable(self, arbitration_id: int, data: bytes) -> Any:
        """For a base frame just decoded from the cache of described frames: its message
        when every frame like it reads and counts the same while ``version`` stays — one
        the decoder does not follow (not bulk, not a bind). A request or beacon must fit now
        (what it fits cannot change without a new version: known devices leave only by one,
        heard ones never); a response fits only after its request, so whoever repeats it
        asks ``_context`` each time. Else None."""
        seen = self._described.get((arbitration_id, data))
        if seen is None or seen[0] != self._version or seen[3] is not None:
            return None
        msg = seen[1]
        code = msg.CODE
        if code == _BULK_DATA or code == 0x01 or code == 0x81:
            return None
        if (code < 0x80 and self.context_checked
                and not self._fits(code, msg.mode, msg.node_id)):
            return None
        return msg

    @property
    def channel_node_ids(self) -> frozenset[int]:
        return frozenset(self.links) | frozenset(self.outputs)

    # -- entry points -----------------------------------------------------------------------

    def decode_message(self, msg: Any) -> DecodedFrame:
        """Decode a ``can.Message`` (or anything with its attributes).

        Channel data of a known output (most of a busy bus) is handled here inline: on a
        saturated bus every call and attribute lookup per frame counts.
        """
        arbitration_id = msg.arbitration_id
        node = arbitration_id & 0xFF
        if (arbitration_id < 0x600 and not arbitration_id & 0x100 and not self.foreign
                and self._t0 is not None and not msg.is_extended_id
                and not msg.is_remote_frame and not msg.is_error_frame
                and (node in self.links or node in self.outputs)):
            data = bytes(msg.data)
            timestamp = msg.timestamp or 0.0
            if len(data) <= 8:
                stats = self.stats
                stats.frames += 1
                if self.meter_on:
                    stats.meter.add_base(arbitration_id, data, timestamp)
                entry = stats.by_id.get(arbitration_id)
                if entry is not None:
                    entry[0] += 1
                    entry[2] = timestamp
                    entry[3] = data
                else:
                    stats.note_id(arbitration_id, timestamp, data)
                return self._channel_data(arbitration_id, node, data, timestamp)
        return self.decode(arbitration_id, bytes(msg.data), msg.timestamp or 0.0,
                           is_extended_id=msg.is_extended_id,
                           is_remote_frame=msg.is_remote_frame,
                           is_error_frame=msg.is_error_frame)

    def decode(self, arbitration_id: int, data: bytes, timestamp: float = 0.0, *,
               is_extended_id: bool = False, is_remote_frame: bool = False,
               is_error_frame: bool = False) -> DecodedFrame:
        """One frame → one line; never raises on what a bus can deliver."""
        if type(data) is not bytes:
            data = bytes(data)
        if self._t0 is None:
            self._t0 = timestamp
        stats = self.stats
        stats.frames += 1
        if is_extended_id or is_error_frame or is_remote_frame or not 0 <= arbitration_id <= 0x7FF:
            return self._odd_frame(arbitration_id, data, timestamp, is_extended_id,
                                   is_remote_frame, is_error_frame)
        if len(data) <= 8:
            if self.meter_on:
                stats.meter.add_base(arbitration_id, data, timestamp)
        entry = stats.by_id.get(arbitration_id)
        if entry is not None:
            entry[0] += 1
            entry[2] = timestamp
            entry[3] = data
        else:
            stats.note_id(arbitration_id, timestamp, data)
        node = arbitration_id & 0xFF
        if self.foreign:
            return self._raw(arbitration_id, data, timestamp)
        if (arbitration_id < 0x600 and not arbitration_id & 0x100 and len(data) <= 8
                and (node in self.links or node in self.outputs)):
            return self._channel_data(arbitration_id, node, data, timestamp)
        key = (arbitration_id, data)
        msg = self._messages.get(key)
        if msg is None:
            try:
                msg = M.decode(arbitration_id, data)
            except FrameError as err:
                msg = str(err)
            if len(self._messages) >= CACHE_SIZE:
                self._messages.clear()
            self._messages[key] = msg
        if isinstance(msg, str):
            base = {"timestamp": timestamp, "time": timestamp - self._t0,
                    "arbitration_id": arbitration_id, "data": data}
            if node <= 254:
                base.update(priority=arbitration_id >> 9, node_id=node)
                if (self.passive and arbitration_id < 0x600 and not arbitration_id & 0x100
                        and node not in self.devices and node not in self.heard):
                    return self._unattributed(base)
            return self._undecodable(base, msg)
        if not self._context(msg):  # a foreign frame that happens to parse: not a command
            return self._unattributed({"timestamp": timestamp, "time": timestamp - self._t0,
                                       "arbitration_id": arbitration_id, "data": data})
        # A frame seen before while the decoder knew exactly what it knows now reads the
        # same: reuse its text, still learning from it (bulk packets always go through).
        version = self._version
        seen = self._described.get(key)
        if seen is not None and seen[0] == version and seen[1] is msg:
            if seen[3] is not None:  # a parameter frame: learn as _describe does
                self._track(msg, self._direction(node, msg.channel, msg.param, seen[3]))
            frame = _new_frame(DecodedFrame, (timestamp, timestamp - self._t0, arbitration_id,
                                              data, *seen[2], msg, seen[4]))
        else:
            base = {"timestamp": timestamp, "time": timestamp - self._t0,
                    "arbitration_id": arbitration_id, "data": data,
                    "priority": arbitration_id >> 9, "node_id": node}
            try:
                frame = self._describe(msg, base)
            except Exception as err:  # a bug here must not stop a monitor: show it raw
                return self._undecodable(base, f"{type(err).__name__}: {err}")
            if (version == self._version and frame.error is None
                    and not isinstance(msg, _UNCACHED)):
                if len(self._described) >= CACHE_SIZE:
                    self._described.clear()
                value = getattr(msg, "value", b"") if isinstance(msg, _LEARNING) else None
                self._described[key] = (version, msg, frame[4:12], value,
                                        frame.text_head)
        stats.by_function[frame.function] += 1
        if frame.response == _FAILURE:
            stats.failures += 1
        if frame.error:
            stats.bulk_errors += 1
        return frame

    def _context(self, msg: Any) -> bool:
        """Follow requests and count frames that fit PDCP in context (a response to a request
        seen before it, a device beaconing again); whether this one may be shown as a PDCP
        message — always, unless ``context_checked`` (see ``_fits``)."""
        code = msg.CODE
        node = msg.node_id
        mode = msg.mode
        if code == _BEACON:  # a node beaconing again fits (devices beacon)
            if node in self._beaconed:
                self.stats.in_context += 1
            elif len(self._beaconed) < 512:
                self._beaconed.add(node)
        if code < 0x80:
            if code != _BEACON and code != _BULK_DATA:  # answered (bulk: after the last)
                self._expect(node, code | 0x80)
            fits = not self.context_checked or self._fits(code, mode, node)
        else:
            key = (node, code)
            pending = self._pending.get(key)
            fits = bool(pending)
            if pending:
                self.stats.in_context += 1
                if pending == 1:
                    del self._pending[key]
                else:
                    self._pending[key] = pending - 1
            fits = fits or not self.context_checked
        if fits and mode is _DEVICE and code != 0x01 and node:
            self.heard.add(node)
        return fits

    def _expect(self, node: int, response: int) -> None:
        """A request was seen: its response (from ``node``, or to it) fits."""
        key = (node, response)
        if len(self._pending) >= CACHE_SIZE:
            self._pending.clear()
        self._pending[key] = self._pending.get(key, 0) + 1

    def _fits(self, code: int, mode: Any, node: int) -> bool:
        """Whether a request or a beacon fits what the decoder knows: a Bind Device Request
        and a device's beacon always (exactly as PDCP frames them), bulk data of an
        announced transfer, the arbitrator's beacon, anything else only to or from a device
        it knows (bound, named in the node map, or heard answering). Responses fit only
        their requests."""
        if code == 0x01 or (code == _BEACON and mode is _DEVICE):
            return True  # how a device comes in, and says it is still there
        if code == _BULK_DATA:
            return (node, mode) in self._bulk
        if code == _BEACON and mode is _ARBITRATOR:
            return node == 0
        if node == 0:
            return mode is _ARBITRATOR and code != _BEACON
        return node in self.devices or node in self.heard

    def _raw(self, arbitration_id: int, data: bytes, timestamp: float) -> DecodedFrame:
        """A frame of a bus that is not PDCP's: shown as it is, counted, not an error."""
        self.stats.by_function[NOT_PDCP] += 1
        return DecodedFrame(timestamp, timestamp - (self._t0 or 0.0), arbitration_id, data,
                            "", None, None, NOT_PDCP,
                            f"[{arbitration_id:03X}] {data.hex(' ').upper() or '(empty)'}")

    def _unattributed(self, base: dict[str, Any]) -> DecodedFrame:
        """A passive monitor's frame from a node it has not learned: likely channel data."""
        self.stats.by_function[UNATTRIBUTED] += 1
        raw = f"[{base['arbitration_id']:03X}] {base['data'].hex(' ').upper() or '(empty)'}"
        return DecodedFrame(**{"direction": "", "priority": None, "node_id": None, **base},
                            function=UNATTRIBUTED, fields=raw)

    def _odd_frame(self, arbitration_id: int, data: bytes, timestamp: float, extended: bool,
                   remote: bool, error: bool) -> DecodedFrame:
        """Error, remote, extended or out-of-range frames: counted, never PDCP."""
        if not (extended or error) and 0 <= arbitration_id <= 0x7FF and len(data) <= 8:
            self.stats.meter.add(arbitration_id, data, timestamp)
        if not error:
            self.stats.note_id(arbitration_id + (EXTENDED_KEY if extended else 0),
                               timestamp, data)
        if self.foreign:
            return self._raw(arbitration_id, data, timestamp)
        reason = ("error frame" if error else
                  "extended 29-bit identifier (PDCP uses 11-bit base frames)" if extended
                  else "remote frame (PDCP sends none)" if remote
                  else f"arbitration ID 0x{arbitration_id:X} is not an 11-bit base identifier")
        base = {"timestamp": timestamp, "time": timestamp - (self._t0 or 0.0),
                "arbitration_id": arbitration_id, "data": data}
        if not (extended or error) and 0 <= arbitration_id <= 0x7FF \
                and arbitration_id & 0xFF <= 254:
            base.update(priority=arbitration_id >> 9, node_id=arbitration_id & 0xFF)
        return self._undecodable(base, reason)

    def _channel_data(self, arbitration_id: int, node: int, data: bytes,
                      timestamp: float) -> DecodedFrame:
        given = self.links.get(node)
        cached = self._link_cache.get(arbitration_id)  # by identifier: the line shows priority
        if cached is None or cached[0] != self._version or cached[1] is not given:
            link = self._link(node)
            ins = ", ".join(map(str, link[1])) or "no input known"
            text = f"{link[0]} → {ins}  "
            cached = (self._version, given, link, text,
                      f"P{arbitration_id >> 9}  #{node} data Channel data  {text}")
            if len(self._link_cache) >= CACHE_SIZE:
                self._link_cache.clear()
            self._link_cache[arbitration_id] = cached
        stats = self.stats
        stats.by_function["Channel data"] += 1
        stats.in_context += 1
        hex_data = data.hex(" ").upper() or "(empty)"
        return _new_frame(DecodedFrame, (
            timestamp, timestamp - self._t0, arbitration_id, data,  # type: ignore[operator]
            CHANNEL_DATA, arbitration_id >> 9, node, "Channel data", cached[3] + hex_data,
            None, None, cached[2], None, cached[4] + hex_data))

    # -- the node map, saved beside a capture ---------------------------------------------------

    def node_map(self) -> dict[str, Any]:
        """What the decoder knows of the bus (given links and what it learned), as JSON."""
        links = [{"node_id": node, "output": _ref_json(out), "inputs": [_ref_json(r) for r in ins]}
                 for node, (out, ins) in sorted(self.links.items())]
        return {
            "format": NODE_MAP_FORMAT,
            "devices": [{"node_id": n, "vid": k.vid, "pid": k.pid, "serial": k.serial}
                        for n, k in sorted(self.devices.items())],
            "outputs": [{"node_id": c, "device_node": d, "index": i}
                        for c, (d, i) in sorted(self.outputs.items())],
            "inputs": [{"node_id": c, "device_node": d, "index": i}
                       for c, ins in sorted(self.inputs.items()) for d, i in sorted(ins)],
            "directions": [{"device_node": d, "index": i, "direction": str(v)}
                           for (d, i), v in sorted(self.directions.items())],
            "links": links,
        }

    def load_node_map(self, doc: Any, where: str = "node map") -> None:
        """Start from a saved node map (``node_map()``); ValueError names what is wrong."""
        try:
            if doc.get("format") != NODE_MAP_FORMAT:
                raise ValueError(f"format is {doc.get('format')!r}, not {NODE_MAP_FORMAT!r}")
            for d in doc.get("devices", []):
                self.devices[_node(d["node_id"])] = DeviceKey(int(d["vid"]), int(d["pid"]),
                                                             int(d["serial"]))
            for o in doc.get("outputs", []):
                self.outputs[_node(o["node_id"])] = (_node(o["device_node"]), int(o["index"]))
            for i in doc.get("inputs", []):
                self.inputs.setdefault(_node(i["node_id"]), set()).add(
                    (_node(i["device_node"]), int(i["index"])))
            for d in doc.get("directions", []):
                self.directions[_node(d["device_node"]), int(d["index"])] = Direction(
                    d["direction"])
            links = doc.get("links", [])
            if links and isinstance(self.links, dict):
                for link in links:
                    self.links[_node(link["node_id"])] = (
                        _ref_from(link["output"]),
                        tuple(_ref_from(r) for r in link["inputs"]))
        except (AttributeError, KeyError, TypeError, ValueError) as err:
            raise ValueError(f"{where}: {err}") from err
        self._changed()

    # -- describing -------------------------------------------------------------------------

    def _undecodable(self, base: dict[str, Any], reason: str) -> DecodedFrame:
        self.stats.undecodable += 1
        self.stats.by_function[UNDECODABLE] += 1
        if "node_id" in base:
            base["direction"] = TO_BA if base["arbitration_id"] >> 8 & 1 == 0 else FROM_BA
        raw = f"[{base['arbitration_id']:03X}] {base['data'].hex(' ').upper() or '(empty)'}"
        return DecodedFrame(**{"direction": "", "priority": None, "node_id": None, **base},
                            function=f"{UNDECODABLE}: {reason}", fields=raw, error=reason)

    def _describe(self, msg: M.Message, base: dict[str, Any]) -> DecodedFrame:
        if isinstance(msg, M.ChannelData):
            link = self._link(msg.node_id)
            ins = ", ".join(map(str, link[1])) or "no input known"
            text = f"{link[0]} → {ins}  {msg.data.hex(' ').upper() or '(empty)'}"
            return DecodedFrame(**base, direction=CHANNEL_DATA, function="Channel data",
                                fields=text, link=link, message=msg)
        node, parts, error = msg.node_id, [], None
        code = getattr(msg, "code", None)
        if code is not None:
            parts.append(code.title)
        if isinstance(msg, M.BindRequest | M.BindResponse):
            if isinstance(msg, M.BindResponse):
                parts.append(f"node {msg.granted_node_id} "
                             + ("granted" if msg.accepted else "suggested"))
                if msg.accepted:
                    self._bound(msg.granted_node_id, DeviceKey(msg.vid, msg.pid, msg.serial))
            else:
                parts.append(f"asks for node {node}")
            parts.append(f"VID 0x{msg.vid:04X} PID 0x{msg.pid:04X} SN {msg.serial}")
        elif isinstance(msg, M.BulkData):
            error = self._bulk_packet(msg, parts)
        elif hasattr(msg, "param"):
            value = getattr(msg, "value", b"")
            direction = self._direction(node, msg.channel, msg.param, value)
            parts.append(f"param {msg.param} "
                         f"{P.parameter_name(msg.param, msg.channel, direction)}  "
                         f"chan {msg.channel}")
            if value:
                spec = P.find_parameter(msg.param, msg.channel, direction)
                parts.append(f"= {P.render_value(spec, value)}")
            if hasattr(msg, "size"):
                parts.append(f"size {msg.size} bytes")
            self._track(msg, direction)
        elif hasattr(msg, "channel"):
            parts.append(f"chan {msg.channel}")
        if hasattr(msg, "ms"):
            parts.append(f"{msg.ms} ms" if msg.ms else "indefinitely")
        return DecodedFrame(**base, direction=TO_BA if msg.mode is Mode.DEVICE else FROM_BA,
                            function=msg.CODE.title, fields="  ".join(parts), error=error,
                            response=None if code is None else code.title, message=msg)

    def _link(self, node: int) -> tuple[ChannelRef | str, tuple[ChannelRef | str, ...]]:
        if node in self.links:
            out, ins = self.links[node]
            return out, tuple(ins)
        dev, index = self.outputs[node]
        inputs = sorted(self.inputs.get(node, ()))
        return self._ref(dev, index), tuple(self._ref(d, i) for d, i in inputs)

    def _ref(self, device_node: int, index: int) -> ChannelRef | str:
        key = self.devices.get(device_node)
        return ChannelRef(*key, index) if key else f"node {device_node}#{index}"

    # -- learning ---------------------------------------------------------------------------

    def _bound(self, node: int, key: DeviceKey) -> None:
        """A device holds ``node`` now: forget its old node and any channel that used ``node``."""
        self._changed()
        for old in [n for n, k in self.devices.items() if k == key and n != node]:
            self._forget_device(old)
        self._forget_device(node)
        self.outputs.pop(node, None)
        self.devices[node] = key

    def _forget_device(self, node: int) -> None:
        self._changed()
        self.devices.pop(node, None)
        for chan_node in [c for c, (d, _) in self.outputs.items() if d == node]:
            del self.outputs[chan_node]
        for listeners in self.inputs.values():
            listeners.difference_update({x for x in listeners if x[0] == node})
        self.directions = {k: v for k, v in self.directions.items() if k[0] != node}

    def _moved(self, old: int, new: int) -> None:
        """The device at ``old`` was given node ID ``new``: its channels keep their node IDs."""
        if new == old or new in _NO_SOURCE:
            return
        self._changed()
        self._bound(new, self.devices.pop(old))
        self.outputs = {c: (new if d == old else d, i) for c, (d, i) in self.outputs.items()}
        self.inputs = {c: {(new if d == old else d, i) for d, i in ins}
                       for c, ins in self.inputs.items()}
        self.directions = {(new if d == old else d, i): v for (d, i), v in self.directions.items()}

    def _direction(self, node: int, chan: int, param: int, value: bytes) -> Direction | None:
        """The channel's direction: learned, else implied by the parameter and value size."""
        if chan == 0:
            return None
        known = self.directions.get((node, chan))
        if known is not None:
            return known
        if param in (P.IN_SOURCE_SN_INDEX, P.IN_SOURCE_NODE_IDS, P.IN_SOURCE_TYPE_PROFILE,
                     P.IN_TERMINAL_PROFILE):
            return Direction.INPUT
        if param == P.OUT_NODE_ID and value:  # 1 byte: Channel Node Id; 4: Source's VID and PID
            return Direction.OUTPUT if len(value) == 1 else Direction.INPUT
        return None

    def _track(self, msg: M.Message, direction: Direction | None) -> None:
        """Learn from parameter traffic and follow bulk transfers."""
        node = msg.node_id
        if isinstance(msg, M.ConfigureGetBulkResponse | M.ConfigureSetBulk):
            ok = isinstance(msg, M.ConfigureSetBulk) or msg.code is ResponseCode.SUCCESS
            if ok:
                try:
                    self._bulk[node, msg.mode] = (msg.param, msg.channel,
                                                  BulkReassembler(msg.size))
                except FrameError:
                    pass  # an impossible size: its packets will show as unannounced
        elif isinstance(msg, M.ConfigureSetBulkResponse) and msg.code is ResponseCode.FAILURE:
            self._bulk.pop((node, Mode.ARBITRATOR), None)
        elif isinstance(msg, M.SetParameter):
            self._learn(node, msg.channel, msg.param, msg.value, direction)
        elif isinstance(msg, M.GetParameterResponse | M.SetParameterResponse):
            if msg.code is ResponseCode.SUCCESS and msg.value:
                self._learn(node, msg.channel, msg.param, msg.value, direction)

    def _learn(self, node: int, chan: int, param: int, value: bytes,
               direction: Direction | None) -> None:
        if direction is not None and self.directions.get((node, chan)) is not direction:
            self.directions[node, chan] = direction
            self._changed()
        if chan == 0:
            if param == P.DEVICE_NODE_ID and len(value) == 1 and node in self.devices:
                self._moved(node, value[0])
            elif param in (P.DEVICE_VID_PID, P.DEVICE_SERIAL):
                self._learn_identity(node, param, value)
        elif param == P.CH_TRANSFER_TYPE and len(value) == 1 and value[0] in (1, 2):
            learned = Direction.from_transfer_type(value[0])
            if self.directions.get((node, chan)) is not learned:
                self.directions[node, chan] = learned
                self._changed()
        elif param == P.OUT_NODE_ID and direction is Direction.OUTPUT and len(value) == 1:
            self._changed()
            for chan_node in [c for c, owner in self.outputs.items() if owner == (node, chan)]:
                del self.outputs[chan_node]
            if value[0] not in _NO_SOURCE and value[0] not in self.devices:
                self.outputs[value[0]] = (node, chan)
        elif param == P.IN_SOURCE_NODE_IDS and len(value) == 2:
            self._changed()
            for listeners in self.inputs.values():
                listeners.discard((node, chan))
            if value[1] not in _NO_SOURCE:
                self.inputs.setdefault(value[1], set()).add((node, chan))

    def _learn_identity(self, node: int, param: int, value: bytes) -> None:
        partial = self._partial.setdefault(node, {})
        if param == P.DEVICE_VID_PID and len(value) == 4:
            partial["vid"] = int.from_bytes(value[:2], "little")
            partial["pid"] = int.from_bytes(value[2:], "little")
        elif param == P.DEVICE_SERIAL and len(value) == 2:
            partial["serial"] = int.from_bytes(value, "little")
        if len(partial) == 3 and node not in self.devices:
            self._bound(node, DeviceKey(**partial))

    def _bulk_packet(self, msg: M.BulkData, parts: list[str]) -> str | None:
        transfer = self._bulk.get((msg.node_id, msg.mode))
        hex_data = msg.data.hex(" ").upper()
        if transfer is None:
            parts.append(f"packet {msg.packet_id}  {hex_data}  (no transfer announced)")
            return None
        param, chan, r = transfer
        self.stats.in_context += 1
        parts.append(f"packet {msg.packet_id}/{packet_count(r.expected_size)}  {hex_data}")
        try:
            complete = r.add(msg.packet_id, msg.data)
        except FrameError as err:
            del self._bulk[msg.node_id, msg.mode]
            self._expect(msg.node_id, _BULK_DATA | 0x80)  # the receiver answers, failing
            parts.append(f"bulk transfer aborted: {err}")
            return str(err)
        if complete:
            del self._bulk[msg.node_id, msg.mode]
            self._expect(msg.node_id, _BULK_DATA | 0x80)
            value = r.result()
            if len(self.bulk_values) >= CACHE_SIZE:
                self.bulk_values.clear()
            self.bulk_values[msg.node_id, chan, param] = value
            direction = self.directions.get((msg.node_id, chan))
            spec = P.find_parameter(param, chan, direction)
            name = P.parameter_name(param, chan, direction)
            parts.append(f"complete: {name} chan {chan} = {P.render_value(spec, value)}")
        return None


def _ref_json(ref: ChannelRef | str) -> Any:
    return ref.as_json() if isinstance(ref, ChannelRef) else ref


def _ref_from(doc: Any) -> ChannelRef | str:
    return doc if isinstance(doc, str) else ChannelRef(**doc)


def _node(value: Any) -> int:
    node = int(value)
    if not 1 <= node <= 254:
        raise ValueError(f"node ID {node} is out of range (1–254)")
    return node


_json_str = json.encoder.encode_basestring_ascii  # type: ignore[attr-defined]


def _link_json(link: Any) -> str:
    return json.dumps({"output": _ref_json(link[0]), "inputs": [_ref_json(r) for r in link[1]]})


def frame_json(frame: DecodedFrame, links: dict[int, tuple[Any, str]] | None = None) -> str:
    """``json.dumps(frame.as_json())`` without building the dict (a monitor's hot path).

    ``links`` (a dict the caller keeps) remembers the JSON of link objects already seen:
    the decoder hands out the same link object for every frame of an output.
    """
    link = frame.link
    if link is None:
        link_text = "null"
    elif links is None:
        link_text = _link_json(link)
    else:
        known = links.get(id(link))
        if known is None or known[0] is not link:
            if len(links) >= CACHE_SIZE:
                links.clear()
            known = links[id(link)] = (link, _link_json(link))
        link_text = known[1]
    return (f'{{"timestamp": {frame.timestamp!r}, "time": {round(frame.time, 6)!r}, '
            f'"arbitration_id": {frame.arbitration_id}, "data": "{frame.data.hex()}", '
            f'"direction": {_json_str(frame.direction)}, '
            f'"priority": {"null" if frame.priority is None else frame.priority}, '
            f'"node_id": {"null" if frame.node_id is None else frame.node_id}, '
            f'"function": {_json_str(frame.function)}, "fields": {_json_str(frame.fields)}, '
            f'"response": {"null" if frame.response is None else _json_str(frame.response)}, '
            f'"error": {"null" if frame.error is None else _json_str(frame.error)}, '
            f'"link": {link_text}, "text": {_json_str(frame.line)}}}')


def utf8_buffer(out: Any) -> Any:
    """The byte buffer under a UTF-8 text stream (sys.stdout), else None: text written
    there as ``str.encode()`` reads exactly as if the stream had encoded it (and where
    a text stream writes "\\n" as it is: not on Windows)."""
    import codecs

    if os.linesep != "\n":
        return None
    encoding = getattr(out, "encoding", None)
    buffer = getattr(out, "buffer", None)
    if buffer is None or not isinstance(encoding, str):
        return None
    try:
        utf8 = codecs.lookup(encoding).name == "utf-8"
    except LookupError:
        return None
    return buffer if utf8 and getattr(out, "errors", "strict") == "strict" else None


class JsonFrameWriter:
    """Writes one JSON list of frames as they come: memory stays flat for any length.

    Nothing is written before the first frame (so a command that fails first prints
    nothing); ``close()`` ends the list — also after a failure, so stdout stays one JSON
    document.
    """

    def __init__(self, stream: Any) -> None:
        self.stream, self.count = stream, 0
        self._links: dict[int, tuple[Any, str]] = {}
        #: The records go to the stream's byte buffer when it has one that encodes as
        #: UTF-8 (sys.stdout): a chunk of records is hundreds of kilobytes, and the text
        #: layer copies it twice more than ``str.encode`` does.
        self._buffer = utf8_buffer(stream)

    def write(self, frame: DecodedFrame) -> None:
        self.write_records([frame_json(frame, self._links)])

    def write_to(self, records: list[str], frame: DecodedFrame) -> None:
        """Append ``frame``'s record to ``records`` (to be written by ``write_records``)."""
        records.append(frame_json(frame, self._links))

    def write_records(self, records: list[str]) -> None:
        """Write records made by ``write_to`` or ``frame_json``, in order."""
        if records:
            head = "[\n" if self.count == 0 else ",\n"
            buffer = self._buffer
            if buffer is not None:
                self.stream.flush()  # what was written as text first
                buffer.write(head.encode())
                buffer.write(",\n".join(records).encode())
            else:
                self.stream.write(head)
                self.stream.write(",\n".join(records))
            self.count += len(records)

    def close(self) -> None:
        self.stream.write("\n]\n" if self.count else "[]\n")


# -- captures --------------------------------------------------------------------------------


#: Largest channel number the log formats carry (BLF stores a u16; 255 is plenty for CAN).
MAX_LOG_CHANNEL = 255


def _loggable(msg: Any, fallback: str | int | None) -> Any:
    """``msg`` with a channel every log format can store.

    python-can's writers turn a channel name into a number by its trailing digits, so a
    virtual channel such as ``pdcp-sim-8a81c7c786c490cb46c66be45734036`` becomes a number no
    BLF record can hold. Such channels are written as ``fallback`` instead (a copy: the
    frame is shared with other listeners).
    """
    from can.util import channel2int

    to_message = getattr(msg, "to_message", None)
    if to_message is not None:  # a frame read without its can.Message (blf_read)
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


def write_node_map(capture: str | Path, node_map: dict[str, Any]) -> Path:
    """Save ``node_map`` atomically beside ``capture``; returns the sidecar's path."""
    from pdcp_studio.storage.atomic import atomic_write_text

    path = Path(str(capture) + NODE_MAP_SUFFIX)
    atomic_write_text(path, json.dumps(node_map, indent=1) + "\n")
    return path


def read_node_map(capture: str | Path) -> dict[str, Any] | None:
    """The node map saved beside ``capture``, or None; CaptureError if it is unreadable."""
    path = Path(str(capture) + NODE_MAP_SUFFIX)
    if not path.is_file():
        return None
    try:
        with path.open("rb") as handle:
            raw = handle.read((1 << 20) + 1)
        if len(raw) > 1 << 20:
            raise ValueError("larger than 1 MiB")
        doc = json.loads(raw)
        if not isinstance(doc, dict):
            raise ValueError("not a JSON object")
        return doc
    except (OSError, ValueError) as err:
        raise CaptureError(path, f"not a readable node map ({err})") from err


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
    ``blf_read.PlainFrame`` (the same attributes, ``to_message()`` for the message itself),
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


def replay(path: str | Path, decoder: FrameDecoder | None = None) -> Iterator[DecodedFrame]:
    """Decode a capture frame by frame (pass a decoder to read its statistics afterwards)."""
    decoder = decoder if decoder is not None else FrameDecoder()
    for msg in read_capture(path, plain_frames=True):
        yield decoder.decode_message(msg)
