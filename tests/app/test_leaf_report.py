"""The fitting report: A4 portrait pages with the devices' serials, the links, the checksum, the
date, page numbers, the patient reference and operator, and each change's effect and next power-on.

Read back with QtPdf (the PDF as a viewer sees it), not with an external tool.
"""

from __future__ import annotations

import datetime as dt
import os

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


def _a4_portrait(path) -> bool:
    """Every page is A4 portrait (210 × 297 mm = 595 × 842 points)."""
    doc = QPdfDocument()
    assert doc.load(str(path)) == QPdfDocument.Error.None_
    sizes = [doc.pagePointSize(p) for p in range(doc.pageCount())]
    return all(abs(s.width() - 595.3) < 1.5 and abs(s.height() - 841.9) < 1.5 for s in sizes)


def _crc_of_encoding(collection: ConfigCollection) -> int:
    """Independently of the decoder: the CRC of the bytes before the checksum record."""
    data = config_codec.dumps(collection)
    assert data[-6] == config_codec.CHECKSUM and data[-3] == config_codec.END
    assert int.from_bytes(data[-5:-3], "little") == crc16_ccitt_false(data[:-6])
    return crc16_ccitt_false(data[:-6])


def test_report_has_serials_links_checksum_and_date(qtbot, tmp_path, systems_dir):
    system = system_file.load_path(systems_dir / "appendix-d.json")
    tree = load_profile_tree(user_dir=False)
    expected = _crc_of_encoding(ConfigCollection([configuration_from_system(system)]))
    assert configuration_checksum(system) == expected
    graph = QImage(800, 400, QImage.Format.Format_RGB32)
    graph.fill(QColor("white"))
    out = write_report(tmp_path / "fitting.pdf", system, tree, graph,
                       date=dt.date(2026, 11, 21))
    pages, text = _pdf_text(qtbot, out)
    assert pages >= 1 and _a4_portrait(out)
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
    assert pages >= 1 and _a4_portrait(out)
    assert f"0x{_crc_of_encoding(stored):04X}" in text
    assert "3 links in 2 set-ups" in text


def test_a_32_device_rig_runs_onto_numbered_a4_pages(qtbot, tmp_path):
    from pdcp_studio.bus.sim.rigs import large_system

    system = large_system()
    out = write_report(tmp_path / "large.pdf", system, load_profile_tree(user_dir=False))
    pages, text = _pdf_text(qtbot, out)
    assert pages > 1 and _a4_portrait(out)
    assert f"Page {pages} of {pages}" in text
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
    assert pages >= 1 and _a4_portrait(out)
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


# -- Issue 26 item 7: pages, words whole, the swap counted right, effect and power-on ------
HAND = (2641, 769, 301)
SPARE = (2641, 769, 302)


def broken_words(doc) -> list[str]:
    """Lines of the laid-out report that end inside a word ("Produ|ct")."""
    out = []
    doc.size()  # lays the document out
    block = doc.begin()
    while block.isValid():
        layout, text = block.layout(), block.text()
        for i in range(layout.lineCount() - 1):
            end = layout.lineAt(i).textStart() + layout.lineAt(i).textLength()
            if 0 < end < len(text) and text[end - 1].isalnum() and text[end].isalnum():
                out.append(f"{text[max(0, end - 12):end]}|{text[end:end + 12]}")
        block = block.next()
    return out


def test_the_word_check_sees_a_word_broken_in_a_narrow_column(qapp):
    from PySide6.QtGui import QTextDocument

    doc = QTextDocument()
    doc.setTextWidth(300)
    doc.setHtml("<table width=100%><tr><td width=92%>a</td><td width=8%>Hardware</td></tr>"
                "</table>")
    assert broken_words(doc)


def _part(t):
    return {"vid": t[0], "pid": t[1], "serial": t[2]}


def _key(t):
    from pdcp_studio.model.refs import DeviceKey

    return DeviceKey(*t)


def _link_doc(out, index_out, inp, index_in):
    return {"output": {"vid": out[0], "pid": out[1], "serial": out[2], "index": index_out},
            "input": {"vid": inp[0], "pid": inp[1], "serial": inp[2], "index": index_in}}


CU = (2641, 513, 201)
#: The swap on sim:transradial as recorded: the prosthesis had linked the spare on its own
#: when it was plugged in, so the write removed the gone hand's links and added none.
_KEPT = [_link_doc((2641, 257, 101), 1, CU, 1), _link_doc((2641, 257, 102), 1, CU, 2)]
_OLD = [_link_doc(CU, 3 + i, HAND, 1 + i) for i in range(3)]
_NEW = [_link_doc(CU, 3 + i, SPARE, 1 + i) for i in range(3)]


def test_a_swap_that_made_three_links_counts_three_added_three_removed(qapp):
    from pdcp_studio.app import report_entries as entries

    recorded = {"id": 5, "action": "replace a part", "outcome": {"status": "applied"},
                "links_before": _KEPT + _OLD + _NEW, "links_after": _KEPT + _NEW}
    assert entries.change_words(recorded) == "3 links added, 3 removed"
    assert entries.replaced_pairs(recorded) == [(_key(HAND), _key(SPARE))]
    # With the replacement recorded (another session adds "replaced"), the same count.
    told = {**recorded, "replaced": [{"old": _part(HAND),
                                      "new": _part(SPARE)}]}
    assert entries.change_words(told) == "3 links added, 3 removed"
    # Not a swap: links before and after, never the other way round.
    plain = {"action": "write to prosthesis", "links_before": _KEPT,
             "links_after": _KEPT + _OLD[:1], "outcome": {"status": "applied"}}
    assert entries.change_words(plain) == "1 link added, 0 removed"


def test_a_swap_after_the_prosthesis_relinked_on_its_own_counts_from_the_stored_set_up(
        qapp, systems_dir):
    """The write came after the prosthesis had dropped the gone hand's links and linked
    the spare itself: the links before and after the write are the same, and the old
    hand's links are those the stored configuration held before."""
    from pdcp_studio.app import report_entries as entries
    from pdcp_studio.engine import configuration_from_system, plan_autoconfigure

    system = system_file.load_path(systems_dir / "transradial.json")
    plan_autoconfigure(system).apply(system)
    assert {lk.input.device for lk in system.links} >= {_key(HAND)}
    stored = config_codec.to_json(ConfigCollection([configuration_from_system(system)]))
    earlier = [{"id": 1, "action": "new fitting: store configuration",
                "configuration_after": stored}]
    swap = {"id": 2, "action": "replace a part", "outcome": {"status": "applied"},
            "links_before": _KEPT + _NEW, "links_after": _KEPT + _NEW}
    assert entries.replaced_pairs(swap, earlier) == [(_key(HAND), _key(SPARE))]
    assert entries.change_words(swap, earlier) == "3 links added, 3 removed"


def test_effect_and_next_power_on_are_shown_and_an_old_entry_says_it_predates_them(
        systems_dir):
    import html as html_mod
    import re

    from pdcp_studio.app.documents.document import load_profile_trees, tree_for
    from pdcp_studio.app.report import FittingInfo, report_html
    from pdcp_studio.engine import plan_autoconfigure

    system = system_file.load_path(systems_dir / "transradial.json")
    plan_autoconfigure(system).apply(system)
    tree = tree_for(load_profile_trees(user_dir=False), system)
    old = {"id": 1, "time": "2026-11-28T09:00:00Z", "action": "config write",
           "outcome": {"status": "applied"}, "links_before": [], "links_after": []}
    new = {"id": 2, "time": "2026-11-28T09:05:00Z", "action": "set parameter",
           "outcome": {"status": "applied"}, "links_before": [], "links_after": [],
           "effect": {"text": ["Hand, channel 1: control mode position → speed"],
                      "technical": ["2641/769/301#1 parameter 0x01: 0x9300 → 0x9700"]},
           "next_power_on": {"links_added": [_OLD[0]], "links_removed": [],
                             "text": ["the control unit links the hand's power grip again."]},
           "replaced": [{"old": _part(HAND),
                         "new": _part(SPARE)}]}
    html = report_html(system, tree, checksum=0x1234, fitting=FittingInfo(
        "P-9", "A. Prosthetist", dt.datetime(2026, 11, 28, 9, 10), "sim:transradial",
        [old, new]))
    body, _, detail = html.partition("Technical detail")
    text = html_mod.unescape(" ".join(re.sub(r"<[^>]+>", " ", body).split()))
    assert "Hand, channel 1: control mode position → speed" in text
    assert "the control unit links the hand's power grip again." in text
    assert "At the next power-on: At the next power-on" not in text
    assert "This entry was recorded before PDCP Studio predicted the next power-on" in text
    assert "Hand replaced by Multi-grip hand" in text  # no twin here: no serial number
    assert "(serial 302)" not in text
    assert set(re.findall(r"0x[0-9A-Fa-f]+", text)) == {"0x1234"}
    assert "0x9300 → 0x9700" in detail and "next power-on adds" in detail
    # the section is whole: the links' codes follow its last sentence
    after = detail.split("profile codes:", 1)[1].split("Entry 1:")[0].split("Entry 2:")[0]
    assert system.links and after.count("<li>") == len(system.links)
    assert after.count("(type 0x") == 2 * len(system.links)


@pytest.mark.parametrize("lang", ["en", "de"])
def test_a_live_swap_report_is_a4_numbered_with_patient_operator_and_whole_words(
        make_window, qtbot, tmp_path, lang):
    """sim:transradial: the hand swapped for the spare through the change road, then the
    report as the window writes it (Write fitting report / the wizard's Save)."""
    from PySide6.QtWidgets import QApplication

    from pdcp_studio.app import i18n
    from pdcp_studio.app.report import report_document
    from pdcp_studio.app.wizards import logic

    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:transradial")
    session = window.live.bridge.session
    try:
        assert session.transact(logic.store_change(session.system())).written
        session.unplug(_key(HAND))
        qtbot.waitUntil(lambda: not session.system().devices[_key(HAND)].present, timeout=20000)
        session.plug(_key(SPARE))
        qtbot.waitUntil(lambda: _key(SPARE) in session.system().devices
                        and session.system().devices[_key(SPARE)].present, timeout=20000)
        session.wait_settled(5)
        system, stored = session.system(), session.read_configuration()
        change = logic.replacement_change(
            system, logic.replacement_plan(system, stored, [_key(SPARE)]))
        window.transactions.set_patient_reference("P-2026-042")
        assert session.transact(change, patient=window.patient_reference()).ok
        window.live.refresh()
        qtbot.waitUntil(lambda: _key(SPARE) in window.doc.system.devices, timeout=20000)
        window.history_panel.refresh()
        qtbot.waitUntil(lambda: any(e.get("action") == "replace a part"
                                    for e in window.fitting_info().changes), timeout=20000)
        app = QApplication.instance()
        if lang == "de":
            i18n.install(app, "de")
        try:
            out = tmp_path / f"swap-{lang}.pdf"
            assert window.write_fitting_report(out)
            info = window.fitting_info()
            doc = report_document(window.doc.system, window.doc.tree, fitting=info)
        finally:
            if lang == "de":
                i18n.uninstall(app)
    finally:
        window.live.disconnect_bus()
    assert info.patient == "P-2026-042" and info.prosthetist
    pdf = QPdfDocument()
    assert pdf.load(str(out)) == QPdfDocument.Error.None_
    pages = pdf.pageCount()
    assert _a4_portrait(out)
    word = "Page {0} of {1}" if lang == "en" else "Seite {0} von {1}"
    for p in range(pages):
        assert word.format(p + 1, pages) in " ".join(pdf.getAllText(p).text().split())
    text = " ".join(_pdf_text(qtbot, out)[1].split())
    assert "P-2026-042" in text and info.prosthetist in text
    swap = ("3 links added, 3 removed" if lang == "en"
            else "3 Verbindungen hinzugefügt, 3 entfernt")
    assert swap in text
    assert broken_words(doc) == []
    assert "Produ ct" not in text and "electro de" not in text
    # one part per row: the device table has five columns, never three groups side by side
    html = doc.toHtml()
    assert html.count(">Firmware<") + html.count(">Firmware <") <= 1
    if os.environ.get("PDCP_REPORT_SHOTS"):  # for looking at: every page as a PNG
        import shutil
        import subprocess

        if shutil.which("pdftoppm"):
            subprocess.run(["pdftoppm", "-png", "-r", "60", str(out),
                            os.path.join(os.environ["PDCP_REPORT_SHOTS"], f"report-{lang}")],
                           check=True)


def test_a_recorded_effect_reads_in_the_reports_language_once_and_line_by_line(qapp):
    """The screenshot trial: the report said "At the next power-on: At the next power-on, …"
    and ran the prediction's lines together. A recorded effect is read back and said in the
    user's language, each line its own."""
    from pdcp_studio.app import i18n
    from pdcp_studio.app import report_entries as entries
    from pdcp_studio.engine.effect import effect_of
    from pdcp_studio.engine.modes import plan_autoconfigure
    from pdcp_studio.paths import resources_dir
    from pdcp_studio.storage.system_file import load_path

    system = load_path(resources_dir() / "systems" / "transradial.json")
    plan_autoconfigure(system).apply(system)
    effect = effect_of(system, links_after=system.links[1:])
    entry = {"id": 1, "effect": effect.to_json(), "next_power_on": effect.power_on_json()}
    lines = entries.power_on_lines(entry)
    assert sum(ln.startswith("At the next power-on") for ln in lines) == 1 and len(lines) >= 2
    i18n.install(qapp, "de")
    try:
        german = entries.power_on_lines(entry) + entries.effect_lines(entry)
    finally:
        i18n.uninstall(qapp)
    assert any(ln.startswith("Beim nächsten Einschalten") for ln in german), german
    assert any(ln.startswith("Verbindung entfernt") for ln in german), german
