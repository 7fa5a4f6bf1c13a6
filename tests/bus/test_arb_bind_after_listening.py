"""A bind request handled after the listening time but before the dispatch loop's next claim
tick: the claim is asked first, so the answer and the set-up's requests go out with the bus
ours (once, under load, the answer was dropped and the set-up failed with "not writing to the
bus"). No threads, no bus: the dispatch thread's frame handler is fed one frame."""

from __future__ import annotations

import logging
import queue
import threading
import time
from collections.abc import Callable

import can

from pdcp_studio.bus.arbitrator.claim import BusClaim
from pdcp_studio.bus.arbitrator.common import _Node
from pdcp_studio.bus.arbitrator.dispatch import Dispatcher
from pdcp_studio.bus.arbitrator.nodes import NodeTable
from pdcp_studio.bus.arbitrator.presence import PresenceTracker
from pdcp_studio.bus.arbitrator.state import SystemState
from pdcp_studio.bus.log_limit import LimitedLog
from pdcp_studio.errors import TransportError
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.protocol import BindRequest, BindResponse, Message

KEY = DeviceKey(2, 2, 4)


class _Conn:
    def __init__(self) -> None:
        self.inbound: queue.SimpleQueue[object] = queue.SimpleQueue()


class _Profile:
    def listening(self, now: float) -> bool:
        return False  # the profile layer's own listening is over too

    def note_bind(self, now: float) -> None:
        pass

    def note_change(self, now: float, *, duty: bool = False) -> None:
        pass


class _Setup:
    def __init__(self, claim: BusClaim) -> None:
        self._claim = claim
        self.first_request_ok: list[bool] = []

    def start(self, node: _Node) -> Callable[[], None]:
        # The set-up's first request goes out as the bind answer is sent.
        return lambda: self.first_request_ok.append(self._claim.may_write)

    def cancel(self, key: DeviceKey) -> None:
        pass


def _dispatcher(claim: BusClaim, send: Callable[[Message], None], setup: _Setup,
                errors: list[tuple[str, str]]) -> Dispatcher:
    return Dispatcher(
        SystemState(), _Conn(), claim, NodeTable(1, 254), PresenceTracker(),  # type: ignore[arg-type]
        None,  # type: ignore[arg-type]  # the request engine: no response is fed here
        links=None,  # type: ignore[arg-type]  # no data channel is updated here
        setup=setup, profile=_Profile(), show_frame=None, channel_events=False,
        reset_on_claim=False, send=send, error=lambda line, kind: errors.append((kind, line)),
        flush_errors=lambda: None, crashes=LimitedLog(logging.getLogger(__name__)),
        emit=lambda event: None, wake=lambda: None, stop=threading.Event(), name="test")


def _bind_request(node_id: int) -> can.Message:
    aid, data = BindRequest(node_id, *KEY).encode()
    return can.Message(arbitration_id=aid, data=data, is_extended_id=False)


def test_a_bind_request_just_after_the_listening_time_is_answered_with_the_bus_ours() -> None:
    claim = BusClaim(time.monotonic() - 2.0, listen_s=1.1)  # over, but not ticked yet
    assert not claim.may_write
    sent: list[Message] = []
    errors: list[tuple[str, str]] = []

    def send(message: Message) -> None:  # as the arbitrator's: nothing while listening
        if not claim.may_write:
            raise TransportError("not writing to the bus (listening)")
        sent.append(message)

    setup = _Setup(claim)
    dispatcher = _dispatcher(claim, send, setup, errors)
    dispatcher._on_frame(_bind_request(1))
    assert claim.may_write and dispatcher.bus_message.endswith("PDCP Studio arbitrates")
    answers = [m for m in sent if isinstance(m, BindResponse)]
    assert len(answers) == 1 and answers[0].granted_node_id == 1
    assert setup.first_request_ok == [True]
    assert errors == []


def test_a_bind_request_while_the_bus_is_still_heard_is_not_answered() -> None:
    claim = BusClaim(time.monotonic(), listen_s=60.0)
    sent: list[Message] = []
    errors: list[tuple[str, str]] = []
    setup = _Setup(claim)
    _dispatcher(claim, sent.append, setup, errors)._on_frame(_bind_request(1))
    assert not claim.may_write and sent == [] and setup.first_request_ok == [] and errors == []
