"""The live bus behind a document: connect off the GUI thread, follow events, disconnect.

``open_session(url)`` (binding, start-up, a first look at the bus) runs on a worker with
progress; the session's events arrive through :class:`SessionBridge` signals and keep the
document in step — a device that leaves is marked missing at once, and every change asks
the session for a fresh snapshot (one request in flight, coalesced), merged by
:meth:`Document.sync_live`. Data frames light up the links they flow on.

The connection is a state of its own (``state``: offline, connecting, live, disconnected;
``stateChanged``), shown by the window at all times. Connecting to another bus keeps the
session you have until the new one answers: a failed Connect changes nothing.
"""

from __future__ import annotations

import logging
import threading
import time
from concurrent.futures import Future
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QObject, QTimer, Signal

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.words.plural import count
from pdcp_studio.app.workers import Worker

if TYPE_CHECKING:
    from pdcp_studio.app.graph.layout import Position
    from pdcp_studio.app.live.session_bridge import SessionBridge
    from pdcp_studio.bus.session.base import BusSession, ProgressFn
    from pdcp_studio.model.refs import DeviceKey
    from pdcp_studio.model.system import System

log = logging.getLogger(__name__)

#: The connection's states (``LiveController.state``).
OFFLINE, CONNECTING, LIVE, DISCONNECTED = "offline", "connecting", "live", "disconnected"
#: How long after a part joined as a newcomer the part it replaces may still leave for the
#: two cards to swap places (the old part is missed once the bus notices it is silent).
SWAP_WINDOW_S = 60.0
#: A live view's positions are remembered this long after the last part joined or left.
REMEMBER_MS = 400


def open_session_blocking(url: str, progress: ProgressFn | None = None,
                          cancel: threading.Event | None = None) -> BusSession:
    """Open a bus session (on a worker thread); PdcpError or ImportError on failure."""
    from pdcp_studio.bus.session.opening import open_session

    if progress is not None:
        progress(0, 0, f"Connecting to {url}…")
    return open_session(url)


def opened_early(opening: Future[BusSession], url: str,
                 progress: ProgressFn | None = None) -> BusSession:
    """The session ``opening`` opens (on a thread of its own since start-up,
    ``application.open_early``); what it raised, raised here."""
    if progress is not None:
        progress(0, 0, f"Connecting to {url}…")
    return opening.result()


def _on_bus(snapshot: System, key: DeviceKey) -> bool:
    device = snapshot.devices.get(key)
    return device is not None and bool(device.present)


def read_and_place(session: BusSession,
                   shape: float = 1.0) -> tuple[System, dict[DeviceKey, Position]]:
    """The bus's first snapshot and its cards' layout (on the worker: the layout imports
    networkx and walks the whole bus, which stalled the GUI thread on ``sim:full``)."""
    from pdcp_studio.app.graph import layout

    system = session.system()
    return system, layout.place(system, {}, shape)


class LiveController(QObject):
    """Owns the bridge of the document's live session, if any."""

    connected = Signal(str)  # url — the document now shows the bus
    failed = Signal(str, str)  # url, message
    disconnected = Signal()
    #: The connection's state changed (``OFFLINE``, ``CONNECTING``, ``LIVE``, ``DISCONNECTED``).
    stateChanged = Signal(str)
    #: A new session's bridge replaced the old one and its first snapshot is on screen.
    sessionStarted = Signal(object)
    #: The bus as it is now (a snapshot merged into the document), after any bus event
    #: that changed it (a snapshot showing the bus exactly as last seen is not passed on).
    snapshotTaken = Signal(object)
    statusMessage = Signal(str)
    progress = Signal(int, int, str)
    busyChanged = Signal(bool)
    #: Every bridge, when made (for docks that want frames or values).
    bridgeReady = Signal(object)

    def __init__(self, doc: Document, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self.bridge: SessionBridge | None = None
        self.url = ""
        #: The URL being connected to (while ``state`` is ``CONNECTING``).
        self.connecting_url = ""
        self.state = OFFLINE
        #: The last connection's URL (shown while ``DISCONNECTED``).
        self.last_url = ""
        self.connecting: Worker | None = None
        self._refreshing = False
        self._again = False
        #: A callable given each output ref that sent data (the scene's ``flow.note_data``).
        self.on_data: Any = None
        #: A callable giving the graph's shape (width / height) for the first layout.
        self.layout_shape: Any = None
        #: Parts that joined this session as newcomers: identity, place given, when.
        self._newcomers: dict[Any, tuple[str, tuple[float, float], float]] = {}
        #: Parts that joined before a snapshot read them: named once one does.
        self._joined_unread: set[Any] = set()
        #: The remembered layouts, read once a session when a part joins (None: not yet).
        self._layouts: list[Any] | None = None
        self._remember_timer = QTimer(self)
        self._remember_timer.setSingleShot(True)
        self._remember_timer.setInterval(REMEMBER_MS)
        self._remember_timer.timeout.connect(self.doc.remember_layout)

    @property
    def is_live(self) -> bool:
        return self.bridge is not None

    # -- connecting -----------------------------------------------------------------
    def _set_state(self, state: str) -> None:
        if state != self.state:
            self.state = state
            self.stateChanged.emit(state)

    def connect_bus(self, url: str, opening: Future[BusSession] | None = None) -> Worker:
        """Open ``url`` on a worker; ``connected`` or ``failed`` follows.

        The current session (if any) stays until the new one has opened: a failed Connect
        leaves the window as it was. ``opening``: the session already being opened (at
        start-up, while the window is built), taken instead of opening another.
        """
        if self.connecting is not None and self.connecting.is_running:
            self.connecting.cancel()  # its session, if it still opens, is closed unused
        self.connecting_url = url
        self._set_state(CONNECTING)
        self.busyChanged.emit(True)

        def work(p: ProgressFn, cancel: threading.Event) -> BusSession:
            session = (open_session_blocking(url, p, cancel) if opening is None
                       else opened_early(opening, url, p))
            if cancel.is_set():  # superseded by another Connect: nobody will use it
                session.close()
            return session

        worker = Worker(work, f"Connect {url}")
        worker.progress.connect(self.progress)
        worker.finished.connect(lambda session: self._opened(url, session))
        worker.failed.connect(lambda msg: self._failed(url, msg))
        worker.done.connect(lambda: self.busyChanged.emit(False))
        self.connecting = worker  # kept until the next connect: its done() must still run
        self.statusMessage.emit(self.tr("Connecting to {url}…").format(url=url))
        return worker.start()

    def _failed(self, url: str, message: str) -> None:
        if url != self.connecting_url:
            return  # an older attempt, superseded
        self.connecting_url = ""
        self._set_state(LIVE if self.bridge is not None else
                        DISCONNECTED if self.last_url else OFFLINE)
        self.failed.emit(url, message)

    def _opened(self, url: str, session: BusSession) -> None:
        from pdcp_studio.app.live.session_bridge import SessionBridge

        if url != self.connecting_url:  # superseded meanwhile
            try:
                session.close()
            except Exception:
                log.warning("closing a superseded session failed", exc_info=True)
            return
        self._close_bridge()  # the old session goes only now that the new one is open
        self.url = url
        bridge = SessionBridge(session, self, url=url)
        self.bridge = bridge
        bridge.deviceJoined.connect(self._on_joined)
        bridge.deviceLeft.connect(self._on_left)
        bridge.linkMade.connect(lambda _l: self.refresh())
        bridge.linkRemoved.connect(lambda _l: self.refresh())
        bridge.planApplied.connect(self._on_plan_applied)
        bridge.busEvent.connect(self._on_bus_event)
        bridge.channelValues.connect(self._on_values)
        bridge.error.connect(
            lambda msg: self.statusMessage.emit(self.tr("Bus: {msg}").format(msg=msg))
        )
        bridge.progress.connect(self.progress)
        bridge.busyChanged.connect(self.busyChanged)
        bridge.scanned.connect(self._on_snapshot)
        self.bridgeReady.emit(bridge)
        shape = self.layout_shape() if self.layout_shape is not None else 1.0
        bridge.run(lambda _p, _c: read_and_place(session, shape), "Read the bus",
                   lambda result: self._first_snapshot(bridge, *result))

    def _first_snapshot(self, bridge: SessionBridge, system: System,
                        positions: dict[DeviceKey, Position]) -> None:
        if bridge is not self.bridge:
            return
        self.connecting_url = ""
        self._newcomers.clear()
        self._layouts = None
        self.doc.set_system(system, None, self.bridge, positions=positions)
        self.last_url = self.url
        self._set_state(LIVE)
        self.sessionStarted.emit(bridge)
        self.snapshotTaken.emit(system)
        self.connected.emit(self.url)
        self.statusMessage.emit(
            self.tr("Live: {url} — {devices}, {links}").format(
                url=self.url,
                devices=count("LiveController", "%n device(s)", len(system.devices)),
                links=count("LiveController", "%n link(s)", len(system.links)))
        )

    def _close_bridge(self) -> bool:
        if self._remember_timer.isActive():  # still the live view: remembered now
            self._remember_timer.stop()
            self.doc.remember_layout()
        bridge, self.bridge = self.bridge, None
        if bridge is None:
            return False
        bridge.close(wait_ms=2000)
        if self.doc.session is bridge:
            self.doc.set_session(None)
        return True

    def disconnect_bus(self) -> None:
        """Close the session (off the GUI thread, bounded wait); the system stays on screen."""
        if self.connecting is not None and self.connecting.is_running:
            self.connecting.cancel()
        self.connecting_url = ""
        if not self._close_bridge():
            if self.state == CONNECTING:
                self._set_state(DISCONNECTED if self.last_url else OFFLINE)
            return
        self._set_state(DISCONNECTED)
        self.disconnected.emit()

    def state_text(self) -> str:
        """The connection in a few words, for the status bar and the window title."""
        if self.state == CONNECTING:
            if self.bridge is not None:
                return self.tr("live on {0}, connecting to {1}…").format(
                    self.url, self.connecting_url)
            return self.tr("connecting to {0}…").format(self.connecting_url)
        if self.state == LIVE:
            return self.tr("live on {0}").format(self.url)
        if self.state == DISCONNECTED:
            return self.tr("disconnected from {0}").format(self.last_url)
        return self.tr("offline")

    # -- following the bus ----------------------------------------------------------
    def refresh(self) -> None:
        """Ask for a fresh snapshot; while one is in flight, ask once more afterwards."""
        if self.bridge is None:
            return
        if self._refreshing:
            self._again = True
            return
        self._refreshing = True
        session = self.bridge.session
        worker = self.bridge.run(lambda _p, _c: session.system(), "Refresh", self._on_snapshot)
        if worker is None:
            self._refreshing = False
            return
        worker.done.connect(self._refresh_done)

    def _refresh_done(self) -> None:
        self._refreshing = False
        if self._again:
            self._again = False
            self.refresh()

    def _on_snapshot(self, system: System) -> None:
        """Merge a snapshot; one that shows the bus exactly as last seen changes nothing
        and is not passed on (a rescan of the same bus costs the GUI thread ~nothing)."""
        if self.bridge is not None and self.doc.session is self.bridge:
            devices = self.doc.system.devices
            left = [k for k, d in devices.items() if d.present and not _on_bus(system, k)]
            joined = self._place_joined(system)
            if self.doc.sync_live(system):
                self.snapshotTaken.emit(system)
            read = [k for k in self._joined_unread if k in self.doc.system.devices]
            self._joined_unread.difference_update(read)
            self._say_joined(read)
            if joined:
                self._note_newcomers(joined)
            if left:
                self._swap_in(left)
            if joined or left:
                self._remember_soon()

    def _place_joined(self, snapshot: System) -> list[DeviceKey]:
        """Before ``snapshot`` is merged: places for the parts new to the view, as a
        connect would give them (:func:`live_layout.place_joined`) — a replacement where
        the part it replaces was, that part put aside. Returns the parts placed as any
        newcomer is (no predecessor yet), to be noted."""
        doc = self.doc
        devices = doc.system.devices
        joined = {k: d for k, d in snapshot.devices.items() if k not in devices}
        if not joined:
            return []
        from pdcp_studio.app.graph import layout, style
        from pdcp_studio.app.live import layout as live_layout

        ident = live_layout.part_identity
        new = {k: ident(k, d) for k, d in joined.items()}
        mine = {k: ident(k, d) for k, d in devices.items()}
        gone = {k: p for k, p in mine.items() if not _on_bus(snapshot, k)}
        where = live_layout.place_joined(doc.positions, gone, new)
        if doc.is_live_view and len(where.placed) < len(new):  # the remembered layout, too
            if self._layouts is None:  # read once a session (~0.4 ms a remembered layout)
                self._layouts = live_layout.stored_layouts()
            remembered = live_layout.remembered_elsewhere(
                [*mine.values(), *new.values()], mine.values(), self._layouts)
            if remembered:
                heights = {k: layout.card_height(d)
                           for k, d in (*devices.items(), *joined.items())}
                where = live_layout.place_joined(doc.positions, gone, new,
                                                 remembered=remembered, heights=heights,
                                                 width=style.CARD_WIDTH)
        for key in where.displaced:  # off the bus: to the bottom of its column
            doc.positions.pop(key, None)
        doc.positions.update(where.placed)
        return [k for k in joined if k not in where.placed]

    def _remember_soon(self) -> None:
        """Remember a live view's positions once the bus has settled (parts binding one
        after another are remembered once, not at each snapshot: ~25 ms a save)."""
        if self.doc.is_live_view:
            self._remember_timer.start()

    def _note_newcomers(self, keys: list[Any]) -> None:
        """Parts placed as newcomers (after the scene placed them): a part that leaves
        soon after may be the one they replace (:meth:`_swap_in`)."""
        from pdcp_studio.app.live.layout import part_identity

        now = time.monotonic()
        for key in keys:
            device = self.doc.system.devices.get(key)
            if device is not None and key in self.doc.positions:
                self._newcomers[key] = (part_identity(key, device), self.doc.positions[key],
                                        now)

    def _swap_in(self, left: list[Any]) -> bool:
        """Parts left the bus: a part that joined just before as a newcomer and replaces
        one of them takes its place, the two cards swapping (:func:`live_layout.swap_in`)."""
        from pdcp_studio.app.live import layout as live_layout

        now = time.monotonic()
        self._newcomers = {k: v for k, v in self._newcomers.items()
                           if now - v[2] <= SWAP_WINDOW_S and k in self.doc.system.devices}
        if not self._newcomers:
            return False
        devices = self.doc.system.devices
        gone = {k: live_layout.part_identity(k, devices[k]) for k in left if k in devices}
        moves = live_layout.swap_in(gone, {k: v[0] for k, v in self._newcomers.items()},
                                    self.doc.positions,
                                    {k: v[1] for k, v in self._newcomers.items()})
        for key, pos in moves.items():
            self._newcomers.pop(key, None)
            self.doc.set_position(key, pos)
        return bool(moves)

    def _on_bus_event(self, event: Any) -> None:
        """Any other event that may change the bus (an arbitrator reset, a stored
        configuration implemented): look at the bus again."""
        if type(event).__name__ == "DeviceReplaced":
            # The arbitrator forgot a part that is replaced: no longer missing here either
            # (once every panel has named it in this event's words).
            QTimer.singleShot(0, self, lambda key=event.key: self._forget_replaced(key))
        if type(event).__name__ not in ("DeviceJoined", "DeviceLeft", "LinkMade",
                                        "LinkRemoved", "PlanApplied", "BusError"):
            self.refresh()

    def _forget_replaced(self, key: Any) -> None:
        device = self.doc.system.devices.get(key)
        if device is not None and not device.present:
            self.doc.remove_device(key)

    def _on_joined(self, key: Any) -> None:
        self.doc.set_present(key, True)
        if key in self.doc.system.devices:
            self._say_joined([key])
        else:  # not read yet: named once the snapshot that reads it is merged
            self._joined_unread.add(key)
        self.refresh()

    def _say_joined(self, keys: list[Any]) -> None:
        """"EMG flexor site joined the bus": the part by its one name (its numbers are in
        the Bus events' detail)."""
        from pdcp_studio.app.words.part_names import part_name

        for key in keys:
            self.statusMessage.emit(self.tr("{part} joined the bus").format(
                part=part_name(self.doc.system, key)))

    def _on_left(self, key: Any) -> None:
        device = self.doc.system.devices.get(key)
        was_here = device is not None and device.present
        self.doc.set_present(key, False)
        if was_here and self._swap_in([key]):
            self._remember_soon()
        from pdcp_studio.app.words.part_names import part_name

        self._joined_unread.discard(key)
        self.statusMessage.emit(
            self.tr("{part} left the bus").format(part=part_name(self.doc.system, key)))
        self.refresh()

    def _on_plan_applied(self, plan: Any) -> None:
        from pdcp_studio.app.words.plan_words import mode_words

        mode = getattr(plan, "mode", None) or (plan.get("mode") if isinstance(plan, dict)
                                                else "plan")
        why = mode_words(str(mode))
        added = len(getattr(plan, "added", ()))
        removed = len(getattr(plan, "removed", ()))
        self.statusMessage.emit(self.tr(
            "The prosthesis changed its links ({why}): {added} made, {removed} removed — "
            "see Bus events").format(why=why, added=added, removed=removed))
        self.refresh()

    def _on_values(self, values: list[Any]) -> None:
        if self.on_data is None:
            return
        for ref in {v.ref for v in values}:
            self.on_data(ref)

    def scan(self) -> Worker | None:
        return self.bridge.scan() if self.bridge is not None else None

    def wait_idle(self, timeout: float = 5.0) -> bool:
        """For shutdown and tests: wait until the bridge's calls finished."""
        if self.bridge is None:
            return True
        return bool(self.bridge._pool.waitForDone(int(timeout * 1000)))

