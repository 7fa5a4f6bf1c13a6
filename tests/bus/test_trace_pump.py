"""The monitor's hot loop (bus/trace/pump.py) writes exactly what decoding every frame one by
one writes: the same lines, the same JSON records, the same statistics — on traffic that
keeps changing what the decoder knows, with odd frames, filters, quiet polls and odd times."""

from __future__ import annotations

import io
import json
import random

import can
from hypothesis import given, settings
from hypothesis import strategies as st

from pdcp_studio.bus.trace.monitor import FrameDecoder, frame_json
from pdcp_studio.bus.trace.pump import TracePump
from pdcp_studio.cli.monitor import make_filter
from pdcp_studio.protocol import messages as M
from tests.bus.test_monitor import session_frames
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


def one_by_one(msgs, *, as_json: bool, show=None, checked: bool = False) -> tuple[str, dict]:
    decoder = FrameDecoder()
    decoder.context_checked = checked
    shown = []
    for msg in msgs:
        frame = decoder.decode_message(msg)
        if show is None or show(frame):
            shown.append((frame, msg))
    if as_json:
        text = (('{"frames": [\n' + ",\n".join(frame_json(f, None, m) for f, m in shown)
                 + '\n], "summary": {}}\n') if shown else '{"frames": [], "summary": {}}\n')
    else:
        text = "".join(f.line + "\n" for f, _ in shown)
    return text, decoder.stats.as_json()


def pumped(msgs, *, as_json: bool, show=None, polls: bool = False,
           checked: bool = False, stdout: bool = False) -> tuple[str, dict]:
    """``stdout``: a UTF-8 text stream over bytes, as sys.stdout is (lines go to its byte
    buffer), with text written to it between frames."""
    decoder = FrameDecoder()
    decoder.context_checked = checked
    out = io.TextIOWrapper(io.BytesIO(), encoding="utf-8") if stdout else io.StringIO()
    pump = TracePump(decoder, out, json=as_json, show=show)
    items = list(msgs)
    if polls:  # quiet polls between frames, as a live bus gives them
        items = [x for m in items for x in ((m, None) if m.arbitration_id % 7 == 0 else (m,))]

    def other(item) -> None:
        if stdout:
            out.write("a report →\n")
    pump.run(items, other)
    pump.close()
    if stdout:
        out.flush()
        text = out.buffer.getvalue().decode()
        return text.replace("a report →\n", ""), decoder.stats.as_json()
    return out.getvalue(), decoder.stats.as_json()


FILTERS = [None, ["node=6"], ["direction=data"], ["direction=to-ba"], ["node=254"],
           ["function=beacon"], ["errors"]]


def test_the_pump_writes_what_one_by_one_decoding_writes():
    msgs = messages(relearning_traffic(2) * 3, seed=2)
    for checked in (False, True):
        for as_json in (False, True):
            for spec in FILTERS:
                show = make_filter(spec) if spec else None
                expected = one_by_one(msgs, as_json=as_json, show=show, checked=checked)
                assert pumped(msgs, as_json=as_json, show=show, checked=checked) == expected, \
                    (as_json, spec)
                assert pumped(msgs, as_json=as_json, show=show, polls=True,
                              checked=checked) == expected
                assert pumped(msgs, as_json=as_json, show=show, polls=True, checked=checked,
                              stdout=True) == expected


def test_most_frames_of_a_busy_bus_take_the_short_ways():
    """Channel data of known outputs, and beacons and requests seen before, are counted by
    the pump from what the decoder said the first time (else the test above proves little)."""
    rng = random.Random(5)
    busy = []
    for _ in range(2000):
        roll = rng.random()
        busy += ([M.ChannelData(6, rng.randbytes(4)).encode()] if roll < 0.8 else
                 [M.Beacon(5).encode()] if roll < 0.87 else
                 # a response nobody asked for: unattributed when the context is checked
                 [M.GetParameterResponse(5, 1, 9, 0, b"\x01").encode()] if roll < 0.9 else
                 [M.GetParameter(5, 9, 0).encode(),
                  M.GetParameterResponse(5, 1, 9, 0, b"\x01").encode()])
    msgs = messages(session_frames() + busy, seed=1)
    decoder = FrameDecoder()
    decoded = []
    real = decoder.decode_message
    decoder.decode_message = lambda msg: decoded.append(msg) or real(msg)  # type: ignore
    pump = TracePump(decoder, io.StringIO())
    pump.run(msgs, lambda item: None)
    assert len(decoded) < 0.2 * len(msgs)
    text, stats = pumped(msgs, as_json=False)
    assert (text, stats) == one_by_one(msgs, as_json=False)
    assert pumped(msgs, as_json=False, stdout=True, polls=True) == (text, stats)
    assert pumped(msgs, as_json=True, checked=True) == \
        one_by_one(msgs, as_json=True, checked=True)
    assert pump._heads and pump._repeats


def test_the_json_is_one_document_of_the_records():
    msgs = messages(relearning_traffic(0))
    text, _ = pumped(msgs, as_json=True)
    records = json.loads(text)["frames"]
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
        checked = bool(seed % 2)
        expected = one_by_one(msgs, as_json=as_json, checked=checked)
        assert pumped(msgs, as_json=as_json, checked=checked) == expected
        assert pumped(msgs, as_json=as_json, checked=checked, stdout=True) == expected
