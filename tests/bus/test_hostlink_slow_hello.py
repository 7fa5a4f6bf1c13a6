"""A version-2 arbitrator whose first HELLO goes unanswered is greeted again, not taken for a
version-1 one (a loaded PC: the app's Connect said "the arbitrator speaks host-link version 1")."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from pdcp_studio.bus.hostlink.client import HostLinkSession
from pdcp_studio.bus.hostlink.testing.relay import TO_ARB, PtyRelay
from pdcp_studio.protocol.hostlink_v1 import PING, encode_v1

from .hostlink_rig import arbitrator_rig

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")

SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"


class LostUntilPing:
    """The line to the arbitrator loses everything until the PC's version-1 PING: the HELLO
    and all its repeats vanish, as when the arbitrator is too busy to answer in time."""

    def __init__(self) -> None:
        self.open = False
        self.dropped = 0

    def __call__(self, direction: str, data: bytes) -> bytes:
        if direction != TO_ARB or self.open:
            return data
        at = data.find(encode_v1(PING))
        if at < 0:
            self.dropped += len(data)
            return b""
        self.open = True
        return data[at:]


def test_an_unanswered_hello_to_a_version_2_arbitrator_is_sent_again(tmp_path):
    line = LostUntilPing()
    with arbitrator_rig(SYSTEMS / "transradial.json", tmp_path / "memory.bin") as (_, server), \
            PtyRelay(server.slave_path, spoil=line) as relay:
        session = HostLinkSession(relay.client_path, url="slow", monitor=False,
                                  ack_timeout=0.05, max_attempts=4)
        try:
            assert line.open and line.dropped > 0  # the first HELLO really was lost
            assert session.status()["devices"] == 4
        finally:
            session.close()
