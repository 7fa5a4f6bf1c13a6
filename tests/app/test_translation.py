"""The German build: every user-visible string of the main window (menus, toolbar, docks, live
panels) and of its dialogs is translated, and the app follows ``--lang`` / the system locale.

A text is untranslated when the German build shows it exactly as the English build does,
unless it is data (device and channel names, numbers, addresses), or the German translation
file says German keeps it as it is (``Plan``, ``Offline``, ``PDCP Studio``…).
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QAbstractButton,
    QAbstractItemView,
    QApplication,
    QComboBox,
    QDockWidget,
    QGroupBox,
    QLabel,
    QLineEdit,
    QMenu,
    QTabBar,
    QWidget,
)

from pdcp_studio.app import i18n

ROOT = Path(__file__).resolve().parents[2]
TS = ROOT / "resources" / "i18n" / "pdcp_studio_de.ts"
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"


def _plain(text: str) -> str:
    return " ".join(text.replace("&&", "\0").replace("&", "").replace("\0", "&").split())


def _texts(widget: QWidget) -> set[str]:
    """What the user reads on ``widget`` and everything in it."""
    out: set[str] = set()
    for w in [widget, *widget.findChildren(QWidget)]:
        if w.isWindow() or isinstance(w, QDockWidget | QMenu):
            out.add(w.windowTitle())
        out.add(w.toolTip())
        if isinstance(w, QLabel | QAbstractButton):
            out.add(w.text())
        if isinstance(w, QLineEdit):
            out.add(w.placeholderText())
        if isinstance(w, QGroupBox):
            out.add(w.title())
        if isinstance(w, QTabBar):
            out.update(w.tabText(i) for i in range(w.count()))
        if isinstance(w, QComboBox):
            out.update(w.itemText(i) for i in range(w.count()))
        if isinstance(w, QAbstractItemView) and w.model() is not None:
            model = w.model()
            try:
                columns = model.columnCount()
            except TypeError:
                columns = 1
            for c in range(columns):
                title = model.headerData(c, Qt.Orientation.Horizontal)
                if isinstance(title, str):
                    out.add(title)
        for action in w.actions():
            out.add(action.text())
            out.add(action.toolTip())
            out.add(action.statusTip())
    return {_plain(t) for t in out if t}


def _kept_in_german() -> set[str]:
    """Sources whose German translation is the same text."""
    kept = set()
    for msg in ET.parse(TS).getroot().iter("message"):
        src, tr = msg.find("source").text or "", msg.find("translation")
        if tr is not None and (tr.text or "") == src:
            kept.add(_plain(src))
    return kept


def _is_data(text: str, data: set[str]) -> bool:
    if text in data or not re.search(r"[A-Za-zÄÖÜäöü]{2}", text):
        return True
    if re.fullmatch(r"\d+ \S+\.(json|pdcfg)", text):
        return True  # a recent file: its number and name
    if re.fullmatch(r"[\w.:/@?=#→←\- ]*(0x[0-9A-Fa-f]+|\d+/\d+/\d+|sim:\S+|can:\S+|serial:\S+)"
                    r"[\w.:/@?=#→←\- ]*", text):
        return True  # an address, a key, a bus URL
    return any(text.startswith(d) for d in data if len(d) > 6)


def _data_strings(window) -> set[str]:
    """Names that come from the prosthesis, the profile tree, the protocol, python-can and
    the simulator's prostheses — not the app's own words."""
    import can.interfaces

    from pdcp_studio.app.trace.dock import CHANNEL_DATA
    from pdcp_studio.bus.sim.rigs import list_prostheses, prosthesis
    from pdcp_studio.protocol.codes import FunctionCode

    out = {c.title for c in FunctionCode} | {CHANNEL_DATA} | set(can.interfaces.BACKENDS)
    for name in list_prostheses():
        entry = prosthesis(name)
        out.add(entry.description)
        for script in entry.scripts:
            out.update((script.name, script.description))
    for path in [window.doc.path, *window.recent_files.paths()]:
        if path is not None:
            out.update((str(path), path.name))
    for device in window.doc.system.devices.values():
        out.add(device.name or "")
        for ch in device.channels.values():
            out.add(ch.descriptor or "")
    bridge = window.live.bridge  # the Simulator panel lists the simulated parts by name
    if bridge is not None and bridge.is_sim:
        out.update(name for _key, name, _plugged in bridge.session.sim_devices())
    tree = window.tree  # the device list shows names and profiles: data, not the app's words
    for i in range(tree.topLevelItemCount()):
        top = tree.topLevelItem(i)
        for item in [top, *(top.child(j) for j in range(top.childCount()))]:
            out.update(item.text(c) for c in range(tree.columnCount()))
    return {_plain(t) for t in out if t}


def _build(make_window, qtbot) -> dict[str, set[str]]:
    """The window on a live simulated prosthesis and each dialog: their texts by part."""
    from pdcp_studio.app.dialogs.compare_dialog import CompareDialog
    from pdcp_studio.app.dialogs.connect_dialog import ConnectDialog
    from pdcp_studio.app.dialogs.help_viewer import HelpViewer
    from pdcp_studio.app.dialogs.profile_tree_editor import ProfileTreeDialog
    from pdcp_studio.app.dialogs.write_config_dialog import WriteConfigDialog
    from pdcp_studio.app.documents.recovery import RecoveryDialog

    window = make_window(TRANSRADIAL, size=(1300, 850))
    with qtbot.waitSignal(window.live.connected, timeout=20000):
        window.connect_bus("sim:transradial")
    window.bus_docks.monitor_dock()
    parts = {"main window": _texts(window)}
    for menu in window.findChildren(QMenu):
        menu.aboutToShow.emit()  # menus that fill themselves when opened
        parts["main window"] |= _texts(menu)
    dialogs = {
        "connect": ConnectDialog(window),
        "compare": CompareDialog(window.doc.system, bridge=window.live.bridge, parent=window),
        "profile tree": ProfileTreeDialog(window.doc.tree, None, window),
        "recovery": RecoveryDialog([], window),
        "manual": HelpViewer(window),
        "write configuration": WriteConfigDialog.for_system(window.live.bridge,
                                                            window.doc.system, window),
    }
    for name, dialog in dialogs.items():
        dialog.show()
        qtbot.waitExposed(dialog)
        parts[name] = _texts(dialog)
        dialog.close()
    data = _data_strings(window)
    return {name: {t for t in texts if not _is_data(t, data)} for name, texts in parts.items()}


def test_the_german_translation_is_complete_and_compiles(tmp_path):
    unfinished = [m.find("source").text for m in ET.parse(TS).getroot().iter("message")
                  if m.find("translation").get("type") == "unfinished"]
    assert not unfinished, f"{len(unfinished)} untranslated: {unfinished[:10]}"
    assert i18n.compile_ts(TS, tmp_path / "de.qm")
    assert (tmp_path / "de.qm").stat().st_size > 10_000


def test_no_untranslated_string_in_the_german_window_and_dialogs(make_window, qtbot):
    english = _build(make_window, qtbot)
    app = QApplication.instance()
    i18n.install(app, "de")
    try:
        german = _build(make_window, qtbot)
    finally:
        i18n.uninstall(app)
    kept = _kept_in_german()
    left = {}
    for part, texts in german.items():
        same = {t for t in (texts & english[part]) - kept
                if not t.startswith("/")}  # a file's path (the history archive's) is data
        if same:
            left[part] = sorted(same)
    assert not left, f"untranslated in the German build: {left}"
    assert "Datei" in german["main window"] and "Hilfe" in german["main window"]


def test_lang_and_system_locale_choose_the_language(monkeypatch):
    from PySide6.QtCore import QLocale

    assert i18n.language("de") == "de" and i18n.language("de_AT") == "de"
    QLocale.setDefault(QLocale("de_DE"))
    try:
        monkeypatch.setattr(QLocale, "system", staticmethod(lambda: QLocale("de_DE")))
        assert i18n.language(None) == "de"
    finally:
        QLocale.setDefault(QLocale(QLocale.Language.English))


def test_the_manual_follows_the_language_with_english_as_the_fallback():
    from pdcp_studio.app.dialogs.help_viewer import manual_path, sections

    assert manual_path("de").name == "de.md" and manual_path("fr").name == "en.md"
    english, german = (sections(manual_path(lang).read_text("utf-8")) for lang in ("en", "de"))
    assert set(english) == set(german)  # F1 finds every part in either language
    assert german["graph"] == "Die Grafik"


def test_a_missing_compiled_translation_is_built_at_first_start(monkeypatch, tmp_path):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    shipped = i18n.ts_path("de").with_suffix(".qm")
    if shipped.exists():  # a build compiled it beside the .ts: hide it for this test
        monkeypatch.setattr(i18n, "ts_path", lambda lang: tmp_path / "src" / TS.name)
        (tmp_path / "src").mkdir()
        (tmp_path / "src" / TS.name).write_bytes(TS.read_bytes())
    qm = i18n.qm_path("de")
    assert qm is not None and qm.is_file() and str(qm).startswith(str(tmp_path))


def test_two_versions_of_the_translation_never_share_a_compiled_file(monkeypatch, tmp_path):
    """The compiled file is named by the translation's content: an older checkout's cached
    .qm (however new its time) is never loaded for a newer .ts."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    src = tmp_path / "src"
    src.mkdir()
    ts = src / TS.name
    monkeypatch.setattr(i18n, "ts_path", lambda lang: ts)
    ts.write_bytes(TS.read_bytes())
    first = i18n.qm_path("de")
    ts.write_bytes(TS.read_bytes().replace(b"</TS>", b"<!-- another version --></TS>"))
    second = i18n.qm_path("de")
    assert first is not None and second is not None and first != second
    assert first.is_file() and second.is_file()
