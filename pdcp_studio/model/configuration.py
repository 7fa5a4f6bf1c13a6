"""Stored configurations: the links an arbitrator remembers (reference §3).

These are plain values. The byte codec lives in ``pdcp_studio.storage.config_codec``;
the profile layer (``pdcp_studio.engine``) reads them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from pdcp_studio.model.refs import ChannelRef


@dataclass(frozen=True)
class StoredChannel:
    """One end of a stored link: where it was and what it looked like."""

    index: int
    vid: int
    pid: int
    serial: int
    type: int = 0
    profile: int = 0
    owner_type: int | None = None
    owner_profile: int | None = None

    @property
    def ref(self) -> ChannelRef:
        return ChannelRef(self.vid, self.pid, self.serial, self.index)


@dataclass(frozen=True)
class StoredLink:
    """A stored output → input link (``index`` counts from 1 per configuration)."""

    input: StoredChannel
    output: StoredChannel
    index: int = 0


@dataclass
class StoredConfiguration:
    """One configuration: a set of links (``index`` counts from 1)."""

    index: int = 1
    links: list[StoredLink] = field(default_factory=list)


@dataclass
class ConfigCollection:
    """What an arbitrator stores: one or more configurations."""

    configurations: list[StoredConfiguration] = field(default_factory=list)
