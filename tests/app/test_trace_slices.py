"""The trace's work on the GUI thread comes in bounded slices, and its memory does not grow
with what it has seen (issue 16 in the app): statistics rows are made only for the rows
painted, a backlog of live frames is taken a slice per turn of the event loop, the plot's
points go to Qt without an object each, and the capture's remembered texts stay bounded."""

from __future__ import annotations

import gc
import tracemalloc

import numpy as np
import pytest

from pdcp_studio.app.live.plot import _polygon
from pdcp_studio.app.trace import dock as monitor_dock
from pdcp_studio.app.trace.disk import RECENT_TEXTS, FileTexts
from pdcp_studio.app.trace.dock import INGEST_SLICE, MonitorDock
from pdcp_studio.app.trace.store import ChunkBuilder, IdStats, StatRows, Tables
from pdcp_studio.bus.events import FrameSeen


def _frames(n: int, ids: int = 40, t0: float = 1000.0) -> list[FrameSeen]:
    """``n`` frames from ``ids`` extended identifiers (garbage on a busy bus has many)."""
    return [FrameSeen(t0 + i / 8000, 0x10000 + i % ids, bytes([3, i & 0xFF]),
                      f"{i / 8000:11.6f}  P0  something {i % ids}") for i in range(n)]


def _stats(tables: Tables, frames: list[tuple[int, bytes, float]]) -> IdStats:
    stats = IdStats(tables)
    builder = ChunkBuilder(tables)
    for aid, data, t in frames:
        builder.add(t, aid, data, f"text of {aid:X}")
    stats.update(builder.take())
    return stats


@pytest.mark.gui
def test_statistics_rows_are_made_only_for_the_rows_painted(qtbot, monkeypatch):
    dock = MonitorDock()
    qtbot.addWidget(dock)
    dock.resize(900, 500)
    dock.show()
    dock.add_frames(_frames(8000, ids=4000))
    dock.flush()
    made: list[int] = []
    stats = dock.live_stats
    row = stats.row
    monkeypatch.setattr(stats, "row", lambda aid: made.append(aid) or row(aid))
    dock._refresh_stats()
    dock.stats_view.grab()  # one paint of what is on screen
    shown = dock.stats_view.viewport().height() // dock.stats_view.rowHeight(0) + 2
    assert isinstance(dock.stats_model.stats, StatRows) and len(dock.stats_model.stats) == 4000
    assert 0 < len(made) <= shown < 100  # not 4,000 rows four times a second
    # the rows made on demand are the statistics' own, in identifier order
    monkeypatch.undo()
    first = dock.stats_model.stats[0]
    assert first == stats.rows()[0] and first.arbitration_id == 0x10000 and first.count == 2
    assert dock.stats_model.row_texts(3999)[0] == "0x%08X" % (0x10000 + 3999)


def test_statistics_entries_are_replaced_whole_and_new_ids_sorted_in():
    tables = Tables()
    stats = _stats(tables, [(5, b"\x01", 1.0), (9, b"\x02", 1.5), (5, b"\x03", 2.0)])
    view = stats.view()
    assert view.ids == [5, 9] and view[0].count == 2 and view[0].last_data == b"\x03"
    held = stats.entries[5]
    before = list(held)
    builder = ChunkBuilder(tables)
    for aid, t in ((7, 3.0), (5, 3.5), (2, 4.0)):
        builder.add(t, aid, b"\x04", "later")
    stats.update(builder.take())
    # a reader holding the old entry sees it whole and unchanged; the new one is complete
    assert held == before and stats.entries[5] is not held
    assert stats.row(5).count == 3 and stats.row(5).last_period_s == pytest.approx(1.5)
    assert stats.sorted_ids() == [2, 5, 7, 9] and view.ids == [5, 9]  # a view keeps its IDs
    assert [s.arbitration_id for s in stats.rows()] == [2, 5, 7, 9]
    stats.clear()
    assert stats.sorted_ids() == [] and stats.view()[:] == []


@pytest.mark.gui
def test_a_backlog_of_live_frames_is_taken_a_slice_per_turn_of_the_event_loop(qtbot):
    dock = MonitorDock()
    qtbot.addWidget(dock)
    frames = _frames(INGEST_SLICE * 3 + 500)
    dock.add_frames(frames)
    dock._tick()
    assert dock.model.rowCount() == INGEST_SLICE  # one slice, the rest after other events
    assert len(dock.feed.incoming) == len(frames) - INGEST_SLICE
    qtbot.waitUntil(lambda: dock.model.rowCount() == len(frames), timeout=5000)
    assert not dock.feed.incoming and dock.frames_seen == len(frames)
    assert [f.timestamp for f in dock.shown_rows()] == [f.timestamp for f in frames]
    other = MonitorDock()  # flush() still takes everything at once
    qtbot.addWidget(other)
    other.add_frames(frames)
    other.flush()
    assert other.model.rowCount() == len(frames) and not other.feed.incoming


@pytest.mark.gui
def test_the_collector_is_spared_once_the_trace_gets_busy(qtbot):
    dock = MonitorDock()
    qtbot.addWidget(dock)
    dock.add_frames(_frames(10))
    dock.flush()
    assert monitor_dock._FROZEN and gc.get_freeze_count() > 0


def test_plot_points_written_into_qt_are_the_values():
    xs = np.linspace(10.0, 590.5, 1201)
    ys = np.sin(xs) * 100 + 150
    polygon = _polygon(xs, ys)
    assert len(polygon) == 1201
    assert [(p.x(), p.y()) for p in polygon] == list(zip(xs.tolist(), ys.tolist(), strict=True))
    assert len(_polygon(np.zeros(0), np.zeros(0))) == 0


def test_remembered_texts_stay_bounded_and_texts_in_use_keep_their_number(tmp_path):
    texts = FileTexts(str(tmp_path))
    try:
        common = texts.add("P0  #5→BA Device Beacon")

        def feed(start: int, stop: int) -> None:
            for i in range(start, stop):
                texts.add(f"P0  #6 data Channel data  value {i}")
                if i % 50 == 0:
                    assert texts.add("P0  #5→BA Device Beacon") == common  # used: remembered

        tracemalloc.start()
        try:
            feed(0, RECENT_TEXTS * 2)  # the window of remembered texts full (and turned over)
            gc.collect()
            full = tracemalloc.get_traced_memory()[0]
            feed(RECENT_TEXTS * 2, RECENT_TEXTS * 6)  # twice as many distinct texts again
            gc.collect()
            grown = tracemalloc.get_traced_memory()[0] - full
        finally:
            tracemalloc.stop()
        assert len(texts) == RECENT_TEXTS * 6 + 2 and len(texts._recent) <= RECENT_TEXTS
        assert grown < 500_000, f"{grown / 1e6:.1f} MB more for {RECENT_TEXTS * 4:,} more texts"
        assert texts[common] == "P0  #5→BA Device Beacon"
        last = RECENT_TEXTS * 6 - 1
        assert texts[last + 2] == f"P0  #6 data Channel data  value {last}"
    finally:
        texts.close()


@pytest.mark.gui
def test_a_repaint_reads_the_frames_on_screen_at_once(qtbot, tmp_path, monkeypatch):
    from pdcp_studio.app.trace.disk import FileFrameStore

    from .trace_frames import synthetic_store

    dock = MonitorDock()
    qtbot.addWidget(dock)
    dock.resize(900, 500)
    dock.show()
    store = synthetic_store(20_000, store=FileFrameStore(str(tmp_path)))
    dock.show_frames(store, title="capture")
    reads: list[int] = []
    records = store._records
    monkeypatch.setattr(store, "_records",
                        lambda start, stop: reads.append(stop - start) or records(start, stop))
    view = dock.view
    view.scrollTo(dock.model.index(12_345, 0))
    view.grab()
    first, last = view.rowAt(0), view.rowAt(view.viewport().height() - 1)
    assert first <= 12_345 <= last and last - first > 5
    assert reads == [last - first + 1]  # one read for the screenful, not one a row
    shown = {r: dock.model.row_texts(r) for r in range(first, last + 1)}  # read ahead already
    assert len(reads) == 1
    assert shown[12_345][4] == store.frame(12_345).data.hex(" ").upper()
    store.clear()  # what was read ahead goes with the frames
    with pytest.raises(IndexError):
        store.frame(12_345)
