"""Stored configurations: the links an arbitrator remembers (reference §3).

These are plain values. The byte codec lives in ``pdcp_studio.storage.config_codec``;
the profile layer (``pdcp_studio.engine``) reads them.

Every declaration (the collection, a configuration, a link, a channel) carries the
records of codes PDCP Studio does not know, in file order, as ``unknown`` (reference §3,
"unknown codes are kept"): a file from newer firmware survives being opened, edited and
saved here.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from pdcp_studio.model.refs import ChannelRef


@dataclass(frozen=True)
class UnknownRecord:
    """A record whose code this program does not know, kept to be written back in place.

    ``after`` is the code of the known record it followed inside its declaration (0: before
    the collection's first record); ``None`` means after all of the declaration's own
    records, where a newer writer usually appends, and where an edited record lands.
    """

    code: int
    value: int
    after: int | None = None


Unknown = tuple[UnknownRecord, ...]


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
    unknown: Unknown = ()

    @property
    def ref(self) -> ChannelRef:
        return ChannelRef(self.vid, self.pid, self.serial, self.index)


@dataclass(frozen=True)
class StoredLink:
    """A stored output → input link (``index`` counts from 1 per configuration)."""

    input: StoredChannel
    output: StoredChannel
    index: int = 0
    unknown: Unknown = ()


@dataclass
class StoredConfiguration:
    """One configuration: a set of links (``index`` counts from 1)."""

    index: int = 1
    links: list[StoredLink] = field(default_factory=list)
    unknown: Unknown = ()


@dataclass
class ConfigCollection:
    """What an arbitrator stores: one or more configurations."""

    configurations: list[StoredConfiguration] = field(default_factory=list)
    unknown: Unknown = ()
