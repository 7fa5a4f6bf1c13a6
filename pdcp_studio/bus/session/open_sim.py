"""Opening a ``sim:`` bus: a built-in prosthesis on an in-process virtual bus.

PDCP Studio's arbitrator and a DeviceHost with the prosthesis's devices, each on its own bus
object, talk in frames as on a real bus; ``open_sim_session`` returns once the devices are
bound and start-up has linked them.
"""

from __future__ import annotations

import time
from typing import Any

from pdcp_studio.bus.session.in_process import arbitrator_options
from pdcp_studio.bus.session.sim import SIM_SETTLE_TIMEOUT_S, SimSession
from pdcp_studio.bus.session.urls import BusSpec
from pdcp_studio.errors import TransportError

#: Start-up waits this long without bind requests on a simulated bus (binding is in-process).
SIM_STARTUP_QUIET_S = 0.2

__all__ = ["SIM_STARTUP_QUIET_S", "open_sim_session", "open_sim_url"]


def open_sim_url(spec: BusSpec, **options: Any) -> SimSession:
    """Open a parsed ``sim:NAME`` URL (the opener the URL table names)."""
    return open_sim_session(spec.name, url=spec.url, **options)


def open_sim_session(name: str, *, url: str = "", settle_timeout: float = SIM_SETTLE_TIMEOUT_S,
                     data_rate_hz: float | None = None, channel: str | None = None,
                     **options: Any) -> SimSession:
    """A built-in prosthesis (or a system file) on a new in-process virtual bus."""
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.bus.connection import virtual_channel_in_use
    from pdcp_studio.bus.session.urls import open_can_bus, unique_virtual_channel
    from pdcp_studio.bus.sim.device import SimulatedDevice
    from pdcp_studio.bus.sim.device_host import DeviceHost
    from pdcp_studio.bus.sim.rigs import resolve_prosthesis

    entry = resolve_prosthesis(name)
    system = entry.load()
    if data_rate_hz is None:
        data_rate_hz = entry.data_rate_hz
    arb_opts = arbitrator_options(options)
    arb_opts.setdefault("startup_quiet_s", SIM_STARTUP_QUIET_S)
    arb_opts.setdefault("frame_events", True)
    channel = channel or unique_virtual_channel(f"pdcp-sim-{entry.name}")
    url = url or f"sim:{name}"
    # On a channel of its own, both parts take their frames straight from the virtual bus
    # (Connection ``direct``: no Notifier threads; the devices answer on the sender's thread).
    # Each attaches while the channel is quiet: the devices first, all unplugged, then the
    # arbitrator, and only then are the devices plugged in. A channel others already use
    # (a caller's ``channel``) is read with Notifiers, as any bus.
    direct = not virtual_channel_in_use(channel)
    kwargs = {} if data_rate_hz is None else {"data_rate_hz": data_rate_hz}
    devices = [SimulatedDevice(d, **kwargs) for d in system.copy().devices.values()]
    host = DeviceHost(open_can_bus("virtual", channel, url=url), devices,
                      name=f"{url} devices", plugged=False, direct=direct)
    arbitrator = None
    try:
        arbitrator = Arbitrator(open_can_bus("virtual", channel, url=url),
                                name=f"{url} arbitrator", direct=direct, **arb_opts)
        # The simulated parts are known: start-up need not wait out the quiet time after them.
        arbitrator.profile.expect({key for key, dev in system.devices.items() if dev.present})
        for dev in system.devices.values():
            if dev.present:
                host.plug(dev.key)
        session = SimSession(arbitrator, host, entry, system, url=url,
                             data_rate_hz=data_rate_hz, **options)
    except BaseException:
        if arbitrator is not None:
            arbitrator.close()
        host.close()
        raise
    # Settled means every device that is plugged in has joined (on a starved machine a
    # device's first bind request can come after the start-up quiet time) and start-up ran.
    expected = {key for key, dev in system.devices.items() if dev.present}
    deadline = time.monotonic() + settle_timeout
    while True:
        settled = session.wait_settled(max(0.0, deadline - time.monotonic()))
        joined = expected <= set(arbitrator.devices_present())
        if settled and joined:
            return session
        if time.monotonic() >= deadline:
            if settled:  # a device that cannot join (IDs exhausted…) is the bus's news
                return session
            session.close()
            raise TransportError(f"{url}: the simulated prosthesis did not settle within "
                                 f"{settle_timeout:g} s")
        time.sleep(0.01)
