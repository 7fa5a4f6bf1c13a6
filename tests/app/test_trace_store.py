"""The trace's column store (no Qt): building, the live ring, filters and search over all
frames, per-ID statistics, and reading a real capture into it."""

from __future__ import annotations

import threading

import can
import numpy as np
import pytest

from pdcp_studio.app.trace.files.capture import load_capture, save_store
from pdcp_studio.app.trace.store import (
    CHANNEL_DATA,
    ChunkBuilder,
    FrameStore,
    IdStats,
    TraceFilter,
    line_head,
)
from pdcp_studio.bus.trace.monitor import read_capture
from pdcp_studio.protocol import messages as M

from .trace_frames import NEEDLE_DATA, NEEDLE_ID, synthetic_store


def test_builder_classifies_and_keeps_the_text_without_repeating_the_data():
    store = FrameStore()
    b = ChunkBuilder(store.tables, {12})
    b.add(1.0, 12, b"\x01\x02", "P0  #12 data Channel data  Hand output 1 → x  01 02")
    b.add(1.1, 0x107, b"\x03\x01\x00", "P0  BA→#7 Get Device Parameter  param 1")
    b.add(1.2, 0x100, b"\x09", "P0  BA→all Release Device")
    b.add(1.3, 7, b"\x0a", "P0  #7→BA Device Beacon")
    store.append(b.take())
    frames = [store.frame(i) for i in range(4)]
    assert [f.function for f in frames] == [CHANNEL_DATA, "Get Device Parameter",
                                           "Release Device", "Device Beacon"]
    assert [f.who for f in frames] == ["#12 data", "BA→#7", "BA→all", "#7→BA"]
    assert frames[0].text == "P0  #12 data Channel data  Hand output 1 → x"  # data stripped
    assert store.text(frames[0]).endswith("→ x  01 02")  # and put back when shown
    assert len(store.tables.texts) == 5  # "" and the four distinct texts
    assert line_head("   0.125000  P0  #7→BA Device Beacon") == "P0  #7→BA Device Beacon"


def test_live_ring_keeps_exactly_its_capacity_with_absolute_row_numbers():
    store = FrameStore(max_rows=1000)
    b = ChunkBuilder(store.tables)
    for i in range(5000):
        b.add(i / 100, 5, b"\x0a", "P0  #5→BA Device Beacon")
        if len(b) == 700:
            store.append(b.take())
            assert len(store) <= 1000
    store.append(b.take())
    assert len(store) == 1000 and (store.base, store.end) == (4000, 5000)
    assert store.frame(4000).timestamp == pytest.approx(40.0)
    with pytest.raises(IndexError):
        store.frame(3999)
    frozen = store.snapshot()
    b.add(99.0, 5, b"\x0a", "x")
    store.append(b.take())
    assert frozen.end == 5000 and store.end == 5001


def test_filters_and_search_run_over_a_million_frames():
    store = synthetic_store(1_000_000)
    assert len(store) == 1_000_000
    hits = store.select(TraceFilter(text=f"0x{NEEDLE_ID:03X}"))
    assert hits.tolist() == [1_000_000 - 17]
    assert store.select(TraceFilter(text="de ad be ef")).tolist() == hits.tolist()
    assert store.select(TraceFilter(text="DEADBEEF")).tolist() == hits.tolist()
    beacons = store.select(TraceFilter(function="Device Beacon"))
    assert len(beacons) == 10_000 and (beacons % 100 == 0).all()
    node5 = store.select(TraceFilter(node=5))
    assert np.array_equal(node5, beacons)
    broadcasts = store.select(TraceFilter(node=0))
    assert len(broadcasts) == 1000 and store.frame(int(broadcasts[-1])).who == "BA→all"
    text = store.select(TraceFilter(text="control unit input"))  # in the decoded text
    assert len(text) == 1_000_000 - 10_000 - 1000 - 1
    cancel = threading.Event()
    cancel.set()
    assert len(store.select(TraceFilter(node=5), cancel=cancel)) == 0


def test_per_id_statistics_count_period_last_data_and_meaning():
    store = synthetic_store(200_000)
    stats = IdStats(store.tables)
    for chunk in store.chunks:
        stats.update(chunk)
    rows = {s.arbitration_id: s for s in stats.rows()}
    assert rows[5].count == 2000 and rows[5].period_s == pytest.approx(100 / 8000)
    assert rows[5].last_period_s == pytest.approx(100 / 8000)
    assert rows[5].function == "Device Beacon"
    assert rows[NEEDLE_ID].count == 1 and rows[NEEDLE_ID].last_data == NEEDLE_DATA
    assert rows[NEEDLE_ID].period_s is None
    last6 = store.frame(199_999)
    assert rows[6].last_data == last6.data and rows[6].text.endswith(last6.data.hex(" ").upper())
    assert sum(s.count for s in rows.values()) == 200_000


def _write(path, n):
    frames = [M.BindRequest(5, 1, 10, 4).encode(), M.BindResponse(5, 5, 1, 10, 4).encode()]
    frames += [M.ChannelData(6, (i & 0xFFFF).to_bytes(2, "little")).encode()
               for i in range(n - 2)]
    with can.Logger(str(path)) as logger:
        for i, (aid, data) in enumerate(frames):
            logger.on_message_received(can.Message(timestamp=1000 + i / 8000,
                                                   arbitration_id=aid, data=data,
                                                   is_extended_id=False))


@pytest.mark.parametrize("suffix", [".asc", ".blf", ".trc", ".csv", ".log"])
def test_every_python_can_format_loads_and_saves_back(tmp_path, suffix):
    path = tmp_path / f"cap{suffix}"
    _write(path, 3000)
    store = FrameStore()
    stats = IdStats(store.tables)
    seen: list[tuple[int, int]] = []
    count = load_capture(store, stats, path,
                         lambda done, permille, _t: seen.append((done, permille)),
                         threading.Event()).frames
    assert count == len(store) == 3000
    assert seen[0][0] == 500 and seen[-1] == (3000, 1000)  # a small first chunk, then all
    assert store.frame(0).function == "Bind Device Request"
    assert stats.frames == 3000
    out = tmp_path / f"back{suffix}"
    assert save_store(out, store) == 3000
    back = list(read_capture(out))
    assert [(m.arbitration_id, bytes(m.data)) for m in back] == \
        [(store.frame(i).arbitration_id, store.frame(i).data) for i in range(3000)]
