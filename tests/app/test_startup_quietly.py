"""Start-up's own settings (issue 11): no cyclic garbage collection and CPython's default
switch interval until the window is live, then the app's (collection on, 1 ms interval,
start-up's objects frozen; the collector is the GUI thread's, app/gui_gc.py). A real
``pdcp-studio gui --bus sim:transradial`` in a fresh
interpreter, looked at while the window is made and once it is live."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.gui

ROOT = Path(__file__).resolve().parents[2]

SCRIPT = """
import gc, json, sys
from pdcp_studio.app import gui_gc
from pdcp_studio.app.window import main_window
from pdcp_studio.app.application import START_UP_SWITCH_INTERVAL_S, SWITCH_INTERVAL_S

seen = {}
init = main_window.MainWindow.__init__

def made(self, *args, **kwargs):
    init(self, *args, **kwargs)
    seen.update(building_gc=gc.isenabled(), building_interval=sys.getswitchinterval())
    self.ready.connect(lambda: QTimer.singleShot(0, lambda: seen.update(
        live_gc=gui_gc.collecting(), live_interval=sys.getswitchinterval(),
        frozen=gc.get_freeze_count())))

from PySide6.QtCore import QTimer
main_window.MainWindow.__init__ = made
from pdcp_studio.cli.main import main
main(["gui", "--bus", "sim:transradial"])
seen.update(start_up=START_UP_SWITCH_INTERVAL_S, app=SWITCH_INTERVAL_S)
print("SEEN " + json.dumps(seen), flush=True)
"""


def test_the_collector_waits_and_the_interval_is_the_default_until_the_window_is_live():
    env = dict(os.environ, PDCP_STUDIO_STARTUP_PROBE="1", QT_QPA_PLATFORM="offscreen",
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    out = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True,
                         env=env, cwd=ROOT, timeout=60)
    line = next((x for x in out.stdout.splitlines() if x.startswith("SEEN ")), None)
    assert line is not None, out.stdout + out.stderr
    seen = json.loads(line[5:])
    assert seen["building_gc"] is False
    assert seen["building_interval"] == pytest.approx(seen["start_up"])
    assert seen["live_gc"] is True
    assert seen["live_interval"] == pytest.approx(seen["app"])
    assert seen["frozen"] > 10_000  # what start-up made is out of the collector's sight


def test_a_start_up_that_ends_early_gives_the_collector_back(tmp_path):
    import gc

    from pdcp_studio.app.application import SWITCH_INTERVAL_S, run_app
    from pdcp_studio.errors import PdcpError

    bad = tmp_path / "broken.json"
    bad.write_text("{ not json", "utf-8")
    with pytest.raises(PdcpError):
        run_app(bad)  # fails before any window: bad input
    from pdcp_studio.app.gui_gc import collecting

    assert gc.isenabled() or collecting()  # (the GUI thread's, when an application exists)
    assert sys.getswitchinterval() == pytest.approx(SWITCH_INTERVAL_S)
