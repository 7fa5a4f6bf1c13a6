"""Every command that reads a file refuses a FIFO or a device in words, within a second
(issue 28): ``info``, ``print``, ``check``, ``plan`` (``--system``, ``--config``,
``--profiles``), ``config decode``/``diff``/``encode``/``write``, ``gui FILE`` and
``--memory``; ``--memory`` takes only a memory image or a new path."""

from __future__ import annotations

import os
import threading
import time

import pytest

from pdcp_studio.cli.main import main
from pdcp_studio.paths import resources_dir

SYSTEM = str(resources_dir() / "systems" / "transradial.json")
CONFIG = str(resources_dir() / "configs" / "fig410.pdcfg")


def _let_go(path) -> None:
    """Open ``path`` for writing without waiting: a reader blocked on it gets its end."""
    try:
        os.close(os.open(path, os.O_WRONLY | os.O_NONBLOCK))
    except OSError:
        pass


@pytest.fixture
def fifo(tmp_path):
    """A named pipe (ending in .pdcfg, so ``gui`` reads it as a configuration too); a
    reader that blocks on it is let go after 5 s, so the test fails rather than hangs."""
    path = tmp_path / "pipe.pdcfg"
    os.mkfifo(path)
    done = threading.Event()

    def rescue() -> None:
        while not done.wait(5):
            _let_go(path)

    thread = threading.Thread(target=rescue, daemon=True)
    thread.start()
    yield str(path)
    done.set()
    thread.join(6)


COMMANDS = [
    ["info", "--system", "{f}"],
    ["print", "--system", "{f}"],
    ["check", "--system", "{f}"],
    ["plan", "startup", "--system", "{f}"],
    ["plan", "implement", "--system", SYSTEM, "--config", "{f}"],
    ["plan", "startup", "--system", SYSTEM, "--profiles", "{f}"],
    ["config", "decode", "{f}"],
    ["config", "diff", "{f}", CONFIG],
    ["config", "diff", CONFIG, "{f}"],
    ["config", "encode", "{f}", "-o", "{tmp}/out.pdcfg"],
    ["config", "write", "{f}", "--bus", "sim:transradial"],
]


@pytest.mark.parametrize("argv", COMMANDS, ids=lambda a: " ".join(a[:2]))
@pytest.mark.parametrize("what", ["fifo", "/dev/zero"])
def test_a_fifo_or_a_device_as_input_is_refused_in_words_within_a_second(
        capsys, tmp_path, fifo, argv, what):
    given = fifo if what == "fifo" else what
    argv = [a.format(f=given, tmp=tmp_path) for a in argv]
    started = time.monotonic()
    code = main(argv)
    elapsed = time.monotonic() - started
    out, err = capsys.readouterr()
    assert code == 2, err
    assert elapsed < 1.0
    kind = "a FIFO (named pipe)" if what == "fifo" else "a character device"
    assert f"{given}: cannot read: is {kind}, not a regular file" in err
    assert "Traceback" not in err and out == ""


@pytest.mark.parametrize("suffix", ["pdcfg", "json"])
def test_gui_refuses_a_fifo_before_any_window(capsys, tmp_path, monkeypatch, suffix):
    monkeypatch.setenv("QT_QPA_PLATFORM", "offscreen")
    path = tmp_path / f"pipe.{suffix}"
    os.mkfifo(path)
    timer = threading.Timer(10.0, _let_go, (path,))  # a reader that waits fails, not hangs
    timer.start()
    started = time.monotonic()
    try:
        code = main(["gui", str(path), "--screenshot", str(tmp_path / "shot.png")])
    finally:
        timer.cancel()
    assert time.monotonic() - started < 5.0  # the app's imports, never a wait on the pipe
    err = capsys.readouterr().err
    assert code == 2, err
    assert f"{path}: cannot read: is a FIFO (named pipe), not a regular file" in err
    assert not (tmp_path / "shot.png").exists()


# -- --memory: a memory image or a new path -----------------------------------------------
MEMORY_COMMANDS = [
    ["info", "--bus", "sim:transradial"],
    ["config", "read", "--bus", "sim:transradial", "-o", "{tmp}/out.pdcfg"],
    ["arbitrator", "--bus", "can:virtual:not-files-memory", "--seconds", "0.1"],
]


@pytest.mark.parametrize("argv", MEMORY_COMMANDS, ids=lambda a: a[0])
def test_memory_refuses_a_stored_configuration_file_never_converting_it(
        capsys, tmp_path, argv):
    """``--memory fig410.pdcfg`` once turned the configuration into a 1 MiB memory image."""
    memory = tmp_path / "fig410.pdcfg"
    memory.write_bytes(open(CONFIG, "rb").read())
    before = memory.read_bytes()
    argv = [a.format(tmp=tmp_path) for a in argv]
    assert main([*argv, "--memory", str(memory)]) == 2
    out, err = capsys.readouterr()
    assert err.startswith(f"pdcp-studio: --memory {memory}: is a stored-configuration file "
                          "(.pdcfg), not a memory image"), err
    assert "config write" in err and out == ""
    assert memory.read_bytes() == before


@pytest.mark.parametrize("argv", MEMORY_COMMANDS, ids=lambda a: a[0])
def test_memory_refuses_garbage_naming_why(capsys, tmp_path, argv):
    memory = tmp_path / "garbage.bin"
    memory.write_bytes(bytes(range(256)) * 12)
    argv = [a.format(tmp=tmp_path) for a in argv]
    assert main([*argv, "--memory", str(memory)]) == 2
    err = capsys.readouterr().err
    assert f"--memory {memory}: is not a memory image (no PDCM header)" in err
    assert memory.read_bytes() == bytes(range(256)) * 12


@pytest.mark.parametrize("argv", MEMORY_COMMANDS, ids=lambda a: a[0])
def test_memory_refuses_a_fifo_or_a_device_within_a_second(capsys, tmp_path, fifo, argv):
    argv = [a.format(tmp=tmp_path) for a in argv]
    for given, kind in ((fifo, "a FIFO (named pipe)"), ("/dev/zero", "a character device")):
        started = time.monotonic()
        assert main([*argv, "--memory", given]) == 2
        assert time.monotonic() - started < 1.0
        assert f"--memory {given}: is {kind}, not a memory file" in capsys.readouterr().err


def test_memory_a_new_path_starts_an_empty_memory_and_opens_again(capsys, tmp_path):
    memory = tmp_path / "new.mem"
    assert main(["config", "read", "--bus", "sim:thesis-test2", "-o",
                 str(tmp_path / "a.pdcfg"), "--memory", str(memory)]) == 0
    assert memory.exists()
    assert main(["config", "read", "--bus", "sim:thesis-test2", "-o",
                 str(tmp_path / "b.pdcfg"), "--memory", str(memory)]) == 0


def test_output_to_a_device_node_is_refused_and_the_device_survives(capsys, tmp_path):
    """``-o /dev/null`` must not destroy it; tried on a copy of the device (root only), so a
    regression destroys the copy, never the system's /dev/null."""
    import stat

    from tests.storage.test_regular_files import device_node

    node = device_node(tmp_path)
    assert main(["config", "read", "--bus", "sim:thesis-test2", "-o", str(node)]) == 1
    assert f"{node}: is a character device, not a regular file; refused to replace it" \
        in capsys.readouterr().err
    assert stat.S_ISCHR(os.lstat(node).st_mode)
