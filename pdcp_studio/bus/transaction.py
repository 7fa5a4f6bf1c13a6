"""The one road for every change to a prosthesis (reference §5): what a change is and what
came of it.

A :class:`Change` says what to do — link actions in order (from a plan, with their reasons),
parameter writes, a stored configuration to write, a profile-layer policy — and a
:class:`TransactionResult` says what happened: applied, declined, failed or rolled back, at
which step and why, the links and the stored configuration's CRC before and after, whether the
change was read back and verified, and what the motion interlock held.

Both are plain values with a JSON form, so the same change runs in-process (simulated and CAN
buses) and over the host link; the arbitrator carries it out
(bus/arbitrator/change/transactions.py), the session previews, asks for confirmation and records it
in the fitting history (bus/session/change_road.py).

Steps, in order (``TransactionResult.step`` names the one that failed)::

    preview → confirm → interlock → write → verify → restore → release → record
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import StrEnum
from typing import TYPE_CHECKING, Any

from pdcp_studio.errors import PdcpError
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Link, System
from pdcp_studio.protocol.records import MutableRecord, Record

if TYPE_CHECKING:
    from pdcp_studio.engine.plan import Plan

#: Suspend Device's TimeValue during a change (reference §5): bounded, renewed while it runs.
INTERLOCK_MS = 2000
#: The interlock is renewed this often (well inside the 2000 ms the devices hold).
INTERLOCK_RENEW_S = 0.7

STEPS = ("preview", "confirm", "interlock", "write", "verify", "restore", "release", "record")


class Status(StrEnum):
    """How a transaction ended."""

    APPLIED = "applied"  # written, read back, verified
    NOTHING = "nothing"  # nothing to change: nothing written
    DECLINED = "declined"  # not confirmed: nothing written
    FAILED = "failed"  # stopped before any write (or a restore failed: see reason)
    ROLLED_BACK = "rolled_back"  # a write or its verification failed; the old state is back


@dataclass(frozen=True, eq=False, repr=False)
class LinkAction(Record):
    """One link made (``op`` "add") or removed ("remove"), and why."""

    op: str
    link: Link
    reason: str = ""

    def to_json(self) -> dict[str, Any]:
        return {"op": self.op, "output": self.link.output.as_json(),
                "input": self.link.input.as_json(), "reason": self.reason}

    @classmethod
    def from_json(cls, doc: dict[str, Any]) -> LinkAction:
        op = str(doc["op"])
        if op not in ("add", "remove"):
            raise ValueError(f"link action {op!r} is neither add nor remove")
        return cls(op, link_from_json(doc), str(doc.get("reason", "")))


@dataclass(frozen=True, eq=False, repr=False)
class ParameterWrite(Record):
    """One parameter value to write to a device (``channel`` 0 = the device itself)."""

    device: DeviceKey
    param: int
    channel: int
    value: bytes

    def to_json(self) -> dict[str, Any]:
        d = self.device
        return {"device": {"vid": d.vid, "pid": d.pid, "serial": d.serial},
                "param": self.param, "channel": self.channel, "value": self.value.hex()}

    @classmethod
    def from_json(cls, doc: dict[str, Any]) -> ParameterWrite:
        d = doc["device"]
        return cls(DeviceKey(int(d["vid"]), int(d["pid"]), int(d["serial"])),
                   int(doc["param"]), int(doc["channel"]), bytes.fromhex(doc["value"]))


@dataclass(frozen=True, eq=False, repr=False)
class Policy(Record):
    """The arbitrator's profile-layer policy (issue 17): may start-up and the duty cycle
    autoconfigure unconnected terminal channels on their own?"""

    autoconfigure: bool = True

    def to_json(self) -> dict[str, Any]:
        return {"autoconfigure": self.autoconfigure}

    @classmethod
    def from_json(cls, doc: dict[str, Any]) -> Policy:
        value = doc.get("autoconfigure", True)
        if not isinstance(value, bool):
            raise ValueError(f"policy autoconfigure {value!r} is not true or false")
        return cls(autoconfigure=value)


@dataclass(eq=False, repr=False)
class Change(MutableRecord):
    """What one transaction changes. Empty parts are left alone.

    ``action`` names it for the history ("apply autoconfigure", "config save", …); ``plan``
    (in-process only) keeps the engine's plan with its rejections and notes for the record.
    """

    action: str
    links: list[LinkAction] = field(default_factory=list)
    parameters: list[ParameterWrite] = field(default_factory=list)
    configuration: ConfigCollection | None = None
    policy: Policy | None = None
    plan: Plan | None = None
    #: Store the links after the change as the arbitrator's configuration, in the same
    #: transaction (``--store``): resolved into ``configuration`` by the preview.
    store: bool = False

    @classmethod
    def from_plan(cls, plan: Plan, action: str = "") -> Change:
        """A plan's actions, in order, with their reasons."""
        return cls(action or f"apply {plan.mode}", plan=plan,
                   links=[LinkAction(a.op.value, a.link, a.reason) for a in plan.actions])

    @classmethod
    def links_to(cls, before: list[Link], after: list[Link], action: str,
                 reason: str = "") -> Change:
        """Removals then additions that turn the links ``before`` into ``after``."""
        old, new = set(before), set(after)
        return cls(action, links=[LinkAction("remove", lk, reason) for lk in sorted(old - new)]
                   + [LinkAction("add", lk, reason) for lk in sorted(new - old)])

    @property
    def empty(self) -> bool:
        return not (self.links or self.parameters or self.configuration is not None
                    or self.policy is not None)

    @property
    def moves(self) -> bool:
        """True when the change can alter channel data (the motion interlock is needed)."""
        return bool(self.links or self.parameters)

    def links_after(self, before: list[Link]) -> list[Link]:
        links = set(before)
        for a in self.links:
            (links.add if a.op == "add" else links.discard)(a.link)
        return sorted(links)

    def plan_json(self) -> list[dict[str, Any]]:
        """The actions with their reasons (what the history keeps as "the plan")."""
        return [a.to_json() for a in self.links]

    def to_json(self) -> dict[str, Any]:
        from pdcp_studio.storage import config_codec

        doc: dict[str, Any] = {"action": self.action,
                               "links": [a.to_json() for a in self.links],
                               "parameters": [p.to_json() for p in self.parameters]}
        if self.configuration is not None:
            doc["configuration"] = config_codec.dumps(self.configuration).hex()
        if self.policy is not None:
            doc["policy"] = self.policy.to_json()
        return doc

    @classmethod
    def from_json(cls, doc: dict[str, Any]) -> Change:
        from pdcp_studio.storage import config_codec

        cfg = doc.get("configuration")
        pol = doc.get("policy")
        return cls(str(doc.get("action", "")),
                   links=[LinkAction.from_json(a) for a in doc.get("links", [])],
                   parameters=[ParameterWrite.from_json(p) for p in doc.get("parameters", [])],
                   configuration=config_codec.loads(bytes.fromhex(cfg)) if cfg else None,
                   policy=Policy.from_json(pol) if pol is not None else None)


@dataclass(eq=False, repr=False)
class TransactionResult(MutableRecord):
    """What came of a transaction. ``step`` and ``reason`` name where and why it stopped."""

    status: Status
    action: str = ""
    step: str = ""
    reason: str = ""
    links_before: list[Link] = field(default_factory=list)
    links_after: list[Link] = field(default_factory=list)
    config_crc_before: str | None = None
    config_crc_after: str | None = None
    verified: bool = False
    interlock: str = ""
    held: list[DeviceKey] = field(default_factory=list)
    devices: list[DeviceKey] = field(default_factory=list)
    policy_before: Policy | None = None
    policy_after: Policy | None = None
    history_id: int | None = None
    notes: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        """Applied, or nothing needed changing."""
        return self.status in (Status.APPLIED, Status.NOTHING)

    @property
    def written(self) -> bool:
        """True when the prosthesis now holds the change."""
        return self.status is Status.APPLIED

    def summary(self) -> str:
        """One line for a person."""
        if self.status is Status.APPLIED:
            return (f"{self.action}: applied and verified ({len(self.links_after)} link(s); "
                    f"interlock: {self.interlock or 'not needed'})")
        if self.status is Status.NOTHING:
            return f"{self.action}: nothing to change"
        if self.status is Status.DECLINED:
            return f"{self.action}: not confirmed, nothing written"
        word = "rolled back" if self.status is Status.ROLLED_BACK else "failed"
        return f"{self.action}: {word} at step {self.step}: {self.reason}"

    def to_json(self) -> dict[str, Any]:
        return {
            "status": self.status.value, "action": self.action, "step": self.step,
            "reason": self.reason,
            "links_before": [lk.as_json() for lk in self.links_before],
            "links_after": [lk.as_json() for lk in self.links_after],
            "config_crc_before": self.config_crc_before,
            "config_crc_after": self.config_crc_after,
            "verified": self.verified, "interlock": self.interlock,
            "held": [key_json(k) for k in self.held],
            "devices": [key_json(k) for k in self.devices],
            "policy_before": self.policy_before.to_json() if self.policy_before else None,
            "policy_after": self.policy_after.to_json() if self.policy_after else None,
            "history_id": self.history_id, "notes": list(self.notes),
        }

    @classmethod
    def from_json(cls, doc: dict[str, Any]) -> TransactionResult:
        def pol(d: Any) -> Policy | None:
            return Policy.from_json(d) if d is not None else None

        return cls(Status(doc["status"]), str(doc.get("action", "")), str(doc.get("step", "")),
                   str(doc.get("reason", "")),
                   [link_from_json(d) for d in doc.get("links_before", [])],
                   [link_from_json(d) for d in doc.get("links_after", [])],
                   doc.get("config_crc_before"), doc.get("config_crc_after"),
                   bool(doc.get("verified")), str(doc.get("interlock", "")),
                   [key_from_json(d) for d in doc.get("held", [])],
                   [key_from_json(d) for d in doc.get("devices", [])],
                   pol(doc.get("policy_before")), pol(doc.get("policy_after")),
                   doc.get("history_id"), list(doc.get("notes", [])))


# -- small helpers shared by the arbitrator, the sessions and the history ---------------
def key_json(key: DeviceKey) -> dict[str, int]:
    return {"vid": key.vid, "pid": key.pid, "serial": key.serial}


def key_from_json(doc: dict[str, Any]) -> DeviceKey:
    return DeviceKey(int(doc["vid"]), int(doc["pid"]), int(doc["serial"]))


def ref_from_json(doc: dict[str, Any]) -> ChannelRef:
    return ChannelRef(int(doc["vid"]), int(doc["pid"]), int(doc["serial"]), int(doc["index"]))


def link_from_json(doc: dict[str, Any]) -> Link:
    return Link(ref_from_json(doc["output"]), ref_from_json(doc["input"]))


def config_crc(collection: ConfigCollection | None) -> str | None:
    """The stored configuration's CRC-16 record as ``"0x68A3"`` (None: nothing stored)."""
    from pdcp_studio.storage import config_codec

    if collection is None:
        return None
    return crc_of_bytes(config_codec.dumps(collection))


def crc_of_bytes(data: bytes | None) -> str | None:
    """The CRC-16 in a stored configuration's checksum record (the one before End); None
    when nothing is stored — no bytes, or a collection with no configuration (what the
    memory holds once only the policy was written): the preview's "nothing stored" and the
    arbitrator's must read alike."""
    if data is None or len(data) < 6 or data == _empty_collection():
        return None
    return f"0x{int.from_bytes(data[-5:-3], 'little'):04X}"


@functools.cache
def _empty_collection() -> bytes:
    from pdcp_studio.storage import config_codec

    return config_codec.dumps(ConfigCollection([]))


def interlocked_devices(system: System, before: list[Link], after: list[Link],
                        parameters: Sequence[ParameterWrite] = ()) -> list[DeviceKey]:
    """Present devices whose output channels feed a terminal channel before or after the
    change (reference §5), plus devices whose parameters are written that feed one."""
    feeders: set[DeviceKey] = set()
    for link in set(before) | set(after):
        ch = system.channel(link.input)
        if ch is not None and ch.terminal and system.is_present(link.output):
            feeders.add(link.output.device)
    for write in parameters:
        device = system.device(write.device)
        if device is not None and device.present and any(
                system.inputs_fed_by(device.ref(o.index)) for o in device.outputs()):
            feeders.add(write.device)
    return sorted(feeders)


def describe_interlock(held: list[DeviceKey], refused: DeviceKey | None = None) -> str:
    """The history's ``interlock`` text: "held 2 devices", "not needed", "refused by …"."""
    if refused is not None:
        return f"refused by {refused}"
    if not held:
        return "not needed"
    return f"held {len(held)} device{'s' if len(held) != 1 else ''}"


class NotRestorable(PdcpError):
    """A fitting-history entry cannot be put back: it was interrupted (what it left is not
    known), or a part it needs is not on the bus (``missing`` names them)."""

    def __init__(self, message: str, missing: Sequence[DeviceKey] = ()) -> None:
        super().__init__(message)
        self.missing = list(missing)


def parts_needed(entry: dict[str, Any]) -> list[DeviceKey]:
    """The parts a restore of ``entry`` writes to: the ends of its links after, and the
    parts whose values it recorded."""
    needed = {r.device for d in entry.get("links_after") or []
              for r in (ref_from_json(d["output"]), ref_from_json(d["input"]))}
    for where in (entry.get("parameters_after") or {}):
        vid, pid, serial = where.split("#", 1)[0].split("/")
        needed.add(DeviceKey(int(vid), int(pid), int(serial)))
    return sorted(needed)


def restore_writes(recorded: dict[str, dict[str, str]], system: System
                   ) -> list[ParameterWrite]:
    """The parameter writes that put back the named values ``recorded`` (an entry's
    ``parameters_after``) on the parts of ``system`` that differ; absent parts are skipped
    (:func:`parts_needed` refuses them first)."""
    from pdcp_studio.model import param_names

    writes: list[ParameterWrite] = []
    for where, wanted in sorted(recorded.items()):
        head, _, index = where.partition("#")
        vid, pid, serial = (int(x) for x in head.split("/"))
        key = DeviceKey(vid, pid, serial)
        device = system.device(key)
        if device is None or not device.present:
            continue
        obj = device.channels.get(int(index)) if index else device
        if obj is None:
            continue
        now = param_names.values(obj)
        differ = {name: value for name, value in wanted.items() if now.get(name) != value}
        for param, data in param_names.writes_for(obj, differ):
            writes.append(ParameterWrite(key, param, int(index or 0), data))
    return writes


def restore_change(entry: dict[str, Any], system: System) -> Change:
    """The Change that puts back what a fitting-history ``entry`` left on the prosthesis
    ``system`` (as read now): its links after, its parts' parameter values, the stored
    configuration read after it and its policy after (one restore for the CLI and app).
    NotRestorable for an interrupted entry, or when a part it needs is absent (before
    anything is written)."""
    from pdcp_studio.engine.effect import system_after
    from pdcp_studio.storage import config_codec

    if entry.get("links_after") is None:
        raise NotRestorable(f"history: entry {entry['id']} was interrupted; what it left is "
                            "not known (restore the entry before it)")
    missing = [k for k in parts_needed(entry)
               if (d := system.device(k)) is None or not d.present]
    if missing:
        raise NotRestorable(f"history: entry {entry['id']} needs parts that are not on the "
                            "bus: " + ", ".join(str(k) for k in missing), missing)
    after = [link_from_json(d) for d in entry["links_after"]]
    change = Change.links_to(list(system.links), after, f"history restore {entry['id']}",
                             reason=f"as after fitting history entry {entry['id']}")
    # The values are compared on the system as the link actions leave it: a link made or
    # removed turns its ends' data transfer on or off, which the recorded values may undo.
    linked = system_after(system, after, [])
    change.parameters = restore_writes(entry.get("parameters_after") or {}, linked)
    cfg = entry.get("configuration_after")
    if cfg is not None:
        change.configuration = config_codec.from_json(cfg)
    if entry.get("policy_after") is not None:
        change.policy = Policy.from_json(entry["policy_after"])
    return change
