"""Every numeric option is checked at parse time (issue 15, contracts §2): ``nan``, ``inf``,
negative and meaningless zero values are exit 2 naming the option, before anything runs."""

from __future__ import annotations

import argparse

import pytest

from pdcp_studio.cli import options
from pdcp_studio.cli.main import main

BUS = "can:virtual:pdcp-options-never-opened"

BAD = [
    (["arbitrator", "--bus", BUS, "--seconds"], "--seconds", ["nan", "inf", "-1", "x"]),
    (["arbitrator", "--bus", BUS, "--startup-quiet"], "--startup-quiet", ["-3", "nan", "inf"]),
    (["sim", "devices", "transradial", "--bus", BUS, "--seconds"], "--seconds",
     ["nan", "-inf", "-2"]),
    (["sim", "devices", "transradial", "--bus", BUS, "--rate"], "--rate", ["-5", "nan", "1e9"]),
    (["monitor", "--bus", BUS, "--seconds"], "--seconds", ["nan", "inf", "-1"]),
    (["scan", "--bus", BUS, "--settle"], "--settle", ["nan", "-1", "inf"]),
    (["config", "encode", "in.json", "-o"], "-o/--output", ["", "  "]),
]


@pytest.mark.parametrize(("argv", "option", "value"),
                         [(a, o, v) for a, o, vs in BAD for v in vs])
def test_a_bad_number_is_exit_2_naming_the_option(argv, option, value, capsys):
    with pytest.raises(SystemExit) as info:
        main([*argv, value])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert f"error: argument {option}: " in err.strip().splitlines()[-1]  # after the usage


def test_the_types_accept_what_is_meaningful():
    assert options.SECONDS("0.5") == 0.5
    assert options.SECONDS("0") == 0.0
    assert options.WAIT_SECONDS("0") == 0.0
    assert options.RATE_HZ("0") == 0.0  # no data
    assert options.file_name("out.pdcfg") == "out.pdcfg"
    with pytest.raises(argparse.ArgumentTypeError, match="finite"):
        options.SECONDS("NaN")
    with pytest.raises(argparse.ArgumentTypeError, match="at most"):
        options.SECONDS("1e300")


def test_config_encode_to_an_empty_name_writes_nothing(tmp_path, capsys, monkeypatch):
    src = tmp_path / "in.json"
    src.write_text('{"configurations": []}')
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as info:
        main(["config", "encode", str(src), "-o", ""])
    assert info.value.code == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.json"]
