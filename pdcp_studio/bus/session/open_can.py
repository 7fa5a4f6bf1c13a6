"""Opening a ``can:`` bus: PDCP Studio as the arbitrator of a python-can bus.

PDCP Studio binds the devices it hears and runs start-up with its own memory, once it has
listened and heard no other arbitrator (reference §5); a pulled adapter is reopened
(``Session.state``).
"""

from __future__ import annotations

from typing import Any

from pdcp_studio.bus.session.in_process import Session, arbitrator_options
from pdcp_studio.bus.session.urls import BusSpec
from pdcp_studio.errors import TransportError

#: Seconds ``open_session`` lets a real bus settle (devices binding, start-up) before returning.
CAN_SETTLE_TIMEOUT_S = 3.0
#: Least gap between two scan requests on a real adapter (its transmit queue must not fill).
CAN_SCAN_PACE_S = 0.0002

__all__ = ["CAN_SCAN_PACE_S", "CAN_SETTLE_TIMEOUT_S", "OtherArbitratorError",
           "open_can_session"]


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
