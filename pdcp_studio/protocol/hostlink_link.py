"""Host link 2, the link state machine: stop-and-wait ARQ with ACK, NAK and retransmission.

Both ends run the same machine (docs/host-link.md §3). Each direction numbers its DATA frames
0…255 and wraps; one DATA frame at a time is unacknowledged, so only a lost frame is ever
sent again and the retransmit buffer is one frame. The receiver:

- DATA with the expected seq → delivered, ACK(seq), expected + 1;
- DATA with expected − 1 (our ACK was lost) → ACK again, *not* delivered: a request is never
  executed twice; but one whose message differs from the last delivered is no repeat: the
  peer numbers anew from a RESET it read late, and the two ends reset (the host sends RESET,
  the arbitrator asks for one) rather than lose it without a word;
- DATA with any other seq → NAK(expected), not delivered;
- a frame that fails COBS, length or CRC → NAK(expected), so the sender need not wait.

The sender, on ACK(inflight) or NAK(inflight + 1) (the peer has it), sends the next frame; on
NAK(inflight) or after ``ack_timeout`` it sends the same frame again, at most
``max_attempts`` times in all, then gives the message up and reports it. A NAK naming any
other seq means the two ends disagree (the peer restarted, a RESET was lost, or the peer gave
up a frame and moved on): the host sends RESET and renumbers from 0; the arbitrator cannot
renumber alone, so it sends RESET to ask the host to (a frame given up while the line was cut
would otherwise leave the host NAKing a number the arbitrator never sends again, for ever).
The host also resets after ``RESYNC_AFTER`` out-of-sequence DATA frames in a row. RESET drops
the frame in flight and everything queued, at both ends; ``take_resynced`` tells the owner.

Pure: the caller passes the time (``now``, seconds) and moves the bytes.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

from pdcp_studio.errors import FrameError
from pdcp_studio.protocol.hostlink import Frame, FrameReader, Kind

#: Seconds to wait for an ACK before sending the same frame again (at 128000 baud the largest
#: frame takes 20.5 ms each way; the rest is slack for a busy host).
ACK_TIMEOUT_S = 0.25
#: Sends of one DATA frame before it is given up (bounded: 8 × 0.25 s = 2 s).
MAX_ATTEMPTS = 8
#: Messages waiting behind the one in flight (the arbitrator's event queue is this deep).
OUTBOX_LIMIT = 64
#: Out-of-sequence DATA frames in a row after which the host resets the link (one can be a
#: stray retransmission; a run means the two ends count differently).
RESYNC_AFTER = 3


@dataclass
class _Inflight:
    seq: int
    payload: bytes
    attempts: int = 0
    deadline: float = 0.0


@dataclass
class LinkStats:
    sent_frames: int = 0
    retransmits: int = 0
    bad_frames: int = 0
    duplicates: int = 0
    out_of_order: int = 0
    naks_sent: int = 0
    resets: int = 0
    given_up: int = 0
    dropped: int = 0  # outbox overflow
    reset_dropped: int = 0  # messages dropped by a RESET (in flight or queued)
    resync_asked: int = 0  # RESETs the arbitrator sent to ask the host to renumber
    last_error: str = ""
    errors: list[str] = field(default_factory=list)


class LinkEndpoint:
    """One end of the link. ``host=True`` for the PC (it sends RESET to resynchronise)."""

    def __init__(self, *, host: bool, ack_timeout: float = ACK_TIMEOUT_S,
                 max_attempts: int = MAX_ATTEMPTS, outbox_limit: int = OUTBOX_LIMIT) -> None:
        self.host = host
        self.ack_timeout = ack_timeout
        self.max_attempts = max_attempts
        self.outbox_limit = outbox_limit
        self.stats = LinkStats()
        self._reader = FrameReader()
        self._tx_seq = 0
        self._rx_expected = 0
        self._outbox: deque[bytes] = deque()
        self._inflight: _Inflight | None = None
        self._control: list[bytes] = []  # ACK/NAK/RESET, sent before any DATA
        self._wire = bytearray()
        self._failed: list[bytes] = []
        self._out_of_order_run = 0
        self._resynced = False
        #: The last message delivered since the last reset: a true repeat carries it again.
        self._last_delivered: bytes | None = None
        #: What the last reset dropped (the owner may count lost events from it).
        self.reset_dropped: list[bytes] = []

    # -- the application's side -----------------------------------------------------------
    def send(self, payload: bytes, now: float) -> bool:
        """Queue one message; False (and counted) when the outbox is full."""
        if len(self._outbox) >= self.outbox_limit:
            self.stats.dropped += 1
            return False
        self._outbox.append(bytes(payload))
        self._pump(now)
        return True

    def reset(self, now: float, *, discard_partial: bool = False) -> None:
        """Start both directions again at 0 and drop what is queued; the host tells the peer.
        ``discard_partial`` also forgets a frame half read (when the owner resets between
        reads, never while a read's frames are handled: the next frame may be half read)."""
        self._tx_seq = self._rx_expected = 0
        self._last_delivered = None
        dropped = ([self._inflight.payload] if self._inflight else []) + list(self._outbox)
        self.stats.reset_dropped += len(dropped)
        self.reset_dropped = dropped[-self.outbox_limit:]
        self._out_of_order_run = 0
        self._resynced = True
        self._outbox.clear()
        self._inflight = None
        self._control.clear()
        self._wire.clear()
        if discard_partial:
            self._reader.discard()  # a frame broken off before the reset is not worth a NAK
        if self.host:
            # 0x00 first ends whatever the peer has half-read, so the RESET itself is whole
            self._control.append(b"\x00" + Frame(Kind.RESET, 0).encode())
            self.stats.resets += 1

    @property
    def queued(self) -> int:
        """Messages waiting behind the one in flight."""
        return len(self._outbox)

    @property
    def idle(self) -> bool:
        """Nothing in flight and nothing queued."""
        return self._inflight is None and not self._outbox

    def take_failed(self) -> list[bytes]:
        """Messages given up since the last call (the peer never acknowledged them)."""
        failed, self._failed = self._failed, []
        return failed

    def take_resynced(self) -> bool:
        """True once after the link was reset (by us or the peer): what was in flight or
        queued is gone, and the owner decides what to send again."""
        resynced, self._resynced = self._resynced, False
        return resynced

    def next_deadline(self) -> float | None:
        return self._inflight.deadline if self._inflight and self._inflight.attempts else None

    # -- the line's side --------------------------------------------------------------------
    def receive(self, data: bytes, now: float) -> list[bytes]:
        """Feed bytes read from the line; returns the messages delivered, in order."""
        delivered: list[bytes] = []
        for item in self._reader.feed(data):
            if isinstance(item, FrameError):
                self.stats.bad_frames += 1
                self.stats.last_error = str(item)
                self._nak()
                continue
            self._on_frame(item, now, delivered)
        self._pump(now)
        return delivered

    def poll(self, now: float) -> None:
        """Retransmit or give up the frame in flight when its ACK is overdue."""
        flight = self._inflight
        if flight is None or not flight.attempts or now < flight.deadline:
            return
        if flight.attempts >= self.max_attempts:
            self.stats.given_up += 1
            self._failed.append(flight.payload)
            self._inflight = None
            self._pump(now)
            return
        self._transmit(flight, now)
        self.stats.retransmits += 1

    def take_output(self) -> bytes:
        """Bytes to write to the line now (control frames first)."""
        out = b"".join(self._control) + bytes(self._wire)
        self._control.clear()
        self._wire.clear()
        return out

    # -- inside --------------------
    def _on_frame(self, frame: Frame, now: float, delivered: list[bytes]) -> None:
        if frame.kind is Kind.DATA:
            if frame.seq == self._rx_expected:
                self._out_of_order_run = 0
                self._rx_expected = (self._rx_expected + 1) & 0xFF
                self._control.append(Frame(Kind.ACK, frame.seq).encode())
                delivered.append(frame.payload)
                self._last_delivered = frame.payload
            elif frame.seq == (self._rx_expected - 1) & 0xFF:
                if self._last_delivered is not None and frame.payload != self._last_delivered:
                    # Not a repeat (a repeat is the same frame): the peer numbers anew from a
                    # RESET it read late, after it had answered with the number we last took.
                    # Taken as a repeat this message would be lost without a word.
                    self.stats.out_of_order += 1
                    if self.host:
                        self.reset(now)
                    else:
                        self._ask_reset()
                    return
                self.stats.duplicates += 1
                self._control.append(Frame(Kind.ACK, frame.seq).encode())
            else:
                self.stats.out_of_order += 1
                self._out_of_order_run += 1
                if self.host and self._out_of_order_run >= RESYNC_AFTER:
                    self.reset(now)
                else:
                    self._nak()
        elif frame.kind is Kind.ACK:
            if self._inflight is not None and frame.seq == self._inflight.seq:
                self._inflight = None
        elif frame.kind is Kind.NAK:
            self._on_nak(frame.seq, now)
        elif frame.kind is Kind.RESET:
            if self.host:
                self.reset(now)  # the arbitrator asks us to renumber: RESET back
            else:
                self.stats.resets += 1
                self.reset(now)

    def _on_nak(self, seq: int, now: float) -> None:
        flight = self._inflight
        if flight is None:
            if seq != self._tx_seq and not self.host:
                self._ask_reset()  # the host waits for a frame we gave up
            return
        if seq == flight.seq:
            if flight.attempts >= self.max_attempts:
                return  # poll() gives it up
            self._transmit(flight, now)
            self.stats.retransmits += 1
        elif seq == (flight.seq + 1) & 0xFF:
            self._inflight = None  # the peer has it; its ACK was lost
        elif self.host:
            # The peer counts differently (it restarted, or our RESET was lost): start over.
            payload = flight.payload
            queued = list(self._outbox)
            self.reset(now)
            self._outbox.extend([payload, *queued])
            self._resynced = False  # nothing lost: all of it is sent again
        else:
            self._ask_reset()

    def _ask_reset(self) -> None:
        """The arbitrator's answer to a NAK naming a frame it will not send again."""
        self.stats.resync_asked += 1
        self._control.append(Frame(Kind.RESET, 0).encode())

    def _nak(self) -> None:
        self.stats.naks_sent += 1
        self._control.append(Frame(Kind.NAK, self._rx_expected).encode())

    def _pump(self, now: float) -> None:
        if self._inflight is None and self._outbox:
            self._inflight = _Inflight(self._tx_seq, self._outbox.popleft())
            self._tx_seq = (self._tx_seq + 1) & 0xFF
            self._transmit(self._inflight, now)

    def _transmit(self, flight: _Inflight, now: float) -> None:
        flight.attempts += 1
        flight.deadline = now + self.ack_timeout
        self.stats.sent_frames += 1
        self._wire += Frame(Kind.DATA, flight.seq, flight.payload).encode()
