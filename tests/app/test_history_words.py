"""The fitting history's detail pane names links as the plan table does (part, channel and
what it carries), the engineer's ``2641/513/201#3 → 2641/769/301#1`` one hover away."""

from __future__ import annotations

import re

import pytest

from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link

pytestmark = pytest.mark.gui

HAND_LINK = Link(ChannelRef(2641, 513, 201, 3), ChannelRef(2641, 769, 301, 1))
RAW = re.compile(r"\d+/\d+/\d+#\d+")
T = 20000


def test_the_details_word_the_links_and_keep_the_numbers_in_the_tooltip(make_window, qtbot):
    from pdcp_studio.bus.transaction import Change

    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=T):
        window.connect_bus("sim:transradial")
    session = window.live.bridge.session
    links = set(session.system().links)
    assert HAND_LINK in links
    assert session.transact(Change.links_to(sorted(links), sorted(links - {HAND_LINK}),
                                            "without the hand link")).written  # entry 1
    assert session.transact(Change.links_to(sorted(links - {HAND_LINK}), sorted(links),
                                            "with it again")).written  # entry 2
    window.live.refresh()
    panel = window.history_panel
    with qtbot.waitSignal(panel.loaded, timeout=5000):
        panel.refresh()
    qtbot.waitUntil(lambda: HAND_LINK.input.device in window.doc.system.devices, timeout=T)
    words = panel.link_words(HAND_LINK)
    assert words == ("Pattern-recognition control unit, Power grip set point → "
                     "Multi-grip hand with wrist rotator, Power grip")  # the one names
    panel.select_ids(1)
    text = panel.details.toPlainText()
    # The entry's effect, in words (the names every text uses), and the next power-on.
    assert ("Link removed: Pattern-recognition control unit, Power grip set point → "
            "Multi-grip hand with wrist rotator, Power grip") in text, text
    assert "At the next power-on" in text
    assert not RAW.search(text), text
    # The codes one click away: the technical detail, collapsed.
    assert panel.technical.isHidden() and not panel.technical_button.isHidden()
    assert "- link 2641/513/201#3 → 2641/769/301#1" in panel.technical.toPlainText()
    panel.technical_button.click()
    assert not panel.technical.isHidden()
    # The list says what each change did, not "config write".
    row = panel.shown.index(next(e for e in panel.shown if e["id"] == 1))
    assert panel.table.item(row, 2).text().startswith("Link removed: Pattern-recognition")
    # Two entries compared: the difference in words too.
    panel.select_ids(1, 2)
    text = panel.details.toPlainText()
    assert f"only after #2: {words}" in text and not RAW.search(text), text
    window.live.disconnect_bus()


def test_a_read_overtaken_by_a_newer_one_is_not_shown(make_window, qtbot):
    """Two reads in a row: only the newer is shown (an older read that ends later held the
    archive as it was before, and showed an empty history on a loaded machine)."""
    window = make_window()
    panel = window.history_panel
    loads: list[int] = []
    panel.loaded.connect(lambda: loads.append(len(panel.all_entries())))
    older, newer = panel.refresh(), panel.refresh()
    qtbot.waitUntil(lambda: not older.is_running and not newer.is_running and bool(loads),
                    timeout=T)
    qtbot.wait(200)  # the older one's result, had it been let through, comes now
    assert len(loads) == 1
