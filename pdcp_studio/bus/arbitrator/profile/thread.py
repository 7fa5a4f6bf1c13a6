"""The profile thread: start-up once it is due, then the duty cycle whenever it is.

The profile driver decides *when* from ``now`` and what it is told of the arbitrator's
business, and carries the plans out; this thread asks it at every wake-up (at most 20 ms
apart), while the arbitrator arbitrates and runs the profile layer.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable

from pdcp_studio.bus.arbitrator.profile.driver import ProfileDriver
from pdcp_studio.bus.arbitrator.state import ReportError
from pdcp_studio.errors import PdcpError
from pdcp_studio.model.refs import DeviceKey

log = logging.getLogger("pdcp_studio.bus.arbitrator.core")  # one logger for the arbitrator


class ProfileThread:
    """The body of the profile thread. ``may_run``: the profile layer is on and the bus is
    ours; ``busy``: binds held or deferred, set-ups or jobs under way; ``setting_up``: a
    set-up is; ``caught_up``: every frame received is handled; ``present``: the devices on
    the bus; ``closed``: the arbitrator is closing (a plan cut off then is no news);
    ``ran``: told after start-up or a duty cycle ran (the bus may have settled)."""

    def __init__(self, driver: ProfileDriver, *, stop: threading.Event, wake: threading.Event,
                 may_run: Callable[[], bool], busy: Callable[[], bool],
                 setting_up: Callable[[], bool], caught_up: Callable[[], bool],
                 present: Callable[[], list[DeviceKey]], error: ReportError,
                 closed: Callable[[], bool], ran: Callable[[], None], name: str) -> None:
        self._driver = driver
        self._stop, self._wake = stop, wake
        self._may_run = may_run
        self._busy = busy
        self._setting_up = setting_up
        self._caught_up = caught_up
        self._present = present
        self._error = error
        self._closed = closed
        self._ran = ran
        self._name = name

    def run(self) -> None:
        driver = self._driver
        while not self._stop.is_set():
            self._wake.wait(0.02)
            self._wake.clear()
            if self._stop.is_set() or not self._may_run():
                continue  # (listening, or another arbitrator is on the bus)
            now = time.monotonic()
            try:
                if not driver.startup_done:
                    setting_up = self._setting_up()
                    present = frozenset(self._present()) if driver.expected else frozenset()
                    due = driver.startup_due(now, self._busy(), setting_up, self._caught_up(),
                                             present)
                    if due == "late":
                        self._error(f"start-up runs after {driver.startup_max_wait_s:g} s "
                                    "although binding has not settled (a device keeps asking "
                                    "for an ID it is not given)", "setup")
                    if due:
                        try:
                            driver.run_startup()
                        finally:
                            self._ran()
                elif driver.duty_due(now, self._busy()):
                    try:
                        driver.run_duty_cycle()
                    finally:
                        self._ran()
            except PdcpError as err:
                if not self._closed():  # a plan cut off by closing the session is no news
                    self._error(f"profile layer: {err}", "plan")
            except Exception:
                log.exception("%s: the profile layer failed", self._name)


__all__ = ["ProfileThread"]
