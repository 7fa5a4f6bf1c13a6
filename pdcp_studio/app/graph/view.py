"""The view on the bus scene: zoom with the wheel, pan with the middle button, fit.

Plain ``QGraphicsView`` with the default viewport update mode (measured fine up to 254
devices); rubber-band selection on empty space, a card drag moves it, a port drag links.
"""

from __future__ import annotations

from PySide6.QtCore import QT_TRANSLATE_NOOP, QPoint, QPointF, QRectF, QSize, Qt
from PySide6.QtGui import (
    QColor,
    QFontMetricsF,
    QMouseEvent,
    QPainter,
    QPaintEvent,
    QPen,
    QResizeEvent,
    QWheelEvent,
)
from PySide6.QtWidgets import QGraphicsView, QWidget

from pdcp_studio.app.graph import style
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.app.i18n import translate

MIN_ZOOM = 0.1
MAX_ZOOM = 4.0
WHEEL_STEP = 1.15
FIT_MARGIN = 30.0
#: Fit never magnifies beyond this (a three-card system should not look bloated).
FIT_MAX_ZOOM = 1.3


#: The legend's rows: (kind, colour, label). Kinds: "role" swatch, "ring" port,
#: "line"/"dash"/"dashdot"/"dot" link.
LEGEND = (
    (
        ("role", style.ROLE_COLOURS["sensor"], QT_TRANSLATE_NOOP("Legend", "Sensor")),
        ("role", style.ROLE_COLOURS["control"], QT_TRANSLATE_NOOP("Legend", "Control")),
        ("role", style.ROLE_COLOURS["terminal"], QT_TRANSLATE_NOOP("Legend", "Terminal device")),
        ("role", style.MISSING_TEXT, QT_TRANSLATE_NOOP("Legend", "Missing")),
        ("ring", style.ERROR, QT_TRANSLATE_NOOP("Legend", "Required input unmet")),
    ),
    (
        ("line", style.LINK, QT_TRANSLATE_NOOP("Legend", "Link")),
        ("dash", style.LINK_LIVE, QT_TRANSLATE_NOOP("Legend", "Data flowing")),
        ("dash", style.LINK_MISSING, QT_TRANSLATE_NOOP("Legend", "End missing")),
        ("line", style.LINK_CONFLICT, QT_TRANSLATE_NOOP("Legend", "Sole-access conflict")),
        ("dash", style.PREVIEW_ADD, QT_TRANSLATE_NOOP("Legend", "Plan adds")),
        ("dash", style.PREVIEW_REMOVE, QT_TRANSLATE_NOOP("Legend", "Plan removes")),
    ),
    (
        ("dashdot", style.PENDING, QT_TRANSLATE_NOOP("Legend", "Pending: to write")),
        (
            "dot",
            style.PENDING_REMOVE,
            QT_TRANSLATE_NOOP("Legend", "Pending: to remove from the prosthesis"),
        ),
    ),
)


class Legend(QWidget):
    """What the colours mean, in a corner of the view (a widget: it does not scroll)."""

    PAD = 8.0
    ROW = 18.0
    GAP = 14.0

    def __init__(self, parent: QWidget) -> None:
        super().__init__(parent)
        self.setAttribute(Qt.WidgetAttribute.WA_TransparentForMouseEvents)
        self.setFont(style.small_font())
        self._metrics = QFontMetricsF(self.font())

    def _width(self, row: tuple) -> float:
        return sum(24 + self._metrics.horizontalAdvance(translate("Legend", label)) + self.GAP
                   for _k, _c, label in row) - self.GAP

    def sizeHint(self) -> QSize:
        w = max(self._width(r) for r in LEGEND) + 2 * self.PAD
        return QSize(int(w) + 1, int(len(LEGEND) * self.ROW + 2 * self.PAD))

    def paintEvent(self, event: QPaintEvent) -> None:
        p = QPainter(self)
        p.setRenderHint(QPainter.RenderHint.Antialiasing)
        p.setPen(QPen(style.CARD_BORDER, 1))
        p.setBrush(QColor(255, 255, 255, 225))
        p.drawRoundedRect(QRectF(self.rect()).adjusted(0.5, 0.5, -0.5, -0.5), 6, 6)
        for r, row in enumerate(LEGEND):
            y = self.PAD + r * self.ROW + self.ROW / 2
            x = self.PAD
            for kind, colour, source in row:
                label = translate("Legend", source)
                if kind == "role":
                    p.setPen(Qt.PenStyle.NoPen)
                    p.setBrush(colour)
                    p.drawRoundedRect(QRectF(x, y - 5, 18, 10), 2, 2)
                elif kind == "ring":
                    p.setPen(QPen(colour, 2.0))
                    p.setBrush(style.PORT_FILL)
                    p.drawEllipse(QPointF(x + 9, y), 4.5, 4.5)
                else:
                    pen = QPen(colour, 2.2)
                    if kind == "dash":
                        pen.setStyle(Qt.PenStyle.DashLine)
                    elif kind == "dashdot":
                        pen.setStyle(Qt.PenStyle.DashDotLine)
                    elif kind == "dot":
                        pen.setStyle(Qt.PenStyle.DotLine)
                    p.setPen(pen)
                    p.drawLine(QPointF(x, y), QPointF(x + 18, y))
                p.setPen(style.TEXT)
                w = self._metrics.horizontalAdvance(label)
                p.drawText(QRectF(x + 24, y - self.ROW / 2, w + 2, self.ROW),
                           Qt.AlignmentFlag.AlignVCenter, label)
                x += 24 + w + self.GAP
        p.end()


class GraphView(QGraphicsView):
    """Shows a :class:`BusScene`; owns only view state (zoom, scroll), never the model."""

    def __init__(self, scene: BusScene, parent: QWidget | None = None) -> None:
        super().__init__(scene, parent)
        self.setRenderHints(QPainter.RenderHint.Antialiasing
                            | QPainter.RenderHint.TextAntialiasing)
        self.setDragMode(QGraphicsView.DragMode.RubberBandDrag)
        self.setTransformationAnchor(QGraphicsView.ViewportAnchor.AnchorUnderMouse)
        self.setResizeAnchor(QGraphicsView.ViewportAnchor.AnchorViewCenter)
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
        self._pan_from: QPoint | None = None
        self.legend = Legend(self)
        self.legend.resize(self.legend.sizeHint())

    def bus_scene(self) -> BusScene:
        return self.scene()  # type: ignore[return-value]

    @property
    def zoom(self) -> float:
        return self.transform().m11()

    def set_zoom(self, factor: float) -> None:
        """Absolute zoom, clamped so cards never vanish or fill the screen with one port."""
        factor = max(MIN_ZOOM, min(MAX_ZOOM, factor))
        self.scale(factor / self.zoom, factor / self.zoom)

    def zoom_by(self, step: float) -> None:
        self.set_zoom(self.zoom * step)

    def fit_all(self) -> None:
        """Show every card, clear of the legend: zoom out as far as that needs, zoom in on
        a small graph up to FIT_MAX_ZOOM (readable, not bloated). The scale is computed
        from the viewport without scroll bars and without the legend's strip at the
        bottom (``fitInView`` counted the legend's area as free and left the bottom cards
        under it)."""
        rect = self.scene().itemsBoundingRect()
        if rect.isEmpty():
            return
        rect = rect.adjusted(-FIT_MARGIN, -FIT_MARGIN, FIT_MARGIN, FIT_MARGIN)
        room = self.maximumViewportSize()
        reserved = self.legend.height() + 16 if self.legend.isVisible() else 0
        # The view centres the graph, so the legend's strip is kept free at both ends.
        width, height = room.width(), max(40, room.height() - 2 * reserved)
        factor = min(width / rect.width(), height / rect.height())
        self.set_zoom(min(FIT_MAX_ZOOM, factor))
        self.centerOn(rect.center())

    def centre_on_item(self, rect: QRectF) -> None:
        self.ensureVisible(rect, 40, 40)

    def set_legend_visible(self, on: bool) -> None:
        self.legend.setVisible(on)

    # -- Qt virtuals ----------------------------------------------------------------
    def resizeEvent(self, event: QResizeEvent) -> None:
        super().resizeEvent(event)
        vp = self.viewport().geometry()
        self.legend.move(vp.left() + 8, vp.bottom() - self.legend.height() - 8)
        self.legend.raise_()

    def wheelEvent(self, event: QWheelEvent) -> None:
        delta = event.angleDelta().y()
        if delta == 0:
            super().wheelEvent(event)
            return
        self.zoom_by(WHEEL_STEP if delta > 0 else 1 / WHEEL_STEP)
        event.accept()

    def mousePressEvent(self, event: QMouseEvent) -> None:
        if event.button() == Qt.MouseButton.MiddleButton:
            self._pan_from = event.position().toPoint()
            self.viewport().setCursor(Qt.CursorShape.ClosedHandCursor)
            event.accept()
            return
        super().mousePressEvent(event)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        if self._pan_from is not None:
            now = event.position().toPoint()
            delta = now - self._pan_from
            self._pan_from = now
            h, v = self.horizontalScrollBar(), self.verticalScrollBar()
            h.setValue(h.value() - delta.x())
            v.setValue(v.value() - delta.y())
            event.accept()
            return
        super().mouseMoveEvent(event)

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:
        if event.button() == Qt.MouseButton.MiddleButton and self._pan_from is not None:
            self._pan_from = None
            self.viewport().unsetCursor()
            event.accept()
            return
        super().mouseReleaseEvent(event)
