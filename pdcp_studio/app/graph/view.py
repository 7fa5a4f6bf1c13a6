"""The view on the bus scene: zoom with the wheel, pan with the middle button, fit.

Plain ``QGraphicsView`` with the default viewport update mode (measured fine up to 254
devices); rubber-band selection on empty space, a card drag moves it, a port drag links.
The zoom picks the cards' level of detail (:meth:`BusScene.set_view_zoom`). Under the
viewport a footer holds a collapsible legend and, for large buses, an overview.
"""

from __future__ import annotations

from PySide6.QtCore import (
    QT_TRANSLATE_NOOP,
    QPoint,
    QPointF,
    QRectF,
    QSettings,
    QSize,
    QSizeF,
    Qt,
    QTimer,
    Signal,
)
from PySide6.QtGui import (
    QColor,
    QFontMetricsF,
    QMouseEvent,
    QPainter,
    QPaintEvent,
    QPen,
    QPixmap,
    QResizeEvent,
    QShowEvent,
    QWheelEvent,
)
from PySide6.QtWidgets import QGraphicsView, QToolButton, QWidget

from pdcp_studio.app.graph import style
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.app.i18n import translate

MIN_ZOOM = 0.1
MAX_ZOOM = 4.0
WHEEL_STEP = 1.15
FIT_MARGIN = 30.0
#: Fit never magnifies beyond this (a three-card system should not look bloated).
FIT_MAX_ZOOM = 1.3
#: The overview is shown by itself for graphs with this many cards or more.
OVERVIEW_MIN_DEVICES = 20
#: The overview redraws its picture at most this often after the scene changed (ms).
OVERVIEW_REDRAW_MS = 700
#: Where the legend's shown/hidden state is remembered.
LEGEND_KEY = "graph/legend_shown"
#: The footer's width when it stands beside the viewport (a tall graph in a wide view).
SIDE_WIDTH = 230


#: The legend's rows: (kind, colour, label). Kinds: "role" swatch, "ring" port,
#: "line"/"dash"/"dashdot"/"dot" link.
LegendEntry = tuple[str, QColor, object]
LEGEND: tuple[tuple[LegendEntry, ...], ...] = (
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
    """What the colours mean (a widget under the scene's viewport: it never covers a card).

    Its entries flow into as many rows as the width it is given needs.
    """

    PAD = 8.0
    ROW = 18.0
    GAP = 14.0

    def __init__(self, parent: QWidget) -> None:
        super().__init__(parent)
        self.setFont(style.small_font())
        self._metrics = QFontMetricsF(self.font())
        self._widths: dict[str, float] = {}  # text → its width in that font
        self._rows: list[list[LegendEntry]] = [list(r) for r in LEGEND]

    def _entry_width(self, label: str) -> float:
        # Asked ~1,000 times while a new window is laid out (the footer tries both places
        # on every resize): measured once per text.
        text = translate("Legend", label)
        width = self._widths.get(text)
        if width is None:
            width = self._widths[text] = 24 + self._metrics.horizontalAdvance(text)
        return width

    def rows_for(self, width: float) -> list[list[LegendEntry]]:
        """The entries flowed into rows no wider than ``width``, in order."""
        rows: list[list[LegendEntry]] = []
        room = width - 2 * self.PAD
        row: list[LegendEntry] = []
        used = 0.0
        for entry in (e for group in LEGEND for e in group):
            w = self._entry_width(str(entry[2]))
            if row and used + self.GAP + w > room:
                rows.append(row)
                row, used = [], 0.0
            used += (self.GAP if row else 0.0) + w
            row.append(entry)
        rows.append(row)
        return rows

    def widest_entry(self) -> int:
        """The width of the widest single entry (the least width that shows it whole)."""
        return int(max(self._entry_width(str(e[2])) for g in LEGEND for e in g) + 2 * self.PAD) + 1

    def natural_width(self) -> int:
        """Wide enough for the longest of the legend's three groups on one row."""
        return int(max(sum(self._entry_width(str(e[2])) for e in g) + self.GAP * (len(g) - 1)
                       for g in LEGEND) + 2 * self.PAD) + 1

    def height_for(self, width: float) -> int:
        return int(len(self.rows_for(width)) * self.ROW + 2 * self.PAD)

    def resizeEvent(self, event: QResizeEvent) -> None:
        super().resizeEvent(event)
        self._rows = self.rows_for(self.width())

    def sizeHint(self) -> QSize:
        w = self.natural_width()
        return QSize(w, self.height_for(w))

    def paintEvent(self, event: QPaintEvent) -> None:
        p = QPainter(self)
        p.setRenderHint(QPainter.RenderHint.Antialiasing)
        p.setPen(QPen(style.CARD_BORDER, 1))
        p.setBrush(QColor(255, 255, 255, 225))
        p.drawRoundedRect(QRectF(self.rect()).adjusted(0.5, 0.5, -0.5, -0.5), 6, 6)
        for r, row in enumerate(self._rows):
            y = self.PAD + r * self.ROW + self.ROW / 2
            x = self.PAD
            for kind, colour, source in row:
                label = translate("Legend", str(source))
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


class Overview(QWidget):
    """The whole graph small, with the part the view shows framed; click or drag in it to
    move the view there. A picture of the scene, redrawn at most every
    ``OVERVIEW_REDRAW_MS`` after the graph changed (not on every change of a big bus)."""

    MIN_SIDE = 72
    MAX_SIDE = 180

    def __init__(self, view: GraphView, parent: QWidget) -> None:
        super().__init__(parent)
        self.view = view
        self.setCursor(Qt.CursorShape.PointingHandCursor)
        self.setToolTip(self.tr("The whole graph: click or drag to show that part"))
        self._picture = QPixmap()
        self._source = QRectF()
        self._target = QRectF()
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(OVERVIEW_REDRAW_MS)
        self._timer.timeout.connect(self.redraw)
        # Redrawn when what it shows changes — cards drawn, moved, linked — not on every
        # change of the scene (data flowing along a link changes it ten times a second).
        scene = view.bus_scene()
        scene.picturesDrawn.connect(self._scene_changed)
        scene.rebuilt.connect(self._scene_changed)
        scene.doc.linksChanged.connect(self._scene_changed)
        scene.doc.positionChanged.connect(self._scene_changed)
        view.horizontalScrollBar().valueChanged.connect(self.update)
        view.verticalScrollBar().valueChanged.connect(self.update)

    def _scene_changed(self, _rects: object = None) -> None:
        if self.isVisible() and not self._timer.isActive():
            self._timer.start()

    def size_for(self, scene_rect: QRectF, *, width: int = 0, height: int = 0) -> QSize:
        """The overview's size for a given width (or height), the other side following
        the graph's shape within MIN_SIDE…MAX_SIDE."""
        aspect = (scene_rect.width() / scene_rect.height()
                  if not scene_rect.isEmpty() else 1.0)
        if width:
            h = (width - 8) / aspect + 8
            return QSize(width, int(max(self.MIN_SIDE, min(self.MAX_SIDE, h))))
        w = (height - 8) * aspect + 8
        return QSize(int(max(self.MIN_SIDE, min(2 * self.MAX_SIDE, w))), height)

    def redraw(self) -> None:
        """Render the scene into the picture (C++ work, one call)."""
        self._timer.stop()
        scene = self.view.scene()
        source = scene.itemsBoundingRect().adjusted(-20, -20, 20, 20)
        box = QRectF(self.rect()).adjusted(4, 4, -4, -4)
        if source.isEmpty() or box.isEmpty():
            self._picture = QPixmap()
            self.update()
            return
        scale = min(box.width() / source.width(), box.height() / source.height())
        size = QSizeF(source.width() * scale, source.height() * scale)
        target = QRectF(box.center().x() - size.width() / 2,
                        box.center().y() - size.height() / 2, size.width(), size.height())
        ratio = self.devicePixelRatioF()
        picture = QPixmap(max(1, round(size.width() * ratio)),
                          max(1, round(size.height() * ratio)))
        picture.setDevicePixelRatio(ratio)
        picture.fill(style.SCENE_BACKGROUND)
        painter = QPainter(picture)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        scene.render(painter, QRectF(0, 0, size.width(), size.height()), source,
                     Qt.AspectRatioMode.IgnoreAspectRatio)
        painter.end()
        self._picture, self._source, self._target = picture, source, target
        self.update()

    def to_scene(self, point: QPointF) -> QPointF:
        """A point of this widget in scene coordinates."""
        if self._target.isEmpty():
            return QPointF()
        fx = (point.x() - self._target.left()) / self._target.width()
        fy = (point.y() - self._target.top()) / self._target.height()
        return QPointF(self._source.left() + fx * self._source.width(),
                       self._source.top() + fy * self._source.height())

    def from_scene(self, rect: QRectF) -> QRectF:
        """A scene rectangle in this widget's coordinates."""
        if self._source.isEmpty():
            return QRectF()
        sx = self._target.width() / self._source.width()
        sy = self._target.height() / self._source.height()
        return QRectF(self._target.left() + (rect.left() - self._source.left()) * sx,
                      self._target.top() + (rect.top() - self._source.top()) * sy,
                      rect.width() * sx, rect.height() * sy)

    def visible_frame(self) -> QRectF:
        """The view's visible part, framed in this widget (clipped to the picture)."""
        view = self.view
        shown = view.mapToScene(view.viewport().rect()).boundingRect()
        return self.from_scene(shown).intersected(self._target)

    def showEvent(self, event: QShowEvent) -> None:
        super().showEvent(event)
        self.redraw()

    def resizeEvent(self, event: QResizeEvent) -> None:
        super().resizeEvent(event)
        if self.isVisible():
            self.redraw()

    def paintEvent(self, event: QPaintEvent) -> None:
        p = QPainter(self)
        p.setRenderHint(QPainter.RenderHint.Antialiasing)
        p.setPen(QPen(style.CARD_BORDER, 1))
        p.setBrush(style.SCENE_BACKGROUND)
        p.drawRoundedRect(QRectF(self.rect()).adjusted(0.5, 0.5, -0.5, -0.5), 6, 6)
        if not self._picture.isNull():
            p.drawPixmap(self._target.topLeft(), self._picture)
            frame = self.visible_frame()
            if not frame.isEmpty():
                fill = QColor(style.CARD_BORDER_SELECTED)
                fill.setAlpha(36)
                p.setBrush(fill)
                p.setPen(QPen(style.CARD_BORDER_SELECTED, 1.5))
                p.drawRect(frame)
        p.end()

    def mousePressEvent(self, event: QMouseEvent) -> None:
        if event.button() == Qt.MouseButton.LeftButton:
            self.view.centerOn(self.to_scene(event.position()))
            event.accept()
            return
        super().mousePressEvent(event)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        if event.buttons() & Qt.MouseButton.LeftButton:
            self.view.centerOn(self.to_scene(event.position()))
            event.accept()
            return
        super().mouseMoveEvent(event)


class GraphFooter(QWidget):
    """The strip under the scene's viewport: the Legend and Overview switches, the legend
    and the overview. The view keeps it outside its viewport (viewport margins), so
    nothing in it ever covers a card."""

    PAD = 4

    def __init__(self, view: GraphView) -> None:
        super().__init__(view)
        self.setAutoFillBackground(True)
        self.side = False
        self.legend_button = self._switch(self.tr("Legend"),
                                          self.tr("Show or hide what the colours mean"))
        self.overview_button = self._switch(
            self.tr("Overview"), self.tr("Show or hide the whole graph in small, to move "
                                         "around a large prosthesis"))
        self.legend = Legend(self)
        self.overview = Overview(view, self)

    def _switch(self, text: str, tip: str) -> QToolButton:
        button = QToolButton(self)
        button.setText(text)
        button.setToolTip(tip)
        button.setCheckable(True)
        button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextBesideIcon)
        button.setArrowType(Qt.ArrowType.RightArrow)
        button.setAutoRaise(True)
        button.toggled.connect(lambda on, b=button: b.setArrowType(
            Qt.ArrowType.DownArrow if on else Qt.ArrowType.RightArrow))
        return button

    def arrange(self, side: bool, width: int, height: int, scene_rect: QRectF) -> int:
        """Place the parts: under the viewport (``side`` False: a strip ``width`` wide;
        returns its height) or beside it (a column ``height`` tall; returns its width)."""
        self.side = side
        pad = self.PAD
        x = pad
        row = 0
        for b in (self.legend_button, self.overview_button):
            hint = b.sizeHint()  # (asked once: a window's first layout arranges ~20 times)
            b.setGeometry(x, pad, hint.width(), hint.height())
            x += hint.width() + pad
            row = max(row, hint.height())
        row += 2 * pad
        show_overview = self.overview.isVisibleTo(self)
        show_legend = self.legend.isVisibleTo(self)
        if side:
            column = max(x, SIDE_WIDTH, self.legend.widest_entry() + 2 * pad)
            inner = column - 2 * pad
            y = row
            if show_overview:
                size = self.overview.size_for(scene_rect, width=inner)
                self.overview.setGeometry(pad, y, size.width(), size.height())
                y += size.height() + pad
            if show_legend:
                lh = self.legend.height_for(inner)
                self.legend.setGeometry(pad, y, inner, lh)
            return column if show_overview or show_legend else x
        strip = row
        right = width - pad
        if show_overview:
            size = self.overview.size_for(scene_rect, height=min(Overview.MAX_SIDE - 52,
                                                                  max(Overview.MIN_SIDE,
                                                                      height // 5)))
            self.overview.setGeometry(right - size.width(), pad, size.width(), size.height())
            right -= size.width() + 2 * pad
            strip = max(strip, size.height() + 2 * pad)
        if show_legend:
            room = max(120, right - x - pad)
            lw = min(self.legend.natural_width(), room)
            lh = self.legend.height_for(lw)
            self.legend.setGeometry(x + pad, pad, lw, lh)
            strip = max(strip, lh + 2 * pad)
        return strip

    def paintEvent(self, event: QPaintEvent) -> None:
        p = QPainter(self)
        p.setPen(QPen(style.CARD_BORDER, 1))
        if getattr(self, "side", False):
            p.drawLine(0, 0, 0, self.height())
        else:
            p.drawLine(0, 0, self.width(), 0)
        p.end()


class GraphView(QGraphicsView):
    """Shows a :class:`BusScene`; owns only view state (zoom, scroll), never the model.

    Under the viewport (in its bottom margin, so they never cover a card) a footer holds
    the legend and the overview, each behind a switch; ``legendVisibleChanged`` follows
    the legend's switch.
    """

    legendVisibleChanged = Signal(bool)

    def __init__(self, scene: BusScene, parent: QWidget | None = None) -> None:
        super().__init__(scene, parent)
        self.setRenderHints(QPainter.RenderHint.Antialiasing
                            | QPainter.RenderHint.TextAntialiasing)
        self.setDragMode(QGraphicsView.DragMode.RubberBandDrag)
        self.setTransformationAnchor(QGraphicsView.ViewportAnchor.AnchorUnderMouse)
        self.setResizeAnchor(QGraphicsView.ViewportAnchor.AnchorViewCenter)
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
        self._pan_from: QPoint | None = None
        self.footer = GraphFooter(self)
        self.legend = self.footer.legend
        self.overview = self.footer.overview
        #: The user's own choice for the overview (None: shown for large graphs only).
        self._overview_choice: bool | None = None
        #: A fit holds until the user zooms or scrolls: when the viewport changes size after
        #: it (a panel or bar of the window appearing) the graph is fitted again, so no card
        #: is left cut off. ``_adjusting``: the view is moving itself (a fit, a resize).
        self._fitted = False
        self._adjusting = False
        shown = QSettings().value(LEGEND_KEY, True)
        shown = shown not in (False, "false", "0", 0)
        self.footer.legend_button.setChecked(shown)
        self.legend.setVisible(shown)
        self.footer.legend_button.toggled.connect(self._legend_toggled)
        self.footer.overview_button.toggled.connect(self._overview_toggled)
        self.overview.setVisible(False)
        scene.rebuilt.connect(self.update_overview_auto)
        scene.doc.systemReset.connect(self.update_overview_auto)  # before a fit, not after
        self.update_overview_auto()

    def bus_scene(self) -> BusScene:
        return self.scene()  # type: ignore[return-value]

    @property
    def zoom(self) -> float:
        return self.transform().m11()

    def set_zoom(self, factor: float) -> None:
        """Absolute zoom, clamped so cards never vanish or fill the screen with one port."""
        factor = max(MIN_ZOOM, min(MAX_ZOOM, factor))
        if not self._adjusting:
            self._fitted = False
        self.scale(factor / self.zoom, factor / self.zoom)
        self.bus_scene().set_view_zoom(self.zoom)
        self._look()
        self.overview.update()

    def zoom_by(self, step: float) -> None:
        self.set_zoom(self.zoom * step)

    def fit_all(self) -> None:
        """Show every card: zoom out as far as that needs, zoom in on a small graph up to
        FIT_MAX_ZOOM (readable, not bloated). The scale is computed from the viewport
        without scroll bars (the legend and overview are outside it, in the footer). The
        fit holds while the viewport changes size, until the user zooms or scrolls."""
        adjusting, self._adjusting = self._adjusting, True
        try:
            self.arrange_footer()
            rect = self.bus_scene().graph_rect()
            if rect.isEmpty():
                return
            rect = rect.adjusted(-FIT_MARGIN, -FIT_MARGIN, FIT_MARGIN, FIT_MARGIN)
            room = self.maximumViewportSize()
            width, height = room.width(), max(40, room.height())
            factor = min(width / rect.width(), height / rect.height())
            # Scroll bars shown before (zoomed in) would stay: the margin left around the
            # graph is narrower than a bar, so with them the graph would not quite fit.
            bars = self.horizontalScrollBarPolicy(), self.verticalScrollBarPolicy()
            self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
            self.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
            self.set_zoom(min(FIT_MAX_ZOOM, factor))
            self.centerOn(rect.center())
            self.setHorizontalScrollBarPolicy(bars[0])
            self.setVerticalScrollBarPolicy(bars[1])
            self._fitted = True
        finally:
            self._adjusting = adjusting

    def settle(self) -> None:
        """Build and draw now what is built and drawn in batches (a large bus's items,
        the cards' pictures, the overview): for a screenshot of the window."""
        self.bus_scene().finish_building()
        self.fit_all()
        self.bus_scene().render_pending()
        if self.overview.isVisible():
            self.overview.redraw()

    def centre_on_item(self, rect: QRectF) -> None:
        self.ensureVisible(rect, 40, 40)

    # -- legend and overview (the footer under the viewport) ---------------------------
    def set_legend_visible(self, on: bool) -> None:
        self.footer.legend_button.setChecked(on)

    def legend_visible(self) -> bool:
        return self.footer.legend_button.isChecked()

    def set_overview_visible(self, on: bool) -> None:
        """The user's choice: it holds over the automatic one from now on."""
        self._overview_choice = on
        self.footer.overview_button.setChecked(on)

    def overview_visible(self) -> bool:
        return self.footer.overview_button.isChecked()

    def update_overview_auto(self) -> None:
        """Shown for a large graph (OVERVIEW_MIN_DEVICES cards or more) unless the user
        chose otherwise."""
        if self._overview_choice is None:
            big = len(self.bus_scene().doc.system.devices) >= OVERVIEW_MIN_DEVICES
            button = self.footer.overview_button
            button.blockSignals(True)
            button.setChecked(big)
            button.setArrowType(Qt.ArrowType.DownArrow if big else Qt.ArrowType.RightArrow)
            button.blockSignals(False)
            self.overview.setVisible(big)
        self.arrange_footer()

    def _legend_toggled(self, on: bool) -> None:
        self.legend.setVisible(on)
        QSettings().setValue(LEGEND_KEY, on)  # remembered for the next session
        self.arrange_footer()
        self.legendVisibleChanged.emit(on)

    def _overview_toggled(self, on: bool) -> None:
        self._overview_choice = on
        self.overview.setVisible(on)
        self.arrange_footer()

    def arrange_footer(self) -> None:
        """Put the footer under or beside the viewport — whichever leaves the graph the
        larger fit zoom — and keep the viewport clear of it."""
        if self.scene() is None:
            return  # being torn down
        frame = self.frameWidth()
        width, height = self.width() - 2 * frame, self.height() - 2 * frame
        graph = self.bus_scene().graph_rect().adjusted(-FIT_MARGIN, -FIT_MARGIN,
                                                       FIT_MARGIN, FIT_MARGIN)
        strip = self.footer.arrange(False, width, height, graph)
        side = False
        if not graph.isEmpty() and width > 2 * SIDE_WIDTH:
            column = self.footer.arrange(True, width, height, graph)
            below = min(width / graph.width(), (height - strip) / graph.height())
            beside = min((width - column) / graph.width(), height / graph.height())
            side = beside > below * 1.05
            if not side:
                self.footer.arrange(False, width, height, graph)
        margins = (0, 0, column, 0) if side else (0, 0, 0, strip)
        m = self.viewportMargins()
        if (m.left(), m.top(), m.right(), m.bottom()) != margins:
            self.setViewportMargins(*margins)
        vp = self.viewport().geometry()
        if side:
            self.footer.setGeometry(vp.right() + 1, frame, column, height)
        else:
            self.footer.setGeometry(frame, vp.bottom() + 1, width, strip)
        self.footer.raise_()
        self.footer.update()

    def _look(self) -> None:
        """Tell the scene where the view looks (half a view's margin around it)."""
        scene = self.scene()
        if not isinstance(scene, BusScene):
            return  # being torn down
        shown = self.mapToScene(self.viewport().rect()).boundingRect()
        w, h = shown.width() / 2, shown.height() / 2
        scene.look_at(shown.adjusted(-w, -h, w, h))

    # -- Qt virtuals ----------------------------------------------------------------
    def scrollContentsBy(self, dx: int, dy: int) -> None:
        super().scrollContentsBy(dx, dy)
        if not self._adjusting:
            self._fitted = False
        self._look()

    def resizeEvent(self, event: QResizeEvent) -> None:
        adjusting, self._adjusting = self._adjusting, True
        try:
            super().resizeEvent(event)
            self._look()
            self.arrange_footer()
        finally:
            self._adjusting = adjusting
        scene = self.scene()
        if not isinstance(scene, BusScene):
            return
        scene.set_pixel_ratio(self.devicePixelRatioF())
        vp = self.viewport().size()
        if vp.height() > 40 and vp.width() > 40:
            scene.layout_aspect = vp.width() / vp.height()
        if self._fitted and not adjusting:
            self.fit_all()

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
