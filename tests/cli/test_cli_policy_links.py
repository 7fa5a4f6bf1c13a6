"""``policy --autoconfigure on`` makes the links the duty cycle would make, in the same
transaction (issue 26 item 5): previewed, interlocked, written, verified, recorded — and
still there seconds later; turning it off removes nothing and says which links stay.

On ``sim:`` every command opens a fresh prosthesis (only ``--memory`` lasts); with the policy
off a fresh ``thesis-test2`` starts with its terminal channels unconnected. Over the host
link the arbitrator keeps running (in this process behind a pseudo-terminal, and as the
fitting room's three processes).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link
from pdcp_studio.storage.history import History
from tests.road_rigs import served

TEST2 = {Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2)),
         Link(ChannelRef(2, 2, 5, 3), ChannelRef(2, 2, 6, 1)),
         Link(ChannelRef(2, 2, 5, 5), ChannelRef(2, 2, 6, 2))}


def _links(doc_links):
    from pdcp_studio.bus.transaction import link_from_json

    return {link_from_json(d) for d in doc_links}


def _live_links(argv_bus, capsys):
    assert main(["info", *argv_bus]) == 0
    out = capsys.readouterr().out
    return [ln.strip() for ln in out.splitlines() if ln.strip().startswith("link ")]


def _turn_on_and_check(argv_bus, capsys):
    """Preview, then ``--yes``: the three links are made in the policy's transaction."""
    assert main(["policy", "--autoconfigure", "on", *argv_bus]) == 0
    out = capsys.readouterr().out
    assert out.count("  Link made: ") == 3, out  # the effect's words (engine/effect.py)
    assert out.count("    + link ") == 3, out  # and its technical detail
    assert "off → on" in out and "held still" in out
    assert main(["policy", "--autoconfigure", "on", "--yes", "--json", *argv_bus]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["autoconfigure"] is True and doc["written"] is True
    tx = doc["transaction"]
    assert tx["status"] == "applied" and tx["verified"] is True
    assert tx["interlock"].startswith("held")
    assert _links(tx["links_after"]) == TEST2
    assert {(a["output"]["serial"], a["input"]["serial"]) for a in doc["links_added"]} == {
        (4, 5), (5, 6)}
    with History.open() as h:
        entry = h.entries()[-1]
    assert entry["action"] == "policy autoconfigure on"
    assert entry["policy_before"] == {"autoconfigure": False}
    assert entry["policy_after"] == {"autoconfigure": True}
    assert entry["verified"] is True and entry["outcome"]["status"] == "applied"
    assert _links(entry["links_before"]) == set()
    assert _links(entry["links_after"]) == TEST2
    assert [a["op"] for a in entry["plan"]["actions"]] == ["add"] * 3


def test_on_sim_turning_autoconfigure_on_makes_the_links(tmp_path, capsys):
    argv_bus = ["--bus", "sim:thesis-test2", "--memory", str(tmp_path / "memory.bin")]
    assert main(["policy", "--autoconfigure", "off", "--yes", *argv_bus]) == 0
    out = capsys.readouterr().out
    assert "Every link stays as it is (3 links)" in out  # turning it off removes nothing
    assert "2/2/5#3 → 2/2/6#1" in out
    assert main(["apply", "clear", "--yes", *argv_bus]) == 0  # (a fresh one has none)
    capsys.readouterr()
    assert _live_links(argv_bus, capsys) == []  # policy off: nothing links them
    _turn_on_and_check(argv_bus, capsys)


def test_on_sim_the_links_are_still_there_seconds_later(tmp_path):
    """One session over the transaction and after it: the duty cycle leaves them be."""
    from pdcp_studio.bus.arbitrator.memory import MemoryStore
    from pdcp_studio.bus.session.api import open_session
    from pdcp_studio.bus.transaction import Change, Policy
    from pdcp_studio.engine.policy_change import policy_switch

    memory = tmp_path / "memory.bin"
    MemoryStore(memory).write_policy({"autoconfigure": False})
    session = open_session("sim:thesis-test2", memory=str(memory))
    try:
        assert session.system().links == []
        switch = policy_switch(session.system(), session.read_policy().autoconfigure, True)
        change = Change.from_plan(switch.plan, switch.action)
        change.policy = Policy(autoconfigure=True)
        result = session.transact(change)
        assert result.written and result.verified, result.summary()
        time.sleep(3)
        assert set(session.system().links) == TEST2
        assert session.read_policy().autoconfigure is True
    finally:
        session.close()


def test_over_the_host_link_turning_autoconfigure_on_makes_the_links(tmp_path, capsys):
    if not hasattr(os, "openpty"):
        pytest.skip("needs POSIX pseudo-terminals")
    with served("thesis-test2", tmp_path / "memory.bin", autoconfigure=False) as (
            arbitrator, _host, url):
        argv_bus = ["--bus", url]
        assert arbitrator.system().links == []
        assert main(["apply", "clear", "--yes", *argv_bus]) == 0
        capsys.readouterr()
        _turn_on_and_check(argv_bus, capsys)
        time.sleep(3)
        assert set(arbitrator.system().links) == TEST2
        assert len(_live_links(argv_bus, capsys)) == 3
        # And off again: nothing is removed, the words say which links stay.
        assert main(["policy", "--autoconfigure", "off", "--yes", *argv_bus]) == 0
        assert "Every link stays as it is (3 links)" in capsys.readouterr().out
        assert set(arbitrator.system().links) == TEST2


@pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")
def test_in_the_fitting_room_three_processes(tmp_path, multicast_url, capsys):
    """Devices, a headless arbitrator started ``--no-autoconfigure`` and this CLI."""
    url = multicast_url("239.74.163.6", 44000)
    cmd = [sys.executable, "-m", "pdcp_studio"]
    devices = subprocess.Popen([*cmd, "sim", "devices", "thesis-test2", "--bus", url,
                                "--seconds", "60"], stderr=subprocess.PIPE, text=True)
    arbitrator = subprocess.Popen([*cmd, "arbitrator", "--bus", url, "--host-serial", "pty",
                                   "--memory", str(tmp_path / "memory.bin"),
                                   "--no-autoconfigure", "--seconds", "60"],
                                  stdout=subprocess.PIPE, text=True)
    try:
        assert "simulating 3 device(s)" in devices.stderr.readline()
        line = arbitrator.stdout.readline()
        assert line.startswith("host link on /dev/"), line
        argv_bus = ["--bus", "serial:" + line.split(" on ", 1)[1].strip()]
        assert main(["scan", *argv_bus, "--json", "--settle", "5"]) == 0
        assert len(json.loads(capsys.readouterr().out)["devices"]) == 3
        assert main(["apply", "clear", "--yes", *argv_bus]) == 0
        capsys.readouterr()
        assert _live_links(argv_bus, capsys) == []
        _turn_on_and_check(argv_bus, capsys)
        time.sleep(3)
        assert len(_live_links(argv_bus, capsys)) == 3
    finally:
        for proc in (arbitrator, devices):
            proc.terminate()
        for proc in (arbitrator, devices):
            proc.wait(10)
        arbitrator.stdout.close()
        devices.stderr.close()
