"""Workers: results, progress, cancel and failures arrive on the GUI thread, never a widget
touched from a pool thread."""

from __future__ import annotations

import threading
import time

import pytest
from PySide6.QtCore import Qt, QThread
from PySide6.QtWidgets import QApplication, QLabel, QPushButton

from pdcp_studio.app import workers
from pdcp_studio.app.workers import Cancelled, Worker, error_message, run_in_thread
from pdcp_studio.errors import TransportError

pytestmark = pytest.mark.gui


def _on_gui_thread() -> bool:
    return QThread.currentThread() is QApplication.instance().thread()


def test_result_and_progress_are_delivered_on_the_gui_thread(qtbot):
    label = QLabel()
    qtbot.addWidget(label)
    seen: list[tuple[int, int, str, bool]] = []
    work_thread: list[bool] = []

    def work(progress, cancel):
        work_thread.append(_on_gui_thread())
        for i in range(5):
            progress(i, 4, f"step {i}")
            time.sleep(workers.PROGRESS_INTERVAL_S + 0.005)
        return 42

    worker = Worker(work, "count")

    def on_progress(done, total, text):
        seen.append((done, total, text, _on_gui_thread()))
        label.setText(text)  # touching a widget here is only legal on the GUI thread

    results: list[tuple[object, bool]] = []
    worker.progress.connect(on_progress)
    worker.finished.connect(lambda r: results.append((r, _on_gui_thread())))
    with qtbot.waitSignal(worker.done, timeout=5000):
        worker.start()
    assert work_thread == [False]  # the work itself ran on a pool thread
    assert results == [(42, True)]
    assert [s[:3] for s in seen] == [(i, 4, f"step {i}") for i in range(5)]
    assert all(s[3] for s in seen)
    assert label.text() == "step 4"
    assert worker.result == 42 and not worker.is_running


def test_chatty_progress_is_throttled_but_the_last_report_arrives(qtbot):
    seen: list[int] = []
    worker = Worker(lambda progress, cancel: [progress(i, 10_000, "") for i in range(10_001)])
    worker.progress.connect(lambda done, total, text: seen.append(done))
    with qtbot.waitSignal(worker.done, timeout=5000):
        worker.start()
    assert seen[-1] == 10_000
    assert len(seen) < 200  # 10,001 reports in a tight loop: most were dropped


def test_cancel_stops_the_work_and_emits_cancelled_not_finished(qtbot):
    started = threading.Event()
    loops: list[int] = []

    def work(progress, cancel):
        started.set()
        while not cancel.is_set():
            loops.append(1)
            time.sleep(0.005)
        return "ran to the end"

    worker = Worker(work, "spin")
    outcome: list[str] = []
    worker.finished.connect(lambda r: outcome.append("finished"))
    worker.cancelled.connect(lambda: outcome.append("cancelled"))
    worker.failed.connect(lambda m: outcome.append("failed"))
    worker.start()
    assert started.wait(5)
    assert worker.is_running
    with qtbot.waitSignal(worker.done, timeout=5000):
        worker.cancel()
    assert outcome == ["cancelled"]
    assert worker.result is None


def test_raising_cancelled_is_a_cancel(qtbot):
    def work(progress, cancel):
        raise Cancelled()

    worker = Worker(work)
    with qtbot.waitSignal(worker.cancelled, timeout=5000):
        worker.start()


def test_failure_becomes_a_readable_message(qtbot):
    def work(progress, cancel):
        raise TransportError("can:pcan:PCAN_USBBUS1: the driver for 'pcan' is not installed")

    messages: list[tuple[str, bool]] = []
    worker = run_in_thread(work, on_failed=lambda m: messages.append((m, _on_gui_thread())))
    qtbot.waitUntil(lambda: bool(messages), timeout=5000)
    assert messages == [("can:pcan:PCAN_USBBUS1: the driver for 'pcan' is not installed", True)]
    assert worker.error == messages[0][0]


def test_error_messages_say_what_went_wrong():
    err = FileNotFoundError(2, "No such file or directory", "/tmp/x.pdcfg")
    assert error_message(err) == "/tmp/x.pdcfg: No such file or directory"
    assert error_message(ValueError("bad value")) == "ValueError: bad value"
    assert error_message(KeyError()) == "KeyError"


def test_worker_call_wraps_a_plain_callable(qtbot):
    worker = Worker.call(sum, [1, 2, 3])
    with qtbot.waitSignal(worker.finished, timeout=5000) as blocker:
        worker.start()
    assert blocker.args == [6]
    with pytest.raises(RuntimeError, match="started twice"):
        worker.start()


def test_run_with_progress_dialog_cancel_button_cancels(qtbot):
    started = threading.Event()

    def work(progress, cancel):
        started.set()
        progress(1, 3, "reading")
        while not cancel.is_set():
            time.sleep(0.005)

    worker, dialog = workers.run_with_progress(None, "Scan", work, min_duration_ms=0)
    assert started.wait(5)
    qtbot.waitUntil(lambda: dialog.labelText() == "reading", timeout=5000)
    assert dialog.maximum() == 3 and dialog.value() == 1
    with qtbot.waitSignal(worker.cancelled, timeout=5000):
        qtbot.mouseClick(dialog.findChild(QPushButton), Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: not dialog.isVisible(), timeout=5000)


def test_handlers_run_even_when_nobody_keeps_a_reference_to_the_worker(qtbot):
    """Regression: the worker dropped its own reference on ``done`` before the other queued
    ``done`` handlers ran, and PySide then discarded them with the deleted sender."""
    calls: list[str] = []

    def start() -> None:
        worker = Worker(lambda p, c: 1)
        worker.finished.connect(lambda r: calls.append(f"finished {r}"))
        worker.done.connect(lambda: calls.append("first"))
        worker.done.connect(lambda: calls.append("second"))
        worker.start()

    start()  # the local reference is gone when start() returns
    qtbot.waitUntil(lambda: len(calls) == 3, timeout=5000)
    assert calls == ["finished 1", "first", "second"]
    qtbot.waitUntil(lambda: not workers._ACTIVE, timeout=5000)  # and released afterwards


def test_slots_connected_after_the_work_already_ended_still_run(qtbot):
    """Regression: a caller connects after ``start()``; fast work may be done by then (the
    bridge returns started workers). The outcome must still reach the late slot."""
    worker = Worker(lambda p, c: "quick").start()
    assert worker.wait(5)  # the work function has returned on its pool thread
    time.sleep(0.05)
    late: list[object] = []
    worker.finished.connect(late.append)
    worker.done.connect(lambda: late.append("done"))
    qtbot.waitUntil(lambda: len(late) == 2, timeout=5000)
    assert late == ["quick", "done"]
