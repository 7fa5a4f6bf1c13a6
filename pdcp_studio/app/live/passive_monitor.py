"""Listening to a ``can:`` bus another arbitrator runs, without ever sending (reference §5).

When connecting finds another bus arbitrator (the prosthesis's own control unit), PDCP Studio
must not arbitrate; it may still show the traffic. :class:`PassiveMonitor` opens the
python-can bus in the interface's listen-only mode where it has one (as ``monitor --bus``
does), wraps it so that a send is impossible, decodes every frame off the GUI thread with a
passive :class:`~pdcp_studio.bus.trace.decoder.FrameDecoder` that learns the node map from what it
hears (the set-up it sees, and what the traffic proves: ``bus/trace/inference.py``) and
hands batches of ``FrameSeen`` to the monitor dock, and the parts and links that learning
proves (``heard_bus.py``) to the graph.

Signals: ``frames(list[FrameSeen])`` (one batch per ``BATCH_S``), ``heard(System,
positions)`` (what the traffic proves, when it changed, at most once per ``HEARD_S``),
``stopped(str)`` (the reason, '' when stopped on purpose).
"""

from __future__ import annotations

import logging
import threading
import time
from typing import Any

from PySide6.QtCore import QObject, Signal

log = logging.getLogger(__name__)

#: Frames are handed to the GUI at most this often.
BATCH_S = 0.05
#: What the traffic proves is handed to the graph at most this often.
HEARD_S = 1.0
_POLL_S = 0.05


class _NoSend:
    """A python-can bus that can only be read: sending raises (nothing ever transmits)."""

    def __init__(self, bus: Any) -> None:
        self._bus = bus

    def recv(self, timeout: float) -> Any:
        return self._bus.recv(timeout=timeout)

    def send(self, *_args: Any, **_kw: Any) -> None:
        raise RuntimeError("a passive monitor never transmits")

    def shutdown(self) -> None:
        self._bus.shutdown()


def open_listen_only(url: str) -> Any:
    """The python-can bus of a ``can:`` URL, opened listen-only where the interface can be
    (TransportError / BusUrlError name the URL)."""
    from pdcp_studio.bus.session.urls import (
        BusUrlError,
        check_bus_url,
        listen_only_options,
        open_spec,
    )

    spec = check_bus_url(url)
    if spec.kind != "can":
        raise BusUrlError(f"{url}: only a CAN bus can be monitored passively")
    return _NoSend(open_spec(spec, **listen_only_options(spec)))


class _Proof:
    """Hands on what the listening proves about the bus when it changed (``HEARD_S``
    apart at most): the ``System`` and its cards' places, both made on the listening
    thread (the layout walks the whole bus)."""

    def __init__(self, emit: Any) -> None:
        self._emit = emit
        self._version = -1
        self._shown: Any = None
        self._due = 0.0

    def check(self, decoder: Any, now: float) -> None:
        if decoder.version == self._version or now < self._due:
            return
        from pdcp_studio.app.graph import layout
        from pdcp_studio.app.live.heard_bus import heard_system, signature

        self._version, self._due = decoder.version, now + HEARD_S
        system = heard_system(decoder)
        shown = signature(system)
        if shown != self._shown and system.devices:
            self._shown = shown
            self._emit(system, layout.place(system, {}, 1.0))


class PassiveMonitor(QObject):
    """A listen-only view of one ``can:`` bus; ``start()`` opens it on a thread."""

    frames = Signal(list)
    heard = Signal(object, object)
    stopped = Signal(str)

    def __init__(self, url: str, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.url = url
        self.received = 0  # frames heard so far
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._opened = threading.Event()

    @property
    def is_running(self) -> bool:
        return self._thread is not None and self._thread.is_alive()

    def start(self) -> None:
        self._thread = threading.Thread(target=self._run, name=f"passive {self.url}",
                                        daemon=True)
        self._thread.start()

    def wait_open(self, timeout: float = 5.0) -> bool:
        """For tests: True once the bus is open and being read."""
        return self._opened.wait(timeout)

    def stop(self, timeout: float = 2.0) -> None:
        """Stop listening and close the bus (bounded wait)."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout)

    def _run(self) -> None:  # the listening thread
        from pdcp_studio.bus.events import FrameSeen
        from pdcp_studio.bus.trace.decoder import FrameDecoder

        try:
            bus = open_listen_only(self.url)
        except Exception as err:  # the URL or the adapter: said once, in one line
            from pdcp_studio.app.workers import error_message

            self.stopped.emit(error_message(err))
            return
        self._opened.set()
        decoder = FrameDecoder(passive=True)
        decoder.learn_from_traffic([])  # devices and channels placed as their frames come
        batch: list[Any] = []
        due = time.monotonic() + BATCH_S
        proves = _Proof(self.heard.emit)
        reason = ""
        try:
            while not self._stop.is_set():
                msg = bus.recv(timeout=_POLL_S)
                if msg is not None:
                    frame = decoder.decode_message(msg)
                    batch.append(FrameSeen(msg.timestamp or time.time(), msg.arbitration_id,
                                           bytes(msg.data), frame.line))
                now = time.monotonic()
                if batch and now >= due:
                    self.received += len(batch)
                    self.frames.emit(batch)
                    batch = []
                    due = now + BATCH_S
                    proves.check(decoder, now)
        except Exception as err:
            log.warning("passive monitor on %s", self.url, exc_info=True)
            reason = str(err) or type(err).__name__
        finally:
            if batch:
                self.received += len(batch)
                self.frames.emit(batch)
            bus.shutdown()
        self.stopped.emit(reason)
