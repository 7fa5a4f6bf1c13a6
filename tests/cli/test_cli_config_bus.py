"""``config read --bus URL -o FILE`` and ``config write FILE --bus URL --yes``."""

from __future__ import annotations

from pathlib import Path

from pdcp_studio.bus.arbitrator.memory import MemoryStore
from pdcp_studio.cli.main import main
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.storage import config_codec

ROOT = Path(__file__).resolve().parents[2]
FIG410 = ROOT / "resources" / "configs" / "fig410.pdcfg"




def _test2_link_file(path: Path) -> Path:
    link = StoredLink(StoredChannel(2, 2, 2, 5, 0x5200, 0x2110),
                      StoredChannel(1, 2, 2, 4, 0x5000, 0x2120), 1)
    config_codec.save_path(ConfigCollection([StoredConfiguration(1, [link])]), path)
    return path


def test_write_without_yes_shows_the_difference_and_refuses(capsys, tmp_path):
    memory = tmp_path / "arb.mem"
    code = main(["config", "write", str(FIG410), "--bus", "sim:thesis-test2",
                 "--memory", str(memory)])
    out, err = capsys.readouterr()
    assert code == 2
    assert "stored now: 0 configuration(s), 0 link(s); to write: 2 configuration(s)" in out
    assert "+ configuration 1: 30/40/50#1 → 30/40/50#1" in out
    assert "--yes" in err and "not written" in err
    assert not MemoryStore(memory).read().configurations


def test_write_yes_then_read_back(capsys, tmp_path):
    memory = tmp_path / "arb.mem"
    cfg = _test2_link_file(tmp_path / "one.pdcfg")
    assert main(["config", "write", str(cfg), "--bus", "sim:thesis-test2",
                 "--memory", str(memory), "--yes"]) == 0
    out = capsys.readouterr().out
    assert "+ configuration 1: 2/2/4#1 → 2/2/5#2" in out and "verified" in out
    saved = tmp_path / "read.pdcfg"
    assert main(["config", "read", "--bus", "sim:thesis-test2", "--memory", str(memory),
                 "-o", str(saved)]) == 0
    assert saved.read_bytes() == cfg.read_bytes()
    # Writing the same again: no link changes.
    assert main(["config", "write", str(cfg), "--bus", "sim:thesis-test2",
                 "--memory", str(memory), "--yes"]) == 0
    assert "no link changes" in capsys.readouterr().out


def test_read_of_an_empty_memory(capsys, tmp_path):
    saved = tmp_path / "empty.pdcfg"
    assert main(["config", "read", "--bus", "sim:thesis-test1", "-o", str(saved)]) == 0
    assert "0 configuration(s), 0 link(s)" in capsys.readouterr().out
    assert config_codec.load_path(saved).configurations == []


def test_a_bad_file_is_refused_before_the_bus_is_opened(capsys, tmp_path):
    bad = tmp_path / "bad.pdcfg"
    bad.write_bytes(b"\x01\x01\x00\x02")
    assert main(["config", "write", str(bad), "--bus", "sim:thesis-test2", "--yes"]) == 2
    err = capsys.readouterr().err
    assert "bad.pdcfg" in err and "offset" in err
    assert main(["config", "write", str(tmp_path / "none.pdcfg"), "--bus",
                 "sim:thesis-test2"]) == 2


def test_a_failed_verification_is_exit_1(capsys, tmp_path, monkeypatch):
    from pdcp_studio.bus.arbitrator.core import Arbitrator

    monkeypatch.setattr(Arbitrator, "read_memory", lambda self: ConfigCollection())
    cfg = _test2_link_file(tmp_path / "one.pdcfg")
    assert main(["config", "write", str(cfg), "--bus", "sim:thesis-test2", "--yes"]) == 1
    assert "does not verify" in capsys.readouterr().err
