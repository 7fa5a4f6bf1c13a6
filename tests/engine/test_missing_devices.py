"""Devices a stored configuration names and the bus lacks are shown as missing."""

from __future__ import annotations

from pdcp_studio.engine import configuration_from_system
from pdcp_studio.engine.procedures import missing_devices
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import DeviceKey, Direction
from pdcp_studio.storage import system_file


def test_a_device_the_configuration_names_and_the_bus_lacks_is_missing(systems_dir):
    full = system_file.load_path(systems_dir / "appendix-d.json")
    stored = ConfigCollection([configuration_from_system(full)])
    bus = full.copy()
    bus.remove_device(DeviceKey(2, 2, 6))
    (device,) = missing_devices(bus, stored)
    assert device.key == DeviceKey(2, 2, 6) and not device.present
    assert {i: (c.direction, c.type, c.profile) for i, c in device.channels.items()} == {
        1: (Direction.INPUT, 0x5300, 0x1110), 2: (Direction.INPUT, 0x7300, 0x1220)}


def test_nothing_is_missing_when_every_device_is_there_or_nothing_is_stored(systems_dir):
    full = system_file.load_path(systems_dir / "appendix-d.json")
    assert missing_devices(full, ConfigCollection([configuration_from_system(full)])) == []
    assert missing_devices(full, None) == []
    assert missing_devices(full, ConfigCollection([])) == []
