"""Shared test set-up: Qt runs headless; paths to the shipped resources."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

ROOT = Path(__file__).resolve().parent.parent
RESOURCES = ROOT / "resources"


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

    from pdcp_studio.bus.urls import open_spec, parse_bus_url

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


@pytest.fixture
def multicast_url():
    """``make(group, base_port)``: a udp_multicast bus URL private to this process (the port
    follows the PID so parallel runs do not hear each other); skips when multicast fails here."""

    def make(group: str, base_port: int) -> str:
        url = f"can:udp_multicast:{group}?port={base_port + os.getpid() % 20000}"
        why = _multicast_problem(url)
        if why is not None:
            pytest.skip(why)
        return url

    return make
