"""Output files the command line cannot write (contracts §2): a folder given as the file is
bad input (exit 2, before anything is done); a write that fails is exit 1 naming the file
asked for and what is wrong with its path — never "[Errno 2]" — and leaves nothing behind."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdcp_studio.cli.main import main

CONFIG = Path(__file__).resolve().parents[2] / "resources" / "configs" / "fig410.pdcfg"
CAPTURE = Path(__file__).resolve().parents[1] / "data" / "captures" / "pdcp-session.asc"


@pytest.fixture
def config_json(tmp_path, capsys):
    assert main(["config", "decode", str(CONFIG), "--json"]) == 0
    source = tmp_path / "in.json"
    source.write_text(capsys.readouterr().out)
    return source


def commands(source: Path, out: Path) -> list[list[str]]:
    return [["config", "encode", str(source), "-o", str(out)],
            ["monitor", "--replay", str(CAPTURE), "--log", str(out.with_suffix(".asc"))
             if out.suffix else str(out)]]


def test_a_folder_as_the_output_is_bad_input(tmp_path, config_json, capsys):
    for argv in commands(config_json, tmp_path):
        with pytest.raises(SystemExit) as exit_:
            main(argv)
        assert exit_.value.code == 2
        assert f"{tmp_path} is a folder" in capsys.readouterr().err


def test_a_missing_folder_is_a_failed_write_naming_the_file_and_folder(tmp_path, config_json,
                                                                       capsys):
    out = tmp_path / "no-such-folder" / "x.pdcfg"
    for argv in commands(config_json, out):
        assert main(argv) == 1
        err = capsys.readouterr().err
        assert str(out.parent) in err and "Errno" not in err
    assert not out.parent.exists()


def test_a_file_used_as_a_folder_is_a_failed_write(tmp_path, config_json, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("keep")
    out = blocker / "x.pdcfg"
    assert main(["config", "encode", str(config_json), "-o", str(out)]) == 1
    err = capsys.readouterr().err
    assert str(out) in err and "not a folder" in err
    assert blocker.read_text() == "keep"
