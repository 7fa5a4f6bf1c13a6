"""Raw frames for the PC's monitor, within what the serial line can carry.

A 1 Mbit/s CAN bus carries up to ~8,000 frames a second; a 128000-baud line carries 12,800
bytes. So the arbitrator passes *protocol* frames (binding, parameters, beacons…) in full, in
FRAMES events, and *channel data* only as counts per output node ID per period
(CHANNEL_COUNTS). Monitor traffic goes out only when the link has nothing else to send and
within a byte budget (``SHARE`` of the line, a token bucket); frames over the budget are
dropped and their number sent with the next FRAMES event, so the PC can say how many it missed.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from typing import TYPE_CHECKING, Any

from pdcp_studio.protocol import hostlink_messages as hm

if TYPE_CHECKING:
    from pdcp_studio.bus.arbitrator.core import Arbitrator

#: Share of the line's bytes per second the monitor may use.
SHARE = 0.5
#: Frames kept waiting for the budget; more are dropped (and counted).
BACKLOG = 256
#: Bytes of one frame record on the line (head + 8 data bytes) and a FRAMES event's overhead.
_RECORD = hm.FRAME_HEAD.size + 8
_PER_EVENT = (hm.MAX_BODY - hm.FRAMES_HEAD.size) // _RECORD


class MonitorFeed:
    """Collects frames (arbitrator threads) and hands out FRAMES / CHANNEL_COUNTS messages."""

    def __init__(self, baudrate: int) -> None:
        self.budget_bytes_s = int(SHARE * max(baudrate, 9600) / 10)
        self._lock = threading.Lock()
        self._frames: deque[hm.WireFrame] = deque()
        self._counts: dict[int, int] = {}
        self._dropped = 0
        self._on_frames = self._on_counts = False
        self._period = 1.0
        self._next_counts = 0.0
        self._tokens = 0.0
        self._last = time.monotonic()
        self._t0 = time.monotonic()

    def configure(self, frames: bool, counts: bool, period_s: float, now: float) -> None:
        with self._lock:
            self._on_frames, self._on_counts = frames, counts
            self._period = period_s
            self._next_counts = now + period_s
            self._frames.clear()
            self._counts.clear()
            self._dropped = 0
            self._tokens, self._last = 0.0, now

    def stop(self) -> None:
        self.configure(False, False, self._period, time.monotonic())

    def observe(self, event: Any, arbitrator: Arbitrator) -> None:
        """A FrameSeen from the arbitrator: queue it, or count it when it is channel data."""
        if not (self._on_frames or self._on_counts) or not hasattr(event, "arbitration_id"):
            return
        aid = event.arbitration_id
        node = aid & 0xFF
        data_frame = not aid >> 8 & 1 and node in getattr(arbitrator, "channel_node_ids", ())
        with self._lock:
            if data_frame:
                if self._on_counts:
                    self._counts[node] = self._counts.get(node, 0) + 1
            elif self._on_frames:
                if len(self._frames) >= BACKLOG:
                    self._frames.popleft()
                    self._dropped += 1
                ms = int((event.timestamp - time.time() + time.monotonic() - self._t0) * 1000)
                self._frames.append(hm.WireFrame(max(ms, 0), aid, bytes(event.data)[:8]))

    def take(self, now: float, idle: bool) -> list[bytes]:
        """Messages to send now (only when the link is ``idle``), within the budget."""
        out: list[bytes] = []
        with self._lock:
            self._tokens = min(self._tokens + (now - self._last) * self.budget_bytes_s,
                               float(self.budget_bytes_s))
            self._last = now
            if self._on_counts and now >= self._next_counts:
                ms = int(self._period * 1000)
                self._next_counts = now + self._period
                if self._counts:
                    out += hm.pack_counts(ms, self._counts)
                    self._counts = {}
            if not idle or out:
                return out
            if self._frames and self._tokens >= _RECORD * min(len(self._frames), _PER_EVENT):
                batch = [self._frames.popleft()
                         for _ in range(min(len(self._frames), _PER_EVENT))]
                message = hm.pack_frames(batch, self._dropped)
                self._dropped = 0
                self._tokens -= len(message) + 8  # + link framing
                out.append(message)
            elif self._frames and len(self._frames) >= BACKLOG:
                self._dropped += len(self._frames)
                self._frames.clear()
        return out
