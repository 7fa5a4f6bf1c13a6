"""The graph's tooltips in a prosthetist's words (issue 11): a planned link says what the
plan does, why and how similar (the plan table's words, not "add: 2/2/5#3 → …"); a card
and its rows say who feeds what, translated, with the codes after them in grey."""

from __future__ import annotations

import re

from PySide6.QtWidgets import QApplication

from pdcp_studio.app import i18n
from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.engine import plan_autoconfigure
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.storage import system_file

HAND = DeviceKey(2641, 769, 301)
CONTROL = DeviceKey(2641, 513, 201)
ENGINE = re.compile(r"\d+/\d+/\d+|#\d|0x[0-9A-F]{4}.*0x|^add:|^remove:|source:|feeds:")


def _scene():
    from pdcp_studio.paths import systems_dir

    system = system_file.load_path(systems_dir() / "transradial.json")
    assert not system.links  # the file as shipped: nothing linked yet
    doc = Document(system)
    return doc, BusScene(doc)


def test_a_planned_link_says_what_the_plan_does_and_why(qtbot):
    doc, scene = _scene()
    plan = plan_autoconfigure(doc.system)
    assert plan.actions
    doc.set_preview(plan)
    tips = [item.toolTip() for item in scene.preview_items]
    assert tips and all(t.startswith("The plan adds this link:") for t in tips), tips
    assert any("Why: it drives a part of the prosthesis" in t for t in tips), tips
    for tip in tips:
        assert not ENGINE.search(tip), tip
        # Each end by its one name: the part, and the channel's descriptor.
        link = tip.splitlines()[1]
        assert link.count(", ") == 2 and " → " in link, link


def test_card_and_row_tooltips_are_worded_and_translated(qtbot):
    _doc, scene = _scene()
    card = scene.cards[HAND]
    row = next(c for c in card.device.channels.values() if c.is_input)
    tip = scene.tooltip_for(card, row)
    assert "Input 1" in tip and "Nothing feeds it" in tip, tip
    assert "source:" not in tip and "feeds:" not in tip
    out = next(c for c in scene.cards[CONTROL].device.channels.values() if c.is_output)
    out_tip = scene.tooltip_for(scene.cards[CONTROL], out)
    assert "Feeds nothing" in out_tip and "0x" in out_tip  # the codes, after the words
    card_tip = scene.tooltip_for(card, None)
    assert "Multi-grip hand" in card_tip and "serial 301" in card_tip
    app = QApplication.instance()
    i18n.install(app, "de")
    try:
        german = scene.tooltip_for(card, row) + scene.tooltip_for(scene.cards[CONTROL], out)
        assert "Eingang 1" in german and "Speist nichts" in german, german
        assert "Input" not in german and "Feeds" not in german and "source" not in german
    finally:
        i18n.uninstall(app)
