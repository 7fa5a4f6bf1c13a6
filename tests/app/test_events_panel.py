"""Hot-swap repairs in the events list (issue 11 item 3): which link, why, how similar.

On ``sim:thesis-test4`` the hot-swap script pulls joystick D1 and plugs D2 while running; the
arbitrator's duty cycle links D2.O2 → D3.I2. The window's Bus events list must say so in
words a prosthetist reads, with the engine's text one hover away.
"""

from __future__ import annotations

import re

import pytest

from pdcp_studio.app.docks.events_panel import EventsPanel, describe_event
from pdcp_studio.bus import events as ev
from pdcp_studio.model.refs import ChannelRef, DeviceKey

pytestmark = pytest.mark.gui

D1, D2, D3 = DeviceKey(2, 2, 4), DeviceKey(2, 2, 5), DeviceKey(2, 2, 6)
RAW = re.compile(r"\b(replacement|superseded|duty-cycle|no_candidate|0x[0-9A-F]+|\d+/\d+/\d+)\b")


def test_a_hot_swap_on_thesis_test4_is_listed_with_link_why_and_similarity(make_window,
                                                                            qtbot):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:thesis-test4")
    bridge = window.live.bridge
    dock = window._leaf_docks["events"]
    panel = dock.widget()
    with qtbot.waitSignal(bridge.scriptFinished, timeout=30000):
        bridge.run_script("hot-swap")
    qtbot.waitUntil(lambda: any(w.startswith("Linked") for w, _y, _s in panel.rows()),
                    timeout=10000)
    rows = panel.rows()
    whats = [w for w, _y, _s in rows]
    # The devices' own names, as the graph shows them (the new one named once known).
    assert "Joystick A left the bus" in whats
    qtbot.waitUntil(lambda: "Joystick B joined the bus" in [w for w, _y, _s in panel.rows()]
                    and not any("Thesis test node" in w for w, _y, _s in panel.rows()),
                    timeout=10000)
    rows = panel.rows()
    linked = [r for r in rows if r[0].startswith("Linked")]
    assert len(linked) == 1, rows
    what, why, similar = linked[0]
    # Which link: device and channel names, new joystick's channel 2 → D3's channel 2.
    # (each channel by its one name: the part and the channel's descriptor)
    assert what.startswith("Linked Joystick B, Joystick Y axis")
    assert what.index("Joystick B") < what.index("→") < what.index("LED terminal, Axis LEDs")
    assert "replaced while the prosthesis was running" in why
    for text in (what, why, similar):
        assert not RAW.search(text), text
    if "drives a part of the prosthesis" in why:
        # Under load the duty cycle may run between the pull and the plug: the link is then
        # made for the terminal that lost its source, with no missing part to compare with.
        assert similar == ""
        return
    # Why: a replacement, naming the missing channel.
    assert re.search(r"\(Joystick A, [^()]+ is missing\)", why), why
    # How similar, in words.
    assert similar.startswith("same product, other serial number")
    assert "signal" in similar
    # The removed link says why, too.
    removed = [r for r in rows if r[0].startswith("Removed the link")]
    assert removed and "Joystick A, " in removed[0][0]
    # The engineer's detail is one hover away.
    item = next(panel.view.item(i, 1) for i in range(panel.view.rowCount())
                if panel.view.item(i, 1).text().startswith("Linked"))
    assert "similarity 23" in item.toolTip() and "replacement" in item.toolTip()
    # Long rows wrap (taller than one line), they are not cut.
    assert panel.view.rowHeight(item.row()) > 1.5 * panel.view.fontMetrics().height()
    window.live.disconnect_bus()


def test_describe_event_words_for_parts_of_other_products():
    from pdcp_studio.engine import plan_autoconfigure
    from pdcp_studio.engine.plan import Action, Op, Plan, Rule
    from pdcp_studio.engine.similarity import similarity_at
    from pdcp_studio.model.system import Link
    from pdcp_studio.paths import systems_dir
    from pdcp_studio.storage import system_file

    system = system_file.load_path(systems_dir() / "transradial.json")
    plan_autoconfigure(system).apply(system)
    link = system.links[0]
    missing = ChannelRef(*DeviceKey(9, 9, 9), link.output.index)
    plan = Plan("startup", links_before=[Link(missing, link.input)])
    plan.actions.append(Action(Op.ADD, link, Rule.REPLACEMENT, "engine words",
                               similarity_at(1, 0x4400, 0x4800), cause=missing))
    rows = describe_event(ev.PlanApplied(plan), system)
    assert len(rows) == 1
    assert "started up" in rows[0].why
    assert rows[0].similar.startswith("another maker's product")
    assert "other control mode" in rows[0].similar
    assert describe_event(ev.FrameSeen(0.0, 1, b"", ""), system) == []


def test_the_list_keeps_a_bounded_number_of_rows(qtbot, monkeypatch):
    from pdcp_studio.app.docks import events_panel
    from pdcp_studio.model.system import System

    monkeypatch.setattr(events_panel, "MAX_ROWS", 5)
    panel = EventsPanel(lambda: System())
    qtbot.addWidget(panel)
    for serial in range(8):
        panel.add_event(ev.DeviceJoined(DeviceKey(1, 1, serial)))
    assert panel.view.rowCount() == 5
    assert "(1/1/7)" in panel.rows()[-1][0]
    panel.clear()
    assert not panel.rows() and "No bus events" in panel.count_label.text()


def test_what_the_arbitrator_changed_on_its_own_is_said_with_whom_it_held(make_window, qtbot):
    """Issue 28 item 8: a hot-swap repair is the arbitrator's own change; Bus events says so,
    why, whom it held still while it wrote, and that the links read back as written."""
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:thesis-test4")
    bridge = window.live.bridge
    panel = window._leaf_docks["events"].widget()
    with qtbot.waitSignal(bridge.scriptFinished, timeout=30000):
        bridge.run_script("hot-swap")

    def own() -> list[tuple[str, str, str]]:
        return [r for r in panel.rows() if r[0].startswith("The arbitrator changed links on "
                                                           "its own")]

    qtbot.waitUntil(lambda: bool(own()), timeout=15000)
    what, why, _similar = own()[-1]
    assert "replaced while the prosthesis was running" in what
    assert why.startswith("It held ") and "read back as written" in why, why
    assert "did not all" not in why
    for text in (what, why):
        assert not RAW.search(text), text
