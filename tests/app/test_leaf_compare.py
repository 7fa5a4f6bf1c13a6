"""Compare dialog (offline sources): links only in one source, links in several."""

from __future__ import annotations

import pytest

from pdcp_studio.app.dialogs.compare_dialog import (
    CompareDialog,
    LinkSource,
    compare,
    load_file_sources,
    sources_of_collection,
)
from pdcp_studio.engine import configuration_from_system
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.storage import config_codec, system_file

pytestmark = pytest.mark.gui


@pytest.fixture
def rig(systems_dir):
    return system_file.load_path(systems_dir / "appendix-d.json")


def test_compare_marks_where_each_link_is(rig):
    l1, l2, l3 = rig.links
    rows = compare([LinkSource("A", frozenset({l1, l2})), LinkSource("B", frozenset({l2, l3}))])
    assert [(r.link, r.present) for r in rows] == [(l1, (True, False)), (l2, (True, True)),
                                                   (l3, (False, True))]
    names = ["A", "B"]
    assert [r.status(names) for r in rows] == ["only in A", "in all", "only in B"]
    three = compare([LinkSource("A", frozenset({l1})), LinkSource("B", frozenset({l1})),
                     LinkSource("C", frozenset())])
    assert three[0].status(["A", "B", "C"]) == "in A and B"


def test_collections_give_one_source_per_configuration(resources):
    collection = config_codec.load_path(resources / "configs" / "fig410.pdcfg")
    sources = sources_of_collection("fig410", collection)
    assert [s.name for s in sources] == ["fig410 #1", "fig410 #2"]
    assert [len(s.links) for s in sources] == [2, 1]
    assert sources_of_collection("empty", ConfigCollection()) == [LinkSource("empty", frozenset())]


def test_dialog_compares_screen_file_and_shows_differences(qtbot, rig, tmp_path):
    l1, l2, l3 = rig.links
    other = rig.copy()
    other.remove_link(l3)
    pdcfg = tmp_path / "stored.pdcfg"
    config_codec.save_path(ConfigCollection([configuration_from_system(other)]), pdcfg)
    assert [s.links for s in load_file_sources(pdcfg)] == [frozenset({l1, l2})]

    dialog = CompareDialog(rig)
    qtbot.addWidget(dialog)
    assert dialog.table.rowCount() == 3  # on screen only: every link "present"
    with qtbot.waitSignal(dialog.compared, timeout=5000):
        dialog.load_file(pdcfg)  # read on a worker
    headers = [dialog.table.horizontalHeaderItem(c).text()
               for c in range(dialog.table.columnCount())]
    assert headers == ["Output", "Input", "On screen", "stored.pdcfg", "Status"]
    status = {dialog.table.item(r, 1).text(): dialog.table.item(r, 4).text()
              for r in range(dialog.table.rowCount())}
    # Part and channel names from the on-screen system label the ends.
    assert status["LED terminal, On-off LED"] == "only in On screen"
    assert status["Control unit, Joystick axis"] == "in all"
    assert "1 only in On screen" in dialog.summary.text()

    dialog.set_differences_only(True)
    assert dialog.table.rowCount() == 1
    assert dialog.table.item(0, 0).text() == "Control unit, Fader B / on-off"

    # A system file as the file source; the on-screen system changes too.
    json_file = tmp_path / "other.json"
    system_file.save_path(other, json_file)
    with qtbot.waitSignal(dialog.compared, timeout=5000):
        dialog.load_file(json_file)
    dialog.set_system(other)
    assert dialog.table.rowCount() == 0  # no differences left
    assert [r.everywhere for r in dialog.rows()] == [True, True]


def test_dialog_reports_a_bad_file_and_no_bus(qtbot, rig, tmp_path):
    bad = tmp_path / "bad.pdcfg"
    bad.write_bytes(b"\x01\x01\x00\x0f")
    dialog = CompareDialog(rig)
    qtbot.addWidget(dialog)
    with qtbot.waitSignal(dialog.error, timeout=5000) as blocker:
        dialog.load_file(bad)
    assert "offset" in blocker.args[0] or "record" in blocker.args[0]
    assert "Error" in dialog.summary.text()
    assert not dialog.read_button.isEnabled()
    with qtbot.waitSignal(dialog.error, timeout=1000):
        assert dialog.read_arbitrator() is None


def test_rows_read_apart_and_the_summary_is_in_words(qtbot, rig, tmp_path):
    """The trial: three rows of one part read the same (the channel was cut away) and the
    summary was codes. Each end now says part, channel and what it carries (wrapped, not
    cut), its numbers in the tooltip; the record-by-record codes are the technical part."""
    import re

    from PySide6.QtWidgets import QHeaderView

    other = rig.copy()
    other.remove_link(rig.links[2])
    stored = ConfigCollection([configuration_from_system(other)])
    dialog = CompareDialog(rig)
    qtbot.addWidget(dialog)
    dialog.resize(520, 400)  # narrow: names must still read apart
    dialog.set_file_sources(sources_of_collection("stored.pdcfg", stored), stored)
    dialog.set_arbitrator(ConfigCollection([configuration_from_system(rig)]))
    ends = [(dialog.table.item(r, 0).text(), dialog.table.item(r, 1).text())
            for r in range(dialog.table.rowCount())]
    assert len(set(ends)) == len(ends) == 3
    outputs = [o for o, _i in ends]
    assert len(set(outputs)) == 3 and all(o.count(", ") >= 1 for o in outputs)
    assert dialog.table.wordWrap()
    assert (dialog.table.verticalHeader().sectionResizeMode(0)
            == QHeaderView.ResizeMode.ResizeToContents)
    tip = dialog.table.item(0, 0).toolTip()
    assert outputs[0] in tip and str(rig.links[0].output) in tip
    summary = dialog.summary.text()
    codes = re.compile(r"\d+/\d+/\d+|0x[0-9A-F]{4}|configuration \d+:")
    assert not codes.search(summary), summary
    assert "LED terminal, On-off LED" in summary
    assert "differ in 1 place" in summary
    assert not dialog.details.isVisibleTo(dialog)
    dialog.details_button.setChecked(True)
    assert dialog.details.isVisibleTo(dialog)
    assert codes.search(dialog.details.toPlainText())
