"""The protocol's whole node-ID range (issue 10 item 5): ``sim:full`` uses every node ID 1–254;
a system needing more (70 devices, 269 IDs) is handled — the arbitrator says which outputs got
no node ID, plans never link from them, nothing crashes — in one process and with the devices
in another process on ``can:udp_multicast``."""

from __future__ import annotations

import json
import logging
import subprocess
import sys

from pdcp_studio.bus.session.sim import open_sim_session
from pdcp_studio.bus.sim.rigs import LARGE_VID, large_system, list_prostheses
from pdcp_studio.cli.main import main
from pdcp_studio.engine import plan_for
from pdcp_studio.engine.modes import without_unrouted_outputs
from pdcp_studio.model.refs import Direction
from pdcp_studio.model.system import Channel, Device, System
from pdcp_studio.storage import system_file


def exhausting_system() -> System:
    """70 devices and 199 outputs: 269 node IDs for a pool of 254."""
    system = large_system(17)  # 68 devices, 119 outputs
    devices = list(system.devices.values())
    for n in range(2):
        hub = Device(LARGE_VID, 0x0501, 5000 + n, name=f"Sensor hub {n + 1}")
        for index in range(1, 41):
            hub.add_channel(Channel(index, Direction.OUTPUT, 0x9000, 0x4620))
        devices.append(hub)
    return System(devices)


def ids_in_use(system: System) -> list[int]:
    ids = [d.node_id for d in system.devices.values() if d.node_id]
    ids += [c.node_id for d in system.devices.values() for c in d.outputs() if c.node_id]
    return sorted(ids)


def test_sim_full_is_listed_and_uses_every_node_id():
    assert "full" in list_prostheses()
    with open_sim_session("full", settle_timeout=60) as session:
        system = session.system()
        assert ids_in_use(system) == list(range(1, 255))
        assert len(system.devices) == 93 and all(d.present for d in system.devices.values())
        assert len(system.links) == 23 * 5  # every arm: two EMG inputs, three hand inputs
        plan = session.arbitrator.applied_plans[0]
        assert not any("no node ID" in note for note in plan.notes)


def test_plans_never_use_outputs_without_a_node_id():
    system = large_system(1)
    for n, device in enumerate(system.devices.values(), start=1):
        device.node_id = n
        for ch in device.outputs():
            ch.node_id = 100 + 10 * n + ch.index
    cu = next(d for d in system.devices.values() if d.pid == 0x0201)
    for ch in cu.outputs():
        ch.node_id = None  # the pool ran out while this control unit was set up
    usable, unrouted = without_unrouted_outputs(system)
    assert not usable.device(cu.key).outputs()
    assert unrouted == [cu.ref(i) for i in (3, 4, 5)]
    plan = plan_for("autoconfigure", system)
    assert all(a.link.output.device != cu.key for a in plan.actions)
    assert any("got no node ID" in note for note in plan.notes)
    assert plan.rejections  # the hand's terminals: refused with a reason, not linked
    offline = large_system(1)  # a file without node IDs is planned as it is
    assert without_unrouted_outputs(offline)[1] == []


def test_269_node_ids_needed_in_one_process(tmp_path, caplog):
    path = tmp_path / "seventy.json"
    path.write_text(system_file.dumps(exhausting_system(), node_ids=False))
    with caplog.at_level(logging.INFO, logger="pdcp_studio.bus.arbitrator.core"), \
            open_sim_session(str(path), settle_timeout=90) as session:
        system = session.system()
        assert len(ids_in_use(system)) == 254
        unassigned = [d.ref(c.index) for d in system.devices.values() if d.present
                      for c in d.outputs() if c.node_id is None]
        unbound = [d.key for d in system.devices.values() if not d.node_id]
        said = "\n".join(r.getMessage() for r in caplog.records)
        for ref in unassigned:  # named, in one line per device
            assert f"output {ref}" in said
        assert "gets no node ID" in said
        assert len(unassigned) + sum(1 + len(exhausting_system().device(k).outputs())
                                     for k in unbound) == 269 - 254
        assert "action(s) failed" not in said and "Traceback" not in said
        for link in system.links:
            assert system.channel(link.output).node_id is not None
        assert session.host.bad_frames == 0


def test_269_node_ids_needed_with_the_devices_in_another_process(tmp_path, capsys,
                                                                  multicast_url):
    path = tmp_path / "seventy.json"
    path.write_text(system_file.dumps(exhausting_system(), node_ids=False))
    url = multicast_url("239.74.163.5", 45000)
    devices = subprocess.Popen(
        [sys.executable, "-m", "pdcp_studio", "sim", "devices", str(path), "--bus", url,
         "--seconds", "120", "--rate", "2"], stderr=subprocess.PIPE, text=True)
    try:
        assert "simulating 70 device(s)" in devices.stderr.readline()
        assert main(["scan", "--bus", url, "--json", "--settle", "40"]) == 0
        assert devices.poll() is None  # the devices' process is still alive
    finally:
        devices.terminate()
        _, err = devices.communicate(timeout=10)
    assert "Traceback" not in err and "IndexError" not in err
    doc = json.loads(capsys.readouterr().out)
    ids = [d["node_id"] for d in doc["devices"] if d.get("node_id")]
    ids += [c["node_id"] for d in doc["devices"] for c in d["channels"] if c.get("node_id")]
    assert len(ids) == len(set(ids)) == 254
