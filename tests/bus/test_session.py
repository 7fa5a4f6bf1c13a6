"""The session interface on sim: and can: buses (python-can's virtual interface)."""

from __future__ import annotations

import sys
import threading

import pytest

from pdcp_studio.bus import events as ev
from pdcp_studio.bus.session.base import ConfigVerifyError
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.session.sim import SimSession
from pdcp_studio.bus.session.urls import BusUrlError, open_can_bus, unique_virtual_channel
from pdcp_studio.bus.sim.device import SimulatedDevice
from pdcp_studio.bus.sim.device_host import DeviceHost
from pdcp_studio.bus.sim.rigs import load_prosthesis
from pdcp_studio.errors import TransportError
from pdcp_studio.model import parameters as P
from pdcp_studio.model.configuration import (
    ConfigCollection,
    StoredChannel,
    StoredConfiguration,
    StoredLink,
)
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link
from pdcp_studio.storage import config_codec

D4, D5, D6 = DeviceKey(2, 2, 4), DeviceKey(2, 2, 5), DeviceKey(2, 2, 6)
TEST2 = [Link(ChannelRef(2, 2, 4, 1), ChannelRef(2, 2, 5, 2)),
         Link(ChannelRef(2, 2, 5, 3), ChannelRef(2, 2, 6, 1)),
         Link(ChannelRef(2, 2, 5, 5), ChannelRef(2, 2, 6, 2))]


@pytest.fixture
def test2():
    with open_session("sim:thesis-test2") as session:
        yield session


def test_sim_session_returns_bound_and_linked(test2):
    assert isinstance(test2, SimSession)
    system = test2.system()
    assert system.links == TEST2
    assert all(d.present and d.node_id for d in system.devices.values())
    outputs = [c.node_id for d in system.devices.values() for c in d.outputs()]
    ids = outputs + [d.node_id for d in system.devices.values()]
    assert len(set(ids)) == len(ids)  # one pool for devices and output channels
    assert test2.system() is not test2.system()  # snapshots, not the live model


def test_events_reach_subscribers_until_they_unsubscribe(test2):
    seen: list = []
    unsubscribe = test2.subscribe(seen.append)
    test2.subscribe(lambda e: 1 / 0)  # a broken subscriber does not stop the others
    test2.remove_link(TEST2[0])
    test2.add_link(TEST2[0])
    kinds = [type(e) for e in seen]
    assert ev.LinkRemoved in kinds and ev.LinkMade in kinds
    assert any(isinstance(e, ev.FrameSeen) and e.text for e in seen)
    unsubscribe()
    n = len(seen)
    test2.remove_link(TEST2[0])
    assert len(seen) == n


def test_parameters_inline_and_bulk(test2):
    assert test2.get_parameter(D5, P.DEVICE_CHANNEL_COUNT) == b"\x05"
    assert test2.get_parameter(D5, P.DEVICE_DESCRIPTOR) == b"Control unit board\0"
    test2.set_parameter(D5, P.CH_DESCRIPTOR, 3, b"Bar graph LEDs\0")  # 15 bytes: bulk
    assert test2.get_parameter(D5, P.CH_DESCRIPTOR, 3) == b"Bar graph LEDs\0"
    test2.set_parameter(D5, P.DEVICE_ACK_TIMEOUT, 0, (60).to_bytes(2, "little"))
    assert test2.get_parameter(D5, P.DEVICE_ACK_TIMEOUT, timeout=1.0) == b"\x3c\x00"


def test_parameters_from_many_threads_at_once(test2):
    errors: list = []
    got: list = []

    def read(key: DeviceKey) -> None:
        try:
            for _ in range(10):
                got.append(test2.get_parameter(key, P.DEVICE_SERIAL))
        except Exception as err:  # pragma: no cover - reported below
            errors.append(err)

    threads = [threading.Thread(target=read, args=(k,)) for k in (D4, D5, D6, D5, D4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(10)
    assert not errors
    assert sorted(set(got)) == [b"\x04\x00", b"\x05\x00", b"\x06\x00"] and len(got) == 50


def test_preview_then_apply_a_plan(test2):
    clear = test2.preview("clear")
    assert clear.final_links == [] and len(clear.removed) == 3
    assert test2.system().links == TEST2  # a preview changes nothing
    progress: list = []
    test2.apply_plan(clear, lambda d, t, s: progress.append((d, t)))
    assert test2.system().links == []
    assert progress[-1] == (3, 3)
    again = test2.preview("autoconfigure")
    test2.apply_plan(again)
    assert test2.system().links == TEST2


def test_preview_uses_the_arbitrators_memory(test2):
    stored = test2.save_configuration()
    assert len(stored.configurations[0].links) == 3
    test2.apply_plan(test2.preview("clear"))
    plan = test2.preview("implement")  # no config given: the stored one
    assert plan.final_links == TEST2 and plan.configuration_source == "given"


def _collection(*links: Link) -> ConfigCollection:
    def end(ref: ChannelRef) -> StoredChannel:
        return StoredChannel(ref.index, ref.vid, ref.pid, ref.serial, 0x5000, 0x2110)

    return ConfigCollection([StoredConfiguration(1, [
        StoredLink(end(lk.input), end(lk.output), n) for n, lk in enumerate(links, 1)])])


def test_write_configuration_reads_back_and_verifies(test2):
    written = _collection(TEST2[0])
    back = test2.write_configuration(written)
    assert config_codec.dumps(back) == config_codec.dumps(written)
    assert config_codec.dumps(test2.read_configuration()) == config_codec.dumps(written)


def test_a_mismatch_after_a_write_raises_and_says_what_differs(test2, monkeypatch):
    other = _collection(TEST2[1])
    monkeypatch.setattr(test2.arbitrator, "read_memory", lambda: other)
    with pytest.raises(ConfigVerifyError) as info:
        test2.write_configuration(_collection(TEST2[0]))
    text = str(info.value)
    assert "rolled back at step verify" in text
    assert "link 2/2/4#1 → 2/2/5#2 is only in written" in text
    assert "link 2/2/5#3 → 2/2/6#1 is only in read back" in text
    assert "what was there is restored" in text


def test_close_is_idempotent_and_closed_sessions_refuse_calls():
    session = open_session("sim:thesis-test1")
    session.close()
    session.close()
    assert session.closed
    with pytest.raises(TransportError, match="closed"):
        session.system()
    with pytest.raises(TransportError, match="closed"):
        session.plug(D6)


def test_simulator_controls_plug_unplug_replace():
    with open_session("sim:thesis-test1") as session:
        devices = {str(k): (label, plugged) for k, label, plugged in session.sim_devices()}
        assert devices == {"2/2/4": ("Joystick", True), "2/2/5": ("LED terminal A", True),
                           "2/2/6": ("LED terminal B", False)}
        session.plug(D6)  # returns once D6 has joined
        assert session.system().devices[D6].present
        session.unplug(D6)
        assert session.arbitrator.wait_for(lambda: not session.system().devices[D6].present,
                                           3.0)
        # A brand-new device model replaces the joystick.
        new = Device(2, 2, 9, name="Joystick C")
        new.add_channel(Channel(1, Direction.OUTPUT, 0x5000, 0x2110))
        assert session.replace(D4, new) == new.key
        assert ("Joystick C", True) in [(lbl, p) for _, lbl, p in session.sim_devices()]
        assert session.arbitrator.wait_for(
            lambda: Link(ChannelRef(2, 2, 9, 1), ChannelRef(2, 2, 5, 1))
            in session.system().links, 3.0)
        with pytest.raises(Exception, match="no simulated device"):
            session.plug(DeviceKey(7, 7, 7))


def test_reset_arbitrator_keeping_or_erasing_memory(test2):
    test2.save_configuration()
    test2.reset_arbitrator(keep_memory=True)
    assert test2.wait_settled(5)
    assert test2.read_configuration().configurations
    assert test2.system().links == TEST2
    test2.reset_arbitrator(keep_memory=False)
    assert test2.wait_settled(5)
    assert not test2.read_configuration().configurations
    assert test2.system().links == TEST2  # rebuilt from the devices' source fields
    assert test2.script_names() == ["thesis"]


def test_bad_urls_and_names():
    with pytest.raises(BusUrlError):
        open_session("nonsense")
    with pytest.raises(BusUrlError, match="thesis-test1"):  # bad input, exit 2 (contracts §2)
        open_session("sim:no-such-arm")


def test_serial_without_the_host_link_client_says_so(monkeypatch):
    monkeypatch.setitem(sys.modules, "pdcp_studio.bus.hostlink.client", None)
    with pytest.raises(TransportError, match="host-link client is not available"):
        open_session("serial:/dev/ttyUSB0")


def test_serial_without_the_whole_host_link_package_says_so(monkeypatch):
    class HidePackage:  # a build without bus/hostlink/: its import finds nothing
        @staticmethod
        def find_spec(name, path=None, target=None):
            if name == "pdcp_studio.bus.hostlink":
                raise ModuleNotFoundError(f"No module named {name!r}", name=name)
            return None

    for name in ("pdcp_studio.bus.hostlink", "pdcp_studio.bus.hostlink.client"):
        monkeypatch.delitem(sys.modules, name, raising=False)
    monkeypatch.setattr(sys, "meta_path", [HidePackage, *sys.meta_path])
    with pytest.raises(TransportError, match="host-link client is not available"):
        open_session("serial:/dev/ttyUSB0")


def test_serial_delegates_to_the_host_link_client(monkeypatch):
    import types

    calls: list = []
    fake = types.ModuleType("pdcp_studio.bus.hostlink.client")
    fake.open_hostlink_session = lambda spec, **kw: calls.append((spec, kw)) or "session"
    monkeypatch.setitem(sys.modules, "pdcp_studio.bus.hostlink.client", fake)
    assert open_session("serial:socket://127.0.0.1:7000@57600", reply_timeout=2) == "session"
    spec, kw = calls[0]
    assert (spec.port, spec.baud, kw) == ("socket://127.0.0.1:7000", 57600,
                                          {"reply_timeout": 2})


def test_can_session_is_the_arbitrator_of_devices_elsewhere(tmp_path):
    channel = unique_virtual_channel("pdcp-test-can")
    system = load_prosthesis("thesis-test2")
    host = DeviceHost(open_can_bus("virtual", channel),
                      [SimulatedDevice(d) for d in system.devices.values()], name="elsewhere")
    try:
        memory = tmp_path / "arbitrator.mem"
        with open_session(f"can:virtual:{channel}", memory=memory, settle_timeout=5,
                          startup_quiet_s=0.2) as session:
            assert type(session).__name__ == "Session"
            assert session.system().links == TEST2
            scanned = session.scan()
            assert scanned.links == TEST2
            session.save_configuration()
        assert memory.exists()
    finally:
        host.close()
