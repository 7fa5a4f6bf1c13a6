"""Repeated events logged once, then summarised with counts at most once a second.

A noisy or hostile bus can produce thousands of undecodable frames, bus errors or retries a
second; logging each one drowns a clinic PC's disk and the person reading the log. A
:class:`RepeatLimiter` decides, per kind of event, which occurrences are told in full: the
first ``burst`` ones, then one a second (a token bucket); the others are counted and told as
one summary line per kind and interval ("1,234 more undecodable frames in the last 1.0 s").
Every occurrence is still counted by its owner (``bad_frames`` and the like); only the telling
is limited.

:class:`LimitedLog` puts it in front of a ``logging.Logger``. :class:`LineBudget` bounds a
whole log, all kinds together: at most so many lines in any second, the rest told as one
summary line a second (the headless arbitrator's output: at most 5 lines a second under any
traffic). The decisions are pure (the clock is passed in), so they are tested without threads
or sleeping. Thread-safe.
"""

from __future__ import annotations

import logging
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass

from pdcp_studio.protocol.records import MutableRecord, Record

#: Summaries of one kind come at most this often.
SUMMARY_INTERVAL_S = 1.0
#: Occurrences of one kind told in full before the limit starts.
DEFAULT_BURST = 1


@dataclass(eq=False, repr=False)
class _Kind(MutableRecord):
    """One kind's token bucket and what it held back since its last summary."""

    tokens: float
    refilled: float
    suppressed: int = 0
    since: float = 0.0
    last: str = ""


@dataclass(frozen=True, eq=False, repr=False)
class Summary(Record):
    """``count`` occurrences of ``kind`` not told in full over ``seconds``; ``last`` the latest."""

    kind: str
    count: int
    seconds: float
    last: str

    def text(self, what: str = "") -> str:
        label = what or self.kind
        return (f"{self.count:,} more {label} in the last {self.seconds:.1f} s "
                f"(latest: {self.last})")


class RepeatLimiter:
    """Per kind: the first ``burst`` occurrences in full, then at most one a second."""

    def __init__(self, burst: int = DEFAULT_BURST, interval_s: float = SUMMARY_INTERVAL_S,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.burst = max(1, burst)
        self.interval_s = interval_s
        self.clock = clock
        self._kinds: dict[str, _Kind] = {}
        self._lock = threading.Lock()
        #: Occurrences not told in full, all kinds, since the start.
        self.suppressed_total = 0

    def admit(self, kind: str, message: str = "", now: float | None = None
              ) -> tuple[bool, Summary | None]:
        """Whether this occurrence is told in full, and a summary that is due before it."""
        now = self.clock() if now is None else now
        with self._lock:
            state = self._kinds.get(kind)
            if state is None:
                state = self._kinds[kind] = _Kind(tokens=float(self.burst), refilled=now)
            summary = self._due(kind, state, now)
            gained = (now - state.refilled) / self.interval_s
            if gained > 0:
                state.tokens = min(float(self.burst), state.tokens + gained)
                state.refilled = now
            if state.tokens >= 1.0:
                state.tokens -= 1.0
                return True, summary
            if state.suppressed == 0:
                state.since = now
            state.suppressed += 1
            state.last = message
            self.suppressed_total += 1
            return False, summary

    def due(self, now: float | None = None, *, final: bool = False) -> list[Summary]:
        """Summaries whose interval has passed (call it from a periodic tick); ``final``:
        every pending one, as the work ends."""
        now = self.clock() if now is None else now
        with self._lock:
            out = [self._due(kind, state, now, final) for kind, state in self._kinds.items()]
        return [s for s in out if s is not None]

    def _due(self, kind: str, state: _Kind, now: float, final: bool = False) -> Summary | None:
        if state.suppressed == 0 or (now - state.since < self.interval_s and not final):
            return None
        summary = Summary(kind, state.suppressed, now - state.since, state.last)
        state.suppressed = 0
        state.since = now
        return summary


class LimitedLog:
    """A logger that tells repeated events once, then in summaries (see the module doc).

    ``log.warning("bad_frame", "undecodable frame: %s", why)``: ``kind`` groups repeats.
    Call :meth:`flush` from a periodic tick so a summary comes even when the events stop.
    """

    def __init__(self, logger: logging.Logger, prefix: str = "", *,
                 burst: int = DEFAULT_BURST, interval_s: float = SUMMARY_INTERVAL_S,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.logger = logger
        self.prefix = prefix
        self.limiter = RepeatLimiter(burst, interval_s, clock)
        self._levels: dict[str, int] = {}

    def log(self, level: int, kind: str, msg: str, *args: object, exc_info: bool = False
            ) -> bool:
        """Log ``msg % args`` if admitted; returns whether it was told in full."""
        text = msg % args if args else msg
        self._levels[kind] = level
        told, summary = self.limiter.admit(kind, text)
        if summary is not None:
            self._tell_summary(summary)
        if told:
            self.logger.log(level, "%s%s", self.prefix, text, exc_info=exc_info)
        return told

    def warning(self, kind: str, msg: str, *args: object) -> bool:
        return self.log(logging.WARNING, kind, msg, *args)

    def exception(self, kind: str, msg: str, *args: object) -> bool:
        return self.log(logging.ERROR, kind, msg, *args, exc_info=True)

    def flush(self, final: bool = False) -> None:
        """Tell the summaries that are due (``final``: all that are pending)."""
        for summary in self.limiter.due(final=final):
            self._tell_summary(summary)

    def _tell_summary(self, summary: Summary) -> None:
        level = self._levels.get(summary.kind, logging.WARNING)
        self.logger.log(level, "%s%s", self.prefix, summary.text())


class LineBudget:
    """At most ``lines`` lines told in any ``window_s`` seconds, whatever their kind; the
    others are counted and told as one summary at most once a window — so never more than
    ``lines + 1`` lines in any window."""

    def __init__(self, lines: int = 4, window_s: float = SUMMARY_INTERVAL_S,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.lines = max(1, lines)
        self.window_s = window_s
        self.clock = clock
        self._told: deque[float] = deque()
        self._suppressed = 0
        self._since = 0.0
        self._last = ""
        self._summarised = float("-inf")
        self._lock = threading.Lock()
        #: Lines not told in full since the start.
        self.suppressed_total = 0

    def admit(self, text: str, now: float | None = None) -> bool:
        """Whether this line is told now (else it is counted for the next summary)."""
        now = self.clock() if now is None else now
        with self._lock:
            while self._told and self._told[0] <= now - self.window_s:
                self._told.popleft()
            if len(self._told) < self.lines:
                self._told.append(now)
                return True
            if self._suppressed == 0:
                self._since = now
            self._suppressed += 1
            self._last = text
            self.suppressed_total += 1
            return False

    def summary(self, now: float | None = None, *, final: bool = False) -> Summary | None:
        """The summary of what was held back, when one is due (at most one a window;
        ``final``: whatever is pending, as the log ends)."""
        now = self.clock() if now is None else now
        with self._lock:
            if not self._suppressed:
                return None
            if not final and (now - self._summarised < self.window_s
                              or now - self._since < self.window_s):
                return None
            out = Summary("lines", self._suppressed, now - self._since, self._last)
            self._suppressed, self._summarised = 0, now
            return out
