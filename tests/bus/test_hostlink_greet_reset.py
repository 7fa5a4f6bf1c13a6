"""A greeting survives the link being reset under it (docs/host-link.md §3.4).

Frames of the session before are still on their way when the PC greets (an event the
arbitrator sent again just before the PC's RESET reached it, on a loaded machine): the PC
sees them out of sequence and the two ends renumber while HELLO waits. HELLO only reads, so
the PC says it again instead of failing the session's opening (a CI run on a loaded machine
failed there: "HELLO failed: the link was reset"). Also when the PC's RESET is lost.
"""

from __future__ import annotations

import os
import threading
from pathlib import Path

import pytest

from pdcp_studio.bus.hostlink.client import HostLinkSession
from pdcp_studio.bus.hostlink.testing.relay import TO_ARB, TO_HOST, PtyRelay
from pdcp_studio.protocol.hostlink import Frame, Kind

from .hostlink_rig import arbitrator_rig

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")

SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"
RESET = Frame(Kind.RESET, 0).encode()


class DropResets:
    """A relay ``spoil`` that, while armed, drops the PC's RESET frames (``count`` of them)."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.left = 0
        self.dropped = 0

    def __call__(self, direction: str, data: bytes) -> bytes:
        with self.lock:
            while self.left and direction == TO_ARB and RESET in data:
                data = data.replace(RESET, b"", 1)
                self.left -= 1
                self.dropped += 1
            return data


class StaleFrames:
    """A relay ``spoil`` that, once armed, puts ``count`` frames of an earlier session in
    front of the first bytes the arbitrator sends after the PC's RESET."""

    def __init__(self, count: int) -> None:
        self.lock = threading.Lock()
        self.count = count
        self.armed = self.after_reset = False
        self.injected = 0

    def __call__(self, direction: str, data: bytes) -> bytes:
        with self.lock:
            if not self.armed:
                return data
            if direction == TO_ARB and RESET in data:
                self.after_reset = True
            elif direction == TO_HOST and self.after_reset:
                self.armed = False
                stale = b"".join(Frame(Kind.DATA, 5 + k, b"\x43\x01").encode()
                                 for k in range(self.count))
                self.injected = self.count
                return stale + data
            return data


def test_a_greeting_that_meets_frames_of_the_session_before_is_said_again(tmp_path):
    spoil = StaleFrames(3)  # three out of sequence in a row: the PC resets the link
    with arbitrator_rig(SYSTEMS / "transradial.json", tmp_path / "memory.bin") as (_, server), \
            PtyRelay(server.slave_path, spoil=spoil) as relay:
        session = HostLinkSession(relay.client_path, url="stale-frames", monitor=False)
        try:
            session.status()
            greetings = session.conn.greetings
            with spoil.lock:
                spoil.armed = True
            session.conn.greet()
            assert spoil.injected == 3
            assert session.conn.greetings == greetings + 1
            assert session.status() is not None
        finally:
            session.close()


def test_a_greeting_whose_reset_is_lost_is_said_again(tmp_path):
    spoil = DropResets()
    with arbitrator_rig(SYSTEMS / "transradial.json", tmp_path / "memory.bin") as (_, server), \
            PtyRelay(server.slave_path, spoil=spoil) as relay:
        session = HostLinkSession(relay.client_path, url="lost-reset", monitor=False)
        try:
            for _ in range(3):
                session.status()  # both ends count past 0
            greetings = session.conn.greetings
            with spoil.lock:
                spoil.left = 1
            session.conn.greet()
            assert spoil.dropped == 1
            assert session.conn.greetings == greetings + 1
            assert session.status() is not None  # and the link carries on
        finally:
            session.close()
