"""A write that fails names the file asked for and says why in plain words (contracts §2),
also where the writer gives no reason (Qt's ``QImage.save`` for ``gui --screenshot``)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from pdcp_studio.storage.write_failure import why_not_written

ROOT = Path(__file__).resolve().parents[2]


def test_reasons_in_plain_words(tmp_path):
    missing = tmp_path / "no-such-folder" / "x.png"
    assert why_not_written(missing) == f"{missing}: the folder {missing.parent} does not exist"
    assert why_not_written(tmp_path) == f"{tmp_path}: is a folder, not a file"
    a_file = tmp_path / "a-file"
    a_file.write_text("")
    assert why_not_written(a_file / "x.png") == \
        f"{a_file / 'x.png'}: a part of the path is a file, not a folder"
    assert os.listdir(tmp_path) == ["a-file"]  # trying the folder left nothing behind


def test_gui_screenshot_into_a_missing_folder_says_why(tmp_path):
    target = tmp_path / "missing" / "dir" / "x.png"
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", XDG_CONFIG_HOME=str(tmp_path),
               PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    done = subprocess.run([sys.executable, "-m", "pdcp_studio", "gui", "--screenshot",
                           str(target)], capture_output=True, text=True, timeout=120,
                          cwd=ROOT, env=env)
    assert done.returncode == 1
    errors = [line for line in done.stderr.splitlines() if line.startswith("pdcp-studio")]
    assert errors == [f"pdcp-studio: error: {target}: the folder {target.parent} does not "
                      "exist"], done.stderr
