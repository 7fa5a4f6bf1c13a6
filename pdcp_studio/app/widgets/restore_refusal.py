"""A restore that needs a part no longer on the bus is refused before anything is written:
the message names the part as every other text does and offers Replace a part.

``bus.transaction.restore_change`` raises ``NotRestorable`` with ``missing`` (the parts'
keys); the History panel and the Restore wizard both ask here, so the refusal reads the same
wherever it is met. It is shown at once, on top, before any progress dialog exists.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Sequence
from typing import Any

from PySide6.QtWidgets import QMessageBox, QWidget

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.words.effect_words import app_names
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import System

_CTX = "RestoreRefusal"


def _tr(text: str) -> str:
    return translate(_CTX, text)


def missing_words(entry_id: Any, missing: Sequence[DeviceKey], system: System | None) -> str:
    """Why a restore of entry ``entry_id`` is refused, naming the absent parts."""
    names = app_names(system)
    parts = ", ".join(names.part(k) for k in missing)
    if len(missing) == 1:
        text = _tr("Fitting history entry {0} cannot be put back: it needs {1}, which is not "
                   "on the bus. Nothing was written.")
    else:
        text = _tr("Fitting history entry {0} cannot be put back: it needs {1}, which are not "
                   "on the bus. Nothing was written.")
    return text.format(entry_id, parts) + "\n\n" + _tr(
        "Plug the part in and try again, or use Replace a part to give its links to the part "
        "that took its place.")


def refuse(parent: QWidget | None, title: str, text: str,
           open_replace: Callable[[], Any] | None) -> QMessageBox:
    """Show the refusal (window-modal, on top) with a Replace a part button when
    ``open_replace`` is given; returns the box (tests read and answer it)."""
    box = QMessageBox(QMessageBox.Icon.Warning, title, text, QMessageBox.StandardButton.Close,
                      parent)
    replace = None
    if open_replace is not None:
        replace = box.addButton(_tr("Replace a part…"), QMessageBox.ButtonRole.ActionRole)
    box.setDefaultButton(QMessageBox.StandardButton.Close)

    def answered(_code: int) -> None:
        if replace is not None and box.clickedButton() is replace and open_replace is not None:
            open_replace()
        box.deleteLater()

    box.finished.connect(answered)
    box.open()
    box.raise_()
    return box


def keep_recorded_configuration(change: Any, on: bool) -> Any:
    """The store box of a restore: ticked puts back the stored configuration the entry
    recorded (the default, as ``history restore``), unticked leaves the prosthesis's."""
    if on:
        return change
    chosen = copy.copy(change)
    chosen.configuration = None
    chosen.store = False
    return chosen
