"""The stored-configuration window's left side: the file's configurations in order, each
with its link count (marked when its checks find an error), and the buttons that add,
duplicate, remove and reorder them.
"""

from __future__ import annotations

from PySide6.QtCore import QCoreApplication, Qt
from PySide6.QtWidgets import (
    QHBoxLayout,
    QLabel,
    QListWidget,
    QListWidgetItem,
    QPushButton,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.documents.config_document import ConfigDocument
from pdcp_studio.app.words.plural import count
from pdcp_studio.engine.config_checks import check_configuration


def _tr(text: str) -> str:
    return QCoreApplication.translate("ConfigWindow", text)


class ConfigListPanel(QWidget):
    """The configurations of ``doc``; picking one makes it the document's current one."""

    def __init__(self, doc: ConfigDocument) -> None:
        super().__init__()
        self._doc = doc
        self.config_list = QListWidget()
        self.config_list.currentRowChanged.connect(doc.set_current)
        self.btn_add_cfg = QPushButton(_tr("Add"))
        self.btn_dup_cfg = QPushButton(_tr("Duplicate"))
        self.btn_del_cfg = QPushButton(_tr("Remove"))
        self.btn_up_cfg = QPushButton(_tr("Move up"))
        self.btn_down_cfg = QPushButton(_tr("Move down"))
        self.btn_add_cfg.clicked.connect(doc.add_configuration)
        self.btn_dup_cfg.clicked.connect(lambda: doc.duplicate_configuration())
        self.btn_del_cfg.clicked.connect(lambda: doc.remove_configuration())
        self.btn_up_cfg.clicked.connect(lambda: doc.move_configuration(-1))
        self.btn_down_cfg.clicked.connect(lambda: doc.move_configuration(+1))
        lv = QVBoxLayout(self)
        lv.setContentsMargins(6, 6, 6, 6)
        title = QLabel(_tr("Configurations"))
        title.setStyleSheet("font-weight: bold;")
        lv.addWidget(title)
        lv.addWidget(self.config_list, 1)
        hint = QLabel(_tr("At start-up the arbitrator picks the configuration that best "
                          "fits the devices present; on a tie, the higher one."))
        hint.setWordWrap(True)
        hint.setStyleSheet("color: #66707b;")
        lv.addWidget(hint)
        for row in ((self.btn_add_cfg, self.btn_dup_cfg), (self.btn_del_cfg,),
                    (self.btn_up_cfg, self.btn_down_cfg)):
            h = QHBoxLayout()
            for b in row:
                h.addWidget(b)
            lv.addLayout(h)

    def fill(self) -> None:
        """The document's configurations, its current one selected (no signal)."""
        doc = self._doc
        self.config_list.blockSignals(True)
        self.config_list.clear()
        for each in doc.collection.configurations:
            text = _tr("Configuration %1 · %2").replace("%1", str(each.index)) \
                .replace("%2", count("ConfigWindow", "%n link(s)", len(each.links)))
            item = QListWidgetItem(text)
            problems = [f for f in check_configuration(each) if f.severity.value == "error"]
            if problems:
                item.setToolTip(count("ConfigWindow", "%n problem(s) found", len(problems)))
                item.setForeground(Qt.GlobalColor.darkRed)
            self.config_list.addItem(item)
        self.config_list.setCurrentRow(doc.current)
        self.config_list.blockSignals(False)

    def update_buttons(self) -> None:
        doc = self._doc
        has_cfg = doc.configuration() is not None
        n = len(doc.collection.configurations)
        self.btn_dup_cfg.setEnabled(has_cfg)
        self.btn_del_cfg.setEnabled(has_cfg)
        self.btn_up_cfg.setEnabled(has_cfg and doc.current > 0)
        self.btn_down_cfg.setEnabled(has_cfg and doc.current < n - 1)
