"""Dropdown entries are never cut in the middle (issue 11 item 6): every combo box's popup
opens as wide as its longest entry."""

from __future__ import annotations

import pytest
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QComboBox

pytestmark = pytest.mark.gui

LONG = "Multi-grip hand with wrist rotator (serial 302) — spare"


def test_a_narrow_combo_box_opens_a_popup_wide_enough_for_its_entries(make_window, qtbot):
    window = make_window()  # the window installs the application-wide fit
    combo = QComboBox(window)
    combo.addItems(["Hand", LONG])
    combo.setFixedWidth(90)
    combo.show()
    combo.showPopup()
    view = combo.view()
    qtbot.waitUntil(lambda: view.isVisible(), timeout=3000)
    needed = view.fontMetrics().horizontalAdvance(LONG)
    assert view.textElideMode() == Qt.TextElideMode.ElideNone
    assert view.viewport().width() >= needed
    combo.hidePopup()


def test_the_connect_dialogs_and_simulator_combos_get_it_too(make_window, qtbot):
    from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog

    make_window()
    dialog = ConnectDialog()
    qtbot.addWidget(dialog)
    dialog.show()
    page = dialog.pages["can"]
    page.channel.addItem("a-very-long-virtual-channel-name-from-a-vendor-driver-0001")
    page.channel.setFixedWidth(80)
    page.channel.showPopup()
    view = page.channel.view()
    qtbot.waitUntil(lambda: view.isVisible(), timeout=3000)
    assert view.viewport().width() >= view.sizeHintForColumn(0)
    page.channel.hidePopup()
