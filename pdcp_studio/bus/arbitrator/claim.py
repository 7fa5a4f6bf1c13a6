"""One arbitrator per bus (reference §5): listen before arbitrating, step aside for another.

PDCP Studio's arbitrator on a ``can:`` bus first listens for at least two beacon intervals.
Any mode-1 frame (only an arbitrator sends those) means the bus is taken: it does not
arbitrate at all, and if one appears later it stops writing at once. Devices beaconing with
node IDs nobody here gave, while no arbitrator is heard, are a replaced arbitrator's bus
(thesis test 5): they may be reset so that they bind again. While arbitrating it beacons
(``0x0A``, mode 1, node ID 0) every beacon interval so that another arbitrator hears it.

On a bus that hands a process its own frames back (``can:udp_multicast``) every frame we
send comes back, possibly late (a loaded receiver: later than a connection's echo filter
waits). Our frames are mode-1 frames, the very thing that means "another arbitrator", and our
beacon is the same frame as any arbitrator's; so the claim keeps the account of what this
arbitrator sent (``sent``) and takes a copy heard within ``OWN_ECHO_S`` for its own, once per
frame sent (``is_own_echo``). A frame with no send of ours outstanding is someone else's; an
echo that never came masks at most one identical foreign frame.

Pure: :class:`BusClaim` takes ``now`` and the frames heard and returns decisions; the
arbitrator carries them out (tested without threads or a bus).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from pdcp_studio.bus.connection import EchoFilter
from pdcp_studio.protocol.codes import FunctionCode
from pdcp_studio.protocol.identifier import NODE_ID_MAX

#: The arbitrator's Beacon Interval (reference §5 decision: default 500 ms).
ARBITRATOR_BEACON_S = 0.5
#: Listening before arbitrating: two beacon intervals and a margin for a late beacon.
LISTEN_INTERVALS = 2.2
#: How long PDCP Studio listens on a ``can:`` bus before arbitrating.
LISTEN_S = LISTEN_INTERVALS * ARBITRATOR_BEACON_S
_BINDING_PRIORITY = 3
#: A copy of one of our own frames later than this is not waited for any more.
OWN_ECHO_S = 30.0


class Phase(enum.Enum):
    LISTENING = "listening"  # not a frame sent yet
    ARBITRATING = "arbitrating"  # the bus is ours
    YIELDED = "yielded"  # another arbitrator is on the bus: never write again


@dataclass(frozen=True)
class Decision:
    """A change of phase, with the one line that says so.

    ``takeover``: node IDs of devices heard beaconing while listening with no arbitrator on
    the bus (bound by a replaced arbitrator: reset them so they bind again); ``later``: the
    other arbitrator appeared after this one had started writing.
    """

    phase: Phase
    message: str
    takeover: tuple[int, ...] = ()
    later: bool = False


def _what(arbitration_id: int, data: bytes) -> str:
    if not data:
        return f"frame 0x{arbitration_id:03X}"
    try:
        name = FunctionCode(data[0]).label
    except ValueError:
        name = f"function 0x{data[0]:02X}"
    return f"{name} 0x{arbitration_id:03X}"


class BusClaim:
    """Whether this arbitrator may write on the bus, decided from what it hears."""

    def __init__(self, now: float, listen_s: float = LISTEN_S,
                 beacon_interval_s: float = ARBITRATOR_BEACON_S, *,
                 own_echoes: bool = False) -> None:
        self.listen_s = max(0.0, listen_s)
        self.beacon_interval_s = beacon_interval_s
        self.phase = Phase.LISTENING if self.listen_s > 0 else Phase.ARBITRATING
        self.listen_until = now + self.listen_s
        self.heard_other = ""  # what the other arbitrator sent first ('' if none)
        self._next_beacon = now if self.phase is Phase.ARBITRATING else self.listen_until
        self._beaconing: set[int] = set()
        #: What we sent, on a bus that hands it back to us (None: a bus that does not).
        self._own = EchoFilter(window_s=OWN_ECHO_S) if own_echoes else None

    def sent(self, arbitration_id: int, data: bytes, now: float) -> None:
        """We sent this frame; on a bus that echoes, its copy may come back once."""
        if self._own is not None:
            self._own.sent((arbitration_id, bytes(data)), now)

    def is_own_echo(self, arbitration_id: int, data: bytes, now: float) -> bool:
        """True (and accounted) when the frame heard is the copy of one we sent."""
        return self._own is not None and self._own.is_echo((arbitration_id, bytes(data)), now)

    @property
    def may_write(self) -> bool:
        return self.phase is Phase.ARBITRATING

    @property
    def yielded(self) -> bool:
        return self.phase is Phase.YIELDED

    def heard(self, arbitration_id: int, data: bytes, now: float) -> Decision | None:
        """A frame from the bus (never our own: ask :meth:`is_own_echo` first); a Decision
        when it changes the phase."""
        if self.phase is Phase.YIELDED:
            return None
        if arbitration_id >> 8 & 1:  # mode 1: only an arbitrator sends it
            later = self.phase is Phase.ARBITRATING
            self.phase = Phase.YIELDED
            self.heard_other = _what(arbitration_id, data)
            if later:
                text = (f"another bus arbitrator appeared on this bus ({self.heard_other}): "
                        "PDCP Studio stopped writing to it at once; one arbitrator per bus "
                        "(reference §5)")
            else:
                text = (f"another bus arbitrator is on this bus ({self.heard_other}): PDCP "
                        "Studio does not arbitrate here (no answers, resets or writes); "
                        "monitor it passively or connect through its host link")
            return Decision(Phase.YIELDED, text, later=later)
        node_id = arbitration_id & 0xFF
        if (self.phase is Phase.LISTENING and data[:1] == bytes([FunctionCode.BEACON])
                and arbitration_id >> 9 != _BINDING_PRIORITY and 0 < node_id <= NODE_ID_MAX):
            self._beaconing.add(node_id)
        return None

    def tick(self, now: float) -> Decision | None:
        """The listening time is over with no arbitrator heard: the bus is ours."""
        if self.phase is not Phase.LISTENING or now < self.listen_until:
            return None
        self.phase = Phase.ARBITRATING
        self._next_beacon = now
        takeover = tuple(sorted(self._beaconing))
        if takeover:
            text = (f"no bus arbitrator heard in {self.listen_s:g} s but {len(takeover)} "
                    "bound device(s) beaconing (a replaced arbitrator's bus): PDCP Studio "
                    "takes it over and resets them so that they bind again")
        else:
            text = f"no other bus arbitrator heard in {self.listen_s:g} s: PDCP Studio arbitrates"
        return Decision(Phase.ARBITRATING, text, takeover=takeover)

    def beacon_due(self, now: float) -> bool:
        """True when our own beacon is due (then it is scheduled one interval later)."""
        if self.phase is not Phase.ARBITRATING or now < self._next_beacon:
            return False
        step = self._next_beacon + self.beacon_interval_s
        self._next_beacon = step if step > now else now + self.beacon_interval_s
        return True
