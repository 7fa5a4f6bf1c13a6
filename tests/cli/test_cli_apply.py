"""``pdcp-studio apply MODE --system FILE [--config CFG] -o NEW.json``."""

from __future__ import annotations

import json
from pathlib import Path

from pdcp_studio.cli.main import main
from pdcp_studio.engine import check_system, configuration_from_system
from pdcp_studio.model import ChannelRef, ConfigCollection
from pdcp_studio.storage import config_codec, system_file

SYSTEMS = Path(__file__).resolve().parents[2] / "resources" / "systems"
APPENDIX_D = system_file.load_path(SYSTEMS / "appendix-d.json").links


def test_apply_autoconfigure_writes_the_configured_system(capsys, tmp_path):
    new = tmp_path / "new.json"
    src = SYSTEMS / "thesis-test2.json"
    before = src.read_bytes()
    assert main(["apply", "autoconfigure", "--system", str(src), "-o", str(new)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("Plan: autoconfigure — add 3, remove 0")
    assert "Links after the plan" not in out  # a summary: the file has the links
    assert out.rstrip().endswith(f"wrote {new}: 3 link(s)")
    assert src.read_bytes() == before
    s = system_file.load_path(new)
    assert s.links == APPENDIX_D
    # The inputs store their sources (redundant storage), so a new arbitrator can rebuild.
    assert s.channel(ChannelRef(2, 2, 6, 1)).source.ref == ChannelRef(2, 2, 5, 3)
    assert check_system(s) == []


def test_apply_startup_with_a_stored_configuration(capsys, tmp_path):
    cfg = tmp_path / "arbitrator.pdcfg"
    config_codec.save_path(
        ConfigCollection([configuration_from_system(system_file.load_path(
            SYSTEMS / "appendix-d.json"))]), cfg)
    new = tmp_path / "new.json"
    assert main(["apply", "startup", "--system", str(SYSTEMS / "thesis-test3.json"),
                 "--config", str(cfg), "-o", str(new), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["mode"] == "startup" and doc["configuration"]["source"] == "stored"
    assert system_file.load_path(new).links == APPENDIX_D


def test_apply_clear_then_startup_rebuilds_from_the_devices(capsys, tmp_path):
    """Thesis test 5 through the command line: a replaced arbitrator."""
    cleared, rebuilt = tmp_path / "cleared.json", tmp_path / "rebuilt.json"
    # Clearing keeps nothing; a reset keeps the devices' stored sources, so drop only links.
    doc = json.loads((SYSTEMS / "appendix-d.json").read_text())
    doc["links"] = []
    cleared.write_text(json.dumps(doc))
    assert main(["apply", "startup", "--system", str(cleared), "-o", str(rebuilt)]) == 0
    assert "Configuration (retrieved)" in capsys.readouterr().out
    assert system_file.load_path(rebuilt).links == APPENDIX_D


def test_bad_config_exits_2_and_writes_nothing(capsys, tmp_path):
    bad = tmp_path / "bad.pdcfg"
    bad.write_bytes(b"\x01\x01\x00")
    new = tmp_path / "new.json"
    assert main(["apply", "startup", "--system", str(SYSTEMS / "appendix-d.json"),
                 "--config", str(bad), "-o", str(new)]) == 2
    err = capsys.readouterr().err
    assert "bad.pdcfg" in err and "offset" in err
    assert not new.exists()


def test_unwritable_output_exits_2_naming_it(capsys, tmp_path):
    new = tmp_path / "no" / "such" / "dir" / "new.json"
    assert main(["apply", "clear", "--system", str(SYSTEMS / "appendix-d.json"),
                 "-o", str(new)]) == 2
    assert str(new) in capsys.readouterr().err


def test_bad_system_exits_2(capsys, tmp_path):
    assert main(["apply", "clear", "--system", str(tmp_path / "none.json"),
                 "-o", str(tmp_path / "new.json")]) == 2
    assert "none.json" in capsys.readouterr().err
