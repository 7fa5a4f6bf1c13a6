"""Host link 2 end to end over a real pseudo-terminal (docs/host-link.md).

A real arbitrator and simulated devices share a python-can virtual bus; the arbitrator serves
the host link on a new pty; the session opens the pty's slave path with pyserial, exactly as
it would open /dev/ttyUSB0.
"""

from __future__ import annotations

import os
import struct

import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.hostlink.client import HostLinkError, open_hostlink_session
from pdcp_studio.bus.hostlink.testing.relay import PtyRelay
from pdcp_studio.bus.session.urls import parse_bus_url
from pdcp_studio.errors import TransportError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.protocol.hostlink_messages import Req, Status

from .hostlink_rig import arbitrator_rig, wait_for

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")

VID = 0x0A51
EMG1 = DeviceKey(VID, 257, 101)
CONTROL = DeviceKey(VID, 513, 201)
FLEXOR_LINK = Link(ChannelRef(VID, 257, 101, 1), ChannelRef(VID, 513, 201, 1))


@pytest.fixture(scope="module")
def rig(tmp_path_factory):
    from pathlib import Path

    systems = Path(__file__).resolve().parents[2] / "resources" / "systems"
    memory = tmp_path_factory.mktemp("hostlink") / "memory.bin"
    with arbitrator_rig(systems / "transradial.json", memory) as parts:
        yield parts


@pytest.fixture
def relay(rig):
    _, server = rig
    with PtyRelay(server.slave_path) as r:
        yield r


@pytest.fixture
def session(relay):
    s = open_hostlink_session(parse_bus_url(f"serial:{relay.client_path}@128000"),
                              monitor=False)
    yield s
    s.close()


def test_the_scan_is_the_arbitrators_tables_and_a_second_one_is_free(rig, relay, session):
    arbitrator, _ = rig
    assert session.info["version"] == 2
    system = session.scan()
    truth = arbitrator.system()
    assert set(system.devices) == set(truth.devices)
    for key, device in truth.devices.items():
        assert system.devices[key] == device  # every parameter, channel and node ID
    assert sorted(system.links) == sorted(truth.links)
    relay.reset_counts()
    session.scan()
    assert relay.total == 0  # nothing changed: the cache answers


def test_a_link_event_refreshes_only_the_two_devices(rig, relay, session):
    arbitrator, _ = rig
    session.scan()
    seen: list[object] = []
    session.subscribe(seen.append)
    arbitrator.add_link(FLEXOR_LINK)  # made by the arbitrator itself, not over the link
    try:
        assert wait_for(lambda: any(isinstance(e, ev.LinkMade) for e in seen))
        relay.reset_counts()
        system = session.system()
        assert system.has_link(FLEXOR_LINK)
        assert system.devices[CONTROL] == arbitrator.system().devices[CONTROL]
        assert 0 < relay.total < 1500  # two devices and the links, not the whole bus
    finally:
        arbitrator.remove_link(FLEXOR_LINK)


def test_links_made_over_the_host_link_are_on_the_bus(rig, session):
    arbitrator, _ = rig
    session.add_link(FLEXOR_LINK)
    assert arbitrator.system().has_link(FLEXOR_LINK)
    assert session.system().has_link(FLEXOR_LINK)
    session.remove_link(FLEXOR_LINK)
    assert not arbitrator.system().has_link(FLEXOR_LINK)
    assert not session.system().has_link(FLEXOR_LINK)


def test_a_refused_request_carries_its_status_and_reason(session):
    from pdcp_studio.bus.hostlink import records as hr
    from pdcp_studio.errors import PdcpError

    ghost = Link(ChannelRef(VID, 999, 1, 1), ChannelRef(VID, 513, 201, 1))
    with pytest.raises(HostLinkError, match="ADD_LINK refused") as err:
        session.request(Req.ADD_LINK, hr.pack_link(ghost))
    assert err.value.status is Status.BAD_LINK
    with pytest.raises(PdcpError, match="add link"):
        session.add_link(ghost)  # a transaction: refused before anything is written
    with pytest.raises(HostLinkError) as err:
        session.get_parameter(DeviceKey(1, 2, 3), P.DEVICE_DESCRIPTOR)
    assert err.value.status is Status.UNKNOWN_DEVICE
    with pytest.raises(HostLinkError) as err:
        session.request(0x3E)  # no such request
    assert err.value.status is Status.UNKNOWN_REQUEST
    assert session.scan().devices  # the link survives refusals


def test_parameters_of_any_length_move_in_chunks(rig, session):
    descriptor = session.get_parameter(EMG1, P.DEVICE_DESCRIPTOR)
    assert b"EMG" in descriptor
    interval = P.encode_value(P.device_parameter(P.DEVICE_BEACON_INTERVAL), 150)
    session.set_parameter(EMG1, P.DEVICE_BEACON_INTERVAL, 0, interval)
    assert session.get_parameter(EMG1, P.DEVICE_BEACON_INTERVAL) == interval
    assert session.system().devices[EMG1].beacon_interval == 150
    long = ("forearm EMG, left, " * 20).encode()[:300]  # longer than a frame
    session.set_parameter(EMG1, P.CH_DESCRIPTOR, 1, long)  # in a transaction's change
    assert session.get_parameter(EMG1, P.CH_DESCRIPTOR, 1) == long
    again = long[::-1]
    session.write_parameter_bytes(EMG1, P.CH_DESCRIPTOR, 1, again)  # SET_PARAM in chunks
    assert session.get_parameter(EMG1, P.CH_DESCRIPTOR, 1) == again


def test_a_managed_parameter_is_refused_as_such(session):
    from pdcp_studio.errors import PdcpError

    with pytest.raises(HostLinkError) as err:
        session.write_parameter_bytes(EMG1, P.DEVICE_NODE_ID, 0, b"\x05")
    assert err.value.status is Status.MANAGED
    with pytest.raises(PdcpError, match="managed"):
        session.set_parameter(EMG1, P.DEVICE_NODE_ID, 0, b"\x05")


def test_the_stored_configuration_is_written_in_chunks_and_verified(rig, relay, session):
    out = StoredChannel(index=1, vid=VID, pid=257, serial=101, type=0x9000, profile=0x4222)
    inp = StoredChannel(index=1, vid=VID, pid=513, serial=201, type=0x9200, profile=0x4222)
    written = ConfigCollection([StoredConfiguration(1, [StoredLink(inp, out, 1)])])
    back = session.write_configuration(written)
    assert back == session.read_configuration() == rig[0].read_memory()
    relay.reset_counts()
    session.read_configuration()
    # Unchanged, so CONFIG_INFO only (~30 bytes both ways): the configuration's own records
    # are 60 bytes, so a re-read would pass 60. Room is left for one retransmitted ACK on a
    # loaded machine.
    assert relay.total < 60


def test_a_commit_with_a_wrong_crc_stores_nothing(rig, session):
    before = rig[0].memory.read_bytes()
    data = b"\x01\x02\x03\x04"
    session.request(Req.CONFIG_WRITE_BEGIN, struct.pack("<HH", len(data), 0x1234))
    session.request(Req.CONFIG_WRITE_CHUNK, b"\x00\x00" + data)
    with pytest.raises(HostLinkError) as err:
        session.request(Req.CONFIG_WRITE_COMMIT)
    assert err.value.status is Status.CHECKSUM
    assert rig[0].memory.read_bytes() == before
    with pytest.raises(HostLinkError) as err:
        session.request(Req.CONFIG_WRITE_CHUNK, b"\x00\x00" + data)
    assert err.value.status is Status.NO_TRANSFER


def test_a_change_runs_as_the_arbitrators_transaction_with_its_interlock(rig, session):
    from pdcp_studio.bus.transaction import Change, LinkAction, ParameterWrite, Policy

    arbitrator, _ = rig
    interval = P.encode_value(P.device_parameter(P.DEVICE_BEACON_INTERVAL), 120)
    change = Change("test change", [LinkAction("add", FLEXOR_LINK, "a reason, in words")],
                    [ParameterWrite(EMG1, P.DEVICE_BEACON_INTERVAL, 0, interval)],
                    policy=Policy(autoconfigure=True))
    result = session.carry_out(change)
    try:
        assert result.status == "applied" and result.verified, result.summary()
        assert FLEXOR_LINK in result.links_after and FLEXOR_LINK not in result.links_before
        assert result.interlock  # the devices feeding the hand were held, then released
        assert arbitrator.system().has_link(FLEXOR_LINK)
        assert session.system().devices[EMG1].beacon_interval == 120
        assert session.read_policy() == Policy(autoconfigure=True)
    finally:
        arbitrator.remove_link(FLEXOR_LINK)


def test_a_staged_change_with_a_wrong_crc_runs_nothing(rig, session):
    before = rig[0].system().links
    session.request(Req.TRANSACT_BEGIN, struct.pack("<HH", 3, 0x0BAD))
    session.request(Req.TRANSACT_CHUNK, b"\x00\x00abc")
    with pytest.raises(HostLinkError) as err:
        session.request(Req.TRANSACT_RUN)
    assert err.value.status is Status.CHECKSUM
    assert rig[0].system().links == before


def test_a_plan_previewed_on_the_host_is_the_plan_applied(rig, session):
    arbitrator, _ = rig
    before = arbitrator.system().links
    plan = session.preview("autoconfigure")
    try:
        result = session.apply_plan(plan)
        assert result.status == "applied" and result.verified, result.summary()
        assert set(arbitrator.system().links) == set(plan.final_links)
        assert set(session.system().links) == set(plan.final_links)
    finally:
        for link in arbitrator.system().links:
            if link not in before:
                arbitrator.remove_link(link)


def test_the_monitor_gets_protocol_frames_and_channel_counts(rig, relay):
    from pdcp_studio.bus.hostlink.client import ChannelCounts

    s = open_hostlink_session(parse_bus_url(f"serial:{relay.client_path}"), monitor=True)
    seen: list[object] = []
    s.subscribe(seen.append)
    rig[0].add_link(FLEXOR_LINK)  # channel data flows on a link
    try:
        s.scan()  # the node IDs of the output channels
        s.get_parameter(EMG1, P.DEVICE_DESCRIPTOR)
        assert wait_for(lambda: any(isinstance(e, ev.FrameSeen) for e in seen), 5.0)
        frame = next(e for e in seen if isinstance(e, ev.FrameSeen))
        assert frame.text  # decoded on the PC
        assert wait_for(lambda: any(isinstance(e, ChannelCounts) and e.counts for e in seen), 5.0)
        counts = next(e for e in seen if isinstance(e, ChannelCounts) and e.counts)
        assert FLEXOR_LINK.output in counts.counts
    finally:
        rig[0].remove_link(FLEXOR_LINK)
        s.close()


def test_a_port_that_does_not_exist_names_itself():
    with pytest.raises(TransportError, match="/dev/pdcp-no-such-port"):
        open_hostlink_session(parse_bus_url("serial:/dev/pdcp-no-such-port"))


def test_the_serial_session_is_a_bus_session(session):
    from pdcp_studio.bus.session.api import BusSession

    assert isinstance(session, BusSession)
    assert not session.closed


def test_the_app_opens_on_a_serial_bus(rig, tmp_path):
    import subprocess
    import sys

    _, server = rig
    shot = tmp_path / "serial.png"
    proc = subprocess.run([sys.executable, "-m", "pdcp_studio", "gui", "--bus",
                           f"serial:{server.slave_path}", "--screenshot", str(shot)],
                          capture_output=True, text=True, timeout=120,
                          env={**os.environ, "QT_QPA_PLATFORM": "offscreen"})
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert shot.stat().st_size > 10_000
