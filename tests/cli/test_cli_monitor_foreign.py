"""``monitor --replay`` on captures from other tools (issue 27): the verdict in the summary
and in ``--json``, every frame kind kept, the node map learned and named, damage said,
bus load never above what the bit rate allows, and conversions that say what they lost."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import can
import pytest

from pdcp_studio.cli.main import main

DATA = Path(__file__).resolve().parents[2] / "tests" / "data" / "captures"
KIND_FIELDS = ("arbitration_id", "is_extended_id", "is_remote_frame", "is_error_frame",
               "is_fd", "channel", "data")
PDCP_WORDS = ("Bind", "Beacon", "Parameter", "undecodable", "Channel data", "BA→", "→BA")


def replay(capsys, path, *more):
    code = main(["monitor", "--replay", str(path), *more])
    out, err = capsys.readouterr()
    return code, out, err


def test_a_simulator_capture_recorded_live_replays_without_its_sidecar(tmp_path, capsys):
    log = tmp_path / "x.asc"
    assert main(["monitor", "--bus", "sim:transradial", "--seconds", "3", "--log",
                 str(log)]) == 0
    capsys.readouterr()
    Path(str(log) + ".nodemap.json").unlink()
    code, out, err = replay(capsys, log, "--json")
    assert code == 0
    summary = json.loads(out)["summary"]
    assert summary["verdict"] == "pdcp" and summary["frames"] > 100
    assert summary["undecodable"] <= 0.01 * summary["frames"], err
    assert summary["node_map"].startswith("node map: inferred from traffic: 4 devices, 5 chan")
    assert "verdict: pdcp" in err and "node map: inferred from traffic" in err


@pytest.mark.parametrize("name", ["canalyzer-car-cp1252.asc", "candump-car.log",
                                  "vector-car.blf", "pcan-car-2.2.trc"])
def test_a_car_capture_is_plain_can_with_every_frame_kind(capsys, name):
    code, out, err = replay(capsys, DATA / name, "--json")
    assert code == 0
    doc = json.loads(out)
    assert doc["summary"]["verdict"] == "not-pdcp" and doc["summary"]["truncated"] is False
    assert "verdict: not-pdcp" in err
    frames = doc["frames"]
    assert all(all(k in f for k in KIND_FIELDS) for f in frames)
    assert not any(word in f["text"] for f in frames for word in PDCP_WORDS)
    ext = [f for f in frames if f["is_extended_id"] and f["arbitration_id"] == 0x123
           and not f["is_error_frame"]]
    assert ext and "P?  0x00000123 not PDCP  [00000123] " in ext[0]["text"]
    assert "0x123 " not in "".join(f["text"] for f in frames)
    errors = [f for f in frames if f["is_error_frame"]]
    assert errors and errors[0]["text"].endswith("P?  error not PDCP  error frame")
    if name != "pcan-car-2.2.trc":  # PCAN's file was written without remote and FD frames
        remote = [f for f in frames if f["is_remote_frame"]]
        assert remote and "[3C2] remote frame" in remote[0]["text"]
        fd = [f for f in frames if f["is_fd"]]
        assert fd and fd[0]["dlc"] == 12 and "[2A1] FD 00 01" in fd[0]["text"]


def test_a_few_foreign_frames_get_no_pdcp_reading(tmp_path, capsys):
    """Under 20 frames too: not one line reads as PDCP."""
    path = tmp_path / "few.log"
    lines = (DATA / "candump-car.log").read_text().splitlines()[:6]
    path.write_text("\n".join(lines) + "\n")
    code, out, err = replay(capsys, path)
    assert code == 0 and "verdict: not-pdcp" in err
    assert len(out.splitlines()) == 6
    assert not any(word in out for word in PDCP_WORDS)


def test_error_remote_and_extended_frames_in_a_pdcp_capture(tmp_path, capsys):
    """A PDCP capture's odd frames show as what they are, not as an empty ID-0 frame, a
    DLC-0 frame or a standard 0x123."""
    path = tmp_path / "mixed.asc"
    shutil.copy(DATA / "sim-transradial-midsession.asc", path)
    odd = [" 3.100000 1  ErrorFrame", " 3.200000 1  123x            Rx   d 2 01 02",
           " 3.300000 1  205             Rx   r 2"]
    text = path.read_text().replace("End TriggerBlock", "\n".join(odd) + "\nEnd TriggerBlock")
    path.write_text(text)
    code, out, _ = replay(capsys, path, "--json")
    assert code == 0
    frames = json.loads(out)["frames"]
    by_kind = {k: [f for f in frames if f[k] and (k == "is_error_frame"
                                                  or not f["is_error_frame"])]
               for k in ("is_error_frame", "is_extended_id", "is_remote_frame")}
    assert by_kind["is_error_frame"][0]["text"].endswith("P?  error undecodable: error frame")
    assert "P?  0x00000123 undecodable: extended" in by_kind["is_extended_id"][0]["text"]
    assert "[00000123] 01 02" in by_kind["is_extended_id"][0]["text"]
    assert "[205] remote frame, DLC 2" in by_kind["is_remote_frame"][0]["text"]
    assert by_kind["is_remote_frame"][0]["dlc"] == 2


def test_an_empty_asc_and_an_empty_blf_give_the_same_verdict(tmp_path, capsys):
    verdicts = []
    for name in ("empty.asc", "empty.blf"):
        (tmp_path / name).write_bytes(b"")
        code, out, err = replay(capsys, tmp_path / name, "--json")
        assert code == 0, err
        summary = json.loads(out)["summary"]
        verdicts.append((summary["verdict"], summary["frames"]))
        assert "verdict: empty" in err
    assert verdicts == [("empty", 0), ("empty", 0)]


def test_a_damaged_capture_is_read_up_to_the_cut_and_said(tmp_path, capsys):
    raw = (DATA / "sim-transradial-midsession.asc").read_bytes()
    path = tmp_path / "cut.asc"
    path.write_bytes(raw[:len(raw) // 2])
    code, out, err = replay(capsys, path, "--json")
    assert code == 2
    doc = json.loads(out)
    assert doc["summary"]["truncated"] is True and doc["frames"]
    assert "cut.asc: line " in doc["summary"]["damage"]
    assert "cut.asc: line " in err and "read up to there" in err


def test_bus_load_never_above_what_the_bit_rate_allows(tmp_path, capsys):
    path = tmp_path / "dense.log"
    path.write_text("".join(f"(1700000000.{k:06d}) can0 123#0102030405060708\n"
                            for k in range(200)))  # 200 frames in 200 µs
    code, out, err = replay(capsys, path, "--json")
    assert code == 0
    assert json.loads(out)["summary"]["bus_load"] is None
    assert "denser than the bit rate allows" in err and "%)" not in err.split("\n")[1]


def test_bus_load_from_the_real_span_of_every_frame(tmp_path, capsys):
    """Extended frames count for the span: the load is not made up from base frames only."""
    path = tmp_path / "span.log"
    path.write_text("(1700000000.000000) can0 1ABCDEF0#01\n"
                    "(1700000000.000500) can0 123#0102\n"
                    "(1700000001.000000) can0 1ABCDEF0#01\n")
    code, out, _ = replay(capsys, path, "--json")
    assert code == 0
    summary = json.loads(out)["summary"]
    assert summary["span_s"] == pytest.approx(1.0) and summary["bus_load"] < 0.001


def test_conversion_says_which_frames_it_could_not_write(tmp_path, capsys):
    out = tmp_path / "y.trc"
    code, _, err = replay(capsys, DATA / "vector-car.blf", "--log", str(out))
    assert code == 1
    assert "3 of 123 frames not written: python-can's TRC writer cannot keep" in err
    assert "1 error frames" in err and "1 remote frames" in err and "1 CAN FD frames" in err
    assert len(list(can.LogReader(str(out)))) == 120
    code, _, err = replay(capsys, DATA / "vector-car.blf", "--log", str(tmp_path / "y.asc"))
    assert code == 0 and "not written" not in err


def test_listening_to_a_running_bus_infers_its_channels(capsys):
    """Listen-only on a bus another arbitrator runs (no set-up seen): after beacons and a
    channel's first 16 frames, its data reads as channel data, not as errors."""
    import threading
    import uuid

    from tests.cli.test_cli_monitor_captures import _play

    channel = f"listen-{uuid.uuid4().hex}"
    frames = [(0x001, b"\x0a"), (0x002, b"\x0a")]
    frames += [(0x206, bytes([t, 1])) for t in range(40)]
    sender = threading.Thread(target=_play, args=(channel, frames, 400.0, 1))
    sender.start()
    try:
        assert main(["monitor", "--bus", f"can:virtual:{channel}", "--seconds", "1.5"]) == 0
    finally:
        sender.join()
    out, err = capsys.readouterr()
    lines = out.splitlines()
    assert len(lines) == len(frames) and "0 errors" in err
    assert all("Channel data  channel node 6 →" in line for line in lines[-24:])
    assert "node map: inferred from traffic: 2 devices, 1 channel" in err
