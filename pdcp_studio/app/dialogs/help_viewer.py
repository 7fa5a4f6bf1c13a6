"""Help: the user manual for prosthetists (``docs/manual.md``, shipped as
``resources/manual/<language>.md``) shown in the app, and About with versions.

F1 opens the manual at the section for what the user is looking at (:func:`section_for`):
the graph, a dock, or the dialog in front. The manual's pictures (``images/NAME.png`` beside
it, package data like the manual, so a source checkout and an installed wheel find them the
same way) are loaded by :class:`ManualBrowser`, which scales them to the page and shows a
plain placeholder for a picture an installation lacks. A manual in another language shows
the pictures taken of the app in that language (``images/<language>/NAME.png``) where there
are any, else the English ones.
"""

from __future__ import annotations

import platform
import re
from importlib import metadata
from pathlib import Path

from PySide6.QtCore import QLocale, QRect, Qt, QUrl
from PySide6.QtGui import QColor, QImage, QPainter, QTextCursor, QTextDocument
from PySide6.QtWidgets import (
    QApplication,
    QDialog,
    QDialogButtonBox,
    QMessageBox,
    QTextBrowser,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import translate

#: What the user is looking at (a dock's or dialog's object/class name) → manual section key.
VIEW_SECTIONS: dict[str, str] = {
    "StartView": "start",
    "GraphView": "graph",
    "DevicesDock": "devices",
    "InspectorDock": "inspector",
    "PlanDock": "plans",
    "PendingDock": "pending",
    "HistoryDock": "history",
    "MonitorDock": "monitor",
    "LivePlotDock": "plot",
    "SimDock": "simulator",
    "ConnectDialog": "connect",
    "CompareDialog": "compare",
    "WriteConfigDialog": "write",
    "ProfileTreeDialog": "profiles",
    "RecoveryDialog": "recovery",
    "NewFittingWizard": "tasks",
    "ReplacePartWizard": "tasks",
    "RestoreWizard": "tasks",
}


def manual_path(language: str | None = None) -> Path:
    """The manual in ``language`` (``de``, ``en``…), else in English."""
    from pdcp_studio.paths import resources_dir

    folder = resources_dir() / "manual"
    lang = (language or QLocale().name()).split("_")[0]
    chosen = folder / f"{lang}.md"
    return chosen if chosen.is_file() else folder / "en.md"


def sections(text: str) -> dict[str, str]:
    """Section key → heading text, from the manual's ``<!-- section: KEY -->`` markers (each
    on the line before its heading)."""
    found: dict[str, str] = {}
    for key, heading in re.findall(r"<!-- section: (\w+) -->\s*\n#+\s*(.+)", text):
        found[key] = heading.strip()
    return found


def section_for(widget: QWidget | None) -> str:
    """The manual section for ``widget`` (the focus widget or the window in front)."""
    while widget is not None:
        for name in (widget.objectName(), type(widget).__name__):
            if name in VIEW_SECTIONS:
                return VIEW_SECTIONS[name]
        widget = widget.parentWidget()
    return "start"


#: The manual's pictures are shown at most this wide (px), so the page needs no side scrolling.
PICTURE_WIDTH = 720


class ManualBrowser(QTextBrowser):
    """The manual's pane: finds its pictures beside the manual file (``folder``), in the
    manual's ``language`` where they were taken in it."""

    def __init__(self, folder: Path, parent: QWidget | None = None,
                 language: str = "") -> None:
        super().__init__(parent)
        self.folder = folder
        self.language = language
        self.setSearchPaths([str(folder)])

    def picture_path(self, url: QUrl | str) -> Path:
        """Where the picture ``url`` (as the manual writes it, e.g. ``images/x.png``) is:
        ``images/<language>/x.png`` when there is one, else ``images/x.png`` (English)."""
        url = QUrl(url)
        if url.isLocalFile():
            return Path(url.toLocalFile())
        return localised(self.folder / url.path(), self.language)

    def loadResource(self, kind: int, url: QUrl | str) -> object:
        if kind != QTextDocument.ResourceType.ImageResource.value:
            return super().loadResource(kind, url)
        url = QUrl(url)
        image = QImage(str(self.picture_path(url)))
        if image.isNull():
            return missing_picture(url.fileName())
        if image.width() > PICTURE_WIDTH:
            image = image.scaledToWidth(PICTURE_WIDTH, Qt.TransformationMode.SmoothTransformation)
        image = image.convertToFormat(QImage.Format.Format_RGB32)
        painter = QPainter(image)  # a thin frame: a picture of a window, not part of the page
        painter.setPen(QColor("#9a9a9a"))
        painter.drawRect(image.rect().adjusted(0, 0, -1, -1))
        painter.end()
        return image


def localised(picture: Path, language: str) -> Path:
    """``images/de/x.png`` for ``images/x.png`` in German when it exists, else ``picture``:
    the manuals name their pictures once, each language's are in a folder of its own."""
    if language and language != "en":
        own = picture.parent / language / picture.name
        if own.is_file():
            return own
    return picture


def missing_picture(name: str) -> QImage:
    """A plain grey box that says which picture this installation lacks."""
    image = QImage(PICTURE_WIDTH // 2, 64, QImage.Format.Format_RGB32)
    image.fill(QColor("#eeeeee"))
    painter = QPainter(image)
    painter.setPen(QColor("#888888"))
    painter.drawRect(image.rect().adjusted(0, 0, -1, -1))
    painter.setPen(QColor("#444444"))
    text = translate("HelpViewer", "Picture not included in this installation: {name}")
    painter.drawText(QRect(8, 4, image.width() - 16, image.height() - 8),
                     Qt.AlignmentFlag.AlignCenter | Qt.TextFlag.TextWordWrap,
                     text.format(name=name))
    painter.end()
    return image


class HelpViewer(QDialog):
    """The manual in a browser pane; :meth:`show_section` scrolls to one section."""

    def __init__(self, parent: QWidget | None = None, language: str | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("HelpViewer")
        self.setWindowTitle(self.tr("PDCP Studio — User manual"))
        self.resize(820, 760)
        self.path = manual_path(language)
        self.browser = ManualBrowser(self.path.parent, self, language=self.path.stem)
        self.browser.setOpenExternalLinks(True)
        self.browser.setAccessibleName(self.tr("User manual"))
        self.browser.setAccessibleDescription(
            self.tr("The user manual for prosthetists; F1 opens the part for the current view"))
        self.text = self.path.read_text("utf-8")
        self.browser.setMarkdown(re.sub(r"<!-- section: \w+ -->\n", "", self.text))
        self.headings = sections(self.text)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Close, self)
        buttons.rejected.connect(self.close)
        layout = QVBoxLayout(self)
        layout.addWidget(self.browser)
        layout.addWidget(buttons)

    def show_section(self, key: str) -> bool:
        """Scroll so that section ``key``'s heading is at the top; False if there is none."""
        heading = self.headings.get(key)
        if heading is None:
            return False
        doc = self.browser.document()
        block = doc.begin()
        while block.isValid():
            if block.text().strip() == heading and block.blockFormat().headingLevel():
                cursor = QTextCursor(block)
                bar = self.browser.verticalScrollBar()
                bar.setValue(bar.maximum())  # then back up: the heading ends at the top
                self.browser.setTextCursor(cursor)
                self.browser.ensureCursorVisible()
                return True
            block = block.next()
        return False

    def current_heading(self) -> str:
        """The heading of the section shown at the top (for tests)."""
        cursor = self.browser.cursorForPosition(self.browser.viewport().rect().topLeft())
        block = cursor.block()
        while block.isValid() and not block.blockFormat().headingLevel():
            block = block.previous()
        return block.text() if block.isValid() else ""


def qt_versions() -> dict[str, str]:
    """The Qt and PySide6 this program runs on."""
    from PySide6 import __version__ as pyside_version
    from PySide6.QtCore import qVersion

    return {"PySide6": pyside_version, "qt": qVersion()}


def versions_text() -> str:
    """PDCP Studio's and its parts' versions, one a line (About, and support requests)."""
    from PySide6 import __version__ as pyside_version
    from PySide6.QtCore import qVersion

    from pdcp_studio import __version__

    parts = [("PDCP Studio", __version__), ("Python", platform.python_version()),
             ("Qt", qVersion()), ("PySide6", pyside_version)]
    for name in ("python-can", "pyserial", "networkx"):
        try:
            parts.append((name, metadata.version(name)))
        except metadata.PackageNotFoundError:
            parts.append((name, "?"))
    return "\n".join(f"{name} {version}" for name, version in parts)


def show_about(parent: QWidget) -> None:
    text = (translate("HelpViewer", "<h3>PDCP Studio</h3><p>See, configure and repair the "
                      "PDCP bus inside a powered prosthesis.</p>")
            + "<p>" + versions_text().replace("\n", "<br>") + "</p>"
            + translate("HelpViewer", "<p>MIT License. Help → User manual (F1) explains "
                        "every view.</p>"))
    QMessageBox.about(parent, translate("HelpViewer", "About PDCP Studio"), text)


def show_about_qt(parent: QWidget) -> None:
    QApplication.aboutQt()


def open_manual(parent: QWidget, key: str = "start") -> HelpViewer:
    """Show the manual (one viewer per parent window) at section ``key``."""
    viewer = parent.findChild(HelpViewer, options=Qt.FindChildOption.FindDirectChildrenOnly)
    if viewer is None:
        viewer = HelpViewer(parent)
        viewer.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose, False)
    viewer.show()
    viewer.raise_()
    viewer.activateWindow()
    viewer.show_section(key)
    return viewer
