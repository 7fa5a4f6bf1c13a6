"""A capture opened in the trace (issue 27 items 2-4): read by the one reader with its own
node map (saved beside it, or learned from its traffic; never the live session's), its
verdict in a banner, a foreign capture shown as plain CAN, every frame kind as what it is,
damage and load errors said where the rows would be, Stop heard at once on any file."""

from __future__ import annotations

import os
import shutil
import time
from pathlib import Path

import pytest
from PySide6.QtCore import Qt

from pdcp_studio.app.trace.dock import MonitorDock
from pdcp_studio.model.refs import ChannelRef

pytestmark = pytest.mark.gui

CAPTURES = Path(__file__).parents[1] / "data" / "captures"
MIDSESSION = CAPTURES / "sim-transradial-midsession.asc"  # a simulator capture, no node map
FOREIGN = ["candump-car.log", "vector-car.blf", "canalyzer-car-cp1252.asc", "pcan-car-2.2.trc"]
PDCP_WORDS = ("Bind Device", "undecodable", "Beacon", "Channel data", "→BA", "BA→", "unattributed")


def _dock(qtbot) -> MonitorDock:
    dock = MonitorDock()
    qtbot.addWidget(dock)
    dock.resize(1200, 600)
    dock.show()
    return dock


def _open(qtbot, dock: MonitorDock, path: Path) -> None:
    with qtbot.waitSignal(dock.loaded, timeout=20_000):
        dock.load_capture(path)


def _cells(dock: MonitorDock) -> list[tuple[str, ...]]:
    return [dock.model.row_texts(r) for r in range(dock.model.rowCount())]


def test_a_pdcp_capture_without_its_node_map_decodes_with_what_its_traffic_teaches(qtbot):
    dock = _dock(qtbot)
    _open(qtbot, dock, MIDSESSION)
    assert dock.banner.isVisible()
    assert dock.banner.text().startswith(
        "PDCP capture · node map inferred from traffic: 4 devices, 5 channels · Vector ASC")
    assert dock.verdict is not None and dock.verdict.verdict == "pdcp"
    rows = _cells(dock)
    assert len(rows) == 408
    assert {r[3] for r in rows} <= {"Device Beacon", "Channel data", "Arbitrator Beacon"}
    undecodable = sum("undecodable" in " ".join(r) for r in rows)
    assert undecodable <= len(rows) // 100  # as the live session decodes it (<= 1 %)
    assert next(r[2] for r in rows if r[1] == "0x205") == "#5 data"


def test_a_capture_opened_while_connected_keeps_its_own_node_map(qtbot):
    """The live session's node 1 is an output channel; in the capture node 1 is a device
    that beacons: the capture's own reading wins (a beacon is never shown as channel data)."""
    dock = _dock(qtbot)
    output = ChannelRef(1, 10, 4, 1)
    dock.feed.learn_output(1, (output, ()))  # what the live session's system says
    _open(qtbot, dock, MIDSESSION)
    first = dock.model.row_texts(0)
    assert first[1:4] == ("0x001", "#1→BA", "Device Beacon")
    assert not any(r[1] == "0x001" and r[3] == "Channel data" for r in _cells(dock))
    dock.show_live()
    assert 1 in dock.channel_nodes  # the live map itself is untouched


def test_a_capture_with_its_node_map_beside_it_says_so(qtbot, tmp_path):
    path = tmp_path / "session.asc"
    shutil.copy(CAPTURES / "pdcp-session.asc", path)
    from pdcp_studio.bus.trace.monitor import FrameDecoder, read_capture, write_node_map

    decoder = FrameDecoder()
    for msg in read_capture(path):
        decoder.decode_message(msg)
    write_node_map(path, decoder.node_map())
    dock = _dock(qtbot)
    _open(qtbot, dock, path)
    assert dock.banner.text() == "PDCP capture · node map from session.asc.nodemap.json · Vector ASC"


def test_a_capture_with_its_set_up_says_so(qtbot):
    dock = _dock(qtbot)
    _open(qtbot, dock, CAPTURES / "pdcp-session.asc")
    assert dock.banner.text() == ("PDCP capture · node map from the capture's set-up: "
                                  "2 devices, 1 channel · Vector ASC")


@pytest.mark.parametrize("name", FOREIGN)
def test_a_foreign_capture_is_shown_as_plain_can(qtbot, name):
    dock = _dock(qtbot)
    _open(qtbot, dock, CAPTURES / name)
    assert dock.banner.text().startswith("Not PDCP: shown as plain CAN frames · ")
    header = [dock.model.headerData(c, Qt.Orientation.Horizontal) for c in range(5)]
    assert header == ["Time", "ID", "Kind", "DLC", "Data"]
    assert dock.view.isColumnHidden(5)  # no meaning column
    rows = _cells(dock)
    assert rows and not any(word in " ".join(r) for r in rows for word in PDCP_WORDS)
    kinds = {r[2] for r in rows}
    assert "data frame" in kinds and "extended frame" in kinds
    extended = {r[1] for r in rows if r[2] == "extended frame"}
    assert "0x00000123" in extended and "0x18FEF100" in extended  # 0x123 was extended
    assert all(r[1] == "—" for r in rows if r[2] == "error frame")
    for r in rows:
        if r[2] == "data frame":
            assert int(r[3]) == len(r[4].split())  # DLC and data agree
    stats = [dock.stats_model.row_texts(i) for i in range(dock.stats_model.rowCount())]
    assert all(s[1] == "" for s in stats)  # no PDCP node
    assert not any(word in " ".join(s) for s in stats for word in PDCP_WORDS)
    assert {"0x00000123", "0x18FEF100"} <= {s[0] for s in stats}


def test_the_remote_and_fd_frames_of_a_foreign_capture_are_what_they_are(qtbot):
    dock = _dock(qtbot)
    _open(qtbot, dock, CAPTURES / "canalyzer-car-cp1252.asc")
    rows = _cells(dock)
    remote = [r for r in rows if r[2] == "remote frame"]
    assert remote and remote[0][1:] == ("0x3C2", "remote frame", "8", "", "")
    fd = [r for r in rows if r[2] == "FD frame"]
    assert fd and fd[0][1] == "0x2A1" and fd[0][3] == "12"


def test_odd_frames_in_a_pdcp_capture_are_shown_as_what_they_are(qtbot, tmp_path):
    car = (CAPTURES / "canalyzer-car-cp1252.asc").read_bytes().decode("cp1252").splitlines()
    odd = [next(line for line in car if mark in line) for mark in ("ErrorFrame", " r 8", "123x")]
    lines = (CAPTURES / "pdcp-session.asc").read_text().splitlines()
    end = lines.index("End TriggerBlock")
    path = tmp_path / "pdcp-odd.asc"  # a car's error, remote and extended frames among PDCP's
    path.write_text("\n".join(lines[:end] + odd + lines[end:]) + "\n")
    dock = _dock(qtbot)
    _open(qtbot, dock, path)
    assert dock.banner.text().startswith("PDCP capture")
    rows = _cells(dock)
    by_kind = {r[3]: r for r in rows if r[3].endswith(" frame")}
    assert set(by_kind) == {"error frame", "remote frame", "extended frame"}
    assert by_kind["error frame"][1:3] == ("—", "")
    assert by_kind["remote frame"][1:3] == ("0x3C2", "")
    assert by_kind["remote frame"][5] == "DLC 8"
    assert by_kind["extended frame"][1:3] == ("0x00000123", "")
    stats = {row[0]: row for row in (dock.stats_model.row_texts(i)
                                     for i in range(dock.stats_model.rowCount()))}
    assert stats["0x00000123"][1] == "" and stats["—"][1] == ""  # no PDCP sender
    assert not any("undecodable" in " ".join(r) for r in by_kind.values())
    assert sum(r[3].startswith("undecodable") for r in rows) <= 1  # as without them (0x209)


def test_an_empty_capture_says_so(qtbot, tmp_path):
    path = tmp_path / "empty.asc"
    path.write_bytes(b"")
    dock = _dock(qtbot)
    _open(qtbot, dock, path)
    assert dock.banner.text() == "Empty capture: no frames · empty"
    assert dock.model.rowCount() == 0


def test_a_damaged_capture_shows_its_frames_up_to_the_cut_and_says_where(qtbot, tmp_path):
    path = tmp_path / "cut.asc"
    path.write_bytes(MIDSESSION.read_bytes()[:9000])  # cut in the middle of line 211
    dock = _dock(qtbot)
    _open(qtbot, dock, path)
    assert dock.model.rowCount() == 205
    first, second = dock.banner.text().split("\n")
    assert first.startswith("PDCP capture · node map inferred from traffic")
    assert second == (f"Cut short: {path}: line 211: the file ends in the middle of a line "
                      "(cut short?) — the 205 frames before it are shown")


@pytest.mark.parametrize(("content", "words"), [
    (b"date Sat Nov 28 22:33:50.470 2026\nbase hex  timestamps absolute\nBegin Triggerblock\n"
     b" 0.000000 943  601             Rx   d 7 01 01\n",
     "line 4: a frame cut short: DLC 7 with 2 data bytes"),
    (b"LOGG" + b"\x00" * 40, "offset"),
    (b"just some text, no capture\n", "not a readable capture"),
])
def test_a_capture_that_cannot_be_read_says_why_where_its_rows_would_be(qtbot, tmp_path,
                                                                         content, words):
    path = tmp_path / "broken.asc"
    path.write_bytes(content)
    dock = _dock(qtbot)
    with qtbot.waitSignal(dock.error, timeout=20_000) as said:
        dock.load_capture(path)
    assert str(path) in said.args[0] and words in said.args[0]
    qtbot.waitUntil(lambda: dock.loading.worker is None, timeout=5000)
    assert dock.pages.currentWidget() is dock.problem_label
    assert dock.problem_label.isVisible()
    assert said.args[0] in dock.problem_label.text()
    assert dock.count_label.text() == "not read"
    assert not dock.stop_load_button.isVisibleTo(dock)  # not "opening" forever
    _open(qtbot, dock, MIDSESSION)  # the next capture shows its rows again
    assert dock.pages.currentWidget() is dock.splitter and dock.problem is None


def test_a_2_gb_file_of_nul_bytes_and_a_line_without_end_are_refused_at_once(qtbot, tmp_path):
    nul = tmp_path / "zeros.asc"
    with open(nul, "wb") as f:
        f.truncate(2 << 30)  # sparse: 2 GB of NUL bytes, nothing written
    endless = tmp_path / "endless.asc"
    endless.write_bytes(b"date Sat Nov 28 22:33:50.470 2026\n" + b"A" * (4 << 20))
    dock = _dock(qtbot)
    for path, words in ((nul, "not a readable capture"), (endless, "longer than 65,536")):
        started = time.monotonic()
        with qtbot.waitSignal(dock.error, timeout=10_000) as said:
            dock.load_capture(path)
        assert time.monotonic() - started < 3.0
        assert words in said.args[0]


def test_a_fifo_is_refused_in_words_never_waited_on(qtbot, tmp_path):
    fifo = tmp_path / "pipe.asc"
    os.mkfifo(fifo)
    dock = _dock(qtbot)
    errors: list[str] = []
    dock.error.connect(errors.append)
    started = time.monotonic()
    assert dock.load_capture(fifo) is None
    assert time.monotonic() - started < 0.5
    assert errors and "a pipe or a device, not a capture file" in errors[0]
    assert dock.pages.currentWidget() is dock.problem_label


def test_stop_is_heard_within_a_fifth_of_a_second_among_millions_of_comment_lines(
        qtbot, tmp_path):
    path = tmp_path / "comments.asc"
    with open(path, "w") as f:
        f.write((CAPTURES / "pdcp-session.asc").read_text().split("End TriggerBlock")[0])
        f.write("// a comment\n" * 2_000_000)  # 26 MB of lines that are no frame
        f.write("End TriggerBlock\n")
    dock = _dock(qtbot)
    worker = dock.load_capture(path)
    assert worker is not None
    qtbot.wait(500)
    assert worker.is_running  # still among the comments (looking for its first frames)
    started = time.monotonic()
    dock.cancel_load()
    assert worker.wait(0.2), "the reader did not stop within 0.2 s"
    assert time.monotonic() - started < 0.25
    qtbot.waitUntil(lambda: dock.loading.worker is None, timeout=2000)
    assert dock.banner.text() == "Stopped before the first frames were read"
    assert not dock.stop_load_button.isVisibleTo(dock)


def test_stop_keeps_the_frames_read(qtbot, tmp_path):
    path = tmp_path / "long.asc"
    head, tail = MIDSESSION.read_text().split("End TriggerBlock")
    body = head.splitlines(keepends=True)
    frames = [line for line in body if " Rx " in line]
    with open(path, "w") as f:
        f.writelines(body)
        f.writelines(frames * 400)  # ~160,000 frames
        f.write("End TriggerBlock" + tail)
    dock = _dock(qtbot)
    worker = dock.load_capture(path)
    qtbot.waitUntil(lambda: dock.model.rowCount() > 0, timeout=10_000)
    dock.cancel_load()
    assert worker.wait(0.2)
    qtbot.waitUntil(lambda: dock.loading.worker is None, timeout=2000)
    shown = dock.model.rowCount()
    assert 0 < shown < 160_000
    assert dock.banner.text().endswith(f"Stopped: the first {shown:,} frames are shown")


def test_the_banner_and_plain_columns_speak_german(qtbot, qapp):
    from pdcp_studio.app import i18n

    i18n.install(qapp, "de")
    try:
        dock = _dock(qtbot)
        _open(qtbot, dock, CAPTURES / "candump-car.log")
        assert dock.banner.text() == "Kein PDCP: als einfache CAN-Nachrichten gezeigt · candump log"
        assert dock.model.headerData(2, Qt.Orientation.Horizontal) == "Art"
        assert dock.model.row_texts(0)[2] == "Datennachricht"
        _open(qtbot, dock, MIDSESSION)
        assert dock.banner.text().startswith(
            "PDCP-Mitschnitt · Knotenzuordnung aus dem Verkehr erschlossen: 4 Geräte, 5 Kanäle")
    finally:
        i18n.uninstall(qapp)


def test_saving_an_opened_capture_keeps_each_frames_kind_and_its_own_node_map(qtbot, tmp_path):
    from pdcp_studio.bus.trace.files.capture import read_capture
    from pdcp_studio.bus.trace.files.nodemap import read_node_map

    dock = _dock(qtbot)
    dock.feed.learn_output(1, (ChannelRef(1, 10, 4, 1), ()))  # the live session's map
    _open(qtbot, dock, CAPTURES / "canalyzer-car-cp1252.asc")
    out = tmp_path / "car.asc"
    with qtbot.waitSignal(dock.error, timeout=20_000) as said:
        dock.save(out)
    assert said.args[0] == (
        f"Saving {out}: the file was written without some frames: 1 CAN FD frames longer "
        "than 8 bytes not written: the trace keeps 8 data bytes a frame (save from the "
        "capture file itself)")
    back = list(read_capture(out))
    original = [m for m in read_capture(CAPTURES / "canalyzer-car-cp1252.asc")
                if not (m.is_fd and m.dlc > 8)]
    assert [(m.arbitration_id, m.is_extended_id, m.is_remote_frame, m.is_error_frame,
             m.dlc if not m.is_error_frame else 0) for m in back] == \
        [(m.arbitration_id, m.is_extended_id, m.is_remote_frame, m.is_error_frame,
          m.dlc if not m.is_error_frame else 0) for m in original]
    assert read_node_map(out) is None  # a foreign capture has no node map to keep
    trc = tmp_path / "car.trc"
    with qtbot.waitSignal(dock.error, timeout=20_000) as said:
        dock.save(trc)
    assert "python-can's TRC writer cannot keep 1 remote frames, 1 error frames" in said.args[0]

    _open(qtbot, dock, MIDSESSION)
    mine = tmp_path / "mid.blf"
    with qtbot.waitSignal(dock.saved, timeout=20_000):
        dock.save(mine)
    saved = read_node_map(mine)
    assert saved is not None and "1/10/4" not in str(saved)  # not the live session's map
    _open(qtbot, dock, mine)
    assert dock.banner.text() == "PDCP capture · node map from mid.blf.nodemap.json · Vector BLF"
    assert next(r for r in _cells(dock) if r[1] == "0x001")[3] == "Device Beacon"
