"""The inspector's Profile box shows the profile's name, not a hex code (issue 11): the code
is in the box's tooltip and in "Details for engineers"."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QComboBox, QLabel

from pdcp_studio.model.refs import ChannelRef
from tests.app.inspector_rig import HAND, transradial_inspector

POWER_GRIP = 0x2220



def _shown(inspector) -> list[str]:
    """Every label and box text the user sees (collapsed sections excluded)."""
    form = inspector.widget()
    texts = [w.text() for w in form.findChildren(QLabel) if w.isVisibleTo(form)]
    texts += [c.currentText() for c in form.findChildren(QComboBox) if c.isVisibleTo(form)]
    return texts


def test_the_profile_box_shows_the_name_and_keeps_the_code_for_engineers(qtbot):
    doc, inspector = transradial_inspector(qtbot)
    ref = ChannelRef(*HAND, 1)
    assert doc.channel(ref).profile == POWER_GRIP
    doc.select(ref)
    combo = inspector.editors["profile"]
    assert combo.currentText() == "Terminal Device › Grip › Power Grip"
    assert not [t for t in _shown(inspector) if "0x" in t]  # no hex in the main part
    assert "0x2220" in combo.lineEdit().toolTip()
    i = combo.findText(combo.currentText())
    assert combo.itemData(i) == POWER_GRIP
    assert "0x2220" in combo.itemData(i, Qt.ItemDataRole.ToolTipRole)
    assert not any("(0x" in combo.itemText(j) for j in range(combo.count()))
    inspector.editors["details"].click()
    assert "0x2220" in _shown(inspector)  # the engineer's detail, one click away
    # Choosing by name and typing a code both still work.
    j = next(j for j in range(combo.count()) if combo.itemData(j) == 0x2240)
    combo.setCurrentIndex(j)
    combo.activated.emit(j)
    assert doc.channel(ref).profile == 0x2240
    combo = inspector.editors["profile"]
    combo.setCurrentText("0x2220")
    combo.lineEdit().editingFinished.emit()
    assert doc.channel(ref).profile == POWER_GRIP
    qtbot.waitUntil(lambda: inspector.editors["profile"].currentText()
                    == "Terminal Device › Grip › Power Grip", timeout=3000)  # shown by name


def test_a_profile_the_tree_does_not_name_says_so(qtbot):
    from pdcp_studio.model import profile as prof

    doc, inspector = transradial_inspector(qtbot)
    named = {value for value, _node in doc.tree.walk()}
    unnamed = next(v for v in range(0x2222, 0x3000, 2)
                   if v not in named and prof.is_well_formed(v))
    ref = ChannelRef(*HAND, 1)
    doc.channel(ref).profile = unnamed
    doc.select(ref)
    combo = inspector.editors["profile"]
    assert combo.currentText() == "Not in the profile tree"
    assert prof.fmt(unnamed) in combo.lineEdit().toolTip()
    combo.lineEdit().editingFinished.emit()  # left as it is: the profile stays
    assert doc.channel(ref).profile == unnamed and doc.undo_stack.count() == 0
    assert inspector.errors["profile"].isHidden()


def test_no_terminal_profile_reads_none(qtbot):
    doc, inspector = transradial_inspector(qtbot)
    ref = next(ChannelRef(*HAND, ch.index) for ch in doc.device(HAND).inputs())
    doc.channel(ref).terminal_profile = 0
    doc.select(ref)
    combo = inspector.editors["terminal_profile"]
    assert combo.currentText() == "(none)" and combo.currentData() == 0


def test_the_profile_box_in_german(qtbot, qapp):
    from pdcp_studio.app import i18n

    i18n.install(qapp, "de")
    try:
        doc, inspector = transradial_inspector(qtbot)
        ref = ChannelRef(*HAND, 1)
        doc.select(ref)
        tip = inspector.editors["profile"].lineEdit().toolTip()
        assert tip.startswith("Terminal Device › Grip › Power Grip: Profilcode 0x2220")
    finally:
        i18n.uninstall(qapp)
