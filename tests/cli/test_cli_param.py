"""``param get/set`` (contracts §2), ``--store/--no-store`` and a whole ``history restore`` on the
simulated prosthesis (``--memory`` keeps the arbitrator's memory between commands)."""

from __future__ import annotations

import json

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.storage.history import History

HAND = "2641/769/301"


@pytest.fixture
def sim(tmp_path):
    memory = str(tmp_path / "memory.bin")
    return lambda *argv: [*argv, "--bus", "sim:transradial", "--memory", memory]


def _json(capsys) -> dict:
    return json.loads(capsys.readouterr().out)


def test_get_prints_the_contracts_document(sim, capsys):
    assert main(sim("param", "get", f"{HAND}#1", "--json")) == 0
    doc = _json(capsys)
    assert doc["part"] == {"vid": 2641, "pid": 769, "serial": 301} and doc["channel"] == 1
    p = doc["parameters"]
    assert (p["type"], p["profile"], p["descriptor"], p["data-transfer"]) == \
        ("0x9300", "0x2220", "Power grip", "on")
    assert main(sim("param", "get", HAND, "--json")) == 0
    doc = _json(capsys)
    assert doc["channel"] is None and doc["parameters"]["beacon-interval"].isdigit()


def test_get_text_names_the_channel(sim, capsys):
    assert main(sim("param", "get", f"{HAND}#1")) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0].startswith("Multi-grip hand") and "Power grip" in out


@pytest.mark.parametrize("part, why", [("2641/769/999", "no such part"),
                                       (f"{HAND}#9", "has no channel 9"),
                                       ("hand", "VID/PID/SERIAL")])
def test_a_bad_part_is_bad_input(sim, capsys, part, why):
    assert main(sim("param", "get", part)) == 2
    assert why in capsys.readouterr().err


def test_a_bad_name_or_value_is_bad_input_and_writes_nothing(sim, capsys):
    assert main(sim("param", "set", f"{HAND}#1", "colour=red", "--yes")) == 2
    assert "'colour' is not a parameter" in capsys.readouterr().err
    assert main(sim("param", "set", f"{HAND}#1", "data-transfer=maybe", "--yes")) == 2
    assert "on or off" in capsys.readouterr().err
    assert main(sim("param", "set", HAND, "node-id=3", "--yes")) == 2
    assert "read-only" in capsys.readouterr().err
    with History.open() as h:
        assert h.entries() == []


def test_set_previews_in_words_and_writes_only_with_yes(sim, capsys):
    assert main(sim("param", "set", f"{HAND}#1", "type=0x9700")) == 0
    out, err = capsys.readouterr()
    words, _, detail = out.partition("Technical detail:")
    assert "Power grip: control mode position → velocity" in words
    assert "0x9700" not in words and "0x9700" in detail
    assert "add --yes" in err
    assert main(sim("param", "get", f"{HAND}#1", "--json")) == 0
    assert _json(capsys)["parameters"]["type"] == "0x9300"


def test_set_with_yes_writes_verifies_records_and_stores(sim, capsys):
    assert main(sim("param", "set", f"{HAND}#1", "type=0x9700", "descriptor=Power grip fast",
                    "--yes", "--json")) == 0
    doc = _json(capsys)
    assert doc["written"] and doc["store"] is True
    assert doc["parameters"]["type"] == "0x9700"
    names = {p["name"]: p for p in doc["effect"]["parameters"]}
    assert names["type"]["before"] == "0x9300" and names["type"]["after"] == "0x9700"
    assert "velocity" in names["type"]["text"]
    assert doc["effect"]["stored_configuration"]["changed"] is True
    assert doc["next_power_on"]["links_added"] == [] == doc["next_power_on"]["links_removed"]
    [entry] = History.open().entries()
    assert entry["effect"]["parameters"][0]["name"] == "type"
    assert entry["parameters_after"][f"{HAND}#1"]["type"] == "0x9700"


def test_no_store_leaves_the_stored_configuration(sim, capsys):
    assert main(sim("apply", "autoconfigure", "--yes")) == 0  # nothing to change: no store
    assert main(sim("config", "save", "--yes")) == 0
    capsys.readouterr()
    assert main(sim("param", "set", f"{HAND}#1", "type=0x9700", "--yes", "--no-store",
                    "--json")) == 0
    doc = _json(capsys)
    assert doc["store"] is False and not doc["effect"]["stored_configuration"]["changed"]


def test_restore_puts_back_a_control_mode(sim, capsys):
    """The trial's failure: restoring an entry whose difference is a channel's control mode
    said "nothing to change on the prosthesis"."""
    assert main(sim("param", "set", f"{HAND}#1", "type=0x9700", "--yes")) == 0
    assert main(sim("param", "set", f"{HAND}#1", "type=0x9300", "--yes")) == 0
    capsys.readouterr()
    first = History.open().entries()[0]["id"]
    assert main(sim("history", "restore", str(first), "--json")) == 0  # preview only
    doc = _json(capsys)
    [change] = doc["effect"]["parameters"]
    assert (change["name"], change["before"], change["after"]) == ("type", "0x9300", "0x9700")
    assert main(sim("history", "restore", str(first), "--yes", "--json")) == 0
    doc = _json(capsys)  # (each sim: command opens a fresh prosthesis: check the write)
    assert doc["written"] and doc["transaction"]["verified"]
    [change] = doc["effect"]["parameters"]
    assert change["after"] == "0x9700"


def test_restore_that_needs_an_absent_part_is_refused_before_anything_is_written(
        sim, capsys):
    assert main(sim("param", "set", f"{HAND}#1", "type=0x9700", "--yes")) == 0
    capsys.readouterr()
    with History.open() as h:
        entry = h.entries()[0]
        before = len(h.entries())
    entry["id"] = 99  # an entry that names a part this prosthesis lacks
    entry["parameters_after"]["2641/769/999#1"] = {"type": "0x9300"}
    with History.open() as h:
        h.append({k: v for k, v in entry.items() if k not in ("id", "hash", "prev_hash")})
        new_id = h.entries()[-1]["id"]
    assert main(sim("history", "restore", str(new_id), "--yes")) == 1
    err = capsys.readouterr().err
    assert "refused, nothing was written" in err and "2641/769/999" in err
    with History.open() as h:
        assert len(h.entries()) == before + 1  # the appended one; no restore recorded


def test_restore_help_says_after():
    import contextlib
    import io

    out = io.StringIO()
    with contextlib.redirect_stdout(out), pytest.raises(SystemExit):
        main(["history", "restore", "--help"])
    assert "AFTER entry ID" in out.getvalue().replace("\n", " ") or \
        "after fitting history entry ID" in out.getvalue().replace("\n", " ")


def test_apply_replacements_stores_even_when_the_links_are_already_there(tmp_path, capsys):
    """The duty cycle may already have linked a spare: storing the links is what makes the
    old part's configuration go (a replacement that writes nothing stores them)."""
    from pdcp_studio.bus.session.change_road import preview_change
    from pdcp_studio.bus.session.opening import open_session
    from pdcp_studio.bus.transaction import Change

    session = open_session("sim:transradial", memory=str(tmp_path / "m.bin"))
    try:
        plan = session.preview("replacements")
        change = Change.from_plan(plan, "apply replacements")
        change.store = True
        preview = preview_change(session, change)
        assert preview.change.configuration is not None
    finally:
        session.close()
