"""Properties of the profile layer on generated prosthesis-shaped systems.

A generated system has sensors (EMG, encoders, accelerometers: outputs under the Sensor
root 0x4), control units (sensor inputs they require or desire, set-point outputs under the
Terminal Device root 0x2), and terminal devices (terminal set-point inputs, often sole
access, sometimes with a sensor output of their own), plus the odd channel with a profile
nobody else shares. Whatever hypothesis draws, the plan must keep the reference's rules.
"""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pdcp_studio.engine import (
    Plan,
    Rule,
    configuration_from_system,
    plan_autoconfigure,
    plan_duty_cycle,
    plan_startup,
)
from pdcp_studio.engine.layer import ProfileLayer
from pdcp_studio.model import (
    Channel,
    ChannelRef,
    ConfigCollection,
    Device,
    Direction,
    Link,
    System,
)
from pdcp_studio.model.profile import common_prefix_depth
from tests.engine.engine_builders import shuffled

SENSOR = [0x4220, 0x4240, 0x4222, 0x4400, 0x4620, 0x4640, 0x4800]
SET_POINT = [0x2220, 0x2240, 0x2200, 0x2400, 0x2600, 0x2420]
ODD = [0x1100, 0x3000, 0x6200]
TYPES = [0x5000, 0x7000, 0x9000, 0x8400, 0x4000, 0xD000]
SOLE, TERMINAL = 0x0200, 0x0100

PROPS = settings(max_examples=60, deadline=None,
                 suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


@st.composite
def device(draw, vid: int, pid: int, serial: int) -> Device:
    kind = draw(st.sampled_from(["sensor", "control", "terminal", "terminal+sensor", "odd"]))
    d = Device(vid, pid, serial, present=draw(st.integers(0, 7)) > 0)
    index = 0

    def add(direction: Direction, profiles: list[int], flags: int = 0, **kw) -> Channel:
        nonlocal index
        index += 1
        t = draw(st.sampled_from(TYPES))
        if direction is Direction.INPUT:
            t |= flags
        ch = Channel(index, direction, t, draw(st.sampled_from(profiles)), **kw)
        return d.add_channel(ch)

    def some_flags(terminal: bool) -> int:
        return (SOLE if draw(st.booleans()) else 0) | (TERMINAL if terminal else 0)

    if kind in ("sensor", "terminal+sensor"):
        for _ in range(draw(st.integers(1, 3))):
            add(Direction.OUTPUT, SENSOR)
    if kind == "control":
        ins = [add(Direction.INPUT, SENSOR, some_flags(False)).index
               for _ in range(draw(st.integers(1, 3)))]
        for i in ins:  # inputs that must be connected together
            sib = draw(st.lists(st.sampled_from(ins), max_size=1))
            d.channels[i].required_inputs = tuple(sorted(set(sib) - {i}))
        for _ in range(draw(st.integers(1, 3))):
            req = draw(st.lists(st.sampled_from(ins), max_size=2, unique=True))
            des = draw(st.lists(st.sampled_from(ins), max_size=2, unique=True))
            add(Direction.OUTPUT, SET_POINT, required_inputs=tuple(sorted(req)),
                desired_inputs=tuple(sorted(des)))
    if kind.startswith("terminal"):
        for _ in range(draw(st.integers(1, 3))):
            ch = add(Direction.INPUT, SET_POINT, some_flags(True))
            ch.terminal_profile = draw(st.sampled_from([ch.profile, *SET_POINT]))
    if kind == "odd":
        add(Direction.OUTPUT, ODD)
        ch = add(Direction.INPUT, ODD + SENSOR, some_flags(draw(st.booleans())))
        ch.terminal_profile = ch.profile if ch.terminal else 0
    return d


@st.composite
def prostheses(draw, max_devices: int = 10) -> System:
    keys = draw(st.lists(st.tuples(st.integers(1, 3), st.integers(1, 2), st.integers(1, 40)),
                         min_size=2, max_size=max_devices, unique=True))
    return System([draw(device(*k)) for k in keys])


# -- the rules every plan keeps -----------------------------------------------------------
def live_links(s: System, plan: Plan):
    return [lk for lk in plan.final_links if s.is_present(lk.output) and s.is_present(lk.input)]


def assert_sole_access_kept(s: System, plan: Plan) -> None:
    fed: dict[ChannelRef, list[ChannelRef]] = {}
    for lk in live_links(s, plan):
        if s.channel(lk.input).sole_access:
            fed.setdefault(lk.output, []).append(lk.input)
    assert all(len(v) == 1 for v in fed.values()), fed


def assert_basic_rules(s: System, plan: Plan) -> None:
    links = live_links(s, plan)
    assert_sole_access_kept(s, plan)
    assert all(lk.output.device != lk.input.device for lk in links), "self link"
    inputs = [lk.input for lk in links]
    assert len(inputs) == len(set(inputs)), "two sources on one input"
    for lk in links:
        o, i = s.channel(lk.output), s.channel(lk.input)
        assert common_prefix_depth(o.profile, i.profile) >= 1, f"{lk} shares no root"


def wanted(s: System, lk) -> set[ChannelRef]:
    out = set()
    for end in (lk.output, lk.input):
        ch = s.channel(end)
        out |= {ChannelRef(*end.device, i) for i in (*ch.required_inputs, *ch.desired_inputs)}
    return out


@PROPS
@given(prostheses(), st.integers(0, 2**16))
def test_autoconfigure_keeps_every_rule(s, seed):
    plan = plan_autoconfigure(s)
    assert_basic_rules(s, plan)
    links = plan.final_links
    linked = {lk.input for lk in links}
    # Every required input of a linked channel is linked.
    for lk in links:
        for end in (lk.output, lk.input):
            for i in s.channel(end).required_inputs:
                assert ChannelRef(*end.device, i) in linked, f"{lk}: required {i} unmet"
    # No link that is neither to a terminal channel nor needed by one.
    needed = {lk for lk in links if s.channel(lk.input).terminal}
    grew = True
    while grew:
        want = set().union(*(wanted(s, lk) for lk in needed)) if needed else set()
        more = {lk for lk in links if lk.input in want} - needed
        needed |= more
        grew = bool(more)
    assert set(links) == needed
    # Determinism: the same plan whatever order devices and channels are listed in.
    assert plan_autoconfigure(shuffled(s, seed)).to_json() == plan.to_json()
    # The plan applies, and running it again never takes a link away.
    plan.apply(s)
    assert s.links == links
    assert set(plan_autoconfigure(s).final_links) >= set(links)


@PROPS
@given(prostheses(), st.data())
def test_startup_after_hardware_changes_keeps_every_rule(s, data):
    plan_autoconfigure(s).apply(s)
    stored = ConfigCollection([configuration_from_system(s)])
    before = {r for r, _ in s.channels() if s.is_present(r)}
    # Unplug some devices, plug back others, and reset (the arbitrator forgets the links
    # it had; the devices keep their source fields).
    for d in s.devices.values():
        d.present = data.draw(st.booleans().map(lambda b, p=d.present: p if b else not p))
    after_reset = s.copy()
    after_reset.clear_links()

    for plan in (plan_startup(after_reset, stored), plan_startup(after_reset, None)):
        assert_basic_rules(after_reset, plan)
        seed = data.draw(st.integers(0, 2**16))
        again = plan_startup(shuffled(after_reset, seed), plan.configuration)
        assert again.final_links == plan.final_links
    duty = plan_duty_cycle(s, before)
    assert_basic_rules(s, duty)
    assert plan_duty_cycle(shuffled(s, 7), before).to_json() == duty.to_json()


@PROPS
@given(prostheses(max_devices=6))
def test_a_rollback_leaves_the_layer_exactly_as_before(s):
    layer = ProfileLayer(s)
    state = (set(layer.links), dict(layer.sole_fed))
    mark = layer.mark()
    for ref in layer.unconnected_terminals():
        found = layer.find_output_for(ref)
        if found:
            layer.intelligently_connect(Link(found[0], ref), Rule.TERMINAL, "test")
    layer.rollback(mark)
    assert (set(layer.links), {k: v for k, v in layer.sole_fed.items() if v}) == (
        state[0], {k: v for k, v in state[1].items() if v})
    assert layer.plan.actions == []
