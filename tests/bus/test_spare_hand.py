"""The default simulated prosthesis has a spare hand (issue 11): simulated but not plugged in,
so it is not on the bus until the user plugs it in; swapped for the hand, the arbitrator
links it in the hand's place. The system file keeps the four parts."""

from __future__ import annotations

import time

from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.sim.rigs import HAND, SPARE_HAND, load_prosthesis, prosthesis
from pdcp_studio.paths import systems_dir
from pdcp_studio.storage import system_file


def test_the_spare_hand_is_simulated_but_not_plugged_in():
    system = load_prosthesis("transradial")
    spare, hand = system.devices[SPARE_HAND], system.devices[HAND]
    assert not spare.present and hand.present and spare.name == "Spare hand"
    assert [(c.index, c.profile, c.type) for c in spare.channels.values()] == \
        [(c.index, c.profile, c.type) for c in hand.channels.values()]
    assert "spare hand" in prosthesis("transradial").description
    assert len(system_file.load_path(systems_dir() / "transradial.json").devices) == 4


def test_the_spare_hand_joins_only_when_plugged_in_and_takes_the_hands_place():
    with open_session("sim:transradial", frame_events=False) as session:
        assert SPARE_HAND not in session.system().devices  # not on the bus
        labels = {k: (name, plugged) for k, name, plugged in session.sim_devices()}
        assert labels[SPARE_HAND] == ("Spare hand", False)
        session.save_configuration()
        session.unplug(HAND)
        assert _until(lambda: not session.system().devices[HAND].present)
        session.plug(SPARE_HAND)

        def spare_inputs() -> list[int]:
            return sorted(lk.input.index for lk in session.system().links
                          if lk.input.device == SPARE_HAND)

        assert _until(lambda: spare_inputs() == [1, 2, 3]), spare_inputs()


def _until(condition, timeout: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.05)
    return False
