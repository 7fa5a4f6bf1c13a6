"""Crash recovery: autosave while dirty, offer after a crash, clear on a clean save or close."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest
from PySide6.QtCore import QObject, Signal
from PySide6.QtGui import QUndoStack

from pdcp_studio.app.documents.recovery import Autosaver, Recovery, RecoveryDialog
from pdcp_studio.storage import system_file

pytestmark = pytest.mark.gui


def _dead_pid() -> int:
    """The id of a process that has ended."""
    proc = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, check=True)
    return int(proc.stdout)


def _as_if_crashed(recovery: Recovery, name: str) -> None:
    """Rewrite an entry as if the process that saved it had died."""
    file = recovery.file_for(name)
    doc = json.loads(file.read_text("utf-8"))
    doc["pid"] = _dead_pid()
    file.write_text(json.dumps(doc), "utf-8")


def test_save_pending_discard(tmp_path):
    rec = Recovery(tmp_path / "rec")
    assert rec.pending() == [] and rec.entries() == []
    file = rec.save("/home/p/arm.pdcpsys.json", '{"format": "pdcp-system/1"}',
                    path="/home/p/arm.pdcpsys.json")
    assert file.parent == tmp_path / "rec"
    assert not [p for p in file.parent.iterdir() if p.name.endswith(".tmp")]  # atomic: no leftovers
    # Our own (running) process's entry is not offered: it is not a crash.
    assert rec.pending() == []
    assert [e.name for e in rec.entries()] == ["/home/p/arm.pdcpsys.json"]
    _as_if_crashed(rec, "/home/p/arm.pdcpsys.json")
    [entry] = rec.pending()
    assert entry.text == '{"format": "pdcp-system/1"}'
    assert entry.path == "/home/p/arm.pdcpsys.json"
    assert "arm.pdcpsys.json" in entry.title
    # A second save of the same name replaces the entry.
    rec.save("/home/p/arm.pdcpsys.json", "v2")
    assert [e.text for e in rec.entries()] == ["v2"]
    assert rec.discard("/home/p/arm.pdcpsys.json") is True
    assert rec.discard("/home/p/arm.pdcpsys.json") is False
    assert rec.entries() == []


def test_unreadable_recovery_files_are_ignored(tmp_path):
    rec = Recovery(tmp_path)
    rec.save("good", "text")
    (tmp_path / "junk.recovery.json").write_text("{not json", "utf-8")
    (tmp_path / "other.recovery.json").write_text('{"format": "something-else"}', "utf-8")
    assert [e.name for e in rec.entries()] == ["good"]


class FakeDocument(QObject):
    """The part of ``Document`` the autosaver watches."""

    linksChanged = Signal()
    deviceChanged = Signal(object)
    channelChanged = Signal(object)
    systemReset = Signal()
    dirtyChanged = Signal(bool)

    def __init__(self, system) -> None:
        super().__init__()
        self.system = system
        self.undo_stack = QUndoStack(self)
        self.is_dirty = False

    def edit(self) -> None:
        was = self.is_dirty
        self.is_dirty = True
        self.linksChanged.emit()
        if not was:
            self.dirtyChanged.emit(True)

    def save(self) -> None:
        self.is_dirty = False
        self.dirtyChanged.emit(False)


def test_autosaver_writes_after_an_edit_and_clears_on_clean_save(qtbot, tmp_path, systems_dir):
    system = system_file.load_path(systems_dir / "thesis-test2.json")
    doc = FakeDocument(system)
    rec = Recovery(tmp_path)
    saver = Autosaver(rec, lambda: "untitled", lambda: system_file.dumps(doc.system),
                      interval_ms=20)
    saver.watch(doc)
    with qtbot.waitSignal(saver.saved, timeout=5000) as blocker:
        doc.edit()
    assert blocker.args[0] == rec.file_for("untitled")
    [entry] = rec.entries()
    restored = system_file.loads(entry.text)
    assert restored.links == system.links and set(restored.devices) == set(system.devices)
    doc.save()  # a clean save drops the recovery entry
    assert rec.entries() == []
    # Further signals while clean do not autosave.
    doc.linksChanged.emit()
    qtbot.wait(80)
    assert rec.entries() == []


def test_autosaver_reports_a_failing_serialiser_without_raising(qtbot, tmp_path):
    def broken() -> str:
        raise ValueError("cannot serialise")

    saver = Autosaver(Recovery(tmp_path), lambda: "x", broken, interval_ms=10)
    with qtbot.waitSignal(saver.error, timeout=5000) as blocker:
        saver.changed()
    assert "cannot serialise" in blocker.args[0]


def test_autosave_survives_a_crash_and_is_offered_on_next_start(tmp_path):
    """A child process autosaves and dies without cleaning up; this process is offered it."""
    code = f"""
import os, sys
os.environ["QT_QPA_PLATFORM"] = "offscreen"
from PySide6.QtWidgets import QApplication
from pdcp_studio.app.documents.recovery import Autosaver, Recovery
app = QApplication([])
saver = Autosaver(Recovery({str(tmp_path)!r}), lambda: "untitled", lambda: "unsaved work",
                  interval_ms=1)
saver.save_now().wait(10)
os._exit(9)  # a crash: no clean-up, no clean close
"""
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60, cwd=os.getcwd())
    assert proc.returncode == 9, proc.stderr
    [entry] = Recovery(tmp_path).pending()
    assert entry.text == "unsaved work" and entry.name == "untitled"


def test_recovery_dialog_lists_entries_and_returns_the_ticked_ones(qtbot, tmp_path):
    rec = Recovery(tmp_path)
    rec.save("a", "A")
    rec.save("b", "B")
    entries = rec.entries()
    dialog = RecoveryDialog(entries)
    qtbot.addWidget(dialog)
    assert dialog.list.count() == 2
    from PySide6.QtCore import Qt

    dialog.list.item(0).setCheckState(Qt.CheckState.Unchecked)
    assert dialog.chosen() == entries[1:]


def test_offer_recovery_restores_the_chosen_and_discards_the_rest(qtbot, tmp_path, systems_dir):
    from PySide6.QtCore import Qt

    from pdcp_studio.app.documents.recovery import offer_recovery, restore_system

    rec = Recovery(tmp_path)
    assert offer_recovery(rec, ask=lambda d: pytest.fail("nothing to offer")) == []
    text = (systems_dir / "appendix-d.json").read_text("utf-8")
    rec.save("/p/arm.json", text, path="/p/arm.json")
    rec.save("untitled", "{}")
    _as_if_crashed(rec, "/p/arm.json")
    _as_if_crashed(rec, "untitled")

    def ask(dialog: RecoveryDialog) -> bool:
        for i, entry in enumerate(dialog.entries):
            if entry.name == "untitled":
                dialog.list.item(i).setCheckState(Qt.CheckState.Unchecked)
        return True

    [chosen] = offer_recovery(rec, ask=ask)
    assert chosen.name == "/p/arm.json"
    assert len(restore_system(chosen).links) == 3
    assert [e.name for e in rec.entries()] == ["/p/arm.json"]  # the declined one is gone
    assert offer_recovery(rec, ask=lambda d: False) == []  # "Discard all"
    assert rec.entries() == []
