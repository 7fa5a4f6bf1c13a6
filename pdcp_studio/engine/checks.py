"""What a prosthetist must know before trusting a system (``pdcp-studio check``).

Each finding names its channels, says what is wrong and, where the engine can tell, why:
an unconnected terminal channel is explained by the same candidate search autoconfigure
uses, so the check and the plan never disagree.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

from pdcp_studio.engine.layer import ProfileLayer
from pdcp_studio.model import profile as prof
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import System


class Severity(StrEnum):
    ERROR = "error"  # the system does not work as configured
    WARNING = "warning"  # it works, but not as a prosthetist would expect
    INFO = "info"  # worth knowing

    @property
    def rank(self) -> int:
        return ("error", "warning", "info").index(self.value)


@dataclass(frozen=True)
class Finding:
    severity: Severity
    code: str
    message: str
    refs: tuple[ChannelRef, ...] = ()

    def to_json(self) -> dict[str, Any]:
        return {"severity": self.severity.value, "code": self.code, "message": self.message,
                "refs": [r.as_json() for r in self.refs]}

    def __str__(self) -> str:
        return f"{self.severity.value:7} {self.code}: {self.message}"


def check_system(system: System, *, autoconfigure: bool = True) -> list[Finding]:
    """Every finding, errors first, then by code and channels. ``autoconfigure`` False (the
    prosthesis's policy, issue 17) says so on each unconnected terminal channel."""
    layer = ProfileLayer(system, "check")
    out: list[Finding] = []
    add = out.append
    for ref in sorted(layer.channels):
        ch = layer.channels[ref]
        what = f"{ch.direction.value} {ref}"
        if ch.profile == prof.NULL_PROFILE:
            add(Finding(Severity.ERROR, "null-profile",
                        f"{what} has the null profile 0x0000: it can never be linked by "
                        "profile", (ref,)))
        elif not prof.is_well_formed(ch.profile):
            add(Finding(Severity.WARNING, "malformed-profile",
                        f"{what} has profile {prof.fmt(ch.profile)}: a component follows a "
                        "zero one, so similarity ignores everything after the zero", (ref,)))
        for kind in ("required", "desired"):
            for index in getattr(ch, f"{kind}_inputs"):
                target = ChannelRef(*ref.device, index)
                tch = layer.channels.get(target)
                if tch is None or not tch.is_input:
                    add(Finding(Severity.ERROR, f"{kind}-not-input",
                                f"{what} names channel {index} as {kind}, but that is not an "
                                "input channel of its device", (ref, target)))
        if ch.terminal and ch.terminal_profile == prof.NULL_PROFILE:
            add(Finding(Severity.WARNING, "terminal-profile-null",
                        f"terminal {what} has terminal profile 0x0000, so autoconfigure "
                        "connects it before every other terminal channel", (ref,)))

    for link in sorted(layer.links):
        ends = [r for r in (link.output, link.input) if r not in layer.present]
        if ends:
            add(Finding(Severity.WARNING, "missing-end",
                        f"link {link} carries no data: " +
                        " and ".join(f"{r} is missing" for r in ends), (link.output, link.input)))
        if link.output.device == link.input.device:
            add(Finding(Severity.WARNING, "self-link",
                        f"link {link} joins a device to itself (a device must not send to "
                        "itself on the bus)", (link.output, link.input)))

    for out_ref in sorted(r for r, n in layer.sole_fed.items() if n > 1):
        fed = layer.sole_inputs_fed_by(out_ref)
        add(Finding(Severity.ERROR, "sole-access",
                    f"output {out_ref} feeds {len(fed)} sole-access inputs "
                    f"({', '.join(map(str, fed))}); `plan enforce` keeps one",
                    (out_ref, *fed)))

    for in_ref in sorted(layer.by_input):
        links = sorted(layer.by_input[in_ref])
        if len(links) > 1:
            add(Finding(Severity.ERROR, "two-sources",
                        f"input {in_ref} has {len(links)} sources "
                        f"({', '.join(str(lk.output) for lk in links)})",
                        (in_ref, *(lk.output for lk in links))))
        ch = layer.channels[in_ref]
        live = layer.sources(in_ref)
        if live and in_ref in layer.present and ch.source.ref not in live:
            stored = ch.source.ref or "none"
            add(Finding(Severity.INFO, "source-field-stale",
                        f"input {in_ref} is linked from {live[0]} but stores source {stored}; "
                        "a replaced arbitrator would rebuild the stored one", (in_ref,)))

    _unmet(layer, add)

    for ref in layer.unconnected_terminals():
        found = layer.find_output_for(ref)
        tp = prof.fmt(layer.channels[ref].terminal_profile)
        if not autoconfigure:
            add(Finding(Severity.WARNING, "terminal-unconnected",
                        f"terminal channel {ref} ({tp}) not connected — autoconfigure is off "
                        "on this prosthesis", (ref,)))
            continue
        if found is None:
            why = layer.why_no_output(ref)
        else:
            why = (f"`plan autoconfigure` would link it to {found[0]} "
                   f"(similarity {found[1].total})")
        add(Finding(Severity.WARNING, "terminal-unconnected",
                    f"terminal channel {ref} ({tp}) is not connected: {why}", (ref,)))

    out.sort(key=lambda f: (f.severity.rank, f.code, f.refs))
    return out


def _unmet(layer: ProfileLayer, add: Callable[[Finding], None]) -> None:
    """Required (error) and desired (info) inputs of channels in use that have no source."""
    in_use: set[ChannelRef] = set()
    for link in layer.links:
        if layer.live(link):
            in_use.update((link.output, link.input))
    for ref in sorted(in_use):
        ch = layer.channels[ref]
        for kind, indices, sev in (("required", ch.required_inputs, Severity.ERROR),
                                   ("desired", ch.desired_inputs, Severity.INFO)):
            for index in indices:
                target = ChannelRef(*ref.device, index)
                tch = layer.channels.get(target)
                if tch is None or not tch.is_input or layer.has_source(target):
                    continue
                add(Finding(sev, f"{kind}-unmet",
                            f"{ch.direction.value} {ref} is linked but its {kind} input "
                            f"{target} has no source", (ref, target)))
