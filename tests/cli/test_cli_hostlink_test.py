"""``pdcp-studio hostlink-test``: the conformance suite against PDCP Studio's own arbitrator
(this is the run CI makes), and a faulty arbitrator that it catches."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from pdcp_studio.bus.hostlink.testing.conformance import case_names
from pdcp_studio.cli.main import main
from pdcp_studio.protocol import hostlink_messages as hm
from tests.bus.hostlink_rig import arbitrator_rig

pytestmark = pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs POSIX pseudo-terminals")

SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"


@pytest.fixture(scope="module")
def rig(tmp_path_factory):
    memory = tmp_path_factory.mktemp("conformance") / "memory.bin"
    with arbitrator_rig(SYSTEMS / "transradial.json", memory) as parts:
        yield parts


def test_pdcp_studios_own_arbitrator_passes_every_case(rig, capsys):
    arbitrator, server = rig
    links, memory = arbitrator.system().links, arbitrator.memory.read_bytes()
    assert main(["hostlink-test", "--bus", f"serial:{server.slave_path}", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["failed"] == [] and doc["passed"] == case_names() and doc["skipped"] == []
    for case in ("hello", "unknown_version", "bad_crc", "lost_ack_no_second_execution",
                 "retransmission", "oversize_frame", "timeouts_bounded", "config_bad_crc",
                 "unknown_request", "transact_empty", "events", "version_1_ping",
                 "reset_drops_frame_in_flight", "sequence_wrap", "paging",
                 "nak_for_given_up_frame"):
        assert case in doc["passed"]
    # the suite changed nothing on the prosthesis
    assert arbitrator.system().links == links
    assert arbitrator.memory.read_bytes() == memory


def test_a_faulty_arbitrator_fails_the_cases_it_breaks(rig, capsys, monkeypatch):
    from pdcp_studio.bus.hostlink.testing import conformance as hostlink_conformance

    _, server = rig
    monkeypatch.setattr(hostlink_conformance, "case_names",
                        lambda: ["hello", "status", "list_links", "bad_crc"])  # quicker
    table = server.handlers._table
    monkeypatch.setitem(table, hm.Req.LIST_LINKS, lambda body: b"\x01\x00\x00\x00abc")
    code = main(["hostlink-test", "--bus", f"serial:{server.slave_path}"])
    out = capsys.readouterr().out
    assert code == 1
    assert "FAIL  list_links: LIST_LINKS: 3 bytes are not whole links" in out
    assert "pass  hello" in out
    assert out.rstrip().endswith("1 failed, 0 skipped")


def test_undeclared_capabilities_are_skipped_not_failed(rig, capsys, monkeypatch):
    from pdcp_studio.bus.hostlink import handlers
    from pdcp_studio.bus.hostlink.testing import conformance as hostlink_conformance

    monkeypatch.setattr(handlers, "CAPABILITIES", 0)  # the lean profile declares none
    monkeypatch.setattr(hostlink_conformance, "case_names",
                        lambda: ["hello", "monitor", "events", "transact_empty", "get_policy",
                                 "get_param_bulk", "status"])
    assert main(["hostlink-test", "--bus", f"serial:{_rig_path(rig)}", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["passed"] == ["hello", "status"]
    assert doc["failed"] == []
    assert doc["skipped"] == ["monitor", "events", "transact_empty", "get_policy",
                              "get_param_bulk"]
    assert "does not declare monitor" in doc["why"]["monitor"]


def _rig_path(rig) -> str:
    return rig[1].slave_path


def test_only_serial_buses(capsys):
    assert main(["hostlink-test", "--bus", "sim:transradial"]) == 2
    assert "serial:PORT" in capsys.readouterr().err


def test_a_missing_port_is_a_failure_naming_it(capsys):
    assert main(["hostlink-test", "--bus", "serial:/dev/pdcp-no-such-port"]) == 1
    assert "/dev/pdcp-no-such-port" in capsys.readouterr().err
