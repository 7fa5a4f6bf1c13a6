"""The confirmation before a change is written: its effect in words, the next power-on, and
whether to store it as the prosthesis's configuration.

Every line comes from the preview's :class:`~pdcp_studio.engine.effect.Effect` (the one
source of every text about a change), in the user's language; the codes behind them (link
references, parameter numbers and bytes, CRCs) only under "Technical detail", collapsed. The
store box (when the change offers it) asks the window's flow for a new preview, since the
stored configuration and the next power-on change with it; Write waits for that preview.
Writing always needs a click: Enter cancels.
"""

from __future__ import annotations

from typing import Any

from PySide6.QtCore import Qt, Signal
from PySide6.QtGui import QFont
from PySide6.QtWidgets import (
    QCheckBox,
    QDialog,
    QDialogButtonBox,
    QLabel,
    QPlainTextEdit,
    QPushButton,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.words.effect_words import effect_tr


def reasons_of(change: Any) -> dict[Any, str]:
    """Why each link of a plan is made or removed, in words (a staged edit has no plan)."""
    plan = getattr(change, "plan", None)
    if plan is None:
        return {}
    from pdcp_studio.app.words.plan_words import rule_words

    return {a.link: rule_words(a.rule) for a in plan.actions}


def effect_words(preview: Any) -> list[str]:
    """What the change does, in the effect's own words."""
    effect = preview.effect
    if effect is None:
        return []
    return list(effect.lines(effect_tr, reasons_of(preview.change)))


def power_on_words(preview: Any) -> list[str]:
    """What the next power-on does after the change, in the effect's own words."""
    effect = preview.effect
    return list(effect.power_on_lines(effect_tr)) if effect is not None else []


class ConfirmDialog(QDialog):
    """The preview of a change in words (see the module docstring).

    ``store``: None offers no store box; True/False shows it, checked or not. Signal
    ``storeToggled(bool)``: the user changed it; the owner answers with :meth:`set_preview`.
    """

    storeToggled = Signal(bool)

    def __init__(self, title: str, preview: Any, parent: QWidget | None = None, *,
                 store: bool | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(title)
        self.resize(860, 640)
        self.preview = preview
        head = QLabel(self.tr("This is what will change on the prosthesis. The devices that "
                              "drive a hand, wrist or elbow are held still while it is "
                              "written, then it is read back and verified; on any mismatch "
                              "the prosthesis is put back as it was."))
        head.setWordWrap(True)
        self.words = QPlainTextEdit()
        self.words.setReadOnly(True)
        self.words.setLineWrapMode(QPlainTextEdit.LineWrapMode.WidgetWidth)
        self.power_on = QLabel()
        self.power_on.setWordWrap(True)
        self.power_on.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.power_on.setMargin(6)
        self.store_box = QCheckBox(self.tr("Store as the prosthesis's configuration (keeps "
                                           "this after the next power-on)"))
        self.store_box.setVisible(store is not None)
        self.store_box.setChecked(bool(store))
        self.store_box.toggled.connect(self._store_toggled)
        self.waiting = QLabel(self.tr("Working out what the next power-on does…"))
        self.waiting.hide()
        self.detail_button = QToolButton()
        self.detail_button.setText(self.tr("Technical detail"))
        self.detail_button.setCheckable(True)
        self.detail_button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextBesideIcon)
        self.detail_button.setArrowType(Qt.ArrowType.RightArrow)
        self.detail_button.setAutoRaise(True)
        self.detail_button.toggled.connect(self._show_detail)
        self.detail = QPlainTextEdit()
        self.detail.setReadOnly(True)
        font = QFont("monospace")
        font.setStyleHint(QFont.StyleHint.Monospace)
        self.detail.setFont(font)
        self.detail.hide()
        buttons = QDialogButtonBox()
        self.write_button = QPushButton(self.tr("Write to prosthesis"))
        self.write_button.setAutoDefault(False)
        self.write_button.setDefault(False)
        buttons.addButton(self.write_button, QDialogButtonBox.ButtonRole.AcceptRole)
        cancel = buttons.addButton(QDialogButtonBox.StandardButton.Cancel)
        cancel.setDefault(True)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        box = QVBoxLayout(self)
        box.addWidget(head)
        box.addWidget(self.words, 3)
        box.addWidget(self.power_on)
        box.addWidget(self.store_box)
        box.addWidget(self.waiting)
        box.addWidget(self.detail_button, 0, Qt.AlignmentFlag.AlignLeft)
        box.addWidget(self.detail, 2)
        box.addWidget(buttons)
        self.set_preview(preview)

    # -- contents ------------------------------------------------------------------------
    def set_preview(self, preview: Any) -> None:
        """Show ``preview`` (a new one after the store box changed); Write may go on."""
        self.preview = preview
        self.words.setPlainText("\n".join(effect_words(preview)))
        effect = preview.effect
        self.power_on.setText("\n".join(power_on_words(preview)))
        undone = effect is not None and effect.next_power_on.reverts
        # Amber when the next power-on undoes (part of) the change: it must not be missed.
        self.power_on.setStyleSheet(
            "QLabel { background: %s; border: 1px solid %s; border-radius: 3px; }"
            % (("#fff3cd", "#d9a400") if undone else ("#eef5ee", "#9cbf9c")))
        self.detail.setPlainText("\n".join(effect.technical() if effect is not None else []))
        self.waiting.hide()
        self.store_box.setEnabled(True)
        self.write_button.setEnabled(True)

    def words_text(self) -> str:
        """What the prosthetist reads (the technical detail apart)."""
        return self.words.toPlainText() + "\n" + self.power_on.text()

    def technical_text(self) -> str:
        return self.detail.toPlainText()

    @property
    def store(self) -> bool:
        return not self.store_box.isHidden() and self.store_box.isChecked()

    def preview_failed(self, message: str) -> None:
        """The new preview could not be made: say why; Write stays off."""
        self.waiting.setText(self.tr("The change could not be previewed again: {0}")
                             .format(message))
        self.waiting.show()
        self.store_box.setEnabled(True)

    # -- reactions -----------------------------------------------------------------------
    def _store_toggled(self, on: bool) -> None:
        self.write_button.setEnabled(False)  # the shown effect is no longer the one written
        self.store_box.setEnabled(False)
        self.waiting.show()
        self.storeToggled.emit(on)

    def _show_detail(self, shown: bool) -> None:
        self.detail.setVisible(shown)
        self.detail_button.setArrowType(Qt.ArrowType.DownArrow if shown
                                        else Qt.ArrowType.RightArrow)
