"""Captures dropped, chosen in Open… or in the recent files are the same files (issue 27
item 2): one list, the reader's, gzipped too; MF4 offered and named as missing when
python-can's mf4 extra is not installed; the status line says how the opening ended."""

from __future__ import annotations

import gzip
from pathlib import Path

import pytest
from PySide6.QtCore import QMimeData, QPointF, Qt, QUrl
from PySide6.QtGui import QDropEvent

from pdcp_studio.app.trace.files.formats import SUFFIXES, is_capture_name, mf4_readable, open_filter
from pdcp_studio.app.window.controllers.desktop import dropped_files

pytestmark = pytest.mark.gui

CAPTURES = Path(__file__).parents[1] / "data" / "captures"


def _drop(paths: list[Path]) -> QDropEvent:
    mime = QMimeData()
    mime.setUrls([QUrl.fromLocalFile(str(p)) for p in paths])
    event = QDropEvent(QPointF(5, 5), Qt.DropAction.CopyAction, mime,
                       Qt.MouseButton.NoButton, Qt.KeyboardModifier.NoModifier)
    event._mime = mime  # kept alive with the event
    return event


def test_a_drop_takes_what_open_offers(qapp, tmp_path):
    names = ["a.asc", "b.asc.gz", "c.blf", "d.trc", "e.log.gz", "f.csv", "g.db", "h.mf4",
             "system.json", "config.pdcfg"]
    paths = [tmp_path / n for n in names]
    taken = dropped_files(_drop([*paths, tmp_path / "notes.txt", tmp_path / "x.gz"]))
    assert taken == paths
    offered = open_filter().split(";;")[0]
    for suffix in SUFFIXES:
        assert f"*{suffix}" in offered and is_capture_name(f"x{suffix}")
        if suffix != ".mf4":
            assert f"*{suffix}.gz" in offered and is_capture_name(f"x{suffix}.gz")


@pytest.mark.skipif(mf4_readable(), reason="python-can's mf4 extra is installed here")
def test_mf4_is_named_as_missing_in_open_and_in_the_trace(make_window, qtbot, tmp_path):
    assert "needs python-can's mf4 extra, not installed (*.mf4)" in open_filter()
    path = tmp_path / "logger.mf4"
    path.write_bytes(b"MDF     4.10    " + bytes(48))
    window = make_window()
    window.desktop.open_dropped(path)
    dock = window.bus_docks.monitor_dock()
    qtbot.waitUntil(lambda: dock.problem is not None, timeout=20_000)
    assert "python-can's mf4 extra, which is not installed" in dock.problem_label.text()
    assert "mf4 extra" in window.statusBar().currentMessage()


def test_a_dropped_gzipped_capture_opens_in_the_trace_and_the_status_line_follows(
        make_window, qtbot, tmp_path):
    path = tmp_path / "session.asc.gz"
    path.write_bytes(gzip.compress((CAPTURES / "sim-transradial-midsession.asc").read_bytes()))
    window = make_window()
    assert window.desktop.open_dropped(path)
    dock = window.bus_docks.monitor_dock()
    assert window.statusBar().currentMessage() == "Opening capture session.asc.gz…"
    with qtbot.waitSignal(dock.loaded, timeout=20_000):
        pass
    assert dock.model.rowCount() == 408
    assert dock.banner.text().endswith("· Vector ASC, gzipped")
    assert window.statusBar().currentMessage() == "Opened capture session.asc.gz"


def test_a_capture_that_cannot_be_read_ends_the_opening_in_the_status_line(
        make_window, qtbot, tmp_path):
    path = tmp_path / "broken.blf"
    path.write_bytes(b"LOGG" + bytes(40))
    window = make_window()
    window.desktop.open_dropped(path)
    dock = window.bus_docks.monitor_dock()
    qtbot.waitUntil(lambda: dock.problem is not None, timeout=20_000)
    said = window.statusBar().currentMessage()
    assert str(path) in said and "Opening" not in said
