"""`monitor` on long and foreign captures (issues 10, 15, 16): streaming --json with flat
memory, a capture replaced only when complete (kill at random moments, a full disk), the
node map saved beside a capture and used on replay, a car's log called `not PDCP`, rotation,
and undecodable frames summarised on stderr instead of flooding it."""

from __future__ import annotations

import errno
import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import can
import pytest

from pdcp_studio.bus.trace.files import recorder as bus_monitor
from pdcp_studio.bus.trace.monitor import FrameDecoder, frame_json, read_capture
from pdcp_studio.cli.main import main
from pdcp_studio.protocol import messages as M
from pdcp_studio.protocol.identifier import make_id

ROOT = Path(__file__).resolve().parents[2]
CAPTURE = ROOT / "tests" / "data" / "captures" / "pdcp-session.asc"
OK = 1


def pdcp_frames(n: int, seed: int = 1) -> list[tuple[int, bytes]]:
    """A session: two devices bound, an output linked, then channel data and reads."""
    rng = random.Random(seed)
    setup = [M.BindRequest(5, 1, 10, 4), M.BindResponse(5, 5, 1, 10, 4),
             M.BindRequest(7, 2, 2, 5), M.BindResponse(7, 7, 2, 2, 5),
             M.GetParameter(5, 3, 1), M.GetParameterResponse(5, OK, 3, 1, b"\x02"),
             M.SetParameter(5, 5, 1, b"\x06"), M.SetParameterResponse(5, OK, 5, 1, b"\x06"),
             M.SetParameter(7, 7, 2, bytes([5, 6])),
             M.SetParameterResponse(7, OK, 7, 2, bytes([5, 6]))]
    frames = [m.encode() for m in setup]
    while len(frames) < n:
        if rng.random() < 0.9:
            frames.append(M.ChannelData(6, rng.randbytes(rng.choice((2, 4, 8)))).encode())
        else:
            frames += [M.GetParameter(5, 9, 0).encode(),
                       M.GetParameterResponse(5, OK, 9, 0, b"\x01").encode()]
    return frames[:n]


def write_capture(path: Path, frames, t0: float = 1_700_000_000.0, rate: float = 8000.0):
    with can.Logger(str(path)) as logger:
        for i, (arbitration_id, data) in enumerate(frames):
            logger.on_message_received(can.Message(
                timestamp=t0 + i / rate, arbitration_id=arbitration_id, data=data,
                is_extended_id=arbitration_id > 0x7FF, channel=0))


def run_cli(*args: str, stdout=subprocess.PIPE, timeout: float = 120):
    return subprocess.run([sys.executable, "-m", "pdcp_studio", *args], cwd=ROOT,
                          stdout=stdout, stderr=subprocess.PIPE, text=True, timeout=timeout,
                          env=dict(os.environ, PYTHONPATH=str(ROOT)), check=False)


def _vm_hwm_mb(pid: int) -> float:
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    return 0.0


# -- streaming --json -------------------------------------------------------------------------


def test_frame_json_is_exactly_the_record():
    decoder = FrameDecoder()
    for msg in read_capture(CAPTURE):
        frame = decoder.decode_message(msg)
        assert json.loads(frame_json(frame)) == json.loads(json.dumps(frame.as_json()))


def test_json_streams_one_document_with_flat_memory(tmp_path):
    """120,000 frames as --json: one valid list, and the process stays small (the old code
    kept every record: ~290 MB for 200,000 frames)."""
    path = tmp_path / "long.blf"
    frames = pdcp_frames(120_000)
    write_capture(path, frames)
    out = tmp_path / "out.json"
    with out.open("w") as handle:
        proc = subprocess.Popen([sys.executable, "-m", "pdcp_studio", "monitor", "--replay",
                                 str(path), "--json"], cwd=ROOT, stdout=handle,
                                stderr=subprocess.PIPE, env=dict(os.environ, PYTHONPATH=str(ROOT)))
        peak_mb = 0.0
        while proc.poll() is None:  # the child's own high-water mark (VmHWM): ru_maxrss
            peak_mb = max(peak_mb, _vm_hwm_mb(proc.pid))  # would count this process too
            time.sleep(0.05)
        proc.stderr.read()
    assert proc.returncode == 0
    assert peak_mb < 120, f"peak RSS {peak_mb:.0f} MB"
    records = json.loads(out.read_text())["frames"]
    assert len(records) == len(frames)
    assert records[-1]["arbitration_id"] == frames[-1][0]
    assert sum(r["function"] == "Channel data" for r in records) > 95_000
    assert all(r["error"] is None for r in records)


# -- a capture replaced only when complete ----------------------------------------------------


def test_kill_at_random_moments_keeps_the_previous_capture(tmp_path):
    source = tmp_path / "source.asc"
    write_capture(source, pdcp_frames(60_000))
    target = tmp_path / "capture.asc"
    write_capture(target, pdcp_frames(30, seed=2))
    before = target.read_bytes()
    rng = random.Random(15)
    killed = partials = 0
    for _ in range(6):
        proc = subprocess.Popen([sys.executable, "-m", "pdcp_studio", "monitor", "--replay",
                                 str(source), "--log", str(target)], cwd=ROOT,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                env=dict(os.environ, PYTHONPATH=str(ROOT)))
        partial = tmp_path / "capture.asc.partial"
        deadline = time.monotonic() + 60
        while not partial.exists() and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)  # writing has started: kill at a random moment from now
        time.sleep(rng.uniform(0.0, 1.0))
        if proc.poll() is None:
            proc.send_signal(signal.SIGKILL)
            killed += 1
        proc.wait(timeout=60)
        if proc.returncode == 0 or target.read_bytes() != before:
            # It finished first, or was killed after the replace (before it exited): the
            # capture is the complete new one. Start again from a fresh previous capture.
            assert len(list(read_capture(target))) == 60_000, "the previous capture was changed"
            write_capture(target, pdcp_frames(30, seed=2))
            before = target.read_bytes()  # its header's date is the rewrite's
        else:
            partials += partial.exists()  # unless killed before it started writing
            partial.unlink(missing_ok=True)
    assert killed, "no run was interrupted: the kill times are too late"
    assert partials, "no interrupted capture was left under the .partial name"


def test_full_disk_leaves_the_previous_capture_and_names_the_target(tmp_path, monkeypatch,
                                                                     capsys):
    target = tmp_path / "capture.blf"
    write_capture(target, pdcp_frames(30, seed=3))
    before = target.read_bytes()
    real = bus_monitor._writer_for

    def failing_writer(target_path, file):
        writer = real(target_path, file)
        count = {"n": 0}
        original = writer.on_message_received

        def on_message_received(msg):
            count["n"] += 1
            if count["n"] > 20:
                raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
            original(msg)

        writer.on_message_received = on_message_received
        return writer

    monkeypatch.setattr(bus_monitor, "_writer_for", failing_writer)
    assert main(["monitor", "--replay", str(CAPTURE), "--log", str(target)]) == 1
    err = capsys.readouterr().err
    assert str(target) in err and "No space left" in err and ".tmp" not in err
    assert target.read_bytes() == before
    assert (tmp_path / "capture.blf.partial").exists()


def test_a_partial_capture_is_not_replayed_as_complete(tmp_path, capsys):
    partial = tmp_path / "capture.asc.partial"
    partial.write_bytes(CAPTURE.read_bytes()[:500])
    assert main(["monitor", "--replay", str(partial)]) == 2
    err = capsys.readouterr().err
    assert "capture.asc.partial" in err and "interrupted capture" in err


@pytest.mark.parametrize("value", ["nan", "inf", "-1"])
def test_seconds_must_be_a_finite_positive_time(value, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["monitor", "--bus", "sim:transradial", "--seconds", value])
    assert exit_.value.code == 2 and "--seconds" in capsys.readouterr().err


# -- captures keep their meaning --------------------------------------------------------------


@pytest.mark.parametrize("suffix", [".asc", ".blf", ".csv", ".log", ".trc", ".db", ".asc.gz"])
def test_own_capture_replays_with_no_undecodable_frame(tmp_path, suffix, capsys):
    """Recorded mid-session (the binds and set-up happened before): the saved node map
    names the channel data of every frame."""
    log = tmp_path / f"sim{suffix}"
    assert main(["monitor", "--bus", "sim:transradial", "--seconds", "1.5", "--log",
                 str(log)]) == 0
    capsys.readouterr()
    assert Path(str(log) + ".nodemap.json").is_file()
    assert main(["monitor", "--replay", str(log), "--json"]) == 0
    out, err = capsys.readouterr()
    frames = json.loads(out)["frames"]
    assert frames and any(f["function"] == "Channel data" for f in frames)
    assert " 0 undecodable" in err or "0 errors" in err, err
    assert all(f["error"] is None for f in frames)


def car_frames(n: int, seed: int = 10) -> list[tuple[int, bytes]]:
    """A car-like log: a few dozen IDs at fixed lengths, counters and sensor bytes, some
    of whose first bytes happen to be PDCP function codes."""
    rng = random.Random(seed)
    ids = [(rng.randrange(0x080, 0x7F0), rng.choice((2, 3, 5, 6, 7, 8))) for _ in range(40)]
    frames = []
    for i in range(n):
        arbitration_id, dlc = ids[i % len(ids)]
        data = bytes([(i // len(ids)) & 0xFF]) + rng.randbytes(dlc - 1)
        frames.append((arbitration_id, data))
    return frames


@pytest.mark.parametrize("suffix", [".asc", ".log"])
def test_a_car_log_is_not_pdcp(tmp_path, suffix, capsys):
    path = tmp_path / f"car{suffix}"
    write_capture(path, car_frames(5000), rate=2000.0)
    assert main(["monitor", "--replay", str(path), "--json"]) == 0
    out, err = capsys.readouterr()
    doc = json.loads(out)
    frames = doc["frames"]
    assert doc["summary"]["verdict"] == "not-pdcp"
    assert len(frames) == 5000
    assert "not PDCP" in err.splitlines()[0] and "undecodable" not in err.splitlines()[0]
    assert {f["function"] for f in frames} == {"not PDCP"}
    assert all(f["error"] is None for f in frames)


def test_rotation_writes_complete_parts_each_with_its_node_map(tmp_path, capsys):
    source = tmp_path / "source.blf"
    write_capture(source, pdcp_frames(40_000))
    log = tmp_path / "rot.asc"
    assert main(["monitor", "--replay", str(source), "--log", str(log), "--rotate-mb", "0.5",
                 "--filter", "node=254"]) == 0
    capsys.readouterr()
    parts = sorted(p for p in tmp_path.glob("rot_*.asc"))
    assert len(parts) >= 2 and log.is_file()
    assert not list(tmp_path.glob("*.partial"))
    total = sum(len(list(read_capture(p))) for p in [*parts, log])
    assert total == 40_000
    assert all(Path(str(p) + ".nodemap.json").is_file() for p in parts)


def test_undecodable_frames_are_summarised_not_flooded(capsys):
    """4,000 garbage frames on a live bus: a handful of stderr lines, every frame counted."""
    import threading
    import uuid

    from can.interfaces.virtual import channels

    channel = f"flood-{uuid.uuid4().hex}"
    bound = [M.BindRequest(9, 1, 2, 3).encode(), M.BindResponse(9, 9, 1, 2, 3).encode()]
    garbage = bound + [(make_id(1, 0, 9), bytes([0x50, i & 0xFF])) for i in range(3998)]

    def hostile() -> None:
        with can.Bus(interface="virtual", channel=channel) as bus:
            deadline = time.monotonic() + 5
            while len(channels.get(channel, ())) < 2 and time.monotonic() < deadline:
                time.sleep(0.01)
            for arbitration_id, data in garbage:
                bus.send(can.Message(arbitration_id=arbitration_id, data=data,
                                     is_extended_id=False))

    thread = threading.Thread(target=hostile)
    thread.start()
    try:
        assert main(["monitor", "--bus", f"can:virtual:{channel}", "--seconds", "2",
                     "--filter", "node=1"]) == 0
    finally:
        thread.join()
    err = capsys.readouterr().err
    assert any(line.startswith("4000 frames") for line in err.splitlines()), err
    noise = [line for line in err.splitlines() if "undecodable frame" in line]
    assert 1 <= len(noise) <= 5, noise


# -- live: every frame counted, and a monitor that only listens -------------------------------


def _play(channel: str, frames, rate: float, ready_listeners: int) -> None:
    """Send ``frames`` on a virtual channel at ``rate`` once ``ready_listeners`` listen."""
    from can.interfaces.virtual import channels

    with can.Bus(interface="virtual", channel=channel) as bus:
        deadline = time.monotonic() + 10
        while len(channels.get(channel, ())) < ready_listeners + 1 and time.monotonic() < deadline:
            time.sleep(0.01)
        t0 = time.perf_counter()
        for i, (arbitration_id, data) in enumerate(frames):
            due = t0 + i / rate
            while time.perf_counter() < due:
                time.sleep(0.0005)
            bus.send(can.Message(arbitration_id=arbitration_id, data=data,
                                 is_extended_id=False))


def test_live_monitor_counts_every_frame_of_a_saturated_bus(capsys):
    """16,000 frames at 8,000 frames/s: the monitor's count equals an independent counter's
    on the same bus (and the number sent)."""
    import threading
    import uuid

    channel = f"load-{uuid.uuid4().hex}"
    frames = pdcp_frames(16_000, seed=4)
    counted = {"n": 0}
    stop = threading.Event()

    def count() -> None:
        with can.Bus(interface="virtual", channel=channel) as bus:
            while not stop.is_set():
                if bus.recv(0.05) is not None:
                    counted["n"] += 1

    counter = threading.Thread(target=count)
    counter.start()
    sender = threading.Thread(target=_play, args=(channel, frames, 8000.0, 2))
    sender.start()
    try:
        assert main(["monitor", "--bus", f"can:virtual:{channel}", "--seconds", "5",
                     "--filter", "node=254"]) == 0
    finally:
        sender.join()
        time.sleep(0.3)
        stop.set()
        counter.join()
    err = capsys.readouterr().err
    seen = int(err.split(" frames", 1)[0].splitlines()[-1])
    assert counted["n"] == len(frames) == seen, err


def test_passive_monitor_never_transmits_and_learns_the_node_map(capsys):
    """Joining a running bus: channel data of an output it has not seen set up is
    unattributed (not an error); after the set-up frames it names the link; and nothing
    it did reached the bus."""
    import threading
    import uuid

    channel = f"passive-{uuid.uuid4().hex}"
    before = [M.ChannelData(6, b"\x12\x34").encode()] * 3
    setup = [M.BindRequest(5, 1, 10, 4).encode(), M.BindResponse(5, 5, 1, 10, 4).encode(),
             M.BindRequest(7, 2, 2, 5).encode(), M.BindResponse(7, 7, 2, 2, 5).encode(),
             M.GetParameter(5, 3, 1).encode(),
             M.GetParameterResponse(5, OK, 3, 1, b"\x02").encode(),
             M.SetParameter(5, 5, 1, b"\x06").encode(),
             M.SetParameterResponse(5, OK, 5, 1, b"\x06").encode(),
             M.SetParameter(7, 7, 2, bytes([5, 6])).encode(),
             M.SetParameterResponse(7, OK, 7, 2, bytes([5, 6])).encode(),
             M.Beacon(5).encode()]
    after = [M.ChannelData(6, b"\x13\x34").encode()] * 3
    frames = before + setup + after
    heard: list = []
    stop = threading.Event()

    def watch() -> None:
        with can.Bus(interface="virtual", channel=channel) as bus:
            while not stop.is_set():
                msg = bus.recv(0.05)
                if msg is not None:
                    heard.append((msg.arbitration_id, bytes(msg.data)))

    watcher = threading.Thread(target=watch)
    watcher.start()
    sender = threading.Thread(target=_play, args=(channel, frames, 500.0, 2))
    sender.start()
    try:
        assert main(["monitor", "--bus", f"can:virtual:{channel}", "--seconds", "2"]) == 0
    finally:
        sender.join()
        time.sleep(0.2)
        stop.set()
        watcher.join()
    out, err = capsys.readouterr()
    lines = out.splitlines()
    assert len(lines) == len(frames)
    assert all("unattributed" in line for line in lines[:3])
    assert all("1/10/4#1 → 2/2/5#2" in line for line in lines[-3:])
    assert "0 errors" in err
    assert heard == frames  # only the sender's frames: the monitor sent nothing


def test_a_pdcp_bus_of_beacons_only_is_not_called_foreign(tmp_path, capsys):
    path = tmp_path / "beacons.asc"
    write_capture(path, [M.Beacon(n).encode() for _ in range(30) for n in (3, 4, 5)])
    assert main(["monitor", "--replay", str(path)]) == 0
    out, err = capsys.readouterr()
    assert "not PDCP" not in out + err and "0 errors" in err
    assert out.count("Device Beacon") == 90


def test_frame_json_with_remembered_links_is_the_same():
    decoder, links = FrameDecoder(), {}
    for msg in list(read_capture(CAPTURE)) * 2:
        frame = decoder.decode_message(msg)
        assert frame_json(frame, links) == frame_json(frame)
