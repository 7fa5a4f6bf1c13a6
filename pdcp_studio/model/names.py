"""One name for every part and channel of a prosthesis, for every text PDCP Studio shows. Pure.

A part is called by its own name (what it tells the bus, or the name a system file gives
it), else by its product in the device catalogue; its serial number is added only where two
parts would otherwise read the same (``model/catalog.py`` ``Catalog.part_names``). A channel
is its part's name and the channel's own descriptor, else its profile's name from the named
profile tree, else its number. The panels, the status bar, events, the fitting history, the
change's effect, the report and the CLI all ask a :class:`Names`, so one part never has two
names.

Templates are English; the app passes Qt's ``translate`` as ``tr`` (context ``Names``) so
German reads German. Numbers (VID/PID/serial, codes) are never part of a name: they belong in
an engineer's detail.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

from pdcp_studio.model.catalog import Catalog, default_catalog
from pdcp_studio.model.profile_tree import ProfileTree
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.system import Device, Link, System

Translate = Callable[[str], str]

#: The templates a name is made of (marked for translation in the app's ``Names`` context).
TWIN = "{name} (serial {serial})"
CHANNEL = "{part}, {channel}"
CHANNEL_NUMBER = "channel {n}"
LINK = "{output} → {input}"


def _same(text: str) -> str:
    return text


@dataclass
class Names:
    """The names of one system's parts and channels.

    ``among``: other parts known to be there (a part taken out, still named by the history
    or the graph), so a part that reads like one of them gets its serial number too.
    """

    system: System | None
    profiles: ProfileTree | None = None
    catalog: Catalog | None = None
    among: Iterable[Device] = ()
    tr: Translate = _same
    _parts: dict[DeviceKey, str] = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        devices = list(self.system.devices.values()) if self.system is not None else []
        keys = {d.key for d in devices}
        others = [d for d in self.among if d.key not in keys]
        every = self._catalog().part_names(devices + others, self.tr(TWIN))
        self._parts = every

    def _catalog(self) -> Catalog:
        return self.catalog if self.catalog is not None else default_catalog()

    def part(self, key: DeviceKey) -> str:
        """The part's name: its own, else its product's (serial only for twins)."""
        name = self._parts.get(key)
        if name is not None:
            return name
        return self._catalog().label(key)

    def channel_only(self, ref: ChannelRef) -> str:
        """The channel without its part: descriptor, else profile name, else "channel N"."""
        ch = self.system.channel(ref) if self.system is not None else None
        if ch is not None:
            own = (ch.descriptor or "").strip()
            if own:
                return own
            if self.profiles is not None and ch.profile:
                if self.profiles.names_exactly(ch.profile):
                    return self.profiles.short_name(ch.profile)
        return self.tr(CHANNEL_NUMBER).format(n=ref.index)

    def channel(self, ref: ChannelRef) -> str:
        """``Hand, Power grip``: the part and the channel."""
        return self.tr(CHANNEL).format(part=self.part(ref.device),
                                       channel=self.channel_only(ref))

    def link(self, link: Link) -> str:
        """``EMG flexor site, Flexor EMG envelope → Control unit, Flexor EMG``."""
        return self.tr(LINK).format(output=self.channel(link.output),
                                    input=self.channel(link.input))

    def profile(self, code: int) -> str:
        """A profile by its name in the profile tree, else its code."""
        if self.profiles is not None and code and self.profiles.names_exactly(code):
            return self.profiles.name_of(code)
        return f"0x{code:04X}"
