"""The session half of the change road: preview, the user's confirmation, the record.

The change road (reference §5) is split where it must be: the arbitrator carries a change out
(interlock → write → verify → restore on mismatch → release:
``bus/arbitrator/change/transactions.py``, reached in-process or over the host link by
``BusSession.carry_out``), and :func:`run_transaction` — behind every session's ``transact`` — does
what belongs to the PC.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from pdcp_studio.bus.session.base import ProgressFn
from pdcp_studio.bus.transaction import (
    Change,
    Policy,
    Status,
    TransactionResult,
    config_crc,
    describe_interlock,
    interlocked_devices,
)
from pdcp_studio.model.config_diff import ConfigDiff, diff_configurations
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Link

if TYPE_CHECKING:
    from pdcp_studio.bus.session.base import BusSession
    from pdcp_studio.storage.history import History

__all__ = ["ChangePreview", "ConfirmFn", "ProgressFn", "preview_change", "run_transaction"]


@dataclass
class ChangePreview:
    """What a change will do, shown before the user confirms it."""

    change: Change
    url: str
    links_before: list[Link]
    links_after: list[Link]
    config_before: ConfigCollection
    config_diff: ConfigDiff | None
    policy_before: Policy
    held: list[DeviceKey]
    devices: list[DeviceKey] = field(default_factory=list)

    @property
    def empty(self) -> bool:
        """True when carrying the change out would change nothing."""
        links_same = set(self.links_before) == set(self.links_after)
        cfg_same = self.config_diff is None or self.config_diff.equal
        pol_same = self.change.policy is None or self.change.policy == self.policy_before
        return links_same and cfg_same and pol_same and not self.change.parameters

    def lines(self) -> list[str]:
        """The preview in plain words (the plan's reasons, the configuration difference)."""
        out = [f"{self.change.action} on {self.url}:"]
        current = set(self.links_before)
        for a in self.change.links:
            if (a.op == "add") == (a.link in current):
                continue
            (current.add if a.op == "add" else current.discard)(a.link)
            sign = "+" if a.op == "add" else "-"
            out.append(f"  {sign} link {a.link}" + (f"  ({a.reason})" if a.reason else ""))
        for p in self.change.parameters:
            out.append(f"  set parameter 0x{p.param:02X} of {p.device} channel {p.channel} "
                       f"to {p.value.hex() or '(empty)'}")
        if self.config_diff is not None:
            diff = self.config_diff.lines("stored now", "to store")
            out += [f"  stored configuration: {line}" for line in diff]
            if not diff:
                out.append("  stored configuration: unchanged")
        if self.change.policy is not None:
            old, new = self.policy_before.autoconfigure, self.change.policy.autoconfigure
            out.append(f"  autoconfigure: {'on' if old else 'off'} → {'on' if new else 'off'}")
        if self.empty:
            out.append("  nothing to change")
        elif self.change.moves:
            out.append(f"  motion interlock: {describe_interlock(self.held)} "
                       + (f"({', '.join(str(k) for k in self.held)}) " if self.held else "")
                       + "while the change is made")
        out.append(f"  links after: {len(self.links_after)}")
        return out


ConfirmFn = Callable[[ChangePreview], bool]


def preview_change(session: BusSession, change: Change) -> ChangePreview:
    """The preview of ``change`` on ``session``'s prosthesis as it is now."""
    system = session.system()
    before = system.links
    after = change.links_after(before)
    config_before = session.read_configuration()
    diff = (diff_configurations(config_before, change.configuration)
            if change.configuration is not None else None)
    held = interlocked_devices(system, before, after, change.parameters) if change.moves else []
    devices = sorted(k for k, d in system.devices.items() if d.present)
    return ChangePreview(change, session.url, before, after, config_before,
                         diff, session.read_policy(), held, devices)


def run_transaction(session: BusSession, change: Change, *, operator: str | None = None,
                    patient: str | None = None, confirm: ConfirmFn | None = None,
                    progress: ProgressFn | None = None, cancel: threading.Event | None = None,
                    history: History | None = None, record: bool = True) -> TransactionResult:
    """The change road's PC half around ``session.carry_out``: preview → confirm → (the
    arbitrator's interlock, write, verify, restore, release) → record.

    ``confirm(preview)`` returns True to go on; None means the caller has already confirmed
    (``--yes``). A declined or empty change writes and records nothing. Every change that
    reached the arbitrator is recorded (applied, failed or rolled back) in ``history`` (the
    user's archive when None) unless ``record`` is False: it is announced before the write
    (``History.begin``) and recorded after (``History.finish``), so a PC that dies in between
    leaves an ``interrupted`` entry, never none. An archive that cannot be written stops the
    change before anything is written (step ``record``).
    """
    try:
        preview = preview_change(session, change)
    except Exception as err:  # any failure to read is the preview's
        return TransactionResult(Status.FAILED, change.action, "preview", str(err))
    if preview.empty:
        before = preview.links_before
        crc = config_crc(preview.config_before)
        return TransactionResult(Status.NOTHING, change.action, "preview", "nothing to change",
                                 before, before, crc, crc, True, "not needed",
                                 devices=preview.devices)
    if confirm is not None and not confirm(preview):
        return TransactionResult(Status.DECLINED, change.action, "confirm",
                                 "the change was not confirmed",
                                 preview.links_before, preview.links_before,
                                 devices=preview.devices)
    if cancel is not None and cancel.is_set():
        return TransactionResult(Status.DECLINED, change.action, "confirm", "cancelled",
                                 preview.links_before, preview.links_before,
                                 devices=preview.devices)
    if not record:
        result = session.carry_out(change, progress, cancel)
        if not result.devices:
            result.devices = preview.devices
        return result
    from pdcp_studio.storage.history import History, entry_from_result, interrupted

    bus = session.url
    archive = history if history is not None else History.open()
    try:
        announced = TransactionResult(
            Status.FAILED, change.action, links_before=preview.links_before,
            config_crc_before=config_crc(preview.config_before), interlock="unknown",
            devices=preview.devices, policy_before=preview.policy_before)
        try:
            token = archive.begin(interrupted(entry_from_result(
                announced, change, bus=bus, operator=operator, patient=patient)))
        except Exception as err:  # no record, no change: a clinic must be able to say
            return TransactionResult(Status.FAILED, change.action, "record",
                                     f"the fitting history cannot be written ({err}); "
                                     "nothing was written to the prosthesis",
                                     preview.links_before, preview.links_before,
                                     devices=preview.devices)
        result = session.carry_out(change, progress, cancel)
        if not result.devices:
            result.devices = preview.devices
        try:
            try:
                after = session.read_configuration()
            except Exception:  # the record still says what happened, without the contents
                after = None
            entry = entry_from_result(result, change, bus=bus, operator=operator,
                                      patient=patient, configuration_after=after)
            result.history_id = archive.finish(token, entry)
        except Exception as err:  # the change stands; its announcement is recovered later
            result.notes.append(f"not recorded in the fitting history: {err}")
            if result.ok:
                result.step, result.reason = "record", f"not recorded: {err}"
    finally:
        if history is None:
            archive.close()
    return result
