"""A warning the command line must show (a bitrate other than PDCP's) is one stderr line
with the program's ``pdcp-studio:`` prefix, like its errors (issue 10 item 6)."""

from __future__ import annotations

import subprocess
import sys


def test_a_bitrate_other_than_pdcps_is_one_prefixed_warning_line():
    # A real process: the line must reach stderr without pytest's log capture in between.
    # slcan on pyserial's loop:// opens without hardware.
    done = subprocess.run(
        [sys.executable, "-m", "pdcp_studio.cli.main", "monitor", "--bus",
         "can:slcan:loop://@500000", "--seconds", "0.2"],
        capture_output=True, text=True, timeout=60, check=False)
    assert done.returncode == 0, done.stderr
    warnings = [ln for ln in done.stderr.splitlines() if "bit/s" in ln]
    assert warnings == [warnings[0]] and warnings[0].startswith(
        "pdcp-studio: warning: can:slcan:loop://@500000: bitrate 500000 bit/s is not PDCP's")


def test_pdcps_own_bitrate_gives_no_warning():
    done = subprocess.run(
        [sys.executable, "-m", "pdcp_studio.cli.main", "monitor", "--bus",
         "can:slcan:loop://@1000000", "--seconds", "0.2"],
        capture_output=True, text=True, timeout=60, check=False)
    assert done.returncode == 0, done.stderr
    assert "warning" not in done.stderr
