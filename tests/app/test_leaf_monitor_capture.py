"""The monitor dock with a large capture (issue 16 item 5, issue 10 item 4): the first rows
at once, the rest in the background with progress and cancel, the capture shown apart from
the live frames, and its node map used."""

from __future__ import annotations

import time
from pathlib import Path

import can

from pdcp_studio.app.trace.dock import CHANNEL_DATA, MonitorDock
from pdcp_studio.bus.events import FrameSeen
from pdcp_studio.protocol import messages as M

OK = 1


def write_capture(path: Path, n: int) -> None:
    setup = [M.BindRequest(5, 1, 10, 4), M.BindResponse(5, 5, 1, 10, 4),
             M.BindRequest(7, 2, 2, 5), M.BindResponse(7, 7, 2, 2, 5),
             M.GetParameter(5, 3, 1), M.GetParameterResponse(5, OK, 3, 1, b"\x02"),
             M.SetParameter(5, 5, 1, b"\x06"), M.SetParameterResponse(5, OK, 5, 1, b"\x06"),
             M.SetParameter(7, 7, 2, bytes([5, 6])),
             M.SetParameterResponse(7, OK, 7, 2, bytes([5, 6]))]
    frames = [m.encode() for m in setup]
    frames += [M.ChannelData(6, (i & 0xFFFF).to_bytes(2, "little")).encode() for i in range(n - len(frames))]
    with can.Logger(str(path)) as logger:
        for i, (arbitration_id, data) in enumerate(frames):
            logger.on_message_received(can.Message(timestamp=1000 + i / 8000,
                                                   arbitration_id=arbitration_id, data=data,
                                                   is_extended_id=False))


def test_large_capture_first_rows_at_once_then_the_rest_with_progress(qtbot, tmp_path):
    path = tmp_path / "big.blf"
    write_capture(path, 60_000)
    dock = MonitorDock(capacity=20_000)
    qtbot.addWidget(dock)
    dock.show()
    progress: list[int] = []
    dock.loadProgress.connect(progress.append)
    t0 = time.perf_counter()
    dock.load_capture(path)
    qtbot.waitUntil(lambda: dock.model.rowCount() > 0, timeout=5000)
    first_rows_s = time.perf_counter() - t0
    assert first_rows_s < 1.0, f"first rows after {first_rows_s:.2f} s"
    with qtbot.waitSignal(dock.loaded, timeout=60_000):
        pass
    # Every frame is kept (compact columns), not only the first ``capacity``: the capacity
    # bounds the live ring only.
    assert dock.capture_total == 60_000 and dock.model.rowCount() == 60_000
    assert progress and progress[-1] == 60_000
    assert "60,000" in dock.count_label.text()
    rows = dock.all_rows
    data = [r for r in rows if r.function == CHANNEL_DATA]
    assert len(data) == 60_000 - 10 and "1/10/4#1 → 2/2/5#2" in data[0].text


def test_loading_can_be_cancelled(qtbot, tmp_path):
    path = tmp_path / "big.asc"
    write_capture(path, 150_000)
    dock = MonitorDock(capacity=200_000)
    qtbot.addWidget(dock)
    worker = dock.load_capture(path)
    qtbot.waitUntil(lambda: dock.model.rowCount() > 0, timeout=5000)
    dock.cancel_load()
    qtbot.waitUntil(lambda: not worker.is_running, timeout=10_000)
    qtbot.wait(100)
    assert 0 < len(dock.store) < 150_000
    assert not dock.stop_load_button.isVisibleTo(dock)


def test_capture_is_shown_apart_from_live_frames_and_its_node_map_used(qtbot, tmp_path):
    path = tmp_path / "mid.asc"
    write_capture(path, 500)
    # Saved mid-session: only channel data, and the node map beside it names the link.
    from pdcp_studio.bus.trace.monitor import FrameDecoder, read_capture, write_node_map

    decoder = FrameDecoder()
    frames = list(read_capture(path))
    for msg in frames:
        decoder.decode_message(msg)
    tail = tmp_path / "tail.asc"
    with can.Logger(str(tail)) as logger:
        for msg in frames[10:]:
            logger.on_message_received(msg)
    write_node_map(tail, decoder.node_map())

    dock = MonitorDock()
    qtbot.addWidget(dock)
    live = [FrameSeen(1.0 + i, 0x205, b"\x01", "   0.0  P1  #5→BA Device Beacon")
            for i in range(3)]
    dock.add_frames(live)
    with qtbot.waitSignal(dock.loaded, timeout=10_000):
        dock.load_capture(tail)
    dock.add_frames(live)  # live frames while the capture is shown: kept apart
    assert len(dock.all_rows) == 490
    assert all(r.function == CHANNEL_DATA and "1/10/4#1 → 2/2/5#2" in r.text
               for r in dock.all_rows)
    assert dock.live_button.isVisibleTo(dock)
    dock.show_live()
    assert len(dock.all_rows) == 6 and dock.capture_path is None
