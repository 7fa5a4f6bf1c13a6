"""Serve the arbitrator host link (docs/host-link.md) on a serial port, for `serial:` clients.

``pdcp-studio arbitrator --bus can:… --host-serial PORT`` puts a headless arbitrator on a CAN
bus and answers host-link requests on PORT, the way the thesis's hardware arbitrator answered its
PC over a USB–UART dongle. PORT is any pyserial URL (``/dev/ttyUSB0``, ``socket://…``,
``loop://``) or ``pty``: a new pseudo-terminal whose slave path is printed for clients, so the
whole host-link path can be run and tested on one machine with no hardware.

One thread reads the port, answers each request in order, and never dies of a bad request: a
garbled frame is dropped by the framing layer, a request that fails gets the failure reply
carrying the reason.
"""

from __future__ import annotations

import json
import logging
import os
import select
import threading
import time
from collections import deque
from collections.abc import Callable
from typing import Any, Protocol

from pdcp_studio import __version__
from pdcp_studio.bus import events as ev
from pdcp_studio.errors import FrameError, PdcpError, TransportError
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.protocol import hostlink as hl
from pdcp_studio.protocol.hostlink import HostCommand, HostMessage

log = logging.getLogger(__name__)

DEFAULT_BAUD = 128_000
#: Events kept for POLL_EVENTS between two polls; older ones are dropped (and counted).
EVENT_BACKLOG = 2_000
#: How long one read waits, which bounds how fast close() returns.
READ_TIMEOUT_S = 0.05


class Port(Protocol):
    """What the server needs of a serial port (pyserial's ``Serial`` has all of it)."""

    def read(self, size: int = 1) -> bytes: ...
    def write(self, data: bytes) -> int | None: ...
    def close(self) -> None: ...


class PtyPort:
    """The master end of a new pseudo-terminal; clients open ``slave_path`` with pyserial."""

    def __init__(self) -> None:
        import tty

        self._master, self._slave = os.openpty()
        tty.setraw(self._slave)  # no echo, no line editing: bytes pass unchanged
        self.slave_path = os.ttyname(self._slave)
        self._closed = False

    def read(self, size: int = 1) -> bytes:
        if self._closed:
            return b""
        ready, _, _ = select.select([self._master], [], [], READ_TIMEOUT_S)
        if not ready:
            return b""
        try:
            return os.read(self._master, size)
        except OSError:  # EIO while no client has the slave open
            time.sleep(READ_TIMEOUT_S)
            return b""

    def write(self, data: bytes) -> int:
        view = memoryview(data)
        while view:
            n = os.write(self._master, view)
            view = view[n:]
        return len(data)

    def close(self) -> None:
        if not self._closed:
            self._closed = True
            os.close(self._master)
            os.close(self._slave)


def open_port(name: str, baudrate: int = DEFAULT_BAUD) -> Port:
    """``pty`` → a new :class:`PtyPort`; anything else → pyserial ``serial_for_url``."""
    if name == "pty":
        return PtyPort()
    import serial

    try:
        return serial.serial_for_url(name, baudrate=baudrate, timeout=READ_TIMEOUT_S)
    except (serial.SerialException, ValueError) as err:
        raise TransportError(f"host link: cannot open serial port {name!r}: {err}") from err


def _key(values: tuple[int, ...]) -> DeviceKey:
    return DeviceKey(*values[:3])


def _link(payload: bytes) -> Link:
    out, inp = hl.unpack_link(payload)
    return Link(ChannelRef(*out), ChannelRef(*inp))


def event_to_json(event: object) -> dict | None:
    """An event as the host link's JSON; ``None`` for per-frame traffic the link does not carry."""
    if isinstance(event, ev.DeviceJoined | ev.DeviceLeft):
        k = event.key
        return {"kind": type(event).__name__, "key": {"vid": k.vid, "pid": k.pid,
                                                       "serial": k.serial}}
    if isinstance(event, ev.LinkMade | ev.LinkRemoved):
        return {"kind": type(event).__name__, "link": event.link.as_json()}
    if isinstance(event, ev.BusError):
        return {"kind": "BusError", "message": event.message, "error_kind": event.kind}
    if isinstance(event, ev.PlanApplied):
        plan = event.plan
        return {"kind": "PlanApplied", "plan": plan.to_json() if hasattr(plan, "to_json") else {}}
    if isinstance(event, ev.TransactionDone):
        return {"kind": "TransactionDone", "result": event.result.to_json()}
    if isinstance(event, ev.TerminalsUnconnected):
        return {"kind": "TerminalsUnconnected", "refs": [r.as_json() for r in event.refs],
                "why": event.why}
    return None  # FrameSeen, ChannelValue, Progress: too chatty for a polled link


class HostLinkServer:
    """Answers host-link requests from ``port`` with ``arbitrator``; close it (or use ``with``)."""

    def __init__(self, arbitrator: Any, port: Port | str, *, baudrate: int = DEFAULT_BAUD,
                 name: str = "host link") -> None:
        self.arbitrator = arbitrator
        self.port: Port = open_port(port, baudrate) if isinstance(port, str) else port
        self.name = name
        self.requests = 0
        self.failures = 0
        self.dropped_events = 0
        self._reader = hl.FrameReader()
        self._events: deque[dict] = deque()
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._unsubscribe: Callable[[], None] = arbitrator.subscribe(self._on_event)
        self._handlers: dict[int, Callable[[bytes], bytes]] = {
            HostCommand.PING: self._ping,
            HostCommand.GET_SYSTEM: self._get_system,
            HostCommand.GET_PARAMETER: self._get_parameter,
            HostCommand.SET_PARAMETER: self._set_parameter,
            HostCommand.ADD_LINK: self._add_link,
            HostCommand.REMOVE_LINK: self._remove_link,
            HostCommand.READ_CONFIGURATION: self._read_configuration,
            HostCommand.WRITE_CONFIGURATION: self._write_configuration,
            HostCommand.POLL_EVENTS: self._poll_events,
            HostCommand.PREVIEW_PLAN: self._preview_plan,
            HostCommand.APPLY_PLAN: self._apply_plan,
            HostCommand.RESET_DEVICE: self._reset_device,
            HostCommand.TRANSACT: self._transact,
            HostCommand.READ_POLICY: self._read_policy,
        }
        self._thread = threading.Thread(target=self._run, name=f"pdcp {name}", daemon=True)
        self._thread.start()

    @property
    def slave_path(self) -> str | None:
        """Where clients connect when serving on a new pseudo-terminal."""
        return getattr(self.port, "slave_path", None)

    @property
    def bad_frames(self) -> int:
        return self._reader.errors

    def __enter__(self) -> HostLinkServer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        if self._stop.is_set():
            return
        self._stop.set()
        self._unsubscribe()
        self._thread.join(timeout=2.0)
        self.port.close()

    # -- the loop ---------------------------------------------------------------------
    def _on_event(self, event: object) -> None:
        """Arbitrator-thread callback: only queue (bounded)."""
        doc = event_to_json(event)
        if doc is None:
            return
        with self._lock:
            if len(self._events) >= EVENT_BACKLOG:
                self._events.popleft()
                self.dropped_events += 1
            self._events.append(doc)

    def _run(self) -> None:
        while not self._stop.is_set():
            try:
                data = self.port.read(4096)
            except Exception as err:  # a pulled cable: say so, keep trying until closed
                if self._stop.is_set():
                    return
                log.warning("%s: reading the port failed: %s", self.name, err)
                time.sleep(0.5)
                continue
            if not data:
                continue
            for message in self._reader.feed(data):
                reply = self.handle(message)
                try:
                    self.port.write(reply.encode())
                except Exception as err:
                    log.warning("%s: writing the reply failed: %s", self.name, err)

    def handle(self, message: HostMessage) -> HostMessage:
        """The reply to one request: success with its payload, or failure with the reason."""
        self.requests += 1
        handler = self._handlers.get(message.msg_id)
        if handler is None:
            self.failures += 1
            return HostMessage(hl.reply_fail(message.msg_id),
                               f"unknown request 0x{message.msg_id:02X}".encode())
        try:
            return HostMessage(hl.reply_ok(message.msg_id), handler(message.payload))
        except (PdcpError, ValueError, KeyError) as err:
            self.failures += 1
            name = HostCommand(message.msg_id).name
            text = str(err) if not isinstance(err, KeyError) else f"unknown {err}"
            return HostMessage(hl.reply_fail(message.msg_id), f"{name}: {text}".encode()[:1000])

    # -- requests ---------------------------------------------------------------------
    def _ping(self, payload: bytes) -> bytes:
        return json.dumps({"name": "pdcp-studio arbitrator", "version": __version__}).encode()

    def _get_system(self, payload: bytes) -> bytes:
        from pdcp_studio.storage import system_file

        return system_file.dumps(self.arbitrator.system(), node_ids=True).encode()

    def _get_parameter(self, payload: bytes) -> bytes:
        (vid, pid, serial, channel, param), _ = hl.unpack_param(payload)
        return bytes(self.arbitrator.get_parameter(DeviceKey(vid, pid, serial), param, channel))

    def _set_parameter(self, payload: bytes) -> bytes:
        (vid, pid, serial, channel, param), value = hl.unpack_param(payload)
        key = DeviceKey(vid, pid, serial)
        self.arbitrator.set_parameter(key, param, channel, value)
        return bytes(self.arbitrator.get_parameter(key, param, channel))

    def _add_link(self, payload: bytes) -> bytes:
        self.arbitrator.add_link(_link(payload))
        return b""

    def _remove_link(self, payload: bytes) -> bytes:
        self.arbitrator.remove_link(_link(payload))
        return b""

    def _read_configuration(self, payload: bytes) -> bytes:
        from pdcp_studio.storage import config_codec

        return config_codec.dumps(self.arbitrator.read_memory())

    def _write_configuration(self, payload: bytes) -> bytes:
        from pdcp_studio.storage import config_codec

        self.arbitrator.write_memory(config_codec.loads(payload))
        return config_codec.dumps(self.arbitrator.read_memory())

    def _poll_events(self, payload: bytes) -> bytes:
        with self._lock:
            docs = list(self._events)
            self._events.clear()
        return json.dumps(docs).encode()

    def _plan(self, payload: bytes) -> Any:
        from pdcp_studio.engine import plan_on_bus

        mode = payload.decode("ascii", errors="replace").strip()
        return plan_on_bus(mode, self.arbitrator.system(), self.arbitrator.read_memory())

    def _preview_plan(self, payload: bytes) -> bytes:
        return json.dumps(self._plan(payload).to_json()).encode()

    def _apply_plan(self, payload: bytes) -> bytes:
        plan = self._plan(payload)
        self.arbitrator.apply_plan(plan)
        return json.dumps(plan.to_json()).encode()

    def _reset_device(self, payload: bytes) -> bytes:
        key = _key(hl.unpack_key(payload))
        node_id = self.arbitrator.node_id_of(key)
        if node_id is None:
            raise FrameError(f"device {key.vid}/{key.pid}/{key.serial} is not bound")
        self.arbitrator.requests.reset(node_id)
        return b""

    # -- the change road (issue 8): kept apart, the host-link rewrite carries it over ----
    def _transact(self, payload: bytes) -> bytes:
        """Carry out one Change (JSON) as the arbitrator's transaction; the result as JSON."""
        from pdcp_studio.bus.transaction import Change

        change = Change.from_json(json.loads(payload.decode("utf-8")))
        return json.dumps(self.arbitrator.transact(change).to_json()).encode()

    def _read_policy(self, payload: bytes) -> bytes:
        return json.dumps(self.arbitrator.read_policy().to_json()).encode()
