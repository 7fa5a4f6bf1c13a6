"""What the prosthetist's trial met (issue 26, point 9): small things, each in their path."""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.gui


def _connect(window, qtbot, url: str) -> None:
    """Connect ``url`` and wait until its prosthesis is the document."""
    window.connect_bus(url)
    qtbot.waitUntil(lambda: window.live.is_live and window.live.url == url
                    and window.doc.session is window.live.bridge, timeout=20000)


# -- the Simulator panel has a View-menu entry --------------------------------------------
def test_simulator_panel_is_in_the_view_menu(make_window, qtbot):
    window = make_window()
    _connect(window, qtbot, "sim:transradial")
    dock = window.bus_docks.leaf_docks["sim"]
    assert dock.toggleViewAction() in window.view_menu.actions()
    dock.toggleViewAction().trigger()
    assert dock.isHidden()
    window.live.disconnect_bus()


# -- switching prostheses leaves nothing of the previous one --------------------------------
def test_switching_prosthesis_clears_events_and_plot(make_window, qtbot):
    window = make_window()
    _connect(window, qtbot, "sim:transradial")
    docks = window.bus_docks
    events = docks.events_dock().widget()
    first = window.live.bridge
    hand = next(k for k, d in window.doc.system.devices.items() if d.pid == 769)
    first.unplug(hand)
    qtbot.waitUntil(lambda: any("left" in r[0] for r in events.rows()), timeout=10000)
    docks.make_trace_docks()
    plot = docks.leaf_docks["plot"].widget()
    ref = next(iter(window.doc.system.links)).output
    plot.add_channel(ref)
    qtbot.waitUntil(lambda: any(len(s.ts) for s in plot.series), timeout=10000)
    before = {s.ref for s in plot.series}

    _connect(window, qtbot, "sim:thesis-test1")
    assert window.live.bridge is not first
    assert not any("Multi-grip" in r[0] for r in events.rows()), events.rows()
    assert not any("left" in r[0] for r in events.rows()), events.rows()
    assert not ({s.ref for s in plot.series} & before)
    assert all(s.ref.device in window.doc.system.devices for s in plot.series)
    window.live.disconnect_bus()


# -- the history panel: a detail pane with room, a hint that follows the selection -------
def test_history_details_have_room_and_the_hint_follows(make_window, qtbot):
    from pdcp_studio.bus.transaction import Change

    window = make_window(size=(1500, 950))
    _connect(window, qtbot, "sim:transradial")
    session = window.live.bridge.session
    links = sorted(session.system().links)
    assert session.transact(Change.links_to(links, links[1:], "one less")).written
    assert session.transact(Change.links_to(links[1:], links, "again")).written
    window.history_dock.show()
    window.history_dock.raise_()
    panel = window.history_panel
    with qtbot.waitSignal(panel.loaded, timeout=5000):
        panel.refresh()
    qtbot.waitUntil(lambda: panel.split.width() > 600, timeout=5000)
    table, details = panel.split.sizes()
    assert details >= 0.4 * (table + details) - 2, (table, details)
    panel.select_ids()
    assert panel.hint.isVisibleTo(panel) and "two" in panel.hint.text()
    panel.select_ids(1)
    assert panel.hint.isVisibleTo(panel) and "second" in panel.hint.text()
    panel.select_ids(1, 2)
    assert not panel.hint.isVisibleTo(panel), panel.hint.text()
    window.live.disconnect_bus()
