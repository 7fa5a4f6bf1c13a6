"""``pdcp-studio config decode|encode`` (contracts §2): output, exit codes, stderr."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from pdcp_studio.cli.main import main

ROOT = Path(__file__).resolve().parents[2]
FIG410 = ROOT / "resources" / "configs" / "fig410.pdcfg"
THESIS = ROOT / "tests" / "data" / "fig410-thesis.pdcfg"

FIRST_CHANNEL = {"type": "0x000A", "profile": "0x0014", "index": 1, "vid": 30, "pid": 40,
                 "serial": 50, "owner_type": 60, "owner_profile": 70}


def test_decode_json_is_the_contract_document(capsys):
    assert main(["config", "decode", str(FIG410), "--json"]) == 0
    out, err = capsys.readouterr()
    doc = json.loads(out)  # exactly one JSON document, nothing else on stdout
    assert err == ""
    configs = doc["configurations"]
    assert [c["index"] for c in configs] == [1, 2]
    assert configs[0]["links"][0] == {"index": 1, "input": FIRST_CHANNEL,
                                      "output": FIRST_CHANNEL}
    assert "owner_type" not in configs[1]["links"][0]["input"]


def test_decode_text_listing(capsys):
    assert main(["config", "decode", str(FIG410)]) == 0
    out = capsys.readouterr().out
    assert "2 configuration(s), 3 link(s)" in out
    assert "checksum 0x" in out and "verified" in out
    assert "link 1: output 30/40/50#1  type 0x000A  profile 0x0014" in out
    assert main(["config", "decode", str(THESIS)]) == 0
    assert "no checksum" in capsys.readouterr().out


def test_encode_reproduces_the_file_and_adds_a_checksum(tmp_path, capsys):
    assert main(["config", "decode", str(THESIS), "--json"]) == 0
    source = tmp_path / "fig410.json"
    source.write_text(capsys.readouterr().out)
    target = tmp_path / "out.pdcfg"
    assert main(["config", "encode", str(source), "-o", str(target)]) == 0
    assert target.read_bytes() == FIG410.read_bytes()
    assert "3 link(s)" in capsys.readouterr().out
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fig410.json", "out.pdcfg"]


def test_bad_file_exit_2_names_file_offset_and_reason(tmp_path, capsys):
    bad = tmp_path / "bad.pdcfg"
    data = bytearray(FIG410.read_bytes())
    data[-5] ^= 0xFF  # break the stored checksum
    bad.write_bytes(bytes(data))
    assert main(["config", "decode", str(bad), "--json"]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert str(bad) in err
    assert f"offset {len(data) - 6}" in err
    assert "checksum mismatch" in err
    assert len(err.strip().splitlines()) == 1


def test_truncated_file(tmp_path, capsys):
    bad = tmp_path / "short.pdcfg"
    bad.write_bytes(FIG410.read_bytes()[:100])
    assert main(["config", "decode", str(bad)]) == 2
    err = capsys.readouterr().err
    assert f"{bad}: offset 99: truncated record" in err


def test_missing_input_file_is_bad_input(tmp_path, capsys):
    missing = tmp_path / "missing.pdcfg"
    assert main(["config", "decode", str(missing)]) == 2
    assert str(missing) in capsys.readouterr().err
    assert main(["config", "encode", str(tmp_path / "nope.json"), "-o", "x.pdcfg"]) == 2


@pytest.mark.parametrize(("text", "words"), [
    ("{not json", "line 1 column 2"),
    ('{"configurations": [{"links": [{"input": {"index": 300}}]}]}',
     "configurations[0].links[0].input.index: 300 is out of range 1…255"),
    ('{"configurations": 5}', "configurations: expected a list"),
])
def test_bad_json_exit_2_and_no_output_file(tmp_path, capsys, text, words):
    source = tmp_path / "in.json"
    source.write_text(text)
    target = tmp_path / "out.pdcfg"
    assert main(["config", "encode", str(source), "-o", str(target)]) == 2
    err = capsys.readouterr().err
    assert str(source) in err and words in err
    assert not target.exists()


def test_module_imports_nothing_heavy():
    code = ("import sys, pdcp_studio.cli.config_cmd; "
            "print(sorted(m for m in ('can', 'PySide6', 'networkx', 'serial', "
            "'pdcp_studio.storage.config_codec') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                         text=True, check=True).stdout
    assert out.strip() == "[]"


def test_real_subprocess_decode_json():
    proc = subprocess.run(
        [sys.executable, "-m", "pdcp_studio", "config", "decode",
         "resources/configs/fig410.pdcfg", "--json"],
        cwd=ROOT, capture_output=True, text=True, timeout=60,
    )
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    assert doc["configurations"][0]["links"][0]["output"] == FIRST_CHANNEL


def test_real_subprocess_bad_file_exit_2(tmp_path):
    bad = tmp_path / "bad.pdcfg"
    bad.write_bytes(b"\x01\x01\x00")
    proc = subprocess.run(
        [sys.executable, "-m", "pdcp_studio", "config", "decode", str(bad)],
        cwd=ROOT, capture_output=True, text=True, timeout=60,
    )
    assert proc.returncode == 2
    assert proc.stdout == ""
    assert f"{bad}: offset 3: missing End record" in proc.stderr
