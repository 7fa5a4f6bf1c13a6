"""Contracts §2, ``history``: reading the fitting history creates nothing (a new computer
has an empty history, not a new archive file), and ``show`` says "not recorded" for a
stored-configuration CRC the change did not read instead of printing ``None``."""

from __future__ import annotations

import json
import os

from pdcp_studio.cli.main import main
from pdcp_studio.storage.history import History


def test_list_on_a_missing_archive_is_empty_and_creates_nothing(tmp_path, monkeypatch, capsys):
    archive = tmp_path / "not-yet" / "history.sqlite"
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(archive))
    assert main(["history", "list", "--json"]) == 0
    out, err = capsys.readouterr()
    assert json.loads(out) == {"entries": []} and err == ""
    assert main(["history", "list"]) == 0
    assert "the fitting history is empty" in capsys.readouterr().out
    assert not archive.exists() and not archive.parent.exists()


def test_show_verify_and_restore_on_a_missing_archive_create_nothing(tmp_path, monkeypatch,
                                                                     capsys):
    archive = tmp_path / "history.sqlite"
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(archive))
    assert main(["history", "show", "1"]) == 2
    assert f"no entry 1: there is no fitting history at {archive} yet" in \
        capsys.readouterr().err
    assert main(["history", "verify"]) == 0  # no entries: nothing is broken
    assert "no fitting history yet (0 entries)" in capsys.readouterr().out
    assert main(["history", "restore", "1", "--bus", "sim:transradial"]) == 2
    assert os.listdir(tmp_path) == []


def test_an_existing_archive_is_still_read(tmp_path, monkeypatch, capsys):
    archive = tmp_path / "history.sqlite"
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(archive))
    with History(archive) as history:
        history.append({"time": "2026-11-22T10:15:00Z", "operator": "op", "bus": "sim:x",
                        "action": "apply clear", "devices": [], "links_before": [],
                        "links_after": [], "config_crc_before": "0x68A3",
                        "config_crc_after": None, "verified": True, "interlock": "not needed"})
    assert main(["history", "list", "--json"]) == 0
    assert [e["id"] for e in json.loads(capsys.readouterr().out)["entries"]] == [1]
    assert main(["history", "show", "1"]) == 0
    assert "stored configuration CRC: 0x68A3 → not recorded" in capsys.readouterr().out


def test_show_of_a_real_change_without_crcs_says_not_recorded(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(tmp_path / "history.sqlite"))
    assert main(["apply", "clear", "--bus", "sim:transradial", "--yes"]) == 0
    capsys.readouterr()
    assert main(["history", "show", "1"]) == 0
    out = capsys.readouterr().out
    assert "None" not in out
    crc = next(line for line in out.splitlines() if "stored configuration CRC:" in line)
    entry = History(tmp_path / "history.sqlite").get(1)
    assert entry is not None
    if entry["config_crc_before"] is None and entry["config_crc_after"] is None:
        assert crc.strip() == "stored configuration CRC: not recorded"
    else:
        before, after = (entry[k] or "not recorded"
                         for k in ("config_crc_before", "config_crc_after"))
        assert crc.strip() == f"stored configuration CRC: {before} → {after}"
