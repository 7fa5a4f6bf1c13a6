"""``pdcp-studio sim list|replay|devices`` (contracts §2)."""

from __future__ import annotations

import json
import subprocess
import sys
import time

from pdcp_studio.bus.arbitrator.core import Arbitrator
from pdcp_studio.bus.session.urls import open_can_bus, unique_virtual_channel
from pdcp_studio.cli.main import main
from pdcp_studio.model.refs import DeviceKey


def test_list_names_one_a_line(capsys):
    assert main(["sim", "list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[:7] == ["thesis-test1", "thesis-test2", "thesis-test3", "thesis-test4",
                         "thesis-test5", "transradial", "large"]
    assert all(line and " " not in line for line in lines)


def test_replay_json_is_a_system_file_with_node_ids(capsys):
    assert main(["sim", "replay", "thesis-test4", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)  # one JSON document, nothing else
    assert doc["format"] == "pdcp-system/1"
    assert doc["links"] == [{"output": {"vid": 2, "pid": 2, "serial": 5, "index": 2},
                             "input": {"vid": 2, "pid": 2, "serial": 6, "index": 2}}]
    present = [d for d in doc["devices"] if d["present"]]
    assert {d["serial"] for d in present} == {5, 6}
    assert all(isinstance(d["node_id"], int) for d in present)
    outputs = [c for d in present for c in d["channels"] if c["direction"] == "output"]
    assert outputs and all(isinstance(c["node_id"], int) for c in outputs)
    # The replaced joystick is gone (after the restart the arbitrator never saw it again).
    assert all(d["serial"] != 4 or not d["present"] for d in doc["devices"])


def test_replay_text_shows_the_steps_and_final_links(capsys):
    assert main(["sim", "replay", "thesis-test1", "--script", "hot-swap"]) == 0
    out = capsys.readouterr().out
    assert "unplug 2/2/5" in out and "plug 2/2/6" in out
    last = out.rstrip().splitlines()[-1]  # the final link: names first, numbers beside
    assert last.startswith("link Joystick, ") and last.endswith("  [2/2/4#1 → 2/2/6#1]"), last


def test_replay_refuses_unknown_names_and_scripts(capsys):
    assert main(["sim", "replay", "no-such-arm"]) == 2
    assert "thesis-test1" in capsys.readouterr().err
    assert main(["sim", "replay", "thesis-test2", "--script", "nope"]) == 2
    assert "no script 'nope'" in capsys.readouterr().err


def test_replay_fails_when_the_links_are_not_the_expected_ones(capsys, monkeypatch):
    from pdcp_studio.bus.sim import rigs as simulator

    monkeypatch.setattr(simulator, "TEST2_LINKS", ())
    entry = simulator.prosthesis("thesis-test2")
    broken = simulator.Script("thesis", "expects nothing", (simulator.SETTLE,), ())
    monkeypatch.setattr(type(entry), "script", lambda self, name=None: broken)
    assert main(["sim", "replay", "thesis-test2"]) == 1
    assert "did not end in the expected links: unexpected 2/2/4#1" in capsys.readouterr().err


def test_devices_needs_a_can_bus(capsys):
    assert main(["sim", "devices", "thesis-test2", "--bus", "sim:thesis-test2"]) == 2
    assert "can:" in capsys.readouterr().err
    assert main(["sim", "devices", "nope", "--bus", "can:virtual:x", "--seconds", "1"]) == 2


def test_devices_run_for_an_arbitrator_elsewhere_on_the_bus():
    import threading

    channel = unique_virtual_channel("pdcp-test-cli-sim")
    arbitrator = Arbitrator(open_can_bus("virtual", channel), startup_quiet_s=0.2)
    try:
        result: list[int] = []
        runner = threading.Thread(target=lambda: result.append(main(
            ["sim", "devices", "thesis-test2", "--bus", f"can:virtual:{channel}",
             "--seconds", "1.5"])))
        runner.start()
        assert arbitrator.wait_for(lambda: len(arbitrator.devices_present()) == 3, 5)
        assert arbitrator.wait_settled(5)
        assert len(arbitrator.system().links) == 3
        runner.join(5)
        assert result == [0]
        # Every device stops at once: nothing from anyone on the bus, so they are gone after
        # the quiet-bus silence (issue 28 item 6), not three beacon intervals.
        assert arbitrator.wait_for(lambda: not arbitrator.devices_present(), 15)
        assert DeviceKey(2, 2, 5) in arbitrator.system().devices
    finally:
        arbitrator.close()


def test_cli_module_does_not_import_qt_or_python_can():
    code = ("import sys; import pdcp_studio.cli.sim, pdcp_studio.cli.live.scan, "
            "pdcp_studio.cli.live.config_bus; "
            "print('PySide6' in sys.modules, 'can' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.split() == ["False", "False"]


def test_sim_list_starts_fast():
    started = time.monotonic()
    subprocess.run([sys.executable, "-m", "pdcp_studio", "sim", "list"], check=True,
                   capture_output=True)
    assert time.monotonic() - started < 5


def test_replay_lists_the_replaced_device_as_missing(capsys):
    """Thesis test 1: D2 is replaced by D3; after the reset the stored configuration still
    names D2, so the final system shows it, not present, beside D1.O1 → D3.I1."""
    assert main(["sim", "replay", "thesis-test1", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    by_serial = {d["serial"]: d for d in doc["devices"]}
    assert by_serial[5]["present"] is False and "node_id" not in by_serial[5]
    assert by_serial[4]["present"] is not False and by_serial[6]["present"] is not False
