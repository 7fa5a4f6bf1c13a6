"""The questions the main window asks before it drops something (unsaved changes, the
connection, unwritten changes to the prosthesis, quitting a live view with them).

Plain functions over a parent widget: the window asks them through methods of its own,
which tests replace with scripted answers.
"""

from __future__ import annotations

from pathlib import Path

from PySide6.QtWidgets import QMessageBox, QWidget

from pdcp_studio.app.i18n import translate
from pdcp_studio.app.words.plural import count

#: ``ask_quit_live`` answers.
QUIT_WRITE, QUIT_DISCARD, QUIT_CANCEL = "write", "discard", "cancel"
#: ``ask_leave_bus`` answers.
LEAVE_COMPARE, LEAVE_DISCONNECT, LEAVE_CANCEL = "compare", "disconnect", "cancel"

_CTX = "WindowFiles"


def _t(text: str) -> str:
    return translate(_CTX, text)


def ask_save_changes(parent: QWidget, title: str) -> QMessageBox.StandardButton:
    """Save, Discard or Cancel the changes to the document called ``title``."""
    SB = QMessageBox.StandardButton
    return QMessageBox.question(
        parent,
        _t("Unsaved changes"),
        _t("Save the changes to {title}?").format(title=title),
        SB.Save | SB.Discard | SB.Cancel,
        SB.Save,
    )


def ask_leave_bus(parent: QWidget, url: str, path: Path | None) -> str:
    """Compare ``path`` with the prosthesis on ``url``, disconnect, or cancel."""
    box = QMessageBox(parent)
    box.setIcon(QMessageBox.Icon.Question)
    box.setWindowTitle(_t("Connected to a prosthesis"))
    name = path.name if path is not None else _t("another document")
    box.setText(_t("This window is connected to the prosthesis on {0}.\n"
                   "Opening {1} ends that connection.").format(url, name))
    box.setInformativeText(_t("You can compare the file with the prosthesis "
                              "instead, and stay connected."))
    compare = box.addButton(_t("Compare with the prosthesis"),
                            QMessageBox.ButtonRole.AcceptRole)
    leave = box.addButton(_t("Disconnect and open"), QMessageBox.ButtonRole.DestructiveRole)
    box.addButton(QMessageBox.StandardButton.Cancel)
    if path is None:
        compare.setEnabled(False)
    box.setDefaultButton(compare if path is not None else leave)
    box.exec()
    clicked = box.clickedButton()
    if clicked is compare:
        return LEAVE_COMPARE
    if clicked is leave:
        return LEAVE_DISCONNECT
    return LEAVE_CANCEL


def ask_unwritten(parent: QWidget, n: int) -> bool:
    """Leave the prosthesis with ``n`` pending changes not written?"""
    SB = QMessageBox.StandardButton
    answer = QMessageBox.warning(
        parent,
        translate("MainWindow", "Pending changes"),
        count(
            "MainWindow",
            "%n change(s) not written to the prosthesis. Leave it without them?\n"
            "(Write to prosthesis writes them; the document keeps them either way.)",
            n,
        ),
        SB.Discard | SB.Cancel,
        SB.Cancel,
    )
    return answer == SB.Discard


def quit_live_words(n: int, url: str) -> tuple[str, str]:
    """What quitting a live view with ``n`` pending changes leaves behind, and the ways on:
    the changes are for the prosthesis (written through the change road), not a file."""
    text = count("MainWindow", "%n change(s) not written to the prosthesis on {url} yet.",
                 n).format(url=url)
    more = translate("MainWindow", "Write them now (you see the difference and confirm it), "
                                   "or quit and discard them: the prosthesis stays as it is.")
    return text, more


def ask_quit_live(parent: QWidget, n: int, url: str) -> str:
    """Quitting a live view with ``n`` pending changes: write them first, discard them
    and quit, or cancel (one question: nothing is "saved" to the prosthesis)."""
    box = QMessageBox(parent)
    box.setIcon(QMessageBox.Icon.Question)
    box.setWindowTitle(translate("MainWindow", "Pending changes"))
    text, more = quit_live_words(n, url)
    box.setText(text)
    box.setInformativeText(more)
    write = box.addButton(translate("MainWindow", "Write to prosthesis…"),
                          QMessageBox.ButtonRole.AcceptRole)
    discard = box.addButton(translate("MainWindow", "Discard and quit"),
                            QMessageBox.ButtonRole.DestructiveRole)
    cancel = box.addButton(QMessageBox.StandardButton.Cancel)
    box.setDefaultButton(cancel)
    box.exec()
    clicked = box.clickedButton()
    if clicked is write:
        return QUIT_WRITE
    if clicked is discard:
        return QUIT_DISCARD
    return QUIT_CANCEL
