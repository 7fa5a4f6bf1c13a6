"""The CLI on a live prosthesis (contracts §2, reference §5): ``apply MODE --bus``,
``config save``, ``config write``, ``history``, ``policy``, ``print/info --bus`` — each over
the simulated bus and over the host link (a real arbitrator behind a pseudo-terminal).

On ``sim:`` every command opens a fresh prosthesis (only ``--memory`` lasts between commands);
over ``serial:`` the arbitrator keeps running, as in a fitting room.
"""

from __future__ import annotations

import json
import os

import pytest

from pdcp_studio.bus.arbitrator.memory import MemoryStore
from pdcp_studio.cli.main import main
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link
from pdcp_studio.protocol import Release, SetParameter, Suspend
from pdcp_studio.storage.history import LIST_FIELDS, History
from tests.road_rigs import FrameRecorder, served

TEST2 = [Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2)),
         Link(ChannelRef(2, 2, 5, 3), ChannelRef(2, 2, 6, 1)),
         Link(ChannelRef(2, 2, 5, 5), ChannelRef(2, 2, 6, 2))]


class Bus:
    """One prosthesis under test: its URL, the options every command needs, its links."""

    def __init__(self, kind: str, url: str, extra: list[str], arbitrator=None,
                 memory=None) -> None:
        self.kind, self.url, self.extra = kind, url, extra
        self.arbitrator, self.memory = arbitrator, memory

    def args(self, *argv: str) -> list[str]:
        return [*argv, "--bus", self.url, *self.extra]

    def links(self, capsys) -> list[str]:
        """The live links, as ``info --bus`` lists them."""
        assert main(self.args("info")) == 0
        out = capsys.readouterr().out
        return [ln.strip() for ln in out.splitlines() if ln.strip().startswith("link ")]


@pytest.fixture(params=["sim", "serial"])
def bus(request, tmp_path):
    if request.param == "serial" and not hasattr(os, "openpty"):
        pytest.skip("needs POSIX pseudo-terminals")
    memory = tmp_path / "memory.bin"
    if request.param == "sim":
        yield Bus("sim", "sim:thesis-test2", ["--memory", str(memory)], memory=memory)
        return
    with served("thesis-test2", memory) as (arbitrator, _host, url):
        yield Bus("serial", url, [], arbitrator, memory)


def history_entries() -> list[dict]:
    with History.open() as h:
        return h.entries()


def test_apply_without_yes_prints_the_plan_and_writes_nothing(bus, capsys):
    assert main(bus.args("apply", "clear")) == 0
    out, err = capsys.readouterr()
    assert "Plan: clear — add 0, remove 3" in out
    assert "these parts are held still: Control unit board" in out
    assert "held 2/2/5" in out.split("Technical detail:")[1]
    assert "not written" in err and "--yes" in err
    assert len(bus.links(capsys)) == 3
    assert history_entries() == []


def test_apply_yes_carries_the_plan_out_and_records_it(bus, capsys):
    assert main(bus.args("apply", "clear", "--yes", "--json", "--patient", "P-42")) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["mode"] == "clear" and doc["links"] == []
    assert doc["written"] is True and doc["transaction"]["status"] == "applied"
    assert doc["transaction"]["verified"] is True
    assert doc["transaction"]["interlock"] == "held 1 device"
    if bus.kind == "serial":
        assert bus.arbitrator.system().links == []
    (entry,) = history_entries()
    assert entry["action"] == "apply clear" and entry["bus"] == bus.url
    assert entry["patient"] == "P-42" and entry["operator"] == "test prosthetist"
    assert len(entry["links_before"]) == 3 and entry["links_after"] == []
    assert main(["history", "list", "--json"]) == 0
    listed = json.loads(capsys.readouterr().out)["entries"]
    assert list(listed[0])[:len(LIST_FIELDS)] == list(LIST_FIELDS)
    assert listed[0]["devices"] == [{"vid": 2, "pid": 2, "serial": s} for s in (4, 5, 6)]


def test_apply_json_without_yes_is_one_document_and_writes_nothing(bus, capsys):
    assert main(bus.args("apply", "clear", "--json")) == 0
    out, _ = capsys.readouterr()
    doc = json.loads(out)
    assert doc["written"] is False and doc["transaction"] is None
    assert len(doc["actions"]) == 3


def test_config_save_stores_the_live_links_as_a_transaction(bus, capsys):
    assert main(bus.args("config", "save")) == 0
    assert "+ configuration 1: 2/2/4#1 → 2/2/5#2" in capsys.readouterr().out
    assert MemoryStore(bus.memory).read().configurations == []
    assert main(bus.args("config", "save", "--yes")) == 0
    out = capsys.readouterr().out
    assert "config save: applied and verified" in out and "entry 1" in out
    stored = MemoryStore(bus.memory).read()
    assert len(stored.configurations[0].links) == 3
    (entry,) = history_entries()
    assert entry["config_crc_before"] is None and entry["config_crc_after"].startswith("0x")
    assert entry["configuration_after"]["configurations"][0]["index"] == 1
    assert main(bus.args("config", "save", "--yes")) == 0  # the same again: nothing to do
    assert "nothing to change" in capsys.readouterr().out
    assert len(history_entries()) == 1


def test_config_write_goes_through_the_road_and_is_recorded(bus, capsys, tmp_path):
    assert main(bus.args("config", "save", "--yes")) == 0
    saved = MemoryStore(bus.memory).read()
    from pdcp_studio.model.configuration import ConfigCollection, StoredConfiguration
    from pdcp_studio.storage import config_codec

    one = ConfigCollection([StoredConfiguration(1, saved.configurations[0].links[:1])])
    path = tmp_path / "one.pdcfg"
    config_codec.save_path(one, path)
    capsys.readouterr()
    assert main(bus.args("config", "write", str(path))) == 2  # refused without --yes
    assert "- configuration 1: 2/2/5#3 → 2/2/6#1" in capsys.readouterr().out
    assert main(bus.args("config", "write", str(path), "--yes")) == 0
    assert "written to" in capsys.readouterr().out
    assert config_codec.dumps(MemoryStore(bus.memory).read()) == config_codec.dumps(one)
    assert [e["action"] for e in history_entries()] == ["config save",
                                                        f"config write {path}"]


def test_history_show_verify_and_restore(bus, capsys):
    assert main(bus.args("apply", "clear", "--yes")) == 0
    capsys.readouterr()
    assert main(["history", "show", "1"]) == 0
    out = capsys.readouterr().out
    assert "apply clear" in out and "links before:" in out and "clear: every link" in out
    assert main(["history", "show", "1", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["hash"]
    assert main(["history", "verify"]) == 0
    assert "1 entry, the chain is intact" in capsys.readouterr().out
    if bus.kind == "serial":  # put the links back on the running prosthesis
        for link in TEST2:
            bus.arbitrator.add_link(link)
    assert main(bus.args("history", "restore", "1")) == 0  # preview only
    assert "- link 2/2/4#1 → 2/2/5#2" in capsys.readouterr().out
    assert len(history_entries()) == 1
    assert main(bus.args("history", "restore", "1", "--yes")) == 0
    assert "applied and verified" in capsys.readouterr().out
    entries = history_entries()
    assert [e["action"] for e in entries] == ["apply clear", "history restore 1"]
    assert entries[1]["links_after"] == []
    assert main(["history", "show", "9"]) == 2


def test_history_verify_names_an_edited_entry(bus, capsys):
    import sqlite3

    assert main(bus.args("apply", "clear", "--yes")) == 0
    with History.open() as h:
        path = h.path
    db = sqlite3.connect(path)
    db.execute("UPDATE entries SET body = replace(body, 'test prosthetist', 'x') WHERE id = 1")
    db.commit()
    db.close()
    capsys.readouterr()
    assert main(["history", "verify"]) == 1
    assert "entry 1 is not intact" in capsys.readouterr().err


def test_policy_is_shown_and_changed_as_a_recorded_transaction(bus, capsys):
    assert main(bus.args("policy", "--json")) == 0
    assert json.loads(capsys.readouterr().out)["autoconfigure"] is True
    assert main(bus.args("policy", "--autoconfigure", "off")) == 0
    assert "(autoconfigure): on → off" in capsys.readouterr().out
    assert MemoryStore(bus.memory).read_policy() == {"autoconfigure": True}
    assert main(bus.args("policy", "--autoconfigure", "off", "--yes", "--json")) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["autoconfigure"] is False and doc["transaction"]["verified"] is True
    assert MemoryStore(bus.memory).read_policy() == {"autoconfigure": False}
    assert main(bus.args("policy")) == 0
    assert "autoconfigure: off" in capsys.readouterr().out
    (entry,) = history_entries()
    assert entry["action"] == "policy autoconfigure off"
    assert entry["policy_before"] == {"autoconfigure": True}
    assert entry["policy_after"] == {"autoconfigure": False}


def test_print_and_info_list_the_live_bus(bus, capsys):
    assert main(bus.args("print")) == 0
    out = capsys.readouterr().out
    assert out.startswith("n_devices: 3\nn_missing_devices: 0\n")
    assert "n_channel_links: 3" in out and "node_id: " in out
    assert main(bus.args("info")) == 0
    out = capsys.readouterr().out
    assert out.startswith("3 devices (0 missing), 8 channels, 3 links")


def test_bad_apply_arguments_are_exit_2(capsys, tmp_path):
    assert main(["apply", "clear"]) == 2
    assert main(["apply", "clear", "--system", "x.json", "--bus", "sim:thesis-test2"]) == 2
    assert main(["apply", "clear", "--bus", "sim:nope"]) == 2
    assert main(["apply", "clear", "--bus", "sim:thesis-test2", "-o", str(tmp_path / "x")]) == 2


def test_every_frame_of_apply_yes_shows_the_interlock_and_none_without_yes(monkeypatch,
                                                                           capsys, tmp_path):
    """The bus as a recorder hears it during ``apply clear`` on a simulated prosthesis."""
    import pdcp_studio.bus.session.urls as urls

    def record(argv):
        channel = f"road-cli-{len(argv)}-{os.getpid()}-{id(argv)}"
        monkeypatch.setattr(urls, "unique_virtual_channel", lambda prefix="": channel)
        recorder = FrameRecorder(channel)
        try:
            assert main(argv) == 0
            return recorder.messages()
        finally:
            recorder.close()

    def is_unlink(m) -> bool:  # writes only a removal makes (start-up only links)
        return isinstance(m, SetParameter) and (
            (m.param == P.CH_DATA_ENABLED and m.value == b"\x00")
            or (m.param == P.IN_SOURCE_NODE_IDS and m.value == b"\0\0"))

    def is_link(m) -> bool:  # what start-up writes to make a link
        return isinstance(m, SetParameter) and (
            (m.param == P.CH_DATA_ENABLED and m.value == b"\x01")
            or (m.param == P.IN_SOURCE_NODE_IDS and any(m.value)))

    quiet = record(["apply", "clear", "--bus", "sim:thesis-test2"])
    assert not [m for m in quiet if is_unlink(m)]
    # Start-up's own interlock holds the prosthesis while it links (reference §5); after
    # start-up's last link nothing is held again without --yes.
    last_link = max(i for i, m in enumerate(quiet) if is_link(m))
    assert not [m for m in quiet[last_link:] if isinstance(m, Suspend)]
    frames = record(["apply", "clear", "--bus", "sim:thesis-test2", "--yes"])
    suspends = [i for i, m in enumerate(frames) if isinstance(m, Suspend)]
    releases = [i for i, m in enumerate(frames) if isinstance(m, Release)]
    writes = [i for i, m in enumerate(frames) if is_unlink(m)]
    assert suspends and releases and writes
    assert suspends[0] < writes[0] and writes[-1] < releases[-1]
    assert all(frames[i].ms == 2000 for i in suspends)
