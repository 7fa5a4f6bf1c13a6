"""Issue 28 item 2, reference §5 Decision: the fitting history's head is anchored in the
arbitrator's memory. The transaction that records a change writes that entry's id and hash
beside the stored configuration (the memory image, under its CRC; the host link's
ANCHOR_READ/ANCHOR_WRITE); ``history verify --bus`` compares; a change refuses an archive that
does not verify — after the newest entry is deleted (head repaired or not), after the chain is
edited and re-hashed, with an empty or 0-byte archive, with injected pending rows."""

from __future__ import annotations

import json
import sqlite3

import pytest

from pdcp_studio.bus.arbitrator.memory import FLAG_ANCHOR, HEADER_SIZE, MemoryStore
from pdcp_studio.cli.main import main
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.storage.archive.anchor import anchor_problem
from pdcp_studio.storage.archive.chain import Anchor, canonical, entry_hash
from pdcp_studio.storage.history import History, interrupted
from tests.road_rigs import fitted_twice

BUS = "sim:transradial"
HAND = {"vid": 2641, "pid": 769, "serial": 301}


# -- the memory image ------------------------------------------------------------------------
def test_the_anchor_is_kept_in_the_slot_beside_configuration_and_policy(tmp_path):
    path = tmp_path / "m.img"
    memory = MemoryStore(path)
    memory.write(ConfigCollection())
    assert memory.read_anchor() is None  # an image without an anchor reads as before
    memory.write_policy({"autoconfigure": False})
    memory.write_anchor(Anchor(3, "ab" * 32))
    memory.write(ConfigCollection())  # a configuration write keeps it
    memory.write_policy({"autoconfigure": False})  # and a policy write
    again = MemoryStore(path)
    assert again.read_anchor() == Anchor(3, "ab" * 32)
    assert again.read_policy() == {"autoconfigure": False}
    assert again.read() == ConfigCollection()


def test_an_image_written_before_anchors_reads_unchanged(tmp_path):
    path = tmp_path / "m.img"
    MemoryStore(path).write(ConfigCollection())
    raw = path.read_bytes()
    flags = int.from_bytes(raw[6:8], "little")
    assert not flags & FLAG_ANCHOR  # no anchor written: the old layout, byte for byte
    memory = MemoryStore(path)
    assert memory.read_anchor() is None and memory.generation == 1


def test_the_anchor_is_covered_by_the_slots_crc(tmp_path):
    path = tmp_path / "m.img"
    memory = MemoryStore(path, capacity=4096)
    memory.write_anchor(Anchor(1, "11" * 32))  # generation 1, slot A
    memory.write_anchor(Anchor(2, "22" * 32))  # generation 2, slot B
    raw = bytearray(path.read_bytes())
    slot_b = HEADER_SIZE + 4096
    length = int.from_bytes(raw[slot_b + 16:slot_b + 20], "little")
    raw[slot_b + HEADER_SIZE + length + 9] ^= 0xFF  # one byte of B's anchor hash
    path.write_bytes(bytes(raw))
    damaged = MemoryStore(path, capacity=4096)
    assert damaged.read_anchor() == Anchor(1, "11" * 32)  # the older, whole slot
    damaged.read()
    assert any("slot B is damaged" in w for w in damaged.warnings)


def test_a_power_cut_in_the_anchor_write_leaves_the_old_anchor(tmp_path):
    path = tmp_path / "m.img"
    MemoryStore(path).write_anchor(Anchor(1, "11" * 32))

    class Cut(Exception):
        pass

    def cut(step: str) -> None:
        if step == "anchor":
            raise Cut

    with pytest.raises(Cut):
        MemoryStore(path, step_hook=cut).write_anchor(Anchor(2, "22" * 32))
    assert MemoryStore(path).read_anchor() == Anchor(1, "11" * 32)


# -- the change road and `history verify --bus` ----------------------------------------------
@pytest.fixture
def fitted(tmp_path, monkeypatch):
    """A simulated prosthesis with its memory file and archive, after two recorded changes."""
    archive, memory = fitted_twice(tmp_path, monkeypatch, BUS)
    with History(archive) as h:
        assert [e["id"] for e in h.entries()] == [1, 2]
    return archive, memory


def _verify(memory, capsys) -> tuple[int, str]:
    capsys.readouterr()
    code = main(["history", "verify", "--bus", BUS, "--memory", str(memory)])
    out, err = capsys.readouterr()
    return code, out + err


def _change(memory, capsys) -> tuple[int, str]:
    capsys.readouterr()
    code = main(["apply", "clear", "--bus", BUS, "--memory", str(memory), "--yes"])
    out, err = capsys.readouterr()
    return code, out + err


def test_a_change_anchors_its_entry_in_the_memory(fitted, capsys):
    archive, memory = fitted
    with History(archive) as h:
        last = h.entries()[-1]
    assert MemoryStore(memory).read_anchor() == Anchor(last["id"], last["hash"])
    code, text = _verify(memory, capsys)
    assert code == 0 and f"remembers entry {last['id']}, hash {last['hash']}" in text


def _delete_newest(archive, *, repair_head: bool) -> None:
    db = sqlite3.connect(str(archive), isolation_level=None)
    last = db.execute("SELECT max(id) FROM entries").fetchone()[0]
    db.execute("DELETE FROM entries WHERE id = ?", (last,))
    if repair_head:
        row = db.execute("SELECT id, hash FROM entries ORDER BY id DESC LIMIT 1").fetchone()
        if row is None:
            db.execute("DELETE FROM head")
        else:
            db.execute("UPDATE head SET last_id = ?, last_hash = ?", row)
    db.close()


@pytest.mark.parametrize("repair_head", [False, True])
def test_deleting_the_newest_entry_then_an_ordinary_change_is_refused(fitted, capsys,
                                                                       repair_head):
    archive, memory = fitted
    anchored = MemoryStore(memory).read_anchor()
    _delete_newest(archive, repair_head=repair_head)
    code, text = _verify(memory, capsys)
    assert code == 1 and "entr" in text and "Traceback" not in text
    before = MemoryStore(memory).generation
    code, text = _change(memory, capsys)
    assert code == 1 and "does not verify" in text and "nothing was written" in text.lower()
    assert "history verify --bus" in text  # and how to go on
    assert MemoryStore(memory).generation == before  # nothing was written to the prosthesis
    assert MemoryStore(memory).read_anchor() == anchored
    code, text = _verify(memory, capsys)  # and verify still fails after the refused change
    assert code == 1
    with History(archive) as h:
        assert len(h.entries()) == anchored.entry - 1  # nothing appended


def test_a_chain_edited_and_rehashed_fails_against_the_anchor(fitted, capsys):
    archive, memory = fitted
    db = sqlite3.connect(str(archive), isolation_level=None)
    db.execute("DROP INDEX IF EXISTS entries_patient")
    previous = "0" * 64
    for entry_id, body in db.execute("SELECT id, body FROM entries ORDER BY id").fetchall():
        doc = json.loads(body)
        doc["operator"] = "somebody else"
        text = json.dumps(doc)
        digest = entry_hash(entry_id, previous, canonical(doc))
        db.execute("UPDATE entries SET body = ?, previous_hash = ?, hash = ? WHERE id = ?",
                   (text, previous, digest, entry_id))
        previous = digest
    db.execute("UPDATE head SET last_hash = ?", (previous,))
    db.close()
    assert main(["history", "verify"]) == 0  # the chain alone cannot tell
    code, text = _verify(memory, capsys)
    assert code == 1 and "re-hashed" in text and "entry 2" in text
    code, text = _change(memory, capsys)
    assert code == 1 and "does not verify" in text


@pytest.mark.parametrize("how", ["zero bytes", "removed", "emptied"])
def test_an_empty_archive_whose_prosthesis_remembers_entries_fails(fitted, capsys, how):
    archive, memory = fitted
    if how == "zero bytes":
        for extra in archive.parent.glob("history.sqlite-*"):
            extra.unlink()
        archive.write_bytes(b"")
    elif how == "removed":
        archive.unlink()
    else:
        db = sqlite3.connect(str(archive), isolation_level=None)
        db.execute("DELETE FROM entries")
        db.execute("DELETE FROM head")
        db.close()
    code, text = _verify(memory, capsys)
    assert code == 1 and "remembers entry 2" in text
    code, text = _change(memory, capsys)
    assert code == 1 and "does not verify" in text


def test_an_injected_pending_row_is_caught_by_the_anchor(fitted, capsys):
    archive, memory = fitted
    fake = interrupted({"time": "2026-11-28T10:00:00Z", "operator": "x", "bus": BUS,
                        "action": "apply clear", "devices": [HAND], "links_before": [],
                        "links_after": [], "verified": True, "interlock": None})
    db = sqlite3.connect(str(archive), isolation_level=None)
    db.execute("INSERT INTO pending (token, pid, host, body) VALUES (?, ?, ?, ?)",
               ("e" * 32, 999999999, "elsewhere", json.dumps(fake)))
    db.close()
    code, text = _verify(memory, capsys)  # recovered as entry 3, which the prosthesis never saw
    assert code == 1 and "entry 3" in text and "does not know" in text


def test_a_pc_stopped_between_record_and_anchor_is_still_accepted(fitted, capsys):
    """The announcement the memory took before the write names the one entry it may lack."""
    archive, memory = fitted
    anchored = MemoryStore(memory).read_anchor()
    with History(archive) as h:
        body = {k: v for k, v in h.entries()[-1].items()
                if k not in ("id", "hash", "previous_hash")}
        h.append({**body, "announcement": "c" * 32})
    MemoryStore(memory).write_anchor(Anchor(anchored.entry, anchored.hash, "c" * 32))
    code, text = _verify(memory, capsys)
    assert code == 0, text
    code, text = _change(memory, capsys)  # the next change anchors past it
    assert code == 0, text
    with History(archive) as h:
        last = h.entries()[-1]
    assert MemoryStore(memory).read_anchor() == Anchor(last["id"], last["hash"])


# -- the comparison on both engines ----------------------------------------------------------
def _body(n: int, devices=(HAND,)) -> dict:
    return {"time": "2026-11-28T10:00:00Z", "bus": BUS, "action": f"apply clear {n}",
            "devices": list(devices), "links_before": [], "links_after": [],
            "verified": True, "interlock": "not needed"}


def test_the_anchor_comparison_on_both_engines(archive_url):
    from pdcp_studio.storage.archive import open_archive
    from pdcp_studio.storage.archive.anchor import check

    other = {"vid": 1, "pid": 2, "serial": 3}
    parts = {(2641, 769, 301)}
    with open_archive(archive_url) as a:
        assert check(a, Anchor(1, "00" * 32), parts) is not None  # empty: remembers entry 1
        a.append(_body(1))
        a.append(_body(2, devices=(other,)))  # another prosthesis's entry
        first = a.get(1)
        assert check(a, Anchor(1, first["hash"]), parts) is None
        assert "re-hashed" in check(a, Anchor(1, "00" * 32), parts)
        a.append(_body(3))
        assert "entry 3" in check(a, Anchor(1, first["hash"]), parts)
        assert check(a, Anchor(3, a.get(3)["hash"]), parts) is None
        assert check(a, None, parts) is None  # an arbitrator that keeps none


def test_anchor_problem_allows_only_the_announced_entry():
    entries = [{"id": 1, "hash": "a", "devices": [HAND]},
               {"id": 2, "hash": "b", "devices": [HAND], "announcement": "t"}]
    assert anchor_problem(entries, Anchor(1, "a", "t"), set()) is None
    assert "entry 2" in anchor_problem(entries, Anchor(1, "a", "u"), set())
    assert "entry 2" in anchor_problem(entries, Anchor(1, "a"), set())
    assert anchor_problem([*entries, {"id": 3, "hash": "c", "devices": [HAND],
                                      "announcement": "t"}], Anchor(1, "a", "t"), set())


# -- the host link ---------------------------------------------------------------------------
def test_the_anchor_over_the_host_link(tmp_path, monkeypatch, capsys):
    from pdcp_studio.bus.hostlink.client import open_hostlink_session
    from pdcp_studio.bus.session.urls import parse_bus_url
    from tests.road_rigs import served

    archive = tmp_path / "history.sqlite"
    monkeypatch.setenv("PDCP_STUDIO_HISTORY", str(archive))
    monkeypatch.delenv("PDCP_STUDIO_ARCHIVE", raising=False)
    with served("transradial", tmp_path / "m.img") as (arbitrator, _host, url):
        session = open_hostlink_session(parse_bus_url(url))
        try:
            assert session.read_anchor() is None
            assert session.write_anchor(Anchor(7, "77" * 32, "d" * 32)) == \
                Anchor(7, "77" * 32, "d" * 32)
            assert arbitrator.read_anchor() == Anchor(7, "77" * 32, "d" * 32)
            session.write_anchor(Anchor(0, ""))
        finally:
            session.close()
        assert main(["apply", "clear", "--bus", url, "--yes"]) == 0
        with History(archive) as h:
            last = h.entries()[-1]
        assert arbitrator.read_anchor() == Anchor(last["id"], last["hash"])
        assert MemoryStore(tmp_path / "m.img").read_anchor() == Anchor(last["id"], last["hash"])
        capsys.readouterr()
        assert main(["history", "verify", "--bus", url]) == 0
        assert f"remembers entry {last['id']}" in capsys.readouterr().out
        _delete_newest(archive, repair_head=True)
        assert main(["history", "verify", "--bus", url]) == 1
        assert main(["apply", "autoconfigure", "--bus", url, "--yes"]) == 1
        assert "does not verify" in capsys.readouterr().err
