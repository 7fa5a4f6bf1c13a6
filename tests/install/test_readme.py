"""The README's commands work as written: the Quick start names every system package Qt
needs, and each line of the command-line tour runs in a fresh copy of the repository
(its files only, no build products) with this environment as the Quick start's ``.venv``."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from pdcp_studio.app import qt_prereqs

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text("utf-8")


def _blocks_after(heading: str) -> list[str]:
    section = README.split(heading, 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```sh\n(.*?)```", section, re.S)


def _commands(block: str) -> list[str]:
    return [line for line in block.splitlines() if line.strip()]


def test_quick_start_names_every_system_package_and_the_two_commands():
    blocks = _blocks_after("## Quick start")
    apt = next(b for b in blocks if "apt-get install" in b)
    assert set(qt_prereqs.APT_PACKAGES) <= set(apt.split()), "README lacks a package Qt needs"
    assert "python3-venv" in apt.split()
    assert any(b.strip() == "python3 -m venv .venv && .venv/bin/pip install -e . && "
               ".venv/bin/pdcp-studio" for b in blocks)
    test_command = ('python3 -m venv .venv && .venv/bin/pip install -e ".[test]" && '
                    ".venv/bin/python -m pytest -n 2 --dist loadfile")
    assert any(b.strip() == test_command for b in blocks)
    # .ci/run runs the README's test command (with its own quiet flags)
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert ".venv/bin/python -m pytest -n 2 --dist loadfile" in ci


def _fresh_copy(dest: Path) -> None:
    """The repository's tracked files (a fresh clone's), or its source folders without git."""
    listed = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True)
    if listed.returncode == 0 and listed.stdout:
        for name in listed.stdout.decode().split("\0"):
            src = ROOT / name
            if name and (src.is_file() or src.is_symlink()):
                (dest / name).parent.mkdir(parents=True, exist_ok=True)
                if src.is_symlink():
                    os.symlink(os.readlink(src), dest / name)
                else:
                    shutil.copy2(src, dest / name)
        return
    for part in ("resources", "docs", "packaging"):  # pragma: no cover - a tarball
        shutil.copytree(ROOT / part, dest / part, symlinks=True)


@pytest.mark.slow
def test_every_tour_command_runs_as_written_in_a_fresh_copy(tmp_path):
    (tour,) = _blocks_after("## A tour of the command line")[:1]
    lines = _commands(tour)
    assert lines[0].startswith(". .venv/bin/activate")
    clone = tmp_path / "clone"
    clone.mkdir()
    _fresh_copy(clone)
    (clone / ".venv").symlink_to(Path(sys.prefix))
    env = {**os.environ, "PDCP_STUDIO_HISTORY": str(tmp_path / "history.sqlite"),
           "QT_QPA_PLATFORM": "offscreen", "XDG_DATA_HOME": str(tmp_path / "data")}
    env.pop("VIRTUAL_ENV", None)
    for line in lines[1:]:
        script = f"set -e\n{lines[0]}\n{line}\n"
        done = subprocess.run(["bash", "-c", script], cwd=clone, env=env,
                              capture_output=True, text=True, timeout=180)
        assert done.returncode == 0, f"README tour line failed:\n{line}\n{done.stderr}"
    assert (clone / "shot.png").stat().st_size > 10_000
    assert (clone / "fig410-again.pdcfg").read_bytes() == \
        (clone / "resources/configs/fig410.pdcfg").read_bytes()
