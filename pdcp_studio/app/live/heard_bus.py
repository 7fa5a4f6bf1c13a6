"""The parts and links a listen-only monitor can prove from what it hears (issue 27 item 1).

Listening to a bus another arbitrator runs, PDCP Studio reads no descriptor and asks no
device anything: it has only the traffic. The decoder learns from it (``bus.trace``'s
``BusKnowledge`` and ``TrafficLearner``): devices that bind (their identity) or beacon
(only their node ID), output channels set up in its hearing (their device and index) or
inferred from periodic data (only their node ID), and inputs whose Source's Node Ids were
written in its hearing. ``heard_system`` turns that into a ``System`` to show — nothing
more than the traffic proves:

- a device known only by its beacons is a part "at node N" (VID and PID 0, serial N);
- an output known only by its data is the one output of a part "channel node N" (its own
  part unknown: VID and PID 0, serial 0x10000 + N, so it never meets a device's key);
- a link is drawn only where an input's Source's Node Ids named the output's node.

The listening thread builds it (Qt's translate is safe there).
"""

from __future__ import annotations

from typing import Any

from pdcp_studio.app.i18n import translate
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link, System

#: Serial numbers of the parts that stand for an output whose device was not heard.
_CHANNEL_PART = 0x10000


def device_key(node: int) -> DeviceKey:
    """The stand-in identity of a device heard only by its node ID."""
    return DeviceKey(0, 0, node)


def channel_part_key(node: int) -> DeviceKey:
    """The stand-in identity of the part behind an output heard only by its data."""
    return DeviceKey(0, 0, _CHANNEL_PART + node)


def heard_system(decoder: Any) -> System:
    """What ``decoder`` (a ``FrameDecoder`` that listened) proves about the bus."""
    from pdcp_studio.bus.trace.knowledge import INFERRED

    known = decoder.known
    learner = decoder.learner
    system = System()

    def device(node: int) -> Device:
        key = known.devices.get(node) or device_key(node)
        found = system.device(key)
        if found is None:
            name = "" if node in known.devices else translate(
                "HeardBus", "Device at node {node}").format(node=node)
            found = system.add_device(Device(key.vid, key.pid, key.serial, name=name,
                                             node_id=node))
        return found

    heard = set(known.devices) | set(decoder.heard) | (learner.devices if learner else set())
    for node in sorted(heard - set(known.outputs)):
        device(node)
    outputs: dict[int, ChannelRef] = {}
    for node, (owner, index) in sorted(known.outputs.items()):
        if (owner, index) == INFERRED:
            key = channel_part_key(node)
            part = system.add_device(Device(key.vid, key.pid, key.serial, name=translate(
                "HeardBus", "Channel node {node}").format(node=node)))
            index = 1
        else:
            part = device(owner)
        if index not in part.channels:
            part.add_channel(Channel(index, Direction.OUTPUT, node_id=node,
                                     data_enabled=True))
        outputs[node] = part.ref(index)
    for node, listeners in sorted(known.inputs.items()):
        source = outputs.get(node)
        for owner, index in sorted(listeners):
            part = device(owner)
            if index not in part.channels:
                part.add_channel(Channel(index, Direction.INPUT))
            if source is not None:
                system.add_link(Link(source, part.ref(index)), check=False)
    return system


def signature(system: System) -> tuple[Any, ...]:
    """What ``system`` shows (parts, their channels, links): equal when nothing changed."""
    return (tuple((key, tuple(sorted((c.index, c.direction.value, c.node_id)
                                     for c in d.channels.values())))
                  for key, d in sorted(system.devices.items())), tuple(system.links))
