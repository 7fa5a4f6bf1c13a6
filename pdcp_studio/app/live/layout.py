"""Card positions of a live view, remembered per prosthesis instead of asked to be saved.

On a live bus with no project file the bus is the document: moving a card there is not a
change anyone should be asked to save ("Save the changes to sim:thesis-test4?"). The
positions are kept in the application's settings for the *prosthesis* — not for the bus
adapter it is plugged into — and used again the next time it is connected, through any
adapter; only the layout is kept (never links or parameters).

Which prosthesis is this? PDCP gives the arbitrator no identity of its own, so a prosthesis
is known by its parts. A part is known by its VID/PID/serial and the channels it declares
(index, direction, type and profile): the thesis test rigs reuse three boards with the
same serials, re-flashed with other channels, and each rig is laid out on its own.

- A remembered layout belongs to the prosthesis on the bus when at least half of the parts
  on the bus are parts of it (the best such layout: most parts shared, then the one with
  fewest parts not on the bus, then the newest). Two prostheses that share no parts — or
  fewer than half — never share positions, whatever adapter they are on.
- A part that was replaced (a new hand with another serial) takes the place of the part
  it replaced: the remembered part with the same VID/PID (same product) that is no longer
  on the bus; a part whose channels were rewritten keeps its own place (same VID/PID/
  serial). Any other newcomer is put at the bottom of its layer's column, as the graph
  puts a device that joins; every part still present keeps its position.
- Saving overwrites the layout the prosthesis matched, so a prosthesis keeps one layout
  through its part swaps. It keeps the parts on the bus; a part off the bus keeps the place
  it had, unless its replacement stands there now (:func:`to_remember`).

The same rules hold while the prosthesis is live (:func:`place_joined`, called by the live
controller before a snapshot with new parts is merged): a part plugged in as a replacement
takes the place of the card of the part that left (which, off the bus, goes to the bottom
of its column), a part the remembered layout knows goes to its remembered place when no
card is there, any other goes to the bottom of its layer's column; nothing else moves, and
the positions are remembered at once. A replacement often binds before the part it replaces
is missed; when that part leaves shortly after, the two cards swap places
(:func:`swap_in`).

Layouts of older versions were kept per bus URL: such a layout is still used for the
prosthesis on that URL when its parts match by VID/PID/serial (the same half rule), and
dropped when that URL's prosthesis is next saved.
"""

from __future__ import annotations

import hashlib
import json
import logging
import time
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any, TypeVar

from PySide6.QtCore import QSettings

from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Device, System

log = logging.getLogger(__name__)

GROUP = "prosthesis_layouts"
#: Layouts of older versions, one per bus URL (read once more, then dropped).
LEGACY_GROUP = "live_layouts"
#: Prostheses remembered at most (the least recently saved are forgotten).
MAX_LAYOUTS = 50

Position = tuple[float, float]
K = TypeVar("K")
G = TypeVar("G")


def part_key(key: DeviceKey) -> str:
    return f"{key.vid}/{key.pid}/{key.serial}"


def channels_signature(device: Device) -> str:
    """A short digest of the channels a part declares (index, direction, type, profile)."""
    text = ";".join(f"{i}:{ch.direction.value}:{ch.type:X}:{ch.profile:X}"
                    for i, ch in sorted(device.channels.items()))
    return hashlib.sha1(text.encode("utf-8")).hexdigest()[:8]


def part_identity(key: DeviceKey, device: Device) -> str:
    """``vid/pid/serial#channels``: one part as the prosthesis presents it."""
    return f"{part_key(key)}#{channels_signature(device)}"


@dataclass
class Layout:
    """One remembered prosthesis: part identity → card position."""

    ident: str
    at: dict[str, Position] = field(default_factory=dict)
    saved: float = 0.0

    def to_json(self) -> str:
        return json.dumps({"saved": self.saved,
                           "parts": {p: [round(x, 1), round(y, 1)]
                                     for p, (x, y) in sorted(self.at.items())}})

    @classmethod
    def from_json(cls, ident: str, text: str) -> Layout:
        doc = json.loads(text)
        at = {str(p): (float(x), float(y)) for p, (x, y) in doc["parts"].items()}
        return cls(ident, at, float(doc.get("saved", 0.0)))


def identities(system: System) -> dict[DeviceKey, str]:
    return {key: part_identity(key, device) for key, device in system.devices.items()}


def best_layout(layouts: Iterable[Layout], parts: Iterable[str]) -> Layout | None:
    """The layout of the prosthesis made of ``parts`` (see the module's rules), or None."""
    wanted = set(parts)
    best: tuple[tuple[int, int, float], Layout] | None = None
    for lay in layouts:
        shared = len(wanted & lay.at.keys())
        if not shared or 2 * shared < len(wanted):
            continue
        rank = (shared, -len(lay.at.keys() - wanted), lay.saved)
        if best is None or rank > best[0]:
            best = (rank, lay)
    return best[1] if best is not None else None


def positions_from(layout: Layout, parts: Mapping[DeviceKey, str]) -> dict[DeviceKey, Position]:
    """Positions for the parts on the bus from ``layout``: the same parts at their place; a
    part with new channels at its own place; a replaced part at its predecessor's place."""
    out: dict[DeviceKey, Position] = {}
    unused = {p: xy for p, xy in layout.at.items() if p not in parts.values()}
    pending: dict[DeviceKey, str] = {}
    for key, ident in parts.items():
        if ident in layout.at:
            out[key] = layout.at[ident]
        else:
            pending[key] = ident
    for key, ident in successors(pending, {p: p for p in unused}).items():
        out[key] = unused[ident]
    return out


def successors(joined: Mapping[K, str], gone: Mapping[G, str]) -> dict[K, G]:
    """Whose place each part of ``joined`` takes among the parts ``gone`` (both: key →
    part identity): the same part with other channels first, then another unit of the same
    product (VID/PID); where several fit, the first by identity. A place is taken once;
    a part with no predecessor is left out."""
    out: dict[K, G] = {}
    free = dict(gone)
    pending = list(joined)
    for same in (_part_of, _product_of):
        for key in list(pending):
            wanted = same(joined[key])
            match = next((g for g in sorted(free, key=lambda g: (free[g], str(g)))
                          if same(free[g]) == wanted), None)
            if match is not None:
                out[key] = match
                del free[match]
                pending.remove(key)
    return out


@dataclass(frozen=True)
class Joined:
    """Where the parts that joined a live bus go (:func:`place_joined`)."""

    #: A joined part → its place (its predecessor's, or its own remembered one).
    placed: dict[DeviceKey, Position]
    #: Parts gone from the bus whose place a successor took: to be put aside.
    displaced: tuple[DeviceKey, ...] = ()


def place_joined(positions: Mapping[DeviceKey, Position], gone: Mapping[DeviceKey, str],
                 joined: Mapping[DeviceKey, str], *,
                 remembered: Mapping[str, Position] | None = None,
                 heights: Mapping[DeviceKey, float] | None = None,
                 width: float = 0.0) -> Joined:
    """Where parts that joined a live bus go — the rule a connect follows, applied live.

    ``positions``: the cards on screen; ``gone``: those of them no longer on the bus (key →
    part identity); ``joined``: the parts new to the view. A joined part that replaces a
    gone one (:func:`successors`) takes its card's place, and the gone card is displaced
    (the caller puts it at the bottom of its column: it is off the bus). Otherwise, the
    place the prosthesis's remembered layout gives it (``remembered``: identity →
    position of parts not on screen), if no card is there (``heights`` and ``width``: the
    cards' sizes). A part given no place here is placed as any newcomer is.
    """
    placed: dict[DeviceKey, Position] = {}
    here = {k: ident for k, ident in gone.items() if k in positions}
    taken = successors(joined, here)
    for key, old in taken.items():
        placed[key] = positions[old]
    displaced = tuple(sorted(set(taken.values())))
    rest = {k: ident for k, ident in joined.items() if k not in placed}
    if rest and remembered:
        heights = heights or {}
        cards = {k: xy for k, xy in positions.items() if k not in displaced}
        cards.update(placed)
        spots: dict[DeviceKey, Position] = {}
        for key, ident in rest.items():
            if ident in remembered:
                spots[key] = remembered[ident]
        unused = {p: p for p in remembered if p not in rest.values()}
        later = {k: i for k, i in rest.items() if k not in spots}
        for key, ident in successors(later, unused).items():
            spots[key] = remembered[ident]
        for key, xy in spots.items():
            if not any(_overlap(xy, heights.get(key, 0.0), other, heights.get(k, 0.0), width)
                       for k, other in cards.items()):
                placed[key] = cards[key] = xy
    return Joined(placed, displaced)


def swap_in(left: Mapping[DeviceKey, str], newcomers: Mapping[DeviceKey, str],
            positions: Mapping[DeviceKey, Position],
            given: Mapping[DeviceKey, Position]) -> dict[DeviceKey, Position]:
    """New positions when parts leave a live bus just *after* their replacements joined
    (a hot-swap seen in that order: the new part binds before the old one is missed).

    ``left``: the parts that left (key → identity); ``newcomers``: parts that joined
    shortly before and were placed as newcomers, at ``given``. A newcomer that replaces a
    part that left (:func:`successors`) and still stands where it was put swaps places
    with it: the new card where the old one was, the old one (off the bus) where the new
    one had been put. A newcomer the user moved meanwhile stays where it is.
    """
    still = {k: ident for k, ident in newcomers.items()
             if k in positions and positions[k] == given.get(k)}
    here = {k: ident for k, ident in left.items() if k in positions}
    out: dict[DeviceKey, Position] = {}
    for new, old in successors(still, here).items():
        out[new], out[old] = positions[old], positions[new]
    return out


def to_remember(on_bus: Mapping[str, Position], off_bus: Iterable[str],
                before: Mapping[str, Position], heights: Mapping[str, float],
                width: float, height: float = 0.0) -> dict[str, Position]:
    """What a prosthesis's layout keeps (identity → position): the parts on the bus where
    they stand; a part off the bus (unplugged, or not seen this session) at its place as
    remembered ``before``, unless a card on the bus stands there now (its replacement,
    which a connect would give that place) — never where its card was put aside, and not
    at all when never remembered: a connect shows only the parts on the bus. ``heights``:
    the cards' heights by identity (``height`` for a part not known here)."""
    out = dict(on_bus)
    for ident in off_bus:
        xy = before.get(ident)
        if xy is None or ident in out:
            continue
        if not any(_overlap(xy, heights.get(ident, height), other, heights.get(p, height),
                            width) for p, other in on_bus.items()):
            out[ident] = xy
    return out


def _overlap(a: Position, ha: float, b: Position, hb: float, width: float) -> bool:
    """Do two cards (top-left corners, heights, one width) cover some of the same ground?"""
    return (abs(a[0] - b[0]) < max(width, 1.0)
            and a[1] < b[1] + max(hb, 1.0) and b[1] < a[1] + max(ha, 1.0))


def _part_of(ident: str) -> str:
    """``vid/pid/serial`` of a part identity."""
    return ident.split("#")[0]


def _product_of(ident: str) -> str:
    """``vid/pid`` of a part identity: the product, whichever unit of it."""
    return "/".join(_part_of(ident).split("/")[:2])


# -- settings -----------------------------------------------------------------------
def _legacy_key(url: str) -> str:
    # A URL holds "/" and ":", which QSettings reads as groups: it was named by a digest.
    return f"{LEGACY_GROUP}/{hashlib.sha1(url.encode('utf-8')).hexdigest()[:16]}"


def stored_layouts(settings: QSettings | None = None) -> list[Layout]:
    """Every remembered prosthesis layout (unreadable ones are skipped and logged)."""
    settings = settings or QSettings()
    settings.beginGroup(GROUP)
    try:
        out = []
        for ident in settings.childKeys():
            try:
                out.append(Layout.from_json(ident, str(settings.value(ident))))
            except (ValueError, TypeError, KeyError, AttributeError) as err:
                log.warning("remembered layout %s ignored: %s", ident, err)
        return out
    finally:
        settings.endGroup()


def _legacy_positions(url: str, settings: QSettings) -> dict[str, Position]:
    raw = settings.value(_legacy_key(url), "") if url else ""
    if not raw:
        return {}
    try:
        return {str(k): (float(x), float(y))
                for k, (x, y) in json.loads(str(raw)).get("positions", {}).items()}
    except (ValueError, TypeError, AttributeError) as err:
        log.warning("remembered layout of %s ignored: %s", url, err)
        return {}


def remembered_elsewhere(parts: Iterable[str], on_screen: Iterable[str],
                         layouts: Iterable[Layout] | None = None) -> dict[str, Position]:
    """The remembered positions of the prosthesis made of ``parts`` for the parts that are
    not ``on_screen`` (empty when no layout is remembered for it); ``layouts``: the
    remembered layouts as read (read now when None)."""
    layout = best_layout(stored_layouts() if layouts is None else layouts, parts)
    if layout is None:
        return {}
    shown = set(on_screen)
    return {p: xy for p, xy in layout.at.items() if p not in shown}


def load(system: System, url: str = "") -> dict[DeviceKey, Position]:
    """The card positions remembered for the prosthesis ``system`` is (empty when none);
    ``url`` finds a layout an older version kept for that bus URL."""
    if not system.devices:
        return {}
    settings = QSettings()
    parts = identities(system)
    layout = best_layout(stored_layouts(settings), parts.values())
    if layout is not None:
        return positions_from(layout, parts)
    legacy = _legacy_positions(url, settings)
    if legacy:  # keyed by VID/PID/serial only
        keys = {key: part_key(key) for key in system.devices}
        old = Layout("legacy", legacy)
        if best_layout([old], keys.values()) is not None:
            return positions_from(old, keys)
    return {}


def restore(system: System, fresh: Mapping[DeviceKey, Position],
            url: str = "") -> dict[DeviceKey, Position]:
    """Positions for a newly connected prosthesis: as last laid out where remembered,
    newcomers placed around them; ``fresh`` (a new layout) when nothing is remembered."""
    remembered = load(system, url)
    if not remembered:
        return dict(fresh)
    if len(remembered) == len(system.devices):
        return remembered
    from pdcp_studio.app.graph import layout

    return layout.place(system, remembered)


def save(system: System, positions: Mapping[Any, Position], url: str = "") -> None:
    """Remember ``positions`` for the prosthesis ``system`` is (QSettings writes safely):
    over the layout it matched, else as a new one."""
    parts = identities(system)
    settings = QSettings()
    layout = best_layout(stored_layouts(settings), parts.values())
    from pdcp_studio.app.graph.layout import card_height
    from pdcp_studio.app.graph.style import CARD_WIDTH

    devices = system.devices
    before = layout.at if layout is not None else {}
    shown = set(parts.values())
    off_bus = [parts[k] for k, d in devices.items() if not d.present]
    off_bus += [p for p in before if p not in shown]  # not seen this session
    at = to_remember({parts[k]: (float(x), float(y)) for k, (x, y) in positions.items()
                      if k in devices and devices[k].present},
                     off_bus, before,
                     {parts[k]: card_height(d) for k, d in devices.items()}, CARD_WIDTH,
                     card_height(Device(0, 0, 0)))
    if not at:
        return
    if layout is None:
        digest = hashlib.sha1(",".join(sorted(parts.values())).encode("utf-8")).hexdigest()
        ident = digest[:16]
    else:
        ident = layout.ident
    settings.setValue(f"{GROUP}/{ident}", Layout(ident, at, time.time()).to_json())
    if url:
        settings.remove(_legacy_key(url))
    _forget_oldest(settings)


def _forget_oldest(settings: QSettings) -> None:
    layouts = stored_layouts(settings)
    if len(layouts) <= MAX_LAYOUTS:
        return
    for lay in sorted(layouts, key=lambda lay: lay.saved)[:len(layouts) - MAX_LAYOUTS]:
        settings.remove(f"{GROUP}/{lay.ident}")
