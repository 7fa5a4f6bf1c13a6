"""Opening and saving what the app shows: system files and stored configurations. No Qt.

A system file (``pdcp-system/1``) is saved with one extra top-level field the contract
allows, ``"x-pdcp-studio": {"positions": …}``, so card positions survive a reopen. A
stored configuration (``.pdcfg``) has no devices of its own: opening one shows a system
built from the channel records of its first configuration (every device present), and
keeps the whole collection for the plans that take a configuration.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

from pdcp_studio.errors import ModelError
from pdcp_studio.model.configuration import ConfigCollection, StoredChannel
from pdcp_studio.model.refs import DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link, System

CONFIG_SUFFIXES = (".pdcfg",)
EXTRA_KEY = "x-pdcp-studio"

Position = tuple[float, float]


@dataclass
class Opened:
    """What a file gave: the system to show, and what kind of file it was."""

    system: System
    kind: str  # "system" or "config"
    config: ConfigCollection | None = None
    positions: dict[DeviceKey, Position] = field(default_factory=dict)
    note: str = ""


def is_config_path(path: str | Path) -> bool:
    return Path(path).suffix.lower() in CONFIG_SUFFIXES


def system_from_configuration(collection: ConfigCollection, which: int = 0
                              ) -> tuple[System, list[str]]:
    """Devices and links named by one configuration (channel type and profile as stored).

    A stored link whose ends cannot both exist (the same channel used as an output and
    an input) is left out and named in the returned list, so the rest can still be seen.
    """
    system = System()
    skipped: list[str] = []
    if not collection.configurations:
        return system, skipped
    cfg = collection.configurations[which]

    def channel(end: StoredChannel, direction: Direction) -> None:
        key = DeviceKey(end.vid, end.pid, end.serial)
        device = system.device(key)
        if device is None:
            device = system.add_device(Device(end.vid, end.pid, end.serial))
        if end.index not in device.channels:
            device.add_channel(Channel(end.index, direction, type=end.type,
                                       profile=end.profile))

    for link in cfg.links:
        channel(link.output, Direction.OUTPUT)
        channel(link.input, Direction.INPUT)
    for link in cfg.links:
        lk = Link(link.output.ref, link.input.ref)
        try:
            system.add_link(lk, check=False)
        except ModelError as err:  # a channel used as both an input and an output
            skipped.append(f"link {link.index}: {err}")
    return system, skipped


def _positions(doc: object) -> dict[DeviceKey, Position]:
    out: dict[DeviceKey, Position] = {}
    extra = doc.get(EXTRA_KEY) if isinstance(doc, dict) else None
    items = extra.get("positions") if isinstance(extra, dict) else None
    for item in items if isinstance(items, list) else ():
        try:
            key = DeviceKey(int(item["vid"]), int(item["pid"]), int(item["serial"]))
            out[key] = (float(item["x"]), float(item["y"]))
        except (KeyError, TypeError, ValueError):
            continue  # positions are a convenience: a bad one is dropped, not fatal
    return out


def open_path(path: str | Path) -> Opened:
    """Load a system file or a stored configuration; SystemFileError / ConfigFormatError."""
    path = Path(path)
    if is_config_path(path):
        from pdcp_studio.app.documents.config_document import load_config_file

        collection = load_config_file(path)  # a bad file's error names it
        system, skipped = system_from_configuration(collection)
        n = len(collection.configurations)
        notes = [f"{n} configurations; showing configuration 1"] if n > 1 else []
        if skipped:
            from pdcp_studio.app.words.plural import count

            notes.append(count("OpenFile", "%n link(s) left out: ", len(skipped))
                         + "; ".join(skipped))
        note = "; ".join(notes)
        return Opened(system, "config", collection, note=note)
    from pdcp_studio.storage import system_file

    # Read once, within the system file's limits; the card positions come from the same bytes.
    data = system_file.read_path(path)
    system = system_file.loads(data, str(path))
    try:
        positions = _positions(json.loads(data))
    except ValueError:
        positions = {}
    return Opened(system, "system", None, positions)


def system_text(system: System, positions: dict[DeviceKey, Position] | None = None) -> str:
    """The ``pdcp-system/1`` JSON text, with card positions as an extra field."""
    from pdcp_studio.storage import system_file

    doc = system_file.to_json(system)
    if positions:
        doc[EXTRA_KEY] = {"positions": [
            {"vid": k.vid, "pid": k.pid, "serial": k.serial, "x": round(x, 1), "y": round(y, 1)}
            for k, (x, y) in positions.items() if k in system.devices]}
    return json.dumps(doc, indent=2) + "\n"


def loads_system(text: str, name: str) -> Opened:
    """A system (and its card positions) from text, e.g. an autosaved recovery entry."""
    from pdcp_studio.storage import system_file

    system = system_file.loads(text, name)
    return Opened(system, "system", None, _positions(json.loads(text)))


def save_system(system: System, path: str | Path,
                positions: dict[DeviceKey, Position] | None = None) -> None:
    """Write a ``pdcp-system/1`` file atomically, with card positions as an extra field."""
    from pdcp_studio.storage.atomic import atomic_write_text

    atomic_write_text(path, system_text(system, positions))


def save_configuration(system: System, path: str | Path) -> None:
    """Write the system's links as a one-configuration ``.pdcfg`` (atomic)."""
    from pdcp_studio.engine import configuration_from_system
    from pdcp_studio.storage import config_codec

    config_codec.save_path(ConfigCollection([configuration_from_system(system)]), path)
