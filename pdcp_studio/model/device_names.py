"""Names for the devices a stored configuration mentions. Pure.

A stored configuration holds only a device's VID, PID and serial number, never its name.
This lookup names a device from a catalogue where one is known and otherwise says plainly
that it is unknown, with the numbers that identify it: never an invented name. A catalogue
is built from what PDCP Studio has seen (an open system file or the live bus, whose
devices carry their own names and descriptors) and falls back on the product names of
the device catalogue (:mod:`pdcp_studio.model.catalog`, ``with_catalog``).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

from pdcp_studio.model.catalog import Catalog, unknown_device_label
from pdcp_studio.model.refs import DeviceKey


def unknown_device_name(key: DeviceKey) -> str:
    """``unknown device (2641/257/101)``: VID/PID/serial of a device no catalogue knows."""
    return unknown_device_label(key)


@dataclass
class DeviceCatalogue:
    """Known names: of one device (VID, PID, serial) or of a product (VID, PID)."""

    devices: dict[DeviceKey, str] = field(default_factory=dict)
    products: dict[tuple[int, int], str] = field(default_factory=dict)
    #: The device catalogue asked last, for a product no open system names.
    catalog: Catalog | None = None

    def name(self, key: DeviceKey) -> str | None:
        """The best known name of ``key``, or None."""
        exact = self.devices.get(key)
        if exact:
            return exact
        return self.products.get((key.vid, key.pid)) or None

    def label(self, key: DeviceKey) -> str:
        """A name to show: the catalogue's, else ``unknown device (VID/PID/serial)``."""
        name = self.name(key)
        if name:
            return name
        return self.catalog.label(key) if self.catalog else unknown_device_name(key)

    def merge(self, other: DeviceCatalogue) -> DeviceCatalogue:
        """A catalogue with ``other``'s names added where this one has none."""
        return DeviceCatalogue({**other.devices, **self.devices},
                               {**other.products, **self.products},
                               self.catalog or other.catalog)

    @classmethod
    def from_names(cls, names: Mapping[DeviceKey, str] | Iterable[tuple[DeviceKey, str]]
                   ) -> DeviceCatalogue:
        """Devices by key; a product takes the name its devices agree on."""
        items = list(names.items() if isinstance(names, Mapping) else names)
        devices = {key: name for key, name in items if name}
        by_product: dict[tuple[int, int], set[str]] = {}
        for key, name in devices.items():
            by_product.setdefault((key.vid, key.pid), set()).add(name)
        products = {vp: next(iter(ns)) for vp, ns in by_product.items() if len(ns) == 1}
        return cls(devices, products)

    def with_catalog(self, catalog: Catalog) -> DeviceCatalogue:
        """This lookup falling back on a device catalogue (``model/catalog.py``)."""
        return DeviceCatalogue(self.devices, self.products, catalog)

    @classmethod
    def from_system(cls, system: object) -> DeviceCatalogue:
        """The names an open system (a file or the live bus) gives its devices: their one
        names (``model/names.py``), a serial number where two would read alike."""
        from pdcp_studio.model.names import parts_named

        devices = [d for d in getattr(system, "devices", {}).values()
                   if (getattr(d, "name", "") or getattr(d, "descriptor", "") or "").strip()]
        return cls.from_names(parts_named(devices, Catalog()))
