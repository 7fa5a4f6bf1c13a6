"""An opened capture on disk (no Qt): memory flat whatever its length, search over all of
it, the temporary files gone on close."""

from __future__ import annotations

import gc
import os
import threading

import numpy as np
import pytest

from pdcp_studio.app.trace.disk import CACHED_TEXTS, RECENT_TEXTS, FileFrameStore, FileTexts
from pdcp_studio.app.trace.files.capture import load_capture, save_store
from pdcp_studio.app.trace.store import IdStats, TraceFilter
from pdcp_studio.bus.trace.monitor import read_capture
from pdcp_studio.protocol import messages as M

from .trace_frames import NEEDLE_DATA, NEEDLE_ID, synthetic_store


def _rss_mb() -> float:
    """The process's resident memory now (not its peak), in MB."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 1e6


def _growth(n: int, tmp_path, before: float) -> tuple[float, FileFrameStore]:
    store = synthetic_store(n, store=FileFrameStore(str(tmp_path)), distinct_every=4)
    gc.collect()
    return _rss_mb() - before, store


def test_memory_stays_flat_from_half_a_million_to_two_million_frames(tmp_path):
    synthetic_store(100_000, store=FileFrameStore(str(tmp_path)), distinct_every=4).close()
    gc.collect()  # (the allocator warmed up: the measure is of what stays per frame)
    start = _rss_mb()
    small, store = _growth(500_000, tmp_path, start)
    store.close()
    big, store = _growth(2_000_000, tmp_path, start)
    try:
        # In memory, the 1,500,000 frames more than the small capture would take 42 MB of
        # columns and their 375,000 texts ~100 MB (string, lower-case copy, index). On disk
        # only the recent texts (to number repeats alike) and a read cache stay in memory,
        # and the allocator's slack (a few chunk-sized blocks).
        assert len(store) == 2_000_000 and len(store.tables.texts) > 490_000
        assert os.path.getsize(store.path) == 2_000_000 * 28
        assert big < 60, f"{big:.1f} MB for 2,000,000 frames"
        assert big - small < 30, f"{small:.1f} MB for 500,000, {big:.1f} MB for 2,000,000"
        # search and filters still see every frame, the last ones included
        hits = store.select(TraceFilter(text=f"0x{NEEDLE_ID:03X}"))
        assert hits.tolist() == [2_000_000 - 17]
        assert store.select(TraceFilter(text="de ad be ef")).tolist() == hits.tolist()
        frame = store.frame(int(hits[0]))
        assert frame.data == NEEDLE_DATA and frame.arbitration_id == NEEDLE_ID
        last = store.select(TraceFilter(text="value 1999998"))  # a text made near the end
        assert last.tolist() == [1_999_998]
        assert store.text(store.frame(1_999_998)).startswith("P0  #6 data Channel data  value")
        assert len(store.select(TraceFilter(function="Device Beacon"))) == 20_000
        gc.collect()
        assert _rss_mb() - start < 50  # reading all of it back held no more than a chunk
    finally:
        store.close()


def test_the_temporary_files_are_removed_on_close_and_when_dropped(tmp_path):
    store = synthetic_store(10_000, store=FileFrameStore(str(tmp_path)))
    folder = store.folder
    assert os.path.exists(store.path)
    paused = store.snapshot()
    assert paused.frame(9_999).index == 9_999
    store.close()
    assert not os.path.exists(folder)
    assert len(paused.select(TraceFilter(node=5))) == 0  # a late reader finds nothing
    store = synthetic_store(1000, store=FileFrameStore(str(tmp_path)))
    folder = store.folder
    del store
    gc.collect()
    assert not os.path.exists(folder) and os.listdir(tmp_path) == []


def test_texts_on_disk_number_repeats_alike_and_keep_memory_bounded(tmp_path):
    texts = FileTexts(str(tmp_path))
    numbers = [texts.add(f"text {i}") for i in range(RECENT_TEXTS * 3)]
    assert numbers == list(range(1, RECENT_TEXTS * 3 + 1))
    assert texts.add(f"text {RECENT_TEXTS * 3 - 1}") == numbers[-1]  # a recent repeat
    assert texts.add("text 0") == len(texts) - 1  # an old one is numbered anew
    assert texts[1] == "text 0" and texts[numbers[-1]] == f"text {RECENT_TEXTS * 3 - 1}"
    assert texts.add("two\nlines") and texts[len(texts) - 1] == "two lines"
    for i in range(1, CACHED_TEXTS * 2):
        assert texts[i] == f"text {i - 1}"
    assert len(texts._cache) <= CACHED_TEXTS and len(texts._recent) <= RECENT_TEXTS + 1
    mask = texts.matching("text 1234")
    assert np.flatnonzero(mask)[:2].tolist() == [1235, 12341]
    texts.close()


def _write_log(path, n: int) -> None:
    """A candump log of ``n`` frames: a binding, then channel data of node 6 counting."""
    frames = [M.BindRequest(5, 1, 10, 4).encode(), M.BindResponse(5, 5, 1, 10, 4).encode()]
    frames += [M.ChannelData(6, (i & 0xFFFF).to_bytes(2, "little")).encode()
               for i in range(n - 3)]
    frames.append((NEEDLE_ID, NEEDLE_DATA))
    with open(path, "w") as out:
        out.writelines(f"({1000 + i / 8000:.6f}) can0 {aid:03X}#{data.hex().upper()}\n"
                       for i, (aid, data) in enumerate(frames))


def test_a_capture_file_opens_into_the_disk_store_and_saves_back(tmp_path):
    path = tmp_path / "capture.log"
    _write_log(path, 20_000)
    store = FileFrameStore(str(tmp_path))
    stats = IdStats(store.tables)
    seen: list[int] = []
    count = load_capture(store, stats, path, lambda done, _p, _t: seen.append(done),
                         threading.Event()).frames
    assert count == len(store) == 20_000 and seen[0] == 500
    assert store.frame(0).function == "Bind Device Request"
    assert store.select(TraceFilter(text="de ad be ef")).tolist() == [19_999]
    assert {s.arbitration_id: s.count for s in stats.rows()}[NEEDLE_ID] == 1
    out = tmp_path / "back.asc"
    assert save_store(out, store) == 20_000
    back = list(read_capture(out))
    assert [(m.arbitration_id, bytes(m.data)) for m in back[-3:]] == \
        [(store.frame(i).arbitration_id, store.frame(i).data) for i in range(19_997, 20_000)]
    folder = store.folder
    store.close()
    assert not os.path.exists(folder)


def test_saving_a_capture_closed_meanwhile_keeps_the_old_file(tmp_path):
    store = synthetic_store(5000, store=FileFrameStore(str(tmp_path)))
    out = tmp_path / "kept.asc"
    out.write_text("old")
    paused = store.snapshot()  # what a save works from
    store.close()
    with pytest.raises(OSError, match="0 of 5,000"):
        save_store(out, paused)
    assert out.read_text() == "old"
