"""The link drag is the scene's gesture (as in Qt's diagramscene): a press on a port, the
moves and the release reach the scene, which draws the rubber link and makes one undo step;
the card under the port does not move."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QEvent, QPointF, Qt
from PySide6.QtWidgets import QGraphicsSceneMouseEvent

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph.links import DragLinkItem
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.model.refs import ChannelRef, Direction
from pdcp_studio.model.system import Channel, Device, Link, System

pytestmark = pytest.mark.gui

OUT, OUT2 = ChannelRef(10, 1, 1, 1), ChannelRef(10, 1, 1, 2)
IN = ChannelRef(10, 3, 1, 1)


def _scene() -> tuple[Document, BusScene]:
    sensor = Device(10, 1, 1, name="EMG sensor")
    sensor.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4222))
    sensor.add_channel(Channel(2, Direction.OUTPUT, type=0x9000, profile=0x4224))
    hand = Device(10, 3, 1, name="Hand")
    hand.add_channel(Channel(1, Direction.INPUT, type=0x9300, profile=0x4222))
    doc = Document(System([sensor, hand]), tree=None)
    return doc, BusScene(doc)


def _mouse(scene: BusScene, kind: QEvent.Type, pos: QPointF) -> QGraphicsSceneMouseEvent:
    event = QGraphicsSceneMouseEvent(kind)
    event.setScenePos(pos)
    event.setButton(Qt.MouseButton.LeftButton)
    event.setButtons(Qt.MouseButton.LeftButton)
    event.setAccepted(False)
    if kind == QEvent.Type.GraphicsSceneMousePress:
        scene.mousePressEvent(event)
    elif kind == QEvent.Type.GraphicsSceneMouseMove:
        scene.mouseMoveEvent(event)
    else:
        scene.mouseReleaseEvent(event)
    return event


def _drag(scene: BusScene, a: ChannelRef, b: ChannelRef) -> None:
    start, end = scene.port(a).scenePos(), scene.port(b).scenePos()
    assert _mouse(scene, QEvent.Type.GraphicsSceneMousePress, start).isAccepted()
    assert any(isinstance(i, DragLinkItem) for i in scene.items())
    _mouse(scene, QEvent.Type.GraphicsSceneMouseMove, (start + end) / 2)
    _mouse(scene, QEvent.Type.GraphicsSceneMouseMove, end)
    _mouse(scene, QEvent.Type.GraphicsSceneMouseRelease, end)
    assert not any(isinstance(i, DragLinkItem) for i in scene.items())


def test_a_drag_from_port_to_port_is_one_undo_step_and_moves_no_card(qtbot):
    doc, scene = _scene()
    card = scene.cards[OUT.device]
    where = card.pos()
    _drag(scene, IN, OUT)  # from the input back to the output: linked output first
    assert scene.last_link_result == (Link(OUT, IN), "")
    assert doc.system.has_link(Link(OUT, IN)) and doc.undo_stack.count() == 1
    assert card.pos() == where
    doc.undo_stack.undo()
    assert not doc.system.has_link(Link(OUT, IN))


def test_a_refused_drop_changes_nothing_and_says_why(qtbot):
    doc, scene = _scene()
    said: list[str] = []
    scene.statusMessage.connect(said.append)
    _drag(scene, OUT, IN)
    _drag(scene, OUT2, IN)
    link, reason = scene.last_link_result
    assert link is None and "already has a source" in reason
    assert doc.undo_stack.count() == 1 and said[-1].startswith("Cannot link")
