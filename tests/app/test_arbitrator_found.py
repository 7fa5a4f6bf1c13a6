"""Connecting the app to a bus another arbitrator runs (issue 10 item 1, reference §5).

Two arbitrators on python-can's virtual bus: a simulated prosthesis (its own arbitrator) on
a virtual channel, and the app connecting to ``can:virtual:<channel>``. The app must say so
plainly, send nothing, and offer a listen-only monitor (which then shows the bus's frames,
still sending nothing) or the host link (the Connect dialog on its serial tab).
"""

from __future__ import annotations

import time

import pytest

from pdcp_studio.bus.session.sim import open_sim_session
from pdcp_studio.bus.session.urls import open_can_bus, unique_virtual_channel
from tests.bus.stray_frames import BeaconingArbitrator


class Tap:
    """Every frame on a virtual channel, as a bystander hears it."""

    def __init__(self, channel: str) -> None:
        import can

        self.bus = open_can_bus("virtual", channel)
        self.frames: list = []
        self.notifier = can.Notifier(self.bus, [self.frames.append])

    def close(self) -> None:
        self.notifier.stop()
        self.bus.shutdown()


@pytest.fixture
def taken_bus():
    """A settled thesis-test2 prosthesis with its own arbitrator on a virtual channel."""
    channel = unique_virtual_channel("pdcp-app-claim")
    first = open_sim_session("thesis-test2", channel=channel)
    tap = Tap(channel)
    yield channel, first, tap
    tap.close()
    first.close()


def _connect_and_get_offer(window, qtbot, url):
    window.connect_bus(url)
    qtbot.waitUntil(lambda: getattr(window, "arbitrator_found_dialog", None) is not None,
                    timeout=15000)
    return window.arbitrator_found_dialog


def test_a_taken_bus_is_said_plainly_and_a_listen_only_monitor_sends_nothing(
        make_window, qtbot, taken_bus):
    channel, first, tap = taken_bus
    window = make_window()
    url = f"can:virtual:{channel}"
    def mode1() -> int:
        return sum(1 for m in list(tap.frames) if m.arbitration_id >> 8 & 1)

    sent_before, heard_before = first.arbitrator.conn.sent, mode1()
    dialog = _connect_and_get_offer(window, qtbot, url)
    assert dialog.isVisible()
    text = dialog.text.text()
    assert "already has an arbitrator" in text and "nothing was sent" in text
    assert "OtherArbitratorError" not in text and "0x" not in text  # no codes up front
    label = dialog.text  # the wrapped text is shown whole, not clipped by the window
    assert label.height() >= label.heightForWidth(label.width())
    assert not dialog.detail.isVisible()
    dialog.details_button.click()
    assert dialog.detail.isVisible() and "another bus arbitrator" in dialog.detail.text()
    assert window.live.bridge is None  # no session on a taken bus
    assert "another bus arbitrator" in window.statusBar().currentMessage()

    dialog.watch_button.click()
    monitor = window.passive_monitor
    assert monitor is not None and monitor.wait_open(5)
    dock = window._leaf_docks["monitor"]
    assert dock.isVisible()
    qtbot.waitUntil(lambda: len(dock.all_rows) > 5, timeout=10000)  # its beacons and data
    assert window.listening_indicator.isVisible()
    # No frame on the bus came from the app: the arbitrator frames heard are the first
    # arbitrator's own (±1 for a beacon in flight while counting; an intruding arbitrator
    # would have sent a beacon every 0.5 s and resets, tens of frames by now).
    time.sleep(0.5)
    theirs = first.arbitrator.conn.sent - sent_before
    assert theirs > 0 and abs((mode1() - heard_before) - theirs) <= 1
    window.listening_indicator.stop_button.click()
    assert window.passive_monitor is None
    assert not monitor.is_running


def test_the_host_link_offer_opens_the_serial_tab(make_window, qtbot, taken_bus):
    channel, _first, _tap = taken_bus
    window = make_window()
    dialog = _connect_and_get_offer(window, qtbot, f"can:virtual:{channel}")
    dialog.host_button.click()
    connect = window.host_link_dialog
    assert connect.isVisible()
    assert connect.tabs.currentWidget() is connect.pages["serial"]
    connect.reject()
    assert getattr(window, "passive_monitor", None) is None


def test_other_connect_failures_are_not_taken_for_an_arbitrator(make_window, qtbot):
    window = make_window()
    window.connect_bus("sim:no-such-prosthesis")
    qtbot.waitUntil(lambda: "Cannot connect" in window.statusBar().currentMessage(),
                    timeout=10000)
    assert getattr(window, "arbitrator_found_dialog", None) is None


def test_an_arbitrator_appearing_later_is_said_and_the_same_offer_made(make_window, qtbot):
    """The app arbitrates a bus; then another arbitrator starts on it: the session stops
    writing at once (bus layer) and the window says so with the same offer."""
    import can

    from pdcp_studio.bus.sim.device import SimulatedDevice
    from pdcp_studio.bus.sim.device_host import DeviceHost
    from pdcp_studio.bus.sim.rigs import load_prosthesis

    channel = unique_virtual_channel("pdcp-app-later")
    system = load_prosthesis("thesis-test2")
    host = DeviceHost(open_can_bus("virtual", channel),
                      [SimulatedDevice(d) for d in system.devices.values()], name="devices")
    other = can.Bus(interface="virtual", channel=channel)
    beacons = BeaconingArbitrator(channel)
    try:
        window = make_window()
        with qtbot.waitSignal(window.ready, timeout=30000):
            window.connect_bus(f"can:virtual:{channel}")
        assert window.live.is_live
        # One stray arbitrator-mode frame (the issue's, then a lone beacon) is no arbitrator:
        # the app stays connected (issue 28 item 1).
        other.send(can.Message(arbitration_id=0x3AC, data=b"\x0e\x00", is_extended_id=False))
        other.send(can.Message(arbitration_id=0x100, data=b"\x0a", is_extended_id=False))
        qtbot.wait(2500)  # longer than three beacon intervals: the two are never heard together
        assert window.live.is_live
        assert getattr(window, "arbitrator_found_dialog", None) is None
        beacons.start()  # a real arbitrator: its beacons every 500 ms
        qtbot.waitUntil(lambda: getattr(window, "arbitrator_found_dialog", None) is not None,
                        timeout=15000)
        dialog = window.arbitrator_found_dialog
        assert dialog.isVisible() and "Another arbitrator started" in dialog.text.text()
        assert "stopped sending at once" in dialog.text.text()
        assert "stopped writing" in dialog.detail.text()
        assert not window.live.is_live  # nothing left that could write
        dialog.reject()
    finally:
        beacons.close()
        other.shutdown()
        host.close()
