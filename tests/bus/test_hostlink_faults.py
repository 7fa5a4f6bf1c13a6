"""Host link 2 in field conditions, each through a real pseudo-terminal: a noisy line, a peer
that vanishes, a reply that never comes, an arbitrator killed mid-write, an older version."""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.hostlink_client import HostLinkSession, VersionRefused
from pdcp_studio.bus.hostlink_relay import TO_ARB, NoisyLine, PtyRelay
from pdcp_studio.bus.memory import MemoryStore
from pdcp_studio.errors import BusTimeoutError, TransportError
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link
from pdcp_studio.protocol import hostlink_messages as hm
from pdcp_studio.protocol.hostlink import Frame, FrameReader, Kind
from pdcp_studio.storage import config_codec

from .hostlink_rig import arbitrator_rig, wait_for

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")

VID = 0x0A51
LINK = Link(ChannelRef(VID, 257, 101, 1), ChannelRef(VID, 513, 201, 1))
SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"
FAST = {"ack_timeout": 0.05, "max_attempts": 4}


def configuration(n: int, serial_base: int = 100) -> ConfigCollection:
    links = []
    for i in range(1, n + 1):
        out = StoredChannel(index=1, vid=VID, pid=257, serial=serial_base + i, type=0x9000,
                            profile=0x4222)
        inp = StoredChannel(index=1, vid=VID, pid=513, serial=serial_base + 500 + i,
                            type=0x9200, profile=0x4222)
        links.append(StoredLink(inp, out, i))
    return ConfigCollection([StoredConfiguration(1, links)])


@pytest.fixture(scope="module")
def rig(tmp_path_factory):
    memory = tmp_path_factory.mktemp("hostlink-faults") / "memory.bin"
    with arbitrator_rig(SYSTEMS / "transradial.json", memory) as parts:
        yield parts


def test_garbage_and_flipped_bits_resync_and_nothing_wrong_is_executed(rig):
    arbitrator, server = rig
    calls: list[Link] = []
    real_add = arbitrator.add_link
    noise = NoisyLine(1e-4, burst_every=1000, burst_len=12, seed=3)
    with PtyRelay(server.slave_path, spoil=noise) as relay:
        session = HostLinkSession(relay.client_path, url="noisy", monitor=False)
        arbitrator.add_link = lambda link: (calls.append(link), real_add(link))[1]
        try:
            for _ in range(5):
                session.add_link(LINK)
                session.remove_link(LINK)
            wanted = configuration(40)
            assert session.write_configuration(wanted) == wanted
            assert arbitrator.read_memory() == wanted
            system = session.scan()
            assert system.devices == {k: d for k, d in arbitrator.system().devices.items()}
        finally:
            del arbitrator.add_link
            session.close()
    assert calls == [LINK] * 5  # every request executed exactly once, despite the noise
    assert noise.flips >= 3 and noise.bursts >= 5
    assert server.link.stats.bad_frames + session.conn.link.stats.bad_frames > 5


def test_a_peer_that_vanishes_mid_transfer_is_a_clear_error_and_the_old_configuration_stays(rig):
    arbitrator, server = rig
    old = configuration(3)
    arbitrator.write_memory(old)
    sent = [0]

    def count(direction: str, data: bytes) -> bytes:
        if direction == TO_ARB:
            sent[0] += len(data)
            if sent[0] > 900:
                relay.cut()  # the cable is pulled in the middle of the chunks
        return data

    with PtyRelay(server.slave_path, spoil=count) as relay:
        session = HostLinkSession(relay.client_path, url="vanishing", monitor=False, **FAST)
        try:
            t0 = time.monotonic()
            with pytest.raises(TransportError, match="no acknowledgement after 4 attempts"):
                session.write_configuration(configuration(60))
            assert time.monotonic() - t0 < 3.0
        finally:
            session.close()
    assert arbitrator.read_memory() == old


def test_a_reply_that_never_comes_is_bounded(rig):
    _, server = rig
    real = server.handlers.handle
    server.handlers.handle = lambda message: None if message[:1] == bytes([hm.Req.STATUS]) \
        else real(message)
    try:
        with PtyRelay(server.slave_path) as relay:
            session = HostLinkSession(relay.client_path, url="mute", monitor=False,
                                      reply_timeout=0.3, **FAST)
            try:
                t0 = time.monotonic()
                with pytest.raises(BusTimeoutError, match=r"no reply to STATUS within 0\.3 s"):
                    session.status()
                assert time.monotonic() - t0 < 1.0
                assert session.scan().devices  # the link still works for the next request
                relay.cut()  # now nothing at all comes back: bounded retransmissions
                t0 = time.monotonic()
                with pytest.raises(TransportError, match="no acknowledgement"):
                    session.conn.request(hm.Req.LIST_LINKS, b"\x00\x00")
                assert time.monotonic() - t0 < 4 * 0.05 + 1.0
            finally:
                session.close()
    finally:
        del server.handlers.handle


def test_an_older_protocol_version_is_refused_clearly_on_both_ends(rig, monkeypatch):
    _, server = rig
    with PtyRelay(server.slave_path) as relay:
        # an older host: HELLO version 1 gets the VERSION status and a reason
        fd = os.open(relay.client_path, os.O_RDWR | os.O_NOCTTY)
        try:
            os.write(fd, Frame(Kind.RESET, 0).encode()
                     + Frame(Kind.DATA, 0, bytes([hm.Req.HELLO, 1, 0, 0])).encode())
            reader, reply = FrameReader(), None
            deadline = time.monotonic() + 3
            while reply is None and time.monotonic() < deadline:
                for f in reader.feed(os.read(fd, 512)):
                    if isinstance(f, Frame) and f.kind is Kind.DATA:
                        reply = f.payload
        finally:
            os.close(fd)
        assert reply is not None and reply[0] == hm.reply_code(hm.Req.HELLO)
        assert reply[1] == hm.Status.VERSION
        assert "version 2, not version 1" in hm.text(reply[2:])
        assert not server.greeted
    # an older arbitrator: this PC refuses it, naming both versions
    monkeypatch.setitem(server.handlers._table, hm.Req.HELLO,
                        lambda body: hm.HELLO.pack(1, 0, 255) + b"old firmware")
    with PtyRelay(server.slave_path) as relay:
        with pytest.raises(VersionRefused, match="speaks host-link version 1; this PDCP "
                                                 "Studio speaks version 2"):
            HostLinkSession(relay.client_path, url="old", monitor=False)


def test_a_dropped_port_is_reopened_with_one_calm_message(rig, tmp_path):
    _, server = rig
    link_path = tmp_path / "ttyPDCP"
    relay = PtyRelay(server.slave_path)
    link_path.symlink_to(relay.client_path)
    session = HostLinkSession(str(link_path), url="serial:ttyPDCP", monitor=False)
    notices: list[str] = []
    session.subscribe(lambda e: notices.append(e.message) if isinstance(e, ev.BusError)
                      else None)
    try:
        assert session.scan().devices
        relay.close()  # the adapter is unplugged
        time.sleep(1.0)  # several reopen attempts fail meanwhile
        with pytest.raises(TransportError):
            session.status()
        relay = PtyRelay(server.slave_path)  # plugged in again (a new pty behind the name)
        link_path.unlink()
        link_path.symlink_to(relay.client_path)
        assert wait_for(lambda: not session.conn._reopener.down, 5.0)
        assert session.status()["devices"] == 4
        assert len([n for n in notices if "lost" in n]) == 1
    finally:
        session.close()
        relay.close()


KILL_POINTS = 20


def _spawn_arbitrator(memory: Path, bus: str) -> tuple[subprocess.Popen, str]:
    proc = subprocess.Popen(
        [sys.executable, "-m", "pdcp_studio", "arbitrator", "--bus", bus, "--memory",
         str(memory), "--host-serial", "pty", "--no-profile-layer", "--seconds", "30"],
        stdout=subprocess.PIPE, text=True, env={**os.environ, "PYTHONUNBUFFERED": "1"})
    line = proc.stdout.readline()
    assert line.startswith("host link on /dev/"), line
    return proc, line.split(" on ", 1)[1].strip()


def _kill_rounds(memory: Path, rounds: list[tuple[int, int]], old: ConfigCollection,
                 new: ConfigCollection) -> dict[str, int]:
    """Write ``new`` over ``old`` and kill the arbitrator when the host has sent ``at`` bytes."""
    outcomes = {"old": 0, "new": 0}
    MemoryStore(memory).write(old)
    for n, kill_at in rounds:
        proc, path = _spawn_arbitrator(memory, f"can:virtual:kill-{os.getpid()}-{n}")
        killed = threading.Event()
        sent = [0]

        def spoil(direction: str, data: bytes, at=kill_at, p=proc, k=killed,
                  sent=sent) -> bytes:
            if direction == TO_ARB and not k.is_set():
                sent[0] += len(data)
                if sent[0] >= at:
                    k.set()
                    p.send_signal(signal.SIGKILL)
            return data

        try:
            with PtyRelay(path, spoil=spoil) as relay:
                session = HostLinkSession(relay.client_path, url="kill", monitor=False,
                                          reply_timeout=1.0, **FAST)
                try:
                    session.write_configuration(new)
                except TransportError as err:
                    assert killed.is_set(), err  # only the kill may fail the write
                finally:
                    session.close()
        finally:
            proc.kill()
            proc.wait(10)
            proc.stdout.close()
        got = MemoryStore(memory).read()
        assert got in (old, new), f"kill point {n} at byte {kill_at}: a mix was stored"
        outcomes["new" if got == new else "old"] += 1
        if got == new:  # the next round starts from the old one again
            MemoryStore(memory).write(old)
    return outcomes


def test_an_arbitrator_killed_during_a_configuration_write_keeps_old_or_new(tmp_path):
    from concurrent.futures import ThreadPoolExecutor

    rng = random.Random(20261123)
    old, new = configuration(20), configuration(45, serial_base=300)
    # the host sends the chunks (≈ the new configuration's size), their headers and ACKs
    span = len(config_codec.dumps(new)) + 300
    points = [(n, rng.randrange(span)) for n in range(KILL_POINTS)]
    workers = 2
    with ThreadPoolExecutor(workers) as pool:
        results = list(pool.map(
            lambda w: _kill_rounds(tmp_path / f"memory{w}.bin", points[w::workers], old, new),
            range(workers)))
    outcomes = {k: sum(r[k] for r in results) for k in ("old", "new")}
    assert sum(outcomes.values()) == KILL_POINTS
    assert outcomes["old"] and outcomes["new"], outcomes
