"""Device cards and their ports.

A :class:`DeviceItem` paints one card (header with name and role, one row per channel:
inputs first with their port on the left, then outputs with their port on the right).
Ports are built-in ellipse items (painted by C++, cheap on big systems). Following Qt's
elasticnodes example, a card tells its links to re-route from ``itemChange``.
"""

from __future__ import annotations

from functools import cache
from typing import TYPE_CHECKING

from PySide6.QtCore import QPointF, QRectF, Qt
from PySide6.QtGui import QBrush, QColor, QFont, QFontMetricsF, QPainter, QPen
from PySide6.QtWidgets import (
    QGraphicsEllipseItem,
    QGraphicsItem,
    QGraphicsRectItem,
    QGraphicsSceneHoverEvent,
    QGraphicsSceneMouseEvent,
    QStyleOptionGraphicsItem,
    QWidget,
)

from pdcp_studio.app.graph import style
from pdcp_studio.app.graph.layout import card_height
from pdcp_studio.app.i18n import translate
from pdcp_studio.model import profile as prof
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Channel, Device

if TYPE_CHECKING:
    from pdcp_studio.app.graph.links import LinkItem
    from pdcp_studio.app.graph.scene import BusScene

DEVICE_TYPE = QGraphicsItem.UserType + 1
PORT_TYPE = QGraphicsItem.UserType + 2


@cache
def _fonts() -> tuple[QFont, QFont, QFont, QFont]:
    return style.title_font(), style.small_font(), style.row_font(), style.mono_font()


@cache
def _metrics() -> tuple[QFontMetricsF, QFontMetricsF, QFontMetricsF, QFontMetricsF]:
    return tuple(QFontMetricsF(f) for f in _fonts())  # type: ignore[return-value]


class PortItem(QGraphicsEllipseItem):
    """A channel's connection point; dragging from it draws a link."""

    def __init__(self, card: DeviceItem, channel: Channel, y: float) -> None:
        r = style.PORT_RADIUS
        super().__init__(-r, -r, 2 * r, 2 * r, card)
        self.card = card
        self.ref: ChannelRef = card.device.ref(channel.index)
        self.is_output = channel.is_output
        self.setPos(card.width if self.is_output else 0.0, y)
        self.setZValue(2)
        self.setAcceptHoverEvents(True)
        self.setAcceptedMouseButtons(Qt.MouseButton.LeftButton)
        self.setCursor(Qt.CursorShape.CrossCursor)
        self.links: list[LinkItem] = []
        self._hover = False
        self.connected = False
        self.unmet = False
        self.live = False
        self.refresh()

    def type(self) -> int:
        return PORT_TYPE

    def refresh(self) -> None:
        """Pen and brush from the port's state (connected, unmet required, live, hover)."""
        missing = not self.card.device.present
        colour = style.MISSING_TEXT if missing else style.PORT_INPUT
        width = 1.6
        if self.unmet:
            colour, width = style.ERROR, 2.2
        if self._hover:
            colour, width = style.DRAG_OK, 2.4
        self.setPen(QPen(colour, width))
        if self.live:
            fill = style.LINK_LIVE
        elif self.connected:
            fill = style.MISSING_TEXT if missing else style.ROLE_COLOURS[self.card.role]
        else:
            fill = style.PORT_FILL
        self.setBrush(QBrush(fill))

    def set_hover(self, on: bool) -> None:
        if on != self._hover:
            self._hover = on
            self.refresh()

    def hoverEnterEvent(self, event: QGraphicsSceneHoverEvent) -> None:
        self.set_hover(True)
        super().hoverEnterEvent(event)

    def hoverLeaveEvent(self, event: QGraphicsSceneHoverEvent) -> None:
        self.set_hover(False)
        super().hoverLeaveEvent(event)

    def mousePressEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        scene = self.scene()
        if event.button() == Qt.MouseButton.LeftButton and scene is not None:
            scene.begin_link_drag(self, event.scenePos())
            event.accept()
            return
        super().mousePressEvent(event)

    def mouseMoveEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        scene = self.scene()
        if scene is not None:
            scene.update_link_drag(event.scenePos())

    def mouseReleaseEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        scene = self.scene()
        if scene is not None:
            scene.end_link_drag(event.scenePos())


class DeviceItem(QGraphicsRectItem):
    """One device as a card; movable, selectable, one row per channel."""

    def __init__(self, scene: BusScene, device: Device, role: str) -> None:
        super().__init__()
        self._scene_ref = scene
        self.device = device
        self.key = device.key
        self.role = role
        self.width = style.CARD_WIDTH
        self.height = card_height(device)
        self.setPen(QPen(Qt.PenStyle.NoPen))
        self._set_bounds()
        self.problems: list[str] = []
        #: Channel indices (0: the device itself) with a parameter change not yet written to
        #: the prosthesis: a violet wash marks the row (a violet bar the header).
        self.pending_rows: set[int] = set()
        self.selected_ref: ChannelRef | None = None
        self.links: set[LinkItem] = set()
        self.ports: dict[int, PortItem] = {}
        self.rows: list[Channel] = []
        self.setFlags(
            QGraphicsItem.GraphicsItemFlag.ItemIsMovable
            | QGraphicsItem.GraphicsItemFlag.ItemIsSelectable
            | QGraphicsItem.GraphicsItemFlag.ItemSendsGeometryChanges
        )
        self.setAcceptHoverEvents(True)
        self.setCacheMode(QGraphicsItem.CacheMode.DeviceCoordinateCache)
        self._build_rows()

    def type(self) -> int:
        return DEVICE_TYPE

    # -- structure ------------------------------------------------------------------
    def _build_rows(self) -> None:
        for port in self.ports.values():
            port.setParentItem(None)
            if port.scene() is not None:
                port.scene().removeItem(port)
        self.ports.clear()
        d = self.device
        self.rows = sorted(d.inputs(), key=lambda c: c.index) + sorted(
            d.outputs(), key=lambda c: c.index)
        for i, ch in enumerate(self.rows):
            y = style.HEADER_HEIGHT + (i + 0.5) * style.ROW_HEIGHT
            self.ports[ch.index] = PortItem(self, ch, y)

    def set_device(self, device: Device, role: str) -> None:
        """The model object changed (same key): rebuild rows if the channels changed."""
        old = [(c.index, c.direction) for c in self.rows]
        self.device, self.role = device, role
        new = sorted(((c.index, c.direction) for c in device.inputs()), key=lambda t: t[0]) + \
            sorted(((c.index, c.direction) for c in device.outputs()), key=lambda t: t[0])
        if old != new:
            self.height = card_height(device)
            self._set_bounds()
            links = {lk for p in self.ports.values() for lk in p.links}
            self._build_rows()
            for lk in links:
                lk.rebind()
        self.refresh()

    def refresh(self) -> None:
        for port in self.ports.values():
            port.refresh()
        self.update()

    def row_at(self, local: QPointF) -> Channel | None:
        i = int((local.y() - style.HEADER_HEIGHT) // style.ROW_HEIGHT)
        if local.y() < style.HEADER_HEIGHT or not 0 <= i < len(self.rows):
            return None
        return self.rows[i]

    # -- Qt virtuals ----------------------------------------------------------------
    def _set_bounds(self) -> None:
        """The card's bounds as the C++ rect (no pen, no brush: ``paint`` draws it).

        A built-in ``boundingRect`` spares the scene a call into Python (and a wait for the
        GIL, which bus threads hold often) every time it looks the card up while painting.
        """
        r = style.PORT_RADIUS + 2
        self.setRect(QRectF(-r, -2, self.width + 2 * r, self.height + 6))

    def itemChange(self, change: QGraphicsItem.GraphicsItemChange, value: object) -> object:
        if change == QGraphicsItem.GraphicsItemChange.ItemPositionHasChanged:
            for link in self.links:
                link.update_path()
        return super().itemChange(change, value)

    def mousePressEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        super().mousePressEvent(event)
        row = self.row_at(event.pos())
        self._scene_ref.card_clicked(self, self.device.ref(row.index) if row else None,
                                     event.modifiers())

    def mouseReleaseEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        super().mouseReleaseEvent(event)
        self._scene_ref.drag_finished()

    def hoverMoveEvent(self, event: QGraphicsSceneHoverEvent) -> None:
        row = self.row_at(event.pos())
        self.setToolTip(self._scene_ref.tooltip_for(self, row))
        super().hoverMoveEvent(event)

    def paint(self, p: QPainter, option: QStyleOptionGraphicsItem,
              widget: QWidget | None = None) -> None:
        title_f, small_f, row_f, _mono_f = _fonts()
        title_m, _small_m, row_m, _mono_m = _metrics()
        d, w, h = self.device, self.width, self.height
        missing = not d.present
        selected = self.isSelected()
        role_colour = style.ROLE_COLOURS[self.role]
        text = style.MISSING_TEXT if missing else style.TEXT
        dim = style.MISSING_TEXT if missing else style.TEXT_DIM
        rect = QRectF(0, 0, w, h)
        p.setRenderHint(QPainter.RenderHint.Antialiasing, True)

        # Card body with a soft shadow.
        p.setPen(Qt.PenStyle.NoPen)
        p.setBrush(QColor(0, 0, 0, 22))
        p.drawRoundedRect(rect.translated(0, 2.5), style.CORNER, style.CORNER)
        border = style.CARD_BORDER_SELECTED if selected else style.CARD_BORDER
        pen = QPen(border, 2.0 if selected else 1.0)
        if missing:
            pen.setStyle(Qt.PenStyle.DashLine)
        p.setPen(pen)
        p.setBrush(style.MISSING_FILL if missing else style.CARD_FILL)
        p.drawRoundedRect(rect, style.CORNER, style.CORNER)

        # Header tinted with the role colour; a solid accent strip on top.
        tint = QColor(role_colour)
        tint.setAlpha(16 if missing else 30)
        p.setPen(Qt.PenStyle.NoPen)
        p.setBrush(tint)
        p.drawRoundedRect(QRectF(1, 1, w - 2, style.HEADER_HEIGHT - 1), style.CORNER - 1,
                          style.CORNER - 1)
        p.drawRect(QRectF(1, style.HEADER_HEIGHT - style.CORNER, w - 2, style.CORNER))
        accent = QColor(style.MISSING_TEXT if missing else role_colour)
        p.setBrush(accent)
        p.drawRoundedRect(QRectF(1, 1, w - 2, 4), 2, 2)
        p.setPen(QPen(style.CARD_BORDER, 0.8))
        p.drawLine(QPointF(1, style.HEADER_HEIGHT), QPointF(w - 1, style.HEADER_HEIGHT))

        badge = 18.0 if self.problems else 0.0
        p.setFont(title_f)
        p.setPen(text)
        name = title_m.elidedText(self._scene_ref.device_label(d),
                                  Qt.TextElideMode.ElideRight, w - 22 - badge)
        p.drawText(QRectF(11, 6, w - 20 - badge, 18), Qt.AlignmentFlag.AlignVCenter, name)
        p.setFont(small_f)
        p.setPen(dim)
        role = translate("Style", style.MISSING_LABEL if missing else style.ROLE_LABELS[self.role])
        p.drawText(QRectF(11, 22, w - 20, 14), Qt.AlignmentFlag.AlignVCenter,
                   f"{role}  ·  {d.vid}/{d.pid}/{d.serial}")
        if self.problems:
            self._paint_badge(p, QPointF(w - 16, 15))
        if 0 in self.pending_rows:  # a device parameter staged, not yet written
            p.setPen(Qt.PenStyle.NoPen)
            p.setBrush(style.PENDING)
            p.drawRect(QRectF(1, 6, 4, style.HEADER_HEIGHT - 8))

        # Channel rows.
        n_in = sum(1 for c in self.rows if c.is_input)
        name_of = self._scene_ref.profile_name
        for i, ch in enumerate(self.rows):
            y = style.HEADER_HEIGHT + i * style.ROW_HEIGHT
            row = QRectF(0, y, w, style.ROW_HEIGHT)
            if self.selected_ref is not None and self.selected_ref.index == ch.index:
                p.setPen(Qt.PenStyle.NoPen)
                p.setBrush(style.ROW_SELECTED)
                p.drawRect(row.adjusted(1, 0, -1, 0))
            if ch.index in self.pending_rows:  # a parameter staged, not yet written
                wash = QColor(style.PENDING)
                wash.setAlpha(40)
                p.setPen(QPen(style.PENDING, 1.0, Qt.PenStyle.DashDotLine))
                p.setBrush(wash)
                p.drawRect(row.adjusted(8, 2, -8, -2))
            if i == n_in and n_in:
                p.setPen(QPen(style.GRID, 1.0))
                p.drawLine(QPointF(10, y), QPointF(w - 10, y))
            # The profile's name from the tree; its hex code is in the row's tooltip.
            idx_text = str(ch.index)
            idx_w = row_m.horizontalAdvance("000")
            pname = name_of(ch.profile)
            if pname == prof.fmt(ch.profile):
                pname = ch.descriptor or pname
            avail = w - 2 * 14 - idx_w - 6
            pname = row_m.elidedText(pname, Qt.TextElideMode.ElideRight, avail)
            p.setFont(row_f)
            if ch.is_input:
                p.setPen(dim)
                p.drawText(QRectF(14, y, idx_w, style.ROW_HEIGHT),
                           Qt.AlignmentFlag.AlignVCenter | Qt.AlignmentFlag.AlignLeft, idx_text)
                p.setPen(text)
                p.drawText(QRectF(14 + idx_w, y, avail, style.ROW_HEIGHT),
                           Qt.AlignmentFlag.AlignVCenter | Qt.AlignmentFlag.AlignLeft, pname)
            else:
                p.setPen(text)
                p.drawText(QRectF(w - 14 - idx_w - avail, y, avail, style.ROW_HEIGHT),
                           Qt.AlignmentFlag.AlignVCenter | Qt.AlignmentFlag.AlignRight, pname)
                p.setPen(dim)
                p.drawText(QRectF(w - 14 - idx_w, y, idx_w, style.ROW_HEIGHT),
                           Qt.AlignmentFlag.AlignVCenter | Qt.AlignmentFlag.AlignRight, idx_text)

    @staticmethod
    def _paint_badge(p: QPainter, centre: QPointF) -> None:
        """A small amber warning disc with "!" (details in the tooltip)."""
        p.setPen(Qt.PenStyle.NoPen)
        p.setBrush(style.WARN)
        p.drawEllipse(centre, 7.5, 7.5)
        f = QFont(_fonts()[0])
        f.setPointSizeF(8.5)
        p.setFont(f)
        p.setPen(QColor("#ffffff"))
        p.drawText(QRectF(centre.x() - 7.5, centre.y() - 7.5, 15, 15),
                   Qt.AlignmentFlag.AlignCenter, "!")
