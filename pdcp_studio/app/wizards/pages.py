"""The pages the guided tasks share: connect, scan, checks, a previewed change, write,
verify and the fitting report.

A :class:`TaskWizard` keeps what its pages found (``system``, ``stored``, ``change``,
``preview``, ``results``…) and its main window; pages read the prosthesis on the bus's
worker (:mod:`.runner`) and never on the GUI thread. The write page is a commit page: its
button is the user's confirmation of the preview shown before it, and after a write there is
no way back (a written change is undone by a new transaction, as everywhere in the app).
"""

from __future__ import annotations

import html
from collections.abc import Callable
from pathlib import Path
from typing import Any

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtGui import QCloseEvent, QKeyEvent
from PySide6.QtWidgets import (
    QButtonGroup,
    QFileDialog,
    QHBoxLayout,
    QLabel,
    QListWidget,
    QListWidgetItem,
    QPlainTextEdit,
    QProgressBar,
    QPushButton,
    QRadioButton,
    QTextBrowser,
    QVBoxLayout,
    QWidget,
    QWizard,
    QWizardPage,
)

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.wizards import words
from pdcp_studio.app.wizards.runner import TransactionRunner, alive, look, on_bus

OK_MARK, WARN_MARK = "✓", "!"


def _t(text: str) -> str:
    return translate("Wizards", text)


def _item(text: str) -> str:
    """One line; what follows a line break is its explanation, shown quieter."""
    first, _, rest = text.partition("\n")
    out = html.escape(first)
    if rest:
        out += f"<br><span style='color:#4b5563'>{html.escape(rest)}</span>"
    return out


def bullets(lines: list[str], head: str = "", *, marks: bool = False) -> str:
    """Lines as an HTML list under an optional heading (escaped); ``marks``: lines that
    carry their own mark (✓, !) as plain paragraphs."""
    out = f"<p>{html.escape(head)}</p>" if head else ""
    if lines and marks:
        out += "".join(f"<p style='margin:3px 0'>{_item(t)}</p>" for t in lines)
    elif lines:
        out += ("<ul style='margin-left:-16px'>"
                + "".join(f"<li style='margin-bottom:5px'>{_item(t)}</li>" for t in lines)
                + "</ul>")
    return out


class TaskWizard(QWizard):
    """A guided task on the main window's prosthesis (not modal: the Simulator panel and
    the graph stay usable beside it)."""

    def __init__(self, window: Any, title: str) -> None:
        super().__init__(window)
        self.main = window
        self.setWindowTitle(title)
        self.setWizardStyle(QWizard.WizardStyle.ClassicStyle)
        self.setOption(QWizard.WizardOption.NoBackButtonOnStartPage, True)
        self.setOption(QWizard.WizardOption.NoDefaultButton, True)
        self.setOption(QWizard.WizardOption.NoCancelButtonOnLastPage, True)
        self.setWindowModality(Qt.WindowModality.NonModal)
        self.resize(820, 600)
        # What the pages found and did.
        self.system: Any = None
        self.stored: Any = None
        self.policy: Any = None
        self.change: Any = None
        self.preview: Any = None
        self.expected_links: list[Any] = []
        self.results: list[Any] = []
        self.report_path: Path | None = None
        # Replace a part: the parts gone, the keys seen before, the parts plugged in since.
        self.missing: list[Any] = []
        self.known: set[Any] = set()
        self.new_parts: list[Any] = []
        # Restore: ("file", (path, collection)) or ("history", entry).
        self.source: Any = None

    @property
    def writing(self) -> bool:
        return any(isinstance(p, WritePage) and p.runner.running
                   for p in (self.page(i) for i in self.pageIds()))

    def reject(self) -> None:
        """Cancel: never while a write runs (its page's Stop puts the prosthesis back)."""
        if self.writing:
            return
        super().reject()

    def closeEvent(self, event: QCloseEvent) -> None:
        if self.writing:
            event.ignore()
            return
        super().closeEvent(event)

    def keyPressEvent(self, event: QKeyEvent) -> None:
        if event.key() == Qt.Key.Key_Escape and self.writing:
            return
        super().keyPressEvent(event)


class Page(QWizardPage):
    """A page with an explanation, a text area for what it found, a busy bar and a status
    line; ``task`` is its :class:`TaskWizard`."""

    def __init__(self, title: str, subtitle: str = "") -> None:
        super().__init__()
        self.setTitle(title)
        self.intro = QLabel(subtitle)
        self.intro.setWordWrap(True)
        self.view = QTextBrowser()
        self.view.setOpenExternalLinks(False)
        self.busy = QProgressBar()
        self.busy.setRange(0, 0)
        self.busy.setTextVisible(False)
        self.busy.setMaximumHeight(10)
        self.busy.hide()
        self.status = QLabel()
        self.status.setWordWrap(True)
        self.box = QVBoxLayout(self)
        self.box.addWidget(self.intro)
        self.box.addWidget(self.view, 1)
        self.box.addWidget(self.busy)
        self.box.addWidget(self.status)
        self.ready = False

    @property
    def task(self) -> TaskWizard:
        wizard = self.wizard()
        assert isinstance(wizard, TaskWizard)
        return wizard

    def set_ready(self, ready: bool) -> None:
        self.ready = ready
        self.completeChanged.emit()

    def isComplete(self) -> bool:
        return self.ready

    def working(self, text: str) -> None:
        self.busy.show()
        self.status.setText(text)

    def idle(self, text: str = "") -> None:
        self.busy.hide()
        self.status.setText(text)

    def failed(self, message: str) -> None:
        self.idle(_t("The prosthesis did not answer: {0}").format(message))

    def read_bus(self, done: Callable[[Any], None], what: str = "") -> None:
        """Look at the prosthesis (system, stored configuration, policy) on the worker."""
        self.set_ready(False)
        self.working(what or _t("Looking at the prosthesis…"))
        if not on_bus(self.task.main, look, "Look at the prosthesis",
                      lambda got: self._looked(got, done), self.failed, owner=self):
            self.idle(_t("No prosthesis is connected."))

    def _looked(self, got: Any, done: Callable[[Any], None]) -> None:
        task = self.task
        task.system, task.stored, task.policy = got
        self.idle()
        done(got)


def prosthesis_words(url: str) -> str:
    """A connection as a prosthetist reads it: a simulated prosthesis by the simulator's
    description (``Transradial prosthesis (simulated)``), any other by its address."""
    from pdcp_studio.app.dialogs.connect_dialog import prosthesis_description

    kind, _, name = url.partition(":")
    if kind == "sim":
        head = prosthesis_description(name).partition(":")[0].strip()
        if head:
            return _t("{0} (simulated)").format(head)
    return url


class SimChoice(QWidget):
    """The simulated prostheses by what they are (the simulator's descriptions), the one
    a new user should try first at the top; ``url()`` is the chosen ``sim:`` address."""

    changed = Signal()

    def __init__(self) -> None:
        super().__init__()
        from pdcp_studio.app.dialogs.connect_dialog import DEFAULT_SIM, prosthesis_description
        from pdcp_studio.bus.sim.rigs import list_prostheses

        self.list = QListWidget()
        self.list.setWordWrap(True)
        names = list_prostheses()
        for name in sorted(names, key=lambda n: n != DEFAULT_SIM):
            item = QListWidgetItem(prosthesis_description(name) or name)
            item.setData(Qt.ItemDataRole.UserRole, name)
            self.list.addItem(item)
        self.list.currentRowChanged.connect(lambda _r: self.changed.emit())
        box = QVBoxLayout(self)
        box.setContentsMargins(20, 0, 0, 0)
        box.addWidget(self.list)
        self.set_url(f"sim:{DEFAULT_SIM}")

    def url(self) -> str | None:
        item = self.list.currentItem()
        return f"sim:{item.data(Qt.ItemDataRole.UserRole)}" if item else None

    def set_url(self, url: str) -> None:
        name = url.partition(":")[2]
        for row in range(self.list.count()):
            if self.list.item(row).data(Qt.ItemDataRole.UserRole) == name:
                self.list.setCurrentRow(row)
                return


class ConnectPage(Page):
    """Which prosthesis: the one connected now, a simulated one, or another connection."""

    def __init__(self) -> None:
        super().__init__(_t("Connect"),
                         _t("Choose the prosthesis to work on. Next connects to it."))
        self.view.hide()
        self.current = QRadioButton()
        self.simulated = QRadioButton(_t("A simulated prosthesis, to practise on:"))
        self.sim_page = SimChoice()
        self.other = QRadioButton(_t("Another connection (CAN adapter or arbitrator "
                                          "cable):"))
        self.other_url: str | None = None
        self.choose = QPushButton(_t("Choose…"))
        self.choose.clicked.connect(self.ask_other)
        self.group = QButtonGroup(self)
        for b in (self.current, self.simulated, self.other):
            self.group.addButton(b)
        row = QHBoxLayout()
        row.addWidget(self.other)
        row.addWidget(self.choose)
        row.addStretch(1)
        self.box.insertWidget(1, self.current)
        self.box.insertWidget(2, self.simulated)
        self.box.insertWidget(3, self.sim_page, 1)
        self.box.insertLayout(4, row)
        self.group.buttonToggled.connect(lambda *_: self.completeChanged.emit())
        self.sim_page.changed.connect(lambda: self.simulated.setChecked(True))
        self.connecting = ""

    def initializePage(self) -> None:
        live = self.task.main.live
        if live.is_live:
            self.current.setText(_t("The prosthesis connected now: {0}").format(
                prosthesis_words(live.url)))
            self.current.setEnabled(True)
            self.current.setChecked(True)
        else:
            self.current.setText(_t("The prosthesis connected now (none)"))
            self.current.setEnabled(False)
            self.simulated.setChecked(True)

    def ask_other(self) -> None:
        from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog

        url = ConnectDialog.get_url(self)
        if url:
            self.other_url = url
            self.other.setText(_t("Another connection: {0}").format(prosthesis_words(url)))
            self.other.setChecked(True)

    def chosen_url(self) -> str | None:
        if self.current.isChecked():
            return self.task.main.live.url or None
        if self.simulated.isChecked():
            return self.sim_page.url()
        return self.other_url

    def isComplete(self) -> bool:
        return self.chosen_url() is not None and not self.connecting

    def _on_current(self) -> bool:
        window = self.task.main
        url = self.chosen_url()
        return (window.live.is_live and window.live.url == url
                and window.doc.session is window.live.bridge)

    def validatePage(self) -> bool:
        if self._on_current():
            return True
        if self.connecting:
            return False
        window = self.task.main
        url = self.chosen_url()
        if url is None or not window.maybe_save():
            return False
        self.connecting = url
        self.completeChanged.emit()
        self.working(_t("Connecting to {0}…").format(prosthesis_words(url)))
        window.live.connected.connect(self._connected)
        window.live.failed.connect(self._failed)
        window.connect_bus(url)
        return False

    def _disconnect_signals(self) -> None:
        live = self.task.main.live
        for signal, slot in ((live.connected, self._connected), (live.failed, self._failed)):
            try:
                signal.disconnect(slot)
            except (RuntimeError, TypeError):
                pass

    def _connected(self, url: str) -> None:
        if url != self.connecting:
            return
        self._disconnect_signals()
        self.connecting = ""
        self.idle(_t("Connected to {0}.").format(prosthesis_words(url)))
        self.completeChanged.emit()
        if self.task.currentPage() is self:
            QTimer.singleShot(0, self.task.next)

    def _failed(self, url: str, message: str) -> None:
        if url != self.connecting:
            return
        self._disconnect_signals()
        self.connecting = ""
        self.idle(_t("Cannot connect to {0}: {1}").format(prosthesis_words(url), message))
        self.completeChanged.emit()


class ScanPage(Page):
    """Read the whole bus and say which parts are on it."""

    def __init__(self) -> None:
        super().__init__(_t("Scan"),
                         _t("PDCP Studio asks every part on the bus what it is and "
                                 "what it can do."))
        self.again = QPushButton(_t("Scan again"))
        self.again.clicked.connect(self.scan)
        self.box.addWidget(self.again, 0, Qt.AlignmentFlag.AlignLeft)

    def initializePage(self) -> None:
        self.scan()

    def scan(self) -> None:
        bridge = self.task.main.live.bridge
        self.set_ready(False)
        self.view.clear()
        if bridge is None:
            self.idle(_t("No prosthesis is connected."))
            return
        self.working(_t("Scanning the bus…"))
        self.again.setEnabled(False)
        worker = bridge.scan()
        if worker is None:
            self.idle(_t("No prosthesis is connected."))
            return
        worker.progress.connect(alive(self, self._scan_progress))
        worker.finished.connect(alive(self, self._scanned))
        worker.failed.connect(alive(self, self._scan_failed))

    def _scan_progress(self, done: int, total: int, _what: str) -> None:
        self.status.setText(_t("Scanning the bus… {0} of {1}").format(done, total) if total
                            else _t("Scanning the bus…"))

    def _scan_failed(self, message: str) -> None:
        self.again.setEnabled(True)
        self.failed(message)

    def _scanned(self, system: Any) -> None:
        self.again.setEnabled(True)
        self.task.system = system
        lines = []
        names = words.part_names(system)
        for key, device in sorted(system.devices.items()):
            state = "" if device.present else _t(" (not on the bus)")
            lines.append(f"{names[key]}{state}")
        present = sum(1 for d in system.devices.values() if d.present)
        self.view.setHtml(bullets(lines, words.count("%n part(s) found on the bus", present)
                                  + ", " + words.count("%n link(s) between them:",
                                                       len(system.links))))
        self.idle(_t("Scan finished."))
        self.set_ready(True)


class ChecksPage(Page):
    """The engine's checks of the prosthesis, in plain words with what to do."""

    def __init__(self) -> None:
        super().__init__(_t("Checks"),
                         _t("PDCP Studio checks that every part is described and linked "
                                 "as it asks to be."))

    def initializePage(self) -> None:
        self.read_bus(self._show)

    def _show(self, _got: Any) -> None:
        from pdcp_studio.app.words.finding_text import plain_finding
        from pdcp_studio.engine import check_system

        task = self.task
        auto = task.policy.autoconfigure if task.policy is not None else True
        findings = check_system(task.system, autoconfigure=auto)
        if not findings:
            self.view.setHtml(bullets([_t("No problems found: every part is described "
                                               "and linked as it asks.")]))
        else:
            names = words.part_names(task.system)  # two hands read apart
            lines = [plain_finding(f, task.system, auto, names) for f in findings]
            self.view.setHtml(bullets(lines, words.count(
                "%n thing(s) to look at. The next step proposes links that fix what can be "
                "fixed automatically:", len(findings))))
        self.set_ready(True)


class ChangePage(Page):
    """A change worked out from the prosthesis as it is, explained, then previewed (what the
    transaction would write). ``build(system, stored) -> (lines, change, expected_links)``
    runs on the bus worker (the engine is pure); the wizard keeps ``change`` and
    ``preview`` for the write page."""

    def __init__(self, title: str, subtitle: str,
                 build: Callable[[TaskWizard, Any, Any], tuple[list[str], Any, list[Any]]]
                 ) -> None:
        super().__init__(title, subtitle)
        self.build = build
        self.detail_button = QPushButton(_t("Show the technical detail"))
        self.detail_button.setCheckable(True)
        self.detail = QPlainTextEdit()
        self.detail.setReadOnly(True)
        self.detail.hide()
        self.detail_button.toggled.connect(self.detail.setVisible)
        self.box.addWidget(self.detail_button, 0, Qt.AlignmentFlag.AlignLeft)
        self.box.addWidget(self.detail, 1)
        self.lines: list[str] = []

    def initializePage(self) -> None:
        self.set_ready(False)
        self.view.clear()
        self.working(_t("Working out the change…"))
        task = self.task

        def work(session: Any) -> Any:
            from pdcp_studio.bus.session.api import preview_change

            system, stored, policy = look(session)
            lines, change, expected = self.build(task, system, stored)
            return system, stored, policy, lines, change, expected, \
                preview_change(session, change)

        if not on_bus(task.main, work, "Preview the change", self._previewed, self.failed,
                      owner=self):
            self.idle(_t("No prosthesis is connected."))

    def _previewed(self, got: Any) -> None:
        task = self.task
        (task.system, task.stored, task.policy, self.lines, task.change,
         task.expected_links, task.preview) = got
        preview_words = words.preview_lines(task.system, task.preview, links=False)
        head, *lines = self.lines or [""]
        self.view.setHtml(bullets(lines, head)
                          + bullets(preview_words, _t("When it is written:")))
        plan = getattr(task.change, "plan", None)
        detail = list(task.preview.lines())
        if plan is not None:
            detail += ["", plan.to_text(task.main.doc.tree)]
        self.detail.setPlainText("\n".join(detail))
        self.idle()
        self.set_ready(True)


class WritePage(Page):
    """Write the previewed change as one transaction, with progress and Stop; the page's
    Write button confirms it. With ``build`` the page works its change out itself (as a
    :class:`ChangePage` does) and shows it before writing."""

    def __init__(self, title: str, subtitle: str, button: str,
                 build: Callable[[TaskWizard, Any, Any], tuple[list[str], Any, list[Any]]]
                 | None = None) -> None:
        super().__init__(title, subtitle)
        self.setCommitPage(True)
        self.setButtonText(QWizard.WizardButton.CommitButton, button)
        self.build = build
        self.runner = TransactionRunner(None, self)
        self.runner.progress.connect(self._progress)
        self.runner.finished.connect(self._finished)
        self.runner.failed.connect(self._failed)
        self.stop = QPushButton(_t("Stop and put the prosthesis back"))
        self.stop.hide()
        self.stop.clicked.connect(self._stop)
        self.box.addWidget(self.stop, 0, Qt.AlignmentFlag.AlignLeft)
        self.result: Any = None
        self.change: Any = None
        self.preview: Any = None

    def initializePage(self) -> None:
        self.runner.window = self.task.main
        self.result = None
        self.set_ready(False)
        if self.build is None:
            self._show(self.task.change, self.task.preview)
            return
        task = self.task
        self.working(_t("Working out the change…"))

        def work(session: Any) -> Any:
            from pdcp_studio.bus.session.api import preview_change

            system, stored, policy = look(session)
            lines, change, expected = self.build(task, system, stored)  # type: ignore[misc]
            return system, stored, policy, lines, change, expected, \
                preview_change(session, change)

        if not on_bus(task.main, work, "Preview the change", self._built, self.failed,
                      owner=self):
            self.idle(_t("No prosthesis is connected."))

    def _built(self, got: Any) -> None:
        task = self.task
        (task.system, task.stored, task.policy, lines, change, task.expected_links,
         preview) = got
        task.change, task.preview = change, preview
        self._show(change, preview, lines)

    def _show(self, change: Any, preview: Any, lines: list[str] | None = None) -> None:
        self.change, self.preview = change, preview
        task = self.task
        if preview is None:
            self.idle(_t("Nothing was worked out to write."))
            return
        what = words.preview_lines(task.system, preview)
        head, *rest = lines or [""]
        intro = bullets(rest, head)
        if preview.empty:
            self.view.setHtml(intro + bullets(
                what, _t("Nothing needs writing: the prosthesis already holds this.")))
            self.idle(_t("Next goes on without writing anything."))
        else:
            how = (_t("Press the button below to write this to the prosthesis. The parts "
                      "that move are held still while it is written, then everything is read "
                      "back and checked; on any difference the prosthesis is put back as it "
                      "was.") if change.moves else
                   _t("Press the button below to write this to the prosthesis. It is read "
                      "back and checked; on any difference the prosthesis is put back as it "
                      "was."))
            self.view.setHtml(intro + bullets(what, how))
            self.idle()
        self.set_ready(True)

    def validatePage(self) -> bool:
        if self.result is not None and self.result.ok:
            return True
        if self.preview is not None and self.preview.empty:
            return True
        if self.runner.running or self.change is None:
            return False
        if not self.runner.start(self.change, list(self.preview.links_before)):
            self.idle(_t("No prosthesis is connected."))
            return False
        self.result = None
        self.set_ready(False)
        self.stop.show()
        self.stop.setEnabled(True)
        self.working(_t("Writing to the prosthesis…"))
        self._buttons(False)
        return False

    def _buttons(self, enabled: bool) -> None:
        for b in (QWizard.WizardButton.BackButton, QWizard.WizardButton.CancelButton):
            button = self.task.button(b)
            if button is not None:
                button.setEnabled(enabled)

    def _progress(self, done: int, total: int, text: str) -> None:
        if total > 0:
            self.busy.setRange(0, total)
            self.busy.setValue(min(done, total))
        if text:
            self.status.setText(text)

    def _stop(self) -> None:
        self.stop.setEnabled(False)
        self.status.setText(_t("Stopping… (the prosthesis is put back as it was)"))
        self.runner.cancel()

    def _finished(self, result: Any) -> None:
        self.stop.hide()
        self.busy.setRange(0, 0)
        self._buttons(True)
        self.result = result
        status = getattr(result.status, "value", str(result.status))
        if result.ok:
            self.task.results.append(result)
            where = (_t(" Recorded in the fitting history as entry {0}.")
                     .format(result.history_id) if result.history_id else "")
            self.idle(_t("Written, read back and verified.") + where)
            self.set_ready(True)
            if self.task.currentPage() is self:
                QTimer.singleShot(0, self.task.next)
            return
        if result.reason == "cancelled" or (self.runner.stop is not None
                                            and self.runner.stop.is_set()):
            text = _t("Stopped. The prosthesis is as it was before.")
        elif status == "declined":
            text = _t("The prosthesis changed after the preview, so nothing was "
                      "written. Go back to look at it again.")
        else:
            text = _t("Not written: {0}. The prosthesis is as it was before.").format(
                result.reason or status)
        self.idle(text)
        self.set_ready(True)

    def _failed(self, message: str) -> None:
        self.stop.hide()
        self._buttons(True)
        self.failed(message)
        self.set_ready(True)


class VerifyPage(Page):
    """Read the prosthesis back and compare it with what the task wrote."""

    def __init__(self) -> None:
        super().__init__(_t("Verify"),
                         _t("PDCP Studio reads the links and the stored configuration "
                                 "back from the prosthesis and compares them with what was "
                                 "written."))
        self.problems: list[Any] = []

    def initializePage(self) -> None:
        self.read_bus(self._check)

    def _check(self, _got: Any) -> None:
        from pdcp_studio.app.wizards.logic import verify

        task = self.task
        configuration = getattr(task.change, "configuration", None)
        self.problems = verify(task.system, task.stored, task.expected_links, configuration)
        lines = []
        for p in self.problems:
            if p.kind == "link-missing" and p.link is not None:
                lines.append(f"{WARN_MARK} " + _t("Not on the prosthesis: {0}").format(
                    words.link_words(task.system, p.link)))
            elif p.kind == "link-extra" and p.link is not None:
                lines.append(f"{WARN_MARK} " + _t("Also on the prosthesis: {0}").format(
                    words.link_words(task.system, p.link)))
            elif p.kind == "config-differs":
                lines.append(f"{WARN_MARK} " + _t("The stored configuration is not the "
                                                       "one written."))
            elif p.kind == "part-missing" and p.key is not None:
                lines.append(f"{WARN_MARK} " + _t("{0} is not on the bus.").format(
                    words.part_words(task.system, p.key)))
        if not self.problems:
            lines = [f"{OK_MARK} " + words.count("On the prosthesis as planned: %n link(s).",
                                                 len(task.expected_links)),
                     f"{OK_MARK} " + _t("Every linked part is on the bus.")]
            if configuration is not None:
                lines.append(f"{OK_MARK} " + _t("The stored configuration reads back as "
                                                     "written."))
        for result in task.results:
            if result.history_id:
                lines.append(f"{OK_MARK} " + _t("Fitting history entry {0}: written and "
                                                "verified by the prosthesis.")
                             .format(result.history_id))
        self.view.setHtml(bullets(lines, marks=True))
        self.idle(_t("Everything is as written.") if not self.problems else
                  _t("The prosthesis is not as written: look at the points above."))
        self.set_ready(True)


class ReportPage(Page):
    """What the task did, and the fitting report to save."""

    def __init__(self) -> None:
        super().__init__(_t("Report"),
                         _t("The fitting is recorded in the fitting history. Save the "
                                 "fitting report to print it or keep it with the patient's "
                                 "file."))
        self.save_button = QPushButton(_t("Save the fitting report (PDF)…"))
        self.save_button.clicked.connect(self.ask_save)
        self.box.addWidget(self.save_button, 0, Qt.AlignmentFlag.AlignLeft)
        self.setFinalPage(True)

    def initializePage(self) -> None:
        task = self.task
        lines = []
        for result in task.results:
            entry = (_t("entry {0}").format(result.history_id) if result.history_id
                     else _t("not recorded"))
            lines.append(_t("{0}: written and verified ({1}, {2})").format(
                words.action_words(result.action), entry,
                words.count("%n link(s) on the prosthesis", len(result.links_after))))
        if not lines:
            lines.append(_t("Nothing needed writing: the prosthesis already held it."))
        self.view.setHtml(bullets(lines, _t("Done:")))
        self.idle()
        self.set_ready(True)

    def ask_save(self) -> None:
        window = self.task.main
        path, _ = QFileDialog.getSaveFileName(
            self, _t("Fitting report"), str(Path(window._last_dir()) / "fitting.pdf"),
            _t("PDF (*.pdf)"))
        if path:
            self.save_report(path)

    def save_report(self, path: str | Path) -> bool:
        """Write the fitting report of this session (the changes just made)."""
        ok = bool(self.task.main.write_fitting_report(path))
        if ok:
            self.task.report_path = Path(path)
            self.idle(_t("Saved the fitting report: {0}").format(path))
        return ok

