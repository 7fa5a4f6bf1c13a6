"""One python-can bus, one Notifier, one inbound queue: the edge every bus role stands on.

Style §5–6: the Notifier's callback only enqueues (it must never raise, or python-can stops the
Notifier), a role's own thread drains the queue; one Notifier per connection, stopped before
``bus.shutdown()``. Sends are serialized and optionally paced so an adapter's transmit queue
never overflows.

python-can's ``udp_multicast`` interface hands every process its own frames back (multicast
loopback; its ``receive_own_messages=False`` is not implemented). A connection on such a bus
remembers what it sent and drops the first identical frame that comes back within
``ECHO_WINDOW_S``, so every role sees only the others' frames, as on a real CAN bus. The
memory of sent frames is bounded (:class:`EchoFilter`): at most ``ECHO_MAX_PENDING`` frames,
none older than the window, whatever the number of frames a long run sends.

An in-process simulation (``direct=True``, issue 11) skips the Notifier: on python-can's
``virtual`` bus, the frames another bus of the channel sends go straight from the sender's
thread into this connection's queue (:func:`attach_direct`), through the same listener and its
flood bound. Each frame then wakes one thread instead of two, and a simulated prosthesis
that opens ~450 frames at start-up no longer waits for a Notifier thread to get the
interpreter between its sender and its reader. Such a bus also sends as python-can's virtual
bus does but without its ``deepcopy`` of each frame for each receiver (its ``send`` is
:func:`send_virtual` then: a new Message of the same fields, ~1 µs against ~8 µs a frame).
Real adapters always have a Notifier and python-can's own ``send``.
"""

from __future__ import annotations

import collections
import functools
import logging
import queue
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

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
#: At most this many sent frames wait for their echo; beyond it the oldest is forgotten.
#: A 1 Mbit/s CAN bus carries at most ~8,000 frames/s: two seconds (the window) of them.
ECHO_MAX_PENDING = 16384
#: Past its deadline, get() drops at most this many of our own echoes before it returns None.
ECHO_DRAIN_LATE = 64
#: At most this many received frames wait for the consumer (a flood it cannot keep up with
#: is dropped and counted beyond it: about 30 MB of frames, 8 s of a full 1 Mbit/s bus).
INBOUND_MAX = 65536
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
    """The Notifier listener: put the frame on the queue, nothing else, never raise.

    A consumer that falls behind a flood must not let the queue take all memory: beyond
    ``INBOUND_MAX`` waiting frames, new frames are dropped and counted (``dropped``)."""

    def __init__(self, target: queue.SimpleQueue[Any]) -> None:
        self._target = target
        self.errors = 0
        self.dropped = 0

    def __call__(self, msg: can.Message) -> None:
        if self._target.qsize() >= INBOUND_MAX:
            self.dropped += 1
            return
        self._target.put(msg)

    def on_error(self, exc: Exception) -> None:  # python-can calls this on a reader error
        self.errors += 1
        self._target.put(exc)

    def stop(self) -> None:
        pass


class _DirectInbound:
    """Stands in a python-can ``VirtualBus``'s receive queue: ``VirtualBus.send`` of another
    bus on the channel calls ``put`` on the sender's thread, and the frame goes through the
    connection's listener (its flood bound) into the connection's queue at once.

    Nothing reads the bus itself in this mode; a stray ``recv()`` finds nothing (it waits out
    its timeout, or a short while, instead of spinning)."""

    def __init__(self, listener: Callable[[Any], None]) -> None:
        self.listener = listener

    def put(self, item: Any, block: bool = True, timeout: float | None = None) -> None:
        self.listener(item)

    def get(self, block: bool = True, timeout: float | None = None) -> Any:
        if block:
            time.sleep(NOTIFIER_POLL_S if timeout is None else max(0.0, timeout))
        raise queue.Empty

    def get_nowait(self) -> Any:
        raise queue.Empty

    def qsize(self) -> int:
        return 0

    def empty(self) -> bool:
        return True


def attach_direct(bus: object, listener: _Enqueue) -> _DirectInbound | None:
    """Make ``bus`` hand the frames it receives to ``listener`` on the sender's thread.

    Only an exact python-can ``VirtualBus`` whose receive queue is where this version of
    python-can keeps it (``bus.queue``, a member of the channel's list ``bus.channel``) is
    attached: its queue is swapped for a :class:`_DirectInbound` under python-can's channel
    lock, and frames already waiting in the old queue are passed on first; from then on the
    bus sends with :func:`send_virtual`; returns the stand-in. None (nothing changed) for any
    other bus, and for a python-can whose virtual bus is laid out otherwise: the caller then
    reads it with a Notifier. A frame that another
    thread is sending at the very moment of the swap may land in the old queue and be lost:
    attach while the channel is quiet (the simulator attaches its buses before its devices are
    plugged in)."""
    try:
        from can.interfaces import virtual
    except ImportError:  # pragma: no cover - python-can always has it
        return None
    if type(bus) is not virtual.VirtualBus:
        return None
    lock = getattr(virtual, "channels_lock", None)
    old = getattr(bus, "queue", None)
    channel = getattr(bus, "channel", None)
    if lock is None or not isinstance(old, queue.Queue) or not isinstance(channel, list) \
            or not all(hasattr(bus, name) for name in _VIRTUAL_SEND_FIELDS):
        return None
    adapter = _DirectInbound(listener)
    with lock:
        for i, q in enumerate(channel):
            if q is old:
                channel[i] = adapter
                break
        else:
            return None
        bus.queue = adapter  # type: ignore[assignment]  # what shutdown() removes
    bus.send = functools.partial(send_virtual, bus)  # type: ignore[method-assign]
    while True:
        try:
            listener(old.get_nowait())
        except queue.Empty:
            return adapter


#: What :func:`send_virtual` reads of a python-can ``VirtualBus`` (besides ``queue`` and
#: ``channel``); a virtual bus without them is not attached.
_VIRTUAL_SEND_FIELDS = ("_check_if_open", "preserve_timestamps", "receive_own_messages",
                        "channel_id")


def send_virtual(bus: Any, msg: can.Message, timeout: float | None = None) -> None:
    """Send a frame on an attached ``VirtualBus`` (:func:`attach_direct`) as its own
    ``send`` does — to every other bus of the channel, stamped now (or with its own time when
    the bus preserves timestamps), marked received, on the channel — but as a new Message per
    receiver instead of a ``deepcopy``: the same fields, at an eighth of the cost."""
    bus._check_if_open()
    timestamp = msg.timestamp if bus.preserve_timestamps else time.time()
    all_sent = True
    for target in bus.channel:
        if target is bus.queue and not bus.receive_own_messages:
            continue
        copy = type(msg)(timestamp=timestamp, arbitration_id=msg.arbitration_id,
                           is_extended_id=msg.is_extended_id,
                           is_remote_frame=msg.is_remote_frame,
                           is_error_frame=msg.is_error_frame, channel=bus.channel_id,
                           dlc=msg.dlc, data=bytearray(msg.data), is_fd=msg.is_fd,
                           is_rx=target is not bus.queue, bitrate_switch=msg.bitrate_switch,
                           error_state_indicator=msg.error_state_indicator)
        try:
            target.put(copy, block=True, timeout=timeout)
        except queue.Full:
            all_sent = False
    if not all_sent:
        import can

        raise can.CanOperationError("Could not send message to one or more recipients")


def virtual_channel_in_use(channel: object) -> bool:
    """True when python-can's virtual bus already has a bus on ``channel`` (and when this
    python-can does not say): the simulator then reads its buses with Notifiers, as a direct
    attach wants a quiet channel, and two device hosts answering on each other's threads
    could wait for each other."""
    try:
        from can.interfaces import virtual

        channels, lock = virtual.channels, virtual.channels_lock
    except (ImportError, AttributeError):  # pragma: no cover - laid out otherwise
        return True
    with lock:
        return bool(channels.get(channel))  # type: ignore[call-overload]


class EchoFilter:
    """The frames this process sent and has not seen come back yet; bounded, thread-safe.

    ``order`` holds every remembered send in send order (for expiry by age and by count);
    ``pending`` holds, per frame, the send times still waiting for their echo, oldest first.
    An echo consumes the oldest pending send of its frame, so the pending sends of a frame are
    always the newest of its entries in ``order``: an entry of ``order`` is still pending exactly
    when its frame's oldest pending time is not later than the entry's. Both stay within
    ``max_pending`` entries; no operation depends on a container being non-empty.
    """

    def __init__(self, window_s: float = ECHO_WINDOW_S, max_pending: int = ECHO_MAX_PENDING
                 ) -> None:
        self.window_s = window_s
        self.max_pending = max_pending
        self._order: collections.deque[tuple[float, tuple[int, bytes]]] = collections.deque()
        self._pending: dict[tuple[int, bytes], collections.deque[float]] = {}
        self._lock = threading.Lock()
        #: Sends forgotten before their echo came (count bound or window passed).
        self.forgotten = 0

    def __len__(self) -> int:
        with self._lock:
            return sum(len(q) for q in self._pending.values())

    @property
    def remembered(self) -> int:
        """Entries held (pending or already echoed, not yet expired): the memory bound."""
        return len(self._order)

    def sent(self, key: tuple[int, bytes], now: float) -> None:
        """Remember one send of ``key`` at ``now``."""
        with self._lock:
            self._expire(now)
            while len(self._order) >= self.max_pending:
                self._drop_oldest()
            self._order.append((now, key))
            self._pending.setdefault(key, collections.deque()).append(now)

    def is_echo(self, key: tuple[int, bytes], now: float) -> bool:
        """True (and the send is consumed) when ``key`` is the echo of a pending send."""
        with self._lock:
            self._expire(now)
            times = self._pending.get(key)
            if not times:
                return False
            times.popleft()
            if not times:
                del self._pending[key]
            return True

    def _expire(self, now: float) -> None:
        while self._order and now - self._order[0][0] > self.window_s:
            self._drop_oldest()

    def _drop_oldest(self) -> None:
        when, key = self._order.popleft()
        times = self._pending.get(key)
        if times and times[0] <= when:  # still pending: its echo never came
            times.popleft()
            self.forgotten += 1
            if not times:
                del self._pending[key]


class Connection:
    """A bus owned by one role (arbitrator, device host); ``inbound`` yields can.Message.

    ``inbound`` may also carry an Exception when the driver failed (adapter unplugged); the
    consumer reports it. ``pace_s`` is the least time between two sends. ``direct``: an
    in-process simulation's virtual bus delivers into ``inbound`` without a Notifier
    (:func:`attach_direct`; any other bus is read by a Notifier all the same).
    """

    def __init__(self, bus: can.BusABC, *, name: str = "bus", pace_s: float = 0.0,
                 drop_own: bool | None = None, direct: bool = False) -> None:
        import can

        self.bus = bus
        self.name = name
        self.pace_s = pace_s
        self.inbound: queue.SimpleQueue[Any] = queue.SimpleQueue()
        self.sent = 0
        self.received = 0
        self._send_lock = threading.Lock()
        self._last_send = 0.0
        self._closed = False
        kind = getattr(bus, "inner_type", type(bus).__name__)  # a ReopeningBus: the real one
        self.drop_own = (kind in _ECHOING) if drop_own is None else drop_own
        self._echoes = EchoFilter()
        self._listener = _Enqueue(self.inbound)
        self._notifier: can.Notifier | None = None
        self._direct = attach_direct(bus, self._listener) if direct else None
        if self._direct is None:
            self._notifier = can.Notifier(bus, [self._listener], timeout=NOTIFIER_POLL_S)
        self._count_lock = threading.Lock()
        with _open_lock:
            _open.add(self)

    @property
    def closed(self) -> bool:
        return self._closed

    @property
    def direct(self) -> bool:
        """True when frames arrive without a Notifier thread (:func:`attach_direct`)."""
        return self._direct is not None

    def hand_over(self, handler: Callable[[can.Message], None]) -> bool:
        """Direct mode only: from now on each frame received is given to ``handler`` on the
        thread that sent it (the in-process simulator's device host, issue 11), instead of
        being queued for the consumer thread; own echoes are still dropped and frames
        counted. ``handler`` must not block: the sender waits for it. False (frames keep
        being queued) when this connection has a Notifier."""
        if self._direct is None:
            return False

        def take(msg: can.Message) -> None:
            if self.drop_own and self._is_own(msg):
                return
            with self._count_lock:
                self.received += 1
            handler(msg)

        self._direct.listener = take
        return True

    @property
    def dropped(self) -> int:
        """Frames dropped because the consumer was ``INBOUND_MAX`` frames behind."""
        return self._listener.dropped

    def send(self, arbitration_id: int, data: bytes, *, filter_echo: bool = True) -> float:
        """Send one base frame; returns its timestamp. TransportError if the bus refuses it.

        ``filter_echo=False``: its echo is not dropped here (the arbitrator's claim accounts
        for the copies of its own frames itself, however late they come)."""
        import can

        if self._closed:
            raise TransportError(f"{self.name}: the bus is closed")
        msg = can.Message(arbitration_id=arbitration_id, data=data, is_extended_id=False)
        if self.drop_own and filter_echo:
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
        self._echoes.sent((arbitration_id, data), time.monotonic())

    def _is_own(self, msg: can.Message) -> bool:
        return self._echoes.is_echo((msg.arbitration_id, bytes(msg.data)), time.monotonic())

    def get(self, timeout: float | None) -> object:
        """The next inbound item (a can.Message, an Exception, a posted callable), or None."""
        deadline = None if timeout is None else time.monotonic() + timeout
        late_drops = 0
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
                if left is not None and left <= 0:
                    late_drops += 1
                    if late_drops >= ECHO_DRAIN_LATE:
                        return None  # the caller's timers are due: a stream of our own
                        # echoes must not keep it here past its deadline
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
            if self._notifier is not None:
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
