"""The presence tracker: who is on the bus at time ``now``, twins on one node ID, strangers.

- A bound device is gone after ``MISSED_BEACONS`` beacon intervals (and ``PRESENCE_GRACE``)
  without a frame (reference §1 Decision), measured against the frames actually received, not
  the PC's clock alone (issue 28 item 6): another part must have beaconed twice after its
  deadline, in bus time (the frames' own timestamps: a backlog handled late is still judged
  in bus time, and a simulated prosthesis starved mid-burst, sending one overdue beacon of
  another part before this one's, is not misread). When no other part beaconed — a starved
  process whose reader or devices did not run, or a bus gone quiet — it is gone only after a
  much longer silence (``SILENT_BUS_FACTOR`` × its limit, at least ``SILENT_BUS_S``) during
  which the checker itself ran without a stall. Each departure says why, in words.
- Twins bound together (one answer binds both) are caught by their echoed responses (two
  identical answers to one request) or by their doubled beacon rate.
- A node nobody bound here (an earlier arbitrator's device) that beacons is reset so that it
  binds with us, at most once every ``UNKNOWN_RESET_S``; its undecodable frames are shown once,
  and after a reset the old channel node IDs' data still in flight is only counted.

Pure: no threads, no bus. Each method takes ``now`` and what was heard and returns a decision;
the arbitrator (holding its lock) carries it out.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Literal, NamedTuple

from pdcp_studio.bus.arbitrator.common import (
    BEACON_WINDOW,
    ECHOES_FOR_TWIN,
    MISSED_BEACONS,
    PRESENCE_GRACE,
    RESET_GRACE_S,
    SILENT_BUS_FACTOR,
    SILENT_BUS_S,
    TWIN_BEACON_RATIO,
    UNKNOWN_RESET_S,
    _Node,
)
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.protocol import FunctionCode


def duplicate_message(key: DeviceKey, why: str) -> str:
    return (f"two devices with VID {key.vid}, PID {key.pid}, serial {key.serial} are on the "
            f"bus ({why}); only one can be bound")


class Gone(NamedTuple):
    """A node that left: why in words, and how long it was silent (seconds)."""

    node: _Node
    why: str
    silent_s: float


def _gone(node: _Node, seconds: float, tail: str) -> Gone:
    """Why a device is gone: "no beacon for 1.5 s, 3 beacon intervals" (and ``tail``)."""
    interval = node.beacon_interval
    intervals = int(seconds / interval) if interval > 0 else 0
    return Gone(node, f"no beacon for {seconds:.1f} s, {intervals} beacon intervals{tail}",
                seconds)


class PresenceTracker:
    """Presence, twins and strangers; ``duplicates`` are the devices reported as twins."""

    def __init__(self) -> None:
        self.duplicates: set[DeviceKey] = set()
        self.unknown_reset: dict[int, float] = {}  # stranger node ID → last Reset sent
        self.foreign_shown: set[int] = set()  # strangers whose undecodable frame was shown
        self.stale_channels: frozenset[int] = frozenset()  # channel IDs before the last reset
        self.stale_until = 0.0
        self.stale_data_frames = 0

    def absent(self, nodes: Iterable[_Node], now: float, smooth_s: float = float("inf"),
               *, by_bus: bool = True) -> list[Gone]:
        """The nodes gone at ``now``, each with why in words.

        ``smooth_s``: how long the checker has run without a stall. A node is gone when it
        has not been heard for its limit by the clock *and* either another part beaconed
        twice after its deadline in bus time (the frames' own timestamps: "the bus moved
        on"), or no other part did and its silence is long (see the module doc).
        ``by_bus=False``: by the clock alone."""
        nodes = list(nodes)
        # The two latest "beaconed twice since": a part whose previous beacon is past a
        # node's deadline beaconed twice after it. (Once is not enough: a sender starved in
        # the middle of a burst sends one overdue beacon of another part first.)
        twice = sorted(((n.prev_beacon_bus, n.node_id) for n in nodes), reverse=True)[:2]
        gone = []
        for node in nodes:
            limit = node.beacon_interval * (MISSED_BEACONS + PRESENCE_GRACE)
            wall = now - node.last_seen
            if wall <= limit:
                continue
            if not by_bus:
                gone.append(_gone(node, wall, ""))
                continue
            others = next((t for t, node_id in twice if node_id != node.node_id), None)
            if others is not None and others - node.last_bus > limit:
                gone.append(_gone(node, others - node.last_bus,
                                  " while the other parts beaconed on"))
                continue
            quiet = max(SILENT_BUS_FACTOR * limit, SILENT_BUS_S)
            if wall > quiet and smooth_s >= quiet:
                gone.append(_gone(node, wall, ", measured by the clock: no other part "
                                              "beaconed meanwhile"))
        return gone

    def beacon(self, node: _Node, now: float, caught_up: bool = True) -> str:
        """A beacon from ``node``; why it has a twin ('' when it has none, or is known).

        ``caught_up``: every frame received so far is handled. After a backlog (a flood, a
        busy machine) a second's beacons are handled in a moment, so a window is opened and
        judged only on a beacon handled caught up: the beacons counted between are then the
        ones received in that span, however late each was handled. A beacon handled behind
        others is counted but neither opens nor closes a window: twins powered together
        beacon back to back, each one's beacon queued behind the other's, and restarting the
        window on every such beacon would never let it fill."""
        if not node.set_up:
            node.window_start, node.window_beacons = None, 0
            return ""
        if node.window_start is None:
            if caught_up:
                node.window_start = now
            return ""
        node.window_beacons += 1
        span = now - node.window_start  # (longer than the window when it closes late)
        if span < BEACON_WINDOW * node.beacon_interval or not caught_up:
            return ""
        why = ""
        if (node.window_beacons > TWIN_BEACON_RATIO * span / node.beacon_interval
                and node.key not in self.duplicates):
            why = f"node {node.node_id} beacons {node.window_beacons} times in {span:.2f} s"
        node.window_start, node.window_beacons = now, 0
        return why

    def response(self, node: _Node, arbitration_id: int, data: bytes, now: float,
                 window: float) -> tuple[bool, str]:
        """A response from ``node``: (it is a second identical answer to one request, why the
        node has a twin — '' unless enough answers came twice within ``window``)."""
        code = data[0] if data else 0
        if not code & 0x80 and code != FunctionCode.BULK_DATA:
            return False, ""
        last = node.last_response
        echo = (last is not None and last[0] == arbitration_id and last[1] == data
                and node.last_request < last[2] and now - last[2] < window)
        node.last_response = None if echo else (arbitration_id, data, now)
        if echo:
            node.echoes += 1
        else:
            node.answers += 1
        twin = (node.echoes >= ECHOES_FOR_TWIN and node.echoes * 2 >= node.answers
                and node.key not in self.duplicates)
        return echo, f"node {node.node_id} answers requests twice" if twin else ""

    def claimed(self) -> None:
        """The bus is ours: the strangers' resets skipped while listening may be sent now."""
        self.unknown_reset.clear()

    def left(self, key: DeviceKey) -> None:
        """``key`` left the bus: a twin reported before may bind when it comes back."""
        self.duplicates.discard(key)

    def report(self, key: DeviceKey, why: str) -> str:
        """``key`` has a twin: remembered (never bound again while present); the line."""
        self.duplicates.add(key)
        return duplicate_message(key, why)

    def may_reset_stranger(self, node_id: int, now: float) -> bool:
        """A stranger beaconing: True when it may get a Reset now (remembered)."""
        if now - self.unknown_reset.get(node_id, -UNKNOWN_RESET_S) < UNKNOWN_RESET_S:
            return False
        self.unknown_reset[node_id] = now
        return True

    def bad_stranger_frame(self, node_id: int, now: float) -> Literal["stale", "show", "count"]:
        """An undecodable frame from a stranger: ``stale`` (data of ours from before the
        reset), ``show`` (the first from that node) or ``count``."""
        if node_id in self.stale_channels and now < self.stale_until:
            self.stale_data_frames += 1
            return "stale"
        if node_id in self.foreign_shown:
            return "count"
        self.foreign_shown.add(node_id)
        return "show"

    def forget(self, channel_ids: Iterable[int], now: float) -> None:
        """A reset: forget everyone; the old channel IDs' data is expected for a while."""
        self.stale_channels = frozenset(channel_ids)
        self.stale_until = now + RESET_GRACE_S
        self.duplicates.clear()
        self.unknown_reset.clear()
        self.foreign_shown.clear()


__all__ = ["Gone", "PresenceTracker", "duplicate_message"]
