"""The pages of a guided task that change the prosthesis: the change worked out and
previewed, then written as one transaction.

The write page is a commit page: its button is the user's confirmation of the preview shown
before it, and after a write there is no way back (a written change is undone by a new
transaction, as everywhere in the app).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, NamedTuple

from PySide6.QtCore import Qt, QTimer
from PySide6.QtWidgets import (
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPlainTextEdit,
    QPushButton,
    QWizard,
)

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.wizards import words
from pdcp_studio.app.wizards.runner import TransactionRunner, look, on_bus
from pdcp_studio.app.wizards.task_wizard import Page, TaskWizard, bullets

if TYPE_CHECKING:
    from pdcp_studio.bus.session.api import ChangePreview
    from pdcp_studio.bus.session.base import BusSession
    from pdcp_studio.bus.transaction import Change, Policy, TransactionResult
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.model.system import Link, System


def _t(text: str) -> str:
    return translate("Wizards", text)


#: ``build(task, system, stored) -> (lines, change, expected_links)``: a task's change
#: worked out from the prosthesis as it is, in words (the first line heads the others).
Build = Callable[[TaskWizard, "System", "ConfigCollection | None"],
                 tuple[list[str], "Change", list["Link"]]]


class Worked(NamedTuple):
    """A change worked out on the bus worker: the prosthesis it was worked out from, its
    words, the change, the links it should leave, and its preview."""

    system: System
    stored: ConfigCollection | None
    policy: Policy | None
    lines: list[str]
    change: Change
    expected_links: list[Link]
    preview: ChangePreview


def work_out(task: TaskWizard, build: Build) -> Callable[[Any], Worked]:
    """What the bus worker runs to work ``build``'s change out and preview it (the engine
    is pure; the session is read there, never on the GUI thread)."""

    def work(session: BusSession) -> Worked:
        from pdcp_studio.app.words.effect_words import app_names
        from pdcp_studio.bus.session.api import preview_change

        system, stored, policy = look(session)
        lines, change, expected = build(task, system, stored)
        return Worked(system, stored, policy, lines, change, expected,
                      preview_change(session, change, names=app_names(system)))

    return work


class ChangePage(Page):
    """A change worked out from the prosthesis as it is, explained, then previewed (what the
    transaction would write). ``build`` (:data:`Build`) runs on the bus worker; the wizard
    keeps ``change`` and ``preview`` for the write page."""

    def __init__(self, title: str, subtitle: str, build: Build) -> None:
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
        #: The effect's words include the links made and removed (False: the lines
        #: ``build`` gives, a plan's steps, already say them).
        self.effect_links = False

    def initializePage(self) -> None:
        self.set_ready(False)
        self.view.clear()
        self.working(_t("Working out the change…"))
        task = self.task
        if not on_bus(task.main, work_out(task, self.build), "Preview the change",
                      self._previewed, self.failed, owner=self):
            self.idle(_t("No prosthesis is connected."))

    def _previewed(self, got: Worked) -> None:
        task = self.task
        (task.system, task.stored, task.policy, self.lines, task.change,
         task.expected_links, task.preview) = got
        preview_words = words.preview_lines(got.system, got.preview,
                                            links=self.effect_links)
        head, *lines = self.lines or [""]
        self.view.setHtml(bullets(lines, head)
                          + bullets(preview_words, _t("When it is written:")))
        plan = got.change.plan
        effect = got.preview.effect  # the codes behind the words, as in the confirmation
        detail = list(effect.technical()) if effect is not None else list(got.preview.lines())
        if plan is not None:
            detail += ["", plan.to_text(task.main.doc.tree)]
        self.detail.setPlainText("\n".join(detail))
        self.idle()
        self.set_ready(True)


class WritePage(Page):
    """Write the previewed change as one transaction, with progress and Stop; the page's
    Write button confirms it. With ``build`` the page works its change out itself (as a
    :class:`ChangePage` does) and shows it before writing.

    The page asks for the patient reference (optional; the window's, as the Pending changes
    panel has it, or the one given on an earlier page of the task): it is recorded in the
    fitting history entry and remembered for the prosthesis. When nothing needs writing the
    button is Continue, and the page says that."""

    def __init__(self, title: str, subtitle: str, button: str,
                 build: Build | None = None) -> None:
        super().__init__(title, subtitle)
        self.setCommitPage(True)
        self.write_label = button
        self.setButtonText(QWizard.WizardButton.CommitButton, button)
        self.build = build
        self.patient = QLineEdit()
        self.patient.setPlaceholderText(_t("optional, e.g. the clinic's case number"))
        self.patient.setClearButtonEnabled(True)
        self.patient_label = QLabel(_t("Patient reference:"))
        self.patient_label.setBuddy(self.patient)
        row = QHBoxLayout()
        row.addWidget(self.patient_label)
        row.addWidget(self.patient, 1)
        self.box.insertLayout(self.box.indexOf(self.busy), row)
        self.runner = TransactionRunner(None, self)
        self.runner.progress.connect(self._progress)
        self.runner.finished.connect(self._finished)
        self.runner.failed.connect(self._failed)
        self.stop = QPushButton(_t("Stop and put the prosthesis back"))
        self.stop.hide()
        self.stop.clicked.connect(self._stop)
        self.box.addWidget(self.stop, 0, Qt.AlignmentFlag.AlignLeft)
        self.result: TransactionResult | None = None
        self.change: Change | None = None
        self.preview: ChangePreview | None = None

    @property
    def writing(self) -> bool:
        return self.runner.running

    def initializePage(self) -> None:
        self.runner.window = self.task.main
        self.result = None
        self.set_ready(False)
        task = self.task
        known = task.patient if task.patient is not None else task.main.patient_reference()
        self.patient.setText(known or "")
        if self.build is None:
            self._show(task.system, task.change, task.preview)
            return
        self.working(_t("Working out the change…"))
        if not on_bus(task.main, work_out(task, self.build), "Preview the change",
                      self._built, self.failed, owner=self):
            self.idle(_t("No prosthesis is connected."))

    def _built(self, got: Worked) -> None:
        task = self.task
        (task.system, task.stored, task.policy, _lines, task.change, task.expected_links,
         task.preview) = got
        self._show(got.system, got.change, got.preview, got.lines)

    def _show(self, system: System | None, change: Change | None,
              preview: ChangePreview | None, lines: list[str] | None = None) -> None:
        """Show the change to write (none was worked out: the page says so)."""
        self.change, self.preview = change, preview
        if system is None or change is None or preview is None:
            self.idle(_t("Nothing was worked out to write."))
            return
        what = words.preview_lines(system, preview)
        head, *rest = lines or [""]
        intro = bullets(rest, head)
        for widget in (self.patient, self.patient_label):
            widget.setVisible(not preview.empty)  # nothing written: nothing recorded
        if preview.empty:
            go_on = _t("Continue")
            self.setButtonText(QWizard.WizardButton.CommitButton, go_on)
            self.view.setHtml(intro + bullets(
                what, _t("Nothing needs writing: the prosthesis already holds this.")))
            self.idle(_t("Press {0} to carry on; nothing is written.").format(go_on))
        else:
            self.setButtonText(QWizard.WizardButton.CommitButton, self.write_label)
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
        if self.runner.running or self.change is None or self.preview is None:
            return False
        patient = self.remember_patient()
        if not self.runner.start(self.change, list(self.preview.links_before), patient):
            self.idle(_t("No prosthesis is connected."))
            return False
        self.result = None
        self.set_ready(False)
        self.stop.show()
        self.stop.setEnabled(True)
        self.working(_t("Writing to the prosthesis…"))
        self._buttons(False)
        return False

    def remember_patient(self) -> str:
        """The patient reference given here, kept for the task's other pages and for the
        window (the Pending changes panel, remembered per prosthesis)."""
        text = self.patient.text().strip()
        self.task.patient = text
        keep = getattr(getattr(self.task.main, "transactions", None), "set_patient_reference",
                       None)
        if callable(keep):
            keep(text)
        return text

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

    def _finished(self, result: TransactionResult) -> None:
        self.stop.hide()
        self.busy.setRange(0, 0)
        self._buttons(True)
        self.result = result
        status = result.status.value
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
