"""The stored-configuration window's dialogs: a stored channel's type and profile, and a
new stored link (its two ends picked from known channels or entered as numbers).
"""

from __future__ import annotations

from PySide6.QtWidgets import (
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QFormLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.model.configuration import StoredChannel


def hex_word(value: int) -> str:
    """A 16-bit value as the file shows it (``0x2110``)."""
    return f"0x{value:04X}"


def parse_word(text: str) -> int:
    """``0x2110``, ``2110h`` is not accepted: hex with 0x, or a decimal number, 0…0xFFFF."""
    text = text.strip()
    value = int(text, 16) if text.lower().startswith("0x") else int(text, 10)
    if not 0 <= value <= 0xFFFF:
        raise ValueError(f"{text} is out of range 0…0xFFFF")
    return value


class ChannelDialog(QDialog):
    """Type and profile of one stored channel."""

    def __init__(self, title: str, ch: StoredChannel, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(title)
        form = QFormLayout(self)
        self.type_edit = QLineEdit(hex_word(ch.type))
        self.profile_edit = QLineEdit(hex_word(ch.profile))
        form.addRow(self.tr("Channel type"), self.type_edit)
        form.addRow(self.tr("Channel profile"), self.profile_edit)
        self.error = QLabel("")
        self.error.setStyleSheet("color: #b3261e;")
        form.addRow(self.error)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok
                                   | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def values(self) -> tuple[int, int] | None:
        try:
            return parse_word(self.type_edit.text()), parse_word(self.profile_edit.text())
        except ValueError:
            return None

    def accept(self) -> None:
        if self.values() is None:
            self.error.setText(self.tr("Type and profile are numbers from 0 to 0xFFFF "
                                       "(write hex as 0x2110)."))
            return
        super().accept()


class _EndEditor(QGroupBox):
    """One end of a new link: pick a known channel or enter its numbers."""

    def __init__(self, title: str, known: list[tuple[str, StoredChannel]]) -> None:
        super().__init__(title)
        form = QFormLayout(self)
        self.pick = QComboBox()
        self.pick.addItem(self.tr("Enter the numbers below"), None)
        for label, ch in known:
            self.pick.addItem(label, ch)
        form.addRow(self.tr("Channel"), self.pick)
        self.spins: dict[str, QSpinBox] = {}
        for name, label, lo, hi in (("vid", self.tr("Vendor ID"), 0, 0xFFFF),
                                    ("pid", self.tr("Product ID"), 0, 0xFFFF),
                                    ("serial", self.tr("Serial number"), 0, 0xFFFF),
                                    ("index", self.tr("Channel index"), 1, 255)):
            spin = QSpinBox()
            spin.setRange(lo, hi)
            self.spins[name] = spin
            form.addRow(label, spin)
        self.type_edit, self.profile_edit = QLineEdit("0x0000"), QLineEdit("0x0000")
        form.addRow(self.tr("Channel type"), self.type_edit)
        form.addRow(self.tr("Channel profile"), self.profile_edit)
        self.pick.currentIndexChanged.connect(self._picked)

    def _picked(self) -> None:
        ch = self.pick.currentData()
        if ch is None:
            return
        for name, spin in self.spins.items():
            spin.setValue(getattr(ch, name))
        self.type_edit.setText(hex_word(ch.type))
        self.profile_edit.setText(hex_word(ch.profile))

    def channel(self) -> StoredChannel:
        """The channel as entered (ValueError naming a bad number)."""
        v = {name: spin.value() for name, spin in self.spins.items()}
        return StoredChannel(index=v["index"], vid=v["vid"], pid=v["pid"], serial=v["serial"],
                             type=parse_word(self.type_edit.text()),
                             profile=parse_word(self.profile_edit.text()))


class AddLinkDialog(QDialog):
    """A new stored link: an output and an input, known channels offered first."""

    def __init__(self, outputs: list[tuple[str, StoredChannel]],
                 inputs: list[tuple[str, StoredChannel]], parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(self.tr("Add a link"))
        layout = QVBoxLayout(self)
        row = QHBoxLayout()
        self.output = _EndEditor(self.tr("From (output)"), outputs)
        self.input = _EndEditor(self.tr("To (input)"), inputs)
        row.addWidget(self.output)
        row.addWidget(self.input)
        layout.addLayout(row)
        self.error = QLabel("")
        self.error.setStyleSheet("color: #b3261e;")
        layout.addWidget(self.error)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok
                                   | QDialogButtonBox.StandardButton.Cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        layout.addWidget(buttons)

    def ends(self) -> tuple[StoredChannel, StoredChannel] | None:
        try:
            return self.output.channel(), self.input.channel()
        except ValueError:
            return None

    def accept(self) -> None:
        ends = self.ends()
        if ends is None:
            self.error.setText(self.tr("Type and profile are numbers from 0 to 0xFFFF "
                                       "(write hex as 0x2110)."))
            return
        if ends[0].ref == ends[1].ref:
            self.error.setText(self.tr("A link joins two different channels."))
            return
        super().accept()
