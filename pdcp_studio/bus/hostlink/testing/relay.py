"""A serial line between two pseudo-terminals, at a UART's speed and with its faults.

``PtyRelay(server_path)`` opens the pseudo-terminal a host-link server serves on and makes a
second one (``client_path``) for the PC's side; one thread per direction copies bytes across
at ``bytes_per_s`` (12,800 for 128000 baud 8N1) and through ``spoil(direction, data)``, which
may flip bits, drop bytes or add garbage. ``cut()`` makes the line go silent (a peer that
vanished) and ``mend()`` restores it; :class:`Cutter` cuts it at a chosen point of an exchange
(after so many more bytes one way) for a while, as the recovery tests need (docs/host-link.md
§3.4). It counts the bytes carried each way, so benchmarks
and tests can measure what a job costs on the line. For tests and benchmarks only.
"""

from __future__ import annotations

import contextlib
import os
import random
import select
import threading
import time
from collections.abc import Callable
from typing import Any

Spoil = Callable[[str, bytes], bytes]
#: Directions: host → arbitrator and arbitrator → host.
TO_ARB, TO_HOST = "to_arbitrator", "to_host"


class PtyRelay:
    """Bytes between the arbitrator's pty (``server_path``) and a new pty for the host."""

    def __init__(self, server_path: str, *, bytes_per_s: float | None = None,
                 spoil: Spoil | None = None) -> None:
        import tty

        self.bytes_per_s = bytes_per_s
        self.spoil = spoil
        self.carried = {TO_ARB: 0, TO_HOST: 0}
        self._server = os.open(server_path, os.O_RDWR | os.O_NOCTTY)
        tty.setraw(self._server)
        self._master, self._slave = os.openpty()
        tty.setraw(self._slave)
        self.client_path = os.ttyname(self._slave)
        self._cut = threading.Event()
        self._stop = threading.Event()
        self._threads = [
            threading.Thread(target=self._pump, args=(self._master, self._server, TO_ARB),
                             daemon=True, name="pty relay to arbitrator"),
            threading.Thread(target=self._pump, args=(self._server, self._master, TO_HOST),
                             daemon=True, name="pty relay to host"),
        ]
        for thread in self._threads:
            thread.start()

    @property
    def total(self) -> int:
        return self.carried[TO_ARB] + self.carried[TO_HOST]

    def reset_counts(self) -> None:
        self.carried = {TO_ARB: 0, TO_HOST: 0}

    def cut(self) -> None:
        self._cut.set()

    def mend(self) -> None:
        self._cut.clear()

    def close(self) -> None:
        self._stop.set()
        for thread in self._threads:
            thread.join(timeout=2.0)
        for fd in (self._server, self._master, self._slave):
            try:
                os.close(fd)
            except OSError:
                pass

    def __enter__(self) -> PtyRelay:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _pump(self, src: int, dst: int, direction: str) -> None:
        next_free = time.perf_counter()
        while not self._stop.is_set():
            ready, _, _ = select.select([src], [], [], 0.02)
            if not ready:
                continue
            try:
                data = os.read(src, 256)
            except OSError:
                time.sleep(0.02)
                continue
            if self._cut.is_set() or not data:
                continue
            if self.spoil is not None:
                data = self.spoil(direction, data)
            if self.bytes_per_s:
                # the UART sends one byte after another: wait for the line to be free
                now = time.perf_counter()
                next_free = max(next_free, now) + len(data) / self.bytes_per_s
                wait = next_free - now
                if wait > 0:
                    time.sleep(wait)
            self.carried[direction] += len(data)
            view = memoryview(data)
            while view and not self._stop.is_set():
                try:
                    view = view[os.write(dst, view):]
                except BlockingIOError:
                    time.sleep(0.001)
                except OSError:
                    break


class Cutter:
    """A ``spoil`` that, once armed, passes ``after`` more bytes one way and then drops every
    byte both ways for ``seconds`` (or, with ``cut_now``, drops them from now on)."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.armed: tuple[str, int, float] | None = None
        self.until = 0.0

    def arm(self, direction: str, after: int, seconds: float) -> None:
        with self.lock:
            self.armed = (direction, after, seconds)

    def cut_now(self, seconds: float) -> None:
        with self.lock:
            self.until = time.monotonic() + seconds

    @property
    def cutting(self) -> bool:
        return time.monotonic() < self.until or self.armed is not None

    def __call__(self, direction: str, data: bytes) -> bytes:
        with self.lock:
            now = time.monotonic()
            if now < self.until:
                return b""
            if self.armed is not None and self.armed[0] == direction:
                _, after, seconds = self.armed
                if len(data) <= after:
                    self.armed = (direction, after - len(data), seconds)
                    return data
                self.armed = None
                self.until = now + seconds
                return data[:after]
            return data


class NoisyLine:
    """A ``spoil`` with a bit error rate and occasional bursts of garbage (seeded)."""

    def __init__(self, bit_error_rate: float, burst_every: int = 0, burst_len: int = 16,
                 seed: int = 1) -> None:
        self.ber = bit_error_rate
        self.burst_every = burst_every
        self.burst_len = burst_len
        self.rng = random.Random(seed)
        self.flips = 0
        self.bursts = 0
        self._since_burst = 0

    def __call__(self, direction: str, data: bytes) -> bytes:
        out = bytearray(data)
        if self.ber:
            bits = len(out) * 8
            n = self._binomial(bits)
            for _ in range(n):
                pos = self.rng.randrange(bits)
                out[pos // 8] ^= 1 << (pos % 8)
            self.flips += n
        if self.burst_every:
            self._since_burst += len(out)
            if self._since_burst >= self.burst_every:
                self._since_burst = 0
                self.bursts += 1
                garbage = bytes(self.rng.randrange(256) for _ in range(self.burst_len))
                at = self.rng.randrange(len(out) + 1)
                out[at:at] = garbage
        return bytes(out)

    def _binomial(self, n: int) -> int:
        expected = n * self.ber
        if expected > 5:
            return max(0, round(self.rng.gauss(expected, expected ** 0.5)))
        count, p = 0, self.ber
        # few expected errors: count them one by one (geometric gaps)
        import math

        pos = 0
        while True:
            u = self.rng.random()
            pos += int(math.log(1 - u) / math.log(1 - p)) + 1 if p < 1 else 1
            if pos > n:
                return count
            count += 1


def cut_during_request(point: str, cutter: Cutter, session: Any,
                       long_request: Callable[[], object], seconds: float) -> bool:
    """Cut the line at ``point`` of an exchange: "request" (the request never arrives),
    "reply" (it arrives, its ACK and reply do not) or "reply-half" (``long_request``'s reply
    broken off after 40 bytes); the request during the cut may fail. False for any other
    point (the caller cuts it its own way)."""
    from pdcp_studio.errors import PdcpError

    cuts = {"request": (TO_ARB, 0, session.status), "reply": (TO_HOST, 0, session.status),
            "reply-half": (TO_HOST, 40, long_request)}
    if point not in cuts:
        return False
    direction, after, call = cuts[point]
    cutter.arm(direction, after, seconds)
    with contextlib.suppress(PdcpError):  # the request during the cut may fail; the next
        call()                            # one must not (the caller checks that)
    return True
