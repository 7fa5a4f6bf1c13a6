"""The wizard every guided task is, and the page all its pages build on.

A :class:`TaskWizard` keeps what its pages found (``system``, ``stored``, ``change``,
``preview``, ``results``…) and its main window; a :class:`Page` reads the prosthesis on the
bus's worker (:mod:`.runner`), never on the GUI thread, and says what it found as an HTML
list (:func:`bullets`).
"""

from __future__ import annotations

import html
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from PySide6.QtCore import Qt, QTimer
from PySide6.QtGui import QCloseEvent, QKeyEvent, QShowEvent
from PySide6.QtWidgets import QLabel, QProgressBar, QTextBrowser, QVBoxLayout, QWizard, QWizardPage

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.wizards.runner import Look, look, on_bus

if TYPE_CHECKING:
    from pdcp_studio.app.wizards.logic import MissingPart
    from pdcp_studio.bus.session.api import ChangePreview
    from pdcp_studio.bus.transaction import Change, Policy, TransactionResult
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.model.refs import DeviceKey
    from pdcp_studio.model.system import Link, System

OK_MARK, WARN_MARK = "✓", "!"

#: Where a restore takes its configuration from: a file (its path and what it stores), or
#: a fitting-history entry (as ``History.entries`` gives it).
Source = (tuple[Literal["file"], tuple[Path, "ConfigCollection"]]
          | tuple[Literal["history"], dict[str, Any]])


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
        self.system: System | None = None
        self.stored: ConfigCollection | None = None
        self.policy: Policy | None = None
        self.change: Change | None = None
        self.preview: ChangePreview | None = None
        self.expected_links: list[Link] = []
        self.results: list[TransactionResult] = []
        self.report_path: Path | None = None
        # Replace a part: the parts gone, the keys seen before, the parts plugged in since.
        self.missing: list[MissingPart] = []
        self.known: set[DeviceKey] = set()
        self.new_parts: list[DeviceKey] = []
        # Restore: where the configuration comes from.
        self.source: Source | None = None
        #: The patient reference the write pages record (asked there; None: not asked yet).
        self.patient: str | None = None
        #: The parts a restore needs that are not on the bus (it was refused for them).
        self.missing_parts: list[DeviceKey] = []

    def showEvent(self, event: QShowEvent) -> None:
        super().showEvent(event)
        # Once the window system has framed it: beside the Simulator panel, not over it.
        QTimer.singleShot(0, self, self.keep_clear_of_simulator)

    def keep_clear_of_simulator(self) -> bool:
        """Place the wizard so that the Simulator panel it points to stays in view."""
        from pdcp_studio.app.wizards.placement import keep_clear

        docks = getattr(self.main, "_leaf_docks", None) or {}
        return keep_clear(self, docks.get("sim"))

    @property
    def writing(self) -> bool:
        return any(isinstance(p, Page) and p.writing
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

    @property
    def writing(self) -> bool:
        """True while the page writes to the prosthesis (the wizard does not close then)."""
        return False

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

    def read_bus(self, done: Callable[[Look], None], what: str = "") -> None:
        """Look at the prosthesis (system, stored configuration, policy) on the worker."""
        self.set_ready(False)
        self.working(what or _t("Looking at the prosthesis…"))
        if not on_bus(self.task.main, look, "Look at the prosthesis",
                      lambda got: self._looked(got, done), self.failed, owner=self):
            self.idle(_t("No prosthesis is connected."))

    def _looked(self, got: Look, done: Callable[[Look], None]) -> None:
        task = self.task
        task.system, task.stored, task.policy = got
        self.idle()
        done(got)
