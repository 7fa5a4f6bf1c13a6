"""A python-can bus that survives its adapter being pulled out and put back.

:class:`ReopeningBus` is a ``can.BusABC`` around the real bus (python-can composes buses the
same way, e.g. ``can.ThreadSafeBus``). When the real bus raises on a read or a write — python-can
reports a pulled slcan or USB adapter as ``CanOperationError`` or ``OSError`` on every call — it
shuts that bus down, reports the outage once, and reopens it with backoff
(:mod:`pdcp_studio.bus.outage`). While it is away a read waits for the next try instead of
returning at once, so python-can's Notifier never spins, and a send raises
``CanOperationError`` at once. ``on_state(state, line)`` is called with ``disconnected`` and
``reconnected`` (on the Notifier's thread: it must only enqueue; the arbitrator posts it to its
own thread, re-reads presence and links, and emits ``ev.BusState``).
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from typing import Any

import can

from pdcp_studio.bus.outage import Outage

log = logging.getLogger(__name__)

StateFn = Callable[[str, str], None]


def _why(err: BaseException) -> str:
    text = " ".join(str(err).split()) or type(err).__name__
    return text if len(text) <= 160 else text[:157] + "…"


class ReopeningBus(can.BusABC):
    """The bus ``opener()`` returns, reopened with backoff whenever it fails.

    The first ``opener()`` runs here and raises as usual (a wrong URL or a missing driver is
    not an outage).
    """

    def __init__(self, opener: Callable[[], can.BusABC], *, name: str = "bus",
                 on_state: StateFn | None = None, outage: Outage | None = None) -> None:
        self._opener = opener
        self.name = name
        self.on_state = on_state
        self.outage = outage or Outage(name)
        self._lock = threading.Lock()
        self._bus: can.BusABC | None = opener()
        #: The real bus's class name (the connection's echo filter needs it).
        self.inner_type = type(self._bus).__name__
        self.channel_info = f"{self._bus.channel_info} (reopened when it fails)"
        super().__init__(channel=getattr(self._bus, "channel", "") or "")

    @property
    def connected(self) -> bool:
        return self._bus is not None

    # -- python-can's bus interface ---------------------------------------------------------
    def _recv_internal(self, timeout: float | None) -> tuple[can.Message | None, bool]:
        bus = self._bus
        if bus is not None:
            try:
                return bus.recv(timeout), True  # the real bus applies its own filters
            except Exception as err:  # what a pulled adapter raises differs per driver
                self._lost(bus, err)
                return None, True
        now = time.monotonic()
        if self.outage.due(now):
            self._reopen(now)
        else:
            pause = self.outage.wait(now)
            time.sleep(pause if timeout is None else min(pause, max(timeout, 0.0)))
        return None, True

    def send(self, msg: can.Message, timeout: float | None = None) -> None:
        bus = self._bus
        if bus is None:
            raise can.CanOperationError(f"{self.name}: the adapter is disconnected; "
                                        "reconnecting")
        try:
            bus.send(msg, timeout)
        except can.CanTimeoutError:
            raise  # a full transmit queue, not a lost adapter
        except (OSError, can.CanOperationError) as err:
            self._lost(bus, err)
            raise can.CanOperationError(f"{self.name}: the adapter is disconnected "
                                        f"({_why(err)}); reconnecting") from err

    def shutdown(self) -> None:
        with self._lock:
            bus, self._bus = self._bus, None
        if bus is not None:
            try:
                bus.shutdown()
            except Exception as err:
                log.debug("%s: shutting the adapter down: %s", self.name, err)
        super().shutdown()

    # -- outages ------------------------------------------------------------------------------
    def _lost(self, bus: can.BusABC, err: BaseException) -> None:
        with self._lock:
            if self._bus is not bus:
                return  # another thread already took it down
            self._bus = None
            line = self.outage.failed(time.monotonic(), _why(err))
        try:
            bus.shutdown()
        except Exception as shut:  # the adapter is gone: closing it may fail too
            log.debug("%s: closing the lost adapter: %s", self.name, shut)
        if line:
            log.warning("%s", line)
            self._tell("disconnected", line)

    def _reopen(self, now: float) -> None:
        try:
            bus = self._opener()
        except Exception as err:
            line = self.outage.attempt_failed(time.monotonic(), _why(err))
            if line:
                log.warning("%s", line)
            return
        with self._lock:
            if self._is_shutdown:
                bus.shutdown()
                return
            self._bus = bus
            line = self.outage.reopened(time.monotonic())
        log.warning("%s", line)
        self._tell("reconnected", line)

    def _tell(self, state: str, line: str) -> None:
        if self.on_state is not None:
            try:
                self.on_state(state, line)
            except Exception:
                log.exception("%s: the %s listener failed", self.name, state)


def open_reopening(spec: Any, **options: Any) -> ReopeningBus:
    """The python-can bus of a ``can:`` spec, reopened when its adapter is pulled and put back."""
    from pdcp_studio.bus.session.urls import DEFAULT_BITRATE, open_can_bus, open_spec

    first = [True]

    def opener() -> can.BusABC:
        if first[0]:  # checks the URL and warns about its bitrate, once
            first[0] = False
            return open_spec(spec, **options)
        return open_can_bus(spec.interface, spec.channel, url=spec.url,
                            bitrate=spec.bitrate or DEFAULT_BITRATE,
                            **{**dict(spec.options), **options})

    return ReopeningBus(opener, name=spec.url)
