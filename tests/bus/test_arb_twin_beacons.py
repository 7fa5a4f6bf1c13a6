"""The presence tracker's beacon count when frames are handled behind others: twins powered
together beacon back to back (each one's beacon queued behind the other's) and are caught; a
single device whose window closes late is not taken for twins. Pure: no threads, no bus."""

from __future__ import annotations

from pdcp_studio.bus.arbitrator.common import BEACON_WINDOW, _Node
from pdcp_studio.bus.arbitrator.presence import PresenceTracker
from pdcp_studio.model.refs import DeviceKey

K4 = DeviceKey(2, 2, 4)


def test_twins_beaconing_back_to_back_are_caught() -> None:
    presence = PresenceTracker()
    node = _Node(K4, 1, 0.0, beacon_interval=0.05, set_up=True)
    verdicts = []
    for n in range(2 * BEACON_WINDOW + 2):
        t = n * 0.05
        verdicts.append(presence.beacon(node, t, caught_up=False))  # the twin's is queued
        verdicts.append(presence.beacon(node, t + 0.0002, caught_up=True))
    assert any("beacons" in v for v in verdicts)


def test_a_window_closing_late_is_judged_on_its_whole_span() -> None:
    presence = PresenceTracker()
    node = _Node(K4, 1, 0.0, beacon_interval=0.05, set_up=True)
    assert presence.beacon(node, 0.0) == ""  # the window opens
    # One beacon an interval, each handled behind other frames for three windows' time:
    verdicts = [presence.beacon(node, n * 0.05, caught_up=False)
                for n in range(1, 3 * BEACON_WINDOW)]
    verdicts.append(presence.beacon(node, 3 * BEACON_WINDOW * 0.05))  # closes, caught up
    assert not any(verdicts)


def test_a_backlog_at_the_window_s_start_opens_none() -> None:
    presence = PresenceTracker()
    node = _Node(K4, 1, 0.0, beacon_interval=0.05, set_up=True)
    # A second's beacons handled in a moment after a stall: no window is open yet …
    assert not any(presence.beacon(node, 1.0 + n * 0.0001, caught_up=False) for n in range(20))
    assert node.window_start is None
    # … it opens on the first beacon handled as it comes.
    assert presence.beacon(node, 1.05) == "" and node.window_start == 1.05
