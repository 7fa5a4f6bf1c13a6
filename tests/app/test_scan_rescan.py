"""A rescan that finds the same bus changes nothing on screen and costs the GUI thread
~nothing (issue 11: the GUI thread never blocked > 50 ms while scans run): no view is
rebuilt, no panel refreshed, no check rerun — only the status bar says the scan ended."""

from __future__ import annotations

import pytest

from pdcp_studio.app.documents.document import Document
from pdcp_studio.model.refs import Direction
from pdcp_studio.model.system import Channel, Device, Link, System

pytestmark = pytest.mark.gui

SIGNALS = ("systemReset", "linksChanged", "deviceChanged", "channelChanged", "busChanged")


def _system() -> System:
    sensor = Device(10, 1, 1, name="EMG sensor")
    sensor.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4222))
    hand = Device(10, 3, 1, name="Hand")
    hand.add_channel(Channel(1, Direction.INPUT, type=0x9300, profile=0x4222))
    return System([sensor, hand], [Link(sensor.ref(1), hand.ref(1))])


def _record(doc: Document) -> list[str]:
    said: list[str] = []
    for name in SIGNALS:
        getattr(doc, name).connect(lambda *_a, n=name: said.append(n))
    return said


def test_a_snapshot_equal_to_the_last_one_sends_no_signal(qtbot):
    doc = Document(tree=None)
    doc.set_system(_system(), None, session=object())
    said = _record(doc)
    bus_before = doc.bus_system
    assert doc.sync_live(_system()) is False  # equal, not the same objects
    assert said == []
    assert doc.bus_system is bus_before


def test_a_snapshot_that_differs_is_merged_and_said(qtbot):
    doc = Document(tree=None)
    doc.set_system(_system(), None, session=object())
    said = _record(doc)
    snapshot = _system()
    snapshot.devices[Device(10, 3, 1).key].fw_version = 7
    assert doc.sync_live(snapshot) is True
    assert said == ["deviceChanged", "busChanged"]
    assert doc.bus_system.devices[Device(10, 3, 1).key].fw_version == 7
    # The same snapshot again: now nothing is new.
    said.clear()
    assert doc.sync_live(snapshot) is False and said == []


def test_a_device_marked_missing_comes_back_even_if_the_bus_looks_the_same(qtbot):
    """The bus's view did not change, but the project's did (a DeviceLeft marked it
    missing): the merge must still put it back and say so."""
    doc = Document(tree=None)
    doc.set_system(_system(), None, session=object())
    key = Device(10, 3, 1).key
    doc.set_present(key, False)
    said = _record(doc)
    assert doc.sync_live(_system()) is True
    assert doc.system.devices[key].present and "deviceChanged" in said


def test_rescanning_the_same_prosthesis_rebuilds_nothing(make_window, qtbot):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    bridge = window.live.bridge
    window.live.wait_idle()
    with qtbot.waitSignal(bridge.scanned, timeout=30000):
        window.scan_bus()  # the first scan may read more than the first snapshot had
    qtbot.wait(100)  # its follow-ups (and the policy, configuration reads) settle
    said = _record(window.doc)
    work: list[str] = []
    window.live.snapshotTaken.connect(lambda _s: work.append("snapshotTaken"))
    # The tree, graph, inspector, pending and plan panels redo their work only on the
    # document's signals (recorded above); the bus docks only on snapshotTaken.
    cards = dict(window.scene.cards)
    messages: list[str] = []
    window.statusBar().messageChanged.connect(messages.append)
    for _ in range(3):
        with qtbot.waitSignal(bridge.scanned, timeout=30000):
            window.scan_bus()
    qtbot.wait(50)  # anything queued by the results runs now
    assert said == [] and work == []
    assert window.scene.cards == cards and all(window.scene.cards[k] is c
                                               for k, c in cards.items())
    assert any(m.startswith("Scan finished: 4 devices") for m in messages)
    window.live.disconnect_bus()


def test_a_scans_progress_reaches_the_window_once_not_twice(make_window, qtbot):
    """The session reports a scan's progress as events (coalesced per drain); the worker's
    own reports stay with the worker (the setup wizard follows them) and are not sent on
    to the window as well."""
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    bridge = window.live.bridge
    window.live.wait_idle()
    seen: list[tuple[int, int, str]] = []
    bridge.progress.connect(lambda *a: seen.append(a))
    worker = bridge.scan()
    mine: list[tuple[int, int, str]] = []
    worker.progress.connect(lambda *a: mine.append(a))
    with qtbot.waitSignal(bridge.scanned, timeout=30000):
        pass
    qtbot.wait(120)  # the last Progress event is drained
    assert mine and seen  # both still report
    assert seen[-1][0] == seen[-1][1]  # the window hears the scan end
    before = len(seen)
    worker.progress.emit(1, 2, "a worker's report")
    assert len(seen) == before
    window.live.disconnect_bus()
