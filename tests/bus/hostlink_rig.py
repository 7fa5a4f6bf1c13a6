"""A real arbitrator with simulated devices, serving host link 2 on a pseudo-terminal."""

from __future__ import annotations

import time
from contextlib import contextmanager

import can

from pdcp_studio.bus.arbitrator.core import Arbitrator
from pdcp_studio.bus.hostlink.server import HostLinkServer
from pdcp_studio.bus.session.urls import unique_virtual_channel
from pdcp_studio.bus.sim.device import SimulatedDevice
from pdcp_studio.bus.sim.device_host import DeviceHost
from pdcp_studio.storage import system_file


def wait_for(predicate, timeout: float = 5.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(0.02)
    return predicate()


@contextmanager
def arbitrator_rig(system_path, memory, *, profile_layer: bool = False, **options):
    """(arbitrator, server): the devices of ``system_path`` bound and set up (``options``:
    more of the arbitrator's, e.g. ``take_back``)."""
    with arbitrator_rig_with_devices(system_path, memory, profile_layer=profile_layer,
                                     **options) as (arbitrator, server, _):
        yield arbitrator, server


@contextmanager
def arbitrator_rig_with_devices(system_path, memory, *, profile_layer: bool = False,
                                **options):
    """(arbitrator, server, device host): as :func:`arbitrator_rig`, with the simulated
    devices' host (to unplug one)."""
    system = system_file.load_path(system_path)
    channel = unique_virtual_channel("hostlink")
    arb_bus = can.Bus(interface="virtual", channel=channel)
    dev_bus = can.Bus(interface="virtual", channel=channel)
    host = DeviceHost(dev_bus, [SimulatedDevice(d) for d in system.devices.values()])
    arbitrator = Arbitrator(arb_bus, memory=memory, profile_layer=profile_layer,
                            frame_events=True, startup_quiet_s=0.2, **options)
    server = None
    try:
        assert wait_for(lambda: len(arbitrator.system().devices) == len(system.devices), 10.0)
        assert arbitrator.wait_settled(10.0)
        server = HostLinkServer(arbitrator, "pty")
        yield arbitrator, server, host
    finally:
        if server is not None:
            server.close()
        arbitrator.close()
        host.close()
        for bus in (arb_bus, dev_bus):
            bus.shutdown()
