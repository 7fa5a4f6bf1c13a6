"""`pdcp-studio monitor`: replaying captures, --json, filters, --log, live on a virtual bus,
the session path for sim: URLs (against a stand-in session), and the exit statuses."""

from __future__ import annotations

import json
import subprocess
import sys
import threading
import time
import uuid
from pathlib import Path

import can
import pytest

from pdcp_studio.bus.events import FrameSeen
from pdcp_studio.cli.main import main
from pdcp_studio.protocol import messages as M

ROOT = Path(__file__).resolve().parents[2]
CAPTURE = ROOT / "tests" / "data" / "captures" / "pdcp-session.asc"
FRAMES_IN_CAPTURE = 49
DESCRIPTOR = "'Prototype PDCP Device Descriptor'"


def test_replay_prints_decoded_lines_and_statistics(capsys):
    assert main(["monitor", "--replay", str(CAPTURE)]) == 0
    out, err = capsys.readouterr()
    lines = out.splitlines()
    assert len(lines) == FRAMES_IN_CAPTURE
    assert "P1  BA→#5 Get Device Parameter  param 9 Number of Data Channels  chan 0" in lines[6]
    assert f"complete: Device Descriptor chan 0 = {DESCRIPTOR}" in out
    assert "#6 data Channel data  1/10/4#1 → 2/2/5#2  12 34" in out
    assert "Reset Device Response  failure" in out
    assert "undecodable: " in lines[-1] and "module-specific" in lines[-1]
    assert err.startswith(f"{FRAMES_IN_CAPTURE} frames, 2 errors (1 undecodable")


def test_replay_json_is_one_document_of_frames_and_summary(capsys):
    assert main(["monitor", "--replay", str(CAPTURE), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    frames, summary = doc["frames"], doc["summary"]
    assert isinstance(frames, list) and len(frames) == FRAMES_IN_CAPTURE
    assert summary["verdict"] == "pdcp" and summary["frames"] == FRAMES_IN_CAPTURE
    assert summary["truncated"] is False and summary["undecodable"] == 1
    first = frames[0]
    assert first["function"] == "Bind Device Request" and first["direction"] == "device→BA"
    assert first["arbitration_id"] == 0x601 and first["data"] == "0101000a000400"
    assert first["priority"] == 3 and first["node_id"] == 1 and first["time"] == 0
    data = [f for f in frames if f["direction"] == "channel data"]
    assert data[0]["link"] == {"output": {"vid": 1, "pid": 10, "serial": 4, "index": 1},
                               "inputs": [{"vid": 2, "pid": 2, "serial": 5, "index": 2}]}
    assert frames[-1]["error"] and frames[-1]["function"].startswith("undecodable")


@pytest.mark.parametrize("filters, count, check", [
    (["function=bulk data transfer"], 15, "Bulk Data Transfer"),
    (["function=0x0E"], 9, "Bulk Data Transfer  packet"),
    (["node=7"], 14, "#7"),
    (["direction=data"], 2, "Channel data"),
    (["direction=from-ba", "node=7"], 7, "BA→#7"),
    (["errors"], 2, ""),
])
def test_filters(capsys, filters, count, check):
    args = ["monitor", "--replay", str(CAPTURE), "--json"]
    for spec in filters:
        args += ["--filter", spec]
    assert main(args) == 0
    frames = json.loads(capsys.readouterr().out)["frames"]
    assert len(frames) == count
    assert all(check in f["text"] for f in frames)


@pytest.mark.parametrize("spec", ["colour=red", "node=x", "direction=sideways", "function=0xZZ"])
def test_bad_filter_exits_2(capsys, spec):
    assert main(["monitor", "--replay", str(CAPTURE), "--filter", spec]) == 2
    assert spec in capsys.readouterr().err


def test_replay_with_log_converts_the_capture(tmp_path, capsys):
    out = tmp_path / "converted.blf"
    assert main(["monitor", "--replay", str(CAPTURE), "--log", str(out), "--json"]) == 0
    original = json.loads(capsys.readouterr().out)["frames"]
    assert main(["monitor", "--replay", str(out), "--json"]) == 0
    again = json.loads(capsys.readouterr().out)["frames"]
    assert [(f["arbitration_id"], f["data"], f["fields"]) for f in again] == \
        [(f["arbitration_id"], f["data"], f["fields"]) for f in original]


@pytest.mark.parametrize("name, content, reason", [
    ("broken.blf", b"\x00\x01\x02 not a BLF file", "not a readable capture"),
    ("broken.trc", b"\xff\xfe binary junk", "not a readable capture"),
    ("capture.xyz", b"some text", "not a readable capture"),
])
def test_bad_capture_exits_2_naming_file_and_reason(tmp_path, capsys, name, content, reason):
    path = tmp_path / name
    path.write_bytes(content)
    assert main(["monitor", "--replay", str(path), "--json"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and name in err and reason in err


def test_missing_capture_exits_2(tmp_path, capsys):
    assert main(["monitor", "--replay", str(tmp_path / "none.asc")]) == 2
    assert "none.asc: no such file" in capsys.readouterr().err


def test_unwritable_log_format_exits_2(tmp_path, capsys):
    assert main(["monitor", "--replay", str(CAPTURE), "--log", str(tmp_path / "x.nope")]) == 2
    assert "x.nope" in capsys.readouterr().err


def test_bad_arguments(capsys):
    assert main(["monitor", "--bus", "can:virtual", "--seconds", "1"]) == 2
    assert "can:INTERFACE:CHANNEL" in capsys.readouterr().err
    assert main(["monitor", "--bus", "can:virtual:x", "--seconds", "0"]) == 2
    assert main(["monitor", "--bus", "can:no-such-interface:x", "--seconds", "0.1"]) == 2
    assert "can:no-such-interface:x" in capsys.readouterr().err
    assert main(["monitor", "--bus", "tcp:somewhere", "--seconds", "0.1"]) == 2
    assert "unknown scheme" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["monitor"])  # --bus or --replay is required


def test_live_virtual_bus_with_log(tmp_path, capsys):
    from can.interfaces.virtual import channels

    channel = f"cli-monitor-{uuid.uuid4().hex}"
    log = tmp_path / "live.trc"
    sent = [M.Beacon(5).encode(), M.GetParameter(5, 9, 0).encode(),
            M.GetParameterResponse(5, 1, 9, 0, b"\x02").encode()]

    def device() -> None:
        with can.Bus(interface="virtual", channel=channel) as bus:
            deadline = time.monotonic() + 5
            while len(channels.get(channel, ())) < 2 and time.monotonic() < deadline:
                time.sleep(0.01)  # wait for the monitor to open the channel
            for arbitration_id, data in sent:
                bus.send(can.Message(arbitration_id=arbitration_id, data=data,
                                     is_extended_id=False))

    thread = threading.Thread(target=device)
    thread.start()
    try:
        code = main(["monitor", "--bus", f"can:virtual:{channel}@1000000", "--seconds", "1.0",
                     "--log", str(log)])
    finally:
        thread.join()
    assert code == 0
    out, err = capsys.readouterr()
    assert "#5→BA Device Beacon" in out and "Number of Data Channels  chan 0  = 2" in out
    assert err.startswith("3 frames, 0 errors") and "live.trc" in err
    assert [(m.arbitration_id, bytes(m.data)) for m in can.LogReader(str(log))] == sent


class FakeSession:
    """Stands in for bus.session's Session: emits FrameSeen events from its own thread."""

    def __init__(self, frames):
        self.frames, self.closed, self._thread = frames, False, None

    def subscribe(self, callback):
        def emit():
            callback(object())  # other events are ignored
            for i, (arbitration_id, data) in enumerate(self.frames):
                callback(FrameSeen(100.0 + i / 100, arbitration_id, data, ""))

        self._thread = threading.Thread(target=emit)
        self._thread.start()

    def close(self):
        self._thread.join()
        self.closed = True


def test_sim_url_names_the_links_of_channel_data(capsys, tmp_path):
    """On a simulated prosthesis the monitor knows the outputs' node IDs from the session, so
    channel data frames read as data on their links, never as undecodable function codes."""
    log = tmp_path / "sim.csv"
    assert main(["monitor", "--bus", "sim:transradial", "--seconds", "1.0", "--json",
                 "--log", str(log)]) == 0
    out, err = capsys.readouterr()
    shown = json.loads(out)["frames"]
    data = [f for f in shown if f["function"] == "Channel data"]
    assert data, "transradial streams EMG and set points at 20 Hz"
    assert all(f["link"] and f["link"]["inputs"] and f["error"] is None for f in data)
    assert "0 undecodable" in err
    logged = [(m.arbitration_id, bytes(m.data)) for m in can.LogReader(str(log))]
    assert len(logged) == len(shown)


def test_subprocess_replay():
    result = subprocess.run(
        [sys.executable, "-m", "pdcp_studio", "monitor", "--replay",
         "tests/data/captures/pdcp-session.asc"],
        cwd=ROOT, capture_output=True, text=True, timeout=60, check=False)
    assert result.returncode == 0, result.stderr
    assert len(result.stdout.splitlines()) == FRAMES_IN_CAPTURE
    assert DESCRIPTOR in result.stdout and "frames" in result.stderr
