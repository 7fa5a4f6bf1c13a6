"""Choose a bus to connect to and produce its URL (contracts §3).

One tab per kind of bus — simulated prosthesis, CAN interface, serial host link — each a
:class:`BusPage` that turns its fields into a URL and back. A new kind is one more
``BusPage`` subclass in :data:`PAGE_TYPES`. The last choice (and the last URL of each kind)
is remembered in QSettings. Detection (python-can's ``detect_available_configs``, pyserial's
port list) runs on a worker, never on the GUI thread; python-can and pyserial are imported
only there. A URL is offered only once ``bus.urls.parse_bus_url`` accepts it.

Public API
    ``ConnectDialog(parent=None, settings=None, initial_url=None)`` — ``settings`` defaults
    to ``QSettings()``. ``url() -> str | None`` (None while the fields are incomplete or
    invalid), ``set_url(url)``, ``pages`` (kind → ``BusPage``), ``accept()`` stores the URL.
    Signal: ``urlChanged(str)`` ("" when incomplete). ``ConnectDialog.get_url(parent,
    settings=None) -> str | None`` runs it modally (not in tests).
    Pages: ``SimPage`` (``list``), ``CanPage`` (``interface``, ``channel``, ``bitrate``,
    ``detect() -> Worker``, ``detected`` signal), ``SerialPage`` (``port``, ``baud``,
    ``detect()``).
"""

from __future__ import annotations

import logging
import threading
from typing import TYPE_CHECKING, Any, ClassVar, cast

from PySide6.QtCore import QSettings, Qt, Signal
from PySide6.QtWidgets import (
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QFormLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QPushButton,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from pdcp_studio.app.i18n import QT_TRANSLATE_NOOP, translate
from pdcp_studio.app.words.plural import count
from pdcp_studio.app.workers import ProgressFn, Worker, WorkFn

if TYPE_CHECKING:
    from can.typechecking import AutoDetectedConfig

log = logging.getLogger(__name__)

SETTINGS_KEY = "connect/last_url"
KIND_KEY = "connect/last_{}"  # the last URL of each kind, so every tab reopens as left
DEFAULT_SIM = "transradial"
DEFAULT_BITRATE = 1_000_000
CAN_BITRATES = (10_000, 20_000, 50_000, 100_000, 125_000, 250_000, 500_000, 800_000, 1_000_000)
SERIAL_BAUDS = (9600, 57_600, 115_200, 128_000, 230_400, 460_800, 921_600)
DEFAULT_BAUD = 128_000
FALLBACK_CAN_INTERFACES = ("socketcan", "pcan", "kvaser", "vector", "ixxat", "slcan",
                           "gs_usb", "virtual")


def list_prostheses() -> list[str]:
    """Built-in simulated prostheses: the simulator's registry, else the shipped systems."""
    try:
        from pdcp_studio.bus.sim.rigs import list_prostheses as registry
    except ImportError:
        from pdcp_studio.paths import systems_dir

        return sorted(p.stem for p in systems_dir().glob("*.json"))
    return list(registry())


def prosthesis_description(name: str) -> str:
    """The simulator's one-line description of a built-in prosthesis ('' if unknown)."""
    try:
        from pdcp_studio.bus.sim.rigs import prosthesis

        return str(prosthesis(name).description)
    except Exception:  # an older simulator, or a name it does not know
        return ""


def can_interface_names() -> list[str]:
    """python-can's interface names (a cheap import of its table, no driver loaded)."""
    try:
        from can.interfaces import VALID_INTERFACES
    except ImportError:
        return list(FALLBACK_CAN_INTERFACES)
    return sorted(VALID_INTERFACES)


def detect_can_configs(progress: ProgressFn | None = None,
                       cancel: threading.Event | None = None) -> list[AutoDetectedConfig]:
    """python-can's available configurations (slow: probes drivers — run on a worker)."""
    import can

    return [c.copy() for c in can.detect_available_configs()]


def list_serial_ports(progress: ProgressFn | None = None,
                      cancel: threading.Event | None = None) -> list[tuple[str, str]]:
    """(device, description) of every serial port pyserial sees (run on a worker)."""
    from serial.tools import list_ports

    return [(p.device, p.description or "") for p in sorted(list_ports.comports())]


class BusPage(QWidget):
    """One kind of bus: fields ↔ URL. Subclasses set ``kind`` (the URL scheme) and ``title``."""

    kind: ClassVar[str] = ""
    title: ClassVar[str] = ""
    changed = Signal()

    def url(self) -> str | None:
        """The URL for the current fields, or None when they are incomplete."""
        raise NotImplementedError

    def set_url(self, url: str) -> None:
        """Show ``url`` (of this page's kind) in the fields."""
        raise NotImplementedError

    def shutdown(self) -> None:
        """Cancel any detection still running (the dialog is closing)."""


class SimPage(BusPage):
    kind = "sim"
    title = QT_TRANSLATE_NOOP("ConnectDialog", "Simulated prosthesis")

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.list = QListWidget()
        self.list.addItems(list_prostheses())
        self.description = QLabel()
        self.description.setWordWrap(True)
        self.list.currentRowChanged.connect(self._selected)
        layout = QVBoxLayout(self)
        layout.addWidget(QLabel(self.tr("A built-in prosthesis on an in-process virtual bus:")))
        layout.addWidget(self.list)
        layout.addWidget(self.description)
        self.set_url(f"sim:{DEFAULT_SIM}")

    def _selected(self, _row: int) -> None:
        item = self.list.currentItem()
        self.description.setText(prosthesis_description(item.text()) if item else "")
        self.changed.emit()

    def url(self) -> str | None:
        item = self.list.currentItem()
        return f"sim:{item.text()}" if item else None

    def set_url(self, url: str) -> None:
        name = url.partition(":")[2]
        for row in range(self.list.count()):
            if self.list.item(row).text() == name:
                self.list.setCurrentRow(row)
                return
        if self.list.count() and self.list.currentRow() < 0:
            self.list.setCurrentRow(0)


class _DetectingPage(BusPage):
    """A page with a Detect button whose probe runs on a worker."""

    detected = Signal()

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.status = QLabel("")
        self.status.setWordWrap(True)
        self.detect_button = QPushButton(self.tr("Detect"))
        self.detect_button.clicked.connect(self.detect)
        self._worker: Worker | None = None

    def _probe(self) -> WorkFn:
        raise NotImplementedError

    def _show(self, result: Any) -> None:
        raise NotImplementedError

    def detect(self) -> Worker:
        """Probe in the background; the result fills the fields and emits ``detected``."""
        self.detect_button.setEnabled(False)
        self.detect_button.setText(self.tr("Detecting…"))
        self.setCursor(Qt.CursorShape.BusyCursor)
        self.status.setText(self.tr("Looking for adapters… this can take a few seconds"))
        self._worker = worker = Worker(self._probe(), f"Detect {self.kind}")
        worker.finished.connect(self._show)
        worker.failed.connect(self._failed)  # bound slots: dropped if the page is gone
        worker.done.connect(self._detect_done)
        return worker.start()

    def _failed(self, message: str) -> None:
        self.status.setText(self.tr("Detection failed: {message}").format(message=message))

    def _detect_done(self) -> None:
        self.detect_button.setEnabled(True)
        self.detect_button.setText(self.tr("Detect"))
        self.unsetCursor()
        self._worker = None
        self.detected.emit()

    def shutdown(self) -> None:
        if self._worker is not None:
            self._worker.cancel()


class CanPage(_DetectingPage):
    kind = "can"
    title = QT_TRANSLATE_NOOP("ConnectDialog", "CAN interface")

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.interface = QComboBox()
        self.interface.addItems(can_interface_names())
        self.channel = QComboBox()
        self.channel.setEditable(True)
        self.bitrate = QComboBox()
        self.bitrate.setEditable(True)
        self.bitrate.addItem(self.tr("(interface default)"), None)
        for rate in CAN_BITRATES:
            self.bitrate.addItem(f"{rate}", rate)
        self.bitrate.setCurrentText(str(DEFAULT_BITRATE))  # PDCP runs at 1 Mbit/s
        for w in (self.interface, self.channel, self.bitrate):
            w.currentTextChanged.connect(lambda _t: self.changed.emit())
        self._configs: list[AutoDetectedConfig] = []
        self.interface.currentTextChanged.connect(lambda _t: self._suggest_channels())
        form = QFormLayout(self)
        form.addRow(self.tr("Interface"), self.interface)
        form.addRow(self.tr("Channel"), self.channel)
        form.addRow(self.tr("Bitrate (bit/s)"), self.bitrate)
        form.addRow(self.detect_button, self.status)
        self.set_url("can:socketcan:can0")

    def _probe(self) -> WorkFn:
        return detect_can_configs

    def _show(self, configs: list[AutoDetectedConfig]) -> None:
        self._configs = [c for c in configs if c.get("interface") and c.get("channel")]
        kinds = sorted({str(c["interface"]) for c in self._configs})
        found = sorted({f"{c['interface']}:{c['channel']}" for c in self._configs})
        self.status.setText(
            self.tr("Found {n}: {which}").format(n=count("CanPage", "%n CAN channel(s)",
                                                         len(found)),
                                                which=", ".join(found))
            if found
            else self.tr("No CAN adapter found. Check that it is plugged in and its driver "
                         "is installed, or type the interface and channel.")
        )
        if self._configs and self.interface.currentText() not in kinds:
            self.interface.setCurrentText(kinds[0])
        self._suggest_channels()

    def _suggest_channels(self) -> None:
        """Offer the detected channels of the chosen interface (the text stays editable)."""
        interface = self.interface.currentText()
        channels = sorted({str(c["channel"]) for c in self._configs
                           if c["interface"] == interface})
        if not channels:
            return
        current = self.channel.currentText()
        self.channel.blockSignals(True)
        self.channel.clear()
        self.channel.addItems(channels)
        self.channel.blockSignals(False)
        self.channel.setCurrentText(current if current in channels else channels[0])
        self.changed.emit()

    def url(self) -> str | None:
        interface = self.interface.currentText().strip()
        channel = self.channel.currentText().strip()
        if not interface or not channel:
            return None
        text = self.bitrate.currentText().strip()
        rate = text if text.isdigit() else ""
        return f"can:{interface}:{channel}" + (f"@{rate}" if rate else "")

    def set_url(self, url: str) -> None:
        body = url.partition(":")[2]
        body, _, rate = body.rpartition("@") if "@" in body else (body, "", "")
        interface, _, channel = body.partition(":")
        self.interface.setCurrentText(interface)
        self.channel.setCurrentText(channel)
        if rate:
            self.bitrate.setCurrentText(rate)


class SerialPage(_DetectingPage):
    kind = "serial"
    title = QT_TRANSLATE_NOOP("ConnectDialog", "Serial host link")

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.port = QComboBox()
        self.port.setEditable(True)
        editor = cast(QLineEdit, self.port.lineEdit())  # an editable combo box has one
        editor.setPlaceholderText(self.tr("/dev/ttyUSB0, COM3 or socket://host:port"))
        self.baud = QComboBox()
        self.baud.setEditable(True)
        self.baud.addItems([str(b) for b in SERIAL_BAUDS])
        self.baud.setCurrentText(str(DEFAULT_BAUD))
        for w in (self.port, self.baud):
            w.currentTextChanged.connect(lambda _t: self.changed.emit())
        form = QFormLayout(self)
        form.addRow(QLabel(self.tr("A hardware arbitrator's host link:")))
        form.addRow(self.tr("Port"), self.port)
        form.addRow(self.tr("Baud"), self.baud)
        form.addRow(self.detect_button, self.status)

    def _probe(self) -> WorkFn:
        return list_serial_ports

    def _show(self, ports: list[tuple[str, str]]) -> None:
        current = self.port.currentText()
        self.port.clear()
        for device, description in ports:
            self.port.addItem(device)
            self.port.setItemData(self.port.count() - 1, description)
        self.port.setCurrentText(current or (ports[0][0] if ports else ""))
        self.status.setText(
            count("SerialPage", "%n port(s) found", len(ports))
            if ports
            else self.tr("No serial port found")
        )

    def url(self) -> str | None:
        port = self.port.currentText().strip()
        if not port:
            return None
        baud = self.baud.currentText().strip()
        return f"serial:{port}" + (f"@{baud}" if baud.isdigit() and int(baud) != DEFAULT_BAUD
                                   else "")

    def set_url(self, url: str) -> None:
        body = url.partition(":")[2]
        port, _, baud = body.rpartition("@") if "@" in body else (body, "", "")
        self.port.setCurrentText(port)
        self.baud.setCurrentText(baud if baud.isdigit() else str(DEFAULT_BAUD))


#: The kinds of bus, in tab order. Add a BusPage subclass here for a new kind.
PAGE_TYPES: list[type[BusPage]] = [SimPage, CanPage, SerialPage]


class ConnectDialog(QDialog):
    """Pick a bus; ``url()`` is the result, ``urlChanged(str)`` follows the fields.

    ``settings`` defaults to the application's QSettings; accepting stores the URL there
    and the next dialog opens on it. Use ``ConnectDialog.get_url(parent)`` from a menu.
    """

    urlChanged = Signal(str)

    def __init__(self, parent: QWidget | None = None, settings: QSettings | None = None,
                 initial_url: str | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(self.tr("Connect to a bus"))
        self.setMinimumWidth(520)
        self._settings = settings if settings is not None else QSettings()
        self.tabs = QTabWidget()
        self.pages: dict[str, BusPage] = {}
        for page_type in PAGE_TYPES:
            page = page_type()
            page.changed.connect(self._changed)
            self.pages[page.kind] = page
            self.tabs.addTab(page, translate("ConnectDialog", page.title))
        self.tabs.currentChanged.connect(lambda _i: self._changed())
        self.url_label = QLabel()
        self.url_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok
                                        | QDialogButtonBox.StandardButton.Cancel)
        self.buttons.button(QDialogButtonBox.StandardButton.Ok).setText(self.tr("Connect"))
        self.buttons.accepted.connect(self.accept)
        self.buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        layout.addWidget(self.tabs)
        layout.addWidget(self.url_label)
        layout.addWidget(self.buttons)
        for kind, page in self.pages.items():
            remembered = str(self._settings.value(KIND_KEY.format(kind), "") or "")
            if remembered.startswith(f"{kind}:"):
                page.set_url(remembered)
        last = initial_url or str(self._settings.value(SETTINGS_KEY, "") or "")
        self.set_url(last or f"sim:{DEFAULT_SIM}")

    def url(self) -> str | None:
        """The chosen URL, or None while it is incomplete or does not parse."""
        return self._checked()[0]

    def _checked(self) -> tuple[str | None, str]:
        page = self.tabs.currentWidget()
        url = page.url() if isinstance(page, BusPage) else None
        if url is None:
            return None, "(incomplete)"
        from pdcp_studio.bus.session.urls import BusUrlError, parse_bus_url

        try:
            parse_bus_url(url)
        except BusUrlError as err:
            return None, str(err)
        return url, url

    def set_url(self, url: str) -> None:
        """Open the tab for ``url``'s kind and fill it in (unknown kinds are ignored)."""
        kind = url.partition(":")[0]
        page = self.pages.get(kind)
        if page is None:
            log.info("connect dialog: unknown bus kind in %r", url)
            return
        page.set_url(url)
        self.tabs.setCurrentWidget(page)
        self._changed()

    def _changed(self) -> None:
        url, shown = self._checked()
        self.url_label.setText(self.tr("URL: {shown}").format(shown=shown))
        self.buttons.button(QDialogButtonBox.StandardButton.Ok).setEnabled(url is not None)
        self.urlChanged.emit(url or "")

    def accept(self) -> None:
        url = self.url()
        if url is None:
            return
        self._settings.setValue(SETTINGS_KEY, url)
        self._settings.setValue(KIND_KEY.format(url.partition(":")[0]), url)
        self._settings.sync()
        self._shutdown()
        super().accept()

    def reject(self) -> None:
        self._shutdown()
        super().reject()

    def _shutdown(self) -> None:
        for page in self.pages.values():
            page.shutdown()

    @classmethod
    def get_url(cls, parent: QWidget | None = None,
                settings: QSettings | None = None) -> str | None:
        """Show the dialog modally; the chosen URL, or None if cancelled (not for tests)."""
        dialog = cls(parent, settings)
        try:
            return dialog.url() if dialog.exec() == QDialog.DialogCode.Accepted else None
        finally:
            dialog.deleteLater()
