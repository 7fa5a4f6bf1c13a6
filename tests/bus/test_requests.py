"""The request engine as scripted exchanges: the frames it must send, the replies injected
(canopen's habit), including the bulk transfers of 001 §3.3.6–3.3.7."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

import pytest

from pdcp_studio.bus.arbitrator.reading.requests import (
    DeviceRefusedError,
    RequestEngine,
    TransferAbortedError,
)
from pdcp_studio.errors import BusTimeoutError
from pdcp_studio.protocol import (
    BulkData,
    BulkDataResponse,
    ConfigureGetBulkResponse,
    ConfigureSetBulkResponse,
    GetParameterResponse,
    Message,
    Mode,
    ResetResponse,
    ResponseCode,
    SetParameterResponse,
    SuspendResponse,
    decode,
)

OK, FAIL, BULK = ResponseCode.SUCCESS, ResponseCode.FAILURE, ResponseCode.USE_BULK
DESCRIPTOR = b"Prototype PDCP Device Descriptor\0"  # 33 bytes, 001 §3.3.6


class Script:
    """Records what the engine sends; ``reply(message)`` returns the frames to inject."""

    def __init__(self, reply: Callable[[Message], list[Message]], *,
                 timeout: float = 0.05, retries: int = 2) -> None:
        self.sent: list[tuple[int, bytes]] = []
        self.reply = reply
        self.engine = RequestEngine(self.send, response_timeout=timeout, retries=retries)

    def send(self, message: Message) -> None:
        self.sent.append(message.encode())
        for answer in self.reply(message):
            # What the dispatcher does: decode the frame, hand it over.
            self.engine.feed(decode(*answer.encode()))

    def hex(self) -> list[str]:
        return [data.hex(" ") for _, data in self.sent]


def test_inline_get_and_set_frames():
    def reply(m: Message) -> list[Message]:
        if m.CODE == 0x03:
            return [GetParameterResponse(5, OK, m.param, m.channel, b"\x02\x00\x02\x00")]
        return [SetParameterResponse(5, OK, m.param, m.channel, m.value)]

    s = Script(reply)
    assert s.engine.get(5, 1, 0) == b"\x02\x00\x02\x00"
    s.engine.set(5, 10, 0, b"\x64\x00")
    assert s.hex() == ["03 01 00", "04 0a 00 64 00"]
    assert [aid for aid, _ in s.sent] == [0x305, 0x305]  # priority 1, mode 1, node 5
    st = s.engine.stats
    assert (st.requests, st.frames_sent, st.frames_received, st.retries) == (2, 2, 2, 0)


def test_bulk_get_of_the_33_byte_descriptor():
    def reply(m: Message) -> list[Message]:
        if m.CODE == 0x03:
            return [GetParameterResponse(5, BULK, 7, 0)]
        if m.CODE == 0x0C:
            packets = [BulkData(5, n + 1, DESCRIPTOR[i:i + 6], mode=Mode.DEVICE)
                       for n, i in enumerate(range(0, 33, 6))]
            return [ConfigureGetBulkResponse(5, OK, 7, 0, 33), *packets]
        return []

    s = Script(reply)
    assert s.engine.get(5, 7, 0) == DESCRIPTOR
    assert s.hex() == ["03 07 00", "0c 07 00", "8e 01"]


def test_a_value_known_to_be_long_starts_with_configure_get_bulk():
    def reply(m: Message) -> list[Message]:
        assert m.CODE != 0x03, "bulk_first must skip the inline Get"
        if m.CODE == 0x0C:
            packets = [BulkData(5, n + 1, DESCRIPTOR[i:i + 6], mode=Mode.DEVICE)
                       for n, i in enumerate(range(0, 33, 6))]
            return [ConfigureGetBulkResponse(5, OK, 7, 0, 33), *packets]
        return []

    s = Script(reply)
    assert s.engine.get(5, 7, 0, bulk_first=True) == DESCRIPTOR
    assert s.hex() == ["0c 07 00", "8e 01"]


def test_bulk_set_of_17_bytes():
    value = bytes(range(17))
    got: list[bytes] = []

    def reply(m: Message) -> list[Message]:
        if m.CODE == 0x0D:
            return [ConfigureSetBulkResponse(5, OK, m.param, m.channel, m.size)]
        if m.CODE == 0x0E:
            got.append(m.data)
            if sum(map(len, got)) == 17:
                return [BulkDataResponse(5, OK, mode=Mode.DEVICE)]
        return []

    s = Script(reply)
    s.engine.set(5, 7, 0, value)
    assert s.hex() == ["0d 07 00 11 00", "0e 01 00 01 02 03 04 05", "0e 02 06 07 08 09 0a 0b",
                       "0e 03 0c 0d 0e 0f 10"]
    assert b"".join(got) == value


def test_a_lost_bulk_packet_restarts_the_transfer():
    attempts = []

    def reply(m: Message) -> list[Message]:
        if m.CODE == 0x03:
            return [GetParameterResponse(5, BULK, 7, 0)]
        if m.CODE == 0x0C:
            attempts.append(1)
            packets = [BulkData(5, n + 1, DESCRIPTOR[i:i + 6], mode=Mode.DEVICE)
                       for n, i in enumerate(range(0, 33, 6))]
            if len(attempts) == 1:
                del packets[2]  # packet 3 never arrives
            return [ConfigureGetBulkResponse(5, OK, 7, 0, 33), *packets]
        return []

    s = Script(reply)
    assert s.engine.get(5, 7, 0) == DESCRIPTOR
    assert s.hex() == ["03 07 00", "0c 07 00", "8e 00", "0c 07 00", "8e 01"]
    assert s.engine.stats.retries == 1


def test_timeouts_retry_a_bounded_number_of_times():
    s = Script(lambda m: [], timeout=0.02, retries=3)
    started = time.monotonic()
    with pytest.raises(BusTimeoutError, match="after 4 attempt"):
        s.engine.get(9, 1, 0)
    assert len(s.sent) == 4
    assert time.monotonic() - started < 0.5
    assert (s.engine.stats.retries, s.engine.stats.timeouts) == (3, 1)


def test_a_refusal_is_not_retried():
    s = Script(lambda m: [GetParameterResponse(5, FAIL, m.param, m.channel)])
    with pytest.raises(DeviceRefusedError, match="refused"):
        s.engine.get(5, 99, 0)
    assert len(s.sent) == 1


def test_answers_to_another_parameter_are_ignored():
    def reply(m: Message) -> list[Message]:
        return [GetParameterResponse(5, OK, 2, 0, b"\x01\x00"),  # a stale answer
                GetParameterResponse(5, OK, m.param, m.channel, b"\x03")]

    s = Script(reply)
    assert s.engine.get(5, 9, 0) == b"\x03"


def test_suspend_release_reset():
    def reply(m: Message) -> list[Message]:
        if m.CODE == 0x08:
            return [SuspendResponse(5, OK, m.ms)]
        if m.CODE == 0x0B:
            return [ResetResponse(5, OK)]
        return []

    s = Script(reply, retries=0)
    s.engine.suspend(5, 250)
    s.engine.reset(5)
    with pytest.raises(BusTimeoutError):
        s.engine.release(5, timeout=0.05)
    assert s.hex()[:2] == ["08 fa 00", "0b"]


def test_abort_cuts_short_only_that_nodes_transaction_and_others_overlap():
    engine = RequestEngine(lambda m: None, response_timeout=1.0, retries=0)
    results: dict[int, object] = {}

    def ask(node: int) -> None:
        try:
            results[node] = engine.get(node, 1, 0)
        except Exception as err:
            results[node] = err

    threads = [threading.Thread(target=ask, args=(n,)) for n in (5, 6)]
    for t in threads:
        t.start()
    deadline = time.monotonic() + 1
    while len(engine._waiters) < 2 and time.monotonic() < deadline:  # both waiting at once
        time.sleep(0.001)
    assert len(engine._waiters) == 2
    engine.abort(5, "the device left the bus")
    assert engine.feed(decode(*GetParameterResponse(6, OK, 1, 0, b"\x07").encode()))
    for t in threads:
        t.join(2)
    assert isinstance(results[5], TransferAbortedError)
    assert "left the bus" in str(results[5])
    assert results[6] == b"\x07"
    assert engine.stats.aborted == 1
    engine.close()
    with pytest.raises(TransferAbortedError):
        engine.get(5, 1, 0)


def test_a_frame_without_a_waiting_transaction_is_not_taken():
    engine = RequestEngine(lambda m: None)
    assert not engine.feed(decode(*GetParameterResponse(5, OK, 1, 0, b"\x01").encode()))
