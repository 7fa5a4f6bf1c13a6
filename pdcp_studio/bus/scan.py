"""Scan: read every parameter of every device on the bus into a ``System`` with node IDs.

The arbitrator's request engine allows one transaction per device at a time and overlapping
transactions to different devices. A scan therefore gives each device to one of ``window``
workers, which reads that device's parameters one after another: at most ``window`` requests
are outstanding on the bus at any moment (the bounded window), so an adapter's transmit queue
holds at most that many frames from the scan; ``pace_s`` adds a least gap between two
requests for slow adapters.

What is read: the device parameters of the catalog (``model/parameters.py``) under channel
0, then for each channel 1…N its Transfer Type and every parameter of that direction. A
parameter a device refuses (it does not implement it) is left at its default. Links are
taken as the bus has them: an input whose Data Transfer Enabled flag is set and whose
Source's Node Ids name the node ID of an output channel on the bus.

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
from typing import Any

from pdcp_studio.bus.requests import DeviceRefusedError
from pdcp_studio.errors import ParameterError, PdcpError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link, SourceInfo, System

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


class _Refused(Exception):
    """A device answered a read with the failure code: the parameter is not implemented."""


@dataclass
class _Job:
    key: DeviceKey
    node_id: int
    values: dict[tuple[int, int], bytes] = field(default_factory=dict)
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


def _device_params() -> list[int]:
    return [s.id for s in P.parameters_for("device")]


def _channel_params(direction: Direction) -> list[int]:
    return [s.id for s in P.parameters_for(direction) if s.id != P.CH_TRANSFER_TYPE]


def estimate_reads(system: System) -> int:
    """Parameter reads a scan of ``system``'s present devices takes (for progress totals)."""
    total = 0
    for device in system.devices.values():
        if not device.present:
            continue
        total += len(_device_params())
        for ch in device.channels.values():
            total += 1 + len(_channel_params(ch.direction))
    return total


def _decode(pid: int, channel: int, direction: Direction | None, data: bytes | None,
            default: Any) -> Any:
    if data is None:
        return default
    spec = P.find_parameter(pid, channel, direction)
    if spec is None:
        return default
    try:
        return P.decode_value(spec, data)
    except ParameterError as err:
        log.info("scan: %s", err)
        return default


def build_device(key: DeviceKey, node_id: int,
                 values: dict[tuple[int, int], bytes]) -> Device:
    """A model Device from the raw parameter bytes a scan read (channel 0 and 1…N)."""
    def dev(pid: int, default: Any) -> Any:
        return _decode(pid, 0, None, values.get((pid, 0)), default)

    fw, hw = dev(P.DEVICE_VERSION, (0, 0))
    dtype, dprofile = dev(P.DEVICE_TYPE_PROFILE, (0, 0))
    device = Device(
        key.vid, key.pid, key.serial, descriptor=dev(P.DEVICE_DESCRIPTOR, ""),
        node_id=dev(P.DEVICE_NODE_ID, node_id) or node_id, fw_version=fw, hw_version=hw,
        device_type=dtype, device_profile=dprofile,
        beacon_interval=dev(P.DEVICE_BEACON_INTERVAL, 100),
        ack_timeout=dev(P.DEVICE_ACK_TIMEOUT, 50), bind_timeout=dev(P.DEVICE_BIND_TIMEOUT, 200),
        ean_low=dev(P.DEVICE_EAN_LOW, 0), ean_high=dev(P.DEVICE_EAN_HIGH, 0),
    )
    count = dev(P.DEVICE_CHANNEL_COUNT, 0)
    for index in range(1, count + 1):
        transfer = _decode(P.CH_TRANSFER_TYPE, index, Direction.INPUT,
                           values.get((P.CH_TRANSFER_TYPE, index)), 0)
        try:
            direction = Direction.from_transfer_type(transfer)
        except ValueError:
            continue  # an index the device does not use

        def get(pid: int, default: Any, i: int = index, d: Direction = direction) -> Any:
            return _decode(pid, i, d, values.get((pid, i)), default)

        ctype, profile = get(P.CH_TYPE_PROFILE, (0, 0))
        ch = Channel(index, direction, ctype, profile,
                     required_inputs=tuple(get(P.CH_REQUIRED_INPUTS, ())),
                     desired_inputs=tuple(get(P.CH_DESIRED_INPUTS, ())),
                     descriptor=get(P.CH_DESCRIPTOR, ""),
                     data_enabled=bool(get(P.CH_DATA_ENABLED, 0)))
        if direction is Direction.INPUT:
            svid, spid = get(P.IN_SOURCE_VID_PID, (0xFFFF, 0xFFFF))
            ssn, sidx = get(P.IN_SOURCE_SN_INDEX, (0xFFFF, 0xFF))
            stype, sprofile = get(P.IN_SOURCE_TYPE_PROFILE, (0, 0))
            ch.source = SourceInfo(svid, spid, ssn, sidx, stype, sprofile)
            ch.terminal_profile = get(P.IN_TERMINAL_PROFILE, 0)
        else:
            ch.node_id = get(P.OUT_NODE_ID, 0) or None
        device.add_channel(ch)
    return device


def links_on_bus(devices: list[Device], values: dict[DeviceKey, dict]) -> list[Link]:
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
            raw = values[device.key].get((P.IN_SOURCE_NODE_IDS, ch.index))
            node_ids = _decode(P.IN_SOURCE_NODE_IDS, ch.index, Direction.INPUT, raw, (0, 0))
            out = by_node.get(node_ids[1])
            if out is not None and out.device != device.key:
                links.append(Link(out, device.ref(ch.index)))
    return links


def scan(arbitrator: Any, progress: ProgressFn | None = None,
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
    requests = arbitrator.requests

    def tick(text: str) -> None:
        with lock:
            done[0] += 1
            n = done[0]
        if progress is not None:
            progress(min(n, total - 1), total, text)

    def read(job: _Job, pid: int, channel: int) -> bytes | None:
        if stop.is_set():
            raise _Stop
        pacer.wait()
        try:
            # A device descriptor is long (the thesis's is 33 bytes): ask for bulk at once.
            # Channel descriptors are often short or empty, so they go inline first.
            long_value = channel == 0 and pid == P.DEVICE_DESCRIPTOR
            value = requests.get(job.node_id, pid, channel, timeout=read_timeout,
                                 bulk_first=long_value)
        except DeviceRefusedError:
            value = None  # not implemented by this device: left at its default
        job.values[pid, channel] = value
        tick(f"{job.key}: {P.parameter_name(pid, channel)}")
        return value

    def run(job: _Job) -> None:
        try:
            for pid in _device_params():
                read(job, pid, 0)
            got = _decode(P.DEVICE_VID_PID, 0, None, job.values.get((P.DEVICE_VID_PID, 0)),
                          None)
            serial = _decode(P.DEVICE_SERIAL, 0, None, job.values.get((P.DEVICE_SERIAL, 0)),
                             None)
            if got is not None and (tuple(got) != (job.key.vid, job.key.pid)
                                    or serial != job.key.serial):
                job.error = (f"node {job.node_id} answered as {got[0]}/{got[1]}/{serial}, "
                             f"not {job.key}")
                return
            count = _decode(P.DEVICE_CHANNEL_COUNT, 0, None,
                            job.values.get((P.DEVICE_CHANNEL_COUNT, 0)), 0)
            for index in range(1, count + 1):
                raw = read(job, P.CH_TRANSFER_TYPE, index)
                transfer = _decode(P.CH_TRANSFER_TYPE, index, Direction.INPUT, raw, 0)
                if transfer not in (1, 2):
                    continue
                for pid in _channel_params(Direction.from_transfer_type(transfer)):
                    read(job, pid, index)
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
