"""Links drawn as cubic curves from an output port to an input port.

Built-in ``QGraphicsPathItem`` painting and bounds (no Python ``paint`` or
``boundingRect``: the scene calls those on every repaint, and each call from C++ into
Python waits for the GIL, which the bus threads hold often) keep big systems fast and
the GUI responsive during a scan; ``shape()`` is a cached wide stroke so a 2-pixel curve
is still easy to click (used for hit tests only).
Kinds: ``link`` (in the system), ``add`` / ``remove`` (a previewed plan, dashed green /
red), ``unwritten`` (on the prosthesis, removed in the project: a pending removal, dotted
violet), ``drag`` (the rubber link while the user drags from a port). A ``link`` that is
``pending`` (in the project, not yet on the prosthesis) is drawn dash-dotted violet.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from PySide6.QtCore import QPointF, Qt
from PySide6.QtGui import QPainterPath, QPainterPathStroker, QPen
from PySide6.QtWidgets import QGraphicsItem, QGraphicsPathItem

from pdcp_studio.app.graph import style
from pdcp_studio.app.graph.items import USER_TYPE
from pdcp_studio.model.system import Link

if TYPE_CHECKING:
    from pdcp_studio.app.graph.items import PortItem
    from pdcp_studio.app.graph.scene import BusScene

LINK_TYPE = USER_TYPE + 3
HIT_WIDTH = 10.0


def curve(p1: QPointF, p2: QPointF) -> QPainterPath:
    """A horizontal-tangent cubic from an output (p1, leaving right) to an input (p2)."""
    dx = max(50.0, abs(p2.x() - p1.x()) * 0.5)
    path = QPainterPath(p1)
    path.cubicTo(QPointF(p1.x() + dx, p1.y()), QPointF(p2.x() - dx, p2.y()), p2)
    return path


class LinkItem(QGraphicsPathItem):
    """One link (or a previewed one) between two ports."""

    def __init__(self, scene: BusScene, link: Link, kind: str = "link") -> None:
        super().__init__()
        self._scene_ref = scene
        self.link = link
        self.kind = kind
        self.out_port: PortItem | None = None
        self.in_port: PortItem | None = None
        self.conflict = False
        self.missing = False
        self.live = False
        #: In the project but not yet written to the prosthesis (a staged link).
        self.pending = False
        self._shape = QPainterPath()
        if kind == "link":
            self.setFlag(QGraphicsItem.GraphicsItemFlag.ItemIsSelectable, True)
            self.setZValue(-1)
        else:
            self.setZValue(1 if kind == "drag" else -0.5)
            self.setAcceptedMouseButtons(Qt.MouseButton.NoButton)
        self.rebind()

    def type(self) -> int:
        return LINK_TYPE

    def rebind(self) -> None:
        """Find the ports again (after a card rebuilt its rows) and re-route."""
        for port in (self.out_port, self.in_port):
            if port is not None and self in port.links:
                port.links.remove(self)
        self.out_port = self._scene_ref.port(self.link.output)
        self.in_port = self._scene_ref.port(self.link.input)
        for port in (self.out_port, self.in_port):
            if port is not None:
                port.links.append(self)
                port.card.links.add(self)
        self.update_path()
        self.refresh()

    def detach(self) -> None:
        for port in (self.out_port, self.in_port):
            if port is not None:
                if self in port.links:
                    port.links.remove(self)
                port.card.links.discard(self)

    def update_path(self) -> None:
        if self.out_port is None or self.in_port is None:
            return
        path = curve(self.out_port.scenePos(), self.in_port.scenePos())
        self.prepareGeometryChange()
        self.setPath(path)
        stroker = QPainterPathStroker()
        stroker.setWidth(HIT_WIDTH)
        self._shape = stroker.createStroke(path)

    def refresh(self) -> None:
        """Pen from the kind and state; selection wins over everything but preview."""
        if self.kind == "add":
            pen = QPen(style.PREVIEW_ADD, style.PREVIEW_WIDTH, Qt.PenStyle.DashLine)
        elif self.kind == "remove":
            pen = QPen(style.PREVIEW_REMOVE, style.PREVIEW_WIDTH, Qt.PenStyle.DashLine)
        elif self.kind == "unwritten":
            pen = QPen(style.PENDING_REMOVE, style.PREVIEW_WIDTH, Qt.PenStyle.DotLine)
        elif self.isSelected():
            pen = QPen(style.LINK_SELECTED, style.LINK_WIDTH_SELECTED)
        elif self.conflict:
            pen = QPen(style.LINK_CONFLICT, style.LINK_WIDTH + 0.6)
        elif self.pending:
            pen = QPen(style.PENDING, style.PREVIEW_WIDTH, Qt.PenStyle.DashDotLine)
        elif self.missing:
            pen = QPen(style.LINK_MISSING, style.LINK_WIDTH, Qt.PenStyle.DashLine)
        elif self.live:
            pen = QPen(style.LINK_LIVE, style.LINK_WIDTH + 0.6, Qt.PenStyle.DashLine)
            pen.setDashPattern([4.0, 3.0])
            pen.setDashOffset(-self._scene_ref.flow_phase)
        else:
            pen = QPen(style.LINK, style.LINK_WIDTH)
        pen.setCapStyle(Qt.PenCapStyle.RoundCap)
        self.setPen(pen)

    # -- Qt virtuals ----------------------------------------------------------------
    def shape(self) -> QPainterPath:
        return self._shape

    def itemChange(self, change: QGraphicsItem.GraphicsItemChange, value: object) -> object:
        if change == QGraphicsItem.GraphicsItemChange.ItemSelectedHasChanged:
            self.refresh()
        return super().itemChange(change, value)


class DragLinkItem(QGraphicsPathItem):
    """The rubber link that follows the mouse while drawing a new link."""

    def __init__(self, start: PortItem) -> None:
        super().__init__()
        self.start = start
        self.setZValue(5)
        self.setAcceptedMouseButtons(Qt.MouseButton.NoButton)
        self.set_ok(True)

    def set_ok(self, ok: bool) -> None:
        pen = QPen(style.DRAG_OK if ok else style.DRAG_BAD, 2.2)
        if not ok:
            pen.setStyle(Qt.PenStyle.DashLine)
        pen.setCapStyle(Qt.PenCapStyle.RoundCap)
        self.setPen(pen)

    def follow(self, pos: QPointF) -> None:
        a = self.start.scenePos()
        path = curve(a, pos) if self.start.is_output else curve(pos, a)
        self.setPath(path)
