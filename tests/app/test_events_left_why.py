"""Bus events says why a part left, the same on the host link as on a simulated or CAN bus
(issue 28 item 6): DEVICE_LEFT carries the arbitrator's figures and words (docs/host-link.md
§5.7); an arbitrator from before that still gets a plain line."""

from __future__ import annotations

from pdcp_studio.app.docks.events_panel import describe_event
from pdcp_studio.bus import events as ev
from pdcp_studio.bus.hostlink import records as hr
from pdcp_studio.paths import systems_dir
from pdcp_studio.storage import system_file


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
