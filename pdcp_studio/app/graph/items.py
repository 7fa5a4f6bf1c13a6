"""Device cards and their ports.

A :class:`DeviceItem` shows one card (header with name and role, one row per channel:
inputs first with their port on the left, then outputs with their port on the right) as
a picture in a built-in pixmap item; ports are built-in ellipse items (painted by C++:
no Python on the paint path).
Following Qt's elasticnodes example, a card tells its links to re-route from
``itemChange``.
"""

from __future__ import annotations

import math
from functools import cache
from typing import TYPE_CHECKING, Any, cast

from PySide6.QtCore import QPointF, QRectF, Qt
from PySide6.QtGui import (
    QBrush,
    QColor,
    QFont,
    QFontInfo,
    QFontMetricsF,
    QImage,
    QPainter,
    QPen,
    QPixmap,
)
from PySide6.QtWidgets import (
    QGraphicsEllipseItem,
    QGraphicsItem,
    QGraphicsPixmapItem,
    QGraphicsRectItem,
    QGraphicsSceneHoverEvent,
    QGraphicsSceneMouseEvent,
    QStyleOptionGraphicsItem,
    QWidget,
)

from pdcp_studio.app.graph import style
from pdcp_studio.app.graph.layout import card_height
from pdcp_studio.app.i18n import translate
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Channel, Device

if TYPE_CHECKING:
    from pdcp_studio.app.graph.links import LinkItem
    from pdcp_studio.app.graph.scene import BusScene

#: ``QGraphicsItem.UserType``: the first item type of an application's own (PySide6's
#: type stubs lack the name).
USER_TYPE = 65536
DEVICE_TYPE = USER_TYPE + 1
PORT_TYPE = USER_TYPE + 2
#: Below this zoom a card shows its name large instead of its rows (the rows' text,
#: grown to fill its row, would be under ROW_MIN_PX on screen).
DETAIL_ZOOM = 0.55
#: Zoomed out (down to DETAIL_ZOOM) the rows' text grows to stay this high on screen.
NAME_MIN_PX = 9.5
ROLE_MIN_PX = 8.0
ROW_MIN_PX = 9.0
#: The device name's height on screen in the summary level, pixels (it may shrink to
#: SUMMARY_MIN_PX to fit a small card, never further).
SUMMARY_NAME_PX = 11.0
SUMMARY_MIN_PX = 9.0
#: Above this zoom cards paint vectors themselves (few are visible; a picture at that
#: scale would be large).
PICTURE_MAX_ZOOM = 2.0
#: The picture's margin around the card (the shadow, the selection border).
PICTURE_PAD = 4.0


@cache
def _fonts() -> tuple[QFont, QFont, QFont, QFont]:
    return style.title_font(), style.small_font(), style.row_font(), style.mono_font()


@cache
def _metrics() -> tuple[QFontMetricsF, QFontMetricsF, QFontMetricsF, QFontMetricsF]:
    return tuple(QFontMetricsF(f) for f in _fonts())  # type: ignore[return-value]



def card_product(key: Any) -> str:
    """The product a card names under the part's name (the catalogue's; "" if unknown)."""
    return _card_catalogue(key.vid, key.pid)[0]


def card_icon(key: Any) -> QImage | None:
    """The picture of the part's kind (the catalogue's ``icon``), None if it has none."""
    return _card_catalogue(key.vid, key.pid)[1]


@cache
def _card_catalogue(vid: int, pid: int) -> tuple[str, QImage | None]:
    """(product, picture) of a VID/PID, looked up once (a catalogue lookup finds the
    user's folder: ~50 µs, too slow for every card's paint); the scene forgets them when
    it rebuilds (:func:`forget_catalogue`)."""
    from pdcp_studio.app.widgets.kind_icons import kind_image
    from pdcp_studio.model.catalog import default_catalog

    entry = default_catalog().lookup(vid, pid)
    if entry is None:
        return "", None
    image = kind_image(entry.icon, 32) if entry.icon else None
    return entry.product, None if image is None or image.isNull() else image


def card_icon_vectors(key: Any) -> Any:
    """The kind's icon as an SVG renderer (for vectors), None if it has none."""
    from pdcp_studio.app.widgets.kind_icons import entry_of, kind_renderer

    entry = entry_of(key)
    return kind_renderer(entry.icon) if entry is not None and entry.icon else None


def elide_keeping_serial(label: str, serial: int, metrics: Any, width: float) -> str:
    """``label`` elided to ``width``; a twin's serial number (``… (serial 302)``) is kept
    whole, so two hands alike never read the same once cut."""
    from pdcp_studio.app.words.part_names import twin_format

    suffix = twin_format().format(name="", serial=serial)
    if (metrics.horizontalAdvance(label) <= width or not suffix.strip()
            or not label.endswith(suffix) or len(label) <= len(suffix)):
        return str(metrics.elidedText(label, Qt.TextElideMode.ElideRight, width))
    room = width - metrics.horizontalAdvance(suffix)
    base = str(metrics.elidedText(label[:-len(suffix)], Qt.TextElideMode.ElideRight,
                                  max(room, 0)))
    return base + suffix


def forget_catalogue() -> None:
    """Look the products up again (a catalogue file was added or changed)."""
    _card_catalogue.cache_clear()


class PortItem(QGraphicsEllipseItem):
    """A channel's connection point; a drag from it draws a link (the scene's gesture,
    :mod:`pdcp_studio.app.graph.link_drag`)."""

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
        self._look: tuple[int, float, int] | None = None
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
        if self.live:
            fill = style.LINK_LIVE
        elif self.connected:
            fill = style.MISSING_TEXT if missing else style.ROLE_COLOURS[self.card.role]
        else:
            fill = style.PORT_FILL
        state = (colour.rgba(), width, fill.rgba())
        if state != self._look:  # unchanged: no repaint
            self._look = state
            self.setPen(QPen(colour, width))
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


class DeviceItem(QGraphicsRectItem):
    """One device as a card; movable, selectable, one row per channel.

    The card is drawn by :meth:`draw` (vectors) into a picture at the view's scale, shown
    by a built-in pixmap child: Qt repaints the scene without calling into Python — each
    such call waits for the GIL, which the threads of a simulated prosthesis hold most of
    the time, and 93 Python-painted cards stalled the GUI for half a second on
    ``sim:full``. The picture is redrawn only when what the card shows changes
    (:meth:`refresh` skips no-ops) or the zoom does, by the scene in small batches
    (:meth:`BusScene.render_pending`). Above ``PICTURE_MAX_ZOOM`` (few cards visible) and
    for a vector export the card paints itself (``vector``), with Qt's cache.

    Two levels of detail: *rows* (the header with name and role, one row per channel)
    when the text is readable, and *summary* below ``DETAIL_ZOOM`` (the device's name
    large across the card, at least ``SUMMARY_MIN_PX`` on screen), e.g. a large bus
    fitted to the window.
    """

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
        self.zoom = 1.0
        self.summary = False
        self.vector = False
        self._shown: tuple[object, ...] | None = None  # the state last drawn (refresh skips no-ops)
        self._drawn: list[str] = []
        self._name_px = 0.0
        self._row_px = 0.0
        self._picture = QGraphicsPixmapItem(self)
        self._picture.setShapeMode(QGraphicsPixmapItem.ShapeMode.BoundingRectShape)
        self._picture.setTransformationMode(Qt.TransformationMode.SmoothTransformation)
        self._picture.setAcceptedMouseButtons(Qt.MouseButton.NoButton)
        self._picture.setOffset(-PICTURE_PAD, -PICTURE_PAD)
        self._picture.setZValue(-1)
        self.setFlags(
            QGraphicsItem.GraphicsItemFlag.ItemIsMovable
            | QGraphicsItem.GraphicsItemFlag.ItemIsSelectable
            | QGraphicsItem.GraphicsItemFlag.ItemSendsGeometryChanges
            | QGraphicsItem.GraphicsItemFlag.ItemHasNoContents
        )
        self.setAcceptHoverEvents(True)
        self._build_rows()

    def type(self) -> int:
        return DEVICE_TYPE

    # -- structure ------------------------------------------------------------------
    def _build_rows(self) -> None:
        for port in self.ports.values():
            port.setParentItem(cast(QGraphicsItem, None))  # Qt takes None: no parent
            if port.scene() is not None:
                port.scene().removeItem(port)
        self.ports.clear()
        d = self.device
        self.rows = sorted(d.inputs(), key=lambda c: c.index) + sorted(
            d.outputs(), key=lambda c: c.index)
        for i, ch in enumerate(self.rows):
            y = style.HEADER_HEIGHT + (i + 0.5) * style.ROW_HEIGHT
            self.ports[ch.index] = PortItem(self, ch, y)
        self._shown = None

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
        else:
            self.rows = sorted(device.inputs(), key=lambda c: c.index) + sorted(
                device.outputs(), key=lambda c: c.index)
        self.refresh()

    def _state(self) -> tuple[object, ...]:
        """Everything the card's picture shows (compared to skip needless redraws)."""
        d = self.device
        return (d.present, self.isSelected(), self.role, tuple(self.problems),
                frozenset(self.pending_rows),
                self.selected_ref.index if self.selected_ref is not None else None,
                self._scene_ref.device_label(d), d.vid, d.pid, self.height,
                tuple((c.index, c.is_input, c.profile, c.descriptor) for c in self.rows),
                self.summary, self.vector, self.picture_scale())

    def refresh(self) -> None:
        """Bring ports and the card's picture up to date; the picture is redrawn (soon, by
        the scene) only when something it shows changed."""
        for port in self.ports.values():
            port.refresh()
        state = self._state()
        if state == self._shown:
            return
        self._shown = state
        if self.vector:
            self.update()
        else:
            self._scene_ref.pictures.schedule(self)

    def picture_scale(self) -> float:
        """Device pixels per scene unit of the card's picture (the view's zoom)."""
        return min(self.zoom, PICTURE_MAX_ZOOM) * self._scene_ref.pixel_ratio

    def render_picture(self) -> None:
        """Draw the card into its picture at the current scale (the scene calls this)."""
        if self.vector:
            return
        scale = self.picture_scale()
        w = self.width + 2 * PICTURE_PAD
        h = self.height + 2 * PICTURE_PAD
        image = QImage(max(1, math.ceil(w * scale)), max(1, math.ceil(h * scale)),
                       QImage.Format.Format_ARGB32_Premultiplied)
        image.fill(Qt.GlobalColor.transparent)
        p = QPainter(image)
        p.setRenderHint(QPainter.RenderHint.TextAntialiasing, True)
        p.scale(scale, scale)
        p.translate(PICTURE_PAD, PICTURE_PAD)
        self.draw(p)
        p.end()
        pixmap = QPixmap.fromImage(image)
        pixmap.setDevicePixelRatio(scale)
        self._picture.setPixmap(pixmap)

    def has_picture(self) -> bool:
        return not self._picture.pixmap().isNull()

    def set_zoom(self, zoom: float, export: bool = False) -> None:
        """The view's zoom: the level of detail, and a picture or vectors (``export``:
        vectors without Qt's pixmap cache, for a vector file)."""
        self.zoom = zoom
        self.summary = zoom < DETAIL_ZOOM
        self.exporting = export
        vector = export or zoom > PICTURE_MAX_ZOOM
        cache = (QGraphicsItem.CacheMode.DeviceCoordinateCache if vector and not export
                 else QGraphicsItem.CacheMode.NoCache)
        if cache != self.cacheMode():
            self.setCacheMode(cache)
        if vector != self.vector:
            self.vector = vector
            self.setFlag(QGraphicsItem.GraphicsItemFlag.ItemHasNoContents, not vector)
            self._picture.setVisible(not vector)
        self.refresh()

    def texts(self) -> list[str]:
        """The text the card showed when last drawn (name, role line and rows; or the
        name alone, in the summary level)."""
        return list(self._drawn)

    def row_pixel_size(self) -> float:
        """The rows' text height in pixels on a view at this card's zoom (0: no rows)."""
        return 0.0 if self.summary else self._row_px * self.zoom

    def name_pixel_size(self) -> float:
        """The device name's text height in pixels on a view at this card's zoom."""
        return self._name_px * self.zoom

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
        elif change == QGraphicsItem.GraphicsItemChange.ItemSelectedHasChanged:
            self.refresh()
        return super().itemChange(change, value)

    def mousePressEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        super().mousePressEvent(event)
        row = self.row_at(event.pos())
        self._scene_ref.moves.pressed(self, self.device.ref(row.index) if row else None,
                                      event.modifiers())

    def mouseReleaseEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        super().mouseReleaseEvent(event)
        self._scene_ref.moves.released()

    def hoverMoveEvent(self, event: QGraphicsSceneHoverEvent) -> None:
        row = None if self.summary else self.row_at(event.pos())
        self.setToolTip(self._scene_ref.tooltip_for(self, row))
        super().hoverMoveEvent(event)

    def paint(self, p: QPainter, option: QStyleOptionGraphicsItem,
              widget: QWidget | None = None) -> None:
        """Vectors (zoomed far in, or an export); otherwise the picture child shows the
        card and Qt never calls this (``ItemHasNoContents``)."""
        self.draw(p)

    # -- drawing --------------------------------------------------------------------
    def draw(self, p: QPainter) -> None:
        """The card in card coordinates, at its current level of detail."""
        d, w, h = self.device, self.width, self.height
        missing = not d.present
        selected = self.isSelected()
        role_colour = style.ROLE_COLOURS[self.role]
        text = style.MISSING_TEXT if missing else style.TEXT
        rect = QRectF(0, 0, w, h)
        p.setRenderHint(QPainter.RenderHint.Antialiasing, True)

        # Card body with a soft shadow. Every fill is opaque (a translucent one laid over
        # what lies under it, here): renderers that ignore fill-opacity (ImageMagick's own
        # SVG renderer) then draw an exported file as the screen shows it.
        p.setPen(Qt.PenStyle.NoPen)
        p.setBrush(_over(self._scene_ref.backgroundBrush().color(), QColor(0, 0, 0, 22)))
        p.drawRoundedRect(rect.translated(0, 2.5), style.CORNER, style.CORNER)
        border = style.CARD_BORDER_SELECTED if selected else style.CARD_BORDER
        pen = QPen(border, 2.0 if selected else 1.0)
        if missing:
            pen.setStyle(Qt.PenStyle.DashLine)
        p.setPen(pen)
        tint = QColor(role_colour)
        tint.setAlpha(16 if missing else 30)
        fill = style.MISSING_FILL if missing else style.CARD_FILL
        tint = _over(fill, tint)
        p.setBrush(tint if self.summary else fill)
        p.drawRoundedRect(rect, style.CORNER, style.CORNER)
        if not self.summary:
            # Header tinted with the role colour.
            p.setPen(Qt.PenStyle.NoPen)
            p.setBrush(tint)
            p.drawRoundedRect(QRectF(1, 1, w - 2, style.HEADER_HEIGHT - 1), style.CORNER - 1,
                              style.CORNER - 1)
            p.drawRect(QRectF(1, style.HEADER_HEIGHT - style.CORNER, w - 2, style.CORNER))
            p.setPen(QPen(style.CARD_BORDER, 0.8))
            p.drawLine(QPointF(1, style.HEADER_HEIGHT), QPointF(w - 1, style.HEADER_HEIGHT))
        p.setPen(Qt.PenStyle.NoPen)
        p.setBrush(QColor(style.MISSING_TEXT if missing else role_colour))
        p.drawRoundedRect(QRectF(1, 1, w - 2, 4), 2, 2)
        if self.problems:
            self._paint_badge(p, QPointF(w - 16, 15))
        if 0 in self.pending_rows:  # a device parameter staged, not yet written
            p.setPen(Qt.PenStyle.NoPen)
            p.setBrush(style.PENDING)
            p.drawRect(QRectF(1, 6, 4, style.HEADER_HEIGHT - 8))
        label = self._scene_ref.device_label(d)
        if self.summary:
            self._draw_summary(p, label, text)
        else:
            self._draw_rows(p, label, text)

    def _draw_rows(self, p: QPainter, label: str, text: QColor) -> None:
        title_f, small_f, row_f, _mono_f = _fonts()
        title_m, small_m, row_m, _mono_m = _metrics()
        if self.zoom < 1.0:  # zoomed out: the text grows in the card to stay readable
            title_f, title_m = _at_least(title_f, NAME_MIN_PX, self.zoom, 17.0)
            small_f, small_m = _at_least(small_f, ROLE_MIN_PX, self.zoom, 14.0)
            row_f, row_m = _at_least(row_f, ROW_MIN_PX, self.zoom, style.ROW_HEIGHT - 3)
        d, w = self.device, self.width
        missing = not d.present
        dim = style.MISSING_TEXT if missing else style.TEXT_DIM
        badge = 18.0 if self.problems else 0.0
        p.setFont(title_f)
        p.setPen(text)
        name = elide_keeping_serial(label, d.serial, title_m, w - 22 - badge)
        p.drawText(QRectF(11, 6, w - 20 - badge, 18), Qt.AlignmentFlag.AlignVCenter, name)
        p.setFont(small_f)
        p.setPen(dim)
        role = translate("Style", str(style.MISSING_LABEL if missing
                                       else style.ROLE_LABELS[self.role]))
        product = card_product(d.key)  # the numbers are in the tooltip and the inspector
        icon = card_icon(d.key)
        left = 11.0
        if icon is not None:
            renderer = card_icon_vectors(d.key) if getattr(self, "exporting", False) else None
            if renderer is not None:  # a vector file gets vectors, not a picture
                renderer.render(p, QRectF(left, 23, 12, 12))
            else:
                p.drawImage(QRectF(left, 23, 12, 12), icon, QRectF(icon.rect()))
            left += 15
        role_line = small_m.elidedText(f"{role}  ·  {product}" if product else role,
                                       Qt.TextElideMode.ElideRight, w - 9 - left)
        p.drawText(QRectF(left, 22, w - 9 - left, 14), Qt.AlignmentFlag.AlignVCenter,
                   role_line)
        drawn = [name, role_line]
        self._row_px = QFontInfo(row_f).pixelSize() if row_f.pixelSize() < 0 \
            else row_f.pixelSize()
        self._name_px = QFontInfo(title_f).pixelSize() if title_f.pixelSize() < 0 \
            else title_f.pixelSize()

        # Channel rows.
        n_in = sum(1 for c in self.rows if c.is_input)
        channel_label = self._scene_ref.words.channel_label
        idx_w = row_m.horizontalAdvance("000")
        avail = w - 2 * 14 - idx_w - 6
        p.setFont(row_f)
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
                under = style.ROW_SELECTED if (
                    self.selected_ref is not None and self.selected_ref.index == ch.index
                ) else style.MISSING_FILL if missing else style.CARD_FILL
                p.setPen(QPen(style.PENDING, 1.0, Qt.PenStyle.DashDotLine))
                p.setBrush(_over(under, wash))
                p.drawRect(row.adjusted(8, 2, -8, -2))
            if i == n_in and n_in:
                p.setPen(QPen(style.GRID, 1.0))
                p.drawLine(QPointF(10, y), QPointF(w - 10, y))
            # The channel's one name (its descriptor, else its profile's name: as every
            # other text calls it), shortened alike on every card; the full name, the
            # profile and its hex code are in the row's tooltip.
            idx_text = str(ch.index)
            pname = _shorten(channel_label(d.ref(ch.index)), row_m, avail)
            drawn.append(pname)
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
        self._drawn = drawn

    def _draw_summary(self, p: QPainter, label: str, colour: QColor) -> None:
        """The name across the card, at least ``SUMMARY_MIN_PX`` on screen at the current
        zoom: the largest size (up to ``SUMMARY_NAME_PX``) at which it fits whole, wrapped
        at words in as many lines as the card holds; else at the least size, shortened
        ("EMG flexor 11" → "flex. 11", so flexor and extensor stay apart)."""
        pad = 6.0
        width = self.width - 2 * pad - (18.0 if self.problems else 0.0)
        top = 7.0
        zoom = max(self.zoom, 0.01)
        whole = " ".join(label.split())
        chosen: tuple[QFont, list[str]] | None = None
        for px in (SUMMARY_NAME_PX, SUMMARY_NAME_PX - 1, SUMMARY_MIN_PX):
            font = QFont(_fonts()[0])
            font.setPixelSize(max(1, math.ceil(px / zoom)))
            metrics = QFontMetricsF(font)
            room = max(1, int((self.height - top - 3) // metrics.lineSpacing()))
            lines = _wrap(label, metrics, width, room)
            chosen = (font, lines)
            if " ".join(lines) == whole:
                break
        assert chosen is not None
        font, lines = chosen
        metrics = QFontMetricsF(font)
        if " ".join(lines) != whole:
            rest = label.split()[len(" ".join(lines[:-1]).split()):]
            lines[-1] = _shorten(" ".join(rest), metrics, width)
        p.setFont(font)
        p.setPen(colour)
        spacing = metrics.lineSpacing()
        y = max(top, (self.height - spacing * len(lines)) / 2)
        for i, line in enumerate(lines):
            p.drawText(QRectF(pad, y + i * spacing, width, spacing),
                       Qt.AlignmentFlag.AlignVCenter | Qt.AlignmentFlag.AlignLeft, line)
        self._drawn = [" ".join(lines)]
        self._name_px = font.pixelSize()

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


def _at_least(font: QFont, px: float, zoom: float, cap: float) -> tuple[QFont, QFontMetricsF]:
    """``font`` grown so that it is ``px`` pixels high on screen at ``zoom`` (never
    smaller than it is, never taller than ``cap`` scene units: it must fit its row)."""
    base = QFontInfo(font).pixelSize()
    size = min(cap, max(base, px / max(zoom, 0.01)))
    if size <= base:
        return font, QFontMetricsF(font)
    grown = QFont(font)
    grown.setPixelSize(max(1, math.floor(size)))
    return grown, QFontMetricsF(grown)


def _over(base: QColor, tint: QColor) -> QColor:
    """``tint`` (with its alpha) laid over the opaque ``base``."""
    a = tint.alphaF()
    return QColor.fromRgbF(base.redF() * (1 - a) + tint.redF() * a,
                           base.greenF() * (1 - a) + tint.greenF() * a,
                           base.blueF() * (1 - a) + tint.blueF() * a)


def _shorten(text: str, metrics: QFontMetricsF, width: float) -> str:
    """``text`` abbreviated to fit ``width``: the first of its fixed short forms
    (``model/names.py`` :func:`short_forms`: "EMG flexor 11" → "EMG flex. 11" → "flex. 11")
    that fits, so a word is cut alike on every card whatever its width; elided only as a
    last resort. The full name is in the card's tooltip and the inspector."""
    from pdcp_studio.model.names import short_forms

    forms = short_forms(text)
    for candidate in forms:
        if metrics.horizontalAdvance(candidate) <= width:
            return candidate
    return metrics.elidedText(forms[-1], Qt.TextElideMode.ElideRight, width)


def _wrap(text: str, metrics: QFontMetricsF, width: float, max_lines: int) -> list[str]:
    """Words into lines no wider than ``width``; at most ``max_lines``, the last elided."""
    lines: list[str] = []
    current = ""
    words = text.split()
    if len(words) > 2 and len(words[-1]) <= 4 and any(c.isdigit() for c in words[-1]):
        words[-2:] = [f"{words[-2]} {words[-1]}"]  # "Control / unit 1", not "… unit / 1"
    for i, word in enumerate(words):
        trial = f"{current} {word}".strip()
        if current and metrics.horizontalAdvance(trial) > width:
            if len(lines) == max_lines - 1:  # the last line takes the rest, elided
                current = " ".join([current, *words[i:]])
                break
            lines.append(current)
            current = word
        else:
            current = trial
    lines.append(current)
    return [metrics.elidedText(line, Qt.TextElideMode.ElideRight, width) for line in lines]
