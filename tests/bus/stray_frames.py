"""Every single-frame arbitrator-mode (mode 1) pattern a misbehaving device could send once
(issue 28 item 1): every function code, several node IDs (broadcast 0, 0xAC, …) and DLCs.

One frame each, so exactly one is the arbitrator beacon itself (``0x0A``, node 0, DLC 1);
the priority cycles with the pattern, as a real device's would be anything."""

from __future__ import annotations

import threading
from collections.abc import Iterator

#: Node IDs: broadcast, the first and last assignable, one of the issue's frame, the reserved.
NODE_IDS = (0x00, 0x01, 0x7F, 0xAC, 0xFE, 0xFF)
#: Data lengths (with the function code as byte 0; 0 is a frame without one).
DLCS = (0, 1, 2, 3, 8)
#: The frame that made the headless arbitrator leave the bus (bulk data, mode 1, node 0xAC).
ISSUE_FRAME = (0x3AC, b"\x0e\x00")


def single_mode_1_frames() -> Iterator[tuple[int, bytes]]:
    """(arbitration ID, data) of each pattern; ``0x3AC 0E 00`` (the issue's) first."""
    yield ISSUE_FRAME
    for node_id in NODE_IDS:
        yield (node_id + node_id % 4 * 0x200) | 0x100, b""
        for code in range(256):
            for dlc in DLCS[1:]:
                priority = (code + node_id + dlc) % 4
                data = bytes([code]) + bytes(range(dlc - 1))
                yield priority << 9 | 0x100 | node_id, data


def is_arbitrator_beacon(arbitration_id: int, data: bytes) -> bool:
    return arbitration_id & 0x1FF == 0x100 and data == b"\x0a"


def is_answer(data: bytes) -> bool:
    """An arbitrator's answer (a response code): one beacon beside it would be heard."""
    return bool(data) and bool(data[0] & 0x80)


class BeaconingArbitrator:
    """A second arbitrator on a virtual channel (or a bus given): its Device Beacon (mode 1,
    node 0) every ``interval`` seconds on a thread of its own, from :meth:`start` until
    :meth:`stop`; :meth:`close` shuts its bus down."""

    def __init__(self, channel: str | object, interval: float = 0.5) -> None:
        import can

        self.bus = can.Bus(interface="virtual", channel=channel) \
            if isinstance(channel, str) else channel
        self.interval = interval
        self.sent = 0
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def start(self) -> BeaconingArbitrator:
        self._stop.clear()
        self._thread = threading.Thread(target=self._run, daemon=True, name="other arbitrator")
        self._thread.start()
        return self

    def _run(self) -> None:
        import can

        while not self._stop.is_set():
            self.bus.send(can.Message(arbitration_id=0x100, data=b"\x0a", is_extended_id=False))
            self.sent += 1
            self._stop.wait(self.interval)

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(5.0)

    def close(self) -> None:
        self.stop()
        self.bus.shutdown()
