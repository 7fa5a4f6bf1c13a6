"""An arbitrator whose non-volatile memory cannot be read still starts the prosthesis."""

from __future__ import annotations

from test_arbitrator_rig import Rig, link, no_bus_left_open  # noqa: F401

from pdcp_studio.bus import events as ev


def test_unreadable_memory_is_reported_once_and_start_up_uses_the_devices(tmp_path):
    # A folder where the memory file should be: every read fails with an OSError.
    with Rig("appendix-d", memory=tmp_path) as rig:
        rig.settle()
        complaints = [e for e in rig.of(ev.BusError) if "unreadable" in e.message]
        assert len(complaints) == 1 and str(tmp_path) in complaints[0].message
        assert set(rig.arb.system().links) == {link((4, 1), (5, 2)), link((5, 3), (6, 1)),
                                               link((5, 5), (6, 2))}
