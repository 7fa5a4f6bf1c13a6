"""The monitor's caches (decoded messages, described frames, link texts, bus time in
batches) change nothing: a decoder with them reads every frame exactly as one without."""

from __future__ import annotations

import random

from hypothesis import given, settings
from hypothesis import strategies as st

from pdcp_studio.bus.trace.bustime import BusTimeMeter
from pdcp_studio.bus.trace.monitor import FrameDecoder
from pdcp_studio.protocol import messages as M
from tests.bus.test_monitor import session_frames

OK = 1


class NeverKeeps(dict):
    """A cache that forgets at once: the decoder computes every frame afresh."""

    def __setitem__(self, key, value) -> None:
        pass


def uncached() -> FrameDecoder:
    decoder = FrameDecoder()
    decoder._messages = NeverKeeps()
    decoder._described = NeverKeeps()
    decoder._link_cache = NeverKeeps()
    return decoder


def relearning_traffic(seed: int) -> list[tuple[int, bytes]]:
    """Repeated frames around changes of what the decoder knows: a channel's direction
    learned, a device rebound to another node, an output given a new node ID."""
    rng = random.Random(seed)
    frames = session_frames() * 2
    chunks = [
        [M.GetParameter(5, 5, 2).encode(), M.GetParameterResponse(5, OK, 5, 2, b"\x09").encode()],
        [M.GetParameter(5, 3, 2).encode(), M.GetParameterResponse(5, OK, 3, 2, b"\x02").encode()],
        [M.SetParameter(5, 8, 0, b"\x0b").encode(),
         M.SetParameterResponse(5, OK, 8, 0, b"\x0b").encode()],
        [M.SetParameter(11, 5, 1, b"\x0c").encode(),
         M.SetParameterResponse(11, OK, 5, 1, b"\x0c").encode()],
        [M.ChannelData(6, b"\x01").encode(), M.ChannelData(12, b"\x02").encode(),
         M.ChannelData(9, b"\x03").encode()],
        [M.Beacon(5).encode(), M.Beacon(11).encode()],
    ]
    for _ in range(300):
        frames += rng.choice(chunks)
    return frames


def test_caches_change_no_line():
    for seed in range(3):
        frames = relearning_traffic(seed)
        cached, plain = FrameDecoder(), uncached()
        for i, (arbitration_id, data) in enumerate(frames):
            a = cached.decode(arbitration_id, data, 10.0 + i / 1000)
            b = plain.decode(arbitration_id, data, 10.0 + i / 1000)
            assert a.as_json() == b.as_json(), (i, a.line, b.line)
        assert cached.stats.as_json() == plain.stats.as_json()
        assert cached.node_map() == plain.node_map()  # and they learned the same


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 0x7FF), st.binary(max_size=8)), max_size=60),
       st.integers(0, 3))
def test_caches_change_no_line_on_any_frames(noise, seed):
    frames = relearning_traffic(seed)[:200] + noise + relearning_traffic(seed)[:200]
    cached, plain = FrameDecoder(), uncached()
    for i, (arbitration_id, data) in enumerate(frames):
        assert cached.decode(arbitration_id, data, float(i)).as_json() == \
            plain.decode(arbitration_id, data, float(i)).as_json()
    assert cached.node_map() == plain.node_map()


def test_meter_total_is_the_same_fed_one_by_one_or_read_midway():
    meter, midway = BusTimeMeter(), BusTimeMeter()
    frames = relearning_traffic(1)
    for i, (arbitration_id, data) in enumerate(frames):
        meter.add(arbitration_id, data)
        midway.add(arbitration_id, data)
        if i % 777 == 0:
            assert midway.bits > 0  # reading counts the queued frames first
    assert meter.bits == midway.bits
