"""The headless arbitrator's log (issue 28): one line per event — a bus error the arbitrator
both logs and emits is written once, not twice — and at most 5 lines a second under hostile
traffic; a warning that is no event still reaches stderr, once."""

from __future__ import annotations

import io
import logging
import random
import threading
import time

import can
import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.cli.live.arbitrator import describe
from pdcp_studio.cli.live.arbitrator_log import HOLD_S, ArbitratorLog
from pdcp_studio.cli.main import main

#: How much later than its admission a line may be stamped on a loaded machine.
JITTER_S = 0.1


def _log(now):
    out, err = io.StringIO(), io.StringIO()
    return ArbitratorLog(describe, out=out, err=err, clock=lambda: now[0]), out, err


@pytest.mark.parametrize("order", ["warning first", "event first"])
def test_a_bus_error_logged_and_emitted_is_one_line(order):
    now = [0.0]
    log, out, err = _log(now)
    logger = logging.getLogger("pdcp_studio.test.arbitrator_log")
    logger.addHandler(log)
    try:
        if order == "warning first":  # as the arbitrator does: log, then emit
            logger.warning("%s: %s", "arbitrator", "error frame #1 on the bus")
            log.on_event(ev.BusError("error frame #1 on the bus", "error_frame"))
        else:
            log.on_event(ev.BusError("error frame #1 on the bus", "error_frame"))
            logger.warning("%s: %s", "arbitrator", "error frame #1 on the bus")
        now[0] = 5.0
        log.pump(0, final=True)
    finally:
        logger.removeHandler(log)
    assert out.getvalue() == "error error frame #1 on the bus\n"
    assert err.getvalue() == ""


def test_a_warning_that_is_no_event_reaches_stderr_once_after_its_hold():
    now = [0.0]
    log, out, err = _log(now)
    record = logging.LogRecord("pdcp_studio.bus.arbitrator.memory", logging.WARNING, "", 0,
                               "memory m.mem: slot A is damaged; using slot B", None, None)
    log.handle(record)
    log.pump(0)
    assert err.getvalue() == ""  # its event may still come
    now[0] = HOLD_S
    log.pump(0)
    log.pump(0, final=True)
    assert err.getvalue() == ("pdcp-studio: warning: memory m.mem: slot A is damaged; "
                              "using slot B\n")
    assert out.getvalue() == ""


class _Stamped(io.TextIOBase):
    """A stream that remembers when each line was written."""

    def __init__(self, lines: list[tuple[float, str]]) -> None:
        self.lines, self._part = lines, ""

    def writable(self) -> bool:
        return True

    def write(self, text: str) -> int:
        self._part += text
        while "\n" in self._part:
            line, self._part = self._part.split("\n", 1)
            self.lines.append((time.monotonic(), line))
        return len(text)


def test_hostile_traffic_writes_each_line_once_and_at_most_5_lines_a_second(monkeypatch):
    from pdcp_studio.bus.session.urls import unique_virtual_channel

    lines: list[tuple[float, str]] = []
    # As outside pytest: no handler on the root logger (pytest's own would hide the warnings
    # Python's last-resort handler writes to stderr).
    monkeypatch.setattr(logging.root, "handlers", [])
    monkeypatch.setattr("sys.stdout", _Stamped(lines))
    monkeypatch.setattr("sys.stderr", _Stamped(lines))
    channel = unique_virtual_channel("hostile-log")
    result: list[int] = []
    run = threading.Thread(target=lambda: result.append(main([
        "arbitrator", "--bus", f"can:virtual:{channel}", "--seconds", "5",
        "--startup-quiet", "0.2"])))
    bus = can.Bus(interface="virtual", channel=channel)
    run.start()
    try:
        r = random.Random(28)
        end = time.monotonic() + 4.5
        while time.monotonic() < end:  # device-mode garbage (mode 0) and error frames
            bus.send(can.Message(arbitration_id=r.randrange(0x800) & ~0x100,
                                 data=bytes(r.randrange(256) for _ in range(r.randrange(9))),
                                 is_extended_id=False))
            if r.random() < 0.05:
                bus.send(can.Message(arbitration_id=0, is_error_frame=True))
            time.sleep(0.0005)
        run.join(15)
    finally:
        bus.shutdown()
    assert result == [0]
    texts = [text for _, text in lines]
    assert any(t.startswith("arbitrator on ") for t in texts), texts
    assert texts[-1] == "arbitrator stopped"
    told = [text.removeprefix("error ").removeprefix("arbitrator: ")
            for text in texts if "frame #" in text]
    assert told and len(told) == len(set(told)), texts  # no line twice, on either stream
    times = [t for t, text in lines
             if not text.startswith(("arbitrator on", "arbitrator stopped", "arbitrating"))]
    assert len(times) >= 5
    # The budget counts by the time a line is admitted; these stamps are the time it reached
    # the stream, later by however long a loaded machine kept the writer waiting (tens of
    # milliseconds): two lines admitted 1.0 s apart can be stamped 0.95 s apart.
    window = 1.0 - JITTER_S
    assert max(sum(1 for t in times if start <= t < start + window) for start in times) <= 5, \
        texts
