"""The headless arbitrator's log: one line per event, each said once, at most 5 a second.

The arbitrator tells a bus error (and a pulled or returned adapter) twice: as a Python
warning and as an event. ``arbitrator`` prints its events on stdout, one line each; Python's
last-resort handler printed the warning on stderr as well, so every such line was written
twice. Here a handler on PDCP Studio's loggers takes the warnings instead: one the arbitrator
also tells as an event (the same text, before or after it) is dropped; any other goes to
stderr as ``pdcp-studio: warning: …`` once its event has had ``HOLD_S`` to come.

Error lines and warnings, all kinds together, pass one :class:`LineBudget`: 4 lines in any
second and one summary line ("1,234 more errors and warnings in the last 1.0 s"), so hostile
traffic never writes more than 5 lines a second. Joins, leaves, links and plans are changes
of the prosthesis: each is one line, never held back.
"""

from __future__ import annotations

import logging
import queue
import sys
import threading
import time
from collections.abc import Callable
from typing import Any, TextIO

from pdcp_studio.bus.log_limit import LineBudget
from pdcp_studio.model.safe_text import shown

#: A warning waits this long for the event that tells the same before it is printed alone.
HOLD_S = 0.25
#: An event's text is remembered this long to drop the warning that comes after it.
REMEMBER_S = 2.0
#: Error lines and warnings told in any second (a summary line comes on top: 5 in all).
ERROR_LINES_PER_S = 4
#: Loggers whose warnings another handler already prints (``cli/main.py``).
_SAID_ELSEWHERE = ("pdcp_studio.bus.session.urls",)


def _same(warning: str, message: str) -> bool:
    """A warning that says what an event says (the arbitrator logs ``name: message``)."""
    return warning == message or warning.endswith(f": {message}")


class ArbitratorLog(logging.Handler):
    """Events from the arbitrator's threads (:meth:`on_event`) and warnings from its loggers
    (a logging handler) in, lines out on the main thread (:meth:`pump`)."""

    def __init__(self, describe: Callable[[Any], str | None], *,
                 out: TextIO | None = None, err: TextIO | None = None,
                 clock: Callable[[], float] = time.monotonic) -> None:
        super().__init__(logging.WARNING)
        self.describe = describe
        self.out, self.err = out, err
        self.clock = clock
        self.budget = LineBudget(ERROR_LINES_PER_S, clock=clock)
        self._lines: queue.SimpleQueue[tuple[str, str]] = queue.SimpleQueue()
        self._lock = threading.Lock()
        self._events: dict[str, float] = {}
        self._pending: list[tuple[float, str]] = []

    # -- in: the arbitrator's threads -----------------------------------------------------
    def on_event(self, event: Any) -> None:
        """An arbitrator event: its line is queued; its text marks the same warning as said."""
        from pdcp_studio.bus import events as ev

        text = self.describe(event)
        message = getattr(event, "message", None)
        if isinstance(message, str) and message:
            with self._lock:
                self._events[message] = self.clock()
                self._pending = [(t, w) for t, w in self._pending if not _same(w, message)]
        if text is not None:
            kind = "error" if isinstance(event, ev.BusError) else "event"
            self._lines.put((kind, shown(text, newlines=True)))

    def emit(self, record: logging.LogRecord) -> None:
        """A warning of PDCP Studio's loggers: held until its event could have come."""
        if record.name.startswith(_SAID_ELSEWHERE):
            return
        try:
            text = record.getMessage()
            if record.exc_info and record.exc_info[1] is not None:
                exc = record.exc_info[1]
                text += f" ({type(exc).__name__}: {exc})"  # one line, not a traceback
        except Exception:
            self.handleError(record)
            return
        now = self.clock()
        with self._lock:
            self._events = {m: t for m, t in self._events.items() if now - t < REMEMBER_S}
            if any(_same(text, m) for m in self._events):
                return  # its event is (or will be) the line
            self._pending.append((now, text))

    # -- out: the main thread -------------------------------------------------------------
    def pump(self, timeout: float = 0.1, *, final: bool = False) -> None:
        """Print what is due, waiting up to ``timeout`` for a line; ``final``: everything."""
        try:
            item = self._lines.get(timeout=timeout) if timeout > 0 else self._lines.get_nowait()
        except queue.Empty:
            item = None
        while item is not None:
            self._print(*item)
            try:
                item = self._lines.get_nowait()
            except queue.Empty:
                item = None
        now = self.clock()
        with self._lock:
            due = [w for t, w in self._pending if final or now - t >= HOLD_S]
            self._pending = [(t, w) for t, w in self._pending if not (final or now - t >= HOLD_S)]
        for text in due:
            self._print("warning", shown(text, newlines=True))
        summary = self.budget.summary(final=final)
        if summary is not None:
            self._write(self.out, "error " + shown(summary.text("errors and warnings")))

    def _print(self, kind: str, text: str) -> None:
        if kind == "event":
            self._write(self.out, text)
        elif self.budget.admit(text.removeprefix("error ")):
            if kind == "error":  # the event's own line ("error …")
                self._write(self.out, text)
            else:
                self._write(self.err, f"pdcp-studio: warning: {text}", sys.stderr)

    @staticmethod
    def _write(stream: TextIO | None, line: str, default: TextIO | None = None) -> None:
        """One line, flushed; the standard streams are looked up at each line."""
        print(line, file=stream or default or sys.stdout, flush=True)

    def install(self, logger: str = "pdcp_studio") -> None:
        """Take the warnings of ``logger`` (and below) from now on, until :meth:`uninstall`."""
        logging.getLogger(logger).addHandler(self)

    def uninstall(self, logger: str = "pdcp_studio") -> None:
        logging.getLogger(logger).removeHandler(self)
