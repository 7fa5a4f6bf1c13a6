"""Terminal escapes from names, references and file names never reach the terminal raw
(issue 28): ESC[2J, BEL and U+202E in a device name or descriptor (a system file, a device on
the bus), a patient reference, the operator ($PDCP_STUDIO_OPERATOR) and a file name are shown
as visible escapes by ``info``, ``print``, ``check``, ``scan``, ``param get``, ``history
list/show``, ``config diff`` and the error lines."""

from __future__ import annotations

import json

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.paths import resources_dir

EVIL = "\x1b[2J\x07\u202e"
SHOWN = "\\x1b[2J\\x07\\u202e"
RAW = ("\x1b", "\x07", "\u202e")


def _clean(text: str) -> None:
    for char in RAW:
        assert char not in text, repr(text)


@pytest.fixture
def evil_system(tmp_path):
    doc = json.loads((resources_dir() / "systems" / "transradial.json").read_text("utf-8"))
    doc["devices"][0]["name"] = f"Hand{EVIL}x"
    doc["devices"][0]["channels"][0]["descriptor"] = f"grip{EVIL}"
    path = tmp_path / "evil.json"
    path.write_text(json.dumps(doc), "utf-8")
    return path


@pytest.mark.parametrize("command", ["info", "print"])
def test_info_and_print_escape_a_device_name_from_a_system_file(capsys, evil_system, command):
    assert main([command, "--system", str(evil_system)]) == 0
    out, err = capsys.readouterr()
    _clean(out + err)
    assert f"Hand{SHOWN}x" in out


def test_a_file_name_with_escapes_is_shown_escaped_in_output_and_errors(capsys, tmp_path,
                                                                         evil_system):
    named = tmp_path / f"fit{EVIL}.json"
    named.write_bytes(evil_system.read_bytes())
    assert main(["check", "--system", str(named)]) == 0
    out, err = capsys.readouterr()
    _clean(out + err)
    assert f"fit{SHOWN}.json: 0 error(s)" in out
    assert main(["info", "--system", str(tmp_path / f"gone{EVIL}.json")]) == 2
    out, err = capsys.readouterr()
    _clean(out + err)
    assert f"gone{SHOWN}.json: cannot read" in err


def test_config_diff_escapes_the_file_names(capsys, tmp_path):
    configs = resources_dir() / "configs"
    a, b = tmp_path / f"a{EVIL}.pdcfg", tmp_path / f"b{EVIL}.pdcfg"
    a.write_bytes((configs / "fig410.pdcfg").read_bytes())
    b.write_bytes((configs / "transradial-hand-and-hook.pdcfg").read_bytes())
    assert main(["config", "diff", str(a), str(b)]) == 3
    out, err = capsys.readouterr()
    _clean(out + err)
    assert f"a{SHOWN}.pdcfg" in out
    assert main(["config", "diff", str(a), str(a)]) == 0
    out, err = capsys.readouterr()
    _clean(out + err)
    assert f"b{SHOWN}" not in out and f"a{SHOWN}.pdcfg and" in out


def test_scan_and_param_get_escape_a_descriptor_read_from_the_bus(capsys, monkeypatch,
                                                                   evil_system):
    monkeypatch.chdir(evil_system.parent)  # sim:evil.json: the system file as a prosthesis
    assert main(["scan", "--bus", "sim:evil.json"]) == 0
    out, err = capsys.readouterr()
    _clean(out + err)
    assert f"grip{SHOWN}" in out
    assert main(["param", "get", "2641/257/101#1", "--bus", "sim:evil.json"]) == 0
    out, err = capsys.readouterr()
    _clean(out + err)
    assert f"descriptor       grip{SHOWN}" in out


def test_history_list_and_show_escape_the_operator_and_the_patient(capsys, monkeypatch,
                                                                    tmp_path):
    monkeypatch.setenv("PDCP_STUDIO_OPERATOR", f"Ann{EVIL}")
    config = resources_dir() / "configs" / "transradial-hand-and-hook.pdcfg"
    assert main(["config", "write", str(config), "--bus", "sim:transradial", "--memory",
                 str(tmp_path / "m.mem"), "--yes", "--patient", f"P-7{EVIL}"]) == 0
    capsys.readouterr()
    assert main(["history", "list"]) == 0
    out, err = capsys.readouterr()
    _clean(out + err)
    assert f"Ann{SHOWN}" in out and f"patient: P-7{SHOWN}" in out
    assert main(["history", "show", "1"]) == 0
    out, err = capsys.readouterr()
    _clean(out + err)
    assert f"Ann{SHOWN}" in out
    assert main(["history", "show", "1", "--json"]) == 0  # JSON escapes them itself
    out = capsys.readouterr().out
    _clean(out)
    assert json.loads(out)["operator"] == f"Ann{EVIL}"
