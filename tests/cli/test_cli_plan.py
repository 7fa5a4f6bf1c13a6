"""``pdcp-studio plan MODE --system FILE [--config CFG] [--json]`` (contracts §2)."""

from __future__ import annotations

import json
import random
import subprocess
import sys
from pathlib import Path

import pytest

from pdcp_studio.cli import plan as plan_cmd
from pdcp_studio.cli.main import main
from pdcp_studio.engine import EXTRA_MODES, MODES, configuration_from_system
from pdcp_studio.model import ConfigCollection
from pdcp_studio.storage import config_codec, system_file

ROOT = Path(__file__).resolve().parents[2]
SYSTEMS = ROOT / "resources" / "systems"


def _ref(serial: int, index: int) -> dict:
    return {"vid": 2, "pid": 2, "serial": serial, "index": index}


APPENDIX_D_LINKS = [{"output": _ref(4, 1), "input": _ref(5, 2)},
                    {"output": _ref(5, 3), "input": _ref(6, 1)},
                    {"output": _ref(5, 5), "input": _ref(6, 2)}]


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def stored(tmp_path) -> Path:
    """The appendix D links as an arbitrator's stored configuration (.pdcfg)."""
    path = tmp_path / "arbitrator.pdcfg"
    cfg = configuration_from_system(system_file.load_path(SYSTEMS / "appendix-d.json"))
    config_codec.save_path(ConfigCollection([cfg]), path)
    return path


def test_json_is_the_contract_document(capsys):
    code, out, err = run(capsys, "plan", "autoconfigure", "--system",
                         str(SYSTEMS / "thesis-test2.json"), "--json")
    assert (code, err) == (0, "")
    doc = json.loads(out)  # one JSON document and nothing else on stdout
    assert doc["mode"] == "autoconfigure"
    assert [{k: a[k] for k in ("op", "output", "input", "similarity", "reason")}
            for a in doc["actions"]] == [
        {"op": "add", "output": _ref(5, 3), "input": _ref(6, 1), "similarity": 23,
         "reason": "terminal channel 0x1110: most similar free output"},
        {"op": "add", "output": _ref(4, 1), "input": _ref(5, 2), "similarity": 23,
         "reason": "required by 2/2/5#3 (0x1100): most similar free output"},
        {"op": "add", "output": _ref(5, 5), "input": _ref(6, 2), "similarity": 31,
         "reason": "terminal channel 0x1220: most similar free output"},
    ]
    assert doc["links"] == APPENDIX_D_LINKS


def test_text_is_the_default(capsys):
    code, out, _ = run(capsys, "plan", "autoconfigure", "--system",
                       str(SYSTEMS / "thesis-test2.json"), "--profiles",
                       str(ROOT / "resources" / "profiles" / "thesis-tests.json"))
    assert code == 0
    assert out.startswith("Plan: autoconfigure — add 3, remove 0")
    assert "similarity 23 = profile 2 levels (16)" in out


def test_startup_recalls_a_stored_pdcfg(capsys, stored):
    code, out, _ = run(capsys, "plan", "startup", "--system", str(SYSTEMS / "thesis-test3.json"),
                       "--config", str(stored), "--json")
    doc = json.loads(out)
    assert code == 0
    assert doc["links"] == APPENDIX_D_LINKS
    assert doc["configuration"]["source"] == "stored"
    assert {a["rule"] for a in doc["actions"]} <= {"stored", "required"}


def test_config_may_be_decode_json_or_a_system_file(capsys, stored, tmp_path):
    as_json = tmp_path / "cfg.json"
    as_json.write_text(json.dumps(config_codec.to_json(config_codec.load_path(stored))))
    for cfg in (as_json, SYSTEMS / "appendix-d.json"):
        code, out, _ = run(capsys, "plan", "implement", "--system",
                           str(SYSTEMS / "thesis-test3.json"), "--config", str(cfg), "--json")
        assert code == 0
        assert json.loads(out)["links"] == APPENDIX_D_LINKS


def test_replacements_with_a_config_naming_devices_the_system_lacks(capsys, tmp_path):
    # Thesis test 4: stored SN4.O1 → SN6.I2; SN4 is gone, SN5 is there instead.
    s = system_file.load_path(SYSTEMS / "thesis-test4.json")
    s.devices[(2, 2, 5)].present = True
    s.remove_device((2, 2, 4))
    sys_path = tmp_path / "after.json"
    system_file.save_path(s, sys_path)
    cfg = {"configurations": [{"index": 1, "links": [{"index": 1,
           "input": {"type": "0x5300", "profile": "0x2110", **_ref(6, 2)},
           "output": {"type": "0x5000", "profile": "0x2110", **_ref(4, 1)}}]}]}
    cfg_path = tmp_path / "cfg.json"
    cfg_path.write_text(json.dumps(cfg))
    code, out, _ = run(capsys, "plan", "replacements", "--system", str(sys_path), "--config",
                       str(cfg_path), "--json")
    assert code == 0
    assert json.loads(out)["links"] == [{"output": _ref(5, 2), "input": _ref(6, 2)}]


def test_bad_config_exits_2_naming_file_and_offset(capsys, tmp_path):
    bad = tmp_path / "bad.pdcfg"
    bad.write_bytes(bytes([1, 1, 0, 2, 1]))
    code, out, err = run(capsys, "plan", "startup", "--system",
                         str(SYSTEMS / "appendix-d.json"), "--config", str(bad))
    assert (code, out) == (2, "")
    assert "bad.pdcfg" in err and "offset" in err


@pytest.mark.parametrize("argv", [
    ["plan", "implement", "--system", str(SYSTEMS / "appendix-d.json"), "--config", "/nope"],
    ["plan", "autoconfigure", "--system", "/nonexistent/system.json"],
    ["plan", "startup", "--system", str(SYSTEMS / "appendix-d.json"), "--config", "/nope.pdcfg"],
])
def test_bad_input_exits_2(capsys, argv):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert err.startswith("pdcp-studio: ")


def test_same_output_whatever_order_the_file_lists_devices_and_channels_in(capsys, tmp_path):
    doc = json.loads((SYSTEMS / "transradial.json").read_text())
    rng = random.Random(4)
    rng.shuffle(doc["devices"])
    for d in doc["devices"]:
        rng.shuffle(d["channels"])
    shuffled = tmp_path / "shuffled.json"
    shuffled.write_text(json.dumps(doc))
    outs = [run(capsys, "plan", "startup", "--system", str(p), "--json")[1]
            for p in (SYSTEMS / "transradial.json", shuffled)]
    assert outs[0] == outs[1]
    assert len(json.loads(outs[0])["links"]) == 5


def test_mode_names_match_the_engine():
    assert plan_cmd.MODE_NAMES == MODES + EXTRA_MODES


def test_plan_runs_without_qt_networkx_or_python_can():
    code = ("import sys, io, contextlib; from pdcp_studio.cli.main import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            f"    assert main(['plan', 'startup', '--system', {str(SYSTEMS / 'appendix-d.json')!r},"
            " '--json']) == 0\n"
            "bad = [m for m in ('PySide6', 'networkx', 'can', 'serial') if m in sys.modules]\n"
            "assert not bad, bad\n")
    subprocess.run([sys.executable, "-c", code], check=True)
