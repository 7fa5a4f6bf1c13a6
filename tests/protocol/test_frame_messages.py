"""Messages against the worked frames of 001 §3.3, byte for byte, and the DLC table.

Reading the OCR of 001 §3.3: "Ox"/"OX" is 0x and "O" in a hex byte is 0; a priority printed
"il" and a mode printed "i)" are 1 (the other rows of each exchange and the direction of the
function decide it: 0x0D is sent by the arbitrator, so mode 1). The beacon row's description
"(VID = 0x0001, …)" is copied from the bind rows; the frame itself is the single byte 0x0A.
Figure 3.1 prints DLC 5 for 0x0C and 1 for 0x88 / 0x89 / 0x8B; §3.2 and the examples (0x0C
DLC 3, 0x8B DLC 2) agree with the reference's table, which these tests follow.
"""

from __future__ import annotations

import pytest

from pdcp_studio.errors import FrameError
from pdcp_studio.model.parameters import DEVICE_DESCRIPTOR, device_parameter, encode_value
from pdcp_studio.model.refs import Direction
from pdcp_studio.protocol.bulk import BulkReassembler, packetize
from pdcp_studio.protocol.codes import DLC_RANGE, FunctionCode, ResponseCode
from pdcp_studio.protocol.identifier import Mode, Priority, make_id
from pdcp_studio.protocol.messages import (
    MESSAGE_TYPES,
    Beacon,
    BindRequest,
    BindResponse,
    BulkData,
    BulkDataResponse,
    ChannelData,
    ConfigureGetBulk,
    ConfigureGetBulkResponse,
    ConfigureSetBulk,
    ConfigureSetBulkResponse,
    GetParameter,
    GetParameterResponse,
    Release,
    ReleaseResponse,
    Reset,
    ResetResponse,
    SetParameter,
    SetParameterResponse,
    Suspend,
    SuspendResponse,
    UpdateDataChannel,
    UpdateDataChannelResponse,
    decode,
    describe,
)

OK, USE_BULK = ResponseCode.SUCCESS, ResponseCode.USE_BULK
DEV, BA = Mode.DEVICE, Mode.ARBITRATOR


def frame(priority: int, mode: int, node: int, hex_bytes: str) -> tuple[int, bytes]:
    """A row of the 001 tables: SID fields, then the data bytes."""
    return make_id(priority, mode, node), bytes.fromhex(hex_bytes)


# (row of 001 §3.3 as (priority, mode, node ID, data), the message it is)
WORKED_FRAMES = [
    # §3.3.1 Device binding: ask for 1, arbitrator suggests 5, ask for 5, granted.
    ((3, 0, 1, "01 01 00 0A 00 04 00"), BindRequest(1, vid=0x0001, pid=0x000A, serial=4)),
    ((1, 1, 1, "81 05 01 00 0A 00 04 00"), BindResponse(1, 5, 0x0001, 0x000A, 4)),
    ((3, 0, 5, "01 01 00 0A 00 04 00"), BindRequest(5, 0x0001, 0x000A, 4)),
    ((1, 1, 5, "81 05 01 00 0A 00 04 00"), BindResponse(5, 5, 0x0001, 0x000A, 4)),
    # §3.3.2 Get Device Parameter: Number of Data Channels = 1.
    ((1, 1, 5, "03 09 00"), GetParameter(5, param=9, channel=0)),
    ((1, 0, 5, "83 01 09 00 01"), GetParameterResponse(5, OK, 9, 0, b"\x01")),
    # §3.3.3 Set Device Parameter: data channel 1's node ID = 6.
    ((1, 1, 5, "04 05 01 06"), SetParameter(5, param=5, channel=1, value=b"\x06")),
    ((1, 0, 5, "84 01 05 01 06"), SetParameterResponse(5, OK, 5, 1, b"\x06")),
    # §3.3.4 Device beacon, high priority.
    ((0, 0, 5, "0A"), Beacon(5)),
    # §3.3.5 Reset.
    ((1, 1, 5, "0B"), Reset(5)),
    ((1, 0, 5, "8B 01"), ResetResponse(5, OK)),
    # §3.3.6 Bulk get of the Device Descriptor (33 bytes).
    ((1, 1, 5, "03 07 00"), GetParameter(5, 7, 0)),
    ((1, 0, 5, "83 02 07 00"), GetParameterResponse(5, USE_BULK, 7, 0)),
    ((1, 1, 5, "0C 07 00"), ConfigureGetBulk(5, 7, 0)),
    ((1, 0, 5, "8C 01 07 00 21 00"), ConfigureGetBulkResponse(5, OK, 7, 0, size=33)),
    ((1, 0, 5, "0E 01 50 72 6F 74 6F 74"), BulkData(5, 1, b"Protot", mode=DEV)),
    ((1, 0, 5, "0E 02 79 70 65 20 50 44"), BulkData(5, 2, b"ype PD", mode=DEV)),
    ((1, 0, 5, "0E 03 43 50 20 44 65 76"), BulkData(5, 3, b"CP Dev", mode=DEV)),
    ((1, 0, 5, "0E 04 69 63 65 20 44 65"), BulkData(5, 4, b"ice De", mode=DEV)),
    ((1, 0, 5, "0E 05 73 63 72 69 70 74"), BulkData(5, 5, b"script", mode=DEV)),
    ((1, 0, 5, "0E 06 6F 72 00"), BulkData(5, 6, b"or\0", mode=DEV)),
    ((1, 1, 5, "8E 01"), BulkDataResponse(5, OK, mode=BA)),
    # §3.3.7 Bulk set of 17 bytes to parameter 0x37 ("arbitrary parameter for this example").
    ((1, 1, 5, "0D 37 00 11 00"), ConfigureSetBulk(5, 0x37, 0, size=17)),
    ((1, 0, 5, "8D 01 37 00 11 00"), ConfigureSetBulkResponse(5, OK, 0x37, 0, 17)),
    ((1, 1, 5, "0E 01 01 02 03 04 05 06"), BulkData(5, 1, bytes(range(1, 7)), mode=BA)),
    ((1, 1, 5, "0E 02 07 08 09 0A 0B 0C"), BulkData(5, 2, bytes(range(7, 13)), mode=BA)),
    ((1, 1, 5, "0E 03 0D 0E 0F 10 11"), BulkData(5, 3, bytes(range(13, 18)), mode=BA)),
    ((1, 0, 5, "8E 01"), BulkDataResponse(5, OK, mode=DEV)),
    # §3.3.8 Update Data Channel for input channel 4.
    ((1, 0, 5, "0F 04"), UpdateDataChannel(5, channel=4)),
    ((1, 1, 5, "8F 01 04"), UpdateDataChannelResponse(5, OK, channel=4)),
]


@pytest.mark.parametrize(("row", "message"), WORKED_FRAMES, ids=lambda v: str(v)[:40])
def test_worked_frame_encodes_byte_for_byte(row: tuple, message: object) -> None:
    assert message.encode() == frame(*row)  # type: ignore[attr-defined]


@pytest.mark.parametrize(("row", "message"), WORKED_FRAMES, ids=lambda v: str(v)[:40])
def test_worked_frame_decodes(row: tuple, message: object) -> None:
    decoded = decode(*frame(*row))
    assert decoded == message
    assert type(decoded).decode(*frame(*row)) == message


def test_binding_exchange_meaning() -> None:
    suggestion = decode(*frame(1, 1, 1, "81 05 01 00 0A 00 04 00"))
    assert isinstance(suggestion, BindResponse)
    assert suggestion.node_id == 1 and suggestion.granted_node_id == 5
    assert not suggestion.accepted
    granted = decode(*frame(1, 1, 5, "81 05 01 00 0A 00 04 00"))
    assert isinstance(granted, BindResponse) and granted.accepted
    request = decode(*frame(3, 0, 1, "01 01 00 0A 00 04 00"))
    assert request.priority is Priority.BINDING and request.mode is Mode.DEVICE


def test_descriptor_bulk_get_reassembles() -> None:
    packets = [m for _, m in WORKED_FRAMES[15:21]]
    reassembler = BulkReassembler(33)
    for packet in packets:
        reassembler.add(packet.packet_id, packet.data)
    spec = device_parameter(DEVICE_DESCRIPTOR)
    payload = reassembler.result()
    assert payload == b"Prototype PDCP Device Descriptor\0"
    # The device side: the catalog's string layout (NUL-terminated) gives the same packets.
    encoded = encode_value(spec, "Prototype PDCP Device Descriptor")
    assert encoded == payload
    assert [BulkData(5, p.packet_id, p.data, mode=DEV) for p in packetize(encoded)] == packets


def test_bulk_set_packets_come_from_packetize() -> None:
    packets = [m for _, m in WORKED_FRAMES[24:27]]
    expected = [BulkData(5, p.packet_id, p.data, mode=BA) for p in packetize(bytes(range(1, 18)))]
    assert expected == packets


def test_reference_table_dlcs() -> None:
    assert {code: DLC_RANGE[code] for code in FunctionCode} == {
        0x01: (7, 7), 0x81: (8, 8), 0x03: (3, 3), 0x83: (4, 8), 0x04: (4, 7), 0x84: (5, 8),
        0x08: (3, 3), 0x88: (4, 4), 0x09: (1, 1), 0x89: (2, 2), 0x0A: (1, 1), 0x0B: (1, 1),
        0x8B: (2, 2), 0x0C: (3, 3), 0x8C: (6, 6), 0x0D: (5, 5), 0x8D: (6, 6), 0x0E: (3, 8),
        0x8E: (2, 2), 0x0F: (2, 2), 0x8F: (3, 3),
    }
    assert set(MESSAGE_TYPES) == set(FunctionCode)


def _valid_identifier(code: FunctionCode) -> int:
    cls = MESSAGE_TYPES[code]
    mode = cls.MODE if cls.MODE is not None else Mode.DEVICE
    priority = Priority.BINDING if code is FunctionCode.BIND_REQUEST else Priority.NORMAL
    return make_id(priority, mode, 5)


@pytest.mark.parametrize("code", list(FunctionCode), ids=lambda c: c.name)
def test_every_dlc_outside_the_table_is_rejected(code: FunctionCode) -> None:
    lo, hi = DLC_RANGE[code]
    arbitration_id = _valid_identifier(code)
    for dlc in range(1, 9):
        data = bytes([code]) + bytes([1] * (dlc - 1))
        if lo <= dlc <= hi:
            assert decode(arbitration_id, data).encode() == (arbitration_id, data)
        else:
            problem = "too short" if dlc < lo else "too long"
            with pytest.raises(FrameError, match=f"^{code.label}: DLC {dlc} is {problem}"):
                decode(arbitration_id, data)


def test_error_message_names_function_and_problem() -> None:
    with pytest.raises(FrameError) as err:
        decode(*frame(1, 0, 5, "83 01 09"))
    assert str(err.value) == "0x83 Get Device Parameter Response: DLC 3 is too short (4–8 expected)"
    with pytest.raises(FrameError, match=r"^0x01 Bind Device Request: DLC 8 is too long \(7 expected\)$"):
        decode(*frame(3, 0, 5, "01 01 00 0A 00 04 00 00"))


@pytest.mark.parametrize(
    ("row", "match"),
    [
        ((1, 0, 5, "03 09 00"), r"0x03 Get Device Parameter: sent in mode 0 .*bus arbitrator"),
        ((1, 1, 5, "83 01 09 00 01"), r"0x83 .*sent in mode 1 .*only a device"),
        ((1, 0, 5, "01 01 00 0A 00 04 00"), r"0x01 .*priority 1 .*priority 3"),
        ((3, 0, 5, "0A"), r"0x0A Device Beacon: priority 3 .*reserved for the Bind"),
        ((3, 1, 5, "03 09 00"), r"0x03 .*priority 3 .*reserved"),
        ((1, 1, 5, "81 00 01 00 0A 00 04 00"), r"granted node ID 0 is out of range \(1–254\)"),
        ((1, 1, 5, "81 FF 01 00 0A 00 04 00"), r"granted node ID 255 is out of range"),
        ((1, 0, 5, "83 03 09 00 01"), r"0x83 .*response code 3 is not one of 0 FAILURE"),
        ((1, 0, 5, "8B 02"), r"0x8B Reset Device Response: response code 2 is not one of"),
        ((1, 0, 5, "0E 00 41"), r"0x0E Bulk Data Transfer: packet ID 0 is out of range \(1–255\)"),
        ((1, 0, 5, ""), r"empty frame has no function code"),
        ((1, 0, 5, "00"), r"function code 0x00 undefined"),
        ((1, 0, 5, "02 01"), r"0x02 deprecated command"),
        ((1, 0, 5, "50"), r"0x50 reserved for module-specific commands"),
        ((1, 0, 5, "D0"), r"0xD0 reserved for device-specific responses"),
        ((1, 0, 5, "0A 00 00 00 00 00 00 00 00"), r"9 data bytes"),
    ],
)
def test_bad_frames_raise_frame_error(row: tuple, match: str) -> None:
    with pytest.raises(FrameError, match=match):
        decode(*frame(*row))


def test_class_decode_checks_its_code() -> None:
    with pytest.raises(FrameError, match=r"^0x03 Get Device Parameter: function code is 0x0C"):
        GetParameter.decode(*frame(1, 1, 5, "0C 07 00"))
    with pytest.raises(FrameError, match="function code is missing"):
        Reset.decode(make_id(1, 1, 5), b"")


@pytest.mark.parametrize(
    ("factory", "match"),
    [
        (lambda: GetParameter(5, 256, 0), r"^0x03 Get Device Parameter: param 256 is out of range"),
        (lambda: GetParameter(255, 1, 0), r"node ID 255 is out of range \(0–254\)"),
        (lambda: BindRequest(1, 0x10000, 0, 0), r"vid 65536 is out of range \(0–65535\)"),
        (lambda: Suspend(5, -1), r"ms -1 is out of range"),
        (lambda: SetParameter(5, 1, 0, b""), r"value of 0 bytes \(1–4 bytes expected\)"),
        (lambda: SetParameter(5, 1, 0, b"12345"), r"value of 5 bytes"),
        (lambda: GetParameterResponse(5, OK, 1, 0, b"12345"), r"value of 5 bytes \(0–4"),
        (lambda: BulkData(5, 1, b"", mode=DEV), r"data of 0 bytes \(1–6 bytes expected\)"),
        (lambda: BulkData(5, 1, b"1234567", mode=DEV), r"data of 7 bytes"),
        (lambda: BulkData(5, 1, b"1", mode=2), r"mode 2 is not one of"),
        (lambda: Beacon(5, priority=Priority.BINDING), r"reserved for the Bind"),
        (lambda: BindRequest(5, 1, 1, 1, priority=Priority.HIGH), r"priority 3 \(BINDING\)"),
        (lambda: ResetResponse(5, 2), r"response code 2"),
        (lambda: GetParameter(5, "1", 0), r"param '1' is not an integer"),
        (lambda: SetParameter(5, 1, 0, "1"), r"value '1' is not bytes"),
        (lambda: ChannelData(0, b""), r"channel node ID 0 is out of range \(1–254\)"),
        (lambda: ChannelData(6, bytes(9)), r"9 bytes \(0–8 expected\)"),
        (lambda: ChannelData(6, b"", priority=Priority.BINDING), r"priority 3 is not one of"),
    ],
)
def test_construction_checks_ranges(factory: object, match: str) -> None:
    with pytest.raises(FrameError, match=match):
        factory()  # type: ignore[operator]


def test_fields_are_normalised() -> None:
    response = GetParameterResponse(5, 1, 9, 0, bytearray(b"\x01"), priority=1)
    assert response.code is ResponseCode.SUCCESS
    assert response.priority is Priority.NORMAL
    assert type(response.value) is bytes
    assert BulkData(5, 1, b"x", mode=1).mode is Mode.ARBITRATOR
    assert GetParameter(5, 9, 0).mode is Mode.ARBITRATOR
    assert GetParameter(5, 9, 0).function_code is FunctionCode.GET_PARAMETER


def test_messages_are_frozen_and_hashable() -> None:
    message = GetParameter(5, 9, 0)
    with pytest.raises(AttributeError):
        message.param = 3  # type: ignore[misc]
    assert len({message, GetParameter(5, 9, 0)}) == 1


def test_other_round_trips() -> None:
    for message in [
        Suspend(5, 0), Suspend(5, 65535), SuspendResponse(5, OK, 1000), Release(5),
        ReleaseResponse(5, ResponseCode.FAILURE), Beacon(0, mode=BA), Beacon(7, priority=2),
        SetParameterResponse(5, USE_BULK, 9, 1, b"\x80"), GetParameterResponse(5, 0, 1, 0),
        GetParameter(0, 1, 0),  # broadcast
    ]:
        assert decode(*message.encode()) == message


def test_channel_data_dispatch() -> None:
    arbitration_id, data = ChannelData(6, b"\x01\x02").encode()
    assert arbitration_id == 0x206
    assert decode(arbitration_id, data, channel_node_ids={6}) == ChannelData(6, b"\x01\x02")
    assert decode(arbitration_id, b"", channel_node_ids=frozenset({6})) == ChannelData(6, b"")
    # Not a channel node ID: the same bytes are read as a function code.
    with pytest.raises(FrameError, match="0x01 Bind Device Request: DLC 2 is too short"):
        decode(arbitration_id, data)
    # Mode 1 frames are never channel data, nor are priority-3 (binding) frames.
    assert decode(*frame(1, 1, 6, "0B"), channel_node_ids={6}) == Reset(6)
    bind = frame(3, 0, 6, "01 01 00 0A 00 04 00")
    assert isinstance(decode(*bind, channel_node_ids={6}), BindRequest)
    with pytest.raises(FrameError, match="only outputs"):
        ChannelData.decode(make_id(1, 1, 6), b"")


def test_describe() -> None:
    assert describe(GetParameterResponse(5, OK, 9, 0, b"\x01")) == (
        "0x83 Get Device Parameter Response ← node 5: success, "
        "Number of Data Channels (param 9, channel 0) = 1"
    )
    assert describe(SetParameter(5, 5, 1, b"\x06")) == (
        "0x04 Set Device Parameter → node 5: "
        "Source's VID and PID / Channel Node Id (param 5, channel 1) = 06"
    )
    assert describe(SetParameter(5, 5, 1, b"\x06"), Direction.OUTPUT) == (
        "0x04 Set Device Parameter → node 5: Channel Node Id (param 5, channel 1) = 6"
    )
    assert describe(BindResponse(1, 5, 1, 10, 4)) == (
        "0x81 Bind Device Request Response → node 1: node ID 5 suggested, "
        "VID 0x0001, PID 0x000A, SN 4"
    )
    assert describe(Beacon(5)) == "0x0A Device Beacon ← node 5"
    assert describe(Reset(0)) == "0x0B Reset Device → node all"
    assert describe(Suspend(5, 0)) == "0x08 Suspend Device → node 5: indefinitely"
    assert describe(ConfigureGetBulkResponse(5, OK, 7, 0, 33)) == (
        "0x8C Configure Get Bulk Data Transfer Response ← node 5: success, "
        "Device Descriptor (param 7, channel 0), 33 bytes"
    )
    assert describe(BulkData(5, 6, b"or\0", mode=DEV)) == (
        "0x0E Bulk Data Transfer ← node 5: packet 6: 6F 72 00"
    )
    assert describe(UpdateDataChannel(5, 4)) == "0x0F Update Data Channel ← node 5: channel 4"
    assert describe(ChannelData(6, b"\x01\xff")) == "Channel data ← node 6: 01 FF"
    assert "use bulk data transfer" in describe(GetParameterResponse(5, USE_BULK, 7, 0))
