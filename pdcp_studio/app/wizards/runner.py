"""A wizard's calls to the prosthesis, off the GUI thread: read, preview, and the one
transaction at the end of each guided task.

The transaction is the change road's (``session.transact``: interlock, write, read back, restore
on a mismatch, release, record in the fitting history), exactly as the main window's Write to
prosthesis runs it (:mod:`pdcp_studio.app.window.controllers.transaction_flow`): the wizard's
Write button is the user's confirmation of the preview shown on the page before, and the
prosthesis must still be as previewed, else nothing is written.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, NamedTuple, ParamSpec, TypeVar

from PySide6.QtCore import QObject, Signal
from shiboken6 import isValid

from pdcp_studio.app.documents import fitting

if TYPE_CHECKING:
    from pdcp_studio.bus.session.api import ChangePreview
    from pdcp_studio.bus.session.base import BusSession
    from pdcp_studio.bus.transaction import Change, Policy, TransactionResult
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.model.system import Link, System

P = ParamSpec("P")
R = TypeVar("R")


class Look(NamedTuple):
    """The prosthesis as one look found it."""

    system: System
    stored: ConfigCollection | None
    policy: Policy | None


class TransactionRunner(QObject):
    """Carries one change out on the window's prosthesis; ``progress(done, total, text)``,
    then ``finished(TransactionResult)`` or ``failed(message)``."""

    progress = Signal(int, int, str)
    finished = Signal(object)
    failed = Signal(str)

    def __init__(self, window: Any, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.window = window
        self.stop: threading.Event | None = None
        self.running = False

    def start(self, change: Change, links_previewed: list[Link],
              patient: str | None = None) -> bool:
        """Write ``change`` (already previewed and confirmed), recording ``patient`` (default:
        the window's patient reference) in the fitting history; False when not connected."""
        bridge = self.window.live.bridge
        if bridge is None or self.running:
            return False
        operator = fitting.operator_name(self.window)
        if patient is None:
            patient = self.window.patient_reference()
        shown = set(links_previewed)

        def same_bus(preview: ChangePreview) -> bool:  # the prosthesis must be as previewed
            return set(preview.links_before) == shown

        stop = threading.Event()
        session = bridge.session
        worker = bridge.run(
            lambda prog, _cancel: session.transact(
                change, operator=operator or None, patient=patient or None,
                confirm=same_bus, progress=prog, cancel=stop),
            change.action)
        if worker is None:
            return False
        self.stop, self.running = stop, True
        worker.progress.connect(self.progress)
        worker.finished.connect(self._done)
        worker.failed.connect(self._failed)
        return True

    def cancel(self) -> None:
        """Stop the running transaction: what was written is put back as it was."""
        if self.stop is not None:
            self.stop.set()

    def _done(self, result: TransactionResult) -> None:
        self.running = False
        self._after()
        self.finished.emit(result)

    def _failed(self, message: str) -> None:
        self.running = False
        self._after()
        self.failed.emit(message)

    def _after(self) -> None:
        """The window follows the prosthesis and its history (as after any transaction)."""
        window = self.window
        window.live.refresh()
        window.reread_configuration()
        window.history_panel.refresh()


def alive(owner: QObject, fn: Callable[P, None]) -> Callable[P, None]:
    """``fn`` that does nothing once ``owner`` is gone (a wizard closed and deleted while
    the bus still answers it)."""
    def call(*args: P.args, **kwargs: P.kwargs) -> None:
        if isValid(owner):
            fn(*args, **kwargs)

    return call


def on_bus(window: Any, fn: Callable[[Any], R], description: str,
           done: Callable[[R], None], failed: Callable[[str], None],
           owner: QObject | None = None) -> bool:
    """Run ``fn(session)`` on the window's bus worker; ``done(result)`` or ``failed(msg)``
    on the GUI thread (not once ``owner`` is gone). False when no prosthesis is connected."""
    bridge = window.live.bridge
    if bridge is None:
        return False
    session = bridge.session
    worker = bridge.run(lambda _p, _c: fn(session), description)
    if worker is None:
        return False
    if owner is not None:
        done, failed = alive(owner, done), alive(owner, failed)
    worker.finished.connect(done)
    worker.failed.connect(failed)
    return True


def look(session: BusSession) -> Look:
    """The prosthesis as it is: its system, stored configuration and policy."""
    return Look(session.system(), session.read_configuration(), session.read_policy())
