"""The guided tasks end to end on the simulated prosthesis ``sim:transradial``.

New fitting from scratch to a recorded history entry and a saved report; Replace a part
with the hand unplugged and the spare hand plugged in (as the Simulator panel does); Restore
from a configuration file and from the fitting history. Back/Next at each step, and Cancel
at each step before a write leaves the prosthesis (links, stored configuration, history)
exactly as it was.
"""

from __future__ import annotations

import time

import pytest

from pdcp_studio.app.wizards import open_wizard
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.storage.history import History

pytestmark = pytest.mark.gui

HAND = DeviceKey(2641, 769, 301)
SPARE = DeviceKey(2641, 769, 302)
CONTROL = DeviceKey(2641, 513, 201)
T = 20000


@pytest.fixture
def live(make_window, qtbot):
    """A window live on ``sim:transradial`` with its stored configuration read."""
    window = make_window()
    with qtbot.waitSignal(window.ready, timeout=T):
        window.connect_bus("sim:transradial")
    assert window.live.is_live, window.statusBar().currentMessage()
    qtbot.waitUntil(lambda: window.doc.config is not None, timeout=5000)
    yield window
    wizard = getattr(window, "task_wizard", None)
    if wizard is not None:
        qtbot.waitUntil(lambda: not wizard.writing, timeout=T)
        wizard.close()
    window.live.disconnect_bus()


def _session(window):
    return window.live.bridge.session


def _bus_state(window):
    """What a cancelled wizard must not change: links, stored configuration, history."""
    session = _session(window)
    with History.open() as history:
        n = len(history.entries())
    return set(session.system().links), session.read_configuration(), n


def _ready(wizard, qtbot, page):
    qtbot.waitUntil(lambda: wizard.currentPage() is page, timeout=T)
    qtbot.waitUntil(page.isComplete, timeout=T)


def _next(wizard, qtbot, page, after):
    _ready(wizard, qtbot, page)
    wizard.next()
    qtbot.waitUntil(lambda: wizard.currentPage() is after, timeout=T)


def _text(page):
    return page.view.toPlainText() + "\n" + page.status.text()


def _store_configuration(window, qtbot):
    """Store the links as the stored configuration (what a New fitting leaves)."""
    from pdcp_studio.app.wizards import logic

    session = _session(window)
    result = session.transact(logic.store_change(session.system()))
    assert result.written, result.summary()
    window.reread_configuration()
    qtbot.waitUntil(lambda: window.doc.config is not None
                    and bool(window.doc.config.configurations), timeout=5000)


# -- New fitting -------------------------------------------------------------------------
def test_new_fitting_from_scratch_to_a_recorded_history_entry_and_report(live, qtbot,
                                                                         tmp_path):
    w = open_wizard(live, "fitting")
    assert live.task_actions["fitting"].text()  # the Tasks menu opens the same wizard
    assert w.currentPage() is w.connect_page and w.connect_page.current.isChecked()
    _next(w, qtbot, w.connect_page, w.scan_page)
    _ready(w, qtbot, w.scan_page)
    text = _text(w.scan_page)
    assert "4 parts found on the bus" in text and "Multi-grip hand with wrist rotator" in text
    assert "302" not in text  # the spare hand is not on the bus until plugged in
    _next(w, qtbot, w.scan_page, w.checks_page)
    _ready(w, qtbot, w.checks_page)
    assert "No problems found" in _text(w.checks_page)
    _next(w, qtbot, w.checks_page, w.plan_page)
    _ready(w, qtbot, w.plan_page)
    # Start-up already autoconfigured the simulated prosthesis: the plan says so.
    assert "already linked" in _text(w.plan_page)
    assert "0x" not in w.plan_page.view.toPlainText()  # no hex in the plain words
    _next(w, qtbot, w.plan_page, w.write_page)
    _ready(w, qtbot, w.write_page)
    assert "Nothing needs writing" in _text(w.write_page)
    _next(w, qtbot, w.write_page, w.store_page)
    _ready(w, qtbot, w.store_page)
    assert "stored from now on: " in _text(w.store_page)  # the effect's words
    assert not _session(live).read_configuration().configurations  # not yet
    w.next()  # the commit button: store the configuration (one transaction)
    qtbot.waitUntil(lambda: w.currentPage() is w.report_page, timeout=T)
    stored = _session(live).read_configuration()
    assert len(stored.configurations[0].links) == 5
    with History.open() as history:
        entries = history.entries()
    assert [e["action"] for e in entries] == ["new fitting: store configuration"]
    assert entries[0]["verified"] and entries[0]["operator"] == "Test Prosthetist"
    assert f"entry {entries[0]['id']}" in _text(w.report_page)
    assert w.report_page.save_report(tmp_path / "fitting.pdf")
    assert (tmp_path / "fitting.pdf").read_bytes()[:5] == b"%PDF-"
    assert w.button(w.WizardButton.FinishButton).isVisible()


def test_new_fitting_writes_the_autoconfigure_plan_with_the_motion_interlock(live, qtbot):
    from pdcp_studio.bus.transaction import Change

    session = _session(live)
    before = list(session.system().links)
    assert session.transact(Change.links_to(before, [], "clear for the test")).written
    live.live.refresh()
    w = open_wizard(live, "fitting")
    _next(w, qtbot, w.connect_page, w.scan_page)
    _next(w, qtbot, w.scan_page, w.checks_page)
    _ready(w, qtbot, w.checks_page)
    assert "nothing feeds it" in _text(w.checks_page)  # the unconnected hand, in words
    _next(w, qtbot, w.checks_page, w.plan_page)
    _ready(w, qtbot, w.plan_page)
    text = _text(w.plan_page)
    assert text.count("Connect ") >= 5 and "drives a part of the prosthesis" in text
    assert "these parts are held still: Pattern-recognition control unit" in text
    assert "At the next power-on" in text  # the effect's next power-on, in words
    _next(w, qtbot, w.plan_page, w.write_page)
    w.next()
    qtbot.waitUntil(lambda: w.currentPage() is w.store_page, timeout=T)
    assert set(session.system().links) == set(before)
    result = w.results[0]
    assert result.written and result.held == [CONTROL]
    assert "Recorded in the fitting history" in w.write_page.status.text()
    _ready(w, qtbot, w.store_page)
    w.next()
    qtbot.waitUntil(lambda: w.currentPage() is w.report_page, timeout=T)
    with History.open() as history:
        actions = [e["action"] for e in history.entries()]
    assert actions[-2:] == ["new fitting: connect", "new fitting: store configuration"]


def test_new_fitting_back_next_and_cancel_at_each_step_change_nothing(live, qtbot):
    before = _bus_state(live)
    w = open_wizard(live, "fitting")
    order = [w.connect_page, w.scan_page, w.checks_page, w.plan_page, w.write_page,
             w.store_page]
    for i, page in enumerate(order[:-1]):
        _next(w, qtbot, page, order[i + 1])
        if i + 1 < 4:  # back and forward again (up to the first write)
            _ready(w, qtbot, order[i + 1])
            w.back()
            assert w.currentPage() is page
            _next(w, qtbot, page, order[i + 1])
    # Cancel before the store: nothing on the prosthesis changed, nothing recorded.
    _ready(w, qtbot, w.store_page)
    w.reject()
    assert not w.isVisible()
    assert _bus_state(live) == before
    for stop_at in range(1, 5):  # cancel at each earlier step too
        w = open_wizard(live, "fitting")
        for i in range(stop_at):
            _next(w, qtbot, order_of(w)[i], order_of(w)[i + 1])
        _ready(w, qtbot, w.currentPage())
        w.reject()
        assert _bus_state(live) == before


def order_of(w):
    return [w.connect_page, w.scan_page, w.checks_page, w.plan_page, w.write_page,
            w.store_page]


def test_new_fitting_connects_to_the_chosen_simulated_prosthesis(make_window, qtbot):
    window = make_window()
    w = open_wizard(window, "fitting")
    page = w.connect_page
    assert not page.current.isEnabled() and page.simulated.isChecked()
    page.sim_page.set_url("sim:thesis-test2")
    w.next()  # connects, then moves on by itself
    qtbot.waitUntil(lambda: w.currentPage() is w.scan_page, timeout=T)
    assert window.live.url == "sim:thesis-test2"
    _ready(w, qtbot, w.scan_page)
    w.close()
    window.live.disconnect_bus()


# -- Replace a part ----------------------------------------------------------------------
def test_replace_a_part_unplug_the_hand_plug_the_spare(live, qtbot, tmp_path):
    _store_configuration(live, qtbot)
    w = open_wizard(live, "replace")
    qtbot.waitUntil(lambda: "Nothing is missing" in _text(w.missing_page), timeout=T)
    assert not w.missing_page.isComplete()
    assert w.missing_page.sim_button.isVisible()
    # The part to pull, by its name: the one whose spare the Simulator panel offers.
    qtbot.waitUntil(lambda: "choose Multi-grip hand with wrist rotator" in
                    _text(w.missing_page), timeout=T)
    assert "and press Unplug" in _text(w.missing_page)
    w.missing_page.show_simulator()
    panel = live._leaf_docks["sim"].widget()
    panel.select(HAND)
    panel.unplug_selected()  # the Simulator panel's Unplug: the page follows the bus
    _ready(w, qtbot, w.missing_page)
    assert "Multi-grip hand with wrist rotator is not on the bus; 3 links led to it" in \
        _text(w.missing_page)
    _next(w, qtbot, w.missing_page, w.plug_page)
    qtbot.waitUntil(lambda: "Waiting for the new part" in _text(w.plug_page), timeout=T)
    assert not w.plug_page.isComplete()
    # The page names the spare as the Simulator panel lists it (no "spare hand" anywhere).
    spare = panel._label(SPARE)
    assert spare == "Multi-grip hand with wrist rotator (serial 302)"
    qtbot.waitUntil(lambda: f"in the Simulator panel choose {spare} and press Plug in"
                    in _text(w.plug_page), timeout=T)
    assert "spare" not in _text(w.plug_page).lower()
    qtbot.waitUntil(lambda: SPARE in {k for k, _n, _p in _session(live).sim_devices()},
                    timeout=T)
    panel.select(SPARE)
    panel.plug_selected()
    _ready(w, qtbot, w.plug_page)
    assert "New on the bus: Multi-grip hand with wrist rotator (serial 302)." in \
        _text(w.plug_page)
    assert ") (" not in _text(w.plug_page)
    _next(w, qtbot, w.plug_page, w.plan_page)
    _ready(w, qtbot, w.plan_page)
    text = _text(w.plan_page)
    # The gone hand's channel by its one name whether or not the bus still remembers it
    # (the plan does): never "channel 1".
    assert "It takes the place of Multi-grip hand with wrist rotator (serial 301), Power " \
           "grip, which is gone" in text, text
    assert ", channel 1" not in text
    assert "Exact match: it does the same job and sends its data the same way (31 of 31 " \
           "points)" in text
    assert "(23 of 23 points)" in text  # the wrist rotation: a two-level profile
    assert "0x" not in w.plan_page.view.toPlainText()
    _next(w, qtbot, w.plan_page, w.write_page)
    _ready(w, qtbot, w.write_page)
    w.next()
    qtbot.waitUntil(lambda: w.currentPage() is w.verify_page, timeout=T)
    _ready(w, qtbot, w.verify_page)
    assert w.verify_page.problems == []
    assert "On the prosthesis as planned: 5 links." in _text(w.verify_page)
    assert "reads back as written" in _text(w.verify_page)
    session = _session(live)
    links = session.system().links
    assert len(links) == 5 and not any(HAND in (lk.output.device, lk.input.device)
                                       for lk in links)
    stored = {sl.input.ref.device for sl in session.read_configuration().configurations[0].links}
    assert SPARE in stored and HAND not in stored
    with History.open() as history:
        assert history.entries()[-1]["action"] == "replace a part"
    _next(w, qtbot, w.verify_page, w.report_page)
    assert w.report_page.save_report(tmp_path / "swap.pdf")


def test_replace_a_part_cancel_before_the_write_changes_nothing(live, qtbot):
    _store_configuration(live, qtbot)
    session = _session(live)
    session.unplug(HAND)
    qtbot.waitUntil(lambda: not session.system().devices[HAND].present, timeout=T)
    session.plug(SPARE)
    qtbot.waitUntil(lambda: SPARE in session.system().devices
                    and session.system().devices[SPARE].present, timeout=T)
    # the arbitrator's own duty cycle may still act on the plugged spare (later on a loaded
    # machine): the state compared is the one it settles in, unchanged for a second
    deadline = time.monotonic() + 60
    before = None
    while time.monotonic() < deadline:
        assert session.wait_settled(30)
        state = _bus_state(live)
        if state == before:
            break
        before = state
        qtbot.wait(1000)
    assert before is not None
    for steps in range(0, 4):
        w = open_wizard(live, "replace")
        order = [w.missing_page, w.plug_page, w.plan_page, w.write_page]
        for i in range(steps):
            _next(w, qtbot, order[i], order[i + 1])
            if i == 1:  # back and next again
                _ready(w, qtbot, order[2])
                w.back()
                _next(w, qtbot, order[1], order[2])
        _ready(w, qtbot, order[steps])
        w.reject()
        assert _bus_state(live) == before
    # The spare plugged in before the wizard opened is found as the new part.
    w = open_wizard(live, "replace")
    _next(w, qtbot, w.missing_page, w.plug_page)
    _ready(w, qtbot, w.plug_page)
    assert w.new_parts == [SPARE]


# -- Restore a configuration ---------------------------------------------------------------
def test_restore_from_a_file(live, qtbot, tmp_path):
    from pdcp_studio.bus.transaction import Change
    from pdcp_studio.engine import configuration_from_system
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.storage import config_codec

    session = _session(live)
    path = tmp_path / "fitted.pdcfg"
    config_codec.save_path(ConfigCollection([configuration_from_system(session.system())]),
                           path)
    wanted = set(session.system().links)
    # The prosthesis loses two links; the file puts them back.
    gone = sorted(wanted)[:2]
    assert session.transact(Change.links_to(sorted(wanted), sorted(wanted - set(gone)),
                                            "lose two")).written
    live.live.refresh()
    w = open_wizard(live, "restore")
    page = w.source_page
    assert not page.isComplete()
    assert not page.load_file(tmp_path / "missing.pdcfg")
    assert "missing.pdcfg" in page.status.text()  # the error names the file
    (tmp_path / "bad.pdcfg").write_bytes(b"\x00\x01garbage")
    assert not page.load_file(tmp_path / "bad.pdcfg")
    assert "bad.pdcfg" in page.status.text() and not page.isComplete()
    assert page.load_file(path) and page.isComplete()
    _next(w, qtbot, page, w.diff_page)
    _ready(w, qtbot, w.diff_page)
    text = _text(w.diff_page)
    assert "From the file fitted.pdcfg" in text
    # The effect's words: links made, the stored configuration, the next power-on.
    assert text.count("Link made: ") >= 2 and "stored from now on: " in text
    assert "At the next power-on" in text
    # Back to the choice and forward again: the same difference.
    w.back()
    _next(w, qtbot, page, w.diff_page)
    _next(w, qtbot, w.diff_page, w.write_page)
    w.next()
    qtbot.waitUntil(lambda: w.currentPage() is w.verify_page, timeout=T)
    _ready(w, qtbot, w.verify_page)
    assert w.verify_page.problems == []
    assert set(session.system().links) == wanted
    assert not config_codec_diff(session.read_configuration(), path)


def config_codec_diff(collection, path):
    from pdcp_studio.model.config_diff import diff_configurations
    from pdcp_studio.storage import config_codec

    return not diff_configurations(collection, config_codec.load_path(path)).equal


def test_restore_from_the_history_and_cancel_changes_nothing(live, qtbot):
    from pdcp_studio.bus.transaction import Change

    session = _session(live)
    _store_configuration(live, qtbot)  # entry 1: five links, stored
    fitted = set(session.system().links)
    assert session.transact(Change.links_to(sorted(fitted), sorted(fitted)[:3],
                                            "lose two")).written  # entry 2
    live.live.refresh()
    live.history_panel.refresh()
    qtbot.waitUntil(lambda: len(live.history_panel.all_entries()) == 2, timeout=T)
    before = _bus_state(live)
    w = open_wizard(live, "restore")
    page = w.source_page
    qtbot.waitUntil(lambda: len(page.history) == 2, timeout=T)
    assert page.history[0]["id"] > page.history[1]["id"]  # newest first
    # Cancel at the choice and at the difference: nothing changes.
    assert page.choose_entry(page.history[1]["id"])
    _next(w, qtbot, page, w.diff_page)
    _ready(w, qtbot, w.diff_page)
    assert "fitting history entry" in _text(w.diff_page)
    w.reject()
    assert _bus_state(live) == before
    w = open_wizard(live, "restore")
    page = w.source_page
    qtbot.waitUntil(lambda: len(page.history) == 2, timeout=T)
    assert page.choose_entry(page.history[1]["id"])
    _next(w, qtbot, page, w.diff_page)
    _next(w, qtbot, w.diff_page, w.write_page)
    w.next()
    qtbot.waitUntil(lambda: w.currentPage() is w.verify_page, timeout=T)
    _ready(w, qtbot, w.verify_page)
    assert w.verify_page.problems == []
    assert set(session.system().links) == fitted
    with History.open() as history:
        assert history.entries()[-1]["action"].startswith("history restore")


def test_the_chosen_history_entry_survives_a_refill_of_the_list(live, qtbot):
    """The background history refresh refills the Restore page's list: the entry the user
    chose stays chosen (found by its number, not its row), and a refill with nothing new
    leaves the list untouched."""
    from pdcp_studio.bus.transaction import Change

    session = _session(live)
    _store_configuration(live, qtbot)  # entry 1
    fitted = set(session.system().links)
    assert session.transact(Change.links_to(sorted(fitted), sorted(fitted)[:3],
                                            "lose two")).written  # entry 2
    live.history_panel.refresh()
    qtbot.waitUntil(lambda: len(live.history_panel.all_entries()) == 2, timeout=T)
    w = open_wizard(live, "restore")
    page = w.source_page
    qtbot.waitUntil(lambda: len(page.history) == 2, timeout=T)
    oldest = page.history[1]["id"]
    assert page.choose_entry(oldest)
    first_item = page.entries.item(0)
    page._fill(live.history_panel.all_entries())  # the refresh lands: nothing new
    assert page.entries.item(0) is first_item
    assert page.chosen_id() == oldest and page.source()[1]["id"] == oldest
    # A new fitting lands while the user looks: the choice moves down with its entry.
    assert session.transact(Change.links_to(sorted(fitted)[:3], sorted(fitted)[:4],
                                            "one back")).written  # entry 3
    live.history_panel.refresh()
    qtbot.waitUntil(lambda: len(live.history_panel.all_entries()) == 3, timeout=T)
    page._fill(live.history_panel.all_entries())
    assert len(page.history) == 3 and page.entries.currentRow() == 2
    assert page.chosen_id() == oldest and page.from_history.isChecked()
    _next(w, qtbot, page, w.diff_page)
    _ready(w, qtbot, w.diff_page)
    assert f"fitting history entry {oldest})" in _text(w.diff_page)
    w.reject()


def test_help_opens_the_manual_at_the_guided_tasks(make_window):
    from pdcp_studio.app.dialogs import help_viewer

    window = make_window()
    for task in ("fitting", "replace", "restore"):
        wizard = open_wizard(window, task)
        assert help_viewer.section_for(wizard.currentPage()) == "tasks"
        wizard.close()
    for lang in ("en", "de"):
        text = help_viewer.manual_path(lang).read_text("utf-8")
        assert "tasks" in help_viewer.sections(text)


def test_stop_during_the_write_puts_the_prosthesis_back_and_cancel_waits(live, qtbot):
    from pdcp_studio.bus.transaction import Change

    session = _session(live)
    links = sorted(session.system().links)
    assert session.transact(Change.links_to(links, [], "clear for the test"),
                            record=False).written
    live.live.refresh()
    before = _bus_state(live)
    w = open_wizard(live, "fitting")
    for page, after in zip(order_of(w)[:4], order_of(w)[1:5], strict=True):
        _next(w, qtbot, page, after)
    _ready(w, qtbot, w.write_page)
    w.next()  # Write to prosthesis …
    assert w.writing and w.write_page.stop.isVisible()
    w.reject()  # … Cancel cannot close the wizard while it writes
    assert w.isVisible() and not w.button(w.WizardButton.CancelButton).isEnabled()
    w.write_page.stop.click()  # … Stop does, and puts the prosthesis back
    qtbot.waitUntil(lambda: not w.writing, timeout=T)
    assert w.currentPage() is w.write_page
    assert "Stopped. The prosthesis is as it was before." in w.write_page.status.text()
    assert set(session.system().links) == before[0]
    assert session.read_configuration() == before[1]
    assert w.button(w.WizardButton.CancelButton).isEnabled()
    w.reject()
    assert not w.isVisible()


def test_a_failed_connect_is_said_on_the_page_and_changes_nothing(live, qtbot):
    w = open_wizard(live, "fitting")
    page = w.connect_page
    page.other_url = "sim:no-such-prosthesis"
    page.other.setChecked(True)
    w.next()
    qtbot.waitUntil(lambda: "Cannot connect to sim:no-such-prosthesis" in page.status.text(),
                    timeout=T)
    assert w.currentPage() is page and page.isComplete()
    assert live.live.url == "sim:transradial" and live.live.is_live
    page.current.setChecked(True)
    _next(w, qtbot, page, w.scan_page)


# -- Words for a prosthetist (issue 11) ----------------------------------------------------
def test_checks_name_the_two_hands_apart(live, qtbot):
    """Both hands on the bus, nothing linked: each finding names its hand by serial."""
    from pdcp_studio.bus.transaction import Change

    session = _session(live)
    session.plug(SPARE)
    qtbot.waitUntil(lambda: SPARE in session.system().devices
                    and session.system().devices[SPARE].present, timeout=T)
    session.wait_settled(5)
    links = sorted(session.system().links)
    assert session.transact(Change.links_to(links, [], "clear for the test"),
                            record=False).written
    live.live.refresh()
    w = open_wizard(live, "fitting")
    _next(w, qtbot, w.connect_page, w.scan_page)
    _next(w, qtbot, w.scan_page, w.checks_page)
    _ready(w, qtbot, w.checks_page)
    text = _text(w.checks_page)
    # Each channel by its one name (its descriptor), never "channel 1".
    assert "Multi-grip hand with wrist rotator (serial 301), Power grip" in text
    assert "Multi-grip hand with wrist rotator (serial 302), Power grip" in text
    assert ", channel 1" not in text
    findings = [line for line in text.splitlines() if "nothing feeds it" in line]
    assert len(findings) == len(set(findings)) >= 2  # no two findings read alike


def test_restoring_an_entry_from_before_any_stored_configuration_warns_and_asks(live, qtbot):
    from pdcp_studio.bus.transaction import Change

    session = _session(live)
    fitted = set(session.system().links)
    assert not session.read_configuration().configurations  # nothing stored yet
    assert session.transact(Change.links_to(sorted(fitted), sorted(fitted)[:3],
                                            "lose two")).written  # entry 1: before storing
    assert session.transact(Change.links_to(sorted(fitted)[:3], sorted(fitted),
                                            "links back")).written  # entry 2
    _store_configuration(live, qtbot)  # entry 3: five links stored
    live.live.refresh()
    live.history_panel.refresh()
    qtbot.waitUntil(lambda: len(live.history_panel.all_entries()) == 3, timeout=T)
    w = open_wizard(live, "restore")
    page, diff = w.source_page, w.diff_page
    qtbot.waitUntil(lambda: len(page.history) == 3, timeout=T)
    # A later entry (made with the configuration stored): no warning.
    assert page.choose_entry(page.history[0]["id"])
    _next(w, qtbot, page, diff)
    _ready(w, qtbot, diff)
    assert not diff.clears and diff.warning.isHidden() and diff.isComplete()
    w.back()
    # The entry from before anything was stored: warned plainly, Next waits for the tick.
    earliest = page.history[-1]["id"]
    assert page.choose_entry(earliest)
    w.next()
    qtbot.waitUntil(lambda: w.currentPage() is diff and diff.clears, timeout=T)
    assert diff.warning.isVisible() and diff.confirm.isVisible()
    assert "clears the stored configuration" in diff.warning.text()
    assert not diff.isComplete() and not w.button(w.WizardButton.NextButton).isEnabled()
    before = _bus_state(live)
    w.next()  # refused: nothing moves, nothing written
    assert w.currentPage() is diff and _bus_state(live) == before
    diff.confirm.setChecked(True)
    assert diff.isComplete()
    _next(w, qtbot, diff, w.write_page)
    w.next()
    qtbot.waitUntil(lambda: w.currentPage() is w.verify_page, timeout=T)
    _ready(w, qtbot, w.verify_page)
    assert w.verify_page.problems == []
    assert not any(c.links for c in session.read_configuration().configurations)
    assert len(session.system().links) == 3


def test_the_connect_page_speaks_of_prostheses_not_buses(make_window, qtbot):
    from pdcp_studio.bus.sim.rigs import list_prostheses, prosthesis

    window = make_window()
    w = open_wizard(window, "fitting")
    page = w.connect_page
    shown = [page.sim_page.list.item(i).text() for i in range(page.sim_page.list.count())]
    assert shown[0] == prosthesis("transradial").description  # the one to try first
    assert sorted(shown) == sorted(prosthesis(n).description for n in list_prostheses())
    assert not set(shown) & set(list_prostheses())  # no raw names
    words = " ".join(b.text() for b in (page.current, page.simulated, page.other))
    words += " " + page.intro.text()
    for engineer in ("virtual bus", "in-process", "built-in", "sim:"):
        assert engineer not in words and engineer not in " ".join(shown), engineer
    assert page.sim_page.url() == "sim:transradial"
    page.sim_page.set_url("sim:appendix-d")
    assert page.sim_page.list.currentItem().text().startswith("Appendix D")
    w.close()


def test_the_connect_page_names_the_connected_prosthesis_plainly(live, qtbot):
    w = open_wizard(live, "fitting")
    assert w.connect_page.current.text() == \
        "The prosthesis connected now: Transradial prosthesis (simulated)"
    w.close()
