"""The one base class of every live bus session, as python-can's ``BusABC`` is of every bus.

What a session means is written here once: its lifetime (``closed``, ``close``, ``with``), its
events (``subscribe``), plans on the live system (``preview``) and the session's half of the
change road (``transact``, ``apply_plan``, ``write_configuration``, single edits — each one a
transaction the arbitrator carries out). A transport fills in the few methods that talk to an
arbitrator: ``system``, ``wait_settled``, ``scan``, ``get_parameter``, ``read_configuration``,
``read_policy``, ``carry_out`` and ``_release``. The transports: ``Session`` (in-process
arbitrator, bus/session/in_process.py), ``SimSession`` (bus/session/sim.py) and
``HostLinkSession`` (bus/hostlink/client.py). What only some sessions can do is a capability
(bus/session/capabilities.py), checked with ``isinstance``.

Sessions are thread-safe. Subscribers are called on the transport's thread and must only
enqueue (the app's SessionBridge does); a subscriber that raises is logged, never fatal.
"""

from __future__ import annotations

import abc
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Self

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.transaction import (
    Change,
    LinkAction,
    ParameterWrite,
    Policy,
    TransactionResult,
)
from pdcp_studio.errors import ModelError, TransportError
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Link, System

if TYPE_CHECKING:
    from pdcp_studio.bus.session.change_road import ConfirmFn
    from pdcp_studio.engine.plan import Plan
    from pdcp_studio.storage.archive.chain import Anchor
    from pdcp_studio.storage.history import History

Subscriber = Callable[[object], None]
#: ``progress(done, total, what)``: how far a long call (a scan, a transaction) has come.
ProgressFn = Callable[[int, int, str], None]

#: Least seconds between two Progress events a scan sends subscribers.
PROGRESS_EVENT_INTERVAL_S = 0.1

__all__ = ["PROGRESS_EVENT_INTERVAL_S", "BusSession", "ConfigVerifyError", "ProgressFn",
           "Subscriber"]


class ConfigVerifyError(TransportError):
    """The stored configuration read back after a write differs from what was written."""


class BusSession(abc.ABC):
    """A live prosthesis, however it is reached. Thread-safe; close it (or use ``with``)."""

    def __init__(self, url: str = "", *, events_owner: str = "session") -> None:
        self.url = url
        self._subs = ev.Subscribers(url or events_owner)
        self._closed = threading.Event()
        self._close_lock = threading.Lock()

    # -- lifetime -----------------------------------------------------------------------
    def __enter__(self) -> Self:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.url!r}{', closed' if self.closed else ''})"

    @property
    def closed(self) -> bool:
        return self._closed.is_set()

    def _check_open(self) -> None:
        if self._closed.is_set():
            raise TransportError(f"{self.url or 'bus'}: the session is closed")

    def close(self) -> None:
        """Release the bus (idempotent)."""
        with self._close_lock:
            if self._closed.is_set():
                return
            self._closed.set()
        self._release()

    @abc.abstractmethod
    def _release(self) -> None:
        """Let go of the transport: called once, by the first ``close``."""

    # -- events -------------------------------------------------------------------------
    def subscribe(self, callback: Subscriber) -> Callable[[], None]:
        """Call ``callback(event)`` for every bus event (bus/events.py); returns unsubscribe."""
        return self._subs.add(callback)

    def _emit(self, event: object) -> None:
        self._subs.emit(event)

    def _has_subscribers(self) -> bool:
        return len(self._subs) > 0

    def _reporting(self, progress: ProgressFn | None) -> ProgressFn:
        """``progress`` that also sends subscribers ``Progress`` events, at most one per
        ``PROGRESS_EVENT_INTERVAL_S`` and always the last one."""
        last = [0.0]

        def report(done: int, total: int, text: str) -> None:
            if progress is not None:
                progress(done, total, text)
            now = time.monotonic()
            if done >= total or now - last[0] >= PROGRESS_EVENT_INTERVAL_S:
                last[0] = now
                self._emit(ev.Progress(done, total, text))

        return report

    # -- the bus, as the transport reads it ---------------------------------------------
    @abc.abstractmethod
    def system(self) -> System:
        """A snapshot of the bus as the arbitrator sees it: devices (present or missing),
        channels, node IDs and links."""

    @abc.abstractmethod
    def wait_settled(self, timeout: float) -> bool:
        """Wait until binding, set-up and plans are done; False at the timeout."""

    @abc.abstractmethod
    def scan(self, progress: ProgressFn | None = None,
             cancel: threading.Event | None = None) -> System:
        """Every device's parameters and the links; ScanCancelled when cancelled."""

    @abc.abstractmethod
    def get_parameter(self, key: DeviceKey, param: int, channel: int = 0, *,
                      timeout: float | None = None) -> bytes:
        """Read one parameter from a device (bulk transfer when the device asks for it)."""

    @abc.abstractmethod
    def read_configuration(self) -> ConfigCollection:
        """The arbitrator's stored configuration (empty when it has none)."""

    @abc.abstractmethod
    def read_policy(self) -> Policy:
        """The arbitrator's profile-layer policy (autoconfigure on or off)."""

    def read_anchor(self) -> Anchor | None:
        """The fitting history's anchor the arbitrator keeps beside its stored configuration
        (reference §5 Decision): the entry that recorded its last change and that entry's
        hash; None when it keeps none. A transport that cannot say raises."""
        return None

    def write_anchor(self, anchor: Anchor) -> Anchor | None:
        """Store ``anchor`` in the arbitrator's memory; returns it as read back (None: this
        arbitrator keeps no anchor)."""
        return None

    @abc.abstractmethod
    def carry_out(self, change: Change, progress: ProgressFn | None = None,
                  cancel: threading.Event | None = None) -> TransactionResult:
        """The arbitrator's half of the change road (interlock, write, verify, restore,
        release); ``transact`` adds the preview, confirmation and record."""

    # -- plans --------------------------------------------------------------------------
    def preview(self, mode: str, config: ConfigCollection | None = None) -> Plan:
        """The engine's plan for ``mode`` on the current system; ``config`` defaults to the
        arbitrator's stored configuration (none when its memory is empty)."""
        from pdcp_studio.engine import plan_for, plan_on_bus

        self._check_open()
        autoconfigure = self.read_policy().autoconfigure
        if config is not None:
            return plan_for(mode, self.system(), config, autoconfigure=autoconfigure)
        return plan_on_bus(mode, self.system(), self.read_configuration(),
                           autoconfigure=autoconfigure)

    # -- the change road: every change is a transaction ---------------------------------
    def transact(self, change: Change, *, operator: str | None = None,
                 patient: str | None = None, confirm: ConfirmFn | None = None,
                 progress: ProgressFn | None = None, cancel: threading.Event | None = None,
                 history: History | None = None, record: bool = True) -> TransactionResult:
        """The whole change road (reference §5); see :func:`run_transaction` (imported
        here: opening a session, on the app's start-up path, needs none of it)."""
        from pdcp_studio.bus.session.change_road import run_transaction

        return run_transaction(self, change, operator=operator, patient=patient,
                               confirm=confirm, progress=progress, cancel=cancel,
                               history=history, record=record)

    def apply_plan(self, plan: Plan, progress: ProgressFn | None = None,
                   cancel: threading.Event | None = None) -> TransactionResult:
        """Carry a previewed plan out as one transaction (interlock, verify, all or nothing);
        not recorded — use ``transact(Change.from_plan(plan), …)`` for a recorded change."""
        return self.carry_out(Change.from_plan(plan), progress, cancel)

    def write_configuration(self, configuration: ConfigCollection) -> ConfigCollection:
        """Write the stored configuration as a transaction; ConfigVerifyError (a
        TransportError) when it does not verify — the old one is then restored."""
        result = self.carry_out(Change("config write", configuration=configuration))
        if not result.written:
            raise ConfigVerifyError(f"{self.url or 'bus'}: {result.summary()}")
        return self.read_configuration()

    def save_configuration(self) -> ConfigCollection:
        """Store the current links as the arbitrator's configuration (verified)."""
        return self.write_configuration(self.configuration_of_links())

    def configuration_of_links(self) -> ConfigCollection:
        """The live links as a stored configuration (what ``config save`` writes)."""
        from pdcp_studio.engine import configuration_from_system

        return ConfigCollection([configuration_from_system(self.system())])

    def add_link(self, link: Link) -> None:
        """Make one link as a transaction; ModelError when the bus refuses it as it is."""
        self._single(Change(f"add link {link}", links=[LinkAction("add", link)]))

    def remove_link(self, link: Link) -> None:
        """Remove one link as a transaction (ModelError if there is no such link)."""
        if link not in self.system().links:
            raise ModelError(f"link {link} is not in the system")
        self._single(Change(f"remove link {link}", links=[LinkAction("remove", link)]))

    def set_parameter(self, key: DeviceKey, param: int, channel: int, value: bytes, *,
                      timeout: float | None = None) -> None:
        """Write one parameter as a transaction (interlock, read back, restore)."""
        self._single(Change(f"set parameter 0x{param:02X} of {key}",
                            parameters=[ParameterWrite(DeviceKey(*key), param, channel,
                                                       bytes(value))]))

    def _single(self, change: Change) -> TransactionResult:
        """A single edit: a small, unrecorded transaction with its interlock."""
        result = self.carry_out(change)
        if not result.written:
            error = ModelError if result.step == "preview" else TransportError
            raise error(result.summary())
        return result
