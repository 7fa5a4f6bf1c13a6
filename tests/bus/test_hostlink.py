"""The arbitrator host link end to end over a real pseudo-terminal (docs/host-link.md).

A real arbitrator and simulated devices share a python-can virtual bus; the arbitrator serves
the host link on a new pty; the client session opens the pty's slave path with pyserial,
exactly as it would open /dev/ttyUSB0.
"""

from __future__ import annotations

import os
import time

import can
import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator import Arbitrator
from pdcp_studio.bus.device_host import DeviceHost
from pdcp_studio.bus.device_sim import SimulatedDevice
from pdcp_studio.bus.hostlink_client import HostLinkError, open_hostlink_session
from pdcp_studio.bus.hostlink_server import HostLinkServer, event_to_json
from pdcp_studio.bus.urls import parse_bus_url, unique_virtual_channel
from pdcp_studio.errors import BusTimeoutError, TransportError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.protocol.hostlink import HostCommand
from pdcp_studio.storage import system_file

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")

VID = 0x0A51
EMG1 = DeviceKey(VID, 257, 101)
CONTROL = DeviceKey(VID, 513, 201)
FLEXOR_LINK = Link(ChannelRef(VID, 257, 101, 1), ChannelRef(VID, 513, 201, 1))


def wait_for(predicate, timeout: float = 5.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(0.02)
    return predicate()


@pytest.fixture
def rig(systems_dir, tmp_path):
    """Transradial devices + a real arbitrator (no memory yet, so no links) + the pty server."""
    system = system_file.load_path(systems_dir / "transradial.json")
    channel = unique_virtual_channel("hostlink")
    arb_bus = can.Bus(interface="virtual", channel=channel)
    dev_bus = can.Bus(interface="virtual", channel=channel)
    host = DeviceHost(dev_bus, [SimulatedDevice(d) for d in system.devices.values()])
    arbitrator = Arbitrator(arb_bus, memory=tmp_path / "memory.bin", profile_layer=False)
    server = None
    try:
        assert wait_for(lambda: len(arbitrator.system().devices) == 4, 10.0)
        assert arbitrator.wait_settled(10.0)
        server = HostLinkServer(arbitrator, "pty")
        yield arbitrator, server
    finally:
        if server is not None:
            server.close()
        arbitrator.close()
        host.close()
        for bus in (arb_bus, dev_bus):
            bus.shutdown()


@pytest.fixture
def session(rig):
    _, server = rig
    s = open_hostlink_session(parse_bus_url(f"serial:{server.slave_path}@128000"))
    yield s
    s.close()


def test_ping_and_system_come_over_the_line(session):
    assert session.info["name"] == "pdcp-studio arbitrator"
    system = session.system()
    assert set(system.devices) >= {EMG1, CONTROL}
    assert all(d.present and d.node_id for d in system.devices.values())


def test_a_link_made_over_the_host_link_is_on_the_bus_and_reported(rig, session):
    arbitrator, _ = rig
    seen: list[object] = []
    session.subscribe(seen.append)
    session.add_link(FLEXOR_LINK)
    assert arbitrator.system().has_link(FLEXOR_LINK)
    assert wait_for(lambda: any(isinstance(e, ev.LinkMade) and e.link == FLEXOR_LINK
                                for e in seen))
    assert session.system().has_link(FLEXOR_LINK)
    session.remove_link(FLEXOR_LINK)
    assert not arbitrator.system().has_link(FLEXOR_LINK)


def test_a_refused_request_carries_the_arbitrators_reason(session):
    ghost = Link(ChannelRef(VID, 999, 1, 1), ChannelRef(VID, 513, 201, 1))
    with pytest.raises(HostLinkError, match="ADD_LINK"):
        session.add_link(ghost)
    assert session.info  # the link survives a failure reply


def test_parameters_are_read_and_set_with_read_back(session):
    descriptor = P.decode_value(P.device_parameter(P.DEVICE_DESCRIPTOR),
                                session.get_parameter(EMG1, P.DEVICE_DESCRIPTOR))
    assert "EMG" in str(descriptor)  # a bulk read: longer than one frame's 4 bytes
    interval = P.encode_value(P.device_parameter(P.DEVICE_BEACON_INTERVAL), 150)
    session.set_parameter(EMG1, P.DEVICE_BEACON_INTERVAL, 0, interval)
    assert session.get_parameter(EMG1, P.DEVICE_BEACON_INTERVAL) == interval


def test_stored_configuration_is_written_then_verified(session):
    out = StoredChannel(index=1, vid=VID, pid=257, serial=101, type=0x9000, profile=0x4222)
    inp = StoredChannel(index=1, vid=VID, pid=513, serial=201, type=0x9200, profile=0x4222)
    written = ConfigCollection([StoredConfiguration(1, [StoredLink(inp, out, 1)])])
    back = session.write_configuration(written)
    assert back == session.read_configuration()
    assert back.configurations[0].links[0].output.serial == 101


def test_a_plan_previewed_on_the_host_is_the_plan_applied(rig, session):
    arbitrator, _ = rig
    plan = session.preview("autoconfigure")
    assert plan.actions, "transradial autoconfigure links the EMG sites and the hand"
    done: list[tuple[int, int]] = []
    result = session.apply_plan(plan, progress=lambda d, t, _text: done.append((d, t)))
    assert result.status == "applied" and result.verified, result.summary()
    assert set(arbitrator.system().links) == set(plan.final_links)
    assert done[-1][0] == done[-1][1]  # finished


def test_garbage_on_the_line_costs_nothing_but_a_counted_frame(rig, session):
    _, server = rig
    with session._io:
        session.port.write(b"\x00\xa5\xff\xff junk \xa5\x01")
    time.sleep(0.1)
    assert session.system().devices
    assert server.bad_frames >= 1


def test_a_pulled_cable_is_a_clear_error_not_a_hang(rig):
    _, server = rig
    s = open_hostlink_session(parse_bus_url(f"serial:{server.slave_path}"),
                              reply_timeout=0.2)
    errors: list[str] = []
    s.subscribe(lambda e: errors.append(e.message) if isinstance(e, ev.BusError) else None)
    server.close()  # the arbitrator end goes away
    t0 = time.monotonic()
    with pytest.raises((BusTimeoutError, TransportError), match=r"PING|no reply|failed"):
        s.request(HostCommand.PING)
    assert time.monotonic() - t0 < 3.0
    assert wait_for(lambda: errors, 3.0)
    s.close()


def test_a_port_that_does_not_exist_names_itself():
    with pytest.raises(TransportError, match="/dev/pdcp-no-such-port"):
        open_hostlink_session(parse_bus_url("serial:/dev/pdcp-no-such-port"))


def test_events_survive_the_json_round_trip():
    from pdcp_studio.bus.hostlink_client import _event_from_json

    for event in (ev.DeviceJoined(EMG1), ev.DeviceLeft(CONTROL), ev.LinkMade(FLEXOR_LINK),
                  ev.LinkRemoved(FLEXOR_LINK), ev.BusError("bad frame at 0x123")):
        assert _event_from_json(event_to_json(event)) == event
    assert event_to_json(ev.FrameSeen(0.0, 0x123, b"", "x")) is None
