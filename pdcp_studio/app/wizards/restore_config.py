"""Restore a configuration: from a configuration file or the fitting history → preview the
difference → write → verify.

A file is implemented (its links made where both ends are on the bus) and stored; a history
entry is put back as it left the prosthesis (``bus.transaction.restore_change``, the CLI's
``history restore`` too). Either is one transaction of the change road.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QButtonGroup,
    QCheckBox,
    QFileDialog,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QListWidgetItem,
    QMessageBox,
    QPushButton,
    QRadioButton,
)

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.wizards import logic, words
from pdcp_studio.app.wizards.change_pages import ChangePage, Worked, WritePage
from pdcp_studio.app.wizards.result_pages import VerifyPage
from pdcp_studio.app.wizards.runner import alive
from pdcp_studio.app.wizards.task_wizard import Page, Source, TaskWizard

if TYPE_CHECKING:
    from pdcp_studio.bus.transaction import Change
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.model.refs import DeviceKey
    from pdcp_studio.model.system import Link, System


def _t(text: str) -> str:
    return translate("Wizards", text)


def restorable(entries: list[dict[str, Any]],
               devices: set[DeviceKey]) -> list[dict[str, Any]]:
    """The history entries of this prosthesis that can be put back (applied, with what they
    left known), newest first."""
    from pdcp_studio.app.docks.history_panel import for_prosthesis

    ok = [e for e in for_prosthesis(entries, devices)
          if e.get("links_after") is not None
          and (e.get("outcome") or {}).get("status") == "applied"]
    return sorted(ok, key=lambda e: int(e.get("id", 0)), reverse=True)



def reason_only(err: BaseException, path: Path) -> str:
    """Why a file could not be read, without the file's name when the error begins with
    it (the message names the file once: "Cannot read P: offset 12: …", not "P: P: …")."""
    text = str(err)
    for name in (str(path), path.name):
        if text.startswith(name + ": "):
            return text[len(name) + 2:]
    return text.replace(f"{path}: ", "", 1) if str(path) in text else text

class SourcePage(Page):
    """Where the configuration comes from: a file, or an entry of the fitting history."""

    def __init__(self) -> None:
        super().__init__(_t("Choose the configuration"),
                         _t("Choose a configuration file, or a fitting of this prosthesis "
                            "from the fitting history, to put back on the prosthesis."))
        self.view.hide()
        self.from_file = QRadioButton(_t("From a configuration file (.pdcfg):"))
        self.path = QLineEdit()
        self.path.setPlaceholderText(_t("No file chosen"))
        self.path.editingFinished.connect(lambda: self.load_file(self.path.text()))
        self.browse = QPushButton(_t("Browse…"))
        self.browse.clicked.connect(self.ask_file)
        self.from_history = QRadioButton(_t("From the fitting history of this prosthesis:"))
        self.entries = QListWidget()
        self.entries.currentRowChanged.connect(lambda _r: self._pick_history())
        self.group = QButtonGroup(self)
        self.group.addButton(self.from_file)
        self.group.addButton(self.from_history)
        self.group.buttonToggled.connect(lambda *_: self.completeChanged.emit())
        row = QHBoxLayout()
        row.addWidget(self.path, 1)
        row.addWidget(self.browse)
        self.box.insertWidget(1, self.from_file)
        self.box.insertLayout(2, row)
        self.box.insertWidget(3, self.from_history)
        self.box.insertWidget(4, self.entries, 1)
        self.collection: ConfigCollection | None = None
        self.file: Path | None = None
        self.history: list[dict[str, Any]] = []

    def initializePage(self) -> None:
        self.from_file.setChecked(True)
        panel = self.task.main.history_panel
        self._fill(panel.all_entries())
        worker = panel.refresh()
        if worker is not None:
            worker.finished.connect(alive(self, lambda _r: self._fill(panel.all_entries())))

    def _fill(self, entries: list[dict[str, Any]]) -> None:
        """Show the restorable entries. A refill (the background history refresh landing)
        keeps the entry the user chose, found again by its number, and leaves the list
        alone when nothing in it changed."""
        bus = self.task.main.doc.bus_system
        devices = set(bus.devices) if bus is not None else set()
        history = restorable(entries, devices)
        if history == self.history and self.entries.count():
            return
        chosen = self.chosen_id()
        self.history = history
        self.entries.blockSignals(True)  # the refill is not the user's choice
        try:
            self.entries.clear()
            for e in self.history:
                item = QListWidgetItem(_t("Entry {0} — {1} — {2} ({3})").format(
                    e["id"], str(e.get("time", ""))[:19].replace("T", " "),
                    words.action_words(str(e.get("action", ""))),
                    words.count("%n link(s)", len(e.get("links_after") or ()))))
                self.entries.addItem(item)
            if not self.history:
                self.entries.addItem(_t("No fitting of this prosthesis is recorded yet."))
                self.entries.item(0).setFlags(Qt.ItemFlag.NoItemFlags)
            if chosen is not None:
                self.choose_entry(chosen)
        finally:
            self.entries.blockSignals(False)
        self.completeChanged.emit()

    def chosen_id(self) -> int | None:
        """The number of the history entry chosen in the list, or None."""
        row = self.entries.currentRow()
        return int(self.history[row]["id"]) if 0 <= row < len(self.history) else None

    def ask_file(self) -> None:
        path, _ = QFileDialog.getOpenFileName(self, _t("Configuration file"),
                                              self.task.main._last_dir(),
                                              _t("Configurations (*.pdcfg)"))
        if path:
            self.load_file(path)

    def load_file(self, path: str | Path) -> bool:
        """Read a configuration file; a bad one is named with why (nothing else changes)."""
        from pdcp_studio.errors import PdcpError
        from pdcp_studio.storage import config_codec

        path = Path(path)
        self.path.setText(str(path))
        self.from_file.setChecked(True)
        try:
            self.collection, self.file = config_codec.load_path(path), path
        except (PdcpError, OSError, ValueError) as err:
            self.collection, self.file = None, None
            self.idle(_t("Cannot read {0}: {1}").format(path, reason_only(err, path)))
            self.completeChanged.emit()
            return False
        n = sum(len(c.links) for c in self.collection.configurations)
        self.idle(_t("{0}: {1}").format(path.name, words.count("%n stored link(s).", n)))
        self.completeChanged.emit()
        return True

    def _pick_history(self) -> None:
        if self.entries.currentRow() >= 0 and self.history:
            self.from_history.setChecked(True)
        self.completeChanged.emit()

    def choose_entry(self, entry_id: int) -> bool:
        for row, e in enumerate(self.history):
            if e["id"] == entry_id:
                self.entries.setCurrentRow(row)
                return True
        return False

    def source(self) -> Source | None:
        if self.from_file.isChecked():
            return ("file", (self.file, self.collection)) \
                if self.collection is not None and self.file is not None else None
        row = self.entries.currentRow()
        if 0 <= row < len(self.history):
            return "history", self.history[row]
        return None

    def isComplete(self) -> bool:
        return self.source() is not None

    def validatePage(self) -> bool:
        self.task.source = self.source()
        return self.task.source is not None


def restore_step(task: TaskWizard, system: System,
                 stored: ConfigCollection | None) -> tuple[list[str], Change, list[Link]]:
    """The change that puts the chosen configuration back, and the difference in words."""
    from pdcp_studio.bus.transaction import restore_change

    source = task.source
    assert source is not None  # the source page goes on only once one is chosen
    if source[0] == "file":
        path, collection = source[1]
        change = logic.restore_file_change(system, collection, path.name)
        lines = [_t("From the file {0}.").format(path.name)]
    else:
        from pdcp_studio.app.widgets.restore_refusal import missing_words
        from pdcp_studio.bus.transaction import NotRestorable

        entry = source[1]
        task.missing_parts = []
        try:
            change = restore_change(entry, system)
        except NotRestorable as err:
            if not err.missing:
                raise
            task.missing_parts = list(err.missing)
            # Refused before anything is written: the page names the parts (by the names
            # every text uses) and offers Replace a part.
            raise NotRestorable(missing_words(entry["id"], err.missing, system),
                                err.missing) from err
        lines = [_t("As the fitting of {0} left the prosthesis (fitting history entry {1}).")
                 .format(str(entry.get("time", ""))[:19].replace("T", " "), entry["id"])]
    # The links made and removed, the parameters, the stored configuration, the policy and
    # the next power-on: the change's effect says them (the page asks it, links included).
    return lines, change, change.links_after(system.links)


class DifferencePage(ChangePage):
    """The difference the restore makes; when it would clear the stored configuration (a
    history entry from before any was stored), a plain warning and a box to tick before
    Next: the stored configuration is what the prosthesis links by after a restart or a
    part swap, so losing it must be chosen, not stumbled into."""

    def __init__(self) -> None:
        super().__init__(
            _t("Difference"),
            _t("What changes on the prosthesis when this configuration is put back. Nothing "
               "is written yet."), restore_step)
        self.effect_links = True  # nothing above says the links: the effect does
        #: The refusal on screen when a part the restore needs is absent (tests read it).
        self.refusal: QMessageBox | None = None
        self.warning = QLabel(_t(
            "Warning: this fitting was made before any configuration was stored on the "
            "prosthesis. Putting it back clears the stored configuration: after a restart, "
            "or when a part is replaced, the prosthesis will no longer link its parts as "
            "they are stored now."))
        self.warning.setWordWrap(True)
        self.warning.setStyleSheet("color:#b00000; font-weight:bold")
        self.confirm = QCheckBox(_t("Yes, clear the stored configuration"))
        self.confirm.toggled.connect(lambda _on: self.completeChanged.emit())
        self.box.insertWidget(1, self.warning)
        self.box.insertWidget(2, self.confirm)
        self.clears = False
        self._warn(False)

    def failed(self, message: str) -> None:
        """A restore refused for an absent part says so on top, with Replace a part (the
        wizard's change is never written: the page does not go on)."""
        from pdcp_studio.app.widgets.restore_refusal import refuse

        task = self.task
        if not task.missing_parts:
            super().failed(message)
            return
        self.idle(message)
        self.refusal = refuse(task, _t("Restore a configuration"), message,
                              lambda: _replace_instead(task))

    def _warn(self, clears: bool) -> None:
        self.clears = clears
        self.warning.setVisible(clears)
        self.confirm.setVisible(clears)
        self.confirm.setChecked(False)

    def initializePage(self) -> None:
        self._warn(False)
        super().initializePage()

    def _previewed(self, got: Worked) -> None:
        super()._previewed(got)
        self._warn(logic.clears_stored(self.task.change, self.task.stored))
        self.completeChanged.emit()

    def isComplete(self) -> bool:
        return super().isComplete() and (not self.clears or self.confirm.isChecked())

    def validatePage(self) -> bool:
        return self.isComplete()  # Next by keyboard or code waits for the tick too


def _replace_instead(task: TaskWizard) -> None:
    """Leave the restore for Replace a part."""
    task.reject()
    task.main.open_task("replace")


class RestoreWizard(TaskWizard):
    """A stored configuration put back, step by step."""

    def __init__(self, window: Any) -> None:
        super().__init__(window, _t("Restore a configuration"))
        self.source_page = SourcePage()
        self.diff_page = DifferencePage()
        self.write_page = WritePage(_t("Write"),
                                    _t("The configuration is written to the prosthesis."),
                                    _t("Write to prosthesis"))
        self.verify_page = VerifyPage()
        for page in (self.source_page, self.diff_page, self.write_page, self.verify_page):
            self.addPage(page)
