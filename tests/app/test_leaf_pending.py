"""Pending changes, the operator and the patient reference, the fitting report's session part
— the pure and small parts, without a bus."""

from __future__ import annotations

import datetime as dt
from pathlib import Path

from PySide6.QtCore import QSettings

from pdcp_studio.app.documents import fitting, pending
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from pdcp_studio.storage import system_file

ROOT = Path(__file__).resolve().parents[2]
CONTROL = DeviceKey(2641, 513, 201)
HAND = DeviceKey(2641, 769, 301)
HAND_LINK = Link(ChannelRef(*CONTROL, 3), ChannelRef(*HAND, 1))


def _linked():
    from pdcp_studio.engine import plan_autoconfigure

    system = system_file.load_path(ROOT / "resources" / "systems" / "transradial.json")
    plan_autoconfigure(system).apply(system)
    return system


def test_pending_changes_and_their_one_change():
    from pdcp_studio.engine import set_links

    bus = _linked()
    project = bus.copy()
    assert pending.pending_changes(bus, project) == []
    assert pending.pending_changes(None, project) == []  # offline: nothing is pending
    set_links(project, [lk for lk in project.links if lk != HAND_LINK])
    project.devices[HAND].channels[2].descriptor = "Pinch motor"
    project.devices[HAND].beacon_interval = 150
    changes = pending.pending_changes(bus, project, {HAND_LINK: "removed by hand"})
    # The removal; Data Transfer Enabled that follows it is the arbitrator's, not listed.
    assert [(c.kind, c.field) for c in changes] == [
        ("remove", ""), ("parameter", "beacon_interval"), ("parameter", "descriptor")]
    assert changes[0].reason == "removed by hand"
    # In the words of the change's effect: the part and channel by name, as on the
    # prosthesis now, the value old → new (the confirmation says the same).
    assert changes[2].describe(bus, project) == "Hand, Pinch grip: name “Pinch grip” → “Pinch motor”"
    assert changes[1].describe(bus, project) == "Hand: beacon interval 100 ms → 150 ms"
    assert changes[0].describe(bus, project) == "Control unit, Power grip set point → Hand, Power grip"
    change = pending.change_for(changes, project)
    assert change.action == pending.WRITE_ACTION
    assert [(a.op, a.link) for a in change.links] == [("remove", HAND_LINK)]
    assert [(w.device, w.param, w.channel) for w in change.parameters] == [
        (HAND, 10, 0), (HAND, 2, 2)]
    assert change.parameters[1].value == b"Pinch motor\0"
    # A switched-off channel that is still linked is a change the user made: listed.
    project.devices[CONTROL].channels[1].data_enabled = False
    assert ("parameter", "data_enabled") in [
        (c.kind, c.field) for c in pending.pending_changes(bus, project)]
    # A missing device cannot be written: its edits wait.
    bus.devices[HAND].present = False
    assert all(c.key != HAND for c in pending.pending_changes(bus, project))


def test_the_operator_is_asked_once_and_the_environment_wins(tmp_path, monkeypatch):
    settings = QSettings(str(tmp_path / "s.ini"), QSettings.Format.IniFormat)
    monkeypatch.delenv(fitting.ENV_OPERATOR, raising=False)
    asked = []

    def ask(_parent, default):
        asked.append(default)
        return "  A. Prosthetist "

    assert fitting.operator_name(settings=settings, ask=ask) == "A. Prosthetist"
    assert fitting.operator_name(settings=settings, ask=ask) == "A. Prosthetist"
    assert len(asked) == 1  # remembered
    monkeypatch.setenv(fitting.ENV_OPERATOR, "From the environment")
    assert fitting.operator_name(settings=settings, ask=ask) == "From the environment"
    assert len(asked) == 1
    monkeypatch.delenv(fitting.ENV_OPERATOR)
    fresh = QSettings(str(tmp_path / "t.ini"), QSettings.Format.IniFormat)
    assert fitting.operator_name(settings=fresh, ask=lambda _p, _d: None) == ""  # declined


def test_the_patient_reference_belongs_to_the_prosthesis(tmp_path):
    settings = QSettings(str(tmp_path / "s.ini"), QSettings.Format.IniFormat)
    mine, other = [CONTROL, HAND], [CONTROL, DeviceKey(2641, 769, 302)]
    history = [{"devices": [{"vid": k.vid, "pid": k.pid, "serial": k.serial} for k in mine],
                "patient": "P-17"}]
    assert fitting.patient_reference(mine, settings=settings, history_entries=history) == "P-17"
    assert fitting.patient_reference(other, settings=settings, history_entries=history) == ""
    fitting.set_patient_reference(mine, "P-18", settings=settings)
    assert fitting.patient_reference(list(reversed(mine)), settings=settings) == "P-18"
    assert fitting.patient_reference(other, settings=settings) == ""


def test_the_report_fills_in_the_session(qapp):
    from pdcp_studio.app.report import FittingInfo, report_html
    from pdcp_studio.storage.profile_trees import load_profile_tree

    system = _linked()
    system.devices[HAND].present = False
    system.devices[HAND].fw_version = 0x0102
    info = FittingInfo("P-17", "A. Prosthetist", dt.datetime(2026, 11, 23, 10, 5, tzinfo=dt.UTC),
                       "sim:transradial",
                       [{"id": 3, "time": "2026-11-23T10:04:00Z", "action": "write to prosthesis",
                         "operator": "A. Prosthetist", "verified": True,
                         "outcome": {"status": "applied"},
                         "plan": {"actions": [{"op": "remove"}], "parameters": [{}]}}])
    html = report_html(system, load_profile_tree(user_dir=False), fitting=info)
    assert "P-17" in html and "A. Prosthetist" in html and "2026-11-23 10:05 UTC" in html
    assert "Changes written to the prosthesis" in html
    assert "0 links added, 1 removed, 1 parameter" in html
    assert "applied, verified" in html
    assert "1.2" in html  # the hand's firmware version
    assert html.count("(to a missing device)") == sum(
        1 for lk in system.links if HAND in (lk.output.device, lk.input.device))
    assert "<h2>Checks</h2>" in html
    blank = report_html(system, load_profile_tree(user_dir=False))
    assert "P-17" not in blank and "_" * 30 in blank
