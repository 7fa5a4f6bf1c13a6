"""Cyclic garbage is collected on the GUI thread only.

CPython runs its cyclic collector in whichever thread happens to allocate when a threshold
is crossed. A closed window (or scene, or dialog) whose Python wrappers form a cycle is
freed by that collection, and freeing a Qt wrapper deletes its C++ widget; when the
allocating thread was a background one (the trace docks' import of numpy, a bus session
decoding frames, the networkx preload), the widget was destroyed off the GUI thread while
the GUI thread painted: the intermittent segfaults of the app tests (``QWidget::~QWidget``
under ``gc_collect_main`` on the "import trace docks" thread; the GUI thread in
``Sbk_GetPyOverride`` on a half-freed wrapper, or "Legend has no ``_rows``").

So the automatic collector is switched off and the GUI thread collects on a timer, with
CPython's own thresholds (the same generations, as often as the garbage asks for it): the
way pyqtgraph's ``GarbageCollector`` does it for the same reason.

Public API
    ``collect_on_gui_thread() -> bool`` — from the GUI thread once a QCoreApplication
    exists (idempotent); False (and nothing changed) without one, or off the GUI thread.
    ``collecting() -> bool`` — whether the GUI thread's collector is running.
"""

from __future__ import annotations

import gc
import threading

import shiboken6
from PySide6.QtCore import QCoreApplication, QObject, QTimer

#: How often the GUI thread looks whether a collection is due (a look costs ~1 µs).
CHECK_MS = 100

_collector: _Collector | None = None


class _Collector(QObject):
    """A timer on the GUI thread that runs the collections CPython's thresholds call for."""

    def __init__(self, parent: QObject) -> None:
        super().__init__(parent)
        self.threshold = gc.get_threshold()
        self.timer = QTimer(self)
        self.timer.timeout.connect(self.check)
        self.timer.start(CHECK_MS)

    def check(self) -> None:
        t0, t1, t2 = self.threshold
        c0, c1, c2 = gc.get_count()
        if c0 <= t0:
            return
        # As CPython chooses once the youngest generation is due: the oldest one due.
        gc.collect(2 if c2 > t2 else 1 if c1 > t1 else 0)


def collect_on_gui_thread() -> bool:
    """Switch the automatic collector off and collect on the GUI thread from now on."""
    global _collector
    app = QCoreApplication.instance()
    if app is None or threading.current_thread() is not threading.main_thread():
        return False
    gc.disable()
    if _collector is None or not shiboken6.isValid(_collector):
        _collector = _Collector(app)
    return True


def collecting() -> bool:
    return (_collector is not None and shiboken6.isValid(_collector)
            and _collector.timer.isActive() and not gc.isenabled())
