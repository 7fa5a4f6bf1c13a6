"""The profile-layer driver: start-up, the hot-swap duty cycle and applying engine plans.

Start-up (listing 4.1) runs once binding has been quiet for ``startup_quiet_s`` — but at the
latest ``startup_max_wait_s`` after the arbitrator started; the duty cycle (listing 4.2) runs
``duty_quiet_s`` after the last join or leave. When is decided by :meth:`ProfileDriver.startup_due`
and :meth:`ProfileDriver.duty_due` from ``now`` and the arbitrator's business (pure); the plans
themselves come from :mod:`pdcp_studio.engine` and are carried out by the link writer on the
profile thread (``bus/arbitrator/profile/thread.py``).

Start-up implements a stored configuration and the duty cycle makes and removes links on a
prosthesis that may be worn and moving: both are changes reference §5's motion interlock
covers. So the devices whose outputs feed a terminal channel before or after the plan are held
(Suspend Device, bounded and renewed) while the plan is written and its inputs are read back
(Source's Node Ids, Data Transfer Enabled), and released after that verify; one that refuses
to hold still stops the plan before anything is written (said as an error; the channels it
would have replaced are planned for again at the next join or leave). A plan that changes no
link writes nothing and holds nothing. What it changed on its own is announced once it is
released: ``PlanApplied(plan, own=True, result=…)`` — each action with its reason, whom it
held, whether it verified (a mismatch is said as an error too).
"""

from __future__ import annotations

import contextlib
import logging
import threading
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.change.interlock import HoldRefused, Interlock, holding
from pdcp_studio.bus.arbitrator.state import Emit, ReportError, SystemState
from pdcp_studio.bus.transaction import (
    Policy,
    Status,
    TransactionResult,
    describe_interlock,
    interlocked_devices,
)
from pdcp_studio.errors import PdcpError
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System

if TYPE_CHECKING:
    from pdcp_studio.engine.plan import Plan

log = logging.getLogger("pdcp_studio.bus.arbitrator.core")  # one logger for the arbitrator


def present_refs(system: System) -> set[ChannelRef]:
    """The channels of the devices on the bus."""
    return {ref for ref, _ in system.channels() if system.is_present(ref)}


@dataclass(frozen=True)
class ProfilePorts:
    """What the profile driver needs outside itself: the system, the link writer's ``add`` and
    ``remove`` (a plan's actions), the motion interlock, the stored configuration and policy
    (the arbitrator's calls, asked each time: tests replace them), and its voice."""

    state: SystemState
    add_link: Callable[[Link], None]
    remove_link: Callable[[Link], None]
    interlock: Interlock
    read_memory: Callable[[], ConfigCollection]
    read_policy: Callable[[], Policy]
    error: ReportError
    emit: Emit
    closed: Callable[[], bool]
    name: str
    #: Read inputs back from their devices: what does not read as the system says (empty:
    #: verified). None: plans are not read back (a test's driver).
    verify_inputs: Callable[[list[ChannelRef]], list[str]] | None = None


class ProfileDriver:
    """Start-up, duty cycle and plans, and when they are due.

    It owns the profile layer's clock (the last bind request, the last change), whether the
    duty cycle is owed and how many plans are under way; the other parts tell it through
    :meth:`note_bind`, :meth:`note_change` and :meth:`running`. Its fields are guarded by the
    arbitrator's lock (the ``state``'s)."""

    def __init__(self, ports: ProfilePorts, now: float, *, quiet_s: float, duty_quiet_s: float,
                 max_wait_s: float, listen_until: float) -> None:
        self._ports = ports
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

    # -- what the other parts tell it ---------------------------------------------------
    def listening(self, now: float) -> bool:
        """Binding waits: the node IDs devices of an earlier arbitrator use are being heard."""
        return now < self.listen_until

    def note_bind(self, now: float) -> None:
        """Under the lock: a bind request at ``now`` (start-up waits for quiet)."""
        self.last_bind = now

    def note_change(self, now: float, *, duty: bool = False) -> None:
        """Under the lock: a join, leave or set-up at ``now``; ``duty``: the devices on the
        bus changed, the duty cycle is owed."""
        self.last_change = now
        if duty:
            self.duty_needed = True

    def settled(self, profile_layer: bool) -> bool:
        """Under the lock: no plan or transaction under way and, with the profile layer on,
        start-up done and no duty cycle owed."""
        if self.plan_running:
            return False
        return not profile_layer or (self.startup_done and not self.duty_needed)

    @contextlib.contextmanager
    def running(self) -> Iterator[None]:
        """A plan or transaction is under way around the block: the bus is not settled."""
        with self._ports.state.lock:
            self.plan_running += 1
        try:
            yield
        finally:
            with self._ports.state.lock:
                self.plan_running -= 1

    # -- plans ----------------------------------------------------------------------------
    def apply_plan(self, plan: Plan, progress: Callable[[int, int, str], Any] | None = None,
                   cancel: threading.Event | None = None, *,
                   interlock: str = "not used", announce: bool = True) -> TransactionResult:
        """See :meth:`Arbitrator.apply_plan` (``interlock``: what held the prosthesis;
        ``announce=False``: the caller emits PlanApplied itself, once it has released)."""
        from pdcp_studio.engine.plan import Op

        ports = self._ports
        failures: list[str] = []
        cancelled = ""
        with ports.state.wire_lock:
            with ports.state.lock:
                self.plan_running += 1
                before = ports.state.system.links
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
                            with ports.state.lock:
                                ports.state.system.check_link(action.link)
                                exists = ports.state.system.has_link(action.link)
                            if not exists:
                                ports.add_link(action.link)
                        else:
                            with ports.state.lock:
                                exists = ports.state.system.has_link(action.link)
                            if exists:
                                ports.remove_link(action.link)
                    except PdcpError as err:
                        if ports.closed():  # closing the session cut the plan off: no error
                            cancelled = f"the bus was closed after {done} of {total} actions"
                            break
                        failures.append(f"{action.op.value} {action.link}: {err}")
                        ports.error(f"plan {plan.mode}: {failures[-1]}", "plan")
                else:
                    if progress is not None:
                        progress(total, total, f"plan {plan.mode} applied")
                self.applied_plans.append(plan)
                log.info("%s: applied plan %s: %d added, %d removed%s", ports.name, plan.mode,
                         len(plan.added), len(plan.removed),
                         f", {len(failures)} failed" if failures else "")
                for action in plan.actions:
                    log.info("%s:   %s %s (%s)", ports.name, action.op.value, action.link,
                             action.reason)
            finally:
                with ports.state.lock:
                    self.plan_running -= 1
                    after = ports.state.system.links
        result = TransactionResult(Status.APPLIED, f"apply {plan.mode}", links_before=before,
                                   links_after=after, verified=False, interlock=interlock)
        if failures or cancelled:
            result.status, result.step = Status.FAILED, "write"
            result.reason = "; ".join(([cancelled] if cancelled else [])
                                      + ([f"{len(failures)} action(s) failed: "
                                          + "; ".join(failures[:5])] if failures else []))
        if announce:
            ports.emit(ev.PlanApplied(plan, result=result))
        return result

    def run_startup(self) -> Plan:
        """See :meth:`Arbitrator.run_startup`."""
        from pdcp_studio.engine import plan_on_bus
        from pdcp_studio.engine.procedures import missing_devices

        ports = self._ports
        with ports.state.wire_lock:
            with ports.state.lock:
                self.duty_needed = False
            try:
                stored = ports.read_memory()
            except (OSError, PdcpError) as err:
                # An unreadable memory must not keep the prosthesis unlinked: say so once and
                # start up from what the devices themselves store (as a replaced arbitrator).
                ports.error(f"stored configuration unreadable, starting up from the devices' "
                            f"own source fields: {err}", "plan")
                stored = ConfigCollection([])
            autoconfigure = self._policy_for_plans()
            snapshot = ports.state.snapshot()
            plan = plan_on_bus("startup", snapshot, stored, autoconfigure=autoconfigure)
            try:
                self._apply_held(plan, snapshot)
                self._report_policy(plan, autoconfigure)
                # What the stored configuration names and the bus lacks is shown as missing.
                stored_cfg = plan.configuration if plan.configuration_source == "stored" else None
                with ports.state.lock:
                    for device in missing_devices(ports.state.system, stored_cfg):
                        ports.state.system.add_device(device)
            finally:
                with ports.state.lock:
                    self.startup_done = True
                    self.last_present = present_refs(ports.state.system)
        return plan

    def run_duty_cycle(self) -> Plan:
        """See :meth:`Arbitrator.run_duty_cycle`."""
        from pdcp_studio.engine import plan_duty_cycle

        ports = self._ports
        # Under way from taking what it owes until done, not only while its plan is written:
        # in between the bus looked settled, and a script that waited for that closed the
        # session under the plan ("did not suspend", two CPU burners).
        with ports.state.wire_lock, self.running():
            with ports.state.lock:
                self.duty_needed = False
                before = set(self.last_present)
            written = False  # a plan that could not be made leaves what it owes owed
            try:
                snapshot = ports.state.snapshot()
                autoconfigure = self._policy_for_plans()
                plan = plan_duty_cycle(snapshot, before, autoconfigure=autoconfigure)
                written = True
                if plan.actions:
                    written = self._apply_held(plan, snapshot)
                if written:
                    self._report_policy(plan, autoconfigure)
            finally:
                if written:  # else the channels that left are still owed a replacement:
                    with ports.state.lock:  # the next join or leave plans for them too
                        self.last_present = present_refs(ports.state.system)
        return plan

    def _apply_held(self, plan: Plan, snapshot: System) -> bool:
        """Write ``plan`` with the motion interlock holding its devices; False (and an error
        said) when a device would not hold still and nothing was written."""
        if not plan.actions:
            return True
        ports = self._ports
        notes: list[str] = []
        keys = interlocked_devices(snapshot, snapshot.links, plan.final_links)
        with self.running():  # busy from the first hold on: the bus is not settled
            try:
                with holding(ports.interlock, keys, notes) as held:
                    result = self.apply_plan(plan, interlock=describe_interlock(held),
                                             announce=False)
                    result.held = list(held)
                    self._verify(plan, result)  # read back while still held
            except HoldRefused as err:
                ports.error(f"plan {plan.mode} not written: {err}; the prosthesis was left "
                            "as it was", "plan")
                return False
            finally:
                for note in notes:  # a release cut off by closing the session is no news
                    (log.debug if ports.closed() else log.warning)("%s: %s", ports.name, note)
        result.notes += notes
        ports.emit(ev.PlanApplied(plan, own=True, result=result))
        return True

    def _verify(self, plan: Plan, result: TransactionResult) -> None:
        """Read the inputs the plan touched back from their devices (the motion interlock
        still holding); a mismatch is said as an error and noted on the result."""
        verify = self._ports.verify_inputs
        if verify is None or self._ports.closed():
            return
        inputs = sorted({a.link.input for a in plan.actions})
        try:
            problems = verify(inputs)
        except PdcpError as err:
            problems = [f"reading the inputs back failed: {err}"]
        result.verified = not problems
        if problems:
            result.notes += problems
            self._ports.error(f"plan {plan.mode}: read back, the prosthesis does not hold "
                              f"what was written: {'; '.join(problems[:5])}", "plan")

    def _policy_for_plans(self) -> bool:
        """The stored autoconfigure policy; the thesis's default (on) when the memory cannot
        be read — start-up already said so once, and an unreadable memory must not leave the
        prosthesis unlinked."""
        try:
            return self._ports.read_policy().autoconfigure
        except (OSError, PdcpError):
            return True

    def _report_policy(self, plan: Plan, autoconfigure: bool) -> None:
        """With autoconfigure off, say which terminal channels were left unconnected."""
        if autoconfigure:
            return
        from pdcp_studio.engine.layer import ProfileLayer
        from pdcp_studio.engine.procedures import AUTOCONFIGURE_OFF

        ports = self._ports
        refs = tuple(ProfileLayer(ports.state.snapshot(), "policy").unconnected_terminals())
        if refs:
            log.info("%s: %d terminal channel(s) not connected: %s", ports.name, len(refs),
                     AUTOCONFIGURE_OFF)
            ports.emit(ev.TerminalsUnconnected(
                refs, f"{len(refs)} terminal channel(s) not connected — {AUTOCONFIGURE_OFF}: "
                + ", ".join(str(r) for r in refs)))


__all__ = ["ProfileDriver", "present_refs"]
