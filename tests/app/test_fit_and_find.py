"""Fit to window fits both ways; Go to device selects and centres a device."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QPoint, QRect

from pdcp_studio.app.graph.view import FIT_MAX_ZOOM

ROOT = Path(__file__).resolve().parents[2]
SMALL = ROOT / "resources" / "systems" / "thesis-test1.json"


def _global(widget):
    """A widget's rectangle in global (screen) coordinates."""
    return QRect(widget.mapToGlobal(QPoint(0, 0)), widget.size())


def _visible(view):
    return view.mapToScene(view.viewport().rect()).boundingRect()


def test_fit_shows_every_card_of_the_large_rig(make_window, qtbot):
    window = make_window(size=(1600, 1000))
    with qtbot.waitSignal(window.ready, timeout=30000):
        window.connect_bus("sim:large")
    qtbot.waitUntil(lambda: len(window.scene.cards) == 32, timeout=30000)
    qtbot.wait(300)
    window.view.fit_all()
    qtbot.wait(50)
    seen = _visible(window.view)
    view = window.view
    assert view.legend.isVisible()
    legend = _global(view.legend)
    for key, card in window.scene.cards.items():
        assert seen.contains(card.sceneBoundingRect()), (key, seen, card.sceneBoundingRect())
        on_screen = view.mapFromScene(card.sceneBoundingRect()).boundingRect()
        on_screen.translate(view.viewport().mapToGlobal(QPoint(0, 0)))
        assert not on_screen.intersects(legend), (key, on_screen, legend)  # not covered


def test_fit_zooms_in_on_a_small_graph_up_to_a_readable_limit(make_window, qtbot):
    window = make_window(SMALL, size=(1600, 1000))
    window.view.set_zoom(0.3)
    window.view.fit_all()
    assert window.view.zoom > 1.0
    assert window.view.zoom <= FIT_MAX_ZOOM + 1e-9
    seen = _visible(window.view)
    assert all(seen.contains(c.sceneBoundingRect()) for c in window.scene.cards.values())


def test_go_to_device_selects_and_centres_it(make_window, qtbot):
    from PySide6.QtCore import Qt

    window = make_window(size=(1600, 1000))
    with qtbot.waitSignal(window.ready, timeout=30000):
        window.connect_bus("sim:large")
    qtbot.waitUntil(lambda: len(window.scene.cards) == 32, timeout=30000)
    window.view.set_zoom(1.5)
    window.view.centerOn(0, 0)
    assert window.act_find.shortcut().toString()  # Ctrl+F (the platform's Find key)
    window.act_find.trigger()
    finder = window.device_finder
    qtbot.keyClicks(finder.field, "hand 7")
    assert [finder.results.item(i).text() for i in range(finder.results.count())] == ["Hand 7"]
    key = finder.results.item(0).data(Qt.ItemDataRole.UserRole)
    assert (key.vid, key.pid, key.serial) == (2641, 769, 1063)
    qtbot.keyClick(finder.field, Qt.Key.Key_Return)
    assert window.doc.selection == key
    card = window.scene.cards[key].sceneBoundingRect()
    centre = window.view.mapToScene(window.view.viewport().rect().center())
    assert _visible(window.view).contains(card)
    assert abs(centre.y() - card.center().y()) < 5
    hbar = window.view.horizontalScrollBar()  # a card at the edge: centred as far as it goes
    assert abs(centre.x() - card.center().x()) < 5 or hbar.value() == hbar.maximum()
    assert not finder.isVisible()
    # By numbers too.
    from pdcp_studio.app.docks.device_finder import device_matches

    assert [lbl for _k, lbl in device_matches(window.doc.system, "2641/769/1063")] == ["Hand 7"]
