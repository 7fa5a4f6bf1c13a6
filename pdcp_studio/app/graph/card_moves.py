"""Moving cards with the mouse: a press remembers where the selected cards were, the
release makes the whole drag one undo step (cards of a multi-selection move together).
"""

from __future__ import annotations

from collections.abc import Callable

from PySide6.QtCore import QPointF, Qt

from pdcp_studio.app.documents import commands
from pdcp_studio.app.documents.document import Document, Position
from pdcp_studio.app.graph.items import DeviceItem
from pdcp_studio.model.refs import ChannelRef, DeviceKey


class CardMoves:
    """The card drag of one scene (``cards``: its table; ``selected``: the cards selected
    now)."""

    def __init__(self, doc: Document, cards: dict[DeviceKey, DeviceItem],
                 selected: Callable[[], list[DeviceItem]]) -> None:
        self._doc = doc
        self._cards = cards
        self._selected = selected
        self._press: dict[DeviceKey, QPointF] = {}

    def pressed(self, card: DeviceItem, ref: ChannelRef | None,
                modifiers: Qt.KeyboardModifier) -> None:
        """A press on ``card`` (on its row ``ref``): remember where the cards are, and
        select the card or the row (Ctrl: Qt's multi-selection only)."""
        self._press = {c.key: c.pos() for c in self._selected()}
        self._press.setdefault(card.key, card.pos())
        if not modifiers & Qt.KeyboardModifier.ControlModifier:
            self._doc.select(ref if ref is not None else card.key)

    def released(self) -> None:
        """A mouse release on a card: the whole drag becomes one undo step."""
        moves: dict[DeviceKey, tuple[Position, Position]] = {}
        for key, old in self._press.items():
            card = self._cards.get(key)
            if card is not None and card.pos() != old:
                moves[key] = ((old.x(), old.y()), (card.pos().x(), card.pos().y()))
        self._press = {}
        if moves:
            self._doc.undo_stack.push(commands.MoveDevicesCommand(self._doc, moves))
