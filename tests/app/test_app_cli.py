"""``pdcp-studio gui FILE --screenshot PNG`` (contracts §2) in a real process."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from PySide6.QtGui import QImage

ROOT = Path(__file__).resolve().parents[2]
TRANSRADIAL = ROOT / "resources" / "systems" / "transradial.json"


def _run(*args: str, timeout: float = 60) -> subprocess.CompletedProcess:
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    return subprocess.run([sys.executable, "-m", "pdcp_studio", *args], capture_output=True,
                          text=True, timeout=timeout, env=env, cwd=ROOT)


def test_gui_file_screenshot_writes_a_png(tmp_path, qapp):
    out = tmp_path / "shot.png"
    r = _run("gui", str(TRANSRADIAL), "--screenshot", str(out), "--size", "1200x780")
    assert r.returncode == 0, r.stderr
    assert r.stdout == ""
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    image = QImage(str(out))
    assert (image.width(), image.height()) == (1200, 780)
    # Not a blank grab: the cards and text put many distinct colours on it.
    colours = {image.pixel(x, y) for x in range(0, 1200, 7) for y in range(0, 780, 7)}
    assert len(colours) > 20


def test_gui_configuration_screenshot(tmp_path):
    out = tmp_path / "cfg.png"
    r = _run("gui", str(ROOT / "resources" / "configs" / "fig410.pdcfg"), "--screenshot", str(out))
    assert r.returncode == 0, r.stderr
    assert out.stat().st_size > 1000


def test_gui_bad_file_exits_2(tmp_path):
    bad = tmp_path / "broken.json"
    bad.write_text('{"format": "pdcp-system/1", "devices": [{"vid": 1}]}')
    r = _run("gui", str(bad), "--screenshot", str(tmp_path / "x.png"))
    assert r.returncode == 2
    assert "broken.json" in r.stderr and "devices[0]" in r.stderr
    assert not (tmp_path / "x.png").exists()


def test_gui_bad_bus_url_exits_2(tmp_path):
    r = _run("gui", "--bus", "nonsense", "--screenshot", str(tmp_path / "x.png"))
    assert r.returncode == 2
    assert "nonsense" in r.stderr


def test_gui_unreachable_bus_exits_1_without_a_picture(tmp_path):
    # A known interface whose device is not there: a failure (1), named in the last line.
    out = tmp_path / "x.png"
    r = _run("gui", "--bus", "can:socketcan:pdcpnope0", "--screenshot", str(out))
    assert r.returncode == 1
    assert "pdcpnope0" in r.stderr.splitlines()[-1]
    assert not out.exists()


def test_gui_unknown_interface_is_bad_input_without_a_picture(tmp_path):
    # contracts §2: an interface python-can does not have is bad input (2), as for every command.
    out = tmp_path / "x.png"
    r = _run("gui", "--bus", "can:nosuchinterface:x", "--screenshot", str(out))
    assert r.returncode == 2
    assert "nosuchinterface" in r.stderr.splitlines()[-1]
    assert not out.exists()
