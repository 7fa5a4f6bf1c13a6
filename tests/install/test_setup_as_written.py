"""Set-up as written, anywhere: the README's system-package line runs as root where there is
no ``sudo`` (a fresh Debian) and through ``sudo`` for a user; the desktop build installs its
own build tool (the ``build`` extra), so it is one command in a fresh venv."""

from __future__ import annotations

import re
import subprocess
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text("utf-8")


def _quick_start_blocks() -> list[str]:
    section = README.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```sh\n(.*?)```", section, re.S)


def _apt_line() -> str:
    return next(b for b in _quick_start_blocks() if "apt-get install" in b).strip()


def _fake(bin_dir: Path, name: str, body: str) -> None:
    path = bin_dir / name
    path.write_text(f"#!/bin/sh\n{body}\n")
    path.chmod(0o755)


def _run_apt_line(tmp_path: Path, with_sudo: bool) -> list[str]:
    """The README's line in ``sh`` with only fake ``apt-get`` (and ``sudo``) on the path; the
    calls they logged."""
    bin_dir, log = tmp_path / "bin", tmp_path / "calls.log"
    bin_dir.mkdir()
    _fake(bin_dir, "apt-get", f'echo "apt-get $*" >> {log}')
    if with_sudo:
        _fake(bin_dir, "sudo", f'echo "sudo $1" >> {log}; exec "$@"')
    done = subprocess.run(["/bin/sh", "-c", _apt_line()], env={"PATH": str(bin_dir)},
                          capture_output=True, text=True, timeout=30)
    assert done.returncode == 0, done.stderr
    return log.read_text().splitlines()


def test_the_system_package_line_runs_as_root_without_sudo(tmp_path):
    from pdcp_studio.app import qt_prereqs

    calls = _run_apt_line(tmp_path, with_sudo=False)
    assert calls[0] == "apt-get update"
    assert calls[1].startswith("apt-get install -y ")
    assert set(qt_prereqs.APT_PACKAGES) | {"python3-venv"} <= set(calls[1].split())
    assert len(calls) == 2


def test_the_system_package_line_runs_through_sudo_for_a_user(tmp_path):
    calls = _run_apt_line(tmp_path, with_sudo=True)
    assert [c for c in calls if c.startswith("sudo")] == ["sudo apt-get"] * 2
    assert [c.split()[:2] for c in calls if c.startswith("apt-get")] == [
        ["apt-get", "update"], ["apt-get", "install"]]


def test_the_desktop_build_installs_its_own_build_tool():
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text("utf-8"))["project"][
        "optional-dependencies"]
    assert any(req.lower().startswith("pyinstaller") for req in extras["build"])
    script = (ROOT / "packaging" / "build.sh").read_text("utf-8")
    install = script.index('"$PY" -m pip install -q -e ".[build]"')
    assert install < script.index("-m PyInstaller")
    assert "python3 -m venv .venv && packaging/build.sh" in README
    packaging = (ROOT / "packaging" / "README.md").read_text("utf-8")
    assert "python3 -m venv .venv && packaging/build.sh" in packaging
    assert "`build` extra" in packaging
