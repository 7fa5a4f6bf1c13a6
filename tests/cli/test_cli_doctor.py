"""``pdcp-studio doctor [--json]`` (contracts §2): what a clinic sends to support."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import can.interfaces

from pdcp_studio.cli import doctor
from pdcp_studio.cli.main import main


def _doc(capsys, monkeypatch, **env) -> dict:
    for k, v in env.items():
        monkeypatch.setenv(k, v)
    assert main(["doctor", "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_json_has_the_contract_keys_every_module_and_every_interface(capsys, monkeypatch,
                                                                     tmp_path):
    archive = tmp_path / "h.sqlite"
    doc = _doc(capsys, monkeypatch, PDCP_STUDIO_HISTORY=str(archive))
    from pdcp_studio import __version__

    assert doc["version"] == __version__
    assert set(doc["can_interfaces"]) == set(can.interfaces.BACKENDS)
    assert doc["can_interfaces"]["virtual"] == {"driver": True}
    for name, entry in doc["can_interfaces"].items():
        assert isinstance(entry["driver"], bool), name
        if not entry["driver"]:
            assert entry["why"] and entry["fix"], name
    assert doc["modules"] and all(doc["modules"].values()), doc["module_errors"]
    for name in ("pdcp_studio.app.dialogs.connect_dialog", "pdcp_studio.app.trace.dock",
                 "pdcp_studio.app.live.plot", "pdcp_studio.app.docks.sim_panel",
                 "pdcp_studio.app.dialogs.compare_dialog", "pdcp_studio.app.dialogs.write_config_dialog",
                 "pdcp_studio.app.dialogs.profile_tree_editor", "pdcp_studio.app.report",
                 "pdcp_studio.cli.doctor", "pdcp_studio.bus.arbitrator.core"):
        assert doc["modules"][name] is True
    assert (Path(doc["resources"]) / "systems" / "transradial.json").is_file()
    assert doc["history"] == str(archive)
    assert {".asc", ".blf", ".csv", ".log", ".trc"} <= set(doc["log_formats"])
    assert doc["log_formats"][".asc"] == {"read": True, "write": True}
    assert isinstance(doc["serial_ports"], list)
    assert doc["versions"]["python-can"] == can.__version__
    assert isinstance(doc["display"]["window"], bool)


def test_history_defaults_to_the_user_data_folder(capsys, monkeypatch, tmp_path):
    monkeypatch.delenv("PDCP_STUDIO_HISTORY", raising=False)
    doc = _doc(capsys, monkeypatch, XDG_DATA_HOME=str(tmp_path))
    assert doc["history"] == str(tmp_path / "pdcp-studio" / "history.sqlite")
    assert doc["user_data"] == str(tmp_path / "pdcp-studio")


def test_a_module_that_does_not_import_is_reported_and_fails(capsys, monkeypatch):
    real = doctor.module_names
    monkeypatch.setattr(doctor, "module_names", lambda: [*real(), "pdcp_studio.app.gone"])
    assert main(["doctor", "--json"]) == 1
    doc = json.loads(capsys.readouterr().out)
    assert doc["modules"]["pdcp_studio.app.gone"] is False
    assert "ModuleNotFoundError" in doc["module_errors"]["pdcp_studio.app.gone"]


def test_text_report_names_each_interface_and_its_fix(capsys):
    assert main(["doctor"]) == 0
    out = capsys.readouterr().out
    for name in can.interfaces.BACKENDS:
        assert f"  {name}: " in out
    assert "resources: " in out and "fitting history: " in out


def test_json_stdout_is_one_document_in_a_fresh_process(tmp_path):
    env = {**os.environ, "PDCP_STUDIO_HISTORY": str(tmp_path / "h.sqlite")}
    done = subprocess.run([sys.executable, "-m", "pdcp_studio", "doctor", "--json"],
                          capture_output=True, text=True, timeout=120, env=env)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["history"] == str(tmp_path / "h.sqlite")
