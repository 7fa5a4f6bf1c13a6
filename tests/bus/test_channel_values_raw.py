"""Channel data reaches the app in the channel type's own numbers: an unsigned 12-bit EMG
envelope reads 0–4095 (the live plot's axis spans that range; fractions of full scale sat
flat at 0 on it)."""

from __future__ import annotations

import threading

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.sim.signals import decode_raw, encode_sample
from pdcp_studio.model.refs import ChannelRef

EMG = ChannelRef(2641, 257, 101, 1)  # type 0x9000: unsigned 12-bit, position


def test_decode_raw_gives_the_types_numbers():
    assert decode_raw(0x9000, encode_sample(0x9000, 1.0)) == 4095
    assert decode_raw(0x9000, encode_sample(0x9000, 0.0)) == 0
    assert decode_raw(0x8400, encode_sample(0x8400, -1.0)) == -2047  # signed 12-bit
    assert decode_raw(0xB000, encode_sample(0xB000, 1.0)) == 1.0  # a flag


def test_the_simulators_emg_envelope_arrives_in_raw_numbers():
    seen: list[float] = []
    done = threading.Event()

    def on(event: object) -> None:
        if isinstance(event, ev.ChannelValue) and event.ref == EMG:
            seen.append(event.value)
            if len(seen) >= 200:
                done.set()

    session = open_session("sim:transradial")
    try:
        session.subscribe(on)
        assert done.wait(30.0), f"only {len(seen)} values"
    finally:
        session.close()
    assert all(0 <= v <= 4095 and v == int(v) for v in seen)
    assert max(seen) > 100  # raw numbers, not fractions of full scale
