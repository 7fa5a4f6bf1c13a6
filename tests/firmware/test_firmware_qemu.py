"""The reference arbitrator firmware (firmware/) on QEMU's lm3s6965evb, end to end: the tests
that need a firmware of their own (a memory written first, a script of unplugs and plugs,
another arbitrator first on the bus). Those that share one start are in
``test_firmware_shared.py``.

Simulated devices run in this process on a udp_multicast bus; ``firmware/run-qemu.sh``
starts the firmware with its CAN side bridged to that bus (``pdcp-studio can-bridge``) and its
host link on a pseudo-terminal; PDCP Studio's own commands talk to it with ``serial:`` URLs.
Skipped with the reason when the toolchain is missing (CI installs gcc-arm-none-eabi,
libnewlib-arm-none-eabi and qemu-system-arm).
"""

from __future__ import annotations

import json
import time

import pytest

from pdcp_studio.cli.main import main
from tests.firmware.rig import (
    Devices,
    Firmware,
    Run,
    missing_tools,
    open_session,
    settle,
    wait_for,
)

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(missing_tools() is not None, reason=missing_tools() or "")]


@pytest.fixture
def bus_url(multicast_url):
    return multicast_url("239.74.163.24", 44000)


def _engine_links(name: str, script: str | None, capsys) -> list[dict]:
    """The final links of ``sim replay`` (PDCP Studio's own arbitrator and engine)."""
    capsys.readouterr()
    args = ["sim", "replay", name, "--json"] + (["--script", script] if script else [])
    assert main(args) == 0
    return json.loads(capsys.readouterr().out)["links"]


def _json_links(links) -> list[dict]:
    def ref(r):
        return {"vid": r.vid, "pid": r.pid, "serial": r.serial, "index": r.index}
    return [{"output": ref(lk.output), "input": ref(lk.input)} for lk in sorted(links)]


def test_a_memory_written_by_pdcp_studio_starts_the_firmware(bus_url, tmp_path, capsys):
    from pdcp_studio.bus.arbitrator.memory import MemoryStore
    from pdcp_studio.engine import configuration_from_system
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.storage import config_codec
    from tests.engine.engine_builders import L

    # thesis test 3's rig with a stored configuration that is not what autoconfigure gives
    devices = Devices("thesis-test3", bus_url)
    system = devices.system.copy()
    system.clear_links()
    system.add_link(L(4, 1, 5, 2))
    store = MemoryStore(tmp_path / "memory.bin")
    store.write(ConfigCollection([configuration_from_system(system)]))
    store.write_policy({"autoconfigure": False})
    firmware = Firmware(bus_url, tmp_path / "memory.bin")
    try:
        with open_session(firmware.serial_url) as session:
            settle(session, devices=devices)
            assert session.read_policy().autoconfigure is False
            assert session.read_configuration_bytes() == store.read_bytes()
            links = sorted(session.system().links)
    finally:
        firmware.stop()
        devices.close()
    assert links == [L(4, 1, 5, 2)]
    assert config_codec.loads(store.read_bytes()).configurations


@pytest.mark.parametrize("name", ["thesis-test1", "thesis-test2", "thesis-test3",
                                  "thesis-test4", "thesis-test5"])
def test_thesis_tests_end_with_the_engines_links(name, bus_url, tmp_path, capsys):
    from pdcp_studio.bus.sim.rigs import prosthesis

    script = prosthesis(name).script()
    run = Run(name, bus_url, tmp_path / "memory.bin")
    try:
        for step in script.steps:
            run.step(step)
        links = run.links()
    finally:
        run.close()
    assert _json_links(links) == _engine_links(name, None, capsys)
    if script.expected_links is not None:
        assert links == sorted(script.expected_links)


@pytest.mark.parametrize("name", ["thesis-test1", "thesis-test4"])
def test_hot_swap_is_repaired_by_the_duty_cycle(name, bus_url, tmp_path, capsys):
    from pdcp_studio.bus.sim.rigs import prosthesis

    script = prosthesis(name).script("hot-swap")
    run = Run(name, bus_url, tmp_path / "memory.bin")
    try:
        for step in script.steps:
            run.step(step)
        links = run.links()
    finally:
        run.close()
    assert links == sorted(script.expected_links)
    assert _json_links(links) == _engine_links(name, "hot-swap", capsys)


def test_the_transradial_rig_survives_a_hot_swap(bus_url, tmp_path, capsys):
    from pdcp_studio.bus.sim.rigs import prosthesis

    script = prosthesis("transradial").script("unplug-replug")
    run = Run("transradial", bus_url, tmp_path / "memory.bin")
    try:
        run.step(script.steps[0])  # settle
        before = run.links()
        assert before, "start-up linked nothing"
        for step in script.steps[1:]:
            run.step(step)
        after = run.links()
        system = run.session.system()
    finally:
        run.close()
    assert after == before
    assert all(d.present for d in system.devices.values() if d.key in {
        lk.output.device for lk in after} | {lk.input.device for lk in after})
    assert _json_links(after) == _engine_links("transradial", "unplug-replug", capsys)


def test_the_firmware_writes_nothing_on_a_bus_another_arbitrator_holds(bus_url, tmp_path):
    import subprocess
    import sys

    devices = Devices("thesis-test2", bus_url)
    other = subprocess.Popen([sys.executable, "-m", "pdcp_studio", "arbitrator", "--bus", bus_url,
                              "--seconds", "60"], stdout=subprocess.PIPE, text=True)
    firmware = None
    try:
        assert other.stdout is not None
        assert "arbitrator on" in other.stdout.readline()
        time.sleep(3)  # it has bound and linked the devices
        firmware = Firmware(bus_url, tmp_path / "memory.bin")
        with open_session(firmware.serial_url) as session:
            wait_for(lambda: session.status()["other_arbitrator"], 10,
                     "the firmware to hear the other arbitrator")
            time.sleep(2)
            status = session.status()
            assert status["devices"] == 0 and status["links"] == 0
            assert not session.system().devices
        assert other.poll() is None  # the other one was not disturbed
    finally:
        if firmware is not None:
            firmware.stop()
        other.terminate()
        other.wait(15)
        if other.stdout is not None:
            other.stdout.close()
        devices.close()


def test_a_part_that_leaves_the_firmware_says_why_on_the_host_link(bus_url, tmp_path):
    """DEVICE_LEFT carries the firmware's silence, beacon interval and reason (host-link
    §5.7), so Bus events says why over the serial line too (issue 28 item 6)."""
    from pdcp_studio.bus import events as ev
    from pdcp_studio.bus.sim.rigs import prosthesis

    script = prosthesis("transradial").script("unplug-replug")
    key = next(s.key for s in script.steps if s.op == "unplug")
    run = Run("transradial", bus_url, tmp_path / "memory.bin")
    left: list[ev.DeviceLeft] = []
    try:
        run.step(script.steps[0])  # settle
        run.session.subscribe(lambda e: left.append(e) if isinstance(e, ev.DeviceLeft) else None)
        run.devices.host.unplug(key)
        wait_for(lambda: any(e.key == key for e in left), 30, f"DEVICE_LEFT for {key}")
    finally:
        run.close()
    got = next(e for e in left if e.key == key)
    assert got.why == f"no beacon for {round(got.silent_s * 1000)} ms", got.why
    assert got.interval_s > 0
    assert got.silent_s >= 1.5  # PRESENCE_MIN_MS on QEMU; 3.5 intervals when longer


def test_a_reply_waiting_behind_a_given_up_frame_still_reaches_the_pc(bus_url, tmp_path):
    """A PC that stops acknowledging (stalled on a loaded machine) makes the firmware give up
    the frame in flight and forget the PC, who must greet again — but a reply already waiting
    behind that frame still answers the request it belongs to. (The firmware dropped it: a
    CI run under two CPU burners waited out its whole 20 s reply timeout for a STATUS.)"""
    import serial

    from pdcp_studio.bus.sim.rigs import prosthesis
    from pdcp_studio.protocol.hostlink import Frame, FrameReader, Kind

    key = next(s.key for s in prosthesis("transradial").script("unplug-replug").steps
               if s.op == "unplug")
    devices = Devices("transradial", bus_url)
    firmware = Firmware(bus_url, tmp_path / "memory.bin")
    port = None
    try:
        session = open_session(firmware.serial_url)
        try:
            settle(session, devices=devices)
            # opened before the session closes: QEMU keeps serving the pseudo-terminal
            port = serial.Serial(firmware.serial_url.split(":", 1)[1], 115200, timeout=0.05)
        finally:
            session.close()
        reader = FrameReader()

        def frames(seconds: float, ack: bool, first: bool = False) -> list[Frame]:
            got: list[Frame] = []
            end = time.monotonic() + seconds
            while time.monotonic() < end:
                for item in reader.feed(port.read(512)):
                    if isinstance(item, Frame) and item.kind is Kind.DATA:
                        got.append(item)
                        if ack:
                            port.write(Frame(Kind.ACK, item.seq).encode())
                if got and first:
                    return got
            return got

        greeted = False
        deadline = time.monotonic() + 20
        while not greeted and time.monotonic() < deadline:  # RESET, HELLO v2 (seq 0)
            port.write(Frame(Kind.RESET, 0).encode()
                       + Frame(Kind.DATA, 0, b"\x01\x02\xff\xff").encode())
            greeted = any(f.payload[:2] == b"\x81\x00" for f in frames(0.5, ack=True))
        assert greeted, "the firmware did not answer HELLO"
        frames(0.5, ack=True)  # anything else it had to say, acknowledged
        devices.host.unplug(key)
        # DEVICE_LEFT (or what comes first) is in flight, and never acknowledged
        in_flight = frames(30.0, ack=False, first=True)
        assert in_flight, "no event after the unplug"
        port.write(Frame(Kind.DATA, 1, b"\x02").encode())  # STATUS, answered behind it
        # 8 sends 250 ms apart, then the frame is given up; the reply must follow
        seen = frames(8.0, ack=False)
        later = [f for f in seen if f.seq != in_flight[0].seq]
        assert any(f.payload[:2] == b"\x82\x00" for f in later), \
            [f.payload[:2].hex() for f in seen]
    finally:
        if port is not None:
            port.close()
        firmware.stop()
        devices.close()
    assert "a frame was given up" in firmware.log.read_text()


def test_a_request_numbered_like_the_last_but_another_asks_the_pc_to_renumber(bus_url,
                                                                              tmp_path):
    """host-link §3.2 Decision: a repeat is the same frame. The firmware acknowledges a true
    repeat again and runs nothing twice; a request numbered like the last one but with
    another CRC (the PC numbers anew from a RESET the firmware read late) is not taken for a
    repeat and dropped: the firmware asks the PC to renumber (a RESET frame)."""
    import serial

    from pdcp_studio.protocol.hostlink import Frame, FrameReader, Kind

    firmware = Firmware(bus_url, tmp_path / "memory.bin")
    port = None
    try:
        port = serial.Serial(firmware.serial_url.split(":", 1)[1], 115200, timeout=0.05)
        reader = FrameReader()

        def frames(seconds: float) -> list[Frame]:
            got: list[Frame] = []
            end = time.monotonic() + seconds
            while time.monotonic() < end:
                for item in reader.feed(port.read(512)):
                    if isinstance(item, Frame):
                        got.append(item)
                        if item.kind is Kind.DATA:
                            port.write(Frame(Kind.ACK, item.seq).encode())
            return got

        hello = Frame(Kind.DATA, 0, b"\x01\x02\xff\xff").encode()
        greeted = False
        deadline = time.monotonic() + 20
        while not greeted and time.monotonic() < deadline:
            port.write(Frame(Kind.RESET, 0).encode() + hello)
            greeted = any(f.kind is Kind.DATA and f.payload[:2] == b"\x81\x00"
                          for f in frames(0.5))
        assert greeted, "the firmware did not answer HELLO"
        frames(0.5)  # anything else it had to say, acknowledged
        port.write(hello)  # a true repeat: acknowledged again, not answered again
        seen = frames(1.0)
        assert [(f.kind, f.seq) for f in seen] == [(Kind.ACK, 0)], seen
        port.write(Frame(Kind.DATA, 0, b"\x02").encode())  # STATUS numbered like HELLO
        seen = frames(1.5)
        assert (Kind.RESET, 0) in [(f.kind, f.seq) for f in seen], seen
        assert not any(f.kind is Kind.ACK for f in seen), seen
        assert not any(f.kind is Kind.DATA and f.payload[:1] == b"\x82" for f in seen), seen
    finally:
        if port is not None:
            port.close()
        firmware.stop()


def test_a_replaced_part_is_forgotten_noted_and_said_on_the_host_link(bus_url, tmp_path):
    """As PDCP Studio's arbitrator does (issue 26 item 6; host-link §5.7 DEVICE_REPLACED): the
    hand is swapped for the spare, the Replace a part wizard's change is written and verified,
    and the firmware forgets the old hand — no longer missing, its dead links gone —, notes
    "replaced … by …" in the result (the fitting history's) and says DEVICE_REPLACED."""
    from pdcp_studio.app.wizards import logic
    from pdcp_studio.bus import events as ev
    from pdcp_studio.bus.sim.rigs import HAND, SPARE_HAND
    from pdcp_studio.engine import configuration_from_system
    from pdcp_studio.model.configuration import ConfigCollection
    from pdcp_studio.storage import config_codec
    from tests.firmware.rig import present

    run = Run("transradial", bus_url, tmp_path / "memory.bin")
    seen: list[object] = []
    try:
        session = run.session
        settle(session, devices=run.devices)
        session.write_configuration_bytes(config_codec.dumps(
            ConfigCollection([configuration_from_system(session.system())])))
        session.subscribe(seen.append)
        run.devices.host.unplug(HAND)
        wait_for(lambda: not present(session, HAND), 30, "the hand to leave")
        run.devices.host.plug(SPARE_HAND)
        wait_for(lambda: sum(lk.input.device == SPARE_HAND for lk in session.system().links)
                 == 3, 60, "the duty cycle to link the spare hand")
        system = session.system()
        assert not system.devices[HAND].present  # missing: the stored configuration names it
        change = logic.replacement_change(system, logic.replacement_plan(
            system, session.read_configuration(), [SPARE_HAND]))
        result = session.transact(change)
        assert result.written and result.verified, result.summary()
        assert "replaced 2641/769/301 by 2641/769/302" in result.notes
        wait_for(lambda: any(isinstance(e, ev.DeviceReplaced) for e in seen), 30,
                 "DEVICE_REPLACED")
        after = session.system()
    finally:
        run.close()
    replaced = [e for e in seen if isinstance(e, ev.DeviceReplaced)]
    assert [(e.key, e.new) for e in replaced] == [(HAND, SPARE_HAND)]
    assert HAND not in after.devices and after.devices[SPARE_HAND].present
    assert not any(HAND in (lk.output.device, lk.input.device) for lk in after.links)
