"""The profile layer's working state and its core moves (listings 4.4, 4.5 and 4.8).

``ProfileLayer`` is an overlay on a ``System``: it reads the devices and channels but keeps
its own copy of the links, so planning never changes the system it was given. Every change
is journalled as a plan ``Action``; a rollback pops the journal back to a mark, which
undoes exactly what one ``intelligently_connect`` call and the calls under it made.

Dead links: a link with an end that is not present (missing device or channel) carries no
data. It does not count as an input's source nor towards sole access, and when an input
that has one gets a new source, the dead link is removed first (rule ``superseded``) so an
input never ends with two sources.
"""

from __future__ import annotations

from collections.abc import Iterator
from enum import Enum

from pdcp_studio.engine.candidates import Candidate, CandidateIndex
from pdcp_studio.engine.plan import (
    Action,
    Attempt,
    ChannelFacts,
    Op,
    Plan,
    Refusal,
    Rejection,
    Rule,
)
from pdcp_studio.engine.similarity import Similarity, determine_similarity
from pdcp_studio.model.profile import fmt
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Channel, Link, System

Cause = Link | ChannelRef | None


class Connected(Enum):
    """Outcome of ``connect``."""

    MADE = "made"
    EXISTS = "exists"
    REFUSED = "refused"


class ProfileLayer:
    """One planning session over a system snapshot; ``plan()`` returns what it decided."""

    def __init__(self, system: System, mode: str = "") -> None:
        self.system = system
        self.channels: dict[ChannelRef, Channel] = {}
        self.present: set[ChannelRef] = set()
        outs: list[Candidate] = []
        ins: list[Candidate] = []
        for device in system.devices.values():
            for ch in device.channels.values():
                ref = device.ref(ch.index)
                self.channels[ref] = ch
                if device.present:
                    self.present.add(ref)
                    (outs if ch.is_output else ins).append(Candidate(ref, ch.type, ch.profile))
        self.output_candidates = {c.ref: c for c in outs}
        self.outputs = CandidateIndex(outs)
        self._input_candidates = ins
        self._inputs: CandidateIndex | None = None  # built on first use (replacements only)
        self.links: set[Link] = set()
        self.by_input: dict[ChannelRef, set[Link]] = {}
        self.by_output: dict[ChannelRef, set[Link]] = {}
        self.sole_fed: dict[ChannelRef, int] = {}  # output → live links to sole-access inputs
        for link in system.links:
            self._add(link)
        self._journal: list[tuple[Op, Link, int]] = []  # (op done, link, index in actions)
        self.plan = Plan(mode=mode, links_before=system.links)

    @property
    def inputs(self) -> CandidateIndex:
        """Present input channels as candidates (for replacing a missing input)."""
        if self._inputs is None:
            self._inputs = CandidateIndex(self._input_candidates)
        return self._inputs

    # -- facts -----------------------------------------------------------------------
    def channel(self, ref: ChannelRef) -> Channel | None:
        return self.channels.get(ref)

    def is_present(self, ref: ChannelRef, direction: Direction | None = None) -> bool:
        if ref not in self.present:
            return False
        return direction is None or self.channels[ref].direction is direction

    def live(self, link: Link) -> bool:
        return link.output in self.present and link.input in self.present

    def sources(self, input_ref: ChannelRef) -> list[ChannelRef]:
        """Live sources of an input, sorted."""
        return sorted(lk.output for lk in self.by_input.get(input_ref, ()) if self.live(lk))

    def has_source(self, input_ref: ChannelRef) -> bool:
        return any(self.live(lk) for lk in self.by_input.get(input_ref, ()))

    def sole_inputs_fed_by(self, output_ref: ChannelRef) -> list[ChannelRef]:
        return sorted(
            lk.input for lk in self.by_output.get(output_ref, ())
            if self.live(lk) and self.channels[lk.input].sole_access
        )

    def unconnected_terminals(self) -> list[ChannelRef]:
        """Present terminal inputs without a live source, by terminal profile then reference."""
        refs = [r for r in self.present
                if self.channels[r].terminal and not self.has_source(r)]
        return sorted(refs, key=lambda r: (self.channels[r].terminal_profile, r))

    def similarity(self, link: Link) -> Similarity:
        out, inp = self.channels[link.output], self.channels[link.input]
        return determine_similarity(out.type, out.profile, inp.type, inp.profile)

    def describe(self, ref: ChannelRef) -> str:
        ch = self.channels.get(ref)
        return f"{ref} ({fmt(ch.profile)})" if ch else str(ref)

    # -- link state (no journal) -------------------------------------------------------
    def _add(self, link: Link) -> None:
        self.links.add(link)
        self.by_input.setdefault(link.input, set()).add(link)
        self.by_output.setdefault(link.output, set()).add(link)
        if self.live(link) and self.channels[link.input].sole_access:
            n = self.sole_fed[link.output] = self.sole_fed.get(link.output, 0) + 1
            if n == 1:
                self.outputs.take(self.output_candidates[link.output])

    def _discard(self, link: Link) -> None:
        self.links.discard(link)
        self.by_input[link.input].discard(link)
        self.by_output[link.output].discard(link)
        if self.live(link) and self.channels[link.input].sole_access:
            self.sole_fed[link.output] -= 1
            if not self.sole_fed[link.output]:
                self.outputs.release(self.output_candidates[link.output])

    # -- journalled changes -------------------------------------------------------------
    def add(self, link: Link, rule: Rule, reason: str, *, similarity: Similarity | None = None,
            cause: Cause = None, depth: int = 0) -> None:
        self._add(link)
        self._record(Action(Op.ADD, link, rule, reason, similarity, cause, depth))

    def remove(self, link: Link, rule: Rule, reason: str, *, cause: Cause = None,
               depth: int = 0) -> None:
        self._discard(link)
        self._record(Action(Op.REMOVE, link, rule, reason, None, cause, depth))

    def _record(self, action: Action) -> None:
        self._journal.append((action.op, action.link, len(self.plan.actions)))
        self.plan.actions.append(action)

    def mark(self) -> int:
        return len(self._journal)

    def rollback(self, mark: int) -> tuple[Link, ...]:
        """Undo every change after ``mark``; returns the links that had been added."""
        undone: list[Link] = []
        while len(self._journal) > mark:
            op, link, index = self._journal.pop()
            if op is Op.ADD:
                self._discard(link)
                undone.append(link)
            else:
                self._add(link)
            del self.plan.actions[index]  # journal order = action order, so index is last
        return tuple(reversed(undone))

    def reject(self, kind: Refusal, attempt: Attempt, reason: str,
               rolled_back: tuple[Link, ...] = ()) -> None:
        self.plan.rejections.append(Rejection(kind, attempt, reason, rolled_back))

    def note(self, text: str) -> None:
        self.plan.notes.append(text)

    # -- listing 4.8 ----------------------------------------------------------------------
    def find_output_for(self, input_ref: ChannelRef) -> tuple[ChannelRef, Similarity] | None:
        """The most similar free output for a present input (its own type and profile)."""
        ch = self.channels[input_ref]
        return self.find_similar_channel(Direction.OUTPUT, ch.type, ch.profile,
                                         exclude=input_ref.device, sole_access=ch.sole_access)

    def find_similar_channel(self, direction: Direction, q_type: int, q_profile: int, *,
                             exclude: DeviceKey | None = None,
                             sole_access: bool = False) -> tuple[ChannelRef, Similarity] | None:
        """Listing 4.8 with the reference's Decisions: present, free, not on ``exclude``,
        sharing at least the root component; ties by lower profile, then reference.

        Free: for a sole-access input an output must not feed a sole-access input yet;
        an input candidate must have no source yet.
        """
        if direction is Direction.OUTPUT:
            found = self.outputs.best(q_type, q_profile, exclude=exclude, sole_free=sole_access)
        else:
            found = self.inputs.best(q_type, q_profile, exclude=exclude,
                                     free=lambda r: not self.has_source(r))
        return (found[0].ref, found[1]) if found else None

    def why_no_output(self, input_ref: ChannelRef) -> str:
        """Explain why ``find_output_for`` found nothing (for rejections and checks).

        Stops as soon as it can say why: autoconfigure on a large, crowded system explains
        hundreds of refusals, so this must not walk every output each time.
        """
        ch = self.channels[input_ref]
        if ch.profile == 0:
            return "its profile is the null profile 0x0000"
        own = input_ref.device
        any_root = off_device = False
        taken: list[ChannelRef] = []
        for c in self.outputs.sharing_root(ch.profile):
            any_root = True
            if c.ref[:3] == own:
                continue
            off_device = True
            for r in self.sole_inputs_fed_by(c.ref):
                if r not in taken:
                    taken.append(r)
            if len(taken) > 3:
                break
        if not any_root:
            return f"no present output shares its root component 0x{ch.profile >> 12:X}"
        if not off_device:
            return "the only outputs sharing its root component are on its own device"
        shown = ", ".join(str(r) for r in taken[:3]) + (" …" if len(taken) > 3 else "")
        return (f"every output sharing its root component already feeds a sole-access input"
                f" ({shown})")

    # -- listing 4.4 ----------------------------------------------------------------------
    def connect(self, link: Link, rule: Rule, reason: str, *, cause: Cause = None,
                depth: int = 0, similarity: Similarity | None = None) -> Connected:
        """Set the link up unless it violates sole access or the input has another source."""
        attempt = Attempt(rule, link, link.input, cause, depth)
        for ref, want in ((link.output, Direction.OUTPUT), (link.input, Direction.INPUT)):
            if not self.is_present(ref, want):
                problem = "missing" if ref not in self.present else f"not an {want.value} channel"
                self.reject(Refusal.MISSING, attempt, f"{ref} is {problem}")
                return Connected.REFUSED
        if link in self.links:
            return Connected.EXISTS
        srcs = self.sources(link.input)
        if srcs:
            self.reject(Refusal.INPUT_TAKEN, attempt,
                        f"input {link.input} already has source {srcs[0]}")
            return Connected.REFUSED
        if self.channels[link.input].sole_access and self.sole_fed.get(link.output):
            taken = self.sole_inputs_fed_by(link.output)[0]
            self.reject(Refusal.SOLE_ACCESS, attempt,
                        f"sole access: output {link.output} already feeds "
                        f"sole-access input {taken}")
            return Connected.REFUSED
        for dead in sorted(self.by_input.get(link.input, ())):
            self.remove(dead, Rule.SUPERSEDED,
                        f"its output {dead.output} is missing; {link.input} gets {link.output}",
                        cause=link, depth=depth)
        self.add(link, rule, reason, similarity=similarity or self.similarity(link),
                 cause=cause, depth=depth)
        return Connected.MADE

    # -- listing 4.5 ----------------------------------------------------------------------
    def wanted(self, link: Link) -> Iterator[tuple[ChannelRef, bool, ChannelRef]]:
        """(input, required?, asked by) in the Decision's order: the output's required, the
        input's required, the output's desired, the input's desired, each by index."""
        out, inp = self.channels[link.output], self.channels[link.input]
        seen: set[ChannelRef] = set()
        for owner_ref, owner, required in ((link.output, out, True), (link.input, inp, True),
                                           (link.output, out, False), (link.input, inp, False)):
            indices = owner.required_inputs if required else owner.desired_inputs
            for index in sorted(indices):
                ref = ChannelRef(*owner_ref.device, index)
                if ref not in seen:
                    seen.add(ref)
                    yield ref, required, owner_ref

    def intelligently_connect(self, link: Link, rule: Rule, reason: str, *, cause: Cause = None,
                              depth: int = 0, similarity: Similarity | None = None,
                              _visited: set[ChannelRef] | None = None) -> bool:
        """Connect ``link``, then every required/desired input not yet connected, recursively.

        A required input that cannot be met removes every link this call and its sub-calls
        made, and nothing else. ``_visited`` holds the inputs tried in this top-level call:
        one that was tried and is still unconnected is not tried again.
        """
        visited = set() if _visited is None else _visited
        mark = self.mark()
        if self.connect(link, rule, reason, cause=cause, depth=depth,
                        similarity=similarity) is Connected.REFUSED:
            return False
        visited.add(link.input)
        for ref, required, owner in self.wanted(link):
            if ref in self.present and self.channels[ref].is_input and self.has_source(ref):
                continue
            sub_rule = Rule.REQUIRED if required else Rule.DESIRED
            attempt = Attempt(sub_rule, None, ref, owner, depth + 1)
            ok = False
            if ref not in self.present or not self.channels[ref].is_input:
                self.reject(Refusal.NOT_INPUT, attempt,
                            f"{owner} names {ref}, which is not an input channel")
            elif ref in visited:
                self.reject(Refusal.ALREADY_TRIED, attempt,
                            f"input {ref} was already tried in this call and is still unconnected")
            else:
                visited.add(ref)
                found = self.find_output_for(ref)
                if found is None:
                    self.reject(Refusal.NO_CANDIDATE, attempt,
                                f"no output for {self.describe(ref)}: {self.why_no_output(ref)}")
                else:
                    out_ref, sim = found
                    verb = "required" if required else "desired"
                    ok = self.intelligently_connect(
                        Link(out_ref, ref), sub_rule,
                        f"{verb} by {self.describe(owner)}: most similar free output",
                        cause=owner, depth=depth + 1, similarity=sim, _visited=visited)
            if not ok and required:
                undone = self.rollback(mark)
                self.reject(Refusal.ROLLED_BACK, Attempt(rule, link, link.input, cause, depth),
                            f"required input {ref} of {owner} could not be connected; "
                            f"removed the {len(undone)} link(s) this call made", undone)
                return False
        return True

    # -- result --------------------------------------------------------------------------
    def finish(self) -> Plan:
        """The plan, with the facts of every channel it mentions (for rendering)."""
        plan = self.plan
        refs: set[ChannelRef] = set()
        for a in plan.actions:
            refs.update((a.link.output, a.link.input))
        for lk in plan.links_before:
            refs.update((lk.output, lk.input))
        for r in plan.rejections:
            if r.attempt.link:
                refs.update((r.attempt.link.output, r.attempt.link.input))
            if r.attempt.channel:
                refs.add(r.attempt.channel)
        for ref in sorted(refs):
            ch = self.channels.get(ref)
            if ch is not None:
                plan.channels[ref] = ChannelFacts(ch.type, ch.profile, ch.terminal_profile,
                                                  ch.descriptor, ref in self.present)
        return plan
