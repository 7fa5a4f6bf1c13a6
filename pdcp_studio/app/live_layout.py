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
  through its part swaps.

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
from typing import Any

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
    pending = []
    for key, ident in parts.items():
        if ident in layout.at:
            out[key] = layout.at[ident]
        else:
            pending.append(key)
    # the same part with other channels first, then another part of the same product
    for same in (_part_of, _product_of):
        for key in list(pending):
            wanted = same(parts[key])
            match = next((p for p in sorted(unused) if same(p) == wanted), None)
            if match is not None:
                out[key] = unused.pop(match)
                pending.remove(key)
    return out


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
    at = {parts[k]: (float(x), float(y)) for k, (x, y) in positions.items() if k in parts}
    if not at:
        return
    settings = QSettings()
    layout = best_layout(stored_layouts(settings), parts.values())
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
