"""The live graph's flow timer runs only while some output sends: once the last data is
older than the hold time it stops, and the next data frame starts it again."""

from __future__ import annotations

from PySide6.QtCore import QObject

from pdcp_studio.app.graph import live_flow
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import System


def test_the_flow_timer_stops_when_data_stops_and_starts_again(qapp, monkeypatch):
    now = [100.0]
    monkeypatch.setattr(live_flow.time, "monotonic", lambda: now[0])
    owner = QObject()
    flow = live_flow.LiveFlow(owner, {}, {}, System, lambda: 1.0)
    output = ChannelRef(1, 2, 3, 1)
    flow.note_data(output)
    assert flow._flow_timer.isActive() and flow.is_live(output)
    flow._flow_tick()  # data is fresh: it keeps ticking
    assert flow._flow_timer.isActive()
    now[0] += live_flow.LIVE_HOLD_S + 0.1
    flow._flow_tick()
    assert not flow.is_live(output) and not flow._flow_timer.isActive()
    flow.note_data(output)
    assert flow._flow_timer.isActive()
