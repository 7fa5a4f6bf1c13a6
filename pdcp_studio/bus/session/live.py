"""One session interface for any live bus: what the CLI and the desktop app talk to.

``open_session(url)`` opens a bus URL (contracts §3):

- ``sim:NAME`` — a built-in prosthesis (``bus/sim/rigs.py``) on an in-process python-can
  ``virtual`` bus with a channel of its own: PDCP Studio's arbitrator and a DeviceHost with
  the prosthesis's devices, each on its own bus object, talk in frames as on a real bus.
  Returns once the devices are bound and start-up has linked them.
- ``can:INTERFACE:CHANNEL[@BITRATE]`` — PDCP Studio is the bus arbitrator: it binds the
  devices it hears and runs start-up with its own memory, once it has listened and heard no
  other arbitrator (reference §5); a pulled adapter is reopened (``Session.state``).
- ``serial:PORT[@BAUD]`` — an arbitrator elsewhere, over its host link
  (``bus/hostlink/client.py``).

Sessions are thread-safe. Subscribers are called on the arbitrator's thread and must only
enqueue (the app's SessionBridge does); a subscriber that raises is logged, never fatal.
Every call that talks to the bus has a timeout. Long calls take ``progress(done, total,
text)`` and ``cancel`` (a ``threading.Event``) like the app's workers.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.session.api import TransactingMixin
from pdcp_studio.bus.session.urls import BusUrlError, check_bus_url
from pdcp_studio.bus.transaction import Change, Policy, TransactionResult
from pdcp_studio.errors import PdcpError, TransportError
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Device, Link, System

if TYPE_CHECKING:
    from pdcp_studio.bus.session.api import BusSession
    from pdcp_studio.bus.sim.rigs import ScriptResult
    from pdcp_studio.engine import Plan

log = logging.getLogger(__name__)

ProgressFn = Callable[[int, int, str], None]
Subscriber = Callable[[object], None]

#: Seconds ``open_session`` waits for a simulated prosthesis to bind and link.
SIM_SETTLE_TIMEOUT_S = 10.0
#: Start-up waits this long without bind requests on a simulated bus (binding is in-process).
SIM_STARTUP_QUIET_S = 0.2
#: Seconds ``open_session`` lets a real bus settle (devices binding, start-up) before returning.
CAN_SETTLE_TIMEOUT_S = 3.0
#: Seconds ``plug`` / ``replace`` wait for the device to join and the arbitrator to settle.
JOIN_TIMEOUT_S = 5.0
#: Seconds ``plug`` gives the arbitrator's thread to take a bind request in before waiting.
JOIN_GRACE_S = 0.03
#: Seconds a simulator control (plug, reset…) may wait for another one to finish.
CONTROL_LOCK_TIMEOUT_S = 15.0
#: Least gap between two scan requests on a real adapter (its transmit queue must not fill).
CAN_SCAN_PACE_S = 0.0002
#: Least seconds between two Progress events a scan sends subscribers.
PROGRESS_EVENT_INTERVAL_S = 0.1
HOSTLINK_MODULE = "pdcp_studio.bus.hostlink.client"

__all__ = ["BusUrlError", "ConfigVerifyError", "OtherArbitratorError", "Session", "SimSession",
           "open_session"]


class OtherArbitratorError(TransportError):
    """Another bus arbitrator is on the bus: PDCP Studio does not arbitrate there (§5)."""


class ConfigVerifyError(TransportError):
    """The stored configuration read back after a write differs from what was written."""


class Session(TransactingMixin):
    """A live bus run by PDCP Studio's own arbitrator. Close it (or use ``with``).

    Implements :class:`pdcp_studio.bus.session.api.BusSession`."""

    def __init__(self, arbitrator: Any, *, url: str = "", scan_window: int = 8,
                 scan_pace_s: float = 0.0) -> None:
        self.url = url
        self.arbitrator = arbitrator
        self.scan_window = scan_window
        self.scan_pace_s = scan_pace_s
        self._subs = ev.Subscribers(url or "session")
        self._closed = threading.Event()
        self._close_lock = threading.Lock()
        # Frames are decoded for display only while someone subscribed here (a simulated
        # prosthesis opens with ~450 frames nobody watches yet).
        self._unsubscribe = arbitrator.subscribe(self._on_event,
                                                 wants_frames=self._has_subscribers)
        self._state = "arbitrating"
        self._state_message = ""

    def __enter__(self) -> Session:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.url!r}{', closed' if self.closed else ''})"

    @property
    def closed(self) -> bool:
        return self._closed.is_set()

    def _check_open(self) -> None:
        if self._closed.is_set():
            raise TransportError(f"{self.url or 'bus'}: the session is closed")

    # -- events -----------------------------------------------------------------------
    def subscribe(self, callback: Subscriber) -> Callable[[], None]:
        """Call ``callback(event)`` for every bus event (bus/events.py); returns unsubscribe."""
        return self._subs.add(callback)

    def _emit(self, event: object) -> None:
        self._subs.emit(event)

    def _has_subscribers(self) -> bool:
        return len(self._subs) > 0

    def _on_event(self, event: object) -> None:
        if isinstance(event, ev.BusState):
            self._state, self._state_message = event.state, event.message
        self._emit(event)

    @property
    def state(self) -> str:
        """The hold on the bus: ``arbitrating``, ``yielded``, ``disconnected`` (shown as
        "disconnected — reconnecting"), ``reconnected`` (see ev.BusState)."""
        return self._state

    @property
    def state_message(self) -> str:
        """The one line that said why the state is what it is ('' at first)."""
        return self._state_message

    # -- the bus ------------------------------------------------------------------------
    def system(self) -> System:
        """A snapshot of the bus as the arbitrator sees it: devices (present or missing),
        channels, node IDs and links."""
        self._check_open()
        return self.arbitrator.system()

    def wait_settled(self, timeout: float) -> bool:
        """Wait until binding, set-up and plans are done; False at the timeout."""
        self._check_open()
        return bool(self.arbitrator.wait_settled(timeout))

    def get_parameter(self, key: DeviceKey, param: int, channel: int = 0, *,
                      timeout: float | None = None) -> bytes:
        """Read one parameter from a device (bulk transfer when the device asks for it)."""
        self._check_open()
        return bytes(self.arbitrator.get_parameter(key, param, channel, timeout=timeout))

    # -- plans --------------------------------------------------------------------------
    def preview(self, mode: str, config: ConfigCollection | None = None) -> Plan:
        """The engine's plan for ``mode`` on the current system; ``config`` defaults to the
        arbitrator's stored configuration (none when its memory is empty)."""
        from pdcp_studio.engine import plan_for, plan_on_bus

        self._check_open()
        autoconfigure = self.read_policy().autoconfigure
        if config is not None:
            return plan_for(mode, self.system(), config, autoconfigure=autoconfigure)
        return plan_on_bus(mode, self.system(), self.read_configuration(),
                           autoconfigure=autoconfigure)

    def carry_out(self, change: Change, progress: ProgressFn | None = None,
                  cancel: threading.Event | None = None) -> TransactionResult:
        """The arbitrator's half of the change road (interlock, write, verify, restore,
        release); ``transact`` adds the preview, confirmation and record."""
        self._check_open()
        return self.arbitrator.transact(change, progress, cancel)

    # -- the stored configuration -------------------------------------------------------
    def read_configuration(self) -> ConfigCollection:
        """The arbitrator's stored configuration (empty when it has none)."""
        self._check_open()
        return self.arbitrator.read_memory()

    def read_policy(self) -> Policy:
        """The arbitrator's profile-layer policy (autoconfigure on or off)."""
        self._check_open()
        return self.arbitrator.read_policy()

    # -- scan ---------------------------------------------------------------------------
    def scan(self, progress: ProgressFn | None = None,
             cancel: threading.Event | None = None) -> System:
        """Read every device's parameters (bus/arbitrator/scan.py); ScanCancelled when cancelled.

        Subscribers also get ``Progress`` events, at most one per
        ``PROGRESS_EVENT_INTERVAL_S`` and always the last one."""
        from pdcp_studio.bus.arbitrator.scan import scan

        self._check_open()
        last = [0.0]

        def report(done: int, total: int, text: str) -> None:
            if progress is not None:
                progress(done, total, text)
            now = time.monotonic()
            if done >= total or now - last[0] >= PROGRESS_EVENT_INTERVAL_S:
                last[0] = now
                self._emit(ev.Progress(done, total, text))

        return scan(self.arbitrator, report, cancel, self.scan_window,
                    pace_s=self.scan_pace_s)

    # -- shutdown -----------------------------------------------------------------------
    def close(self) -> None:
        """Stop the arbitrator and release the bus (idempotent)."""
        with self._close_lock:
            if self._closed.is_set():
                return
            self._closed.set()
        try:
            self._unsubscribe()
        except Exception:
            log.debug("unsubscribe failed", exc_info=True)
        self._close_parts()

    def _close_parts(self) -> None:
        self.arbitrator.close()


class SimSession(Session):
    """A built-in simulated prosthesis: the session plus the simulator's controls.

    ``plug`` and ``replace`` return once the arbitrator has set the device up and settled
    (at most ``JOIN_TIMEOUT_S``); ``unplug`` returns at once — the arbitrator notices the
    silence after 3 beacon intervals, as on a real bus. ``run_script`` first restores the
    prosthesis as it starts (fresh devices, arbitrator memory erased) unless nothing has
    changed it since it was opened.
    """

    def __init__(self, arbitrator: Any, host: Any, prosthesis: Any, system: System, *,
                 url: str = "", data_rate_hz: float | None = None, **kwargs: Any) -> None:
        super().__init__(arbitrator, url=url, **kwargs)
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

    def _device(self, model: Device) -> Any:
        from pdcp_studio.bus.sim.device import SimulatedDevice

        kwargs = {} if self.data_rate_hz is None else {"data_rate_hz": self.data_rate_hz}
        return SimulatedDevice(model, **kwargs)

    def _wait_joined(self, key: DeviceKey, timeout: float = 0.0) -> None:
        timeout = timeout or JOIN_TIMEOUT_S
        deadline = time.monotonic() + timeout
        time.sleep(JOIN_GRACE_S)  # let the arbitrator's thread take the bind request in

        def joined() -> bool:  # no system() copy per poll
            return (key in self.arbitrator.devices_present()
                    and self.arbitrator.node_id_of(key) is not None)

        while not joined():
            if time.monotonic() >= deadline:
                raise TransportError(f"{self.url}: device {key} was plugged in but did not "
                                     f"join within {timeout:g} s")
            time.sleep(0.01)
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

    # -- changes through the session also leave the initial state ---------------------------
    def add_link(self, link: Link) -> None:
        self._changed()
        super().add_link(link)

    def remove_link(self, link: Link) -> None:
        self._changed()
        super().remove_link(link)

    def carry_out(self, change: Change, progress: ProgressFn | None = None,
                  cancel: threading.Event | None = None) -> TransactionResult:
        self._changed()
        return super().carry_out(change, progress, cancel)

    def set_parameter(self, key: DeviceKey, param: int, channel: int, value: bytes, *,
                      timeout: float | None = None) -> None:
        self._changed()
        super().set_parameter(key, param, channel, value, timeout=timeout)

    def _close_parts(self) -> None:
        try:
            self.arbitrator.close()
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


def _known(host: Any, key: DeviceKey) -> DeviceKey:
    key = DeviceKey(*key)
    if key not in host.keys():
        raise PdcpError(f"no simulated device {key} (devices: "
                        + ", ".join(str(k) for k in host.keys()) + ")")
    return key


# -- opening --------------------------------------------------------------------------------
def _arbitrator_options(options: dict[str, Any]) -> dict[str, Any]:
    names = ("memory", "profile_layer", "autoconfigure", "pace_s", "response_timeout", "retries",
             "startup_quiet_s", "duty_quiet_s", "node_ids", "frame_events", "channel_events",
             "reset_on_start", "listen_s")
    return {n: options.pop(n) for n in names if n in options}


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
    arb_opts = _arbitrator_options(options)
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


def open_can_session(spec: Any, *, settle_timeout: float = CAN_SETTLE_TIMEOUT_S,
                     **options: Any) -> Session:
    """PDCP Studio as the arbitrator of a python-can bus, once it has listened and heard no
    other arbitrator there (reference §5); OtherArbitratorError (one line) if it heard one."""
    from pdcp_studio.bus.arbitrator.claim import LISTEN_S
    from pdcp_studio.bus.arbitrator.core import Arbitrator
    from pdcp_studio.bus.reopen import open_reopening

    arb_opts = _arbitrator_options(options)
    arb_opts.setdefault("frame_events", True)
    arb_opts.setdefault("listen_s", LISTEN_S)
    options.setdefault("scan_pace_s", CAN_SCAN_PACE_S if spec.interface != "virtual" else 0.0)
    # A pulled adapter is reopened with backoff (bus/reopen.py); the session says
    # "disconnected — reconnecting" meanwhile (ev.BusState).
    arbitrator = Arbitrator(open_reopening(spec), name=f"{spec.url} arbitrator", **arb_opts)
    try:
        session = Session(arbitrator, url=spec.url, **options)
        if not arbitrator.wait_claimed(arb_opts["listen_s"] + 2.0):
            raise OtherArbitratorError(f"{spec.url}: {arbitrator.bus_message}")
    except BaseException:
        arbitrator.close()
        raise
    if settle_timeout > 0:
        session.wait_settled(settle_timeout)  # devices may keep binding later: not an error
    return session


def open_session(url: str, **options: Any) -> BusSession:
    """Open a bus URL (``sim:``, ``can:``, ``serial:``) as a session; see the module doc.

    BusUrlError for a URL that does not parse, names an interface python-can does not have
    or a ``sim:`` prosthesis that does not exist, or carries options the interface refuses;
    TransportError when the bus cannot be opened (a missing driver or adapter: the fix).
    """
    spec = check_bus_url(url)
    if spec.kind == "sim":
        return open_sim_session(spec.name, url=url, **options)
    if spec.kind == "can":
        return open_can_session(spec, **options)
    try:
        import importlib

        module = importlib.import_module(HOSTLINK_MODULE)
    except ModuleNotFoundError as err:
        if err.name != HOSTLINK_MODULE:
            raise
        raise TransportError(f"{url}: the host-link client is not available in this build, "
                             "so serial: buses cannot be opened") from err
    return module.open_hostlink_session(spec, **options)

