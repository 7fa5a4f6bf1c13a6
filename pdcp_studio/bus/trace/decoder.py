"""The monitor's decoder: every CAN frame as one readable line, learning the bus as it goes.

``FrameDecoder`` keeps what a listener can learn from the traffic (``BusKnowledge``: which
node IDs are devices, which are output channels and which inputs listen to them) so that
parameter names fit the channel's direction and a data frame names its link; it follows
bulk transfers (``BulkTransfers``) and counts everything (``MonitorStats``). A frame that
does not decode becomes an "undecodable: <reason>" line and is counted; the decoder never
raises on bus input. It is not thread-safe: one consumer (a session thread or a GUI timer)
feeds it.
"""

from __future__ import annotations

from typing import Any

from pdcp_studio.bus.trace.bulk import BulkTransfers
from pdcp_studio.bus.trace.files.nodemap import load_node_map, node_map_json
from pdcp_studio.bus.trace.frames import (
    CACHE_SIZE,
    CHANNEL_DATA,
    FROM_BA,
    NOT_PDCP,
    TO_BA,
    UNATTRIBUTED,
    UNDECODABLE,
    DecodedFrame,
    Link,
    LinkMap,
    new_frame,
)
from pdcp_studio.bus.trace.inference import TrafficLearner
from pdcp_studio.bus.trace.knowledge import INFERRED, BusKnowledge
from pdcp_studio.bus.trace.stats import EXTENDED_KEY, MonitorStats
from pdcp_studio.errors import FrameError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import DeviceKey, Direction
from pdcp_studio.protocol import messages as M
from pdcp_studio.protocol.codes import FunctionCode, ResponseCode
from pdcp_studio.protocol.identifier import Mode

_FAILURE = ResponseCode.FAILURE.title
_BEACON, _BULK_DATA = int(FunctionCode.BEACON), int(FunctionCode.BULK_DATA)
_DEVICE, _ARBITRATOR = Mode.DEVICE, Mode.ARBITRATOR
#: Messages the decoder follows (``_track``) every time they are seen: each starts or ends
#: a bulk transfer. Seen again while the decoder knows what it knew (same ``version``), the
#: other parameter messages teach nothing new — what they taught the first time did not
#: change what it knows, or the version would have moved on.
_LEARNING = (M.ConfigureGetBulkResponse, M.ConfigureSetBulk, M.ConfigureSetBulkResponse)
#: Messages whose line depends on more than what the decoder learned (bulk packets follow a
#: transfer) or that teach it something every time (binds): never described from a cache.
_UNCACHED = (M.BulkData, M.BindRequest, M.BindResponse)
#: Messages that name a parameter of a channel.
_PARAMETER_MESSAGES = (M.GetParameter, M.GetParameterResponse, M.SetParameter,
                       M.SetParameterResponse, M.ConfigureGetBulk, M.ConfigureGetBulkResponse,
                       M.ConfigureSetBulk, M.ConfigureSetBulkResponse)


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
        #: What the traffic taught; its maps are read here (the fast path reads ``outputs``
        #: directly) and changed only by ``known``, in place.
        self.known = BusKnowledge(self._changed)
        self.devices = self.known.devices  # device node ID → identity
        self.outputs = self.known.outputs  # channel node → (device node, index)
        self.inputs = self.known.inputs  # channel node → {(device node, index)}
        self.directions = self.known.directions
        self.bulk = BulkTransfers(self._expect, self._in_context, self.directions)
        self.bulk_values = self.bulk.values  # (node, chan, param) → value
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
        #: Infers devices and output channels from traffic whose set-up was not seen
        #: (``inference.py``); frames the decoder cannot place feed it (None: off).
        self.learner: TrafficLearner | None = None

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
                and not msg.is_remote_frame and not msg.is_error_frame and not msg.is_fd
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
                           is_error_frame=msg.is_error_frame, is_fd=msg.is_fd, dlc=msg.dlc)

    def decode(self, arbitration_id: int, data: bytes, timestamp: float = 0.0, *,
               is_extended_id: bool = False, is_remote_frame: bool = False,
               is_error_frame: bool = False, is_fd: bool = False,
               dlc: int | None = None) -> DecodedFrame:
        """One frame → one line; never raises on what a bus can deliver."""
        if type(data) is not bytes:
            data = bytes(data)
        if self._t0 is None:
            self._t0 = timestamp
        stats = self.stats
        stats.frames += 1
        if (is_extended_id or is_error_frame or is_remote_frame or is_fd
                or not 0 <= arbitration_id <= 0x7FF):
            return self._odd_frame(arbitration_id, data, timestamp, is_extended_id,
                                   is_remote_frame, is_error_frame, is_fd,
                                   len(data) if dlc is None else dlc)
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
        learner = self.learner
        if learner is not None and learner.observe(arbitration_id, data):
            self.adopt()
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
                self._track(msg, self.known.direction(node, msg.channel, msg.param, seen[3]))
            frame = new_frame(DecodedFrame, (timestamp, timestamp - self._t0, arbitration_id,
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

    def _in_context(self) -> None:
        """A frame fitted PDCP in context (a packet of an announced bulk transfer)."""
        self.stats.in_context += 1

    def _fits(self, code: int, mode: Any, node: int) -> bool:
        """Whether a request or a beacon fits what the decoder knows: a Bind Device Request
        and a device's beacon always (exactly as PDCP frames them), bulk data of an
        announced transfer, the arbitrator's beacon, anything else only to or from a device
        it knows (bound, named in the node map, or heard answering). Responses fit only
        their requests."""
        if code == 0x01 or (code == _BEACON and mode is _DEVICE):
            return True  # how a device comes in, and says it is still there
        if code == _BULK_DATA:
            return self.bulk.announced(node, mode)
        if code == _BEACON and mode is _ARBITRATOR:
            return node == 0
        if node == 0:
            return mode is _ARBITRATOR and code != _BEACON
        return node in self.devices or node in self.heard

    def _raw(self, arbitration_id: int, data: bytes, timestamp: float,
             text: str | None = None, who: str = "") -> DecodedFrame:
        """A frame of a bus that is not PDCP's: shown as it is (plain CAN: identifier,
        kind, data), counted, not an error. ``who``: the sender column of an extended or
        error frame (a standard identifier's is the default)."""
        self.stats.by_function[NOT_PDCP] += 1
        fields = text or f"[{arbitration_id:03X}] {data.hex(' ').upper() or '(empty)'}"
        return DecodedFrame(timestamp, timestamp - (self._t0 or 0.0), arbitration_id, data,
                            "", None, None, NOT_PDCP, fields,
                            head=f"P?  {who} {NOT_PDCP}  {fields}" if who else "")

    def _unattributed(self, base: dict[str, Any]) -> DecodedFrame:
        """A passive monitor's frame from a node it has not learned: likely channel data."""
        self.stats.by_function[UNATTRIBUTED] += 1
        raw = f"[{base['arbitration_id']:03X}] {base['data'].hex(' ').upper() or '(empty)'}"
        return DecodedFrame(**{"direction": "", "priority": None, "node_id": None, **base},
                            function=UNATTRIBUTED, fields=raw)

    def _odd_frame(self, arbitration_id: int, data: bytes, timestamp: float, extended: bool,
                   remote: bool, error: bool, fd: bool, dlc: int) -> DecodedFrame:
        """Error, remote, extended, CAN FD or out-of-range frames: counted, never PDCP,
        each shown as what it is."""
        if not (extended or error or fd) and 0 <= arbitration_id <= 0x7FF and len(data) <= 8:
            self.stats.meter.add(arbitration_id, data, timestamp)
        if not error:
            self.stats.note_id(arbitration_id + (EXTENDED_KEY if extended else 0),
                               timestamp, data)
        text = plain_can_text(arbitration_id, data, extended=extended, remote=remote,
                              error=error, fd=fd, dlc=dlc)
        # The sender column: an error frame has no identifier, an extended one 8 digits.
        who = ("error" if error else f"0x{arbitration_id:08X}" if extended
               or not 0 <= arbitration_id <= 0x7FF else "")
        if self.foreign:
            return self._raw(arbitration_id, data, timestamp, text, who)
        reason = ("error frame" if error else
                  "extended 29-bit identifier (PDCP uses 11-bit base frames)" if extended
                  else "remote frame (PDCP sends none)" if remote
                  else "CAN FD frame (PDCP uses classical CAN)" if fd
                  else f"arbitration ID 0x{arbitration_id:X} is not an 11-bit base identifier")
        base = {"timestamp": timestamp, "time": timestamp - (self._t0 or 0.0),
                "arbitration_id": arbitration_id, "data": data}
        if not (extended or error) and 0 <= arbitration_id <= 0x7FF \
                and arbitration_id & 0xFF <= 254:
            base.update(priority=arbitration_id >> 9, node_id=arbitration_id & 0xFF)
        frame = self._undecodable(base, reason, "" if error else text)
        if who:
            frame = frame._replace(head=f"P?  {who} {frame.function}"
                                   + (f"  {frame.fields}" if frame.fields else ""))
        return frame

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
        return new_frame(DecodedFrame, (
            timestamp, timestamp - self._t0, arbitration_id, data,  # type: ignore[operator]
            CHANNEL_DATA, arbitration_id >> 9, node, "Channel data", cached[3] + hex_data,
            None, None, cached[2], None, cached[4] + hex_data))

    # -- the node map, saved beside a capture or inferred -------------------------------------

    def learn_from_traffic(self, head: Any = ()) -> TrafficLearner:
        """Infer devices and output channels from traffic (``inference.py``): from ``head``
        (frames read ahead, e.g. a capture's first ones) now, and from every frame the
        decoder cannot place afterwards. Returns the learner (its evidence)."""
        if self.learner is None:
            self.learner = TrafficLearner()
        self.learner.observe_all(head)
        self.learner.settle()
        self.adopt()
        return self.learner

    def adopt(self) -> None:
        """Take what the learner infers now: its channels as outputs known only by node ID
        (a channel set up, bound or named by the caller wins), the devices that announced
        themselves (beacon, bind request) as heard."""
        learner = self.learner
        if learner is None:
            return
        channels = learner.channels
        outputs = self.outputs
        changed = False
        for node in [n for n, owner in outputs.items() if owner == INFERRED
                     and n not in channels]:
            del outputs[node]
            changed = True
        for node in channels:
            if node not in outputs and node not in self.links and node not in self.devices:
                outputs[node] = INFERRED
                changed = True
        for node in learner.devices - self.heard:
            if node not in outputs:
                self.heard.add(node)
                changed = True
        if changed:
            self._changed()


    def node_map(self) -> dict[str, Any]:
        """What the decoder knows of the bus (given links and what it learned), as JSON."""
        return node_map_json(self.known, self.links)

    def load_node_map(self, doc: Any, where: str = "node map") -> None:
        """Start from a saved node map (``node_map()``); ValueError names what is wrong."""
        load_node_map(self.known, self.links, doc, where)
        self._changed()

    # -- describing -------------------------------------------------------------------------

    def _undecodable(self, base: dict[str, Any], reason: str,
                     raw: str | None = None) -> DecodedFrame:
        self.stats.undecodable += 1
        self.stats.by_function[UNDECODABLE] += 1
        if "node_id" in base:
            base["direction"] = TO_BA if base["arbitration_id"] >> 8 & 1 == 0 else FROM_BA
        if raw is None:
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
                    self.known.bound(msg.granted_node_id, DeviceKey(msg.vid, msg.pid, msg.serial))
            else:
                parts.append(f"asks for node {node}")
            parts.append(f"VID 0x{msg.vid:04X} PID 0x{msg.pid:04X} SN {msg.serial}")
        elif isinstance(msg, M.BulkData):
            error = self.bulk.packet(msg, parts)
        elif isinstance(msg, _PARAMETER_MESSAGES):
            value = getattr(msg, "value", b"")
            direction = self.known.direction(node, msg.channel, msg.param, value)
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

    def _link(self, node: int) -> Link:
        if node in self.links:
            out, ins = self.links[node]
            return out, tuple(ins)
        owner = self.outputs[node]
        if owner == INFERRED:  # its device and index not seen (inferred from traffic)
            fed = tuple(self.known.ref(d, i) for d, i in sorted(self.inputs.get(node, ())))
            return f"channel node {node}", fed
        dev, index = owner
        inputs = sorted(self.inputs.get(node, ()))
        ref = self.known.ref
        return ref(dev, index), tuple(ref(d, i) for d, i in inputs)

    # -- learning ---------------------------------------------------------------------------

    def _track(self, msg: M.Message, direction: Direction | None) -> None:
        """Learn from parameter traffic and follow bulk transfers."""
        node = msg.node_id
        if isinstance(msg, M.ConfigureGetBulkResponse | M.ConfigureSetBulk):
            ok = isinstance(msg, M.ConfigureSetBulk) or msg.code is ResponseCode.SUCCESS
            if ok:
                self.bulk.start(node, msg.mode, msg.param, msg.channel, msg.size)
        elif isinstance(msg, M.ConfigureSetBulkResponse) and msg.code is ResponseCode.FAILURE:
            self.bulk.refused(node)
        elif isinstance(msg, M.SetParameter):
            self.known.learn(node, msg.channel, msg.param, msg.value, direction)
        elif isinstance(msg, M.GetParameterResponse | M.SetParameterResponse):
            if msg.code is ResponseCode.SUCCESS and msg.value:
                self.known.learn(node, msg.channel, msg.param, msg.value, direction)


def plain_can_text(arbitration_id: int, data: bytes, *, extended: bool = False,
                   remote: bool = False, error: bool = False, fd: bool = False,
                   dlc: int | None = None) -> str:
    """A frame as plain CAN shows it: identifier (8 digits when extended), kind, data."""
    ident = f"{arbitration_id:08X}" if extended else f"{arbitration_id:03X}"
    hex_data = data.hex(" ").upper() or "(empty)"
    if error:
        return f"error frame  {hex_data}" if data else "error frame"
    if remote:
        return f"[{ident}] remote frame, DLC {len(data) if dlc is None else dlc}"
    return f"[{ident}] {'FD ' if fd else ''}{hex_data}"
