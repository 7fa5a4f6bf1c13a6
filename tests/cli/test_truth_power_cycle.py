"""The predicted next power-on is what a real power cycle does (issue 26, point 2).

Three processes (tests/cli/truth_rig.py): simulated ``transradial`` devices, a headless
arbitrator with a memory file, and the CLI over its host link. A change is made through the CLI
with ``--store`` or ``--no-store``; the preview's ``next_power_on`` (``--json``, contracts §2)
is read; then the arbitrator is killed (SIGKILL) and a new one started on the same memory. Once
every device has bound again and start-up has run, the links read over the new host link must
be the links right after the change + ``next_power_on.links_added`` −
``next_power_on.links_removed``.
"""

from __future__ import annotations

import os
from typing import Any

import pytest

from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link
from pdcp_studio.storage import config_codec
from tests.cli.truth_rig import TruthRig, after_power_on, cli, cli_json, links_of

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not hasattr(os, "openpty"),
                                 reason="needs POSIX pseudo-terminals")]

#: The control unit's wrist rotation velocity → the hand's wrist rotator: a terminal channel,
#: so only automatic set-up (autoconfigure) makes it when no configuration asks for it. (An
#: EMG link cannot be removed so: start-up makes it again for the grips that require it.)
WRIST_LINK = Link(ChannelRef(2641, 513, 201, 5), ChannelRef(2641, 769, 301, 3))


@pytest.fixture
def rig(tmp_path, multicast_url):
    url = multicast_url("239.74.163.26", 44000)
    with TruthRig.running(url, tmp_path / "memory.bin", "transradial", count=4) as running:
        yield running


def change(*args: str) -> dict[str, Any]:
    """A CLI change with --yes --json that must be written; its document."""
    code, doc = cli_json(*args, "--yes")
    assert code == 0, doc
    assert doc["written"], (doc["transaction"], doc.get("actions"), doc["effect"]["text"])
    assert "next_power_on" in doc and "effect" in doc
    return doc


def store_links_and_policy(rig: TruthRig, *, autoconfigure: bool) -> set[Link]:
    """The live links stored as the configuration, the policy set; the links."""
    code, out, err = cli("policy", "--bus", rig.url, "--autoconfigure",
                         "on" if autoconfigure else "off", "--yes")
    assert code == 0, out + err
    code, out, err = cli("config", "save", "--bus", rig.url, "--yes")
    assert code == 0, out + err
    links = rig.links()
    assert WRIST_LINK in links and len(links) == 5
    return links


def remove_wrist_link(rig: TruthRig, tmp_path, store: bool) -> dict[str, Any]:
    """``apply startup --config`` with the stored configuration less the wrist link: one
    link removed through the CLI (autoconfigure is off, so the plan makes nothing)."""
    saved = tmp_path / "stored.pdcfg"
    assert cli("config", "read", "--bus", rig.url, "-o", str(saved))[0] == 0
    collection = config_codec.load_path(saved)
    cfg = collection.configurations[0]
    cfg.links[:] = [sl for sl in cfg.links if Link(sl.output.ref, sl.input.ref) != WRIST_LINK]
    less = tmp_path / "less.pdcfg"
    config_codec.save_path(collection, less)
    doc = change("apply", "startup", "--bus", rig.url, "--config", str(less),
                 "--store" if store else "--no-store")
    assert links_of(doc["effect"]["links_removed"]) == {WRIST_LINK}
    assert doc["effect"]["links_added"] == []
    return doc


def check_power_cycle(rig: TruthRig, doc: dict[str, Any]) -> set[Link]:
    """Kill and restart the arbitrator; the links must be as ``doc``'s next_power_on said."""
    now = rig.links()
    effect = doc["effect"]
    assert now == (links_of(effect["links_before"]) - links_of(effect["links_removed"])) \
        | links_of(effect["links_added"])
    predicted = after_power_on(now, doc["next_power_on"])
    rig.power_cycle()
    powered = rig.links()
    assert powered == predicted, (
        f"predicted {sorted(map(str, predicted))}\nafter the power cycle "
        f"{sorted(map(str, powered))}\nnext_power_on: {doc['next_power_on']['text']}\n"
        + (rig.arbitrator.text() if rig.arbitrator else ""))
    return powered


def test_a_link_removed_and_not_stored_comes_back(rig, tmp_path):
    links = store_links_and_policy(rig, autoconfigure=False)
    doc = remove_wrist_link(rig, tmp_path, store=False)
    po = doc["next_power_on"]
    assert links_of(po["links_added"]) == {WRIST_LINK} and po["links_removed"] == []
    assert po["reverts"] and any("comes back" in t for t in po["text"])
    assert check_power_cycle(rig, doc) == links


def test_a_link_removed_and_stored_stays_removed_with_autoconfigure_off(rig, tmp_path):
    links = store_links_and_policy(rig, autoconfigure=False)
    doc = remove_wrist_link(rig, tmp_path, store=True)
    assert doc["effect"]["stored_configuration"]["changed"]
    po = doc["next_power_on"]
    assert po["links_added"] == [] and po["links_removed"] == []
    assert check_power_cycle(rig, doc) == links - {WRIST_LINK}


def test_clear_stored_with_autoconfigure_on_powers_on_as_predicted(rig):
    store_links_and_policy(rig, autoconfigure=True)
    doc = change("apply", "clear", "--bus", rig.url, "--store")
    assert len(links_of(doc["effect"]["links_removed"])) == 5
    powered = check_power_cycle(rig, doc)
    # Start-up's automatic set-up links the hand's terminal channels again from nothing.
    assert powered and doc["next_power_on"]["autoconfigure"] is True


def test_clear_not_stored_comes_back_from_the_stored_configuration(rig):
    links = store_links_and_policy(rig, autoconfigure=False)
    doc = change("apply", "clear", "--bus", rig.url, "--no-store")
    assert links_of(doc["next_power_on"]["links_added"]) == links
    assert check_power_cycle(rig, doc) == links


@pytest.mark.parametrize("store", [True, False])
def test_a_control_mode_set_stored_or_not_powers_on_as_predicted(rig, store):
    store_links_and_policy(rig, autoconfigure=True)
    doc = change("param", "set", "--bus", rig.url, "2641/769/301#1", "type=0x9700",
                 "--store" if store else "--no-store")
    [p] = doc["effect"]["parameters"]
    assert (p["name"], p["before"], p["after"]) == ("type", "0x9300", "0x9700")
    check_power_cycle(rig, doc)
    # The control mode is the part's own (non-volatile): it survives the power cycle.
    code, got = cli_json("param", "get", "--bus", rig.url, "2641/769/301#1")
    assert code == 0 and got["parameters"]["type"] == "0x9700"


@pytest.mark.parametrize("store", [True, False])
def test_a_second_sole_access_input_on_one_output_goes_at_power_on_as_predicted(
        tmp_path, multicast_url, store):
    """thesis-test1: the arbitrator makes a link start-up would not make from nothing (the
    LED terminal's sole-access Y input on the joystick that already feeds its X input); the
    prediction must say it goes, stored or not (engine/effect.py predict_power_on)."""
    from pdcp_studio.bus.session.change_road import preview_change
    from pdcp_studio.bus.transaction import Change, LinkAction

    extra = Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2))
    url = multicast_url("239.74.163.27", 45000)
    with TruthRig.running(url, tmp_path / "memory.bin", "thesis-test1", count=2) as rig:
        before = rig.links()
        assert extra not in before
        with rig.session() as session:
            edit = Change("add a link", links=[LinkAction("add", extra, "test")], store=store)
            preview = preview_change(session, edit)
            assert preview.effect is not None
            doc = {"effect": preview.effect.to_json(),
                   "next_power_on": preview.effect.power_on_json()}
            assert session.transact(preview.change).written
        assert links_of(doc["next_power_on"]["links_removed"]) == {extra}
        assert check_power_cycle(rig, doc) == before


def test_a_history_restore_not_stored_is_undone_at_power_on(rig):
    """Links put back by ``history restore --no-store`` over a stored empty configuration,
    autoconfigure off: start-up makes none of them again, as predicted."""
    links = store_links_and_policy(rig, autoconfigure=False)
    code, doc = cli_json("history", "list")
    assert code == 0
    [saved] = [e for e in doc["entries"] if e["action"] == "config save"]
    change("apply", "clear", "--bus", rig.url, "--store")
    assert rig.links() == set()
    doc = change("history", "restore", str(saved["id"]), "--bus", rig.url, "--no-store")
    assert links_of(doc["effect"]["links_added"]) == links
    assert not doc["effect"]["stored_configuration"]["changed"]
    assert links_of(doc["next_power_on"]["links_removed"]) == links
    assert check_power_cycle(rig, doc) == set()
