"""A session on PDCP Studio's own arbitrator in this process, and opening a ``can:`` bus so.

The arbitrator (bus/arbitrator/core.py) does the bus work on its own thread; the session is
its face: it passes the arbitrator's events on, follows its hold on the bus (``state``) and
reads through it. Frames are decoded for display only while someone subscribed here (a
simulated prosthesis opens with ~450 frames nobody watches yet).

On ``can:INTERFACE:CHANNEL[@BITRATE]`` PDCP Studio is the bus arbitrator: it binds the devices
it hears and runs start-up with its own memory, once it has listened and heard no other
arbitrator (reference §5); a pulled adapter is reopened (``Session.state``).
"""

from __future__ import annotations

import logging
import threading
from typing import TYPE_CHECKING, Any

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.session.base import BusSession, ProgressFn
from pdcp_studio.bus.session.urls import BusSpec
from pdcp_studio.bus.transaction import Change, Policy, TransactionResult
from pdcp_studio.errors import TransportError
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import System

if TYPE_CHECKING:
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.storage.archive.chain import Anchor

log = logging.getLogger(__name__)

#: Seconds ``open_session`` lets a real bus settle (devices binding, start-up) before returning.
CAN_SETTLE_TIMEOUT_S = 3.0
#: Least gap between two scan requests on a real adapter (its transmit queue must not fill).
CAN_SCAN_PACE_S = 0.0002

__all__ = ["ARBITRATOR_OPTIONS", "OtherArbitratorError", "Session", "arbitrator_options",
           "open_can_session"]


class Session(BusSession):
    """A live bus run by PDCP Studio's own arbitrator. Close it (or use ``with``)."""

    def __init__(self, arbitrator: Arbitrator, *, url: str = "", scan_window: int = 8,
                 scan_pace_s: float = 0.0) -> None:
        super().__init__(url)
        self.arbitrator = arbitrator
        self.scan_window = scan_window
        self.scan_pace_s = scan_pace_s
        self._unsubscribe = arbitrator.subscribe(self._on_event,
                                                 wants_frames=self._has_subscribers)
        self._state = "arbitrating"
        self._state_message = ""

    def _on_event(self, event: object) -> None:
        if isinstance(event, ev.BusState):
            self._state, self._state_message = event.state, event.message
        self._emit(event)

    @property
    def state(self) -> str:
        """The hold on the bus: ``arbitrating``, ``yielded``, ``disconnected`` (shown as
        "disconnected — reconnecting"), ``reconnected`` (see ev.BusState)."""
        return self._state

    @property
    def state_message(self) -> str:
        """The one line that said why the state is what it is ('' at first)."""
        return self._state_message

    # -- the bus ------------------------------------------------------------------------
    def system(self) -> System:
        self._check_open()
        return self.arbitrator.system()

    def wait_settled(self, timeout: float) -> bool:
        self._check_open()
        return bool(self.arbitrator.wait_settled(timeout))

    def get_parameter(self, key: DeviceKey, param: int, channel: int = 0, *,
                      timeout: float | None = None) -> bytes:
        self._check_open()
        return bytes(self.arbitrator.get_parameter(key, param, channel, timeout=timeout))

    def read_configuration(self) -> ConfigCollection:
        self._check_open()
        return self.arbitrator.read_memory()

    def read_policy(self) -> Policy:
        self._check_open()
        return self.arbitrator.read_policy()

    def read_anchor(self) -> Anchor | None:
        self._check_open()
        return self.arbitrator.read_anchor()

    def write_anchor(self, anchor: Anchor) -> Anchor | None:
        self._check_open()
        return self.arbitrator.write_anchor(anchor)

    def carry_out(self, change: Change, progress: ProgressFn | None = None,
                  cancel: threading.Event | None = None) -> TransactionResult:
        self._check_open()
        return self.arbitrator.transact(change, progress, cancel)

    def scan(self, progress: ProgressFn | None = None,
             cancel: threading.Event | None = None) -> System:
        """Read every device's parameters (bus/arbitrator/reading/scan.py); ScanCancelled when
        cancelled.

        Subscribers also get ``Progress`` events (``BusSession._reporting``)."""
        from pdcp_studio.bus.arbitrator.reading.scan import scan

        self._check_open()
        return scan(self.arbitrator, self._reporting(progress), cancel, self.scan_window,
                    pace_s=self.scan_pace_s)

    # -- shutdown -----------------------------------------------------------------------
    def _release(self) -> None:
        """Stop listening, then stop the arbitrator and release the bus."""
        try:
            self._unsubscribe()
        except Exception:
            log.debug("unsubscribe failed", exc_info=True)
        self.arbitrator.close()


#: The options of ``open_session`` that configure the in-process Arbitrator itself.
ARBITRATOR_OPTIONS = ("memory", "profile_layer", "autoconfigure", "pace_s", "response_timeout",
                      "retries", "startup_quiet_s", "duty_quiet_s", "node_ids", "frame_events",
                      "channel_events", "reset_on_start", "listen_s")


def arbitrator_options(options: dict[str, Any]) -> dict[str, Any]:
    """Take the Arbitrator's own options out of ``options``; the rest are the session's."""
    return {n: options.pop(n) for n in ARBITRATOR_OPTIONS if n in options}


class OtherArbitratorError(TransportError):
    """Another bus arbitrator is on the bus: PDCP Studio does not arbitrate there (§5)."""


def open_can_session(spec: BusSpec, *, settle_timeout: float = CAN_SETTLE_TIMEOUT_S,
                     **options: Any) -> Session:
    """PDCP Studio as the arbitrator of a python-can bus, once it has listened and heard no
    other arbitrator there (reference §5); OtherArbitratorError (one line) if it heard one."""
    from pdcp_studio.bus.arbitrator.claim import LISTEN_S
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.bus.reopen import open_reopening

    arb_opts = arbitrator_options(options)
    arb_opts.setdefault("frame_events", True)
    arb_opts.setdefault("listen_s", LISTEN_S)
    options.setdefault("scan_pace_s", CAN_SCAN_PACE_S if spec.interface != "virtual" else 0.0)
    # A pulled adapter is reopened with backoff (bus/reopen.py); the session says
    # "disconnected — reconnecting" meanwhile (ev.BusState).
    arbitrator = Arbitrator(open_reopening(spec), name=f"{spec.url} arbitrator", **arb_opts)
    try:
        session = Session(arbitrator, url=spec.url, **options)
        if not arbitrator.wait_claimed(arb_opts["listen_s"] + 2.0):
            raise OtherArbitratorError(f"{spec.url}: {arbitrator.bus_message}")
    except BaseException:
        arbitrator.close()
        raise
    if settle_timeout > 0:
        session.wait_settled(settle_timeout)  # devices may keep binding later: not an error
    return session
