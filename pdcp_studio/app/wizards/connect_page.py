"""The first page of a guided task: which prosthesis to work on — the one connected now, a
simulated one (by what it is), or another connection — and connecting to it."""

from __future__ import annotations

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtWidgets import (
    QButtonGroup,
    QHBoxLayout,
    QListWidget,
    QListWidgetItem,
    QPushButton,
    QRadioButton,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.wizards.task_wizard import Page


def _t(text: str) -> str:
    return translate("Wizards", text)


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
