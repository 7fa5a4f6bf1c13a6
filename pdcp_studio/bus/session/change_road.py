"""The session half of the change road: preview, the user's confirmation, the record.

The change road (reference §5) is split where it must be: the arbitrator carries a change out
(interlock → write → verify → restore on mismatch → release:
``bus/arbitrator/change/transactions.py``, reached in-process or over the host link by
``BusSession.carry_out``), and :func:`run_transaction` — behind every session's ``transact`` — does
what belongs to the PC.
"""

from __future__ import annotations

import copy
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
    interlocked_devices,
)
from pdcp_studio.engine import configuration_from_system
from pdcp_studio.engine.effect import Effect, effect_of, system_after
from pdcp_studio.model.config_diff import ConfigDiff, diff_configurations
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.names import Names
from pdcp_studio.model.param_names import snapshot
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Link, System

Translate = Callable[[str], str]

if TYPE_CHECKING:
    from pdcp_studio.bus.session.base import BusSession
    from pdcp_studio.storage.archive.chain import Anchor
    from pdcp_studio.storage.history import History

__all__ = ["ChangePreview", "ConfirmFn", "ProgressFn", "names_for", "preview_change",
           "resolve_store", "run_transaction"]


@dataclass
class ChangePreview:
    """What a change will do, shown before the user confirms it: the change (its stored
    configuration resolved when it is to be stored) and its :class:`Effect`, the one source
    of every text about it."""

    change: Change
    url: str
    links_before: list[Link]
    links_after: list[Link]
    config_before: ConfigCollection
    config_diff: ConfigDiff | None
    policy_before: Policy
    held: list[DeviceKey]
    devices: list[DeviceKey] = field(default_factory=list)
    effect: Effect | None = None

    @property
    def empty(self) -> bool:
        """True when carrying the change out would change nothing."""
        links_same = set(self.links_before) == set(self.links_after)
        cfg_same = self.config_diff is None or self.config_diff.equal
        pol_same = self.change.policy is None or self.change.policy == self.policy_before
        params_same = (self.effect is None and not self.change.parameters) or (
            self.effect is not None and not self.effect.parameters)
        return links_same and cfg_same and pol_same and params_same

    def lines(self, tr: Translate | None = None) -> list[str]:
        """The preview in plain words: what changes, what the next power-on does, and the
        codes last, under "Technical detail"."""
        t: Translate = tr or (lambda text: text)
        out = [f"{self.change.action} on {self.url}:"]
        if self.effect is None:
            return out
        reasons = {a.link: a.reason for a in self.change.links if a.reason}
        out += [f"  {line}" for line in self.effect.lines(t, reasons)]
        out += [f"  {line}" for line in self.effect.power_on_lines(t)]
        technical = self.effect.technical()
        if technical:
            out.append("  " + t("Technical detail:"))
            out += [f"    {line}" for line in technical]
        return out


ConfirmFn = Callable[[ChangePreview], bool]


def resolve_store(system: System, change: Change) -> Change:
    """``change`` with ``store`` carried out: the links (and parameters) after it become
    the stored configuration it writes. A change that moves nothing stores nothing —
    except a replacement, whose links the duty cycle may already have made: storing them
    is what lets start-up forget the replaced part."""
    if not change.store:
        return change
    after = change.links_after(system.links)
    repairs = change.plan is not None and change.plan.mode == "replacements"
    if set(after) == set(system.links) and not change.parameters and not repairs:
        return change
    written = system_after(system, after, change.parameters)
    resolved = copy.copy(change)
    resolved.configuration = ConfigCollection([configuration_from_system(written)])
    return resolved


def names_for(system: System, tr: Translate | None = None) -> Names:
    """The names every text of a change uses (the profile names from the named trees)."""
    from pdcp_studio.storage.profile_trees import system_names

    return system_names(system, tr=tr)


def preview_change(session: BusSession, change: Change, *,
                   names: Names | None = None) -> ChangePreview:
    """The preview of ``change`` on ``session``'s prosthesis as it is now."""
    system = session.system()
    change = resolve_store(system, change)
    before = system.links
    after = change.links_after(before)
    config_before = session.read_configuration()
    diff = (diff_configurations(config_before, change.configuration)
            if change.configuration is not None else None)
    held = interlocked_devices(system, before, after, change.parameters) if change.moves else []
    devices = sorted(k for k, d in system.devices.items() if d.present)
    policy_before = session.read_policy()
    effect = effect_of(system, links_after=after, parameters=change.parameters,
                       config_before=config_before, config_after=change.configuration,
                       policy_before=policy_before.autoconfigure,
                       policy_after=(change.policy.autoconfigure
                                     if change.policy is not None else None),
                       held=held, names=names or names_for(system), crc=config_crc)
    return ChangePreview(change, session.url, before, after, config_before,
                         diff, policy_before, held, devices, effect)


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
    change = preview.change  # its stored configuration resolved (``store``)
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
    from pdcp_studio.storage.history import (
        History,
        NotAllowedError,
        entry_from_result,
        interrupted,
    )

    bus = session.url
    try:
        archive = history if history is not None else History.open()
    except Exception as err:  # the archive in use cannot be opened (a server down)
        return TransactionResult(Status.FAILED, change.action, "record",
                                 f"the fitting history cannot be written ({err}); "
                                 "nothing was written to the prosthesis",
                                 preview.links_before, preview.links_before,
                                 devices=preview.devices)
    try:
        announced = TransactionResult(
            Status.FAILED, change.action, links_before=preview.links_before,
            config_crc_before=config_crc(preview.config_before), interlock="unknown",
            devices=preview.devices, policy_before=preview.policy_before)
        refused = _unverified(session, archive, preview.devices)
        if refused:
            return TransactionResult(Status.FAILED, change.action, "record", refused,
                                     preview.links_before, preview.links_before,
                                     devices=preview.devices)
        try:
            token = archive.begin(interrupted(entry_from_result(
                announced, change, bus=bus, operator=operator, patient=patient)))
        except NotAllowedError as err:  # a reader: refused before any frame, in words
            return TransactionResult(Status.FAILED, change.action, "record",
                                     f"refused: {err}; nothing was written to the prosthesis",
                                     preview.links_before, preview.links_before,
                                     devices=preview.devices)
        except Exception as err:  # no record, no change: a clinic must be able to say
            return TransactionResult(Status.FAILED, change.action, "record",
                                     f"the fitting history cannot be written ({err}); "
                                     "nothing was written to the prosthesis",
                                     preview.links_before, preview.links_before,
                                     devices=preview.devices)
        try:
            anchor = _announce(session, archive, token)
        except Exception as err:  # the memory cannot take the anchor: nor would it the change
            reason = (f"the fitting history's anchor cannot be written to the prosthesis "
                      f"({err}); nothing was written to the prosthesis")
            archive.finish(token, {**entry_from_result(TransactionResult(
                Status.FAILED, change.action, "record", reason, preview.links_before,
                preview.links_before, devices=preview.devices), change, bus=bus,
                operator=operator, patient=patient), "announcement": token})
            return TransactionResult(Status.FAILED, change.action, "record", reason,
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
            try:
                values = snapshot(d for d in session.system().devices.values() if d.present)
            except Exception:  # the record still says what happened, without the values
                values = None
            entry = entry_from_result(result, change, bus=bus, operator=operator,
                                      patient=patient, configuration_after=after,
                                      effect=preview.effect if result.written else None,
                                      parameters_after=values)
            entry["announcement"] = token
            result.history_id = archive.finish(token, entry)
            if anchor is not None:
                _anchor(session, archive, result)
        except Exception as err:  # the change stands; its announcement is recovered later
            result.notes.append(f"not recorded in the fitting history: {err}")
            if result.ok:
                result.step, result.reason = "record", f"not recorded: {err}"
    finally:
        if history is None:
            archive.close()
    return result


# -- the fitting history's anchor (reference §5 Decision, issue 28; docs/decisions.md) ------
def _unverified(session: BusSession, archive: History, devices: list[DeviceKey]) -> str | None:
    """Why a change must not append to ``archive`` (its chain is broken, or its last entry
    for this prosthesis is not the one the prosthesis remembers), in words with the way on;
    None when it may."""
    from pdcp_studio.storage.archive.anchor import check

    try:
        anchor = session.read_anchor()
        problem = check(archive, anchor, {(k.vid, k.pid, k.serial) for k in devices})
    except Exception as err:  # an anchor or archive that cannot be read is not verified
        problem = str(err)
    if problem is None:
        return None
    return (f"refused: the fitting history {archive.location} does not verify against this "
            f"prosthesis: {problem}. Nothing was written to the prosthesis. See what differs "
            f"with `pdcp-studio history verify --bus {session.url}`; keep the evidence "
            "(`pdcp-studio history export -o FILE`) and put back the archive that recorded "
            "this prosthesis's changes (its backup, or a clinic's archive with --archive); "
            "if it is lost for good, `pdcp-studio history re-anchor --bus "
            f"{session.url} --reason TEXT --yes` records that and ties the prosthesis to "
            "this archive")


def _announce(session: BusSession, archive: History, token: str) -> Anchor | None:
    """Tell the prosthesis, before the change writes, which announcement it is changed
    under: the anchor keeps its entry and adds ``token``. An earlier announcement whose
    entry was recorded but never anchored (the PC stopped) is anchored first, so one
    unanchored entry at most ever follows the anchored one. None: it keeps no anchor."""
    from pdcp_studio.storage.archive.chain import Anchor

    current = session.read_anchor()
    entry, digest = (current.entry, current.hash) if current is not None else (0, "")
    if current is not None and current.announced:
        for e in archive.entries():
            if e.get("announcement") == current.announced:
                entry, digest = int(e["id"]), str(e["hash"])
    return session.write_anchor(Anchor(entry, digest, token))


def _anchor(session: BusSession, archive: History, result: TransactionResult) -> None:
    """Anchor the entry just recorded: its id (the archive's entry count then) and hash, in
    the prosthesis's memory. A failure is said in the result; the announcement the memory
    already holds still lets ``history verify --bus`` accept this one entry."""
    from pdcp_studio.storage.archive.chain import Anchor

    entry = archive.get(result.history_id) if result.history_id else None
    try:
        if entry is None:
            raise ValueError(f"entry {result.history_id} cannot be read back")
        session.write_anchor(Anchor(int(entry["id"]), str(entry["hash"])))
    except Exception as err:
        result.notes.append(f"the prosthesis's fitting history anchor was not updated: {err}")
