"""Every subcommand's arguments fuzzed (issue 15), in process: any exit is 0, 1, 2 or 3, never
a traceback, and with ``--json`` stdout is empty or one valid JSON document.

The values are the attacks that broke the program once: non-numbers and non-finite numbers
for durations and rates, malformed and unknown bus URLs, hostile files (nested 5,000 deep,
keys given twice, the null profile, binary garbage, a directory, an empty name). Commands that
would run until interrupted always get a ``--seconds`` last (valid ones short), and the desktop
app (``gui``, and bare ``pdcp-studio``) is left to the app tests. Bounded: under a minute on a busy 2-core machine.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pdcp_studio.cli.main import build_parser, main

#: Leaves that open a window: not fuzzed here.
SKIP = {("gui",), ("hostlink-test",)}
#: Leaves that run until interrupted: a --seconds is appended last.
LONG = {("arbitrator",), ("sim", "devices"), ("monitor",)}
EXITS = {0, 1, 2, 3}

NUMBERS = ["nan", "-nan", "inf", "-inf", "-1", "0", "1e309", "1e-320", "abc", "", "0x10",
           "9" * 40]
BUSES = ["sim:nosuch", "sim:", "can:nosuch:0", "can:virtual:x?port=99999", "bogus",
         "serial:/nonexistent/tty", "can:", "can:virtual:", "tcp:host:1", "sim:thesis-test1?x=1",
         "thesis-test1", "autoconfigure"]


def _leaves(parser: argparse.ArgumentParser, path: tuple[str, ...] = ()):
    """(command path, parser) for every leaf subcommand."""
    subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield path, parser
        return
    for name, sub in subs[0].choices.items():
        yield from _leaves(sub, (*path, name))


LEAVES = [(path, p) for path, p in _leaves(build_parser()) if path[:1] and path not in SKIP
          and path[:1] not in SKIP]


@pytest.fixture(scope="module")
def hostile(tmp_path_factory) -> list[str]:
    d = tmp_path_factory.mktemp("hostile")
    files = {
        "deep.json": "[" * 5000 + "]" * 5000,
        "dup.json": '{"format": "pdcp-system/1", "format": "pdcp-system/1", "devices": []}',
        "null-profile.json": json.dumps({"format": "pdcp-system/1", "devices": [
            {"vid": 1, "pid": 1, "serial": 1, "channels": [
                {"index": 1, "direction": "output", "profile": "0x0000"}]}]}),
        "nan.json": '{"format": "pdcp-system/1", "devices": [{"vid": NaN}]}',
        "empty.json": "",
        "config-dup.json": '{"configurations": [], "configurations": []}',
    }
    for name, text in files.items():
        (d / name).write_text(text)
    (d / "garbage.pdcfg").write_bytes(bytes(range(256)) * 7)
    (d / "a-directory").mkdir()
    return [str(d / n) for n in (*files, "garbage.pdcfg", "a-directory")] + [
        str(d / "missing" / "out.pdcfg"), str(d / "out.pdcfg"), "", "-", "/dev/null"]


def _options(parser: argparse.ArgumentParser) -> list[str]:
    return [o for a in parser._actions for o in a.option_strings if o not in ("-h", "--help")]


def _positionals(parser: argparse.ArgumentParser) -> list[argparse.Action]:
    return [a for a in parser._actions if not a.option_strings
            and not isinstance(a, argparse._SubParsersAction)]


def _check(argv: list[str], capsys) -> None:
    capsys.readouterr()
    try:
        code = main(argv)
    except SystemExit as exit_:  # argparse: usage errors are 2
        code = exit_.code if isinstance(exit_.code, int) else 2
    out, err = capsys.readouterr()
    assert code in EXITS, (argv, code, err)
    assert "Traceback" not in err, (argv, err)
    if "--json" in argv and out.strip():
        json.loads(out)  # one JSON document and nothing else


@pytest.mark.parametrize(("path", "parser"), LEAVES, ids=[" ".join(p) for p, _ in LEAVES])
@settings(max_examples=15, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_fuzzed_arguments_exit_cleanly(path, parser, hostile, capsys, monkeypatch, tmp_path,
                                       data):
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(tmp_path / "history.sqlite"))
    monkeypatch.setenv("PDCP_STUDIO_OPERATOR", "fuzz")
    values = st.sampled_from(NUMBERS + BUSES + hostile)
    # Long runners get a bus that opens at once (a fuzzed --bus later overrides it).
    argv = [*path, "--bus", "can:virtual:pdcp-fuzz"] if path in LONG else list(path)
    for action in _positionals(parser):
        if action.choices:
            argv.append(data.draw(st.sampled_from([*map(str, action.choices), "nosuch"])))
        else:
            argv.append(data.draw(values))
    options = _options(parser)
    if options:
        tokens = data.draw(st.lists(st.one_of(st.sampled_from(options), values), max_size=6))
        argv += tokens
    if path in LONG:
        argv += ["--seconds", data.draw(st.sampled_from(["0", "0.05", "nan", "inf", "-1"]))]
    _check(argv, capsys)


def test_every_subcommand_is_fuzzed():
    names = {p[0] for p, _ in LEAVES}
    assert {"config", "print", "info", "plan", "scan", "sim", "arbitrator", "monitor"} <= names


def test_the_json_check_catches_a_traceback_free_bad_document(hostile, capsys):
    """The attacks of the issue, each once, named."""
    deep = next(h for h in hostile if h.endswith("deep.json"))
    for argv in (["info", "--system", deep], ["print", "--system", deep],
                 ["plan", "autoconfigure", "--system", deep, "--json"],
                 ["config", "encode", deep, "-o", str(Path(deep).with_suffix(".pdcfg"))],
                 ["arbitrator", "--bus", "can:virtual:fuzz", "--seconds", "nan"],
                 ["sim", "devices", "thesis-test1", "--bus", "can:virtual:f", "--rate", "-5"]):
        _check(argv, capsys)
