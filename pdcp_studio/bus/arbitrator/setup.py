"""Device set-up after binding (reference §1 steps 1–6), on the arbitrator's set-up pool.

Reads a newly bound device and its channels with the device reader the scan uses too
(``bus/arbitrator/reading/device_reader.py``), gives its outputs node IDs from the node table,
installs it in the system and re-makes its links through the link writer. A set-up of an older
binding (or from before a reset: another ``epoch``) discards its result. A failed set-up resets
the device so it binds again, up to ``SETUP_ATTEMPTS`` times.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.common import SETUP_ATTEMPTS, _Node
from pdcp_studio.bus.arbitrator.nodes import MAX_KEYS_REMEMBERED
from pdcp_studio.bus.arbitrator.reading.device_reader import SETUP, DeviceReader
from pdcp_studio.bus.arbitrator.state import (
    Emit,
    NoteChange,
    ReportError,
    SendFrame,
    SystemState,
)
from pdcp_studio.errors import ModelError, PdcpError
from pdcp_studio.model import param_fields
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Device, Link
from pdcp_studio.protocol import Reset

if TYPE_CHECKING:
    from pdcp_studio.bus.arbitrator.nodes import NodeTable
    from pdcp_studio.bus.arbitrator.reading.requests import RequestEngine

log = logging.getLogger("pdcp_studio.bus.arbitrator.core")  # one logger for the arbitrator


class DeviceSetup:
    """The set-up jobs (one per binding) and their bookkeeping: which set-ups are in flight
    and how often a device's failed.

    ``run`` puts a set-up on the pool; ``wire_add`` re-makes a link (the link writer's);
    ``note_change`` tells the profile layer a device was set up (``duty``: it joined);
    ``stopping`` says the arbitrator is closing; ``wake`` wakes the profile thread."""

    def __init__(self, state: SystemState, nodes: NodeTable, requests: RequestEngine, *,
                 run: Callable[[Callable[[], None]], None], wire_add: Callable[[Link], None],
                 note_change: NoteChange, send: SendFrame, error: ReportError,
                 emit: Emit, wake: Callable[[], None], stopping: Callable[[], bool],
                 name: str) -> None:
        self._state = state
        self._nodes = nodes
        self._requests = requests
        self._run = run
        self._wire_add = wire_add
        self._note_change = note_change
        self._send = send
        self._error = error
        self._emit = emit
        self._wake = wake
        self._stopping = stopping
        self._name = name
        self.reader = DeviceReader(requests, descriptor_bulk=False)
        self.in_flight: dict[DeviceKey, tuple[int, int]] = {}  # key → (epoch, generation)
        self.failures: dict[DeviceKey, int] = {}
        self.epoch = 0  # bumped by a reset: stale set-ups discard their results

    def start(self, node: _Node) -> Callable[[], None]:
        """Under the lock: ``node``'s device is to be set up (it counts as in flight from now
        on). Returns what puts the set-up on the pool, to be called once the bind answer is
        on the bus: the set-up's first request must not overtake the answer that binds the
        device, or the device ignores it and it is asked again a response timeout later."""
        key, node_id, generation, epoch = node.key, node.node_id, node.generation, self.epoch
        self.in_flight[key] = (epoch, generation)

        def submit() -> None:
            try:
                self._run(lambda: self._job(key, node_id, generation, epoch))
            except RuntimeError:  # closing
                with self._state.lock:
                    if self.in_flight.get(key) == (epoch, generation):
                        del self.in_flight[key]

        return submit

    def under_way(self) -> bool:
        """A set-up is in flight."""
        with self._state.lock:
            return bool(self.in_flight)

    def cancel(self, key: DeviceKey) -> None:
        """Under the lock: ``key`` left; its set-up under way no longer counts (and its
        result is discarded: the node it was for is gone)."""
        self.in_flight.pop(key, None)

    def forget(self) -> None:
        """Under the lock: a reset; set-ups under way will discard their results."""
        self.epoch += 1
        self.in_flight.clear()
        self.failures.clear()

    def _current(self, key: DeviceKey, node_id: int, generation: int, epoch: int) -> bool:
        with self._state.lock:
            node = self._nodes.by_id.get(node_id)
            return (epoch == self.epoch and node is not None and node.key == key
                    and node.generation == generation)

    def _job(self, key: DeviceKey, node_id: int, generation: int, epoch: int) -> None:
        try:
            if not self._current(key, node_id, generation, epoch):
                return  # it left (or bound again) while queued: a bind flood of made-up
                # devices must not keep a real one waiting behind their timeouts
            device = self.read_device(key, node_id)
            if self._current(key, node_id, generation, epoch):
                self._commit(key, node_id, generation, epoch, device)
        except PdcpError as err:
            if self._current(key, node_id, generation, epoch) and not self._stopping():
                with self._state.lock:
                    if key not in self.failures and len(self.failures) >= MAX_KEYS_REMEMBERED:
                        del self.failures[next(iter(self.failures))]  # the oldest
                    failures = self.failures[key] = self.failures.get(key, 0) + 1
                again = failures < SETUP_ATTEMPTS
                self._error(f"set-up of device {key} (node {node_id}) failed: {err}"
                            + ("; resetting it to try again" if again else ""), "setup")
                if again:
                    self._send(Reset(node_id))
        except Exception:
            log.exception("%s: set-up of %s failed", self._name, key)
        finally:
            with self._state.lock:
                if self.in_flight.get(key) == (epoch, generation):
                    del self.in_flight[key]
                self._note_change(time.monotonic())
            self._wake()

    def read_device(self, key: DeviceKey, node_id: int) -> Device:
        """Steps 1–3 and the reads of steps 4–5: the device and all its channels."""
        values: param_fields.Values = {}
        self.reader.read_device(key, node_id, SETUP, values)
        problem = self.reader.identity_problem(key, node_id, values)
        if problem:
            self._error(f"device {key} after binding: {problem}", "setup")
        self.reader.read_channels(key, node_id, SETUP, values,
                                  lambda why: self._error(why, "setup"))
        return param_fields.device_from_values(key, values)

    def _commit(self, key: DeviceKey, node_id: int, generation: int, epoch: int,
                device: Device) -> None:
        """Steps 4 (channel node IDs), 5 and 6: install the device, re-make its links."""
        state, nodes = self._state, self._nodes
        with state.wire_lock:
            with state.lock:
                if not self._current(key, node_id, generation, epoch):
                    return
                ids, refused, why = nodes.give_outputs(key, [c.index for c in
                                                             device.outputs()])
            if refused:  # one line per device naming every output left without an ID
                names = ", output ".join(str(device.ref(i)) for i in refused)
                self._error(f"output {names} gets no node ID and cannot be linked: {why}",
                            "node_ids_exhausted")
            for index, channel_id in ids.items():
                self._requests.set(node_id, P.OUT_NODE_ID, index, bytes([channel_id]))
            with state.lock:
                if not self._current(key, node_id, generation, epoch):
                    return
                system = state.system
                old = system.device(key)
                joined = old is None or not old.present
                device.present = True
                nodes.stamp(device)
                device.name = old.name if old is not None else ""
                if old is None:
                    system.add_device(device)
                else:
                    system.devices[key] = device
                    for link in system.links:
                        if key in (link.output.device, link.input.device):
                            try:
                                system.check_link(link)
                            except ModelError:
                                system.remove_link(link)
                links = [lk for lk in system.links
                         if key in (lk.output.device, lk.input.device)
                         and system.is_present(lk.output) and system.is_present(lk.input)]
                nodes.set_up(nodes.by_id[node_id], max(device.beacon_interval, 1) / 1000.0)
                self.failures.pop(key, None)
                self._note_change(time.monotonic(), duty=joined)
            for link in links:
                try:
                    self._wire_add(link)
                except PdcpError as err:
                    self._error(f"link {link} could not be re-made: {err}", "transport")
        if joined:
            log.info("%s: device %s joined (node %d, %d channels)", self._name, key, node_id,
                     len(device.channels))
            self._emit(ev.DeviceJoined(key))
        self._wake()


__all__ = ["DeviceSetup"]
