"""The arbitrator answers a bind before it sets the device up (issue 11): the set-up's first
request used to overtake the Bind Device Request Response now and then; the device, not bound
yet, ignored it and the set-up waited a response timeout (0.1 s) before asking again.

Real parts: the simulated prosthesis on python-can's virtual bus, watched by a bus of its own.
"""

from __future__ import annotations

import can

from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.errors import FrameError
from pdcp_studio.protocol import BindResponse, ConfigureGetBulk, GetParameter, decode

OPENS = 6


def test_no_set_up_request_overtakes_the_bind_answer():
    for _ in range(OPENS):
        channel = unique_virtual_channel("pdcp-bind-order")
        watcher = can.Bus(interface="virtual", channel=channel)
        frames: list[can.Message] = []
        notifier = can.Notifier(watcher, [frames.append], timeout=0.02)
        try:
            with open_session("sim:transradial", channel=channel):
                pass  # (its retries are not counted here: on a loaded machine a real
                # response timeout may come; the order of the frames is what must hold)
        finally:
            notifier.stop()
            watcher.shutdown()
        bound: set[int] = set()
        asked = 0
        for frame in frames:
            try:
                message = decode(frame.arbitration_id, bytes(frame.data))
            except FrameError:
                continue
            if isinstance(message, BindResponse) and message.accepted:
                bound.add(message.granted_node_id)
            elif isinstance(message, GetParameter | ConfigureGetBulk):
                asked += 1
                assert message.node_id in bound, f"node {message.node_id} asked before bound"
        assert asked > 50 and len(bound) == 4
