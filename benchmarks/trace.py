"""The trace against a saturated bus (issue 16): replay speed and memory on a large capture.

Generates (once, cached in the temp folder) a capture of mixed PDCP traffic — binding and
set-up of a known node map (Channel Node Id, Source's Node Ids), parameter reads, beacons,
channel data of every output, and some garbage (module-specific codes, extended identifiers,
random bytes) — at about 8,000 frames/s of capture time, in ASC and BLF. Prints for each format:

- python-can's reader alone (``can.LogReader`` over the file, nothing else): the anchor;
- for BLF also the monitor's own reader alone (``bus/trace/files/blf.py``: python-can's BLFReader
  with a faster loop over a container's objects, the same frames without a ``can.Message``
  each), which ``monitor --replay`` uses;
- ``pdcp-studio monitor --replay FILE`` (frames to /dev/null, its summary shown);
- the same with a filter that matches nothing, and with ``--json`` to /dev/null;

each with wall and CPU time, frames per second (and how many saturated buses that is), the
ratio to python-can's reader alone (target ≤ 2×) and peak RSS (target < 150 MB, whatever the
length). The bus time the monitor reports must equal the
exact figure computed here bit by bit (bus/trace/bustime.py's plain bit-stream path). The bus bound:
a 1 Mbit/s CAN bus carries at most ~8,000 8-byte (≈ 11,000 4-byte) frames a second.

Live (``--live-seconds``, 10 by default): the same traffic played at its original rate onto a
cross-process bus (python-can's udp_multicast on loopback, paced), counted by ``monitor --bus``
and by an independent python-can counter in a third process; prints both counts, the frames
sent, and the monitor's CPU while the traffic ran as a share of one core (target ≤ 30 %).

Three captures (``--kinds``): ``mixed`` (the above, with its set-up, ``--frames``),
``midsession`` (the same session recorded by another tool after its set-up: no bind, no
Channel Node Id write, no node map beside it, so the decoder infers the node map from the
traffic; ≤ 1 % undecodable) and ``foreign`` (a car's bus with extended identifiers: the
verdict must be not-pdcp), the last two of ``--other-frames`` (400,000).

Run: ``python benchmarks/trace.py [--frames N] [--formats asc,blf] [--kinds K,…] [--live-seconds S]``
(``--formats ""`` for the live case alone, ``--live-seconds 0`` to skip it).
"""

from __future__ import annotations

import argparse
import os
import random
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import IO

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

FRAMES = 1_000_000
RATE_HZ = 8_000  # capture time: about a saturated 1 Mbit/s bus
TARGET_RATIO = 2.0
TARGET_RSS_MB = 150
#: Frames per second a 1 Mbit/s bus carries at most, 8-byte frames (worst-case stuffing).
BUS_BOUND_8 = 1_000_000 // 135
BUS_BOUND_4 = 1_000_000 // 95


#: (node, vid, pid, serial, outputs) of a device; (channel node, device node, channel index,
#: listener device node, listener channel) of an output.
DeviceRow = tuple[int, int, int, int, int]
OutputRow = tuple[int, int, int, int, int]
#: (arbitration_id, data, is_extended) of a frame.
Frame = tuple[int, bytes, bool]


def node_map() -> tuple[list[DeviceRow], list[OutputRow]]:
    """Eight devices, each with one or two outputs; every output feeds one input elsewhere.

    Returns (devices, outputs): devices = [(node, vid, pid, serial, n_outputs)], outputs =
    [(channel node, device node, channel index, listener device node, listener channel)].
    """
    devices: list[DeviceRow] = []
    outputs: list[OutputRow] = []
    next_channel_node = 100
    for k in range(8):
        devices.append((10 + k, 0x0A0 + k, 0x10 + k % 3, 1000 + k, 1 + k % 2))
    for node, _vid, _pid, _sn, n_out in devices:
        for index in range(1, n_out + 1):
            listener = devices[(node - 10 + 1) % len(devices)][0]
            outputs.append((next_channel_node, node, index, listener, 10 + index))
            next_channel_node += 1
    return devices, outputs


#: Frames of the last ``traffic()`` made undecodable on purpose (module-specific codes, random
#: base frames, extended identifiers): what a replay may call undecodable.
GARBAGE = [0]


def traffic(n: int, seed: int = 16, setup_frames: bool = True) -> list[Frame]:
    """``n`` frames (arbitration_id, data, is_extended) of a session on the node map
    (``setup_frames``: starting with its binds and set-up); ``GARBAGE[0]`` counts the
    garbage in them."""
    from pdcp_studio.model import parameters as P
    from pdcp_studio.protocol import messages as M
    from pdcp_studio.protocol.codes import ResponseCode

    ok = ResponseCode.SUCCESS
    rng = random.Random(seed)
    devices, outputs = node_map()
    setup: list[M.Message] = []
    for node, vid, pid, sn, _ in devices:
        setup += [M.BindRequest(node, vid, pid, sn), M.BindResponse(node, node, vid, pid, sn)]
        setup += [M.GetParameter(node, P.DEVICE_VID_PID, 0),
                  M.GetParameterResponse(node, ok, P.DEVICE_VID_PID, 0,
                                         vid.to_bytes(2, "little") + pid.to_bytes(2, "little")),
                  M.GetParameter(node, P.DEVICE_SERIAL, 0),
                  M.GetParameterResponse(node, ok, P.DEVICE_SERIAL, 0, sn.to_bytes(2, "little"))]
    for chan_node, dev, index, listener, lchan in outputs:
        setup += [M.GetParameter(dev, P.CH_TRANSFER_TYPE, index),
                  M.GetParameterResponse(dev, ok, P.CH_TRANSFER_TYPE, index, b"\x02"),
                  M.SetParameter(dev, P.OUT_NODE_ID, index, bytes([chan_node])),
                  M.SetParameterResponse(dev, ok, P.OUT_NODE_ID, index, bytes([chan_node])),
                  M.SetParameter(listener, P.IN_SOURCE_NODE_IDS, lchan, bytes([dev, chan_node])),
                  M.SetParameterResponse(listener, ok, P.IN_SOURCE_NODE_IDS, lchan,
                                         bytes([dev, chan_node])),
                  M.SetParameter(dev, P.CH_DATA_ENABLED, index, b"\x01"),
                  M.SetParameterResponse(dev, ok, P.CH_DATA_ENABLED, index, b"\x01")]
    frames: list[Frame] = [(*m.encode(), False) for m in setup] if setup_frames else []
    reads = [(P.DEVICE_VID_PID, 0), (P.DEVICE_SERIAL, 0), (P.CH_TRANSFER_TYPE, 1),
             (P.DEVICE_BEACON_INTERVAL, 0)]
    phase = [rng.random() * 6.28 for _ in outputs]
    import math

    t = 0
    GARBAGE[0] = 0
    while len(frames) < n:
        t += 1
        roll = rng.random()
        if roll < 0.86:  # channel data: a 12-bit EMG-like sample pair per output
            k = t % len(outputs)
            chan_node = outputs[k][0]
            level = int(2048 + 1500 * math.sin(t / 400 + phase[k])) + rng.randint(-40, 40)
            data = level.to_bytes(2, "little") + (4095 - level).to_bytes(2, "little")
            data = data * (1 + t % 2)  # 4- and 8-byte frames
            frames.append((make_data_id(chan_node), data, False))
        elif roll < 0.91:
            node = devices[t % len(devices)][0]
            frames.append((*M.Beacon(node).encode(), False))
        elif roll < 0.98:
            node, vid, pid, sn, _ = devices[t % len(devices)]
            param, chan = reads[t % len(reads)]
            frames.append((*M.GetParameter(node, param, chan).encode(), False))
            value = {P.DEVICE_VID_PID: vid.to_bytes(2, "little") + pid.to_bytes(2, "little"),
                     P.DEVICE_SERIAL: sn.to_bytes(2, "little"),
                     P.CH_TRANSFER_TYPE: b"\x02"}.get(param, b"\xe8\x03")
            frames.append((*M.GetParameterResponse(node, ok, param, chan, value).encode(),
                           False))
        elif roll < 0.99:  # a module-specific function code
            GARBAGE[0] += len(frames) < n
            node = devices[t % len(devices)][0]
            frames.append((0x200 | node, bytes([0x50, t & 0xFF]), False))
        elif roll < 0.995:  # random base frame
            GARBAGE[0] += len(frames) < n
            frames.append((rng.randrange(0x800), rng.randbytes(rng.randint(0, 8)), False))
        else:  # a 29-bit identifier
            GARBAGE[0] += len(frames) < n
            frames.append((rng.randrange(1 << 29), rng.randbytes(8), True))
    return frames[:n]


def midsession(n: int, seed: int = 27) -> list[Frame]:
    """``n`` frames of the same session recorded by another tool after its set-up: no bind,
    no Channel Node Id write, no node map beside it (the decoder infers the node map)."""
    return traffic(n, seed, setup_frames=False)


def foreign(n: int, seed: int = 27) -> list[Frame]:
    """``n`` frames of a car-like bus: 60 identifiers (a tenth extended) at fixed lengths,
    counters and sensor bytes; nothing of PDCP's."""
    rng = random.Random(seed)
    ids = [(rng.randrange(0x080, 0x7F0), rng.choice((2, 4, 6, 8)), False) for _ in range(54)]
    ids += [(rng.randrange(1 << 29), 8, True) for _ in range(6)]
    frames: list[Frame] = []
    for i in range(n):
        arbitration_id, dlc, extended = ids[i % len(ids)]
        frames.append((arbitration_id, bytes([(i // len(ids)) & 0xFF]) + rng.randbytes(dlc - 1),
                       extended))
    return frames


#: The capture kinds: how to make them, and whether their bus time is checked bit by bit.
KINDS = {"mixed": (lambda n: traffic(n), True), "midsession": (midsession, False),
         "foreign": (foreign, False)}


def make_data_id(chan_node: int) -> int:
    from pdcp_studio.protocol.identifier import make_id

    return make_id(1, 0, chan_node)


def exact_bus_bits(frames: list[Frame]) -> int:
    """The bus bits of the base frames, by the plain bit-stream computation (memoised)."""
    from pdcp_studio.bus.trace import bustime

    memo: dict[tuple[int, bytes], int] = {}
    total = 0
    for arbitration_id, data, extended in frames:
        if extended:
            continue
        key = (arbitration_id, data)
        bits = memo.get(key)
        if bits is None:
            stream = bustime.frame_bitstream(arbitration_id, data)
            bits = memo[key] = len(stream) + bustime.stuff_bit_count(stream) + bustime.TRAILER_BITS
        total += bits
    return total


def write_capture(path: Path, frames: list[Frame]) -> None:
    import can

    t0 = 1_700_000_000.0
    with can.Logger(str(path)) as logger:
        for i, (arbitration_id, data, extended) in enumerate(frames):
            logger.on_message_received(can.Message(
                timestamp=t0 + i / RATE_HZ, arbitration_id=arbitration_id, data=data,
                is_extended_id=extended, channel=0))


def _pipe(stream: IO[str] | None) -> IO[str]:
    """A child's pipe (it was started with ``subprocess.PIPE``)."""
    if stream is None:
        raise ValueError("the child was started without this pipe")
    return stream


def _peak_rss_mb(pid: int) -> float:
    """The child's own peak RSS (VmHWM) in MB, 0 once it is gone.

    Not ``ru_maxrss``: on Linux that keeps the high-water mark of the memory the child
    had before ``exec`` — this benchmark's own, with its million frames in memory.
    """
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    return 0.0


def best_of(repeat: int, cmd: list[str]) -> tuple[float, float, str, float]:
    """``timed`` run ``repeat`` times: the least wall and CPU time (a shared machine only
    ever adds to them), the largest peak RSS."""
    runs = [timed(cmd) for _ in range(max(1, repeat))]
    return (min(r[0] for r in runs), max(r[1] for r in runs), runs[-1][2],
            min(r[3] for r in runs))


def timed(cmd: list[str]) -> tuple[float, float, str, float]:
    """Wall seconds, peak RSS in MB, stderr and CPU seconds (user + system) of one child.

    On a shared machine wall time follows the load of the moment; CPU time much less, so
    the ratios are printed for both."""
    import threading

    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            env=dict(os.environ, PYTHONPATH=str(ROOT)))
    peak = [0.0]
    done = threading.Event()

    def watch() -> None:
        while not done.is_set():
            peak[0] = max(peak[0], _peak_rss_mb(proc.pid))
            done.wait(0.05)

    watcher = threading.Thread(target=watch, daemon=True)
    watcher.start()
    err = _pipe(proc.stderr).read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - t0
    done.set()
    watcher.join()
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} exited {proc.returncode}: {err[-2000:]}")
    return wall, peak[0], err, usage.ru_utime + usage.ru_stime


READER = ("import can, sys\n"
          "p = sys.argv[1]\n"
          "kw = {'relative_timestamp': False} if p.endswith('.asc') else {}\n"
          "n = 0\n"
          "for m in can.LogReader(p, **kw):\n"
          "    n += 1\n"
          "print(n)\n")
#: The monitor's BLF reader alone (what ``monitor --replay`` reads a .blf with).
OWN_BLF_READER = ("import sys\n"
                  "from pdcp_studio.bus.trace.monitor import open_capture\n"
                  "frames, close = open_capture(sys.argv[1], plain_frames=True)\n"
                  "n = 0\n"
                  "for m in frames:\n"
                  "    n += 1\n"
                  "print(n)\n")


#: The independent counter: python-can alone, with the same kernel receive buffer the monitor
#: asks for (the default ~200 KB holds a few dozen milliseconds of a saturated bus, and a
#: datagram that does not fit is dropped by the kernel, not by either program). Run as root
#: (SO_RCVBUFFORCE) or with net.core.rmem_max raised.
COUNTER = ("import can, socket, sys, time\n"
           "bus = can.Bus(interface='udp_multicast', channel=sys.argv[1])\n"
           "sock = bus._multicast._socket\n"
           "try:\n"
           "    sock.setsockopt(socket.SOL_SOCKET, 33, 16 << 20)  # SO_RCVBUFFORCE (Linux)\n"
           "except OSError:\n"
           "    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 16 << 20)\n"
           "import resource\n"
           "r = resource.getrusage(resource.RUSAGE_SELF)\n"
           "t_ready = r.ru_utime + r.ru_stime\n"
           "print('ready', flush=True)\n"
           "n, last = 0, None\n"
           "while True:\n"
           "    m = bus.recv(0.2)\n"
           "    if m is not None:\n"
           "        if m.arbitration_id != int(sys.argv[2]) or m.is_extended_id:\n"
           "            n += 1; last = time.monotonic()\n"
           "    elif last is not None and time.monotonic() - last > 2.0:\n"
           "        break\n"
           "bus.shutdown()\n"
           "u = resource.getrusage(resource.RUSAGE_SELF)\n"
           "print(n, u.ru_utime + u.ru_stime, t_ready)\n")
#: A beacon from a node the traffic does not use: pings until the monitor shows it.
PING_NODE = 253


def _cpu_s(pid: int) -> float:
    """User + system CPU seconds a running process has used (/proc/PID/stat)."""
    with open(f"/proc/{pid}/stat") as stat:
        fields = stat.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def live(seconds: float, rate: int) -> None:
    """Frames played onto a cross-process bus (python-can udp_multicast on loopback) at
    ``rate``: ``monitor --bus`` must count every frame an independent counter counts, and
    its CPU is measured (target ≤ 30 % of a core). The monitor shows only the pings that
    tell the sender it is listening (``--filter node=253``), so its output costs nothing."""
    import threading

    import can

    from pdcp_studio.protocol import messages as M

    ping_id, ping_data = M.Beacon(PING_NODE).encode()
    group = f"239.74.163.{random.randrange(10, 250)}"
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    counter = subprocess.Popen([sys.executable, "-c", COUNTER, group, str(ping_id)],
                               stdout=subprocess.PIPE, text=True, env=env)
    listen = seconds + 30
    monitor = subprocess.Popen(
        [sys.executable, "-m", "pdcp_studio", "monitor", "--bus", f"can:udp_multicast:{group}",
         "--seconds", str(listen), "--filter", f"node={PING_NODE}"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    assert _pipe(counter.stdout).readline().strip() == "ready"
    bus = can.Bus(interface="udp_multicast", channel=group)
    shown: list[str] = []
    out = _pipe(monitor.stdout)
    reader = threading.Thread(target=lambda: shown.extend(out), daemon=True)
    reader.start()
    while not shown:  # ping until the monitor listens
        bus.send(can.Message(arbitration_id=ping_id, data=ping_data, is_extended_id=False))
        time.sleep(0.1)
    time.sleep(0.5)
    # Frames the pings could be confused with are left out: the monitor shows only pings.
    frames = [f for f in traffic(int(seconds * rate))
              if f[2] or (f[0] & 0xFF) != PING_NODE]
    cpu_before = _cpu_s(monitor.pid)
    t0 = time.perf_counter()
    for i, (arbitration_id, data, extended) in enumerate(frames):
        due = t0 + i / rate
        while time.perf_counter() < due:
            time.sleep(0.0005)
        bus.send(can.Message(arbitration_id=arbitration_id, data=data, is_extended_id=extended))
    sent_s = time.perf_counter() - t0
    pings = len(shown)
    bus.send(can.Message(arbitration_id=ping_id, data=ping_data, is_extended_id=False))
    deadline = time.monotonic() + 300
    while len(shown) == pings and time.monotonic() < deadline:
        time.sleep(0.05)  # the end marker: every frame before it has been decoded
    drained_s = time.perf_counter() - t0
    cpu_traffic = _cpu_s(monitor.pid) - cpu_before
    count_text, counter_cpu, counter_start = counter.communicate(timeout=60)[0].split()
    counted = int(count_text)
    counter_cpu_s = float(counter_cpu) - float(counter_start)  # after it was ready
    monitor.send_signal(2)  # Ctrl-C: the monitor ends and prints its summary
    err = _pipe(monitor.stderr).read()
    _, _, usage = os.wait4(monitor.pid, 0)
    reader.join(5)
    bus.shutdown()
    match = re.search(r"^(\d+) frames", err, re.MULTILINE)
    if match is None:
        raise SystemExit(f"monitor --bus failed: {err[-2000:]}")
    seen = int(match.group(1)) - len(shown)
    cpu = usage.ru_utime + usage.ru_stime
    print(f"[live] {len(frames):,} frames sent in {sent_s:.2f} s ({len(frames) / sent_s:,.0f} "
          f"frames/s; bus bound {BUS_BOUND_8:,}–{BUS_BOUND_4:,}): independent counter "
          f"{counted:,}, monitor --bus {seen:,} — {'equal' if seen == counted == len(frames) else 'DIFFERENT'}"
          f"; monitor CPU while the traffic ran {cpu_traffic:.2f} s = "
          f"{100 * cpu_traffic / drained_s:.0f} % of a core (target ≤ 30 %; {cpu:.2f} s = "
          f"{100 * cpu / sent_s:.0f} % with its start-up and shutdown); it had decoded the "
          f"last frame {drained_s - sent_s:.2f} s after it was sent. The independent "
          f"counter (python-can's recv alone) used {counter_cpu_s:.2f} s = "
          f"{100 * counter_cpu_s / drained_s:.0f} % of a core over the same time, with its "
          "2 s wait for the end")


def replay_kind(kind: str, count: int, args: argparse.Namespace, cache: Path) -> None:
    """The replay cases for one capture kind, in every format asked for."""
    make, exact_checked = KINDS[kind]
    t0 = time.perf_counter()
    frames = make(count)
    garbage = GARBAGE[0]
    exact = 0
    if exact_checked:
        exact_file = cache / f"{kind}-{count}-v1.bits"
        if exact_file.exists():
            exact = int(exact_file.read_text())
        else:
            exact = exact_bus_bits(frames)
            exact_file.write_text(str(exact))
    what = {"mixed": "mixed PDCP traffic with its set-up",
            "midsession": "PDCP traffic recorded after its set-up, no node map",
            "foreign": "a car's bus (not PDCP)"}[kind]
    print(f"[{kind}] {len(frames):,} frames of {what} at {RATE_HZ:,} frames/s of capture time"
          + (f"; exact bus time {exact / 1000:.3f} ms (bit by bit, "
             f"{time.perf_counter() - t0:.1f} s)" if exact_checked else "")
          + f"; bus bound {BUS_BOUND_8:,} 8-byte / {BUS_BOUND_4:,} 4-byte frames/s at 1 Mbit/s")
    python = sys.executable
    n = len(frames)
    for fmt in filter(None, args.formats.split(",")):
        tag = f"{kind} {fmt}"
        path = cache / f"{kind}-{count}-v1.{fmt}"
        if not path.exists():
            t1 = time.perf_counter()
            partial = path.with_name(path.name + ".tmp." + fmt)
            write_capture(partial, frames)
            partial.replace(path)
            print(f"[{tag}] wrote {path} in {time.perf_counter() - t1:.1f} s")
        size = path.stat().st_size / 1e6
        wall, rss, _, cpu = best_of(args.repeat, [python, "-c", READER, str(path)])
        anchor, anchor_cpu = wall, cpu
        print(f"[{tag}] {size:.0f} MB — python-can reader alone: {wall:.2f} s ({cpu:.2f} s "
              f"CPU), {n / wall:,.0f} frames/s, peak RSS {rss:.0f} MB")
        if fmt == "blf":
            wall, rss, _, cpu = best_of(args.repeat, [python, "-c", OWN_BLF_READER, str(path)])
            print(f"[{tag}] the monitor's BLF reader alone (bus/trace/files/blf.py): {wall:.2f} s "
                  f"({cpu:.2f} s CPU), {n / wall:,.0f} frames/s, {cpu / anchor_cpu:.2f}× "
                  f"python-can's CPU time, peak RSS {rss:.0f} MB")
        monitor = [python, "-m", "pdcp_studio", "monitor", "--replay", str(path)]
        cases = [("monitor --replay", monitor),
                 ("--filter node=254 (matches nothing)", [*monitor, "--filter", "node=254"]),
                 ("--json", [*monitor, "--json"])]
        for label, cmd in cases:
            wall, rss, err, cpu = best_of(args.repeat, cmd)
            ratio, cpu_ratio = wall / anchor, cpu / anchor_cpu
            verdict = ("ok" if min(ratio, cpu_ratio) <= TARGET_RATIO and rss < TARGET_RSS_MB
                       else "MISSES TARGET")
            print(f"[{tag}] {label}: {wall:.2f} s ({cpu:.2f} s CPU), {n / wall:,.0f} frames/s "
                  f"({n / wall / BUS_BOUND_8:.1f}× a saturated bus), "
                  f"{ratio:.2f}× the reader's wall time, {cpu_ratio:.2f}× its CPU time (target "
                  f"≤ {TARGET_RATIO}×), peak RSS {rss:.0f} MB (target < {TARGET_RSS_MB} MB) — "
                  f"{verdict}")
            if label == "monitor --replay":
                shown = [x for x in err.strip().splitlines()
                         if not x.startswith("  ")][:3]
                shown += [x for x in err.splitlines()
                          if x.startswith(("verdict:", "node map:"))]
                print("    summary: " + "\n    ".join(dict.fromkeys(shown)))
                if kind == "midsession":
                    match = re.search(r"\((\d+) undecodable", err)
                    bad = int(match.group(1)) if match else n
                    beyond = max(0, bad - garbage)
                    print(f"    {bad:,} undecodable; the traffic holds {garbage:,} frames of "
                          f"garbage made on purpose; undecodable beyond them: {beyond:,} = "
                          f"{100 * beyond / n:.2f} % of the frames (target ≤ 1 %) — "
                          f"{'ok' if beyond <= n / 100 else 'MISSES TARGET'}")
                if kind == "foreign" and "verdict: not-pdcp" not in err:
                    raise SystemExit(f"[{tag}] a car's bus not called not-pdcp: {err[:500]}")
            if exact_checked:
                match = re.search(r"bus time ([\d.]+) ms", err)
                if match is None or abs(float(match.group(1)) * 1000 - exact) > 0.5:
                    raise SystemExit(f"[{tag}] bus time {match and match.group(1)} ms ≠ exact "
                                     f"{exact / 1000:.3f} ms")
        if exact_checked:
            print(f"[{tag}] bus time of the capture equals the exact bit-by-bit figure "
                  f"({exact / 1000:.3f} ms)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--frames", type=int, default=FRAMES)
    parser.add_argument("--formats", default="asc,blf")
    parser.add_argument("--kinds", default=",".join(KINDS),
                        help="captures: mixed (PDCP with its set-up, --frames), midsession "
                             "(PDCP without set-up or node map) and foreign (a car's bus), "
                             "the last two of --other-frames")
    parser.add_argument("--other-frames", type=int, default=400_000)
    parser.add_argument("--live-seconds", type=float, default=10.0,
                        help="length of the live case (0: skip it)")
    parser.add_argument("--live-rate", type=int, default=RATE_HZ)
    parser.add_argument("--repeat", type=int, default=1,
                        help="runs of the reader and of each replay case; the best is shown "
                             "(steadier ratios on a loaded machine)")
    args = parser.parse_args()
    cache = Path(tempfile.gettempdir()) / "pdcp-trace-bench"
    cache.mkdir(exist_ok=True)
    for kind in filter(None, args.kinds.split(",")):
        n = args.frames if kind == "mixed" else args.other_frames
        replay_kind(kind, n, args, cache)
    if args.live_seconds:
        live(args.live_seconds, args.live_rate)


if __name__ == "__main__":
    main()
