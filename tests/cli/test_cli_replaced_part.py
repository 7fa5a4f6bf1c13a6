"""``apply replacements --yes`` over the host link leaves the replaced hand no longer missing
(issue 26 item 6): ``info`` counts 0 missing, the fitting history says what replaced it."""

from __future__ import annotations

import json
import os
import time

import pytest

from pdcp_studio.bus.sim.rigs import HAND, SPARE_HAND
from pdcp_studio.cli.main import main
from pdcp_studio.storage.history import History
from tests.road_rigs import served

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")


def test_apply_replacements_over_the_host_link_leaves_nothing_missing(tmp_path, capsys):
    with served("transradial", tmp_path / "memory.bin", profile_layer=False) as (
            arbitrator, host, url):
        bus = ["--bus", url]
        assert main(["apply", "autoconfigure", "--yes", *bus]) == 0
        assert main(["config", "save", "--yes", *bus]) == 0
        host.unplug(HAND)
        assert arbitrator.wait_for(lambda: not arbitrator.system().devices[HAND].present, 10)
        host.plug(SPARE_HAND)
        assert arbitrator.wait_for(lambda: SPARE_HAND in arbitrator.devices_present(), 10)
        assert arbitrator.wait_settled(10)
        assert not arbitrator.system().devices[HAND].present  # kept, absent: missing
        capsys.readouterr()
        assert main(["apply", "replacements", "--yes", "--json", *bus]) == 0
        doc = json.loads(capsys.readouterr().out)
        tx = doc["transaction"]
        assert tx["status"] == "applied" and tx["verified"] is True
        assert "replaced 2641/769/301 by 2641/769/302" in tx["notes"]
        assert HAND not in arbitrator.system().devices  # forgotten: replaced
        time.sleep(0.5)  # the DeviceLeft for good crosses the line as an event
        assert main(["info", *bus]) == 0
        out = capsys.readouterr().out
        assert "(0 missing)" in out and "2641/769/301" not in out
        with History.open() as h:
            entry = h.entries()[-1]
        assert entry["action"] == "apply replacements"
        assert entry["replaced"] == [{"old": {"vid": 2641, "pid": 769, "serial": 301},
                                      "new": {"vid": 2641, "pid": 769, "serial": 302}}]
        assert main(["history", "show", str(entry["id"]), "--json"]) == 0
        assert json.loads(capsys.readouterr().out)["replaced"] == entry["replaced"]
