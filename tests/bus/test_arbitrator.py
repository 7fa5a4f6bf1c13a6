"""The arbitrator against simulated devices on python-can's virtual bus."""

from __future__ import annotations

import struct
import time

import can
import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.arbitrator.core import MISSED_BEACONS, Arbitrator
from pdcp_studio.bus.arbitrator.reading.requests import DeviceRefusedError
from pdcp_studio.bus.sim.device import State
from pdcp_studio.engine import plan_autoconfigure, plan_startup
from pdcp_studio.errors import ModelError, TransportError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.system import Link
from pdcp_studio.protocol import (
    BindRequest,
    BindResponse,
    FunctionCode,
    UpdateDataChannel,
    UpdateDataChannelResponse,
    decode,
)
from tests.bus.test_arbitrator_rig import Rig, key, link, load, ref

APPENDIX_D = [link((4, 1), (5, 2)), link((5, 3), (6, 1)), link((5, 5), (6, 2))]


class Tap:
    """A passive listener on the rig's channel: every frame, decoded where possible."""

    def __init__(self, rig: Rig) -> None:
        self.bus = rig.bus()
        self.frames: list[can.Message] = []
        self.notifier = can.Notifier(self.bus, [self.frames.append], timeout=0.02)

    def messages(self, kind: type) -> list:
        out = []
        for msg in list(self.frames):
            try:
                m = decode(msg.arbitration_id, bytes(msg.data))
            except Exception:
                continue
            if isinstance(m, kind):
                out.append(m)
        return out

    def close(self) -> None:
        self.notifier.stop(timeout=1)
        self.bus.shutdown()


def test_binding_suggests_a_free_id_then_grants_it_and_shares_the_pool_with_outputs():
    system = load("appendix-d")
    for device in system.devices.values():
        device.node_id = 1  # every device asks for node ID 1
    with Rig(system, arbitrator=False) as rig:
        tap = Tap(rig)
        try:
            rig.start_arbitrator()
            rig.settle()
            snapshot = rig.arb.system()
        finally:
            tap.close()
    device_ids = {d.key: d.node_id for d in snapshot.devices.values()}
    output_ids = [c.node_id for d in snapshot.devices.values() for c in d.outputs()]
    assert all(device_ids.values()) and all(output_ids)
    every = list(device_ids.values()) + output_ids
    assert len(every) == len(set(every)) == 7  # one pool: no ID twice
    assert set(every) == set(range(1, 8))  # lowest free first
    # On the wire: one device got 1 at once; the others were told another ID, asked for
    # exactly that one, and only then got it.
    answers = tap.messages(BindResponse)
    asks = tap.messages(BindRequest)
    granted = [a for a in answers if a.accepted]
    assert sorted(a.granted_node_id for a in granted) == sorted(device_ids.values())
    for a in answers:
        if not a.accepted:
            assert a.node_id == 1
            assert any(r.node_id == a.granted_node_id and r.serial == a.serial for r in asks)
    assert sum(not a.accepted for a in answers) >= 2


def test_setup_reads_every_channel_and_writes_output_node_ids():
    with Rig("appendix-d") as rig:
        rig.settle()
        got = rig.arb.system()
        for original in rig.system.devices.values():
            device = got.devices[original.key]
            assert device.present
            assert device.descriptor == original.descriptor
            assert device.beacon_interval == 50
            assert device.node_id == rig.device(original.key).node_id
            assert sorted(device.channels) == sorted(original.channels)
            for index, want in original.channels.items():
                ch = device.channels[index]
                assert (ch.direction, ch.type, ch.profile) == (want.direction, want.type,
                                                               want.profile)
                assert ch.required_inputs == want.required_inputs
                assert ch.descriptor == want.descriptor
                if ch.is_input:
                    assert ch.terminal_profile == want.terminal_profile
                else:  # step 4: the Channel Node Id on the device is the one in the model
                    assert rig.nv(original.key, P.OUT_NODE_ID, index) == bytes([ch.node_id])
        assert [type(e) for e in rig.of(ev.DeviceJoined)] == [ev.DeviceJoined] * 3


def test_get_and_set_parameters_including_bulk_both_ways():
    with Rig("appendix-d") as rig:
        rig.settle()
        arb, d5 = rig.arb, key(5)
        # Inline get and set.
        assert arb.get_parameter(d5, P.DEVICE_VID_PID) == struct.pack("<HH", 2, 2)
        arb.set_parameter(d5, P.DEVICE_ACK_TIMEOUT, 0, struct.pack("<H", 77))
        assert rig.nv(d5, P.DEVICE_ACK_TIMEOUT) == struct.pack("<H", 77)
        assert arb.system().devices[d5].ack_timeout == 77
        # Bulk get (the device answers "use bulk"), then bulk set of 40 bytes and back.
        assert arb.get_parameter(d5, P.DEVICE_DESCRIPTOR) == b"Control unit board\0"
        text = "Prototype PDCP Device Descriptor, rev B"
        arb.set_parameter(d5, P.CH_DESCRIPTOR, 3, text.encode() + b"\0")
        assert rig.nv(d5, P.CH_DESCRIPTOR, 3) == text.encode() + b"\0"
        assert arb.get_parameter(d5, P.CH_DESCRIPTOR, 3) == text.encode() + b"\0"
        assert arb.system().devices[d5].channels[3].descriptor == text
        # What a device refuses, and what the arbitrator keeps to itself.
        with pytest.raises(DeviceRefusedError):
            arb.get_parameter(d5, 99)
        with pytest.raises(DeviceRefusedError):
            arb.set_parameter(d5, P.DEVICE_SERIAL, 0, b"\1\0")
        with pytest.raises(ModelError, match="managed by the arbitrator"):
            arb.set_parameter(d5, P.OUT_NODE_ID, 3, b"\x09")
        with pytest.raises(TransportError, match="not on the bus"):
            arb.get_parameter(key(99), P.DEVICE_VID_PID)
        stats = arb.requests.stats
        assert stats.timeouts == 0


def test_beacon_interval_written_by_set_parameter_drives_presence():
    with Rig("appendix-d") as rig:
        rig.settle()
        rig.arb.set_parameter(key(4), P.DEVICE_BEACON_INTERVAL, 0, struct.pack("<H", 250))
        node = rig.arb._nodes[rig.arb.node_id_of(key(4))]
        assert node.beacon_interval == pytest.approx(0.25)
        time.sleep(0.6)  # silent for longer than 3.5 of the old 50 ms intervals
        assert not rig.of(ev.DeviceLeft)


def _listening(rig: Rig, inp) -> tuple[bytes, bytes]:
    return (rig.nv(inp.device, P.IN_SOURCE_NODE_IDS, inp.index),
            rig.nv(inp.device, P.CH_DATA_ENABLED, inp.index))


def test_links_on_the_wire_make_data_flow_and_removal_clears_them():
    with Rig("thesis-test2", profile_layer=False) as rig:
        rig.settle()
        arb = rig.arb
        new = link((4, 1), (5, 2))
        arb.add_link(new)
        out_node = arb.channel_node_id(new.output)
        assert _listening(rig, new.input) == (bytes([arb.node_id_of(key(4)), out_node]), b"\1")
        assert rig.nv(key(4), P.CH_DATA_ENABLED, 1) == b"\1"
        # The redundant source fields (behaviour 1, §4.3.2).
        assert rig.nv(key(5), P.IN_SOURCE_VID_PID, 2) == struct.pack("<HH", 2, 2)
        assert rig.nv(key(5), P.IN_SOURCE_SN_INDEX, 2) == struct.pack("<HB", 4, 1)
        assert rig.nv(key(5), P.IN_SOURCE_TYPE_PROFILE, 2) == struct.pack("<HH", 0x5000,
                                                                            0x2120)
        got = arb.system()
        assert got.links == [new]
        assert got.channel(new.input).source.ref == new.output
        assert got.channel(new.input).data_enabled and got.channel(new.output).data_enabled
        # Data flows: the input receives the output's samples.
        assert rig.wait(lambda: 2 in rig.device(key(5)).received, 2.0)
        assert rig.wait(lambda: rig.values > 0, 2.0)
        assert [e.link for e in rig.of(ev.LinkMade)] == [new]
        # Refused by the model: a second source, the wrong direction.
        with pytest.raises(ModelError, match="already has source"):
            arb.add_link(link((5, 3), (5, 2)))
        with pytest.raises(ModelError):
            arb.add_link(Link(new.input, new.output))
        arb.remove_link(new)
        assert _listening(rig, new.input) == (b"\0\0", b"\0")
        assert rig.nv(key(5), P.IN_SOURCE_SN_INDEX, 2) == struct.pack("<HB", 0xFFFF, 0xFF)
        assert rig.nv(key(4), P.CH_DATA_ENABLED, 1) == b"\0"
        assert arb.system().links == []
        assert [e.link for e in rig.of(ev.LinkRemoved)] == [new]
        with pytest.raises(ModelError):
            arb.remove_link(new)


def test_startup_on_appendix_d_gives_the_engines_links():
    with Rig("appendix-d") as rig:
        rig.settle()
        expected = plan_startup(rig.system, None).final_links
        assert expected == APPENDIX_D
        assert rig.arb.system().links == expected
        plans = rig.arb.applied_plans
        assert [p.mode for p in plans] == ["startup"]
        assert plans[0].configuration_source == "retrieved"
        assert [type(e) for e in rig.of(ev.PlanApplied)] == [ev.PlanApplied]
        for lk in expected:  # each link is live on the wire
            assert _listening(rig, lk.input)[1] == b"\1"


def test_startup_without_any_configuration_autoconfigures_test2():
    with Rig("thesis-test2") as rig:
        rig.settle()
        assert rig.arb.system().links == plan_autoconfigure(rig.system).final_links
        assert rig.arb.system().links == APPENDIX_D


def test_stored_configuration_wins_over_the_devices_and_survives_a_reset(tmp_path):
    memory = tmp_path / "arbitrator.mem"
    auto, chosen = link((4, 1), (5, 1)), link((4, 1), (5, 2))
    with Rig("thesis-test1", memory=memory) as rig:
        rig.settle()
        arb = rig.arb
        assert arb.system().links == [auto]  # autoconfigure: no configuration anywhere
        arb.remove_link(auto)
        arb.add_link(chosen)
        saved = arb.save_configuration()
        assert [sl.input.ref for sl in saved.configurations[0].links] == [chosen.input]
        # Input 5.1 now claims 4.1 as its source too (a device configured elsewhere).
        arb.set_parameter(key(5), P.IN_SOURCE_VID_PID, 1, struct.pack("<HH", 2, 2))
        arb.set_parameter(key(5), P.IN_SOURCE_SN_INDEX, 1, struct.pack("<HB", 4, 1))
        arb.set_parameter(key(5), P.IN_SOURCE_TYPE_PROFILE, 1, struct.pack("<HH", 0x5000,
                                                                            0x2110))
        arb.reset(keep_memory=True)  # test 3: the stored configuration wins
        assert rig.wait(lambda: len(arb.applied_plans) >= 2, 5)
        rig.settle()
        assert arb.system().links == [chosen]
        assert arb.applied_plans[-1].configuration_source == "stored"
        # Test 5: a replaced arbitrator (memory erased) rebuilds from the devices' fields,
        # in ascending input order: 5.1 takes 4.1 first, 5.2 then breaks sole access.
        arb.reset(keep_memory=False)
        assert arb.read_memory() == ConfigCollection()
        assert rig.wait(lambda: len(arb.applied_plans) >= 3, 5)
        rig.settle()
        assert arb.system().links == [auto]
        assert arb.applied_plans[-1].configuration_source == "retrieved"
    # The memory file outlives the arbitrator: what was stored last is what a new one reads.
    again = Arbitrator(can.Bus(interface="virtual", channel="pdcp-mem-reopen"),
                       memory=memory, profile_layer=False)
    try:
        assert again.read_memory() == ConfigCollection()
        assert again.memory.generation == 2
    finally:
        again.close()


def test_memory_round_trip_through_a_new_arbitrator(tmp_path):
    memory = tmp_path / "mem.bin"
    with Rig("appendix-d", memory=memory) as rig:
        rig.settle()
        stored = rig.arb.save_configuration()
    with Rig("thesis-test2", memory=memory) as rig:  # devices without stored sources
        rig.settle()
        assert rig.arb.read_memory() == stored
        assert rig.arb.system().links == APPENDIX_D
        assert rig.arb.applied_plans[0].configuration_source == "stored"


def test_departure_after_three_missed_beacons_reclaims_ids_and_rejoin_relinks():
    with Rig("appendix-d") as rig:
        rig.settle()
        arb = rig.arb
        free_before = arb._pool.free_count
        gone_at = time.monotonic()
        rig.host.unplug(key(4))
        assert rig.wait(lambda: rig.of(ev.DeviceLeft), 2)
        waited = time.monotonic() - gone_at
        assert waited >= MISSED_BEACONS * 0.05 * 0.9
        assert rig.of(ev.DeviceLeft)[0].key == key(4)
        snap = arb.system()
        assert not snap.devices[key(4)].present
        assert snap.devices[key(4)].node_id is None
        assert snap.has_link(APPENDIX_D[0])  # a dead link, kept for the duty cycle
        assert arb.node_id_of(key(4)) is None
        assert arb._pool.free_count == free_before + 2  # device + its output
        # The input it fed stops listening (its node ID may be handed out again).
        assert rig.wait(lambda: _listening(rig, APPENDIX_D[0].input)[1] == b"\0", 2)
        rig.settle(devices=2)
        # Re-plugged: it binds again, is set up, and its link is live again.
        rig.host.plug(key(4))
        assert rig.wait(lambda: len(rig.of(ev.DeviceJoined)) == 4, 3)
        rig.settle()
        assert arb.system().links == APPENDIX_D
        out = arb.channel_node_id(APPENDIX_D[0].output)
        assert _listening(rig, APPENDIX_D[0].input) == (
            bytes([arb.node_id_of(key(4)), out]), b"\1")


def test_hot_swap_duty_cycle_replaces_a_missing_input_test1():
    with Rig("thesis-test1") as rig:
        rig.settle()
        assert rig.arb.system().links == [link((4, 1), (5, 1))]
        rig.host.unplug(key(5))
        rig.host.plug(key(6))
        assert rig.wait(lambda: rig.of(ev.DeviceLeft) and len(rig.of(ev.DeviceJoined)) == 3)
        rig.settle()
        assert rig.wait(lambda: rig.arb.system().links == [link((4, 1), (6, 1))], 2)
        modes = [p.mode for p in rig.arb.applied_plans]
        assert modes[0] == "startup" and "duty-cycle" in modes
        assert _listening(rig, ref(6, 1))[1] == b"\1"


def test_update_data_channel_requests_are_answered():
    with Rig("appendix-d", plug=[]) as rig:
        tap = Tap(rig)  # listening before any device is plugged: it hears every request
        asked = {(d.key, c.index) for d in rig.system.devices.values() for c in d.inputs()}

        def answered() -> bool:
            """Every input asked and answered OK (the tap hears the answers a moment after
            the arbitrator settles: on a loaded machine, later)."""
            by_node = {rig.arb.node_id_of(k): k for k in rig.arb.devices_present()}
            return {(by_node.get(a.node_id), a.channel)
                    for a in tap.messages(UpdateDataChannelResponse) if a.code == 1} >= asked

        try:
            keys = [d.key for d in rig.system.devices.values() if d.present]
            for k in keys:
                rig.host.plug(k)
            rig.settle(devices=len(keys))
            rig.wait(answered, 10)
            requests = {(u.node_id, u.channel) for u in tap.messages(UpdateDataChannel)}
            answers = tap.messages(UpdateDataChannelResponse)
        finally:
            tap.close()
        assert requests <= {(a.node_id, a.channel) for a in answers}  # every one answered
        ok = {(a.node_id, a.channel) for a in answers if a.code == 1}
        if not rig.of(ev.DeviceLeft):  # (a starved test machine may drop one and re-bind it)
            by_node = {rig.arb.node_id_of(k): k for k in rig.arb.devices_present()}
            assert {(by_node[n], c) for n, c in ok} == asked
        for k in rig.arb.devices_present():
            assert rig.host.call(lambda k=k: dict(rig.device(k)._pending_updates)) == {}


def test_an_update_data_channel_request_after_setup_remakes_that_inputs_link():
    with Rig("appendix-d") as rig:
        rig.settle()
        lk = APPENDIX_D[0]
        want = _listening(rig, lk.input)
        assert want[1] == b"\1"

        def forget() -> None:  # the input lost its session values (a glitch, say)
            dev = rig.device(key(5))
            dev.nv[P.IN_SOURCE_NODE_IDS, 2] = b"\0\0"
            dev.nv[P.CH_DATA_ENABLED, 2] = b"\0"
            dev._pending_updates[2] = 1
            dev._request_update(2)  # and asks the arbitrator for its source again

        rig.host.call(forget)
        assert rig.wait(lambda: _listening(rig, lk.input) == want, 2)
        assert rig.arb.system().links == APPENDIX_D


def test_suspend_release_and_reset_device():
    with Rig("appendix-d") as rig:
        rig.settle()
        arb, d6 = rig.arb, key(6)

        def fresh() -> bool:
            got = rig.device(d6).received.get(1)
            return got is not None and time.time() - got[1] < 0.15

        assert rig.wait(fresh, 2)
        arb.suspend(key(5), 0)
        time.sleep(0.3)
        assert not fresh()
        assert not rig.of(ev.DeviceLeft)  # beacons go on while suspended
        arb.release(key(5))
        assert rig.wait(fresh, 2)
        joined = len(rig.of(ev.DeviceJoined))
        node = arb.node_id_of(d6)
        device = rig.device(d6)
        restarts = []
        restart = device.power_on
        device.power_on = lambda: (restarts.append(1), restart())  # the reset's restart
        arb.reset_device(d6)  # it restarts: binds again and is set up again
        assert rig.wait(lambda: restarts and device.state is State.BOUND, 2), \
            "the reset device did not restart and bind again"
        rig.settle()
        assert len(rig.of(ev.DeviceJoined)) == joined  # not a new device
        assert arb.node_id_of(d6) == node
        assert rig.wait(fresh, 2)  # its links were made again
        assert arb.system().links == APPENDIX_D


def test_a_device_bound_by_an_earlier_arbitrator_is_reset_and_binds_again():
    with Rig("appendix-d") as rig:
        rig.settle()
        rig.arb.close()
        rig.start_arbitrator(reset_on_start=False)  # it hears beacons of nodes it never bound
        rig.settle()
        assert sorted(rig.arb.devices_present()) == [key(4), key(5), key(6)]
        assert rig.arb.system().links == APPENDIX_D


def test_apply_plan_reports_progress_logs_and_can_be_cancelled():
    import threading

    with Rig("thesis-test2", profile_layer=False) as rig:
        rig.settle()
        plan = plan_autoconfigure(rig.arb.system())
        seen: list[tuple[int, int, str]] = []
        rig.arb.apply_plan(plan, progress=lambda d, t, w: seen.append((d, t, w)))
        assert seen[-1][:2] == (3, 3)
        assert rig.arb.applied_plans == [plan]
        assert rig.arb.system().links == plan.final_links
        cancel = threading.Event()
        cancel.set()
        from pdcp_studio.engine import plan_clear

        clear = plan_clear(rig.arb.system())
        result = rig.arb.apply_plan(clear, cancel=cancel)
        assert rig.arb.system().links == plan.final_links
        assert result.status == "failed" and "cancelled after 0 of 3 actions" in result.reason
        assert clear.notes == []  # the plan is not changed by carrying it out
        rig.arb.apply_plan(plan_clear(rig.arb.system()))
        assert rig.arb.system().links == []


def test_close_is_idempotent_and_a_context_manager():
    bus = can.Bus(interface="virtual", channel="pdcp-close-test")
    with Arbitrator(bus, profile_layer=False) as arb:
        assert arb.wait_settled(1)
    assert arb.closed
    arb.close()
    assert not arb.wait_settled(0.01) or arb.closed


def test_unsubscribe_stops_events():
    with Rig("appendix-d", arbitrator=False) as rig:
        arb = rig.start_arbitrator()
        got: list = []
        stop = arb.subscribe(got.append)
        rig.settle()
        assert any(isinstance(e, ev.DeviceJoined) for e in got)
        stop()
        n = len(got)
        arb.reset()
        rig.settle()
        assert len(got) == n


def test_frame_events_describe_frames():
    with Rig("appendix-d", frame_events=True) as rig:
        rig.settle()
        frames = rig.of(ev.FrameSeen)
        assert frames
        texts = " | ".join(f.text for f in frames[:400])
        assert FunctionCode.BIND_REQUEST.title in texts
        assert "Get Device Parameter" in texts


def _frame(prio: int, mode: int, node: int, hexdata: str) -> tuple[int, bytes]:
    from pdcp_studio.protocol import make_id

    return make_id(prio, mode, node), bytes.fromhex(hexdata)


def test_the_worked_frames_of_001_section_3_3_appear_on_the_bus_in_order():
    """001 §3.3.1, 3.3.2, 3.3.3, 3.3.4 and 3.3.6, frame for frame: a device VID 1, PID 10,
    SN 4 with one output asks for node 1, is told 5 (1–4 are in use), gets it, is read and
    has its output numbered 6; its 33-byte descriptor comes by bulk transfer."""
    from pdcp_studio.model.refs import Direction
    from pdcp_studio.model.system import Channel, Device, System

    device = Device(1, 10, 4, descriptor="Prototype PDCP Device Descriptor", node_id=1,
                    beacon_interval=50, bind_timeout=60)
    device.add_channel(Channel(1, Direction.OUTPUT, 0x5000, 0x2110))
    with Rig(System([device]), arbitrator=False) as rig:
        tap = Tap(rig)
        try:
            rig.start_arbitrator(node_ids=(5, 254), profile_layer=False)
            rig.settle()
            time.sleep(0.06)
        finally:
            tap.close()
    seen = [(m.arbitration_id, bytes(m.data)) for m in tap.frames]
    expected = [
        _frame(3, 0, 1, "01 01 00 0A 00 04 00"),  # 3.3.1 binding
        _frame(1, 1, 1, "81 05 01 00 0A 00 04 00"),
        _frame(3, 0, 5, "01 01 00 0A 00 04 00"),
        _frame(1, 1, 5, "81 05 01 00 0A 00 04 00"),
        _frame(0, 0, 5, "0A"),  # 3.3.4 beacon
        _frame(1, 1, 5, "03 07 00"),  # 3.3.6 bulk get of the device descriptor
        _frame(1, 0, 5, "83 02 07 00"),
        _frame(1, 1, 5, "0C 07 00"),
        _frame(1, 0, 5, "8C 01 07 00 21 00"),
        _frame(1, 0, 5, "0E 01 50 72 6F 74 6F 74"),
        _frame(1, 0, 5, "0E 02 79 70 65 20 50 44"),
        _frame(1, 0, 5, "0E 03 43 50 20 44 65 76"),
        _frame(1, 0, 5, "0E 04 69 63 65 20 44 65"),
        _frame(1, 0, 5, "0E 05 73 63 72 69 70 74"),
        _frame(1, 0, 5, "0E 06 6F 72 00"),
        _frame(1, 1, 5, "8E 01"),
        _frame(1, 1, 5, "03 09 00"),  # 3.3.2 Number of Data Channels
        _frame(1, 0, 5, "83 01 09 00 01"),
        _frame(1, 1, 5, "04 05 01 06"),  # 3.3.3 Channel #1's Node Id = 6
        _frame(1, 0, 5, "84 01 05 01 06"),
    ]
    at = 0
    for want in expected:  # each one, in this order (other frames may come between)
        assert want in seen[at:], f"{want[0]:03X} {want[1].hex(' ')} missing after frame {at}"
        at = seen.index(want, at) + 1
