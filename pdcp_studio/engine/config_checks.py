"""Checks of one stored configuration on its own (no prosthesis needed). Pure.

A stored configuration holds links and the type and profile of each linked channel, and
nothing else: no terminal profiles, no required inputs, no sources, no device names. So
these checks judge only what it holds — whether the stored links could all be made
together (one source per input, sole access, no channel both an output and an input, no
device feeding itself, no link twice) and whether each link's ends fit each other by
their stored type and profile. What needs the devices themselves (is the device there,
is a terminal channel connected) belongs to fitting the configuration to a prosthesis
(:mod:`pdcp_studio.engine.config_fit`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from pdcp_studio.engine.checks import Severity
from pdcp_studio.engine.similarity import determine_similarity
from pdcp_studio.model import profile as prof
from pdcp_studio.model.channel_type import SOLE_ACCESS_MASK
from pdcp_studio.model.configuration import StoredConfiguration
from pdcp_studio.model.refs import ChannelRef

_TYPE_FIELDS = ("control mode", "data type", "byte size")


@dataclass(frozen=True)
class ConfigFinding:
    """One thing wrong or worth knowing about a stored configuration.

    ``links`` are positions (0-based) in the configuration's link list, so a view can
    select them; ``refs`` are the channels concerned.
    """

    severity: Severity
    code: str
    message: str
    links: tuple[int, ...] = ()
    refs: tuple[ChannelRef, ...] = ()

    def to_json(self) -> dict[str, Any]:
        return {"severity": self.severity.value, "code": self.code, "message": self.message,
                "links": list(self.links), "refs": [r.as_json() for r in self.refs]}


def _n(cfg: StoredConfiguration, pos: int) -> int:
    """The link's number as the file stores it (its position + 1 when unnumbered)."""
    return cfg.links[pos].index or pos + 1


def _names(cfg: StoredConfiguration, positions: list[int]) -> str:
    nums = [str(_n(cfg, p)) for p in positions]
    return ("link " if len(nums) == 1 else "links ") + ", ".join(nums)


def check_configuration(cfg: StoredConfiguration) -> list[ConfigFinding]:
    """Every finding of ``cfg``, errors first, then in link order."""
    out: list[ConfigFinding] = []
    links = cfg.links
    by_ends: dict[tuple[ChannelRef, ChannelRef], list[int]] = {}
    by_input: dict[ChannelRef, list[int]] = {}
    as_output: dict[ChannelRef, list[int]] = {}
    as_input: dict[ChannelRef, list[int]] = {}
    records: dict[ChannelRef, dict[tuple[int, int], list[int]]] = {}
    for pos, sl in enumerate(links):
        out_ref, in_ref = sl.output.ref, sl.input.ref
        by_ends.setdefault((out_ref, in_ref), []).append(pos)
        by_input.setdefault(in_ref, []).append(pos)
        as_output.setdefault(out_ref, []).append(pos)
        as_input.setdefault(in_ref, []).append(pos)
        for ch in (sl.output, sl.input):
            records.setdefault(ch.ref, {}).setdefault((ch.type, ch.profile), []).append(pos)
        if out_ref.device == in_ref.device:
            out.append(ConfigFinding(
                Severity.ERROR, "same-device",
                f"{_names(cfg, [pos])}: device {out_ref.device} would feed itself "
                f"(output {out_ref.index} → input {in_ref.index})", (pos,), (out_ref, in_ref)))
    for (out_ref, in_ref), positions in by_ends.items():
        if len(positions) > 1:
            out.append(ConfigFinding(
                Severity.WARNING, "duplicate-link",
                f"{_names(cfg, positions)} store the same link {out_ref} → {in_ref}; "
                "it is made once", tuple(positions), (out_ref, in_ref)))
    for in_ref, positions in by_input.items():
        sources = sorted({links[p].output.ref for p in positions})
        if len(sources) > 1:
            out.append(ConfigFinding(
                Severity.ERROR, "two-sources",
                f"input {in_ref} is given {len(sources)} sources "
                f"({', '.join(map(str, sources))}) by {_names(cfg, positions)}; an input "
                "takes one source, so only the first would be made", tuple(positions),
                (in_ref, *sources)))
    for ref in sorted(set(as_output) & set(as_input)):
        positions = sorted(as_output[ref] + as_input[ref])
        out.append(ConfigFinding(
            Severity.ERROR, "both-directions",
            f"channel {ref} is stored as an output ({_names(cfg, as_output[ref])}) and as an "
            f"input ({_names(cfg, as_input[ref])}); a channel is one or the other",
            tuple(positions), (ref,)))
    out += _sole_access(cfg, as_output)
    for ref in sorted(records):
        variants = records[ref]
        if len(variants) > 1:
            said = "; ".join(f"type {t:#06x} profile {prof.fmt(p)} in {_names(cfg, ps)}"
                             for (t, p), ps in variants.items())
            positions = sorted(p for ps in variants.values() for p in ps)
            out.append(ConfigFinding(
                Severity.WARNING, "inconsistent-records",
                f"channel {ref} is stored with different records: {said}",
                tuple(positions), (ref,)))
    for pos in range(len(links)):
        out += _fitness(cfg, pos)
    out.sort(key=lambda f: (f.severity.rank, f.links[:1] or (len(links),), f.code))
    return out


def _sole_access(cfg: StoredConfiguration, as_output: dict[ChannelRef, list[int]]
                 ) -> list[ConfigFinding]:
    """An output may feed at most one sole-access input (reference §1, channel type)."""
    out = []
    for out_ref, positions in sorted(as_output.items()):
        sole = sorted({cfg.links[p].input.ref for p in positions
                       if cfg.links[p].input.type & SOLE_ACCESS_MASK})
        if len(sole) > 1:
            which = [p for p in positions if cfg.links[p].input.ref in sole]
            out.append(ConfigFinding(
                Severity.ERROR, "sole-access",
                f"output {out_ref} feeds {len(sole)} sole-access inputs "
                f"({', '.join(map(str, sole))}) in {_names(cfg, which)}; a sole-access input "
                "must be the only sole-access input its source feeds", tuple(which),
                (out_ref, *sole)))
    return out


def _fitness(cfg: StoredConfiguration, pos: int) -> list[ConfigFinding]:
    """Do the link's ends fit by stored profile and type? A profile of 0 is "not stored"."""
    sl = cfg.links[pos]
    o, i = sl.output, sl.input
    if o.profile == prof.NULL_PROFILE or i.profile == prof.NULL_PROFILE:
        return []
    sim = determine_similarity((o.type, o.profile), (i.type, i.profile))
    name = _names(cfg, [pos])
    if not sim.shares_root:
        return [ConfigFinding(
            Severity.WARNING, "profile-misfit",
            f"{name}: output {o.ref} (profile {prof.fmt(o.profile)}) and input {i.ref} "
            f"(profile {prof.fmt(i.profile)}) share no profile component; the input may not "
            "understand what it is sent", (pos,), (o.ref, i.ref))]
    if o.type == 0 or i.type == 0:
        return []
    differ = [f for f, same in zip(_TYPE_FIELDS, (sim.control_mode, sim.data_type,
                                                   sim.byte_size), strict=True) if not same]
    if differ:
        return [ConfigFinding(
            Severity.INFO, "type-differs",
            f"{name}: output {o.ref} and input {i.ref} differ in {' and '.join(differ)} "
            f"(types {o.type:#06x} and {i.type:#06x})", (pos,), (o.ref, i.ref))]
    return []
