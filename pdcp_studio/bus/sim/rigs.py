"""The built-in simulated prostheses: a registry of systems and their scripted events.

Each prosthesis is a ``pdcp-system/1`` system (the shipped ``resources/systems/*.json``, or
the generated 32-device ``large`` rig) plus scripts: plug, unplug, replace a device, reset
the arbitrator with or without its memory, wait. A script is data; :func:`run_script`
carries it out on anything with the simulator controls of a ``SimSession``
(``bus/session/sim.py``), so each thesis test (reference §4) replays end to end on the bus.

Devices marked ``present: false`` in a system file are simulated but start unplugged (the
replacement a script plugs in later). Every script names the links it must end in; for the
thesis tests those are the links the thesis reports.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import Literal, Protocol

from pdcp_studio.errors import PdcpError
from pdcp_studio.model.refs import ChannelRef, DeviceKey, Direction
from pdcp_studio.model.system import Channel, Device, Link, System

ProgressFn = Callable[[int, int, str], None]
StepOp = Literal["plug", "unplug", "replace", "reset", "save", "settle", "await_left",
                 "await_joined", "sleep"]

#: The thesis rigs' devices (reference §4): VID 2, PID 2, serials 4, 5 and 6.
D1, D2, D3 = DeviceKey(2, 2, 4), DeviceKey(2, 2, 5), DeviceKey(2, 2, 6)
#: Seconds a ``settle`` step waits for the arbitrator at most.
SETTLE_TIMEOUT_S = 20.0
#: Seconds an ``await_left`` / ``await_joined`` step waits at most.
PRESENCE_TIMEOUT_S = 15.0
LARGE = "large"


class UnknownProsthesisError(PdcpError):
    """No built-in prosthesis has this name and no system file is at this path."""


class ScriptError(PdcpError):
    """A script step could not be carried out (a device never left, a wait timed out…)."""


def _ref(key: DeviceKey, index: int) -> ChannelRef:
    return ChannelRef(key.vid, key.pid, key.serial, index)


def _link(out: DeviceKey, out_index: int, inp: DeviceKey, in_index: int) -> Link:
    return Link(_ref(out, out_index), _ref(inp, in_index))


@dataclass(frozen=True)
class Step:
    """One scripted event. ``key``: the device acted on; ``new``: a replacement's key."""

    op: StepOp
    key: DeviceKey | None = None
    new: DeviceKey | None = None
    keep_memory: bool = True
    seconds: float = 0.0

    def describe(self) -> str:
        if self.op == "plug":
            return f"plug {self.key}"
        if self.op == "unplug":
            return f"unplug {self.key}"
        if self.op == "replace":
            return f"replace {self.key} by {self.new}"
        if self.op == "reset":
            return "reset the arbitrator " + ("(memory kept)" if self.keep_memory
                                              else "(memory erased: a replaced arbitrator)")
        if self.op == "save":
            return "store the current links in the arbitrator's memory"
        if self.op == "settle":
            return "wait until the arbitrator has settled"
        if self.op == "await_left":
            return f"wait until the arbitrator notices {self.key} is gone"
        if self.op == "await_joined":
            return f"wait until {self.key} has joined"
        return f"wait {self.seconds:g} s"


def plug(key: DeviceKey) -> Step:
    return Step("plug", key)


def unplug(key: DeviceKey) -> Step:
    return Step("unplug", key)


def replace(old: DeviceKey, new: DeviceKey) -> Step:
    return Step("replace", old, new)


def reset(keep_memory: bool) -> Step:
    return Step("reset", keep_memory=keep_memory)


SAVE = Step("save")
SETTLE = Step("settle")


@dataclass(frozen=True)
class Script:
    """Scripted events and the links they must end in (None: what autoconfigure gives)."""

    name: str
    description: str
    steps: tuple[Step, ...]
    expected_links: tuple[Link, ...] | None = None


@dataclass
class ScriptResult:
    """What a run did: each step with the links after it, and the final links."""

    script: Script
    trace: list[tuple[str, list[Link]]] = field(default_factory=list)
    final_links: list[Link] = field(default_factory=list)
    expected_links: list[Link] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.final_links == self.expected_links

    def mismatch(self) -> str:
        """A sentence saying how the final links differ from the expected ones ('' if not)."""
        got, want = set(self.final_links), set(self.expected_links)
        parts = []
        if want - got:
            parts.append("missing " + ", ".join(str(lk) for lk in sorted(want - got)))
        if got - want:
            parts.append("unexpected " + ", ".join(str(lk) for lk in sorted(got - want)))
        return "; ".join(parts)


@dataclass(frozen=True)
class Prosthesis:
    """A registry entry: where its system comes from and its scripts (the first is the
    one ``sim replay`` runs)."""

    name: str
    description: str
    load: Callable[[], System]
    scripts: tuple[Script, ...] = ()
    #: Channel data per output per second when the session does not say (None: the
    #: simulated device's default); the full rig's 161 outputs send slower so one process
    #: can simulate them all.
    data_rate_hz: float | None = None

    def script(self, name: str | None = None) -> Script:
        if not self.scripts:
            raise ScriptError(f"prosthesis {self.name} has no scripts")
        if name is None:
            return self.scripts[0]
        for s in self.scripts:
            if s.name == name:
                return s
        names = ", ".join(s.name for s in self.scripts)
        raise ScriptError(f"prosthesis {self.name} has no script {name!r} (scripts: {names})")


# -- the thesis tests (reference §4) --------------------------------------------------------
TEST2_LINKS = (_link(D1, 1, D2, 2), _link(D2, 3, D3, 1), _link(D2, 5, D3, 2))
START = Script("start-up", "power on: the arbitrator binds, sets up and runs start-up",
               (SETTLE,))

_THESIS_SCRIPTS: dict[str, tuple[Script, ...]] = {
    "thesis-test1": (
        Script("thesis",
               "Test 1: D1.O1 → D2.I1 autoconfigured and stored; D2 is replaced by D3 and the "
               "prosthesis restarts: find_replacements links D1.O1 → D3.I1",
               (SETTLE, SAVE, unplug(D2), plug(D3), reset(True), SETTLE),
               (_link(D1, 1, D3, 1),)),
        Script("hot-swap",
               "Test 1 without a restart: D2 is pulled and D3 plugged in while running; the "
               "duty cycle repairs the link",
               (SETTLE, unplug(D2), Step("await_left", D2), plug(D3), Step("await_joined", D3),
                SETTLE),
               (_link(D1, 1, D3, 1),)),
    ),
    "thesis-test2": (
        Script("thesis", "Test 2: no stored configuration: autoconfigure (appendix D's links)",
               (SETTLE,), TEST2_LINKS),
    ),
    "thesis-test3": (
        Script("thesis",
               "Test 3: configure, save, reset the arbitrator keeping its memory: start-up "
               "recalls the stored configuration",
               (SETTLE, SAVE, reset(True), SETTLE), TEST2_LINKS),
    ),
    "thesis-test4": (
        Script("thesis",
               "Test 4: D1.O1 → D3.I2 autoconfigured and stored; D1 is replaced by D2 and the "
               "prosthesis restarts: find_replacements links D2.O2 → D3.I2",
               (SETTLE, SAVE, unplug(D1), plug(D2), reset(True), SETTLE),
               (_link(D2, 2, D3, 2),)),
        Script("hot-swap",
               "Test 4 without a restart: D1 is pulled and D2 plugged in while running",
               (SETTLE, unplug(D1), Step("await_left", D1), plug(D2), Step("await_joined", D2),
                SETTLE),
               (_link(D2, 2, D3, 2),)),
    ),
    "thesis-test5": (
        Script("thesis",
               "Test 5: configure, then reset the arbitrator with its memory erased (a replaced "
               "arbitrator): start-up rebuilds the links from the devices' source fields",
               (SETTLE, reset(False), SETTLE), TEST2_LINKS),
    ),
}

_DESCRIPTIONS = {
    "thesis-test1": "Thesis test 1: replacement of a terminal device by a different one",
    "thesis-test2": "Thesis test 2: autoconfigure without a stored configuration",
    "thesis-test3": "Thesis test 3: recall of the stored configuration after a reset",
    "thesis-test4": "Thesis test 4: replacement of a joystick by a different one",
    "thesis-test5": "Thesis test 5: a replaced arbitrator rebuilds from the devices",
    "transradial": "Transradial prosthesis: two EMG sites, a control unit and a hand, with a "
                   "spare hand to swap in",
    "appendix-d": "Appendix D: the thesis rig after test 5, links stored on the devices",
    LARGE: "A generated 32-device rig (8 arms of 4 devices) for scans and benchmarks",
    "full": "Every node ID 1–254 in use: 23 arms of 4 devices and a battery pack "
            "(93 devices, 161 outputs)",
}


def _generic_scripts(first: DeviceKey | None, last: DeviceKey | None) -> tuple[Script, ...]:
    scripts = [START]
    if last is not None:
        scripts.append(Script(
            "unplug-replug", f"pull {last} and plug it back in: it keeps its sources and the "
                             "arbitrator links it again",
            (SETTLE, unplug(last), Step("await_left", last), plug(last),
             Step("await_joined", last), SETTLE)))
    scripts.append(Script("reset-keep-memory", "reset the arbitrator keeping its memory",
                          (SETTLE, SAVE, reset(True), SETTLE)))
    scripts.append(Script("reset-erase-memory",
                          "reset the arbitrator with its memory erased: rebuild from devices",
                          (SETTLE, reset(False), SETTLE)))
    return tuple(scripts)


# -- the large rig --------------------------------------------------------------------------
LARGE_ARMS = 8
LARGE_VID = 0x0A51


def large_system(arms: int = LARGE_ARMS) -> System:
    """``arms`` × (two EMG sensors, a control unit, a hand): 32 devices for 8 arms.

    Each sensor has an EMG envelope and an accelerometer output; each control unit two
    sole-access EMG inputs and three set-point outputs that require them; each hand three
    terminal inputs. Node IDs used: 11 per arm (88 for 8), well inside the pool.
    """
    devices: list[Device] = []
    for arm in range(arms):
        sn = 1000 + arm * 10
        for k, (muscle, profile) in enumerate((("flexor", 0x4222), ("extensor", 0x4224))):
            dev = Device(LARGE_VID, 0x0101, sn + k, name=f"EMG {muscle} {arm + 1}",
                         beacon_interval=100)
            dev.add_channel(Channel(1, Direction.OUTPUT, 0x9000, profile))
            dev.add_channel(Channel(2, Direction.OUTPUT, 0x9000, 0x4620))
            devices.append(dev)
        cu = Device(LARGE_VID, 0x0201, sn + 2, name=f"Control unit {arm + 1}")
        cu.add_channel(Channel(1, Direction.INPUT, 0x9200, 0x4222))
        cu.add_channel(Channel(2, Direction.INPUT, 0x9200, 0x4224))
        for index, profile in ((3, 0x2220), (4, 0x2240), (5, 0x2600)):
            cu.add_channel(Channel(index, Direction.OUTPUT, 0x9000, profile,
                                   required_inputs=(1, 2)))
        devices.append(cu)
        hand = Device(LARGE_VID, 0x0301, sn + 3, name=f"Hand {arm + 1}")
        for index, profile in ((1, 0x2220), (2, 0x2240), (3, 0x2600)):
            hand.add_channel(Channel(index, Direction.INPUT, 0x9300, profile,
                                     terminal_profile=profile))
        devices.append(hand)
    return System(devices)


# -- the registry ---------------------------------------------------------------------------
#: Rigs whose simulated outputs send slower than a device's default (see Prosthesis).
_DATA_RATES_HZ = {"full": 2.0}

_ORDER = ("thesis-test1", "thesis-test2", "thesis-test3", "thesis-test4", "thesis-test5",
          "transradial", LARGE, "full")


def _file_loader(path: Path) -> Callable[[], System]:
    def load() -> System:
        from pdcp_studio.storage import system_file

        return system_file.load_path(path)

    return load


#: The transradial rig's hand and its spare (issue 11): the spare is simulated but not plugged
#: in, so a new user can swap it in from the Simulator panel (the hand unplugged, the spare
#: plugged in). It is not in the system file: opened as a file, the rig is its four parts.
HAND, SPARE_HAND = DeviceKey(2641, 769, 301), DeviceKey(2641, 769, 302)


def with_spare_hand(load: Callable[[], System]) -> Callable[[], System]:
    """``load`` with a second, unplugged hand of the same product beside the hand."""
    def loader() -> System:
        import copy
        import dataclasses

        system = load()
        hand = system.device(HAND)
        if hand is not None and system.device(SPARE_HAND) is None:
            system.add_device(dataclasses.replace(
                hand, serial=SPARE_HAND.serial, name="Spare hand", present=False,
                node_id=None, channels=copy.deepcopy(hand.channels)))
        return system

    return loader


@cache
def _files() -> dict[str, Path]:
    """The shipped system files by name, in the registry's order."""
    from pdcp_studio.paths import systems_dir

    files = {p.stem: p for p in systems_dir().glob("*.json")}
    return {name: files[name] for name in
            sorted(files, key=lambda n: (_ORDER.index(n) if n in _ORDER else 99, n))}


@cache
def _entry(name: str) -> Prosthesis:
    """One registry entry, made when first asked for: opening ``sim:transradial`` reads
    its own file, not every shipped one (``full``'s 254 devices among them)."""
    if name == LARGE:
        large = large_system()
        keys = list(large.devices)
        return Prosthesis(LARGE, _DESCRIPTIONS[LARGE], large_system,
                          _generic_scripts(keys[0], keys[-1]))
    path = _files()[name]
    scripts = _THESIS_SCRIPTS.get(name)
    if scripts is None:
        scripts = _scripts_from_file(path)
    load = _file_loader(path)
    if name == "transradial":
        load = with_spare_hand(load)
    return Prosthesis(name, _DESCRIPTIONS.get(name, f"System file {name}.json"), load, scripts,
                      _DATA_RATES_HZ.get(name))


def _names() -> list[str]:
    return [*_files(), LARGE]


def _registry() -> dict[str, Prosthesis]:
    return {name: _entry(name) for name in _names()}


def _scripts_from_file(path: Path) -> tuple[Script, ...]:
    from pdcp_studio.storage import system_file

    return scripts_for(system_file.load_path(path))


def scripts_for(system: System) -> tuple[Script, ...]:
    """The generic scripts for any system: start-up, unplug and replug its last present
    device, reset keeping and erasing the arbitrator's memory."""
    keys = [k for k, d in system.devices.items() if d.present]
    return _generic_scripts(keys[0] if keys else None, keys[-1] if keys else None)


def list_prostheses() -> list[str]:
    """The built-in prostheses' names: thesis-test1 … thesis-test5, transradial, large, …"""
    names = _names()
    return sorted(names, key=lambda n: (_ORDER.index(n) if n in _ORDER else len(_ORDER), n))


def prosthesis(name: str) -> Prosthesis:
    """The registry entry ``name``; UnknownProsthesisError names the choices."""
    if name in _names():
        return _entry(name)
    raise UnknownProsthesisError(
        f"no built-in prosthesis {name!r} (one of {', '.join(list_prostheses())})")


def resolve_prosthesis(name_or_path: str | Path) -> Prosthesis:
    """A built-in prosthesis by name, or one made from a ``pdcp-system/1`` file (with the
    generic scripts)."""
    text = str(name_or_path)
    if text in _names():
        return _entry(text)
    path = Path(text)
    if path.is_file():
        from pdcp_studio.storage import system_file

        system = system_file.load_path(path)
        return Prosthesis(path.stem, f"System file {path}", system.copy, scripts_for(system))
    raise UnknownProsthesisError(
        f"no built-in prosthesis {text!r} (one of {', '.join(list_prostheses())}) "
        "and no system file at that path")


def load_prosthesis(name_or_path: str | Path) -> System:
    """A built-in prosthesis's system, or a ``pdcp-system/1`` file's (a fresh copy)."""
    return resolve_prosthesis(name_or_path).load()


def expected_links(script: Script, system: System) -> list[Link]:
    """The links a script must end in: its own, or what start-up without a stored
    configuration gives the devices plugged in at first (their sources, then autoconfigure)."""
    if script.expected_links is not None:
        return sorted(script.expected_links)
    from pdcp_studio.engine import plan_startup

    start = system.copy()
    for key in [k for k, d in start.devices.items() if not d.present]:
        start.remove_device(key)
    start.clear_links()
    return plan_startup(start, None).final_links


# -- running a script -----------------------------------------------------------------------
class SimControls(Protocol):
    """What a script needs: the simulator controls of a SimSession."""

    def plug(self, key: DeviceKey) -> None: ...
    def unplug(self, key: DeviceKey) -> None: ...
    def replace(self, old_key: DeviceKey, new: DeviceKey | Device) -> object: ...
    def reset_arbitrator(self, keep_memory: bool) -> None: ...
    def save_configuration(self) -> object: ...
    def wait_settled(self, timeout: float) -> bool: ...
    def system(self) -> System: ...


def _await_presence(controls: SimControls, key: DeviceKey, present: bool,
                    timeout: float, cancel: threading.Event | None) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if cancel is not None and cancel.is_set():
            return
        device = controls.system().device(key)
        if (device is not None and device.present) == present:
            return
        time.sleep(0.02)
    raise ScriptError(f"device {key} did not {'join' if present else 'leave'} "
                      f"within {timeout:g} s")


def run_script(controls: SimControls, script: Script, system: System,
               progress: ProgressFn | None = None, cancel: threading.Event | None = None,
               settle_timeout: float = SETTLE_TIMEOUT_S) -> ScriptResult:
    """Carry out ``script``'s steps in order; the result compares the final links with the
    expected ones (it does not raise on a mismatch; ScriptError if a step fails)."""
    result = ScriptResult(script, expected_links=expected_links(script, system))
    steps: Sequence[Step] = script.steps
    for n, step in enumerate(steps):
        if cancel is not None and cancel.is_set():
            raise ScriptError(f"script {script.name} cancelled after {n} of {len(steps)} steps")
        if progress is not None:
            progress(n, len(steps), step.describe())
        _do(controls, step, settle_timeout, cancel)
        result.trace.append((step.describe(), controls.system().links))
    if progress is not None:
        progress(len(steps), len(steps), f"script {script.name} done")
    result.final_links = controls.system().links
    return result


def _do(controls: SimControls, step: Step, settle_timeout: float,
        cancel: threading.Event | None) -> None:
    if step.op == "plug":
        controls.plug(_key(step))
    elif step.op == "unplug":
        controls.unplug(_key(step))
    elif step.op == "replace":
        if step.new is None:
            raise ScriptError("a replace step needs the new device's key")
        controls.replace(_key(step), step.new)
    elif step.op == "reset":
        controls.reset_arbitrator(step.keep_memory)
    elif step.op == "save":
        controls.save_configuration()
    elif step.op == "settle":
        if not controls.wait_settled(settle_timeout):
            raise ScriptError(f"the arbitrator did not settle within {settle_timeout:g} s")
    elif step.op in ("await_left", "await_joined"):
        _await_presence(controls, _key(step), step.op == "await_joined", PRESENCE_TIMEOUT_S,
                        cancel)
    elif step.op == "sleep":
        time.sleep(step.seconds)
    else:  # pragma: no cover - Step.op is a Literal
        raise ScriptError(f"unknown step {step.op!r}")


def _key(step: Step) -> DeviceKey:
    if step.key is None:
        raise ScriptError(f"step {step.op} needs a device key")
    return step.key
