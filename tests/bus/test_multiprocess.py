"""Devices here, the arbitrator in another process: python-can udp_multicast on loopback."""

from __future__ import annotations

import queue
import signal
import subprocess
import sys
import threading
import time

import pytest

from pdcp_studio.bus.session.urls import open_spec, parse_bus_url
from pdcp_studio.bus.sim.device import SimulatedDevice, State
from pdcp_studio.bus.sim.device_host import DeviceHost
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import DeviceKey
from tests.bus.test_arbitrator_rig import load

GROUP = "239.74.163.2"


class Lines:
    """A subprocess's stdout, line by line, readable with a timeout; its stderr is drained
    too (into ``errors``), so a chatty child never blocks on a full pipe."""

    def __init__(self, proc: subprocess.Popen) -> None:
        self.all: list[str] = []
        self.errors: list[str] = []
        self._q: queue.SimpleQueue[str] = queue.SimpleQueue()
        threading.Thread(target=self._read, args=(proc,), daemon=True).start()
        self.stderr_reader = threading.Thread(target=self.errors.extend, args=(proc.stderr,),
                                              daemon=True)
        self.stderr_reader.start()

    def _read(self, proc: subprocess.Popen) -> None:
        for line in proc.stdout:
            self._q.put(line.rstrip("\n"))

    def until(self, predicate, timeout: float = 10.0) -> bool:
        deadline = time.monotonic() + timeout
        while not predicate(self.all):
            left = deadline - time.monotonic()
            if left <= 0:
                return False
            try:
                self.all.append(self._q.get(timeout=left))
            except queue.Empty:
                return False
        return True


#: ``python -m pdcp_studio`` that Ctrl-C stops whatever the test run inherited: a shell
#: starts a background job (``pytest &``) with SIGINT ignored, every child inherits that,
#: and the arbitrator below would then never hear the SIGINT that ends the test.
_CTRL_C_ABLE = ("import signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler); "
                "from pdcp_studio.cli.main import main; sys.exit(main())")


@pytest.mark.slow
def test_arbitrator_process_binds_and_links_devices_of_this_process(tmp_path, multicast_url):
    url = multicast_url(GROUP, 41000)
    system = load("appendix-d")
    devices = [SimulatedDevice(d, data_rate_hz=20) for d in system.devices.values()]
    host = DeviceHost(open_spec(parse_bus_url(url)), devices, plugged=True, name="here")
    proc = subprocess.Popen(
        [sys.executable, "-c", _CTRL_C_ABLE, "arbitrator", "--bus", url,
         "--memory", str(tmp_path / "mem"), "--startup-quiet", "0.3"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    lines = Lines(proc)
    try:
        assert lines.until(lambda ls: any(s.startswith("plan startup") for s in ls), 20), \
            "\n".join(lines.all)
        assert lines.until(lambda ls: sum(s.startswith("  add ") for s in ls) == 3, 15)
        text = "\n".join(lines.all)
        for serial in (4, 5, 6):
            assert f"joined 2/2/{serial}" in text
        assert "plan startup: 3 added, 0 removed, 3 links" in text
        # The links exist in this process's devices: inputs listen to their sources.
        sn4, sn5, sn6 = (DeviceKey(2, 2, s) for s in (4, 5, 6))

        def state(k, param, ch):
            return host.call(lambda: host.device(k).nv[param, ch])

        out_node = state(sn4, P.OUT_NODE_ID, 1)[0]
        assert out_node
        assert state(sn5, P.IN_SOURCE_NODE_IDS, 2) == bytes([host.device(sn4).node_id,
                                                              out_node])
        assert state(sn5, P.CH_DATA_ENABLED, 2) == b"\x01"
        deadline = time.monotonic() + 3
        while 2 not in host.device(sn6).received and time.monotonic() < deadline:
            time.sleep(0.02)
        assert 2 in host.device(sn6).received  # data flows SN5.O5 → SN6.I2
        # A device leaving is noticed by its beacons.
        host.unplug(sn4)
        assert lines.until(lambda ls: "left 2/2/4" in ls, 15), "\n".join(lines.all)
        assert host.device(sn5).state is State.BOUND
    finally:
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(30)
        finally:
            if proc.poll() is None:
                proc.kill()
            host.close()
    assert lines.until(lambda ls: "arbitrator stopped" in ls, 20)
    lines.stderr_reader.join(5)  # the child has exited: its stderr is at its end
    assert proc.returncode == 0, "".join(lines.errors)
    proc.stdout.close()
    proc.stderr.close()
