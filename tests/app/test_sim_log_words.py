"""The Simulator panel's log and the bridge's ``simChanged`` speak a prosthetist's words:
"Unplugged the …" with the part's name, never "Done: Unplug 2641/769/301" (issue 11)."""

from __future__ import annotations

import re

import pytest

from pdcp_studio.app.docks.sim_panel import SimPanel
from pdcp_studio.app.live.session_bridge import SessionBridge
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.model.refs import DeviceKey

pytestmark = pytest.mark.gui

HAND = DeviceKey(2641, 769, 301)


def test_the_log_says_what_was_done_to_which_part(qtbot):
    bridge = SessionBridge(open_session("sim:transradial"), interval_ms=20,
                           url="sim:transradial")
    try:
        panel = SimPanel(bridge)
        qtbot.addWidget(panel)
        qtbot.waitUntil(lambda: panel.tree.topLevelItemCount() == 5, timeout=5000)
        name = panel._label(HAND)
        assert name.startswith("Multi-grip hand with wrist rotator")
        panel.select(HAND)
        with qtbot.waitSignal(bridge.simChanged, timeout=10_000) as changed:
            panel.unplug_selected()
        assert changed.args[0] == f"Unplugged {name}"
        with qtbot.waitSignal(bridge.simChanged, timeout=10_000) as changed:
            panel.plug_selected()
        assert changed.args[0] == f"Plugged in {name}"
        with qtbot.waitSignal(bridge.simChanged, timeout=10_000):
            panel.reset(keep_memory=True)
        log = panel.log_lines()
        assert any(line.endswith(f"Unplugged {name}") for line in log), log
        assert any("arbitrator restarted" in line for line in log), log
        for line in log:
            assert "Done:" not in line and not re.search(r"\d+/\d+/\d+", line), line
    finally:
        bridge.close(wait_ms=5000)


def test_both_event_lists_name_the_new_joystick_alike(make_window, qtbot):
    """sim:thesis-test4's hot-swap: the Simulator panel's Events list and the Bus events
    list call the joystick plugged in by one name, the one it tells the bus."""
    d1, d2 = DeviceKey(2, 2, 4), DeviceKey(2, 2, 5)
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:thesis-test4")
    sim = window._leaf_docks["sim"].widget()
    events = window._leaf_docks["events"].widget()
    qtbot.waitUntil(lambda: sim.tree.topLevelItemCount() == 3, timeout=10000)
    assert sim._label(d2) == "Joystick B"  # before it ever was on the bus
    bridge = window.live.bridge
    with qtbot.waitSignal(bridge.scriptFinished, timeout=30000):
        bridge.run_script("hot-swap")
    qtbot.waitUntil(lambda: "Joystick B joined the bus" in [w for w, _y, _s in events.rows()],
                    timeout=10000)
    joined = [line.split("  ", 1)[1] for line in sim.log_lines() if "joined the bus" in line]
    assert joined == ["Joystick B joined the bus"], sim.log_lines()
    left = [line.split("  ", 1)[1] for line in sim.log_lines() if "left the bus" in line]
    assert left == [f"{sim._label(d1)} left the bus"] == ["Joystick A left the bus"]
    assert not any("Thesis test node" in line for line in sim.log_lines())
    window.live.disconnect_bus()
