"""``pdcp-studio gui CAPTURE`` opens the capture in the trace, chosen by its content as
``monitor --replay`` chooses (issue 27 item 3): never "not valid JSON"."""

from __future__ import annotations

import gzip
import os
import subprocess
import sys
from pathlib import Path

import pytest

from pdcp_studio.cli.gui import is_capture

ROOT = Path(__file__).resolve().parents[2]
CAPTURES = ROOT / "tests" / "data" / "captures"


@pytest.mark.parametrize("name", sorted(p.name for p in CAPTURES.iterdir() if p.is_file()))
def test_every_capture_is_told_by_its_content(tmp_path, name):
    assert is_capture(str(CAPTURES / name))
    renamed = tmp_path / "capture.data"  # whatever its name
    renamed.write_bytes((CAPTURES / name).read_bytes())
    assert is_capture(str(renamed))


def test_documents_and_other_files_are_not_captures(tmp_path):
    system = tmp_path / "system.json"
    system.write_text('{"format": "pdcp-system/1"}')
    empty_asc, empty_json = tmp_path / "empty.asc", tmp_path / "empty.json"
    empty_asc.write_bytes(b"")
    empty_json.write_bytes(b"")
    gz = tmp_path / "c.asc.gz"
    gz.write_bytes(gzip.compress((CAPTURES / "pdcp-session.asc").read_bytes()))
    fifo = tmp_path / "pipe.asc"
    os.mkfifo(fifo)
    assert not is_capture(str(system)) and not is_capture(str(empty_json))
    assert is_capture(str(empty_asc)) and is_capture(str(gz))
    assert not is_capture(str(fifo))  # never opened here (it would wait for a writer)
    assert not is_capture(str(tmp_path / "missing.asc"))


def test_gui_capture_shows_it_in_the_trace(tmp_path):
    shot = tmp_path / "shot.png"
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", XDG_CONFIG_HOME=str(tmp_path),
               PDCP_STUDIO_HISTORY=str(tmp_path / "history.sqlite3"),
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    done = subprocess.run([sys.executable, "-m", "pdcp_studio", "gui",
                           str(CAPTURES / "candump-car.log"), "--screenshot", str(shot)],
                          capture_output=True, text=True, timeout=120, cwd=ROOT, env=env)
    assert done.returncode == 0, done.stderr
    assert "JSON" not in done.stderr and shot.stat().st_size > 0
