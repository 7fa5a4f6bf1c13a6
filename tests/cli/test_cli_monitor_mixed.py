"""Stray frames of another bus inside a PDCP capture (issue 10 item 4): no foreign frame is
shown as a PDCP command unless it fits one in context — a response only after its request,
a request only to or from a device the monitor knows — and none teaches the decoder a node
map; the PDCP frames around them read exactly as in the clean capture."""

from __future__ import annotations

import json
import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdcp_studio.bus.trace.monitor import FrameDecoder
from pdcp_studio.cli.main import main
from pdcp_studio.protocol import messages as M
from pdcp_studio.protocol.codes import ResponseCode
from pdcp_studio.protocol.identifier import Mode
from tests.bus.test_monitor import session_frames
from tests.cli.test_cli_monitor_captures import write_capture

OK = ResponseCode.SUCCESS
BA, DEV = Mode.ARBITRATOR, Mode.DEVICE
#: Node IDs of the PDCP session (devices 1→5 and 7, output 6, the undecodable frame's 9).
SESSION_NODES = {0, 1, 5, 6, 7, 9}


def car_frames_that_parse() -> list[tuple[int, bytes]]:
    """A car's frames that happen to have the exact shape of PDCP messages, on node IDs the
    PDCP session never uses: every request and bulk packet kind to some, every response
    kind from others (a request and its answer both by chance would fit)."""
    frames = []
    for node in (0x21, 0x44, 0x63):
        msgs = [
            M.GetParameter(node, 9, 0),
            M.SetParameter(node, 5, 1, b"\x30"),  # would make node 0x30 an output
            M.SetParameter(node, 7, 2, bytes([5, 0x32])),
            M.Suspend(node, 0), M.Release(node), M.Reset(node),
            M.ConfigureGetBulk(node, 2, 1), M.ConfigureSetBulk(node, 2, 1, 7),
            M.BulkData(node, 1, b"abc", mode=DEV), M.BulkData(node, 1, b"abc", mode=BA),
            M.Beacon(node, mode=BA),
        ]
        frames += [m.encode() for m in msgs]
    for node in (0xA5, 0xC8):
        msgs = [
            M.GetParameterResponse(node, OK, 9, 0, b"\x02"),
            M.SetParameterResponse(node, OK, 5, 1, b"\x31"),
            M.SetParameterResponse(node, OK, 8, 0, b"\x33"),  # would move a device
            M.SuspendResponse(node, OK, 0), M.ReleaseResponse(node, OK),
            M.ResetResponse(node, OK), M.ConfigureGetBulkResponse(node, OK, 2, 1, 7),
            M.ConfigureSetBulkResponse(node, OK, 2, 1, 7),
            M.BulkDataResponse(node, OK, mode=BA), M.UpdateDataChannelResponse(node, OK, 2),
            M.BindResponse(node, node, 9, 9, 9),
        ]
        frames += [m.encode() for m in msgs]
    # A response from a session device to a request it never got.
    frames.append(M.GetParameterResponse(5, OK, 9, 0, b"\x07").encode())
    return frames


def mixed(car, seed: int = 0):
    """The PDCP session with ``car`` frames spread through it (after the first bind)."""
    rng = random.Random(seed)
    pdcp = session_frames()
    out = [pdcp[0]]
    slots = sorted(rng.randrange(1, len(pdcp)) for _ in car)
    car_iter = iter(car)
    k = 0
    for i, frame in enumerate(pdcp[1:], start=1):
        while k < len(slots) and slots[k] == i:
            out.append(next(car_iter))
            k += 1
        out.append(frame)
    out += list(car_iter)
    return out


def replay_json(tmp_path, frames, capsys, name="mixed.asc"):
    path = tmp_path / name
    write_capture(path, frames)
    assert main(["monitor", "--replay", str(path), "--json"]) == 0
    out, err = capsys.readouterr()
    return json.loads(out)["frames"], err


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_stray_frames_that_parse_are_not_shown_as_commands(tmp_path, capsys, seed):
    car = car_frames_that_parse()
    clean, _ = replay_json(tmp_path, session_frames(), capsys, "clean.asc")
    records, err = replay_json(tmp_path, mixed(car, seed), capsys)
    strays = {(a, d.hex()) for a, d in car}
    shown = [r for r in records if (r["arbitration_id"], r["data"]) in strays]
    assert len(shown) == len(car)
    commands = [r["text"] for r in shown if r["function"] != "unattributed"]
    assert not commands, commands
    assert all(r["error"] is None for r in shown)  # unattributed, not errors
    # The PDCP frames read exactly as in the clean capture (the car taught nothing).
    pdcp = [r for r in records if (r["arbitration_id"], r["data"]) not in strays]
    assert [(r["function"], r["fields"], r["link"]) for r in pdcp] == \
        [(r["function"], r["fields"], r["link"]) for r in clean]
    assert "not PDCP" not in err and "2 errors (1 undecodable" in err


def test_the_stray_frames_teach_no_node_map():
    decoder = FrameDecoder()
    decoder.context_checked = True
    for i, (a, d) in enumerate(mixed(car_frames_that_parse())):
        decoder.decode(a, d, 10.0 + i / 1000)
    clean = FrameDecoder()
    clean.context_checked = True
    for i, (a, d) in enumerate(session_frames()):
        clean.decode(a, d, 10.0 + i / 1000)
    assert decoder.node_map() == clean.node_map()
    assert not set(decoder.heard) - SESSION_NODES


def test_a_request_to_a_node_first_heard_answering_fits_from_then_on():
    """Joining a bus late: the first request to an unknown node is unattributed, its answer
    fits (a request was seen), and the node's next requests are shown as commands."""
    decoder = FrameDecoder()
    decoder.context_checked = True
    frames = [M.GetParameter(12, 9, 0), M.GetParameterResponse(12, OK, 9, 0, b"\x01"),
              M.GetParameter(12, 9, 0), M.GetParameterResponse(12, OK, 9, 0, b"\x01"),
              M.GetParameterResponse(12, OK, 9, 0, b"\x01")]  # an answer nobody asked for
    functions = [decoder.decode(*m.encode(), float(i)).function for i, m in enumerate(frames)]
    assert functions == ["unattributed", "Get Device Parameter Response",
                         "Get Device Parameter", "Get Device Parameter Response",
                         "unattributed"]


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 0x7FF), st.binary(max_size=8)), max_size=60),
       st.integers(0, 5))
def test_no_stray_frame_from_an_unknown_node_is_a_command(noise, seed):
    """Any foreign base frames on node IDs the session does not use: none becomes a PDCP
    message but bind requests and device beacons (PDCP's ways in, exactly framed)."""
    noise = [(a, d) for a, d in noise if a & 0xFF not in SESSION_NODES]
    decoder = FrameDecoder()
    decoder.context_checked = True
    strays = set(noise)
    for i, (a, d) in enumerate(mixed(noise, seed)):
        frame = decoder.decode(a, d, float(i))
        if (a, d) in strays and frame.message is not None:
            assert frame.message.CODE in (0x01, 0x0A, 0x81, 0x83, 0x84, 0x88, 0x89, 0x8B,
                                          0x8C, 0x8D, 0x8E, 0x8F) or \
                frame.node_id in decoder.devices or frame.node_id in decoder.heard, frame.line
            if frame.message.CODE >= 0x80:  # a response: only to a request just seen
                assert frame.node_id not in SESSION_NODES or frame.node_id in decoder.heard
