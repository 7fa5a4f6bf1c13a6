"""The arbitrator's two-slot non-volatile memory: power cuts leave old or new, never a mix."""

from __future__ import annotations

import logging
import os
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest

from pdcp_studio.bus.arbitrator import memory as M
from pdcp_studio.bus.arbitrator.memory import HEADER_SIZE, MemoryStore, MemoryStoreError
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.storage import config_codec


def collection(tag: int, links: int = 3) -> ConfigCollection:
    """A distinct collection per ``tag`` (serial numbers carry it), ``links`` long."""
    return ConfigCollection([StoredConfiguration(1, [
        StoredLink(StoredChannel(1, 2, 2, tag, 0x5300, 0x1110),
                   StoredChannel(n % 255 + 1, 2, 2, 1000 + tag, 0x5000, 0x1100), n + 1)
        for n in range(links)
    ])])


class PowerCut(BaseException):
    """Raised by the step hook: nothing more gets written (like the power going)."""


def test_empty_memory_reads_as_no_configuration(tmp_path):
    store = MemoryStore(tmp_path / "mem")
    assert store.read() == ConfigCollection()
    assert store.read_bytes() is None
    assert store.generation == 0
    assert (tmp_path / "mem").exists()


def test_round_trip_alternates_slots_and_counts_generations(tmp_path):
    store = MemoryStore(tmp_path / "mem", capacity=4096)
    for n in range(1, 6):
        assert store.write(collection(n)) == n
        assert store.read() == collection(n)
        assert MemoryStore(tmp_path / "mem", capacity=4096).read() == collection(n)
    raw = (tmp_path / "mem").read_bytes()
    assert raw[:4] == M.MAGIC and raw[HEADER_SIZE + 4096:HEADER_SIZE + 4096 + 4] == M.MAGIC
    assert not store.warnings


def test_ram_store_behaves_the_same():
    store = MemoryStore(None, capacity=2048)
    assert store.read() == ConfigCollection()
    store.write(collection(1))
    store.write(collection(2))
    assert store.read() == collection(2)
    assert store.erase() == 3
    assert store.read() == ConfigCollection()


@pytest.mark.parametrize("links", [1, 60])  # one chunk, and several
def test_a_cut_at_any_step_leaves_the_old_or_the_new_configuration(tmp_path, links):
    path = tmp_path / "mem"
    MemoryStore(path, capacity=8192).write(collection(1, links))
    MemoryStore(path, capacity=8192).write(collection(2, links))
    image = path.read_bytes()
    steps: list[str] = []
    MemoryStore(path, capacity=8192, step_hook=steps.append).write(collection(3, links))
    assert steps[-1] == "header synced" and len(steps) >= 4
    for cut in range(len(steps)):
        path.write_bytes(image)
        calls = iter(range(len(steps)))

        def hook(step: str, cut: int = cut, calls=calls) -> None:
            if next(calls) == cut:
                raise PowerCut(step)

        with pytest.raises(PowerCut):
            MemoryStore(path, capacity=8192, step_hook=hook).write(collection(3, links))
        got = MemoryStore(path, capacity=8192).read()
        # Until the last step the new slot is not whole: the previous configuration is read.
        assert got == (collection(3, links) if cut == len(steps) - 1 else collection(2, links))


def test_a_damaged_slot_is_skipped_with_a_warning(tmp_path, caplog):
    path = tmp_path / "mem"
    store = MemoryStore(path, capacity=1024)
    store.write(collection(1))  # slot A, generation 1
    store.write(collection(2))  # slot B, generation 2
    raw = bytearray(path.read_bytes())
    raw[HEADER_SIZE + 1024 + HEADER_SIZE + 5] ^= 0xFF  # flip a payload byte in slot B
    path.write_bytes(bytes(raw))
    with caplog.at_level(logging.WARNING, logger="pdcp_studio.bus.arbitrator.memory"):
        fresh = MemoryStore(path, capacity=1024)
        assert fresh.read() == collection(1)
    assert "slot B is damaged" in caplog.text and "using slot A (generation 1)" in caplog.text
    assert fresh.warnings and "checksum" in fresh.warnings[0]
    # The next write goes into the damaged slot, so the good one survives it.
    assert fresh.write(collection(3)) == 2
    assert MemoryStore(path, capacity=1024).read() == collection(3)


def test_both_slots_damaged_reads_as_nothing_stored_with_warnings(tmp_path, caplog):
    path = tmp_path / "mem"
    store = MemoryStore(path, capacity=512)
    store.write(collection(1))
    store.write(collection(2))
    raw = bytearray(path.read_bytes())
    raw[HEADER_SIZE + 2] ^= 1
    raw[512 + 2 * HEADER_SIZE + 2] ^= 1
    path.write_bytes(bytes(raw))
    with caplog.at_level(logging.WARNING):
        assert MemoryStore(path, capacity=512).read() == ConfigCollection()
    assert caplog.text.count("is damaged") == 2


def test_a_plain_pdcfg_file_is_refused_as_a_configuration_never_converted(tmp_path):
    """``--memory fig410.pdcfg`` once turned the configuration into a 1 MiB memory image."""
    path = tmp_path / "thesis.pdcfg"
    config_codec.save_path(collection(5), path)
    before = path.read_bytes()
    with pytest.raises(MemoryStoreError, match=r"is a stored-configuration file \(\.pdcfg\), "
                                               "not a memory image"):
        MemoryStore(path, capacity=2048)
    assert path.read_bytes() == before


def test_a_file_that_is_not_a_memory_is_refused_and_never_overwritten(tmp_path):
    path = tmp_path / "notes.txt"
    path.write_bytes(b"shopping list: milk, eggs, a CAN adapter" * 3)
    with pytest.raises(MemoryStoreError, match="is not a memory image"):
        MemoryStore(path)
    assert path.read_bytes().startswith(b"shopping list")


@pytest.mark.parametrize("make", ["empty", "written", "slot A erased", "first write cut"])
def test_a_memory_image_in_any_state_it_can_be_in_opens(tmp_path, make):
    """An empty file, a written one, one whose slot A header is blank (slot B holds the
    configuration) and one whose first write was cut before its header: all memories."""
    path = tmp_path / "m.mem"
    if make == "empty":
        path.write_bytes(b"")
    else:
        store = MemoryStore(path, capacity=512)
        store.write(collection(1))
        if make == "slot A erased":
            store.write(collection(2))
            store.write(collection(3))  # generation 3 in slot A, 2 in slot B
            raw = bytearray(path.read_bytes())
            raw[:HEADER_SIZE] = bytes(HEADER_SIZE)
            path.write_bytes(bytes(raw))
        elif make == "first write cut":
            path.write_bytes(bytes(HEADER_SIZE) + config_codec.dumps(collection(1)))
    assert M.memory_file_problem(path, 512) is None
    MemoryStore(path, capacity=512).read()


def test_a_fifo_or_a_device_as_the_memory_is_refused_at_once(tmp_path):
    fifo = tmp_path / "m.fifo"
    os.mkfifo(fifo)
    assert M.memory_file_problem(fifo) == "is a FIFO (named pipe), not a memory file"
    assert M.memory_file_problem("/dev/zero") == "is a character device, not a memory file"
    # The store itself reports such a memory unreadable at each read, never waits on it.
    def let_go() -> None:  # a reader that waits on the pipe fails the test, not hangs it
        try:
            os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
        except OSError:
            pass

    timer = threading.Timer(5.0, let_go)
    timer.start()
    started = time.monotonic()
    try:
        with pytest.raises(OSError, match="FIFO"):
            MemoryStore(fifo).read()
    finally:
        timer.cancel()
    assert time.monotonic() - started < 1.0


def test_a_configuration_too_large_for_the_slot_is_refused(tmp_path):
    store = MemoryStore(tmp_path / "mem", capacity=64)
    store.write(collection(1, 1))
    with pytest.raises(MemoryStoreError, match="holds 64"):
        store.write(collection(2, 10))
    assert store.read() == collection(1, 1)


_CUT_SCRIPT = textwrap.dedent("""
    import os, sys
    from pdcp_studio.bus.arbitrator.memory import MemoryStore
    sys.path.insert(0, {root!r})
    from tests.bus.test_memory import collection
    path, cut = sys.argv[1], int(sys.argv[2])
    calls = iter(range(1000))
    def hook(step):
        if next(calls) == cut:
            os._exit(3)  # the process dies between two writes: nothing is flushed or closed
    MemoryStore(path, capacity=16384, step_hook=hook).write(collection(3, 200))
    os._exit(0)
""")


def test_a_process_dying_between_writes_leaves_old_or_new(tmp_path):
    path = tmp_path / "mem"
    MemoryStore(path, capacity=16384).write(collection(1, 200))
    MemoryStore(path, capacity=16384).write(collection(2, 200))
    steps: list[str] = []
    probe = tmp_path / "probe"
    probe.write_bytes(path.read_bytes())
    MemoryStore(probe, capacity=16384, step_hook=steps.append).write(collection(3, 200))
    image = path.read_bytes()
    script = _CUT_SCRIPT.format(root=str(Path(__file__).resolve().parents[2]))
    for cut in (0, len(steps) // 2, len(steps) - 3, len(steps) - 2, len(steps) - 1, 999):
        path.write_bytes(image)
        done = subprocess.run([sys.executable, "-c", script, str(path), str(cut)],
                              capture_output=True, text=True, timeout=60)
        assert done.returncode == (0 if cut == 999 else 3), done.stderr
        got = MemoryStore(path, capacity=16384).read()
        new = cut >= len(steps) - 1
        assert got == (collection(3, 200) if new else collection(2, 200)), cut


def test_a_slot_holds_exactly_the_largest_collection_the_codec_accepts():
    """The memory keeps its own copy of the codec's limit (so an empty memory needs no codec
    at start-up); the two must never drift apart."""
    from pdcp_studio.storage import config_codec

    assert M.SLOT_CAPACITY == config_codec.MAX_INPUT_BYTES
