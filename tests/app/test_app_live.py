"""The window on a live bus: connect off the GUI thread, hot-swap, edits sent to the bus.

Two kinds: a scripted fake session (always runs; checks the window's side exactly) and the
real simulated prosthesis ``sim:transradial`` through ``open_session`` (skipped only if
this build's bus layer cannot open it).
"""

from __future__ import annotations

import threading
from pathlib import Path

import pytest

from pdcp_studio.app.live import live_bus as live_mod
from pdcp_studio.bus import events as ev
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.storage import system_file

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"
CONTROL = DeviceKey(2641, 513, 201)
HAND = DeviceKey(2641, 769, 301)
FLEXOR = DeviceKey(2641, 257, 101)


class FakeSession:
    """The session face the app uses, over an in-memory system; events on another thread."""

    def __init__(self) -> None:
        from pdcp_studio.engine import plan_autoconfigure

        self._system = system_file.load_path(TRANSRADIAL)
        plan_autoconfigure(self._system).apply(self._system)
        self._subs: list = []
        self.applied: list = []
        self.written: list = []
        self.closed = False
        self.url = "sim:fake"

    def subscribe(self, callback):
        self._subs.append(callback)
        return lambda: self._subs.remove(callback)

    def _emit(self, *events) -> None:
        def run() -> None:
            for e in events:
                for cb in list(self._subs):
                    cb(e)
        t = threading.Thread(target=run)
        t.start()
        t.join()

    def system(self):
        return self._system.copy()

    def read_configuration(self):
        from pdcp_studio.model.configuration import ConfigCollection

        return ConfigCollection([])

    def scan(self, progress=None, cancel=None):
        return self._system.copy()

    def apply_plan(self, plan, progress=None, cancel=None):
        plan.apply(self._system)
        self.applied.append(plan)
        self._emit(*(ev.LinkMade(a.link) if a.op.value == "add" else ev.LinkRemoved(a.link)
                     for a in plan.actions), ev.PlanApplied(plan))
        return plan

    def close(self) -> None:
        self.closed = True

    # simulator controls
    def sim_devices(self):
        return [(k, d.label, d.present) for k, d in self._system.devices.items()]

    def plug(self, key) -> None:
        self._system.devices[key].present = True
        self._emit(ev.DeviceJoined(key))

    def unplug(self, key) -> None:
        self._system.devices[key].present = False
        self._emit(ev.DeviceLeft(key))

    def script_names(self):
        return []

    def set_parameter(self, key, param, channel, value, *, timeout=None):
        self.written.append((key, param, channel, bytes(value)))

    def send_data(self, ref: ChannelRef) -> None:
        self._emit(ev.ChannelValue(ref, 1.0, 0.0))


@pytest.fixture
def window(make_window):
    return make_window()


@pytest.fixture
def fake(monkeypatch):
    session = FakeSession()
    monkeypatch.setattr(live_mod, "open_session_blocking", lambda url, p=None, c=None: session)
    return session


def test_connect_hot_swap_and_live_edits_with_fake_session(window, fake, qtbot):
    with qtbot.waitSignal(window.ready, timeout=5000):
        window.connect_bus("sim:fake")
    doc = window.doc
    assert window.live.is_live and doc.session is window.live.bridge
    assert window.mode_label.text() == "● Live on sim:fake"
    assert "live on sim:fake" in window.windowTitle().lower()
    assert len(doc.system.links) == 5
    assert window.plan_panel.apply_button.text() == "Stage for the prosthesis"
    # Unplug the hand: its card shows it missing, its links are drawn as missing.
    fake.unplug(HAND)
    qtbot.waitUntil(lambda: not window.scene.cards[HAND].device.present, timeout=3000)
    assert window.tree.row_for(HAND).text(1) == "missing"
    qtbot.waitUntil(lambda: bool(window.scene.states.missing_links), timeout=3000)
    assert all(HAND in (lk.output.device, lk.input.device)
               for lk in window.scene.states.missing_links)
    fake.plug(HAND)
    qtbot.waitUntil(lambda: window.scene.cards[HAND].device.present, timeout=3000)
    # A link deleted by hand on a live bus is staged: one undo step, nothing sent.
    link = Link(ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1))
    doc.select(link)
    window.act_delete.trigger()
    assert not doc.system.has_link(link) and doc.undo_stack.count() == 1
    assert fake.applied == [] and doc.bus_system.has_link(link)
    # A plan on a live bus is staged too (one more undo step).
    plan = window.preview_plan("autoconfigure")
    assert [a.link for a in plan.added] == [link]
    window.plan_panel.apply()
    assert doc.system.has_link(link) and doc.undo_stack.count() == 2 and fake.applied == []
    # A parameter edit is staged; Undo unstages it; nothing reaches the bus.
    ref = ChannelRef(*HAND, 2)
    doc.select(ref)
    window.inspector.editors["descriptor"].setText("Pinch")
    window.inspector.editors["descriptor"].editingFinished.emit()
    assert doc.channel(ref).descriptor == "Pinch" and doc.undo_stack.count() == 3
    window.act_undo.trigger()
    assert doc.channel(ref).descriptor == "Pinch grip"
    assert fake.written == []
    doc.select(ChannelRef(*CONTROL, 3))
    spin = window.inspector.editors["node_id"]
    spin.setValue(9)
    spin.editingFinished.emit()
    assert "assigned by the arbitrator" in window.inspector.errors["node_id"].text()
    assert fake.written == []
    # Data on a link lights it up.
    fake.send_data(ChannelRef(*FLEXOR, 1))
    qtbot.waitUntil(lambda: ChannelRef(*FLEXOR, 1) in window.scene.flow.outputs(), timeout=3000)
    window.live.disconnect_bus()
    assert fake.closed or window.live.bridge is None
    assert window.mode_label.text() == "Disconnected from sim:fake"


def test_failed_default_connection_falls_back_offline(window, monkeypatch, qtbot):
    def boom(url, p=None, c=None):
        raise OSError("no virtual bus here")

    monkeypatch.setattr(live_mod, "open_session_blocking", boom)
    with qtbot.waitSignal(window.ready, timeout=5000):
        window.connect_bus("sim:transradial")
    assert not window.live.is_live
    assert len(window.doc.system.devices) == 4
    assert len(window.doc.system.links) == 5  # linked by autoconfigure, offline
    assert "Offline" in window.statusBar().currentMessage()
    assert "no virtual bus here" in window.statusBar().currentMessage()


def test_real_simulated_prosthesis_hot_swap(window, qtbot):
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    assert window.live.is_live, window.statusBar().currentMessage()
    doc = window.doc
    assert len(doc.system.devices) == 4 and len(doc.system.links) == 5  # bound and linked
    bridge = window.live.bridge
    assert bridge.is_sim
    hand = next(k for k, d in doc.system.devices.items() if d.pid == 769)
    bridge.unplug(hand)
    qtbot.waitUntil(lambda: not window.scene.cards[hand].device.present, timeout=10000)
    assert "missing" in window.tree.row_for(hand).text(1)
    bridge.plug(hand)
    qtbot.waitUntil(lambda: window.scene.cards[hand].device.present, timeout=10000)
    # A parameter edit is staged: the device keeps its value until it is written.
    doc.select(ChannelRef(*hand, 2))
    window.inspector.editors["descriptor"].setText("Pinch motor")
    window.inspector.editors["descriptor"].editingFinished.emit()
    qtbot.waitUntil(lambda: not bridge.busy, timeout=10000)
    back = bridge.session.get_parameter(hand, 2, 2)
    assert back.split(b"\0")[0] == b"Pinch grip"
    assert doc.channel(ChannelRef(*hand, 2)).descriptor == "Pinch motor"
    # The arbitrator's stored configuration becomes the one plans use.
    window.read_configuration()
    qtbot.waitUntil(lambda: "stored configuration" in window.statusBar().currentMessage(),
                    timeout=10000)
    assert window.doc.config is not None
    plan = window.preview_plan("startup")
    assert plan is not None, window.statusBar().currentMessage()
    window.live.disconnect_bus()
