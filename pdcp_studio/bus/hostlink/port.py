"""Serial ports for the host link: pyserial URLs, a new pseudo-terminal, and reopening.

``open_port("pty")`` makes a new pseudo-terminal (its ``slave_path`` is where the other end
connects), anything else is a pyserial URL (``/dev/ttyUSB0``, ``COM3``, ``socket://…``).
:class:`Reopener` paces attempts to reopen a dropped port (backoff 0.1 s doubling to 2 s) and
says so once per outage, not once per attempt; :class:`SerialLine` is the read-or-reopen loop
both ends of the link run on it (the PC's ``conn.py`` and the arbitrator's ``server.py``).
"""

from __future__ import annotations

import logging
import os
import select
import threading
import time
from collections.abc import Callable
from typing import Protocol

from pdcp_studio.errors import TransportError

log = logging.getLogger(__name__)

DEFAULT_BAUD = 128_000
#: How long one read waits (bounds how fast a reader thread notices close()).
READ_TIMEOUT_S = 0.05
#: How long a write may wait for the peer to read (then the bytes are dropped: the link
#: layer sends again what matters).
WRITE_TIMEOUT_S = 2.0
#: Reopening a dropped port: first wait, growth, longest wait.
BACKOFF_FIRST_S = 0.1
BACKOFF_FACTOR = 2.0
BACKOFF_MAX_S = 2.0


class Port(Protocol):
    """What the host link needs of a serial port (pyserial's ``Serial`` has all of it)."""

    def read(self, size: int = 1) -> bytes: ...
    def write(self, data: bytes) -> int | None: ...
    def close(self) -> None: ...


class PtyPort:
    """The master end of a new pseudo-terminal; the peer opens ``slave_path`` with pyserial."""

    def __init__(self) -> None:
        import tty

        self._master, self._slave = os.openpty()
        tty.setraw(self._slave)
        os.set_blocking(self._master, False)  # no echo, no line editing: bytes pass unchanged
        self.slave_path = os.ttyname(self._slave)
        self.baudrate = DEFAULT_BAUD
        self._closed = False

    def read(self, size: int = 1) -> bytes:
        if self._closed:
            raise OSError("the pseudo-terminal is closed")
        ready, _, _ = select.select([self._master], [], [], READ_TIMEOUT_S)
        if not ready:
            return b""
        try:
            return os.read(self._master, max(size, 4096))
        except BlockingIOError:
            return b""
        except OSError:  # EIO while no peer has the slave open
            time.sleep(READ_TIMEOUT_S)
            return b""

    def write(self, data: bytes) -> int:
        """Write it all, or OSError when the peer has not read for ``WRITE_TIMEOUT_S`` (a
        pseudo-terminal nobody reads fills up and would block the writer for ever)."""
        view = memoryview(data)
        deadline = time.monotonic() + WRITE_TIMEOUT_S
        while view:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([], [self._master], [], left)[1]:
                raise OSError(f"nobody reads {self.slave_path}: {len(view)} bytes not written")
            try:
                view = view[os.write(self._master, view):]
            except BlockingIOError:
                continue
        return len(data)

    def close(self) -> None:
        if not self._closed:
            self._closed = True
            os.close(self._master)
            os.close(self._slave)


def open_port(name: str, baudrate: int = DEFAULT_BAUD, where: str = "host link") -> Port:
    """``pty`` → a new :class:`PtyPort`; anything else → pyserial ``serial_for_url``.
    TransportError names ``where`` (the bus URL) and the port, and ends with the fix
    (``bus/session/serial_ports.py``)."""
    if name == "pty":
        return PtyPort()
    import serial

    try:
        port: Port = serial.serial_for_url(name, baudrate=baudrate, timeout=READ_TIMEOUT_S,
                                           write_timeout=5.0)
    except (serial.SerialException, ValueError, OSError) as err:
        from pdcp_studio.bus.session.serial_ports import open_failure, seen_ports

        raise TransportError(open_failure(where, name, err, seen_ports())) from err
    return port


def read_available(port: Port) -> bytes:
    """What the port has now, waiting at most its read timeout for the first byte."""
    waiting = getattr(port, "in_waiting", 0) or 0
    return bytes(port.read(max(1, waiting)))


class Reopener:
    """Backoff and one calm message per outage while a dropped port is opened again."""

    def __init__(self, what: str, report: Callable[[str], None]) -> None:
        self.what = what
        self.report = report
        self.outages = 0
        self._delay = BACKOFF_FIRST_S
        self._down = False

    @property
    def down(self) -> bool:
        return self._down

    def lost(self, err: object) -> None:
        if not self._down:
            self._down = True
            self.outages += 1
            self._delay = BACKOFF_FIRST_S
            self.report(f"{self.what}: the serial port was lost ({err}); reopening it")

    def wait(self, stop: threading.Event) -> None:
        """Sleep the current backoff (returns early when ``stop`` is set) and grow it."""
        stop.wait(self._delay)
        self._delay = min(self._delay * BACKOFF_FACTOR, BACKOFF_MAX_S)

    def back(self) -> None:
        if self._down:
            self._down = False
            log.info("%s: the serial port is open again", self.what)


class SerialLine:
    """A serial port that survives being pulled out: each :meth:`read` gives what the port
    has, and when it fails the port is closed, the outage said once and the port opened again
    by name with backoff. The owner is told through ``on_lost(err)`` (before the port is
    closed) and ``on_reopened()`` (before the line counts as back: make a fresh link state).
    A port handed in, or a pseudo-terminal made here (``"pty"``), cannot be opened again by
    name: its line waits instead until it reads again."""

    def __init__(self, port: Port | str, baudrate: int, where: str, stop: threading.Event,
                 report: Callable[[str], None], *, on_lost: Callable[[object], None],
                 on_reopened: Callable[[], None]) -> None:
        self._name = port if isinstance(port, str) and port != "pty" else None
        self.port: Port = open_port(port, baudrate, where) if isinstance(port, str) else port
        self.baudrate = baudrate
        self.where = where
        self.reopener = Reopener(where, report)
        self._stop = stop
        self._on_lost = on_lost
        self._on_reopened = on_reopened

    @property
    def down(self) -> bool:
        """The port was lost and is not open again yet."""
        return self.reopener.down

    def read(self) -> bytes | None:
        """What the port has now (b"" when nothing came within its read timeout); None when
        there is nothing to handle this round: the port is down, or it just failed."""
        if self.reopener.down and not self._reopen():
            return None
        try:
            return read_available(self.port)
        except Exception as err:
            if not self._stop.is_set():
                self._lose(err)
            return None

    def close(self) -> None:
        try:
            self.port.close()
        except Exception:
            log.debug("%s: closing the port failed", self.where, exc_info=True)

    def _lose(self, err: object) -> None:
        self.reopener.lost(err)
        self._on_lost(err)
        if self._name is None:
            self._stop.wait(0.2)
            return
        self.close()

    def _reopen(self) -> bool:
        if self._name is None:
            self.reopener.back()
            return True
        self.reopener.wait(self._stop)
        if self._stop.is_set():
            return False
        try:
            self.port = open_port(self._name, self.baudrate, self.where)
        except Exception:
            return False
        self._on_reopened()
        self.reopener.back()
        return True
