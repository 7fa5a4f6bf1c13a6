"""Scan: read every parameter of every device on the bus into a ``System`` with node IDs.

The arbitrator's request engine allows one transaction per device at a time and overlapping
transactions to different devices. A scan therefore gives each device to one of ``window``
workers, which reads that device's parameters one after another: at most ``window`` requests
are outstanding on the bus at any moment (the bounded window), so an adapter's transmit queue
holds at most that many frames from the scan; ``pace_s`` adds a least gap between two
requests for slow adapters.

What is read: the device parameters of the catalog (``model/parameters.py``) under channel 0,
then for each channel 1…N its Transfer Type and every parameter of that direction (the reader
the arbitrator's set-up uses too: ``bus/arbitrator/reading/device_reader.py``; the values become
model fields through the catalog's one mapping, ``model/param_fields.py``). A parameter a device
refuses (it does not implement it) is left at its default. Links are taken as the bus has them:
an input whose Data Transfer Enabled flag is set and whose Source's Node Ids name the node ID of
an output channel on the bus.

Cancellation: when ``cancel`` is set, the workers stop before their next request and
:class:`ScanCancelled` is raised; its ``partial`` holds the devices read completely so far.
A device that leaves mid-scan or stops answering is left out and named in ``problems``.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from pdcp_studio.bus.arbitrator.reading.device_reader import EVERYTHING, DeviceReader
from pdcp_studio.errors import PdcpError
from pdcp_studio.model import param_fields
from pdcp_studio.model import parameters as P
from pdcp_studio.model.param_fields import Values
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Device, Link, System

if TYPE_CHECKING:
    from pdcp_studio.bus.arbitrator.core import Arbitrator

log = logging.getLogger(__name__)

ProgressFn = Callable[[int, int, str], None]

#: Devices read at the same time (requests outstanding on the bus at most).
DEFAULT_WINDOW = 8
#: Seconds one parameter read may take, retries included.
READ_TIMEOUT_S = 2.0


class ScanCancelled(PdcpError):
    """The scan was cancelled; ``partial`` is a System of the devices read completely."""

    def __init__(self, message: str, partial: System) -> None:
        super().__init__(message)
        self.partial = partial


@dataclass
class _Job:
    key: DeviceKey
    node_id: int
    values: Values = field(default_factory=dict)
    device: Device | None = None
    error: str = ""


class _Pacer:
    """At most one request start per ``pace_s`` across all workers."""

    def __init__(self, pace_s: float) -> None:
        self.pace_s = pace_s
        self._lock = threading.Lock()
        self._next = 0.0

    def wait(self) -> None:
        if self.pace_s <= 0:
            return
        with self._lock:
            now = time.perf_counter()
            start = max(now, self._next)
            self._next = start + self.pace_s
        if start > now:
            time.sleep(start - now)


def estimate_reads(system: System) -> int:
    """Parameter reads a scan of ``system``'s present devices takes (for progress totals)."""
    return sum(EVERYTHING.count([ch.direction for ch in device.channels.values()])
               for device in system.devices.values() if device.present)


def build_device(key: DeviceKey, node_id: int, values: Values) -> Device:
    """A model Device from the raw parameter bytes a scan read (channel 0 and 1…N)."""
    return param_fields.device_from_values(key, values, node_id)


def links_on_bus(devices: list[Device], values: dict[DeviceKey, Values]) -> list[Link]:
    """Links as the bus has them: enabled inputs whose Source's Node Ids name an output."""
    by_node: dict[int, ChannelRef] = {}
    for device in devices:
        for ch in device.outputs():
            if ch.node_id:
                by_node[ch.node_id] = device.ref(ch.index)
    links = []
    for device in devices:
        for ch in device.inputs():
            if not ch.data_enabled:
                continue
            node_ids = param_fields.decoded(values[device.key], P.IN_SOURCE_NODE_IDS, ch.index,
                                            Direction.INPUT) or (0, 0)
            out = by_node.get(node_ids[1])
            if out is not None and out.device != device.key:
                links.append(Link(out, device.ref(ch.index)))
    return links


def scan(arbitrator: Arbitrator, progress: ProgressFn | None = None,
         cancel: threading.Event | None = None, window: int = DEFAULT_WINDOW, *,
         pace_s: float = 0.0, read_timeout: float = READ_TIMEOUT_S,
         problems: list[str] | None = None,
         raw: dict[DeviceKey, dict[tuple[int, int], bytes | None]] | None = None) -> System:
    """Read the whole bus through ``arbitrator`` (its ``system()`` and ``requests``).

    Returns the present devices (by key) with every parameter, their node IDs and the links;
    see the module docstring for the window, pacing, cancellation and devices that fail.
    ``raw``, when given, receives every value read: key → (parameter, channel) → bytes (None
    where the device refused).
    """
    if window < 1:
        raise ValueError(f"scan window {window} must be at least 1")
    known = arbitrator.system()
    jobs = [_Job(key, dev.node_id) for key, dev in known.devices.items()
            if dev.present and dev.node_id]
    total = max(estimate_reads(System(d for d in known.devices.values()
                                      if d.present and d.node_id)), 1)
    done = [0]
    lock = threading.Lock()
    pacer = _Pacer(pace_s)
    stop = cancel or threading.Event()

    def tick(text: str) -> None:
        with lock:
            done[0] += 1
            n = done[0]
        if progress is not None:
            progress(min(n, total - 1), total, text)

    def before() -> None:
        if stop.is_set():
            raise _Stop
        pacer.wait()

    def after(key: DeviceKey, pid: int, channel: int) -> None:
        tick(f"{key}: {P.parameter_name(pid, channel)}")

    reader = DeviceReader(arbitrator.requests, timeout=read_timeout, before=before, after=after)

    def run(job: _Job) -> None:
        try:
            reader.read_device(job.key, job.node_id, EVERYTHING, job.values)
            job.error = reader.identity_problem(job.key, job.node_id, job.values)
            if job.error:
                return
            reader.read_channels(job.key, job.node_id, EVERYTHING, job.values)
            job.device = build_device(job.key, job.node_id, job.values)
        except _Stop:
            return
        except PdcpError as err:
            job.error = f"{job.key} (node {job.node_id}): {err}"

    if progress is not None:
        progress(0, total, f"Scanning {len(jobs)} device(s)")
    if jobs:
        with ThreadPoolExecutor(max_workers=min(window, len(jobs)),
                                thread_name_prefix="pdcp scan") as pool:
            for future in [pool.submit(run, job) for job in jobs]:
                future.result()
    devices = sorted((job.device for job in jobs if job.device is not None),
                     key=lambda d: d.key)
    values = {job.key: job.values for job in jobs}
    if raw is not None:
        raw.update(values)
    result = System(devices, links_on_bus(devices, values))
    for job in jobs:
        if job.error:
            log.warning("scan: %s", job.error)
            if problems is not None:
                problems.append(job.error)
    if stop.is_set():
        raise ScanCancelled(f"scan cancelled after {done[0]} of {total} parameter reads "
                            f"({len(devices)} of {len(jobs)} devices complete)", result)
    if progress is not None:
        progress(total, total, f"{len(devices)} device(s), {len(result.links)} link(s)")
    return result


class _Stop(Exception):
    """Internal: the scan was cancelled; unwind this worker."""
