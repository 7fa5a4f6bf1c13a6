"""The stored-configuration window's link table: one row per stored link of the current
configuration (its number, each end's channel, form and what it carries), and the buttons
that add, remove and edit them.
"""

from __future__ import annotations

from PySide6.QtCore import QCoreApplication
from PySide6.QtWidgets import (
    QAbstractItemView,
    QHBoxLayout,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.configuration.dialogs import hex_word
from pdcp_studio.app.configuration.words import ConfigWords
from pdcp_studio.model import profile as prof
from pdcp_studio.model.configuration import StoredConfiguration


def _tr(text: str) -> str:
    return QCoreApplication.translate("ConfigWindow", text)


class LinksPanel(QWidget):
    """The table (``links``) and its buttons; the window connects what they do."""

    def __init__(self, words: ConfigWords) -> None:
        super().__init__()
        self._words = words
        self.links = QTableWidget(0, 7)
        self.links.setHorizontalHeaderLabels([
            _tr("Link"), _tr("From (output)"), _tr("Form"), _tr("What it carries"),
            _tr("To (input)"), _tr("Form"), _tr("What it carries")])
        self.links.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.links.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        self.links.verticalHeader().hide()
        self.links.horizontalHeader().setStretchLastSection(True)
        self.btn_add_link = QPushButton(_tr("Add link…"))
        self.btn_del_link = QPushButton(_tr("Remove link"))
        self.btn_edit_out = QPushButton(_tr("Edit output channel…"))
        self.btn_edit_in = QPushButton(_tr("Edit input channel…"))
        bv = QVBoxLayout(self)
        bv.setContentsMargins(0, 0, 0, 0)
        bv.addWidget(self.links, 1)
        h = QHBoxLayout()
        for b in (self.btn_add_link, self.btn_del_link, self.btn_edit_out, self.btn_edit_in):
            h.addWidget(b)
        h.addStretch(1)
        bv.addLayout(h)

    def fill(self, cfg: StoredConfiguration | None) -> None:
        """The stored links of ``cfg`` (none without a configuration)."""
        words = self._words
        links = cfg.links if cfg is not None else []
        self.links.setRowCount(len(links))
        for row, sl in enumerate(links):
            cells = [str(sl.index or row + 1), words.channel_text(sl.output),
                     words.type_text(sl.output.type), words.profile_text(sl.output.profile),
                     words.channel_text(sl.input), words.type_text(sl.input.type),
                     words.profile_text(sl.input.profile)]
            for col, text in enumerate(cells):
                item = QTableWidgetItem(text)
                ch = sl.output if col in (1, 2, 3) else sl.input
                if col in (1, 4):  # the engineer's detail, one hover away
                    item.setToolTip(f"{ch.vid}/{ch.pid}/{ch.serial} #{ch.index}")
                elif col in (2, 5):
                    item.setToolTip(_tr("type {code}").format(code=hex_word(ch.type)))
                elif col in (3, 6):
                    item.setToolTip(_tr("profile {code}").format(code=prof.fmt(ch.profile)))
                self.links.setItem(row, col, item)
        self.links.resizeColumnsToContents()

    def selected(self) -> list[int]:
        """The positions of the selected links, in order."""
        return sorted({i.row() for i in self.links.selectionModel().selectedRows()})

    def select(self, positions: list[int]) -> None:
        self.links.clearSelection()
        mode = self.links.selectionMode()
        self.links.setSelectionMode(QAbstractItemView.SelectionMode.MultiSelection)
        for p in positions:
            self.links.selectRow(p)
        self.links.setSelectionMode(mode)

    def update_buttons(self, has_cfg: bool) -> None:
        selected = self.selected() if has_cfg else []
        self.btn_add_link.setEnabled(has_cfg)
        self.btn_del_link.setEnabled(bool(selected))
        self.btn_edit_out.setEnabled(len(selected) == 1)
        self.btn_edit_in.setEnabled(len(selected) == 1)
