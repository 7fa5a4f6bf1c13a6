"""Arbitrator faults around its memory and resets: an unreadable memory, data in flight."""

from __future__ import annotations

from pdcp_studio.bus import events as ev
from tests.bus.test_arbitrator_rig import Rig, link


def test_unreadable_memory_is_reported_once_and_start_up_uses_the_devices(tmp_path):
    # A folder where the memory file should be: every read fails with an OSError.
    with Rig("appendix-d", memory=tmp_path) as rig:
        rig.settle()
        complaints = [e for e in rig.of(ev.BusError) if "unreadable" in e.message]
        assert len(complaints) == 1 and str(tmp_path) in complaints[0].message
        assert set(rig.arb.system().links) == {link((4, 1), (5, 2)), link((5, 3), (6, 1)),
                                               link((5, 5), (6, 2))}


def test_channel_data_in_flight_when_the_arbitrator_resets_is_not_an_error():
    import can

    from pdcp_studio.protocol import make_id

    with Rig("appendix-d") as rig:
        rig.settle()
        old_channel_ids = {rig.arb.channel_node_id(lk.output) for lk in rig.arb.system().links}
        rig.arb.reset(keep_memory=True)
        sender = rig.bus()
        try:
            for node in old_channel_ids:  # data a device queued before the Reset reached it
                sender.send(can.Message(arbitration_id=make_id(1, 0, node), data=b"\xfa\x00",
                                        is_extended_id=False))
            assert rig.wait(lambda: rig.arb.stale_data_frames >= len(old_channel_ids))
        finally:
            sender.shutdown()
        assert not [e for e in rig.of(ev.BusError) if "undecodable" in e.message]
        rig.settle()
