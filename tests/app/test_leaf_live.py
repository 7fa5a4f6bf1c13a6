"""Live plot and bus monitor on the real simulated prosthesis (frames and values through the
SessionBridge), plus the monitor's table mechanics."""

from __future__ import annotations

import pytest
from PySide6.QtGui import QColor, QImage

from pdcp_studio.app.live.plot import LivePlot, as_number
from pdcp_studio.app.live.session_bridge import SessionBridge
from pdcp_studio.app.trace.dock import CHANNEL_DATA, MonitorDock, make_row
from pdcp_studio.bus.events import FrameSeen
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.trace.monitor import read_capture
from pdcp_studio.model.refs import ChannelRef

pytestmark = pytest.mark.gui

CU_O3 = ChannelRef(2641, 513, 201, 3)  # control unit output 3 → hand input 1


@pytest.fixture
def live(qtbot):
    """A bridge on sim:transradial (its arbitrator reports every frame as ``FrameSeen``)."""
    session = open_session("sim:transradial")
    bridge = SessionBridge(session, interval_ms=20)
    yield bridge
    bridge.close(wait_ms=5000)
    assert session.closed


def test_live_plot_shows_the_values_of_the_selected_link(qtbot, live):
    plot = LivePlot(window_s=5.0, fps=50)
    qtbot.addWidget(plot)
    plot.resize(400, 200)
    plot.show()
    live.channelValues.connect(plot.add_values)
    link = next(lk for lk in live.system().links if lk.output == CU_O3)
    seen: list[float] = []
    live.channelValues.connect(lambda vs: seen.extend(v.value for v in vs if v.ref == CU_O3))
    with qtbot.waitSignal(plot.channelChanged) as changed:
        plot.set_link(link, "Control unit #3 → Hand #1")
    assert changed.args == [CU_O3]
    qtbot.waitUntil(lambda: len(plot.points) >= 10, timeout=5000)
    assert [p[1] for p in plot.points] == seen[-len(plot.points):]  # only this link's values
    qtbot.waitUntil(lambda: plot.paint_count > 0, timeout=2000)
    image: QImage = plot.grab().toImage()
    highlight = QColor(plot.series[0].color)
    traced = sum(1 for x in range(0, image.width(), 2) for y in range(0, image.height(), 2)
                 if image.pixelColor(x, y) == highlight)
    assert traced > 10  # the polyline is drawn in the signal's colour
    plot.set_window(0.2)  # the axis shows 0.2 s; values are kept for the longest window
    assert plot.window_s == 0.2 and plot.window_box.currentIndex() >= 0
    assert len(plot.points) >= 10
    plot.set_link(None)
    assert plot.ref is None and not plot.points
    plot.add_values([])  # nothing selected: ignored


def test_live_plot_repaints_are_capped(qtbot):
    import time

    from pdcp_studio.bus.events import ChannelValue

    plot = LivePlot(fps=10)  # at most one repaint per 100 ms
    qtbot.addWidget(plot)
    plot.show()
    plot.set_channel(CU_O3)
    qtbot.wait(50)
    before = plot.paint_count
    start = time.monotonic()
    for i in range(200):  # 200 batches, the event loop turning in between
        plot.add_values([ChannelValue(CU_O3, float(i % 7), 1000.0 + i * 0.01)])
        qtbot.wait(1)
    qtbot.wait(150)
    elapsed_ms = (time.monotonic() - start) * 1000
    assert len(plot.points) == 200
    painted = plot.paint_count - before
    assert 1 <= painted <= elapsed_ms / 100 + 2  # capped, however slow the machine


def test_as_number():
    assert as_number(True) == 1.0 and as_number(3) == 3.0 and as_number(0.5) == 0.5
    assert as_number(b"\x01\x02") == 513.0 and as_number(b"") is None and as_number("x") is None


def test_monitor_shows_decoded_bus_frames_filters_pauses_and_saves(qtbot, live, tmp_path):
    dock = MonitorDock(capacity=5000)
    qtbot.addWidget(dock)
    dock.set_system(live.system())
    assert dock.channel_nodes  # the output channels' node IDs
    live.frameSeen.connect(dock.add_frames)
    qtbot.waitUntil(lambda: len(dock.all_rows) >= 50, timeout=5000)
    functions = {r.function for r in dock.all_rows}
    assert CHANNEL_DATA in functions and "Device Beacon" in functions
    data = next(i for i, r in enumerate(dock.shown_rows()) if r.function == CHANNEL_DATA)
    cells = [dock.model.data(dock.model.index(data, c)) for c in range(6)]
    assert cells[2].endswith(" data") and cells[3] == CHANNEL_DATA
    # decoded: which output feeds which input, by device name (the raw reference in the tip)
    assert "→" in cells[5] and "2641/" not in cells[5] and " #" in cells[5]
    tip = dock.model.data(dock.model.index(data, 5), 3)
    assert "2641/" in tip

    dock.set_filter(function="Device Beacon")
    assert dock.shown_rows() and all(r.function == "Device Beacon" for r in dock.shown_rows())
    node = dock.shown_rows()[0].node
    dock.set_filter(function="Device Beacon", node=node)
    assert {r.node for r in dock.shown_rows()} == {node}

    dock.set_paused(True)
    frozen = len(dock.shown_rows())
    total = len(dock.all_rows)
    qtbot.waitUntil(lambda: len(dock.all_rows) > total + 20, timeout=5000)
    assert len(dock.shown_rows()) == frozen  # paused: the table holds still, frames recorded
    dock.set_paused(False)  # the held frames appear, filtered
    assert dock.shown_rows() == [r for r in dock.all_rows
                                 if r.function == "Device Beacon" and r.node == node]
    assert len(dock.shown_rows()) > frozen

    dock.set_filter()
    out = tmp_path / "capture.asc"
    kept = list(dock.all_rows)  # save() takes this snapshot; frames keep coming meanwhile
    with qtbot.waitSignal(dock.saved, timeout=10_000) as saved:
        dock.save(out)
    assert saved.args == [str(out)]
    back = list(read_capture(out))
    assert [(m.arbitration_id, bytes(m.data)) for m in back] == \
        [(r.arbitration_id, r.data) for r in kept]


def _frame(i: int, node: int = 5, data: bytes = b"\x0a") -> FrameSeen:
    return FrameSeen(1000.0 + i * 0.001, node, data, f"{i:11.6f}  P0  #{node}→BA Device Beacon")


def test_monitor_row_count_is_bounded(qtbot):
    dock = MonitorDock(capacity=1000)
    qtbot.addWidget(dock)
    for start in range(0, 5000, 700):
        dock.add_frames([_frame(i) for i in range(start, min(start + 700, 5000))])
    assert len(dock.all_rows) == 1000 and dock.model.rowCount() == 1000
    assert dock.all_rows[0].timestamp == pytest.approx(1004.0)  # the oldest were dropped
    dock.add_frames([_frame(i) for i in range(3000)])  # one batch bigger than the capacity
    assert dock.model.rowCount() == 1000
    dock.clear()
    assert dock.model.rowCount() == 0 and not dock.all_rows


def test_monitor_text_filter_and_row_classification(qtbot):
    dock = MonitorDock()
    qtbot.addWidget(dock)
    dock.channel_nodes = {12}
    data = FrameSeen(1.0, 12, b"\x01\x02", "   0.000000  P0  #12 data Channel data  x → y  01 02")
    to_ba = _frame(1, node=7, data=b"\x83\x01\x01\x00\x02\x00")
    from_ba = FrameSeen(1.0, 0x100 | 7, b"\x03\x01\x00", "   0.1  P0  BA→#7 Get Device Parameter")
    assert make_row(data, {12}).function == CHANNEL_DATA
    assert make_row(data, set()).function == CHANNEL_DATA  # from the decoded text
    assert make_row(from_ba).who == "BA→#7"
    assert make_row(to_ba).who == "#7→BA"
    dock.add_frames([data, to_ba, from_ba])
    dock.flush()  # frames are taken on the dock's next tick; now, for the test
    with qtbot.waitSignal(dock.countChanged, timeout=2000) as counted:
        dock.text_filter.setText("ba→#7")  # debounced; case-insensitive
    assert counted.args == [1, 3]
    assert dock.shown_rows()[0].arbitration_id == 0x107


def test_monitor_save_failure_is_reported(qtbot, tmp_path):
    dock = MonitorDock()
    qtbot.addWidget(dock)
    dock.add_frames([_frame(i) for i in range(3)])
    with qtbot.waitSignal(dock.error, timeout=5000) as blocker:
        dock.save(tmp_path / "no-such-dir" / "x.asc")
    assert "no-such-dir" in blocker.args[0]
    txt = tmp_path / "frames.txt"
    with qtbot.waitSignal(dock.saved, timeout=5000):
        dock.save(txt)
    lines = txt.read_text("utf-8").splitlines()
    assert len(lines) == 3 and "Device Beacon" in lines[0]


def test_decoded_column_shows_the_fields_or_why_a_frame_does_not_decode():
    from pdcp_studio.app.trace.dock import _decoded

    line = "   0.100000  P0  BA→#7 Get Device Parameter  param 1 VID and PID  chan 0"
    assert _decoded(line) == "param 1 VID and PID  chan 0"
    assert _decoded("   0.1  P0  #3→BA Device Beacon") == ""
    bad = "   1.0  P?  0x10A undecodable: DLC 3 is too short  [10A] 01 02 03"
    assert _decoded(bad) == "P?  0x10A undecodable: DLC 3 is too short  [10A] 01 02 03"
    assert _decoded("free text") == "free text"


def test_monitor_opens_a_saved_capture(qtbot, live, tmp_path):
    dock = MonitorDock()
    qtbot.addWidget(dock)
    live.frameSeen.connect(dock.add_frames)
    qtbot.waitUntil(lambda: len(dock.all_rows) >= 30, timeout=5000)
    kept = list(dock.all_rows)
    out = tmp_path / "bus.blf"
    with qtbot.waitSignal(dock.saved, timeout=10_000):
        dock.save(out)
    dock.set_paused(True)  # hold live frames back while the capture is looked at
    with qtbot.waitSignal(dock.loaded, timeout=10_000):
        dock.load_capture(out)
    shown = list(dock.all_rows)
    assert [(r.arbitration_id, r.data) for r in shown] == \
        [(r.arbitration_id, r.data) for r in kept]
    assert {r.function for r in shown} == {r.function for r in kept}
    with qtbot.waitSignal(dock.error, timeout=5000) as blocker:
        dock.load_capture(tmp_path / "missing.asc")
    assert "missing.asc" in blocker.args[0]
