"""The fitting history: append-only, hash-chained, safe for two writers (storage/history.py)."""

from __future__ import annotations

import itertools
import json
import multiprocessing
import sqlite3

import pytest

from pdcp_studio.storage.history import (
    LIST_FIELDS,
    History,
    default_operator,
    default_path,
    list_json,
)


def body(n: int) -> dict:
    return {"time": f"2026-11-22T10:{n:02d}:00Z", "operator": "op", "bus": "sim:x",
            "action": f"apply clear {n}", "devices": [], "links_before": [], "links_after": [],
            "config_crc_before": None, "config_crc_after": None, "verified": True,
            "interlock": "not needed", "patient": "P-1", "plan": {"actions": []}}


def filled(path, n: int = 5) -> History:
    h = History(path)
    for i in range(1, n + 1):
        assert h.append(body(i)) == i
    return h


def test_entries_chain_and_verify(tmp_path):
    h = filled(tmp_path / "h.sqlite3")
    entries = h.entries()
    assert [e["id"] for e in entries] == [1, 2, 3, 4, 5]
    assert entries[0]["previous_hash"] == "0" * 64
    assert all(b["previous_hash"] == a["hash"] for a, b in itertools.pairwise(entries))
    assert h.verify().ok and h.verify().entries == 5
    assert set(LIST_FIELDS) <= set(list_json(entries[0]))
    assert list(list_json(entries[0]))[:len(LIST_FIELDS)] == list(LIST_FIELDS)
    h.close()


def test_an_edited_entry_is_detected(tmp_path):
    path = tmp_path / "h.sqlite3"
    filled(path).close()
    db = sqlite3.connect(path)
    doc = json.loads(db.execute("SELECT body FROM entries WHERE id = 3").fetchone()[0])
    doc["operator"] = "someone else"
    db.execute("UPDATE entries SET body = ? WHERE id = 3", (json.dumps(doc),))
    db.commit()
    db.close()
    report = History(path).verify()
    assert not report.ok and report.first_bad == 3 and "edited" in report.reason


def test_a_deleted_entry_is_detected_in_the_middle_and_at_the_end(tmp_path):
    path = tmp_path / "h.sqlite3"
    filled(path).close()
    db = sqlite3.connect(path)
    db.execute("DELETE FROM entries WHERE id = 2")
    db.commit()
    report = History(path).verify()
    assert not report.ok and report.first_bad == 2 and "deleted" in report.reason
    path2 = tmp_path / "h2.sqlite3"
    filled(path2).close()
    db = sqlite3.connect(path2)
    db.execute("DELETE FROM entries WHERE id = 5")
    db.commit()
    report = History(path2).verify()
    assert not report.ok and report.first_bad == 5


def test_renumbered_entries_after_a_deletion_are_detected(tmp_path):
    path = tmp_path / "h.sqlite3"
    filled(path).close()
    db = sqlite3.connect(path)
    db.execute("DELETE FROM entries WHERE id = 2")
    for i in (3, 4, 5):
        db.execute("UPDATE entries SET id = ? WHERE id = ?", (i - 1, i))
    db.execute("UPDATE head SET last_id = 4")
    db.commit()
    report = History(path).verify()
    assert not report.ok and report.first_bad == 2


def test_path_and_operator_come_from_the_environment(tmp_path, monkeypatch):
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(tmp_path / "x.sqlite3"))
    monkeypatch.setenv("PDCP_STUDIO_OPERATOR", "Dr. Who")
    assert default_path() == tmp_path / "x.sqlite3" and default_operator() == "Dr. Who"
    monkeypatch.delenv("PDCP_STUDIO_HISTORY")
    monkeypatch.delenv("PDCP_STUDIO_OPERATOR")
    from pdcp_studio.paths import history_path

    assert default_path() == history_path() and default_path().name.startswith("history.")
    assert default_operator()


def test_wal_mode_and_full_sync(tmp_path):
    h = History(tmp_path / "h.sqlite3")
    assert h._db.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
    assert h._db.execute("PRAGMA synchronous").fetchone()[0] == 2
    h.close()


def _writer(path: str, tag: str, n: int) -> None:
    with History(path) as h:
        for i in range(n):
            h.append({**body(i), "action": f"{tag} {i}"})


def test_two_processes_append_at_once_and_the_chain_holds(tmp_path):
    path = str(tmp_path / "h.sqlite3")
    History(path).close()
    ctx = multiprocessing.get_context("spawn")
    procs = [ctx.Process(target=_writer, args=(path, tag, 25)) for tag in ("A", "B")]
    for p in procs:
        p.start()
    for p in procs:
        p.join(60)
        assert p.exitcode == 0
    with History(path) as h:
        entries = h.entries()
        assert len(entries) == 50 and h.verify().ok
        assert {e["action"].split()[0] for e in entries} == {"A", "B"}


def test_an_unopenable_archive_is_a_clear_error(tmp_path):
    from pdcp_studio.storage.history import HistoryError

    (tmp_path / "dir").mkdir()
    with pytest.raises(HistoryError, match="cannot open"):
        History(tmp_path / "dir")


def test_an_announced_change_whose_process_died_is_recorded_as_interrupted(tmp_path):
    from pdcp_studio.storage.history import interrupted

    h = filled(tmp_path / "h.sqlite3", 1)
    token = h.begin(interrupted(body(2)))
    assert h.recover() == []  # this process is alive: its change is still running
    h.finish(token, body(2))
    assert [e["action"] for e in h.entries()] == ["apply clear 1", "apply clear 2"]
    h.begin(interrupted(body(3)))
    h._db.execute("UPDATE pending SET pid = 999999999")  # a process that no longer exists
    assert h.recover() == [3]
    last = h.get(3)
    assert last["outcome"]["status"] == "interrupted" and last["links_after"] is None
    assert last["verified"] is False and h.verify().ok
    h.close()
