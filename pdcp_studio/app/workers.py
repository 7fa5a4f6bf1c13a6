"""Run slow work (bus I/O, file I/O, detection) off the GUI thread.

A :class:`Worker` wraps a callable ``fn(progress, cancel)``: ``progress(done, total, text)``
reports how far it got and ``cancel`` is a :class:`threading.Event` it should poll. The
worker runs on a :class:`QThreadPool`; its public signals are emitted on the thread that
created it (the GUI thread), so no widget is ever touched from a pool thread and a slot
connected after ``start()`` is never missed. An exception becomes ``failed(message)``.

Public API: ``Worker(fn, description="")`` with ``start(pool=None)``, ``cancel()``,
``wait(timeout)``, ``is_running``, ``result``, ``error``; signals ``progress``,
``finished(object)``, ``failed(str)``, ``cancelled()``, ``done()``. ``Worker.call(f, *args)``
wraps a plain callable; ``run_in_thread(fn, on_finished=, on_failed=)``;
``run_with_progress(parent, title, fn) -> (worker, QProgressDialog)``;
``error_message(exc)``; raise ``Cancelled`` from ``fn`` to stop early.

``run_with_progress`` adds a non-blocking :class:`QProgressDialog` with a Cancel button.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from typing import Any

from PySide6.QtCore import QObject, QRunnable, Qt, QThreadPool, Signal
from PySide6.QtWidgets import QProgressDialog, QWidget

from pdcp_studio.app.i18n import translate
from pdcp_studio.errors import PdcpError

log = logging.getLogger(__name__)

ProgressFn = Callable[[int, int, str], None]
WorkFn = Callable[[ProgressFn, threading.Event], Any]

#: Progress reports closer together than this are dropped (the last one always gets through),
#: so a chatty loop cannot flood the GUI thread's event queue.
PROGRESS_INTERVAL_S = 0.03

# Workers still running, kept alive here so Python never collects one mid-flight.
_ACTIVE: set[Worker] = set()


def error_message(err: BaseException) -> str:
    """A message a user can read: our own errors say where and why already."""
    if isinstance(err, PdcpError):
        return str(err)
    if isinstance(err, OSError) and err.strerror:
        where = f"{err.filename}: " if err.filename else ""
        return f"{where}{err.strerror}"
    text = str(err)
    return f"{type(err).__name__}: {text}" if text else type(err).__name__


class Cancelled(Exception):
    """Raise from a work function to stop early; the worker then emits ``cancelled``."""


class _Runnable(QRunnable):
    def __init__(self, worker: Worker) -> None:
        super().__init__()
        self._worker = worker
        self.setAutoDelete(True)

    def run(self) -> None:  # runs on a pool thread
        self._worker._execute()


class Worker(QObject):
    """One piece of work on a thread pool; its signals are emitted on the thread that made it.

    Signals: ``progress(done, total, text)``; then exactly one of ``finished(result)``,
    ``failed(message)`` or ``cancelled()``; then always ``done()`` (for clean-up).

    The pool thread never emits these public signals itself: it hands the outcome to the
    worker's own thread (a queued private signal), which emits them there. So a caller may
    connect right after ``start()`` — even to a worker that has already finished — and its
    slots still run, on the GUI thread.
    """

    progress = Signal(int, int, str)
    finished = Signal(object)
    failed = Signal(str)
    cancelled = Signal()
    done = Signal()
    _progress = Signal(int, int, str)  # pool thread → own thread, re-emitted as ``progress``
    _outcome = Signal(str, object)  # pool thread → own thread: (kind, payload)

    def __init__(self, fn: WorkFn, description: str = "", parent: QObject | None = None) -> None:
        super().__init__(parent)
        self._fn = fn
        self.description = description or getattr(fn, "__name__", "work")
        self.cancel_event = threading.Event()
        self._last_progress = 0.0
        self._started = False
        self._finished_event = threading.Event()
        self.result: Any = None
        self.error: str | None = None
        #: The exception behind ``failed`` (None otherwise): callers that act on its kind.
        self.exception: BaseException | None = None
        self._progress.connect(self.progress)
        self._outcome.connect(self._deliver)

    @classmethod
    def call(cls, fn: Callable[..., Any], *args: Any, description: str = "",
             **kwargs: Any) -> Worker:
        """A worker for a plain callable that takes neither progress nor cancel."""
        return cls(lambda _p, _c: fn(*args, **kwargs),
                   description or getattr(fn, "__name__", "work"))

    # -- control (GUI thread) -----------------------------------------------------
    def start(self, pool: QThreadPool | None = None) -> Worker:
        """Queue the work; returns self so ``Worker(fn).start()`` reads naturally."""
        if self._started:
            raise RuntimeError(f"worker {self.description!r} was started twice")
        self._started = True
        _ACTIVE.add(self)
        (pool or QThreadPool.globalInstance()).start(_Runnable(self))
        return self

    def cancel(self) -> None:
        """Ask the work to stop; it stops when it next looks at its cancel event."""
        self.cancel_event.set()

    @property
    def is_running(self) -> bool:
        """True from ``start()`` until the work function has returned."""
        return self._started and not self._finished_event.is_set()

    def wait(self, timeout: float | None = None) -> bool:
        """Block until the work function returned (for shutdown and tests, not the GUI)."""
        return self._finished_event.wait(timeout)

    def _deliver(self, kind: str, payload: Any) -> None:
        """On the worker's own thread: emit the outcome, then ``done``, then let go."""
        try:
            if kind == "finished":
                self.finished.emit(payload)
            elif kind == "failed":
                self.failed.emit(payload)
            else:
                self.cancelled.emit()
            self.done.emit()
        finally:
            _ACTIVE.discard(self)

    # -- pool thread ----------------------------------------------------------------
    def _report(self, done: int, total: int, text: str = "") -> None:
        now = time.monotonic()
        if done < total and now - self._last_progress < PROGRESS_INTERVAL_S:
            return
        self._last_progress = now
        self._progress.emit(int(done), int(total), str(text))

    def _execute(self) -> None:
        try:
            result = self._fn(self._report, self.cancel_event)
        except Cancelled:
            self._end("cancelled", None)
        except BaseException as err:
            if self.cancel_event.is_set():
                self._end("cancelled", None)
                return
            if isinstance(err, PdcpError | OSError):  # expected: the message says it all
                log.info("%s failed: %s", self.description, err)
            else:  # a bug: keep the traceback
                log.warning("%s failed", self.description, exc_info=True)
            self.error = error_message(err)
            self.exception = err
            self._end("failed", self.error)
        else:
            if self.cancel_event.is_set():
                self._end("cancelled", None)
            else:
                self.result = result
                self._end("finished", result)

    def _end(self, kind: str, payload: Any) -> None:
        self._finished_event.set()
        self._outcome.emit(kind, payload)


def run_in_thread(fn: WorkFn, *, description: str = "", pool: QThreadPool | None = None,
                  on_finished: Callable[[Any], None] | None = None,
                  on_failed: Callable[[str], None] | None = None) -> Worker:
    """Start ``fn(progress, cancel)`` on the pool with optional result/error handlers."""
    worker = Worker(fn, description)
    if on_finished is not None:
        worker.finished.connect(on_finished)
    if on_failed is not None:
        worker.failed.connect(on_failed)
    return worker.start(pool)


def run_with_progress(parent: QWidget | None, title: str, fn: WorkFn, *,
                      pool: QThreadPool | None = None,
                      min_duration_ms: int = 400) -> tuple[Worker, QProgressDialog]:
    """Start ``fn`` with a window-modal progress dialog whose Cancel cancels the work.

    The dialog is shown (not exec'd) and only if the work takes longer than
    ``min_duration_ms``, so quick jobs never flash a window. It closes itself when the
    work ends; connect to the worker's signals for the outcome.
    """
    dialog = QProgressDialog(title, "Cancel", 0, 0, parent)
    dialog.setWindowTitle(title)
    dialog.setWindowModality(Qt.WindowModality.WindowModal)
    dialog.setMinimumDuration(min_duration_ms)
    dialog.setAutoClose(False)
    dialog.setAutoReset(False)
    worker = Worker(fn, title)

    def on_progress(done: int, total: int, text: str) -> None:
        if total > 0:
            dialog.setMaximum(total)
            dialog.setValue(min(done, total))
        if text:
            dialog.setLabelText(text)

    def on_done() -> None:
        dialog.close()
        dialog.deleteLater()

    def on_cancel() -> None:
        dialog.setLabelText(translate("workers", "Cancelling…"))
        worker.cancel()

    worker.progress.connect(on_progress)
    worker.done.connect(on_done)
    dialog.canceled.connect(on_cancel)
    worker.start(pool)
    return worker, dialog
