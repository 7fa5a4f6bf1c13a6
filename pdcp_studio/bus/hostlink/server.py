"""Serve host link 2 (docs/host-link.md) on a serial port: the arbitrator's side.

``pdcp-studio arbitrator --bus can:… --host-serial PORT`` answers a PC's requests on PORT the
way a hardware arbitrator's firmware would. Two threads: the *line* thread reads the port,
runs the link state machine (protocol/hostlink_link.py), pushes queued events and monitor
traffic, and reopens a dropped port with backoff; the *request* thread answers one request at a
time (a parameter read may wait on the CAN bus, and the line must keep ACKing meanwhile).
The handlers are in ``hostlink_handlers``.
"""

from __future__ import annotations

import logging
import queue
import threading
import time
from typing import TYPE_CHECKING

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.hostlink.handlers import Handlers
from pdcp_studio.bus.hostlink.monitor import MonitorFeed
from pdcp_studio.bus.hostlink.port import DEFAULT_BAUD, Port, SerialLine
from pdcp_studio.protocol import hostlink_messages as hm
from pdcp_studio.protocol.hostlink_link import LinkEndpoint
from pdcp_studio.protocol.hostlink_v1 import V1Sniffer, encode_v1

if TYPE_CHECKING:
    from pdcp_studio.bus.arbitrator.core import Arbitrator

log = logging.getLogger(__name__)

#: Requests answered from the arbitrator's tables, on the line thread (no CAN traffic, no
#: waiting): a scan's round trips skip the hand-over to the request thread.
_FROM_TABLES = {bytes([code]) for code in (
    hm.Req.STATUS, hm.Req.LIST_DEVICES, hm.Req.GET_DEVICE, hm.Req.GET_CHANNELS,
    hm.Req.LIST_LINKS, hm.Req.CONFIG_INFO, hm.Req.CONFIG_READ, hm.Req.RESULT_READ,
    hm.Req.GET_POLICY)}
#: Events kept while the PC is slow to acknowledge; beyond this they are counted as lost.
EVENT_QUEUE = 16


class HostLinkServer:
    """Answers host-link requests from ``port`` with ``arbitrator``; close it (or ``with``)."""

    def __init__(self, arbitrator: Arbitrator, port: Port | str, *, baudrate: int = DEFAULT_BAUD,
                 name: str = "host link") -> None:
        self.arbitrator = arbitrator
        self.name = name
        self.baudrate = baudrate
        self._stop = threading.Event()
        self.line = SerialLine(port, baudrate, name, self._stop,
                               lambda text: log.warning("%s", text),
                               on_lost=lambda _err: self.lost_host(), on_reopened=self._reopened)
        self.link = LinkEndpoint(host=False)
        self.handlers = Handlers(arbitrator, self)
        self.monitor = MonitorFeed(getattr(self.port, "baudrate", 0) or baudrate)
        self.events_lost = 0
        self.changes = 0
        self._lost_pending = False
        self._io = threading.Lock()
        self._requests: queue.SimpleQueue[bytes | None] = queue.SimpleQueue()
        self._events: queue.SimpleQueue[bytes] = queue.SimpleQueue()
        self._v1 = V1Sniffer()
        self._unsubscribe = arbitrator.subscribe(self._on_event)
        self._line = threading.Thread(target=self._run_line, name=f"pdcp {name} line",
                                      daemon=True)
        self._worker = threading.Thread(target=self._run_requests, name=f"pdcp {name} requests",
                                        daemon=True)
        self._line.start()
        self._worker.start()

    @property
    def port(self) -> Port:
        """The serial port now open (a new one after a reopen)."""
        return self.line.port

    @property
    def slave_path(self) -> str | None:
        """Where the PC connects when serving on a new pseudo-terminal."""
        return getattr(self.port, "slave_path", None)

    @property
    def bad_frames(self) -> int:
        return self.link.stats.bad_frames

    @property
    def greeted(self) -> bool:
        return self.handlers.greeted

    def __enter__(self) -> HostLinkServer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        if self._stop.is_set():
            return
        self._stop.set()
        self._unsubscribe()
        self._requests.put(None)
        self._line.join(timeout=2.0)
        self._worker.join(timeout=5.0)
        self.line.close()

    # -- sending --------------------
    def post(self, message: bytes) -> None:
        """Send one message (a reply) now; thread-safe."""
        with self._io:
            self.link.send(message, time.monotonic())
            self._flush()

    def _flush(self) -> None:
        data = self.link.take_output()
        if data:
            try:
                self.port.write(data)
            except Exception as err:
                log.debug("%s: write failed: %s", self.name, err)

    # -- events (arbitrator threads: only enqueue) ----------------------------------------------
    def _on_event(self, event: object) -> None:
        if isinstance(event, ev.FrameSeen | ev.ChannelValue):
            self.monitor.observe(event, self.arbitrator)
            return
        message = self.handlers.event_message(event)
        if message is not None:
            if not isinstance(event, ev.BusError):
                self.changes = (self.changes + 1) & 0xFFFF
            self._events.put(message)

    def lost_host(self) -> None:
        """The PC stopped acknowledging: forget it (it greets again), end its transaction."""
        self.handlers.forget_host()
        self.monitor.stop()

    # -- the line thread --------------------
    def _run_line(self) -> None:
        while not self._stop.is_set():
            data = self.line.read()
            if data is None:
                continue
            now = time.monotonic()
            if data:
                self._refuse_v1(data)
            with self._io:
                delivered = self.link.receive(data, now) if data else []
                self.link.poll(now)
                if self.link.take_failed():
                    self.lost_host()
                self._count_reset_drops()
                self._push_events(now)
                self._flush()
            for message in delivered:
                if message[:1] in _FROM_TABLES and self._requests.empty():
                    reply = self.handlers.handle(message)  # answered from the tables at once
                    if reply is not None:
                        self.post(reply)
                else:
                    self._requests.put(message)

    def _count_reset_drops(self) -> None:
        """A RESET dropped queued events: counted as lost, so the PC (told by EVENTS_LOST,
        the session being still greeted) reads its tables again rather than trusting them."""
        if not self.link.take_resynced():
            return
        events = [m for m in self.link.reset_dropped if m and 0x40 <= m[0] < hm.REPLY
                  and m[0] not in (hm.Event.FRAMES, hm.Event.CHANNEL_COUNTS)]
        if events and self.handlers.greeted:
            self.events_lost = (self.events_lost + len(events)) & 0xFFFF
            self._lost_pending = True

    def _push_events(self, now: float) -> None:
        greeted = self.handlers.greeted
        while True:
            try:
                message = self._events.get_nowait()
            except queue.Empty:
                break
            if not greeted:
                continue
            if self.link.queued >= EVENT_QUEUE:
                self.events_lost += 1
                self._lost_pending = True
                continue
            self.link.send(message, now)
        if greeted and self._lost_pending and self.link.queued < EVENT_QUEUE:
            self._lost_pending = False
            self.link.send(bytes([hm.Event.EVENTS_LOST]) + self.events_lost.to_bytes(2, "little"),
                           now)
        if greeted:
            for message in self.monitor.take(now, self.link.idle):
                self.link.send(message, now)

    def _refuse_v1(self, data: bytes) -> None:
        """A version-1 PC gets a version-1 failure reply saying why (docs/host-link.md §4)."""
        for msg_id, _ in self._v1.feed(data):
            if 0x10 <= msg_id <= 0x37 and (msg_id - 0x10) % 3 == 0:  # a version-1 request
                text = (f"this arbitrator speaks host-link version {hm.VERSION}, not version "
                        "1: update PDCP Studio").encode()
                with self._io:
                    try:
                        self.port.write(encode_v1(msg_id + 2, text))
                    except Exception as err:
                        log.debug("%s: write failed: %s", self.name, err)

    def _reopened(self) -> None:
        with self._io:
            self.link = LinkEndpoint(host=False)

    # -- the request thread --------------------
    def _run_requests(self) -> None:
        while True:
            message = self._requests.get()
            if message is None or self._stop.is_set():
                return
            reply = self.handlers.handle(message)
            if reply is not None:
                self.post(reply)
