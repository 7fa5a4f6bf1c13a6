"""Plans: what the profile layer would do, step by step, and why — before it does it.

The engine never changes a bus or a system directly. It returns a ``Plan``: the ordered
add/remove actions, each with the rule that made it and the similarity behind it, plus
what was tried and refused (sole access, a required input that could not be met and the
rollback it caused). A prosthetist reads it, the app previews it, and only ``apply``
changes a ``System``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum
from typing import TYPE_CHECKING, Any, NamedTuple

from pdcp_studio.engine.similarity import Similarity
from pdcp_studio.errors import EngineError, ModelError
from pdcp_studio.model.configuration import StoredConfiguration
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import NO_SOURCE, Link, SourceInfo, System

if TYPE_CHECKING:
    from pdcp_studio.model.names import Names
    from pdcp_studio.model.profile_tree import ProfileTree


class Op(StrEnum):
    ADD = "add"
    REMOVE = "remove"


class Rule(StrEnum):
    """Why an action was taken. Values are stable identifiers for JSON; ``label`` is prose."""

    STORED = "stored"
    RETRIEVED = "retrieved"
    REPLACEMENT = "replacement"
    TERMINAL = "terminal"
    REQUIRED = "required"
    DESIRED = "desired"
    SOLE_ACCESS = "sole_access"
    CLEAR = "clear"
    NOT_STORED = "not_stored"
    REPLACED = "replaced"
    SUPERSEDED = "superseded"

    @property
    def label(self) -> str:
        return _RULE_LABELS[self]


_RULE_LABELS = {
    Rule.STORED: "stored configuration",
    Rule.RETRIEVED: "retrieved from devices",
    Rule.REPLACEMENT: "replacement for a missing channel",
    Rule.TERMINAL: "terminal channel",
    Rule.REQUIRED: "required by",
    Rule.DESIRED: "desired by",
    Rule.SOLE_ACCESS: "sole-access enforcement",
    Rule.CLEAR: "clear",
    Rule.NOT_STORED: "not in stored configuration",
    Rule.REPLACED: "replaced (an end is missing)",
    Rule.SUPERSEDED: "superseded (its output is missing)",
}


class Refusal(StrEnum):
    """Kinds of rejection."""

    SOLE_ACCESS = "sole_access"  # the output already feeds a sole-access input
    INPUT_TAKEN = "input_taken"  # the input already has another source
    NO_CANDIDATE = "no_candidate"  # nothing similar and free
    ROLLED_BACK = "rolled_back"  # a required input failed: this call's links were removed
    ALREADY_TRIED = "already_tried"  # tried (and failed) earlier in the same call
    MISSING = "missing"  # a stored link whose ends are both missing, or a wrong channel
    NOT_INPUT = "not_input"  # a required/desired index that is not an input channel


def _ref_json(ref: ChannelRef | None) -> dict[str, Any] | None:
    return ref.as_json() if ref is not None else None


def _cause_json(cause: Link | ChannelRef | None) -> dict[str, Any] | None:
    if cause is None:
        return None
    if isinstance(cause, Link):
        return {"link": cause.as_json()}
    return {"channel": cause.as_json()}


@dataclass(frozen=True)
class Action:
    """One step of a plan: add or remove one link, and why."""

    op: Op
    link: Link
    rule: Rule
    reason: str
    similarity: Similarity | None = None
    cause: Link | ChannelRef | None = None
    depth: int = 0  # recursion depth inside intelligently_connect (0 = top level)

    def to_json(self) -> dict[str, Any]:
        return {
            "op": self.op.value,
            "output": self.link.output.as_json(),
            "input": self.link.input.as_json(),
            "similarity": self.similarity.total if self.similarity else None,
            "reason": self.reason,
            "rule": self.rule.value,
            "breakdown": self.similarity.as_json() if self.similarity else None,
            "cause": _cause_json(self.cause),
            "depth": self.depth,
        }


@dataclass(frozen=True)
class Attempt:
    """Something the engine tried: a link, or (with no link yet) a channel to feed."""

    rule: Rule
    link: Link | None = None
    channel: ChannelRef | None = None
    cause: Link | ChannelRef | None = None
    depth: int = 0


@dataclass(frozen=True)
class Rejection:
    """An attempt that was refused, and what it undid (``rolled_back``)."""

    kind: Refusal
    attempt: Attempt
    reason: str
    rolled_back: tuple[Link, ...] = ()

    def to_json(self) -> dict[str, Any]:
        a = self.attempt
        return {
            "kind": self.kind.value,
            "rule": a.rule.value,
            "output": _ref_json(a.link.output) if a.link else None,
            "input": _ref_json(a.link.input) if a.link else None,
            "channel": _ref_json(a.channel),
            "cause": _cause_json(a.cause),
            "depth": a.depth,
            "reason": self.reason,
            "rolled_back": [lk.as_json() for lk in self.rolled_back],
        }


class ChannelFacts(NamedTuple):
    """What a plan remembers of a channel so that it can be rendered without the system."""

    type: int
    profile: int
    terminal_profile: int = 0
    descriptor: str = ""
    present: bool = True


@dataclass
class Plan:
    """The outcome of one profile-layer operation, as data."""

    mode: str
    actions: list[Action] = field(default_factory=list)
    rejections: list[Rejection] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    links_before: list[Link] = field(default_factory=list)
    configuration: StoredConfiguration | None = None
    configuration_source: str = ""  # "stored", "retrieved", "given", "system" or ""
    configuration_reason: str = ""
    channels: dict[ChannelRef, ChannelFacts] = field(default_factory=dict)

    # -- results -------------------------------------------------------------------
    @property
    def final_links(self) -> list[Link]:
        """Every link after the plan, sorted by output then input reference."""
        links = set(self.links_before)
        for a in self.actions:
            if a.op is Op.ADD:
                links.add(a.link)
            else:
                links.discard(a.link)
        return sorted(links)

    @property
    def added(self) -> list[Action]:
        return [a for a in self.actions if a.op is Op.ADD]

    @property
    def removed(self) -> list[Action]:
        return [a for a in self.actions if a.op is Op.REMOVE]

    def is_empty(self) -> bool:
        return not self.actions

    def diff(self, system: System) -> tuple[list[Link], list[Link]]:
        """(links to add, links to remove) to bring ``system`` to this plan's result."""
        current = set(system.links)
        final = set(self.final_links)
        return sorted(final - current), sorted(current - final)

    # -- rendering -----------------------------------------------------------------
    def to_json(self) -> dict[str, Any]:
        """The contract's ``plan --json`` document (contracts §2) plus explanations."""
        final = self.final_links
        doc: dict[str, Any] = {
            "mode": self.mode,
            "actions": [a.to_json() for a in self.actions],
            "links": [lk.as_json() for lk in final],
            "rejections": [r.to_json() for r in self.rejections],
            "notes": list(self.notes),
        }
        if self.configuration is not None or self.configuration_reason:
            cfg = self.configuration
            doc["configuration"] = {
                "index": cfg.index if cfg else None,
                "links": len(cfg.links) if cfg else 0,
                "source": self.configuration_source,
                "reason": self.configuration_reason,
            }
        doc["summary"] = {
            "added": len(self.added),
            "removed": len(self.removed),
            "links_before": len(self.links_before),
            "links_after": len(final),
            "rejections": len(self.rejections),
        }
        return doc

    def to_text(self, tree: ProfileTree | None = None, names: Names | None = None) -> str:
        """Readable prose; profile names come from ``tree`` when one is given, part and
        channel names from ``names`` (the one naming, ``model/names.py``)."""
        from pdcp_studio.engine.render import plan_to_text

        return plan_to_text(self, tree, names)

    # -- applying ------------------------------------------------------------------
    def apply(self, system: System) -> None:
        """Carry the actions out on ``system`` in order (all or nothing).

        Also keeps the redundant storage of behaviour 1 (§4.3.2) in step: an input's
        ``source`` names its new source output (VID/PID/SN/index, type, profile), or
        ``NO_SOURCE`` once it has none; and Data Transfer Enabled is set on linked
        channels and cleared on channels left unlinked (setup step 6, appendix D).
        """
        links = set(system.links)
        for n, a in enumerate(self.actions, 1):
            if a.op is Op.ADD and a.link in links:
                raise EngineError(f"action {n}: {a.link} is already in the system")
            if a.op is Op.REMOVE and a.link not in links:
                raise EngineError(f"action {n}: {a.link} is not in the system")
            try:
                system.check_link(a.link)
            except ModelError as err:
                raise EngineError(f"action {n}: {err}") from err
            (links.add if a.op is Op.ADD else links.discard)(a.link)
        for a in self.actions:
            if a.op is Op.ADD:
                system.add_link(a.link, check=False)
            else:
                system.remove_link(a.link)
            _sync_channels(system, a.link)


def set_links(system: System, links: list[Link] | set[Link]) -> tuple[list[Link], list[Link]]:
    """Bring ``system`` to exactly ``links``: the ONE offline apply path (issue 8).

    Removes the links not wanted, adds the new ones, and keeps every touched input's
    redundant source fields and both ends' Data Transfer Enabled in step — exactly what
    ``Plan.apply`` and the arbitrator on a live bus do — so the app (plans, undo, link
    edits) and the CLI produce the same system for the same operation. Returns
    (added, removed). ModelError for a link the model refuses (nothing is changed then).
    """
    wanted = set(links)
    current = set(system.links)
    added, removed = sorted(wanted - current), sorted(current - wanted)
    trial = system.copy()
    for link in removed:
        trial.remove_link(link)
    for link in added:
        trial.add_link(link)  # raises ModelError before the real system is touched
    for link in removed:
        system.remove_link(link)
        _sync_channels(system, link)
    for link in added:
        system.add_link(link, check=False)
        _sync_channels(system, link)
    return added, removed


def _sync_channels(system: System, link: Link) -> None:
    """Mirror the links into the input's source fields and both ends' enabled flags."""
    inp = system.channel(link.input)
    out = system.channel(link.output)
    assert inp is not None and out is not None  # checked before any change
    src = system.source_of(link.input)
    if src is None:
        inp.source = NO_SOURCE
    else:
        sch = system.channel(src)
        inp.source = SourceInfo(
            src.vid, src.pid, src.serial, src.index,
            sch.type if sch else 0, sch.profile if sch else 0,
        )
    inp.data_enabled = src is not None
    out.data_enabled = bool(system.inputs_fed_by(link.output))
