"""The profile-layer driver: start-up, the hot-swap duty cycle and applying engine plans.

Start-up (listing 4.1) runs once binding has been quiet for ``startup_quiet_s`` — but at the
latest ``startup_max_wait_s`` after the arbitrator started; the duty cycle (listing 4.2) runs
``duty_quiet_s`` after the last join or leave. When is decided by :meth:`ProfileDriver.startup_due`
and :meth:`ProfileDriver.duty_due` from ``now`` and the arbitrator's business (pure); the plans
themselves come from :mod:`pdcp_studio.engine` and are carried out by the link writer on the
profile thread the arbitrator starts (:meth:`ProfileDriver.loop`).

Start-up implements a stored configuration and the duty cycle makes and removes links on a
prosthesis that may be worn and moving: both are changes reference §5's motion interlock
covers. So the devices whose outputs feed a terminal channel before or after the plan are held
(Suspend Device, bounded and renewed) while the plan is written, and released after; one that
refuses to hold still stops the plan before anything is written (said as an error; the
channels it would have replaced are planned for again at the next join or leave). A plan
that changes no link writes nothing and holds nothing.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Literal

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.transaction import (
    Status,
    TransactionResult,
    describe_interlock,
    interlocked_devices,
)
from pdcp_studio.errors import PdcpError
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import System

if TYPE_CHECKING:
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.engine.plan import Plan

log = logging.getLogger("pdcp_studio.bus.arbitrator.core")  # one logger for the arbitrator


def present_refs(system: System) -> set[ChannelRef]:
    """The channels of the devices on the bus."""
    return {ref for ref, _ in system.channels() if system.is_present(ref)}


class ProfileDriver:
    """Start-up, duty cycle and plans of an :class:`Arbitrator`, and when they are due."""

    def __init__(self, arb: Arbitrator, now: float, *, quiet_s: float, duty_quiet_s: float,
                 max_wait_s: float, listen_until: float) -> None:
        self.arb = arb
        self.startup_quiet_s = quiet_s
        self.duty_quiet_s = duty_quiet_s
        self.startup_max_wait_s = max_wait_s
        self.started = now
        self.last_bind = now  # the last bind request (start-up waits for quiet)
        self.last_change = now  # the last join, leave or set-up (the duty cycle waits)
        self.listen_until = listen_until  # binding waits while the bus is being heard
        self.startup_done = False
        self.duty_needed = False
        self.last_present: set[ChannelRef] = set()  # before the joins and leaves since
        self.plan_running = 0
        self.applied_plans: list[Plan] = []
        #: The devices the first start-up may stop waiting for (:meth:`expect`).
        self.expected: frozenset[DeviceKey] = frozenset()

    def expect(self, keys: set[DeviceKey] | frozenset[DeviceKey]) -> None:
        """The devices on the bus are known beforehand (a simulated prosthesis knows what
        it simulates): the first start-up runs once they have all joined and nothing is
        being set up, without waiting out the quiet time after the last bind request. A
        restart waits the quiet time again (who comes back after a reset is the bus's news)."""
        self.expected = frozenset(keys)

    # -- when (pure) ----------------------------------------------------------------------
    def startup_due(self, now: float, busy: bool, setting_up: bool, caught_up: bool,
                    present: frozenset[DeviceKey] | set[DeviceKey] = frozenset()
                    ) -> Literal["", "due", "late"]:
        """Listing 4.1's wait: no bind request for ``startup_quiet_s``, nothing being set up
        (``busy``: binds held or deferred, set-ups, jobs) and every frame handled
        (``caught_up``); but never longer than ``startup_max_wait_s`` (a device that keeps
        asking for a taken ID and ignores the suggestion must not hold the prosthesis up):
        then ``late`` while binding has not settled. With :meth:`expect`'s devices all
        ``present`` the quiet time is not waited out."""
        if now - self.started >= self.startup_max_wait_s and not setting_up:
            return "late" if busy else "due"
        since = max(self.started, self.last_bind, self.listen_until)
        quiet = now - since >= self.startup_quiet_s or (
            bool(self.expected) and self.expected <= present and now >= self.listen_until)
        return "due" if quiet and not busy and caught_up else ""

    def duty_due(self, now: float, busy: bool) -> bool:
        """The duty cycle runs after start-up, ``duty_quiet_s`` after the last change."""
        return (self.startup_done and self.duty_needed and not busy
                and now - self.last_change >= self.duty_quiet_s)

    def restart(self, now: float) -> None:
        """Under the lock: a reset; start-up runs again."""
        self.startup_done = False
        self.duty_needed = False
        self.last_present = set()
        self.expected = frozenset()
        self.started = self.last_bind = self.last_change = now

    # -- the profile thread ---------------------------------------------------------------
    def loop(self) -> None:
        arb = self.arb
        while not arb._stop.is_set():
            arb._wake.wait(0.02)
            arb._wake.clear()
            if arb._stop.is_set() or not arb.profile_layer or not arb.claim.may_write:
                continue  # (listening, or another arbitrator is on the bus)
            now = time.monotonic()
            try:
                if not self.startup_done:
                    with arb._lock:
                        setting_up = bool(arb.setup.in_flight)
                    present = frozenset(arb.devices_present()) if self.expected \
                        else frozenset()
                    due = self.startup_due(now, arb._busy(), setting_up,
                                           arb.conn.inbound.empty(), present)
                    if due == "late":
                        arb._error(f"start-up runs after {self.startup_max_wait_s:g} s although "
                                   "binding has not settled (a device keeps asking for an ID "
                                   "it is not given)", "setup")
                    if due:
                        self.run_startup()
                elif self.duty_due(now, arb._busy()):
                    self.run_duty_cycle()
            except PdcpError as err:
                if not arb.closed:  # a plan cut off by closing the session is no news
                    arb._error(f"profile layer: {err}", "plan")
            except Exception:
                log.exception("%s: the profile layer failed", arb.name)

    # -- plans ----------------------------------------------------------------------------
    def apply_plan(self, plan: Plan, progress: Callable[[int, int, str], Any] | None = None,
                   cancel: threading.Event | None = None, *,
                   interlock: str = "not used") -> TransactionResult:
        """See :meth:`Arbitrator.apply_plan` (``interlock``: what held the prosthesis)."""
        from pdcp_studio.engine.plan import Op

        arb = self.arb
        failures: list[str] = []
        cancelled = ""
        with arb._plan_lock:
            with arb._lock:
                self.plan_running += 1
                before = arb._system.links
            try:
                total = len(plan.actions)
                for done, action in enumerate(plan.actions):
                    if cancel is not None and cancel.is_set():
                        cancelled = f"cancelled after {done} of {total} actions"
                        break
                    if progress is not None:
                        progress(done, total, f"{action.op.value} {action.link}")
                    try:
                        if action.op is Op.ADD:
                            with arb._lock:
                                arb._system.check_link(action.link)
                                exists = arb._system.has_link(action.link)
                            if not exists:
                                arb.links.add(action.link)
                        else:
                            with arb._lock:
                                exists = arb._system.has_link(action.link)
                            if exists:
                                arb.links.remove(action.link)
                    except PdcpError as err:
                        if arb.closed:  # closing the session cut the plan off: no error
                            cancelled = f"the bus was closed after {done} of {total} actions"
                            break
                        failures.append(f"{action.op.value} {action.link}: {err}")
                        arb._error(f"plan {plan.mode}: {failures[-1]}", "plan")
                else:
                    if progress is not None:
                        progress(total, total, f"plan {plan.mode} applied")
                self.applied_plans.append(plan)
                log.info("%s: applied plan %s: %d added, %d removed%s", arb.name, plan.mode,
                         len(plan.added), len(plan.removed),
                         f", {len(failures)} failed" if failures else "")
                for action in plan.actions:
                    log.info("%s:   %s %s (%s)", arb.name, action.op.value, action.link,
                             action.reason)
            finally:
                with arb._lock:
                    self.plan_running -= 1
                    after = arb._system.links
        arb._emit(ev.PlanApplied(plan))
        result = TransactionResult(Status.APPLIED, f"apply {plan.mode}", links_before=before,
                                   links_after=after, verified=False, interlock=interlock)
        if failures or cancelled:
            result.status, result.step = Status.FAILED, "write"
            result.reason = "; ".join(([cancelled] if cancelled else [])
                                      + ([f"{len(failures)} action(s) failed: "
                                          + "; ".join(failures[:5])] if failures else []))
        return result

    def run_startup(self) -> Plan:
        """See :meth:`Arbitrator.run_startup`."""
        from pdcp_studio.engine import plan_on_bus
        from pdcp_studio.engine.procedures import missing_devices

        arb = self.arb
        with arb._plan_lock:
            with arb._lock:
                self.duty_needed = False
            try:
                stored = arb.read_memory()
            except (OSError, PdcpError) as err:
                # An unreadable memory must not keep the prosthesis unlinked: say so once and
                # start up from what the devices themselves store (as a replaced arbitrator).
                arb._error(f"stored configuration unreadable, starting up from the devices' "
                           f"own source fields: {err}", "plan")
                stored = ConfigCollection([])
            autoconfigure = self._policy_for_plans()
            snapshot = arb.system()
            plan = plan_on_bus("startup", snapshot, stored, autoconfigure=autoconfigure)
            try:
                self._apply_held(plan, snapshot)
                self._report_policy(plan, autoconfigure)
                # What the stored configuration names and the bus lacks is shown as missing.
                stored_cfg = plan.configuration if plan.configuration_source == "stored" else None
                with arb._lock:
                    for device in missing_devices(arb._system, stored_cfg):
                        arb._system.add_device(device)
            finally:
                with arb._lock:
                    self.startup_done = True
                    self.last_present = present_refs(arb._system)
        return plan

    def run_duty_cycle(self) -> Plan:
        """See :meth:`Arbitrator.run_duty_cycle`."""
        from pdcp_studio.engine import plan_duty_cycle

        arb = self.arb
        with arb._plan_lock:
            with arb._lock:
                self.duty_needed = False
                before = set(self.last_present)
            snapshot = arb.system()
            autoconfigure = self._policy_for_plans()
            plan = plan_duty_cycle(snapshot, before, autoconfigure=autoconfigure)
            written = True
            try:
                if plan.actions:
                    written = self._apply_held(plan, snapshot)
                if written:
                    self._report_policy(plan, autoconfigure)
            finally:
                if written:  # else the channels that left are still owed a replacement:
                    with arb._lock:  # the next join or leave plans for them too
                        self.last_present = present_refs(arb._system)
        return plan

    def _apply_held(self, plan: Plan, snapshot: System) -> bool:
        """Write ``plan`` with the motion interlock holding its devices; False (and an error
        said) when a device would not hold still and nothing was written."""
        from pdcp_studio.bus.arbitrator.transactions import HoldRefused, holding

        if not plan.actions:
            return True
        arb = self.arb
        notes: list[str] = []
        keys = interlocked_devices(snapshot, snapshot.links, plan.final_links)
        with arb._lock:
            self.plan_running += 1  # busy from the first hold on: the bus is not settled
        try:
            with holding(arb, keys, notes) as held:
                self.apply_plan(plan, interlock=describe_interlock(held))
        except HoldRefused as err:
            arb._error(f"plan {plan.mode} not written: {err}; the prosthesis was left as it "
                       "was", "plan")
            return False
        finally:
            with arb._lock:
                self.plan_running -= 1
            for note in notes:  # a release cut off by closing the session is no news
                (log.debug if arb.closed else log.warning)("%s: %s", arb.name, note)
        return True

    def _policy_for_plans(self) -> bool:
        """The stored autoconfigure policy; the thesis's default (on) when the memory cannot
        be read — start-up already said so once, and an unreadable memory must not leave the
        prosthesis unlinked."""
        try:
            return self.arb.read_policy().autoconfigure
        except (OSError, PdcpError):
            return True

    def _report_policy(self, plan: Plan, autoconfigure: bool) -> None:
        """With autoconfigure off, say which terminal channels were left unconnected."""
        if autoconfigure:
            return
        from pdcp_studio.engine.layer import ProfileLayer
        from pdcp_studio.engine.procedures import AUTOCONFIGURE_OFF

        arb = self.arb
        refs = tuple(ProfileLayer(arb.system(), "policy").unconnected_terminals())
        if refs:
            log.info("%s: %d terminal channel(s) not connected: %s", arb.name, len(refs),
                     AUTOCONFIGURE_OFF)
            arb._emit(ev.TerminalsUnconnected(
                refs, f"{len(refs)} terminal channel(s) not connected — {AUTOCONFIGURE_OFF}: "
                + ", ".join(str(r) for r in refs)))


__all__ = ["ProfileDriver", "present_refs"]
