"""Soak: a simulated prosthesis and its arbitrator on a cross-process bus for N minutes.

Issue 15: every role on an echoing bus (python-can ``udp_multicast`` hands each process its own
frames back) died after 4,096 distinct frames, about 77 s into a run. This runs
``pdcp-studio sim devices transradial --bus can:udp_multicast:…`` and ``pdcp-studio arbitrator``
on the same group, as two processes, for N minutes, and listens on the group itself to count
frames. It prints the frames seen, the links lost (a device that left or a link removed after
start-up: must be 0) and each process's resident memory at the start and at the end (flat:
bounded echo filter and tables). The physical bound beside the rate: a 1 Mbit/s CAN bus
carries at most ~8,000 frames/s.

Run: ``python benchmarks/soak.py MINUTES [--rate HZ]`` (default 1 minute, 50 Hz data).
"""

from __future__ import annotations

import argparse
import os
import queue
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import IO

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

GROUP = "239.74.163.15"
#: Frames a 1 Mbit/s CAN bus can carry at most, per second (8-byte frames, stuffing aside).
CAN_MAX_FPS = 8000
#: The run starts counting losses once the arbitrator has applied its start-up plan.
SETTLE_TIMEOUT_S = 60.0


def rss_kib(pid: int) -> int:
    """A process's resident set size (VmRSS) in KiB, from /proc."""
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


class Lines:
    """A child's stdout, line by line, on a thread (it must never block on a full pipe)."""

    def __init__(self, stream: IO[str] | None) -> None:
        if stream is None:
            raise ValueError("the child was started without this pipe")
        self.q: queue.SimpleQueue[str] = queue.SimpleQueue()
        self.all: list[str] = []
        threading.Thread(target=self._read, args=(stream,), daemon=True).start()

    def _read(self, stream: IO[str]) -> None:
        for line in stream:
            self.q.put(line.rstrip("\n"))

    def drain(self) -> list[str]:
        new = []
        while True:
            try:
                new.append(self.q.get_nowait())
            except queue.Empty:
                break
        self.all.extend(new)
        return new

    def until(self, predicate: Callable[[list[str]], bool], timeout: float) -> bool:
        deadline = time.monotonic() + timeout
        while not predicate(self.all):
            if time.monotonic() > deadline:
                return False
            try:
                self.all.append(self.q.get(timeout=0.2))
            except queue.Empty:
                pass
        return True


def count_frames(url: str, stop: threading.Event, counter: list[int]) -> None:
    """Listen on the group (as a monitor would) and count every frame."""
    from pdcp_studio.bus.session.urls import open_spec, parse_bus_url

    bus = open_spec(parse_bus_url(url))
    try:
        while not stop.is_set():
            if bus.recv(0.2) is not None:
                counter[0] += 1
    finally:
        bus.shutdown()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("minutes", type=float, nargs="?", default=1.0)
    parser.add_argument("--rate", type=float, default=50.0, help="data rate of the outputs")
    parser.add_argument("--port", type=int, default=43015)
    args = parser.parse_args()
    url = f"can:udp_multicast:{GROUP}?port={args.port}"
    env = dict(os.environ, PYTHONPATH=str(ROOT), PYTHONUNBUFFERED="1")
    cli = [sys.executable, "-m", "pdcp_studio"]
    memory = Path(os.environ.get("TMPDIR", "/tmp")) / f"pdcp-soak-{os.getpid()}.mem"
    arb = subprocess.Popen([*cli, "arbitrator", "--bus", url, "--memory", str(memory)],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    devices = subprocess.Popen([*cli, "sim", "devices", "transradial", "--bus", url,
                                "--rate", str(args.rate)],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                               env=env)
    arb_out, arb_err, dev_err = Lines(arb.stdout), Lines(arb.stderr), Lines(devices.stderr)
    stop = threading.Event()
    frames = [0]
    listener = threading.Thread(target=count_frames, args=(url, stop, frames), daemon=True)
    listener.start()
    try:
        if not arb_out.until(lambda ls: any(s.startswith("plan startup") for s in ls),
                             SETTLE_TIMEOUT_S):
            raise SystemExit("the arbitrator did not start up:\n" + "\n".join(arb_out.all))
        time.sleep(2.0)  # the start-up plan's links made
        arb_out.drain()
        joined = sum(s.startswith("joined ") for s in arb_out.all)
        rss0 = {"arbitrator": rss_kib(arb.pid), "devices": rss_kib(devices.pid)}
        frames0, t0 = frames[0], time.monotonic()
        print(f"soak: {joined} devices joined, links made; running {args.minutes:g} min "
              f"at {args.rate:g} Hz data on {url}", flush=True)
        end = t0 + args.minutes * 60
        next_report = t0 + 60
        stamped: list[str] = []
        while time.monotonic() < end:
            time.sleep(1.0)
            stamped += [f"{time.monotonic() - t0:6.1f} s  {s}" for s in arb_out.drain()]
            if arb.poll() is not None or devices.poll() is not None:
                break
            if time.monotonic() >= next_report:
                next_report += 60
                print(f"  {time.monotonic() - t0:5.0f} s: {frames[0] - frames0:,} frames, "
                      f"RSS arbitrator {rss_kib(arb.pid):,} KiB, devices "
                      f"{rss_kib(devices.pid):,} KiB", flush=True)
        seconds = time.monotonic() - t0
        alive = arb.poll() is None and devices.poll() is None
        rss1 = {"arbitrator": rss_kib(arb.pid) if arb.poll() is None else 0,
                "devices": rss_kib(devices.pid) if devices.poll() is None else 0}
        stamped += [f"{time.monotonic() - t0:6.1f} s  {s}" for s in arb_out.drain()]
        lost = [s for s in stamped if s.split("  ", 1)[1].startswith(("left ", "link removed "))]
        errors = [s for s in stamped if s.split("  ", 1)[1].startswith("error ")]
        n = frames[0] - frames0
        print(f"soak: {seconds:.0f} s, both processes {'alive' if alive else 'DEAD'}")
        print(f"frames: {n:,} ({n / seconds:,.0f}/s; a 1 Mbit/s CAN bus carries at most "
              f"~{CAN_MAX_FPS:,}/s)")
        print(f"links lost: {len(lost)} (must be 0)" + "".join(f"\n  {s}" for s in lost[:10]))
        print(f"arbitrator error lines: {len(errors)}"
              + "".join(f"\n  {s}" for s in errors[:5]))
        for role in ("arbitrator", "devices"):
            print(f"RSS {role}: start {rss0[role]:,} KiB, end {rss1[role]:,} KiB "
                  f"({rss1[role] - rss0[role]:+,} KiB)")
        tracebacks = [s for s in arb_err.drain() + dev_err.drain() if "Traceback" in s]
        print(f"tracebacks on stderr: {len(tracebacks)}; load average "
              f"{' '.join(f'{x:.1f}' for x in os.getloadavg())} on {os.cpu_count()} CPUs")
    finally:
        stop.set()
        for proc in (devices, arb):
            if proc.poll() is None:
                proc.send_signal(signal.SIGINT)
        for proc in (devices, arb):
            try:
                proc.wait(10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(5)
        listener.join(2)
        memory.unlink(missing_ok=True)


if __name__ == "__main__":
    main()
