"""Data flowing on a live bus, drawn on the graph: the ports and links of outputs that send.

The live session reports each output that sent a data frame (:meth:`LiveFlow.note_data`);
outputs whose data starts or stops are redrawn in one batch at most every
``LIVE_BATCH_MS`` (a bus with 161 outputs sending must not redraw every item per frame),
and the dashes of a few links at a readable zoom move along them.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from PySide6.QtCore import QObject, QTimer

from pdcp_studio.app.graph.items import DETAIL_ZOOM, DeviceItem
from pdcp_studio.app.graph.links import LinkItem
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System

#: A link counts as "live" this long after its output's last data frame.
LIVE_HOLD_S = 1.5
#: Data that starts or stops flowing is drawn at most this often (milliseconds).
LIVE_BATCH_MS = 100
FLOW_TICK_MS = 80
#: Flowing data is animated on at most this many links at once.
FLOW_ANIMATE_MAX = 24


class LiveFlow(QObject):
    """Which outputs send (and since when), and their ports and links drawn so.

    ``cards`` and ``link_items`` are the scene's own tables (read, never changed);
    ``system`` and ``zoom`` give the document's system and the view's zoom now.
    """

    def __init__(self, parent: QObject, cards: dict[DeviceKey, DeviceItem],
                 link_items: dict[Link, LinkItem], system: Callable[[], System],
                 zoom: Callable[[], float]) -> None:
        super().__init__(parent)
        self._cards = cards
        self._link_items = link_items
        self._system = system
        self._zoom = zoom
        #: Where the dashes of a flowing link are (scene units along the link).
        self.phase = 0.0
        self._live: dict[ChannelRef, float] = {}
        self._flow_timer = QTimer(self)
        self._flow_timer.setInterval(FLOW_TICK_MS)
        self._flow_timer.timeout.connect(self._flow_tick)
        #: Outputs whose data started or stopped since the last update, drawn in one batch.
        self._changed: set[ChannelRef] = set()
        self._batch_timer = QTimer(self)
        self._batch_timer.setSingleShot(True)
        self._batch_timer.setInterval(LIVE_BATCH_MS)
        self._batch_timer.timeout.connect(self.apply)

    def note_data(self, output: ChannelRef) -> None:
        """An output sent data just now: animate its links."""
        fresh = output not in self._live
        self._live[output] = time.monotonic()
        if fresh:  # only the ports and links of outputs that start or stop: not every item
            self._changed.add(output)
            if not self._batch_timer.isActive():
                self._batch_timer.start()
        if not self._flow_timer.isActive():
            self._flow_timer.start()

    def outputs(self) -> set[ChannelRef]:
        """The outputs sending now."""
        return set(self._live)

    def is_live(self, ref: ChannelRef | None) -> bool:
        return ref in self._live

    def _flow_tick(self) -> None:
        now = time.monotonic()
        stale = [r for r, t in self._live.items() if now - t > LIVE_HOLD_S]
        for ref in stale:
            del self._live[ref]
        self._changed.update(stale)
        if self._changed:
            self.apply()
        if not self._live:  # nothing sends any more: no tick until data comes again
            self._flow_timer.stop()
            return
        live = [item for link, item in self._link_items.items() if link.output in self._live]
        if self.animated(len(live)):
            self.phase = (self.phase + 1.5) % 70.0
            for item in live:
                item.refresh()

    def animated(self, live_links: int) -> bool:
        """Whether flowing data moves along its links: only when the links are drawn
        large enough to see it and few enough to redraw 12 times a second (on a large
        bus fitted to the window every link redrawn per tick meant the whole view).
        Otherwise a link with data is shown still, in the colour of data flowing."""
        return self._zoom() >= DETAIL_ZOOM and live_links <= FLOW_ANIMATE_MAX

    def apply(self) -> None:
        """Redraw only the ports and links of outputs whose data started or stopped."""
        self._batch_timer.stop()
        changed, self._changed = self._changed, set()
        if not changed:
            return
        system, live = self._system(), self._live
        touched: set[DeviceItem] = set()
        for ref in changed:
            card = self._cards.get(ref.device)
            port = card.ports.get(ref.index) if card is not None else None
            if card is not None and port is not None and port.is_output:
                port.live = ref in live
                touched.add(card)
            for target in system.inputs_fed_by(ref):
                in_card = self._cards.get(target.device)
                in_port = in_card.ports.get(target.index) if in_card is not None else None
                if in_card is not None and in_port is not None:
                    in_port.live = system.source_of(target) in live
                    touched.add(in_card)
        for card in touched:
            card.refresh()
        for link, item in self._link_items.items():
            if link.output in changed:
                item.live = link.output in live
                item.refresh()
