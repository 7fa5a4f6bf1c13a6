"""The app shows names, references and file names, never runs them (issue 28): ESC[2J, BEL
and U+202E in a device name and descriptor (a system file), its file name, the operator and
the patient reference appear in the graph, the device tree, the window title, the status line
and the fitting history as visible escapes, never raw."""

from __future__ import annotations

import json

import pytest

from pdcp_studio.paths import resources_dir

pytestmark = pytest.mark.gui

EVIL = "\x1b[2J\x07\u202e"
SHOWN = "\\x1b[2J\\x07\\u202e"


def _clean(text: str) -> None:
    for char in ("\x1b", "\x07", "\u202e"):
        assert char not in text, repr(text)


@pytest.fixture
def evil_system(tmp_path):
    doc = json.loads((resources_dir() / "systems" / "transradial.json").read_text("utf-8"))
    doc["devices"][0]["name"] = f"Hand{EVIL}x"
    doc["devices"][0]["channels"][0]["descriptor"] = f"grip{EVIL}"
    path = tmp_path / f"fit{EVIL}.json"
    path.write_text(json.dumps(doc), "utf-8")
    return path


def test_names_and_the_file_name_show_as_escapes(make_window, evil_system):
    window = make_window(evil_system)
    device = next(d for d in window.doc.system.devices.values() if d.name.startswith("Hand"))
    label = window.scene.device_label(device)
    assert f"Hand{SHOWN}x" in label
    _clean(label)
    tree = window.tree
    top = [tree.topLevelItem(i) for i in range(tree.topLevelItemCount())]
    texts = [item.text(0) for item in top]
    texts += [item.child(j).text(0) for item in top for j in range(item.childCount())]
    for text in texts:
        _clean(text)
    assert any(f"Hand{SHOWN}x" in t for t in texts), texts
    assert any(f"grip{SHOWN}" in t for t in texts), texts
    title = window.windowTitle()
    _clean(title)
    assert f"fit{SHOWN}" in title
    window.status_line.say(f"Saved {evil_system}")
    message = window.statusBar().currentMessage()
    _clean(message)
    assert f"fit{SHOWN}.json" in message


def test_the_history_panel_shows_operator_and_patient_as_escapes(make_window, qtbot,
                                                                monkeypatch, tmp_path):
    from pdcp_studio.cli.main import main

    monkeypatch.setenv("PDCP_STUDIO_OPERATOR", f"Ann{EVIL}")
    config = resources_dir() / "configs" / "transradial-hand-and-hook.pdcfg"
    assert main(["config", "write", str(config), "--bus", "sim:transradial", "--memory",
                 str(tmp_path / "m.mem"), "--yes", "--patient", f"P-7{EVIL}"]) == 0
    window = make_window()
    panel = window.history_panel
    with qtbot.waitSignal(panel.loaded, timeout=10000):
        panel.refresh()
    cells = [panel.table.item(0, c).text() for c in range(panel.table.columnCount())]
    for cell in cells:
        _clean(cell)
    assert f"Ann{SHOWN}" in cells and f"P-7{SHOWN}" in cells, cells
    panel.select_ids(1)
    details = panel.details.toPlainText()
    _clean(details)
    assert f"Ann{SHOWN}" in details and f"P-7{SHOWN}" in details
