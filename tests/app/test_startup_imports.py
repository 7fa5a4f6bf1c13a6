"""What starting the app on the simulated prosthesis imports (issue 11: start-up < 1.5 s).

Start-up is mostly import time, so a module that creeps onto its path costs every user every
start. This starts ``pdcp-studio gui --bus sim:transradial`` in a fresh interpreter and looks
at ``sys.modules`` the moment the window is ready (shown, laid out, live):

- numpy, the trace store and the live plot come only with the trace and plot docks, made
  just after the window is up (``app/window/bus_docks.py``), never before it;
- the other commands' modules are not loaded for the desktop app (``cli/main.py``);
- the manual and About (``help_viewer``) come when first asked for (``window_desktop``);
- networkx is there (the graph is laid out with it), and python-can (the simulated
  prosthesis talks over python-can's virtual bus: contracts §3 ``sim:``).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.gui

ROOT = Path(__file__).resolve().parents[2]
NOT_AT_START = ("numpy", "pdcp_studio.app.live.plot", "pdcp_studio.app.trace.dock",
                "pdcp_studio.app.trace.store", "pdcp_studio.cli.doctor",
                "pdcp_studio.cli.monitor", "pdcp_studio.cli.config_cmd",
                "pdcp_studio.app.dialogs.help_viewer")
NEEDED = ("networkx", "can", "pdcp_studio.bus.arbitrator.core")

SCRIPT = """
import json, sys
from pdcp_studio.app.window import main_window

seen = {}
mark_ready = main_window.MainWindow._mark_ready

def on_ready(self):
    if not self.is_ready:
        seen.update(live=self.live.is_live, modules=sorted(
            m for m in %r if m in sys.modules))
    mark_ready(self)

main_window.MainWindow._mark_ready = on_ready
from pdcp_studio.cli.main import main
main(["gui", "--bus", "sim:transradial"])
print("SEEN " + json.dumps(seen), flush=True)
"""


def test_the_window_is_ready_before_numpy_the_trace_and_the_plot_are_imported():
    env = dict(os.environ, PDCP_STUDIO_STARTUP_PROBE="1", QT_QPA_PLATFORM="offscreen",
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    watched = NOT_AT_START + NEEDED
    out = subprocess.run([sys.executable, "-c", SCRIPT % (watched,)], capture_output=True,
                         text=True, env=env, cwd=ROOT, timeout=60)
    line = next((x for x in out.stdout.splitlines() if x.startswith("SEEN ")), None)
    assert line is not None, out.stdout + out.stderr
    seen = json.loads(line[5:])
    assert seen["live"], out.stdout
    loaded = set(seen["modules"])
    assert not loaded & set(NOT_AT_START), sorted(loaded & set(NOT_AT_START))
    assert set(NEEDED) <= loaded  # the check can see imports at all
