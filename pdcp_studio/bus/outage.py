"""A pulled adapter: when to try reopening it and what to say, decided without a clock or a bus.

Issue 10 item 2: one line when the adapter goes away, one when it is back, and in between at
most one reminder every ``REMIND_S`` — never a line per failed read (a pulled slcan adapter once
wrote 101,988 lines in 6 s). Reopening backs off from ``BACKOFF_S[0]`` to ``BACKOFF_S[-1]``
between tries, so the wait is never a busy loop. Pure: :class:`Outage` takes ``now``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

#: Seconds between reopening tries: growing, then the last one for as long as it takes.
BACKOFF_S = (0.1, 0.25, 0.5, 1.0, 2.0)
#: While it stays away, a reminder line at most this often.
REMIND_S = 30.0


@dataclass
class Outage:
    """One adapter's outages: ``down_since`` is None while it works."""

    name: str
    backoff_s: tuple[float, ...] = BACKOFF_S
    remind_s: float = REMIND_S
    down_since: float | None = None
    attempts: int = 0
    next_try: float = 0.0
    outages: int = 0
    _reminded: float = field(default=0.0, repr=False)
    last_error: str = ""

    @property
    def down(self) -> bool:
        return self.down_since is not None

    def failed(self, now: float, why: str) -> str | None:
        """The bus raised: the line to say (None when it was already down)."""
        self.last_error = why
        if self.down_since is not None:
            return None
        self.down_since = self._reminded = now
        self.attempts = 0
        self.outages += 1
        self.next_try = now + self.backoff_s[0]
        return f"{self.name}: the adapter is disconnected ({why}); reconnecting"

    def due(self, now: float) -> bool:
        """True when a reopening try is due."""
        return self.down_since is not None and now >= self.next_try

    def wait(self, now: float) -> float:
        """Seconds until the next try (0 when due or up)."""
        return max(0.0, self.next_try - now) if self.down_since is not None else 0.0

    def attempt_failed(self, now: float, why: str) -> str | None:
        """A reopening try failed: schedule the next; a reminder line at most every
        ``remind_s`` (None otherwise)."""
        self.last_error = why
        self.attempts += 1
        step = self.backoff_s[min(self.attempts, len(self.backoff_s) - 1)]
        self.next_try = now + step
        if self.down_since is not None and now - self._reminded >= self.remind_s:
            self._reminded = now
            return (f"{self.name}: still disconnected after {now - self.down_since:.0f} s "
                    f"({self.attempts} tries; {why}); reconnecting")
        return None

    def reopened(self, now: float) -> str:
        """The adapter is back: the line to say."""
        since = self.down_since if self.down_since is not None else now
        tries = self.attempts + 1
        self.down_since = None
        self.attempts = 0
        return (f"{self.name}: the adapter is back after {now - since:.1f} s "
                f"({tries} {'try' if tries == 1 else 'tries'}); re-reading devices and links")
