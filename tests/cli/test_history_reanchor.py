"""``history re-anchor``: a prosthesis whose fitting history is lost for good is tied to the
archive in use again — previewed, confirmed with a reason, recorded, then anchored; a damaged
chain is never re-anchored onto (issue 28, docs/decisions.md)."""

from __future__ import annotations

import sqlite3

import pytest

from pdcp_studio.bus.arbitrator.memory import MemoryStore
from pdcp_studio.cli.main import main
from pdcp_studio.storage.archive.chain import Anchor
from pdcp_studio.storage.history import History
from tests.road_rigs import fitted_twice

BUS = "sim:transradial"


@pytest.fixture
def fitted(tmp_path, monkeypatch):
    """A prosthesis fitted twice, both changes recorded and anchored."""
    return fitted_twice(tmp_path, monkeypatch, BUS)


@pytest.fixture
def lost(fitted):
    """The fitted prosthesis's archive lost (removed): a new, empty archive takes its place."""
    archive, memory = fitted
    archive.unlink()
    for extra in archive.parent.glob("history.sqlite-*"):
        extra.unlink()
    return archive, memory


def _run(capsys, *argv: str) -> tuple[int, str]:
    capsys.readouterr()
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out + err


def test_a_lost_history_is_re_anchored_on_the_record_and_changes_go_on(lost, capsys):
    archive, memory = lost
    change = ("apply", "clear", "--bus", BUS, "--memory", str(memory), "--yes")
    code, text = _run(capsys, *change)
    assert code == 1 and "does not verify" in text  # refused before
    remembered = MemoryStore(memory).read_anchor()
    assert remembered is not None and remembered.entry == 2

    # the preview: what the prosthesis remembers, what the archive lacks; nothing written
    code, text = _run(capsys, "history", "re-anchor", "--bus", BUS, "--memory", str(memory))
    assert code == 0 and "remembers entry 2" in text and "Nothing written" in text
    assert MemoryStore(memory).read_anchor() == remembered
    # --yes wants a reason
    code, text = _run(capsys, "history", "re-anchor", "--bus", BUS, "--memory", str(memory),
                      "--yes")
    assert code == 2 and "--reason" in text
    assert MemoryStore(memory).read_anchor() == remembered

    code, text = _run(capsys, "history", "re-anchor", "--bus", BUS, "--memory", str(memory),
                      "--yes", "--reason", "workstation disk failed, no backup")
    assert code == 0 and "Re-anchored: entry 1" in text
    with History(archive) as h:
        [entry] = h.entries()
    assert entry["action"] == "history re-anchored"
    assert entry["re_anchor"]["previous"]["entry"] == 2
    assert entry["re_anchor"]["reason"] == "workstation disk failed, no backup"
    assert entry["operator"] and entry["devices"]
    assert MemoryStore(memory).read_anchor() == Anchor(1, entry["hash"])

    code, text = _run(capsys, "history", "verify", "--bus", BUS, "--memory", str(memory))
    assert code == 0
    code, text = _run(capsys, *change)  # changes go on, recorded after the re-anchor
    assert code == 0
    with History(archive) as h:
        actions = [e["action"] for e in h.entries()]
    assert len(actions) == 2 and actions[0] == "history re-anchored"
    # and a second re-anchor finds nothing to do
    code, text = _run(capsys, "history", "re-anchor", "--bus", BUS, "--memory", str(memory))
    assert code == 0 and "nothing to re-anchor" in text


def test_a_damaged_chain_is_never_re_anchored_onto(fitted, capsys):
    archive, memory = fitted
    db = sqlite3.connect(str(archive), isolation_level=None)
    db.execute("UPDATE entries SET body = replace(body, 'apply', 'APPLY') WHERE id = 1")
    db.close()
    before = MemoryStore(memory).read_anchor()
    code, text = _run(capsys, "history", "re-anchor", "--bus", BUS, "--memory", str(memory),
                      "--yes", "--reason", "try")
    assert code == 1 and "entry 1 is not intact" in text and "Traceback" not in text
    assert MemoryStore(memory).read_anchor() == before
    with History(archive) as h:
        assert len(h.entries()) == 2  # nothing appended
