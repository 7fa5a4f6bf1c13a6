"""What only some sessions can do, as protocols a caller checks with ``isinstance``.

Every session has the face of :class:`~pdcp_studio.bus.session.base.BusSession`; a simulated
prosthesis also has the simulator's controls. A caller asks ``isinstance(session,
SimulatedDevices)`` rather than sniffing for a method, so the capability has one name and one
definition.
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING, Protocol, runtime_checkable

from pdcp_studio.bus.session.base import ProgressFn
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Device, System

if TYPE_CHECKING:
    from pdcp_studio.bus.sim.rigs import Prosthesis, ScriptResult

__all__ = ["SimulatedDevices", "SimulatorControls"]


@runtime_checkable
class SimulatedDevices(Protocol):
    """A bus whose devices are simulated: listed, plugged in and unplugged at will."""

    def sim_devices(self) -> list[tuple[DeviceKey, str, bool]]:
        """Every simulated device: (key, label, plugged)."""
        ...

    def plug(self, key: DeviceKey) -> None:
        """Power a simulated device on; returns once it has joined."""
        ...

    def unplug(self, key: DeviceKey) -> None:
        """Cut a simulated device off the bus."""
        ...

    def script_names(self) -> list[str]:
        """The prosthesis's scripted events."""
        ...


@runtime_checkable
class SimulatorControls(SimulatedDevices, Protocol):
    """The whole simulator: parts replaced, the arbitrator reset, scripts run end to end."""

    @property
    def initial_system(self) -> System:
        """The prosthesis as it starts."""
        ...

    @property
    def prosthesis(self) -> Prosthesis:
        """The built-in prosthesis (its name, scripts and data rate)."""
        ...

    def replace(self, old_key: DeviceKey, new: DeviceKey | Device) -> DeviceKey:
        """Unplug ``old_key`` and plug ``new`` in; the new device's key once it joined."""
        ...

    def reset_arbitrator(self, keep_memory: bool) -> None:
        """Reset the arbitrator, keeping or erasing its stored configuration."""
        ...

    def run_script(self, name: str | None = None, progress: ProgressFn | None = None,
                   cancel: threading.Event | None = None) -> ScriptResult:
        """Run a script end to end from the prosthesis's initial state."""
        ...
