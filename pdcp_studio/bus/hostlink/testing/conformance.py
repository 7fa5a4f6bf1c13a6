"""The host-link conformance suite: what ``pdcp-studio hostlink-test`` runs against an arbitrator.

For a firmware author: every case drives the link with raw frames (its own sequence numbers,
ACKs withheld or damaged on purpose), so it checks the arbitrator's side of docs/host-link.md,
not PDCP Studio's client. Nothing it does changes the prosthesis: writes put back what was
read (the same Beacon Interval, the same stored configuration), refused writes are refused by
design, and the one transaction is empty.

Each case returns nothing (pass), raises :class:`CaseFailed` saying what was expected and
what came, or :class:`CaseSkipped` when it tests a capability the arbitrator's HELLO does not
declare (docs/host-link.md §7: the lean profile may leave the monitor, transactions, the
policy and bulk parameters out). ``run_suite(port)`` runs them all in order, one greeting each
where needed.
"""

from __future__ import annotations

import struct
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from pdcp_studio.bus.hostlink import records as hr
from pdcp_studio.bus.hostlink.port import Port, read_available
from pdcp_studio.protocol import hostlink_messages as hm
from pdcp_studio.protocol.crc import crc16_ccitt_false
from pdcp_studio.protocol.hostlink import Frame, FrameReader, Kind, cobs_encode
from pdcp_studio.protocol.hostlink_link import MAX_ATTEMPTS
from pdcp_studio.protocol.hostlink_messages import Req, Status
from pdcp_studio.protocol.hostlink_v1 import PING as V1_PING
from pdcp_studio.protocol.hostlink_v1 import V1Sniffer, encode_v1

# Device parameters the cases use (reference §1; model/parameters.py), by their numbers.
DEVICE_DESCRIPTOR = 7
DEVICE_NODE_ID = 8
DEVICE_BEACON_INTERVAL = 10
#: Seconds to wait for a frame the arbitrator must send.
WAIT_S = 2.0
#: Seconds within which the arbitrator must have given up an unacknowledged reply
#: (8 sends, 0.25 s apart, and slack).
GIVE_UP_S = 4.0


class CaseFailed(Exception):
    """A conformance case failed; the message says what was expected and what came."""


class CaseSkipped(Exception):
    """The case tests a capability the arbitrator does not declare in HELLO."""


#: The capability each optional case needs (the HELLO reply's bits, docs/host-link.md §4).
CAPABILITY_NAMES = {hm.CAP_MONITOR: "monitor", hm.CAP_TRANSACTIONS: "transactions",
                    hm.CAP_POLICY: "policy", hm.CAP_PARAM_BULK: "bulk parameters"}


@dataclass
class SuiteResult:
    passed: list[str] = field(default_factory=list)
    failed: list[str] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)
    why: dict[str, str] = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return not self.failed

    def to_json(self) -> dict[str, Any]:
        return {"passed": list(self.passed), "failed": list(self.failed),
                "skipped": list(self.skipped), "why": dict(self.why)}


class RawLink:
    """The host's end driven by hand: explicit sequence numbers, ACKs sent or withheld."""

    def __init__(self, port: Port) -> None:
        self.port = port
        self.reader = FrameReader()
        self.seq = 0
        self.pending: list[Frame] = []

    def write(self, data: bytes) -> None:
        self.port.write(data)

    def frames(self, timeout: float) -> list[Frame]:
        """Every frame that arrives within ``timeout`` (garbled ones left out)."""
        out = self.pending
        self.pending = []
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            for item in self.reader.feed(read_available(self.port)):
                if isinstance(item, Frame):
                    out.append(item)
        return out

    def next_frame(self, kinds: tuple[Kind, ...], timeout: float = WAIT_S) -> Frame | None:
        deadline = time.monotonic() + timeout
        while True:
            while self.pending:
                frame = self.pending.pop(0)
                if frame.kind in kinds:
                    return frame
            if time.monotonic() >= deadline:
                return None
            for item in self.reader.feed(read_available(self.port)):
                if isinstance(item, Frame):
                    self.pending.append(item)

    def reset(self) -> None:
        self.write(b"\x00" + Frame(Kind.RESET, 0).encode())
        self.seq = 0
        time.sleep(0.05)
        self.frames(0.05)  # drop what was on its way before the reset

    def send(self, message: bytes, seq: int | None = None) -> int:
        seq = self.seq if seq is None else seq
        self.write(Frame(Kind.DATA, seq, message).encode())
        if seq == self.seq:
            self.seq = (self.seq + 1) & 0xFF
        return seq

    def reply(self, code: int, timeout: float = WAIT_S, ack: bool = True) -> tuple[Frame, Status,
                                                                                   bytes]:
        """The reply DATA frame to request ``code`` (events before it are ACKed and skipped)."""
        deadline = time.monotonic() + timeout
        while True:
            frame = self.next_frame((Kind.DATA,), max(deadline - time.monotonic(), 0.0))
            if frame is None:
                raise CaseFailed(f"no reply to request 0x{code:02X} within {timeout:g} s")
            is_reply = frame.payload[:1] == bytes([hm.reply_code(code)])
            if ack or not is_reply:
                self.write(Frame(Kind.ACK, frame.seq).encode())
            if is_reply:
                if len(frame.payload) < 2:
                    raise CaseFailed(f"a reply of {len(frame.payload)} bytes has no status")
                try:
                    status = Status(frame.payload[1])
                except ValueError as err:
                    raise CaseFailed(f"status 0x{frame.payload[1]:02X} is not in the "
                                     "table") from err
                return frame, status, frame.payload[2:]

    def request(self, code: int, body: bytes = b"", timeout: float = WAIT_S) -> tuple[Status,
                                                                                     bytes]:
        self.send(bytes([code]) + body)
        _, status, out = self.reply(code, timeout)
        return status, out

    def hello(self) -> int:
        """RESET and HELLO; the capabilities the arbitrator declares."""
        self.reset()
        status, body = self.request(Req.HELLO, bytes([hm.VERSION, 0xFF, 0xFF]))
        if status is not Status.OK:
            raise CaseFailed(f"HELLO version {hm.VERSION} answered {status.name}: "
                             f"{hm.text(body)}")
        if len(body) < hm.HELLO.size:
            raise CaseFailed(f"HELLO reply of {len(body)} bytes, needs {hm.HELLO.size}")
        return int(hm.HELLO.unpack_from(body)[1])


def expect(status: Status, body: bytes, wanted: Status, what: str) -> bytes:
    if status is not wanted:
        raise CaseFailed(f"{what}: expected {wanted.name}, got {status.name} "
                         f"({hm.text(body) if status is not Status.OK else body.hex()})")
    if wanted is not Status.OK and not body:
        raise CaseFailed(f"{what}: the {wanted.name} reply carries no reason")
    return body


class Suite:
    """The cases, in the order they run; ``self.link`` is greeted before each request case."""

    def __init__(self, port: Port) -> None:
        self.link = RawLink(port)
        self.device: hr.DeviceRow | None = None
        self.capabilities: int | None = None

    def _needs(self, capability: int) -> None:
        """CaseSkipped unless the HELLO declares ``capability``."""
        if self.capabilities is None:
            self.capabilities = self.link.hello()
        if not self.capabilities & capability:
            raise CaseSkipped(f"the HELLO does not declare {CAPABILITY_NAMES[capability]} "
                              f"(capabilities 0x{self.capabilities:04X})")

    # -- the handshake ---------------------------------------------------------------------
    def case_hello(self) -> None:
        self.link.reset()
        status, body = self.link.request(Req.HELLO, bytes([hm.VERSION, 0xFF, 0xFF]))
        expect(status, body, Status.OK, "HELLO")
        if len(body) < hm.HELLO.size:
            raise CaseFailed(f"HELLO reply of {len(body)} bytes, needs {hm.HELLO.size}")
        version, self.capabilities, largest = hm.HELLO.unpack_from(body)
        if version != hm.VERSION or largest > 255:
            raise CaseFailed(f"HELLO reply: version {version}, largest payload {largest}")

    def case_unknown_version(self) -> None:
        self.link.reset()
        status, body = self.link.request(Req.HELLO, bytes([hm.VERSION + 7, 0, 0]))
        expect(status, body, Status.VERSION, "HELLO with an unknown version")
        status, body = self.link.request(Req.STATUS)
        expect(status, body, Status.NOT_GREETED, "a request after a refused HELLO")

    def case_not_greeted(self) -> None:
        self.link.reset()
        status, body = self.link.request(Req.LIST_DEVICES, b"\x00\x00")
        expect(status, body, Status.NOT_GREETED, "a request before HELLO")

    # -- the link layer --------------------------------------------------------------------------
    def case_bad_crc(self) -> None:
        self.link.hello()
        raw = bytes([Kind.DATA, self.link.seq, 1, Req.STATUS])
        crc = crc16_ccitt_false(raw) ^ 0x0101
        self.link.write(cobs_encode(raw + crc.to_bytes(2, "big")) + b"\x00")
        nak = self.link.next_frame((Kind.NAK, Kind.DATA))
        if nak is None or nak.kind is not Kind.NAK or nak.seq != self.link.seq:
            raise CaseFailed(f"a bad CRC: expected NAK({self.link.seq}), got {nak}")
        expect(*self.link.request(Req.STATUS), Status.OK, "the request after a bad CRC")

    def case_garbage_resync(self) -> None:
        """Garbage, then a request glued to more garbage (lost: NAK), then the same request
        again: answered once."""
        self.link.hello()
        self.link.write(bytes(range(1, 120)) + b"\x00\x7f\x00" + bytes(range(200, 256)))
        seq = self.link.send(bytes([Req.STATUS]))
        nak = self.link.next_frame((Kind.NAK,))
        if nak is None or nak.seq != seq:
            raise CaseFailed(f"a frame behind garbage: expected NAK({seq}), got {nak}")
        self.link.send(bytes([Req.STATUS]), seq=seq)
        expect(*self.link.reply(Req.STATUS)[1:], Status.OK, "the request sent again")

    def case_oversize_frame(self) -> None:
        self.link.hello()
        self.link.write(b"\x41" * 600 + b"\x00")
        nak = self.link.next_frame((Kind.NAK,))
        if nak is None:
            raise CaseFailed("an oversize frame: expected a NAK")
        expect(*self.link.request(Req.STATUS), Status.OK, "a request after an oversize frame")

    def case_out_of_order(self) -> None:
        self.link.hello()
        self.link.send(bytes([Req.STATUS]), seq=(self.link.seq + 5) & 0xFF)
        nak = self.link.next_frame((Kind.NAK, Kind.DATA, Kind.ACK))
        if nak is None or nak.kind is not Kind.NAK or nak.seq != self.link.seq:
            raise CaseFailed(f"a frame out of sequence: expected NAK({self.link.seq}), "
                             f"got {nak}")

    def case_lost_ack_no_second_execution(self) -> None:
        self.link.hello()
        message = bytes([Req.STATUS])
        seq = self.link.send(message)
        self.link.reply(Req.STATUS)
        self.link.send(message, seq=seq)  # as if the arbitrator's ACK had been lost
        frames = self.link.frames(0.6)
        acks = [f for f in frames if f.kind is Kind.ACK and f.seq == seq]
        replies = [f for f in frames if f.kind is Kind.DATA
                   and f.payload[:1] == bytes([hm.reply_code(Req.STATUS)])]
        if not acks or replies:
            raise CaseFailed(f"a repeated frame: expected ACK({seq}) and no second reply, got "
                             f"{len(acks)} ACK(s) and {len(replies)} reply(ies)")

    def case_retransmission(self) -> None:
        self.link.hello()
        self.link.send(bytes([Req.STATUS]))
        first, _, _ = self.link.reply(Req.STATUS, ack=False)
        again = self.link.next_frame((Kind.DATA,), 1.5)
        if again is None or again.seq != first.seq or again.payload != first.payload:
            raise CaseFailed("an unacknowledged reply: expected it again with the same seq")
        self.link.write(Frame(Kind.NAK, (first.seq + 1) & 0xFF).encode())  # "I have it"
        self.link.write(Frame(Kind.ACK, first.seq).encode())
        expect(*self.link.request(Req.STATUS), Status.OK, "the request after a retransmission")

    def case_nak_retransmits_at_once(self) -> None:
        self.link.hello()
        self.link.send(bytes([Req.STATUS]))
        first, _, _ = self.link.reply(Req.STATUS, ack=False)
        t0 = time.monotonic()
        self.link.write(Frame(Kind.NAK, first.seq).encode())
        again = self.link.next_frame((Kind.DATA,), 0.2)
        if again is None or again.seq != first.seq:
            raise CaseFailed("a NAK: expected the reply again within 0.2 s")
        self.link.write(Frame(Kind.ACK, first.seq).encode())
        del t0

    def case_timeouts_bounded(self) -> None:
        """An unacknowledged reply is sent a bounded number of times, then the PC is
        forgotten (the next request without HELLO is NOT_GREETED)."""
        self.link.hello()
        self.link.send(bytes([Req.STATUS]))
        self.link.reply(Req.STATUS, ack=False)
        frames = self.link.frames(GIVE_UP_S)
        sends = 1 + len([f for f in frames if f.kind is Kind.DATA])
        if sends != MAX_ATTEMPTS:
            raise CaseFailed(f"an unacknowledged reply was sent {sends} times in "
                             f"{GIVE_UP_S:g} s (docs/host-link.md §3: exactly "
                             f"{MAX_ATTEMPTS} sends, then given up)")
        status, body = self.link.request(Req.STATUS)
        expect(status, body, Status.NOT_GREETED, "a request after the arbitrator gave up")

    # -- requests ----------------------------------------------------------------------------------
    def case_status(self) -> None:
        self.link.hello()
        body = expect(*self.link.request(Req.STATUS), Status.OK, "STATUS")
        if len(body) != hm.STATUS.size:
            raise CaseFailed(f"STATUS reply of {len(body)} bytes, not {hm.STATUS.size}")

    def case_list_devices(self) -> None:
        self.link.hello()
        body = expect(*self.link.request(Req.LIST_DEVICES, b"\x00\x00"), Status.OK,
                      "LIST_DEVICES")
        total, start = struct.unpack_from("<HH", body)
        rows = hr.unpack_device_rows(body[4:])
        if start != 0 or len(rows) > total:
            raise CaseFailed(f"LIST_DEVICES: start {start}, {len(rows)} rows of {total}")
        present = [r for r in rows if r.present and r.node_id]
        self.device = present[0] if present else None

    def _need_device(self) -> hr.DeviceRow:
        if self.device is None:
            self.case_list_devices()
        if self.device is None:
            raise CaseFailed("no device is on the bus (cases that read a device need one)")
        return self.device

    def case_get_device(self) -> None:
        row = self._need_device()
        self.link.hello()
        body = expect(*self.link.request(Req.GET_DEVICE, hr.pack_key(row.key)), Status.OK,
                      "GET_DEVICE")
        _, count, used = hr.unpack_device_info(row.key, body)
        hr.unpack_channel_page(body[used:])
        if count != row.channels:
            raise CaseFailed(f"GET_DEVICE: {count} channels, LIST_DEVICES said {row.channels}")

    def case_get_channels(self) -> None:
        row = self._need_device()
        self.link.hello()
        body = expect(*self.link.request(Req.GET_CHANNELS, hr.pack_key(row.key) + b"\x00"),
                      Status.OK, "GET_CHANNELS")
        channels, _ = hr.unpack_channel_page(body)
        if row.channels and not channels:
            raise CaseFailed("GET_CHANNELS from 0 returned no channel")

    def case_list_links(self) -> None:
        self.link.hello()
        body = expect(*self.link.request(Req.LIST_LINKS, b"\x00\x00"), Status.OK, "LIST_LINKS")
        if (len(body) - 4) % (2 * hm.REF.size):
            raise CaseFailed(f"LIST_LINKS: {len(body) - 4} bytes are not whole links")

    def case_get_param_bulk(self) -> None:
        self._needs(hm.CAP_PARAM_BULK)
        row = self._need_device()
        self.link.hello()
        address = hm.PARAM.pack(*row.key, 0, DEVICE_DESCRIPTOR)
        body = expect(*self.link.request(Req.GET_PARAM, address + b"\x00\x00", 3.0), Status.OK,
                      "GET_PARAM")
        offset, total = hm.SPAN.unpack_from(body)
        if offset != 0 or len(body) - hm.SPAN.size > min(total, hm.CHUNK):
            raise CaseFailed(f"GET_PARAM: offset {offset}, {len(body) - 4} bytes of {total}")

    def case_set_param_same_value(self) -> None:
        row = self._need_device()
        self.link.hello()
        address = hm.PARAM.pack(*row.key, 0, DEVICE_BEACON_INTERVAL)  # written back as it is
        body = expect(*self.link.request(Req.GET_PARAM, address + b"\x00\x00", 3.0), Status.OK,
                      "GET_PARAM Beacon Interval")
        value = body[hm.SPAN.size:]
        expect(*self.link.request(Req.SET_PARAM, address + hm.SPAN.pack(0, len(value)) + value,
                                  3.0), Status.OK, "SET_PARAM of the same value")

    def case_suspend_release(self) -> None:
        row = self._need_device()
        self.link.hello()
        expect(*self.link.request(Req.SUSPEND, hr.pack_key(row.key) + struct.pack("<H", 200),
                                  3.0), Status.OK, "SUSPEND for 200 ms")
        expect(*self.link.request(Req.RELEASE, hr.pack_key(row.key), 3.0), Status.OK,
               "RELEASE")

    def case_config_read(self) -> None:
        self.link.hello()
        info = expect(*self.link.request(Req.CONFIG_INFO), Status.OK, "CONFIG_INFO")
        length, crc = hm.CONFIG_INFO.unpack(info)
        data = bytearray()
        while len(data) < length:
            body = expect(*self.link.request(Req.CONFIG_READ, struct.pack("<H", len(data))),
                          Status.OK, f"CONFIG_READ at {len(data)}")
            if not body[4:]:
                break
            data += body[4:]
        if len(data) != length or crc16_ccitt_false(data) != crc:
            raise CaseFailed(f"CONFIG_READ: {len(data)} bytes, CRC "
                             f"0x{crc16_ccitt_false(data):04X}; CONFIG_INFO said {length} "
                             f"bytes, 0x{crc:04X}")
        self.stored = bytes(data)

    def case_config_write_same(self) -> None:
        if not hasattr(self, "stored"):
            self.case_config_read()
        data = self.stored
        self.link.hello()
        if not data:
            return  # nothing stored: nothing to write back (the commit path is checked below)
        expect(*self.link.request(Req.CONFIG_WRITE_BEGIN,
                                  hm.CONFIG_INFO.pack(len(data), crc16_ccitt_false(data))),
               Status.OK, "CONFIG_WRITE_BEGIN")
        for offset in range(0, len(data), hm.CHUNK):
            expect(*self.link.request(Req.CONFIG_WRITE_CHUNK, struct.pack("<H", offset)
                                      + data[offset:offset + hm.CHUNK]), Status.OK,
                   f"CONFIG_WRITE_CHUNK at {offset}")
        body = expect(*self.link.request(Req.CONFIG_WRITE_COMMIT, timeout=5.0), Status.OK,
                      "CONFIG_WRITE_COMMIT")
        if hm.CONFIG_INFO.unpack(body) != (len(data), crc16_ccitt_false(data)):
            raise CaseFailed("CONFIG_WRITE_COMMIT: the stored length and CRC differ")

    def case_get_policy(self) -> None:
        self._needs(hm.CAP_POLICY)
        self.link.hello()
        body = expect(*self.link.request(Req.GET_POLICY), Status.OK, "GET_POLICY")
        if len(body) != 1:
            raise CaseFailed(f"GET_POLICY reply of {len(body)} bytes, not 1")

    def case_monitor(self) -> None:
        self._needs(hm.CAP_MONITOR)
        self.link.hello()
        expect(*self.link.request(Req.MONITOR, b"\x03\x05"), Status.OK, "MONITOR on")
        expect(*self.link.request(Req.MONITOR, b"\x00\x0a"), Status.OK, "MONITOR off")

    def case_transact_empty(self) -> None:
        self._needs(hm.CAP_TRANSACTIONS)
        self.link.hello()
        change = b"\x0bconformance" + b"\x00\x00" + b"\x00" + b"\x00" + b"\xff"
        expect(*self.link.request(Req.TRANSACT_BEGIN, hm.CONFIG_INFO.pack(
            len(change), crc16_ccitt_false(change))), Status.OK, "TRANSACT_BEGIN")
        expect(*self.link.request(Req.TRANSACT_CHUNK, b"\x00\x00" + change), Status.OK,
               "TRANSACT_CHUNK")
        body = expect(*self.link.request(Req.TRANSACT_RUN, timeout=10.0), Status.OK,
                      "TRANSACT_RUN of an empty change")
        length, crc = hm.CONFIG_INFO.unpack(body)
        result = expect(*self.link.request(Req.RESULT_READ, b"\x00\x00"), Status.OK,
                        "RESULT_READ")
        data = result[4:]
        if length <= hm.CHUNK and (len(data) != length or crc16_ccitt_false(data) != crc):
            raise CaseFailed("RESULT_READ: the result does not match its length and CRC")

    # -- error replies --------------------
    def case_unknown_request(self) -> None:
        self.link.hello()
        for code in (0x3E, 0x40, 0x7F, 0xC1):  # a free request code, an event's, a reply's
            expect(*self.link.request(code), Status.UNKNOWN_REQUEST, f"request 0x{code:02X}")

    def case_bad_length(self) -> None:
        self.link.hello()
        expect(*self.link.request(Req.GET_DEVICE, b"\x01\x02\x03"), Status.BAD_LENGTH,
               "GET_DEVICE with 3 bytes")
        for code in (Req.STATUS, Req.LIST_DEVICES, Req.CONFIG_INFO):  # one byte too many
            body = b"\x00\x00\x00" if code is Req.LIST_DEVICES else b"\x00"
            expect(*self.link.request(code, body), Status.BAD_LENGTH,
                   f"{code.name} with {len(body)} bytes")

    def case_unknown_device(self) -> None:
        self.link.hello()
        expect(*self.link.request(Req.GET_DEVICE, b"\xfe\xff\xfe\xff\xfe\xff"),
               Status.UNKNOWN_DEVICE, "GET_DEVICE of a device nobody has")

    def case_bad_link(self) -> None:
        self.link.hello()
        ghost = b"\xfe\xff\xfe\xff\xfe\xff\x01" * 2
        status, _ = self.link.request(Req.ADD_LINK, ghost, 3.0)
        if status not in (Status.BAD_LINK, Status.UNKNOWN_DEVICE):
            raise CaseFailed(f"ADD_LINK of unknown channels: expected BAD_LINK or "
                             f"UNKNOWN_DEVICE, got {status.name}")

    def case_managed_parameter(self) -> None:
        row = self._need_device()
        self.link.hello()
        address = hm.PARAM.pack(*row.key, 0, DEVICE_NODE_ID)  # the arbitrator's own
        expect(*self.link.request(Req.SET_PARAM, address + hm.SPAN.pack(0, 1) + b"\x05", 3.0),
               Status.MANAGED, "SET_PARAM of the Device Node Id")

    def case_param_bad_offset(self) -> None:
        row = self._need_device()
        self.link.hello()
        address = hm.PARAM.pack(*row.key, 0, DEVICE_DESCRIPTOR)
        self.link.request(Req.GET_PARAM, address + b"\x00\x00", 3.0)
        expect(*self.link.request(Req.GET_PARAM, address + b"\xff\x7f"), Status.BAD_OFFSET,
               "GET_PARAM at offset 32767")

    def case_config_bad_crc(self) -> None:
        self.link.hello()
        expect(*self.link.request(Req.CONFIG_WRITE_BEGIN, hm.CONFIG_INFO.pack(4, 0x1234)),
               Status.OK, "CONFIG_WRITE_BEGIN")
        expect(*self.link.request(Req.CONFIG_WRITE_CHUNK, b"\x00\x00abcd"), Status.OK,
               "CONFIG_WRITE_CHUNK")
        expect(*self.link.request(Req.CONFIG_WRITE_COMMIT), Status.CHECKSUM,
               "CONFIG_WRITE_COMMIT with a wrong CRC")

    def case_config_bad_offset(self) -> None:
        self.link.hello()
        expect(*self.link.request(Req.CONFIG_WRITE_BEGIN, hm.CONFIG_INFO.pack(8, 0)), Status.OK,
               "CONFIG_WRITE_BEGIN")
        expect(*self.link.request(Req.CONFIG_WRITE_CHUNK, b"\x04\x00abcd"), Status.BAD_OFFSET,
               "CONFIG_WRITE_CHUNK leaving a gap")
        expect(*self.link.request(Req.CONFIG_WRITE_COMMIT), Status.BAD_OFFSET,
               "CONFIG_WRITE_COMMIT of an incomplete configuration")

    def case_config_no_transfer(self) -> None:
        self.link.hello()
        expect(*self.link.request(Req.CONFIG_WRITE_COMMIT), Status.NO_TRANSFER,
               "CONFIG_WRITE_COMMIT without BEGIN")

    def case_config_too_large(self) -> None:
        self.link.hello()
        expect(*self.link.request(Req.CONFIG_WRITE_BEGIN, hm.CONFIG_INFO.pack(65000, 0)),
               Status.TOO_LARGE, "CONFIG_WRITE_BEGIN of 65,000 bytes")

    def case_transact_bad_crc(self) -> None:
        self._needs(hm.CAP_TRANSACTIONS)
        self.link.hello()
        expect(*self.link.request(Req.TRANSACT_BEGIN, hm.CONFIG_INFO.pack(3, 0x0BAD)),
               Status.OK, "TRANSACT_BEGIN")
        expect(*self.link.request(Req.TRANSACT_CHUNK, b"\x00\x00abc"), Status.OK,
               "TRANSACT_CHUNK")
        expect(*self.link.request(Req.TRANSACT_RUN), Status.CHECKSUM,
               "TRANSACT_RUN with a wrong CRC")

    # -- what a link must survive --------------------
    def case_reset_drops_frame_in_flight(self) -> None:
        """RESET while a reply is unacknowledged: the reply is dropped (not sent again) and
        the PC stays greeted (docs/host-link.md §3.3)."""
        self.link.hello()
        self.link.send(bytes([Req.STATUS]))
        self.link.reply(Req.STATUS, ack=False)
        self.link.write(b"\x00" + Frame(Kind.RESET, 0).encode())
        self.link.seq = 0
        again = [f for f in self.link.frames(0.6) if f.kind is Kind.DATA]
        if again:
            raise CaseFailed(f"after RESET the dropped reply came again ({len(again)} DATA "
                             "frame(s))")
        expect(*self.link.request(Req.STATUS), Status.OK, "STATUS after RESET (still greeted)")

    def case_sequence_wrap(self) -> None:
        """300 requests: both directions' numbers wrap past 255."""
        self.link.hello()
        for i in range(300):
            status, _ = self.link.request(Req.STATUS)
            if status is not Status.OK:
                raise CaseFailed(f"request {i} (seq {(i + 1) & 0xFF}): {status.name}")

    def case_paging(self) -> None:
        """LIST_DEVICES and LIST_LINKS paged one record at a time give the same records as
        from 0; a start at or past the end gives an empty page with the total."""
        self.link.hello()
        for code, size in ((Req.LIST_DEVICES, hm.DEVICE_ROW.size), (Req.LIST_LINKS,
                                                                     2 * hm.REF.size)):
            body = expect(*self.link.request(code, b"\x00\x00"), Status.OK, code.name)
            total, _ = struct.unpack_from("<HH", body)
            whole = body[4:]
            paged = bytearray()
            for start in range(total):
                page = expect(*self.link.request(code, struct.pack("<H", start)), Status.OK,
                              f"{code.name} from {start}")
                got_total, got_start = struct.unpack_from("<HH", page)
                if got_total != total or got_start != start or not page[4:]:
                    raise CaseFailed(f"{code.name} from {start}: total {got_total}, start "
                                     f"{got_start}, {len(page) - 4} bytes")
                paged += page[4:4 + size]
            if len(whole) == total * size and bytes(paged) != whole:
                raise CaseFailed(f"{code.name}: the records paged one by one differ")
            end = expect(*self.link.request(code, struct.pack("<H", total + 3)), Status.OK,
                         f"{code.name} past the end")
            if struct.unpack_from("<H", end)[0] != total or end[4:]:
                raise CaseFailed(f"{code.name} past the end: expected total {total} and no "
                                 "records")

    def case_events(self) -> None:
        """Events are DATA frames in the same numbering as replies: one left unacknowledged
        is sent again, the same seq; a reply still comes among them. Needs the monitor (the
        one event source a tester can start without changing the prosthesis)."""
        self._needs(hm.CAP_MONITOR)
        self.link.hello()
        expect(*self.link.request(Req.MONITOR, b"\x03\x05"), Status.OK, "MONITOR on")
        first = self.link.next_frame((Kind.DATA,), 6.0)
        if first is None or not 0x41 <= first.payload[0] < 0x80:
            raise CaseFailed(f"MONITOR on: expected an event within 6 s, got {first}")
        again = self.link.next_frame((Kind.DATA,), 1.0)
        if again is None or again.seq != first.seq or again.payload != first.payload:
            raise CaseFailed("an unacknowledged event: expected it again with the same seq")
        self.link.write(Frame(Kind.ACK, first.seq).encode())
        expect(*self.link.request(Req.MONITOR, b"\x00\x0a", 3.0), Status.OK,
               "MONITOR off among events")
        self.link.frames(0.3)

    def case_version_1_ping(self) -> None:
        """A version-1 PING gets a version-1 failure reply that says why (§4)."""
        self.link.reset()
        self.link.write(encode_v1(V1_PING) + b"\x00")
        sniffer = V1Sniffer()
        deadline = time.monotonic() + WAIT_S
        while time.monotonic() < deadline:
            for msg_id, payload in sniffer.feed(read_available(self.link.port)):
                if msg_id == V1_PING + 2 and bytes(payload):
                    return
                raise CaseFailed(f"a version-1 PING: expected a failure reply (0x"
                                 f"{V1_PING + 2:02X}) with a reason, got 0x{msg_id:02X}")
        raise CaseFailed("a version-1 PING: no version-1 reply within 1 s")

    def case_nak_for_given_up_frame(self) -> None:
        """Recovery after a cut: once a reply was given up, a NAK naming it is answered
        with RESET (the PC must renumber, §3.4); after RESET and HELLO requests work."""
        self.link.hello()
        self.link.send(bytes([Req.STATUS]))
        first, _, _ = self.link.reply(Req.STATUS, ack=False)
        self.link.frames(GIVE_UP_S)  # the line is "cut": every resend goes unanswered
        self.link.write(Frame(Kind.NAK, first.seq).encode())
        answer = self.link.next_frame((Kind.RESET,), WAIT_S)
        if answer is None:
            raise CaseFailed(f"a NAK({first.seq}) for a given-up reply: expected RESET")
        self.link.hello()
        expect(*self.link.request(Req.STATUS), Status.OK, "STATUS after the resync")


def case_names() -> list[str]:
    return [name[5:] for name in Suite.__dict__ if name.startswith("case_")]


def run_suite(port: Port, report: Callable[[str, str | None], None] | None = None
              ) -> SuiteResult:
    """Run every case on ``port`` (an open serial port); ``report(name, None | why)``."""
    suite = Suite(port)
    result = SuiteResult()
    for name in case_names():
        try:
            getattr(suite, f"case_{name}")()
            why = None
        except CaseSkipped as err:
            result.skipped.append(name)
            result.why[name] = str(err)
            if report is not None:
                report(name, "skipped: " + str(err))
            continue
        except CaseFailed as err:
            why = str(err)
        except (hm.MessageError, OSError, ValueError) as err:
            why = f"{type(err).__name__}: {err}"
        if why is None:
            result.passed.append(name)
        else:
            result.failed.append(name)
            result.why[name] = why
        if report is not None:
            report(name, why)
    return result
