"""Ctrl-C and ``monitor --log`` (contracts §2): "`--log FILE` replaces FILE only once the
capture is complete: an interrupted capture leaves FILE as it was".

A live monitor without ``--seconds`` ends with Ctrl-C: that capture is complete. With
``--seconds N`` a Ctrl-C before N seconds interrupts it: FILE keeps its old content, the
frames so far stay in ``FILE.partial`` (nothing is lost), and the exit status is 1.
"""

from __future__ import annotations

import signal
import subprocess
import sys
import time

import pytest

from pdcp_studio.bus.trace.monitor import read_capture


def _monitor_then_ctrl_c(target, *extra: str) -> subprocess.CompletedProcess:
    proc = subprocess.Popen(
        [sys.executable, "-m", "pdcp_studio", "monitor", "--bus", "sim:transradial",
         "--log", str(target), *extra],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        first = proc.stdout.readline()  # the bus is live and frames are being written
        assert first, proc.stderr.read()
        time.sleep(0.5)
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    return subprocess.CompletedProcess(proc.args, proc.returncode, first + out, err)


@pytest.mark.timeout(120)
def test_ctrl_c_before_seconds_leaves_the_file_as_it_was(tmp_path):
    target = tmp_path / "capture.asc"
    target.write_text("the previous capture\n")
    done = _monitor_then_ctrl_c(target, "--seconds", "60")
    assert done.returncode == 1, done.stderr
    assert target.read_text() == "the previous capture\n"
    partial = tmp_path / "capture.asc.partial"
    assert "interrupted after" in done.stderr and str(partial) in done.stderr
    kept = tmp_path / "kept.asc"  # a .partial is read once renamed (it may end anywhere)
    partial.rename(kept)
    assert len(list(read_capture(kept))) > 0, "the frames so far were lost"
    assert "Traceback" not in done.stderr


@pytest.mark.timeout(120)
def test_ctrl_c_ends_a_capture_without_seconds_and_writes_it(tmp_path):
    target = tmp_path / "capture.asc"
    target.write_text("the previous capture\n")
    done = _monitor_then_ctrl_c(target)
    assert done.returncode == 0, done.stderr
    assert f"wrote {target}" in done.stderr
    assert len(list(read_capture(target))) > 0
    assert not (tmp_path / "capture.asc.partial").exists()
