"""Recording the live frames to a capture file while the trace keeps only a bounded ring.

The trace holds the newest ``capacity`` frames in memory; an afternoon on a busy bus is tens
of millions. ``LiveRecorder`` writes every frame to a python-can capture (by extension,
through the bus monitor's ``Recorder``: replaced only once complete, the node map saved
beside it) on a thread of its own, fed in batches from the window's tick; the file opens
later in the trace like any capture. Qt-free.
"""

from __future__ import annotations

import queue
import threading
from pathlib import Path
from typing import Any

_STOP = None


class LiveRecorder:
    """Writes batches of frames ``(timestamps, ids, data)`` to ``path`` on a thread.

    ``feed(frames)`` queues a batch (any iterable of ``(timestamp, arbitration_id, data)``);
    ``stop()`` finishes the file and returns the count. ``error`` holds why writing failed
    (the thread stops; frames fed later are dropped and counted in ``lost``).
    """

    def __init__(self, path: str | Path, links: dict[int, Any] | None = None) -> None:
        from pdcp_studio.bus.trace.decoder import FrameDecoder
        from pdcp_studio.bus.trace.files.recorder import Recorder

        self.path = Path(path)
        self.written = 0
        self.lost = 0
        self.error: str | None = None
        self._queue: queue.SimpleQueue[Any] = queue.SimpleQueue()
        self._recorder = Recorder(self.path, node_map=FrameDecoder(dict(links or {})).node_map)
        self._thread = threading.Thread(target=self._run, name="trace recorder", daemon=True)
        self._thread.start()

    def feed(self, frames: list[tuple[float, int, bytes]]) -> None:
        if self.error is not None:
            self.lost += len(frames)
        elif frames:
            self._queue.put(frames)

    def _run(self) -> None:
        recorder = self._recorder
        try:
            while True:
                batch = self._queue.get()
                if batch is _STOP:
                    break
                for timestamp, arbitration_id, data in batch:
                    recorder.write(arbitration_id, data, timestamp)
                self.written += len(batch)
            recorder.close()
        except Exception as err:  # a full disk, a vanished folder: say so, lose nothing else
            self.error = f"{self.path}: {err}"
            recorder.abandon()

    def stop(self, timeout: float = 30.0) -> int:
        """Write what is queued, close the file; returns the frames written."""
        self._queue.put(_STOP)
        self._thread.join(timeout)
        return self.written
