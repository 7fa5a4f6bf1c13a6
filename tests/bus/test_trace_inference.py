"""The node map learned from traffic whose set-up was never seen (bus/trace/inference.py),
and where a replay's node map came from (bus/trace/files/replay.py)."""

from __future__ import annotations

import json
import random
import shutil
from pathlib import Path

from pdcp_studio.bus.trace.decoder import FrameDecoder
from pdcp_studio.bus.trace.files.replay import CaptureReplay
from pdcp_studio.bus.trace.inference import TrafficLearner
from pdcp_studio.bus.trace.knowledge import INFERRED

DATA = Path(__file__).resolve().parents[2] / "tests" / "data" / "captures"
SIM = DATA / "sim-transradial-midsession.asc"


def replayed(path):
    with CaptureReplay(path) as opened:
        frames = list(opened.decoded())
        return opened, frames


def test_a_simulator_capture_without_its_node_map_decodes_like_the_live_session():
    opened, frames = replayed(SIM)
    stats = opened.decoder.stats
    assert stats.frames == 408 and stats.undecodable <= 0.01 * stats.frames
    assert stats.by_function["Channel data"] == 286
    assert opened.node_map_words() == "node map: inferred from traffic: 4 devices, 5 channels"
    data = [f for f in frames if f.function == "Channel data"]
    assert data[0].link[0] == "channel node 5"


def test_a_capture_cut_to_start_mid_stream(tmp_path):
    """The first 150 frames gone (the cut falls between beacons): still ≤ 1 %."""
    lines = SIM.read_text().splitlines()
    body = [i for i, x in enumerate(lines) if " Rx " in x]
    cut = tmp_path / "late.asc"
    cut.write_text("\n".join(lines[:body[0]] + lines[body[150]:]) + "\n")
    opened, _ = replayed(cut)
    stats = opened.decoder.stats
    assert stats.frames == 408 - 150 and stats.undecodable <= 0.01 * stats.frames
    assert "inferred from traffic: 4 devices, 5 channels" in opened.node_map_words()


def test_the_capture_s_set_up_and_the_saved_node_map_are_named(tmp_path):
    opened, _ = replayed(DATA / "pdcp-session.asc")
    assert opened.node_map_words() == "node map: from the capture's set-up: 2 devices, 1 channel"
    copy = tmp_path / "sim.asc"
    shutil.copy(SIM, copy)
    first, _ = replayed(copy)
    (tmp_path / "sim.asc.nodemap.json").write_text(json.dumps(first.decoder.node_map()))
    again, _ = replayed(copy)
    assert again.node_map_words() == f"node map: from {copy}.nodemap.json"
    assert again.decoder.stats.undecodable == 0  # the inferred channels were saved (owner 0)
    assert sum(owner == INFERRED for owner in again.decoder.outputs.values()) == 5


def car(n: int, seed: int = 3) -> list[tuple[int, bytes]]:
    rng = random.Random(seed)
    ids = [rng.randrange(0x80, 0x7F0) for _ in range(30)]
    return [(ids[i % 30], rng.randbytes(rng.choice((2, 4, 8)))) for i in range(n)]


def test_a_foreign_bus_gets_no_channel():
    learner = TrafficLearner()
    for aid, data in car(3000):
        learner.observe(aid, data)
    assert not learner.evidence and learner.channels == set() and learner.devices == set()


def test_beacons_and_streaming_nodes():
    learner = TrafficLearner()
    for t in range(40):
        learner.observe(0x001, b"\x0a")  # device 1 beacons
        learner.observe(0x205, bytes([t, 1]))  # channel node 5 streams
        if t % 10 == 0:
            learner.observe(0x201, b"\x50\x01")  # device 1: a module-specific frame
            learner.observe(0x301, b"\x03\x01\x00")  # the arbitrator asks device 1
            learner.observe(0x201, b"\x83\x01\x01\x00\x02")  # and it answers
    assert learner.channels == {5} and learner.devices == {1}


def test_a_stray_frame_does_not_unmake_a_settled_channel():
    decoder = FrameDecoder()
    decoder.context_checked = True
    head = [(0x001, b"\x0a"), (0x002, b"\x0a")] + [(0x205, bytes([t, 0])) for t in range(10)]
    for aid, data in head:
        decoder.learner = decoder.learner or TrafficLearner()
        decoder.learner.observe(aid, data)
    decoder.learner.settle()
    decoder.adopt()
    assert 5 in decoder.outputs
    decoder.decode(0x305, b"\x03\x01\x00")  # a stray "request" to node 5
    for t in range(20):
        decoder.decode(0x205, bytes([t, 9]))
    assert decoder.outputs.get(5) == INFERRED and decoder.stats.undecodable == 0


def test_a_node_first_heard_late_is_learned_after_enough_frames():
    decoder = FrameDecoder()
    decoder.context_checked = True
    decoder.learn_from_traffic([])
    for aid, data in [(0x001, b"\x0a"), (0x002, b"\x0a")]:
        decoder.decode(aid, data)
    shown = [decoder.decode(0x207, bytes([t, 0, 1])) for t in range(40)]
    assert 7 in decoder.outputs
    assert sum(f.function == "Channel data" for f in shown) >= 40 - 16
