"""Output files the command line cannot write (contracts §2): a failed write — a folder given
as the file, a missing folder, a file used as a folder — is exit 1 for every command, naming
the file asked for and what is wrong with its path (never "[Errno 2]"), leaving nothing behind."""

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


def test_a_folder_as_the_output_is_a_failed_write(tmp_path, config_json, capsys):
    for argv in commands(config_json, tmp_path):
        assert main(argv) == 1
        err = capsys.readouterr().err
        assert str(tmp_path) in err and "is a folder" in err and ".tmp" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.json"]


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
