"""Fit to window shows every card, also from a zoomed-in view with its scroll bars, and holds
until the user zooms or scrolls: when the viewport gets smaller after it (a bar of the window
appearing) every card is still shown; after a zoom of the user's, a resize leaves the zoom
alone."""

from __future__ import annotations

from pathlib import Path

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.app.graph.view import GraphView
from pdcp_studio.storage import system_file

ROOT = Path(__file__).resolve().parents[2]


def _view(qtbot) -> tuple[GraphView, BusScene]:
    system = system_file.load_path(ROOT / "resources" / "systems" / "full.json")
    scene = BusScene(Document(system))  # kept: a view does not own its scene
    view = GraphView(scene)
    qtbot.addWidget(view)
    view.resize(1200, 900)
    view.show()
    return view, scene


def _all_shown(view: GraphView, scene: BusScene) -> bool:
    seen = view.mapToScene(view.viewport().rect()).boundingRect()
    return all(seen.contains(card.sceneBoundingRect()) for card in scene.cards.values())


def test_a_fit_holds_when_the_viewport_gets_smaller(qtbot):
    view, scene = _view(qtbot)
    view.fit_all()
    assert _all_shown(view, scene)
    view.resize(1200, 780)
    assert _all_shown(view, scene)


def test_a_fit_from_a_zoomed_in_view_shows_every_card(qtbot):
    view, scene = _view(qtbot)
    view.set_zoom(2.0)  # scroll bars shown: they must not stay and cut the graph's edge
    view.fit_all()
    assert _all_shown(view, scene)
    assert not view.verticalScrollBar().isVisible()


def test_after_the_user_zooms_a_resize_keeps_the_zoom(qtbot):
    view, _scene = _view(qtbot)
    view.fit_all()
    view.zoom_by(1.5)
    zoom = view.zoom
    view.resize(1200, 780)
    assert view.zoom == zoom
