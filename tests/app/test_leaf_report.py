"""The fitting report: one PDF page with the devices' serials, the links, the checksum, the date.

Read back with QtPdf (the PDF as a viewer sees it), not with an external tool.
"""

from __future__ import annotations

import datetime as dt

import pytest
from PySide6.QtGui import QColor, QImage
from PySide6.QtPdf import QPdfDocument

from pdcp_studio.app.report import configuration_checksum, write_report
from pdcp_studio.engine import configuration_from_system
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.protocol.crc import crc16_ccitt_false
from pdcp_studio.storage import config_codec, system_file
from pdcp_studio.storage.profile_trees import load_profile_tree

pytestmark = pytest.mark.gui


def _pdf_text(qtbot, path) -> tuple[int, str]:
    doc = QPdfDocument()
    assert doc.load(str(path)) == QPdfDocument.Error.None_
    text = "\n".join(doc.getAllText(p).text() for p in range(doc.pageCount()))
    return doc.pageCount(), text


def _crc_of_encoding(collection: ConfigCollection) -> int:
    """Independently of the decoder: the CRC of the bytes before the checksum record."""
    data = config_codec.dumps(collection)
    assert data[-6] == config_codec.CHECKSUM and data[-3] == config_codec.END
    assert int.from_bytes(data[-5:-3], "little") == crc16_ccitt_false(data[:-6])
    return crc16_ccitt_false(data[:-6])


def test_report_is_one_page_with_serials_links_checksum_and_date(qtbot, tmp_path, systems_dir):
    system = system_file.load_path(systems_dir / "appendix-d.json")
    tree = load_profile_tree(user_dir=False)
    expected = _crc_of_encoding(ConfigCollection([configuration_from_system(system)]))
    assert configuration_checksum(system) == expected
    graph = QImage(800, 400, QImage.Format.Format_RGB32)
    graph.fill(QColor("white"))
    out = write_report(tmp_path / "fitting.pdf", system, tree, graph,
                       date=dt.date(2026, 11, 21))
    pages, text = _pdf_text(qtbot, out)
    assert pages == 1
    assert f"0x{expected:04X}" in text
    assert "2026-11-21" in text
    for device in system.devices.values():
        assert device.label in text
    assert "Control unit" in text and "Joystick" in text
    assert "Links (3)" in text
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]


def test_report_prints_a_given_stored_configuration_checksum(qtbot, tmp_path, resources,
                                                             systems_dir):
    system = system_file.load_path(systems_dir / "transradial.json")
    stored = config_codec.load_path(resources / "configs" / "fig410.pdcfg")
    out = write_report(tmp_path / "r.pdf", system, load_profile_tree(user_dir=False),
                       collection=stored)
    pages, text = _pdf_text(qtbot, out)
    assert pages == 1
    assert f"0x{_crc_of_encoding(stored):04X}" in text
    assert "3 links in 2 set-ups" in text


def test_a_32_device_rig_still_fits_on_one_page(qtbot, tmp_path):
    from pdcp_studio.bus.sim.rigs import large_system

    system = large_system()
    out = write_report(tmp_path / "large.pdf", system, load_profile_tree(user_dir=False))
    pages, text = _pdf_text(qtbot, out)
    assert pages == 1
    compact = text.replace(" ", "").replace("\n", "")
    for device in system.devices.values():  # every serial is printed
        assert str(device.serial) in compact


def test_unwritable_path_raises(tmp_path, systems_dir):
    system = system_file.load_path(systems_dir / "appendix-d.json")
    with pytest.raises(OSError):
        write_report(tmp_path / "no-such-dir" / "r.pdf", system,
                     load_profile_tree(user_dir=False))


def test_the_report_speaks_plainly_with_the_detail_in_its_own_section(systems_dir):
    """Issue 11: no raw keys, internal codes, hex without words or command names in the
    report's body; the engineer's codes are in the Technical detail section at the end."""
    import re

    from pdcp_studio.app.report import FittingInfo, action_words, report_html
    from pdcp_studio.engine import plan_autoconfigure
    from pdcp_studio.storage.profile_trees import load_profile_trees, tree_for

    system = system_file.load_path(systems_dir / "transradial.json")
    plan_autoconfigure(system).apply(system)
    tree = tree_for(load_profile_trees(user_dir=False), system)
    info = FittingInfo("P-1", "A. Prosthetist", None, "sim:transradial",
                       [{"id": 1, "action": "apply autoconfigure", "outcome":
                         {"status": "applied"}, "plan": {"actions": [{"op": "add"}]}},
                        {"id": 2, "action": "config write", "outcome": {"status": "failed"}}])
    html = report_html(system, tree, fitting=info, checksum=0x1234)
    body, _, detail = html.partition("Technical detail")
    assert detail and "0x2220" in detail and "VID 0x0A51" in detail
    text = re.sub(r"<[^>]+>", " ", body)
    assert "Check number" in text and "0x1234" in text  # hex, with its words
    hexes = set(re.findall(r"0x[0-9A-Fa-f]+", text))
    assert hexes == {"0x1234"}, hexes
    for raw in ("terminal-unconnected", "required-unmet", "apply autoconfigure",
                "config write", "pdcp-studio", "CRC-16"):
        assert raw not in text, raw
    assert "Autoconfigure carried out" in text and "Stored set-up written" in text
    assert "Power Grip" in text and "2641 / 769 / 301" in text
    assert action_words("undo write to prosthesis") == "Undone: Changes written to the prosthesis"


def test_the_german_build_prints_a_german_report(qtbot, tmp_path, systems_dir):
    """Issue 11: the report goes through Qt's translation like the window: with the German
    translation installed, every heading of the printed page is German and none English."""
    from PySide6.QtWidgets import QApplication

    from pdcp_studio.app import i18n
    from pdcp_studio.app.report import FittingInfo

    system = system_file.load_path(systems_dir / "transradial.json")
    info = FittingInfo("P-7", "A. Prosthetist", dt.datetime(2026, 11, 24, 9, 30), "sim:x",
                       [{"id": 1, "action": "config write", "outcome": {"status": "applied"},
                         "verified": True}])
    app = QApplication.instance()
    i18n.install(app, "de")
    try:
        out = write_report(tmp_path / "de.pdf", system, load_profile_tree(user_dir=False),
                           fitting=info)
    finally:
        i18n.uninstall(app)
    pages, text = _pdf_text(qtbot, out)
    flat = " ".join(text.split())
    assert pages == 1
    for german in ("PDCP-Anpassungsbericht", "Datum:", "Prothese:", "Unterschrift:",
                   f"Geräte ({len(system.devices)})", f"Verbindungen ({len(system.links)})",
                   "Gespeicherte Einrichtung", "Änderungen in dieser Sitzung (1)",
                   "Prüfungen", "Technische Einzelheiten", "Ausgang", "Eingang",
                   "Gespeicherte Einrichtung geschrieben", "ausgeführt, geprüft"):
        assert german in flat, german
    for english in ("fitting report", "Date:", "Prosthesis:", "Signature:", "Devices (",
                    "Links (", "Stored set-up", "Changes made", "Checks", "Technical detail",
                    "Output", "Firmware version", "every check passed", "channel ",
                    "Generated by", "link(s)", "links"):
        assert english not in flat, english
    # and back in English afterwards: the translation is looked up when the report is made
    english_html = write_report(tmp_path / "en.pdf", system, load_profile_tree(user_dir=False))
    assert "Stored set-up" in " ".join(_pdf_text(qtbot, english_html)[1].split())
