"""A change of the change road and its result, as the bytes TRANSACT moves (docs/host-link.md §5.8).

The PC stages the change in chunks (TRANSACT_BEGIN / _CHUNK, CRC-checked like a
configuration write), the arbitrator carries it out as one transaction (interlock, write,
read back, restore on a mismatch, release) and keeps the result for RESULT_READ. Binary, with
length-prefixed texts, so a firmware parses it with a cursor and no allocation::

    change: action (str8) | links u16 × [op u8 (1 add, 2 remove), output ref, input ref,
            reason (str8)] | parameters u8 × [key, channel u8, parameter u8, value (bytes16)]
            | configuration: u8 present, then bytes16 | policy u8 (0 off, 1 on, 0xFF keep)
    result: status u8 | step u8 | verified u8 | CRC before, after: u8 present + u16 each |
            policy before, after u8 (0xFF none) | action (str8) | reason (str16) |
            interlock (str8) | links before, after: u16 × link | held, devices: u8 × key |
            notes u8 × str16

A change has a size limit, :data:`MAX_CHANGE` bytes (the arbitrator stages it in its memory's
spare slot): :func:`size_problem` says, before anything is sent or recorded, that a change is
beyond it — in words naming its size and the limit — and a count or a length beyond its field
is :class:`ChangeTooLarge`, never a ``struct.error``.

Pure apart from the model types it builds.
"""

from __future__ import annotations

import struct

from pdcp_studio.bus.hostlink import records as hr
from pdcp_studio.bus.transaction import (
    STEPS,
    Change,
    LinkAction,
    ParameterWrite,
    Policy,
    Status,
    TransactionResult,
)
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.protocol import hostlink_messages as hm

_STATUSES = list(Status)

#: The largest change (its stored configuration included) an arbitrator takes over the host
#: link: TRANSACT_BEGIN answers TOO_LARGE above it (``handlers.py``), so the PC refuses such a
#: change itself, before sending it and before the fitting history announces it.
MAX_CHANGE = 16384


class ChangeTooLarge(ValueError):
    """A change whose counts or lengths do not fit the fields of its encoding."""


def size_problem(change: Change, limit: int = MAX_CHANGE) -> str | None:
    """Why the host link cannot carry ``change``, in words naming its size and the limit;
    None when it fits."""
    from pdcp_studio.storage import config_codec

    config = (len(config_codec.dumps(change.configuration))
              if change.configuration is not None else 0)
    try:
        size = len(encode_change(change))
    except ChangeTooLarge:
        size = None
    if size is not None and size <= limit:
        return None
    took = f"{size:,} bytes" if size is not None else "more than 65,535 bytes"
    if config:
        took += f" (its stored configuration {config:,} bytes)"
    return (f"the change takes {took}; the host link carries at most {limit:,} bytes per "
            "change, so nothing was sent to the arbitrator")


class _Reader:
    def __init__(self, data: bytes) -> None:
        self.data, self.pos = data, 0

    def take(self, n: int, what: str) -> bytes:
        hm.need(self.data, self.pos + n, what)
        out = self.data[self.pos:self.pos + n]
        self.pos += n
        return out

    def u8(self, what: str) -> int:
        return self.take(1, what)[0]

    def u16(self, what: str) -> int:
        return int.from_bytes(self.take(2, what), "little")

    def str8(self, what: str) -> str:
        return hm.text(self.take(self.u8(what), what))

    def str16(self, what: str) -> str:
        return hm.text(self.take(self.u16(what), what))

    def link(self) -> Link:
        return hr.unpack_link(self.take(2 * hm.REF.size, "link"))

    def key(self) -> DeviceKey:
        return hr.unpack_key(self.take(hm.KEY.size, "device key"))


def _str8(text: str) -> bytes:
    data = hm.short_text(text, 255)
    return bytes([len(data)]) + data


def _str16(text: str, limit: int = 4000) -> bytes:
    data = hm.short_text(text, limit)
    return struct.pack("<H", len(data)) + data


def _policy(policy: Policy | None) -> int:
    return 0xFF if policy is None else int(policy.autoconfigure)


def _policy_of(value: int) -> Policy | None:
    return None if value == 0xFF else Policy(autoconfigure=bool(value))


def _crc(text: str | None) -> bytes:
    return b"\x00\x00\x00" if text is None else b"\x01" + struct.pack("<H", int(text, 16))


def encode_change(change: Change) -> bytes:
    """The change's bytes; ChangeTooLarge when a count or a length does not fit its field."""
    try:
        return _encode_change(change)
    except (struct.error, ValueError) as err:  # a u16 length of 70,000, 300 parameters …
        raise ChangeTooLarge(f"the change does not fit the host link's encoding ({err})") \
            from None


def _encode_change(change: Change) -> bytes:
    from pdcp_studio.storage import config_codec

    out = bytearray(_str8(change.action))
    out += struct.pack("<H", len(change.links))
    for action in change.links:
        out += bytes([1 if action.op == "add" else 2]) + hr.pack_link(action.link)
        out += _str8(action.reason)
    out += bytes([len(change.parameters)])
    for p in change.parameters:
        out += hr.pack_key(p.device) + bytes([p.channel, p.param])
        out += struct.pack("<H", len(p.value)) + p.value
    if change.configuration is None:
        out += b"\x00"
    else:
        data = config_codec.dumps(change.configuration)
        out += b"\x01" + struct.pack("<H", len(data)) + data
    out += bytes([_policy(change.policy)])
    return bytes(out)


def decode_change(data: bytes) -> Change:
    from pdcp_studio.storage import config_codec

    r = _Reader(bytes(data))
    action = r.str8("action")
    links = []
    for _ in range(r.u16("link count")):
        op = r.u8("link op")
        if op not in (1, 2):
            raise hm.MessageError(f"link op {op} is neither 1 (add) nor 2 (remove)")
        link = r.link()
        links.append(LinkAction("add" if op == 1 else "remove", link, r.str8("reason")))
    params = []
    for _ in range(r.u8("parameter count")):
        key = r.key()
        channel, param = r.u8("channel"), r.u8("parameter")
        params.append(ParameterWrite(key, param, channel, r.take(r.u16("value length"),
                                                                 "value")))
    configuration = None
    if r.u8("configuration flag"):
        configuration = config_codec.loads(r.take(r.u16("configuration length"),
                                                  "configuration"))
    policy = _policy_of(r.u8("policy"))
    if r.pos != len(r.data):
        raise hm.MessageError(f"{len(r.data) - r.pos} bytes after the change")
    return Change(action, links, params, configuration, policy)


def encode_result(result: TransactionResult) -> bytes:
    status = _STATUSES.index(Status(result.status))
    step = STEPS.index(result.step) if result.step in STEPS else 0xFF
    out = bytearray([status, step, int(bool(result.verified))])
    out += _crc(result.config_crc_before) + _crc(result.config_crc_after)
    out += bytes([_policy(result.policy_before), _policy(result.policy_after)])
    out += _str8(result.action) + _str16(result.reason) + _str8(result.interlock)
    for links in (result.links_before, result.links_after):
        out += struct.pack("<H", len(links)) + b"".join(hr.pack_link(lk) for lk in links)
    for keys in (result.held, result.devices):
        keys = keys[:255]
        out += bytes([len(keys)]) + b"".join(hr.pack_key(k) for k in keys)
    notes = result.notes[:255]
    out += bytes([len(notes)]) + b"".join(_str16(n, 1000) for n in notes)
    return bytes(out)


def decode_result(data: bytes) -> TransactionResult:
    r = _Reader(bytes(data))
    status, step, verified = r.u8("status"), r.u8("step"), r.u8("verified")
    if status >= len(_STATUSES):
        raise hm.MessageError(f"transaction status {status} is unknown")
    crcs = []
    for _ in range(2):
        present, value = r.u8("CRC flag"), r.u16("CRC")
        crcs.append(f"0x{value:04X}" if present else None)
    pol_before, pol_after = r.u8("policy"), r.u8("policy")
    action, reason, interlock = r.str8("action"), r.str16("reason"), r.str8("interlock")
    links = [[r.link() for _ in range(r.u16("link count"))] for _ in range(2)]
    keys = [[r.key() for _ in range(r.u8("key count"))] for _ in range(2)]
    notes = [r.str16("note") for _ in range(r.u8("note count"))]
    return TransactionResult(
        _STATUSES[status], action, STEPS[step] if step < len(STEPS) else "", reason,
        links[0], links[1], crcs[0], crcs[1], bool(verified), interlock, keys[0], keys[1],
        _policy_of(pol_before), _policy_of(pol_after), None, notes)
