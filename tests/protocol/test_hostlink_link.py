"""The link state machine: two endpoints wired through a lossy line, time passed by hand."""

from __future__ import annotations

from pdcp_studio.protocol.hostlink_link import LinkEndpoint


class Line:
    """Host ↔ arbitrator with a hook that may drop or damage what one side writes."""

    def __init__(self, **options):
        self.host = LinkEndpoint(host=True, **options)
        self.arb = LinkEndpoint(host=False, **options)
        self.now = 0.0
        self.got = {"host": [], "arb": []}
        self.spoil = None  # spoil(sender, bytes) -> bytes

    def step(self, dt: float = 0.01, rounds: int = 1) -> None:
        for _ in range(rounds):
            self.now += dt
            for name, src, dst in (("host", self.host, self.arb), ("arb", self.arb, self.host)):
                src.poll(self.now)
                data = src.take_output()
                if self.spoil is not None:
                    data = self.spoil(name, data)
                if data:
                    other = "arb" if name == "host" else "host"
                    self.got[other] += dst.receive(data, self.now)


def test_messages_arrive_in_order_once():
    line = Line()
    for n in range(5):
        line.host.send(bytes([n]), line.now)
    line.step(rounds=20)
    assert line.got["arb"] == [bytes([n]) for n in range(5)]
    assert line.host.stats.retransmits == 0


def test_a_lost_data_frame_is_sent_again_and_only_it():
    line = Line(ack_timeout=0.05)
    dropped = []

    def drop_first(sender, data):
        if sender == "host" and data and not dropped:
            dropped.append(data)
            return b""
        return data

    line.spoil = drop_first
    line.host.send(b"\x01a", line.now)
    line.host.send(b"\x01b", line.now)
    line.step(rounds=30)
    assert line.got["arb"] == [b"\x01a", b"\x01b"]
    assert line.host.stats.retransmits == 1


def test_a_lost_ack_never_delivers_a_request_twice():
    line = Line(ack_timeout=0.05)
    lost = []

    def drop_first_ack(sender, data):
        if sender == "arb" and data and not lost:
            lost.append(data)
            return b""
        return data

    line.spoil = drop_first_ack
    line.host.send(b"\x09add-link", line.now)
    line.step(rounds=30)
    assert line.got["arb"] == [b"\x09add-link"]
    assert line.arb.stats.duplicates == 1


def test_a_damaged_frame_gets_a_nak_and_a_retransmission_before_the_timeout():
    line = Line(ack_timeout=10.0)
    damaged = []

    def flip(sender, data):
        if sender == "host" and data and not damaged:
            damaged.append(data)
            data = bytearray(data)
            data[3] ^= 0x40
        return bytes(data)

    line.spoil = flip
    line.host.send(b"\x05hello", line.now)
    line.step(rounds=5)
    assert line.got["arb"] == [b"\x05hello"]
    assert line.arb.stats.naks_sent == 1 and line.host.stats.retransmits == 1


def test_no_answer_at_all_gives_up_after_the_bounded_attempts():
    line = Line(ack_timeout=0.05, max_attempts=4)
    line.spoil = lambda sender, data: b"" if sender == "host" else data
    line.host.send(b"\x02", line.now)
    line.step(dt=0.02, rounds=40)
    assert line.host.take_failed() == [b"\x02"]
    assert line.host.stats.sent_frames == 4


def test_a_restarted_peer_is_resynchronised_by_the_host():
    line = Line()
    for n in range(3):
        line.host.send(bytes([n]), line.now)
    line.step(rounds=10)
    line.arb = LinkEndpoint(host=False)  # the arbitrator rebooted: it expects seq 0
    line.host.send(b"\x07after", line.now)
    line.step(rounds=10)
    assert line.got["arb"][-1] == b"\x07after"
    assert line.host.stats.resets == 1


def test_sequence_numbers_wrap():
    line = Line()
    for n in range(300):
        line.host.send(n.to_bytes(2, "little"), line.now)
        line.step(rounds=3)
    assert line.got["arb"] == [n.to_bytes(2, "little") for n in range(300)]


def test_a_message_queued_behind_a_given_up_frame_is_still_sent():
    """host-link §3 Decision: the arbitrator gives up an event the PC never acknowledged, but
    the reply waiting behind it still goes out (the PC waits for it)."""
    line = Line(ack_timeout=0.05, max_attempts=4)
    acks = {"on": False}
    # the PC's acknowledgements are lost until it wakes up again
    line.spoil = lambda sender, data: data if sender == "arb" or acks["on"] else b""
    line.arb.send(b"\x42event", line.now)
    line.arb.send(b"\x82\x00status", line.now)  # the reply, queued behind the event
    line.step(dt=0.02, rounds=12)  # 4 sends 0.05 s apart: the event is given up
    assert line.arb.take_failed() == [b"\x42event"]
    acks["on"] = True
    line.step(dt=0.02, rounds=20)
    assert b"\x82\x00status" in line.got["host"]


def test_a_frame_numbered_like_the_last_but_carrying_another_message_resets_the_link():
    """host-link §3.2 Decision, from a trace on QEMU under load: the firmware answered an
    older HELLO as seq 0, read the PC's last RESET only then, and sent the next reply as seq 0
    again. Taken for a repeat it was acknowledged and dropped (the PC waited out its 20 s);
    now the PC resets the link, and a true repeat is still only acknowledged again."""
    from pdcp_studio.protocol.hostlink import Frame, Kind

    host = LinkEndpoint(host=True)
    assert host.receive(Frame(Kind.DATA, 0, b"\x81\x00hello").encode(), 0.0) == \
        [b"\x81\x00hello"]
    host.take_output()
    host.take_resynced()
    # the same frame again (our ACK was lost): acknowledged, not delivered, no reset
    assert host.receive(Frame(Kind.DATA, 0, b"\x81\x00hello").encode(), 0.1) == []
    assert host.take_output() == Frame(Kind.ACK, 0).encode()
    assert not host.take_resynced()
    # seq 0 again with another message: the peer numbers anew; not acknowledged as a repeat
    assert host.receive(Frame(Kind.DATA, 0, b"\x82\x00status").encode(), 0.2) == []
    assert host.take_resynced()
    out = host.take_output()
    assert Frame(Kind.RESET, 0).encode() in out and Frame(Kind.ACK, 0).encode() not in out
    # after the reset both ends count from 0: the reply sent again is delivered
    assert host.receive(Frame(Kind.DATA, 0, b"\x82\x00status").encode(), 0.3) == \
        [b"\x82\x00status"]

    arbitrator = LinkEndpoint(host=False)
    arbitrator.receive(Frame(Kind.DATA, 0, b"\x02").encode(), 0.0)
    arbitrator.take_output()
    assert arbitrator.receive(Frame(Kind.DATA, 0, b"\x05list").encode(), 0.1) == []
    out = arbitrator.take_output()  # it asks the PC to renumber, and runs nothing twice
    assert out == Frame(Kind.RESET, 0).encode()
