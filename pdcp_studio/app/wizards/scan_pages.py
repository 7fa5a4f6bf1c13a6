"""The pages that read the prosthesis and say what is on it: the scan (every part) and the
engine's checks (what to look at, in plain words)."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QPushButton

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.wizards import words
from pdcp_studio.app.wizards.runner import Look, alive
from pdcp_studio.app.wizards.task_wizard import Page, bullets
from pdcp_studio.model.system import System


def _t(text: str) -> str:
    return translate("Wizards", text)


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

    def _scanned(self, system: System) -> None:
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

    def _show(self, got: Look) -> None:
        from pdcp_studio.app.words.finding_text import plain_finding
        from pdcp_studio.engine import check_system

        system, policy = got.system, got.policy
        auto = policy.autoconfigure if policy is not None else True
        findings = check_system(system, autoconfigure=auto)
        if not findings:
            self.view.setHtml(bullets([_t("No problems found: every part is described "
                                               "and linked as it asks.")]))
        else:
            names = words.part_names(system)  # two hands read apart
            lines = [plain_finding(f, system, auto, names) for f in findings]
            self.view.setHtml(bullets(lines, words.count(
                "%n thing(s) to look at. The next step proposes links that fix what can be "
                "fixed automatically:", len(findings))))
        self.set_ready(True)
