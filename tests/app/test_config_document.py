"""The configuration document (issue 12): a .pdcfg opens in its own window — open, select,
edit, undo, save, reopen identical — with names, checks and a fit that judge only what a
configuration holds. Real files, a real main window, pytest-qt."""

from __future__ import annotations

import json
import struct
from pathlib import Path

import pytest
from PySide6.QtWidgets import QMessageBox

from pdcp_studio.app.configuration.window import (
    ConfigWindow,
    configuration_names,
    system_for_configuration,
)
from pdcp_studio.app.documents.config_document import ConfigDocument
from pdcp_studio.engine import configuration_from_system, plan_autoconfigure
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
    UnknownRecord,
)
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.paths import systems_dir
from pdcp_studio.storage import config_codec, system_file

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = systems_dir() / "transradial.json"
HAND = DeviceKey(2641, 769, 301)


def _transradial_collection() -> ConfigCollection:
    """The transradial fitting as configuration 1; configuration 2 without the hand's
    second input (a patient with two terminal devices stores one per device)."""
    system = system_file.load_path(TRANSRADIAL)
    if not system.links:
        plan_autoconfigure(system).apply(system)
    first = configuration_from_system(system)
    second = StoredConfiguration(2, [StoredLink(lk.input, lk.output, n) for n, lk in
                                     enumerate(first.links[:-1], 1)])
    return ConfigCollection([first, second])


def _with_unknown_records(coll: ConfigCollection) -> bytes:
    """The collection's bytes with records of codes PDCP Studio does not know at every
    level, written as newer firmware would (before the checksum is added again)."""
    rec = UnknownRecord
    coll.unknown = (rec(0x20, 1),)
    cfg = coll.configurations[0]
    cfg.unknown = (rec(0x21, 2),)
    first = cfg.links[0]
    from dataclasses import replace

    cfg.links[0] = replace(first, unknown=(rec(0x22, 3),),
                           input=replace(first.input, unknown=(rec(0x23, 4), rec(0x23, 5))),
                           output=replace(first.output, unknown=(rec(0x24, 6),)))
    return config_codec.dumps(coll)


@pytest.fixture
def main_window(make_window):
    return make_window(TRANSRADIAL, size=(1200, 800))


@pytest.fixture
def pdcfg(tmp_path) -> Path:
    path = tmp_path / "patient.pdcfg"
    path.write_bytes(_with_unknown_records(_transradial_collection()))
    return path


def _open(main, path) -> ConfigWindow:
    main.config_windows = []
    assert main.open_path(path)
    (window,) = main.config_windows
    window.quiet = True
    return window


def _close(window: ConfigWindow) -> None:
    window.doc.mark_saved()
    window.close()


def test_open_shows_the_configurations_in_their_own_window(main_window, pdcfg, qtbot):
    before = set(main_window.doc.system.links)
    window = _open(main_window, pdcfg)
    try:
        assert window.config_list.count() == 2
        assert window.config_list.currentRow() == 0
        assert window.doc.path == pdcfg and not window.doc.is_dirty
        # The main window stays on its prosthesis; its plans use the opened configurations.
        assert set(main_window.doc.system.links) == before
        assert main_window.doc.config is window.doc.collection
        cfg = window.doc.configuration()
        assert window.links.rowCount() == len(cfg.links) == 5
        assert len(window.scene.link_items) == 5
        # Names come from the open prosthesis: no "Device 2641/257/101", no "#1 output".
        labels = {card.device.label for card in window.scene.cards.values()}
        names = {d.name for d in main_window.doc.system.devices.values()}
        assert labels <= names and not any(lb.startswith("Device ") for lb in labels)
        # A configuration saved from a working fitting has nothing to report.
        assert window.findings == []
        assert "6 records from newer firmware or tools kept" in window.info.text()
    finally:
        _close(window)


def test_select_edit_undo_save_reopen_identical(main_window, pdcfg, tmp_path, qtbot):
    original = pdcfg.read_bytes()
    window = _open(main_window, pdcfg)
    doc = window.doc
    try:
        start = config_codec.to_json(doc.collection)
        window.config_list.setCurrentRow(1)
        assert doc.current == 1 and window.links.rowCount() == 4
        window.config_list.setCurrentRow(0)
        assert doc.current == 0

        # Edit a stored channel's type and profile: every record of that channel follows.
        out_ref = doc.configuration().links[0].output.ref
        window.edit_channel("output", 0, 0x5000, 0x2110)
        assert doc.is_dirty
        edited = [lk.output for lk in doc.configuration().links if lk.output.ref == out_ref]
        assert edited and all((c.type, c.profile) == (0x5000, 0x2110) for c in edited)
        assert edited[0].unknown == (UnknownRecord(0x24, 6),)  # kept through the edit
        # Remove a link, add one back, then configurations: add, duplicate, move, remove.
        window.select_links([4])
        window.remove_selected_links()
        assert len(doc.configuration().links) == 4
        gone = config_codec.loads(original).configurations[0].links[4]
        doc.add_link(gone.output, gone.input)
        assert len(doc.configuration().links) == 5
        window.btn_dup_cfg.click()
        assert [c.index for c in doc.collection.configurations] == [1, 2, 3]
        assert doc.current == 1 and doc.collection.configurations[1].unknown == (
            UnknownRecord(0x21, 2),)
        window.btn_down_cfg.click()
        assert doc.current == 2 and window.config_list.currentRow() == 2
        window.btn_add_cfg.click()
        assert len(doc.collection.configurations) == 4 and doc.current == 3
        assert window.links.rowCount() == 0
        window.btn_del_cfg.click()
        assert len(doc.collection.configurations) == 3

        # Undo everything: back to the file as opened; redo it all again.
        steps = doc.undo_stack.count()
        assert steps == 7
        while doc.undo_stack.canUndo():
            window.act_undo.trigger()
        assert config_codec.to_json(doc.collection) == start and not doc.is_dirty
        while doc.undo_stack.canRedo():
            window.act_redo.trigger()
        edited_json = config_codec.to_json(doc.collection)
        assert edited_json != start

        # Save, reopen: identical, unknown records in place.
        saved = tmp_path / "saved.pdcfg"
        assert window.save_to(saved) and not doc.is_dirty
        assert window.windowTitle().startswith("saved.pdcfg")
        again = ConfigDocument.open(saved)
        assert config_codec.to_json(again.collection) == edited_json
        assert config_codec.dumps(again.collection) == saved.read_bytes()
    finally:
        _close(window)


def test_open_then_save_unchanged_keeps_every_byte(main_window, pdcfg, qtbot):
    original = pdcfg.read_bytes()
    window = _open(main_window, pdcfg)
    try:
        assert window.save()
        assert pdcfg.read_bytes() == original
    finally:
        _close(window)


def test_a_thesis_era_file_with_unknown_records_gains_only_a_checksum(main_window, tmp_path,
                                                                      qtbot):
    pairs = [(1, 1), (0x30, 9), (2, 1), (3, 1), (4, 1),
             (5, 0), (7, 0x5200), (8, 0x2110), (9, 2), (10, 2), (11, 2), (12, 5), (0x20, 0x1234),
             (6, 0), (7, 0x5000), (8, 0x2120), (9, 1), (10, 2), (11, 2), (12, 4), (15, 0)]
    body = b"".join(struct.pack("<BH", c, v) for c, v in pairs)
    path = tmp_path / "old.pdcfg"
    path.write_bytes(body)
    window = _open(main_window, path)
    try:
        assert window.save()
        head = body[:-3]
        assert path.read_bytes() == head + struct.pack(
            "<BHBH", 16, config_codec.crc16_ccitt_false(head), 15, 0)
    finally:
        _close(window)


def test_checks_name_the_links_and_selecting_a_finding_selects_them(main_window, tmp_path,
                                                                    qtbot):
    a = StoredChannel(1, 2, 2, 4, 0x5000, 0x2120)
    b = StoredChannel(1, 2, 2, 5, 0x5000, 0x1100)
    inp = StoredChannel(2, 2, 2, 6, 0x7300, 0x1220)
    path = tmp_path / "two-sources.pdcfg"
    config_codec.save_path(ConfigCollection([StoredConfiguration(1, [
        StoredLink(inp, a, 1), StoredLink(inp, b, 2)])]), path)
    window = _open(main_window, path)
    try:
        codes = [f.code for f in window.findings]
        assert codes[0] == "two-sources"
        first = window.checks.item(0)
        assert first.text().startswith("Error: Thesis test node (serial 6), channel 2 is given "
                                       "more than one source (links 1, 2)")
        assert "input 2/2/6#2 is given 2 sources" in first.toolTip()  # the engineer's words
        window._on_finding(first)
        assert window.selected_links() == [0, 1]
        window.select_links([1])
        assert window.graph_doc.selection.output == b.ref  # highlighted in the graph
        # Unknown devices are named plainly with their numbers.
        labels = {card.device.label for card in window.scene.cards.values()}
        assert "Thesis test node (serial 6)" in labels  # the device catalogue knows 2/2
    finally:
        _close(window)


def test_fit_to_a_system_file_shows_presence_replacement_and_start_up_choice(
        main_window, tmp_path, qtbot):
    system = system_file.load_path(systems_dir() / "thesis-test1.json")
    plan_autoconfigure(system).apply(system)
    stored = configuration_from_system(system)
    path = tmp_path / "test1.pdcfg"
    config_codec.save_path(ConfigCollection([stored]), path)
    # The prosthesis now: device 2 (SN5) gone, device 3 (SN6) plugged in.
    system.devices[DeviceKey(2, 2, 5)].present = False
    system.devices[DeviceKey(2, 2, 6)].present = True
    now = tmp_path / "now.json"
    now.write_text(json.dumps(system_file.to_json(system)))
    window = _open(main_window, path)
    try:
        assert window.fit_to_file(now)
        fit = window.fit
        assert fit is not None and fit.chosen_index == 1
        (lf,) = fit.links
        assert lf.input == "missing"
        assert "replaced by 2/2/4#1 → 2/2/6#1" in lf.summary()
        assert window.fit_choice.text().startswith("At start-up: the only stored "
                                                   "configuration 1")
        texts = [window.fit_list.item(i).text() for i in range(window.fit_list.count())]
        assert texts[0].startswith("Link 1: ") and "\nthe input is missing: replaced by" in texts[0]
        assert "/" not in texts[0].partition("\n")[2]  # no raw references in the words
        assert "input missing: replaced by" in window.fit_list.item(0).toolTip()
        assert texts[1].startswith("What start-up would do") and len(texts) == 2 + len(
            fit.plan.actions)
        # Back to the main window's prosthesis (transradial): nothing of test 1 there.
        window.fit_to_main()
        assert window.fit is not None and window.fit.whole == 0
        assert "the prosthesis in the main window" in window.fit_label.text()
    finally:
        _close(window)


def test_close_with_unsaved_changes_asks(main_window, pdcfg, qtbot, monkeypatch):
    window = _open(main_window, pdcfg)
    window.doc.add_configuration()
    monkeypatch.setattr(window, "ask_save_changes", lambda: QMessageBox.StandardButton.Cancel)
    assert not window.close()
    assert window.isVisible()
    monkeypatch.setattr(window, "ask_save_changes", lambda: QMessageBox.StandardButton.Discard)
    assert window.close()
    assert pdcfg.read_bytes() == _with_unknown_records(_transradial_collection())


def test_a_configuration_drawn_alone_has_no_device_data_to_complain_about():
    coll = _transradial_collection()
    system = system_for_configuration(coll.configurations[0],
                                      configuration_names(None, coll.configurations))
    for ch in (c for d in system.devices.values() for c in d.channels.values()):
        assert not ch.terminal_profile and not ch.required_inputs
    # named by the catalogue's products (the one naming), never by their numbers
    assert not any(d.label.startswith("unknown device (") for d in system.devices.values())
    assert len(system.links) == 5


def test_fit_follows_the_live_bus(make_window, qtbot):
    """Fitted to the simulated transradial prosthesis on its bus: the hook's configuration
    is repaired with the hand; when the hand is unplugged the fit says so."""
    main = make_window()
    with qtbot.waitSignal(main.ready, timeout=20000):
        main.connect_bus("sim:transradial")
    assert main.live.is_live, main.statusBar().currentMessage()
    window = _open(main, ROOT / "resources" / "configs" / "transradial-hand-and-hook.pdcfg")
    try:
        assert "the live bus sim:transradial" in window.fit_label.text()
        assert window.side.currentIndex() == 1  # nothing to report: the fit is shown
        window.config_list.setCurrentRow(1)
        qtbot.waitUntil(lambda: window.fit is not None and window.fit.index == 2,
                        timeout=5000)
        assert [lf.whole for lf in window.fit.links] == [True, True, False, False]
        assert "2641/769/301#1" in window.fit.links[2].summary()  # the hand stands in
        assert window.fit.chosen_index == 1
        labels = {card.device.label for card in window.scene.cards.values()}
        control = main.doc.system.devices[DeviceKey(2641, 513, 201)]
        assert control.label in labels and not control.label.startswith("unknown")
        # The hook, not on the bus, by its catalogue product (the one naming: no serial
        # number, as no other part reads the same).
        assert "Electric hook" in labels
        assert not any(label.startswith("unknown") for label in labels), labels
        hand = DeviceKey(2641, 769, 301)
        main.live.bridge.unplug(hand)
        qtbot.waitUntil(lambda: window.fit is not None and not window.fit.links[2].actions,
                        timeout=10000)
        assert "no replacement found" in window.fit.links[2].summary()
    finally:
        _close(window)
        main.live.disconnect_bus()


def test_add_link_and_channel_dialogs(qtbot):
    from pdcp_studio.app.configuration.window import AddLinkDialog, ChannelDialog

    out = StoredChannel(3, 2641, 513, 201, 0x9000, 0x2220)
    inp = StoredChannel(1, 2641, 770, 302, 0x9300, 0x2220)
    dialog = AddLinkDialog([("control unit, channel 3", out)], [("hook, channel 1", inp)])
    qtbot.addWidget(dialog)
    dialog.output.pick.setCurrentIndex(1)
    dialog.input.pick.setCurrentIndex(1)
    assert dialog.ends() == (out, inp)
    dialog.input.type_edit.setText("0x1FFFF")
    dialog.accept()
    assert dialog.result() == 0 and "0 to 0xFFFF" in dialog.error.text()
    dialog.input.type_edit.setText("0x9300")
    dialog.input.spins["serial"].setValue(201)
    dialog.input.spins["pid"].setValue(513)
    dialog.input.spins["index"].setValue(3)
    dialog.accept()
    assert "two different channels" in dialog.error.text()
    edit = ChannelDialog("channel", out)
    qtbot.addWidget(edit)
    assert edit.values() == (0x9000, 0x2220)
    edit.profile_edit.setText("8720")
    assert edit.values() == (0x9000, 8720)
    edit.type_edit.setText("nine")
    assert edit.values() is None


def test_the_window_speaks_plainly_with_codes_one_hover_away(main_window, pdcfg):
    """Issue 11: the links table and the checks say what a channel carries and in what form,
    in words; the hex codes and the engine's rule keys are in the tooltips."""
    import re

    window = _open(main_window, pdcfg)
    try:
        table = window.links
        headers = [table.horizontalHeaderItem(c).text() for c in range(table.columnCount())]
        assert "Type" not in headers and "Profile" not in headers
        cells = [table.item(r, c).text() for r in range(table.rowCount())
                 for c in range(table.columnCount())]
        assert cells and not [t for t in cells if re.search(r"0x[0-9A-F]", t)], cells
        assert any("Power Grip" in t for t in cells) and any("bits" in t for t in cells)
        tips = [table.item(r, c).toolTip() for r in range(table.rowCount()) for c in (2, 3)]
        assert any(t.startswith("type 0x") for t in tips)
        assert any(t.startswith("profile 0x") for t in tips)
        for i in range(window.checks.count()):
            assert not re.search(r"\d+/\d+/\d+#\d+|0x[0-9A-F]", window.checks.item(i).text())
    finally:
        _close(window)
