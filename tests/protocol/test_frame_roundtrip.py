"""Property tests: every message survives encode → decode, and any frame in gives a Message
or FrameError — never another exception."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from pdcp_studio.errors import FrameError
from pdcp_studio.protocol import messages as m
from pdcp_studio.protocol.codes import ResponseCode
from pdcp_studio.protocol.identifier import Mode, Priority

node = st.integers(0, 254)
u8 = st.integers(0, 0xFF)
u16 = st.integers(0, 0xFFFF)
prio = st.sampled_from([Priority.HIGH, Priority.NORMAL, Priority.LOW])
mode = st.sampled_from(list(Mode))
code = st.sampled_from([ResponseCode.FAILURE, ResponseCode.SUCCESS])
code_bulk = st.sampled_from(list(ResponseCode))

data4 = st.binary(max_size=4)
value = st.binary(min_size=1, max_size=4)
b = st.builds

STRATEGIES = {
    m.BindRequest: b(m.BindRequest, node, u16, u16, u16),
    m.BindResponse: b(m.BindResponse, node, st.integers(1, 254), u16, u16, u16, priority=prio),
    m.GetParameter: b(m.GetParameter, node, u8, u8, priority=prio),
    m.GetParameterResponse: b(m.GetParameterResponse, node, code_bulk, u8, u8, data4,
                              priority=prio),
    m.SetParameter: b(m.SetParameter, node, u8, u8, value, priority=prio),
    m.SetParameterResponse: b(m.SetParameterResponse, node, code_bulk, u8, u8, value,
                              priority=prio),
    m.Suspend: b(m.Suspend, node, u16, priority=prio),
    m.SuspendResponse: b(m.SuspendResponse, node, code, u16, priority=prio),
    m.Release: b(m.Release, node, priority=prio),
    m.ReleaseResponse: b(m.ReleaseResponse, node, code, priority=prio),
    m.Beacon: b(m.Beacon, node, mode=mode, priority=prio),
    m.Reset: b(m.Reset, node, priority=prio),
    m.ResetResponse: b(m.ResetResponse, node, code, priority=prio),
    m.ConfigureGetBulk: b(m.ConfigureGetBulk, node, u8, u8, priority=prio),
    m.ConfigureGetBulkResponse: b(m.ConfigureGetBulkResponse, node, code, u8, u8, u16,
                                  priority=prio),
    m.ConfigureSetBulk: b(m.ConfigureSetBulk, node, u8, u8, u16, priority=prio),
    m.ConfigureSetBulkResponse: b(m.ConfigureSetBulkResponse, node, code, u8, u8, u16,
                                  priority=prio),
    m.BulkData: b(m.BulkData, node, st.integers(1, 255), st.binary(min_size=1, max_size=6),
                  mode=mode, priority=prio),
    m.BulkDataResponse: b(m.BulkDataResponse, node, code, mode=mode, priority=prio),
    m.UpdateDataChannel: b(m.UpdateDataChannel, node, u8, priority=prio),
    m.UpdateDataChannelResponse: b(m.UpdateDataChannelResponse, node, code, u8, priority=prio),
    m.ChannelData: b(m.ChannelData, st.integers(1, 254), st.binary(max_size=8), priority=prio),
}
MESSAGES = st.one_of(*STRATEGIES.values())
#: Frame data that starts with a known function code, so decoding often gets past byte 0.
FRAME_DATA = st.one_of(
    st.binary(max_size=8),
    st.builds(lambda c, rest: bytes([c]) + rest, st.sampled_from(sorted(m.MESSAGE_TYPES)),
              st.binary(max_size=7)),
)


def test_the_strategies_cover_every_message_type() -> None:
    assert set(STRATEGIES) == set(m.Message.__args__)


@given(MESSAGES)
def test_encode_decode_round_trip(message: m.Message) -> None:
    arbitration_id, data = message.encode()
    assert 0 <= arbitration_id <= 0x7FF and len(data) <= 8
    channels = {message.node_id} if isinstance(message, m.ChannelData) else set()
    decoded = m.decode(arbitration_id, data, channel_node_ids=channels)
    assert decoded == message
    assert type(decoded) is type(message)
    assert type(message).decode(arbitration_id, data) == message
    assert isinstance(m.describe(decoded), str)


@given(
    st.integers(0, 0x7FF),
    FRAME_DATA,
    st.frozensets(st.integers(0, 255), max_size=4),
)
def test_any_frame_decodes_or_raises_frame_error(
    arbitration_id: int, data: bytes, channels: frozenset[int]
) -> None:
    try:
        message = m.decode(arbitration_id, data, channel_node_ids=channels)
    except FrameError:
        return
    # Whatever decodes re-encodes to exactly the same frame.
    assert message.encode() == (arbitration_id, data)
    assert isinstance(m.describe(message), str)


@given(st.integers(-(2**31), 2**31), st.binary(max_size=16))
def test_any_input_only_frame_error(arbitration_id: int, data: bytes) -> None:
    try:
        m.decode(arbitration_id, data)
    except FrameError:
        pass


@given(st.sampled_from(sorted(m.MESSAGE_TYPES)), st.integers(0, 0x7FF), st.binary(max_size=8))
def test_class_decode_only_frame_error(code: int, arbitration_id: int, data: bytes) -> None:
    try:
        m.MESSAGE_TYPES[code].decode(arbitration_id, bytes([code]) + data)
    except FrameError:
        pass
