"""`monitor --bus` across processes at full load (issue 16 item 4): a player sends a session at
8,000 frames/s, paced, onto python-can's udp_multicast bus on loopback; the monitor (another
process) counts every frame, exactly as many as an independent python-can counter (a third
process) and as were sent. ``benchmarks/trace.py`` runs the same rig longer and quotes CPU."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import can

from pdcp_studio.protocol import messages as M
from tests.cli.test_cli_monitor_captures import pdcp_frames

ROOT = Path(__file__).resolve().parents[2]
GROUP = "239.74.163.61"
PING_NODE = 253
#: python-can alone, with the receive buffer the monitor asks for (a datagram that does not
#: fit the kernel's buffer is dropped before either program sees it).
COUNTER = """
import can, socket, sys, time
bus = can.Bus(interface="udp_multicast", channel=sys.argv[1], port=int(sys.argv[2]))
sock = bus._multicast._socket
try:
    sock.setsockopt(socket.SOL_SOCKET, 33, 16 << 20)  # SO_RCVBUFFORCE (Linux)
except OSError:
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 16 << 20)
print("ready", flush=True)
n, last = 0, None
while True:
    m = bus.recv(0.2)
    if m is not None:
        if m.arbitration_id != int(sys.argv[3]):
            n += 1
            last = time.monotonic()
    elif last is not None and time.monotonic() - last > 2.0:
        break
bus.shutdown()
print(n)
"""


def test_monitor_counts_every_frame_a_separate_counter_counts(multicast_url):
    url = multicast_url(GROUP, 44100)
    port = int(url.rsplit("port=", 1)[1])
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    ping_id, ping_data = M.Beacon(PING_NODE).encode()
    frames = [f for f in pdcp_frames(16_000, seed=16) if f[0] & 0xFF != PING_NODE]
    counter = subprocess.Popen([sys.executable, "-c", COUNTER, GROUP, str(port), str(ping_id)],
                               stdout=subprocess.PIPE, text=True, env=env)
    monitor = subprocess.Popen(
        [sys.executable, "-m", "pdcp_studio", "monitor", "--bus", url, "--seconds", "120",
         "--filter", f"node={PING_NODE}"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env, cwd=ROOT)
    shown: list[str] = []
    reader = threading.Thread(target=lambda: shown.extend(monitor.stdout), daemon=True)
    bus = None
    try:
        assert counter.stdout.readline().strip() == "ready"
        reader.start()
        bus = can.Bus(interface="udp_multicast", channel=GROUP, port=port)
        ping = can.Message(arbitration_id=ping_id, data=ping_data, is_extended_id=False)
        deadline = time.monotonic() + 60
        while not shown and time.monotonic() < deadline:  # until the monitor listens
            bus.send(ping)
            time.sleep(0.1)
        assert shown, "the monitor never showed a ping"
        time.sleep(0.3)
        pings = len(shown)
        t0 = time.perf_counter()
        for i, (arbitration_id, data) in enumerate(frames):  # 8,000 frames/s, paced
            due = t0 + i / 8000
            while time.perf_counter() < due:
                time.sleep(0.0005)
            bus.send(can.Message(arbitration_id=arbitration_id, data=data,
                                 is_extended_id=False))
        bus.send(ping)  # the end marker: the monitor has read every frame before it
        deadline = time.monotonic() + 60
        while len(shown) == pings and time.monotonic() < deadline:
            time.sleep(0.05)
        counted = int(counter.communicate(timeout=60)[0].strip())
        monitor.send_signal(signal.SIGINT)
        err = monitor.stderr.read()
        monitor.wait(30)
    finally:
        if bus is not None:
            bus.shutdown()
        for proc in (counter, monitor):
            if proc.poll() is None:
                proc.kill()
                proc.wait()
    match = re.search(r"^(\d+) frames", err, re.MULTILINE)
    assert match, err
    seen = int(match.group(1)) - len(shown)  # the pings it showed are not the session's
    assert seen == counted == len(frames), (seen, counted, len(frames), err[-1500:])
