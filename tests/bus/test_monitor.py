"""The bus monitor: every function code decoded, undecodable frames counted, learning the bus,
bulk transfers reassembled, and captures written and read back in python-can's log formats.

``tests/data/captures/pdcp-session.asc`` was made by ``record_on_virtual_bus(session_frames())``:
the worked frames of 001 §3.3 (binding with a suggested ID, get/set, beacon, reset, bulk get
of the 33-byte descriptor, bulk set of 17 bytes, update data channel) around a second device
whose input is linked to the first device's output, then channel data and one frame with a
module-specific code. ``test_committed_capture_matches_a_fresh_recording`` keeps it honest.
"""

from __future__ import annotations

import itertools
import threading
import time
import uuid
from pathlib import Path

import can
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdcp_studio.bus.trace.bustime import frame_bits
from pdcp_studio.bus.trace.monitor import (
    CHANNEL_DATA,
    FROM_BA,
    TO_BA,
    CaptureError,
    FrameDecoder,
    Recorder,
    read_capture,
    replay,
)
from pdcp_studio.model.parameters import DEVICE_DESCRIPTOR, device_parameter, encode_value
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.protocol import messages as M
from pdcp_studio.protocol.bulk import packetize
from pdcp_studio.protocol.codes import FunctionCode, ResponseCode
from pdcp_studio.protocol.identifier import Mode, make_id

CAPTURES = Path(__file__).resolve().parent.parent / "data" / "captures"
SESSION_CAPTURE = CAPTURES / "pdcp-session.asc"
OK, FAIL, BULK = ResponseCode.SUCCESS, ResponseCode.FAILURE, ResponseCode.USE_BULK
DEV, BA = Mode.DEVICE, Mode.ARBITRATOR
DESCRIPTOR = "Prototype PDCP Device Descriptor"
UNDECODABLE_FRAME = (make_id(1, 0, 9), b"\x50\x01")  # a module-specific code (0x50)


def session_frames() -> list[tuple[int, bytes]]:
    """001 §3.3 plus a link: device 1/10/4 at node 5 (output 1 = node 6) → 2/2/5#2 at node 7."""
    desc = encode_value(device_parameter(DEVICE_DESCRIPTOR), DESCRIPTOR)
    msgs = [
        M.BindRequest(1, 1, 0x0A, 4), M.BindResponse(1, 5, 1, 0x0A, 4),
        M.BindRequest(5, 1, 0x0A, 4), M.BindResponse(5, 5, 1, 0x0A, 4),
        M.BindRequest(7, 2, 2, 5), M.BindResponse(7, 7, 2, 2, 5),
        M.GetParameter(5, 9, 0), M.GetParameterResponse(5, OK, 9, 0, b"\x01"),
        M.GetParameter(5, 3, 1), M.GetParameterResponse(5, OK, 3, 1, b"\x02"),
        M.SetParameter(5, 5, 1, b"\x06"), M.SetParameterResponse(5, OK, 5, 1, b"\x06"),
        M.Beacon(5),
        M.GetParameter(5, 7, 0), M.GetParameterResponse(5, BULK, 7, 0),
        M.ConfigureGetBulk(5, 7, 0), M.ConfigureGetBulkResponse(5, OK, 7, 0, len(desc)),
        *(M.BulkData(5, p.packet_id, p.data, mode=DEV) for p in packetize(desc)),
        M.BulkDataResponse(5, OK, mode=BA),
        M.ConfigureSetBulk(5, 0x37, 0, 17), M.ConfigureSetBulkResponse(5, OK, 0x37, 0, 17),
        *(M.BulkData(5, p.packet_id, p.data, mode=BA) for p in packetize(bytes(range(1, 18)))),
        M.BulkDataResponse(5, OK, mode=DEV),
        M.UpdateDataChannel(7, 2),
        M.GetParameter(7, 3, 2), M.GetParameterResponse(7, OK, 3, 2, b"\x01"),
        M.SetParameter(7, 7, 2, bytes([5, 6])), M.SetParameterResponse(7, OK, 7, 2, bytes([5, 6])),
        M.SetParameter(7, 4, 2, b"\x01"), M.SetParameterResponse(7, OK, 4, 2, b"\x01"),
        M.UpdateDataChannelResponse(7, OK, 2),
        M.SetParameter(5, 4, 1, b"\x01"), M.SetParameterResponse(5, OK, 4, 1, b"\x01"),
        M.ChannelData(6, b"\x12\x34"), M.ChannelData(6, b"\x13\x34"),
        M.Suspend(7, 1000), M.SuspendResponse(7, OK, 1000),
        M.Release(7), M.ReleaseResponse(7, OK),
        M.Reset(5), M.ResetResponse(5, FAIL),
    ]
    return [m.encode() for m in msgs] + [UNDECODABLE_FRAME]


def record_on_virtual_bus(frames: list[tuple[int, bytes]], path: Path, gap_s: float = 0.001) -> None:
    """Send ``frames`` on a fresh virtual bus and record what a second node receives."""
    channel = f"monitor-{uuid.uuid4().hex}"
    rx = can.Bus(interface="virtual", channel=channel)
    tx = can.Bus(interface="virtual", channel=channel)
    received = threading.Event()
    count = 0
    with Recorder(path) as recorder:
        def on_frame(msg: can.Message) -> None:
            nonlocal count
            recorder.write_message(msg)
            count += 1
            if count == len(frames):
                received.set()

        notifier = can.Notifier(rx, [on_frame], timeout=0.05)
        try:
            for arbitration_id, data in frames:
                tx.send(can.Message(arbitration_id=arbitration_id, data=data,
                                    is_extended_id=False))
                time.sleep(gap_s)
            assert received.wait(5), f"only {count} of {len(frames)} frames arrived"
        finally:
            notifier.stop(0.5)
            tx.shutdown()
            rx.shutdown()


def decode_all(frames, decoder: FrameDecoder | None = None):
    decoder = decoder or FrameDecoder()
    return [decoder.decode(a, d, 100.0 + i / 1000) for i, (a, d) in enumerate(frames)], decoder


# -- every function code ------------------------------------------------------------------------

ONE_OF_EACH = [
    M.BindRequest(1, 1, 2, 3), M.BindResponse(1, 4, 1, 2, 3),
    M.GetParameter(3, 9, 0), M.GetParameterResponse(3, OK, 9, 0, b"\x02"),
    M.SetParameter(3, 10, 0, b"\xe8\x03"), M.SetParameterResponse(3, OK, 10, 0, b"\xe8\x03"),
    M.Suspend(3, 0), M.SuspendResponse(3, OK, 0), M.Release(3), M.ReleaseResponse(3, OK),
    M.Beacon(3), M.Beacon(0, mode=BA), M.Reset(3), M.ResetResponse(3, OK),
    M.ConfigureGetBulk(3, 2, 1), M.ConfigureGetBulkResponse(3, OK, 2, 1, 7),
    M.ConfigureSetBulk(3, 2, 1, 7), M.ConfigureSetBulkResponse(3, OK, 2, 1, 7),
    M.BulkData(3, 1, b"abc", mode=DEV), M.BulkDataResponse(3, OK, mode=BA),
    M.UpdateDataChannel(3, 2), M.UpdateDataChannelResponse(3, OK, 2),
]


def test_one_of_each_covers_every_function_code():
    assert {m.CODE for m in ONE_OF_EACH} == set(FunctionCode)


@pytest.mark.parametrize("msg", ONE_OF_EACH, ids=lambda m: f"{m.CODE:02X}")
def test_every_function_code_decodes_to_its_name(msg):
    decoder = FrameDecoder()
    frame = decoder.decode(*msg.encode(), 5.0)
    assert frame.error is None and frame.message == msg
    assert frame.function == msg.CODE.title
    assert frame.direction == (TO_BA if msg.mode is DEV else FROM_BA)
    assert frame.priority == msg.priority and frame.node_id == msg.node_id
    assert msg.CODE.title in frame.line and decoder.stats.by_function[msg.CODE.title] == 1
    assert decoder.stats.errors == 0


def test_get_parameter_line_names_parameter_and_channel():
    frame = FrameDecoder().decode(*M.GetParameter(3, 9, 0).encode())
    assert "P1  BA→#3 Get Device Parameter  param 9 Number of Data Channels  chan 0" in frame.line


def test_fields_of_typical_frames():
    lines = [f.line for f in decode_all([m.encode() for m in ONE_OF_EACH])[0]]
    text = "\n".join(lines)
    for expected in ["#1→BA Bind Device Request  asks for node 1  VID 0x0001 PID 0x0002 SN 3",
                     "BA→#1 Bind Device Request Response  node 4 suggested",
                     "success  param 9 Number of Data Channels  chan 0  = 2",
                     "param 10 Beacon Interval  chan 0  = 1000 ms",
                     "Suspend Device  indefinitely", "BA→all Device Beacon",
                     "param 2 Channel Descriptor  chan 1  size 7 bytes",
                     "packet 1/2  61 62 63  bulk transfer aborted: bulk packet 1 carries 3 bytes",
                     "#3→BA Update Data Channel  chan 2"]:
        assert expected in text, expected


def test_response_codes_are_named_and_failures_counted():
    frames, decoder = decode_all([
        M.ResetResponse(3, FAIL).encode(), M.GetParameterResponse(3, BULK, 7, 0).encode(),
        M.SetParameterResponse(3, FAIL, 8, 0, b"\x09").encode()])
    assert [f.response for f in frames] == ["failure", "use bulk data transfer", "failure"]
    assert "Reset Device Response  failure" in frames[0].line
    assert decoder.stats.failures == 2 and decoder.stats.undecodable == 0


# -- undecodable frames -------------------------------------------------------------------------

BAD_FRAMES = [
    (make_id(1, 0, 4), b"\x50\x01", {}, "module-specific"),
    (make_id(1, 0, 4), b"\x02", {}, "deprecated"),
    (make_id(1, 1, 4), b"\x83", {}, "DLC 1 is too short"),
    (make_id(1, 1, 4), b"\x83\x01\x09\x00\x01", {}, "only a device sends it"),
    (make_id(1, 0, 4), b"", {}, "empty frame"),
    (0x0FF, b"\x0a", {}, "node ID 255"),
    (0x1234567, b"\x0a", {"is_extended_id": True}, "extended 29-bit"),
    (make_id(1, 0, 4), b"", {"is_remote_frame": True}, "remote frame"),
    (0, b"", {"is_error_frame": True}, "error frame"),
    (make_id(1, 0, 4), bytes(9), {}, "9 data bytes"),
]


def test_undecodable_frames_are_shown_and_counted_never_raised():
    decoder = FrameDecoder()
    for arbitration_id, data, flags, reason in BAD_FRAMES:
        frame = decoder.decode(arbitration_id, data, 1.0, **flags)
        assert frame.function.startswith("undecodable: ") and reason in frame.function, frame.line
        assert frame.error and reason in frame.error
    assert decoder.stats.undecodable == len(BAD_FRAMES) == decoder.stats.frames
    assert decoder.stats.by_function["undecodable"] == len(BAD_FRAMES)
    assert decoder.stats.errors == len(BAD_FRAMES)


@settings(max_examples=300, deadline=None)
@given(st.integers(0, 0x7FF), st.binary(max_size=8))
def test_any_base_frame_decodes_to_a_line(arbitration_id, data):
    frame = FrameDecoder().decode(arbitration_id, data)
    assert frame.line and frame.as_json()["data"] == data.hex()


# -- learning the bus ---------------------------------------------------------------------------

LINK_SETUP = [
    M.BindResponse(5, 5, 1, 10, 4), M.BindResponse(7, 7, 2, 2, 5),
    M.SetParameter(5, 5, 1, b"\x06"),  # output 1 of node 5 sends as node 6
    M.SetParameter(7, 7, 2, bytes([5, 6])),  # input 2 of node 7 listens to node 6
]


def test_data_frame_names_the_link_it_learned():
    frames, decoder = decode_all([m.encode() for m in LINK_SETUP] + [M.ChannelData(6, b"\x42").encode()])
    data = frames[-1]
    assert data.direction == CHANNEL_DATA and data.function == "Channel data"
    assert data.link == (ChannelRef(1, 10, 4, 1), (ChannelRef(2, 2, 5, 2),))
    assert "#6 data Channel data  1/10/4#1 → 2/2/5#2  42" in data.line
    assert decoder.channel_node_ids == {6}
    assert "Source's Node Ids" in frames[3].line and "device node 5, channel node 6" in frames[3].line


def test_unlinking_and_unknown_devices():
    decoder = FrameDecoder()
    decode_all([m.encode() for m in LINK_SETUP], decoder)
    decoder.decode(*M.SetParameter(7, 7, 2, bytes([0, 0])).encode())  # source removed
    assert "1/10/4#1 → no input known" in decoder.decode(*M.ChannelData(6, b"").encode()).line
    decoder.decode(*M.SetParameter(9, 5, 3, b"\x0b").encode())  # node 9 never bound
    assert "node 9#3 →" in decoder.decode(*M.ChannelData(11, b"\x01").encode()).line
    decoder.decode(*M.SetParameter(5, 5, 1, b"\x00").encode())  # output 1 no longer sends
    assert decoder.channel_node_ids == {11}


def test_caller_mapping_wins_and_may_change():
    out, inp = ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2)
    links: dict = {}
    decoder = FrameDecoder(links)
    assert decoder.decode(*M.ChannelData(20, b"\x01").encode()).direction != CHANNEL_DATA
    links[20] = (out, [inp])
    frame = decoder.decode(*M.ChannelData(20, b"\x01").encode())
    assert frame.link == (out, (inp,)) and "2/2/4#1 → 2/2/5#2" in frame.line
    assert frame.as_json()["link"] == {"output": out.as_json(), "inputs": [inp.as_json()]}


def test_direction_learned_names_channel_parameters():
    decoder = FrameDecoder()
    # Unknown direction: param 5 on a channel is named for both.
    assert "Source's VID and PID / Channel Node Id" in decoder.decode(*M.GetParameter(4, 5, 2).encode()).line
    decoder.decode(*M.GetParameterResponse(4, OK, 3, 2, b"\x01").encode())  # Transfer Type: input
    assert "param 5 Source's VID and PID  chan 2" in decoder.decode(*M.GetParameter(4, 5, 2).encode()).line
    decoder.decode(*M.GetParameterResponse(4, OK, 3, 1, b"\x02").encode())  # output
    line = decoder.decode(*M.GetParameterResponse(4, OK, 5, 1, b"\x09").encode()).line
    assert "param 5 Channel Node Id  chan 1  = 9" in line and decoder.channel_node_ids == {9}


def test_identity_from_reads_and_device_node_id_writes():
    decoder = FrameDecoder()
    decode_all([M.GetParameterResponse(8, OK, 1, 0, bytes([2, 0, 3, 0])).encode(),
                M.GetParameterResponse(8, OK, 2, 0, bytes([7, 0])).encode(),
                M.SetParameter(8, 5, 1, b"\x0c").encode()], decoder)
    assert "2/3/7#1" in decoder.decode(*M.ChannelData(12, b"").encode()).line
    decoder.decode(*M.SetParameter(8, 8, 0, b"\x0d").encode())  # the device moves to node 13
    assert decoder.devices == {13: (2, 3, 7)} and decoder.outputs == {12: (13, 1)}
    assert "2/3/7#1" in decoder.decode(*M.ChannelData(12, b"").encode()).line
    decoder.decode(*M.BindResponse(13, 13, 2, 3, 8).encode())  # another device takes node 13
    assert decoder.devices == {13: (2, 3, 8)} and decoder.channel_node_ids == frozenset()


# -- bulk transfers -----------------------------------------------------------------------------


def test_bulk_get_of_001_descriptor_is_reassembled():
    frames, decoder = decode_all(session_frames())
    done = [f for f in frames if "complete:" in f.fields]
    assert len(done) == 2
    assert done[0].fields.endswith(f"complete: Device Descriptor chan 0 = '{DESCRIPTOR}'")
    assert "packet 6/6" in done[0].line and "packet 3/3" in done[1].line
    assert decoder.bulk_values[5, 0, 7] == DESCRIPTOR.encode() + b"\0"
    assert decoder.bulk_values[5, 0, 0x37] == bytes(range(1, 18))


def test_bulk_fault_aborts_that_transfer_only():
    frames, decoder = decode_all([
        M.ConfigureGetBulkResponse(5, OK, 7, 0, 12).encode(),
        M.ConfigureSetBulk(6, 2, 1, 3).encode(),
        M.BulkData(5, 2, b"abcdef", mode=DEV).encode(),  # packet 1 expected
        M.BulkData(6, 1, b"xyz", mode=BA).encode(),
    ])
    assert frames[2].error and "bulk transfer aborted" in frames[2].line
    assert "complete: Channel Descriptor chan 1 = 'xyz'" in frames[3].line
    assert decoder.stats.bulk_errors == 1 and decoder.stats.undecodable == 0


def test_refused_set_bulk_is_forgotten():
    frames, _ = decode_all([M.ConfigureSetBulk(6, 2, 1, 3).encode(),
                            M.ConfigureSetBulkResponse(6, FAIL, 2, 1, 3).encode(),
                            M.BulkData(6, 1, b"xyz", mode=BA).encode()])
    assert "no transfer announced" in frames[2].line


# -- statistics ---------------------------------------------------------------------------------


def test_statistics_count_functions_errors_and_bus_time():
    frames = session_frames()
    decoded, decoder = decode_all(frames)
    stats = decoder.stats
    assert stats.frames == len(frames) and stats.undecodable == 1 and stats.failures == 1
    assert stats.by_function["Bulk Data Transfer"] == 9 and stats.by_function["Channel data"] == 2
    assert stats.meter.bits == sum(frame_bits(a, d) for a, d in frames)
    span = decoded[-1].timestamp - decoded[0].timestamp
    assert stats.meter.load() == pytest.approx(stats.meter.bits / 1e6 / span)
    summary = stats.summary()
    assert summary.startswith(f"{len(frames)} frames, 2 errors (1 undecodable, 1 failure")
    assert "bus load" in summary and stats.as_json()["by_function"]["Channel data"] == 2


# -- captures -----------------------------------------------------------------------------------

FORMATS = [".asc", ".blf", ".csv", ".log", ".trc", ".db", ".asc.gz", ".log.gz", ".trc.gz"]


@pytest.mark.parametrize("suffix", FORMATS)
def test_capture_round_trip(tmp_path, suffix):
    frames = session_frames()
    path = tmp_path / f"capture{suffix}"
    t0 = 1_700_000_000.25
    with Recorder(path) as recorder:
        for i, (arbitration_id, data) in enumerate(frames):
            recorder.write(arbitration_id, data, t0 + i * 0.0015)
    assert recorder.frames == len(frames)
    back = list(read_capture(path))
    assert [(m.arbitration_id, bytes(m.data), m.is_extended_id) for m in back] == \
        [(a, d, False) for a, d in frames]
    for i, msg in enumerate(back):
        assert msg.timestamp - back[0].timestamp == pytest.approx(i * 0.0015, abs=2e-6)
    def shown(f):
        return f.who, f.priority, f.function, f.fields

    assert [shown(f) for f in replay(path)] == [shown(f) for f in decode_all(frames)[0]]


def test_recorder_refuses_unknown_format(tmp_path):
    with pytest.raises(CaptureError, match=r"capture\.xyz"):
        Recorder(tmp_path / "capture.xyz")


@pytest.mark.parametrize("name, content", [
    ("garbage.blf", b"\x00\xffnot a blf file at all"),
    ("garbage.asc", b"\xff\xfe\x00 binary"),
    ("garbage.db", b"not a database, not at all, really not"),
    ("capture.xyz", b"whatever"),
])
def test_unreadable_capture_names_file_and_reason(tmp_path, name, content):
    path = tmp_path / name
    path.write_bytes(content)
    with pytest.raises(CaptureError) as info:
        list(replay(path))
    assert name in str(info.value) and info.value.reason


def test_missing_capture(tmp_path):
    with pytest.raises(CaptureError, match="no such file"):
        list(replay(tmp_path / "nope.asc"))


def test_virtual_bus_capture_decodes(tmp_path):
    path = tmp_path / "live.blf"
    record_on_virtual_bus(session_frames(), path, gap_s=0)
    decoder = FrameDecoder()
    lines = [f.line for f in replay(path, decoder)]
    assert len(lines) == len(session_frames()) and decoder.stats.undecodable == 1
    assert any(f"'{DESCRIPTOR}'" in line for line in lines)
    assert any("1/10/4#1 → 2/2/5#2  12 34" in line for line in lines)


def test_committed_capture_matches_a_fresh_recording(tmp_path):
    fresh = tmp_path / "fresh.asc"
    record_on_virtual_bus(session_frames(), fresh, gap_s=0)
    committed = [m for m in read_capture(SESSION_CAPTURE)]
    assert [(m.arbitration_id, bytes(m.data)) for m in committed] == \
        [(m.arbitration_id, bytes(m.data)) for m in read_capture(fresh)]
    assert all(b.timestamp > a.timestamp for a, b in itertools.pairwise(committed))


if __name__ == "__main__":  # pragma: no cover - regenerates the committed capture
    record_on_virtual_bus(session_frames(), SESSION_CAPTURE)


def test_a_channel_name_with_long_trailing_digits_still_records(tmp_path):
    """python-can reads a channel number from a name's trailing digits; BLF holds a u16."""
    path = tmp_path / "named.blf"
    msg = can.Message(arbitration_id=0x601, data=b"\x01\x01\x00", is_extended_id=False,
                      channel="monitor-08a81c7c786c490cb46c66be45734036", timestamp=1.0)
    with Recorder(path) as recorder:
        recorder.write_message(msg)
    assert msg.channel == "monitor-08a81c7c786c490cb46c66be45734036"  # not changed in place
    (back,) = list(read_capture(path))
    assert back.arbitration_id == 0x601 and bytes(back.data) == b"\x01\x01\x00"


def test_a_folder_is_not_a_capture(tmp_path):
    with pytest.raises(CaptureError, match="folder"):
        list(read_capture(tmp_path))
