"""The host link while another arbitrator is on the arbitrator's bus (reference §5): STATUS
says so (flag 4; the arbitrator's public ``yielded``, issue 10 items 1 and 7), the link is
read-only — every request that would send a frame or change the prosthesis is refused with
OTHER_ARBITRATOR in words, the tables are still answered — and once the other's beacons have
been gone for five beacon intervals the arbitrator takes the bus back and writes again
(issue 28 item 1)."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdcp_studio.bus.hostlink.client import open_hostlink_session
from pdcp_studio.bus.hostlink.testing.relay import PtyRelay
from pdcp_studio.bus.session.urls import parse_bus_url
from pdcp_studio.errors import PdcpError
from tests.bus.stray_frames import BeaconingArbitrator

from .hostlink_rig import arbitrator_rig, wait_for

SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"


def test_status_tells_of_another_arbitrator_and_the_link_is_read_only_till_it_is_gone(
        tmp_path):
    with arbitrator_rig(SYSTEMS / "thesis-test1.json", tmp_path / "memory.bin",
                        take_back=True) as (arb, server), \
            PtyRelay(server.slave_path) as relay:
        session = open_hostlink_session(parse_bus_url(f"serial:{relay.client_path}@128000"),
                                        monitor=False)
        other = BeaconingArbitrator(arb.conn.bus.channel_id)
        try:
            assert session.status()["other_arbitrator"] is False
            key = sorted(session.system().devices)[0]
            session.suspend(key, 100)  # writes go through while the bus is ours
            other.start()
            assert wait_for(lambda: arb.yielded, 10.0)
            assert session.status()["other_arbitrator"] is True
            assert sorted(session.system().devices)  # the tables are still answered
            for write in (lambda: session.suspend(key, 100), lambda: session.release(key),
                          lambda: session.reset_device(key),
                          lambda: session.get_parameter(key, 10, 0)):
                with pytest.raises(PdcpError, match=r"read-only until the other.s beacons have "
                                                    r"been gone for 2\.5 s"):
                    write()
            other.stop()
            assert wait_for(lambda: not arb.yielded, 30.0)
            assert session.status()["other_arbitrator"] is False
            session.suspend(key, 100)  # the bus is ours again
            session.release(key)
        finally:
            other.close()
            session.close()
