"""The device catalogue: shipped for every simulated device, user files, clear errors."""

from __future__ import annotations

import json

import pytest

from pdcp_studio import paths
from pdcp_studio.bus.sim import rigs as simulator
from pdcp_studio.model.catalog import (
    Catalog,
    CatalogError,
    load_catalog,
    parse_catalog,
    unknown_device_label,
)
from pdcp_studio.model.device_names import DeviceCatalogue
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Device
from pdcp_studio.storage import system_file


def _shipped() -> Catalog:
    catalog, problems = load_catalog([paths.catalogs_dir()])
    assert problems == []
    return catalog


def test_every_simulated_device_is_in_the_shipped_catalogue():
    catalog = _shipped()
    systems = [system_file.load_path(p) for p in paths.systems_dir().glob("*.json")]
    systems.append(simulator.large_system())
    keys = {k for s in systems for k in s.devices}
    assert len(keys) > 30
    for key in keys:
        entry = catalog.lookup(key.vid, key.pid)
        assert entry is not None, key
        assert entry.vendor and entry.product and entry.kind and entry.icon


def test_label_prefers_the_device_name_then_product_then_unknown():
    catalog = _shipped()
    hand = DeviceKey(2641, 769, 301)
    assert catalog.label(hand, "My hand") == "My hand"
    assert catalog.label(hand) == "Multi-grip hand (serial 301)"
    odd = DeviceKey(9999, 1, 7)
    assert catalog.label(odd) == unknown_device_label(odd) == "unknown device (9999/1/7)"
    assert catalog.device_label(Device(2641, 257, 5)) == "EMG sensor (serial 5)"
    assert catalog.device_label(Device(2641, 257, 5, name="Flexor")) == "Flexor"


def test_user_catalogue_adds_and_overrides(tmp_path):
    user = tmp_path / "catalogs"
    user.mkdir()
    (user / "acme.json").write_text(json.dumps({
        "format": "pdcp-catalog/1", "vendor": "Acme",
        "products": [{"vid": "0x0A51", "pid": 769, "product": "Acme hand", "kind": "hand"},
                     {"vid": 77, "pid": 1, "product": "Wrist rotator", "kind": "wrist"}]}))
    (user / "broken.json").write_text("{not json")
    catalog, problems = load_catalog([paths.catalogs_dir(), user])
    assert catalog.lookup(2641, 769).product == "Acme hand"
    assert catalog.lookup(2641, 769).vendor == "Acme"
    assert catalog.lookup(77, 1).kind == "wrist"
    assert catalog.lookup(2641, 513).product == "Control unit"  # shipped entry kept
    (problem,) = problems
    assert "broken.json" in problem and "not JSON" in problem


@pytest.mark.parametrize("doc, words", [
    ({"format": "other"}, "not a device catalogue"),
    ({"format": "pdcp-catalog/1", "products": {}}, "must be a list"),
    ({"format": "pdcp-catalog/1", "products": [{"vid": 1, "pid": 2}]}, "product 1: has no"),
    ({"format": "pdcp-catalog/1", "products": [{"vid": 70000, "pid": 2, "product": "x"}]},
     "vid 70000 is outside"),
    ({"format": "pdcp-catalog/1", "products": [{"vid": "zz", "pid": 2, "product": "x"}]},
     "vid 'zz' is not a number"),
])
def test_bad_catalogue_names_file_and_entry(doc, words):
    with pytest.raises(CatalogError) as err:
        parse_catalog(json.dumps(doc), "vendor.json")
    assert str(err.value).startswith("vendor.json") and words in str(err.value)


def test_configuration_names_fall_back_on_the_catalogue():
    seen = DeviceCatalogue.from_names({DeviceKey(2641, 513, 201): "Control unit"})
    names = seen.with_catalog(_shipped())
    assert names.label(DeviceKey(2641, 513, 201)) == "Control unit"
    assert names.label(DeviceKey(2641, 769, 301)) == "Multi-grip hand (serial 301)"
    assert names.label(DeviceKey(2641, 770, 302)) == "Electric hook (serial 302)"
    assert names.label(DeviceKey(2641, 999, 302)) == "unknown device (2641/999/302)"
    assert seen.label(DeviceKey(2641, 769, 301)) == "unknown device (2641/769/301)"


def test_a_fifo_among_the_users_catalogues_is_skipped_never_opened(tmp_path):
    """A named pipe called ``*.json`` would hang every start-up (issue 28)."""
    import contextlib
    import os
    import threading
    import time

    user = tmp_path / "catalogs"
    user.mkdir()
    os.mkfifo(user / "pipe.json")

    def rescue() -> None:  # a reader that waits on the pipe is let go: the test fails, not hangs
        with contextlib.suppress(OSError):
            os.close(os.open(user / "pipe.json", os.O_WRONLY | os.O_NONBLOCK))

    timer = threading.Timer(5.0, rescue)
    timer.start()
    started = time.monotonic()
    try:
        _, problems = load_catalog([paths.catalogs_dir(), user])
    finally:
        timer.cancel()
    assert time.monotonic() - started < 1.0
    assert problems == [f"{user / 'pipe.json'}: cannot be read (not a regular file)"]


def test_the_users_data_folder_follows_its_environment_though_looked_up_once(monkeypatch,
                                                                             tmp_path):
    """user_data_dir is cached (start-up asks ~30 times), per value of what platformdirs
    reads: a changed XDG_DATA_HOME (a test's, a user's) is a new folder."""
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "one"))
    first = paths.user_data_dir()
    assert paths.user_data_dir() is first  # looked up once
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "two"))
    assert paths.user_data_dir().parent == tmp_path / "two"
    assert paths.user_catalogs_dir() == tmp_path / "two" / "pdcp-studio" / "catalogs"
