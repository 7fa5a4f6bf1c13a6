"""What the arbitrator's parts share: the system, the lock over it, the wire lock, the ports.

The :class:`~pdcp_studio.bus.arbitrator.core.Arbitrator` makes one :class:`SystemState` and
hands it to the parts that read or change the system; the system object is replaced by a
reset, so the parts hold the state, never the system itself. The parts' own fields are
guarded by the same lock (one lock, so a decision over the node table, the system and a
part's bookkeeping is taken at once). The wire lock serializes the work that changes links
on the bus: plans, set-ups, transactions.

The ports are what a part may do outside itself, each a plain callable (as canopen's
``SdoClient`` sees only ``send_message`` and ``subscribe``).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Protocol

from pdcp_studio.bus import events as ev
from pdcp_studio.model.system import System
from pdcp_studio.protocol import Message

#: Put a frame on the bus unless the arbitrator may not write (errors are reported, not raised).
SendFrame = Callable[[Message], None]
#: Tell the subscribers an event.
Emit = Callable[[ev.Event], None]
#: Log and show a bus error: ``(message, kind)``; repeats of one kind are limited.
ReportError = Callable[[str, str], None]
#: Run a job on the set-up pool; it counts as business until it returns.
SubmitJob = Callable[[Callable[[], None]], None]


class NoteChange(Protocol):
    """Tell the profile layer of a join, leave or set-up at ``now`` (``duty``: the devices on
    the bus changed, the duty cycle is owed)."""

    def __call__(self, now: float, *, duty: bool = False) -> None: ...


class SystemState:
    """The system as the arbitrator knows it, its lock and the wire lock."""

    def __init__(self) -> None:
        self.lock = threading.RLock()  # the system and the parts' state
        self.wire_lock = threading.RLock()  # wire work on links: plans, set-ups, transactions
        self.system = System()

    def snapshot(self) -> System:
        """A copy of the system, taken under the lock."""
        with self.lock:
            return self.system.copy()

    def forget(self) -> None:
        """Under the lock: a reset; the bus is known afresh."""
        self.system = System()


__all__ = ["Emit", "NoteChange", "ReportError", "SendFrame", "SubmitJob", "SystemState"]
