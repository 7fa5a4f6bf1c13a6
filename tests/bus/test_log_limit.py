"""Repeated events told once, then summarised at most once a second (bus/log_limit.py)."""

from __future__ import annotations

import logging

import can

from pdcp_studio.bus.log_limit import LimitedLog, RepeatLimiter
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.bus.sim.device_host import DeviceHost


def test_the_first_occurrence_is_told_then_one_summary_a_second():
    limiter = RepeatLimiter(burst=1, interval_s=1.0)
    told = [limiter.admit("bad", f"frame {i}", now=i / 4000)[0] for i in range(4000)]
    assert told[0] and sum(told) == 1  # 4,000 in the first second: one told
    told, summary = limiter.admit("bad", "frame 4000", now=1.001)
    assert told  # a token a second
    assert summary is not None and summary.count == 3999 and summary.last == "frame 3999"
    assert "3,999 more undecodable frames in the last 1.0 s" in summary.text(
        "undecodable frames")
    assert limiter.due(now=1.5) == []  # nothing suppressed since
    assert not limiter.admit("bad", "x", now=1.6)[0]
    assert [s.count for s in limiter.due(now=2.7)] == [1]  # flushed by the tick


def test_kinds_are_limited_separately_and_a_burst_is_allowed():
    limiter = RepeatLimiter(burst=3, interval_s=1.0)
    a = [limiter.admit("a", now=0.0)[0] for _ in range(5)]
    b = [limiter.admit("b", now=0.0)[0] for _ in range(2)]
    assert a == [True, True, True, False, False] and b == [True, True]
    assert limiter.suppressed_total == 2


def test_a_hostile_rate_gives_a_few_lines_a_second(caplog):
    now = [0.0]
    log = LimitedLog(logging.getLogger("pdcp_studio.test.limit"), "bus: ",
                     clock=lambda: now[0])
    caplog.set_level(logging.WARNING, logger="pdcp_studio.test.limit")
    for i in range(40_000):  # 10 s at 4 kHz
        now[0] = i / 4000
        log.warning("bad_frame", "undecodable frame #%d", i)
        if i % 400 == 0:
            log.flush()
    lines = [r.getMessage() for r in caplog.records]
    assert len(lines) <= 2 * 10 + 2  # one told and one summary a second
    assert lines[0] == "bus: undecodable frame #0"
    assert any("more bad_frame in the last" in line for line in lines)


def test_a_failing_simulated_device_is_logged_once_then_summarised(caplog):
    bus = can.Bus(interface="virtual", channel=unique_virtual_channel("pdcp-limit"))
    host = DeviceHost(bus, name="limit devices")
    caplog.set_level(logging.WARNING, logger="pdcp_studio.bus.sim.device_host")
    try:
        def boom() -> None:
            raise RuntimeError("a device bug")

        for _ in range(2000):
            host.conn.post(boom)
        host.call(lambda: None, timeout=10)
        assert host.failures == 2000
    finally:
        host.close()
    records = [r for r in caplog.records if r.name == "pdcp_studio.bus.sim.device_host"]
    assert 1 <= len(records) <= 3, [r.getMessage() for r in records]
    assert records[0].exc_info is not None  # the first one with its traceback


def test_a_line_budget_tells_at_most_its_lines_and_one_summary_in_any_window():
    """All kinds together (issue 28): at most 4 lines and 1 summary in any second."""
    from pdcp_studio.bus.log_limit import LineBudget

    budget = LineBudget(lines=4, window_s=1.0)
    told: list[float] = []
    for i in range(20_000):  # 20,000 lines over 10 s
        now = i / 2000
        if budget.admit(f"line {i}", now=now):
            told.append(now)
        if budget.summary(now=now) is not None:
            told.append(now)
    assert told
    assert max(sum(1 for t in told if start <= t < start + 1.0)
               for start in (x / 100 for x in range(1000))) <= 5
    assert budget.suppressed_total > 19_000
    final = budget.summary(now=10.0, final=True)
    assert final is None or final.count < 4000


def test_a_line_budget_summary_counts_and_names_the_latest():
    from pdcp_studio.bus.log_limit import LineBudget

    budget = LineBudget(lines=2, window_s=1.0)
    assert [budget.admit(str(i), now=0.1 * i) for i in range(5)] == [True, True, False,
                                                                     False, False]
    assert budget.summary(now=0.5) is None  # not a window since the first held back
    summary = budget.summary(now=1.3)
    assert summary is not None and (summary.count, summary.last) == (3, "4")
    assert budget.summary(now=1.4) is None and budget.summary(now=5.0, final=True) is None
