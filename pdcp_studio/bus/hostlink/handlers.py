"""The arbitrator's answers to host-link requests (docs/host-link.md §5), one method each.

Every request gets exactly one reply: ``code | 0x80``, a status byte, then the body (OK) or a
short reason (any other status). A handler never raises out: a malformed body is BAD_LENGTH,
an arbitrator error is mapped to the status that says why (the table in ``_status_of``).

State kept between requests is what a firmware keeps too, and as small: whether the PC has
greeted, one parameter value in transfer, one configuration being written (staged; committed
only whole with a matching CRC, by the memory's atomic double-buffered write), one change being
sent for TRANSACT_RUN (carried out by the arbitrator's own transaction: interlock, write, read
back, restore, release) and the last transaction's result for RESULT_READ.

While another arbitrator is heard on the bus (reference §5) the link is read-only: what the
tables hold (status, devices, links, the stored configuration, results) is answered, and every
request that would put a frame on the bus or change the prosthesis — parameters, links,
suspend, release, reset, a configuration commit, a transaction — is refused with status
OTHER_ARBITRATOR and the words why and until when.
"""

from __future__ import annotations

import logging
import struct
import time
from typing import TYPE_CHECKING, Any, Protocol

from pdcp_studio import __version__
from pdcp_studio.bus import events as ev
from pdcp_studio.bus.hostlink import records as hr
from pdcp_studio.bus.hostlink.change import MAX_CHANGE as _MAX_CHANGE
from pdcp_studio.errors import (
    BusTimeoutError,
    ConfigFormatError,
    FrameError,
    ModelError,
    PdcpError,
)
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.protocol import hostlink_messages as hm
from pdcp_studio.protocol.crc import crc16_ccitt_false
from pdcp_studio.protocol.hostlink import MAX_PAYLOAD
from pdcp_studio.protocol.hostlink_messages import Req, Status

if TYPE_CHECKING:
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.bus.hostlink.monitor import MonitorFeed

log = logging.getLogger(__name__)


class ServerState(Protocol):
    """What the handlers read of the server that owns them: its change and lost-event
    counters and its raw-frame monitor (``bus/hostlink/server.py``)."""

    changes: int
    events_lost: int
    monitor: MonitorFeed


#: Largest parameter value moved over the link (the arbitrator's value buffer).
MAX_VALUE = 512
#: Largest stored configuration accepted (the memory's slot).
MAX_CONFIG = 8192
#: Largest change accepted by TRANSACT (links, parameters, a configuration): the PC refuses a
#: larger one before sending it (``change.size_problem``).
MAX_CHANGE = _MAX_CHANGE
BUS_ERROR_KINDS = ("", "bad_frame", "error_frame", "duplicate_device", "node_ids_exhausted",
                   "setup", "plan", "transport", "other_arbitrator")
CAPABILITIES = hm.CAP_FULL
#: Requests that put frames on the bus or change the prosthesis: refused while another
#: arbitrator is heard (the link is read-only then).
_WRITES = frozenset({Req.GET_PARAM, Req.SET_PARAM, Req.ADD_LINK, Req.REMOVE_LINK, Req.SUSPEND,
                     Req.RELEASE, Req.RESET_DEVICE, Req.CONFIG_WRITE_COMMIT, Req.TRANSACT_RUN})


class Refused(Exception):
    """A handler's refusal: the status and the reason."""

    def __init__(self, status: Status, reason: str) -> None:
        super().__init__(reason)
        self.status = status


def _status_of(err: Exception) -> Status:
    from pdcp_studio.bus.arbitrator.reading.requests import DeviceRefusedError

    if isinstance(err, DeviceRefusedError):
        return Status.DEVICE_REFUSED
    if isinstance(err, BusTimeoutError):
        return Status.DEVICE_TIMEOUT
    if isinstance(err, ConfigFormatError):
        return Status.BAD_CONFIGURATION
    if isinstance(err, ModelError):
        return Status.MANAGED if "managed" in str(err) else Status.BAD_LINK
    if isinstance(err, FrameError):
        return Status.BAD_LENGTH
    if "not on the bus" in str(err):
        return Status.DEVICE_ABSENT
    return Status.INTERNAL


class Handlers:
    """The request handlers of one :class:`HostLinkServer`."""

    def __init__(self, arbitrator: Arbitrator, server: ServerState) -> None:
        self.arb = arbitrator
        self.server = server
        self.greeted = False
        self._value: tuple[tuple[int, ...], bytes] | None = None  # GET_PARAM in transfer
        self._setting: tuple[tuple[int, ...], int, bytearray] | None = None  # SET_PARAM
        self._staged: tuple[int, int, bytearray] | None = None  # total, crc, bytes
        self._change: tuple[int, int, bytearray] | None = None  # TRANSACT being sent
        self._result: bytes | None = None  # the last transaction's result
        self._table = {
            Req.HELLO: self.hello, Req.STATUS: self.status,
            Req.LIST_DEVICES: self.list_devices, Req.GET_DEVICE: self.get_device,
            Req.GET_CHANNELS: self.get_channels, Req.LIST_LINKS: self.list_links,
            Req.GET_PARAM: self.get_param, Req.SET_PARAM: self.set_param,
            Req.ADD_LINK: self.add_link, Req.REMOVE_LINK: self.remove_link,
            Req.SUSPEND: self.suspend, Req.RELEASE: self.release,
            Req.RESET_DEVICE: self.reset_device, Req.CONFIG_INFO: self.config_info,
            Req.CONFIG_READ: self.config_read, Req.CONFIG_WRITE_BEGIN: self.config_begin,
            Req.CONFIG_WRITE_CHUNK: self.config_chunk,
            Req.CONFIG_WRITE_COMMIT: self.config_commit,
            Req.TRANSACT_BEGIN: self.transact_begin, Req.TRANSACT_CHUNK: self.transact_chunk,
            Req.TRANSACT_RUN: self.transact_run, Req.RESULT_READ: self.result_read,
            Req.GET_POLICY: self.get_policy, Req.MONITOR: self.monitor,
            Req.ANCHOR_READ: self.anchor_read, Req.ANCHOR_WRITE: self.anchor_write,
        }

    # -- dispatch --------------------
    def handle(self, message: bytes) -> bytes | None:
        """The reply to one request (None for a message that is not a request)."""
        if not message:
            return None
        code, body = message[0], bytes(message[1:])
        if code & hm.REPLY or 0x40 <= code < 0x80:  # an event's or reply's code, from the PC
            return self._fail(code, Status.UNKNOWN_REQUEST,
                              f"0x{code:02X} is not a request code (requests are 0x01-0x3F)")
        try:
            request = Req(code)
        except ValueError:
            return self._fail(code, Status.UNKNOWN_REQUEST, f"unknown request 0x{code:02X}")
        if request is not Req.HELLO and not self.greeted:
            return self._fail(code, Status.NOT_GREETED, "send HELLO first")
        if request in _WRITES and getattr(self.arb, "yielded", False):
            if request is Req.CONFIG_WRITE_COMMIT:
                self._staged = None
            elif request is Req.TRANSACT_RUN:
                self._change = None
            return self._fail(code, Status.OTHER_ARBITRATOR, self._read_only(request))
        try:
            out = self._table[request](body)
        except Refused as err:
            return self._fail(code, err.status, str(err))
        except hm.MessageError as err:
            return self._fail(code, Status.BAD_LENGTH, f"{request.name}: {err}")
        except (PdcpError, ValueError, KeyError) as err:
            return self._fail(code, _status_of(err), f"{request.name}: {err}")
        except Exception as err:
            log.exception("host link: %s failed", request.name)
            return self._fail(code, Status.INTERNAL, f"{request.name}: {err}")
        reply = bytes([hm.reply_code(code), Status.OK]) + out
        if len(reply) > MAX_PAYLOAD:  # a bug here, never the PC's fault
            return self._fail(code, Status.INTERNAL, f"{request.name}: reply too long")
        return reply

    @staticmethod
    def _fail(code: int, status: Status, reason: str) -> bytes:
        return bytes([hm.reply_code(code), status]) + hm.short_text(reason, 200)

    def _read_only(self, request: Req) -> str:
        """Why ``request`` is refused while another arbitrator is heard, and until when."""
        claim = getattr(self.arb, "claim", None)
        if getattr(self.arb, "read_only", False) and claim is not None:
            until = (f"until the other's beacons have been gone for {claim.take_back_s:g} s "
                     f"and a random wait ({claim.take_back_wait_s:.1f} s in all; then this "
                     "arbitrator takes the bus back)")
        else:
            until = "for good"
        return (f"{request.name}: another bus arbitrator is on this bus: this arbitrator is "
                f"read-only {until}; nothing was sent or changed (reference §5)")

    def forget_host(self) -> None:
        """The PC is gone: what it was sending is dropped (a transaction already running
        finishes on its own — the arbitrator restores and releases by itself)."""
        self.greeted = False
        self._staged = self._change = self._setting = None

    # -- look-ups -------------------------------------------------------------------------------
    def _device(self, key: DeviceKey, present: bool = False) -> Any:
        device = self.arb.system().device(key)
        if device is None:
            raise Refused(Status.UNKNOWN_DEVICE, f"device {key} is not known to the arbitrator")
        if present and (not device.present or self.arb.node_id_of(key) is None):
            raise Refused(Status.DEVICE_ABSENT, f"device {key} is not on the bus")
        return device

    @staticmethod
    def _exact(body: bytes, size: int, what: str) -> None:
        if len(body) != size:
            raise hm.MessageError(f"{what} is {size} bytes, not {len(body)}")

    # -- hello and status --------------------
    def hello(self, body: bytes) -> bytes:
        hm.need(body, 1, "HELLO")
        if body[0] != hm.VERSION:
            self.greeted = False
            raise Refused(Status.VERSION,
                          f"this arbitrator speaks host-link version {hm.VERSION}, "
                          f"not version {body[0]}")
        self.greeted = True
        name = hm.short_text(f"pdcp-studio arbitrator {__version__}", 64)
        return hm.HELLO.pack(hm.VERSION, CAPABILITIES, MAX_PAYLOAD) + name

    def status(self, body: bytes) -> bytes:
        self._exact(body, 0, "STATUS")
        system = self.arb.system()
        flags = ((1 if self.arb.wait_settled(0) else 0) | (2 if self.arb.startup_done else 0)
                 | (4 if getattr(self.arb, "yielded", False) else 0))
        return hm.STATUS.pack(flags, min(len(system.devices), 255), len(system.links),
                              self.server.changes, self.server.events_lost & 0xFFFF)

    # -- tables --------------------
    def list_devices(self, body: bytes) -> bytes:
        self._exact(body, 2, "LIST_DEVICES")
        (start,) = struct.unpack("<H", body)
        devices = [d for _, d in sorted(self.arb.system().devices.items())]
        per = (hm.MAX_BODY - 1 - 4) // hm.DEVICE_ROW.size
        rows = b"".join(hr.pack_device_row(d) for d in devices[start:start + per])
        return struct.pack("<HH", len(devices), start) + rows

    def get_device(self, body: bytes) -> bytes:
        """The device's own parameters, then as much of its channel table as fits."""
        self._exact(body, hm.KEY.size, "GET_DEVICE")
        device = self._device(hr.unpack_key(body))
        info = hr.pack_device_info(device)
        channels = [device.channels[i] for i in sorted(device.channels)]
        page, _ = hr.pack_channel_page(channels, 0, room=hm.MAX_BODY - 1 - len(info))
        return info + page

    def get_channels(self, body: bytes) -> bytes:
        self._exact(body, hm.KEY.size + 1, "GET_CHANNELS")
        device = self._device(hr.unpack_key(body))
        channels = [device.channels[i] for i in sorted(device.channels)]
        page, _ = hr.pack_channel_page(channels, body[hm.KEY.size])
        return page

    def list_links(self, body: bytes) -> bytes:
        self._exact(body, 2, "LIST_LINKS")
        (start,) = struct.unpack("<H", body)
        links = sorted(self.arb.system().links)
        per = (hm.MAX_BODY - 1 - 4) // (2 * hm.REF.size)
        return (struct.pack("<HH", len(links), start)
                + b"".join(hr.pack_link(lk) for lk in links[start:start + per]))

    # -- parameters --------------------
    def get_param(self, body: bytes) -> bytes:
        self._exact(body, hm.PARAM.size + 2, "GET_PARAM")
        address = hm.PARAM.unpack_from(body)
        (offset,) = struct.unpack_from("<H", body, hm.PARAM.size)
        if offset == 0:
            key = DeviceKey(*address[:3])
            self._device(key, present=True)
            value = bytes(self.arb.get_parameter(key, address[4], address[3]))
            if len(value) > MAX_VALUE:
                raise Refused(Status.TOO_LARGE, f"the value is {len(value)} bytes, more than "
                                                f"this arbitrator moves ({MAX_VALUE})")
            self._value = (address, value)
        elif self._value is None or self._value[0] != address:
            raise Refused(Status.BAD_OFFSET, "read this parameter from offset 0 first")
        value = self._value[1]
        if offset > len(value):
            raise Refused(Status.BAD_OFFSET, f"offset {offset} is past the value's "
                                             f"{len(value)} bytes")
        return hm.SPAN.pack(offset, len(value)) + value[offset:offset + hm.CHUNK]

    def set_param(self, body: bytes) -> bytes:
        hm.need(body, hm.PARAM.size + hm.SPAN.size, "SET_PARAM")
        address = hm.PARAM.unpack_from(body)
        offset, total = hm.SPAN.unpack_from(body, hm.PARAM.size)
        chunk = body[hm.PARAM.size + hm.SPAN.size:]
        if total > MAX_VALUE:
            raise Refused(Status.TOO_LARGE, f"a value of {total} bytes is more than this "
                                            f"arbitrator moves ({MAX_VALUE})")
        if offset == 0:
            self._setting = (address, total, bytearray())
        setting = self._setting
        if setting is None or setting[0] != address or setting[1] != total:
            raise Refused(Status.NO_TRANSFER, "start the value at offset 0")
        if offset != len(setting[2]):
            raise Refused(Status.BAD_OFFSET, f"expected offset {len(setting[2])}, not {offset}")
        if offset + len(chunk) > total:
            raise Refused(Status.BAD_OFFSET, f"{offset + len(chunk)} bytes is past the value's "
                                             f"{total}")
        setting[2].extend(chunk)
        if len(setting[2]) < total:
            return struct.pack("<HB", len(setting[2]), 0)
        self._setting = None
        key = DeviceKey(*address[:3])
        self._device(key, present=True)
        self.arb.set_parameter(key, address[4], address[3], bytes(setting[2]))
        return struct.pack("<HB", total, 1)

    # -- links and devices --------------------
    def add_link(self, body: bytes) -> bytes:
        self._exact(body, 2 * hm.REF.size, "ADD_LINK")
        self.arb.add_link(hr.unpack_link(body))
        return b""

    def remove_link(self, body: bytes) -> bytes:
        self._exact(body, 2 * hm.REF.size, "REMOVE_LINK")
        self.arb.remove_link(hr.unpack_link(body))
        return b""

    def suspend(self, body: bytes) -> bytes:
        self._exact(body, hm.KEY.size + 2, "SUSPEND")
        key = hr.unpack_key(body)
        self._device(key, present=True)
        self.arb.suspend(key, int.from_bytes(body[6:8], "little"))
        return b""

    def release(self, body: bytes) -> bytes:
        self._exact(body, hm.KEY.size, "RELEASE")
        key = hr.unpack_key(body)
        self._device(key, present=True)
        self.arb.release(key)
        return b""

    def reset_device(self, body: bytes) -> bytes:
        self._exact(body, hm.KEY.size, "RESET_DEVICE")
        key = hr.unpack_key(body)
        self._device(key, present=True)
        self.arb.reset_device(key)
        return b""

    # -- the stored configuration --------------------
    def _stored(self) -> bytes:
        from pdcp_studio.storage import config_codec

        raw = getattr(self.arb.memory, "read_bytes", None)
        if raw is None:
            return config_codec.dumps(self.arb.read_memory())
        data = raw()
        return bytes(data) if data is not None else b""  # nothing stored: 0 bytes

    def config_info(self, body: bytes) -> bytes:
        self._exact(body, 0, "CONFIG_INFO")
        data = self._stored()
        return hm.CONFIG_INFO.pack(len(data), crc16_ccitt_false(data))

    def config_read(self, body: bytes) -> bytes:
        self._exact(body, 2, "CONFIG_READ")
        (offset,) = struct.unpack("<H", body)
        data = self._stored()
        if offset > len(data):
            raise Refused(Status.BAD_OFFSET, f"offset {offset} is past the stored "
                                             f"configuration's {len(data)} bytes")
        return (hm.CONFIG_INFO.pack(len(data), crc16_ccitt_false(data))
                + data[offset:offset + hm.CHUNK])

    def config_begin(self, body: bytes) -> bytes:
        self._exact(body, hm.CONFIG_INFO.size, "CONFIG_WRITE_BEGIN")
        total, crc = hm.CONFIG_INFO.unpack(body)
        if total > MAX_CONFIG:
            self._staged = None
            raise Refused(Status.TOO_LARGE, f"a configuration of {total} bytes does not fit "
                                            f"the memory ({MAX_CONFIG})")
        self._staged = (total, crc, bytearray())
        return b""

    def config_chunk(self, body: bytes) -> bytes:
        hm.need(body, 2, "CONFIG_WRITE_CHUNK")
        return self._chunk(self._staged, body, "configuration")

    def config_commit(self, body: bytes) -> bytes:
        from pdcp_studio.storage import config_codec

        self._exact(body, 0, "CONFIG_WRITE_COMMIT")
        staged, self._staged = self._staged, None
        data = self._whole(staged, "configuration")
        try:
            collection = config_codec.loads(data)
        except ConfigFormatError as err:
            raise Refused(Status.BAD_CONFIGURATION, f"{err}; nothing stored") from err
        try:
            self.arb.write_memory(collection)
        except (OSError, PdcpError) as err:
            raise Refused(Status.STORAGE, f"the memory write failed: {err}") from err
        stored = self._stored()
        return hm.CONFIG_INFO.pack(len(stored), crc16_ccitt_false(stored))

    # -- transactions (the change road, reference §5) ------------------------------------
    def transact_begin(self, body: bytes) -> bytes:
        self._exact(body, hm.CONFIG_INFO.size, "TRANSACT_BEGIN")
        total, crc = hm.CONFIG_INFO.unpack(body)
        if total > MAX_CHANGE:
            self._change = None
            raise Refused(Status.TOO_LARGE, f"a change of {total} bytes is more than this "
                                            f"arbitrator takes ({MAX_CHANGE})")
        self._change = (total, crc, bytearray())
        return b""

    def transact_chunk(self, body: bytes) -> bytes:
        hm.need(body, 2, "TRANSACT_CHUNK")
        return self._chunk(self._change, body, "change")

    def transact_run(self, body: bytes) -> bytes:
        """Carry the staged change out as one transaction; the reply is the result's size and
        CRC (RESULT_READ reads it)."""
        self._exact(body, 0, "TRANSACT_RUN")
        from pdcp_studio.bus.hostlink.change import decode_change, encode_result

        self._exact(body, 0, "TRANSACT_RUN")
        staged, self._change = self._change, None
        data = self._whole(staged, "change")
        change = decode_change(data)
        result = encode_result(self.arb.transact(change))
        self._result = result
        return hm.CONFIG_INFO.pack(len(result), crc16_ccitt_false(result))

    def result_read(self, body: bytes) -> bytes:
        self._exact(body, 2, "RESULT_READ")
        (offset,) = struct.unpack("<H", body)
        if self._result is None:
            raise Refused(Status.NO_TRANSFER, "no transaction result (TRANSACT_RUN first)")
        data = self._result
        if offset > len(data):
            raise Refused(Status.BAD_OFFSET, f"offset {offset} is past the result's "
                                             f"{len(data)} bytes")
        return (hm.CONFIG_INFO.pack(len(data), crc16_ccitt_false(data))
                + data[offset:offset + hm.CHUNK])

    def _chunk(self, staged: tuple[int, int, bytearray] | None, body: bytes,
               what: str) -> bytes:
        (offset,) = struct.unpack_from("<H", body)
        if staged is None:
            raise Refused(Status.NO_TRANSFER, f"no {what} is being sent (BEGIN first)")
        total, _, data = staged
        if offset > len(data):
            raise Refused(Status.BAD_OFFSET, f"expected offset {len(data)}, not {offset}")
        chunk = body[2:]
        if offset + len(chunk) > total:
            raise Refused(Status.BAD_OFFSET, f"{offset + len(chunk)} bytes is past the "
                                             f"announced {total}")
        data[offset:offset + len(chunk)] = chunk
        return struct.pack("<H", len(data))

    @staticmethod
    def _whole(staged: tuple[int, int, bytearray] | None, what: str) -> bytes:
        if staged is None:
            raise Refused(Status.NO_TRANSFER, f"no {what} is being sent (BEGIN first)")
        total, crc, data = staged
        if len(data) != total:
            raise Refused(Status.BAD_OFFSET, f"{len(data)} of {total} bytes received; "
                                             "nothing done")
        if crc16_ccitt_false(data) != crc:
            raise Refused(Status.CHECKSUM, f"CRC 0x{crc16_ccitt_false(data):04X} of the bytes "
                                           f"received is not the announced 0x{crc:04X}; "
                                           "nothing done")
        return bytes(data)

    # -- policy and monitor --------------------
    def get_policy(self, body: bytes) -> bytes:
        self._exact(body, 0, "GET_POLICY")
        return bytes([1 if self._autoconfigure() else 0])

    def _autoconfigure(self) -> bool:
        read = getattr(self.arb, "read_policy", None)
        if read is not None:
            return bool(read().autoconfigure)
        return bool(getattr(self.arb, "profile_layer", True))

    # -- the fitting history's anchor (issue 28) --------------------
    def anchor_read(self, body: bytes) -> bytes:
        self._exact(body, 0, "ANCHOR_READ")
        return hr.pack_anchor(self.arb.read_anchor())

    def anchor_write(self, body: bytes) -> bytes:
        self._exact(body, hr.ANCHOR_SIZE, "ANCHOR_WRITE")
        return hr.pack_anchor(self.arb.write_anchor(hr.unpack_anchor(body)))

    def monitor(self, body: bytes) -> bytes:
        self._exact(body, 2, "MONITOR")
        flags, period = body[0], max(body[1], 1)
        self.server.monitor.configure(bool(flags & 1), bool(flags & 2), period / 10.0,
                                      time.monotonic())
        return hm.MONITOR_REPLY.pack(self.server.monitor.budget_bytes_s)

    # -- events --------------------
    def event_message(self, event: object) -> bytes | None:
        """The EVENT message for an arbitrator event (None for what the link does not push)."""
        if isinstance(event, ev.DeviceJoined):
            return (bytes([hm.Event.DEVICE_JOINED]) + hr.pack_key(event.key)
                    + bytes([self.arb.node_id_of(event.key) or 0]))
        if isinstance(event, ev.DeviceReplaced):  # forgotten: no longer missing (§5.7)
            return (bytes([hm.Event.DEVICE_REPLACED]) + hr.pack_key(event.key)
                    + hr.pack_key(event.new))
        if isinstance(event, ev.DeviceLeft):  # why it left, when the arbitrator knows (§5.7)
            if not event.why and event.silent_s <= 0 and event.interval_s <= 0:
                return bytes([hm.Event.DEVICE_LEFT]) + hr.pack_key(event.key)
            return bytes([hm.Event.DEVICE_LEFT]) + hr.pack_left(
                event.key, event.silent_s, event.interval_s, event.why, 200)
        if isinstance(event, ev.LinkMade | ev.LinkRemoved):
            code = hm.Event.LINK_MADE if isinstance(event, ev.LinkMade) else hm.Event.LINK_REMOVED
            return bytes([code]) + hr.pack_link_event(
                event.link, self.arb.channel_node_id(event.link.output))
        if isinstance(event, ev.BusError):
            if event.kind == "other_arbitrator":
                return bytes([hm.Event.OTHER_ARBITRATOR]) + hm.short_text(event.message, 200)
            if event.kind in ("bad_frame", "error_frame"):
                return None  # the monitor counts these; too chatty for the line
            kind = BUS_ERROR_KINDS.index(event.kind) if event.kind in BUS_ERROR_KINDS else 0
            return bytes([hm.Event.BUS_ERROR, kind]) + hm.short_text(event.message, 200)
        if isinstance(event, ev.BusState) and event.state == "yielded":
            return bytes([hm.Event.OTHER_ARBITRATOR]) + hm.short_text(event.message, 200)
        if isinstance(event, ev.TransactionDone):
            from pdcp_studio.bus.hostlink.change import encode_result

            result = event.result
            return (bytes([hm.Event.TRANSACTION_DONE]) + encode_result(result)[:1]
                    + hm.short_text(result.action, 120))
        if isinstance(event, ev.TerminalsUnconnected):
            refs = event.refs[:24]
            return (bytes([hm.Event.TERMINALS_UNCONNECTED, len(refs)])
                    + b"".join(hm.REF.pack(*r) for r in refs) + hm.short_text(event.why, 60))
        return None
