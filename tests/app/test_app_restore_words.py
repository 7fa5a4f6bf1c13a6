"""Restoring a fitting-history entry in the app: its preview in the words of the change's
effect, and — when a part it needs is not on the bus — a refusal that names the part (as
every text names it) and offers Replace a part, shown at once, before anything is written
and before any progress dialog. On a real ``sim:transradial`` bus.
"""

from __future__ import annotations

import pytest

from pdcp_studio.app.wizards import open_wizard
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.storage.history import History

pytestmark = pytest.mark.gui

CONTROL = DeviceKey(2641, 513, 201)
HAND = DeviceKey(2641, 769, 301)
HAND_LINK = Link(ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1))
T = 20000


@pytest.fixture
def live(make_window, qtbot):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=T):
        window.connect_bus("sim:transradial")
    qtbot.waitUntil(lambda: window.doc.config is not None, timeout=5000)
    yield window
    wizard = getattr(window, "task_wizard", None)
    if wizard is not None:
        wizard.close()
    window.live.disconnect_bus()


def _entries():
    with History.open() as history:
        return history.entries()


def _hand_unplugged_after_an_entry(window, qtbot):
    """Entry 1 (the hand link removed, the hand's values recorded), then the hand
    unplugged; returns the prosthesis's links then."""
    from pdcp_studio.bus.transaction import Change

    session = window.live.bridge.session
    links = sorted(session.system().links)
    assert session.transact(Change.links_to(links, [lk for lk in links if lk != HAND_LINK],
                                            "without the hand link")).written
    window.live.bridge.unplug(HAND)

    def gone():
        window.live.refresh()
        bus = window.doc.bus_system
        return bus is not None and not bus.devices[HAND].present
    qtbot.waitUntil(gone, timeout=T)
    qtbot.waitUntil(lambda: not window.live.bridge.busy, timeout=T)
    return set(session.system().links)


def test_the_restore_wizard_refuses_naming_the_absent_part_and_offers_replace(live, qtbot):
    links = _hand_unplugged_after_an_entry(live, qtbot)
    entries = _entries()
    w = open_wizard(live, "restore")
    page = w.source_page
    qtbot.waitUntil(lambda: len(page.history) == 1, timeout=T)
    assert page.choose_entry(entries[0]["id"])
    qtbot.waitUntil(page.isComplete, timeout=T)
    w.next()
    qtbot.waitUntil(lambda: w.diff_page.refusal is not None, timeout=T)
    box = w.diff_page.refusal
    assert box.isVisible()
    assert "Multi-grip hand" in box.text() and "not on the bus" in box.text()
    assert "Nothing was written" in box.text() and "2641/" not in box.text()
    replace = [b for b in box.buttons() if b.text() == "Replace a part…"]
    assert replace, [b.text() for b in box.buttons()]
    assert not w.diff_page.isComplete()  # the wizard cannot go on to write
    assert live.flow.progress_dialog is None
    # Nothing written, nothing recorded.
    assert set(live.live.bridge.session.system().links) == links
    assert len(_entries()) == 1
    # Replace a part… leaves the restore for the replacement task.
    replace[0].click()
    qtbot.waitUntil(lambda: getattr(live, "task_wizard", None) is not w, timeout=T)
    assert type(live.task_wizard).__name__ == "ReplacePartWizard"


def test_the_history_panel_refuses_naming_the_absent_part_before_any_progress(live, qtbot):
    links = _hand_unplugged_after_an_entry(live, qtbot)
    panel = live.history_panel
    with qtbot.waitSignal(panel.loaded, timeout=T):
        panel.refresh()
    panel.select_ids(_entries()[0]["id"])
    assert panel.restore_selected() is False
    box = panel.refusal
    assert box is not None and box.isVisible()
    assert "Multi-grip hand" in box.text() and "not on the bus" in box.text()
    assert "2641/" not in box.text()
    assert any(b.text() == "Replace a part…" for b in box.buttons())
    # Refused before the road: no preview, no progress dialog, nothing written.
    assert not live.flow.busy and live.flow.progress_dialog is None
    assert live.flow.dialog is None
    assert set(live.live.bridge.session.system().links) == links
    assert len(_entries()) == 1
    box.reject()


def test_a_history_restore_previews_in_words_and_puts_back_a_control_mode(live, qtbot):
    from pdcp_studio.app.wizards import logic
    from pdcp_studio.bus.transaction import Change, ParameterWrite

    session = live.live.bridge.session
    assert session.transact(logic.store_change(session.system())).written  # entry 1
    links = sorted(session.system().links)
    change = Change.links_to(links, [lk for lk in links if lk != HAND_LINK], "lose one")
    change.parameters = [ParameterWrite(HAND, 1, 1, bytes.fromhex("00972022"))]  # velocity
    assert session.transact(change).written  # entry 2
    live.live.refresh()
    panel = live.history_panel
    with qtbot.waitSignal(panel.loaded, timeout=T):
        panel.refresh()
    first = min(e["id"] for e in panel.all_entries())
    panel.select_ids(first)
    assert panel.restore_selected()
    qtbot.waitUntil(lambda: live.flow.dialog is not None and live.flow.dialog.isVisible(),
                    timeout=T)
    dialog = live.flow.dialog
    words = dialog.words_text()
    assert "Link made: " in words and "control mode velocity → position" in words, words
    assert "At the next power-on" in words
    assert "0x" not in words and "2641/" not in words
    assert dialog.store_box.isChecked()  # the recorded stored configuration goes back
    with qtbot.waitSignal(live.flow.finished, timeout=T) as got:
        dialog.write_button.click()
    assert got.args[0].written, got.args[0].summary()
    assert set(session.system().links) == set(links)
    assert session.system().channel(ChannelRef(*HAND, 1)).ctype.control_mode.label == "position"


def test_an_entry_from_before_the_effect_says_so(live, qtbot):
    from pdcp_studio.app.words.history_words import entry_summary, predates
    from pdcp_studio.bus.transaction import Change

    session = live.live.bridge.session
    links = sorted(session.system().links)
    assert session.transact(Change.links_to(links, links[1:], "config write")).written
    panel = live.history_panel
    with qtbot.waitSignal(panel.loaded, timeout=T):
        panel.refresh()
    old = dict(panel.all_entries()[0])
    assert entry_summary(old).startswith("Link removed: ")
    old.pop("effect")
    old.pop("next_power_on")
    assert entry_summary(old) == "config write"  # as recorded
    panel._show_entry(old)
    assert predates() in panel.details.toPlainText()
