"""The bus scene: device cards and links that follow a :class:`Document`.

The scene subscribes to the document and updates only what changed (links added or
removed, one card's rows, a position). User gestures become undo commands — a link
dragged from port to port, a card drag (one command per drag), Delete on links — and
the document's signals bring the items up to date; items never change the model.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from PySide6.QtCore import QPointF, QRectF, Qt, QTimer, Signal
from PySide6.QtWidgets import QGraphicsScene

from pdcp_studio.app.documents import commands
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph import layout, style
from pdcp_studio.app.graph.analysis import SystemStates, compute_states, link_refusal
from pdcp_studio.app.graph.items import DETAIL_ZOOM, DeviceItem, PortItem, forget_catalogue
from pdcp_studio.app.graph.links import DragLinkItem, LinkItem
from pdcp_studio.model import profile as prof
from pdcp_studio.model.catalog import default_catalog
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Channel, Device, Link

#: A link counts as "live" this long after its output's last data frame.
LIVE_HOLD_S = 1.5
#: Data that starts or stops flowing is drawn at most this often (milliseconds).
LIVE_BATCH_MS = 100
FLOW_TICK_MS = 80
#: A live bus with more devices than this is built over several turns of the event loop,
#: at most BUILD_BUDGET_S of card making per turn.
BUILD_AT_ONCE = 40
BUILD_BUDGET_S = 0.008
#: Flowing data is animated on at most this many links at once.
FLOW_ANIMATE_MAX = 24
#: Card pictures are drawn for at most this long per turn of the event loop (about
#: 0.3 ms each; the GUI thread stays free for input and painting in between).
RENDER_BUDGET_S = 0.006


class BusScene(QGraphicsScene):
    """Cards, ports and links for one document."""

    statusMessage = Signal(str)
    #: Every item was made anew (a new system): views recount the cards.
    rebuilt = Signal()
    #: Some cards' pictures were drawn (what an overview shows changed).
    picturesDrawn = Signal()

    def __init__(self, doc: Document, parent: object | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self.cards: dict[DeviceKey, DeviceItem] = {}
        self.link_items: dict[Link, LinkItem] = {}
        self.preview_items: list[LinkItem] = []
        #: Ghosts of links on the prosthesis that the project removes (pending removals).
        self.unwritten_items: list[LinkItem] = []
        self._pending_cache: dict[DeviceKey, set[int]] | None = None
        self.states = SystemStates()
        self.flow_phase = 0.0
        self._live: dict[ChannelRef, float] = {}
        self._flow_timer = QTimer(self)
        self._flow_timer.setInterval(FLOW_TICK_MS)
        self._flow_timer.timeout.connect(self._flow_tick)
        #: Outputs whose data started or stopped since the last update, drawn in one batch
        #: (a bus with 161 outputs sending must not redraw every item per frame).
        self._live_changed: set[ChannelRef] = set()
        self._live_timer = QTimer(self)
        self._live_timer.setSingleShot(True)
        self._live_timer.setInterval(LIVE_BATCH_MS)
        self._live_timer.timeout.connect(self._apply_live)
        self._drag: DragLinkItem | None = None
        self._drag_target: PortItem | None = None
        self._press: dict[DeviceKey, QPointF] = {}
        self._syncing = False
        #: The outcome of the last link drag: (link or None, refusal reason or "").
        self.last_link_result: tuple[Link | None, str] = (None, "")
        #: The zoom of the view showing the scene (cards choose their level of detail).
        self.zoom = 1.0
        #: The shape (width / height) of the view: a fresh layout takes it.
        self.layout_aspect = 1.0
        #: Device pixels per pixel of the screen the view is on (set by the view).
        self.pixel_ratio = 1.0
        self._vector = False
        self._catalog: Any = None
        self._to_render: dict[DeviceKey, DeviceItem] = {}
        #: Where the view looks, with a margin (scene coordinates; empty: everywhere).
        self._sight = QRectF(-1e9, -1e9, 2e9, 2e9)
        self._render_timer = QTimer(self)
        self._render_timer.setSingleShot(True)
        self._render_timer.setInterval(0)
        self._render_timer.timeout.connect(self._render_batch)
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
            self._cancel_drag()
            self.clear()
            self.cards.clear()
            self._to_render.clear()
            self._catalog = None
            forget_catalogue()
            self.link_items.clear()
            self.preview_items.clear()
            self.unwritten_items.clear()
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
        self._show_unwritten()
        self._show_preview(self.doc.preview_plan)
        self._select_items(self.doc.selection)

    def graph_rect(self) -> QRectF:
        """Where the graph is, also while it is still being built (from the cards'
        places: every card has one before it is made)."""
        if not self.building:
            return self.itemsBoundingRect()
        rect = QRectF()
        r = style.PORT_RADIUS + 2
        for key, device in self.doc.system.devices.items():
            x, y = self.doc.positions.get(key, (0.0, 0.0))
            rect = rect.united(QRectF(x - r, y - 2, style.CARD_WIDTH + 2 * r,
                                      layout.card_height(device) + 6))
        return rect

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

    def schedule_render(self, card: DeviceItem) -> None:
        """Redraw a card's picture soon (batched: a bus's worth of cards is not drawn in
        one go on the GUI thread)."""
        self._to_render[card.key] = card
        if not self._render_timer.isActive():
            self._render_timer.start()

    def render_pending(self, budget_s: float | None = None) -> int:
        """Draw waiting card pictures; returns how many still wait. With None, all of
        them now. With a time budget (a batch on the event loop), for at most that long
        (at least one card), only the cards near the view's sight and those with no
        picture yet: a card out of sight keeps its old picture until it comes near
        (:meth:`look_at`), so a zoom on a large bus redraws what is seen, not all."""
        waiting = self._to_render
        keys = list(waiting)
        if budget_s is not None:
            sight = self._sight
            near = [k for k in keys if sight.intersects(waiting[k].sceneBoundingRect())]
            keys = near + [k for k in keys if k not in set(near)
                           and not waiting[k].has_picture()]
        start = time.perf_counter()
        for key in keys:
            card = waiting.pop(key)
            if self.cards.get(key) is card:
                card.render_picture()
            if budget_s is not None and time.perf_counter() - start > budget_s:
                break
        more = [k for k in keys if k in waiting]
        if more and not self._render_timer.isActive():
            self._render_timer.start()
        if keys:
            self.picturesDrawn.emit()
        return len(waiting)

    def look_at(self, sight: QRectF) -> None:
        """The part of the scene the view shows (with a margin): waiting pictures there
        are drawn soon."""
        self._sight = QRectF(sight)
        if self._to_render and not self._render_timer.isActive():
            self._render_timer.start()

    def _render_batch(self) -> None:
        self.render_pending(RENDER_BUDGET_S)

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

    def _add_link_item(self, link: Link) -> LinkItem:
        item = LinkItem(self, link)
        self.addItem(item)
        self.link_items[link] = item
        return item

    def port(self, ref: ChannelRef) -> PortItem | None:
        card = self.cards.get(ref.device)
        return card.ports.get(ref.index) if card else None

    def device_label(self, device: Device) -> str:
        """The device's own name, else its product from the device catalogue (looked up
        once per rebuild: finding the catalogue reads the user's folder)."""
        if self._catalog is None:
            from pdcp_studio.app.words.part_names import part_names

            self._catalog = part_names(self.doc.system)
        name = self._catalog.get(device.key)
        if name is None:  # a device just added: name the system again
            from pdcp_studio.app.words.part_names import part_name

            name = part_name(self.doc.system, device.key)
        return name

    def profile_name(self, profile: int) -> str:
        return self.doc.profile_name(profile)

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
            self._add_link_item(link)
        self.states = compute_states(self.doc.system)
        self._pending_cache = None
        self._show_unwritten()
        self._apply_states()

    def _on_bus_changed(self) -> None:
        if self.building:
            return  # finish_building shows the system as it is then
        self._pending_cache = None
        self._show_unwritten()
        if self._states_timer.isActive():
            return  # a changed device's states follow at once: shown once, not twice
        self._start_state_slices()

    def _show_unwritten(self) -> None:
        """Ghost links: on the prosthesis, removed in the project (not yet written)."""
        for item in self.unwritten_items:
            item.detach()
            self.removeItem(item)
        self.unwritten_items.clear()
        bus = self.doc.bus_system
        if bus is None:
            return
        for link in sorted(set(bus.links) - set(self.doc.system.links)):
            if self.port(link.output) is None or self.port(link.input) is None:
                continue
            item = LinkItem(self, link, "unwritten")
            item.setToolTip(
                self.tr("Pending removal (still on the prosthesis): {link}").format(link=link)
            )
            self.addItem(item)
            self.unwritten_items.append(item)

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
        before, self._catalog = self._catalog, None
        if before is not None and before.get(key) != self.device_label(device):
            for other, name in before.items():  # two parts now read alike, or no longer
                if other != key and other in self.cards and self._catalog.get(other) != name:
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

    def _pending_rows(self) -> dict[DeviceKey, set[int]]:
        """Channels (0: the device) with a parameter staged but not yet written."""
        from pdcp_studio.app.documents.pending import PARAMETER, pending_changes

        marks: dict[DeviceKey, set[int]] = {}
        if self.doc.bus_system is None:
            return marks
        for c in pending_changes(self.doc.bus_system, self.doc.system):
            if c.kind == PARAMETER and c.key is not None:
                marks.setdefault(c.key, set()).add(c.index)
        return marks

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
        system, st = self.doc.system, self.states
        live = set(self._live)
        if self._pending_cache is None:  # not on every data tick: only after a change
            self._pending_cache = self._pending_rows()
        pending_rows = self._pending_cache
        for key, card in list(self.cards.items()):
            card.role = st.roles.get(key, card.role)
            card.problems = st.device_problems(key)
            card.pending_rows = pending_rows.get(key, set())
            for port in card.ports.values():
                ref = port.ref
                if port.is_output:
                    port.connected = bool(system.inputs_fed_by(ref))
                    port.live = ref in live
                else:
                    source = system.source_of(ref)
                    port.connected = source is not None
                    port.live = source in live
                port.unmet = ref in st.unmet_required
                port.setToolTip(self.port_advice(ref))
            card.refresh()
            yield
        dim = bool(self.preview_items)
        bus = self.doc.bus_system
        on_bus = set(bus.links) if bus is not None else None
        for link, item in list(self.link_items.items()):
            item.pending = on_bus is not None and link not in on_bus
            item.conflict = link in st.conflict_links
            item.missing = link in st.missing_links
            item.setToolTip(self.link_advice(link))
            item.live = link.output in live
            item.setOpacity(0.35 if dim else 1.0)
            item.refresh()
            yield

    def _apply_live(self) -> None:
        """Redraw only the ports and links of outputs whose data started or stopped."""
        self._live_timer.stop()
        changed, self._live_changed = self._live_changed, set()
        if not changed:
            return
        system, live = self.doc.system, self._live
        touched: set[DeviceItem] = set()
        for ref in changed:
            card = self.cards.get(ref.device)
            port = card.ports.get(ref.index) if card is not None else None
            if port is not None and port.is_output:
                port.live = ref in live
                touched.add(card)
            for target in system.inputs_fed_by(ref):
                in_card = self.cards.get(target.device)
                in_port = in_card.ports.get(target.index) if in_card is not None else None
                if in_port is not None:
                    in_port.live = system.source_of(target) in live
                    touched.add(in_card)
        for card in touched:
            card.refresh()
        for link, item in self.link_items.items():
            if link.output in changed:
                item.live = link.output in live
                item.refresh()

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
        self._show_preview(plan)
        self._apply_states()

    def _show_preview(self, plan: object) -> None:
        from pdcp_studio.app.words import plan_words

        for item in self.preview_items:
            item.detach()
            self.removeItem(item)
        self.preview_items.clear()
        if plan is None:
            return
        for action in getattr(plan, "actions", ()):
            link = action.link
            if self.port(link.output) is None or self.port(link.input) is None:
                continue
            item = LinkItem(self, link, "add" if action.op == "add" else "remove")
            item.setToolTip(plan_words.step_words(self.doc.system, plan, action,
                                                  self.profile_name))
            self.addItem(item)
            self.preview_items.append(item)

    # -- live data ------------------------------------------------------------------
    def note_data(self, output: ChannelRef) -> None:
        """An output sent data just now (from the live session): animate its links."""
        fresh = output not in self._live
        self._live[output] = time.monotonic()
        if fresh:  # only the ports and links of outputs that start or stop: not every item
            self._live_changed.add(output)
            if not self._live_timer.isActive():
                self._live_timer.start()
        if not self._flow_timer.isActive():
            self._flow_timer.start()

    def live_outputs(self) -> set[ChannelRef]:
        return set(self._live)

    def _flow_tick(self) -> None:
        now = time.monotonic()
        stale = [r for r, t in self._live.items() if now - t > LIVE_HOLD_S]
        for ref in stale:
            del self._live[ref]
        self._live_changed.update(stale)
        if self._live_changed:
            self._apply_live()
        live = [item for link, item in self.link_items.items() if link.output in self._live]
        if self.flow_animated(len(live)):
            self.flow_phase = (self.flow_phase + 1.5) % 70.0
            for item in live:
                item.refresh()

    def flow_animated(self, live_links: int) -> bool:
        """Whether flowing data moves along its links: only when the links are drawn
        large enough to see it and few enough to redraw 12 times a second (on a large
        bus fitted to the window every link redrawn per tick meant the whole view).
        Otherwise a link with data is shown still, in the colour of data flowing."""
        return self.zoom >= DETAIL_ZOOM and live_links <= FLOW_ANIMATE_MAX
        if not self._live:
            self._flow_timer.stop()

    # -- gestures: selection and moves ----------------------------------------------
    def card_clicked(self, card: DeviceItem, ref: ChannelRef | None,
                     modifiers: Qt.KeyboardModifier) -> None:
        self._press = {c.key: c.pos() for c in self.selected_cards()}
        self._press.setdefault(card.key, card.pos())
        if not modifiers & Qt.KeyboardModifier.ControlModifier:
            self.doc.select(ref if ref is not None else card.key)

    def selected_cards(self) -> list[DeviceItem]:
        return [i for i in self.selectedItems() if isinstance(i, DeviceItem)]

    def drag_finished(self) -> None:
        """A mouse release on a card: the whole drag becomes one undo step."""
        moves = {}
        for key, old in self._press.items():
            card = self.cards.get(key)
            if card is not None and card.pos() != old:
                moves[key] = ((old.x(), old.y()), (card.pos().x(), card.pos().y()))
        self._press = {}
        if moves:
            self.doc.undo_stack.push(commands.MoveDevicesCommand(self.doc, moves))

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
            self.statusMessage.emit(self.tr("Removed {n} link{v1}").format(n=n, v1='s' * (n != 1)))
        return n

    # -- gestures: drawing a link ---------------------------------------------------
    def begin_link_drag(self, port: PortItem, pos: QPointF) -> None:
        self._cancel_drag()
        self._drag = DragLinkItem(port)
        self.addItem(self._drag)
        self._drag.follow(pos)
        what = "an input" if port.is_output else "an output"
        self.statusMessage.emit(
            self.tr("Drag from {ref} to {what} to link them").format(ref=port.ref, what=what)
        )

    def port_at(self, pos: QPointF) -> PortItem | None:
        r = style.PORT_RADIUS + 4
        for item in self.items(QRectF(pos.x() - r, pos.y() - r, 2 * r, 2 * r)):
            if isinstance(item, PortItem):
                return item
        return None

    def _ends(self, start: PortItem, target: PortItem) -> tuple[ChannelRef, ChannelRef]:
        """Output first: a drag may go either way between an output and an input."""
        if not start.is_output and target.is_output:
            return target.ref, start.ref
        return start.ref, target.ref

    def update_link_drag(self, pos: QPointF) -> None:
        if self._drag is None:
            return
        target = self.port_at(pos)
        if target is self._drag.start:
            target = None
        if self._drag_target is not None and self._drag_target is not target:
            self._drag_target.set_hover(False)
        self._drag_target = target
        if target is None:
            self._drag.set_ok(True)
            self._drag.follow(pos)
            return
        a, b = self._ends(self._drag.start, target)
        reason = link_refusal(self.doc.system, a, b)
        self._drag.set_ok(reason is None)
        target.set_hover(reason is None)
        self._drag.follow(target.scenePos())
        message = f"Cannot link: {reason}" if reason else f"Release to link {a} → {b}"
        self.statusMessage.emit(message)

    def end_link_drag(self, pos: QPointF) -> Link | None:
        if self._drag is None:
            return None
        start = self._drag.start
        self._cancel_drag()
        target = self.port_at(pos)
        if target is None or target is start:
            self.last_link_result = (None, "no target port")
            self.statusMessage.emit(self.tr("Link cancelled: release over a port to link"))
            return None
        a, b = self._ends(start, target)
        reason = link_refusal(self.doc.system, a, b)
        if reason:
            self.last_link_result = (None, reason)
            self.statusMessage.emit(
                self.tr("Cannot link {a} → {b}: {reason}").format(a=a, b=b, reason=reason)
            )
            return None
        link = Link(a, b)
        commands.push_add_link(self.doc, link)
        self.last_link_result = (link, "")
        self.statusMessage.emit(
            self.tr("Linked {v0} → {v1}").format(v0=self._describe(a), v1=self._describe(b))
        )
        return link

    def _cancel_drag(self) -> None:
        if self._drag_target is not None:
            self._drag_target.set_hover(False)
            self._drag_target = None
        if self._drag is not None:
            if self._drag.scene() is self:
                self.removeItem(self._drag)
            self._drag = None

    # -- text -------------------------------------------------------------------------
    def _describe(self, ref: ChannelRef) -> str:
        """``Multi-grip hand, channel 1 (Power grip)``: a channel in words."""
        from pdcp_studio.app.words.plan_words import channel_words

        ch = self.doc.system.channel(ref)
        name = self.profile_name(ch.profile) if ch else ""
        return channel_words(self.doc.system, ref, "" if name.startswith("0x") else name)

    def tooltip_for(self, card: DeviceItem, row: Channel | None) -> str:
        """A card's (``row`` None) or a channel row's tooltip: the prosthetist's words
        first, the engineer's codes after them in grey."""
        from html import escape

        from pdcp_studio.app.words.part_names import numbers

        def grey(text: str) -> str:
            return f"<span style='color:#6b7280'>{escape(text)}</span>"

        d = card.device
        if row is None:
            lines = [f"<b>{escape(self.device_label(d))}</b>"]
            entry = default_catalog().lookup(d.vid, d.pid)
            if entry is not None:
                lines.append(escape(" · ".join(x for x in (entry.product, entry.vendor)
                                               if x)))
            if not d.present:
                lines.append(f"<i>{escape(self.tr('Missing from the bus'))}</i>")
            lines += [f"<span style='color:#b45309'>⚠ {p}</span>"
                      for p in self.problem_advice(d.key)]
            detail = numbers(d.key)
            if d.node_id is not None:
                detail += " · " + self.tr("node ID {0}").format(d.node_id)
            lines.append(grey(detail))
            return "<br>".join(lines)
        ref = d.ref(row.index)
        what = self.doc.tree.name_of(row.profile)
        head = (self.tr("Input {n}") if row.is_input else self.tr("Output {n}")).format(
            n=row.index)
        lines = [f"<b>{escape(head)}</b> — {escape(what)}"]
        if row.descriptor:
            lines.append(f"“{escape(row.descriptor)}”")
        if row.is_input:
            src = self.doc.system.source_of(ref)
            lines.append(escape(self.tr("Fed by {0}").format(self._describe(src)) if src
                                else self.tr("Nothing feeds it")))
        else:
            fed = self.doc.system.inputs_fed_by(ref)
            lines.append(escape(self.tr("Feeds {0}").format(
                "; ".join(self._describe(r) for r in fed)) if fed
                else self.tr("Feeds nothing")))
        detail = self.tr("profile {profile} · signal type {type}: {description}").format(
            profile=prof.fmt(row.profile), type=prof.fmt(row.type),
            description=row.ctype.describe())
        if row.is_input and row.terminal:
            detail += " · " + self.tr("drives the part with profile {0}").format(
                prof.fmt(row.terminal_profile))
        lines.append(grey(detail))
        advice = self.port_advice(ref)
        if advice:
            lines.append(f"<span style='color:#b91c1c'>⚠ {advice}</span>")
        return "<br>".join(lines)

    # -- findings in plain words (the same ones the Checks list reports) -----------
    def port_advice(self, ref: ChannelRef) -> str:
        """What is wrong with one input and what to do (empty: nothing)."""
        st = self.states
        if ref in st.unmet_required:
            return self.tr("Input {n} must be connected: a channel of this device that is "
                           "in use needs it. Connect a source to it, or let Autoconfigure "
                           "do it.").format(n=ref.index)
        if ref in st.unconnected_terminals:
            return self.tr("Input {n} drives a part of the prosthesis but nothing feeds it, "
                           "so that part will not move. Connect a matching output, or let "
                           "Autoconfigure do it.").format(n=ref.index)
        return ""

    def problem_advice(self, key: DeviceKey) -> list[str]:
        """Every finding behind a card's warning badge, with what to do."""
        st = self.states
        refs = sorted(r for r in st.unmet_required | st.unconnected_terminals
                      if r.device == key)
        out = [self.port_advice(r) for r in refs]
        if any(key in (lk.output.device, lk.input.device) for lk in st.conflict_links):
            out.append(self.tr("One output feeds several inputs that each need it for "
                               "themselves. Keep one of these links and remove the others."))
        return out

    def link_advice(self, link: Link) -> str:
        """What a marked link means and what to do (empty: nothing marked)."""
        st = self.states
        if link in st.conflict_links:
            return self.tr("Conflict: this output also feeds another input that needs it "
                           "for itself. Keep one of these links and remove the others.")
        if link in st.missing_links:
            return self.tr("This link carries no data: a device at one of its ends is not "
                           "on the bus. Plug the device in, or remove the link.")
        return ""
