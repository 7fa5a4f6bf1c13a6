"""Which absent parts have been replaced (issue 26 item 6): no longer missing, but "replaced by"
the part that took their place.

An absent device is replaced when every role it had — each link it was an end of, on the
bus or in the stored configuration, whose other end is on the bus — is now held by a present
device in its place: the same other end linked to a channel of that device instead. Its own
links left on the bus are dead (they carry nothing) and no longer needed then. The
arbitrator asks after a verified transaction and forgets the parts this names (nothing needs
them now); the fitting history records the pairs. Pure.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from typing import NamedTuple

from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Link, System


class Replaced(NamedTuple):
    """``old`` (absent) is replaced by ``new`` (present)."""

    old: DeviceKey
    new: DeviceKey


def replaced_parts(system: System, roles: Iterable[Link]) -> list[Replaced]:
    """The absent devices of ``system`` whose every role in ``roles`` (the links before the
    change: on the bus and stored) a present device now holds, each with the device that
    holds most of them (the lowest key on a tie)."""
    roles = set(roles) | set(system.links)
    out: list[Replaced] = []
    for key, device in sorted(system.devices.items()):
        if device.present:
            continue
        takers: Counter[DeviceKey] = Counter()
        taken = judged = 0
        for role in sorted(roles):
            holders = _holders(system, role, key)
            if holders is None:
                continue
            judged += 1
            if holders:
                taken += 1
                takers.update(holders)
        if judged and taken == judged:
            best = max(takers.values())
            out.append(Replaced(key, min(k for k, n in takers.items() if n == best)))
    return out


def _holders(system: System, role: Link, old: DeviceKey) -> set[DeviceKey] | None:
    """The present devices that hold ``old``'s end of ``role`` now (None: not its role, or
    its other end is not on the bus either, so nothing can be judged). An output feeds many
    inputs: of the inputs it feeds, those that carry what ``old``'s input carried (its
    profile) hold the role."""
    if role.input.device == old and role.output.device != old:
        other = role.output
        if not system.is_present(other):
            return None
        mine = system.channel(role.input)
        profile = mine.profile if mine is not None else 0
        fed = [ref for ref in system.inputs_fed_by(other)
               if system.is_present(ref) and ref.device != old]
        alike = [ref for ref in fed if profile and (ch := system.channel(ref)) is not None
                 and ch.profile == profile]
        return {ref.device for ref in (alike or fed)}
    if role.output.device == old and role.input.device != old:
        other = role.input
        if not system.is_present(other):
            return None
        return {ref.device for ref in system.sources_of(other)
                if system.is_present(ref) and ref.device != old}
    return None


__all__ = ["Replaced", "replaced_parts"]
