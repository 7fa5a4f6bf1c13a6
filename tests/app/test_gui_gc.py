"""Garbage is collected on the GUI thread only (app/gui_gc.py): a closed window whose
wrappers form a cycle is freed by the GUI thread, never by a background thread that happens
to allocate (the trace docks' import, a bus session decoding frames). Freed there, its
C++ widget was destroyed off the GUI thread: the app tests' intermittent segfaults."""

from __future__ import annotations

import gc
import threading
import weakref

import pytest
from PySide6.QtWidgets import QWidget

pytestmark = pytest.mark.gui


class _Cycle:
    """What a closed window's wrappers are after a test (or a user) lets go of it: only a
    reference cycle holds them."""


def test_a_closed_window_in_a_cycle_is_freed_on_the_gui_thread_not_a_busy_one(
        make_window, qtbot):
    make_window()  # as in the app: the collector is the GUI thread's once a window exists
    gc.collect()  # (nothing young left: what follows is the only garbage)
    holder = _Cycle()
    holder.me = holder
    holder.window = QWidget()
    holder.window.setWindowTitle("closed early")
    holder.window.show()
    qtbot.waitExposed(holder.window)
    holder.window.close()
    freed_on: list[str] = []
    weakref.finalize(holder.window, lambda: freed_on.append(threading.current_thread().name))
    del holder  # garbage now, in a cycle: only a collection frees it

    kept: list[list] = []

    def busy() -> None:  # allocates as an import of numpy or a decoding bus thread does
        kept.extend([] for _ in range(20 * gc.get_threshold()[0]))

    worker = threading.Thread(target=busy, name="busy background thread")
    worker.start()
    worker.join()
    qtbot.waitUntil(lambda: bool(freed_on), timeout=5000)
    assert freed_on == [threading.main_thread().name]
    assert not gc.isenabled()  # no automatic collection, in any thread


def test_collecting_keeps_up_with_garbage_made_on_other_threads(make_window, qtbot):
    """The GUI thread's collector frees cycles made anywhere, as often as CPython would."""
    from pdcp_studio.app import gui_gc

    make_window()
    assert gui_gc.collecting()
    freed = threading.Event()

    def make_garbage() -> None:
        c = _Cycle()
        c.me = c
        weakref.finalize(c, freed.set)
        junk = [[] for _ in range(2 * gc.get_threshold()[0])]  # a collection is due
        make_garbage.junk = junk  # type: ignore[attr-defined]

    worker = threading.Thread(target=make_garbage)
    worker.start()
    worker.join()
    qtbot.waitUntil(freed.is_set, timeout=5000)
