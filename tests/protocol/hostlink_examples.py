"""The hex examples of docs/host-link.md, made by the implementation itself.

``python -m tests.protocol.hostlink_examples`` prints the block the document carries;
``test_hostlink_doc.py`` checks that the document's examples are exactly these.
"""

from __future__ import annotations

import struct

from pdcp_studio.bus.hostlink import records as hr
from pdcp_studio.bus.hostlink.change import encode_change, encode_result
from pdcp_studio.bus.transaction import Change, LinkAction, Policy, TransactionResult
from pdcp_studio.bus.transaction import Status as TxnStatus
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link, SourceInfo
from pdcp_studio.protocol import hostlink_messages as hm
from pdcp_studio.protocol.crc import crc16_ccitt_false
from pdcp_studio.protocol.hostlink import Frame, Kind
from pdcp_studio.protocol.hostlink_messages import Event, Req, Status
from pdcp_studio.storage import config_codec

EMG = DeviceKey(0x0A51, 0x0101, 101)
HAND = DeviceKey(0x0A51, 0x0201, 201)
LINK = Link(ChannelRef(*EMG, 1), ChannelRef(*HAND, 1))


def _device() -> Device:
    dev = Device(*EMG, node_id=1, descriptor="EMG electrode", fw_version=1, hw_version=2,
                 device_type=0x0010, device_profile=0x0001, beacon_interval=100,
                 ack_timeout=50, bind_timeout=200)
    dev.add_channel(Channel(1, Direction.OUTPUT, 0x9000, 0x4222, descriptor="flexor",
                            node_id=5))
    return dev


def _input() -> Channel:
    return Channel(1, Direction.INPUT, 0x9200, 0x4222, terminal_profile=0x4200,
                   required_inputs=(0x4222,), descriptor="open",
                   source=SourceInfo(*EMG, 1, 0x9000, 0x4222), data_enabled=True)


def _config() -> bytes:
    out = StoredChannel(index=1, vid=EMG.vid, pid=EMG.pid, serial=EMG.serial, type=0x9000,
                        profile=0x4222)
    inp = StoredChannel(index=1, vid=HAND.vid, pid=HAND.pid, serial=HAND.serial,
                        type=0x9200, profile=0x4222)
    return config_codec.dumps(ConfigCollection([StoredConfiguration(1, [StoredLink(inp, out,
                                                                                    1)])]))


def _anchor() -> bytes:
    """Entry 12's anchor, its hash 0x11 0x22 … (as the arbitrator's memory keeps it)."""
    from pdcp_studio.storage.archive.chain import Anchor, pack_anchor

    return pack_anchor(Anchor(12, "1122" * 16))


def _ok(code: int, body: bytes = b"") -> bytes:
    return bytes([hm.reply_code(code), Status.OK]) + body


def _fail(code: int, status: Status, why: str) -> bytes:
    return bytes([hm.reply_code(code), status]) + why.encode()


def _real(*requests: bytes) -> bytes:
    """The reply of PDCP Studio's arbitrator-side handlers to the last of ``requests`` (after
    HELLO): the exact bytes and reason text on the line. Only requests answered without the
    CAN bus (no arbitrator is needed for them)."""
    from pdcp_studio.bus.hostlink.handlers import Handlers

    handlers = Handlers(None, None)  # type: ignore[arg-type]  # these requests touch neither
    reply = handlers.handle(bytes([Req.HELLO, hm.VERSION, 0xFF, 0xFF]))
    for request in requests:
        reply = handlers.handle(request)
    assert reply is not None
    return reply


def messages() -> list[tuple[str, bytes]]:
    """(label, message) for every request with its reply, and every event."""
    key = hr.pack_key(EMG)
    param = hm.PARAM.pack(*EMG, 0, 10)
    cfg = _config()
    change = encode_change(Change("apply", [LinkAction("add", LINK, "")],
                                  policy=Policy(True)))
    result = encode_result(TransactionResult(TxnStatus.APPLIED, "apply", "", "", [], [LINK],
                                             None, None, True, "held 1 device", [EMG],
                                             [EMG, HAND]))
    dev = _device()
    info = hr.pack_device_info(dev)
    page, _ = hr.pack_channel_page([_input()], 0)
    return [
        ("HELLO request", bytes([Req.HELLO, hm.VERSION]) + b"\xff\xff"),
        ("HELLO reply", _ok(Req.HELLO, hm.HELLO.pack(2, 0x000F, 255) + b"arb 1.0")),
        ("HELLO refused", _real(bytes([Req.HELLO, 1, 0xFF, 0xFF]))),
        ("STATUS request", bytes([Req.STATUS])),
        ("STATUS reply", _ok(Req.STATUS, hm.STATUS.pack(0x03, 4, 5, 17, 0))),
        ("LIST_DEVICES request", bytes([Req.LIST_DEVICES]) + struct.pack("<H", 0)),
        ("LIST_DEVICES reply", _ok(Req.LIST_DEVICES, struct.pack("<HH", 1, 0)
                                   + hr.pack_device_row(dev))),
        ("GET_DEVICE request", bytes([Req.GET_DEVICE]) + key),
        ("GET_DEVICE reply", _ok(Req.GET_DEVICE, info + hr.pack_channel_page(
            list(dev.channels.values()), 0, room=hm.MAX_BODY - 1 - len(info))[0])),
        ("GET_CHANNELS request", bytes([Req.GET_CHANNELS]) + hr.pack_key(HAND) + b"\x00"),
        ("GET_CHANNELS reply", _ok(Req.GET_CHANNELS, page)),
        ("LIST_LINKS request", bytes([Req.LIST_LINKS]) + struct.pack("<H", 0)),
        ("LIST_LINKS reply", _ok(Req.LIST_LINKS, struct.pack("<HH", 1, 0)
                                 + hr.pack_link(LINK))),
        ("GET_PARAM request", bytes([Req.GET_PARAM]) + param + b"\x00\x00"),
        ("GET_PARAM reply", _ok(Req.GET_PARAM, hm.SPAN.pack(0, 2) + b"\x64\x00")),
        ("SET_PARAM request", bytes([Req.SET_PARAM]) + param + hm.SPAN.pack(0, 2)
         + b"\x96\x00"),
        ("SET_PARAM reply", _ok(Req.SET_PARAM, struct.pack("<HB", 2, 1))),
        ("SET_PARAM managed", _fail(Req.SET_PARAM, Status.MANAGED, "node IDs are mine")),
        ("ADD_LINK request", bytes([Req.ADD_LINK]) + hr.pack_link(LINK)),
        ("ADD_LINK reply", _ok(Req.ADD_LINK)),
        ("REMOVE_LINK request", bytes([Req.REMOVE_LINK]) + hr.pack_link(LINK)),
        ("REMOVE_LINK reply", _ok(Req.REMOVE_LINK)),
        ("SUSPEND request", bytes([Req.SUSPEND]) + key + struct.pack("<H", 2000)),
        ("SUSPEND reply", _ok(Req.SUSPEND)),
        ("RELEASE request", bytes([Req.RELEASE]) + key),
        ("RELEASE reply", _ok(Req.RELEASE)),
        ("RESET_DEVICE request", bytes([Req.RESET_DEVICE]) + key),
        ("RESET_DEVICE absent", _fail(Req.RESET_DEVICE, Status.DEVICE_ABSENT, "not on bus")),
        ("CONFIG_INFO request", bytes([Req.CONFIG_INFO])),
        ("CONFIG_INFO reply", _ok(Req.CONFIG_INFO, hm.CONFIG_INFO.pack(
            len(cfg), crc16_ccitt_false(cfg)))),
        ("CONFIG_READ request", bytes([Req.CONFIG_READ]) + struct.pack("<H", 0)),
        ("CONFIG_READ reply", _ok(Req.CONFIG_READ, hm.CONFIG_INFO.pack(
            len(cfg), crc16_ccitt_false(cfg)) + cfg)),
        ("CONFIG_WRITE_BEGIN request", bytes([Req.CONFIG_WRITE_BEGIN]) + hm.CONFIG_INFO.pack(
            len(cfg), crc16_ccitt_false(cfg))),
        ("CONFIG_WRITE_BEGIN reply", _ok(Req.CONFIG_WRITE_BEGIN)),
        ("CONFIG_WRITE_CHUNK request", bytes([Req.CONFIG_WRITE_CHUNK]) + b"\x00\x00" + cfg),
        ("CONFIG_WRITE_CHUNK reply", _ok(Req.CONFIG_WRITE_CHUNK, struct.pack("<H", len(cfg)))),
        ("CONFIG_WRITE_COMMIT request", bytes([Req.CONFIG_WRITE_COMMIT])),
        ("CONFIG_WRITE_COMMIT reply", _ok(Req.CONFIG_WRITE_COMMIT, hm.CONFIG_INFO.pack(
            len(cfg), crc16_ccitt_false(cfg)))),
        ("CONFIG_WRITE_COMMIT bad", _real(
            bytes([Req.CONFIG_WRITE_BEGIN]) + hm.CONFIG_INFO.pack(len(cfg), 0x1234),
            bytes([Req.CONFIG_WRITE_CHUNK]) + b"\x00\x00" + cfg,
            bytes([Req.CONFIG_WRITE_COMMIT]))),
        ("TRANSACT_BEGIN request", bytes([Req.TRANSACT_BEGIN]) + hm.CONFIG_INFO.pack(
            len(change), crc16_ccitt_false(change))),
        ("TRANSACT_BEGIN reply", _ok(Req.TRANSACT_BEGIN)),
        ("TRANSACT_CHUNK request", bytes([Req.TRANSACT_CHUNK]) + b"\x00\x00" + change),
        ("TRANSACT_CHUNK reply", _ok(Req.TRANSACT_CHUNK, struct.pack("<H", len(change)))),
        ("TRANSACT_RUN request", bytes([Req.TRANSACT_RUN])),
        ("TRANSACT_RUN reply", _ok(Req.TRANSACT_RUN, hm.CONFIG_INFO.pack(
            len(result), crc16_ccitt_false(result)))),
        ("RESULT_READ request", bytes([Req.RESULT_READ]) + struct.pack("<H", 0)),
        ("RESULT_READ reply", _ok(Req.RESULT_READ, hm.CONFIG_INFO.pack(
            len(result), crc16_ccitt_false(result)) + result)),
        ("GET_POLICY request", bytes([Req.GET_POLICY])),
        ("GET_POLICY reply", _ok(Req.GET_POLICY, b"\x01")),
        ("MONITOR request", bytes([Req.MONITOR, 0x03, 10])),
        ("MONITOR reply", _ok(Req.MONITOR, hm.MONITOR_REPLY.pack(6400))),
        ("ANCHOR_READ request", bytes([Req.ANCHOR_READ])),
        ("ANCHOR_READ reply", _ok(Req.ANCHOR_READ, _anchor())),
        ("ANCHOR_WRITE request", bytes([Req.ANCHOR_WRITE]) + _anchor()),
        ("ANCHOR_WRITE reply", _ok(Req.ANCHOR_WRITE, _anchor())),
        ("unknown request", _real(bytes([0x3E]))),
        ("event code as request", _real(bytes([0x41]))),
        ("STATUS too long", _real(bytes([Req.STATUS, 0]))),
        ("DEVICE_JOINED event", bytes([Event.DEVICE_JOINED]) + key + b"\x01"),
        ("DEVICE_LEFT event", bytes([Event.DEVICE_LEFT])
         + hr.pack_left(EMG, 1.5, 0.5, "no beacon for 1.5 s")),
        ("DEVICE_LEFT event, key alone", bytes([Event.DEVICE_LEFT]) + key),
        ("LINK_MADE event", bytes([Event.LINK_MADE]) + hr.pack_link_event(LINK, 5)),
        ("LINK_REMOVED event", bytes([Event.LINK_REMOVED]) + hr.pack_link_event(LINK, None)),
        ("OTHER_ARBITRATOR event", bytes([Event.OTHER_ARBITRATOR]) + b"another arbitrator"),
        ("BUS_ERROR event", bytes([Event.BUS_ERROR, 4]) + b"node IDs exhausted"),
        ("FRAMES event", hm.pack_frames([hm.WireFrame(1000, 0x30A, b"\x00\x01")], 0)),
        ("CHANNEL_COUNTS event", hm.pack_counts(1000, {5: 100})[0]),
        ("EVENTS_LOST event", bytes([Event.EVENTS_LOST]) + struct.pack("<H", 3)),
        ("TRANSACTION_DONE event", bytes([Event.TRANSACTION_DONE, 0]) + b"apply"),
        ("TERMINALS_UNCONNECTED event", bytes([Event.TERMINALS_UNCONNECTED, 1])
         + hm.REF.pack(*HAND, 1) + b"autoconfigure is off"),
        ("DEVICE_REPLACED event", bytes([Event.DEVICE_REPLACED]) + hr.pack_key(HAND)
         + hr.pack_key(DeviceKey(HAND[0], HAND[1], HAND[2] + 1))),
    ]


def examples() -> list[tuple[str, bytes]]:
    """(label, the frame on the line): link frames, then each message in a DATA frame (the
    host's requests with seq 0, the arbitrator's replies and events with seq 0)."""
    out = [("RESET", Frame(Kind.RESET, 0).encode()), ("ACK 0", Frame(Kind.ACK, 0).encode()),
           ("NAK 1", Frame(Kind.NAK, 1).encode())]
    out += [(label, Frame(Kind.DATA, 0, message).encode()) for label, message in messages()]
    return out


def render(width: int = 16) -> str:
    lines = []
    for label, wire in examples():
        chunks = [wire[i:i + width].hex(" ") for i in range(0, len(wire), width)]
        lines.append(f"{label + ':':<30}{chunks[0]}")
        lines += [f"{'':<30}{c}" for c in chunks[1:]]
    return "\n".join(lines)


if __name__ == "__main__":
    print(render())
