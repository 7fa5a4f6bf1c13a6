"""Captures written by other tools (Vector, PEAK, can-utils), taken from public repositories
(tests/data/captures/public/README.md), and damaged variants of each: the monitor reads them as
python-can does, calls them what they are, and never fails with a traceback."""

from __future__ import annotations

import gzip
import json
import subprocess
import sys
from pathlib import Path

import can
import pytest

PUBLIC = Path(__file__).resolve().parents[1] / "data" / "captures" / "public"
CAPTURES = sorted(p for p in PUBLIC.iterdir() if p.suffix != ".md")


def _monitor(path: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "pdcp_studio", "monitor", "--replay",
                           str(path), "--json"], capture_output=True, text=True, timeout=120)


def _python_can_count(path: Path) -> int:
    name = path.name.removesuffix(".gz")
    opener = gzip.open if path.suffix == ".gz" else open
    if name.endswith(".asc"):
        with opener(path, "rt", encoding="utf-8", errors="replace") as f:  # type: ignore[operator]
            return sum(1 for _ in can.ASCReader(f))
    if name.endswith(".blf"):
        return sum(1 for _ in can.BLFReader(str(path)))
    if name.endswith(".trc"):
        return sum(1 for _ in can.TRCReader(str(path)))
    return sum(1 for _ in can.CanutilsLogReader(str(path)))


@pytest.mark.parametrize("path", CAPTURES, ids=lambda p: p.name)
def test_a_capture_from_another_tool_reads_as_python_can_reads_it(path):
    done = _monitor(path)
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    doc = json.loads(done.stdout)
    summary = doc["summary"]
    assert summary["verdict"] == "not-pdcp"  # none of them is a prosthesis
    assert summary["frames"] == len(doc["frames"]) == _python_can_count(path)
    assert not summary["truncated"]
    for frame in doc["frames"]:
        assert {"arbitration_id", "is_extended_id", "is_remote_frame", "is_error_frame",
                "is_fd", "channel", "data"} <= set(frame)


@pytest.mark.parametrize("path", [p for p in CAPTURES if p.stat().st_size > 400],
                         ids=lambda p: p.name)
def test_a_capture_cut_in_half_is_read_to_the_cut_and_said(path, tmp_path):
    data = path.read_bytes()
    if path.suffix == ".gz":
        data = gzip.decompress(data)
    cut = tmp_path / path.name.removesuffix(".gz")
    cut.write_bytes(data[: len(data) // 2])
    done = _monitor(cut)
    assert "Traceback" not in done.stderr
    assert done.returncode in (0, 2), done.stderr
    if done.returncode == 2:
        assert str(cut) in done.stderr  # names the file, and where
    if done.stdout.strip():
        summary = json.loads(done.stdout)["summary"]
        assert summary["frames"] <= _python_can_count(path)
