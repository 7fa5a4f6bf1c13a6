"""One archive interface, two engines: every test here runs on SQLite and on PostgreSQL (a
real throw-away server, tests/pg_cluster.py), and the PostgreSQL-only rules (signed-in
operators, append-only by the server) against that server too."""

from __future__ import annotations

import json
import multiprocessing

import pytest

from pdcp_studio.storage.archive import EntryFilter, HistoryError, NotAllowedError, open_archive
from pdcp_studio.storage.archive.transfer import export_lines, import_entries, read_lines
from tests.pg_cluster import FITTER, FITTER_NAME, READER

HAND = {"vid": 2641, "pid": 769, "serial": 301}
ELBOW = {"vid": 2641, "pid": 1025, "serial": 401}


def body(n: int, *, patient: str | None = "P-1", devices=(HAND,)) -> dict:
    return {"time": "2026-11-28T10:00:00Z", "bus": "sim:transradial", "action": f"apply clear {n}",
            "devices": list(devices), "links_before": [], "links_after": [],
            "config_crc_before": None, "config_crc_after": None, "verified": True,
            "interlock": "not needed", "patient": patient,
            "outcome": {"status": "applied", "step": "", "reason": "", "notes": []}}


def test_appends_chain_and_verify(archive_url):
    with open_archive(archive_url) as a:
        ids = [a.append(body(n)) for n in range(1, 6)]
        assert ids == [1, 2, 3, 4, 5]
        entries = a.entries()
        assert [e["id"] for e in entries] == ids
        assert entries[1]["previous_hash"] == entries[0]["hash"]
        assert all(e["workstation"] for e in entries)
        assert a.verify().ok and a.verify().entries == 5
        assert a.get(3)["action"] == "apply clear 3" and a.get(99) is None


def test_a_clinics_view_filters_by_patient_and_by_part(archive_url):
    with open_archive(archive_url) as a:
        a.append(body(1, patient="P-1"))
        a.append(body(2, patient="P-2", devices=(HAND, ELBOW)))
        a.append(body(3, patient="P-1", devices=(ELBOW,)))
        a.append(body(4, patient=None))
        by_patient = a.entries(EntryFilter(patient="P-1"))
        assert [e["id"] for e in by_patient] == [1, 3]
        by_part = a.entries(EntryFilter(device=(2641, 1025, 401)))
        assert [e["id"] for e in by_part] == [2, 3]
        both = a.entries(EntryFilter(patient="P-2", device=(2641, 769, 301)))
        assert [e["id"] for e in both] == [2]
        assert a.entries(EntryFilter(patient="nobody")) == []


def test_an_announced_change_becomes_its_entry_and_a_dead_ones_is_recovered(archive_url):
    from pdcp_studio.storage.history import interrupted

    with open_archive(archive_url) as a:
        token = a.begin(interrupted(body(1)))
        assert a.recover() == []  # this process is alive: its change is still running
        assert a.finish(token, body(1)) == 1
        assert a.recover() == [] and len(a.entries()) == 1
    # A process that died mid-change: its announcement is recorded as interrupted.
    ctx = multiprocessing.get_context("spawn")
    p = ctx.Process(target=_announce_and_die, args=(archive_url,))
    p.start()
    p.join(60)
    with open_archive(archive_url) as a:
        assert a.recover() == [2]
        assert a.get(2)["outcome"]["status"] == "interrupted" and a.verify().ok


def _announce_and_die(url: str) -> None:
    import os

    from pdcp_studio.storage.history import interrupted

    a = open_archive(url)
    a.begin(interrupted(body(2)))
    os._exit(0)


def _record(url: str, tag: str, n: int) -> None:
    with open_archive(url) as a:
        for i in range(n):
            token = a.begin({**body(i), "action": f"{tag} {i}"})
            a.finish(token, {**body(i), "action": f"{tag} {i}"})


def test_two_workstations_recording_at_once_never_fork_or_lose_the_chain(archive_url):
    """Two processes, each announcing and recording 25 changes into the same archive."""
    open_archive(archive_url).close()
    ctx = multiprocessing.get_context("spawn")
    procs = [ctx.Process(target=_record, args=(archive_url, tag, 25)) for tag in ("A", "B")]
    for p in procs:
        p.start()
    for p in procs:
        p.join(120)
        assert p.exitcode == 0
    with open_archive(archive_url) as a:
        entries = a.entries()
        assert [e["id"] for e in entries] == list(range(1, 51))
        actions = {e["action"] for e in entries}
        assert actions == {f"{t} {i}" for t in "AB" for i in range(25)}
        assert a.verify().ok


def test_export_and_import_keep_every_entry_verifiable_with_its_origin(archive_url, tmp_path):
    """A workstation's SQLite history moves into the archive under test (either engine)."""
    source = f"sqlite:///{tmp_path / 'laptop.sqlite'}"
    with open_archive(source) as laptop:
        for n in range(1, 4):
            laptop.append({**body(n), "operator": "Laptop User", "workstation": "laptop-7"})
        lines = list(export_lines(laptop))
    assert all(set(json.loads(x)) >= {"id", "hash", "previous_hash"} for x in lines)
    export = tmp_path / "laptop.jsonl"
    export.write_text("\n".join(lines) + "\n")
    with open_archive(archive_url) as clinic:
        clinic.append(body(0))  # the clinic's own entry first: the ids differ
        with export.open() as f:
            report = import_entries(clinic, read_lines(f, str(export)), source="laptop")
        assert report.imported == [2, 3, 4] and report.skipped == 0
        moved = clinic.get(3)
        assert moved["operator"] == "Laptop User"  # the original operator, kept
        assert moved["origin"]["id"] == 2 and moved["origin"]["workstation"] == "laptop-7"
        assert moved["origin"]["hash"] == json.loads(lines[1])["hash"]
        assert clinic.verify().ok
        with export.open() as f:  # again: nothing is imported twice
            assert import_entries(clinic, read_lines(f, "x"), source="laptop").skipped == 3
        assert len(clinic.entries()) == 4


def test_an_edited_export_is_refused_whole(archive_url, tmp_path):
    with open_archive(f"sqlite:///{tmp_path / 'laptop.sqlite'}") as laptop:
        laptop.append(body(1))
        laptop.append(body(2))
        lines = [json.loads(x) for x in export_lines(laptop)]
    lines[1]["patient"] = "someone else"
    with open_archive(archive_url) as clinic:
        with pytest.raises(HistoryError, match="entry 2 was edited"):
            import_entries(clinic, lines, source="edited")
        assert clinic.entries() == []


# -- PostgreSQL only: signed-in operators, append-only by the server -------------------------

def test_the_operator_is_the_signed_in_role_whatever_the_environment_says(pg_db, monkeypatch):
    monkeypatch.setenv("PDCP_STUDIO_OPERATOR", "Mallory")
    with open_archive(pg_db.fitter) as a:
        assert a.signed_in() == FITTER and a.operator() == FITTER_NAME
        a.append({**body(1), "operator": "Mallory"})
        entry = a.get(1)
    assert entry["operator"] == FITTER_NAME and entry["signed_in"] == FITTER


def test_on_sqlite_the_operator_comes_from_the_environment(tmp_path, monkeypatch):
    monkeypatch.setenv("PDCP_STUDIO_OPERATOR", "A. Fitter")
    with open_archive(f"sqlite:///{tmp_path / 'h.sqlite'}") as a:
        a.append(body(1))
        assert a.get(1)["operator"] == "A. Fitter" and a.signed_in() is None


def test_a_reader_may_read_but_not_record(pg_db):
    with open_archive(pg_db.fitter) as a:
        a.append(body(1))
    with open_archive(pg_db.reader) as r:
        assert [e["id"] for e in r.entries()] == [1] and r.verify().ok
        with pytest.raises(NotAllowedError, match=f"signed in as {READER}, who may read the "
                                                  "fitting history but not record changes"):
            r.begin(body(2))
        with pytest.raises(NotAllowedError):
            r.append(body(2))
        assert r.recover() == []


def test_the_server_refuses_an_update_or_delete_by_a_fitter_and_by_the_owner(pg_db):
    import psycopg

    with open_archive(pg_db.fitter) as a:
        a.append(body(1))
    for url in (pg_db.fitter, pg_db.admin):
        with psycopg.connect(url, autocommit=True) as db:
            for sql in ("UPDATE pdcp.entries SET body = '{}'", "DELETE FROM pdcp.entries",
                        "TRUNCATE pdcp.entries"):
                with pytest.raises(psycopg.errors.InsufficientPrivilege):
                    db.execute(sql)
    with open_archive(pg_db.fitter) as a:
        assert len(a.entries()) == 1 and a.verify().ok


def test_the_server_refuses_a_forged_operator_and_a_forked_chain(pg_db):
    import psycopg

    from pdcp_studio.storage.archive.chain import GENESIS, canonical, entry_hash

    forged = {**body(1), "operator": "Mallory", "signed_in": FITTER}
    with psycopg.connect(pg_db.fitter, autocommit=True) as db:
        with pytest.raises(psycopg.errors.InsufficientPrivilege, match="signed-in role"):
            db.execute("INSERT INTO pdcp.entries (id, previous_hash, hash, body) "
                       "VALUES (1, %s, %s, %s)",
                       (GENESIS, entry_hash(1, GENESIS, canonical(forged)), json.dumps(forged)))
    with open_archive(pg_db.fitter) as a:
        a.append(body(1))
    honest = {**body(2), "operator": FITTER_NAME, "signed_in": FITTER}
    with psycopg.connect(pg_db.fitter, autocommit=True) as db:  # a second entry 1: a fork
        with pytest.raises(psycopg.errors.SerializationFailure, match="fork"):
            db.execute("INSERT INTO pdcp.entries (id, previous_hash, hash, body) "
                       "VALUES (2, %s, %s, %s)",
                       (GENESIS, entry_hash(2, GENESIS, canonical(honest)), json.dumps(honest)))


def test_a_database_without_the_schema_says_to_run_archive_init(pg_cluster):
    with pytest.raises(HistoryError, match="archive init"):
        open_archive(pg_cluster.url("postgres", "postgres"))


def test_an_unreachable_server_is_said_in_words(pg_cluster):
    from pdcp_studio.storage.archive.postgres import ServerUnreachable

    with pytest.raises(ServerUnreachable, match="cannot be reached"):
        open_archive("postgresql://anna@127.0.0.1:1/nowhere")


def test_a_login_in_neither_group_is_told_so(pg_db):
    pg_db.cluster.sql("DO $$ BEGIN IF NOT EXISTS (SELECT FROM pg_roles WHERE rolname = "
                      "'stranger') THEN CREATE ROLE stranger LOGIN; END IF; END $$")
    with pytest.raises(NotAllowedError, match=r"signed in as stranger, who may neither read "
                                              r"nor record.*pdcp_fitter or pdcp_reader"):
        open_archive(pg_db.cluster.url("stranger", pg_db.name))


def test_a_kept_outcome_is_recorded_under_its_own_operator_only(pg_db, tmp_path, monkeypatch):
    """An outcome kept on this workstation while the server was away waits for the role
    that made the change: another fitter signed in to the same archive does not record it
    under their name; its own role does."""
    from pdcp_studio.storage.archive import journal
    from tests.pg_cluster import PASSWORD_ROLE

    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    with open_archive(pg_db.fitter) as a:
        theirs = journal.keep(a.location, "t1", {**body(1), "signed_in": PASSWORD_ROLE})
        mine = journal.keep(a.location, "t2", a.stamp(body(2)))
        assert a.recover() == [1]
        assert a.get(1)["action"] == "apply clear 2" and a.get(1)["recorded_late"] is True
    assert theirs.exists() and not mine.exists()
