"""Output piped to a reader that stops early (``| head``): the command ends quietly — no
"error: [Errno 32] Broken pipe", no Python complaint at exit — with exit status 1 (not all
of its output was delivered; contracts §2 allows 0, 1, 2). Real pipes, real processes."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _run_with_the_reader_gone(argv: list[str], read_lines: int, tmp_path: Path):
    env = dict(os.environ, PDCP_STUDIO_HISTORY=str(tmp_path / "h.sqlite"))
    proc = subprocess.Popen([sys.executable, "-m", "pdcp_studio", *argv],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=ROOT, env=env)
    assert proc.stdout is not None and proc.stderr is not None
    for _ in range(read_lines):
        proc.stdout.readline()
    proc.stdout.close()  # the reader goes, as `head -n N` does
    err = proc.stderr.read().decode()
    return proc.wait(timeout=120), err


@pytest.mark.parametrize("argv", [
    ["sim", "list"],  # all of it still buffered: the failure shows at the final flush
    ["sim", "replay", "full", "--json"],  # a large document, written while the pipe is shut
    ["monitor", "--replay", "tests/data/captures/pdcp-session.asc"],
])
def test_a_closed_pipe_ends_the_command_quietly(argv, tmp_path):
    code, err = _run_with_the_reader_gone(argv, 0, tmp_path)
    assert code == 1
    assert "Broken pipe" not in err and "Traceback" not in err and "Exception ignored" not in err
    assert err == ""


def test_a_reader_that_takes_the_first_line_then_goes(tmp_path):
    # Whether the rest still fits the pipe depends on the kernel: 0 when it did, 1 when not.
    code, err = _run_with_the_reader_gone(["sim", "replay", "full", "--json"], 1, tmp_path)
    assert code in (0, 1) and err == ""


def test_head_in_a_shell_pipeline(tmp_path):
    done = subprocess.run(f"{sys.executable} -m pdcp_studio sim replay full --json | head -n 2",
                          shell=True, capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert done.stdout.splitlines()[0] == "{" and done.stderr == ""


def test_in_process_a_broken_pipe_is_exit_1_without_a_message(capsys, monkeypatch):
    from pdcp_studio.cli import main as cli_main

    class Gone:
        def write(self, text: str) -> int:
            raise BrokenPipeError(32, "Broken pipe")

        def flush(self) -> None:
            raise BrokenPipeError(32, "Broken pipe")

        def fileno(self) -> int:
            raise ValueError("no file descriptor")

    monkeypatch.setattr(sys, "stdout", Gone())
    assert cli_main.main(["sim", "list"]) == 1
    assert capsys.readouterr().err == ""
