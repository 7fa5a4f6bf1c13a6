"""Benchmark: host link 2 on a pseudo-terminal line at a real UART's speed (docs/host-link.md).

A relay between two pseudo-terminals (``bus/hostlink/testing/relay.py``) carries the bytes at
12,800 bytes/s each way — 128000 baud 8N1, the thesis's rig — and can flip bits and add
garbage. PDCP Studio's arbitrator serves the host link on one pty; a ``serial:`` session
opens the other. Prints, each next to its physical minimum (the content bytes alone, at the
line's speed, with no framing, no acknowledgements and no waiting):

1. scan of ``large`` (32 devices): bytes on the line (target ≤ 16 KB) and time (< 1.5 s);
2. a generated 70-device bus that needs more node IDs than there are (the arbitrator binds
   what it can and says so; the scan must not fail);
3. a 2 KB stored configuration written and read back (target ≤ 3.5× its size on the line);
4. the same at a bit error rate of 1e-4 with a 16-byte garbage burst every 2 KB (must
   succeed; the slowdown is quoted);
5. the same configuration through the change road (preview, transaction, verification,
   recorded in a fitting history) from a session that has read nothing yet: target ≤ 3.5× its
   size plus the device table (a cold scan's bytes) — the preview and the record come from the
   arbitrator's tables and the stored configuration, not a scan of every parameter.

Run: ``python benchmarks/host_link.py [--rate 12800]``.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from pdcp_studio.bus.hostlink import records as hr
from pdcp_studio.bus.hostlink.client import HostLinkSession
from pdcp_studio.bus.hostlink.server import HostLinkServer
from pdcp_studio.bus.hostlink.testing.relay import NoisyLine, PtyRelay
from pdcp_studio.bus.session.sim import open_sim_session
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.model.system import System
from pdcp_studio.protocol import hostlink_messages as hm
from pdcp_studio.storage import config_codec, system_file

RATE = 12_800  # bytes/s: 128000 baud, 8N1
TARGET_SCAN_BYTES = 16_000
TARGET_SCAN_S = 1.5
TARGET_CONFIG_RATIO = 3.5


def content_bytes(system: System) -> int:
    """The tables' content: the records a scan must move, without any framing."""
    total = hm.DEVICE_ROW.size * len(system.devices) + 2 * hm.REF.size * len(system.links)
    for device in system.devices.values():
        total += len(hr.pack_device_info(device))
        total += sum(len(hr.pack_channel(ch)) for ch in device.channels.values())
    return total


def seventy_devices(path: Path) -> Path:
    """A system file with 70 devices and 3 output channels each: 280 node IDs wanted, 254
    exist."""
    import copy
    from dataclasses import replace

    from pdcp_studio.bus.sim.rigs import load_prosthesis

    base = [d for _, d in sorted(load_prosthesis("large").devices.items())]
    devices = []
    for i in range(70):
        dev = copy.deepcopy(base[i % len(base)])
        dev.serial = 5000 + i
        dev.node_id = None
        for ch in list(dev.channels.values()):
            dev.channels[ch.index] = replace(ch, source=type(ch.source)(), node_id=None,
                                             data_enabled=False)
        outputs = [c for c in dev.channels.values() if c.is_output]
        template = outputs[0] if outputs else None
        index = max(dev.channels) + 1
        while template is not None and len(outputs) < 3:
            extra = replace(template, index=index, descriptor=f"spare output {index}")
            dev.channels[index] = extra
            outputs.append(extra)
            index += 1
        devices.append(dev)
    system_file.save_path(System(devices), path)
    return path


def two_kb_configuration() -> ConfigCollection:
    links = []
    n = 0
    while True:
        n += 1
        out = StoredChannel(index=1 + n % 3, vid=2641, pid=257, serial=100 + n, type=0x9000,
                            profile=0x4222)
        inp = StoredChannel(index=1, vid=2641, pid=513, serial=200 + n, type=0x9200,
                            profile=0x4222)
        links.append(StoredLink(inp, out, n))
        collection = ConfigCollection([StoredConfiguration(1, links)])
        if len(config_codec.dumps(collection)) >= 2048:
            return collection


def line(label: str, value: str, bound: str, verdict: str = "") -> None:
    print(f"  {label:<44} {value:>14}   minimum {bound:<12} {verdict}")


def _pty(server: HostLinkServer) -> str:
    """The path of the server's pseudo-terminal (it was opened on ``pty``)."""
    if server.slave_path is None:
        raise SystemExit("the host-link server has no pseudo-terminal")
    return server.slave_path


def run_scan(name: str, rate: float, settle: float) -> dict[str, Any]:
    sim = open_sim_session(name, settle_timeout=settle, data_rate_hz=0.0)
    try:
        with HostLinkServer(sim.arbitrator, "pty") as server, \
                PtyRelay(_pty(server), bytes_per_s=rate) as relay:
            session = HostLinkSession(relay.client_path, url="bench", monitor=False)
            try:
                greet = relay.total
                relay.reset_counts()
                t0 = time.perf_counter()
                system = session.scan()
                took = time.perf_counter() - t0
                scan_bytes = relay.total
                relay.reset_counts()
                t1 = time.perf_counter()
                session.scan()
                again = time.perf_counter() - t1, relay.total
            finally:
                session.close()
        truth = sim.arbitrator.system()
        return {"devices": len(system.devices), "known": len(truth.devices),
                "links": len(system.links), "bytes": scan_bytes, "seconds": took,
                "greeting": greet, "content": content_bytes(system), "again": again,
                "equal": all(system.devices.get(k) == d for k, d in truth.devices.items()
                             if d.present)}
    finally:
        sim.close()


def run_config(rate: float, noise: NoisyLine | None) -> dict[str, Any]:
    collection = two_kb_configuration()
    size = len(config_codec.dumps(collection))
    sim = open_sim_session("transradial", data_rate_hz=0.0)
    try:
        with HostLinkServer(sim.arbitrator, "pty") as server, \
                PtyRelay(_pty(server), bytes_per_s=rate) as relay:
            session = HostLinkSession(relay.client_path, url="bench", monitor=False)
            try:
                relay.spoil = noise
                relay.reset_counts()
                t0 = time.perf_counter()
                back = session.write_configuration(collection)
                took = time.perf_counter() - t0
                total = relay.total
                stats = session.conn.link.stats
                retrans = stats.retransmits + server.link.stats.retransmits
                bad = stats.bad_frames + server.link.stats.bad_frames
            finally:
                relay.spoil = None
                session.close()
        ok = back == collection and sim.arbitrator.read_memory() == collection
        return {"size": size, "bytes": total, "seconds": took, "ok": ok,
                "retransmits": retrans, "bad_frames": bad}
    finally:
        sim.close()


def run_road(rate: float) -> dict[str, Any]:
    """A configuration written through the change road by a cold session, and the bytes of
    a cold scan (the device table) on the same line, for the bound."""
    from pdcp_studio.bus.transaction import Change
    from pdcp_studio.storage.history import History

    collection = two_kb_configuration()
    size = len(config_codec.dumps(collection))
    sim = open_sim_session("transradial", data_rate_hz=0.0)
    try:
        with HostLinkServer(sim.arbitrator, "pty") as server, \
                PtyRelay(_pty(server), bytes_per_s=rate) as relay:
            session = HostLinkSession(relay.client_path, url="bench", monitor=False)
            try:
                relay.reset_counts()
                session.scan()
                table = relay.total
            finally:
                session.close()
            session = HostLinkSession(relay.client_path, url="bench", monitor=False)
            try:
                with tempfile.TemporaryDirectory() as tmp:
                    history = History(Path(tmp) / "history.sqlite")
                    relay.reset_counts()
                    t0 = time.perf_counter()
                    result = session.transact(Change("config write", configuration=collection),
                                              history=history)
                    took = time.perf_counter() - t0
                    total = relay.total
                    history.close()
            finally:
                session.close()
        ok = result.written and sim.arbitrator.read_memory() == collection
        return {"size": size, "table": table, "bytes": total, "seconds": took, "ok": ok,
                "status": result.status.name}
    finally:
        sim.close()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rate", type=float, default=RATE, help="line bytes per second")
    args = parser.parse_args(argv)
    rate = args.rate
    failures = []
    print(f"host link 2 on a pseudo-terminal relay at {rate:,.0f} bytes/s each way")

    scan = run_scan("large", rate, 20.0)
    print(f"\n1. scan of large: {scan['devices']} devices, {scan['links']} links "
          f"(greeting {scan['greeting']} B before it)")
    ok_b = scan["bytes"] <= TARGET_SCAN_BYTES
    ok_t = scan["seconds"] < TARGET_SCAN_S
    line("bytes on the line (target ≤ 16,000)", f"{scan['bytes']:,} B",
         f"{scan['content']:,} B", "ok" if ok_b else "OVER")
    line("time (target < 1.5 s)", f"{scan['seconds']:.2f} s",
         f"{scan['content'] / rate:.2f} s", "ok" if ok_t else "OVER")
    line("the same scan again (nothing changed)", f"{scan['again'][1]} B",
         "0 B", f"{scan['again'][0] * 1000:.1f} ms")
    line("every device equals the arbitrator's", str(scan["equal"]), "", "")
    failures += [] if ok_b and ok_t and scan["equal"] else ["scan of large"]

    with tempfile.TemporaryDirectory() as tmp:
        path = seventy_devices(Path(tmp) / "seventy.json")
        big = run_scan(str(path), rate, 30.0)
    print(f"\n2. 70 devices wanting 280 node IDs (254 exist): {big['devices']} devices read, "
          f"{big['known']} known to the arbitrator")
    line("bytes on the line", f"{big['bytes']:,} B", f"{big['content']:,} B")
    line("time", f"{big['seconds']:.2f} s", f"{big['content'] / rate:.2f} s")
    failures += [] if big["devices"] and big["equal"] else ["70-device scan"]

    clean = run_config(rate, None)
    print(f"\n3. a {clean['size']:,}-byte stored configuration written and read back")
    ratio = clean["bytes"] / clean["size"]
    line("bytes on the line (target ≤ 3.5× its size)", f"{clean['bytes']:,} B",
         f"{2 * clean['size']:,} B", f"{ratio:.2f}× its size "
         + ("ok" if ratio <= TARGET_CONFIG_RATIO else "OVER"))
    line("time", f"{clean['seconds']:.2f} s", f"{2 * clean['size'] / rate:.2f} s",
         "verified" if clean["ok"] else "NOT VERIFIED")
    failures += [] if clean["ok"] and ratio <= TARGET_CONFIG_RATIO else ["configuration"]

    noise = NoisyLine(1e-4, burst_every=2048, burst_len=16, seed=7)
    noisy = run_config(rate, noise)
    print(f"\n4. the same at a bit error rate of 1e-4 with a 16-byte garbage burst every 2 KB "
          f"({noise.flips} bits flipped, {noise.bursts} bursts)")
    line("bytes on the line", f"{noisy['bytes']:,} B", f"{2 * noisy['size']:,} B",
         f"{noisy['retransmits']} retransmitted, {noisy['bad_frames']} bad frames")
    line("time", f"{noisy['seconds']:.2f} s", f"{2 * noisy['size'] / rate:.2f} s",
         f"{noisy['seconds'] / clean['seconds']:.2f}× the clean line; "
         + ("verified" if noisy["ok"] else "NOT VERIFIED"))
    failures += [] if noisy["ok"] else ["noisy configuration"]

    road = run_road(rate)
    bound = TARGET_CONFIG_RATIO * road["size"] + road["table"]
    print(f"\n5. the same {road['size']:,}-byte configuration through the change road (preview, "
          f"transaction, verified, recorded) from a cold session; device table "
          f"{road['table']:,} B")
    line(f"bytes on the line (target ≤ 3.5× + table = {bound:,.0f})", f"{road['bytes']:,} B",
         f"{2 * road['size']:,} B", f"{road['bytes'] / road['size']:.2f}× its size "
         + ("ok" if road["bytes"] <= bound else "OVER"))
    line("time", f"{road['seconds']:.2f} s", f"{2 * road['size'] / rate:.2f} s",
         road["status"] if road["ok"] else "NOT WRITTEN")
    failures += [] if road["ok"] and road["bytes"] <= bound else ["change road"]

    if failures:
        print(f"\nmissed: {', '.join(failures)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
