"""Every text the app shows about a change comes from the change's effect
(``engine.effect``), in words — the Write confirmation, the pending changes, the undo text,
a refused link drag — in English and in German; codes only under "Technical detail".

On a real ``sim:transradial`` bus, with the real confirmation dialog (no test hook).
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from PySide6.QtWidgets import QApplication

from pdcp_studio.app import i18n
from pdcp_studio.app.documents import commands
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link

pytestmark = pytest.mark.gui

ROOT = Path(__file__).resolve().parents[2]
TS = ROOT / "resources" / "i18n" / "pdcp_studio_de.ts"
CONTROL = DeviceKey(2641, 513, 201)
HAND = DeviceKey(2641, 769, 301)
POWER = ChannelRef(*HAND, 1)
PINCH = ChannelRef(*HAND, 2)
HAND_LINK = Link(ChannelRef(*CONTROL, 3), POWER)
#: What a prosthetist must never read outside the technical detail: hex, raw bytes, keys.
CODES = re.compile(r"0x[0-9A-Fa-f]+|\b[0-9a-f]{8,}\b|\d+/\d+/\d+|#\d")


def test_every_effect_template_is_marked_for_translation_and_german():
    from pdcp_studio.app.words.effect_words import MARKED
    from pdcp_studio.engine.effect import TEMPLATES, TYPE_WORDS

    assert sorted(MARKED) == sorted((*TEMPLATES, *TYPE_WORDS))  # none forgotten, none extra
    german = {m.findtext("source"): m.findtext("translation")
              for c in ET.parse(TS).getroot().iter("context") if c.findtext("name") == "Effect"
              for m in c.iter("message")}
    assert set(MARKED) <= set(german)
    assert all(german[t] for t in MARKED)


@pytest.fixture
def live(make_window, qtbot):
    """A window live on ``sim:transradial`` that asks with its real confirmation."""
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    assert window.live.is_live
    qtbot.waitUntil(lambda: window.doc.config is not None, timeout=5000)
    yield window
    if window.flow.dialog is not None:
        window.flow.dialog.reject()
    window.live.disconnect_bus()


def _confirmation(window, qtbot):
    """Write to prosthesis, up to its confirmation (shown, its preview in)."""
    assert window.write_pending() is not False
    qtbot.waitUntil(lambda: window.flow.dialog is not None and window.flow.dialog.isVisible(),
                    timeout=20000)
    return window.flow.dialog


def _no_codes(text):
    assert not CODES.search(text), f"codes outside the technical detail: {CODES.findall(text)}"


def test_the_confirmation_speaks_words_and_keeps_codes_under_technical_detail(live, qtbot):
    doc = live.doc
    # A channel type: its control mode in words.
    assert commands.push_channel_field(doc, POWER, "type", 0x9700)
    dialog = _confirmation(live, qtbot)
    words = dialog.words_text()
    _no_codes(words)
    assert "Power grip: control mode position → velocity" in words
    assert "At the next power-on" in words
    assert dialog.store_box.isChecked() and not dialog.store_box.isHidden()
    assert dialog.detail.isHidden()  # collapsed
    assert "parameter 0x01 (type)" in dialog.technical_text()
    dialog.detail_button.click()
    assert not dialog.detail.isHidden()
    dialog.reject()
    qtbot.waitUntil(lambda: not live.flow.busy, timeout=5000)
    # A channel's name: as text, not 120 hex digits.
    assert commands.push_channel_field(doc, PINCH, "descriptor", "Pinch motor")
    dialog = _confirmation(live, qtbot)
    words = dialog.words_text()
    _no_codes(words)
    assert "name “Pinch grip” → “Pinch motor”" in words
    assert "50696e6368" in dialog.technical_text()
    dialog.reject()
    qtbot.waitUntil(lambda: not live.flow.busy, timeout=5000)
    doc.undo_stack.setIndex(0)
    # A link removed: by its channels' names.
    assert commands.push_remove_links(doc, [HAND_LINK]) == 1
    dialog = _confirmation(live, qtbot)
    words = dialog.words_text()
    _no_codes(words)
    assert "Link removed: " in words and "Power grip set point → " in words
    assert "- link 2641/513/201#3 → 2641/769/301#1" in dialog.technical_text()
    dialog.reject()


def test_unticking_store_previews_again_and_says_the_power_on_undoes_it(live, qtbot):
    assert commands.push_remove_links(live.doc, [HAND_LINK]) == 1
    dialog = _confirmation(live, qtbot)
    assert "Stored configuration: stored for the first time" in dialog.words_text()
    dialog.store_box.setChecked(False)
    assert not dialog.write_button.isEnabled()  # the shown effect is not the one written yet
    qtbot.waitUntil(lambda: dialog.write_button.isEnabled(), timeout=10000)
    words = dialog.words_text()
    assert "This change is not stored: the next power-on undoes it." in words
    assert "comes back: " in words and "Stored configuration: unchanged." in words
    # Written as shown: the stored configuration stays as it was (none).
    with qtbot.waitSignal(live.flow.finished, timeout=20000) as got:
        dialog.write_button.click()
    assert got.args[0].written
    session = live.live.bridge.session
    assert HAND_LINK not in session.system().links
    assert not session.read_configuration().configurations


def test_written_with_store_the_configuration_keeps_the_change(live, qtbot):
    assert commands.push_remove_links(live.doc, [HAND_LINK]) == 1
    dialog = _confirmation(live, qtbot)
    with qtbot.waitSignal(live.flow.finished, timeout=20000) as got:
        dialog.write_button.click()
    assert got.args[0].written
    stored = live.live.bridge.session.read_configuration().configurations
    assert len(stored) == 1 and len(stored[0].links) == 4


def test_the_confirmation_in_german(make_window, qtbot):
    app = QApplication.instance()
    i18n.install(app, "de")
    try:
        window = make_window()
        with qtbot.waitSignal(window.ready, timeout=20000):
            window.connect_bus("sim:transradial")
        qtbot.waitUntil(lambda: window.doc.config is not None, timeout=5000)
        assert commands.push_channel_field(window.doc, POWER, "type", 0x9700)
        assert window.doc.undo_stack.undoText().endswith("Regelungsart Position → Geschwindigkeit")
        assert commands.push_remove_links(window.doc, [HAND_LINK]) == 1
        panel = window.pending_panel
        qtbot.waitUntil(lambda: len(panel.changes) == 2, timeout=3000)
        rows = [[panel.view.topLevelItem(i).text(c) for c in (1, 2)] for i in range(2)]
        assert rows[0][1] == "von Hand entfernt"
        assert rows[1][0].endswith("Regelungsart Position → Geschwindigkeit"), rows
        dialog = _confirmation(window, qtbot)
        words = dialog.words_text()
        _no_codes(words)
        assert "Regelungsart Position → Geschwindigkeit" in words
        assert "Beim nächsten Einschalten" in words
        assert "Gespeicherte Konfiguration" in words
        assert "Konfiguration der Prothese speichern" in dialog.store_box.text()
        assert dialog.detail_button.text() == "Technische Einzelheiten"
        dialog.reject()
        window.live.disconnect_bus()
    finally:
        i18n.uninstall(app)


def test_pending_list_and_undo_text_are_in_words(live, qtbot):
    doc = live.doc
    assert commands.push_channel_field(doc, POWER, "type", 0x9700)
    assert live.act_undo.text().startswith("&Undo") or live.act_undo.text()
    text = doc.undo_stack.undoText()
    assert text.endswith("Power grip: control mode position → velocity"), text
    _no_codes(text)
    qtbot.waitUntil(lambda: len(live.pending_panel.changes) == 1, timeout=3000)
    row = live.pending_panel.view.topLevelItem(0).text(1)
    assert row.endswith("Power grip: control mode position → velocity"), row
    _no_codes(row)
    assert commands.push_remove_links(doc, [HAND_LINK]) == 1
    _no_codes(doc.undo_stack.undoText())
    assert "Power grip set point → " in doc.undo_stack.undoText()


def test_a_refused_link_drag_names_parts_and_channels(live):
    from pdcp_studio.app.graph.link_drop import decide_drop

    words = live.scene.words.describe
    # The hand's power grip already has a source: the refusal names both by name.
    drop = decide_drop(live.doc.system, ChannelRef(*CONTROL, 4), POWER, words)
    assert drop.link is None and "already has a source" in drop.reason
    assert "power grip" in drop.reason.lower() and "Multi-grip hand" in drop.reason
    _no_codes(drop.reason)
