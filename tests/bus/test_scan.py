"""Scan: every parameter, node IDs, links as the bus has them; window, progress, cancel."""

from __future__ import annotations

import random
import threading
import time

import pytest

from pdcp_studio.bus.arbitrator.reading.scan import ScanCancelled, estimate_reads, scan
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.sim.rigs import load_prosthesis
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import DeviceKey
from pdcp_studio.storage import system_file


def _without_runtime(doc: dict) -> dict:
    """A system document without what only a bus gives (node IDs, enabled flags, sources)."""
    for dev in doc["devices"]:
        dev.pop("node_id", None)
        dev.pop("name", None)
        dev.pop("descriptor", None)
        for ch in dev["channels"]:
            for key in ("node_id", "data_enabled", "source"):
                ch.pop(key, None)
    doc["links"] = []
    return doc


def test_scan_reads_every_parameter_as_the_system_file_has_it():
    original = load_prosthesis("transradial")
    for key in [k for k, d in original.devices.items() if not d.present]:
        original.remove_device(key)  # the spare hand: not on the bus until plugged in
    with open_session("sim:transradial", frame_events=False) as session:
        raw: dict = {}
        scanned = scan(session.arbitrator, raw=raw)
        known = session.system()
    assert _without_runtime(system_file.to_json(scanned)) == \
        _without_runtime(system_file.to_json(original))
    # Descriptors by bulk transfer, node IDs as the arbitrator gave them.
    hand = scanned.devices[DeviceKey(2641, 769, 301)]
    assert hand.descriptor == original.devices[hand.key].descriptor
    assert hand.channels[1].descriptor == original.devices[hand.key].channels[1].descriptor
    for key, dev in scanned.devices.items():
        assert dev.node_id == known.devices[key].node_id
        for ch in dev.outputs():
            assert ch.node_id == known.devices[key].channels[ch.index].node_id
        # Every catalog parameter of the device and of each channel was read.
        assert (P.DEVICE_BIND_TIMEOUT, 0) in raw[key]
        for ch in dev.channels.values():
            names = {s.id for s in P.parameters_for(ch.direction)}
            assert names <= {pid for pid, c in raw[key] if c == ch.index}
    assert scanned.links == known.links and len(scanned.links) == 5
    inputs = [c for d in scanned.devices.values() for c in d.inputs()]
    assert all(c.source.connected and c.data_enabled for c in inputs)
    assert len(raw) == 4 and sum(map(len, raw.values())) == estimate_reads(scanned)


def test_links_come_from_the_wire_not_from_the_model():
    with open_session("sim:thesis-test2", frame_events=False) as session:
        link = session.system().links[0]
        # Disable the input behind the arbitrator's back: the bus no longer has that link.
        session.arbitrator.requests.set(session.arbitrator.node_id_of(link.input.device),
                                        P.CH_DATA_ENABLED, link.input.index, b"\x00")
        scanned = session.scan()
        assert link in session.system().links
        assert link not in scanned.links and len(scanned.links) == 2


def test_window_bounds_outstanding_requests_and_progress_counts_up():
    with open_session("sim:transradial", frame_events=False) as session:
        engine = session.arbitrator.requests
        real_get = engine.get
        lock = threading.Lock()
        active, peak = [0], [0]

        def counting_get(*args, **kwargs):
            with lock:
                active[0] += 1
                peak[0] = max(peak[0], active[0])
            try:
                time.sleep(0.001)
                return real_get(*args, **kwargs)
            finally:
                with lock:
                    active[0] -= 1

        engine.get = counting_get
        progress: list[tuple[int, int]] = []
        scan(session.arbitrator, lambda d, t, s: progress.append((d, t)), window=2)
        assert peak[0] == 2
        peak[0] = 0
        scan(session.arbitrator, window=1)
        assert peak[0] == 1
    done = [d for d, _ in progress]
    assert done == sorted(done) and progress[-1][0] == progress[-1][1] == progress[0][1]


def test_cancel_raises_with_the_devices_read_so_far():
    with open_session("sim:large", frame_events=False) as session:
        cancel = threading.Event()

        def progress(done: int, total: int, text: str) -> None:
            if done >= total // 3:
                cancel.set()

        started = time.monotonic()
        with pytest.raises(ScanCancelled, match="cancelled after") as info:
            scan(session.arbitrator, progress, cancel, window=4)
        assert time.monotonic() - started < 2.0
        partial = info.value.partial
        assert 0 < len(partial.devices) < 32
        assert all(d.channels for d in partial.devices.values())


def test_a_device_that_leaves_mid_scan_is_left_out_and_named():
    with open_session("sim:thesis-test2", frame_events=False) as session:
        engine = session.arbitrator.requests
        real_get = engine.get
        gone = session.arbitrator.node_id_of(DeviceKey(2, 2, 6))

        def get(node_id, param, channel, **kwargs):
            if node_id == gone and channel == 1 and param == P.CH_TRANSFER_TYPE:
                session.host.unplug(DeviceKey(2, 2, 6))
            return real_get(node_id, param, channel, **kwargs)

        engine.get = get
        problems: list[str] = []
        scanned = scan(session.arbitrator, problems=problems, read_timeout=1.0)
    assert set(scanned.devices) == {DeviceKey(2, 2, 4), DeviceKey(2, 2, 5)}
    assert len(problems) == 1 and "2/2/6" in problems[0]
    assert len(scanned.links) == 1  # the link into the gone device is not on the bus


def test_scan_completes_correctly_with_5_percent_of_frames_dropped():
    rng = random.Random(7)
    with open_session("sim:thesis-test2", frame_events=False) as session:
        expected = session.scan()
        buses = [session.host.conn.bus, session.arbitrator.conn.bus]
        dropped = [0]
        for bus in buses:
            real_send = bus.send

            def lossy(msg, timeout=None, _send=real_send):
                if rng.random() < 0.05:
                    dropped[0] += 1
                    return None
                return _send(msg, timeout)

            bus.send = lossy
        scanned = session.scan()
        retries = session.arbitrator.requests.stats.retries
    assert dropped[0] > 5 and retries > 0
    assert system_file.to_json(scanned) == system_file.to_json(expected)
