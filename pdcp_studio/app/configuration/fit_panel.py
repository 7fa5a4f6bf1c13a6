"""The stored-configuration window's Fit tab: how the current configuration fits a
prosthesis — which configuration start-up would pick and why, what becomes of each stored
link, and the steps start-up would take.
"""

from __future__ import annotations

from typing import Any

from PySide6.QtCore import QCoreApplication, Qt, QTimer
from PySide6.QtWidgets import (
    QLabel,
    QListView,
    QListWidget,
    QListWidgetItem,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.configuration.words import ConfigWords
from pdcp_studio.app.documents.config_document import ConfigDocument
from pdcp_studio.app.words.plural import count
from pdcp_studio.errors import PdcpError
from pdcp_studio.model.system import System


def _tr(text: str) -> str:
    return QCoreApplication.translate("ConfigWindow", text)


def wrapping_list() -> QListWidget:
    """A list of sentences: wrapped to the width, never cut short."""
    lst = QListWidget()
    lst.setWordWrap(True)
    lst.setSpacing(3)
    lst.setTextElideMode(Qt.TextElideMode.ElideNone)
    lst.setResizeMode(QListView.ResizeMode.Adjust)
    return lst


class FitPanel(QWidget):
    """The fit of ``doc``'s current configuration (``fit``: the last one shown, or None)."""

    def __init__(self, doc: ConfigDocument, words: ConfigWords) -> None:
        super().__init__()
        self._doc = doc
        self._words = words
        self.fit: Any = None
        self.fit_label = QLabel("")
        self.fit_label.setWordWrap(True)
        self.fit_choice = QLabel("")
        self.fit_choice.setWordWrap(True)
        self.fit_list = wrapping_list()
        self.btn_fit_main = QPushButton(_tr("Fit to the prosthesis in the main window"))
        self.btn_fit_file = QPushButton(_tr("Fit to a system file…"))
        fv = QVBoxLayout(self)
        fv.addWidget(self.fit_label)
        fv.addWidget(self.fit_choice)
        fv.addWidget(self.fit_list, 1)
        fv.addWidget(self.btn_fit_main)
        fv.addWidget(self.btn_fit_file)

    def show_fit(self, system: System | None, name: str) -> None:
        """Fit the current configuration to ``system`` (named ``name``; None: no
        prosthesis to fit to)."""
        from pdcp_studio.app.words.part_names import one_naming

        with one_naming(system):  # a row per stored link and step: one lookup for all
            self._show_fit(system, name)

    def _show_fit(self, system: System | None, name: str) -> None:
        from pdcp_studio.engine.config_fit import fit_configuration

        doc, words = self._doc, self._words
        self.fit_list.clear()
        self.fit = None
        cfg = doc.configuration()
        if system is None or not system.devices:
            self.fit_label.setText(_tr(
                "No prosthesis to fit to. Open a system file or connect to a bus in the main "
                "window, or choose a system file here."))
            self.fit_choice.setText("")
            return
        self.fit_label.setText(_tr("Fitted to %1.").replace("%1", name))
        if cfg is None:
            self.fit_choice.setText("")
            return
        try:
            fit = fit_configuration(system, doc.collection, doc.current)
        except PdcpError as err:
            self.fit_choice.setText(str(err))
            return
        self.fit = fit
        self.fit_choice.setText(_tr("At start-up: %1").replace("%1", fit.chosen_reason))
        self.fit_choice.setStyleSheet("font-weight: bold;" if fit.chosen_index == fit.index
                                      else "")
        for lf in fit.links:
            sl = lf.link
            number = str(sl.index or lf.position + 1)
            label = _tr("Link %1: %2 → %3\n%4").replace("%1", number) \
                .replace("%2", words.channel_text(sl.output)) \
                .replace("%3", words.channel_text(sl.input)) \
                .replace("%4", words.link_fit_words(lf, system, fit.plan))
            item = QListWidgetItem(label)
            item.setToolTip(lf.summary())  # the engineer's words
            if not lf.whole:
                item.setForeground(Qt.GlobalColor.darkRed if not lf.actions
                                   else Qt.GlobalColor.darkYellow)
            self.fit_list.addItem(item)
        if fit.plan.actions:
            head = QListWidgetItem(count("ConfigWindow", "What start-up would do with this "
                                         "configuration (%n step(s)):", len(fit.plan.actions)))
            head.setForeground(Qt.GlobalColor.darkBlue)
            self.fit_list.addItem(head)
            for a in fit.plan.actions:
                step = QListWidgetItem("    " + words.plan_step_words(a, system))
                step.setToolTip(f"{a.op.value} {a.link.output} → {a.link.input}: {a.reason}")
                self.fit_list.addItem(step)
        QTimer.singleShot(0, self.fit_list.doItemsLayout)  # wrap at the width it has now
