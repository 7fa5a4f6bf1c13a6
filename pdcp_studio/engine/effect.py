"""What a change does to a prosthesis — computed once, said in words everywhere. Pure.

A change (link actions, parameter writes, a stored configuration, a policy) is judged against
the prosthesis as read: the links it makes and removes, each parameter old → new by name and
in words (a type's control mode, data type and size; a profile by its name in the profile
tree; a descriptor as text; a flag as on/off), the stored configuration before and after, the
policy, the parts the motion interlock holds, and what the next power-on will do — the
engine's own start-up run on the system as written and the stored configuration as it will
be (reference §2 start-up, §5: a live change that is not stored reverts then).

:class:`Effect` is the one source for the Write confirmation, the pending changes, undo and
redo, the CLI preview and its ``--json`` (contracts §2 ``effect`` and ``next_power_on``), the
fitting history, the restore preview, the wizards' last page and the report. Its words come
from templates (``tr`` translates them: the app passes Qt's translate, context ``Effect``);
the names of parts and channels come from :mod:`pdcp_studio.model.names` and travel with the
effect (``names``), so an effect read back from the history reads as it did. Codes and hex
appear only in :meth:`Effect.technical`.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

from pdcp_studio.engine.modes import plan_on_bus
from pdcp_studio.engine.plan import set_links
from pdcp_studio.engine.procedures import resolve_configuration
from pdcp_studio.errors import ModelError, ParameterError
from pdcp_studio.model import param_fields as F
from pdcp_studio.model import param_names as N
from pdcp_studio.model import parameters as P
from pdcp_studio.model.channel_type import ChannelType
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.names import Names
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Channel, Device, Link, System

Translate = Callable[[str], str]


def _same(text: str) -> str:
    return text


class ParameterWriteLike(Protocol):
    """A parameter write (``bus.transaction.ParameterWrite``), as the effect reads it."""

    @property
    def device(self) -> DeviceKey: ...
    @property
    def param(self) -> int: ...
    @property
    def channel(self) -> int: ...
    @property
    def value(self) -> bytes: ...


# -- the words (English templates; the app marks them for translation, context "Effect") --
T_LINK_ADDED = "Link made: {link}"
T_LINK_REMOVED = "Link removed: {link}"
T_PARAM = "{where}: {what}"
T_CHANGE = "{what} {old} → {new}"
T_CONTROL_MODE = "control mode"
T_DATA_TYPE = "data type"
T_TERMINAL = "terminal channel"
T_SOLE = "sole access"
T_PRESCALER = "prescaler"
T_PROFILE = "profile"
T_NAME = "name"
T_DATA_TRANSFER = "data transfer"
T_BEACON = "beacon interval"
T_ACK = "acknowledgement timeout"
T_BIND = "bind request timeout"
T_REQUIRED = "required inputs"
T_DESIRED = "desired inputs"
T_TERMINAL_PROFILE = "terminal profile"
T_MS = "{n} ms"
T_ON = "on"
T_OFF = "off"
T_YES = "yes"
T_NO = "no"
T_NONE = "none"
T_BITS = "{bits}-bit {kind}"
T_STORED_SAME = "Stored configuration: unchanged."
T_STORED_NEW = ("Stored configuration: replaced; it will hold {links} "
                "({added} added, {removed} removed).")
T_STORED_CLEARED = "Stored configuration: cleared (nothing stored)."
T_STORED_ADD = "  stored from now on: {link}"
T_STORED_DROP = "  no longer stored: {link}"
T_POLICY = "Automatic set-up (autoconfigure): {old} → {new}."
T_POLICY_OFF_STAY = "Turning automatic set-up off removes nothing: {links} stay as they are."
T_POLICY_STAYS = "  stays: {link}"
T_MUTED = ("This link stays but carries no data while data transfer is off at one of its "
           "ends: {link}")
T_ONE_LINK = "{n} link"
T_LINKS = "{n} links"
T_HELD = "While the change is made, these parts are held still: {parts}."
T_HELD_NONE = "No part needs to be held still for this change."
T_NOTHING = "Nothing changes on the prosthesis."
T_PO_SAME = "At the next power-on: nothing changes; start-up keeps these links."
T_PO_HEAD = "At the next power-on, start-up will change the links:"
T_PO_BACK = "  comes back: {link}"
T_PO_ADD = "  is made: {link}"
T_PO_DROP = "  is removed: {link}"
T_PO_REVERT = ("This change is not stored: the next power-on undoes it. Store it as the "
               "prosthesis's configuration to keep it.")
T_PO_REVERT_AUTO = ("Even stored, start-up's automatic set-up makes this again (autoconfigure "
                    "is on): turn automatic set-up off to keep the change.")
T_PO_PARTLY = "Start-up undoes part of this change."
T_STORED_FIRST = "Stored configuration: stored for the first time, {links}."
T_PO_RETRIEVED = ("No configuration is stored: start-up rebuilds the links from what the "
                  "parts themselves remember.")
T_PO_AUTO = "Automatic set-up is on: start-up links unconnected terminal channels."

#: Every template, for the app's translation table (a test keeps the two in step).
TEMPLATES: tuple[str, ...] = tuple(
    value for name, value in sorted(globals().items())
    if name.startswith("T_") and isinstance(value, str))

#: The words of each named parameter (``param_names``).
_WHAT = {"type": "", "profile": T_PROFILE, "descriptor": T_NAME,
         "data-transfer": T_DATA_TRANSFER, "beacon-interval": T_BEACON,
         "ack-timeout": T_ACK, "bind-timeout": T_BIND, "required-inputs": T_REQUIRED,
         "desired-inputs": T_DESIRED, "terminal-profile": T_TERMINAL_PROFILE}


@dataclass(frozen=True)
class ParameterChange:
    """One named value of a part or channel, old → new (contract texts: ``0x9300``, ``on``)."""

    part: DeviceKey
    channel: int | None
    name: str
    before: str
    after: str
    param: int = 0
    raw_before: str = ""
    raw_after: str = ""

    @property
    def where(self) -> DeviceKey | ChannelRef:
        return self.part if self.channel is None else ChannelRef(*self.part, self.channel)

    def to_json(self, text: str = "") -> dict[str, Any]:
        return {"part": _key_json(self.part), "channel": self.channel, "name": self.name,
                "before": self.before, "after": self.after, "text": text,
                "param": f"0x{self.param:02X}", "raw_before": self.raw_before,
                "raw_after": self.raw_after}

    @classmethod
    def from_json(cls, doc: dict[str, Any]) -> ParameterChange:
        return cls(_key(doc["part"]), doc.get("channel"), str(doc["name"]),
                   str(doc["before"]), str(doc["after"]), int(str(doc.get("param", "0")), 0),
                   str(doc.get("raw_before", "")), str(doc.get("raw_after", "")))


@dataclass
class PowerOn:
    """What start-up would do if the prosthesis powered on right after the change."""

    links_added: list[Link] = field(default_factory=list)
    links_removed: list[Link] = field(default_factory=list)
    #: "stored" (start-up implements the stored configuration) or "retrieved" (none stored).
    configuration: str = "stored"
    autoconfigure: bool = True
    #: The change's own link edits that start-up undoes (they are not stored).
    reverts: bool = False

    @property
    def changes(self) -> bool:
        return bool(self.links_added or self.links_removed)


@dataclass
class Effect:
    """What one change does (see the module's docstring)."""

    links_before: list[Link]
    links_added: list[Link]
    links_removed: list[Link]
    parameters: list[ParameterChange]
    stored_before: list[Link] | None  # None: nothing stored
    stored_after: list[Link] | None
    stored_changed: bool
    policy_before: bool
    policy_after: bool
    held: list[DeviceKey]
    next_power_on: PowerOn
    names: dict[str, str] = field(default_factory=dict)
    crc_before: str | None = None
    crc_after: str | None = None

    @property
    def empty(self) -> bool:
        """True when the prosthesis would not change at all."""
        return not (self.links_added or self.links_removed or self.parameters
                    or self.stored_changed or self.policy_before != self.policy_after)

    @property
    def links_after(self) -> list[Link]:
        return sorted((set(self.links_before) - set(self.links_removed))
                      | set(self.links_added))

    # -- words ---------------------------------------------------------------------------
    def name(self, what: DeviceKey | ChannelRef | Link, tr: Translate = _same) -> str:
        """A part, channel or link by the names the effect was computed with."""
        if isinstance(what, Link):
            return f"{self.name(what.output, tr)} → {self.name(what.input, tr)}"
        known = self.names.get(str(what))
        if known:
            return known
        if isinstance(what, ChannelRef):
            return f"{self.name(what.device, tr)}, channel {what.index}"
        return str(what)

    def parameter_text(self, change: ParameterChange, tr: Translate = _same) -> str:
        return tr(T_PARAM).format(where=self.name(change.where, tr),
                                  what=_parameter_words(change, self.names, tr))

    def lines(self, tr: Translate = _same, reasons: Mapping[Link, str] | None = None
              ) -> list[str]:
        """The effect in plain words, one line each (no codes); ``reasons``: why each link
        is made or removed (a plan's words), added in brackets."""
        reasons = reasons or {}

        def why(link: Link) -> str:
            reason = reasons.get(link, "")
            return f"  ({reason})" if reason else ""

        out: list[str] = []
        if self.empty:
            out.append(tr(T_NOTHING))
        out += [tr(T_LINK_ADDED).format(link=self.name(lk, tr)) + why(lk)
                for lk in self.links_added]
        out += [tr(T_LINK_REMOVED).format(link=self.name(lk, tr)) + why(lk)
                for lk in self.links_removed]
        out += [self.parameter_text(p, tr) for p in self.parameters]
        out += self.muted_lines(tr)
        out += self.stored_lines(tr)
        out += self.policy_lines(tr)
        if not self.empty and (self.links_added or self.links_removed or self.parameters):
            out.append(tr(T_HELD).format(parts=", ".join(self.name(k, tr) for k in self.held))
                       if self.held else tr(T_HELD_NONE))
        return out

    def muted_lines(self, tr: Translate = _same) -> list[str]:
        """Links the change leaves listed but silent (data transfer turned off at an end)."""
        off = {p.where for p in self.parameters
               if p.name == "data-transfer" and p.after == "off" and p.channel is not None}
        return [tr(T_MUTED).format(link=self.name(lk, tr)) for lk in self.links_after
                if lk.output in off or lk.input in off]

    def stored_lines(self, tr: Translate = _same) -> list[str]:
        if not self.stored_changed:
            return [tr(T_STORED_SAME)] if not self.empty else []
        if self.stored_after is None:
            return [tr(T_STORED_CLEARED)]
        before = set(self.stored_before or [])
        after = set(self.stored_after)
        if self.stored_before is None:
            return [tr(T_STORED_FIRST).format(links=_links_count(len(after), tr))] + [
                tr(T_STORED_ADD).format(link=self.name(lk, tr)) for lk in sorted(after)]
        out = [tr(T_STORED_NEW).format(links=_links_count(len(after), tr),
                                       added=len(after - before),
                                       removed=len(before - after))]
        out += [tr(T_STORED_ADD).format(link=self.name(lk, tr)) for lk in sorted(after - before)]
        out += [tr(T_STORED_DROP).format(link=self.name(lk, tr))
                for lk in sorted(before - after)]
        return out

    def policy_lines(self, tr: Translate = _same) -> list[str]:
        if self.policy_before == self.policy_after:
            return []
        out = [tr(T_POLICY).format(old=tr(T_ON if self.policy_before else T_OFF),
                                   new=tr(T_ON if self.policy_after else T_OFF))]
        if not self.policy_after:
            out.append(tr(T_POLICY_OFF_STAY).format(
                links=_links_count(len(self.links_after), tr)))
            out += [tr(T_POLICY_STAYS).format(link=self.name(lk, tr))
                    for lk in self.links_after]
        return out

    def power_on_lines(self, tr: Translate = _same) -> list[str]:
        """What the next power-on will do, in words."""
        po = self.next_power_on
        out: list[str] = []
        if po.configuration == "retrieved":
            out.append(tr(T_PO_RETRIEVED))
        if not po.changes:
            out.append(tr(T_PO_SAME))
        else:
            out.append(tr(T_PO_HEAD))
            removed_now = set(self.links_removed)
            out += [tr(T_PO_BACK if lk in removed_now else T_PO_ADD).format(
                link=self.name(lk, tr)) for lk in po.links_added]
            out += [tr(T_PO_DROP).format(link=self.name(lk, tr)) for lk in po.links_removed]
        if po.reverts and not self.stored_changed:
            out.append(tr(T_PO_REVERT))
        elif po.reverts and po.autoconfigure and po.links_added:
            out.append(tr(T_PO_REVERT_AUTO))
        elif po.reverts:
            out.append(tr(T_PO_PARTLY))
        elif po.autoconfigure and po.links_added:
            out.append(tr(T_PO_AUTO))
        return out

    def technical(self) -> list[str]:
        """The codes behind the words: link references, parameter numbers and bytes, CRCs."""
        out = [f"+ link {lk}" for lk in self.links_added]
        out += [f"- link {lk}" for lk in self.links_removed]
        for p in self.parameters:
            where = f"{p.part}" + (f" channel {p.channel}" if p.channel is not None else "")
            out.append(f"parameter 0x{p.param:02X} ({p.name}) of {where}: "
                       f"{p.before} → {p.after}"
                       + (f" [{p.raw_before or '-'} → {p.raw_after or '-'}]"
                          if p.raw_before or p.raw_after else ""))
        if self.stored_changed or self.crc_before != self.crc_after:
            out.append(f"stored configuration CRC {self.crc_before or 'none'} → "
                       f"{self.crc_after or 'none'}")
        if self.policy_before != self.policy_after:
            out.append(f"policy autoconfigure {str(self.policy_before).lower()} → "
                       f"{str(self.policy_after).lower()}")
        out += [f"held {k}" for k in self.held]
        po = self.next_power_on
        out += [f"power-on + link {lk}" for lk in po.links_added]
        out += [f"power-on - link {lk}" for lk in po.links_removed]
        return out

    # -- JSON (contracts §2 "effect" and "next_power_on") ----------------------------------
    def to_json(self) -> dict[str, Any]:
        return {
            "links_added": [lk.as_json() for lk in self.links_added],
            "links_removed": [lk.as_json() for lk in self.links_removed],
            "parameters": [p.to_json(self.parameter_text(p)) for p in self.parameters],
            "policy": {"before": {"autoconfigure": self.policy_before},
                       "after": {"autoconfigure": self.policy_after}},
            "held": [_key_json(k) for k in self.held],
            "stored_configuration": {
                "changed": self.stored_changed,
                "links_before": _links_json(self.stored_before),
                "links_after": _links_json(self.stored_after),
                "crc_before": self.crc_before, "crc_after": self.crc_after},
            "links_before": [lk.as_json() for lk in self.links_before],
            "text": self.lines(), "technical": self.technical(),
            "names": dict(self.names),
        }

    def power_on_json(self) -> dict[str, Any]:
        po = self.next_power_on
        return {"links_added": [lk.as_json() for lk in po.links_added],
                "links_removed": [lk.as_json() for lk in po.links_removed],
                "configuration": po.configuration, "autoconfigure": po.autoconfigure,
                "reverts": po.reverts, "text": self.power_on_lines()}

    @classmethod
    def from_json(cls, doc: dict[str, Any], power_on: dict[str, Any] | None = None
                  ) -> Effect:
        """An effect read back (the fitting history keeps ``to_json`` and ``power_on_json``)."""
        pol = doc.get("policy") or {}
        before = bool((pol.get("before") or {}).get("autoconfigure", True))
        stored = doc.get("stored_configuration") or {}
        po = power_on or {}
        return cls(
            _links(doc.get("links_before")) or [],
            _links(doc.get("links_added")) or [], _links(doc.get("links_removed")) or [],
            [ParameterChange.from_json(p) for p in doc.get("parameters", [])],
            _links(stored.get("links_before")), _links(stored.get("links_after")),
            bool(stored.get("changed")), before,
            bool((pol.get("after") or {}).get("autoconfigure", before)),
            [_key(k) for k in doc.get("held", [])],
            PowerOn(_links(po.get("links_added")) or [], _links(po.get("links_removed")) or [],
                    str(po.get("configuration", "stored")), bool(po.get("autoconfigure", True)),
                    bool(po.get("reverts"))),
            {str(k): str(v) for k, v in (doc.get("names") or {}).items()},
            stored.get("crc_before"), stored.get("crc_after"))


# -- computing it ------------------------------------------------------------------------
def effect_of(system: System, *, links_after: Iterable[Link],
              parameters: Sequence[ParameterWriteLike] = (),
              config_before: ConfigCollection | None = None,
              config_after: ConfigCollection | None = None,
              policy_before: bool = True, policy_after: bool | None = None,
              held: Sequence[DeviceKey] = (), names: Names | None = None,
              crc: Callable[[ConfigCollection | None], str | None] | None = None) -> Effect:
    """The effect of a change on ``system`` (the prosthesis as read, links included).

    ``config_after`` None leaves the stored configuration as it is (``config_before``);
    ``policy_after`` None leaves the policy. ``names`` names parts and channels (a plain
    :class:`Names` of ``system`` when None); ``crc`` gives a stored configuration's CRC for
    the technical detail.
    """
    names = names or Names(system)
    before = sorted(system.links)
    after = sorted(set(links_after))
    written = system_after(system, after, parameters)
    pchanges = _parameter_changes(system, parameters)
    stored_now = config_before if config_before is not None else ConfigCollection([])
    stored_next = config_after if config_after is not None else stored_now
    policy = policy_before if policy_after is None else policy_after
    po = predict_power_on(written, stored_next, autoconfigure=policy)
    own_edits = (set(after) - set(before)) | (set(before) - set(after))
    po.reverts = bool(own_edits & (set(po.links_added) | set(po.links_removed)))
    stored_before = _stored_links(system, stored_now)
    stored_after = _stored_links(written, stored_next)
    changed = config_after is not None and (
        crc(config_before) != crc(config_after) if crc is not None
        else stored_before != stored_after)
    effect = Effect(before, sorted(set(after) - set(before)), sorted(set(before) - set(after)),
                    pchanges, stored_before, stored_after, changed, policy_before, policy,
                    sorted(held), po,
                    crc_before=_crc(crc, stored_now), crc_after=_crc(crc, stored_next))
    effect.names = _names_for(effect, names, written)
    return effect


def _crc(crc: Callable[[ConfigCollection | None], str | None] | None,
         collection: ConfigCollection) -> str | None:
    """A stored configuration's CRC; None when nothing is stored (as the arbitrator says)."""
    return crc(collection) if crc is not None and collection.configurations else None


def predict_power_on(system: System, stored: ConfigCollection, *, autoconfigure: bool
                     ) -> PowerOn:
    """The engine's start-up on ``system`` and ``stored`` (reference §2): the links it would
    make and remove, relative to ``system``'s links.

    Start-up runs on the parts as they power on: unlinked (enabled flags and source node IDs
    are bus-session values every part clears), each input keeping its stored source fields.
    So the plan starts from no links, as the arbitrator's does: a link kept on the live bus
    that start-up would not make again from nothing (a second sole-access input on one
    output, say) is predicted to go."""
    powered = system.copy()
    powered.clear_links()  # the inputs' source fields stay: "retrieved" reads them
    plan = plan_on_bus("startup", powered, stored, autoconfigure=autoconfigure)
    now = set(system.links)
    final = set(plan.final_links)
    source = "stored" if stored.configurations and plan.configuration_source == "stored" \
        else "retrieved"
    return PowerOn(sorted(final - now), sorted(now - final), source, autoconfigure)


def system_after(system: System, links: list[Link],
                  parameters: Sequence[ParameterWriteLike]) -> System:
    """``system`` as the change leaves it: its links, the input's source fields and flags
    kept in step as the arbitrator keeps them, and the parameter values written."""
    written = system.copy()
    try:
        set_links(written, links)
    except ModelError:  # a link the model refuses is the preview's to report; keep the rest
        for link in set(written.links) - set(links):
            written.remove_link(link)
    for w in parameters:
        device = written.device(w.device)
        if device is not None:
            F.learn_value(device, w.param, w.channel, w.value)
    return written


def _parameter_changes(system: System, parameters: Sequence[ParameterWriteLike]
                       ) -> list[ParameterChange]:
    out: list[ParameterChange] = []
    for w in parameters:
        device = system.device(w.device)
        obj: Device | Channel | None = device
        if device is not None and w.channel:
            obj = device.channels.get(w.channel)
        channel = w.channel or None
        try:
            before = N.current_bytes(obj, w.param) if obj is not None else b""
        except (ParameterError, AssertionError):
            before = b""
        named = N.changes_of(obj, w.param, before, w.value) if obj is not None and before \
            else []
        if named:
            out += [ParameterChange(w.device, channel, n.name, old, new, w.param,
                                    before.hex(), w.value.hex()) for n, old, new in named]
            continue
        if before == w.value:
            continue
        direction = obj.direction if isinstance(obj, Channel) else None
        spec = P.find_parameter(w.param, w.channel, direction)
        label = spec.name.lower().replace(" ", "-") if spec else f"parameter-0x{w.param:02X}"
        out.append(ParameterChange(w.device, channel, label,
                                   P.render_value(spec, before) if before else "unknown",
                                   P.render_value(spec, w.value), w.param, before.hex(),
                                   w.value.hex()))
    return out


def _parameter_words(p: ParameterChange, names: dict[str, str], tr: Translate) -> str:
    """A parameter change in words: a type by its fields, a profile by its name …"""
    def change(what: str, old: str, new: str) -> str:
        return tr(T_CHANGE).format(what=tr(what), old=old, new=new)

    if p.name == "type":
        return "; ".join(_type_words(int(p.before, 0), int(p.after, 0), tr)) or \
            change(T_DATA_TYPE, p.before, p.after)
    if p.name in ("profile", "terminal-profile"):
        return change(_WHAT[p.name], names.get(f"profile:{p.before}", p.before),
                      names.get(f"profile:{p.after}", p.after))
    if p.name == "descriptor":
        return change(T_NAME, f"“{p.before}”", f"“{p.after}”")
    if p.name == "data-transfer":
        return change(T_DATA_TRANSFER, tr(T_ON if p.before == "on" else T_OFF),
                      tr(T_ON if p.after == "on" else T_OFF))
    if p.name in ("beacon-interval", "ack-timeout", "bind-timeout"):
        return change(_WHAT[p.name], tr(T_MS).format(n=p.before), tr(T_MS).format(n=p.after))
    if p.name in ("required-inputs", "desired-inputs"):
        return change(_WHAT[p.name], p.before.replace(",", ", ") or tr(T_NONE),
                      p.after.replace(",", ", ") or tr(T_NONE))
    return change(p.name.replace("-", " "), p.before, p.after)


def _type_words(old: int, new: int, tr: Translate) -> list[str]:
    a, b = ChannelType(old), ChannelType(new)

    def change(what: str, x: str, y: str) -> str:
        return tr(T_CHANGE).format(what=tr(what), old=x, new=y)

    def yes(flag: bool) -> str:
        return tr(T_YES if flag else T_NO)

    out: list[str] = []
    if a.control_mode != b.control_mode:
        out.append(change(T_CONTROL_MODE, tr(a.control_mode.label), tr(b.control_mode.label)))
    if (a.bits, a.data_type) != (b.bits, b.data_type):
        out.append(change(T_DATA_TYPE,
                          tr(T_BITS).format(bits=a.bits, kind=tr(a.data_type.label)),
                          tr(T_BITS).format(bits=b.bits, kind=tr(b.data_type.label))))
    if a.terminal != b.terminal:
        out.append(change(T_TERMINAL, yes(a.terminal), yes(b.terminal)))
    if a.sole_access != b.sole_access:
        out.append(change(T_SOLE, yes(a.sole_access), yes(b.sole_access)))
    if a.prescaler != b.prescaler:
        out.append(change(T_PRESCALER, f"≈{a.prescaler_hint}", f"≈{b.prescaler_hint}"))
    return out


#: The words of a channel type's fields, for the translation table.
TYPE_WORDS = ("position", "velocity", "acceleration", "other", "signed int", "unsigned int",
              "float", "boolean")


def _stored_links(system: System, collection: ConfigCollection) -> list[Link] | None:
    """The links of the configuration start-up would pick from ``collection`` (None: none)."""
    if not collection.configurations:
        return None
    cfg, _why = resolve_configuration(system, collection)
    if cfg is None:
        cfg = collection.configurations[0]
    return sorted({Link(sl.output.ref, sl.input.ref) for sl in cfg.links})


def _names_for(effect: Effect, names: Names, written: System) -> dict[str, str]:
    """The names the effect's words use: every part, channel and profile it mentions."""
    links: set[Link] = set(effect.links_added) | set(effect.links_removed)
    links |= set(effect.next_power_on.links_added) | set(effect.next_power_on.links_removed)
    links |= set(effect.stored_before or []) | set(effect.stored_after or [])
    links |= set(effect.links_before)
    out: dict[str, str] = {}
    for link in links:
        for ref in (link.output, link.input):
            out.setdefault(str(ref), names.channel(ref))
    for p in effect.parameters:
        out.setdefault(str(p.where), names.channel(p.where) if isinstance(p.where, ChannelRef)
                       else names.part(p.where))
        if p.name in ("profile", "terminal-profile"):
            for code in (p.before, p.after):
                try:
                    out[f"profile:{code}"] = names.profile(int(code, 0))
                except ValueError:
                    continue
    for key in effect.held:
        out.setdefault(str(key), names.part(key))
    return out


def _links_count(n: int, tr: Translate) -> str:
    """``1 link`` / ``3 links`` (each form translated on its own, so German reads
    "1 Verbindung" / "3 Verbindungen")."""
    return tr(T_ONE_LINK if n == 1 else T_LINKS).format(n=n)


def _key_json(key: DeviceKey) -> dict[str, int]:
    return {"vid": key.vid, "pid": key.pid, "serial": key.serial}


def _key(doc: dict[str, Any]) -> DeviceKey:
    return DeviceKey(int(doc["vid"]), int(doc["pid"]), int(doc["serial"]))


def _ref(doc: dict[str, Any]) -> ChannelRef:
    return ChannelRef(int(doc["vid"]), int(doc["pid"]), int(doc["serial"]), int(doc["index"]))


def _links_json(links: list[Link] | None) -> list[dict[str, Any]] | None:
    return None if links is None else [lk.as_json() for lk in links]


def _links(docs: list[dict[str, Any]] | None) -> list[Link] | None:
    if docs is None:
        return None
    return [Link(_ref(d["output"]), _ref(d["input"])) for d in docs]


def parameter_words(system: System, writes: Sequence[ParameterWriteLike],
                    names: Names | None = None, tr: Translate = _same, *,
                    only: str | None = None) -> list[str]:
    """Parameter writes on ``system`` (as it is before them) in the effect's own words, one
    line per named value that changes ("Hand, Power grip: control mode position →
    velocity"): for texts about a change that is not previewed whole — a staged edit in
    the pending changes, an undo step. ``only``: just this named value (``type``,
    ``profile``, ``descriptor``…)."""
    changes = [p for p in _parameter_changes(system, writes) if only is None or p.name == only]
    effect = Effect([], [], [], changes, None, None, False, True, True, [], PowerOn())
    effect.names = _names_for(effect, names or Names(system), system)
    return [effect.parameter_text(p, tr) for p in changes]
