"""Card pictures drawn in small batches on the GUI thread, what the view shows first.

A card draws itself into a picture (:meth:`DeviceItem.render_picture`, ~0.3 ms); a bus's
worth of cards at once would stop the GUI thread, so the pictures wait here and are drawn
``RENDER_BUDGET_S`` at a time per turn of the event loop, the cards near the view's sight
first.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from PySide6.QtCore import QObject, QRectF, QTimer

from pdcp_studio.app.graph.items import DeviceItem
from pdcp_studio.model.refs import DeviceKey

#: Card pictures are drawn for at most this long per turn of the event loop (about
#: 0.3 ms each; the GUI thread stays free for input and painting in between).
RENDER_BUDGET_S = 0.006


class PictureQueue(QObject):
    """Cards waiting for their picture; ``cards`` is the scene's table (a card no longer
    in it is not drawn), ``drawn`` is called after a batch drew some."""

    def __init__(self, parent: QObject, cards: dict[DeviceKey, DeviceItem],
                 drawn: Callable[[], None]) -> None:
        super().__init__(parent)
        self._cards = cards
        self._drawn = drawn
        self.waiting: dict[DeviceKey, DeviceItem] = {}
        #: Where the view looks, with a margin (scene coordinates; at first: everywhere).
        self._sight = QRectF(-1e9, -1e9, 2e9, 2e9)
        self.timer = QTimer(self)
        self.timer.setSingleShot(True)
        self.timer.setInterval(0)
        self.timer.timeout.connect(self._batch)

    def schedule(self, card: DeviceItem) -> None:
        """Redraw a card's picture soon."""
        self.waiting[card.key] = card
        if not self.timer.isActive():
            self.timer.start()

    def clear(self) -> None:
        self.waiting.clear()

    def render(self, budget_s: float | None = None) -> int:
        """Draw waiting card pictures; returns how many still wait. With None, all of
        them now. With a time budget (a batch on the event loop), for at most that long
        (at least one card), only the cards near the view's sight and those with no
        picture yet: a card out of sight keeps its old picture until it comes near
        (:meth:`look_at`), so a zoom on a large bus redraws what is seen, not all."""
        waiting = self.waiting
        keys = list(waiting)
        if budget_s is not None:
            sight = self._sight
            near = [k for k in keys if sight.intersects(waiting[k].sceneBoundingRect())]
            seen = set(near)
            keys = near + [k for k in keys if k not in seen and not waiting[k].has_picture()]
        start = time.perf_counter()
        for key in keys:
            card = waiting.pop(key)
            if self._cards.get(key) is card:
                card.render_picture()
            if budget_s is not None and time.perf_counter() - start > budget_s:
                break
        more = [k for k in keys if k in waiting]
        if more and not self.timer.isActive():
            self.timer.start()
        if keys:
            self._drawn()
        return len(waiting)

    def look_at(self, sight: QRectF) -> None:
        """The part of the scene the view shows (with a margin): waiting pictures there
        are drawn soon."""
        self._sight = QRectF(sight)
        if self.waiting and not self.timer.isActive():
            self.timer.start()

    def _batch(self) -> None:
        self.render(RENDER_BUDGET_S)
