"""Drawing a link with the mouse: the scene's gesture, as in Qt's diagramscene example.

The scene hands the gesture its mouse events: a press on a port starts a rubber link,
moves show whether a drop there would link (green) or be refused (red dashed, the reason
in the status line), the release decides (:func:`~pdcp_studio.app.graph.link_drop.decide_drop`)
and a link made is one undo command. Ports only show where they are; they run no gesture.
"""

from __future__ import annotations

from collections.abc import Callable

from PySide6.QtCore import QPointF, QRectF
from PySide6.QtWidgets import QGraphicsScene

from pdcp_studio.app.documents import commands
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph import style
from pdcp_studio.app.graph.items import PortItem
from pdcp_studio.app.graph.link_drop import decide_drop
from pdcp_studio.app.graph.links import DragLinkItem
from pdcp_studio.app.i18n import translate
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link


def _tr(text: str) -> str:
    return translate("BusScene", text)


class LinkDrag:
    """One link drag at a time on ``scene``: the rubber link, the hovered target, and the
    outcome of the last drop (``last_result``: the link or None, the refusal or "")."""

    def __init__(self, scene: QGraphicsScene, doc: Document, say: Callable[[str], None],
                 describe: Callable[[ChannelRef], str]) -> None:
        self._scene = scene
        self._doc = doc
        self._say = say
        self._describe = describe
        self._rubber: DragLinkItem | None = None
        self._target: PortItem | None = None
        self.last_result: tuple[Link | None, str] = (None, "")

    @property
    def active(self) -> bool:
        """A drag is under way (the scene routes the mouse here)."""
        return self._rubber is not None

    def port_at(self, pos: QPointF) -> PortItem | None:
        """The port within reach of ``pos`` (scene coordinates), if any."""
        r = style.PORT_RADIUS + 4
        for item in self._scene.items(QRectF(pos.x() - r, pos.y() - r, 2 * r, 2 * r)):
            if isinstance(item, PortItem):
                return item
        return None

    def begin(self, port: PortItem, pos: QPointF) -> None:
        self.cancel()
        self._rubber = DragLinkItem(port)
        self._scene.addItem(self._rubber)
        self._rubber.follow(pos)
        self._say((_tr("Drag from {channel} to an input to link them") if port.is_output else
                   _tr("Drag from {channel} to an output to link them")).format(
                       channel=self._describe(port.ref)))

    def move(self, pos: QPointF) -> None:
        rubber = self._rubber
        if rubber is None:
            return
        target = self.port_at(pos)
        if target is rubber.start:
            target = None
        if self._target is not None and self._target is not target:
            self._target.set_hover(False)
        self._target = target
        if target is None:
            rubber.set_ok(True)
            rubber.follow(pos)
            return
        drop = decide_drop(self._doc.system, rubber.start.ref, target.ref, self._describe)
        rubber.set_ok(not drop.reason)
        target.set_hover(not drop.reason)
        rubber.follow(target.scenePos())
        if drop.reason:
            self._say(_tr("Cannot link: {0}").format(drop.reason))
        elif drop.output is not None and drop.input is not None:
            self._say(_tr("Release to link {0} → {1}").format(
                self._describe(drop.output), self._describe(drop.input)))

    def end(self, pos: QPointF) -> Link | None:
        """Drop at ``pos``: the link made (one undo step), or None (refused, said why)."""
        rubber = self._rubber
        if rubber is None:
            return None
        self.cancel()
        target = self.port_at(pos)
        drop = decide_drop(self._doc.system, rubber.start.ref,
                           None if target is None or target is rubber.start else target.ref,
                           self._describe)
        link = drop.link
        self.last_result = (link, drop.reason)
        if drop.output is None or drop.input is None:
            self._say(_tr("Link cancelled: release over a port to link"))
        elif link is None:
            self._say(_tr("Cannot link {a} → {b}: {reason}").format(
                a=self._describe(drop.output), b=self._describe(drop.input),
                reason=drop.reason))
        else:
            commands.push_add_link(self._doc, link)
            self._say(_tr("Linked {v0} → {v1}").format(
                v0=self._describe(drop.output), v1=self._describe(drop.input)))
        return link

    def cancel(self) -> None:
        """Drop the rubber link without deciding anything (a rebuild, a new drag)."""
        if self._target is not None:
            self._target.set_hover(False)
            self._target = None
        if self._rubber is not None:
            if self._rubber.scene() is self._scene:
                self._scene.removeItem(self._rubber)
            self._rubber = None
