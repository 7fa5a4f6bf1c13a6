"""The host link's STATUS says when another arbitrator appeared on the arbitrator's bus
(flag 4; the arbitrator's public ``yielded``, issue 10 items 1 and 7)."""

from __future__ import annotations

from pathlib import Path

import can

from pdcp_studio.bus.hostlink.client import open_hostlink_session
from pdcp_studio.bus.hostlink.testing.relay import PtyRelay
from pdcp_studio.bus.session.urls import parse_bus_url
from pdcp_studio.protocol import Beacon, Mode

from .hostlink_rig import arbitrator_rig, wait_for

SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"


def test_status_tells_of_another_arbitrator(tmp_path):
    with arbitrator_rig(SYSTEMS / "thesis-test1.json", tmp_path / "memory.bin") as (arb, server), \
            PtyRelay(server.slave_path) as relay:
        session = open_hostlink_session(parse_bus_url(f"serial:{relay.client_path}@128000"),
                                        monitor=False)
        try:
            assert session.status()["other_arbitrator"] is False
            aid, data = Beacon(0, mode=Mode.ARBITRATOR).encode()
            tap = can.Bus(interface="virtual", channel=arb.conn.bus.channel_id)
            try:
                tap.send(can.Message(arbitration_id=aid, data=data, is_extended_id=False))
                assert wait_for(lambda: arb.yielded, 5.0)
            finally:
                tap.shutdown()
            assert session.status()["other_arbitrator"] is True
        finally:
            session.close()
