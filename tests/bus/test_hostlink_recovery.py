"""The host link always recovers (issue 24 item 1): a relay between two pseudo-terminals drops
every byte for a while at each point of an exchange — the request on its way, the reply half
sent, an event pushed — and the next request after the line is back succeeds within
``RECOVERY_BOUND_S`` (docs/host-link.md §3.4 states the bound; measured figures are printed).
"""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

from pdcp_studio.bus.hostlink.client import HostLinkSession
from pdcp_studio.bus.hostlink.testing.relay import (
    Cutter,
    PtyRelay,
    cut_during_request,
)
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link
from pdcp_studio.protocol import hostlink_messages as hm
from pdcp_studio.protocol.hostlink_link import LinkEndpoint

from .hostlink_rig import arbitrator_rig, wait_for

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")

VID = 0x0A51
LINK = Link(ChannelRef(VID, 257, 101, 1), ChannelRef(VID, 513, 201, 1))
SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"
#: How long the line stays dead (the issue's 5 s cut).
CUT_S = 5.0
#: The next request after the line is back answers within this (docs/host-link.md §3.4):
#: one resync (RESET from the arbitrator, or the PC's after 3 frames out of sequence), a
#: greeting and the request again; measured 0.00–0.8 s (1.6 s against an arbitrator that
#: ignores the NAK) on an idle machine, once 4.3 s at a load average of 18 (a greeting whose
#: first HELLO went unanswered): the bound is the reply timeout, 6 s.
RECOVERY_BOUND_S = 6.0


@pytest.fixture(scope="module")
def rig(tmp_path_factory):
    memory = tmp_path_factory.mktemp("hostlink-recovery") / "memory.bin"
    with arbitrator_rig(SYSTEMS / "transradial.json", memory) as parts:
        yield parts


def _recovers(session: HostLinkSession, cutter: Cutter) -> float:
    """Wait for the line to be back; the seconds the next request takes (it must succeed)."""
    assert wait_for(lambda: not cutter.cutting, CUT_S + 10.0)
    t0 = time.monotonic()
    session.conn.request(hm.Req.LIST_DEVICES, b"\x00\x00")
    took = time.monotonic() - t0
    print(f"recovered in {took:.3f} s")
    assert took < RECOVERY_BOUND_S
    return took


@pytest.mark.parametrize("point", ["request", "reply", "reply-half", "event"])
def test_the_next_request_after_a_cut_succeeds_within_the_bound(rig, point):
    arbitrator, server = rig
    cutter = Cutter()
    with PtyRelay(server.slave_path, spoil=cutter) as relay:
        session = HostLinkSession(relay.client_path, url=f"cut-{point}", monitor=False)
        try:
            session.status()
            long_request = lambda: session.conn.request(  # noqa: E731
                hm.Req.GET_DEVICE, hm.KEY.pack(VID, 257, 101))
            if not cut_during_request(point, cutter, session, long_request, CUT_S):
                # an event pushed into a dead line: the arbitrator gives it up
                cutter.cut_now(CUT_S)
                arbitrator.add_link(LINK)
                time.sleep(CUT_S)
                arbitrator.remove_link(LINK)
            _recovers(session, cutter)
            _recovers(session, cutter)  # and stays recovered
            assert relay.total > 0
        finally:
            session.close()


def test_an_arbitrator_that_ignores_a_nak_for_a_given_up_frame_is_reset_by_the_pc(
        rig, monkeypatch):
    """Today's firmware (no RESET answer to such a NAK): the PC resets after 3 frames out of
    sequence in a row."""
    arbitrator, server = rig
    monkeypatch.setattr(LinkEndpoint, "_ask_reset", lambda self: None)
    cutter = Cutter()
    with PtyRelay(server.slave_path, spoil=cutter) as relay:
        session = HostLinkSession(relay.client_path, url="cut-old", monitor=False)
        try:
            session.status()
            cutter.cut_now(CUT_S)
            arbitrator.add_link(LINK)
            time.sleep(CUT_S)
            arbitrator.remove_link(LINK)
            _recovers(session, cutter)
            assert relay.total > 0
        finally:
            session.close()


def test_the_arbitrator_answers_a_nak_for_a_given_up_frame_with_reset():
    from pdcp_studio.protocol.hostlink import Frame, FrameReader, Kind

    arb = LinkEndpoint(host=False, ack_timeout=0.01, max_attempts=2)
    arb.send(b"\x43event", 0.0)
    arb.take_output()
    for t in (0.02, 0.04, 0.06):
        arb.poll(t)
    assert arb.take_failed() == [b"\x43event"]  # given up: the next frame is seq 1
    arb.take_output()
    arb.receive(Frame(Kind.NAK, 0).encode(), 0.1)  # the host still waits for seq 0
    frames = list(FrameReader().feed(arb.take_output()))
    assert [f.kind for f in frames] == [Kind.RESET]
    arb.receive(Frame(Kind.NAK, 1).encode(), 0.2)  # the next one: a bad frame, nothing more
    assert arb.take_output() == b""


def test_the_host_resets_after_three_frames_out_of_sequence():
    from pdcp_studio.protocol.hostlink import Frame, FrameReader, Kind

    host = LinkEndpoint(host=True)
    for _ in range(2):
        host.receive(Frame(Kind.DATA, 5, b"\xc2\x03").encode(), 0.0)
    assert not host.take_resynced()
    host.receive(Frame(Kind.DATA, 5, b"\xc2\x03").encode(), 0.0)
    assert host.take_resynced()
    kinds = [f.kind for f in FrameReader().feed(host.take_output())]
    assert kinds[-1] is Kind.RESET
