"""The node map a listener infers from traffic whose set-up it never saw: a capture that
starts mid-session, or a bus joined listen-only while another arbitrator runs it.

A set-up teaches the node map exactly (bind answers, Channel Node Id and Source's Node Ids
writes: ``knowledge.py``). Without one, the traffic still tells devices from output
channels (reference §1: one node-ID pool for both):

- a **device** beacons (``0A`` from mode 0) or asks to bind (``01`` at priority 3); a node
  the arbitrator addresses (mode 1 frames carry the target device's node ID) is no channel;
- an **output channel** sends mode-0 frames, repeatedly, that are none of those, and is
  never addressed: channel data (no function code).

Channels are inferred only on a bus that shows PDCP at all (at least two beacons or a bind
request), so a foreign capture never gets a PDCP reading from this. Which device owns an
inferred channel, and which inputs listen to it, the traffic does not say: the decoder
names such a channel by its node ID ("channel node 5").

``TrafficLearner`` is pure (no python-can, no Qt): feed it frames with ``observe`` (the
CLI's replay feeds a capture's first frames, then the decoder the ones it cannot place;
the app can feed a live bus); ``devices`` and ``channels`` are what it infers now.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

#: Frames an unplaced node must send before it is taken for an output channel.
MIN_CHANNEL_FRAMES = 3
_BEACON = b"\x0a"
_BIND_PRIORITY = 3


class TrafficLearner:
    """Devices and output channels inferred from frames, with the evidence counted."""

    def __init__(self, min_frames: int = MIN_CHANNEL_FRAMES) -> None:
        self.min_frames = min_frames
        self.beacons: dict[int, int] = {}  # node → beacons sent
        self.bound: set[int] = set()  # nodes that asked to bind
        self.addressed: set[int] = set()  # nodes the arbitrator addressed
        self.other: dict[int, int] = {}  # node → mode-0 frames that are none of those
        self.total_beacons = 0

    # -- feeding ------------------------------------------------------------------------------

    def observe(self, arbitration_id: int, data: bytes) -> bool:
        """Count one classical base frame; whether what is inferred changed."""
        if arbitration_id > 0x7FF:
            return False
        node = arbitration_id & 0xFF
        if node == 0 or node == 0xFF:
            return False
        if arbitration_id & 0x100:  # from the arbitrator: the node is a device's
            if node in self.addressed:
                return False
            self.addressed.add(node)
            return self.other.get(node, 0) >= self.min_frames
        if data == _BEACON and arbitration_id >> 9 != _BIND_PRIORITY:
            self.total_beacons += 1
            count = self.beacons.get(node, 0) + 1
            self.beacons[node] = count
            # The first beacons of the bus may confirm the candidates seen so far; a node's
            # beacons may turn a candidate into a device.
            return self.total_beacons == 2 or count == self.other.get(node, 0)
        if arbitration_id >> 9 == _BIND_PRIORITY:
            if data[:1] == b"\x01" and len(data) == 7 and node not in self.bound:
                self.bound.add(node)
                return True
            return False
        count = self.other.get(node, 0) + 1
        self.other[node] = count
        return count == self.min_frames and self.evidence and self._is_channel(node, count)

    def observe_all(self, frames: Iterable[Any]) -> None:
        """``observe`` every classical data frame of ``frames`` (``can.Message`` or alike)."""
        for msg in frames:
            if not (msg.is_extended_id or msg.is_remote_frame or msg.is_error_frame
                    or getattr(msg, "is_fd", False)):
                self.observe(msg.arbitration_id, bytes(msg.data))

    # -- what is inferred ---------------------------------------------------------------------

    @property
    def evidence(self) -> bool:
        """Whether the traffic shows PDCP at all (beacons, a bind request)."""
        return self.total_beacons >= 2 or bool(self.bound)

    def _is_channel(self, node: int, count: int) -> bool:
        return (count >= self.min_frames and node not in self.addressed
                and node not in self.bound and count > self.beacons.get(node, 0))

    @property
    def channels(self) -> set[int]:
        """Node IDs taken for output channels."""
        if not self.evidence:
            return set()
        return {n for n, count in self.other.items() if self._is_channel(n, count)}

    @property
    def devices(self) -> set[int]:
        """Node IDs taken for devices: those that beacon or asked to bind. (A node the
        arbitrator addresses is no channel, but a stray frame of another bus can look
        like an address: that alone does not make a device.)"""
        if not self.evidence:
            return set()
        return (set(self.beacons) | self.bound) - self.channels

    def summary(self) -> str:
        """"4 devices, 6 channels" (what the evidence line of a summary says)."""
        devices, channels = len(self.devices), len(self.channels)
        return (f"{devices} device{'s' if devices != 1 else ''}, "
                f"{channels} channel{'s' if channels != 1 else ''}")
