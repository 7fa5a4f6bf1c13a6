"""Bridge a bus ``Session`` (threads, callbacks) to Qt signals on the GUI thread.

The session calls its subscribers on its own thread. Our callback only appends the
event to a deque (thread-safe, never blocks, never raises into the session); a
``QTimer`` on the GUI thread drains it every ``interval_ms`` in bounded batches, so a
flood of frames costs the GUI one batched signal per tick instead of one per frame.

Session calls that talk to the bus (scan, configuration read/write, plans, simulator
controls) run on a private one-thread pool — in order, one at a time, never on the GUI
thread — and report their results by signal.
"""

from __future__ import annotations

import logging
import threading
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QObject, QThreadPool, QTimer, Signal

from pdcp_studio.app.workers import Worker
from pdcp_studio.bus.session.capabilities import SimulatedDevices, SimulatorControls
from pdcp_studio.errors import PdcpError

if TYPE_CHECKING:
    from pdcp_studio.bus.session.base import BusSession
    from pdcp_studio.engine.plan import Plan
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.model.refs import DeviceKey
    from pdcp_studio.model.system import Device, System

log = logging.getLogger(__name__)

#: Events handled per timer tick; the rest wait for the next tick so the GUI stays responsive.
MAX_BATCH = 20_000
SIGNAL_CHANNEL_VALUE = "2channelValue(PyObject)"


class SessionBridge(QObject):
    """Qt face of a ``Session``: its events as signals, its slow calls on a worker.

    Construct with an open session (``open_session(url)``); the bridge subscribes at once.
    Event signals: ``deviceJoined(key)``, ``deviceLeft(key)``, ``linkMade(link)``,
    ``linkRemoved(link)``, ``frameSeen(list[FrameSeen])`` (one list per tick),
    ``channelValue(ChannelValue)`` and ``channelValues(list[ChannelValue])`` (per tick),
    ``planApplied(plan)``, ``error(str)`` (bus errors and failed calls),
    ``progress(done, total, text)`` (coalesced: the newest per tick),
    ``busEvent(event)`` (every event except frames, values and progress, for logging).
    Call results: ``scanned(System)``, ``configurationRead(ConfigCollection)``,
    ``configurationWritten(ConfigCollection)`` (the session's verified read-back),
    ``simChanged(str)`` (after a simulator control, with a description), ``simDevices(list)``
    (``(DeviceKey, label, plugged)`` tuples), ``scriptFinished(ScriptResult)``,
    ``busyChanged(bool)``, ``closed()``.

    Calls (each returns the ``Worker``, or None once closed; failures go to ``error``):
    ``scan()``, ``read_configuration()``, ``write_configuration(collection)``,
    ``save_configuration()``, ``apply_plan(plan)``, ``run(fn, description, on_result)``;
    simulator controls ``refresh_sim_devices()``, ``plug(key)``, ``unplug(key)``,
    ``replace(old, new)``, ``reset_arbitrator(keep_memory)``, ``run_script(name)``;
    ``script_names()`` (no bus traffic), ``system()`` (a snapshot), ``cancel_all()``,
    ``close(wait_ms)``. Properties: ``is_sim``, ``busy``.
    """

    deviceJoined = Signal(object)
    deviceLeft = Signal(object)
    linkMade = Signal(object)
    linkRemoved = Signal(object)
    frameSeen = Signal(list)
    channelValue = Signal(object)
    channelValues = Signal(list)
    planApplied = Signal(object)
    error = Signal(str)
    progress = Signal(int, int, str)
    busEvent = Signal(object)

    scanned = Signal(object)
    configurationRead = Signal(object)
    configurationWritten = Signal(object)
    simChanged = Signal(str)
    simDevices = Signal(list)
    scriptFinished = Signal(object)
    busyChanged = Signal(bool)
    closed = Signal()

    def __init__(self, session: BusSession, parent: QObject | None = None, *,
                 interval_ms: int = 50, url: str = "") -> None:
        super().__init__(parent)
        self.session = session
        self.url = url
        self._queue: deque[Any] = deque()
        self._pool = QThreadPool(self)
        self._pool.setMaxThreadCount(1)  # one bus conversation at a time, in order
        self._pending: set[Worker] = set()
        self._closed = False
        self._unsubscribe: Callable[[], None] | None = session.subscribe(self._enqueue)
        self._timer = QTimer(self)
        self._timer.setInterval(interval_ms)
        self._timer.timeout.connect(self.drain)
        self._timer.start()

    # -- events ------------------------------------------------------------------------
    def _enqueue(self, event: Any) -> None:
        """Session-thread callback: only enqueue (deque.append is atomic)."""
        self._queue.append(event)

    @property
    def is_sim(self) -> bool:
        """True when the session is a simulated prosthesis (it has simulator controls)."""
        return isinstance(self.session, SimulatedDevices)

    @property
    def busy(self) -> bool:
        """True while any call of this bridge is queued or running."""
        return bool(self._pending)

    def drain(self) -> int:
        """Deliver up to MAX_BATCH queued events as signals; returns how many.

        Frames and channel values go out as one list each per call; progress reports are
        coalesced to the newest one (a scan reports thousands); every other event is
        dispatched in the order it happened.
        """
        frames: list[Any] = []
        values: list[Any] = []
        progress: Any = None
        n = 0
        queue = self._queue
        while queue and n < MAX_BATCH:
            event = queue.popleft()
            n += 1
            kind = type(event).__name__
            if kind == "ChannelValue":
                values.append(event)
            elif kind == "FrameSeen":
                frames.append(event)
            elif kind == "Progress":
                progress = event
            else:
                self._dispatch(kind, event)
        if progress is not None:
            self.progress.emit(int(progress.done), int(progress.total), str(progress.what))
        if frames:
            self.frameSeen.emit(frames)
        if values:
            self.channelValues.emit(values)
            if self.receivers(SIGNAL_CHANNEL_VALUE) > 0:  # per-value only when someone listens
                for v in values:
                    self.channelValue.emit(v)
        return n

    def _dispatch(self, kind: str, event: Any) -> None:
        if kind == "DeviceJoined":
            self.deviceJoined.emit(event.key)
        elif kind == "DeviceLeft":
            self.deviceLeft.emit(event.key)
        elif kind == "LinkMade":
            self.linkMade.emit(event.link)
        elif kind == "LinkRemoved":
            self.linkRemoved.emit(event.link)
        elif kind == "BusError":
            self.error.emit(str(event.message))
        elif kind == "PlanApplied":
            self.planApplied.emit(event.plan)
        else:
            log.debug("unhandled bus event %r", event)
        self.busEvent.emit(event)

    # -- calls on the worker -----------------------------------------------------------
    def run(self, fn: Callable[[Any, threading.Event], Any], description: str,
            on_result: Callable[[Any], None] | None = None, *,
            forward_progress: bool = True) -> Worker | None:
        """Run ``fn(progress, cancel)`` on the bridge's worker; failures go to ``error``.

        Its progress reports become ``progress`` signals unless ``forward_progress`` is
        False (a call whose session reports ``Progress`` events itself: they already do).
        Returns the worker (to cancel it or connect more) or None once closed.
        """
        if self._closed:
            self.error.emit(
                self.tr("{description}: the bus connection is closed").format(
                    description=description
                )
            )
            return None
        worker = Worker(fn, description)
        if forward_progress:
            worker.progress.connect(self.progress)
        worker.failed.connect(lambda msg: self.error.emit(f"{description}: {msg}"))
        if on_result is not None:
            worker.finished.connect(on_result)
        worker.done.connect(lambda: self._finished(worker))
        was_busy = self.busy
        self._pending.add(worker)
        worker.start(self._pool)
        if not was_busy:
            self.busyChanged.emit(True)
        return worker

    def _finished(self, worker: Worker) -> None:
        self._pending.discard(worker)
        if not self._pending:
            self.busyChanged.emit(False)

    def cancel_all(self) -> None:
        """Ask every queued or running call to stop."""
        for w in list(self._pending):
            w.cancel()

    def system(self) -> System:
        """The session's current view of the bus (a copy is the session's business)."""
        return self.session.system()

    def scan(self) -> Worker | None:
        """Read the whole bus; the result arrives as ``scanned(System)``.

        The session reports the scan's progress as ``Progress`` events (``progress``, at
        most one per drain): the worker's own reports (its ``progress``, for a caller that
        follows this scan alone) are not sent on as well — twice the status bar updates
        on the GUI thread for the same news."""
        return self.run(lambda p, c: self.session.scan(p, c), "Scan", self._scanned,
                        forward_progress=False)

    def _scanned(self, system: System) -> None:
        self.drain()  # the scan's own events (its last Progress) come before its result
        self.scanned.emit(system)

    def read_configuration(self) -> Worker | None:
        """The arbitrator's stored configuration arrives as ``configurationRead``."""
        return self.run(lambda p, c: self.session.read_configuration(),
                        "Read configuration", self.configurationRead.emit)

    def write_configuration(self, configuration: ConfigCollection) -> Worker | None:
        """Write, and emit ``configurationWritten`` with what the session returned."""
        return self.run(lambda p, c: self.session.write_configuration(configuration),
                        "Write configuration", self.configurationWritten.emit)

    def apply_plan(self, plan: Plan) -> Worker | None:
        """Apply a plan; the session reports ``PlanApplied`` which becomes ``planApplied``."""
        return self.run(lambda p, c: self.session.apply_plan(plan, p, c), "Apply plan")

    # -- simulator controls ------------------------------------------------------------
    #: ``namer(key) -> str``: a part's name in the messages below (the Simulator panel
    #: sets its own, the graph's names; else the catalogue's product).
    namer: Callable[[Any], str] | None = None

    def _name(self, key: Any) -> str:
        if self.namer is not None:
            return self.namer(key)
        from pdcp_studio.app.words.part_names import part_name
        from pdcp_studio.model.refs import DeviceKey

        return part_name(None, DeviceKey(*key))

    def _sim(self, what: str, call: Callable[[], Any], done: str = "") -> Worker | None:
        """``what``: the control, in words (errors begin with it); ``done``: the sentence
        ``simChanged`` carries once it is done."""
        if not self.is_sim:
            self.error.emit(
                self.tr("{what}: only a simulated bus has simulator controls").format(what=what)
            )
            return None
        return self.run(lambda p, c: call(), what,
                        lambda _r: self.simChanged.emit(done or what))

    def refresh_sim_devices(self) -> Worker | None:
        """Ask for the simulator's devices; they arrive as ``simDevices(list)``."""
        if not self.is_sim:
            return None
        session = _simulated(self.session)
        return self.run(lambda p, c: list(session.sim_devices()), "List simulated devices",
                        self.simDevices.emit)

    def plug(self, key: DeviceKey) -> Worker | None:
        """Power a simulated device on (``simChanged`` when done)."""
        name = self._name(key)
        return self._sim(self.tr("Plugging in {device}").format(device=name),
                         lambda: _simulated(self.session).plug(key),
                         self.tr("Plugged in {device}").format(device=name))

    def unplug(self, key: DeviceKey) -> Worker | None:
        """Cut a simulated device off the bus; ``deviceLeft`` follows once noticed."""
        name = self._name(key)
        return self._sim(self.tr("Unplugging {device}").format(device=name),
                         lambda: _simulated(self.session).unplug(key),
                         self.tr("Unplugged {device}").format(device=name))

    def replace(self, old: DeviceKey, new: DeviceKey | Device) -> Worker | None:
        """Unplug ``old`` and plug ``new`` in (a simulated device's key or a Device)."""
        from pdcp_studio.model.system import Device

        old_name = self._name(old)
        new_name = self._name(new.key if isinstance(new, Device) else new)
        return self._sim(self.tr("Replacing {old} by {new}").format(old=old_name, new=new_name),
                         lambda: _simulator(self.session).replace(old, new),
                         self.tr("Replaced {old} by {new}").format(old=old_name, new=new_name))

    def reset_arbitrator(self, keep_memory: bool) -> Worker | None:
        """Restart the arbitrator, keeping or erasing its stored configuration."""
        what = (self.tr("Restarting the arbitrator, keeping its memory") if keep_memory else
                self.tr("Restarting the arbitrator, erasing its memory"))
        done = (self.tr("The arbitrator restarted; its stored configuration was kept")
                if keep_memory else
                self.tr("The arbitrator restarted with its memory erased"))
        return self._sim(what, lambda: _simulator(self.session).reset_arbitrator(keep_memory),
                         done)

    def script_names(self) -> list[str]:
        """The simulator's scripted events (a lookup, no bus traffic)."""
        session = self.session
        return list(session.script_names()) if isinstance(session, SimulatedDevices) else []

    def run_script(self, name: str) -> Worker | None:
        """Run a simulator script with progress and cancel; ``scriptFinished(result)``."""
        if not self.is_sim:
            self.error.emit(
                self.tr("Script {name}: only a simulated bus has simulator controls").format(
                    name=name
                )
            )
            return None

        def done(result: Any) -> None:
            self.scriptFinished.emit(result)
            self.simChanged.emit(self.tr("Script {name} finished").format(name=name))

        return self.run(lambda p, c: _simulator(self.session).run_script(name, p, c),
                        self.tr("Script {name}").format(name=name), done)

    def save_configuration(self) -> Worker | None:
        """Store the bus's current links as the arbitrator's configuration (verified);
        the read-back arrives as ``configurationWritten``."""
        return self.run(lambda p, c: self.session.save_configuration(),
                        "Store the current links", self.configurationWritten.emit)

    # -- shutdown ------------------------------------------------------------------------
    def close(self, wait_ms: int = 3000) -> None:
        """Unsubscribe, cancel pending calls, close the session off the GUI thread.

        Waits at most ``wait_ms`` for the close to finish (0: return at once); ``closed``
        is emitted when the session has closed.
        """
        if self._closed:
            return
        self._closed = True
        self._timer.stop()
        if self._unsubscribe is not None:
            try:
                self._unsubscribe()
            except Exception:
                log.warning("unsubscribe failed", exc_info=True)
            self._unsubscribe = None
        self._queue.clear()
        self.cancel_all()
        worker = Worker(lambda p, c: self.session.close(), "Close bus")
        worker.done.connect(self.closed.emit)
        worker.failed.connect(lambda msg: log.warning("closing the bus: %s", msg))
        worker.start(self._pool)
        if wait_ms:
            self._pool.waitForDone(wait_ms)


def _simulated(session: BusSession) -> SimulatedDevices:
    """``session``'s simulated devices (callers ask ``is_sim`` first)."""
    if not isinstance(session, SimulatedDevices):
        raise PdcpError(f"{session.url}: only a simulated bus has simulator controls")
    return session


def _simulator(session: BusSession) -> SimulatorControls:
    """``session``'s whole simulator (callers ask ``is_sim`` first)."""
    if not isinstance(session, SimulatorControls):
        raise PdcpError(f"{session.url}: only a simulated bus has simulator controls")
    return session
