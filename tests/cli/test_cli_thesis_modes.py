"""The thesis's host program ``pdcp_run`` and its seven modes (issue 17), each through the CLI on
a simulated thesis rig (test 2's devices) — over ``sim:`` and over the host link.

``autoconfig`` → ``apply autoconfigure``; ``noautoconfig`` → the policy (``policy
--autoconfigure off``, ``arbitrator --no-autoconfigure``); ``save`` → ``config save``; ``print``
and ``info`` → ``print/info --bus``; ``clear`` → ``apply clear``; ``enforce`` → ``apply enforce``.
"""

from __future__ import annotations

import json
import os
import time

import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.memory import MemoryStore
from pdcp_studio.bus.session.api import open_session
from pdcp_studio.bus.transaction import Change, Policy
from pdcp_studio.cli.main import main
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link
from tests.road_rigs import served

TEST2 = [Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2)),
         Link(ChannelRef(2, 2, 5, 3), ChannelRef(2, 2, 6, 1)),
         Link(ChannelRef(2, 2, 5, 5), ChannelRef(2, 2, 6, 2))]
TEXT = ["link 2/2/4#1 (0x2120) → 2/2/5#2 (0x2110)", "link 2/2/5#3 (0x1100) → 2/2/6#1 (0x1110)",
        "link 2/2/5#5 (0x1220) → 2/2/6#2 (0x1220)"]


def policy_off(memory) -> None:
    """A memory whose policy is off (what ``arbitrator --no-autoconfigure`` leaves)."""
    MemoryStore(memory).write_policy({"autoconfigure": False})


class Rig:
    """A thesis test-2 rig over ``sim:`` (each command a fresh start-up from the memory) or
    over the host link (``restart()`` starts the arbitrator again with the same memory)."""

    def __init__(self, kind: str, memory) -> None:
        self.kind, self.memory = kind, memory
        self._ctx = None
        self.url = "sim:thesis-test2"
        self.arbitrator = None

    def start(self) -> Rig:
        if self.kind == "serial":
            self._ctx = served("thesis-test2", self.memory)
            self.arbitrator, _, self.url = self._ctx.__enter__()
        return self

    def stop(self) -> None:
        if self._ctx is not None:
            self._ctx.__exit__(None, None, None)
            self._ctx = None

    def restart(self) -> None:
        self.stop()
        self.start()

    def args(self, *argv: str) -> list[str]:
        extra = ["--memory", str(self.memory)] if self.kind == "sim" else []
        return [*argv, "--bus", self.url, *extra]

    def links(self, capsys) -> list[str]:
        """The links ``info`` lists, by their numbers (given in brackets after the names)."""
        assert main(self.args("info")) == 0
        return ["link " + ln.strip().rpartition("  [")[2].rstrip("]")
                for ln in capsys.readouterr().out.splitlines()
                if ln.strip().startswith("link ")]


@pytest.fixture(params=["sim", "serial"])
def rig(request, tmp_path):
    if request.param == "serial" and not hasattr(os, "openpty"):
        pytest.skip("needs POSIX pseudo-terminals")
    r = Rig(request.param, tmp_path / "memory.bin")
    yield r
    r.stop()


def test_autoconfig_mode_is_apply_autoconfigure(rig, capsys):
    policy_off(rig.memory)  # so start-up leaves the rig unlinked
    rig.start()
    assert rig.links(capsys) == []
    assert main(rig.args("apply", "autoconfigure", "--yes")) == 0
    assert "apply autoconfigure: applied and verified (3 link(s)" in capsys.readouterr().out
    if rig.kind == "serial":
        assert rig.links(capsys) == TEXT


def test_noautoconfig_mode_links_nothing_without_a_stored_configuration(rig, capsys):
    rig.start()
    assert rig.links(capsys) == TEXT  # autoconfigure on: start-up links the rig
    assert main(rig.args("policy", "--autoconfigure", "off", "--yes")) == 0
    capsys.readouterr()
    rig.restart()
    assert rig.links(capsys) == []
    assert main(rig.args("policy", "--json")) == 0
    assert json.loads(capsys.readouterr().out)["autoconfigure"] is False


def test_noautoconfig_mode_implements_exactly_the_stored_configuration(rig, capsys, tmp_path):
    from pdcp_studio.model.configuration import ConfigCollection, StoredConfiguration
    from pdcp_studio.storage import config_codec

    session = open_session("sim:thesis-test2")  # test 2's first link, as a stored record
    try:
        full = session.configuration_of_links()
    finally:
        session.close()
    path = tmp_path / "one.pdcfg"
    config_codec.save_path(
        ConfigCollection([StoredConfiguration(1, full.configurations[0].links[:1])]), path)
    rig.start()
    assert main(rig.args("config", "write", str(path), "--yes")) == 0
    assert main(rig.args("policy", "--autoconfigure", "off", "--yes")) == 0
    capsys.readouterr()
    rig.restart()
    assert rig.links(capsys) == [TEXT[0]], "exactly the stored link, nothing autoconfigured"


def test_arbitrator_no_autoconfigure_flag_sets_the_stored_policy(tmp_path):
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.bus.session.urls import open_can_bus, unique_virtual_channel

    memory = tmp_path / "m.bin"
    bus = open_can_bus("virtual", unique_virtual_channel("noauto"))
    with Arbitrator(bus, memory=memory, autoconfigure=False) as arb:
        assert arb.read_policy() == Policy(False)
    bus2 = open_can_bus("virtual", unique_virtual_channel("noauto"))
    with Arbitrator(bus2, memory=memory) as arb:  # without the flag the stored policy holds
        assert arb.read_policy() == Policy(False)
    assert MemoryStore(memory).read_policy() == {"autoconfigure": False}


def test_save_mode_is_config_save(rig, capsys):
    rig.start()
    assert main(rig.args("config", "save", "--yes")) == 0
    assert len(MemoryStore(rig.memory).read().configurations[0].links) == 3


def test_print_mode_is_print_bus(rig, capsys):
    rig.start()
    assert main(rig.args("print")) == 0
    out = capsys.readouterr().out
    assert out.startswith("n_devices: 3\nn_missing_devices: 0\nn_input_channels: 4\n"
                          "n_output_channels: 4\nn_channel_links: 3\n")
    assert "channel link 0:\ninput channel: 2/2/5#2\noutput channel: 2/2/4#1\n" \
           "link status: connected" in out


def test_info_mode_is_info_bus(rig, capsys):
    rig.start()
    assert main(rig.args("info")) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0] == "3 devices (0 missing), 8 channels, 3 links"
    assert "Control unit board: 2 in, 3 out  [2/2/5, node 2]" in out  # names first


def test_clear_mode_is_apply_clear(rig, capsys):
    rig.start()
    assert main(rig.args("apply", "clear", "--yes")) == 0
    assert "apply clear: applied and verified (0 link(s)" in capsys.readouterr().out
    if rig.kind == "serial":
        assert rig.links(capsys) == []


def test_enforce_mode_is_apply_enforce(rig, capsys):
    rig.start()
    assert main(rig.args("apply", "enforce", "--yes")) == 0
    out = capsys.readouterr().out
    assert "Plan: enforce" in out and "nothing to change" in out  # test 2 keeps sole access
    assert rig.links(capsys) == TEXT


def _events_during_hot_swap(name: str, memory, out_key: DeviceKey, in_key: DeviceKey):
    session = open_session(f"sim:{name}", memory=memory)
    got: list = []
    try:
        result = session.carry_out(Change("policy autoconfigure off", policy=Policy(False)))
        assert result.written
        session.subscribe(got.append)
        session.unplug(out_key)
        assert session.arbitrator.wait_for(
            lambda: out_key not in session.arbitrator.devices_present(), 5)
        session.plug(in_key)
        assert session.wait_settled(5)
        time.sleep(0.2)
        return session.system().links, got
    finally:
        session.close()


def test_a_hot_swap_with_policy_off_makes_the_replacement_and_nothing_autoconfigured(tmp_path):
    links, got = _events_during_hot_swap("thesis-test4", tmp_path / "m4", DeviceKey(2, 2, 4),
                                         DeviceKey(2, 2, 5))
    assert links == [Link(ChannelRef(2, 2, 5, 2), ChannelRef(2, 2, 6, 2))]
    plans = [e.plan for e in got if isinstance(e, ev.PlanApplied)]
    assert plans and all(a.rule.value != "terminal" for p in plans for a in p.actions)
    assert any(a.rule.value == "replacement" for p in plans for a in p.actions)


def test_a_hot_swap_with_policy_off_says_what_it_left_unconnected(tmp_path):
    memory = tmp_path / "m2"
    policy_off(memory)
    links, got = _events_during_hot_swap("thesis-test2", memory, DeviceKey(2, 2, 4),
                                         DeviceKey(2, 2, 4))
    assert links == []
    said = [e for e in got if isinstance(e, ev.TerminalsUnconnected)]
    assert said and "autoconfigure is off on this prosthesis" in said[-1].why
    assert ChannelRef(2, 2, 6, 1) in said[-1].refs


def test_check_reports_unconnected_terminals_under_policy_off(systems_dir):
    from pdcp_studio.engine import check_system
    from pdcp_studio.storage.system_file import load_path

    system = load_path(systems_dir / "transradial.json")
    system.clear_links()
    findings = [f for f in check_system(system, autoconfigure=False)
                if f.code == "terminal-unconnected"]
    assert findings and all("not connected — autoconfigure is off on this prosthesis"
                            in f.message for f in findings)
