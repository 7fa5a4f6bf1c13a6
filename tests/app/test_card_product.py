"""Cards and the Simulator panel show the catalogue's product and the kind's icon, never a
VID/PID/serial triple; the numbers are in the tooltip (issue 11 item 1)."""

from __future__ import annotations

import re

import pytest
from PySide6.QtCore import QRectF, Qt
from PySide6.QtGui import QImage, QPainter

from pdcp_studio.app.documents.document import Document
from pdcp_studio.app.graph.scene import BusScene
from pdcp_studio.app.widgets.kind_icons import icon_for
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.storage import system_file

from .trace_imports import wait_for_trace_imports

TRIPLE = re.compile(r"\d+/\d+/\d+")
HAND = DeviceKey(2641, 769, 301)


def _scene(qtbot):
    from pdcp_studio.paths import systems_dir

    system = system_file.load_path(systems_dir() / "transradial.json")
    doc = Document(system)
    return doc, BusScene(doc)


def test_cards_name_the_product_and_keep_the_numbers_for_the_tooltip(qtbot):
    _doc, scene = _scene(qtbot)
    hand = scene.cards[HAND]
    scene.render_pending()
    image = QImage(400, 300, QImage.Format.Format_ARGB32)
    image.fill(0)
    painter = QPainter(image)
    scene.render(painter, QRectF(image.rect()), hand.sceneBoundingRect())
    painter.end()
    texts = hand.texts()
    assert any("Multi-grip hand" in t and "Terminal device" in t for t in texts), texts
    assert not any(TRIPLE.search(t) for t in texts), texts
    tip = scene.tooltip_for(hand, None)
    assert "VID 2641" in tip and "serial 301" in tip


def test_every_shipped_kind_has_its_icon():
    from pdcp_studio.model.catalog import default_catalog

    for entry in default_catalog().entries.values():
        assert entry.icon, entry
        assert not icon_for(DeviceKey(entry.vid, entry.pid, 1)).isNull(), entry.icon


@pytest.mark.gui
def test_the_simulator_panel_and_tree_show_products_not_numbers(make_window, qtbot):
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    panel = window._leaf_docks["sim"].widget()
    qtbot.waitUntil(lambda: panel.tree.topLevelItemCount() == 5, timeout=20000)
    header = panel.tree.headerItem()
    for i in range(panel.tree.topLevelItemCount()):
        item = panel.tree.topLevelItem(i)
        shown = [item.text(c) for c in range(4)] + [header.text(c) for c in range(4)]
        assert not any(TRIPLE.search(t) or "VID" in t for t in shown), shown
        key = item.data(0, Qt.ItemDataRole.UserRole)
        assert f"serial {key.serial}" in item.toolTip(1)
    row = next(panel.tree.topLevelItem(i) for i in range(5)
               if panel.tree.topLevelItem(i).data(0, Qt.ItemDataRole.UserRole) == HAND)
    assert row.text(1) == "Multi-grip hand"
    tree = window.tree
    assert all(not tree.topLevelItem(i).icon(0).isNull()
               for i in range(tree.topLevelItemCount()))
    wait_for_trace_imports(qtbot)
    window.live.disconnect_bus()


def test_a_cut_name_keeps_its_serial_number(qtbot):
    from PySide6.QtGui import QFont, QFontMetricsF

    from pdcp_studio.app.graph.items import elide_keeping_serial

    metrics = QFontMetricsF(QFont())
    label = "Multi-grip hand with wrist rotator (serial 302)"
    narrow = metrics.horizontalAdvance(label) * 0.7
    cut = elide_keeping_serial(label, 302, metrics, narrow)
    assert cut.endswith(" (serial 302)") and cut.startswith("Multi-grip") and "…" in cut
    assert metrics.horizontalAdvance(cut) <= narrow + 1
    assert elide_keeping_serial(label, 302, metrics, 10_000) == label
    plain = elide_keeping_serial("EMG electrode (wrist flexors)", 101, metrics, 60)
    assert plain.startswith("EMG") and plain.endswith("…")


def test_the_tree_cuts_a_twin_in_the_middle_so_its_serial_stays(qtbot):
    import copy

    from PySide6.QtWidgets import QStyleOptionViewItem

    from pdcp_studio.app.docks.tree_panel import DeviceTree

    doc, _the_scene = _scene(qtbot)
    hand = doc.system.devices[HAND]
    spare = copy.deepcopy(hand)
    spare.serial = 302
    doc.system.add_device(spare)
    doc.set_system(doc.system)
    tree = DeviceTree(doc)
    qtbot.addWidget(tree)
    delegate = tree.itemDelegateForColumn(0)
    modes = {}
    for i in range(tree.topLevelItemCount()):
        item = tree.topLevelItem(i)
        option = QStyleOptionViewItem()
        delegate.initStyleOption(option, tree.indexFromItem(item, 0))
        modes[item.text(0)] = option.textElideMode
    assert modes["Hand (serial 302)"] == Qt.TextElideMode.ElideMiddle
    assert modes["Hand (serial 301)"] == Qt.TextElideMode.ElideMiddle
    assert modes["Control unit"] == Qt.TextElideMode.ElideRight
