"""Connect dialog: one page per kind of bus, URLs per contracts §3, remembered across restarts,
detection on a worker."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QSettings, Qt

from pdcp_studio.app.dialogs import connect_dialog as cd
from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog
from pdcp_studio.bus.session.urls import parse_bus_url

pytestmark = pytest.mark.gui


@pytest.fixture
def ini(tmp_path):
    return str(tmp_path / "settings.ini")


def _dialog(qtbot, ini: str, **kwargs) -> ConnectDialog:
    dialog = ConnectDialog(settings=QSettings(ini, QSettings.Format.IniFormat), **kwargs)
    qtbot.addWidget(dialog)
    return dialog


def test_defaults_to_the_built_in_simulated_prosthesis(qtbot, ini):
    from pdcp_studio.bus.sim.rigs import list_prostheses

    dialog = _dialog(qtbot, ini)
    sim = dialog.pages["sim"]
    names = [sim.list.item(i).text() for i in range(sim.list.count())]
    assert names == list_prostheses()
    assert {"thesis-test1", "thesis-test5", "transradial"} <= set(names)
    assert dialog.url() == "sim:transradial"
    assert "Transradial" in sim.description.text()  # the simulator's description
    assert dialog.tabs.currentWidget() is sim
    assert [dialog.tabs.tabText(i) for i in range(dialog.tabs.count())] == \
        ["Simulated prosthesis", "CAN interface", "Serial host link"]


def test_can_and_serial_pages_make_contract_urls(qtbot, ini):
    dialog = _dialog(qtbot, ini)
    can_page = dialog.pages["can"]
    interfaces = [can_page.interface.itemText(i) for i in range(can_page.interface.count())]
    assert {"socketcan", "pcan", "virtual"} <= set(interfaces)
    dialog.tabs.setCurrentWidget(can_page)
    can_page.interface.setCurrentText("pcan")
    can_page.channel.setCurrentText("PCAN_USBBUS1")
    assert dialog.url() == "can:pcan:PCAN_USBBUS1@1000000"  # PDCP's 1 Mbit/s by default
    can_page.bitrate.setCurrentIndex(0)  # "(interface default)"
    assert dialog.url() == "can:pcan:PCAN_USBBUS1"
    can_page.channel.setCurrentText("")
    assert dialog.url() is None
    assert not dialog.buttons.button(dialog.buttons.StandardButton.Ok).isEnabled()

    serial = dialog.pages["serial"]
    dialog.tabs.setCurrentWidget(serial)
    assert dialog.url() is None  # no port yet
    serial.port.setCurrentText("/dev/ttyUSB0")
    assert dialog.url() == "serial:/dev/ttyUSB0"  # 128000 baud is the default
    serial.baud.setCurrentText("115200")
    assert dialog.url() == "serial:/dev/ttyUSB0@115200"
    serial.set_url("serial:socket://127.0.0.1:7000")
    assert dialog.url() == "serial:socket://127.0.0.1:7000"
    for url in ("can:pcan:PCAN_USBBUS1", "serial:socket://127.0.0.1:7000", "sim:transradial"):
        dialog.set_url(url)
        assert dialog.url() == url
        parse_bus_url(url)


def test_an_invalid_url_is_not_offered(qtbot, ini):
    dialog = _dialog(qtbot, ini, initial_url="serial:/dev/ttyUSB0")
    dialog.pages["serial"].baud.setCurrentText("0")  # digits, but no valid baud rate
    assert dialog.url() is None
    assert "must be positive" in dialog.url_label.text()


def test_the_last_choice_is_remembered_across_restarts(qtbot, ini):
    first = _dialog(qtbot, ini)
    first.set_url("sim:thesis-test3")
    first.accept()
    second = _dialog(qtbot, ini)
    second.set_url("can:virtual:bus7@500000")
    second.accept()
    # A new process reads the settings file afresh.
    again = _dialog(qtbot, ini)
    assert again.url() == "can:virtual:bus7@500000"
    assert again.tabs.currentWidget() is again.pages["can"]
    assert again.pages["sim"].url() == "sim:thesis-test3"  # each tab reopens as it was left
    stored = QSettings(ini, QSettings.Format.IniFormat)
    assert stored.value(cd.SETTINGS_KEY) == "can:virtual:bus7@500000"


def test_can_detection_runs_on_a_worker_and_fills_the_channels(qtbot, ini, monkeypatch):
    import can

    calls: list[bool] = []

    def detect(progress=None, cancel=None):
        from PySide6.QtCore import QThread
        from PySide6.QtWidgets import QApplication

        calls.append(QThread.currentThread() is QApplication.instance().thread())
        found = [dict(c) for c in can.detect_available_configs(interfaces=["virtual"])]
        return [*found, {"interface": "virtual", "channel": "vcan-test"}]

    monkeypatch.setattr(cd, "detect_can_configs", detect)
    dialog = _dialog(qtbot, ini, initial_url="can:socketcan:can0")
    page = dialog.pages["can"]
    with qtbot.waitSignal(page.detected, timeout=10_000):
        page.detect()
        # Busy while it looks: the button says so and the status says what is going on.
        assert not page.detect_button.isEnabled()
        assert page.detect_button.text() == "Detecting…"
        assert "Looking for adapters" in page.status.text()
        assert page.cursor().shape() == Qt.CursorShape.BusyCursor
    assert calls == [False]  # probed off the GUI thread
    assert page.detect_button.isEnabled() and page.detect_button.text() == "Detect"
    n = len({c["channel"] for c in detect()})
    assert page.status.text().startswith(
        f"Found {n} CAN channel{'' if n == 1 else 's'}: ")
    assert "virtual:vcan-test" in page.status.text()
    assert page.interface.currentText() == "virtual"
    channels = [page.channel.itemText(i) for i in range(page.channel.count())]
    assert "vcan-test" in channels
    assert dialog.url().startswith("can:virtual:")


def test_can_detection_that_finds_nothing_says_so(qtbot, ini, monkeypatch):
    monkeypatch.setattr(cd, "detect_can_configs", lambda progress=None, cancel=None: [])
    dialog = _dialog(qtbot, ini, initial_url="can:socketcan:can0")
    page = dialog.pages["can"]
    with qtbot.waitSignal(page.detected, timeout=5000):
        page.detect()
    assert page.status.text().startswith("No CAN adapter found.")
    assert dialog.url().startswith("can:socketcan:can0")  # what was typed stays


def test_detection_failure_is_shown(qtbot, ini, monkeypatch):
    def broken(progress=None, cancel=None):
        raise OSError(19, "No such device")

    monkeypatch.setattr(cd, "list_serial_ports", broken)
    dialog = _dialog(qtbot, ini, initial_url="serial:COM3")
    page = dialog.pages["serial"]
    with qtbot.waitSignal(page.detected, timeout=5000):
        page.detect()
    assert page.status.text() == "Detection failed: No such device"
    assert dialog.url() == "serial:COM3"  # the typed port is kept


def test_serial_ports_are_listed_by_pyserial(qtbot, ini):
    from serial.tools import list_ports

    expected = sorted(p.device for p in list_ports.comports())
    dialog = _dialog(qtbot, ini, initial_url="serial:/dev/ttyUSB9")
    page = dialog.pages["serial"]
    with qtbot.waitSignal(page.detected, timeout=10_000):
        page.detect()
    assert sorted(page.port.itemText(i) for i in range(page.port.count())) == expected
    assert page.port.currentText() == "/dev/ttyUSB9"  # what the user typed stays chosen
    assert page.status.text() == (f"{len(expected)} port{'' if len(expected) == 1 else 's'} found" if expected
                                  else "No serial port found")
