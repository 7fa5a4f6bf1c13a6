"""One name for every part and channel of a prosthesis, for every text PDCP Studio shows. Pure.

**A part** is called by the first of these it has (one rule, everywhere):

1. its *own name*: the role a fitter gave it in the prosthesis's system file ("EMG flexor
   site", "Hand"); a live bus never tells one, so a live part goes on to 2;
2. its *descriptor*: what the part tells the bus about itself, which names its product and
   its role in its maker's words ("Multi-grip hand with wrist rotator", "EMG electrode
   (wrist flexors)");
3. its *product* in the device catalogue ("Multi-grip hand"): a part known only by its
   numbers (a stored configuration's, an event's that came before the part was read);
4. ``unknown device (VID/PID/serial)``: no catalogue knows it (never an invented name).

Its serial number is added (``TWIN``) only where two parts would otherwise read the same:
the parts of the system and the ``among`` parts (one taken out, still named by the graph or
the history) are named together, so both hands are "… (serial 301)" / "… (serial 302)" in
every panel, and a part outside the system that reads like one of them gets its serial too.

**A channel** is its part's name and the channel's own descriptor, else its profile's name
from the named profile tree, else "channel N" (``CHANNEL``); its number is added only where
two channels of one part would otherwise read the same. A card too narrow for a name
shows one of :func:`short_forms`, the same abbreviation on every card; the full name is in
the tooltip and the inspector.

The panels, the status bar, events, the fitting history, the change's effect, the report
and the CLI all ask a :class:`Names`, so one part never has two names. Templates are
English; the app passes Qt's ``translate`` as ``tr`` (context ``Names``) so German reads
German. Numbers (VID/PID/serial, codes) are never part of a name but of an engineer's
detail (:meth:`Names.numbers`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

from pdcp_studio.model.catalog import Catalog, default_catalog, unknown_device_label
from pdcp_studio.model.profile_tree import ProfileTree
from pdcp_studio.model.refs import ChannelRef, DeviceKey
from pdcp_studio.model.safe_text import shown
from pdcp_studio.model.system import Channel, Device, Link, System

Translate = Callable[[str], str]

#: The templates a name is made of (marked for translation in the app's ``Names`` context).
TWIN = "{name} (serial {serial})"
CHANNEL = "{part}, {channel}"
CHANNEL_NUMBER = "channel {n}"
CHANNEL_TWIN = "{name} ({channel})"
LINK = "{output} → {input}"
NUMBERS = "VID {vid} · PID {pid} · serial {serial}"

#: A word is abbreviated to this many letters and a full stop ("flexor" → "flex.").
STEM = 4


def _same(text: str) -> str:
    return text


def own_name(device: Device, catalog: Catalog) -> str:
    """What a part is called before any serial number is added (rules 1–4 above)."""
    for text in (device.name, device.descriptor):
        if text and text.strip():  # from a file or the bus: shown, never executed
            return shown(" ".join(text.split()))
    return catalog.product_name(device.key) or unknown_device_label(device.key)


def parts_named(devices: Iterable[Device], catalog: Catalog,
                twin: str = TWIN) -> dict[DeviceKey, str]:
    """One name per part of ``devices`` taken together: the serial number (``twin``) only
    where two of them would otherwise read the same."""
    own = {d.key: own_name(d, catalog) for d in devices}
    seen: dict[str, int] = {}
    for name in own.values():
        seen[name] = seen.get(name, 0) + 1
    return {key: twin.format(name=name, serial=key.serial) if seen[name] > 1 else name
            for key, name in own.items()}


def short_forms(name: str) -> list[str]:
    """``name`` and its abbreviations, longest first, for a card too narrow for it.

    Fixed steps, never cut letter by letter to the pixel, so a word reads alike on every
    card ("EMG flexor 1" and "EMG flexor 11" → "EMG flex. 1" / "EMG flex. 11", never
    "EMG fle. 11"): the words longer than ``STEM`` + 1 letters cut to their first ``STEM``
    letters ("EMG flex. 11"); then the leading words dropped one by one while two stay
    ("flex. 11"); then the last two words cut to their initial ("f. 11"). Numbers and a
    twin's "(serial 302)" stay whole, so "flexor 11" and "extensor 11" stay apart."""
    words: list[str] = []
    for word in name.split():  # "(serial 302)" is one word: it is never cut apart
        if words and words[-1].startswith("(") and not words[-1].endswith(")"):
            words[-1] += " " + word
        else:
            words.append(word)
    if not words:
        return [name]

    def cut(word: str, least: int) -> str:
        if not word.replace("-", "").isalpha() or len(word) <= max(least + 1, 2):
            return word  # numbers, "(serial", "302)" stay whole
        return word[:least] + "."

    forms = [" ".join(words)]
    stems = [cut(w, STEM) for w in words]
    forms.append(" ".join(stems))
    for start in range(1, len(stems) - 1):
        forms.append(" ".join(stems[start:]))
    tail = words[-2:] if len(words) > 1 else words
    forms.append(" ".join(cut(w, 1) for w in tail))
    out: list[str] = []
    for form in forms:
        if form not in out:
            out.append(form)
    return out


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
    _known: list[Device] = field(default_factory=list, init=False, repr=False)

    def __post_init__(self) -> None:
        devices = list(self.system.devices.values()) if self.system is not None else []
        keys = {d.key for d in devices}
        others = [d for d in self.among if d.key not in keys]
        self._known = devices + others
        self._parts = parts_named(self._known, self._catalog(), self.tr(TWIN))

    def _catalog(self) -> Catalog:
        return self.catalog if self.catalog is not None else default_catalog()

    def parts(self) -> dict[DeviceKey, str]:
        """Every part of the system and of ``among`` by key."""
        return dict(self._parts)

    def knows(self, key: DeviceKey) -> bool:
        """True when ``key`` is a part of the system or of ``among``."""
        return key in self._parts

    def part(self, key: DeviceKey) -> str:
        """The part's name (the module's rule); a part neither in the system nor ``among``
        by its product, with its serial number where a known part reads the same."""
        name = self._parts.get(key)
        if name is not None:
            return name
        product = self._catalog().product_name(key)
        if product is None:
            return unknown_device_label(key)
        clash = any(own_name(d, self._catalog()) == product for d in self._known)
        return self.tr(TWIN).format(name=product, serial=key.serial) if clash else product

    def numbers(self, key: DeviceKey) -> str:
        """``VID 2641 · PID 257 · serial 101``: the engineer's detail beside a name."""
        return self.tr(NUMBERS).format(vid=key.vid, pid=key.pid, serial=key.serial)

    def _own_channel(self, ch: Channel) -> str:
        own = shown(" ".join((ch.descriptor or "").split()))
        if own:
            return own
        if self.profiles is not None and ch.profile and self.profiles.names_exactly(ch.profile):
            return self.profiles.short_name(ch.profile)
        return ""

    def channel_only(self, ref: ChannelRef, profile_name: str = "") -> str:
        """The channel without its part: descriptor, else profile name (``profile_name``
        where the tree is not at hand), else "channel N"; "Grip (channel 2)" where two
        channels of one part would read the same."""
        device = self.system.devices.get(ref.device) if self.system is not None else None
        ch = device.channels.get(ref.index) if device is not None else None
        own = self._own_channel(ch) if ch is not None else ""
        if not own and profile_name and not profile_name.startswith("0x"):
            own = profile_name
        if not own:
            return self.tr(CHANNEL_NUMBER).format(n=ref.index)
        if device is not None and any(
                c.index != ref.index and self._own_channel(c) == own
                for c in device.channels.values()):
            return self.tr(CHANNEL_TWIN).format(
                name=own, channel=self.tr(CHANNEL_NUMBER).format(n=ref.index))
        return own

    def channel(self, ref: ChannelRef, profile_name: str = "") -> str:
        """``Hand, Power grip``: the part and the channel."""
        return self.tr(CHANNEL).format(part=self.part(ref.device),
                                       channel=self.channel_only(ref, profile_name))

    def link(self, link: Link) -> str:
        """``EMG flexor site, Flexor EMG envelope → Control unit, Flexor EMG``."""
        return self.tr(LINK).format(output=self.channel(link.output),
                                    input=self.channel(link.input))

    def profile(self, code: int) -> str:
        """A profile by its name in the profile tree, else its code."""
        if self.profiles is not None and code and self.profiles.names_exactly(code):
            return self.profiles.name_of(code)
        return f"0x{code:04X}"
