"""The PC's end of host link 2: one request at a time, replies matched, events passed on.

A *line* thread owns the port: it reads, runs the link state machine, hands replies to the
waiting request and events to ``on_event``, and when the port fails it reopens it with
backoff (one calm BusError per outage, never one per attempt). ``request`` sends one message
and waits: the link retransmits what is lost (bounded: ``MAX_ATTEMPTS`` sends), then the reply
must come within the request's timeout — both ends of the wait are bounded and raise errors
that say which. A greeting (RESET + HELLO, version check) happens on open and again whenever
the arbitrator has forgotten the PC (it restarted, or gave the PC up), and before the next
request after a reply timed out or the link was reset under a request (the two ends may count
differently then: docs/host-link.md §3.4). A request that only reads the arbitrator's tables
is sent once more after such a reset; any other fails, and the next one greets first.
"""

from __future__ import annotations

import logging
import queue
import threading
import time
from collections.abc import Callable
from typing import Any, TypedDict

from pdcp_studio.bus.hostlink.port import DEFAULT_BAUD, Port, SerialLine
from pdcp_studio.errors import BusTimeoutError, PdcpError, TransportError
from pdcp_studio.protocol import hostlink_messages as hm
from pdcp_studio.protocol.hostlink_link import LinkEndpoint
from pdcp_studio.protocol.hostlink_messages import Req, Status
from pdcp_studio.protocol.hostlink_v1 import PING as V1_PING
from pdcp_studio.protocol.hostlink_v1 import V1Sniffer, encode_v1

log = logging.getLogger(__name__)

#: Seconds a reply may take once the request is acknowledged (the arbitrator may be waiting
#: on the CAN bus: a device's retries, a bulk transfer, a memory write).
REPLY_TIMEOUT_S = 6.0
#: Seconds to wait for a version-1 arbitrator's answer to a version-1 PING.
V1_PROBE_S = 1.0
#: What a version-2 arbitrator's version-1 failure reply says (docs/host-link.md §4).
#: Requests that change nothing: sent again after the link was reset under them.
READ_ONLY = frozenset({Req.HELLO, Req.STATUS, Req.LIST_DEVICES, Req.GET_DEVICE,
                       Req.GET_CHANNELS, Req.LIST_LINKS, Req.CONFIG_INFO, Req.CONFIG_READ,
                       Req.RESULT_READ, Req.GET_POLICY, Req.ANCHOR_READ})
_V2_REFUSAL = f"speaks host-link version {hm.VERSION}, not version 1".encode()


class HostLinkError(PdcpError):
    """The arbitrator refused a request; ``status`` says why (docs/host-link.md §5)."""

    def __init__(self, message: str, status: Status = Status.INTERNAL) -> None:
        super().__init__(message)
        self.status = status


class VersionRefused(HostLinkError, TransportError):
    """The two ends speak different host-link versions."""


class _Lost:
    """Put in the reply queue when the request's frame was given up or the port failed."""

    def __init__(self, why: str, *, resynced: bool = False) -> None:
        self.why = why
        self.resynced = resynced


#: HELLO is said again at most this many times when the link is reset under it, each time a
#: little later (``GREET_RESET_PAUSE_S`` × the count): frames of the session before, still on
#: their way from a loaded arbitrator, are let through first instead of resetting it again.
GREET_RESETS = 6
GREET_RESET_PAUSE_S = 0.1


class LinkResynced(TransportError):
    """The link was reset while a request waited: it may or may not have been carried out."""


class _LinkOptions(TypedDict, total=False):
    """The link timings a connection was given; the protocol's defaults for the others."""

    ack_timeout: float
    max_attempts: int


class HostLinkConnection:
    """The host link on one serial port (``port`` a name to open, or an open port object)."""

    def __init__(self, port: Port | str, *, baudrate: int = DEFAULT_BAUD, where: str = "",
                 on_event: Callable[[bytes], None] | None = None,
                 on_notice: Callable[[str], None] | None = None,
                 on_greeted: Callable[[int], None] | None = None,
                 reply_timeout: float = REPLY_TIMEOUT_S, ack_timeout: float | None = None,
                 max_attempts: int | None = None) -> None:
        self.where = where or (port if isinstance(port, str) else "host link")
        self.baudrate = baudrate
        self.reply_timeout = reply_timeout
        self.on_event = on_event or (lambda message: None)
        self.on_greeted = on_greeted or (lambda count: None)
        self._link_options: _LinkOptions = {}
        if ack_timeout is not None:
            self._link_options["ack_timeout"] = ack_timeout
        if max_attempts is not None:
            self._link_options["max_attempts"] = max_attempts
        self._stop = threading.Event()
        self.line = SerialLine(port, baudrate, self.where, self._stop,
                               on_notice or (lambda text: log.warning(text)),
                               on_lost=self._lost, on_reopened=self._reopened)
        self.link = LinkEndpoint(host=True, **self._link_options)
        self.info: dict[str, Any] = {}
        self.greetings = 0
        self._greeted = False
        self._io = threading.Lock()
        self._request_lock = threading.Lock()
        self._replies: queue.SimpleQueue[bytes | _Lost] = queue.SimpleQueue()
        self._waiting: int | None = None
        self._v1 = V1Sniffer()
        self._v1_replies: queue.SimpleQueue[tuple[int, bytes]] = queue.SimpleQueue()
        self._thread = threading.Thread(target=self._run, name="pdcp host link", daemon=True)
        self._thread.start()
        try:
            self.greet()
        except BaseException:
            self.close()
            raise

    @property
    def port(self) -> Port:
        """The serial port now open (a new one after a reopen)."""
        return self.line.port

    @property
    def closed(self) -> bool:
        return self._stop.is_set()

    def close(self) -> None:
        if self._stop.is_set():
            return
        self._stop.set()
        self._thread.join(timeout=2.0)
        self.line.close()

    # -- greeting --------------------
    def greet(self) -> None:
        """RESET the link and say HELLO; VersionRefused when the versions differ."""
        with self._request_lock:
            self._greet_locked()

    def _greet_locked(self) -> None:
        resets = probes = 0
        while True:
            with self._io:
                self.link.reset(time.monotonic(), discard_partial=True)
                self.link.take_resynced()  # our own reset: nothing waits on it
                self._flush()
            try:
                status, body = self._exchange(Req.HELLO, bytes([hm.VERSION, 0xFF, 0xFF]),
                                              self.reply_timeout)
                break
            except LinkResynced:
                # The arbitrator asked to renumber while HELLO was on its way (it still
                # counted an earlier session's frames): HELLO only reads, so say it again.
                resets += 1
                if resets > GREET_RESETS:
                    raise
                self._stop.wait(GREET_RESET_PAUSE_S * resets)
            except TransportError:
                # A version-2 arbitrator refusing the version-1 PING is there, only slow
                # (a loaded PC or arbitrator): greet it once more rather than give up.
                if not self._probe_v1() or probes:
                    raise
                probes += 1
        if status is Status.VERSION:
            raise VersionRefused(f"{self.where}: the arbitrator refuses host-link version "
                                 f"{hm.VERSION}: {hm.text(body)}", status)
        if status is not Status.OK:
            raise HostLinkError(f"{self.where}: HELLO refused: {hm.text(body)}", status)
        hm.need(body, hm.HELLO.size, "HELLO reply")
        version, caps, largest = hm.HELLO.unpack_from(body)
        if version != hm.VERSION:
            raise VersionRefused(f"{self.where}: the arbitrator speaks host-link version "
                                 f"{version}; this PDCP Studio speaks version {hm.VERSION} only "
                                 "(update one of them)", Status.VERSION)
        self.info = {"version": version, "capabilities": caps, "max_payload": largest,
                     "name": hm.text(body[hm.HELLO.size:])}
        self._greeted = True
        self.greetings += 1
        self.on_greeted(self.greetings)

    def _probe_v1(self) -> bool:
        """HELLO went unanswered: is it a version-1 arbitrator? Ask it its own way.

        VersionRefused for a version-1 answer; True when a version-2 arbitrator refused the
        version-1 PING (docs/host-link.md §4: it is there and speaks our version); False
        when nothing answered."""
        while True:
            try:
                self._v1_replies.get_nowait()
            except queue.Empty:
                break
        with self._io:
            try:
                self.port.write(encode_v1(V1_PING) + b"\x00")
            except Exception:
                return False
        try:
            msg_id, payload = self._v1_replies.get(timeout=V1_PROBE_S)
        except queue.Empty:
            return False
        if msg_id == V1_PING + 2 and _V2_REFUSAL in bytes(payload):
            return True
        if msg_id in (V1_PING + 1, V1_PING + 2):
            raise VersionRefused(f"{self.where}: the arbitrator speaks host-link version 1; "
                                 f"this PDCP Studio speaks version {hm.VERSION} only (update "
                                 "the arbitrator's firmware)", Status.VERSION)
        return False

    # -- requests --------------------
    def request(self, code: Req, body: bytes = b"", *, timeout: float | None = None) -> bytes:
        """Send one request; the OK reply's body, or HostLinkError naming the arbitrator's
        reason. TransportError when the line fails, BusTimeoutError when no reply comes."""
        timeout = self.reply_timeout if timeout is None else timeout
        with self._request_lock:
            if not self._greeted:
                self._greet_locked()
            try:
                status, out = self._exchange(code, body, timeout)
            except LinkResynced:
                self._greeted = False
                if code not in READ_ONLY:
                    raise
                self._greet_locked()
                status, out = self._exchange(code, body, timeout)
            except BusTimeoutError:
                self._greeted = False  # the ends may count differently: RESET, HELLO next
                raise
            if status is Status.NOT_GREETED:  # the arbitrator restarted or gave us up
                self._greet_locked()
                status, out = self._exchange(code, body, timeout)
        if status is not Status.OK:
            name = code.name if isinstance(code, Req) else f"request 0x{int(code):02X}"
            raise HostLinkError(f"{self.where}: {name} refused "
                                f"({status.name.lower().replace('_', ' ')}): {hm.text(out)}",
                                status)
        return out

    def _exchange(self, code: Req, body: bytes, timeout: float) -> tuple[Status, bytes]:
        name = code.name if isinstance(code, Req) else f"request 0x{int(code):02X}"
        if self._stop.is_set():
            raise TransportError(f"{self.where}: the host link is closed")
        if self.line.down:
            raise TransportError(f"{self.where}: the serial port is lost; reopening it")
        message = bytes([code]) + bytes(body)
        if len(message) > hm.MAX_BODY + 1:
            raise ValueError(f"{name}: a message of {len(message)} bytes does not fit "
                             "a frame")
        while True:  # drop what a timed-out request left behind
            try:
                self._replies.get_nowait()
            except queue.Empty:
                break
        self._waiting = hm.reply_code(code)
        with self._io:
            self.link.send(message, time.monotonic())
            self._flush()
        deadline = time.monotonic() + timeout
        # bounded even if the line thread stalls: every send's ACK wait, then the reply's
        hard = deadline + self.link.max_attempts * self.link.ack_timeout + 1.0
        try:
            while True:
                if time.monotonic() > hard:
                    raise BusTimeoutError(f"{self.where}: no reply to {name} within "
                                          f"{hard - deadline + timeout:.1f} s")
                left = deadline - time.monotonic()
                try:
                    reply = self._replies.get(timeout=max(left, 0.0) if left > 0 else 0.0)
                except queue.Empty:
                    if not self.link.idle:  # not even acknowledged yet: the link decides
                        deadline = time.monotonic() + 0.05
                        continue
                    raise BusTimeoutError(f"{self.where}: no reply to {name} within "
                                          f"{timeout:g} s") from None
                if isinstance(reply, _Lost):
                    if reply.resynced:
                        raise LinkResynced(f"{self.where}: {name} failed: {reply.why}")
                    raise TransportError(f"{self.where}: {name} failed: {reply.why}")
                if len(reply) < 2:
                    continue
                try:
                    status = Status(reply[1])
                except ValueError:
                    status = Status.INTERNAL
                return status, bytes(reply[2:])
        finally:
            self._waiting = None

    # -- the line thread --------------------
    def _flush(self) -> None:
        data = self.link.take_output()
        if data:
            try:
                self.port.write(data)
            except Exception as err:
                log.debug("%s: write failed: %s", self.where, err)

    def _run(self) -> None:
        while not self._stop.is_set():
            data = self.line.read()
            if data is None:
                continue
            now = time.monotonic()
            if data and not self._greeted:
                for found in self._v1.feed(data):
                    self._v1_replies.put(found)
            with self._io:
                delivered = self.link.receive(data, now) if data else []
                self.link.poll(now)
                failed = self.link.take_failed()
                resynced = self.link.take_resynced()
                self._flush()
            if resynced and self._waiting is not None:
                self._replies.put(_Lost("the link was reset (the two ends counted frames "
                                        "differently); it may not have been carried out",
                                        resynced=True))
            if failed and self._waiting is not None:
                self._replies.put(_Lost(f"no acknowledgement after "
                                        f"{self.link.max_attempts} attempts (is the "
                                        "arbitrator on and the cable connected?)"))
            for message in delivered:
                if message and message[0] & hm.REPLY:
                    if message[0] == self._waiting:
                        self._replies.put(message)
                elif message:
                    try:
                        self.on_event(message)
                    except Exception:
                        log.exception("%s: an event handler failed", self.where)

    def _lost(self, err: object) -> None:
        """The port failed: greet again once it is back; a waiting request fails now."""
        self._greeted = False
        if self._waiting is not None:
            self._replies.put(_Lost(f"the serial port was lost ({err})"))

    def _reopened(self) -> None:
        with self._io:
            self.link = LinkEndpoint(host=True, **self._link_options)
