"""The one difference between two stored configurations (contracts §2, ``config diff``).

Two ``ConfigCollection``\\ s are compared configuration by configuration (matched by their
``index``). Within a configuration a link is named by its ends (output and input channel
references): a link only in A, only in B, or in both with different channel records (type,
profile, owner type/profile) — ``changed``. The link's own index inside its configuration is
not compared: it only orders the records. Records of codes PDCP Studio does not know
(reference §3, "unknown codes are kept") are compared too, on the declaration they belong
to: a link whose channels or link record carry different unknown records is ``changed``;
a configuration or collection whose own unknown records differ says so in
``unknown_records`` (``{"a": […], "b": […]}``, present only then).

Every place that must say how two stored configurations differ (a write's read-back, the CLI's
``config diff`` and ``config write``, the app's compare and write dialogs, the fitting history)
uses this one function, so they always agree.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredLink,
    Unknown,
)
from pdcp_studio.model.refs import ChannelRef

LinkEnds = tuple[ChannelRef, ChannelRef]  # (output, input)


def channel_json(ch: StoredChannel) -> dict[str, Any]:
    """A channel record as ``config decode --json`` writes it."""
    doc: dict[str, Any] = {
        "type": f"0x{ch.type:04X}", "profile": f"0x{ch.profile:04X}", "index": ch.index,
        "vid": ch.vid, "pid": ch.pid, "serial": ch.serial}
    if ch.owner_type is not None:
        doc["owner_type"] = ch.owner_type
    if ch.owner_profile is not None:
        doc["owner_profile"] = ch.owner_profile
    return with_unknown(doc, ch.unknown)


def unknown_json(records: Unknown) -> list[dict[str, int]]:
    """Unknown records as ``config decode --json`` writes them."""
    return [{"code": rec.code, "value": rec.value} for rec in records]


def with_unknown(doc: dict[str, Any], records: Unknown) -> dict[str, Any]:
    """``doc`` with its ``unknown_records`` when it has some (contracts §2)."""
    if records:
        doc["unknown_records"] = unknown_json(records)
    return doc


def link_json(link: StoredLink) -> dict[str, Any]:
    """A stored link as ``config decode --json`` writes it."""
    return with_unknown({"index": link.index, "input": channel_json(link.input),
                          "output": channel_json(link.output)}, link.unknown)


def _records_json(link: StoredLink) -> dict[str, Any]:
    return with_unknown({"input": channel_json(link.input),
                          "output": channel_json(link.output)}, link.unknown)


def _unknown_pair_json(pair: tuple[Unknown, Unknown] | None) -> dict[str, Any]:
    if pair is None:
        return {}
    return {"unknown_records": {"a": unknown_json(pair[0]), "b": unknown_json(pair[1])}}


def _ends(link: StoredLink) -> LinkEnds:
    return (link.output.ref, link.input.ref)


@dataclass(frozen=True)
class ChangedLink:
    """The same link (same ends) stored with different channel records in A and B."""

    a: StoredLink
    b: StoredLink

    @property
    def ends(self) -> LinkEnds:
        return _ends(self.a)


@dataclass
class ConfigurationDiff:
    """How configuration ``index`` differs (``index`` missing on one side: all its links
    are only on the other)."""

    index: int
    only_in_a: list[StoredLink] = field(default_factory=list)
    only_in_b: list[StoredLink] = field(default_factory=list)
    changed: list[ChangedLink] = field(default_factory=list)
    in_a: bool = True
    in_b: bool = True
    #: The configuration's own unknown records (A, B) when they differ, else None.
    unknown: tuple[Unknown, Unknown] | None = None

    @property
    def equal(self) -> bool:
        return (not self.only_in_a and not self.only_in_b and not self.changed
                and self.in_a == self.in_b and self.unknown is None)

    def to_json(self) -> dict[str, Any]:
        return {
            "index": self.index,
            "only_in_a": [link_json(sl) for sl in self.only_in_a],
            "only_in_b": [link_json(sl) for sl in self.only_in_b],
            "changed": [{"link": {"output": c.ends[0].as_json(), "input": c.ends[1].as_json()},
                         "a": _records_json(c.a), "b": _records_json(c.b)}
                        for c in self.changed],
            **_unknown_pair_json(self.unknown),
        }


@dataclass
class ConfigDiff:
    """The difference between collection A and collection B."""

    configurations: list[ConfigurationDiff] = field(default_factory=list)
    #: The collection's own unknown records (A, B) when they differ, else None.
    unknown: tuple[Unknown, Unknown] | None = None

    @property
    def equal(self) -> bool:
        return self.unknown is None and all(c.equal for c in self.configurations)

    def to_json(self) -> dict[str, Any]:
        """``config diff --json`` (contracts §2): every configuration of either side."""
        return {"configurations": [c.to_json() for c in self.configurations],
                **_unknown_pair_json(self.unknown)}

    def lines(self, a_name: str = "A", b_name: str = "B") -> list[str]:
        """Plain words, one line per difference (empty when equal)."""
        out: list[str] = []
        if self.unknown is not None:
            out.append(f"the collection's unknown records differ ({_unknown_change(self.unknown)})")
        for c in self.configurations:
            if c.unknown is not None:
                out.append(f"configuration {c.index}: its unknown records differ "
                           f"({_unknown_change(c.unknown)})")
            if not c.in_a:
                out.append(f"configuration {c.index} is only in {b_name}")
            elif not c.in_b:
                out.append(f"configuration {c.index} is only in {a_name}")
            for sl in c.only_in_a:
                out.append(f"configuration {c.index}: link {sl.output.ref} → {sl.input.ref} "
                           f"is only in {a_name}")
            for sl in c.only_in_b:
                out.append(f"configuration {c.index}: link {sl.output.ref} → {sl.input.ref} "
                           f"is only in {b_name}")
            for ch in c.changed:
                out.append(f"configuration {c.index}: link {ch.ends[0]} → {ch.ends[1]} has "
                           f"different channel records ({_record_change(ch)})")
        return out

    def describe(self, a_name: str = "A", b_name: str = "B") -> str:
        """One sentence for messages: the differences joined, or ``no difference``."""
        return "; ".join(self.lines(a_name, b_name)) or "no difference"


def _record_change(ch: ChangedLink) -> str:
    parts = []
    for end in ("output", "input"):
        a, b = getattr(ch.a, end), getattr(ch.b, end)
        for name in ("type", "profile", "owner_type", "owner_profile"):
            va, vb = getattr(a, name), getattr(b, name)
            if va != vb:
                parts.append(f"{end} {name.replace('_', ' ')} {_fmt(va)} → {_fmt(vb)}")
        if a.unknown != b.unknown:
            parts.append(f"{end} unknown records {_unknown_change((a.unknown, b.unknown))}")
    if ch.a.unknown != ch.b.unknown:
        parts.append(f"link unknown records {_unknown_change((ch.a.unknown, ch.b.unknown))}")
    return ", ".join(parts) or "record order"


def _unknown_change(pair: tuple[Unknown, Unknown]) -> str:
    def text(records: Unknown) -> str:
        return "[" + ", ".join(f"{r.code}={r.value:#06x}" for r in records) + "]"

    return f"{text(pair[0])} → {text(pair[1])}"


def _fmt(value: int | None) -> str:
    return "none" if value is None else f"0x{value:04X}"


def diff_configurations(a: ConfigCollection, b: ConfigCollection) -> ConfigDiff:
    """Compare ``a`` and ``b`` configuration by configuration (sorted by index)."""
    by_a = {c.index: c for c in a.configurations}
    by_b = {c.index: c for c in b.configurations}
    result = ConfigDiff(unknown=_unknown_pair(a.unknown, b.unknown))
    for index in sorted(set(by_a) | set(by_b)):
        ca, cb = by_a.get(index), by_b.get(index)
        links_a = {_ends(sl): sl for sl in (ca.links if ca else [])}
        links_b = {_ends(sl): sl for sl in (cb.links if cb else [])}
        diff = ConfigurationDiff(index, in_a=ca is not None, in_b=cb is not None)
        if ca is not None and cb is not None:
            diff.unknown = _unknown_pair(ca.unknown, cb.unknown)
        diff.only_in_a = [links_a[k] for k in sorted(set(links_a) - set(links_b))]
        diff.only_in_b = [links_b[k] for k in sorted(set(links_b) - set(links_a))]
        for k in sorted(set(links_a) & set(links_b)):
            sa, sb = links_a[k], links_b[k]
            if (sa.input, sa.output, sa.unknown) != (sb.input, sb.output, sb.unknown):
                diff.changed.append(ChangedLink(sa, sb))
        result.configurations.append(diff)
    return result


def link_ends(collection: ConfigCollection) -> set[LinkEnds]:
    """Every (output, input) pair stored in any configuration of ``collection``."""
    return {_ends(sl) for c in collection.configurations for sl in c.links}


def _unknown_pair(a: Unknown, b: Unknown) -> tuple[Unknown, Unknown] | None:
    """Unknown records compared by code and value in order (where exactly they sat among
    the known records does not change what they say)."""
    def key(records: Unknown) -> list[tuple[int, int]]:
        return [(r.code, r.value) for r in records]

    return None if key(a) == key(b) else (a, b)
