"""The bus scene: device cards and links that follow a :class:`Document`.

The scene subscribes to the document and updates only what changed (links added or
removed, one card's rows, a position). User gestures become undo commands — a link
dragged from port to port, a card drag (one command per drag), Delete on links — and
the document's signals bring the items up to date; items never change the model.

The scene composes parts with one job each: ``link_drag`` (drawing a link: the scene takes
the mouse from a port, as Qt's diagramscene does; ``link_drop`` decides what a drop means),
``card_moves`` (a card drag, one undo step), ``live_flow`` (data flowing on a live bus),
``card_pictures`` (card pictures drawn in batches), ``ghost_links`` (a previewed plan and
the pending removals), ``state_marks`` (the findings on every item) and ``scene_words``
(names, tooltips, advice). The scene itself builds the items and follows the document.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from contextlib import contextmanager

from PySide6.QtCore import QObject, QPointF, QRectF, Qt, QTimer, Signal
from PySide6.QtGui import QTransform
from PySide6.QtWidgets import QGraphicsScene, QGraphicsSceneMouseEvent

from pdcp_studio.app.documents import commands
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph import layout, state_marks, style
from pdcp_studio.app.graph.analysis import SystemStates, compute_states
from pdcp_studio.app.graph.card_moves import CardMoves
from pdcp_studio.app.graph.card_pictures import PictureQueue
from pdcp_studio.app.graph.ghost_links import GhostLinks
from pdcp_studio.app.graph.items import DeviceItem, PortItem, forget_catalogue
from pdcp_studio.app.graph.link_drag import LinkDrag
from pdcp_studio.app.graph.links import LinkItem
from pdcp_studio.app.graph.live_flow import LiveFlow
from pdcp_studio.app.graph.scene_words import SceneWords
from pdcp_studio.app.words.plural import count
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Channel, Device, Link

#: A live bus with more devices than this is built over several turns of the event loop,
#: at most BUILD_BUDGET_S of card making per turn.
BUILD_AT_ONCE = 40
BUILD_BUDGET_S = 0.008


class BusScene(QGraphicsScene):
    """Cards, ports and links for one document."""

    statusMessage = Signal(str)
    #: Every item was made anew (a new system): views recount the cards.
    rebuilt = Signal()
    #: Some cards' pictures were drawn (what an overview shows changed).
    picturesDrawn = Signal()

    def __init__(self, doc: Document, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self.cards: dict[DeviceKey, DeviceItem] = {}
        self.link_items: dict[Link, LinkItem] = {}
        self.ghosts = GhostLinks(self)
        self._pending_cache: dict[DeviceKey, set[int]] | None = None
        self.states = SystemStates()
        self._syncing = False
        #: The zoom of the view showing the scene (cards choose their level of detail).
        self.zoom = 1.0
        #: The shape (width / height) of the view: a fresh layout takes it.
        self.layout_aspect = 1.0
        #: Device pixels per pixel of the screen the view is on (set by the view).
        self.pixel_ratio = 1.0
        self._vector = False
        self.words = SceneWords(doc, lambda: self.states)
        self.flow = LiveFlow(self, self.cards, self.link_items, lambda: self.doc.system,
                             lambda: self.zoom)
        self.pictures = PictureQueue(self, self.cards, self.picturesDrawn.emit)
        self.moves = CardMoves(doc, self.cards, lambda: [
            i for i in self.selectedItems() if isinstance(i, DeviceItem)])
        self.link_drag = LinkDrag(self, doc, self.statusMessage.emit, self.words.describe)
        self.setBackgroundBrush(style.SCENE_BACKGROUND)
        doc.systemReset.connect(self.rebuild)
        doc.linksChanged.connect(self._on_links_changed)
        doc.channelChanged.connect(lambda ref: self._on_device_changed(ref.device))
        doc.deviceChanged.connect(self._on_device_changed)
        doc.positionChanged.connect(self._on_position_changed)
        doc.selectionChanged.connect(self._on_doc_selection)
        doc.previewChanged.connect(self._on_preview)
        doc.busChanged.connect(self._on_bus_changed)
        self.selectionChanged.connect(self._on_qt_selection)
        self._states_timer = QTimer(self)
        self._states_timer.setSingleShot(True)
        self._states_timer.setInterval(0)
        self._states_timer.timeout.connect(self._refresh_states_in_slices)
        #: The states being shown a slice at a time (a live snapshot's), or None.
        self._state_slices: Iterator[None] | None = None
        self._slice_timer = QTimer(self)
        self._slice_timer.setSingleShot(True)
        self._slice_timer.setInterval(0)
        self._slice_timer.timeout.connect(self._state_slice)
        self._to_build: list[DeviceKey] = []
        self._chunked = False
        self._steps: Iterator[None] | None = None
        self._build_timer = QTimer(self)
        self._build_timer.setSingleShot(True)
        self._build_timer.setInterval(0)
        self._build_timer.timeout.connect(self._build_step)
        self.rebuild()

    # -- building -------------------------------------------------------------------
    def rebuild(self) -> None:
        """Recreate every item (a new system); remembered positions are kept.

        A large live bus (more than ``BUILD_AT_ONCE`` devices) is built over several
        turns of the event loop, ``BUILD_BUDGET_S`` at a time, so the GUI thread never
        stops long while the bus threads compete for the GIL; ``building`` is True
        meanwhile, :meth:`graph_rect` already spans every card, :meth:`finish_building`
        completes it at once and ``rebuilt`` follows when it is complete.
        """
        self._syncing = True
        try:
            self._build_timer.stop()
            self._steps = None
            self._stop_state_slices()
            self.link_drag.cancel()
            self.clear()
            self.cards.clear()
            self.pictures.clear()
            self.words.forget()
            forget_catalogue()
            self.link_items.clear()
            self.ghosts.forget()
            self._pending_cache = None
            system = self.doc.system
            self.states = compute_states(system)
            placed = layout.place(system, self.doc.positions, self.layout_aspect)
            self.doc.positions.update(placed)
            self._to_build = list(system.devices)
        finally:
            self._syncing = False
        self._chunked = len(self._to_build) > BUILD_AT_ONCE and self.doc.session is not None
        self._steps = self._build_steps()
        if self._chunked:
            self._build_step()
        else:
            self.finish_building()

    @property
    def building(self) -> bool:
        """True while a large bus is still being built (see :meth:`rebuild`)."""
        return self._steps is not None

    def _build_step(self) -> None:
        """One turn's worth of building (``BUILD_BUDGET_S``)."""
        self._run_steps(BUILD_BUDGET_S)
        if self._steps is not None:
            self._build_timer.start()

    def finish_building(self) -> None:
        """Build what is still to build, at once."""
        self._build_timer.stop()
        self._run_steps(None)

    def _run_steps(self, budget_s: float | None) -> None:
        steps = self._steps
        if steps is None:
            return
        start = time.perf_counter()
        self._syncing = True
        try:
            for _step in steps:
                if budget_s is not None and time.perf_counter() - start > budget_s:
                    return
        finally:
            self._syncing = False
        if self._steps is steps:  # not restarted by a changed system
            self._steps = None
            self.rebuilt.emit()

    def _build_steps(self) -> Iterator[None]:
        """The cards, then the links, then their states, a step at a time — off the
        scene, so the view is not repainted at every step — and then into the scene at
        once."""
        system = self.doc.system
        while self._to_build:
            key = self._to_build.pop(0)
            device = system.devices.get(key)
            if device is None or key in self.cards:
                continue
            card = DeviceItem(self, device, self.states.roles.get(key, "sensor"))
            card.set_zoom(self.zoom, self._vector)
            card.setPos(*self.doc.positions.get(key, (0.0, 0.0)))
            self.cards[key] = card
            yield
        system = self.doc.system
        if self._chunked:  # the system may have changed while the cards were made
            if set(self.cards) != set(system.devices):
                self._steps = None
                self._syncing = False
                self.rebuild()
                return
            self.states = compute_states(system)
            for key, card in self.cards.items():
                if card.device is not system.devices[key]:
                    card.set_device(system.devices[key], self.states.roles[key])
        for link in system.links:
            self.link_items[link] = LinkItem(self, link)
            yield
        yield from self._state_steps()
        for card in self.cards.values():
            self.addItem(card)
        for item in self.link_items.values():
            self.addItem(item)
        self.ghosts.show_unwritten()
        self.ghosts.show_preview(self.doc.preview_plan)
        self._select_items(self.doc.selection)

    def graph_rect(self) -> QRectF:
        """Where the graph is, also while it is still being built (from the cards'
        places: every card has one before it is made)."""
        if not self.building:
            return self.itemsBoundingRect()
        return QRectF(*layout.planned_bounds(self.doc.system, self.doc.positions))

    def set_view_zoom(self, zoom: float) -> None:
        """The main view's zoom changed: cards pick their level of detail for it (their
        pictures are redrawn in batches, see :meth:`render_pending`)."""
        if abs(zoom - self.zoom) < 1e-6:
            return
        self.zoom = zoom
        for card in self.cards.values():
            card.set_zoom(zoom, self._vector)

    def set_pixel_ratio(self, ratio: float) -> None:
        """The screen's device pixels per pixel (cards draw their pictures that fine)."""
        if ratio > 0 and ratio != self.pixel_ratio:
            self.pixel_ratio = ratio
            for card in self.cards.values():
                card.refresh()

    def render_pending(self, budget_s: float | None = None) -> int:
        """Draw waiting card pictures; returns how many still wait (see
        :meth:`PictureQueue.render`)."""
        return self.pictures.render(budget_s)

    def look_at(self, sight: QRectF) -> None:
        """The part of the scene the view shows (with a margin): waiting pictures there
        are drawn soon."""
        self.pictures.look_at(sight)

    @contextmanager
    def full_detail(self) -> Iterator[None]:
        """Every card painting its rows as vectors for a while (an export: read at its
        own scale, and a vector file wants vectors)."""
        zoom = self.zoom
        self._vector = True
        self.zoom = -1.0
        self.set_view_zoom(1.0)
        try:
            yield
        finally:
            self._vector = False
            self.zoom = -1.0
            self.set_view_zoom(zoom)

    def relayout(self) -> dict[DeviceKey, tuple[float, float]]:
        """A fresh layered layout (View ▸ Arrange); returns the new positions."""
        return layout.layered_layout(self.doc.system, self.layout_aspect)

    def port(self, ref: ChannelRef) -> PortItem | None:
        card = self.cards.get(ref.device)
        return card.ports.get(ref.index) if card else None

    def device_label(self, device: Device) -> str:
        """The device's own name, else its product from the device catalogue."""
        return self.words.device_label(device)

    # -- document → items -----------------------------------------------------------
    def _on_links_changed(self) -> None:
        if self.building:
            return  # finish_building shows the system as it is then
        current = set(self.doc.system.links)
        for link in [lk for lk in self.link_items if lk not in current]:
            item = self.link_items.pop(link)
            item.detach()
            self.removeItem(item)
        for link in current - self.link_items.keys():
            self.link_items[link] = item = LinkItem(self, link)
            self.addItem(item)
        self.states = compute_states(self.doc.system)
        self._pending_cache = None
        self.ghosts.show_unwritten()
        self._apply_states()

    def _on_bus_changed(self) -> None:
        if self.building:
            return  # finish_building shows the system as it is then
        self._pending_cache = None
        self.ghosts.show_unwritten()
        if self._states_timer.isActive():
            return  # a changed device's states follow at once: shown once, not twice
        self._start_state_slices()

    def _on_device_changed(self, key: DeviceKey) -> None:
        if self.building:
            return  # finish_building shows the system as it is then
        self._pending_cache = None
        device = self.doc.system.device(key)
        card = self.cards.get(key)
        if device is None or card is None:
            self.rebuild()
            return
        card.set_device(device, card.role)
        for other in self.words.renamed_others(device):  # two parts now read alike, or no longer
            if other in self.cards:
                self.cards[other].refresh()
        # A live snapshot changes many devices at once: recompute the states (O(system))
        # once, when the event loop is free, not once per device.
        self._states_timer.start()

    def refresh_states(self) -> None:
        """Recompute roles and problems for the whole system and show them on every item."""
        if self.building:
            return  # finish_building shows the system as it is then
        self._states_timer.stop()
        self.states = compute_states(self.doc.system)
        self._apply_states()

    def _refresh_states_in_slices(self) -> None:
        """:meth:`refresh_states` for a live snapshot: the items over several turns."""
        if self.building:
            return
        self.states = compute_states(self.doc.system)
        self._start_state_slices()

    def _on_position_changed(self, key: DeviceKey) -> None:
        card = self.cards.get(key)
        pos = self.doc.positions.get(key)
        if card is not None and pos is not None and (card.pos().x(), card.pos().y()) != pos:
            card.setPos(*pos)

    def _apply_states(self) -> None:
        """Show the states on every item now (a pass in slices is superseded)."""
        self._stop_state_slices()
        for _step in self._state_steps():
            pass

    def _start_state_slices(self) -> None:
        """Show the states on every item, ``BUILD_BUDGET_S`` of them per turn of the event
        loop: after a live snapshot a large bus's items (93 devices: ~25 ms, more while the
        bus threads hold the GIL) must not stop the GUI thread in one go."""
        self._state_slices = self._state_steps()
        self._state_slice()

    def _state_slice(self) -> None:
        steps = self._state_slices
        if steps is None:
            return
        start = time.perf_counter()
        for _step in steps:
            if time.perf_counter() - start > BUILD_BUDGET_S:
                self._slice_timer.start()
                return
        if self._state_slices is steps:
            self._state_slices = None

    def _stop_state_slices(self) -> None:
        self._state_slices = None
        self._slice_timer.stop()

    def _state_steps(self) -> Iterator[None]:
        """Show the states on every item, one item per step (a large bus being built
        spreads them over turns of the event loop)."""
        if self._pending_cache is None:  # not on every data tick: only after a change
            self._pending_cache = state_marks.pending_rows(self.doc.bus_system, self.doc.system)
        return state_marks.mark_steps(
            self.cards, self.link_items, self.doc.system, self.doc.bus_system, self.states,
            self.flow.outputs(), self._pending_cache, bool(self.preview_items), self.words)

    def _on_doc_selection(self, obj: object) -> None:
        if self._syncing:
            return
        self._syncing = True
        try:
            self._select_items(obj)
        finally:
            self._syncing = False

    def _select_items(self, obj: object) -> None:
        self.clearSelection()
        for card in self.cards.values():
            if card.selected_ref is not None:
                card.selected_ref = None
                card.refresh()
        item = self.item_for(obj)
        if item is None:
            return
        item.setSelected(True)
        if isinstance(obj, ChannelRef) and isinstance(item, DeviceItem):
            item.selected_ref = obj
            item.refresh()

    def item_for(self, obj: object) -> DeviceItem | LinkItem | None:
        """The graphics item showing a device, channel or link (for centring the view)."""
        if isinstance(obj, Link):
            return self.link_items.get(obj)
        if isinstance(obj, ChannelRef):
            return self.cards.get(obj.device)
        if isinstance(obj, DeviceKey):
            return self.cards.get(obj)
        return None

    # -- preview --------------------------------------------------------------------
    def _on_preview(self, plan: object) -> None:
        if self.building:
            return  # finish_building shows the preview
        if plan is None and not self.preview_items:
            return  # no preview before or after (a new system resets it): nothing to show
        self.ghosts.show_preview(plan)
        self._apply_states()

    @property
    def preview_items(self) -> list[LinkItem]:
        """A previewed plan's links (dashed green: added, red: removed)."""
        return self.ghosts.preview

    @property
    def unwritten_items(self) -> list[LinkItem]:
        """Ghosts of links on the prosthesis that the project removes (pending removals)."""
        return self.ghosts.unwritten

    # -- live data ------------------------------------------------------------------
    @property
    def flow_phase(self) -> float:
        """Where the dashes of a flowing link are (links draw them there)."""
        return self.flow.phase

    # -- gestures: selection and moves ----------------------------------------------
    def _on_qt_selection(self) -> None:
        if self._syncing:
            return
        items = self.selectedItems()
        if not items:
            self.doc.select(None)
            return
        if len(items) > 1:
            return  # a multi-selection (rubber band): the document keeps its primary
        item = items[0]
        if isinstance(item, LinkItem):
            self.doc.select(item.link)
        elif isinstance(item, DeviceItem):
            sel = self.doc.selection
            if not (isinstance(sel, ChannelRef) and sel.device == item.key):
                self.doc.select(item.key)

    def delete_selected(self) -> int:
        """Remove the selected links (one undo step); returns how many were removed."""
        links = [i.link for i in self.selectedItems() if isinstance(i, LinkItem)]
        if isinstance(self.doc.selection, Link) and self.doc.selection not in links:
            links.append(self.doc.selection)
        n = commands.push_remove_links(self.doc, links)
        if n:
            self.statusMessage.emit(count("BusScene", "Removed %n link(s)", n))
        return n

    # -- gestures: drawing a link (the scene's, as in Qt's diagramscene) -------------
    def mousePressEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        """A left press on a port starts a link drag; anything else is Qt's."""
        if not self._press_on_port(event):
            super().mousePressEvent(event)

    def mouseDoubleClickEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        if not self._press_on_port(event):
            super().mouseDoubleClickEvent(event)

    def _press_on_port(self, event: QGraphicsSceneMouseEvent) -> bool:
        """Start a link drag if a left press lands on a port: the topmost item there
        that takes the left button (a card's row beside it moves the card)."""
        if event.button() != Qt.MouseButton.LeftButton:
            return False
        for item in self.items(event.scenePos(), Qt.ItemSelectionMode.IntersectsItemShape,
                               Qt.SortOrder.DescendingOrder, QTransform()):
            if item.acceptedMouseButtons() & Qt.MouseButton.LeftButton:
                if not isinstance(item, PortItem):
                    return False
                self.begin_link_drag(item, event.scenePos())
                event.accept()
                return True
        return False

    def mouseMoveEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        if self.link_drag.active:
            self.update_link_drag(event.scenePos())
            event.accept()
            return
        super().mouseMoveEvent(event)

    def mouseReleaseEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        if self.link_drag.active:
            self.end_link_drag(event.scenePos())
            event.accept()
            return
        super().mouseReleaseEvent(event)

    def begin_link_drag(self, port: PortItem, pos: QPointF) -> None:
        self.link_drag.begin(port, pos)

    def update_link_drag(self, pos: QPointF) -> None:
        self.link_drag.move(pos)

    def end_link_drag(self, pos: QPointF) -> Link | None:
        """Drop the link drag at ``pos``: the link made (one undo step), or None."""
        return self.link_drag.end(pos)

    def port_at(self, pos: QPointF) -> PortItem | None:
        return self.link_drag.port_at(pos)

    @property
    def last_link_result(self) -> tuple[Link | None, str]:
        """The outcome of the last link drag: (link or None, refusal reason or "")."""
        return self.link_drag.last_result

    # -- words ------------------------------------------------------------------------
    def tooltip_for(self, card: DeviceItem, row: Channel | None) -> str:
        """A card's (``row`` None) or a channel row's tooltip: the prosthetist's words
        first, the engineer's codes after them in grey."""
        return self.words.tooltip_for(card.device, row)
