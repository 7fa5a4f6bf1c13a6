"""The trace and the live plot are made just after the window is up (issue 11, start-up).

They are hidden tabs when a bus connects and the costliest part of the window (numpy, the
trace store), so ``app/window/bus_docks.py`` makes them once the first system is on screen. Nothing may be
lost by waiting: the trace shows every frame since the session started, the tabs and the
View menu keep their order, and selecting a channel before then gives the plot at once.
"""

from __future__ import annotations

import pytest
from PySide6.QtWidgets import QTabBar

from pdcp_studio.model.refs import ChannelRef

pytestmark = pytest.mark.gui


def _tabs(window):
    return [[bar.tabText(i) for i in range(bar.count())]
            for bar in window.findChildren(QTabBar) if bar.count()]


def test_the_trace_comes_after_the_window_with_every_frame_since_the_session(make_window,
                                                                               qtbot):
    window = make_window()
    counted = []

    def count_from(bridge):  # connected after the window's own slot, as the trace's buffer
        bridge.frameSeen.connect(lambda frames: counted.append(len(frames)))

    window.live.sessionStarted.connect(count_from)
    at_ready = []
    window.ready.connect(lambda: at_ready.append(set(window._leaf_docks)))
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    assert at_ready == [{"events", "sim"}]  # the window is up before the trace and plot
    qtbot.waitUntil(lambda: {"monitor", "plot"} <= set(window._leaf_docks), timeout=5000)
    qtbot.waitUntil(lambda: sum(counted) > 50, timeout=10000)
    window.live.disconnect_bus()  # no more frames: compare what arrived with what is shown
    monitor = window._leaf_docks["monitor"]
    monitor.flush()
    assert len(monitor.all_rows) == sum(counted)
    # (the tab bar is rebuilt when the layout next runs: on a loaded machine, a moment later)
    qtbot.waitUntil(lambda: any("Bus monitor" in t for t in _tabs(window)), timeout=5000)
    bottom = next(t for t in _tabs(window) if "Plan" in t)
    assert bottom[-3:] == ["Bus monitor", "Live plot", "Bus events"]
    entries = [a.text() for a in window.view_menu.actions()]
    assert entries.index("Bus monitor") < entries.index("Live plot") < entries.index(
        "Bus events")
    assert window._leaf_docks["monitor"].isVisible()  # a tab beside the plan, not hidden
    assert window.plan_dock.isVisible()


def test_selecting_a_channel_before_then_gives_the_plot_at_once(make_window, qtbot):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    ref = window.doc.system.links[0].output  # a linked output: its values flow
    assert isinstance(ref, ChannelRef)
    if "plot" not in window._leaf_docks:  # (a starved machine may be past the wait already)
        window.doc.select(ref)
        assert "plot" in window._leaf_docks and "monitor" in window._leaf_docks
    else:
        window.doc.select(ref)
    plot = window._leaf_docks["plot"].widget()
    assert plot.ref == ref
    qtbot.waitUntil(lambda: len(plot.points) > 0, timeout=10000)  # its values arrive
    window.live.disconnect_bus()
