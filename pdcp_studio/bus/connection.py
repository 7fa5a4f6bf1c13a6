"""One python-can bus, one Notifier, one inbound queue: the edge every bus role stands on.

Style §5–6: the Notifier's callback only enqueues (it must never raise, or python-can stops the
Notifier), a role's own thread drains the queue; one Notifier per connection, stopped before
``bus.shutdown()``. Sends are serialized and optionally paced so an adapter's transmit queue
never overflows.

python-can's ``udp_multicast`` interface hands every process its own frames back (multicast
loopback; its ``receive_own_messages=False`` is not implemented). A connection on such a bus
remembers what it sent and drops the first identical frame that comes back within
``ECHO_WINDOW_S``, so every role sees only the others' frames, as on a real CAN bus.
"""

from __future__ import annotations

import collections
import logging
import queue
import threading
import time
from typing import TYPE_CHECKING

from pdcp_studio.errors import TransportError

if TYPE_CHECKING:
    import can

log = logging.getLogger(__name__)

#: How long the Notifier's reader waits per recv() call; bounds how fast close() returns.
NOTIFIER_POLL_S = 0.05
#: How long close() waits for the Notifier's reader thread.
NOTIFIER_STOP_S = 1.0
#: A send that cannot be queued by the driver within this time raises TransportError.
SEND_TIMEOUT_S = 0.2

#: How long a sent frame waits for its multicast echo before it is forgotten.
ECHO_WINDOW_S = 2.0
#: Interfaces that return a process's own frames to it.
_ECHOING = ("UdpMulticastBus",)

#: Connections not closed yet (a test fixture fails a test that leaves one open).
_open: set[Connection] = set()
_open_lock = threading.Lock()


def open_connections() -> list[Connection]:
    """Connections opened in this process and not closed yet."""
    with _open_lock:
        return list(_open)


class _Enqueue:
    """The Notifier listener: put the frame on the queue, nothing else, never raise."""

    def __init__(self, target: queue.SimpleQueue) -> None:
        self._target = target
        self.errors = 0

    def __call__(self, msg: can.Message) -> None:
        self._target.put(msg)

    def on_error(self, exc: Exception) -> None:  # python-can calls this on a reader error
        self.errors += 1
        self._target.put(exc)

    def stop(self) -> None:
        pass


class Connection:
    """A bus owned by one role (arbitrator, device host); ``inbound`` yields can.Message.

    ``inbound`` may also carry an Exception when the driver failed (adapter unplugged); the
    consumer reports it. ``pace_s`` is the least time between two sends.
    """

    def __init__(self, bus: can.BusABC, *, name: str = "bus", pace_s: float = 0.0,
                 drop_own: bool | None = None) -> None:
        import can

        self.bus = bus
        self.name = name
        self.pace_s = pace_s
        self.inbound: queue.SimpleQueue = queue.SimpleQueue()
        self.sent = 0
        self.received = 0
        self._send_lock = threading.Lock()
        self._last_send = 0.0
        self._closed = False
        kind = getattr(bus, "inner_type", type(bus).__name__)  # a ReopeningBus: the real one
        self.drop_own = (kind in _ECHOING) if drop_own is None else drop_own
        self._own: dict[tuple[int, bytes], collections.deque[float]] = {}
        self._own_lock = threading.Lock()
        self._listener = _Enqueue(self.inbound)
        self._notifier = can.Notifier(bus, [self._listener], timeout=NOTIFIER_POLL_S)
        with _open_lock:
            _open.add(self)

    @property
    def closed(self) -> bool:
        return self._closed

    def send(self, arbitration_id: int, data: bytes) -> float:
        """Send one base frame; returns its timestamp. TransportError if the bus refuses it."""
        import can

        if self._closed:
            raise TransportError(f"{self.name}: the bus is closed")
        msg = can.Message(arbitration_id=arbitration_id, data=data, is_extended_id=False)
        if self.drop_own:
            self._remember(arbitration_id, bytes(data))
        with self._send_lock:
            if self.pace_s:
                wait = self._last_send + self.pace_s - time.perf_counter()
                if wait > 0:
                    time.sleep(wait)
            try:
                self.bus.send(msg, timeout=SEND_TIMEOUT_S)
            except can.CanError as err:
                raise TransportError(f"{self.name}: cannot send 0x{arbitration_id:03X}: {err}") \
                    from err
            self._last_send = time.perf_counter()
            self.sent += 1
        return time.time()

    def _remember(self, arbitration_id: int, data: bytes) -> None:
        now = time.monotonic()
        with self._own_lock:
            self._own.setdefault((arbitration_id, data), collections.deque()).append(now)
            if len(self._own) > 4096:  # echoes that never came: forget the stale ones
                for key in [k for k, q in self._own.items() if now - q[-1] > ECHO_WINDOW_S]:
                    del self._own[key]

    def _is_own(self, msg: can.Message) -> bool:
        key = (msg.arbitration_id, bytes(msg.data))
        now = time.monotonic()
        with self._own_lock:
            sent = self._own.get(key)
            while sent and now - sent[0] > ECHO_WINDOW_S:
                sent.popleft()
            if not sent:
                self._own.pop(key, None)
                return False
            sent.popleft()
            return True

    def get(self, timeout: float | None) -> object:
        """The next inbound item (a can.Message, an Exception, a posted callable), or None."""
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            left = None if deadline is None else deadline - time.monotonic()
            try:
                item = self.inbound.get(timeout=left) if left is None or left > 0 \
                    else self.inbound.get_nowait()
            except queue.Empty:
                return None
            if item is None or isinstance(item, Exception) or callable(item):
                return item
            if self.drop_own and self._is_own(item):
                continue
            self.received += 1
            return item

    def post(self, fn: object) -> None:
        """Queue a callable for the consumer thread (how other threads ask it to act)."""
        self.inbound.put(fn)

    def wake(self) -> None:
        """Make a consumer blocked in :meth:`get` return (it gets None back)."""
        self.inbound.put(None)

    def close(self) -> None:
        """Stop the Notifier (short timeout), then shut the bus down. Idempotent."""
        if self._closed:
            return
        self._closed = True
        try:
            self._notifier.stop(timeout=NOTIFIER_STOP_S)
        except Exception as err:  # a dying driver must not keep the bus open
            log.warning("%s: stopping the notifier failed: %s", self.name, err)
        try:
            self.bus.shutdown()
        except Exception as err:
            log.warning("%s: shutting the bus down failed: %s", self.name, err)
        with _open_lock:
            _open.discard(self)
        self.wake()
