"""The prosthesis registry, the large rig and the scripts as data (no bus needed)."""

from __future__ import annotations

import pytest

from pdcp_studio.bus.arbitrator.node_ids import NodeIdPool
from pdcp_studio.bus.sim import rigs as sim
from pdcp_studio.engine import plan_autoconfigure
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link
from pdcp_studio.storage import system_file


def L(o: tuple[int, int], i: tuple[int, int]) -> Link:
    return Link(ChannelRef(2, 2, o[0], o[1]), ChannelRef(2, 2, i[0], i[1]))


def test_registry_names_every_shipped_system_and_large(systems_dir):
    names = sim.list_prostheses()
    assert names[:7] == ["thesis-test1", "thesis-test2", "thesis-test3", "thesis-test4",
                         "thesis-test5", "transradial", "large"]
    assert {p.stem for p in systems_dir.glob("*.json")} <= set(names)
    assert len(names) == len(set(names))


def test_unknown_name_says_which_exist():
    with pytest.raises(sim.UnknownProsthesisError, match="thesis-test1"):
        sim.load_prosthesis("no-such-arm")


def test_load_by_path_and_by_name_agree(systems_dir):
    by_name = sim.load_prosthesis("thesis-test2")
    by_path = sim.load_prosthesis(systems_dir / "thesis-test2.json")
    assert system_file.to_json(by_name) == system_file.to_json(by_path)
    assert by_name is not sim.load_prosthesis("thesis-test2")  # a fresh copy each time


def test_large_rig_has_32_devices_within_the_node_id_pool():
    system = sim.load_prosthesis("large")
    assert len(system.devices) == 32
    system.validate()
    ids = len(system.devices) + sum(len(d.outputs()) for d in system.devices.values())
    assert ids <= NodeIdPool().capacity
    # Every arm gets fully configured: each hand's three terminal inputs are linked.
    plan = plan_autoconfigure(system)
    assert len(plan.final_links) == 8 * 5
    assert not plan.rejections


def test_large_rig_round_trips_through_a_system_file():
    system = sim.large_system()
    again = system_file.loads(system_file.dumps(system))
    assert system_file.to_json(again) == system_file.to_json(system)


@pytest.mark.parametrize("name, links", [
    ("thesis-test1", [L((4, 1), (6, 1))]),
    ("thesis-test2", [L((4, 1), (5, 2)), L((5, 3), (6, 1)), L((5, 5), (6, 2))]),
    ("thesis-test3", [L((4, 1), (5, 2)), L((5, 3), (6, 1)), L((5, 5), (6, 2))]),
    ("thesis-test4", [L((5, 2), (6, 2))]),
    ("thesis-test5", [L((4, 1), (5, 2)), L((5, 3), (6, 1)), L((5, 5), (6, 2))]),
])
def test_thesis_scripts_end_in_the_reference_links(name, links):
    entry = sim.prosthesis(name)
    script = entry.script()
    assert script.name == "thesis"
    assert sim.expected_links(script, entry.load()) == sorted(links)


def test_thesis_scripts_do_what_the_thesis_did():
    ops = {n: [s.op for s in sim.prosthesis(n).script().steps]
           for n in ("thesis-test1", "thesis-test3", "thesis-test4", "thesis-test5")}
    assert ops["thesis-test1"] == ["settle", "save", "unplug", "plug", "reset", "settle"]
    assert ops["thesis-test3"] == ["settle", "save", "reset", "settle"]
    resets = {n: [s.keep_memory for s in sim.prosthesis(n).script().steps if s.op == "reset"]
              for n in ops}
    assert resets["thesis-test3"] == [True] and resets["thesis-test5"] == [False]
    # The replacement device starts unplugged, the replaced one plugged.
    t1 = sim.load_prosthesis("thesis-test1")
    assert t1.devices[sim.D2].present and not t1.devices[sim.D3].present
    t4 = sim.load_prosthesis("thesis-test4")
    assert t4.devices[sim.D1].present and not t4.devices[sim.D2].present


def test_generic_scripts_expect_what_start_up_gives():
    entry = sim.prosthesis("appendix-d")
    system = entry.load()
    # appendix-d's devices store their sources: start-up retrieves exactly those links.
    assert sim.expected_links(entry.script(), system) == system.links
    assert [s.name for s in entry.scripts] == ["start-up", "unplug-replug",
                                               "reset-keep-memory", "reset-erase-memory"]


def test_unknown_script_is_named():
    with pytest.raises(sim.ScriptError, match="hot-swap"):
        sim.prosthesis("thesis-test1").script("nope")


def test_script_result_reports_the_difference():
    script = sim.prosthesis("thesis-test4").script()
    result = sim.ScriptResult(script, final_links=[L((4, 1), (6, 2))],
                              expected_links=[L((5, 2), (6, 2))])
    assert not result.ok
    assert "missing 2/2/5#2" in result.mismatch() and "unexpected 2/2/4#1" in result.mismatch()
