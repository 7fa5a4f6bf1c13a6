"""``sim:NAME``: a built-in simulated prosthesis as a session, and opening one.

The devices are simulated (bus/sim/) on an in-process python-can ``virtual`` bus with a
channel of its own: PDCP Studio's arbitrator and a DeviceHost with the prosthesis's devices,
each on its own bus object, talk in frames as on a real bus; ``open_sim_session`` returns once
the devices are bound and start-up has linked them. The session adds the controls a bench
would have — plug, unplug, replace, reset the arbitrator, restart, run a scripted event
(``SimulatorControls``, bus/session/capabilities.py).
"""

from __future__ import annotations

import threading
import time
from typing import TYPE_CHECKING, Any

from pdcp_studio.bus.session.base import ProgressFn
from pdcp_studio.bus.session.in_process import Session, arbitrator_options
from pdcp_studio.bus.session.urls import BusSpec
from pdcp_studio.bus.transaction import Change, TransactionResult
from pdcp_studio.errors import PdcpError, TransportError
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Device, System

if TYPE_CHECKING:
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.bus.sim.device import SimulatedDevice
    from pdcp_studio.bus.sim.device_host import DeviceHost
    from pdcp_studio.bus.sim.rigs import Prosthesis, ScriptResult

#: Seconds a simulated prosthesis gets to bind and link when it opens or restarts.
SIM_SETTLE_TIMEOUT_S = 10.0
#: Start-up waits this long without bind requests on a simulated bus (binding is in-process).
SIM_STARTUP_QUIET_S = 0.2
#: Seconds ``plug`` / ``replace`` wait for the device to join and the arbitrator to settle.
JOIN_TIMEOUT_S = 5.0
#: Seconds ``plug`` gives the arbitrator's thread to take a bind request in before waiting.
JOIN_GRACE_S = 0.03
#: Seconds a simulator control (plug, reset…) may wait for another one to finish.
CONTROL_LOCK_TIMEOUT_S = 15.0

__all__ = ["SIM_SETTLE_TIMEOUT_S", "SimSession", "open_sim_session", "open_sim_url"]


class SimSession(Session):
    """A built-in simulated prosthesis: the session plus the simulator's controls.

    ``plug`` and ``replace`` return once the arbitrator has set the device up and settled
    (at most ``JOIN_TIMEOUT_S``); ``unplug`` returns at once — the arbitrator notices the
    silence after 3 beacon intervals, as on a real bus. ``run_script`` first restores the
    prosthesis as it starts (fresh devices, arbitrator memory erased) unless nothing has
    changed it since it was opened.
    """

    def __init__(self, arbitrator: Arbitrator, host: DeviceHost, prosthesis: Prosthesis,
                 system: System, *, url: str = "", data_rate_hz: float | None = None,
                 scan_window: int = 8, scan_pace_s: float = 0.0) -> None:
        super().__init__(arbitrator, url=url, scan_window=scan_window, scan_pace_s=scan_pace_s)
        self.host = host
        self.prosthesis = prosthesis
        self.initial_system = system
        self.data_rate_hz = data_rate_hz
        self._labels = {key: dev.label for key, dev in system.devices.items()}
        self._control = threading.Lock()
        self._pristine = True

    def _locked(self) -> _Held:
        return _Held(self._control, f"{self.url}: another simulator control is still running")

    def _changed(self) -> None:
        self._pristine = False

    def _device(self, model: Device) -> SimulatedDevice:
        from pdcp_studio.bus.sim.device import SimulatedDevice

        if self.data_rate_hz is None:
            return SimulatedDevice(model)
        return SimulatedDevice(model, data_rate_hz=self.data_rate_hz)

    def _wait_joined(self, key: DeviceKey, timeout: float = 0.0) -> None:
        timeout = timeout or JOIN_TIMEOUT_S
        deadline = time.monotonic() + timeout
        time.sleep(JOIN_GRACE_S)  # let the arbitrator's thread take the bind request in

        def joined() -> bool:  # no system() copy per look
            return (key in self.arbitrator.devices_present()
                    and self.arbitrator.node_id_of(key) is not None)

        if not self.arbitrator.wait_for(joined, max(0.0, deadline - time.monotonic())):
            raise TransportError(f"{self.url}: device {key} was plugged in but did not "
                                 f"join within {timeout:g} s")
        self.arbitrator.wait_settled(max(0.0, deadline - time.monotonic()))

    # -- the simulator's controls ---------------------------------------------------------
    def sim_devices(self) -> list[tuple[DeviceKey, str, bool]]:
        """Every simulated device: (key, label, plugged)."""
        self._check_open()
        return [(key, self._labels.get(key, str(key)), self.host.is_plugged(key))
                for key in self.host.keys()]

    def plug(self, key: DeviceKey) -> None:
        """Power a simulated device on (nothing if it is on); returns once it has joined."""
        self._check_open()
        with self._locked():
            key = _known(self.host, key)
            if self.host.is_plugged(key):
                return
            self._changed()
            self.host.plug(key)
            self._wait_joined(key)

    def unplug(self, key: DeviceKey) -> None:
        """Cut a simulated device off the bus (nothing if it is off); the arbitrator
        notices by its missing beacons."""
        self._check_open()
        with self._locked():
            key = _known(self.host, key)
            if self.host.is_plugged(key):
                self._changed()
                self.host.unplug(key)

    def replace(self, old_key: DeviceKey, new: DeviceKey | Device) -> DeviceKey:
        """Unplug ``old_key`` and plug in ``new``: a simulated device's key, or a model Device
        that joins the simulation. Returns the new device's key once it has joined."""
        self._check_open()
        with self._locked():
            old_key = _known(self.host, old_key)
            if isinstance(new, Device):
                key = new.key
                if key not in self.host.keys():
                    self.host.add(self._device(new), plugged=False)
                    self._labels[key] = new.label
            else:
                key = _known(self.host, DeviceKey(*new))
            if key == old_key:
                raise PdcpError(f"{self.url}: a device cannot replace itself ({key})")
            self._changed()
            if self.host.is_plugged(old_key):
                self.host.unplug(old_key)
            if not self.host.is_plugged(key):
                self.host.plug(key)
                self._wait_joined(key)
            return key

    def reset_arbitrator(self, keep_memory: bool) -> None:
        """Reset PDCP Studio's arbitrator, keeping or erasing its stored configuration; the
        devices bind again and start-up runs (wait with ``wait_settled``)."""
        self._check_open()
        with self._locked():
            self._changed()
            self.arbitrator.reset(keep_memory=keep_memory)

    def restart(self, timeout: float = SIM_SETTLE_TIMEOUT_S) -> None:
        """Put the prosthesis back as it starts: fresh devices (their memories too), the
        initially present ones plugged in, the arbitrator's memory erased; then settle."""
        self._check_open()
        with self._locked():
            for key in list(self.host.keys()):
                self.host.remove(key)
            self.arbitrator.reset(keep_memory=False)
            for model in self.initial_system.copy().devices.values():
                self.host.add(self._device(model), plugged=model.present)
            self._labels = {k: d.label for k, d in self.initial_system.devices.items()}
            if not self.arbitrator.wait_settled(timeout):
                raise TransportError(f"{self.url}: the restarted prosthesis did not settle "
                                     f"within {timeout:g} s")
            self._pristine = True

    def script_names(self) -> list[str]:
        """The prosthesis's scripted events (the first is the one ``sim replay`` runs)."""
        return [s.name for s in self.prosthesis.scripts]

    def run_script(self, name: str | None = None, progress: ProgressFn | None = None,
                   cancel: threading.Event | None = None) -> ScriptResult:
        """Run a script end to end from the prosthesis's initial state; the result compares
        the final links with the ones the script must end in."""
        from pdcp_studio.bus.sim.rigs import run_script

        self._check_open()
        script = self.prosthesis.script(name)
        if not self._pristine:
            if progress is not None:
                progress(0, len(script.steps), "restarting the prosthesis")
            self.restart()
        self._changed()
        return run_script(self, script, self.initial_system, progress, cancel)

    # -- every change through the session (links, parameters: all carried out) leaves the
    # -- initial state
    def carry_out(self, change: Change, progress: ProgressFn | None = None,
                  cancel: threading.Event | None = None) -> TransactionResult:
        self._changed()
        return super().carry_out(change, progress, cancel)

    def _release(self) -> None:
        try:
            super()._release()
        finally:
            self.host.close()


class _Held:
    """``with`` a lock acquired with a timeout (TransportError when it is not free)."""

    def __init__(self, lock: threading.Lock, message: str) -> None:
        self._lock, self._message = lock, message

    def __enter__(self) -> None:
        if not self._lock.acquire(timeout=CONTROL_LOCK_TIMEOUT_S):
            raise TransportError(self._message)

    def __exit__(self, *exc: object) -> None:
        self._lock.release()


def _known(host: DeviceHost, key: DeviceKey) -> DeviceKey:
    key = DeviceKey(*key)
    if key not in host.keys():
        raise PdcpError(f"no simulated device {key} (devices: "
                        + ", ".join(str(k) for k in host.keys()) + ")")
    return key


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
