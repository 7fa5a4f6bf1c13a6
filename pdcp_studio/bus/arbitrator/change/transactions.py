"""Transactions in the arbitrator: the part of the change road that touches the bus.

A part of :class:`pdcp_studio.bus.arbitrator.core.Arbitrator` (``arbitrator.transactions``), so
every transport gets it — the in-process sessions call :meth:`Arbitrator.transact` directly,
the host link's TRANSACT request calls it on the arbitrator's side of the line. Reference §5::

    interlock → write → read back and compare → restore on mismatch → release

- **Interlock.** Every present device whose output channels feed a terminal channel before or
  after the change gets Suspend Device with TimeValue ``INTERLOCK_MS`` (2000 ms), renewed every
  ``INTERLOCK_RENEW_S`` by a small thread while the change runs, so a PC or arbitrator that dies
  mid-change cannot leave the prosthesis held. A device that refuses (or does not answer)
  stops the change before anything is written; the ones already held are released.
- **Write.** Link actions in order, then parameter writes, then the stored configuration and
  the policy (the memory's two-slot write: a power cut leaves the old or the new, never a mix).
- **Verify.** The links are read back from the input channels (Data Transfer Enabled and
  Source's Node Ids), the parameters and the memory are read back and compared.
- **Restore.** Any failure or mismatch puts back the links, parameter values, stored
  configuration and policy that were there; the result says which step failed and why.
- **Release.** Release Device (0x09) to every held device, after verify or restore.

Recording in the fitting history is the PC's part (``bus/session/change_road.py``).
The whole transaction holds the wire lock: no start-up, duty cycle or other plan runs inside it.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable
from contextlib import AbstractContextManager
from typing import TYPE_CHECKING, Any

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.change.interlock import HoldRefused, Interlock, holding
from pdcp_studio.bus.arbitrator.state import Emit, SystemState
from pdcp_studio.bus.transaction import (
    Change,
    ParameterWrite,
    Policy,
    Status,
    TransactionResult,
    crc_of_bytes,
    describe_interlock,
    interlocked_devices,
)
from pdcp_studio.errors import PdcpError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System

if TYPE_CHECKING:
    from pdcp_studio.bus.arbitrator.links import LinkWriter
    from pdcp_studio.bus.arbitrator.memory import MemoryStore
    from pdcp_studio.storage.archive.chain import Anchor

log = logging.getLogger("pdcp_studio.bus.arbitrator.core")

ProgressFn = Callable[[int, int, str], Any]


class _Stop(Exception):
    """The change was cancelled between two writes."""


class Transactions:
    """``transact`` and the policy (no state of its own: what it changes is the bus's, the
    memory's and the system's).

    It reaches the devices through the arbitrator's parameter calls (``get_parameter``,
    ``set_parameter``: node IDs looked up, values learnt), puts links back through the link
    writer, holds devices through ``interlock`` and counts as a plan under way through
    ``running`` (the bus is not settled meanwhile). ``do_link`` (one link action, through the
    arbitrator's ``add_link`` and ``remove_link``) and ``read_memory`` are the arbitrator's
    own methods, asked each time (tests replace them on the instance)."""

    def __init__(self, state: SystemState, memory: MemoryStore, links: LinkWriter, *,
                 interlock: Interlock, running: Callable[[], AbstractContextManager[None]],
                 get_parameter: Callable[[DeviceKey, int, int], bytes],
                 set_parameter: Callable[[DeviceKey, int, int, bytes], None],
                 node_id_of: Callable[[DeviceKey], int | None],
                 channel_node_id: Callable[[ChannelRef], int | None],
                 do_link: Callable[[str, Link], None],
                 read_memory: Callable[[], ConfigCollection],
                 write_memory: Callable[[ConfigCollection], None],
                 emit: Emit, name: str) -> None:
        self._state = state
        self._memory = memory
        self._links = links
        self._interlock = interlock
        self._running = running
        self._get = get_parameter
        self._set = set_parameter
        self._node_id_of = node_id_of
        self._channel_node_id = channel_node_id
        self._do_link = do_link
        self._read_memory = read_memory
        self._write_memory = write_memory
        self._emit = emit
        self._name = name

    # -- the policy (issue 17) ---------------------------------------------------------
    def read_policy(self) -> Policy:
        """The profile-layer policy kept in memory beside the stored configuration; an
        unreadable memory gives the thesis's default (autoconfigure on), as start-up
        falls back to the devices' own configuration then."""
        try:
            stored = self._memory.read_policy()
        except (OSError, PdcpError) as err:
            log.warning("%s: policy unreadable (%s): autoconfigure on", self._name, err)
            return Policy()
        return Policy(autoconfigure=stored.get("autoconfigure", True))

    # -- the fitting history's anchor (reference §5 Decision, issue 28) -----------------
    def read_anchor(self) -> Anchor | None:
        """The anchor kept in memory beside the stored configuration (None: none kept)."""
        return self._memory.read_anchor()

    def write_anchor(self, anchor: Anchor) -> Anchor | None:
        """Store ``anchor`` beside the configuration and policy (the memory's two-slot
        write: a cut leaves the old anchor or the new); returns it as read back."""
        self._memory.write_anchor(anchor)
        stored = self._memory.read_anchor()
        log.info("%s: fitting history anchor: %s", self._name,
                 stored.text() if stored else "none")
        return stored

    # -- transactions ------------------------------------------------------------------
    def transact(self, change: Change, progress: ProgressFn | None = None,
                 cancel: threading.Event | None = None) -> TransactionResult:
        """Carry ``change`` out as one transaction; never raises for a bus failure — the
        result says applied, failed or rolled back, at which step and why."""
        with self._state.wire_lock, self._running():
            result = self._transact(change, progress, cancel)
        log.info("%s: transaction %s: %s", self._name, change.action, result.summary())
        self._emit(ev.TransactionDone(result))
        return result

    def _transact(self, change: Change, progress: ProgressFn | None,
                  cancel: threading.Event | None) -> TransactionResult:
        system = self._state.snapshot()
        before = system.links
        after = change.links_after(before)
        cfg_before = self._memory.read_bytes()
        policy_before = self.read_policy()
        result = TransactionResult(
            Status.FAILED, change.action, links_before=before, links_after=before,
            config_crc_before=crc_of_bytes(cfg_before), config_crc_after=crc_of_bytes(cfg_before),
            policy_before=policy_before, policy_after=policy_before,
            devices=sorted(k for k, d in system.devices.items() if d.present))
        problem = _check_change(system, change)
        if problem:  # the change does not fit the bus as it is now
            result.step, result.reason = "preview", f"{problem}; nothing was written"
            return result
        keys = interlocked_devices(system, before, after, change.parameters) \
            if change.moves else []
        try:
            with holding(self._interlock, keys, result.notes) as held:
                result.held = list(held)
                result.interlock = describe_interlock(held)
                self._write_verify_restore(change, after, cfg_before, policy_before, result,
                                           progress, cancel)
        except HoldRefused as err:
            result.step = "interlock"
            result.reason = f"device {err.key} did not suspend ({err.why}); nothing was written"
            result.interlock = describe_interlock([], refused=err.key)
            return result
        if result.status is Status.APPLIED:
            self._forget_replaced(change, result, cfg_before)
        result.links_after = self._state.snapshot().links
        result.config_crc_after = crc_of_bytes(self._memory.read_bytes())
        result.policy_after = self.read_policy()
        return result

    def _forget_replaced(self, change: Change, result: TransactionResult,
                         cfg_before: bytes | None) -> None:
        """After a verified change: forget the absent parts whose every role (their links
        on the bus and stored, before the change) a present part now holds — they are no
        longer missing but replaced (``engine/replaced.py``); noted in the result (the
        fitting history's ``replaced``) and said as :class:`~pdcp_studio.bus.events.
        DeviceReplaced`. Only a change that made the replacement's links or stored the
        configuration does so (not, say, a parameter written after the duty cycle linked
        a spare on its own: the replacement was not part of that change), and never a part
        the configuration it stores still names (that keeps it in the fitting)."""
        from pdcp_studio.engine.replaced import replaced_parts
        from pdcp_studio.storage.history import replaced_note

        roles = set(result.links_before) | _stored_links(cfg_before)
        kept = {ref.device for lk in _links_of(change.configuration)
                for ref in (lk.output, lk.input)}
        with self._state.lock:
            pairs = [p for p in replaced_parts(self._state.system, roles)
                     if (change.configuration is not None or any(
                         {a.link.output.device, a.link.input.device} & set(p)
                         for a in change.links))
                     and p.old not in kept]
            for old, _new in pairs:  # (with its dead links: they carried nothing)
                self._state.system.remove_device(old)
        for old, new in pairs:
            log.info("%s: %s is replaced by %s: no longer missing", self._name, old, new)
            result.notes.append(replaced_note(old, new))
            self._emit(ev.DeviceReplaced(old, new))

    def _write_verify_restore(self, change: Change, after: list[Link], cfg_before: bytes | None,
                              policy_before: Policy, result: TransactionResult,
                              progress: ProgressFn | None, cancel: threading.Event | None) -> None:
        old_params: list[tuple[Any, bytes]] = []
        total = (len(change.links) + len(change.parameters)
                 + (change.configuration is not None) + (change.policy is not None))
        step, why = "", ""
        try:
            for p in change.parameters:  # read what is there first, to restore it
                old_params.append((p, bytes(self._get(p.device, p.param, p.channel))))
            # The ends' Data Transfer Enabled too: taking a link out again on a rollback
            # turns an output off when it feeds no present input, though it was sending
            # before (it fed a part that is missing now).
            old_params[:0] = self._end_flags(change)
            for n, action in enumerate(change.links):
                _check_cancel(cancel, n, total)
                if progress is not None:
                    progress(n, total, f"{action.op} {action.link}")
                self._do_link(action.op, action.link)
            for n, p in enumerate(change.parameters, len(change.links)):
                _check_cancel(cancel, n, total)
                if progress is not None:
                    progress(n, total, f"parameter 0x{p.param:02X} of {p.device}")
                self._set(p.device, p.param, p.channel, p.value)
            done = len(change.links) + len(change.parameters)
            if change.configuration is not None:
                _check_cancel(cancel, done, total)
                if progress is not None:
                    progress(done, total, "stored configuration")
                self._write_memory(change.configuration)
                done += 1
            if change.policy is not None:
                if progress is not None:
                    progress(done, total, "policy")
                self._store_policy(change.policy)
        except _Stop as err:
            step, why = "write", str(err)
        except (PdcpError, OSError, ValueError) as err:
            step, why = "write", f"{type(err).__name__}: {err}" if not str(err) else str(err)
        if not step:
            if progress is not None:
                progress(total, total, "reading back")
            try:
                mismatch = self._verify(change, after)
            except (PdcpError, OSError) as err:
                mismatch = [f"reading back failed: {err}"]
            if mismatch:
                step, why = "verify", "; ".join(mismatch)
        if not step:
            result.status, result.verified = Status.APPLIED, True
            if progress is not None:
                progress(total, total, f"{change.action} applied")
            return
        result.step, result.reason = step, why
        restore_errors = self._restore(result.links_before, cfg_before, old_params,
                                       policy_before, change)
        if restore_errors:
            result.status = Status.FAILED
            result.reason += "; restoring what was there failed: " + "; ".join(restore_errors)
        else:
            result.status = Status.ROLLED_BACK
            result.reason += "; what was there is restored"

    # -- the parts -----------------------------------------------------------------------
    def _store_policy(self, policy: Policy) -> None:
        self._memory.write_policy(policy.to_json())

    def _verify(self, change: Change, after: list[Link]) -> list[str]:
        """What does not read back as written (empty: verified)."""
        problems: list[str] = []
        system = self._state.snapshot()
        if set(system.links) != set(after):
            missing = set(after) - set(system.links)
            extra = set(system.links) - set(after)
            problems += [f"link {lk} is missing" for lk in sorted(missing)]
            problems += [f"link {lk} should not be there" for lk in sorted(extra)]
        touched = {a.link.input for a in change.links}
        for ref in sorted(touched):
            problems += self._verify_input(system, ref)
        for p in change.parameters:
            got = bytes(self._get(p.device, p.param, p.channel))
            if got != p.value:
                problems.append(f"parameter 0x{p.param:02X} of {p.device} channel {p.channel} "
                                f"reads {got.hex()}, {p.value.hex()} was written")
        if change.configuration is not None:
            from pdcp_studio.model.config_diff import diff_configurations
            from pdcp_studio.storage import config_codec

            back = self._read_memory()
            if config_codec.dumps(back) != config_codec.dumps(change.configuration):
                problems.append("the stored configuration does not verify when read back: "
                                + diff_configurations(change.configuration, back)
                                .describe("written", "read back"))
        if change.policy is not None and self.read_policy() != change.policy:
            problems.append("the policy does not read back as written")
        return problems

    def verify_inputs(self, refs: list[ChannelRef]) -> list[str]:
        """Read each input of ``refs`` back from its device (the profile layer's own plans
        verify so before they release the devices they held)."""
        system = self._state.snapshot()
        return [problem for ref in refs for problem in self._verify_input(system, ref)]

    def _verify_input(self, system: System, ref: ChannelRef) -> list[str]:
        """Read an input's Data Transfer Enabled and Source's Node Ids from the device."""
        if not system.is_present(ref):
            return []
        live = [s for s in system.sources_of(ref) if system.is_present(s)]
        enabled = self._get(ref.device, P.CH_DATA_ENABLED, ref.index)
        if not live:
            if enabled[:1] not in (b"\x00", b""):
                return [f"input {ref} still receives data after its link was removed"]
            return []
        source = live[0]
        want = bytes([self._node_id_of(source.device) or 0,
                      self._channel_node_id(source) or 0])
        ids = self._get(ref.device, P.IN_SOURCE_NODE_IDS, ref.index)
        out: list[str] = []
        if enabled[:1] != b"\x01":
            out.append(f"input {ref} does not receive data from {source}")
        if bytes(ids[:2]) != want:
            out.append(f"input {ref} listens to node IDs {bytes(ids[:2]).hex()}, "
                       f"not {source} ({want.hex()})")
        return out

    def _end_flags(self, change: Change) -> list[tuple[Any, bytes]]:
        """(write, value) pairs holding the present link ends' Data Transfer Enabled now."""
        system = self._state.snapshot()
        ends = sorted({ref for a in change.links for ref in (a.link.output, a.link.input)
                       if system.is_present(ref)})
        return [(ParameterWrite(ref.device, P.CH_DATA_ENABLED, ref.index, b""),
                 bytes(self._get(ref.device, P.CH_DATA_ENABLED, ref.index))) for ref in ends]

    def _restore(self, links_before: list[Link], cfg_before: bytes | None,
                 old_params: list[tuple[Any, bytes]], policy_before: Policy,
                 change: Change) -> list[str]:
        """Put back what was there; returns what could not be put back."""
        errors: list[str] = []
        current = set(self._state.snapshot().links)
        wanted = set(links_before)
        for link in sorted(current - wanted):
            try:
                self._links.remove(link)
            except PdcpError as err:
                errors.append(f"removing {link}: {err}")
        for link in sorted(wanted - current):
            try:
                with self._state.lock:
                    if not self._state.system.has_link(link):
                        self._state.system.check_link(link)
                self._links.add(link)
            except PdcpError as err:
                errors.append(f"re-making {link}: {err}")
        for p, value in reversed(old_params):
            try:
                self._set(p.device, p.param, p.channel, value)
            except PdcpError as err:
                errors.append(f"parameter 0x{p.param:02X} of {p.device}: {err}")
        if change.configuration is not None:
            try:
                from pdcp_studio.storage import config_codec

                if self._memory.read_bytes() != cfg_before:
                    old = (config_codec.loads(cfg_before) if cfg_before is not None
                           else ConfigCollection())
                    self._write_memory(old)
            except (PdcpError, OSError) as err:
                errors.append(f"the stored configuration: {err}")
        if change.policy is not None and self.read_policy() != policy_before:
            try:
                self._store_policy(policy_before)
            except (PdcpError, OSError) as err:
                errors.append(f"the policy: {err}")
        return errors


def _stored_links(data: bytes | None) -> set[Link]:
    """The links of every stored configuration in the memory's bytes (none if unreadable)."""
    from pdcp_studio.storage import config_codec

    if data is None:
        return set()
    try:
        return _links_of(config_codec.loads(data))
    except (PdcpError, ValueError):
        return set()


def _links_of(collection: ConfigCollection | None) -> set[Link]:
    """The links of every configuration in ``collection`` (none for None)."""
    if collection is None:
        return set()
    return {Link(sl.output.ref, sl.input.ref)
            for cfg in collection.configurations for sl in cfg.links}


def _check_cancel(cancel: threading.Event | None, done: int, total: int) -> None:
    if cancel is not None and cancel.is_set():
        raise _Stop(f"cancelled after {done} of {total} steps")


def _check_change(system: System, change: Change) -> str:
    """Why the change cannot be made on ``system`` (empty: it can), before any write."""
    from pdcp_studio.errors import ModelError

    trial = system.copy()
    for n, a in enumerate(change.links, 1):
        try:
            trial.check_link(a.link)
        except ModelError as err:
            return f"action {n} ({a.op} {a.link}): {err}"
        if a.op == "add" and not trial.has_link(a.link):
            for end in (a.link.output, a.link.input):
                if not trial.is_present(end):
                    return f"action {n} (add {a.link}): {end} is not on the bus"
            for s in trial.sources_of(a.link.input):
                if not trial.is_present(s):
                    trial.remove_link(Link(s, a.link.input))
            try:
                trial.add_link(a.link)
            except ModelError as err:
                return f"action {n} (add {a.link}): {err}"
        elif a.op == "remove" and trial.has_link(a.link):
            trial.remove_link(a.link)
    for p in change.parameters:
        device = system.device(p.device)
        if device is None or not device.present:
            return f"device {p.device} is not on the bus"
    return ""


__all__ = ["Transactions"]
