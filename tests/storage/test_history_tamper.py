"""Issue 28 item 2: every row read defensively. An archive file edited by hand — bad JSON, a
body that is not an object, missing keys, wrong types, huge integers, deleted or swapped rows,
a damaged head, injected pending rows — gives exit 1 naming the entry in ``history list``,
``show``, ``verify``, ``export`` and ``restore``: never a traceback. IDs no entry can have are
exit 2 in words."""

from __future__ import annotations

import json
import sqlite3

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.storage.history import History

HAND = {"vid": 2641, "pid": 769, "serial": 301}
LINK = {"output": {"vid": 2641, "pid": 513, "serial": 201, "index": 3},
        "input": {"vid": 2641, "pid": 769, "serial": 301, "index": 1}}


def body(n: int) -> dict:
    return {"time": f"2026-11-28T10:0{n}:00Z", "operator": "op", "bus": "sim:transradial",
            "action": f"apply clear {n}", "devices": [HAND], "links_before": [LINK],
            "links_after": [], "config_crc_before": None, "config_crc_after": None,
            "verified": True, "interlock": "not needed", "patient": "P-1",
            "outcome": {"status": "applied", "step": "", "reason": "", "notes": []},
            "effect": {"text": ["Link removed: a → b"], "technical": ["- link x"]},
            "plan": {"actions": [{"op": "remove", **LINK, "reason": "clear"}]}}


def edit_body(n: int, change) -> callable:
    """A tamper that rewrites entry ``n``'s body (its hash left as it was)."""
    def run(db: sqlite3.Connection) -> None:
        db.execute("DROP INDEX IF EXISTS entries_patient")  # it would refuse malformed JSON
        doc = json.loads(db.execute("SELECT body FROM entries WHERE id = ?", (n,)).fetchone()[0])
        doc = change(doc)
        db.execute("UPDATE entries SET body = ? WHERE id = ?",
                   (doc if isinstance(doc, str | bytes) else json.dumps(doc), n))
    return run


def sql(*statements: str) -> callable:
    def run(db: sqlite3.Connection) -> None:
        for s in statements:
            db.execute(s)
    return run


def _set(key, value):
    return lambda d: {**d, key: value}


def _drop(key):
    return lambda d: {k: v for k, v in d.items() if k != key}


#: (name, tamper, the entry verify names) — each one a way an editor breaks the archive.
DAMAGE = [
    ("delete newest", sql("DELETE FROM entries WHERE id = 3"), 3),
    ("delete middle", sql("DELETE FROM entries WHERE id = 2"), 2),
    ("delete first", sql("DELETE FROM entries WHERE id = 1"), 1),
    ("delete head row", sql("DELETE FROM head"), 1),
    ("head id as text", sql("UPDATE head SET last_id = 'three'"), 3),
    ("head id huge", sql("UPDATE head SET last_id = 9223372036854775807"), 4),
    ("head hash as number", sql("UPDATE head SET last_hash = 7"), 3),
    ("edit a field", edit_body(2, _set("operator", "someone else")), 2),
    ("bad JSON", edit_body(2, lambda d: "{not json"), 2),
    ("JSON list", edit_body(2, lambda d: "[1, 2]"), 2),
    ("JSON text", edit_body(2, lambda d: '"a string"'), 2),
    ("JSON number", edit_body(2, lambda d: "12345678901234567890123"), 2),
    ("JSON null", edit_body(2, lambda d: "null"), 2),
    ("deep JSON", edit_body(2, lambda d: "[" * 100000 + "]" * 100000), 2),
    ("body as blob", edit_body(2, lambda d: b"\xff\xfe not utf-8"), 2),
    ("missing time", edit_body(2, _drop("time")), 2),
    ("missing action", edit_body(2, _drop("action")), 2),
    ("missing devices", edit_body(2, _drop("devices")), 2),
    ("missing links before", edit_body(2, _drop("links_before")), 2),
    ("missing verified", edit_body(2, _drop("verified")), 2),
    ("time is null", edit_body(2, _set("time", None)), 2),
    ("operator is a number", edit_body(2, _set("operator", 7)), 2),
    ("devices a record", edit_body(2, _set("devices", {"vid": 1})), 2),
    ("device a list", edit_body(2, _set("devices", [[1, 2, 3]])), 2),
    ("device vid text", edit_body(2, _set("devices", [{**HAND, "vid": "x"}])), 2),
    ("device vid huge", edit_body(2, _set("devices", [{**HAND, "vid": 10 ** 30}])), 2),
    ("device lacks serial", edit_body(2, _set("devices", [{"vid": 1, "pid": 2}])), 2),
    ("links before text", edit_body(2, _set("links_before", "none")), 2),
    ("link lacks output", edit_body(2, _set("links_before", [{"input": LINK["input"]}])), 2),
    ("link index huge", edit_body(2, _set("links_after", [
        {**LINK, "input": {**LINK["input"], "index": 2 ** 70}}])), 2),
    ("links after text", edit_body(2, _set("links_after", "x")), 2),
    ("verified text", edit_body(2, _set("verified", "yes")), 2),
    ("outcome a list", edit_body(2, _set("outcome", ["applied"])), 2),
    ("outcome status number", edit_body(2, _set("outcome", {"status": 1})), 2),
    ("effect text a number", edit_body(2, _set("effect", {"text": 5})), 2),
    ("plan actions text", edit_body(2, _set("plan", {"actions": "all"})), 2),
    ("plan action without op", edit_body(2, _set("plan", {"actions": [{"x": 1}]})), 2),
    ("origin text", edit_body(2, _set("origin", "elsewhere")), 2),
    ("id moved", sql("UPDATE entries SET id = 7 WHERE id = 3"), 3),
    ("hash as number", sql("UPDATE entries SET hash = 5 WHERE id = 2"), 2),
    ("previous hash as number", sql("UPDATE entries SET previous_hash = 5 WHERE id = 2"), 2),
    ("swap two bodies", sql(
        "UPDATE entries SET body = (SELECT body FROM entries WHERE id = 3) WHERE id = 2"), 2),
    ("id huge", sql("UPDATE entries SET id = 9223372036854775807 WHERE id = 3"), 3),
]


@pytest.fixture
def archive(tmp_path, monkeypatch):
    path = tmp_path / "history.sqlite"
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(path))
    monkeypatch.delenv("PDCP_STUDIO_ARCHIVE", raising=False)
    with History(path) as h:
        for n in (1, 2, 3):
            h.append(body(n))
    return path


def tamper(path, how) -> None:
    db = sqlite3.connect(str(path), isolation_level=None)
    try:
        how(db)
    finally:
        db.close()


COMMANDS = [["history", "list"], ["history", "list", "--json"], ["history", "show", "1"],
            ["history", "show", "2"], ["history", "show", "3"], ["history", "show", "2", "--json"],
            ["history", "export"], ["history", "restore", "2", "--bus", "sim:transradial"]]


@pytest.mark.parametrize(("name", "how", "bad"), DAMAGE, ids=[d[0] for d in DAMAGE])
def test_damage_is_exit_1_naming_the_entry_never_a_traceback(archive, capsys, name, how, bad):
    tamper(archive, how)
    assert main(["history", "verify"]) == 1
    err = capsys.readouterr().err
    assert f"entry {bad}" in err and "Traceback" not in err
    for argv in COMMANDS:
        code = main(argv)  # a traceback here fails the test
        _out, err = capsys.readouterr()
        assert code in (0, 1, 2), (argv, code)
        if code == 1:
            assert "entry" in err, (argv, err)


@pytest.mark.parametrize("kind", ["bad JSON", "JSON list", "missing time", "device vid text",
                                  "outcome a list", "verified text", "body as blob"])
def test_list_and_show_name_the_damaged_entry(archive, capsys, kind):
    how = dict((d[0], d[1]) for d in DAMAGE)[kind]
    tamper(archive, how)
    assert main(["history", "list"]) == 1
    assert "entry 2 is damaged" in capsys.readouterr().err
    assert main(["history", "show", "2"]) == 1
    assert "entry 2 is damaged" in capsys.readouterr().err
    assert main(["history", "show", "1"]) == 0  # the others are still read
    capsys.readouterr()
    assert main(["history", "restore", "2", "--bus", "sim:transradial"]) == 1
    assert "entry 2 is damaged" in capsys.readouterr().err


@pytest.mark.parametrize("typed", ["9223372036854775808", "99999999999999999999999", "0", "-1",
                                   "1e3", "x", ""])
def test_an_id_no_entry_can_have_is_exit_2_in_words(archive, capsys, typed):
    with pytest.raises(SystemExit) as stop:
        main(["history", "show", typed])
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert "entry" in err and "Traceback" not in err
    assert main(["history", "show", "9223372036854775807"]) == 2  # in range, not there
    assert "no entry 9223372036854775807" in capsys.readouterr().err


def _pending(path, token: str, text, pid: int = 999999999, host: str = "elsewhere") -> None:
    tamper(path, lambda db: db.execute(
        "INSERT INTO pending (token, pid, host, body) VALUES (?, ?, ?, ?)",
        (token, pid, host, text)))


@pytest.mark.parametrize("text", ["{not json", "[]", json.dumps({"action": "x"}),
                                  json.dumps({**body(9)})])  # the last: not "interrupted"
def test_damaged_or_foreign_pending_rows_are_never_chained_in(archive, capsys, text):
    _pending(archive, "f" * 32, text)
    assert main(["history", "list", "--json"]) == 0
    assert [e["id"] for e in json.loads(capsys.readouterr().out)["entries"]] == [1, 2, 3]
    assert main(["history", "verify"]) == 0


def test_a_recovered_announcement_keeps_its_token(archive, capsys):
    from pdcp_studio.storage.history import interrupted

    _pending(archive, "a" * 32, json.dumps(interrupted(body(4))))
    with History(archive) as h:
        assert h.recover() == [4]
        assert h.get(4)["announcement"] == "a" * 32
        assert h.get(4)["outcome"]["status"] == "interrupted"


def test_a_zero_byte_archive_reads_as_empty(archive, capsys):
    archive.write_bytes(b"")
    assert main(["history", "verify"]) == 0
    assert "0 entries" in capsys.readouterr().out
    assert main(["history", "list"]) == 0
