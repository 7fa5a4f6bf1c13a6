"""Edits of a stored-configuration collection, each returning a new collection. Pure.

The configuration document's undo commands are built on these, so every edit can be
tested without Qt and an undo is simply the collection from before. Edits never drop
what they do not touch: unknown records (reference §3) stay on their declaration, owner
type and profile stay on their channel.

Numbering: configurations are numbered 1…n in collection order after any edit of the
collection (the order is start-up's tie-break, so a move is a change of priority); links
are numbered 1…n in configuration order after a link is removed.
"""

from __future__ import annotations

from dataclasses import replace

from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.model.refs import ChannelRef


def copy_collection(coll: ConfigCollection) -> ConfigCollection:
    """A copy whose lists can be changed without touching ``coll`` (records are frozen)."""
    return ConfigCollection(
        [StoredConfiguration(c.index, list(c.links), c.unknown) for c in coll.configurations],
        coll.unknown)


def _numbered(coll: ConfigCollection) -> ConfigCollection:
    for n, cfg in enumerate(coll.configurations, 1):
        cfg.index = n
    return coll


def _numbered_links(links: list[StoredLink]) -> list[StoredLink]:
    return [lk if lk.index == n else replace(lk, index=n) for n, lk in enumerate(links, 1)]


def add_configuration(coll: ConfigCollection, links: list[StoredLink] | None = None
                      ) -> ConfigCollection:
    """A new configuration at the end (empty, or with ``links``)."""
    new = copy_collection(coll)
    new.configurations.append(StoredConfiguration(0, _numbered_links(list(links or []))))
    return _numbered(new)


def duplicate_configuration(coll: ConfigCollection, position: int) -> ConfigCollection:
    """A copy of configuration ``position`` right after it (unknown records included)."""
    new = copy_collection(coll)
    src = new.configurations[position]
    new.configurations.insert(position + 1,
                              StoredConfiguration(0, list(src.links), src.unknown))
    return _numbered(new)


def remove_configuration(coll: ConfigCollection, position: int) -> ConfigCollection:
    new = copy_collection(coll)
    del new.configurations[position]
    return _numbered(new)


def move_configuration(coll: ConfigCollection, position: int, to: int) -> ConfigCollection:
    """Move configuration ``position`` to ``to`` (both 0-based)."""
    new = copy_collection(coll)
    cfg = new.configurations.pop(position)
    new.configurations.insert(to, cfg)
    return _numbered(new)


def add_link(coll: ConfigCollection, position: int, output: StoredChannel,
             input: StoredChannel) -> ConfigCollection:
    """Append the link ``output → input`` to configuration ``position``."""
    new = copy_collection(coll)
    cfg = new.configurations[position]
    index = max((lk.index for lk in cfg.links), default=0) + 1
    cfg.links.append(StoredLink(input=input, output=output, index=index))
    return new


def remove_links(coll: ConfigCollection, position: int, link_positions: list[int]
                 ) -> ConfigCollection:
    """Remove the given links (0-based positions) of configuration ``position``."""
    new = copy_collection(coll)
    cfg = new.configurations[position]
    drop = set(link_positions)
    cfg.links = _numbered_links([lk for i, lk in enumerate(cfg.links) if i not in drop])
    return new


def set_channel(coll: ConfigCollection, position: int, ref: ChannelRef, *,
                type: int | None = None, profile: int | None = None) -> ConfigCollection:
    """Change the stored type and/or profile of channel ``ref`` in every link of
    configuration ``position`` that stores it (one channel, one record)."""
    new = copy_collection(coll)
    cfg = new.configurations[position]
    for name, value in (("type", type), ("profile", profile)):
        if value is not None and (isinstance(value, bool) or not 0 <= value <= 0xFFFF):
            raise ValueError(f"{name} {value!r} is out of range 0…0xFFFF")

    def fix(ch: StoredChannel) -> StoredChannel:
        if ch.ref != ref:
            return ch
        return replace(ch, type=ch.type if type is None else type,
                       profile=ch.profile if profile is None else profile)

    cfg.links = [replace(lk, output=fix(lk.output), input=fix(lk.input))
                 if ref in (lk.output.ref, lk.input.ref) else lk for lk in cfg.links]
    return new


def channels_of(cfg: StoredConfiguration) -> dict[ChannelRef, tuple[str, StoredChannel]]:
    """Each stored channel of ``cfg`` once: its direction ("output"/"input") and its first
    record, in link order."""
    out: dict[ChannelRef, tuple[str, StoredChannel]] = {}
    for lk in cfg.links:
        out.setdefault(lk.output.ref, ("output", lk.output))
        out.setdefault(lk.input.ref, ("input", lk.input))
    return out
