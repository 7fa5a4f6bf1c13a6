"""Counts read "1 link" / "2 links" everywhere in the app (and in German "1 Verbindung" /
"2 Verbindungen"), not only in the guided tasks: no "(s)" is left for the user to read."""

from __future__ import annotations

import ast
import xml.etree.ElementTree as ET
from pathlib import Path
from types import SimpleNamespace

import pytest
from PySide6.QtWidgets import QApplication

from pdcp_studio.app import i18n
from pdcp_studio.app.words.plural import count

ROOT = Path(__file__).resolve().parents[2]
APP = ROOT / "pdcp_studio" / "app"
TS = ROOT / "resources" / "i18n" / "pdcp_studio_de.ts"
#: "(s)" as the unit seconds, not a plural.
SECONDS = {"time before now (s)", "time before the hold (s)"}


def _docstrings(tree: ast.AST) -> set[int]:
    ids = set()
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr) \
                and isinstance(body[0].value, ast.Constant):
            ids.add(id(body[0].value))
    return ids


def _app_modules():
    for path in sorted(APP.rglob("*.py")):
        yield path, ast.parse(path.read_text(encoding="utf-8"))


def test_no_string_in_the_app_leaves_a_plural_in_brackets():
    left = []
    for path, tree in _app_modules():
        skip = _docstrings(tree)
        for node in ast.walk(tree):
            if (isinstance(node, ast.Constant) and isinstance(node.value, str)
                    and id(node) not in skip and ("(s)" in node.value or "(es)" in node.value)
                    and "%n" not in node.value and node.value not in SECONDS
                    and path.name != "plural.py"):  # its markers, resolved there
                left.append(f"{path.relative_to(ROOT)}:{node.lineno}: {node.value!r}")
    assert not left, "\n".join(left)


def _numerus() -> dict[tuple[str, str], list[str]]:
    out = {}
    for context in ET.parse(TS).getroot().iter("context"):
        name = context.findtext("name")
        for message in context.iter("message"):
            if message.get("numerus") == "yes":
                forms = [f.text or "" for f in message.find("translation").iter("numerusform")]
                out[(name, message.findtext("source"))] = forms
    return out


def _count_calls():
    """(module, context, text) of every ``count(context, "…%n…", n)`` in the app."""
    for path, tree in _app_modules():
        names = {t.id: n.value.value for n in tree.body if isinstance(n, ast.Assign)
                 for t in n.targets if isinstance(t, ast.Name)
                 and isinstance(n.value, ast.Constant) and isinstance(n.value.value, str)}
        for node in ast.walk(tree):
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                    and node.func.id == "count" and len(node.args) == 3):
                ctx, text = node.args[0], node.args[1]
                if isinstance(ctx, ast.Name):
                    ctx = ast.Constant(names.get(ctx.id))
                if isinstance(ctx, ast.Constant) and isinstance(text, ast.Constant):
                    yield path.name, ctx.value, text.value


def test_every_count_in_the_app_has_its_german_forms():
    known = _numerus()
    calls = list(_count_calls())
    assert len(calls) >= 30
    missing = [c for c in calls if (c[1], c[2]) not in known]
    assert not missing, missing
    modules = {m for m, _c, _t in calls}
    assert {"bus.py", "events_panel.py", "compare_dialog.py", "report.py",
            "write_config_dialog.py", "window.py"} <= modules


@pytest.fixture
def german(qapp):
    i18n.install(qapp, "de")
    yield
    i18n.uninstall(qapp)


@pytest.mark.parametrize(("context", "text", "one", "two"), [
    ("WindowBus", "%n device(s)", "1 device", "2 devices"),
    ("EventsPanel", "%n event(s)", "1 event", "2 events"),
    ("ConfigWindow", "%n problem(s) found", "1 problem found", "2 problems found"),
    ("FittingReport", "%n set-up(s)", "1 set-up", "2 set-ups"),
    ("WriteConfigDialog", "Writing changes nothing (%n link(s) kept).",
     "Writing changes nothing (1 link kept).", "Writing changes nothing (2 links kept)."),
])
def test_counts_in_english(context, text, one, two):
    assert count(context, text, 1) == one and count(context, text, 2) == two


def test_every_count_reads_right_in_german(german):
    for (context, text), forms in _numerus().items():
        assert count(context, text, 1) == forms[0].replace("%n", "1"), (context, text)
        assert count(context, text, 2) == forms[1].replace("%n", "2"), (context, text)
    assert count("EventsPanel", "%n event(s)", 1) == "1 Ereignis"
    assert count("EventsPanel", "%n event(s)", 2) == "2 Ereignisse"
    assert count("ConfigWindow", "%n configuration(s)", 2) == "2 Konfigurationen"


def _events(panel, n):
    from pdcp_studio.bus import events as ev
    from pdcp_studio.model.system import DeviceKey

    panel.clear()
    for serial in range(n):
        panel.add_event(ev.DeviceJoined(DeviceKey(1, 1, serial)))
    return panel.count_label.text()


def test_the_events_panel_counts_its_events(qtbot):
    from pdcp_studio.app.docks.events_panel import EventsPanel
    from pdcp_studio.model.system import System

    panel = EventsPanel(lambda: System())
    qtbot.addWidget(panel)
    assert _events(panel, 1) == "1 event" and _events(panel, 2) == "2 events"
    app = QApplication.instance()
    i18n.install(app, "de")
    try:
        assert _events(panel, 1) == "1 Ereignis" and _events(panel, 2) == "2 Ereignisse"
    finally:
        i18n.uninstall(app)


def test_the_scan_finished_message_counts(make_window, qtbot):
    window = make_window()
    said = []
    window.show_message = lambda text, *a, **k: said.append(text)
    window._scan_finished(SimpleNamespace(devices={1: None}, links=[1, 2]))
    window._scan_finished(SimpleNamespace(devices={1: None, 2: None}, links=[1]))
    app = QApplication.instance()
    i18n.install(app, "de")
    try:
        window._scan_finished(SimpleNamespace(devices={1: None}, links=[1, 2]))
        window._scan_finished(SimpleNamespace(devices={1: None, 2: None}, links=[1]))
    finally:
        i18n.uninstall(app)
    assert said == ["Scan finished: 1 device, 2 links", "Scan finished: 2 devices, 1 link",
                    "Lesen beendet: 1 Gerät, 2 Verbindungen",
                    "Lesen beendet: 2 Geräte, 1 Verbindung"]
