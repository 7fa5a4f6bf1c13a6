"""Bus events says why a part left, the same on the host link as on a simulated or CAN bus
(issue 28 item 6): DEVICE_LEFT carries the arbitrator's figures and words (docs/host-link.md
§5.7); an arbitrator from before that still gets a plain line."""

from __future__ import annotations

import os
import re

import pytest

from pdcp_studio.app.docks.events_panel import describe_event
from pdcp_studio.bus import events as ev
from pdcp_studio.bus.hostlink import records as hr
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.paths import systems_dir
from pdcp_studio.storage import system_file

WAIT_MS = 30000  # a loaded machine: the host link is slow, never wrong


def _system():
    return system_file.load_path(systems_dir() / "transradial.json")


def _over_the_host_link(event: ev.DeviceLeft) -> ev.DeviceLeft:
    """What the PC makes of the arbitrator's event: the server's body, the client's reading."""
    left = hr.unpack_left(hr.pack_left(event.key, event.silent_s, event.interval_s, event.why))
    return ev.DeviceLeft(left.key, why=left.why, silent_s=left.silent_s,
                         interval_s=left.interval_s)


def test_a_part_that_left_over_the_host_link_is_worded_as_on_the_bus(qapp):
    system = _system()
    key = next(iter(system.devices))
    on_bus = ev.DeviceLeft(key, why="no beacon for 1.9 s, 3 beacon intervals while the other "
                           "parts beaconed on", silent_s=1.9, interval_s=0.5)
    [bus_row] = describe_event(on_bus, system)
    [link_row] = describe_event(_over_the_host_link(on_bus), system)
    assert link_row == bus_row
    assert link_row.why == "No beacon for 1.9 s: 3 beacon intervals of 500 ms"
    assert "while the other parts beaconed on" in link_row.detail


def test_an_arbitrators_words_alone_are_shown(qapp):
    system = _system()
    key = next(iter(system.devices))
    [row] = describe_event(ev.DeviceLeft(key, why="unplugged"), system)
    assert row.what.endswith("left the bus") and row.why == "unplugged"


def test_a_part_that_left_without_a_reason_is_still_said_plainly(qapp):
    system = _system()
    key = next(iter(system.devices))
    [row] = describe_event(ev.DeviceLeft(key), system)  # an arbitrator from before reasons
    assert row.what.endswith("left the bus")
    assert row.why == "It is no longer heard on the bus; the arbitrator gave no details"


@pytest.mark.gui
@pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")
def test_bus_events_says_why_a_part_left_over_the_host_link(make_window, qtbot, tmp_path):
    """The window on a serial host link: a part unplugged behind the arbitrator is listed
    with the arbitrator's measured reason, as on a simulated bus."""
    from tests.road_rigs import served

    hand = DeviceKey(2641, 769, 301)
    with served("transradial", tmp_path / "memory.bin") as (_arbitrator, host, url):
        window = make_window()
        with qtbot.waitSignal(window.ready, timeout=WAIT_MS):
            window.connect_bus(url)
        dock = window._leaf_docks["events"]
        dock.show()
        dock.raise_()
        panel = dock.widget()
        host.unplug(hand)

        def left_rows():
            return [r for r in panel.rows() if r[0].endswith("left the bus")]

        qtbot.waitUntil(lambda: bool(left_rows()), timeout=WAIT_MS)
        what, why, _similar = left_rows()[0]
        assert what.startswith("Multi-grip hand"), what
        found = re.fullmatch(r"No beacon for \d+\.\d s: (\d+) beacon intervals of \d+ ms", why)
        assert found and int(found[1]) >= 3, why
        shot = os.environ.get("PDCP_SHOT")
        if shot:  # for a person to look at
            dock.raise_()
            qtbot.wait(300)
            window.grab().save(shot)
        window.live.disconnect_bus()
