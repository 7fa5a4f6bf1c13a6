"""Benchmark: one change-road transaction (reference §5) and the fitting history.

For ``sim:thesis-test2`` and ``sim:transradial`` it alternates ``clear`` and ``autoconfigure``
transactions (interlock, write, read back, release; not recorded) and prints:

- wall time per transaction on the in-process virtual bus (median and best);
- the frames one transaction puts on the bus and their time on a real 1 Mbit/s bus
  (bus/trace/bustime.py, the frames' own stuff bits) — the physical floor of the same exchange,
  since every request waits for its response;

then the fitting history: milliseconds per append (WAL, synchronous=FULL: one fsync'd commit
each, the floor is the disk's sync time) and per verified entry. Run:
``python benchmarks/transaction.py [--repeat N]``.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import threading
import time
from pathlib import Path

import can

from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.bus.trace.bustime import BusTimeMeter
from pdcp_studio.bus.transaction import Change
from pdcp_studio.storage.history import History


class Tap:
    """Counts the frames on a virtual channel while ``on`` is set."""

    def __init__(self, channel: str) -> None:
        self.bus = can.Bus(interface="virtual", channel=channel)
        self.on = threading.Event()
        self.frames: list[can.Message] = []
        self._notifier = can.Notifier(self.bus, [self._seen])

    def _seen(self, msg: can.Message) -> None:
        if self.on.is_set():
            self.frames.append(msg)

    def close(self) -> None:
        self._notifier.stop()
        self.bus.shutdown()


def bench_transactions(name: str, repeat: int) -> None:
    channel = unique_virtual_channel("bench-tx")
    tap = Tap(channel)
    session = open_session(f"sim:{name}", channel=channel, data_rate_hz=0)
    try:
        walls: list[float] = []
        per_tx_frames: list[int] = []
        per_tx_us: list[float] = []
        for n in range(repeat):
            mode = "clear" if n % 2 == 0 else "autoconfigure"
            change = Change.from_plan(session.preview(mode))
            tap.frames.clear()
            tap.on.set()
            t0 = time.perf_counter()
            result = session.carry_out(change)
            walls.append((time.perf_counter() - t0) * 1000)
            time.sleep(0.02)
            tap.on.clear()
            if not result.written:
                sys.exit(f"{name}: {result.summary()}")
            meter = BusTimeMeter()
            for f in tap.frames:
                if f.arbitration_id >> 9 != 3:  # not channel data (priority 3)
                    meter.add(f.arbitration_id, bytes(f.data))
            per_tx_frames.append(meter.frames)
            per_tx_us.append(meter.bus_time_us)
        print(f"{name}: {len(change.links)} link actions per transaction")
        print(f"  wall per transaction (virtual bus): median {statistics.median(walls):.1f} ms, "
              f"best {min(walls):.1f} ms")
        print(f"  frames per transaction: median {statistics.median(per_tx_frames):.0f}; "
              f"their time on a 1 Mbit/s bus: {statistics.median(per_tx_us) / 1000:.2f} ms "
              "(physical floor of the same exchange)")
    finally:
        session.close()
        tap.close()


def bench_history(entries: int) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "h.sqlite3"
        with History(path) as h:
            body = {"time": "2026-11-23T10:00:00Z", "operator": "bench", "bus": "sim:x",
                    "action": "apply clear", "devices": [{"vid": 2, "pid": 2, "serial": 5}],
                    "links_before": [], "links_after": [], "config_crc_before": None,
                    "config_crc_after": None, "verified": True, "interlock": "held 1 device"}
            t0 = time.perf_counter()
            for _ in range(entries):
                h.append(body)
            append_ms = (time.perf_counter() - t0) * 1000 / entries
            t0 = time.perf_counter()
            assert h.verify().ok
            verify_ms = (time.perf_counter() - t0) * 1000
    print(f"history: {append_ms:.2f} ms per append (one fsync'd WAL commit each); "
          f"verify of {entries} entries {verify_ms:.1f} ms "
          f"({verify_ms * 1000 / entries:.0f} µs per entry)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=20)
    args = parser.parse_args()
    for name in ("thesis-test2", "transradial"):
        bench_transactions(name, args.repeat)
    bench_history(200)


if __name__ == "__main__":
    main()
