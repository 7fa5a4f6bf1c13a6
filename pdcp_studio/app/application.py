"""Start the desktop app: a file, a bus, or the start page (no file, no bus).

``run_app`` is what ``pdcp-studio`` and ``pdcp-studio gui`` call. With ``screenshot`` it
waits until the first system is on screen and laid out, saves the window as a PNG and
exits (contracts §2). With the environment variable ``PDCP_STUDIO_STARTUP_PROBE`` set it
prints how long start-up took once the window is shown and laid out, and when each of its
phases ended (:class:`StartUpPhases`), then exits — the start-up benchmark uses it.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from concurrent.futures import Future

    from PySide6.QtWidgets import QApplication

    from pdcp_studio.app.documents.recovery import Recovery
    from pdcp_studio.bus.session.api import BusSession

PROBE_ENV = "PDCP_STUDIO_STARTUP_PROBE"
#: A screenshot run gives up after this long (a bus that never answers must not hang CI).
SCREENSHOT_TIMEOUT_MS = 30_000
#: After "ready", let queued layout and paint events settle before grabbing.
SETTLE_MS = 150
#: The interpreter's switch interval for the whole app once its window is live (CPython's
#: default is 5 ms); until then the default (see :func:`start_up_quietly`).
SWITCH_INTERVAL_S = 0.001
START_UP_SWITCH_INTERVAL_S = 0.005
#: Start-up's settings are given back after this long even if the window never gets ready.
START_UP_LIMIT_MS = 10_000


class StartUpPhases:
    """When each phase of start-up ended: seconds since ``started``, the process's CPU
    seconds (all threads) and the GUI thread's then, printed by the probe as
    ``<phase>_s=<wall>/<cpu>/<gui cpu>`` so the benchmark can say where the time goes
    (imported: the window's modules; built: the window made; shown: shown, the bus
    connecting; opened: the session open; ready: the first system on screen)."""

    def __init__(self, started: float) -> None:
        self.started = started
        self.ends: dict[str, tuple[float, float, float]] = {}

    def end(self, phase: str) -> None:
        """``phase`` ends now (the first time only; on the GUI thread)."""
        self.ends.setdefault(phase, (time.perf_counter() - self.started, time.process_time(),
                                     time.thread_time()))

    def fields(self) -> str:
        return " ".join(f"{phase}_s={wall:.3f}/{cpu:.3f}/{gui:.3f}"
                        for phase, (wall, cpu, gui) in self.ends.items())


def run_app(path: str | Path | None = None, bus: str | None = None,
            screenshot: str | Path | None = None, *, size: tuple[int, int] | None = None,
            started: float | None = None, lang: str | None = None,
            capture: str | Path | None = None) -> int:
    """Run the app until its window closes; returns the exit status.

    ``path`` is opened before the window appears so a bad file fails like any CLI input
    (``SystemFileError`` / ``ConfigFormatError`` → exit 2 in the CLI). ``capture`` opens in
    the trace once the window is up (the start page under it); one that cannot be read
    says why there.
    """
    started = time.perf_counter() if started is None else started
    start_up_quietly()  # until the window is live (start_up_over, connected in _run_app)
    try:
        return _run_app(path, bus, screenshot, size=size, started=started, lang=lang,
                        capture=capture)
    finally:
        start_up_over()  # however it ended (a bad file, a window never ready)


def _run_app(path: str | Path | None, bus: str | None, screenshot: str | Path | None, *,
             size: tuple[int, int] | None, started: float, lang: str | None,
             capture: str | Path | None = None) -> int:
    from pdcp_studio.app.pyside_import_scan import spare_source_scan

    spare_source_scan()  # before the app's imports: PySide6 would read each one's source
    opened = None
    if path is not None:
        from pdcp_studio.app.documents import files

        opened = files.open_path(path)

    if screenshot is not None and not _has_display():
        # A screenshot needs no screen: render off screen (CI, ssh) rather than abort.
        os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtCore import QTimer

    app = _application()
    app.setApplicationName("PDCP Studio")
    app.setOrganizationName("PDCP Studio")
    app.setApplicationDisplayName("PDCP Studio")
    app.setDesktopFileName("pdcp-studio")  # matches packaging/pdcp-studio.desktop
    from pdcp_studio.app import i18n

    i18n.install(app, lang)  # the system's language, or --lang
    _set_icon(app)

    from pdcp_studio.app.smoke import SMOKE_ENV

    smoke_report = os.environ.get(SMOKE_ENV)
    scripted = screenshot is not None or bool(os.environ.get(PROBE_ENV)) or bool(smoke_report)
    recovery = None if scripted else _recovery()
    opening = None
    if bus is not None and path is None and not _has_pending(recovery):
        # The bus opens on a thread of its own from now on, while the window is made: a
        # simulated prosthesis spends most of its ~0.3 s start-up waiting for its threads'
        # frames, time the window's construction can use. (Not while unsaved work waits
        # to be recovered: the user may take that instead of the bus.)
        opening = open_early(bus)
        _preload_layout()  # networkx too: the bus's first snapshot is laid out with it
    from pdcp_studio.app.window.main_window import DEFAULT_BUS, MainWindow

    phases = StartUpPhases(started)
    phases.end("imported")
    window = MainWindow(recovery=recovery)
    window.quiet = scripted
    if not scripted:
        from pdcp_studio.app.window.controllers.desktop import remember_layout

        remember_layout(window)  # last session's size and docks; saved again on close
    if size is not None:
        window.resize(*size)
    phases.end("built")
    status = {"code": 0}

    def finish_screenshot(png: str | Path) -> None:
        window._make_trace_docks()  # made just after the window is up: in the picture too
        app.processEvents()  # their tabs are laid out
        window.view.fit_all()
        bridge = window.live.bridge
        if window.progress.isVisible() and (bridge is None or not bridge.busy):
            window.progress.hide()  # the last job's bar, hidden a moment later anyway
        # A .pdcfg opens in its own window (app/configuration/window.py): that is what was asked
        # for.
        target = (getattr(window, "config_windows", None) or [window])[-1]
        target.view.fit_all()
        target.view.settle()  # every card's picture drawn, not the first few
        image = target.grab()
        # Not when what was asked for is not on screen: no picture of an empty window.
        if not status["code"] and not image.save(str(png), "PNG"):
            from pdcp_studio.storage.write_failure import why_not_written  # the CLI's words

            print(f"pdcp-studio: error: {why_not_written(png)}", file=sys.stderr)
            status["code"] = 1
        window.doc.mark_saved()  # nothing to ask about on the way out
        window.close()
        app.quit()

    def smoke() -> None:
        from pdcp_studio.app import smoke as smoke_mod

        status["code"] = smoke_mod.run(window, str(smoke_report))
        window.doc.mark_saved()
        window.close()
        app.quit()

    def on_ready() -> None:
        if smoke_report:
            QTimer.singleShot(SETTLE_MS, smoke)
        if os.environ.get(PROBE_ENV):
            QTimer.singleShot(0, probe)
        if screenshot is not None:
            png = screenshot
            QTimer.singleShot(SETTLE_MS, lambda: after_capture(lambda: finish_screenshot(png)))

    def after_capture(then: Callable[[], None]) -> None:
        """``then`` once the capture asked for is read (its rows and banner in the picture)."""
        if capture is not None and window.bus_docks.monitor_dock().loading.worker is not None:
            QTimer.singleShot(50, lambda: after_capture(then))
        else:
            then()

    def probe() -> None:
        app.processEvents()
        print(f"startup_s={time.perf_counter() - started:.3f} "
              f"devices={len(window.doc.system.devices)} live={window.live.is_live} "
              f"cpu_s={time.process_time():.3f} "  # the process's, all threads
              f"gui_cpu_s={time.thread_time():.3f} "  # this (the GUI) thread's
              f"{phases.fields()}", flush=True)
        window.doc.mark_saved()
        window.close()
        app.quit()

    def give_up() -> None:
        if not window.is_ready:
            print("pdcp-studio: error: the window did not finish loading in time",
                  file=sys.stderr)
            status["code"] = 1
            window.doc.mark_saved()
            window.close()
            app.quit()

    def on_failed(url: str, message: str) -> None:
        # A bus asked for by name that does not answer is a failure for a scripted run
        # (the built-in prosthesis falls back to its file instead, and says so).
        if scripted and url != DEFAULT_BUS:
            where = "" if message.startswith(url) else f"{url}: "
            print(f"pdcp-studio: error: {where}{message}", file=sys.stderr)
            status["code"] = 1

    window.live.failed.connect(on_failed)
    window.live.bridgeReady.connect(lambda _bridge: phases.end("opened"))
    window.ready.connect(lambda: phases.end("ready"))
    window.ready.connect(start_up_over)  # before on_ready: the probe's CPU is the app's
    window.ready.connect(on_ready)
    QTimer.singleShot(START_UP_LIMIT_MS, start_up_over)  # a window that never gets ready
    window.show()
    if opened is not None and path is not None:
        window.show_opened(opened, Path(path))
    elif not scripted and window.offer_recovery():
        _discard(opening)  # the recovered document is on screen; connect later (Bus menu)
    elif bus is None:
        window.show_start()  # no file, no bus: the start page (tasks, connect, open, recent)
        QTimer.singleShot(0, _preload_layout)
    else:
        window.connect_bus(bus, opening)
        if opening is None:
            # The graph's layout needs networkx (~0.3 s to import): load it while the bus
            # connects on its worker, not after the bus has answered.
            QTimer.singleShot(0, _preload_layout)
    if capture is not None:
        window.desktop.open_capture(Path(capture))
    if screenshot is not None or os.environ.get(PROBE_ENV) or smoke_report:
        QTimer.singleShot(SCREENSHOT_TIMEOUT_MS, give_up)
    phases.end("shown")
    code = app.exec()
    window.live.disconnect_bus()
    return status["code"] or int(code)


def open_early(url: str) -> Future[BusSession]:
    """Start opening ``url``'s session on a thread of its own (no Qt there); the window's
    connection takes it (``LiveController.connect_bus``). Its failure is the connection's."""
    import threading
    from concurrent.futures import Future

    opening: Future[BusSession] = Future()

    def run() -> None:
        if not opening.set_running_or_notify_cancel():
            return
        try:
            from pdcp_studio.bus.session.opening import open_session

            opening.set_result(open_session(url))
        except BaseException as err:  # the worker that takes it raises it (as open_session)
            opening.set_exception(err)

    threading.Thread(target=run, name=f"open {url}", daemon=True).start()
    return opening


def _has_pending(recovery: Recovery | None) -> bool:
    """Is there unsaved work from a crash to offer back?"""
    return recovery is not None and bool(recovery.pending())


def _discard(opening: Future[BusSession] | None) -> None:
    """Close the early session nobody takes, once it has opened."""
    def close(done: Future[BusSession]) -> None:
        if done.exception() is None:
            done.result().close()

    if opening is not None:
        opening.add_done_callback(close)


def start_up_quietly() -> None:
    """Until the window is live: no cyclic garbage collection, CPython's default switch
    interval.

    Start-up imports ~750 modules and builds the window: ~160 collections, 70-100 ms of a
    2-core machine, for ~1,000 unreachable objects in all.
    The window freezes what start-up made once it is ready (``MainWindow._mark_ready``),
    so those objects are never looked at again anyway. The 1 ms switch interval is for the
    live trace (:func:`share_the_interpreter`); while the GUI thread, the bus opening and the
    networkx import all want the interpreter at once it only adds hand-overs: start-up took
    ~0.1 s less CPU with the default (benchmarks/gui.py, ``--only startup``)."""
    import gc

    gc.disable()
    sys.setswitchinterval(START_UP_SWITCH_INTERVAL_S)


def start_up_over() -> None:
    """The window is live (or start-up gave up waiting for it): collect garbage again (on
    the GUI thread only: :mod:`pdcp_studio.app.gui_gc`), and the app's switch interval from
    now on. Safe to call more than once."""
    import gc

    from pdcp_studio.app.gui_gc import collect_on_gui_thread

    if not collect_on_gui_thread():  # no application (a start-up that failed before one)
        gc.enable()
    share_the_interpreter()


def share_the_interpreter() -> None:
    """Let the GUI thread take the interpreter sooner from the bus threads, decided once at
    start-up for the whole app.

    Qt calls into Python for every cell it paints and every event a Python object handles,
    and each call waits for the interpreter lock; with a session thread decoding a saturated
    bus, CPython hands the lock over only every switch interval (5 ms by default), so painting
    the trace's table took hundreds of ms (benchmarks/gui.py, trace case: 196 ms gaps at 5 ms,
    56 ms at 0.5 ms on a loaded 2-core machine). Shorter intervals cost the bus threads
    little. Set once the window is live (:func:`start_up_over`)."""
    if sys.getswitchinterval() > SWITCH_INTERVAL_S:
        sys.setswitchinterval(SWITCH_INTERVAL_S)


def _recovery() -> Recovery | None:
    """The autosave store, or None when this build has none."""
    try:
        from pdcp_studio.app.documents.recovery import Recovery
    except ImportError:
        return None
    return Recovery()


def _preload_layout() -> None:
    """Import networkx on a thread of its own (an import of ~0.3 s on the GUI thread was
    a stall the user saw)."""
    import threading

    def load() -> None:
        import networkx  # noqa: F401

    threading.Thread(target=load, name="preload networkx", daemon=True).start()


def _application() -> QApplication:
    """The app's QApplication: the one already made (tests make theirs), else a new one."""
    from PySide6.QtWidgets import QApplication

    existing = QApplication.instance()
    if existing is None:
        return QApplication(sys.argv[:1])
    if not isinstance(existing, QApplication):
        raise RuntimeError("a QCoreApplication without widgets is already running")
    return existing


def _has_display() -> bool:
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
                or os.environ.get("QT_QPA_PLATFORM") or sys.platform in ("win32", "darwin"))


def _set_icon(app: QApplication) -> None:
    from PySide6.QtGui import QIcon

    try:
        from pdcp_studio.paths import icon_path

        icon = icon_path()
    except FileNotFoundError:
        return
    if icon.is_file():
        app.setWindowIcon(QIcon(str(icon)))
