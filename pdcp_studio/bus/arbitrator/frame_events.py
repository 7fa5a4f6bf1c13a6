"""Frame events: every frame heard or sent, decoded for display, in the order of the frames.

The decoder (``bus/trace/decoder.py``) learns the bus from the frames, so none may be skipped;
but decoding costs, and while no subscriber shows frames (a session opening a simulated
prosthesis nobody watches yet) the frames wait undecoded — ``FRAME_BACKLOG`` at most, then
they are decoded in a batch — and are decoded, in order, before the next one is shown.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.state import Emit

if TYPE_CHECKING:
    from pdcp_studio.bus.trace.decoder import FrameDecoder

#: At most this many frames wait undecoded while nobody wants frame events.
FRAME_BACKLOG = 1024


class FrameFeed:
    """The frame decoder, the frames waiting for it and who wants frames now (the gates)."""

    def __init__(self, emit: Emit) -> None:
        self._emit = emit
        self._lock = threading.Lock()
        self.decoder: FrameDecoder | None = None  # made when a frame is first shown
        self.unshown: list[tuple[int, bytes, float]] = []
        self.gates: list[Callable[[], bool]] = []

    def watch(self, gate: Callable[[], bool]) -> Callable[[], None]:
        """A subscriber shows frames while ``gate()``; returns what ends that (idempotent)."""
        with self._lock:
            self.gates.append(gate)

        def unwatch() -> None:
            with self._lock:
                if gate in self.gates:
                    self.gates.remove(gate)

        return unwatch

    def frame(self, arbitration_id: int, data: bytes, timestamp: float) -> None:
        """A FrameSeen event for a frame heard or sent; or, while nobody wants frame events,
        the frame kept to be decoded later."""
        with self._lock:
            if not any(gate() for gate in self.gates):
                self.unshown.append((arbitration_id, bytes(data), timestamp))
                if len(self.unshown) < FRAME_BACKLOG:
                    return
                self._catch_up()  # memory stays bounded; the work is the same
                return
            decoder = self._catch_up()
            line = decoder.decode(arbitration_id, data, timestamp).line
        self._emit(ev.FrameSeen(timestamp, arbitration_id, bytes(data), line))

    def _catch_up(self) -> FrameDecoder:
        """Under the lock: the decoder, made if need be, learns the waiting frames."""
        if self.decoder is None:
            from pdcp_studio.bus.trace.decoder import FrameDecoder

            self.decoder = FrameDecoder()
        frames, self.unshown = self.unshown, []
        for arbitration_id, data, timestamp in frames:
            self.decoder.decode(arbitration_id, data, timestamp)
        return self.decoder


__all__ = ["FRAME_BACKLOG", "FrameFeed"]
