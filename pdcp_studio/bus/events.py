"""Events a live bus session reports to its subscribers (the desktop app, the CLI, tests).

Plain frozen dataclasses so a subscriber on any thread can keep them; they carry model values
(keys, links, plans), never python-can objects, so the app needs no python-can import. Their
equality, hash and repr are the protocol's :class:`~pdcp_studio.protocol.records.Record`'s
(the same as ``dataclass(frozen=True)`` generates, made once rather than per class).
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.protocol.records import Record

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False, repr=False)
class DeviceJoined(Record):
    """A device bound and was set up (its channels are known)."""

    key: DeviceKey


@dataclass(frozen=True, eq=False, repr=False)
class DeviceLeft(Record):
    """A device stopped beaconing (3 missed intervals) or was unplugged.

    ``why``: the arbitrator's words ("no beacon for 1.5 s, 3 beacon intervals …"; empty when
    a transport does not say); ``silent_s`` and ``interval_s``: how long it was not heard and
    its beacon interval, for a window's own words (0 when unknown). Not compared."""

    key: DeviceKey
    why: str = field(default="", compare=False, kw_only=True)
    silent_s: float = field(default=0.0, compare=False, kw_only=True)
    interval_s: float = field(default=0.0, compare=False, kw_only=True)


@dataclass(frozen=True, eq=False, repr=False)
class DeviceReplaced(DeviceLeft):
    """An absent device (``key``) is replaced by ``new``: a verified transaction left a present
    device in every role it had, so the arbitrator forgets it (it is no longer missing).

    A :class:`DeviceLeft` for good: a subscriber or transport that knows only that (the host
    link) still learns the device is gone from the arbitrator's system."""

    new: DeviceKey


@dataclass(frozen=True, eq=False, repr=False)
class LinkMade(Record):
    link: Link


@dataclass(frozen=True, eq=False, repr=False)
class LinkRemoved(Record):
    link: Link


@dataclass(frozen=True, eq=False, repr=False)
class FrameSeen(Record):
    """One CAN frame, sent or received, decoded to a readable ``text``."""

    timestamp: float
    arbitration_id: int
    data: bytes
    text: str


@dataclass(frozen=True, eq=False, repr=False)
class BusError(Record):
    """Something went wrong that did not stop the session (a bad frame, a timeout, …).

    ``kind`` names the fault for programs: ``bad_frame``, ``error_frame``,
    ``duplicate_device``, ``node_ids_exhausted``, ``setup``, ``plan``, ``transport``,
    ``other_arbitrator`` (empty when unclassified).
    """

    message: str
    kind: str = ""


@dataclass(frozen=True, eq=False, repr=False)
class BusState(Record):
    """The session's hold on the bus changed; ``message`` is the one line that says so.

    ``state`` is one of :data:`BUS_STATES`: ``listening`` (a ``can:`` bus is heard before
    arbitrating), ``arbitrating`` (PDCP Studio is the bus arbitrator), ``yielded`` (another
    arbitrator is on the bus: PDCP Studio writes nothing), ``disconnected`` (the adapter went
    away: "disconnected — reconnecting"), ``reconnected`` (it is back; presence and links
    are being re-read).
    """

    state: str
    message: str


#: The states a BusState event reports.
BUS_STATES = ("listening", "arbitrating", "yielded", "disconnected", "reconnected")
#: How the CLI shows each state (the app translates its own words for them).
BUS_STATE_TEXT = {"listening": "listening for another arbitrator",
                  "arbitrating": "arbitrating", "yielded": "another arbitrator: not writing",
                  "disconnected": "disconnected — reconnecting", "reconnected": "reconnected"}


@dataclass(frozen=True, eq=False, repr=False)
class PlanApplied(Record):
    """The arbitrator applied a profile-layer plan (start-up, duty cycle or by request).

    ``own``: the arbitrator changed the prosthesis on its own (start-up, the duty cycle), not
    because someone asked; ``result``: the ``TransactionResult`` (bus/transaction.py) — whom
    the motion interlock held (``held``), whether the links read back as written
    (``verified``), notes. Each action of the plan carries its reason. Not compared."""

    plan: Any
    own: bool = field(default=False, compare=False, kw_only=True)
    result: Any = field(default=None, compare=False, kw_only=True)


@dataclass(frozen=True, eq=False, repr=False)
class TerminalsUnconnected(Record):
    """Start-up or the duty cycle left terminal channels unconnected because the
    prosthesis's policy has autoconfigure off (issue 17); ``why`` says so in words."""

    refs: tuple[ChannelRef, ...]
    why: str


@dataclass(frozen=True, eq=False, repr=False)
class TransactionDone(Record):
    """A change of the change road finished (applied, failed or rolled back): ``result`` is
    the ``TransactionResult`` (bus/transaction.py)."""

    result: Any


@dataclass(frozen=True, eq=False, repr=False)
class ChannelValue(Record):
    """A data frame on a link: the output ``ref`` sent ``value``, in its type's own numbers
    (``bus/sim/signals.decode_raw``: an unsigned 12-bit envelope reads 0–4095)."""

    ref: ChannelRef
    value: float
    timestamp: float


@dataclass(frozen=True, eq=False, repr=False)
class Progress(Record):
    """``done`` of ``total`` steps of a long job (a scan, a plan) finished."""

    done: int
    total: int
    what: str


Event = (
    DeviceJoined | DeviceLeft | LinkMade | LinkRemoved | FrameSeen | BusError | PlanApplied
    | ChannelValue | Progress | TerminalsUnconnected | TransactionDone | BusState
)


class Subscribers:
    """Thread-safe fan-out of events to callbacks (arbitrator, sessions, host link).

    A callback runs on the emitting thread and must not block; one that raises is logged and
    the others still get the event, so a subscriber's bug never stops a bus thread.
    """

    def __init__(self, owner: str) -> None:
        self.owner = owner
        self._callbacks: list[Callable[[Any], None]] = []
        self._lock = threading.Lock()

    def __len__(self) -> int:
        return len(self._callbacks)

    def add(self, callback: Callable[[Any], None]) -> Callable[[], None]:
        """Register ``callback``; returns the function that unregisters it (idempotent)."""
        with self._lock:
            self._callbacks.append(callback)

        def remove() -> None:
            with self._lock:
                if callback in self._callbacks:
                    self._callbacks.remove(callback)

        return remove

    def emit(self, event: Any) -> None:
        with self._lock:
            callbacks = list(self._callbacks)
        for callback in callbacks:
            try:
                callback(event)
            except Exception:
                log.exception("%s: a subscriber failed on %s", self.owner, type(event).__name__)
