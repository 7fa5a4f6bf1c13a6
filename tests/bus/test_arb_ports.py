"""The arbitrator's parts work with their ports alone (issue 23 item 2): each is given the few
callables and objects it needs — here recording fakes — never the arbitrator."""

from __future__ import annotations

import threading
import time

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.jobs import JobPool
from pdcp_studio.bus.arbitrator.links import LinkWriter
from pdcp_studio.bus.arbitrator.nodes import NodeTable
from pdcp_studio.bus.arbitrator.state import SystemState
from pdcp_studio.model import parameters as P
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link
from pdcp_studio.protocol import BindRequest, UpdateDataChannel, UpdateDataChannelResponse

SENSOR, HAND = DeviceKey(2, 2, 4), DeviceKey(2, 2, 6)
LINK = Link(ChannelRef(*SENSOR, 1), ChannelRef(*HAND, 2))


def _device(key: DeviceKey, channel: Channel) -> Device:
    device = Device(*key)
    device.add_channel(channel)
    return device


def _bound(table: NodeTable, key: DeviceKey, node_id: int) -> None:
    assert table.decide_bind(BindRequest(node_id, *key), 0.0).kind == "grant"
    table.install(key, node_id, 0.0, 0.1)


class Requests:
    """Set Parameter recorded, never on a bus."""

    def __init__(self) -> None:
        self.sets: list[tuple[int, int, int, bytes]] = []

    def set(self, node_id: int, param: int, channel: int, value: bytes) -> None:
        self.sets.append((node_id, param, channel, value))


def _rig() -> tuple[SystemState, NodeTable, Requests, LinkWriter, list[object], list[object]]:
    state, table, requests = SystemState(), NodeTable(1, 254), Requests()
    state.system.add_device(_device(SENSOR, Channel(1, Direction.OUTPUT, 0x5001)))
    state.system.add_device(_device(HAND, Channel(2, Direction.INPUT)))
    _bound(table, SENSOR, 10)
    _bound(table, HAND, 12)
    table.give_outputs(SENSOR, [1])
    said: list[object] = []
    jobs: list[object] = []
    writer = LinkWriter(state, table, requests, send=said.append, submit=jobs.append,  # type: ignore[arg-type]
                        error=lambda message, kind: said.append((kind, message)),
                        emit=said.append, name="ports")
    return state, table, requests, writer, said, jobs


def test_the_node_table_stamps_the_model_s_node_ids_and_clears_them_when_a_device_leaves() -> None:
    table = NodeTable(1, 254)
    _bound(table, SENSOR, 10)
    ids, refused, _ = table.give_outputs(SENSOR, [1])
    device = _device(SENSOR, Channel(1, Direction.OUTPUT))
    device.add_channel(Channel(2, Direction.INPUT))
    table.stamp(device)
    assert device.node_id == 10 and device.channels[1].node_id == ids[1] and not refused
    assert device.channels[2].node_id is None  # an input sends nothing
    node = table.node(SENSOR)
    assert node is not None and table.remove(node)
    table.stamp(device)
    assert device.node_id is None and device.channels[1].node_id is None


def test_the_link_writer_makes_a_link_through_its_ports_only() -> None:
    state, table, requests, writer, said, _ = _rig()
    writer.add_link(LINK)
    out_id = table.output_id(LINK.output)
    assert out_id is not None
    assert requests.sets[0] == (12, P.IN_SOURCE_NODE_IDS, 2, bytes([10, out_id]))
    assert requests.sets[-1] == (10, P.CH_DATA_ENABLED, 1, b"\x01")
    assert state.system.has_link(LINK) and said == [ev.LinkMade(LINK)]
    hand = state.system.channel(LINK.input)
    assert hand is not None and hand.data_enabled


def test_an_update_request_is_answered_through_send_and_the_links_re_made_as_a_job() -> None:
    _, table, requests, writer, said, jobs = _rig()
    writer.add_link(LINK)
    said.clear()
    node = table.node(HAND)
    assert node is not None
    node.set_up = True
    writer.on_update(node, UpdateDataChannel(12, 2))
    assert isinstance(said[0], UpdateDataChannelResponse) and len(jobs) == 1
    before = len(requests.sets)
    jobs[0]()  # type: ignore[operator]
    assert len(requests.sets) > before  # the link written again


def test_a_job_counts_as_business_until_it_returns() -> None:
    lock = threading.RLock()
    pool = JobPool(1, "ports", lock)
    inside, leave = threading.Event(), threading.Event()

    def job() -> None:
        inside.set()
        leave.wait(5)

    try:
        pool.submit(job)
        assert inside.wait(5)
        with lock:
            assert pool.busy()
        leave.set()
        deadline = time.monotonic() + 5
        while pool.busy() and time.monotonic() < deadline:
            time.sleep(0.01)
        with lock:
            assert not pool.busy()
    finally:
        pool.shutdown()
