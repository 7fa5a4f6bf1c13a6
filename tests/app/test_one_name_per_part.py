"""One name per part everywhere (issue 11 items 1 and 6): on ``sim:transradial`` with its
spare hand, the graph's cards, the device tree, the Simulator panel (and its log), Checks
and each page of the guided tasks call every part by the same name: its own name, else
its product from the catalogue; a serial number only where two parts would read alike."""

from __future__ import annotations

import re

import pytest

from pdcp_studio.app.wizards import open_wizard
from pdcp_studio.model.refs import DeviceKey

from .trace_imports import wait_for_trace_imports

pytestmark = pytest.mark.gui

HAND = DeviceKey(2641, 769, 301)
SPARE = DeviceKey(2641, 769, 302)
T = 20000


def _graph(window):
    return {k: window.scene.device_label(d) for k, d in window.doc.system.devices.items()}


def _tree(window):
    tree = window.tree
    return {tree.topLevelItem(i).data(0, 0x0100): tree.topLevelItem(i).text(0)
            for i in range(tree.topLevelItemCount())}


def _sim(panel):
    return {panel.tree.topLevelItem(i).data(0, 0x0100): panel.tree.topLevelItem(i).text(0)
            for i in range(panel.tree.topLevelItemCount())}


def _no_other_names(text, names):
    """Every "(serial N)" in ``text`` belongs to one of ``names`` (no second naming rule)."""
    for m in re.finditer(r"[\w -]+\(serial \d+\)", text):
        assert any(m.group(0).strip().endswith(n) or n.endswith(m.group(0).strip())
                   for n in names.values()), (m.group(0), names)
    for old in ("EMG sensor", "Control unit (serial", "Spare hand"):
        assert old not in text, (old, text)


def _text(page):
    return page.view.toPlainText() + "\n" + page.status.text()


def _ready(wizard, qtbot, page):
    qtbot.waitUntil(lambda: wizard.currentPage() is page, timeout=T)
    qtbot.waitUntil(page.isComplete, timeout=T)


def test_every_panel_and_wizard_page_names_each_part_alike(make_window, qtbot):
    from pdcp_studio.app.docks.inspector_checks import checked_findings
    from pdcp_studio.app.wizards import logic

    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=T):
        window.connect_bus("sim:transradial")
    panel = window._leaf_docks["sim"].widget()
    qtbot.waitUntil(lambda: panel.tree.topLevelItemCount() == 5, timeout=T)
    graph = _graph(window)
    assert graph[HAND] == "Multi-grip hand with wrist rotator"
    assert graph[DeviceKey(2641, 257, 101)] == "EMG electrode (wrist flexors)"
    assert _tree(window) == graph
    sim = _sim(panel)
    assert {k: sim[k] for k in graph} == graph
    # The spare (not on the bus) is called what the graph will call it, told apart from
    # the hand by its serial number, never by the simulator's own label "Spare hand".
    assert sim[SPARE] == "Multi-grip hand with wrist rotator (serial 302)"
    assert panel.replace_combo.itemText(0) == sim[SPARE]

    # The swap, as the Replace-a-part task guides it: the hand out, the spare in.
    session = window.live.bridge.session
    result = session.transact(logic.store_change(session.system()))
    assert result.written, result.summary()
    window.reread_configuration()
    qtbot.waitUntil(lambda: window.doc.config is not None
                    and bool(window.doc.config.configurations), timeout=T)
    w = open_wizard(window, "replace")
    qtbot.waitUntil(lambda: "Nothing is missing" in _text(w.missing_page), timeout=T)
    panel.select(HAND)
    panel.unplug_selected()
    _ready(w, qtbot, w.missing_page)
    _no_other_names(_text(w.missing_page), _graph(window))
    assert _graph(window)[HAND] in _text(w.missing_page)
    w.next()
    qtbot.waitUntil(lambda: w.currentPage() is w.plug_page, timeout=T)
    panel.select(SPARE)
    panel.plug_selected()
    _ready(w, qtbot, w.plug_page)
    graph = _graph(window)
    assert graph[SPARE] == "Multi-grip hand with wrist rotator (serial 302)"
    assert graph[HAND] == "Multi-grip hand with wrist rotator (serial 301)"
    assert graph[SPARE] in _text(w.plug_page)
    _no_other_names(_text(w.plug_page), graph)
    w.next()
    _ready(w, qtbot, w.plan_page)
    assert graph[HAND] in _text(w.plan_page)
    _no_other_names(_text(w.plan_page), graph)
    w.close()
    qtbot.waitUntil(lambda: _tree(window) == graph, timeout=T)
    qtbot.waitUntil(lambda: _sim(panel) == graph, timeout=T)
    log = "\n".join(panel.log_lines())
    assert graph[SPARE] in log
    _no_other_names(log, graph)
    _findings, texts = checked_findings(window.doc.system, window.doc.autoconfigure)
    _no_other_names("\n".join(plain for plain, _detail in texts), graph)

    # The New fitting task's pages too.
    w = open_wizard(window, "fitting")
    for page in (w.connect_page, w.scan_page, w.checks_page, w.plan_page):
        qtbot.waitUntil(lambda page=page: w.currentPage() is page, timeout=T)
        qtbot.waitUntil(page.isComplete, timeout=T)
        if hasattr(page, "view"):
            _no_other_names(page.view.toPlainText(), graph)
        if page is w.scan_page:
            assert all(name in page.view.toPlainText() for k, name in graph.items()
                       if window.doc.system.devices[k].present)
        w.next()
    w.close()
    wait_for_trace_imports(qtbot)
    window.live.disconnect_bus()
