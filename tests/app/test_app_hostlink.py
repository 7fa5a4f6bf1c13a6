"""The app's flows of issue 8 over the host link: a real arbitrator behind a pseudo-terminal.

The same flows as ``test_app_transactions.py`` runs on ``sim:``, but the window reaches the
prosthesis as a fitting room would: the Connect dialog's ``serial:`` URL, pyserial on a real
pseudo-terminal, host link 2 to an arbitrator that keeps running between transactions. Every
check of what was written is made on that arbitrator (its links, its devices' parameters, the
frames on its bus), not on the app's own view of it. The fitting history is a temporary file
(``PDCP_STUDIO_HISTORY``, set for every app test in conftest).
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from pdcp_studio.app.documents import commands, pending
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.protocol import Release, SetParameter, Suspend
from pdcp_studio.storage.history import History
from tests.road_rigs import FrameRecorder, served

pytestmark = [pytest.mark.gui,
              pytest.mark.skipif(not hasattr(os, "openpty"),
                                 reason="needs POSIX pseudo-terminals")]

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"
CONTROL = DeviceKey(2641, 513, 201)
HAND = DeviceKey(2641, 769, 301)
HAND_LINK = Link(ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1))
WAIT_MS = 30000  # a loaded machine: the host link is slow, never wrong


class Rig:
    """The prosthesis behind the pty: its arbitrator, URL and a recorder on its bus."""

    def __init__(self, arbitrator, host, url: str, recorder: FrameRecorder) -> None:
        self.arbitrator, self.host, self.url, self.recorder = arbitrator, host, url, recorder

    def links(self) -> set[Link]:
        return set(self.arbitrator.system().links)

    def descriptor(self, key: DeviceKey, channel: int) -> bytes:
        """Read from the device itself, by the arbitrator (not the app's view of it)."""
        return self.arbitrator.get_parameter(key, P.CH_DESCRIPTOR, channel).split(b"\0")[0]


@pytest.fixture
def rig(tmp_path, monkeypatch):
    import pdcp_studio.bus.session.urls as urls

    channel = f"app-hostlink-{os.getpid()}-{id(tmp_path)}"
    monkeypatch.setattr(urls, "unique_virtual_channel", lambda prefix="": channel)
    recorder = FrameRecorder(channel)
    try:
        with served("transradial", tmp_path / "memory.bin") as (arbitrator, host, url):
            yield Rig(arbitrator, host, url, recorder)
    finally:
        recorder.close()


def _connect(window, monkeypatch, url: str) -> None:
    """Bus ▸ Connect: the dialog's Serial host link page, the port typed in, OK."""
    from PySide6.QtWidgets import QDialog

    from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog

    port = url.removeprefix("serial:")
    chosen = []

    def fill_in_and_accept(dialog):
        page = dialog.pages["serial"]
        dialog.tabs.setCurrentWidget(page)
        page.port.setCurrentText(port)
        chosen.append(dialog.url())
        return QDialog.DialogCode.Accepted

    monkeypatch.setattr(ConnectDialog, "exec", fill_in_and_accept)
    window.ask_connect()
    assert chosen == [url]  # 128000 baud, the default, is not written in the URL


@pytest.fixture
def live(make_window, qtbot, monkeypatch, rig):
    """A window live on the host link, confirming every previewed change."""
    window = make_window()
    with qtbot.waitSignal(window.live.connected, timeout=WAIT_MS):
        _connect(window, monkeypatch, rig.url)
    assert window.live.is_live and window.live.url == rig.url
    qtbot.waitUntil(lambda: window.doc.config is not None, timeout=WAIT_MS)
    qtbot.waitUntil(lambda: window.doc.system.has_link(HAND_LINK), timeout=WAIT_MS)
    window.previews = []

    def confirm(title, preview):
        window.previews.append((title, preview))
        return True

    window.flow.confirm = confirm
    yield window
    window.live.disconnect_bus()


def _write(window, qtbot, action=None):
    """Run ``action`` (default: Write to prosthesis) and wait for the transaction's result."""
    with qtbot.waitSignal(window.flow.finished, timeout=WAIT_MS) as got:
        assert (action or window.write_pending)() is not False
    qtbot.waitUntil(lambda: not window.live.bridge.busy, timeout=WAIT_MS)
    return got.args[0]


def _history() -> list[dict]:
    with History.open() as archive:
        return archive.entries()


def test_staged_edits_are_written_in_one_interlocked_transaction(live, rig, qtbot):
    doc = live.doc
    assert HAND_LINK in rig.links()
    doc.select(HAND_LINK)
    live.act_delete.trigger()  # Del: staged, the prosthesis untouched
    ref = ChannelRef(*HAND, 2)
    doc.select(ref)
    live.inspector.editors["descriptor"].setText("Pinch motor")
    live.inspector.editors["descriptor"].editingFinished.emit()
    assert doc.undo_stack.count() == 2
    qtbot.waitUntil(lambda: [c.kind for c in live.pending_panel.changes]
                    == [pending.REMOVE, pending.PARAMETER], timeout=WAIT_MS)
    assert HAND_LINK in rig.links() and rig.descriptor(HAND, 2) == b"Pinch grip"
    rig.recorder.frames.clear()

    result = _write(live, qtbot)
    assert result.written and result.verified, result.summary()
    assert result.interlock == "held 1 device", result.interlock  # the hand's control
    title, preview = live.previews[-1]
    assert title == "Write to prosthesis" and any("- link" in ln for ln in preview.lines())
    # On the arbitrator: the link is gone and the parameter written.
    assert HAND_LINK not in rig.links()
    assert rig.descriptor(HAND, 2) == b"Pinch motor"
    # On its bus: Suspend before the first write, Release after the last.
    frames = rig.recorder.messages()
    suspends = [i for i, m in enumerate(frames) if isinstance(m, Suspend)]
    releases = [i for i, m in enumerate(frames) if isinstance(m, Release)]
    writes = [i for i, m in enumerate(frames) if isinstance(m, SetParameter)]
    assert suspends and releases and writes, [type(m).__name__ for m in frames]
    assert suspends[0] < writes[0] and writes[-1] < releases[-1]
    # The project follows the prosthesis; the write is one undo step; it is on record.
    qtbot.waitUntil(lambda: not live.pending_panel.changes, timeout=WAIT_MS)
    assert "Write to prosthesis" in doc.undo_stack.undoText()
    [entry] = _history()
    assert entry["action"] == "write to prosthesis" and entry["verified"]
    assert entry["bus"] == rig.url and entry["operator"] == "Test Prosthetist"
    assert entry["interlock"].startswith("held")
    assert len(entry["links_before"]) == len(entry["links_after"]) + 1


def test_undo_of_a_written_change_is_a_new_confirmed_transaction(live, rig, qtbot):
    doc = live.doc
    doc.select(HAND_LINK)
    live.act_delete.trigger()
    assert _write(live, qtbot).written
    assert HAND_LINK not in rig.links()
    live.flow.confirm = lambda title, preview: False  # declined: nothing changes
    rig.recorder.frames.clear()
    with qtbot.waitSignal(live.flow.busyChanged, timeout=WAIT_MS,
                          check_params_cb=lambda busy: not busy):
        live.act_undo.trigger()
    assert HAND_LINK not in rig.links() and doc.undo_stack.index() == 2
    assert not [m for m in rig.recorder.messages() if isinstance(m, Suspend | SetParameter)]
    seen = []
    live.flow.confirm = lambda title, preview: seen.append((title, preview)) or True
    result = _write(live, qtbot, live.act_undo.trigger)
    assert result.written and result.verified, result.summary()
    assert seen and seen[0][0].startswith("Undo on the prosthesis")
    assert any("+ link" in ln for ln in seen[0][1].lines())
    assert HAND_LINK in rig.links()
    assert doc.undo_stack.index() == 0 and doc.system.has_link(HAND_LINK)
    assert [e["action"] for e in _history()] == [
        "write to prosthesis", "undo write to prosthesis (1 change)"]


def test_history_restore_is_a_previewed_transaction(live, rig, qtbot):
    doc = live.doc
    doc.select(HAND_LINK)
    live.act_delete.trigger()
    assert _write(live, qtbot).written  # entry 1: without the hand link
    doc.undo_stack.push(commands.AddLinkCommand(doc, HAND_LINK))
    assert _write(live, qtbot).written  # entry 2: with it again
    assert HAND_LINK in rig.links()
    panel = live.history_panel
    with qtbot.waitSignal(panel.loaded, timeout=WAIT_MS):
        panel.refresh()
    assert [e["id"] for e in panel.shown] == [2, 1]
    panel.select_ids(1)
    assert panel.restore_button.isEnabled()
    result = _write(live, qtbot, panel.restore_selected)
    assert result.written and result.verified, result.summary()
    assert live.previews[-1][0] == "Restore history entry 1"
    assert HAND_LINK not in rig.links()
    entries = _history()
    assert entries[-1]["action"] == "history restore 1" and entries[-1]["bus"] == rig.url
    with History.open() as archive:
        assert archive.verify().ok
    qtbot.waitUntil(lambda: not doc.system.has_link(HAND_LINK), timeout=WAIT_MS)
    qtbot.waitUntil(lambda: not live.pending_panel.changes, timeout=WAIT_MS)


def test_a_failed_connect_keeps_the_host_link_session(live, rig, qtbot, monkeypatch):
    doc = live.doc
    system_before, bridge = doc.system, live.live.bridge
    with qtbot.waitSignal(live.live.failed, timeout=WAIT_MS):
        _connect(live, monkeypatch, "serial:/dev/pdcp-no-such-port")
    assert live.live.is_live and live.live.url == rig.url and live.live.bridge is bridge
    assert doc.system is system_before and doc.session is bridge
    assert live.mode_label.text() == f"● Live on {rig.url}"
    assert "/dev/pdcp-no-such-port" in live.statusBar().currentMessage()
    # The session still works: a change is written over it.
    doc.select(HAND_LINK)
    live.act_delete.trigger()
    assert _write(live, qtbot).written and HAND_LINK not in rig.links()


def test_a_failed_serial_connect_offline_keeps_the_file(make_window, qtbot, monkeypatch):
    window = make_window(TRANSRADIAL)
    with qtbot.waitSignal(window.live.failed, timeout=WAIT_MS):
        _connect(window, monkeypatch, "serial:/dev/pdcp-no-such-port")
    assert window.doc.path == TRANSRADIAL and window.doc.session is None
    assert window.mode_label.text() == "Offline"


def test_opening_a_file_while_connected_asks(live, rig, qtbot):
    answers = []
    live.ask_leave_bus = lambda path: answers.pop(0)
    answers.append(live.LEAVE_CANCEL)
    assert not live.open_path(TRANSRADIAL)
    assert live.live.is_live and live.doc.session is live.live.bridge
    answers.append(live.LEAVE_COMPARE)
    assert not live.open_path(TRANSRADIAL)
    assert live.live.is_live
    dialog = live.compare_dialog
    qtbot.waitUntil(lambda: bool(dialog.file_sources) and bool(dialog.arbitrator_sources),
                    timeout=WAIT_MS)
    assert [s.name for s in dialog.sources()] == ["On screen", "transradial.json",
                                                  "Arbitrator"]
    dialog.close()
    answers.append(live.LEAVE_DISCONNECT)
    assert live.open_path(TRANSRADIAL)
    assert not live.live.is_live and live.doc.session is None
    assert live.mode_label.text() == f"Disconnected from {rig.url}"
    assert HAND_LINK in rig.links()  # leaving wrote nothing


def _flags(system) -> dict[ChannelRef, tuple]:
    return {ref: (ch.data_enabled, ch.source, ch.node_id) for ref, ch in system.channels()
            if system.is_present(ref)}


def _settle(window, qtbot, until):
    def ok() -> bool:
        window.live.refresh()
        return bool(until())
    qtbot.waitUntil(ok, timeout=WAIT_MS)
    qtbot.waitUntil(lambda: not window.live.bridge.busy, timeout=WAIT_MS)


def test_a_hot_swap_behind_the_host_link_shows_as_it_is(live, rig, qtbot):
    """A hand unplugged and plugged back on the prosthesis's own bus (not by the app)."""
    flowing = ChannelRef(*HAND, 1)
    live.doc.select(flowing)
    rig.host.unplug(HAND)
    _settle(live, qtbot, lambda: not live.doc.system.devices[HAND].present
            and _flags(live.doc.system) == _flags(rig.arbitrator.system()))
    assert not live.doc.system.channel(flowing).data_enabled
    rig.host.plug(HAND)
    _settle(live, qtbot, lambda: live.doc.system.devices[HAND].present
            and _flags(live.doc.system) == _flags(rig.arbitrator.system()))
    assert rig.arbitrator.system().channel(flowing).data_enabled
    qtbot.waitUntil(lambda: "data_enabled" in live.inspector.editors
                    and live.inspector.editors["data_enabled"].isChecked(), timeout=WAIT_MS)
    assert not live.pending_panel.changes  # the bus's own changes are not staged edits


def test_a_transaction_made_at_the_arbitrator_updates_the_stored_configuration(live, rig,
                                                                              qtbot):
    """Another user of the arbitrator stores the links: the window reads the stored
    configuration again without being asked, and previews use it."""
    from pdcp_studio.bus.transaction import Change
    from pdcp_studio.engine import configuration_from_system
    from pdcp_studio.model.configuration import ConfigCollection

    assert live.doc.config is not None and not live.doc.config.configurations
    change = Change("config save", configuration=ConfigCollection(
        [configuration_from_system(rig.arbitrator.system())]))
    assert rig.arbitrator.transact(change).written
    qtbot.waitUntil(lambda: bool(live.doc.config.configurations), timeout=WAIT_MS)
    assert live.preview_plan("startup").configuration_source == "stored"


def test_a_parameter_edit_written_then_undone_and_redone(live, rig, qtbot):
    ref = ChannelRef(*HAND, 2)
    live.doc.select(ref)
    live.inspector.editors["descriptor"].setText("Pinch motor")
    live.inspector.editors["descriptor"].editingFinished.emit()
    assert _write(live, qtbot).written
    assert rig.descriptor(HAND, 2) == b"Pinch motor"
    result = _write(live, qtbot, live.act_undo.trigger)
    assert result.written and result.verified, result.summary()
    assert rig.descriptor(HAND, 2) == b"Pinch grip"
    assert live.doc.undo_stack.index() == 0
    live.act_redo.trigger()  # the edit, staged again
    qtbot.waitUntil(lambda: [c.kind for c in live.pending_panel.changes]
                    == [pending.PARAMETER], timeout=WAIT_MS)
    assert rig.descriptor(HAND, 2) == b"Pinch grip"
    assert _write(live, qtbot, live.act_redo.trigger).written
    assert rig.descriptor(HAND, 2) == b"Pinch motor"


def test_the_autoconfigure_policy_over_the_host_link(live, qtbot, rig):
    """Issue 17 in the app over the host link: shown, changed as a recorded transaction,
    checked on the arbitrator itself."""
    qtbot.waitUntil(lambda: live.policy_label.text() == "Autoconfigure: on", timeout=WAIT_MS)
    assert rig.arbitrator.read_policy().autoconfigure
    with qtbot.waitSignal(live.flow.finished, timeout=WAIT_MS) as got:
        live.act_autoconfigure.trigger()
    assert got.args[0].ok, got.args[0].summary()
    assert rig.arbitrator.read_policy().autoconfigure is False
    assert History(os.environ["PDCP_STUDIO_HISTORY"]).entries()[-1]["action"] == (
        "policy autoconfigure off")
    qtbot.waitUntil(lambda: live.policy_label.text() == "Autoconfigure: off", timeout=WAIT_MS)
    assert not live.act_autoconfigure.isChecked()


def test_a_replaced_hand_is_no_longer_missing_over_the_host_link(live, rig, qtbot):
    """As on ``sim:`` (test_app_replaced_part.py): once the replacement is written and
    verified the arbitrator forgets the old hand, and so does the window — it is not left
    missing, and Bus events says what replaced it, not that it "left" again (DEVICE_REPLACED,
    docs/host-link.md §5.7)."""
    from pdcp_studio.app.wizards import logic
    from pdcp_studio.bus.sim.rigs import SPARE_HAND
    from pdcp_studio.bus.transaction import Change
    from pdcp_studio.engine import configuration_from_system
    from pdcp_studio.model.configuration import ConfigCollection

    def missing() -> list[DeviceKey]:
        return [k for k, d in live.doc.system.devices.items() if not d.present]

    panel = live._leaf_docks["events"].widget()
    assert rig.arbitrator.transact(Change("config save", configuration=ConfigCollection(
        [configuration_from_system(rig.arbitrator.system())]))).written
    qtbot.waitUntil(lambda: bool(live.doc.config.configurations), timeout=WAIT_MS)
    rig.host.unplug(HAND)
    qtbot.waitUntil(lambda: missing() == [HAND], timeout=WAIT_MS)
    rig.host.plug(SPARE_HAND)
    qtbot.waitUntil(lambda: sum(lk.input.device == SPARE_HAND
                                for lk in live.doc.system.links) == 3, timeout=WAIT_MS)
    assert missing() == [HAND]  # linked by the duty cycle, not yet a fitting
    system = rig.arbitrator.system()
    change = logic.replacement_change(system, logic.replacement_plan(
        system, live.live.bridge.session.read_configuration(), [SPARE_HAND]))
    with qtbot.waitSignal(live.flow.finished, timeout=WAIT_MS) as got:
        live.flow.run(change, "Replace a part")
    assert got.args[0].written, got.args[0].summary()
    assert HAND not in rig.arbitrator.system().devices  # the arbitrator forgot it
    qtbot.waitUntil(lambda: HAND not in live.doc.system.devices, timeout=WAIT_MS)
    assert missing() == []
    qtbot.waitUntil(lambda: any("is replaced by" in w for w, _y, _s in panel.rows()),
                    timeout=WAIT_MS)
    said = [w for w, _y, _s in panel.rows() if "serial 301" in w]
    assert said[-1].endswith("is replaced by Multi-grip hand with wrist rotator (serial 302)")
    assert not any(w.endswith("left the bus") for w in said)  # (it left when unplugged)
