"""Contracts §2: bare ``pdcp-studio`` opens the desktop app on the built-in simulated
prosthesis; ``pdcp-studio gui`` with neither file nor bus keeps the start page. Real
processes, the app's start-up probe (``PDCP_STUDIO_STARTUP_PROBE``) says what is on screen."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _probe(tmp_path: Path, *argv: str) -> dict[str, str]:
    env = dict(os.environ, PDCP_STUDIO_STARTUP_PROBE="1", QT_QPA_PLATFORM="offscreen",
               XDG_CONFIG_HOME=str(tmp_path), XDG_DATA_HOME=str(tmp_path),
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    done = subprocess.run([sys.executable, "-m", "pdcp_studio", *argv], capture_output=True,
                          text=True, env=env, cwd=tmp_path, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    line = next((x for x in done.stdout.splitlines() if x.startswith("startup_s=")), None)
    assert line is not None, done.stdout + done.stderr
    return dict(re.findall(r"(\w+)=(\S+)", line))


@pytest.mark.parametrize("argv", [(), ("--lang", "de")])
def test_bare_pdcp_studio_opens_live_on_the_simulated_prosthesis(tmp_path, argv):
    seen = _probe(tmp_path, *argv)
    assert (seen["devices"], seen["live"]) == ("4", "True")  # sim:transradial's four devices


def test_gui_without_file_or_bus_keeps_the_start_page(tmp_path):
    seen = _probe(tmp_path, "gui")
    assert (seen["devices"], seen["live"]) == ("0", "False")
