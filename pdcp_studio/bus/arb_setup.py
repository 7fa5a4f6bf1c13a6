"""Device set-up after binding (reference §1 steps 1–6), on the arbitrator's set-up pool.

A mixin of :class:`pdcp_studio.bus.arbitrator.Arbitrator`: reads a newly bound device and its
channels, gives its outputs node IDs, installs it in the system and re-makes its links. A set-up
of an older binding (or from before a reset) discards its result.
"""

from __future__ import annotations

import logging
import time

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arb_binding import MAX_KEYS_REMEMBERED
from pdcp_studio.bus.arb_common import SETUP_ATTEMPTS
from pdcp_studio.bus.device_reader import SETUP, DeviceReader
from pdcp_studio.errors import ModelError, NodeIdExhaustedError, PdcpError
from pdcp_studio.model import param_fields
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.model.system import Device
from pdcp_studio.protocol import Reset

log = logging.getLogger("pdcp_studio.bus.arbitrator")  # one logger for the arbitrator


class SetupMixin:
    """The set-up jobs of the :class:`Arbitrator` (one per binding)."""

    # -- set-up (reference §1 steps 1–6) --------------------------------------------------
    def _current(self, key: DeviceKey, node_id: int, generation: int, epoch: int) -> bool:
        with self._lock:
            node = self._nodes.get(node_id)
            return (epoch == self._epoch and node is not None and node.key == key
                    and node.generation == generation)

    def _setup_job(self, key: DeviceKey, node_id: int, generation: int, epoch: int) -> None:
        try:
            if not self._current(key, node_id, generation, epoch):
                return  # it left (or bound again) while queued: a bind flood of made-up
                # devices must not keep a real one waiting behind their timeouts
            device = self._read_device(key, node_id)
            if self._current(key, node_id, generation, epoch):
                self._commit(key, node_id, generation, epoch, device)
        except PdcpError as err:
            if self._current(key, node_id, generation, epoch) and not self._stop.is_set():
                with self._lock:
                    if (key not in self._setup_failures
                            and len(self._setup_failures) >= MAX_KEYS_REMEMBERED):
                        del self._setup_failures[next(iter(self._setup_failures))]  # oldest
                    failures = self._setup_failures[key] = self._setup_failures.get(key, 0) + 1
                again = failures < SETUP_ATTEMPTS
                self._error(f"set-up of device {key} (node {node_id}) failed: {err}"
                            + ("; resetting it to try again" if again else ""), "setup")
                if again:
                    self._send_quiet(Reset(node_id))
        except Exception:
            log.exception("%s: set-up of %s failed", self.name, key)
        finally:
            with self._lock:
                if self._setups.get(key) == (epoch, generation):
                    del self._setups[key]
                self._last_change = time.monotonic()
            self._wake.set()

    def _read_device(self, key: DeviceKey, node_id: int) -> Device:
        """Steps 1–3 and the reads of steps 4–5: the device and all its channels (the reader
        the scan uses too)."""
        reader = DeviceReader(self.requests, descriptor_bulk=False)
        values: param_fields.Values = {}
        reader.read_device(key, node_id, SETUP, values)
        problem = reader.identity_problem(key, node_id, values)
        if problem:
            self._error(f"device {key} after binding: {problem}", "setup")
        reader.read_channels(key, node_id, SETUP, values,
                             lambda why: self._error(why, "setup"))
        return param_fields.device_from_values(key, values)

    def _commit(self, key: DeviceKey, node_id: int, generation: int, epoch: int,
                device: Device) -> None:
        """Steps 4 (channel node IDs), 5 and 6: install the device, re-make its links."""
        with self._plan_lock:
            ids: dict[int, int] = {}
            refused: list[str] = []
            why = ""
            with self._lock:
                if not self._current(key, node_id, generation, epoch):
                    return
                for ch in device.outputs():
                    try:
                        ids[ch.index] = self._pool.take((key, ch.index))
                    except NodeIdExhaustedError as err:
                        refused.append(str(device.ref(ch.index)))
                        why = str(err)
                self._refresh_channel_ids()
            if refused:  # one line per device naming every output left without an ID
                self._error(f"output {', output '.join(refused)} gets no node ID and cannot be "
                            f"linked: {why}", "node_ids_exhausted")
            for index, channel_id in ids.items():
                self.requests.set(node_id, P.OUT_NODE_ID, index, bytes([channel_id]))
                device.channels[index].node_id = channel_id
            with self._lock:
                if not self._current(key, node_id, generation, epoch):
                    return
                node = self._nodes[node_id]
                old = self._system.device(key)
                joined = old is None or not old.present
                device.present, device.node_id = True, node_id
                device.name = old.name if old is not None else ""
                node.beacon_interval = max(device.beacon_interval, 1) / 1000.0
                if old is None:
                    self._system.add_device(device)
                else:
                    self._system.devices[key] = device
                    for link in self._system.links:
                        if key in (link.output.device, link.input.device):
                            try:
                                self._system.check_link(link)
                            except ModelError:
                                self._system.remove_link(link)
                links = [lk for lk in self._system.links
                         if key in (lk.output.device, lk.input.device)
                         and self._system.is_present(lk.output)
                         and self._system.is_present(lk.input)]
                node.set_up = True
                node.updates.clear()
                self._setup_failures.pop(key, None)
                if joined:
                    self._duty_needed = True
                self._last_change = time.monotonic()
            for link in links:
                try:
                    self._wire_add(link)
                except PdcpError as err:
                    self._error(f"link {link} could not be re-made: {err}", "transport")
        if joined:
            log.info("%s: device %s joined (node %d, %d channels)", self.name, key, node_id,
                     len(device.channels))
            self._emit(ev.DeviceJoined(key))
        self._wake.set()

