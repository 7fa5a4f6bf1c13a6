"""The device catalogue: what a VID/PID pair is (vendor, product, kind, icon). Pure.

A device on the bus tells its VID, PID and serial number and sometimes a name of its own;
the catalogue says what product that is, as the device catalogues of ETS and CANopen's EDS
files do. One catalogue file (``pdcp-catalog/1`` JSON) is shipped for every simulated
device under ``resources/catalog/``; users drop their vendors' files into
``paths.user_catalogs_dir()``, read after the shipped ones so a vendor's entry wins.
A device no catalogue knows is shown as ``unknown device (VID/PID/serial)``: never an
invented name.
"""

from __future__ import annotations

import json
import logging
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from pdcp_studio.model.refs import DeviceKey

if TYPE_CHECKING:
    from pdcp_studio.model.system import Device

FORMAT = "pdcp-catalog/1"
log = logging.getLogger(__name__)


class CatalogError(ValueError):
    """A catalogue file that cannot be read; the message names the file and the entry."""


@dataclass(frozen=True)
class CatalogEntry:
    """One product: who makes it, what it is called and what kind of part it is."""

    vid: int
    pid: int
    vendor: str
    product: str
    kind: str = ""
    icon: str = ""

    @property
    def label(self) -> str:
        return self.product


def unknown_device_label(key: DeviceKey) -> str:
    """``unknown device (2641/257/101)``: VID/PID/serial of a device no catalogue knows."""
    return f"unknown device ({key.vid}/{key.pid}/{key.serial})"


@dataclass
class Catalog:
    """Products by (VID, PID); later additions replace earlier ones."""

    entries: dict[tuple[int, int], CatalogEntry] = field(default_factory=dict)

    def lookup(self, vid: int, pid: int) -> CatalogEntry | None:
        return self.entries.get((vid, pid))

    def product_name(self, key: DeviceKey) -> str | None:
        entry = self.lookup(key.vid, key.pid)
        return entry.product if entry else None

    def label(self, key: DeviceKey, own_name: str = "") -> str:
        """The device's own name if it has one, else the product with its serial number
        (two sensors of one product stay apart), else "unknown device (VID/PID/serial)"."""
        own = own_name.strip()
        if own:
            return own
        product = self.product_name(key)
        return f"{product} (serial {key.serial})" if product else unknown_device_label(key)

    def device_label(self, device: Device) -> str:
        """A device's name to show: its own name or descriptor, else the catalogue's."""
        return self.label(device.key, device.name or device.descriptor or "")

    def own_name(self, device: Device) -> str:
        """What a part is called before any serial number is added: the one rule of
        ``model/names.py`` (own name, descriptor, product, ``unknown device (…)``)."""
        from pdcp_studio.model.names import own_name

        return own_name(device, self)

    def part_names(self, devices: Iterable[Device],
                   twin: str = "{name} (serial {serial})") -> dict[DeviceKey, str]:
        """One name per part (``model/names.py``); the serial number (``twin``) only where
        two of ``devices`` would otherwise read the same."""
        from pdcp_studio.model.names import parts_named

        return parts_named(devices, self, twin)

    def add(self, entries: Iterable[CatalogEntry]) -> Catalog:
        merged = dict(self.entries)
        merged.update({(e.vid, e.pid): e for e in entries})
        return Catalog(merged)


def _int(value: object, where: str, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int | str):
        raise CatalogError(f"{where}: {name} must be a number, not {value!r}")
    try:
        number = int(value, 0) if isinstance(value, str) else value
    except ValueError:
        raise CatalogError(f"{where}: {name} {value!r} is not a number") from None
    if not 0 <= number <= 0xFFFF:
        raise CatalogError(f"{where}: {name} {number} is outside 0…65535")
    return number


def parse_catalog(text: str, source: str) -> list[CatalogEntry]:
    """The entries of one catalogue file's text; ``source`` names the file in errors."""
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise CatalogError(f"{source}: not JSON ({exc.msg}, line {exc.lineno})") from None
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise CatalogError(f"{source}: not a device catalogue (expected format {FORMAT!r})")
    vendor = str(doc.get("vendor", "")).strip()
    products = doc.get("products")
    if not isinstance(products, list):
        raise CatalogError(f"{source}: 'products' must be a list")
    entries = []
    for i, item in enumerate(products):
        where = f"{source}, product {i + 1}"
        if not isinstance(item, dict):
            raise CatalogError(f"{where}: must be an object")
        product = str(item.get("product", "")).strip()
        if not product:
            raise CatalogError(f"{where}: has no product name")
        entries.append(CatalogEntry(
            _int(item.get("vid"), where, "vid"), _int(item.get("pid"), where, "pid"),
            str(item.get("vendor", vendor)).strip(), product,
            str(item.get("kind", "")).strip(), str(item.get("icon", "")).strip()))
    return entries


def load_catalog(folders: Iterable[Path]) -> tuple[Catalog, list[str]]:
    """Every ``*.json`` in ``folders`` (in order, files sorted by name) merged into one
    catalogue, and the problems of the files that could not be read (those are skipped)."""
    catalog = Catalog()
    problems: list[str] = []
    for folder in folders:
        if not folder.is_dir():
            continue
        for path in sorted(folder.glob("*.json")):
            if not path.is_file():  # a FIFO or a device would be waited on: never opened
                problems.append(f"{path}: cannot be read (not a regular file)")
                continue
            try:
                catalog = catalog.add(parse_catalog(path.read_text(encoding="utf-8"),
                                                    str(path)))
            except (OSError, UnicodeDecodeError) as exc:
                problems.append(f"{path}: cannot be read ({exc})")
            except CatalogError as exc:
                problems.append(str(exc))
    return catalog, problems


def default_catalog() -> Catalog:
    """The shipped catalogues followed by the user's (a user's broken file is skipped, and
    said: :func:`default_catalog_problems`, the log)."""
    from pdcp_studio import paths

    return _default_catalog_cached(paths.catalogs_dir(), paths.user_catalogs_dir())[0]


def default_catalog_problems() -> list[str]:
    """Which catalogue files :func:`default_catalog` skipped and why (file, entry, reason),
    for the app's warning and ``pdcp-studio doctor``."""
    from pdcp_studio import paths

    return list(_default_catalog_cached(paths.catalogs_dir(), paths.user_catalogs_dir())[1])


_CACHE: dict[tuple[Path, Path], tuple[Catalog, list[str]]] = {}


def _default_catalog_cached(shipped: Path, user: Path) -> tuple[Catalog, list[str]]:
    key = (shipped, user)
    if key not in _CACHE:
        catalog, problems = load_catalog((shipped, user))
        for problem in problems:
            log.warning("device catalogue skipped: %s", problem)
        _CACHE[key] = (catalog, problems)
    return _CACHE[key]


def reload_default_catalog() -> None:
    """Forget the cached default catalogue (after the user adds a file)."""
    _CACHE.clear()
