"""The document is the project, the prosthesis the target — over the simulated prosthesis.

Each flow of issue 8 on a real ``sim:`` bus through ``open_session``: edits staged and
written in one transaction, undo of a written change as a new transaction, opening a file
while connected, a failed Connect, and restoring a history entry. The fitting history is a
temporary file (``PDCP_STUDIO_HISTORY``, set for every app test in conftest).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from pdcp_studio.app.documents import commands, pending
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.storage.history import History

pytestmark = pytest.mark.gui

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"
CONTROL = DeviceKey(2641, 513, 201)
HAND = DeviceKey(2641, 769, 301)
HAND_LINK = Link(ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1))


@pytest.fixture
def live(make_window, qtbot):
    """A window live on ``sim:transradial``, confirming every previewed change."""
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    assert window.live.is_live, window.statusBar().currentMessage()
    qtbot.waitUntil(lambda: window.doc.config is not None, timeout=5000)
    window.previews = []

    def confirm(title, preview):
        window.previews.append((title, preview))
        return True

    window.flow.confirm = confirm
    yield window
    window.live.disconnect_bus()


def _write(window, qtbot, action=None):
    """Run ``action`` (default: Write to prosthesis) and wait for the transaction's result."""
    with qtbot.waitSignal(window.flow.finished, timeout=20000) as got:
        assert (action or window.write_pending)() is not False
    result = got.args[0]
    # The prosthesis as it is now arrives as a snapshot: wait until the project agrees.
    qtbot.waitUntil(lambda: not window.live.bridge.busy, timeout=10000)
    return result


def _bus_links(window):
    return set(window.live.bridge.session.system().links)


def test_live_edits_are_staged_then_written_in_one_transaction(live, qtbot, tmp_path):
    doc = live.doc
    assert HAND_LINK in _bus_links(live)
    # Delete a link (Del): staged — one undo step, drawn as a pending removal, listed.
    doc.select(HAND_LINK)
    live.act_delete.trigger()
    assert not doc.system.has_link(HAND_LINK) and doc.undo_stack.count() == 1
    assert HAND_LINK in _bus_links(live)  # the prosthesis is untouched
    assert [i.link for i in live.scene.unwritten_items] == [HAND_LINK]
    # A parameter edit: staged too.
    ref = ChannelRef(*HAND, 2)
    doc.select(ref)
    live.inspector.editors["descriptor"].setText("Pinch motor")
    live.inspector.editors["descriptor"].editingFinished.emit()
    assert doc.undo_stack.count() == 2
    qtbot.waitUntil(lambda: len(live.pending_panel.changes) == 2, timeout=3000)
    qtbot.waitUntil(lambda: live.scene.cards[HAND].pending_rows == {2}, timeout=3000)
    kinds = [c.kind for c in live.pending_panel.changes]
    assert kinds == [pending.REMOVE, pending.PARAMETER]
    assert live.act_write_pending.isEnabled()
    session = live.live.bridge.session
    assert session.get_parameter(HAND, 2, 2).split(b"\0")[0] == b"Pinch grip"
    live.pending_panel.patient.setText("Clinic ref 42")
    live.pending_panel.patient.editingFinished.emit()
    # Drag the link back: one undo step; the project equals the prosthesis there again, so
    # the removal is no longer pending (nothing drawn, nothing listed, nothing sent).
    scene = live.scene
    out, inp = scene.port(HAND_LINK.output), scene.port(HAND_LINK.input)
    scene.begin_link_drag(out, out.scenePos())
    assert scene.end_link_drag(inp.scenePos()) == HAND_LINK
    assert doc.undo_stack.count() == 3 and not scene.link_items[HAND_LINK].pending
    assert not scene.unwritten_items
    qtbot.waitUntil(lambda: [c.kind for c in live.pending_panel.changes]
                    == [pending.PARAMETER], timeout=3000)
    live.act_undo.trigger()
    assert not doc.system.has_link(HAND_LINK) and doc.undo_stack.index() == 2
    # A plan is staged too (Apply on a live bus): autoconfigure would relink the hand.
    plan = live.preview_plan("autoconfigure")
    assert [a.link for a in plan.added] == [HAND_LINK]
    live.plan_panel.discard()

    result = _write(live, qtbot)
    assert result.written, result.summary()
    title, preview = live.previews[-1]
    assert title == "Write to prosthesis" and any("- link" in line for line in preview.lines())
    assert HAND_LINK not in _bus_links(live)
    assert session.get_parameter(HAND, 2, 2).split(b"\0")[0] == b"Pinch motor"
    qtbot.waitUntil(lambda: HAND_LINK not in doc.bus_system.links, timeout=5000)
    qtbot.waitUntil(lambda: not live.pending_panel.changes, timeout=5000)
    qtbot.waitUntil(lambda: not live.scene.cards[HAND].pending_rows, timeout=3000)
    # One undo step more: the write itself.
    assert doc.undo_stack.index() == 3 and "Write to prosthesis" in doc.undo_stack.undoText()
    with History.open() as archive:
        [entry] = archive.entries()
    assert entry["operator"] == "Test Prosthetist" and entry["patient"] == "Clinic ref 42"
    assert entry["action"] == "write to prosthesis" and entry["verified"]
    qtbot.waitUntil(lambda: bool(live.history_panel.shown), timeout=5000)
    assert live.history_panel.shown[0]["patient"] == "Clinic ref 42"
    # The fitting report of this session: who, for whom, and the change just made.
    info = live.fitting_info()
    assert (info.patient, info.prosthetist, info.bus) == ("Clinic ref 42", "Test Prosthetist",
                                                         "sim:transradial")
    assert [e["action"] for e in info.changes] == ["write to prosthesis"]
    pdf = tmp_path / "fitting.pdf"
    assert live.write_fitting_report(pdf) and pdf.read_bytes().startswith(b"%PDF")


def test_undo_of_a_written_change_is_a_new_transaction(live, qtbot):
    doc = live.doc
    doc.select(HAND_LINK)
    live.act_delete.trigger()
    assert _write(live, qtbot).written
    assert HAND_LINK not in _bus_links(live)
    # Declined: nothing changes anywhere.
    live.flow.confirm = lambda title, preview: False
    with qtbot.waitSignal(live.flow.busyChanged, timeout=10000,
                          check_params_cb=lambda busy: not busy):
        live.act_undo.trigger()
    assert HAND_LINK not in _bus_links(live) and doc.undo_stack.index() == 2
    # Confirmed: the prosthesis gets the link back, and the project steps back over the edit.
    seen = []

    def confirm(title, preview):  # the operator says yes, and we keep what was shown
        seen.append((title, preview))
        return True

    live.flow.confirm = confirm
    result = _write(live, qtbot, lambda: live.act_undo.trigger())
    assert result.written, result.summary()
    assert seen and seen[0][0].startswith("Undo on the prosthesis")
    assert any("+ link" in line for line in seen[0][1].lines())
    assert HAND_LINK in _bus_links(live)
    assert doc.undo_stack.index() == 0 and doc.system.has_link(HAND_LINK)
    qtbot.waitUntil(lambda: not live.pending_panel.changes, timeout=5000)
    with History.open() as archive:
        assert [e["action"] for e in archive.entries()] == [
            "write to prosthesis", "undo write to prosthesis (1 change)"]
    # Redo: first the edit (staged again, drawn as a pending removal), then the write —
    # a transaction again.
    live.act_redo.trigger()
    assert [i.link for i in live.scene.unwritten_items] == [HAND_LINK]
    assert HAND_LINK in _bus_links(live)
    result = _write(live, qtbot, lambda: live.act_redo.trigger())
    assert result.written and HAND_LINK not in _bus_links(live)
    assert doc.undo_stack.index() == 2


def test_opening_a_file_while_connected_asks_and_can_compare_instead(live, qtbot):
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
                    timeout=5000)
    assert [s.name for s in dialog.sources()] == ["On screen", "transradial.json",
                                                  "Arbitrator"]
    dialog.close()
    answers.append(live.LEAVE_DISCONNECT)
    assert live.open_path(TRANSRADIAL)
    assert not live.live.is_live and live.doc.session is None
    assert live.mode_label.text() == "Disconnected from sim:transradial"
    assert "Simulator" not in [d.windowTitle() for d in live.findChildren(type(live.plan_dock))
                               if d.isVisible()]


def test_a_failed_connect_keeps_the_session_you_had(live, qtbot):
    doc = live.doc
    system_before = doc.system
    with qtbot.waitSignal(live.live.failed, timeout=20000):
        live.connect_bus("can:socketcan:pdcp-no-such-can")
    assert live.live.is_live and live.live.url == "sim:transradial"
    assert doc.system is system_before and doc.session is live.live.bridge
    assert live.mode_label.text() == "● Live on sim:transradial"
    assert "live on sim:transradial" in live.windowTitle().lower()
    assert "pdcp-no-such-can" in live.statusBar().currentMessage()


def test_a_failed_connect_offline_keeps_the_file(make_window, qtbot):
    window = make_window(TRANSRADIAL)
    with qtbot.waitSignal(window.live.failed, timeout=20000):
        window.connect_bus("can:socketcan:pdcp-no-such-can")
    assert window.doc.path == TRANSRADIAL and window.doc.session is None
    assert window.mode_label.text() == "Offline"
    assert window.windowTitle().startswith("transradial.json")


def test_history_restore_is_a_previewed_transaction(live, qtbot, tmp_path):
    doc = live.doc
    doc.select(HAND_LINK)
    live.act_delete.trigger()
    assert _write(live, qtbot).written  # entry 1: without the hand link
    doc.undo_stack.push(commands.AddLinkCommand(doc, HAND_LINK))
    assert _write(live, qtbot).written  # entry 2: with it again
    assert HAND_LINK in _bus_links(live)
    panel = live.history_panel
    with qtbot.waitSignal(panel.loaded, timeout=5000):
        panel.refresh()
    assert [e["id"] for e in panel.shown] == [2, 1]
    panel.select_ids(1, 2)
    assert "only after #2" in panel.details.toPlainText()
    panel.select_ids(1)
    assert panel.restore_button.isEnabled()
    result = _write(live, qtbot, panel.restore_selected)
    assert result.written, result.summary()
    title, preview = live.previews[-1]
    assert title == "Restore history entry 1"
    assert any("+" not in line and "- link" in line for line in preview.lines())
    assert HAND_LINK not in _bus_links(live)
    with History.open() as archive:
        entries = archive.entries()
        assert archive.verify().ok
    assert entries[-1]["action"] == "history restore 1"  # as the CLI's restore names it
    # The fitting report of one entry: its own patient, operator, time and change.
    first = next(e for e in panel.all_entries() if e["id"] == 1)
    info = live.fitting_info(first)
    assert info.changes == [first] and info.prosthetist == "Test Prosthetist"
    assert info.time is not None and info.time.tzinfo is not None
    assert live.write_fitting_report(tmp_path / "entry1.pdf", entry=first)
    # The project follows the prosthesis: nothing is left pending.
    qtbot.waitUntil(lambda: not doc.system.has_link(HAND_LINK), timeout=5000)
    qtbot.waitUntil(lambda: not live.pending_panel.changes, timeout=5000)


def test_previews_use_the_stored_configuration_read_after_a_write(live, qtbot):
    from pdcp_studio.app.dialogs import write_config_dialog as wcd

    live.ask_write_configuration()
    dialog = next(d for d in live.findChildren(wcd.WriteConfigDialog))
    qtbot.waitUntil(lambda: dialog.state == wcd.READY, timeout=5000)
    with qtbot.waitSignal(dialog.verified, timeout=10000) as got:
        dialog.write()
    assert got.args[0], got.args[1]
    dialog.close()
    qtbot.waitUntil(lambda: bool(live.doc.config is not None
                                 and live.doc.config.configurations), timeout=5000)
    plan = live.preview_plan("startup")
    assert plan is not None and plan.configuration_source == "stored"
    assert "no configuration" not in live.plan_panel.summary.text()


def test_leaving_with_unwritten_changes_asks(live, qtbot):
    live.doc.select(HAND_LINK)
    live.act_delete.trigger()
    qtbot.waitUntil(lambda: len(live.pending_panel.changes) == 1, timeout=3000)
    asked = []
    answers = iter([False, True])  # the operator keeps the changes, then drops them

    def ask_unwritten(n):
        asked.append(n)
        return next(answers)

    live.ask_unwritten = ask_unwritten
    live.quiet = False  # the question is only skipped for scripted, quiet windows
    try:
        live.act_disconnect.trigger()
        assert asked == [1] and live.live.is_live  # kept: nothing lost
        live.act_disconnect.trigger()
    finally:
        live.quiet = True
    assert asked == [1, 1] and not live.live.is_live
    assert not live.doc.system.has_link(HAND_LINK)  # the document keeps its edits


def test_the_confirmation_never_writes_on_enter(qtbot):
    from PySide6.QtCore import Qt

    from pdcp_studio.app.dialogs.confirm_change import ConfirmDialog
    from pdcp_studio.bus.session.api import open_session, preview_change
    from pdcp_studio.bus.transaction import Change

    session = open_session("sim:transradial")
    try:
        links = session.system().links
        preview = preview_change(session, Change.links_to(
            links, [lk for lk in links if lk != HAND_LINK], "write to prosthesis"))
    finally:
        session.close()
    dialog = ConfirmDialog("Write to prosthesis", preview, store=True)
    qtbot.addWidget(dialog)
    dialog.show()
    assert not dialog.write_button.isDefault() and not dialog.write_button.autoDefault()
    qtbot.keyClick(dialog, Qt.Key.Key_Return)
    assert dialog.result() != dialog.DialogCode.Accepted
