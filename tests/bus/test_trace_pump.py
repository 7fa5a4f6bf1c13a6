"""The monitor's hot loop (bus/trace_pump.py) writes exactly what decoding every frame one by
one writes: the same lines, the same JSON records, the same statistics — on traffic that
keeps changing what the decoder knows, with odd frames, filters, quiet polls and odd times."""

from __future__ import annotations

import io
import json
import random

import can
from hypothesis import given, settings
from hypothesis import strategies as st

from pdcp_studio.bus.monitor import FrameDecoder, frame_json
from pdcp_studio.bus.trace_pump import TracePump
from pdcp_studio.cli.monitor import make_filter
from pdcp_studio.protocol import messages as M
from tests.bus.test_monitor_caches import relearning_traffic


def messages(frames, t0: float = 1_700_000_000.0, step: float = 1 / 8000, seed: int = 0):
    """can.Messages of ``frames``, now and then an extended, remote or error frame on an
    identifier that also carries channel data."""
    rng = random.Random(seed)
    out = []
    for i, (arbitration_id, data) in enumerate(frames):
        out.append(can.Message(timestamp=t0 + i * step, arbitration_id=arbitration_id,
                               data=bytearray(data), is_extended_id=False))
        if rng.random() < 0.02:
            kind = rng.choice(["extended", "remote", "error"])
            out.append(can.Message(timestamp=t0 + i * step, arbitration_id=0x006,
                                   data=b"" if kind == "remote" else b"\x01\x02",
                                   is_extended_id=kind == "extended",
                                   is_remote_frame=kind == "remote",
                                   is_error_frame=kind == "error"))
    return out


def one_by_one(msgs, *, as_json: bool, show=None) -> tuple[str, dict]:
    decoder = FrameDecoder()
    shown = []
    for msg in msgs:
        frame = decoder.decode_message(msg)
        if show is None or show(frame):
            shown.append(frame)
    if as_json:
        text = ("[\n" + ",\n".join(frame_json(f) for f in shown) + "\n]\n") if shown else "[]\n"
    else:
        text = "".join(f.line + "\n" for f in shown)
    return text, decoder.stats.as_json()


def pumped(msgs, *, as_json: bool, show=None, polls: bool = False) -> tuple[str, dict]:
    decoder = FrameDecoder()
    out = io.StringIO()
    pump = TracePump(decoder, out, json=as_json, show=show)
    items = list(msgs)
    if polls:  # quiet polls between frames, as a live bus gives them
        items = [x for m in items for x in ((m, None) if m.arbitration_id % 7 == 0 else (m,))]
    pump.run(items, lambda item: None)
    pump.close()
    return out.getvalue(), decoder.stats.as_json()


FILTERS = [None, ["node=6"], ["direction=data"], ["direction=to-ba"], ["node=254"],
           ["function=beacon"], ["errors"]]


def test_the_pump_writes_what_one_by_one_decoding_writes():
    msgs = messages(relearning_traffic(2) * 3, seed=2)
    for as_json in (False, True):
        for spec in FILTERS:
            show = make_filter(spec) if spec else None
            expected = one_by_one(msgs, as_json=as_json, show=show)
            assert pumped(msgs, as_json=as_json, show=show) == expected, (as_json, spec)
            assert pumped(msgs, as_json=as_json, show=show, polls=True) == expected


def test_the_json_is_one_document_of_the_records():
    msgs = messages(relearning_traffic(0))
    text, _ = pumped(msgs, as_json=True)
    records = json.loads(text)
    assert len(records) == len(msgs)
    assert [r["text"] for r in records] == one_by_one(msgs, as_json=False)[0].splitlines()


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 0x7FF), st.binary(max_size=8)), max_size=80),
       st.integers(0, 3), st.sampled_from([0.0, 1e-6, 3e-5, 0.5, 1e8, 2e9]),
       st.floats(-5.0, 1e10, allow_nan=False))
def test_any_frames_at_any_times(noise, seed, step, t0):
    """Times near zero, far from it and going backwards (repr switches to exponents)."""
    frames = relearning_traffic(seed)[:150] + noise + [M.ChannelData(6, b"\x01").encode()] * 5
    msgs = messages(frames, t0=t0, step=step if seed % 2 else -step, seed=seed)
    for as_json in (False, True):
        assert pumped(msgs, as_json=as_json) == one_by_one(msgs, as_json=as_json)
