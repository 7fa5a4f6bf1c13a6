"""The guided tasks' decisions, without Qt: what is missing, what is new, the plan and the
one change each task writes, and whether the prosthesis holds it afterwards.

Every wizard ends in the change road (reference §5): the change made here is previewed,
confirmed and carried out by ``session.transact`` like any other. Nothing in this module
talks to a bus; each function takes what the bus said and returns a decision, so the
decisions are tested without threads or windows.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from pdcp_studio.bus.transaction import Change, LinkAction
from pdcp_studio.engine import Plan, configuration_from_system, plan_for, set_links
from pdcp_studio.engine.procedures import missing_devices
from pdcp_studio.model.config_diff import diff_configurations
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Link, System

#: What a wizard's change is called in the fitting history.
ACTION_FITTING = "new fitting: connect"
ACTION_STORE = "new fitting: store configuration"
ACTION_REPLACE = "replace a part"
ACTION_RESTORE_FILE = "restore configuration from file"


@dataclass(frozen=True)
class MissingPart:
    """A part the prosthesis expects (links on the bus or in the stored configuration reach
    it) that is not on the bus."""

    key: DeviceKey
    links: int


def stored_links(collection: ConfigCollection | None) -> set[Link]:
    """Every link of every stored configuration, as links between channel references."""
    if collection is None:
        return set()
    return {Link(sl.output.ref, sl.input.ref)
            for cfg in collection.configurations for sl in cfg.links}


def _touches(link: Link, keys: Iterable[DeviceKey]) -> bool:
    keys = set(keys)
    return link.output.device in keys or link.input.device in keys


def missing_parts(system: System, stored: ConfigCollection | None) -> list[MissingPart]:
    """The parts that are gone: absent devices that links on the bus or in the stored
    configuration still reach (a spare that was never linked is not missing)."""
    keys = {k for k, d in system.devices.items() if not d.present}
    keys |= {d.key for d in missing_devices(system, stored or None)}
    links = set(system.links) | stored_links(stored)
    out = []
    for key in sorted(keys):
        n = sum(1 for lk in links if _touches(lk, (key,)))
        if n:
            out.append(MissingPart(key, n))
    return out


def new_parts(system: System, known: Iterable[DeviceKey]) -> list[DeviceKey]:
    """The present devices that are not among ``known`` (the parts plugged in since)."""
    seen = set(known)
    return sorted(k for k, d in system.devices.items() if d.present and k not in seen)


def _usable(stored: ConfigCollection | None) -> ConfigCollection | None:
    return stored if stored is not None and stored.configurations else None


def replacement_plan(system: System, stored: ConfigCollection | None,
                     new: Iterable[DeviceKey]) -> Plan:
    """Find replacements (listing 4.6) as if the new parts had just been plugged in: the
    links the arbitrator may already have made to them on its own are set aside first, so
    the plan says for each one why it is made and how similar it is."""
    base = system.copy()
    set_links(base, [lk for lk in base.links if not _touches(lk, new)])
    return plan_for("replacements", base, _usable(stored))


def autoconfigure_plan(system: System) -> Plan:
    """Autoconfigure (listing 4.7) on the prosthesis as it is."""
    return plan_for("autoconfigure", system)


def implement_plan(system: System, collection: ConfigCollection) -> Plan:
    """Implement a stored configuration (listing 4.3) on the prosthesis as it is."""
    return plan_for("implement", system, collection)


def change_to(links_now: Iterable[Link], plan: Plan, action: str,
              other_reason: str = "not in the plan") -> Change:
    """The change that brings the links on the bus to the plan's result: removals, then
    additions, each with the plan's reason (links the bus already has are left alone)."""
    now, final = set(links_now), set(plan.final_links)
    reasons = {a.link: a.reason for a in plan.actions}
    return Change(action, plan=plan,
                  links=[LinkAction("remove", lk, reasons.get(lk, other_reason))
                         for lk in sorted(now - final)]
                  + [LinkAction("add", lk, reasons.get(lk, "")) for lk in sorted(final - now)])


def configuration_of(system: System, links: Iterable[Link]) -> ConfigCollection:
    """``links`` on ``system``'s devices as a stored configuration (configuration 1)."""
    trial = system.copy()
    set_links(trial, list(links))
    return ConfigCollection([configuration_from_system(trial)])


def store_change(system: System) -> Change:
    """Store the links on the prosthesis now as its configuration (one transaction)."""
    return Change(ACTION_STORE, configuration=configuration_of(system, system.links))


def replacement_change(system: System, plan: Plan) -> Change:
    """The replacement plan's links, and the stored configuration that names the new part
    (so the next start-up needs no replacement), in one transaction."""
    change = change_to(system.links, plan, ACTION_REPLACE, "not in the replacement plan")
    change.configuration = configuration_of(system, plan.final_links)
    return change


def restore_file_change(system: System, collection: ConfigCollection, name: str) -> Change:
    """Write a configuration file back: its links made (implement), the file stored."""
    plan = implement_plan(system, collection)
    change = change_to(system.links, plan, f"{ACTION_RESTORE_FILE} {name}",
                       "not in the configuration being restored")
    change.configuration = collection
    return change


def clears_stored(change: Change | None, stored: ConfigCollection | None) -> bool:
    """True when ``change`` writes an empty stored configuration over one that holds links:
    a history entry made before any configuration was stored puts that emptiness back, and
    after it the prosthesis links nothing as stored at its next start-up."""
    configuration = getattr(change, "configuration", None)
    return (configuration is not None and not stored_links(configuration)
            and bool(stored_links(stored)))


@dataclass(frozen=True)
class Problem:
    """One way the prosthesis does not hold what was written.

    ``kind``: ``link-missing`` (a planned link is not on the bus), ``link-extra`` (a link
    the plan does not have), ``config-differs`` (the stored configuration read back is not
    the one written), ``part-missing`` (a part a link needs is not on the bus)."""

    kind: str
    link: Link | None = None
    key: DeviceKey | None = None


def verify(system: System, stored_now: ConfigCollection | None, links: Iterable[Link],
           configuration: ConfigCollection | None) -> list[Problem]:
    """Read-back check after a wizard's write: the links and stored configuration as
    planned, and every linked part on the bus. Empty when all is as written."""
    out: list[Problem] = []
    want, have = set(links), set(system.links)
    out += [Problem("link-missing", lk) for lk in sorted(want - have)]
    out += [Problem("link-extra", lk) for lk in sorted(have - want)]
    if configuration is not None:
        if stored_now is None or not diff_configurations(stored_now, configuration).equal:
            out.append(Problem("config-differs"))
    for key in sorted({k for lk in want for k in (lk.output.device, lk.input.device)}):
        device = system.devices.get(key)
        if device is None or not device.present:
            out.append(Problem("part-missing", key=key))
    return out
