"""A BLF capture replayed through the fast reader (bus/trace/files/blf.py) and the pump writes what
python-can's reader and one-by-one decoding write: the same lines, JSON records, statistics
and summary, byte for byte — with CAN FD, error, remote and extended frames on several
channels; and ``--log`` converts it to the same capture."""

from __future__ import annotations

import random
from pathlib import Path

import can
import pytest

from pdcp_studio.bus.trace.files import capture as bus_monitor
from pdcp_studio.bus.trace.files.blf import FastBLFReader, PlainFrame
from pdcp_studio.cli.main import main
from pdcp_studio.cli.monitor import make_filter
from tests.bus.test_monitor import session_frames
from tests.bus.test_monitor_caches import relearning_traffic
from tests.bus.test_trace_pump import FILTERS, messages, one_by_one, pumped


def odd_frames(msgs: list[can.Message], seed: int = 7) -> list[can.Message]:
    """``msgs`` with CAN FD frames (up to 64 bytes, on identifiers that carry channel data
    too), error frames, remote and extended frames put in, on three channels."""
    rng = random.Random(seed)
    out = []
    for i, msg in enumerate(msgs):
        msg.channel = i % 3
        out.append(msg)
        if rng.random() < 0.04:
            kind = rng.choice(["fd", "fd8", "error", "remote", "extended"])
            ids = [msg.arbitration_id, 0x006, 0x1F0]
            out.append(can.Message(
                timestamp=msg.timestamp, arbitration_id=rng.choice(ids),
                is_fd=kind.startswith("fd"), bitrate_switch=kind == "fd",
                is_error_frame=kind == "error", is_remote_frame=kind == "remote",
                is_extended_id=kind == "extended", channel=rng.randrange(3),
                dlc=3 if kind == "remote" else None,
                data=None if kind == "remote" else
                rng.randbytes(rng.choice([12, 24, 64])) if kind == "fd" else
                bytes(msg.data)))
    return out


def capture(tmp_path: Path, msgs, name: str = "mixed.blf", **kwargs) -> Path:
    path = tmp_path / name
    with can.BLFWriter(str(path), **kwargs) as writer:
        for msg in msgs:
            writer.on_message_received(msg)
    return path


def test_fast_reader_and_pump_write_what_python_can_and_one_by_one_write(tmp_path):
    msgs = odd_frames(messages(relearning_traffic(2) * 3, seed=2))
    path = capture(tmp_path, msgs, max_container_size=4096)
    slow = list(can.BLFReader(str(path)))
    fast = list(FastBLFReader(path))
    assert sum(isinstance(f, PlainFrame) for f in fast) > 0.8 * len(fast)
    assert any(m.is_fd and len(m.data) > 8 for m in slow)
    for checked in (False, True):
        for as_json in (False, True):
            for spec in FILTERS:
                show = make_filter(spec) if spec else None
                expected = one_by_one(slow, as_json=as_json, show=show, checked=checked)
                assert pumped(fast, as_json=as_json, show=show, checked=checked) == expected
                assert pumped(fast, as_json=as_json, show=show, checked=checked,
                              stdout=True, polls=True) == expected


def python_can_only(monkeypatch) -> None:
    """The monitor reads every capture with python-can's own readers, as before the fast
    reader."""
    original = bus_monitor.open_capture
    monkeypatch.setattr(bus_monitor, "open_capture",
                        lambda path, plain_frames=False: original(path))


@pytest.mark.parametrize("args", [[], ["--json"], ["--filter", "direction=data"],
                                  ["--filter", "errors", "--json"], ["--filter", "node=6"]])
def test_monitor_replay_of_blf_is_byte_identical(tmp_path, capsys, monkeypatch, args):
    busy = []
    rng = random.Random(3)
    for frame in relearning_traffic(1) * 2:
        busy.append(frame)
        if rng.random() < 0.3:
            busy.append(rng.choice(session_frames()))
    path = capture(tmp_path, odd_frames(messages(busy, seed=4), seed=5),
                   max_container_size=2000)
    assert main(["monitor", "--replay", str(path), *args]) == 0
    fast = capsys.readouterr()
    python_can_only(monkeypatch)
    assert main(["monitor", "--replay", str(path), *args]) == 0
    slow = capsys.readouterr()
    assert fast.out == slow.out and fast.err == slow.err
    assert len(fast.out) > 1000 or args[-1] == "node=6"


@pytest.mark.parametrize("target", ["back.asc", "back.blf"])
def test_log_of_a_blf_replay_is_the_same_capture(tmp_path, capsys, monkeypatch, target):
    """``--log`` writes the can.Message each frame stands for (``PlainFrame.to_message``)."""
    path = capture(tmp_path, odd_frames(messages(session_frames() * 4, seed=6)))
    fast_log, slow_log = tmp_path / f"fast-{target}", tmp_path / f"slow-{target}"
    assert main(["monitor", "--replay", str(path), "--log", str(fast_log)]) == 0
    python_can_only(monkeypatch)
    assert main(["monitor", "--replay", str(path), "--log", str(slow_log)]) == 0
    capsys.readouterr()
    if target.endswith(".asc"):  # the header holds the time it was written
        fast_text = fast_log.read_text().splitlines()[3:]
        assert fast_text == slow_log.read_text().splitlines()[3:] and len(fast_text) > 40
    else:
        assert fast_log.read_bytes() == slow_log.read_bytes()
