"""A session over an arbitrator's serial host link (`serial:PORT[@BAUD]` bus URLs).

The same session face as a CAN or simulated bus (bus/session.py), so the CLI and the desktop
app need not know how the arbitrator is reached. The host always initiates (docs/host-link.md):
one request at a time under a lock, each with a timeout; read-only requests are retried, writes
are not (a lost reply to ADD_LINK must not add the link twice — the next GET_SYSTEM tells). A
poll thread asks for events and keeps a cached copy of the system current.

Plans are computed here with the engine on the arbitrator's system and stored configuration,
then carried out action by action, so what the user previewed is exactly what is applied.
"""

from __future__ import annotations

import json
import logging
import threading
import time
from collections.abc import Callable
from typing import Any

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.session_api import TransactingMixin
from pdcp_studio.bus.transaction import Change, Policy, Status, TransactionResult
from pdcp_studio.errors import BusTimeoutError, PdcpError, TransportError
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System
from pdcp_studio.protocol import hostlink as hl
from pdcp_studio.protocol.hostlink import HostCommand, HostMessage

log = logging.getLogger(__name__)

#: Seconds to wait for one reply (a 60 kB payload at 128 kbaud takes ~4.7 s; see _timeout_for).
REPLY_TIMEOUT_S = 1.0
#: Extra attempts for requests that change nothing on the arbitrator.
READ_RETRIES = 2
#: Extra seconds a TRANSACT reply may take (the arbitrator writes and reads back first).
TRANSACT_TIMEOUT_S = 20.0
#: Seconds between two POLL_EVENTS requests.
POLL_INTERVAL_S = 0.2
#: How long the arbitrator's system must stay the same to count as settled.
SETTLE_QUIET_S = 0.6
_READ_ONLY = {HostCommand.PING, HostCommand.GET_SYSTEM, HostCommand.GET_PARAMETER,
              HostCommand.READ_CONFIGURATION, HostCommand.PREVIEW_PLAN,
              HostCommand.READ_POLICY}


class HostLinkError(PdcpError):
    """The arbitrator answered a request with its failure reply; the message says why."""


def _link_payload(link: Link) -> bytes:
    return hl.pack_link(tuple(link.output), tuple(link.input))


def _event_from_json(doc: dict) -> object | None:
    kind = doc.get("kind")
    if kind in ("DeviceJoined", "DeviceLeft"):
        k = doc["key"]
        key = DeviceKey(k["vid"], k["pid"], k["serial"])
        return ev.DeviceJoined(key) if kind == "DeviceJoined" else ev.DeviceLeft(key)
    if kind in ("LinkMade", "LinkRemoved"):
        d = doc["link"]
        link = Link(ChannelRef(**d["output"]), ChannelRef(**d["input"]))
        return ev.LinkMade(link) if kind == "LinkMade" else ev.LinkRemoved(link)
    if kind == "BusError":
        return ev.BusError(str(doc.get("message", "")), str(doc.get("error_kind", "")))
    if kind == "TransactionDone":
        return ev.TransactionDone(TransactionResult.from_json(doc.get("result", {})))
    if kind == "TerminalsUnconnected":
        return ev.TerminalsUnconnected(tuple(ChannelRef(**r) for r in doc.get("refs", [])),
                                       str(doc.get("why", "")))
    if kind == "PlanApplied":
        return ev.PlanApplied(doc.get("plan", {}))
    return None


class HostLinkSession(TransactingMixin):
    """A live arbitrator reached over a serial line. Close it (or use ``with``).

    Implements :class:`pdcp_studio.bus.session_api.BusSession`."""

    @property
    def closed(self) -> bool:
        return self._closed.is_set()

    def __init__(self, port: Any, *, url: str = "", reply_timeout: float = REPLY_TIMEOUT_S,
                 poll_interval: float = POLL_INTERVAL_S) -> None:
        self.url = url
        self.port = port
        self.reply_timeout = reply_timeout
        self.bad_frames = 0
        self._reader = hl.FrameReader()
        self._io = threading.Lock()
        self._subscribers = ev.Subscribers(url or "host link")
        self._system: System | None = None
        self._stale = True
        self._closed = threading.Event()
        self.info = json.loads(self.request(HostCommand.PING))
        self._refresh()
        self._poller = threading.Thread(target=self._poll_loop, args=(poll_interval,),
                                        name="pdcp host-link poll", daemon=True)
        self._poller.start()

    def __enter__(self) -> HostLinkSession:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- the wire ---------------------------------------------------------------------
    def _timeout_for(self, size: int) -> float:
        baud = getattr(self.port, "baudrate", 0) or 0
        wire = (size + 6) * 10 / baud if baud else 0.0
        return self.reply_timeout + 2 * wire

    def request(self, command: HostCommand, payload: bytes = b"", *,
                reply_size_hint: int = 0) -> bytes:
        """Send one request and return the success payload (HostLinkError on a failure reply)."""
        if self._closed.is_set():
            raise TransportError(f"host link {self.url or self.port}: the session is closed")
        attempts = 1 + (READ_RETRIES if command in _READ_ONLY else 0)
        frame = HostMessage(int(command), payload).encode()
        timeout = self._timeout_for(len(payload) + reply_size_hint)
        if command == HostCommand.TRANSACT:  # interlock, writes, read-back on the far side
            timeout += TRANSACT_TIMEOUT_S
        with self._io:
            for attempt in range(1, attempts + 1):
                try:
                    self.port.reset_input_buffer()
                    self.port.write(frame)
                    reply = self._await(command, timeout)
                except Exception as err:  # SerialException, OSError, termios.error: a lost line
                    raise TransportError(
                        f"host link {self.url or self.port}: {command.name} failed: {err} "
                        "(is the cable connected?)") from err
                if reply is not None:
                    break
                log.info("host link: no reply to %s (attempt %d/%d)", command.name, attempt,
                         attempts)
            else:
                raise BusTimeoutError(
                    f"host link {self.url or self.port}: no reply to {command.name} within "
                    f"{timeout:.1f} s ({attempts} attempt{'s' if attempts > 1 else ''})")
        if reply.msg_id == hl.reply_fail(command):
            raise HostLinkError(reply.payload.decode("utf-8", errors="replace"))
        return reply.payload

    def _await(self, command: HostCommand, timeout: float) -> HostMessage | None:
        deadline = time.monotonic() + timeout
        wanted = {hl.reply_ok(command), hl.reply_fail(command)}
        while time.monotonic() < deadline:
            data = self.port.read(max(1, getattr(self.port, "in_waiting", 0) or 1))
            if not data:
                continue
            for message in self._reader.feed(data):
                if message.msg_id in wanted:
                    return message
                log.debug("host link: ignoring message 0x%02X", message.msg_id)
            self.bad_frames = self._reader.errors
        return None

    # -- events -----------------------------------------------------------------------
    def subscribe(self, callback: Callable[[object], None]) -> Callable[[], None]:
        """Call ``callback(event)`` from the poll thread; returns the unsubscribe function."""
        return self._subscribers.add(callback)

    def _emit(self, event: object) -> None:
        self._subscribers.emit(event)

    def _poll_loop(self, interval: float) -> None:
        reported = False
        while not self._closed.wait(interval):
            try:
                docs = json.loads(self.request(HostCommand.POLL_EVENTS))
                if self._stale:
                    self._refresh()
                reported = False
            except PdcpError as err:
                if self._closed.is_set():
                    return
                if not reported:  # say it once per outage, not every poll
                    self._emit(ev.BusError(str(err)))
                    reported = True
                continue
            for doc in docs:
                event = _event_from_json(doc)
                if event is None:
                    continue
                if not isinstance(event, ev.BusError):
                    self._stale = True
                self._emit(event)

    # -- the session face -------------------------------------------------------------
    def _refresh(self) -> System:
        from pdcp_studio.storage import system_file

        text = self.request(HostCommand.GET_SYSTEM).decode("utf-8")
        system = system_file.loads(text, name=f"{self.url or 'host link'} GET_SYSTEM")
        self._system = system
        self._stale = False
        return system

    def system(self) -> System:
        """A copy of the arbitrator's system (node IDs, presence, links)."""
        system = self._refresh() if self._stale or self._system is None else self._system
        return system.copy()

    def wait_settled(self, timeout: float, quiet: float = SETTLE_QUIET_S) -> bool:
        """Wait until the arbitrator's devices and links stop changing for ``quiet`` seconds.

        The arbitrator binds and starts up on its own; from here the only sign that it is done
        is a system that has devices and stays the same. False when ``timeout`` passes first.
        """
        deadline = time.monotonic() + timeout
        last, since = None, time.monotonic()
        while True:
            system = self._refresh()
            shape = (frozenset((k, d.present) for k, d in system.devices.items()),
                     frozenset(system.links))
            now = time.monotonic()
            if shape != last:
                last, since = shape, now
            elif system.devices and now - since >= quiet:
                return True
            if now >= deadline:
                return False
            time.sleep(min(0.1, max(0.0, deadline - now)))

    def scan(self, progress: Callable[[int, int, str], None] | None = None,
             cancel: threading.Event | None = None) -> System:
        """The arbitrator already knows its bus: one GET_SYSTEM answers a scan."""
        if progress:
            progress(0, 1, "Asking the arbitrator for its system")
        system = self._refresh().copy()
        if progress:
            progress(1, 1, f"{len(system.devices)} devices")
        return system

    def get_parameter(self, key: DeviceKey, param: int, channel: int = 0, *,
                      timeout: float | None = None) -> bytes:
        return self.request(HostCommand.GET_PARAMETER,
                            hl.pack_param(key.vid, key.pid, key.serial, channel, param))

    def set_parameter(self, key: DeviceKey, param: int, channel: int, value: bytes, *,
                      timeout: float | None = None) -> None:
        """Set and verify: the arbitrator replies with the value read back."""
        back = self.request(HostCommand.SET_PARAMETER,
                            hl.pack_param(key.vid, key.pid, key.serial, channel, param, value))
        if bytes(back) != bytes(value):
            raise TransportError(
                f"{key.vid}/{key.pid}/{key.serial} parameter 0x{param:02X} channel {channel}: "
                f"wrote {bytes(value).hex()} but read back {bytes(back).hex()}")
        self._stale = True

    def add_link(self, link: Link) -> None:
        self.request(HostCommand.ADD_LINK, _link_payload(link))
        self._stale = True

    def remove_link(self, link: Link) -> None:
        self.request(HostCommand.REMOVE_LINK, _link_payload(link))
        self._stale = True

    def read_configuration(self) -> ConfigCollection:
        from pdcp_studio.storage import config_codec

        return config_codec.loads(self.request(HostCommand.READ_CONFIGURATION))

    def preview(self, mode: str, config: ConfigCollection | None = None) -> Any:
        """The engine's plan on the arbitrator's system (and its memory unless ``config``)."""
        from pdcp_studio.engine import plan_for, plan_on_bus

        if config is not None:
            return plan_for(mode, self.system(), config)
        return plan_on_bus(mode, self.system(), self.read_configuration())

    # -- the change road (issue 8): kept apart, the host-link rewrite carries it over ----
    def carry_out(self, change: Change, progress: Callable[[int, int, str], None] | None = None,
                  cancel: threading.Event | None = None) -> TransactionResult:
        """The arbitrator carries the change out as one transaction (TRANSACT request)."""
        if cancel is not None and cancel.is_set():
            return TransactionResult(Status.DECLINED, change.action, "confirm", "cancelled")
        if progress:
            progress(0, 1, f"{change.action}: sent to the arbitrator")
        payload = json.dumps(change.to_json()).encode()
        try:
            reply = self.request(HostCommand.TRANSACT, payload, reply_size_hint=len(payload))
        except HostLinkError as err:
            return TransactionResult(Status.FAILED, change.action, "write",
                                     f"the arbitrator refused the change: {err}")
        finally:
            self._stale = True
        result = TransactionResult.from_json(json.loads(reply.decode("utf-8")))
        if progress:
            progress(1, 1, result.summary())
        return result

    def read_policy(self) -> Policy:
        return Policy.from_json(json.loads(self.request(HostCommand.READ_POLICY)))

    def reset_device(self, key: DeviceKey) -> None:
        self.request(HostCommand.RESET_DEVICE, hl.pack_key(key.vid, key.pid, key.serial))

    def close(self) -> None:
        """Stop polling and close the port (idempotent)."""
        if self._closed.is_set():
            return
        self._closed.set()
        if self._poller.is_alive() and threading.current_thread() is not self._poller:
            self._poller.join(timeout=2 * self.reply_timeout + POLL_INTERVAL_S)
        with self._io:
            self.port.close()


#: Options of other session kinds (memory, scan window, …) that mean nothing over a host link.
_SESSION_OPTIONS = ("reply_timeout", "poll_interval", "settle_timeout")


def open_hostlink_session(spec: Any, **options: Any) -> HostLinkSession:
    """Open ``spec`` (a parsed ``serial:`` BusSpec) and greet the arbitrator with PING.

    Options meant for an in-process arbitrator (``memory``, ``scan_window``, …) are ignored:
    the arbitrator at the other end of the line owns its memory and its bus.
    """
    import serial

    ignored = sorted(k for k in options if k not in _SESSION_OPTIONS)
    if ignored:
        log.debug("host link: ignoring options %s", ", ".join(ignored))
    options = {k: v for k, v in options.items() if k in _SESSION_OPTIONS}
    settle = options.pop("settle_timeout", None)

    try:
        port = serial.serial_for_url(spec.port, baudrate=spec.baud, timeout=0.05)
    except (serial.SerialException, ValueError) as err:
        raise TransportError(f"{spec.url}: cannot open serial port {spec.port!r}: {err}") from err
    try:
        session = HostLinkSession(port, url=spec.url, **options)
    except BaseException:
        port.close()
        raise
    if settle is not None:
        session.wait_settled(settle)
    return session
