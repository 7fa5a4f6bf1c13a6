"""Atomic writes: a failure at any step leaves the old file intact and no temporary file."""

from __future__ import annotations

import os
import stat
import sys

import pytest

from pdcp_studio.storage import atomic
from pdcp_studio.storage.atomic import atomic_write_bytes, atomic_write_text


def test_creates_and_replaces(tmp_path):
    target = tmp_path / "memory.bin"
    atomic_write_bytes(target, b"first")
    assert target.read_bytes() == b"first"
    atomic_write_bytes(str(target), b"second")
    assert target.read_bytes() == b"second"
    assert os.listdir(tmp_path) == ["memory.bin"]


def test_text_is_utf8_without_newline_translation(tmp_path):
    target = tmp_path / "system.json"
    atomic_write_text(target, "a\nb\r\n→\n")
    assert target.read_bytes() == "a\nb\r\n→\n".encode()


class Boom(Exception):
    pass


class DiskFull:
    """A file object that writes half the data, then fails like a full disk."""

    def __init__(self, handle):
        self.handle = handle

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.handle.close()

    def write(self, data):
        self.handle.write(data[: len(data) // 2])
        self.handle.flush()
        raise OSError(28, "No space left on device")


@pytest.mark.parametrize("step", ["write", "fsync", "replace", "interrupt"])
def test_failure_mid_write_keeps_old_file_and_removes_temp(tmp_path, monkeypatch, step):
    target = tmp_path / "config.pdcfg"
    target.write_bytes(b"old contents")

    def fail(*args, **kwargs):
        raise KeyboardInterrupt if step == "interrupt" else Boom(step)

    if step == "write":
        real_fdopen = os.fdopen
        monkeypatch.setattr(atomic.os, "fdopen", lambda *a, **k: DiskFull(real_fdopen(*a, **k)))
    elif step in ("fsync", "interrupt"):
        monkeypatch.setattr(atomic.os, "fsync", fail)
    else:
        monkeypatch.setattr(atomic.os, "replace", fail)
    with pytest.raises((Boom, KeyboardInterrupt, OSError)):
        atomic_write_bytes(target, b"new contents")
    assert target.read_bytes() == b"old contents"
    assert os.listdir(tmp_path) == ["config.pdcfg"]


def test_failure_creating_a_new_file_leaves_nothing(tmp_path, monkeypatch):
    monkeypatch.setattr(atomic.os, "replace", lambda *a: (_ for _ in ()).throw(Boom()))
    with pytest.raises(Boom):
        atomic_write_bytes(tmp_path / "new.bin", b"data")
    assert os.listdir(tmp_path) == []


def test_missing_directory_raises_oserror(tmp_path):
    with pytest.raises(FileNotFoundError):
        atomic_write_bytes(tmp_path / "nope" / "x.bin", b"data")


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX permission bits")
def test_permissions_of_an_existing_file_are_kept(tmp_path):
    target = tmp_path / "private.bin"
    target.write_bytes(b"old")
    target.chmod(0o640)
    atomic_write_bytes(target, b"new")
    assert stat.S_IMODE(target.stat().st_mode) == 0o640


@pytest.mark.skipif(sys.platform == "win32", reason="symlinks need privileges on Windows")
def test_a_symlink_is_followed_and_kept(tmp_path):
    real = tmp_path / "real.bin"
    real.write_bytes(b"old")
    link = tmp_path / "link.bin"
    link.symlink_to(real)
    atomic_write_bytes(link, b"new")
    assert link.is_symlink()
    assert real.read_bytes() == b"new"
