"""Writers that never lose the previous file and always name the target (issue 15).

A read-only folder, a missing parent, a full disk and a ``kill -9`` in the middle of a write:
the error names the file asked for (never the hidden temporary file), the previous file stays
as it was, and a temporary file a killed writer left is removed by the next write.
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.storage import atomic
from pdcp_studio.storage.atomic import atomic_write_bytes, remove_stale_temps

ROOT = Path(__file__).resolve().parents[2]


def _temps(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".tmp"))


@contextlib.contextmanager
def read_only(folder: Path):
    """The folder made read-only for this process (root ignores mode bits: chattr +i then)."""
    folder.chmod(0o555)
    immutable = False
    try:
        probe = folder / "probe"
        try:
            probe.write_bytes(b"")
        except OSError:
            pass
        else:
            probe.unlink()
            if shutil.which("chattr") is None or subprocess.run(
                    ["chattr", "+i", str(folder)], capture_output=True).returncode != 0:
                pytest.skip("cannot make a folder read-only for this user")
            immutable = True
        yield folder
    finally:
        if immutable:
            subprocess.run(["chattr", "-i", str(folder)], check=True)
        folder.chmod(0o755)


def test_a_read_only_folder_names_the_target_and_keeps_the_old_file(tmp_path):
    folder = tmp_path / "locked"
    folder.mkdir()
    target = folder / "out.pdcfg"
    target.write_bytes(b"old")
    with read_only(folder), pytest.raises(OSError) as info:
        atomic_write_bytes(target, b"new")
    assert info.value.filename == str(target)
    assert ".tmp" not in str(info.value) and str(target) in str(info.value)
    assert target.read_bytes() == b"old" and _temps(folder) == []


def test_a_missing_parent_names_the_target(tmp_path):
    target = tmp_path / "no" / "such" / "out.pdcfg"
    with pytest.raises(FileNotFoundError) as info:
        atomic_write_bytes(target, b"new")
    assert info.value.filename == str(target) and ".tmp" not in str(info.value)


def test_config_encode_into_a_missing_folder_names_the_file_asked_for(tmp_path, capsys):
    src = tmp_path / "in.json"
    src.write_text('{"configurations": []}')
    target = tmp_path / "missing" / "out.pdcfg"
    assert main(["config", "encode", str(src), "-o", str(target)]) == 1
    err = capsys.readouterr().err
    assert str(target) in err and ".tmp" not in err


class FullDisk:
    """A file object that writes half the data, then fails the way a full disk does."""

    def __init__(self, handle):
        self.handle = handle

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.handle.close()

    def write(self, data):
        self.handle.write(data[: len(data) // 2])
        self.handle.flush()
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def test_a_full_disk_names_the_target_and_keeps_the_old_file(tmp_path, monkeypatch):
    target = tmp_path / "capture.pdcfg"
    target.write_bytes(b"the previous file")
    real_fdopen = os.fdopen
    monkeypatch.setattr(atomic.os, "fdopen", lambda *a, **k: FullDisk(real_fdopen(*a, **k)))
    with pytest.raises(OSError) as info:
        atomic_write_bytes(target, b"x" * 100_000)
    assert info.value.errno == errno.ENOSPC
    assert info.value.filename == str(target) and ".tmp" not in str(info.value)
    assert target.read_bytes() == b"the previous file" and _temps(tmp_path) == []


_SLOW_WRITER = """
import os, sys, time
from pdcp_studio.storage import atomic
def stall(fd):
    print("writing", flush=True)
    time.sleep(60)
atomic.os.fsync = stall
atomic.atomic_write_bytes(sys.argv[1], b"new" * 100000)
"""


def test_kill_9_mid_write_keeps_the_old_file_and_the_next_write_removes_the_leftover(tmp_path):
    target = tmp_path / "system.json"
    target.write_bytes(b"old")
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    proc = subprocess.Popen([sys.executable, "-c", _SLOW_WRITER, str(target)],
                            stdout=subprocess.PIPE, text=True, env=env)
    try:
        assert proc.stdout.readline().strip() == "writing"
        os.kill(proc.pid, signal.SIGKILL)
    finally:
        proc.wait(10)
        proc.stdout.close()
    assert target.read_bytes() == b"old"
    assert len(_temps(tmp_path)) == 1  # what the killed writer left
    atomic_write_bytes(target, b"newer")
    assert target.read_bytes() == b"newer" and _temps(tmp_path) == []


def test_only_our_stale_temporary_files_are_removed(tmp_path):
    target = tmp_path / "out.pdcfg"
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    names = {
        f".out.pdcfg.{dead.pid}.0123abcd.tmp": False,   # its writer is gone: removed
        f".out.pdcfg.{os.getpid()}.0123abcd.tmp": True,  # a live writer's: kept
        ".out.pdcfg.89abcdef.tmp": True,                 # an older version's, fresh: kept
        ".out.pdcfg.fedcba98.tmp": False,                # … untouched for hours: removed
        f".other.pdcfg.{dead.pid}.0123abcd.tmp": True,   # another target's: kept
        "out.pdcfg.tmp": True,                           # not our pattern: kept
        f".out.pdcfg.{dead.pid}.0123abcd.tmp.bak": True,
    }
    for name in names:
        (tmp_path / name).write_bytes(b"")
    hours_ago = time.time() - 3 * 3600
    os.utime(tmp_path / ".out.pdcfg.fedcba98.tmp", (hours_ago, hours_ago))
    removed = {p.name for p in remove_stale_temps(target)}
    assert removed == {n for n, kept in names.items() if not kept}
    assert all((tmp_path / n).exists() == kept for n, kept in names.items())
