"""The profile-layer driver: start-up, the hot-swap duty cycle and applying engine plans.

A mixin of :class:`pdcp_studio.bus.arbitrator.Arbitrator`: its profile thread runs start-up
once binding has been quiet and the duty cycle after joins and leaves; the plans themselves come
from :mod:`pdcp_studio.engine`.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.transaction import Status, TransactionResult
from pdcp_studio.errors import PdcpError
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import ChannelRef

if TYPE_CHECKING:
    from pdcp_studio.engine.plan import Plan

log = logging.getLogger("pdcp_studio.bus.arbitrator")  # one logger for the arbitrator


class ProfileMixin:
    """Start-up, duty cycle and plans of the :class:`Arbitrator`."""

    # -- plans ----------------------------------------------------------------------------
    def apply_plan(self, plan: Plan, progress: Callable[[int, int, str], Any] | None = None,
                   cancel: threading.Event | None = None) -> TransactionResult:
        """Carry out an engine plan's actions on the bus, in order, with no interlock (the
        profile layer's own start-up and duty cycle); log it and return what came of it.

        An action that fails on the wire is reported and skipped, the others go on (status
        ``failed``, reason naming them). ``cancel`` stops between actions. Changes a person
        asks for go through :meth:`transact` instead (interlock, verify, all or nothing).
        """
        from pdcp_studio.engine.plan import Op

        failures: list[str] = []
        cancelled = ""
        with self._plan_lock:
            with self._lock:
                self._plan_running += 1
                before = self._system.links
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
                            with self._lock:
                                self._system.check_link(action.link)
                                exists = self._system.has_link(action.link)
                            if not exists:
                                self._add(action.link)
                        else:
                            with self._lock:
                                exists = self._system.has_link(action.link)
                            if exists:
                                self._remove(action.link)
                    except PdcpError as err:
                        failures.append(f"{action.op.value} {action.link}: {err}")
                        self._error(f"plan {plan.mode}: {failures[-1]}", "plan")
                else:
                    if progress is not None:
                        progress(total, total, f"plan {plan.mode} applied")
                self.applied_plans.append(plan)
                log.info("%s: applied plan %s: %d added, %d removed%s", self.name, plan.mode,
                         len(plan.added), len(plan.removed),
                         f", {len(failures)} failed" if failures else "")
                for action in plan.actions:
                    log.info("%s:   %s %s (%s)", self.name, action.op.value, action.link,
                             action.reason)
            finally:
                with self._lock:
                    self._plan_running -= 1
                    after = self._system.links
        self._emit(ev.PlanApplied(plan))
        result = TransactionResult(Status.APPLIED, f"apply {plan.mode}", links_before=before,
                                   links_after=after, verified=False, interlock="not used")
        if failures or cancelled:
            result.status, result.step = Status.FAILED, "write"
            result.reason = "; ".join(([cancelled] if cancelled else [])
                                      + ([f"{len(failures)} action(s) failed: "
                                          + "; ".join(failures[:5])] if failures else []))
        return result

    def run_startup(self) -> Plan:
        """Listing 4.1 / 5.1 with the memory's configuration (or the devices' own)."""
        from pdcp_studio.engine import plan_on_bus
        from pdcp_studio.engine.procedures import missing_devices

        with self._plan_lock:
            with self._lock:
                self._duty_needed = False
            try:
                stored = self.read_memory()
            except (OSError, PdcpError) as err:
                # An unreadable memory must not keep the prosthesis unlinked: say so once and
                # start up from what the devices themselves store (as a replaced arbitrator).
                self._error(f"stored configuration unreadable, starting up from the devices' "
                            f"own source fields: {err}", "plan")
                stored = ConfigCollection([])
            autoconfigure = self._policy_for_plans()
            plan = plan_on_bus("startup", self.system(), stored, autoconfigure=autoconfigure)
            try:
                self.apply_plan(plan)
                self._report_policy(plan, autoconfigure)
                # What the stored configuration names and the bus lacks is shown as missing.
                stored_cfg = plan.configuration if plan.configuration_source == "stored" else None
                with self._lock:
                    for device in missing_devices(self._system, stored_cfg):
                        self._system.add_device(device)
            finally:
                with self._lock:
                    self._startup_done = True
                    self._last_present = self._present_refs()
        return plan

    def _policy_for_plans(self) -> bool:
        """The stored autoconfigure policy; the thesis's default (on) when the memory cannot
        be read — start-up already said so once, and an unreadable memory must not leave the
        prosthesis unlinked."""
        try:
            return self.read_policy().autoconfigure
        except (OSError, PdcpError):
            return True

    def run_duty_cycle(self) -> Plan:
        """Listing 4.2: replacements for channels that left, then autoconfigure."""
        from pdcp_studio.engine import plan_duty_cycle

        with self._plan_lock:
            with self._lock:
                self._duty_needed = False
                before = set(self._last_present)
            snapshot = self.system()
            autoconfigure = self._policy_for_plans()
            plan = plan_duty_cycle(snapshot, before, autoconfigure=autoconfigure)
            try:
                if plan.actions:
                    self.apply_plan(plan)
                self._report_policy(plan, autoconfigure)
            finally:
                with self._lock:
                    self._last_present = self._present_refs()
        return plan

    def _report_policy(self, plan: Plan, autoconfigure: bool) -> None:
        """With autoconfigure off, say which terminal channels were left unconnected."""
        if autoconfigure:
            return
        from pdcp_studio.engine.layer import ProfileLayer
        from pdcp_studio.engine.procedures import AUTOCONFIGURE_OFF

        refs = tuple(ProfileLayer(self.system(), "policy").unconnected_terminals())
        if refs:
            log.info("%s: %d terminal channel(s) not connected: %s", self.name, len(refs),
                     AUTOCONFIGURE_OFF)
            self._emit(ev.TerminalsUnconnected(
                refs, f"{len(refs)} terminal channel(s) not connected — {AUTOCONFIGURE_OFF}: "
                + ", ".join(str(r) for r in refs)))

    def _present_refs(self) -> set[ChannelRef]:
        return {ref for ref, _ in self._system.channels() if self._system.is_present(ref)}

    def _busy(self) -> bool:
        with self._lock:
            return bool(self._setups or self._held or self._deferred or self._jobs)

    def _profile_loop(self) -> None:
        while not self._stop.is_set():
            self._wake.wait(0.02)
            self._wake.clear()
            if self._stop.is_set() or not self.profile_layer or not self._claim.may_write:
                continue  # (listening, or another arbitrator is on the bus)
            now = time.monotonic()
            try:
                if not self._startup_done:
                    if self._startup_due(now):
                        self.run_startup()
                elif (self._duty_needed and not self._busy()
                      and now - self._last_change >= self.duty_quiet_s):
                    self.run_duty_cycle()
            except PdcpError as err:
                self._error(f"profile layer: {err}", "plan")
            except Exception:
                log.exception("%s: the profile layer failed", self.name)

    def _startup_due(self, now: float) -> bool:
        """Listing 4.1's wait: no bind request for ``startup_quiet_s`` and nothing being set
        up; but never longer than ``startup_max_wait_s`` (a device that keeps asking for a
        taken ID and ignores the suggestion must not hold the prosthesis up)."""
        with self._lock:
            setups = bool(self._setups)
        if now - self._started >= self.startup_max_wait_s and not setups:
            if not self._busy():
                return True
            self._error(f"start-up runs after {self.startup_max_wait_s:g} s although binding "
                        "has not settled (a device keeps asking for an ID it is not given)",
                        "setup")
            return True
        since = max(self._started, self._last_bind, self._listen_until)
        quiet = now - since >= self.startup_quiet_s
        return quiet and not self._busy() and self.conn.inbound.empty()

