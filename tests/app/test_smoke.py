"""The installation smoke test (also run on the frozen build by packaging/smoke_test.sh):
every dialog and dock of a live window opens, every plan previews, the report is written."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from pdcp_studio.app.smoke import SMOKE_ENV


def test_every_dialog_and_dock_opens_on_the_simulated_prosthesis(tmp_path):
    report = tmp_path / "smoke.json"
    env = {**os.environ, SMOKE_ENV: str(report), "QT_QPA_PLATFORM": "offscreen"}
    done = subprocess.run([sys.executable, "-m", "pdcp_studio", "gui", "--bus", "sim:transradial"],
                          env=env, capture_output=True, text=True, timeout=120, cwd=tmp_path)
    result = json.loads(report.read_text())
    failed = {k: v for k, v in result["steps"].items() if v != "ok"}
    assert not failed and done.returncode == 0, (failed, done.stderr)
    steps = set(result["steps"])
    for name in ("connect dialog", "compare dialog", "profile tree", "recovery dialog",
                 "user manual", "write configuration dialog", "dock MonitorDock",
                 "dock LivePlotDock", "dock SimDock", "dock PlanDock", "fitting report",
                 "about", "manual F1", "plan autoconfigure"):
        assert name in steps
