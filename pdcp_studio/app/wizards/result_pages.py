"""The last pages of a guided task: the prosthesis read back and compared with what was
written, and what the task did with the fitting report to save."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QFileDialog, QPushButton

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.wizards import words
from pdcp_studio.app.wizards.logic import Problem, verify
from pdcp_studio.app.wizards.runner import Look
from pdcp_studio.app.wizards.task_wizard import OK_MARK, WARN_MARK, Page, bullets


def _t(text: str) -> str:
    return translate("Wizards", text)


class VerifyPage(Page):
    """Read the prosthesis back and compare it with what the task wrote."""

    def __init__(self) -> None:
        super().__init__(_t("Verify"),
                         _t("PDCP Studio reads the links and the stored configuration "
                                 "back from the prosthesis and compares them with what was "
                                 "written."))
        self.problems: list[Problem] = []

    def initializePage(self) -> None:
        self.read_bus(self._check)

    def _check(self, got: Look) -> None:
        task = self.task
        system = got.system
        configuration = task.change.configuration if task.change is not None else None
        self.problems = verify(system, got.stored, task.expected_links, configuration)
        lines = []
        for p in self.problems:
            if p.kind == "link-missing" and p.link is not None:
                lines.append(f"{WARN_MARK} " + _t("Not on the prosthesis: {0}").format(
                    words.link_words(system, p.link)))
            elif p.kind == "link-extra" and p.link is not None:
                lines.append(f"{WARN_MARK} " + _t("Also on the prosthesis: {0}").format(
                    words.link_words(system, p.link)))
            elif p.kind == "config-differs":
                lines.append(f"{WARN_MARK} " + _t("The stored configuration is not the "
                                                       "one written."))
            elif p.kind == "part-missing" and p.key is not None:
                lines.append(f"{WARN_MARK} " + _t("{0} is not on the bus.").format(
                    words.part_words(system, p.key)))
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
        html = bullets(lines, marks=True)
        effect = task.preview.effect if task.preview is not None else None
        if effect is not None and task.results:  # what was written stays, or not
            from pdcp_studio.app.words.effect_words import effect_tr

            html += bullets(effect.power_on_lines(effect_tr),
                            _t("When the prosthesis is next switched on:"))
        self.view.setHtml(html)
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
