"""The clinic archive on the command line (contracts §2, issue 25): ``archive init``,
``--archive URL`` on the commands that record or read history, ``history list --patient
--prosthesis``, ``history export`` / ``import``, and ``doctor`` naming the archive and the
signed-in operator."""

from __future__ import annotations

import json

import pytest

from pdcp_studio.cli.main import main
from tests.pg_cluster import FITTER, FITTER_NAME, READER

HAND = "2641/769/301"


def _apply(archive: str, patient: str, capsys) -> int:
    code = main(["apply", "clear", "--bus", "sim:transradial", "--yes", "--archive", archive,
                 "--patient", patient])
    capsys.readouterr()
    return code


def test_archive_init_is_idempotent_and_refuses_sqlite(pg_db, capsys):
    assert main(["archive", "init", pg_db.admin]) == 0  # a second time: nothing changes
    assert "roles pdcp_fitter and pdcp_reader" in capsys.readouterr().out
    assert main(["archive", "init", "sqlite:///tmp/x.sqlite"]) == 2
    assert "PostgreSQL database" in capsys.readouterr().err


def test_changes_are_recorded_in_the_archive_named_and_listed_by_patient_and_part(
        archive_url, capsys):
    assert _apply(archive_url, "P-1", capsys) == 0
    assert _apply(archive_url, "P-2", capsys) == 0
    assert main(["history", "list", "--json", "--archive", archive_url,
                 "--patient", "P-2"]) == 0
    entries = json.loads(capsys.readouterr().out)["entries"]
    assert [e["patient"] for e in entries] == ["P-2"] and entries[0]["workstation"]
    assert main(["history", "list", "--archive", archive_url, "--prosthesis", HAND]) == 0
    assert len(capsys.readouterr().out.strip().splitlines()) == 2
    assert main(["history", "list", "--archive", archive_url, "--prosthesis", "1/2/3"]) == 0
    assert "no entry matches" in capsys.readouterr().out
    with pytest.raises(SystemExit) as bad:
        main(["history", "list", "--archive", archive_url, "--prosthesis", "x"])
    assert bad.value.code == 2 and "a part is VID/PID/SERIAL" in capsys.readouterr().err
    assert main(["history", "verify", "--archive", archive_url]) == 0
    assert "2 entries, the chain is intact" in capsys.readouterr().out


def test_the_archive_comes_from_the_environment_too(archive_url, monkeypatch, capsys):
    monkeypatch.setenv("PDCP_STUDIO_ARCHIVE", archive_url)
    assert main(["apply", "clear", "--bus", "sim:transradial", "--yes"]) == 0
    capsys.readouterr()
    assert main(["history", "list", "--json"]) == 0
    assert len(json.loads(capsys.readouterr().out)["entries"]) == 1


def test_a_reader_is_refused_in_words_and_nothing_is_recorded(pg_db, capsys):
    assert main(["apply", "clear", "--bus", "sim:transradial", "--yes",
                 "--archive", pg_db.reader]) == 1
    err = capsys.readouterr().err
    assert f"signed in as {READER}, who may read the fitting history but not record" in err
    assert "nothing was written to the prosthesis" in err
    assert main(["history", "list", "--json", "--archive", pg_db.reader]) == 0
    assert json.loads(capsys.readouterr().out) == {"entries": []}


def test_an_unreachable_archive_refuses_the_change(capsys):
    assert main(["apply", "clear", "--bus", "sim:transradial", "--yes",
                 "--archive", "postgresql://anna@127.0.0.1:1/clinic"]) == 1
    err = capsys.readouterr().err
    assert "cannot be reached" in err and "nothing was written to the prosthesis" in err


def test_the_operator_from_the_environment_is_ignored_on_postgresql(pg_db, monkeypatch,
                                                                    capsys):
    monkeypatch.setenv("PDCP_STUDIO_OPERATOR", "Mallory")
    assert _apply(pg_db.fitter, "P-1", capsys) == 0
    assert main(["history", "list", "--json", "--archive", pg_db.fitter]) == 0
    assert json.loads(capsys.readouterr().out)["entries"][0]["operator"] == FITTER_NAME


def test_export_then_import_into_the_clinic_verifies(archive_url, tmp_path, capsys):
    laptop = f"sqlite:///{tmp_path / 'laptop.sqlite'}"
    assert _apply(laptop, "P-1", capsys) == 0
    assert _apply(laptop, "P-2", capsys) == 0
    export = tmp_path / "laptop.jsonl"
    assert main(["history", "export", "--archive", laptop, "-o", str(export)]) == 0
    lines = [json.loads(x) for x in export.read_text().splitlines()]
    assert [x["id"] for x in lines] == [1, 2] and all(x["hash"] for x in lines)
    assert main(["history", "import", str(export), "--archive", archive_url]) == 0
    assert "2 entries imported" in capsys.readouterr().out
    assert main(["history", "verify", "--archive", archive_url]) == 0
    assert main(["history", "import", str(export), "--archive", archive_url]) == 0
    assert "2 already there" in capsys.readouterr().out
    assert main(["history", "show", "2", "--json", "--archive", archive_url]) == 0
    shown = json.loads(capsys.readouterr().out)
    assert shown["origin"]["id"] == 2 and shown["origin"]["hash"] == lines[1]["hash"]
    lines[0]["operator"] = "someone else"
    export.write_text("".join(json.dumps(x) + "\n" for x in lines))
    assert main(["history", "import", str(export), "--archive", archive_url]) == 1
    assert "does not verify: entry 1 was edited" in capsys.readouterr().err


def test_doctor_names_the_archive_and_who_is_signed_in(pg_db, capsys):
    assert main(["doctor", "--json", "--archive", pg_db.fitter]) in (0, 1)
    doc = json.loads(capsys.readouterr().out)["archive"]
    assert doc["engine"] == "postgresql" and doc["signed_in"] == FITTER
    assert doc["operator"] == FITTER_NAME and doc["may_record"] is True
    assert "password" not in json.dumps(doc)
    main(["doctor", "--archive", pg_db.reader])
    out = capsys.readouterr().out
    assert f"signed in as {READER}" in out and "may read the fitting history but not" in out


def test_archive_init_by_a_clinic_administrator_who_is_no_superuser(pg_cluster, capsys,
                                                                    monkeypatch, tmp_path):
    """docs/clinic-archive.md's set-up as written: an administrator role with CREATEROLE
    owning the database runs archive init and makes a fitter's login, who then records."""
    import psycopg

    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    pg_cluster.sql("DO $$ BEGIN IF NOT EXISTS (SELECT FROM pg_roles WHERE rolname = "
                   "'pdcp_admin') THEN CREATE ROLE pdcp_admin LOGIN CREATEROLE; END IF; END $$")
    pg_cluster.sql("CREATE DATABASE clinic_doc OWNER pdcp_admin")
    try:
        admin = pg_cluster.url("pdcp_admin", "clinic_doc")
        assert main(["archive", "init", admin]) == 0, capsys.readouterr().err
        with psycopg.connect(admin, autocommit=True) as db:
            db.execute("DO $$ BEGIN IF NOT EXISTS (SELECT FROM pg_roles WHERE rolname = "
                       "'bea') THEN CREATE ROLE bea LOGIN IN ROLE pdcp_fitter; END IF; END $$")
            db.execute("INSERT INTO pdcp.operators VALUES ('bea', 'Bea Lund')")
        fitter = pg_cluster.url("bea", "clinic_doc")
        assert _apply(fitter, "P-7", capsys) == 0
        assert main(["history", "list", "--json", "--archive", fitter]) == 0
        entries = json.loads(capsys.readouterr().out)["entries"]
        assert [e["operator"] for e in entries] == ["Bea Lund"]
    finally:
        pg_cluster.sql("DROP DATABASE clinic_doc WITH (FORCE)")
