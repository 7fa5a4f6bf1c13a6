"""The arbitrator's request/response engine: one transaction per device at a time.

Callers (session calls, set-up jobs, scan workers) run on their own threads and block here
with a timeout; the arbitrator's dispatch thread hands every device frame to :meth:`feed`,
which only puts it on the waiting caller's queue (canopen's SDO client works the same way).
Transactions to one node are serialized (a device handles one at a time and has one bulk
reassembler); transactions to different nodes overlap, which is what makes a scan fast.

Every request has a timeout and bounded retries (named constants below). A device that
leaves mid-transfer has its transaction aborted by :meth:`abort`, and only that one.
"""

from __future__ import annotations

import queue
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass

from pdcp_studio.errors import BusTimeoutError, FrameError, PdcpError, TransportError
from pdcp_studio.protocol import (
    BulkData,
    BulkDataResponse,
    BulkReassembler,
    ConfigureGetBulk,
    ConfigureSetBulk,
    FunctionCode,
    GetParameter,
    Message,
    Mode,
    Release,
    Reset,
    ResponseCode,
    SetParameter,
    Suspend,
    packetize,
)

#: Seconds to wait for one response frame (and between two bulk packets).
RESPONSE_TIMEOUT_S = 0.1
#: Further attempts after the first one times out (so at most RETRIES + 1 requests).
RETRIES = 3
#: Values up to this many bytes go in 0x04; longer ones by bulk transfer.
INLINE_MAX = 4

F = FunctionCode


class DeviceRefusedError(PdcpError):
    """A device answered a request with the failure code (a bad parameter, a read-only one)."""


class TransferAbortedError(TransportError):
    """A transaction was cut short: the device left the bus, or the session closed."""


@dataclass
class RequestStats:
    """Counters for the benchmark and the monitor (frames of transactions only)."""

    requests: int = 0  # transactions started
    frames_sent: int = 0
    frames_received: int = 0
    retries: int = 0
    timeouts: int = 0
    aborted: int = 0

    @property
    def frames(self) -> int:
        return self.frames_sent + self.frames_received


class _Abort:
    def __init__(self, reason: str) -> None:
        self.reason = reason


#: Every frame a device may send within a transaction. A waiter accepts all of them from the
#: start, so a frame that comes before the caller gets round to waiting for it (the bulk
#: packets right behind 0x8C, the 0x8E right behind the last packet sent) is never lost;
#: ``_wait`` then picks the one it needs.
_TRANSACTION_CODES = frozenset({
    F.GET_PARAMETER_RESPONSE, F.SET_PARAMETER_RESPONSE, F.SUSPEND_RESPONSE,
    F.RELEASE_RESPONSE, F.RESET_RESPONSE, F.CONFIGURE_GET_BULK_RESPONSE,
    F.CONFIGURE_SET_BULK_RESPONSE, F.BULK_DATA, F.BULK_DATA_RESPONSE,
})


class _Waiter:
    """The one transaction in progress with a node, and the queue its frames arrive on."""

    def __init__(self, node_id: int) -> None:
        self.node_id = node_id
        self.codes: frozenset[FunctionCode] = _TRANSACTION_CODES
        self.inbox: queue.SimpleQueue[Message | _Abort] = queue.SimpleQueue()


class RequestEngine:
    """Send requests through ``send`` and wait for the matching responses fed by the dispatcher."""

    def __init__(self, send: Callable[[Message], None], *,
                 response_timeout: float = RESPONSE_TIMEOUT_S, retries: int = RETRIES) -> None:
        self._send_message = send
        self.response_timeout = response_timeout
        self.retries = retries
        self.stats = RequestStats()
        self._lock = threading.Lock()
        self._node_locks: dict[int, threading.Lock] = {}
        self._waiters: dict[int, _Waiter] = {}
        self._closed = False

    # -- the dispatcher's side -------------------------------------------------------
    def feed(self, message: Message) -> bool:
        """Route a device's frame to the transaction waiting for it; False if none is."""
        code = getattr(message, "CODE", None)
        with self._lock:
            waiter = self._waiters.get(message.node_id)
            if waiter is None or code not in waiter.codes:
                return False
            self.stats.frames_received += 1
        waiter.inbox.put(message)
        return True

    def abort(self, node_id: int, reason: str) -> None:
        """Cut short the transaction with ``node_id`` (its device left); others go on."""
        with self._lock:
            waiter = self._waiters.get(node_id)
        if waiter is not None:
            waiter.inbox.put(_Abort(reason))

    def close(self) -> None:
        """Abort every transaction and refuse new ones."""
        with self._lock:
            self._closed = True
            waiters = list(self._waiters.values())
        for waiter in waiters:
            waiter.inbox.put(_Abort("the session closed"))

    # -- plumbing -----------------------------------------------------------------------
    @contextmanager
    def _exchange(self, node_id: int, deadline: float) -> Iterator[_Waiter]:
        with self._lock:
            lock = self._node_locks.setdefault(node_id, threading.Lock())
        if not lock.acquire(timeout=max(0.0, deadline - time.monotonic())):
            raise BusTimeoutError(f"node {node_id}: busy with another transaction")
        try:
            waiter = _Waiter(node_id)
            with self._lock:
                if self._closed:
                    raise TransferAbortedError("the session is closed")
                self._waiters[node_id] = waiter
                self.stats.requests += 1
            try:
                yield waiter
            finally:
                with self._lock:
                    self._waiters.pop(node_id, None)
        finally:
            lock.release()

    def _send(self, message: Message) -> None:
        with self._lock:
            self.stats.frames_sent += 1
        self._send_message(message)

    def _wait(self, waiter: _Waiter, codes: set[FunctionCode], deadline: float,
              match: Callable[[Message], bool] = lambda m: True) -> Message | None:
        """The next frame with one of ``codes`` that ``match``es, or None at the timeout.

        Frames before it that do not fit (late answers to an earlier attempt) are dropped.
        """
        end = min(deadline, time.monotonic() + self.response_timeout)
        while True:
            left = end - time.monotonic()
            if left <= 0:
                return None
            try:
                item = waiter.inbox.get(timeout=left)
            except queue.Empty:
                return None
            if isinstance(item, _Abort):
                with self._lock:
                    self.stats.aborted += 1
                raise TransferAbortedError(f"node {waiter.node_id}: {item.reason}")
            if getattr(item, "CODE", None) in codes and match(item):
                return item

    def _attempts(self, node_id: int, what: str, timeout: float | None,
                  retries: int | None) -> Iterator[tuple[int, float]]:
        """Yield (attempt, deadline); raise BusTimeoutError when all attempts are used up."""
        total = (self.retries if retries is None else retries) + 1
        deadline = time.monotonic() + (timeout if timeout is not None
                                       else total * self.response_timeout * 8)
        for attempt in range(total):
            if attempt:
                with self._lock:
                    self.stats.retries += 1
            yield attempt, deadline
            if time.monotonic() >= deadline:
                break
        with self._lock:
            self.stats.timeouts += 1
        raise BusTimeoutError(f"node {node_id}: no answer to {what} "
                              f"after {attempt + 1} attempt(s)")

    @staticmethod
    def _check(response: Message, what: str) -> None:
        if response.code is not ResponseCode.SUCCESS:  # type: ignore[union-attr]
            raise DeviceRefusedError(f"node {response.node_id}: {what} refused "
                                     f"({response.code.title})")  # type: ignore[union-attr]

    # -- requests -----------------------------------------------------------------------
    def get(self, node_id: int, param: int, channel: int, *, timeout: float | None = None,
            retries: int | None = None, bulk_first: bool = False) -> bytes:
        """Get Device Parameter, following the device into a bulk transfer when it asks.

        ``bulk_first`` starts with Configure Get Bulk for a value known to be long (a
        descriptor string), saving the Get and its "use bulk" reply: two frames a string.
        """
        what = f"get parameter {param} of channel {channel}"
        same = lambda m: m.param == param and m.channel == channel  # noqa: E731
        bulk = bulk_first
        for _, deadline in self._attempts(node_id, what, timeout, retries):
            with self._exchange(node_id, deadline) as w:
                if not bulk:
                    self._send(GetParameter(node_id, param, channel))
                    resp = self._wait(w, {F.GET_PARAMETER_RESPONSE}, deadline, same)
                    if resp is None:
                        continue
                    if resp.code is ResponseCode.SUCCESS:  # type: ignore[union-attr]
                        return resp.value  # type: ignore[union-attr]
                    if resp.code is not ResponseCode.USE_BULK:  # type: ignore[union-attr]
                        self._check(resp, what)
                    bulk = True
                value = self._bulk_get(w, node_id, param, channel, deadline, what)
                if value is not None:
                    return value
        raise AssertionError("unreachable")  # pragma: no cover

    def _bulk_get(self, w: _Waiter, node_id: int, param: int, channel: int,
                  deadline: float, what: str) -> bytes | None:
        same = lambda m: m.param == param and m.channel == channel  # noqa: E731
        self._send(ConfigureGetBulk(node_id, param, channel))
        resp = self._wait(w, {F.CONFIGURE_GET_BULK_RESPONSE}, deadline, same)
        if resp is None:
            return None
        self._check(resp, f"{what} (bulk)")
        try:
            collector = BulkReassembler(resp.size)  # type: ignore[union-attr]
        except FrameError as err:
            raise DeviceRefusedError(f"node {node_id}: {err}") from err
        while not collector.complete:
            packet = self._wait(w, {F.BULK_DATA}, deadline)
            if packet is None:
                return None  # lost packet or a silent device: start over
            try:
                collector.add(packet.packet_id, packet.data)  # type: ignore[union-attr]
            except FrameError:
                self._send(BulkDataResponse(node_id, ResponseCode.FAILURE, mode=Mode.ARBITRATOR))
                return None
        self._send(BulkDataResponse(node_id, ResponseCode.SUCCESS, mode=Mode.ARBITRATOR))
        return collector.result()

    def set(self, node_id: int, param: int, channel: int, value: bytes, *,
            timeout: float | None = None, retries: int | None = None) -> None:
        """Set Device Parameter; values over 4 bytes (or when the device asks) go by bulk."""
        what = f"set parameter {param} of channel {channel}"
        same = lambda m: m.param == param and m.channel == channel  # noqa: E731
        bulk = len(value) > INLINE_MAX
        for _, deadline in self._attempts(node_id, what, timeout, retries):
            with self._exchange(node_id, deadline) as w:
                if not bulk:
                    self._send(SetParameter(node_id, param, channel, value))
                    resp = self._wait(w, {F.SET_PARAMETER_RESPONSE}, deadline, same)
                    if resp is None:
                        continue
                    if resp.code is ResponseCode.SUCCESS:  # type: ignore[union-attr]
                        return
                    if resp.code is not ResponseCode.USE_BULK:  # type: ignore[union-attr]
                        self._check(resp, what)
                    bulk = True
                if self._bulk_set(w, node_id, param, channel, value, deadline, what):
                    return
        raise AssertionError("unreachable")  # pragma: no cover

    def _bulk_set(self, w: _Waiter, node_id: int, param: int, channel: int, value: bytes,
                  deadline: float, what: str) -> bool:
        same = lambda m: m.param == param and m.channel == channel  # noqa: E731
        self._send(ConfigureSetBulk(node_id, param, channel, len(value)))
        resp = self._wait(w, {F.CONFIGURE_SET_BULK_RESPONSE}, deadline, same)
        if resp is None:
            return False
        self._check(resp, f"{what} (bulk)")
        for packet in packetize(value):
            self._send(BulkData(node_id, packet.packet_id, packet.data, mode=Mode.ARBITRATOR))
        done = self._wait(w, {F.BULK_DATA_RESPONSE}, deadline)
        if done is None or done.code is not ResponseCode.SUCCESS:  # type: ignore[union-attr]
            return False  # a packet got lost on the way: send the whole value again
        return True

    def _simple(self, node_id: int, request: Message, code: FunctionCode, what: str,
                timeout: float | None, retries: int | None) -> Message:
        for _, deadline in self._attempts(node_id, what, timeout, retries):
            with self._exchange(node_id, deadline) as w:
                self._send(request)
                resp = self._wait(w, {code}, deadline)
                if resp is not None:
                    self._check(resp, what)
                    return resp
        raise AssertionError("unreachable")  # pragma: no cover

    def suspend(self, node_id: int, ms: int, *, timeout: float | None = None) -> None:
        self._simple(node_id, Suspend(node_id, ms), F.SUSPEND_RESPONSE, "suspend", timeout, None)

    def release(self, node_id: int, *, timeout: float | None = None) -> None:
        self._simple(node_id, Release(node_id), F.RELEASE_RESPONSE, "release", timeout, None)

    def reset(self, node_id: int, *, timeout: float | None = None) -> None:
        self._simple(node_id, Reset(node_id), F.RESET_RESPONSE, "reset", timeout, None)
