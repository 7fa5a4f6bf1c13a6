"""Inputs are what they claim (issue 28): a FIFO or a device is refused in words, at once,
wherever a file is read or replaced; the atomic writer writes through a symlink."""

from __future__ import annotations

import os
import stat
import threading
import time

import pytest

from pdcp_studio.storage import config_codec, system_file
from pdcp_studio.storage.atomic import atomic_write_bytes, atomic_write_text
from pdcp_studio.storage.bounded_input import read_capped
from pdcp_studio.storage.profile_trees import read_tree_json
from pdcp_studio.storage.regular_file import NotARegularFile, open_regular


@pytest.fixture
def fifo(tmp_path):
    """A named pipe; if a reader ever blocks on it, a writer opens it after 5 s so the test
    fails instead of hanging."""
    path = tmp_path / "pipe.json"
    os.mkfifo(path)
    done = threading.Event()

    def rescue() -> None:
        if not done.wait(5):
            fd = os.open(path, os.O_WRONLY | os.O_NONBLOCK)
            os.close(fd)

    thread = threading.Thread(target=rescue, daemon=True)
    thread.start()
    yield path
    done.set()
    thread.join(6)


@pytest.mark.parametrize("read", [
    lambda p: read_capped(p, 100),
    lambda p: open_regular(p),
    lambda p: config_codec.load_path(p),
    lambda p: read_tree_json(p),
], ids=["read_capped", "open_regular", "config_codec.load_path", "profile tree"])
def test_every_reader_refuses_a_fifo_at_once_saying_what_it_is(fifo, read):
    started = time.monotonic()
    with pytest.raises(NotARegularFile) as info:
        read(fifo)
    assert time.monotonic() - started < 1.0
    assert "is a FIFO (named pipe), not a regular file" in str(info.value)
    assert info.value.filename == str(fifo)


def test_a_device_is_refused_too_and_a_system_file_error_names_it():
    with pytest.raises(system_file.SystemFileError,
                       match=r"/dev/zero: cannot read: is a character device, not a regular"):
        system_file.load_path("/dev/zero")
    with pytest.raises(NotARegularFile, match="character device"):
        config_codec.load_path("/dev/null")


def test_a_regular_file_and_a_symlink_to_one_still_read(tmp_path):
    real = tmp_path / "real.json"
    real.write_bytes(b"{}")
    link = tmp_path / "link.json"
    link.symlink_to(real)
    assert read_capped(link, 10) == b"{}"


# -- the atomic writer -------------------------------------------------------------------
def test_the_writer_never_replaces_a_fifo(fifo):
    with pytest.raises(NotARegularFile, match=r"is a FIFO \(named pipe\), not a regular file; "
                                              "refused to replace it"):
        atomic_write_text(fifo, "data")
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    assert [p.name for p in fifo.parent.iterdir()] == [fifo.name]  # no temporary left


def device_node(folder):
    """A character device like /dev/null (1, 3) made in ``folder`` (root only): a writer
    that wrongly replaces it destroys this copy, never the system's /dev/null."""
    path = folder / "null"
    try:
        os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    except (PermissionError, AttributeError):
        pytest.skip("making a device node needs root")
    return path


def test_the_writer_never_replaces_a_device_node(tmp_path):
    """``-o /dev/null`` as root once turned the device into a regular file."""
    node = device_node(tmp_path)
    with pytest.raises(NotARegularFile, match="is a character device, not a regular file; "
                                              "refused to replace it"):
        atomic_write_bytes(node, b"data")
    assert stat.S_ISCHR(os.lstat(node).st_mode)


def test_the_writer_writes_through_a_symlink_and_the_link_stays_a_link(tmp_path):
    real = tmp_path / "real.pdcfg"
    real.write_bytes(b"old")
    os.chmod(real, 0o640)
    link = tmp_path / "link.pdcfg"
    link.symlink_to("real.pdcfg")
    atomic_write_bytes(link, b"new")
    assert link.is_symlink() and os.readlink(link) == "real.pdcfg"
    assert real.read_bytes() == b"new"
    assert stat.S_IMODE(real.stat().st_mode) == 0o640
    dangling = tmp_path / "to-be.pdcfg"
    dangling.symlink_to("made-by-the-write.pdcfg")
    atomic_write_bytes(dangling, b"first")
    assert dangling.is_symlink() and (tmp_path / "made-by-the-write.pdcfg").read_bytes() == b"first"


def test_the_writer_refuses_a_symlink_loop_and_leaves_the_links(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    a.symlink_to("b")
    b.symlink_to("a")
    with pytest.raises(OSError) as info:
        atomic_write_bytes(a, b"x")
    assert info.value.filename == str(a)
    assert a.is_symlink() and b.is_symlink()
