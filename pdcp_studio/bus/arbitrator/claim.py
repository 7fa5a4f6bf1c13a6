"""One arbitrator per bus (reference §5): listen before arbitrating, step aside for another —
known by its beacons, never by one frame.

PDCP Studio's arbitrator on a ``can:`` bus first listens for at least two beacon intervals.
Another arbitrator is *heard* when its beacons are (reference §5, Decision revised): at least
``HEAR_BEACONS`` mode-1 Device Beacons with node ID 0 within ``HEAR_WINDOW_INTERVALS`` beacon
intervals, or one such beacon together with an answer to a request this arbitrator did not
send (a device's response with no request of ours to it outstanding, or a mode-1 response —
a bind or update answer — that is not ours). Any other single mode-1 frame is a *stray*
frame: the dispatcher logs it (rate-limited) and ignores it, since one misbehaving device
could otherwise take the prosthesis's arbitrator away.

Heard while listening, the other arbitrator keeps this one off the bus (no answers, resets
or writes). Heard later, this one stops writing at once; with ``take_back`` (the headless
arbitrator, which stays up and serves its host link read-only) it takes the bus back when
the other's beacons have been gone for ``TAKE_BACK_INTERVALS`` beacon intervals and a random
wait of up to as many again (two arbitrators on buses joined, each stepping aside for the
other, must not take the bus back together for ever), judged only while every frame received
so far is handled (a starved process must not mistake its own
backlog for silence). Devices beaconing with node IDs nobody here gave, while no arbitrator
is heard, are a replaced arbitrator's bus (thesis test 5): they may be reset so that they
bind again. While arbitrating it beacons (``0x0A``, mode 1, node ID 0) every beacon interval
so that another arbitrator hears it.

On a bus that hands a process its own frames back (``can:udp_multicast``) every frame we
send comes back, possibly late (a loaded receiver: later than a connection's echo filter
waits). Our beacon is the same frame as any arbitrator's; so the claim keeps the account of
what this arbitrator sent (``sent``) and takes a copy heard within ``OWN_ECHO_S`` for its own,
once per frame sent (``is_own_echo``). A frame with no send of ours outstanding is someone
else's; an echo that never came masks at most one identical foreign frame.

Pure: :class:`BusClaim` takes ``now`` and the frames heard and returns decisions; the
arbitrator carries them out (tested without threads or a bus).
"""

from __future__ import annotations

import collections
import enum
import random
from collections.abc import Callable
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
#: Another arbitrator is heard: this many of its beacons …
HEAR_BEACONS = 2
#: … within this many beacon intervals (or one beacon and a foreign answer within them).
HEAR_WINDOW_INTERVALS = 3
#: The bus is taken back when the other's beacons have been gone this many intervals …
TAKE_BACK_INTERVALS = 5
#: … plus a random part of as many again: two arbitrators that heard each other (two buses
#: joined) and both stepped aside must not both take the bus back at the same moment, forever.
TAKE_BACK_JITTER = 1.0
#: A device's answer is ours when we sent that device (or everyone) a request this recently
#: (by when it was handled: generous, so a backlog on a busy PC is not taken for strangers').
OUR_REQUEST_S = 10.0
_BINDING_PRIORITY = 3
#: A copy of one of our own frames later than this is not waited for any more.
OWN_ECHO_S = 30.0
#: Device node IDs remembered as beaconing (a channel's data is no device's answer).
_BEACONING_FOR_S = 10.0


class Phase(enum.Enum):
    LISTENING = "listening"  # not a frame sent yet
    ARBITRATING = "arbitrating"  # the bus is ours
    YIELDED = "yielded"  # another arbitrator is on the bus: nothing written


@dataclass(frozen=True)
class Decision:
    """A change of phase, with the one line that says so.

    ``takeover``: node IDs of devices heard beaconing while listening with no arbitrator on
    the bus (bound by a replaced arbitrator: reset them so they bind again); ``later``: the
    other arbitrator appeared after this one had started writing; ``taken_back``: the bus is
    ours again after the other's beacons were gone long enough.
    """

    phase: Phase
    message: str
    takeover: tuple[int, ...] = ()
    later: bool = False
    taken_back: bool = False


@dataclass(frozen=True)
class Stray:
    """A mode-1 frame that is not (yet) another arbitrator: logged, then ignored."""

    message: str


def _what(arbitration_id: int, data: bytes) -> str:
    if not data:
        return f"frame 0x{arbitration_id:03X}"
    try:
        name = FunctionCode(data[0]).label
    except ValueError:
        name = f"function 0x{data[0]:02X}"
    return f"{name} 0x{arbitration_id:03X}"


def _is_arbitrator_beacon(arbitration_id: int, data: bytes) -> bool:
    """A Device Beacon an arbitrator sends: mode 1, node ID 0, DLC 1 (reference §5)."""
    return arbitration_id & 0x1FF == 0x100 and bytes(data) == bytes([FunctionCode.BEACON])


class BusClaim:
    """Whether this arbitrator may write on the bus, decided from what it hears."""

    def __init__(self, now: float, listen_s: float = LISTEN_S,
                 beacon_interval_s: float = ARBITRATOR_BEACON_S, *,
                 own_echoes: bool = False, take_back: bool = False,
                 jitter: Callable[[], float] = random.random) -> None:
        self.listen_s = max(0.0, listen_s)
        self._jitter = jitter  # 0…1: where in its random part a take-back falls
        #: How long the other's beacons must be gone, chosen when this one stepped aside.
        self.take_back_wait_s = 0.0
        self.beacon_interval_s = beacon_interval_s
        self.take_back = take_back
        self.phase = Phase.LISTENING if self.listen_s > 0 else Phase.ARBITRATING
        self.listen_until = now + self.listen_s
        self.heard_other = ""  # what the other arbitrator sent first ('' if none)
        self.later = False  # the other arbitrator was heard after we had started writing
        self.strays = 0  # stray mode-1 frames heard (each ignored)
        self._next_beacon = now if self.phase is Phase.ARBITRATING else self.listen_until
        self._beaconing: set[int] = set()  # strangers heard while listening (takeover)
        self._devices: dict[int, float] = {}  # device node ID → its last beacon
        self._asked: dict[int, float] = {}  # node ID (0: everyone) → our last request to it
        self._other_beacons: collections.deque[float] = collections.deque(maxlen=HEAR_BEACONS)
        self._foreign_answer = float("-inf")  # the last answer to a request not ours
        self.last_other_beacon = float("-inf")
        self._lone_beacon: float | None = None  # a beacon whose second has not come yet
        #: What we sent, on a bus that hands it back to us (None: a bus that does not).
        self._own = EchoFilter(window_s=OWN_ECHO_S) if own_echoes else None

    @property
    def hear_window_s(self) -> float:
        return HEAR_WINDOW_INTERVALS * self.beacon_interval_s

    @property
    def take_back_s(self) -> float:
        """How long the other's beacons must be gone before the bus is taken back."""
        return TAKE_BACK_INTERVALS * self.beacon_interval_s

    def sent(self, arbitration_id: int, data: bytes, now: float) -> None:
        """We sent this frame: a request's answer is ours for a while; on a bus that echoes,
        its copy may come back once."""
        code = data[0] if data else FunctionCode.BEACON
        if arbitration_id >> 8 & 1 and not code & 0x80 and code != FunctionCode.BEACON:
            self._asked[arbitration_id & 0xFF] = now
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

    @property
    def listening(self) -> bool:
        """Still deciding whether another arbitrator holds the bus."""
        return self.phase is Phase.LISTENING

    def heard(self, arbitration_id: int, data: bytes, now: float,
              bus_time: float | None = None) -> Decision | Stray | None:
        """A frame from the bus (never our own: ask :meth:`is_own_echo` first), handled at
        ``now`` and stamped ``bus_time`` by the bus: a Decision when another arbitrator is
        heard now, a :class:`Stray` for a mode-1 frame that does not make one, else None.

        Which frames are "within three beacon intervals" of each other is judged by their bus
        times (a backlog handled late must not crowd two lone beacons together); when the
        other's beacons stopped, by when they were handled (``now``: taking the bus back
        waits for a backlog to be handled)."""
        data = bytes(data)
        at = now if bus_time is None else bus_time
        node_id = arbitration_id & 0xFF
        code = data[0] if data else -1
        if arbitration_id >> 8 & 1:  # mode 1: an arbitrator's frame, or a stray one
            if _is_arbitrator_beacon(arbitration_id, data):
                self._other_beacons.append(at)
                self.last_other_beacon = now
            elif self.phase is Phase.YIELDED:
                return None  # the other arbitrator at work: nothing of ours
            elif code >= 0 and code & 0x80:  # an arbitrator's answer to a device: not ours
                self._foreign_answer = at
            else:
                return self._stray(arbitration_id, data)
            return self._judge(arbitration_id, data, at, now)
        if code == FunctionCode.BEACON and arbitration_id >> 9 != _BINDING_PRIORITY \
                and 0 < node_id <= NODE_ID_MAX:
            self._devices[node_id] = now
            if self.phase is Phase.LISTENING:
                self._beaconing.add(node_id)
        elif code >= 0 and code & 0x80 and self._foreign_device_answer(node_id, now):
            self._foreign_answer = at  # evidence beside a beacon; alone it is nothing
            decision = self._judge(arbitration_id, data, at, now)
            return decision if isinstance(decision, Decision) else None
        return None

    def _foreign_device_answer(self, node_id: int, now: float) -> bool:
        """A response from a device (a node that beacons) none of our requests asked for."""
        beaconed = self._devices.get(node_id)
        if beaconed is None or now - beaconed > _BEACONING_FOR_S:
            return False
        asked = max(self._asked.get(node_id, float("-inf")), self._asked.get(0, float("-inf")))
        return now - asked > OUR_REQUEST_S

    def _stray(self, arbitration_id: int, data: bytes) -> Stray:
        self.strays += 1
        what = _what(arbitration_id, data).rsplit(" ", 1)[0]
        return Stray(f"a stray arbitrator-mode frame 0x{arbitration_id:03X} "
                     f"[{data.hex(' ').upper()}] ({what}) ignored: "
                     "another arbitrator is known by its beacons, never by one frame "
                     "(reference §5)")

    def _judge(self, arbitration_id: int, data: bytes, at: float, now: float
               ) -> Decision | Stray | None:
        """Another arbitrator's frame (bus time ``at``, handled at ``now``): is it heard now
        (its beacons, reference §5)?"""
        window = self.hear_window_s
        beacons = [t for t in self._other_beacons if abs(at - t) <= window]
        heard = len(beacons) >= HEAR_BEACONS or (
            bool(beacons) and abs(at - self._foreign_answer) <= window)
        if self.phase is Phase.YIELDED:
            return None  # (said once; its beacons keep the bus from being taken back)
        if not heard:  # one frame: not (yet) another arbitrator
            if _is_arbitrator_beacon(arbitration_id, data):
                if self._lone_beacon is None:  # a stray if no second one comes in time
                    self._lone_beacon = now
                return None
            return self._stray(arbitration_id, data)
        self._lone_beacon = None
        later = self.phase is Phase.ARBITRATING
        self.phase = Phase.YIELDED
        self.later = later
        self.heard_other = _what(arbitration_id, data)
        why = (f"its beacons heard: {len(beacons)} within {window:g} s"
               if len(beacons) >= HEAR_BEACONS else
               "its beacon and an answer to a request PDCP Studio did not send")
        if later and self.take_back:
            jitter = min(max(self._jitter(), 0.0), 1.0)
            self.take_back_wait_s = self.take_back_s * (1.0 + TAKE_BACK_JITTER * jitter)
            text = (f"another bus arbitrator appeared on this bus ({why}): PDCP Studio stopped "
                    "writing to it at once and serves its host link read-only; it takes the "
                    f"bus back when the other's beacons have been gone for {self.take_back_s:g} "
                    f"s ({TAKE_BACK_INTERVALS} beacon intervals) and a random "
                    f"{self.take_back_wait_s - self.take_back_s:.1f} s more "
                    f"({self.take_back_wait_s:.1f} s; reference §5)")
        elif later:
            text = (f"another bus arbitrator appeared on this bus ({why}): PDCP Studio "
                    "stopped writing to it at once; one arbitrator per bus (reference §5)")
        else:
            text = (f"another bus arbitrator is on this bus ({why}): PDCP Studio does not "
                    "arbitrate here (no answers, resets or writes); monitor it passively or "
                    "connect through its host link")
        return Decision(Phase.YIELDED, text, later=later)

    def lone_beacon(self, now: float) -> Stray | None:
        """A beacon heard alone — no second within three beacon intervals, nor an answer
        beside it — is a stray frame too (told once its window has passed)."""
        since = self._lone_beacon
        if since is None or now - since <= self.hear_window_s:
            return None
        self._lone_beacon = None
        if self.phase is Phase.YIELDED:
            return None
        return self._stray(0x100, bytes([FunctionCode.BEACON]))

    def tick(self, now: float, caught_up: bool = True) -> Decision | None:
        """The listening time is over with no arbitrator heard: the bus is ours. With
        ``take_back``, after a later yield: the other's beacons have been gone long enough
        (judged only ``caught_up``: every frame received so far handled)."""
        if self.phase is Phase.YIELDED:
            return self._take_back(now) if caught_up else None
        if self.phase is not Phase.LISTENING or now < self.listen_until:
            return None
        if now - self.last_other_beacon <= self.hear_window_s:
            return None  # one beacon heard: listen on until its second is due, or overdue
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

    def _take_back(self, now: float) -> Decision | None:
        if not (self.take_back and self.later) \
                or now - self.last_other_beacon < self.take_back_wait_s:
            return None
        self.phase = Phase.ARBITRATING
        self._next_beacon = now
        self._other_beacons.clear()
        gone = now - self.last_other_beacon
        text = (f"the other bus arbitrator's beacons have been gone for {gone:.1f} s (at least "
                f"{TAKE_BACK_INTERVALS} beacon intervals, {self.take_back_s:g} s, and the "
                "random wait chosen when it appeared): PDCP Studio takes the bus back and "
                "writes again (reference §5)")
        return Decision(Phase.ARBITRATING, text, taken_back=True)

    def beacon_due(self, now: float) -> bool:
        """True when our own beacon is due (then it is scheduled one interval later)."""
        if self.phase is not Phase.ARBITRATING or now < self._next_beacon:
            return False
        step = self._next_beacon + self.beacon_interval_s
        self._next_beacon = step if step > now else now + self.beacon_interval_s
        return True
