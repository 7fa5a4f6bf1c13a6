"""Go to device: type part of a name (or VID/PID/serial), pick it, the graph shows it.

A small non-modal popup: on a 32- or 254-device bus a prosthetist finds "Hand 3" faster
by typing than by scrolling the graph.
"""

from __future__ import annotations

from collections.abc import Callable

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QDialog, QLineEdit, QListWidget, QListWidgetItem, QVBoxLayout, QWidget

from pdcp_studio.app.words.part_names import part_names
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import System


def device_matches(system: System, text: str) -> list[tuple[DeviceKey, str]]:
    """Devices whose shown name or ``VID/PID/serial`` contains ``text`` (any case), by name."""
    needle = text.strip().lower()
    names = part_names(system)
    out = []
    for key in system.devices:
        label = names[key]
        numbers = f"{key.vid}/{key.pid}/{key.serial}"
        if not needle or needle in label.lower() or needle in numbers:
            out.append((key, label))
    return sorted(out, key=lambda kl: (kl[1].lower(), kl[0]))


class DeviceFinder(QDialog):
    """The Go to device popup; ``chosen(key)`` is called with the device picked."""

    def __init__(self, system: System, chosen: Callable[[DeviceKey], None],
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(self.tr("Go to device"))
        self.system, self.chosen = system, chosen
        self.field = QLineEdit()
        self.field.setPlaceholderText(self.tr("Device name or VID/PID/serial"))
        self.results = QListWidget()
        layout = QVBoxLayout(self)
        layout.addWidget(self.field)
        layout.addWidget(self.results)
        self.field.textChanged.connect(self._filter)
        self.field.returnPressed.connect(self._accept_current)
        self.results.itemActivated.connect(lambda _item: self._accept_current())
        self._filter("")
        self.resize(360, 320)

    def _filter(self, text: str) -> None:
        self.results.clear()
        for key, label in device_matches(self.system, text):
            item = QListWidgetItem(label)
            item.setData(Qt.ItemDataRole.UserRole, key)
            item.setToolTip(f"VID {key.vid} · PID {key.pid} · serial {key.serial}")
            self.results.addItem(item)
        if self.results.count():
            self.results.setCurrentRow(0)

    def _accept_current(self) -> None:
        item = self.results.currentItem()
        if item is None:
            return
        self.chosen(item.data(Qt.ItemDataRole.UserRole))
        self.accept()
