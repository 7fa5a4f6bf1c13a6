"""The live merge and what may be staged, without Qt: the project follows the prosthesis
except where the user staged a change (issue 23: logic out of Qt objects)."""

from __future__ import annotations

import subprocess
import sys

from pdcp_studio.app.documents.live_sync import (
    merge_snapshot,
    same_system,
    staging_refusal,
)
from pdcp_studio.model.refs import ChannelRef, Direction
from pdcp_studio.model.system import Channel, Device, Link, System

SENSOR, HAND = Device(10, 1, 1).key, Device(10, 3, 1).key
OUT, IN = ChannelRef(*SENSOR, 1), ChannelRef(*HAND, 1)


def _system(linked: bool = True) -> System:
    sensor = Device(10, 1, 1, name="EMG sensor")
    sensor.add_channel(Channel(1, Direction.OUTPUT, type=0x9000, profile=0x4222))
    sensor.add_channel(Channel(2, Direction.OUTPUT, type=0x9000, profile=0x4224))
    hand = Device(10, 3, 1, name="Hand")
    hand.add_channel(Channel(1, Direction.INPUT, type=0x9300, profile=0x4222))
    return System([sensor, hand], [Link(OUT, IN)] if linked else [])


def test_the_same_bus_again_changes_nothing():
    project, seen = _system(), _system()
    result = merge_snapshot(project, seen, _system())
    assert result.same_bus and result.unchanged
    assert same_system(project, _system())


def test_what_the_bus_owns_follows_it_and_the_device_objects_stay():
    project, seen = _system(), _system()
    hand = project.devices[HAND]
    snapshot = _system()
    snapshot.devices[HAND].fw_version = 7
    snapshot.devices[HAND].node_id = 12
    result = merge_snapshot(project, seen, snapshot)
    assert not result.unchanged and result.changed_devices == [HAND]
    assert project.devices[HAND] is hand and hand.fw_version == 7 and hand.node_id == 12


def test_a_staged_field_is_kept_and_an_unstaged_one_follows_the_bus():
    project, seen = _system(), _system()
    project.devices[HAND].descriptor = "left hand"  # staged here
    snapshot = _system()
    snapshot.devices[HAND].descriptor = "from the bus"
    snapshot.devices[HAND].beacon_interval = 250  # changed on the bus only
    merge_snapshot(project, seen, snapshot)
    assert project.devices[HAND].descriptor == "left hand"
    assert project.devices[HAND].beacon_interval == 250


def test_staged_links_are_kept_and_the_bus_links_follow():
    seen = _system(linked=False)
    project = _system(linked=False)
    staged = Link(ChannelRef(*SENSOR, 2), IN)
    project.add_link(staged, check=False)  # staged here
    snapshot = _system(linked=False)
    snapshot.add_link(Link(OUT, IN), check=False)  # made on the bus meanwhile
    result = merge_snapshot(project, seen, snapshot)
    assert set(result.links) == {staged, Link(OUT, IN)} and result.links_changed
    assert set(project.links) == {staged}  # the links are the caller's to set


def test_a_link_removed_here_stays_removed():
    seen, project = _system(), _system()
    project.remove_link(Link(OUT, IN))
    result = merge_snapshot(project, seen, _system())
    assert result.links == [] and not result.links_changed


def test_a_device_the_bus_lacks_stays_marked_missing_and_a_new_one_is_added():
    project, seen = _system(), _system()
    snapshot = _system()
    del snapshot.devices[SENSOR]
    result = merge_snapshot(project, seen, snapshot)
    assert SENSOR in project.devices and not project.devices[SENSOR].present
    assert SENSOR in result.changed_devices and not result.added
    again = merge_snapshot(project, snapshot, _system())
    assert project.devices[SENSOR].present and SENSOR in again.changed_devices
    fresh = System()
    assert merge_snapshot(fresh, None, _system()).added and set(fresh.devices) == {SENSOR, HAND}


def test_what_may_be_staged_on_a_live_bus():
    assert staging_refusal("descriptor", device=True) is None
    assert staging_refusal("profile", device=False) is None
    assert "arbitrator" in (staging_refusal("node_id", device=False) or "")
    assert staging_refusal("fw_version", device=True) == "fw version cannot be written to a live device"


def test_the_merge_imports_no_qt():
    code = ("import sys, pdcp_studio.app.documents.live_sync, pdcp_studio.app.graph.link_drop;"
            "print('PySide6' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "False"
