"""What the prosthetist's trial met (issue 26, point 9): small things, each in their path."""

from __future__ import annotations

import shutil
import subprocess

import pytest

pytestmark = pytest.mark.gui


def _connect(window, qtbot, url: str) -> None:
    """Connect ``url`` and wait until its prosthesis is the document."""
    window.connect_bus(url)
    qtbot.waitUntil(lambda: window.live.is_live and window.live.url == url
                    and window.doc.session is window.live.bridge, timeout=20000)


# -- the Simulator panel has a View-menu entry --------------------------------------------
def test_simulator_panel_is_in_the_view_menu(make_window, qtbot):
    window = make_window()
    _connect(window, qtbot, "sim:transradial")
    dock = window.bus_docks.leaf_docks["sim"]
    assert dock.toggleViewAction() in window.view_menu.actions()
    dock.toggleViewAction().trigger()
    assert dock.isHidden()
    dock.toggleViewAction().trigger()
    assert not dock.isHidden()
    window.live.disconnect_bus()
    qtbot.waitUntil(lambda: "sim" not in window.bus_docks.leaf_docks, timeout=5000)
    assert dock.isHidden() and not dock.toggleViewAction().isEnabled()


def test_the_simulator_panel_stays_after_switching_prosthesis(make_window, qtbot):
    """A new Simulator dock made after a switch came back hidden (the old one's place was
    restored as closed): the one dock stays, with the new session's panel."""
    window = make_window()
    _connect(window, qtbot, "sim:transradial")
    first = window.bus_docks.leaf_docks["sim"].widget()
    _connect(window, qtbot, "sim:thesis-test1")
    qtbot.wait(200)  # the docks made after start-up are restored on the next turn
    dock = window.bus_docks.leaf_docks["sim"]
    assert not dock.isHidden()
    assert dock.widget() is not first and dock.widget().bridge is window.live.bridge
    assert dock.toggleViewAction() in window.view_menu.actions()
    assert [a for a in window.view_menu.actions() if a.text() == "Simulator"] == [
        dock.toggleViewAction()]
    window.live.disconnect_bus()


# -- switching prostheses leaves nothing of the previous one --------------------------------
def test_switching_prosthesis_clears_events_and_plot(make_window, qtbot):
    window = make_window()
    _connect(window, qtbot, "sim:transradial")
    docks = window.bus_docks
    events = docks.events_dock().widget()
    first = window.live.bridge
    hand = next(k for k, d in window.doc.system.devices.items() if d.pid == 769)
    first.unplug(hand)
    qtbot.waitUntil(lambda: any("left" in r[0] for r in events.rows()), timeout=10000)
    docks.make_trace_docks()
    plot = docks.leaf_docks["plot"].widget()
    ref = next(iter(window.doc.system.links)).output
    plot.add_channel(ref)
    qtbot.waitUntil(lambda: any(len(s.ts) for s in plot.series), timeout=10000)
    before = {s.ref for s in plot.series}

    _connect(window, qtbot, "sim:thesis-test1")
    assert window.live.bridge is not first
    assert not any("Multi-grip" in r[0] for r in events.rows()), events.rows()
    assert not any("left" in r[0] for r in events.rows()), events.rows()
    assert not ({s.ref for s in plot.series} & before)
    assert all(s.ref.device in window.doc.system.devices for s in plot.series)
    window.live.disconnect_bus()


# -- the history panel: a detail pane with room, a hint that follows the selection -------
def test_history_details_have_room_and_the_hint_follows(make_window, qtbot):
    from pdcp_studio.bus.transaction import Change

    window = make_window(size=(1500, 950))
    _connect(window, qtbot, "sim:transradial")
    session = window.live.bridge.session
    links = sorted(session.system().links)
    assert session.transact(Change.links_to(links, links[1:], "one less")).written
    assert session.transact(Change.links_to(links[1:], links, "again")).written
    window.history_dock.show()
    window.history_dock.raise_()
    panel = window.history_panel
    with qtbot.waitSignal(panel.loaded, timeout=5000):
        panel.refresh()
    qtbot.waitUntil(lambda: panel.split.width() > 600, timeout=5000)
    table, details = panel.split.sizes()
    assert details >= 0.4 * (table + details) - 2, (table, details)
    panel.select_ids()
    assert panel.hint.isVisibleTo(panel) and "two" in panel.hint.text()
    panel.select_ids(1)
    assert panel.hint.isVisibleTo(panel) and "second" in panel.hint.text()
    panel.select_ids(1, 2)
    assert not panel.hint.isVisibleTo(panel), panel.hint.text()
    window.live.disconnect_bus()


# -- the graph's export: no selection highlight, and a PDF beside PNG and SVG --------------
RIG_FILE = "appendix-d.json"  # a system with links


def test_png_export_shows_no_selection(make_window, systems_dir, qtbot):
    window = make_window(systems_dir / RIG_FILE)
    plain = window.graph_image(1.0)
    card = next(iter(window.doc.system.devices))
    link = next(iter(window.doc.system.links))
    for chosen in (card, link.output, link):
        window.doc.select(chosen)
        assert window.scene.selectedItems()
        shown = window.graph_image(1.0)
        assert shown == plain, f"the export shows the selection of {chosen}"
        # The window's selection is as it was.
        assert window.doc.selection == chosen
        assert window.scene.selectedItems()


def test_graph_exports_a_one_page_vector_pdf(make_window, qtbot, tmp_path):
    import re

    window = make_window()
    _connect(window, qtbot, "sim:transradial")
    window.doc.select(next(iter(window.doc.system.devices)))
    path = tmp_path / "bus.pdf"
    window.export_graph(path)
    data = path.read_bytes()
    assert data.startswith(b"%PDF-") and data.rstrip().endswith(b"%%EOF")
    assert len(re.findall(rb"/Type\s*/Page[^s]", data)) == 1
    assert b"/Subtype /Image" not in data and b"/Subtype/Image" not in data  # vectors
    assert window.scene.selectedItems()  # the selection stays on screen
    menus = [a.menu() for a in window.menuBar().actions() if a.menu() is not None]
    texts = [a.text().replace("&", "") for m in menus for a in m.actions()]
    assert "Export graph as PDF…" in texts
    if shutil.which("pdfinfo"):
        info = subprocess.run(["pdfinfo", str(path)], capture_output=True, text=True,
                              check=True).stdout
        assert re.search(r"^Pages:\s+1$", info, re.M), info
    window.live.disconnect_bus()


# -- quitting a live view with pending changes asks once, in words of the prosthesis -------
def _live_with_a_pending_change(make_window, qtbot):
    from pdcp_studio.app.documents import commands

    window = make_window()
    _connect(window, qtbot, "sim:transradial")
    doc = window.doc
    doc.undo_stack.push(commands.RemoveLinkCommand(doc, doc.system.links[0]))
    qtbot.waitUntil(lambda: window.transactions.unwritten() == 1, timeout=5000)
    return window


def test_quitting_a_live_view_with_pending_changes_asks_once(make_window, qtbot, monkeypatch):
    from pdcp_studio.app.window import questions

    window = _live_with_a_pending_change(make_window, qtbot)
    asked: list[int] = []
    answers = iter([questions.QUIT_CANCEL, questions.QUIT_DISCARD])

    def ask_quit_live(n):
        asked.append(n)
        return next(answers)

    monkeypatch.setattr(window, "ask_quit_live", ask_quit_live)
    monkeypatch.setattr(window, "ask_unwritten", lambda n: pytest.fail("asked twice"))
    monkeypatch.setattr(window, "ask_save_changes",
                        lambda: pytest.fail("asked to save a live view to the prosthesis"))
    window.quiet = False
    try:
        assert not window.close()  # cancelled: nothing lost
        assert asked == [1] and window.isVisible() and window.live.is_live
        assert window.close()  # discarded: closes, after one question
        assert asked == [1, 1]
    finally:
        window.quiet = True


def test_the_quit_question_says_what_is_pending_and_where_it_goes():
    from pdcp_studio.app.window.questions import quit_live_words

    text, more = quit_live_words(3, "sim:transradial")
    assert text == "3 changes not written to the prosthesis on sim:transradial yet."
    assert "discard" in more and "Save" not in text + more
    assert quit_live_words(1, "sim:x")[0] == "1 change not written to the prosthesis on sim:x yet."


# -- German: plurals, the simulator's scripts, the arbiter's cable ---------------------------
@pytest.fixture
def german(qapp):
    from pdcp_studio.app import i18n

    i18n.install(qapp, "de")
    yield
    i18n.uninstall(qapp)


def test_german_counts_findings_with_its_own_plural(german):
    from pdcp_studio.app.docks.inspector import checks_title

    assert checks_title(1) == "<b>Prüfungen</b> — 1 Befund"
    assert checks_title(3) == "<b>Prüfungen</b> — 3 Befunde"
    assert checks_title(0) == "<b>Prüfungen</b> — keine Befunde"


def test_english_counts_findings(qapp):
    from pdcp_studio.app.docks.inspector import checks_title

    assert checks_title(1) == "<b>Checks</b> — 1 finding"
    assert checks_title(2) == "<b>Checks</b> — 2 findings"


def test_every_simulator_script_reads_in_german(german):
    from pdcp_studio.app.docks.sim_panel import script_name_words, script_words
    from pdcp_studio.bus.sim.rigs import list_prostheses, prosthesis

    seen = 0
    for name in list_prostheses():
        for script in prosthesis(name).scripts:
            said = script_words(script.description, lambda key: "Die Hand")
            assert said != script.description, (name, script.name, said)
            assert script_name_words(script.name) != script.name, script.name
            seen += 1
    assert seen > 10
    said = script_words("pull 2641/769/301 and plug it back in: it keeps its sources and "
                        "the arbitrator links it again", lambda key: f"Hand {key.serial}")
    assert said.startswith("Hand 301 abziehen und wieder anstecken")


def test_the_german_file_names_the_arbiters_cable_in_german():
    from pathlib import Path

    ts = (Path(__file__).resolve().parents[2] / "resources" / "i18n"
          / "pdcp_studio_de.ts").read_text(encoding="utf-8")
    assert "Arbiter-Kabel" not in ts and "Befund(e)" not in ts


def test_the_inspector_counts_parts_and_links_with_plurals(make_window, qtbot, german):
    from PySide6.QtWidgets import QLabel

    window = make_window()
    _connect(window, qtbot, "sim:thesis-test1")  # 2 parts, 1 link
    window.doc.select(None)
    qtbot.waitUntil(lambda: any("Verbindung" in lb.text()
                                for lb in window.inspector.findChildren(QLabel)), timeout=5000)
    texts = [lb.text() for lb in window.inspector.findChildren(QLabel)]
    assert any("2 Geräte, 1 Verbindung · " in t for t in texts), texts
    assert not any("1 Verbindungen" in t or "Befund(e)" in t for t in texts), texts
    window.live.disconnect_bus()
