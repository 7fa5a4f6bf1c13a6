"""The inspector, prosthetist first (issue 11): a device shows its product and maker from
the catalogue; a channel shows what a prosthetist sets (control mode, name, inputs) without
wire layouts (u8, pair16, bitmap) or the prescaler code, which wait in a collapsed
"Details for engineers" section with the VID/PID/serial."""

from __future__ import annotations

import re

from PySide6.QtWidgets import QLabel, QWidget

from pdcp_studio.model.refs import ChannelRef
from tests.app.inspector_rig import HAND, transradial_inspector

LAYOUTS = re.compile(r"\b(u8|u16|pair16|bitmap|sn_index|node_ids)\b")


def _visible_text(inspector) -> str:
    form = inspector.widget()
    return "\n".join(w.text() for w in form.findChildren(QLabel) if w.isVisibleTo(form))


def test_a_device_shows_its_product_and_maker(qtbot):
    doc, inspector = transradial_inspector(qtbot)
    doc.select(HAND)
    text = _visible_text(inspector)
    assert "Multi-grip hand by PDCP Studio simulator" in text
    assert inspector.editors["product"].text() == "Multi-grip hand"
    assert inspector.editors["vendor"].text() == "PDCP Studio simulator"
    assert "2641/769/301" not in text and "serial 301" not in text
    details = inspector.editors["details"]
    assert not details.isChecked()
    details.click()
    assert "serial 301" in _visible_text(inspector)


def test_a_channel_keeps_encoding_and_prescaler_in_its_details(qtbot):
    doc, inspector = transradial_inspector(qtbot)
    doc.select(ChannelRef(*HAND, 1))
    text = _visible_text(inspector)
    assert "Input 1" in text and "Control mode" in text
    assert not LAYOUTS.search(text), text
    assert "prescaler" not in text.lower() and "≈" not in text
    mode = inspector.editors["type"]
    assert mode.isVisibleTo(inspector.widget())
    prescaler = inspector.editors["type.prescaler"]
    assert not prescaler.isVisibleTo(inspector.widget())  # collapsed until asked for
    inspector.editors["details"].click()
    assert prescaler.isVisibleTo(inspector.widget())
    assert prescaler.currentText().startswith("code 0 (suggested ×")
    assert LAYOUTS.search(_visible_text(inspector))  # the engineer's detail, one click away
    assert isinstance(inspector.editors["type.detail"], QWidget)
