"""The profile-layer policy in the app (issue 17) over the simulated thesis rig.

The status bar shows it while live; Bus ▸ Autoconfigure on this prosthesis changes it
through the transaction road (previewed, confirmed, recorded in the fitting history); the
checks and the fitting report follow the prosthesis's policy; a declined change writes
nothing and leaves the check mark as the prosthesis has it.
"""

from __future__ import annotations

import pytest

from pdcp_studio.app import report
from pdcp_studio.storage.history import History

pytestmark = pytest.mark.gui


@pytest.fixture
def live(make_window, qtbot, tmp_path, monkeypatch):
    """A window live on ``sim:thesis-test2`` with its own fitting history."""
    history = tmp_path / "history.sqlite3"
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(history))
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=20000):
        window.connect_bus("sim:thesis-test2")
    assert window.live.is_live, window.statusBar().currentMessage()
    qtbot.waitUntil(lambda: window.doc.policy is not None, timeout=10000)
    window.previews = []
    window.answer = True

    def confirm(title, preview):
        window.previews.append((title, preview))
        return window.answer

    window.flow.confirm = confirm
    window.history_path = history
    yield window
    window.live.disconnect_bus()


def _bus_policy(window):
    return window.live.bridge.session.read_policy()


def _idle(window, qtbot):
    qtbot.waitUntil(lambda: not window.flow.busy and not window.live.bridge.busy,
                    timeout=10000)


def _link_into_a_terminal(system):
    """A link whose removal leaves a terminal channel (a motor) unconnected."""
    from pdcp_studio.engine import check_system

    for link in system.links:
        trial = system.copy()
        trial.remove_link(link)
        if any(f.code == "terminal-unconnected" for f in check_system(trial)):
            return link
    raise AssertionError("the rig has no link into a terminal channel")


def _findings(window):
    window.doc.select(None)
    window.inspector.show_object(None)
    lst = window.inspector.editors["findings"]
    return [lst.item(i).text() for i in range(lst.count())]


def test_the_status_bar_and_the_bus_menu_show_the_prosthesis_policy(live):
    assert live.policy_label.isVisible()
    assert live.policy_label.text() == "Autoconfigure: on"
    assert "on its own" in live.policy_label.toolTip()
    assert live.act_autoconfigure.isEnabled() and live.act_autoconfigure.isChecked()
    assert live.act_autoconfigure in live.bus_menu.actions()


def test_turning_autoconfigure_off_is_a_recorded_transaction(live, qtbot, tmp_path):
    assert _bus_policy(live).autoconfigure
    with qtbot.waitSignal(live.flow.finished, timeout=20000) as got:
        live.act_autoconfigure.trigger()  # checked → unchecked: turn it off
    result = got.args[0]
    assert result.ok, result.summary()
    # Previewed and confirmed first, in plain words.
    [(title, preview)] = live.previews
    assert title == "Turn autoconfigure off"
    assert preview.change.policy.autoconfigure is False
    assert preview.change.links == [] and preview.change.configuration is None
    assert any("(autoconfigure): on → off" in line for line in preview.lines())
    # Written: the prosthesis has it now, read back through the session.
    assert _bus_policy(live).autoconfigure is False
    # Recorded in the fitting history.
    entries = History(live.history_path).entries()
    assert entries and entries[-1]["action"] == "policy autoconfigure off"
    assert entries[-1]["policy_after"] == {"autoconfigure": False}
    # The label and the check mark follow (read on the worker after the transaction).
    qtbot.waitUntil(lambda: live.policy_label.text() == "Autoconfigure: off", timeout=10000)
    assert not live.act_autoconfigure.isChecked()
    assert "links nothing new" in live.policy_label.toolTip()
    _idle(live, qtbot)

    # The checks use the live policy: an unconnected hand channel is reported as left
    # alone because autoconfigure is off, not as something autoconfigure would link.
    doc = live.doc
    link = _link_into_a_terminal(doc.system)
    doc.select(link)
    live.act_delete.trigger()  # staged in the project only
    texts = _findings(live)
    assert any("Autoconfigure is off on this prosthesis" in t for t in texts), texts
    assert not any("let Autoconfigure do it" in t for t in texts), texts
    tips = [live.inspector.editors["findings"].item(i).toolTip()
            for i in range(live.inspector.editors["findings"].count())]
    assert any("autoconfigure is off" in t for t in tips), tips
    assert not any("would link it" in t for t in tips), tips

    # The fitting report states the policy (and its checks use it).
    html = report.report_html(doc.system, doc.tree, fitting=live.fitting_info())
    assert "Autoconfigure: <b>off</b>" in html
    assert "Autoconfigure is off on this prosthesis" in html  # the checks, in plain words
    pdf = tmp_path / "report.pdf"
    assert live.write_fitting_report(pdf)
    assert pdf.read_bytes().startswith(b"%PDF")

    # And back on: the label says so again.
    live.answer = True
    with qtbot.waitSignal(live.flow.finished, timeout=20000):
        live.act_autoconfigure.trigger()
    assert _bus_policy(live).autoconfigure is True
    qtbot.waitUntil(lambda: live.policy_label.text() == "Autoconfigure: on", timeout=10000)
    assert live.act_autoconfigure.isChecked()


def test_declining_changes_nothing(live, qtbot):
    live.answer = False
    before = History(live.history_path).entries()
    with qtbot.waitSignal(live.flow.busyChanged, timeout=20000,
                          check_params_cb=lambda busy: busy is False):
        live.act_autoconfigure.trigger()
    assert len(live.previews) == 1
    assert _bus_policy(live).autoconfigure is True
    assert History(live.history_path).entries() == before
    assert live.act_autoconfigure.isChecked()  # as the prosthesis has it
    assert live.policy_label.text() == "Autoconfigure: on"


def test_the_report_states_autoconfigure_on(live):
    html = report.report_html(live.doc.system, live.doc.tree, fitting=live.fitting_info())
    assert "Autoconfigure: <b>on</b>" in html


def test_the_policy_reads_in_german(make_window, qtbot):
    from PySide6.QtWidgets import QApplication

    from pdcp_studio.app import i18n

    app = QApplication.instance()
    i18n.install(app, "de")
    try:
        window = make_window()
        with qtbot.waitSignal(window.ready, timeout=20000):
            window.connect_bus("sim:thesis-test2")
        qtbot.waitUntil(lambda: window.policy_label.text() == "Autokonfiguration: an",
                        timeout=10000)
        assert window.act_autoconfigure.text() == "&Autokonfiguration an dieser Prothese"
        assert "Handgelenk" in window.policy_label.toolTip()
        window.live.disconnect_bus()
    finally:
        i18n.uninstall(app)


def test_the_policy_is_read_again_after_an_arbitrator_reset(live, qtbot):
    with qtbot.waitSignal(live.flow.finished, timeout=20000):
        live.act_autoconfigure.trigger()
    qtbot.waitUntil(lambda: live.policy_label.text() == "Autoconfigure: off", timeout=10000)
    _idle(live, qtbot)
    # Kept with the stored configuration: still off after a reset that keeps the memory.
    with qtbot.waitSignal(live.live.bridge.simChanged, timeout=20000):
        live.live.bridge.reset_arbitrator(True)
    _idle(live, qtbot)
    assert _bus_policy(live).autoconfigure is False
    assert live.policy_label.text() == "Autoconfigure: off"
    # Erased memory: the label shows what the restarted arbitrator holds now.
    with qtbot.waitSignal(live.live.bridge.simChanged, timeout=20000):
        live.live.bridge.reset_arbitrator(False)
    _idle(live, qtbot)
    now = "on" if _bus_policy(live).autoconfigure else "off"
    qtbot.waitUntil(lambda: live.policy_label.text() == f"Autoconfigure: {now}", timeout=10000)
    assert live.act_autoconfigure.isChecked() == (now == "on")


def test_turning_autoconfigure_on_previews_and_makes_the_links(live, qtbot):
    """Issue 26 item 5: off says which links stay; on, with the terminal channels left
    unconnected, previews the links the duty cycle would make and makes them in the
    same transaction (verified, recorded)."""
    from pdcp_studio.bus.transaction import Change

    with qtbot.waitSignal(live.flow.finished, timeout=20000) as got:
        live.act_autoconfigure.trigger()  # off
    assert got.args[0].ok
    notes = live.policy.last_switch.words  # the words for the effect (the lead's)
    assert notes[0].startswith("Every link stays as it is (3 links)"), notes
    assert len(notes) == 4 and all(" → " in n for n in notes[1:]), notes
    assert live.previews[-1][1].change.links == []  # nothing is removed
    _idle(live, qtbot)
    session = live.live.bridge.session
    cleared = session.transact(Change.from_plan(session.preview("clear")))
    assert cleared.written and session.system().links == []
    live.live.refresh()
    _idle(live, qtbot)
    qtbot.waitUntil(lambda: live.policy_label.text() == "Autoconfigure: off", timeout=10000)

    with qtbot.waitSignal(live.flow.finished, timeout=20000) as got:
        live.act_autoconfigure.trigger()  # on
    result = got.args[0]
    assert result.written and result.verified, result.summary()
    title, preview = live.previews[-1]
    assert title == "Turn autoconfigure on"
    assert preview.change.policy.autoconfigure is True
    assert [a.op for a in preview.change.links] == ["add"] * 3
    lines = preview.lines()
    assert sum(line.startswith("  Link made: ") for line in lines) == 3, lines
    assert live.policy.last_switch.words == []
    assert len(session.system().links) == 3 and _bus_policy(live).autoconfigure is True
    entry = History(live.history_path).entries()[-1]
    assert entry["action"] == "policy autoconfigure on" and entry["verified"] is True
    assert len(entry["links_after"]) == 3 and entry["links_before"] == []


def test_the_kept_words_headlines_are_the_engines():
    from pdcp_studio.app.window.controllers import policy
    from pdcp_studio.engine import policy_change

    assert policy.KEPT == policy_change.KEPT  # translated by the same text
    assert policy.NONE_KEPT == policy_change.NONE_KEPT


def test_the_kept_words_read_in_german():
    from PySide6.QtWidgets import QApplication

    from pdcp_studio.app import i18n
    from pdcp_studio.app.window.controllers.policy import _CTX
    from pdcp_studio.app.words.plural import count
    from pdcp_studio.engine.policy_change import kept_words
    from pdcp_studio.model.refs import ChannelRef
    from pdcp_studio.model.system import Link

    app = QApplication.instance() or QApplication([])
    i18n.install(app, "de")
    try:
        link = Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2))
        words = kept_words([link, link], say=lambda text, n: count(_CTX, text, n))
        assert words[0].startswith("Jede Verbindung bleibt, wie sie ist (2 Verbindungen)")
        assert kept_words([], say=lambda text, n: count(_CTX, text, n))[0].startswith(
            "Keine Verbindung wird entfernt")
    finally:
        i18n.uninstall(app)
