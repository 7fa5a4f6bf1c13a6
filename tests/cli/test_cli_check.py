"""``pdcp-studio check --system FILE [--json]``: findings and exit status."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from pdcp_studio.cli.main import build_parser, main
from pdcp_studio.model import ChannelRef, Link
from pdcp_studio.storage import system_file

SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"


def _broken(tmp_path) -> Path:
    """Appendix D with a second sole-access input on SN5.O5 (on its own device, and without
    storing the source) and the joystick unplugged."""
    s = system_file.load_path(SYSTEMS / "appendix-d.json")
    s.add_link(Link(ChannelRef(2, 2, 5, 5), ChannelRef(2, 2, 5, 1)))
    s.devices[(2, 2, 4)].present = False
    path = tmp_path / "broken.json"
    system_file.save_path(s, path)
    return path


def test_a_clean_system_exits_0(capsys):
    assert main(["check", "--system", str(SYSTEMS / "appendix-d.json")]) == 0
    assert capsys.readouterr().out.strip().endswith("0 error(s), 0 warning(s), 0 note(s)")


def test_warnings_alone_exit_0(capsys):
    assert main(["check", "--system", str(SYSTEMS / "thesis-test2.json")]) == 0
    out = capsys.readouterr().out
    assert out.count("terminal-unconnected") == 2
    assert "`plan autoconfigure` would link it to 2/2/5#3 (similarity 23)" in out


def test_errors_exit_1_and_are_listed(capsys, tmp_path):
    assert main(["check", "--system", str(_broken(tmp_path))]) == 1
    out = capsys.readouterr().out
    lines = out.splitlines()
    assert "sole-access: output 2/2/5#5 feeds 2 sole-access inputs (2/2/5#1, 2/2/6#2)" in out
    # SN5.I2 lost its source, which both SN5.O3 and SN5.O5 require.
    assert [line.split(":")[0] for line in lines[:-1]] == [
        "error   required-unmet", "error   required-unmet", "error   sole-access",
        "warning missing-end", "warning self-link", "info    source-field-stale"]
    assert lines[-1].endswith("3 error(s), 2 warning(s), 1 note(s)")


def test_json(capsys, tmp_path):
    path = _broken(tmp_path)
    assert main(["check", "--system", str(path), "--json"]) == 1
    out, err = capsys.readouterr()
    doc = json.loads(out)
    assert err == ""
    assert doc["system"] == str(path)
    assert doc["summary"] == {"error": 3, "warning": 2, "info": 1}
    assert [f["code"] for f in doc["findings"]] == [
        "required-unmet", "required-unmet", "sole-access", "missing-end", "self-link",
        "source-field-stale"]
    assert doc["findings"][2]["refs"][0] == {"vid": 2, "pid": 2, "serial": 5, "index": 5}


def test_bad_file_exits_2(capsys, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "pdcp-system/1", "devices": [{"vid": 1}]}')
    assert main(["check", "--system", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "bad.json" in err and "devices[0]" in err


def test_help_documents_the_exit_status(capsys):
    with pytest.raises(SystemExit):
        build_parser().parse_args(["check", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "exit status: 0 when no finding is an error" in out
    assert "1 when at least one error is found, 2 when FILE cannot be read" in out
