"""The node map a listener infers from traffic whose set-up it never saw: a capture that
starts mid-session, or a bus joined listen-only while another arbitrator runs it.

A set-up teaches the node map exactly (bind answers, Channel Node Id and Source's Node Ids
writes: ``knowledge.py``). Without one, the traffic still tells devices from output
channels (reference §1: one node-ID pool for both). Each classical base frame counts for
its node ID:

- as a **device's**: a beacon (``0A`` from mode 0), a bind request (``01`` at priority 3),
  a frame from mode 0 that parses as a device's PDCP message (a response, an Update Data
  Channel), or a frame the arbitrator sends it (mode 1) that parses as a request;
- as an **output channel's**: any other frame from mode 0 — channel data has no function
  code, so it mostly parses as nothing.

A node is taken for an output channel when at least ``min_frames`` frames count for a
channel and more than three times as many as for a device (a device's occasional
module-specific frame, or a stray frame, does not make a channel, nor one sample that
happens to read like a response a device). Channels are inferred only on a bus that shows
PDCP at all (two beacons, or a bind request), so a foreign capture never gets a PDCP
reading from this. Which device owns an inferred channel, and which inputs listen to it,
the traffic does not say: the decoder names it by its node ID ("channel node 5").

``settle()`` fixes what is inferred so far: later frames only place nodes not seen before
(a decoder that skips frames it has seen, as the monitor's pump does, would otherwise
undercount a device's beacons against its other frames). ``TrafficLearner`` is pure (no
python-can, no Qt): the CLI's replay feeds a capture's first frames, settles, then the
decoder feeds the frames it cannot place; the app can feed a live bus the same way.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from pdcp_studio.errors import FrameError
from pdcp_studio.protocol import messages as M

#: Frames an unplaced node must send, as a channel's, before it is taken for one.
MIN_CHANNEL_FRAMES = 3
#: After ``settle()``: a node first heard later must send this many (a channel streams
#: at tens of frames a second; a stray frame of another bus comes once or twice).
LATE_CHANNEL_FRAMES = 16
#: A channel's frames must outnumber a device's by more than this.
DOMINANCE = 3
_BEACON = b"\x0a"
_BIND_PRIORITY = 3


def _parses(arbitration_id: int, data: bytes) -> bool:
    try:
        M.decode(arbitration_id, data)
    except FrameError:
        return False
    return True


class TrafficLearner:
    """Devices and output channels inferred from frames, with the evidence counted."""

    def __init__(self, min_frames: int = MIN_CHANNEL_FRAMES) -> None:
        self.min_frames = min_frames
        self.as_device: dict[int, int] = {}  # node → frames that count for a device
        self.as_channel: dict[int, int] = {}  # node → frames that count for a channel
        self.beacons = 0
        self.binds = 0
        self.settled: set[int] = set()  # nodes whose reading is fixed
        #: Nodes that beaconed or asked to bind: devices for sure (a stray frame of another
        #: bus can look like a request to a node, never like these).
        self.announced: set[int] = set()
        self._devices: set[int] = set()
        self._channels: set[int] = set()

    # -- feeding ------------------------------------------------------------------------------

    def observe(self, arbitration_id: int, data: bytes, parses: bool | None = None) -> bool:
        """Count one classical base frame (``parses``: whether it parses as a PDCP message,
        if the caller knows); whether what is inferred changed."""
        if arbitration_id > 0x7FF:
            return False
        node = arbitration_id & 0xFF
        if node == 0 or node == 0xFF or node in self.settled:
            return False
        if arbitration_id & 0x100:  # the arbitrator to a device
            if parses is None:
                parses = _parses(arbitration_id, data)
            return parses and self._count(self.as_device, node)
        if data == _BEACON and arbitration_id >> 9 != _BIND_PRIORITY:
            self.beacons += 1
            self.announced.add(node)
            return self._count(self.as_device, node) or self.beacons == 2
        if arbitration_id >> 9 == _BIND_PRIORITY:
            if data[:1] == b"\x01" and len(data) == 7:
                self.binds += 1
                self.announced.add(node)
                return self._count(self.as_device, node) or self.binds == 1
            return False
        if parses is None:
            parses = _parses(arbitration_id, data)
        return self._count(self.as_device if parses else self.as_channel, node)

    def _count(self, counts: dict[int, int], node: int) -> bool:
        counts[node] = counts.get(node, 0) + 1
        return self._place(node)

    def _place(self, node: int) -> bool:
        """Re-read ``node``; whether its reading changed."""
        channel = self._is_channel(node)
        device = not channel and node in self.as_device
        changed = (node in self._channels) != channel or (node in self._devices) != device
        (self._channels.add if channel else self._channels.discard)(node)
        (self._devices.add if device else self._devices.discard)(node)
        return changed and self.evidence

    def _is_channel(self, node: int) -> bool:
        count = self.as_channel.get(node, 0)
        return count >= self.min_frames and count > DOMINANCE * self.as_device.get(node, 0)

    def observe_all(self, frames: Iterable[Any]) -> None:
        """``observe`` every classical data frame of ``frames`` (``can.Message`` or alike)."""
        for msg in frames:
            if not (msg.is_extended_id or msg.is_remote_frame or msg.is_error_frame
                    or msg.is_fd):
                self.observe(msg.arbitration_id, bytes(msg.data))

    def settle(self) -> None:
        """Fix the reading of every node seen so far (see the module's docstring); nodes
        heard later need ``LATE_CHANNEL_FRAMES`` to be taken for channels."""
        self.settled.update(self.as_device, self.as_channel)
        self.min_frames = max(self.min_frames, LATE_CHANNEL_FRAMES)

    # -- what is inferred ---------------------------------------------------------------------

    @property
    def evidence(self) -> bool:
        """Whether the traffic shows PDCP at all (beacons, a bind request)."""
        return self.beacons >= 2 or self.binds > 0

    @property
    def channels(self) -> set[int]:
        """Node IDs taken for output channels."""
        return set(self._channels) if self.evidence else set()

    @property
    def devices(self) -> set[int]:
        """Node IDs taken for devices: those that announced themselves (a beacon, a bind
        request). A node the arbitrator only addresses is no channel, but is not counted
        as a device either: a stray frame can look like an address."""
        return (self.announced - self._channels) if self.evidence else set()

    def summary(self) -> str:  # pragma: no cover - the replay's words use the parts
        """"4 devices, 6 channels" (what the evidence line of a summary says)."""
        return _counted(len(self.devices), "device") + ", " + _counted(len(self.channels),
                                                                       "channel")


def _counted(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"
