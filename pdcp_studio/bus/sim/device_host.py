"""Many simulated devices on one bus, one Notifier and one thread (a 32-device rig, 1 thread).

The host owns the connection and a timer heap; it routes each frame to the device it is for
(by node ID, by key for bind answers, by source channel node ID for data), and runs every
device's timers. Other threads act on devices only by posting a callable to the host thread
(:meth:`call`), so device state needs no locks of its own: the host's lock, held while the
host thread runs timers and posted callables, serializes everything the devices do.

``direct=True`` (the in-process simulator, issue 11): the devices answer a frame on the thread
that sent it, under the host's lock (``Connection.hand_over``), so a request and its answer
cost no thread hand-over; the host thread still runs the timers and posted callables, and is
woken when a frame handled elsewhere set a timer earlier than it planned to wake.
"""

from __future__ import annotations

import functools
import heapq
import itertools
import logging
import threading
import time
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, TypeVar, cast

from pdcp_studio.bus.connection import Connection
from pdcp_studio.bus.log_limit import LimitedLog
from pdcp_studio.bus.sim.device import SimulatedDevice, State
from pdcp_studio.errors import BusTimeoutError, FrameError, TransportError
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.protocol import BindResponse, ChannelData, Message, decode

if TYPE_CHECKING:
    import can

log = logging.getLogger(__name__)
T = TypeVar("T")

#: The host thread wakes at least this often (to notice close()).
IDLE_WAKE_S = 0.1
#: How long plug()/unplug()/call() wait for the host thread.
CALL_TIMEOUT_S = 2.0


class DeviceHost:
    """Drives ``SimulatedDevice``s on a python-can bus. Close it (or use ``with``)."""

    def __init__(self, bus: can.BusABC, devices: Iterable[SimulatedDevice] = (), *,
                 name: str = "devices", plugged: bool = True,
                 drop_own: bool | None = None, direct: bool = False) -> None:
        self.conn = Connection(bus, name=name, drop_own=drop_own, direct=direct)
        #: Held by whoever acts on the devices: the host thread, or a sender handing a frame
        #: over (direct mode).
        self._lock = threading.RLock()
        self._wake_at = 0.0  # when the host thread plans to wake next (under the lock)
        self.name = name
        self.bad_frames = 0
        self.failures = 0
        #: Repeated driver errors and device failures: told once, then summarised each second.
        self._log = LimitedLog(log, f"{name}: ")
        self._devices: dict[DeviceKey, SimulatedDevice] = {}
        self._timers: list[tuple[float, int, Callable[[], None]]] = []
        self._seq = itertools.count()
        self._dirty = True
        self._by_node: dict[int, SimulatedDevice] = {}
        self._binding: list[SimulatedDevice] = []
        self._listeners: dict[int, list[tuple[SimulatedDevice, int]]] = {}
        self._stop = False
        #: True when frames are handled on the sender's thread (direct mode).
        self.inline = self.conn.hand_over(self._take)
        with self._lock:
            for device in devices:
                self._add(device, plugged)
        self._thread = threading.Thread(target=self._run, name=f"pdcp {name}", daemon=True)
        self._thread.start()

    def __enter__(self) -> DeviceHost:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- the Host protocol (called by devices on the host thread) -----------------------
    def send_message(self, message: Message) -> None:
        arbitration_id, data = message.encode()
        try:
            self.conn.send(arbitration_id, data)
        except TransportError as err:
            log.debug("%s: %s", self.name, err)
            return
        if isinstance(message, ChannelData):  # devices of this host hear each other too
            self._route()
            for device, index in self._listeners.get(message.node_id, ()):
                device.on_data(index, data, time.time())

    def call_later(self, delay: float, fn: Callable[[], None]) -> None:
        heapq.heappush(self._timers, (time.monotonic() + delay, next(self._seq), fn))

    def routing_changed(self) -> None:
        self._dirty = True

    def now(self) -> float:
        return time.monotonic()

    # -- other threads --------------------------------------------------------------------
    def call(self, fn: Callable[[], T], timeout: float = CALL_TIMEOUT_S) -> T:
        """Run ``fn`` on the host thread and return its result (BusTimeoutError if stuck)."""
        if threading.current_thread() is self._thread:
            return fn()
        done = threading.Event()
        results: list[T] = []
        errors: list[Exception] = []

        def run() -> None:
            try:
                results.append(fn())
            except Exception as err:
                errors.append(err)
            done.set()

        self.conn.post(run)
        if not done.wait(timeout):
            raise BusTimeoutError(f"{self.name}: the device host did not answer in {timeout} s")
        if errors:
            raise errors[0]
        return results[0]

    def keys(self) -> list[DeviceKey]:
        return list(self._devices)

    def device(self, key: DeviceKey) -> SimulatedDevice:
        try:
            return self._devices[key]
        except KeyError:
            raise KeyError(f"no simulated device {key} on {self.name}") from None

    def add(self, device: SimulatedDevice, *, plugged: bool = True) -> None:
        self.call(lambda: self._add(device, plugged))

    def _add(self, device: SimulatedDevice, plugged: bool) -> None:
        if device.key in self._devices:
            raise ValueError(f"{self.name}: device {device.key} is already simulated here")
        self._devices[device.key] = device
        device.attach(self)
        if plugged:
            device.power_on()

    def remove(self, key: DeviceKey) -> SimulatedDevice:
        def run() -> SimulatedDevice:
            device = self.device(key)
            device.power_off()
            del self._devices[key]
            return device

        return self.call(run)

    def plug(self, key: DeviceKey) -> None:
        """Power the device on (it binds again, keeping its non-volatile parameters)."""
        self.call(lambda: self.device(key).power_on())

    def unplug(self, key: DeviceKey) -> None:
        """Cut the device off the bus at once (mid-transfer, mid-beacon, whatever it does)."""
        self.call(lambda: self.device(key).power_off())

    def is_plugged(self, key: DeviceKey) -> bool:
        return self._devices[key].state is not State.OFF

    def close(self) -> None:
        """Stop the thread, then the Notifier, then the bus. Idempotent."""
        self._stop = True
        self.conn.wake()
        self._thread.join(timeout=CALL_TIMEOUT_S)
        self.conn.close()

    # -- the host thread ------------------------------------------------------------------
    def _route(self) -> None:
        if not self._dirty:
            return
        self._dirty = False
        self._by_node, self._binding, self._listeners = {}, [], {}
        for device in self._devices.values():
            if device.state is State.BINDING:
                self._binding.append(device)
            elif device.state is State.BOUND:
                self._by_node[device.node_id] = device
                for node, indices in device.listening().items():
                    self._listeners.setdefault(node, []).extend((device, i) for i in indices)

    def _run(self) -> None:
        while not self._stop:
            with self._lock:
                now = time.monotonic()
                while self._timers and self._timers[0][0] <= now and not self._stop:
                    _, _, fn = heapq.heappop(self._timers)
                    self._guard(fn)
                wait = max(0.0, IDLE_WAKE_S if not self._timers
                           else min(IDLE_WAKE_S, self._timers[0][0] - now))
                self._wake_at = now + wait
            item = self.conn.get(wait)
            self._log.flush()
            if item is None or self._stop:
                continue
            with self._lock:
                if isinstance(item, Exception):
                    self._log.warning("transport", "the bus reported %s", item)
                elif callable(item):
                    self._guard(item)
                else:  # what is neither an error nor a call is a frame (Connection.get)
                    self._guard(functools.partial(self._on_frame, cast("can.Message", item)))

    def _take(self, msg: can.Message) -> None:
        """A frame handed over on the thread that sent it (direct mode)."""
        with self._lock:
            if self._stop:
                return
            self._guard(lambda: self._on_frame(msg))
            early = bool(self._timers) and self._timers[0][0] < self._wake_at
        if early:  # the host thread sleeps past a timer this frame set: wake it
            self.conn.wake()

    def _guard(self, fn: Callable[[], object]) -> None:
        try:
            fn()
        except Exception:  # one device's bug must not stop the others
            self.failures += 1
            self._log.exception("device", "a simulated device failed")

    def _on_frame(self, msg: can.Message) -> None:
        if msg.is_extended_id or msg.is_error_frame or msg.is_remote_frame:
            return
        aid, data = msg.arbitration_id, bytes(msg.data)
        self._route()
        if not aid >> 8 & 1:  # mode 0: another device; only channel data concerns us
            if aid >> 9 != 3:
                for device, index in self._listeners.get(aid & 0xFF, ()):
                    device.on_data(index, data, msg.timestamp)
            return
        try:
            message = decode(aid, data)
        except FrameError:
            self.bad_frames += 1
            return
        if isinstance(message, BindResponse):
            for device in list(self._binding):
                if (device.key.vid, device.key.pid, device.key.serial) == \
                        (message.vid, message.pid, message.serial):
                    device.handle(message)
        elif message.node_id == 0:
            for device in list(self._by_node.values()):
                device.handle(message)
        else:
            addressed = self._by_node.get(message.node_id)
            if addressed is not None:
                addressed.handle(message)
