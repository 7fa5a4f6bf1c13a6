"""A restore puts back every recorded value, also those a link action of the restore itself
turns over (issue 26, point 3).

Found by tests/bus/test_effect_property.py: removing a link turns its output's data transfer
off; an entry that recorded the output still sending (data transfer on, no link) was restored
without it, since the values to write were compared before the restore's own link actions.
"""

from __future__ import annotations

from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.transaction import Change, LinkAction, ParameterWrite, restore_change
from pdcp_studio.model import param_names as N
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.storage.history import History

JOYSTICK = DeviceKey(2, 2, 4)
LINK = Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 1))


def _joystick_sends(session) -> str:
    return N.values(session.system().device(JOYSTICK).channels[1])["data-transfer"]


def test_restore_puts_back_a_value_its_own_link_removal_turns_over():
    with open_session("sim:thesis-test1", frame_events=False) as session:
        assert session.wait_settled(20)
        assert LINK in session.system().links
        joystick = session.system().device(JOYSTICK).channels[1]
        [(param, on)] = N.writes_for(joystick, {"data-transfer": "on"})
        recorded = session.transact(Change(
            "unlink, keep sending", links=[LinkAction("remove", LINK)],
            parameters=[ParameterWrite(JOYSTICK, param, 1, on)]))
        assert recorded.written and _joystick_sends(session) == "on"
        assert session.transact(Change("link again", links=[LinkAction("add", LINK)])).written

        archive = History.open()
        try:
            entry = archive.get(recorded.history_id)
        finally:
            archive.close()
        assert entry is not None
        restore = restore_change(entry, session.system())
        assert session.transact(restore).written
        assert LINK not in session.system().links
        assert _joystick_sends(session) == "on"
