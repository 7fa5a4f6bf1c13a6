"""Shared test set-up: Qt runs headless; paths to the shipped resources; no test leaves a
bus open."""

from __future__ import annotations

import atexit
import os
import shutil
import tempfile
from pathlib import Path

import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
# The user's own data and settings (profile trees, recent files, window layout, autosaves)
# are never read or written by a test run: a private home for both, per run.
_HOME = tempfile.mkdtemp(prefix="pdcp-studio-tests-")
os.environ["XDG_DATA_HOME"] = os.path.join(_HOME, "data")
os.environ["XDG_CONFIG_HOME"] = os.path.join(_HOME, "config")
os.environ["XDG_CACHE_HOME"] = os.path.join(_HOME, "cache")
atexit.register(shutil.rmtree, _HOME, True)

ROOT = Path(__file__).resolve().parent.parent
RESOURCES = ROOT / "resources"


@pytest.fixture(autouse=True)
def no_bus_left_open():
    """Fails a test that leaves a bus connection open (style §6): every test, every layer.

    Connections already open when the test starts (a module-scoped rig) are not its own."""
    from pdcp_studio.bus.connection import open_connections

    before = set(open_connections())
    yield
    left = [c.name for c in open_connections() if c not in before]
    assert not left, f"a test left a bus open: {left}"


@pytest.fixture
def resources() -> Path:
    return RESOURCES


@pytest.fixture
def systems_dir() -> Path:
    return RESOURCES / "systems"


def _multicast_problem(url: str) -> str | None:
    """None when two python-can buses on ``url`` hear each other on loopback, else why not."""
    import time

    import can

    from pdcp_studio.bus.session.urls import open_spec, parse_bus_url

    spec = parse_bus_url(url)
    try:
        a, b = open_spec(spec), open_spec(spec)
    except Exception as err:
        return f"cannot open udp_multicast: {err}"
    try:
        a.send(can.Message(arbitration_id=0x7AB, data=b"ping", is_extended_id=False))
        deadline = time.monotonic() + 1.0
        while time.monotonic() < deadline:
            msg = b.recv(0.2)
            if msg is not None and msg.arbitration_id == 0x7AB:
                return None
        return "multicast frames do not arrive on loopback"
    finally:
        a.shutdown()
        b.shutdown()


def _claim_udp_port(first: int):
    """A UDP port from ``first`` on that no socket on this machine holds, and a socket that
    holds it for us (SO_REUSEADDR/SO_REUSEPORT on 127.0.0.1, so python-can's multicast
    sockets here and in our child processes can still bind it, while another test run's
    exclusive probe fails and moves on). Another run's PID may map to the same first port
    (PIDs wrap at pid_max; the bases are 1000 apart): then the two would hear each other."""
    import socket

    for port in range(first, first + 200):
        probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            probe.bind(("", port))
        except OSError:
            continue  # someone (another test run) is on this port
        finally:
            probe.close()
        hold = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        hold.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        if hasattr(socket, "SO_REUSEPORT"):
            hold.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEPORT, 1)
        try:
            hold.bind(("127.0.0.1", port))  # not the group's address: it receives nothing
        except OSError:
            hold.close()
            continue
        return port, hold
    pytest.skip(f"no free UDP port in {first}..{first + 199}")


@pytest.fixture
def multicast_url():
    """``make(group, base_port)``: a udp_multicast bus URL private to this test run (the port
    follows the PID and is held for the test, so parallel runs do not hear each other);
    skips when multicast fails here."""
    held = []

    def make(group: str, base_port: int) -> str:
        port, hold = _claim_udp_port(base_port + os.getpid() % 20000)
        held.append(hold)
        url = f"can:udp_multicast:{group}?port={port}"
        why = _multicast_problem(url)
        if why is not None:
            pytest.skip(why)
        return url

    yield make
    for hold in held:
        hold.close()


@pytest.fixture(autouse=True)
def _private_fitting_history(tmp_path_factory, monkeypatch):
    """Every test records its transactions in an archive of its own, never the user's."""
    path = tmp_path_factory.mktemp("history") / "history.sqlite3"
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(path))
    monkeypatch.setenv("PDCP_STUDIO_OPERATOR", "test prosthetist")


# The clinic archive's throw-away PostgreSQL server and its engine-parametrised fixtures
# (archive_url runs a test on SQLite and on PostgreSQL): tests/pg_cluster.py.
from tests.pg_cluster import archive_url, pg_cluster, pg_db  # noqa: E402, F401
