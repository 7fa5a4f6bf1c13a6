"""SessionBridge and the simulator panel on the real simulated prosthesis (``sim:…``).

Hot-swap seen through the bridge, batched event delivery on the GUI thread, progress and
cancel of a scan, failure messages, and the simulator panel's controls.
"""

from __future__ import annotations

import threading

import pytest
from PySide6.QtCore import Qt, QThread
from PySide6.QtWidgets import QApplication

from pdcp_studio.app.docks.sim_panel import SimPanel
from pdcp_studio.app.live.session_bridge import SessionBridge
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.model.refs import DeviceKey

pytestmark = pytest.mark.gui

EMG_FLEXOR = DeviceKey(2641, 257, 101)
CONTROL_UNIT = DeviceKey(2641, 513, 201)
HAND = DeviceKey(2641, 769, 301)


def _on_gui_thread() -> bool:
    return QThread.currentThread() is QApplication.instance().thread()


@pytest.fixture
def make_bridge(qtbot):
    bridges: list[SessionBridge] = []

    def make(url: str = "sim:transradial") -> SessionBridge:
        bridge = SessionBridge(open_session(url), interval_ms=20, url=url)
        bridges.append(bridge)
        return bridge

    yield make
    for bridge in bridges:
        session = bridge.session
        bridge.close(wait_ms=5000)
        assert session.closed


def test_hot_swap_is_seen_as_device_left_then_joined(qtbot, make_bridge):
    bridge = make_bridge()
    assert bridge.is_sim and bridge.system().device(HAND).present
    with qtbot.waitSignal(bridge.deviceLeft, timeout=5000,
                          check_params_cb=lambda key: key == HAND) as left:
        bridge.unplug(HAND)
    assert left.args == [HAND]
    assert not bridge.system().device(HAND).present
    with qtbot.waitSignal(bridge.deviceJoined, timeout=5000,
                          check_params_cb=lambda key: key == HAND):
        bridge.plug(HAND)
    assert bridge.system().device(HAND).present


def test_channel_values_arrive_in_batches_on_the_gui_thread(qtbot, make_bridge):
    bridge = make_bridge()
    batches: list[tuple[int, bool]] = []
    singles: list[object] = []
    bridge.channelValues.connect(lambda vs: batches.append((len(vs), _on_gui_thread())))
    bridge.channelValue.connect(singles.append)
    qtbot.waitUntil(lambda: sum(n for n, _ in batches) >= 40, timeout=5000)
    total = sum(n for n, _ in batches)
    assert all(on_gui for _, on_gui in batches)
    assert len(batches) < total  # batched: fewer signals than values
    assert max(n for n, _ in batches) > 1
    assert len(singles) >= total  # the per-value signal too, for those who want it
    outputs = {v.ref for v in singles}
    assert outputs <= {ref for ref, ch in bridge.system().channels() if ch.is_output}


def test_drain_coalesces_progress_and_keeps_event_order(qtbot, make_bridge):
    from pdcp_studio.bus import events as ev

    bridge = make_bridge()
    bridge._timer.stop()  # drain by hand
    bridge._queue.clear()
    seen: list[object] = []
    bridge.progress.connect(lambda d, t, w: seen.append(("progress", d, t)))
    bridge.deviceLeft.connect(lambda k: seen.append(("left", k)))
    bridge.deviceJoined.connect(lambda k: seen.append(("joined", k)))
    bridge.error.connect(lambda m: seen.append(("error", m)))
    for i in range(500):
        bridge._enqueue(ev.Progress(i, 499, "scan"))
    bridge._enqueue(ev.DeviceLeft(HAND))
    bridge._enqueue(ev.BusError("a bad frame"))
    bridge._enqueue(ev.DeviceJoined(HAND))
    assert bridge.drain() == 503
    assert seen == [("left", HAND), ("error", "a bad frame"), ("joined", HAND),
                    ("progress", 499, 499)]


def test_scan_reports_progress_and_its_result(qtbot, make_bridge):
    bridge = make_bridge()
    progress: list[tuple[int, int]] = []
    busy: list[bool] = []
    bridge.progress.connect(lambda d, t, _w: progress.append((d, t)))
    bridge.busyChanged.connect(busy.append)
    with qtbot.waitSignal(bridge.scanned, timeout=10_000) as result:
        worker = bridge.scan()
    system = result.args[0]
    assert set(system.devices) == set(bridge.system().devices)
    assert len(system.links) == 5
    assert progress and progress[-1][0] == progress[-1][1] > 0
    qtbot.waitUntil(lambda: busy == [True, False], timeout=5000)
    assert worker.result is system


def test_cancelling_a_scan_stops_it(qtbot, make_bridge):
    bridge = make_bridge("sim:large")  # 32 devices: a scan long enough to cancel midway
    scanned: list[object] = []
    bridge.scanned.connect(scanned.append)
    session_progress: list[tuple[int, int]] = []  # the session's own Progress events
    bridge.progress.connect(lambda d, t, _w: session_progress.append((d, t)))
    worker = bridge.scan()
    reports: list[tuple[int, int]] = []

    def cancel_on_first(done: int, total: int, _text: str) -> None:
        reports.append((done, total))
        worker.cancel()

    worker.progress.connect(cancel_on_first)
    with qtbot.waitSignal(worker.cancelled, timeout=10_000):
        pass
    assert reports and scanned == []
    done, total = reports[-1]
    assert 0 <= done < total
    qtbot.wait(300)  # longer than a whole scan takes: had it gone on, it would have finished
    assert session_progress and all(d < t for d, t in session_progress if t)


def test_failures_become_error_messages(qtbot, make_bridge):
    bridge = make_bridge()
    with qtbot.waitSignal(bridge.error, timeout=5000) as blocker:
        bridge.plug(DeviceKey(9, 9, 9))
    assert blocker.args[0].startswith(
        "Plugging in unknown device (9/9/9): no simulated device 9/9/9")
    failed: list[str] = []
    worker = bridge.run(lambda p, c: 1 / 0, "Divide")
    worker.failed.connect(failed.append)
    with qtbot.waitSignal(bridge.error, timeout=5000) as blocker:
        pass
    assert blocker.args[0] == "Divide: ZeroDivisionError: division by zero"


def test_calls_after_close_are_refused_with_a_message(qtbot, make_bridge):
    bridge = make_bridge()
    session = bridge.session
    with qtbot.waitSignal(bridge.closed, timeout=5000):
        bridge.close(wait_ms=0)
    qtbot.waitUntil(lambda: session.closed, timeout=5000)
    with qtbot.waitSignal(bridge.error, timeout=1000) as blocker:
        assert bridge.scan() is None
    assert "closed" in blocker.args[0]


def test_a_simulator_script_runs_with_progress(qtbot, make_bridge):
    bridge = make_bridge()
    assert "unplug-replug" in bridge.script_names()
    left: list[DeviceKey] = []
    joined: list[DeviceKey] = []
    bridge.deviceLeft.connect(left.append)
    bridge.deviceJoined.connect(joined.append)
    with qtbot.waitSignal(bridge.scriptFinished, timeout=15_000) as blocker:
        bridge.run_script("unplug-replug")
    result = blocker.args[0]
    assert result.ok, result.mismatch()
    qtbot.waitUntil(lambda: HAND in left and HAND in joined, timeout=5000)


# -- the simulator panel -----------------------------------------------------------------------
def test_sim_panel_lists_devices_and_follows_a_hot_swap(qtbot, make_bridge):
    bridge = make_bridge()
    panel = SimPanel(bridge)
    qtbot.addWidget(panel)
    # the four parts and the spare hand, simulated but not plugged in
    qtbot.waitUntil(lambda: panel.tree.topLevelItemCount() == 5, timeout=5000)
    assert panel.state(HAND) == (True, True)
    assert panel.state(DeviceKey(2641, 769, 302))[0] is False
    assert panel.script_combo.count() == len(bridge.script_names())
    assert panel.script_info.text()  # the selected script is described

    panel.select(HAND)
    assert panel.unplug_button.isEnabled() and not panel.plug_button.isEnabled()
    with qtbot.waitSignal(bridge.deviceLeft, timeout=5000):
        panel.unplug_button.click()
    qtbot.waitUntil(lambda: panel.state(HAND) == (False, False), timeout=5000)
    qtbot.waitUntil(lambda: panel.plug_button.isEnabled(), timeout=5000)
    assert any("left the bus" in line for line in panel.log_lines())
    row = next(panel.tree.topLevelItem(i) for i in range(5)
               if panel.tree.topLevelItem(i).data(0, Qt.ItemDataRole.UserRole) == HAND)
    assert (row.text(2), row.text(3)) == ("off", "left")

    with qtbot.waitSignal(bridge.deviceJoined, timeout=5000):
        panel.plug_button.click()
    qtbot.waitUntil(lambda: panel.state(HAND) == (True, True), timeout=5000)
    assert any("Multi-grip hand with wrist rotator (serial 301) joined the bus" in line
               for line in panel.log_lines())


def test_sim_panel_replaces_a_device_by_an_unplugged_one(qtbot, make_bridge):
    bridge = make_bridge("sim:thesis-test1")  # D3 (2/2/6) starts unplugged
    d2, d3 = DeviceKey(2, 2, 5), DeviceKey(2, 2, 6)
    panel = SimPanel(bridge)
    qtbot.addWidget(panel)
    qtbot.waitUntil(lambda: panel.tree.topLevelItemCount() == 3, timeout=5000)
    assert panel.state(d3)[0] is False
    panel.select(d2)
    assert panel.replace_combo.count() == 1 and panel.replace_combo.currentData() == d3
    with qtbot.waitSignal(bridge.deviceJoined, timeout=5000,
                          check_params_cb=lambda key: key == d3):
        panel.replace_button.click()
    qtbot.waitUntil(lambda: panel.state(d2)[0] is False and panel.state(d3)[0] is True,
                    timeout=5000)
    qtbot.waitUntil(lambda: panel.state(d2)[1] is False, timeout=5000)  # D2 left the bus


def test_sim_panel_resets_the_arbitrator_with_and_without_memory(qtbot, make_bridge):
    bridge = make_bridge("sim:thesis-test2")
    panel = SimPanel(bridge)
    qtbot.addWidget(panel)
    qtbot.waitUntil(lambda: panel.reset_keep_button.isEnabled(), timeout=5000)
    links = bridge.system().links
    assert len(links) == 3
    with qtbot.waitSignal(bridge.configurationWritten, timeout=5000) as stored:
        panel.save_links()
    assert len(stored.args[0].configurations[0].links) == 3
    with qtbot.waitSignal(bridge.simChanged, timeout=10_000) as changed:
        panel.reset(keep_memory=True)
    assert changed.args[0] == "The arbitrator restarted; its stored configuration was kept"
    assert bridge.session.wait_settled(10)
    assert bridge.system().links == links
    done = threading.Event()
    bridge.simChanged.connect(lambda _w: done.set())
    panel.reset(keep_memory=False)
    qtbot.waitUntil(done.is_set, timeout=10_000)
    assert bridge.session.wait_settled(10)
    assert bridge.system().links == links  # rebuilt from the devices' own source fields
    assert bridge.session.read_configuration().configurations == []
    assert any("erasing its memory" in line for line in panel.log_lines())


def test_a_deleted_sim_panel_does_not_break_the_bridge(qtbot, make_bridge):
    bridge = make_bridge()
    panel = SimPanel(bridge)
    qtbot.waitUntil(lambda: panel.tree.topLevelItemCount() == 5, timeout=5000)
    panel.deleteLater()
    qtbot.wait(10)  # the panel is gone; the bridge's signals must not reach it
    with qtbot.waitSignal(bridge.deviceLeft, timeout=5000):
        bridge.unplug(HAND)
    with qtbot.waitSignal(bridge.error, timeout=5000):
        bridge.plug(DeviceKey(9, 9, 9))
