"""A simulated PDCP device: the device side of the wire protocol (reference §1), no threads.

Built from a model Device; driven by a DeviceHost that owns the bus and the one thread many
devices share. The host calls :meth:`handle` with frames addressed to the device and
:meth:`on_data` with data for its inputs; the device answers through the host and asks it for
timers (beacons, bind retries, data ticks). Parameters live in ``nv`` — non-volatile, so a
re-plugged device still knows its sources — except the bus-session values in ``VOLATILE``
(node IDs, enabled flags), which power-on clears. Suspend stops data only; beacons go on so
the arbitrator does not take a suspended device for gone.
"""

from __future__ import annotations

import zlib
from collections.abc import Callable
from enum import Enum
from typing import Protocol

from pdcp_studio.bus.sim.signals import decode_sample, encode_sample, synthetic_value
from pdcp_studio.errors import FrameError, ParameterError
from pdcp_studio.model import param_fields
from pdcp_studio.model import parameters as P
from pdcp_studio.model.system import Device
from pdcp_studio.protocol import (
    Beacon,
    BindRequest,
    BindResponse,
    BulkData,
    BulkDataResponse,
    BulkReassembler,
    ChannelData,
    ConfigureGetBulk,
    ConfigureGetBulkResponse,
    ConfigureSetBulk,
    ConfigureSetBulkResponse,
    GetParameter,
    GetParameterResponse,
    Message,
    Mode,
    Release,
    ReleaseResponse,
    Reset,
    ResetResponse,
    ResponseCode,
    SetParameter,
    SetParameterResponse,
    Suspend,
    SuspendResponse,
    UpdateDataChannel,
    UpdateDataChannelResponse,
    packetize,
)

OK, FAIL, BULK = ResponseCode.SUCCESS, ResponseCode.FAILURE, ResponseCode.USE_BULK
#: Update Data Channel requests are repeated this often when unanswered.
UPDATE_RETRIES = 3
#: Data rate of enabled outputs when the simulator does not say otherwise.
DEFAULT_DATA_RATE_HZ = 20.0


class Host(Protocol):
    """What a device needs from the host that drives it."""

    def send_message(self, message: Message) -> None: ...
    def call_later(self, delay: float, fn: Callable[[], None]) -> None: ...
    def routing_changed(self) -> None: ...
    def now(self) -> float: ...


class State(Enum):
    OFF = "off"  # unplugged
    BINDING = "binding"
    BOUND = "bound"


def _param_table(device: Device) -> tuple[dict[tuple[int, int], bytes], set[tuple[int, int]]]:
    """(parameter, channel) → bytes for every parameter the device has, and the volatile keys
    (the model's values through the catalog's field mapping; a device with no descriptor
    of its own tells its name)."""
    nv = param_fields.parameter_table(device)
    nv[P.DEVICE_DESCRIPTOR, 0] = P.encode_value(P.device_parameter(P.DEVICE_DESCRIPTOR),
                                                device.descriptor or device.name)
    volatile = {(P.DEVICE_NODE_ID, 0)}
    for ch in device.channels.values():
        volatile.add((P.CH_DATA_ENABLED, ch.index))
        volatile.add((P.IN_SOURCE_NODE_IDS if ch.is_input else P.OUT_NODE_ID, ch.index))
    for key in volatile:  # power-on: no node IDs, nothing enabled
        nv[key] = bytes(len(nv[key]))
    return nv, volatile


class SimulatedDevice:
    """One device. All methods run on its host's thread (the host serializes them)."""

    def __init__(self, device: Device, *, data_rate_hz: float = DEFAULT_DATA_RATE_HZ,
                 packet_gap_s: float = 0.0) -> None:
        self.model = device
        self.key = device.key
        self.nv, self._volatile_keys = _param_table(device)
        self._defaults = {k: self.nv[k] for k in self._volatile_keys}
        self.preferred_node_id = device.node_id or 1
        self.data_rate_hz = data_rate_hz
        self.packet_gap_s = packet_gap_s  # > 0 slows bulk sends down (tests unplug mid-way)
        self.state = State.OFF
        self.node_id = 0
        self.suspended_until: float | None = None
        self.refuse_suspend = False  # tests: a device that refuses the motion interlock
        self.suspensions = 0  # Suspend Device requests honoured (renewals included)
        self.received: dict[int, tuple[bytes, float]] = {}  # input index → (data, time)
        self.frames_sent = 0
        self._host: Host | None = None
        self._epoch = 0  # bumped on power-off/reset: stale timers see it and do nothing
        self._requested = 0
        self._incoming: tuple[int, int, BulkReassembler] | None = None
        self._pending_updates: dict[int, int] = {}
        self._phase = (zlib.crc32(repr(self.key).encode()) % 1000) / 159.0

    # -- host interface ---------------------------------------------------------------
    def attach(self, host: Host) -> None:
        self._host = host

    @property
    def host(self) -> Host:
        if self._host is None:
            raise RuntimeError(f"device {self.key} is not attached to a host")
        return self._host

    def param(self, pid: int, channel: int = 0) -> bytes | None:
        return self.nv.get((pid, channel))

    def _int(self, pid: int, channel: int = 0) -> int:
        return int.from_bytes(self.nv.get((pid, channel), b"\0"), "little")

    def listening(self) -> dict[int, list[int]]:
        """Source channel node ID → enabled input indices (the host routes data by it)."""
        out: dict[int, list[int]] = {}
        if self.state is not State.BOUND:
            return out
        for ch in self.model.inputs():
            if self._int(P.CH_DATA_ENABLED, ch.index):
                source = self.nv[P.IN_SOURCE_NODE_IDS, ch.index][1]
                if source:
                    out.setdefault(source, []).append(ch.index)
        return out

    def send(self, message: Message) -> None:
        self.frames_sent += 1
        self.host.send_message(message)

    def _later(self, delay: float, fn: Callable[[], None]) -> None:
        epoch = self._epoch

        def run() -> None:
            if self._epoch == epoch and self.state is not State.OFF:
                fn()

        self.host.call_later(delay, run)

    # -- power ------------------------------------------------------------------------
    def power_on(self) -> None:
        """Plug in: volatile values back to defaults, then ask for a node ID."""
        self._epoch += 1
        self.nv.update(self._defaults)
        self.state, self.node_id = State.BINDING, 0
        self.suspended_until, self._incoming = None, None
        self.received.clear()
        self._requested = self.preferred_node_id
        self.host.routing_changed()
        self._send_bind()

    def power_off(self) -> None:
        """Unplug: silent at once; non-volatile parameters are kept."""
        self._epoch += 1
        self.state, self.node_id = State.OFF, 0
        self.host.routing_changed()

    def _send_bind(self) -> None:
        if self.state is not State.BINDING:
            return
        self.send(BindRequest(self._requested, self.key.vid, self.key.pid, self.key.serial))
        epoch = self._epoch
        timeout = max(self._int(P.DEVICE_BIND_TIMEOUT), 5) / 1000.0

        def retry() -> None:
            if self._epoch == epoch:
                self._send_bind()

        self._later(timeout, retry)

    def _bound(self, node_id: int) -> None:
        self._epoch += 1  # cancels the bind retry
        self.state, self.node_id = State.BOUND, node_id
        self.preferred_node_id = node_id
        self.nv[P.DEVICE_NODE_ID, 0] = bytes([node_id])
        self.host.routing_changed()
        self._beacon()
        self._stream_tick()
        for ch in self.model.inputs():
            self._pending_updates[ch.index] = UPDATE_RETRIES
            self._request_update(ch.index)

    def _beacon(self) -> None:
        self.send(Beacon(self.node_id))
        self._later(max(self._int(P.DEVICE_BEACON_INTERVAL), 5) / 1000.0, self._beacon)

    def _request_update(self, index: int) -> None:
        left = self._pending_updates.get(index, 0)
        if left <= 0:
            self._pending_updates.pop(index, None)
            return
        self._pending_updates[index] = left - 1
        self.send(UpdateDataChannel(self.node_id, index))
        wait = max(self._int(P.DEVICE_ACK_TIMEOUT), 5) / 1000.0 * 4
        self._later(wait, lambda: self._request_update(index))

    # -- data -------------------------------------------------------------------------
    def _stream_tick(self) -> None:
        now = self.host.now()
        if self.suspended_until is not None and now >= self.suspended_until:
            self.suspended_until = None
        if self.suspended_until is None:
            for ch in self.model.outputs():
                node = self._int(P.OUT_NODE_ID, ch.index)
                if node and self._int(P.CH_DATA_ENABLED, ch.index):
                    self.send_data(ch.index, node, self._output_value(ch.index, now))
        if self.data_rate_hz > 0 and self.model.outputs():
            self._later(1.0 / self.data_rate_hz, self._stream_tick)

    def _output_value(self, index: int, now: float) -> float:
        ch = self.model.channels[index]
        for source in ch.required_inputs:  # a computed output forwards what it receives
            got = self.received.get(source)
            if got is not None:
                kind = int.from_bytes(self.nv[P.IN_SOURCE_TYPE_PROFILE, source][:2], "little")
                return decode_sample(kind or ch.type, got[0])
        return synthetic_value(ch, now, self._phase)

    def send_data(self, index: int, node_id: int, value: float) -> None:
        kind = int.from_bytes(self.nv[P.CH_TYPE_PROFILE, index][:2], "little")
        self.send(ChannelData(node_id, encode_sample(kind, value)))

    def on_data(self, index: int, data: bytes, when: float) -> None:
        """Data from the source of enabled input ``index``: kept as received."""
        self.received[index] = (bytes(data), when)

    # -- requests ---------------------------------------------------------------------
    def handle(self, msg: Message) -> None:
        """A frame addressed to this device (its node ID, broadcast, or a bind answer)."""
        if isinstance(msg, BindResponse):
            if self.state is State.BINDING and msg.node_id == self._requested:
                if msg.accepted:
                    self._bound(msg.granted_node_id)
                else:
                    self._requested = msg.granted_node_id
                    self._epoch += 1
                    self._send_bind()
            return
        if self.state is not State.BOUND:
            return
        match msg:
            case GetParameter():
                self._on_get(msg)
            case SetParameter():
                self._on_set(msg)
            case ConfigureGetBulk():
                self._on_get_bulk(msg)
            case ConfigureSetBulk():
                self._on_set_bulk(msg)
            case BulkData():
                self._on_bulk_data(msg)
            case Suspend():
                self._on_suspend(msg)
            case Release():
                self._on_release(msg)
            case Reset():
                self._on_reset(msg)
            case UpdateDataChannelResponse():
                self._on_update_response(msg)

    def _spec(self, pid: int, channel: int) -> P.ParameterSpec | None:
        if channel == 0:
            return P.find_parameter(pid, 0)
        ch = self.model.channels.get(channel)
        return None if ch is None else P.find_parameter(pid, channel, ch.direction)

    def _on_get(self, msg: GetParameter) -> None:
        value = self.nv.get((msg.param, msg.channel))
        if value is None:
            code, data = FAIL, b""
        elif len(value) > P.MAX_INLINE_SIZE:
            code, data = BULK, b""
        else:
            code, data = OK, value
        self.send(GetParameterResponse(self.node_id, code, msg.param, msg.channel, data))

    def _accept(self, pid: int, channel: int, value: bytes) -> bool:
        """Store a written value if the catalog allows it; apply its side effects."""
        spec = self._spec(pid, channel)
        if spec is None or not spec.writable or (pid, channel) not in self.nv:
            return False
        try:
            P.decode_value(spec, value)
        except ParameterError:
            return False
        self.nv[pid, channel] = bytes(value)
        if channel == 0 and pid == P.DEVICE_NODE_ID and value[0]:
            self._later(0.0, lambda: self._renumber(value[0]))
        if channel and pid in (P.CH_DATA_ENABLED, P.IN_SOURCE_NODE_IDS):
            self.host.routing_changed()
        return True

    def _renumber(self, node_id: int) -> None:
        self.node_id = self.preferred_node_id = node_id
        self.host.routing_changed()

    def _on_set(self, msg: SetParameter) -> None:
        code = OK if self._accept(msg.param, msg.channel, msg.value) else FAIL
        self.send(SetParameterResponse(self.node_id, code, msg.param, msg.channel, msg.value))

    def _on_get_bulk(self, msg: ConfigureGetBulk) -> None:
        value = self.nv.get((msg.param, msg.channel))
        if value is None:
            self.send(ConfigureGetBulkResponse(self.node_id, FAIL, msg.param, msg.channel, 0))
            return
        self.send(ConfigureGetBulkResponse(self.node_id, OK, msg.param, msg.channel, len(value)))
        packets = packetize(value)

        def send_from(i: int) -> None:
            if i < len(packets) and self.state is State.BOUND:
                pkt = packets[i]
                self.send(BulkData(self.node_id, pkt.packet_id, pkt.data, mode=Mode.DEVICE))
                self._later(self.packet_gap_s, lambda: send_from(i + 1))

        if self.packet_gap_s > 0:
            send_from(0)
        else:
            for pkt in packets:
                self.send(BulkData(self.node_id, pkt.packet_id, pkt.data, mode=Mode.DEVICE))

    def _on_set_bulk(self, msg: ConfigureSetBulk) -> None:
        spec = self._spec(msg.param, msg.channel)
        ok = (spec is not None and spec.writable and (msg.param, msg.channel) in self.nv
              and 0 < msg.size <= spec.size)
        self._incoming = (msg.param, msg.channel, BulkReassembler(msg.size)) if ok else None
        self.send(ConfigureSetBulkResponse(self.node_id, OK if ok else FAIL, msg.param,
                                           msg.channel, msg.size))

    def _on_bulk_data(self, msg: BulkData) -> None:
        if msg.mode is not Mode.ARBITRATOR or self._incoming is None:
            return
        pid, channel, collector = self._incoming
        try:
            done = collector.add(msg.packet_id, msg.data)
        except FrameError:
            self._incoming = None
            self.send(BulkDataResponse(self.node_id, FAIL, mode=Mode.DEVICE))
            return
        if done:
            self._incoming = None
            ok = self._accept(pid, channel, collector.result())
            self.send(BulkDataResponse(self.node_id, OK if ok else FAIL, mode=Mode.DEVICE))

    def _on_suspend(self, msg: Suspend) -> None:
        """Hold the outputs' data for TimeValue ms (0: until released); a renewal restarts
        the bound. ``refuse_suspend`` answers failure (a device that cannot stop safely)."""
        if self.refuse_suspend:
            self.send(SuspendResponse(self.node_id, FAIL, msg.ms))
            return
        now = self.host.now()
        self.suspended_until = now + msg.ms / 1000.0 if msg.ms else float("inf")
        self.suspensions += 1
        self.send(SuspendResponse(self.node_id, OK, msg.ms))

    def _on_release(self, msg: Release) -> None:
        self.suspended_until = None
        self.send(ReleaseResponse(self.node_id, OK))

    def _on_reset(self, msg: Reset) -> None:
        self.send(ResetResponse(self.node_id, OK))
        self._later(0.002, self.power_on)

    def _on_update_response(self, msg: UpdateDataChannelResponse) -> None:
        self._pending_updates.pop(msg.channel, None)

