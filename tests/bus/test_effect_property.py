"""What the preview shows is what the prosthesis does (issue 26, "Done when"): a property test
over random changes on the simulated rigs.

Each example opens a built-in prosthesis (``sim:thesis-test1`` … ``5``, ``sim:transradial``),
draws a change the model accepts — links removed and added, parameters written by name (a
channel's control mode, a descriptor, data transfer, the beacon interval), stored or not, a
policy or none — previews it, carries it out through the change road (recorded in the test's
own fitting history) and reads the prosthesis back from the arbitrator. The effect the preview
showed must be exactly the difference read back: links made and removed, every named value
old → new (and the device itself must hold the written bytes), the stored configuration and the
policy after. A change the arbitrator refuses or rolls back must leave everything as it was.
Then the arbitrator is reset on its memory (every part resets and binds again, start-up runs):
the links must be exactly what the preview's next power-on said. (The real process killed and
started again on its memory is tests/cli/test_truth_power_cycle.py.)

Changes draw only what the model accepts, sometimes after a part has left the bus (its links
stay as dead links). Data transfer is not written on a channel that is an end of a link before
or after the change: turning it off under a link is accepted and verified though the link then
carries no data (the arbitrator verifies only the links a change makes or removes), and a later
restore of that state is rolled back at verify; turning it on under a link the change removes
is rolled back, and around dead links the rollback leaves the output's flag off.
"""

from __future__ import annotations

from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pdcp_studio.bus.session.change_road import preview_change
from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.bus.transaction import (
    Change,
    LinkAction,
    NotRestorable,
    ParameterWrite,
    Policy,
    Status,
    link_from_json,
    restore_change,
)
from pdcp_studio.engine.effect import system_after
from pdcp_studio.engine.procedures import resolve_configuration
from pdcp_studio.errors import ModelError
from pdcp_studio.model import param_names as N
from pdcp_studio.model.channel_type import CONTROL_MODE_MASK
from pdcp_studio.model.configuration import ConfigCollection
from pdcp_studio.model.param_names import snapshot
from pdcp_studio.model.system import Channel, Device, Link, System
from pdcp_studio.storage.history import History

RIGS = ("thesis-test1", "thesis-test2", "thesis-test3", "thesis-test4", "thesis-test5",
        "transradial")
#: Seconds the arbitrator gets to settle after opening and after each change.
SETTLE_S = 20.0

Where = tuple[str, int | None, str]  # (part, channel or None, name)


def named_values(system: System) -> dict[Where, str]:
    """Every named value of every present part and channel, by (part, channel, name)."""
    out: dict[Where, str] = {}
    for key, device in system.devices.items():
        if not device.present:
            continue
        objs: list[tuple[int | None, Device | Channel]] = [(None, device)]
        objs += [(i, ch) for i, ch in device.channels.items()]
        for index, obj in objs:
            for name, value in N.values(obj).items():
                if name != "node-id":  # the arbitrator's to give, not the change's
                    out[(str(key), index, name)] = value
    return out


def stored_links(system: System, collection: ConfigCollection) -> list[Link] | None:
    """The links of the stored configuration start-up would pick (None: nothing stored)."""
    if not collection.configurations:
        return None
    cfg, _ = resolve_configuration(system, collection)
    cfg = cfg or collection.configurations[0]
    return sorted({Link(sl.output.ref, sl.input.ref) for sl in cfg.links})


def accepted(system: System, links: list[Link]) -> bool:
    trial = system.copy()
    try:
        for link in set(trial.links) - set(links):
            trial.remove_link(link)
        for link in sorted(set(links) - set(trial.links)):
            trial.add_link(link)
    except ModelError:
        return False
    return True


#: Choices are drawn as plain numbers and mapped onto the system as read: the draws stay the
#: same when the system differs between runs (timing), as hypothesis requires.
CHOICE = st.integers(0, 255)


def pick(data: st.DataObject, seq: list[Any], label: str) -> Any:
    """An element of ``seq`` (None when it is empty), by a draw that does not depend on it."""
    i = data.draw(CHOICE, label=label)
    return seq[i % len(seq)] if seq else None


def picks(data: st.DataObject, seq: list[Any], max_size: int, label: str) -> list[Any]:
    """Up to ``max_size`` distinct elements of ``seq``, in order of the draws."""
    got = data.draw(st.lists(CHOICE, max_size=max_size), label=label)
    return list(dict.fromkeys(seq[i % len(seq)] for i in got)) if seq else []


def draw_links(data: st.DataObject, system: System) -> list[LinkAction]:
    """Random removals, then additions the model accepts on top of them."""
    links = sorted(system.links)
    removed = picks(data, links, 3, "removed")
    after = [lk for lk in links if lk not in removed]
    present = sorted(((ref, ch) for ref, ch in system.channels() if system.is_present(ref)),
                     key=lambda rc: rc[0])
    outputs = [ref for ref, ch in present if ch.is_output]
    inputs = [ref for ref, ch in present if ch.is_input]
    candidates = [Link(o, i) for o in outputs for i in inputs
                  if o.device != i.device and Link(o, i) not in system.links]
    added: list[Link] = []
    for link in picks(data, candidates, 2, "added"):
        if accepted(system, after + added + [link]):
            added.append(link)
    return ([LinkAction("remove", lk, "test") for lk in removed]
            + [LinkAction("add", lk, "test") for lk in added])


KINDS = ("type", "descriptor", "data-transfer", "beacon-interval", "part-descriptor")


def draw_parameters(data: st.DataObject, system: System, links: list[LinkAction]
                    ) -> list[ParameterWrite]:
    """Random writes by name: a channel's control mode, a descriptor, data transfer, the
    beacon interval (at most one per parameter and target). Data transfer is not written on
    an end of a link before or after ``links``: that would contradict the link (see the
    module's docstring)."""
    ends = {r for lk in [*system.links, *(a.link for a in links)]
            for r in (lk.output, lk.input)}
    devices = sorted((d for d in system.devices.values() if d.present), key=lambda d: d.key)
    writes: dict[tuple[Any, int, int], ParameterWrite] = {}
    for _ in range(data.draw(st.integers(0, 2), label="n_params")):
        device = pick(data, devices, "part")
        kind = data.draw(st.sampled_from(KINDS), label="kind")
        if kind == "beacon-interval":
            value = str(data.draw(st.sampled_from((50, 100, 150, 250)), label="ms"))
        elif kind == "part-descriptor":
            value = data.draw(st.sampled_from(("Spare hand", "Hand (left)", "Ω test")),
                              label="text")
        elif kind == "type":
            step = data.draw(st.integers(1, 3), label="control mode step")
        elif kind == "descriptor":
            value = data.draw(st.sampled_from(("Grip A", "Grip (test)", "Ärmel")), label="text")
        else:
            value = data.draw(st.sampled_from(("on", "off")), label="flag")
        channels = sorted(device.channels.values(), key=lambda c: c.index)
        if kind == "data-transfer":
            channels = [c for c in channels if device.ref(c.index) not in ends]
        obj: Device | Channel | None
        if kind in ("beacon-interval", "part-descriptor"):
            obj, name = device, "beacon-interval" if kind == "beacon-interval" else "descriptor"
        else:
            obj, name = pick(data, channels, "channel"), kind
        if obj is None:
            continue
        if kind == "type":
            now = int(N.values(obj)["type"], 0)
            mode = (((now & CONTROL_MODE_MASK) >> 10) + step) % 4
            value = f"0x{(now & ~CONTROL_MODE_MASK) | (mode << 10):04X}"
        channel = 0 if isinstance(obj, Device) else obj.index
        for param, raw in N.writes_for(obj, {name: value}):
            writes[(device.key, param, channel)] = ParameterWrite(device.key, param, channel, raw)
    return list(writes.values())


def settled(session: Any) -> System:
    assert session.wait_settled(SETTLE_S), "the arbitrator did not settle"
    return session.system()


@pytest.mark.slow
@settings(max_examples=15, deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(rig=st.sampled_from(RIGS), data=st.data())
def test_the_effect_shown_is_the_difference_read_back(rig: str, data: st.DataObject) -> None:
    with open_session(f"sim:{rig}", frame_events=False) as session:
        system = settled(session)
        if data.draw(st.booleans(), label="stored first"):  # a configuration already stored
            assert session.transact(Change("config save", store=True,
                                           configuration=session.configuration_of_links())
                                    ).written
            system = settled(session)
        parts = sorted(k for k, d in system.devices.items() if d.present)
        gone = pick(data, [None] * len(parts) + parts, "unplugged")
        if gone is not None:  # a part leaves: its links stay dead, start-up will miss it
            session.unplug(gone)
            assert session.arbitrator.wait_for(
                lambda: gone not in session.arbitrator.devices_present(), SETTLE_S)
            system = settled(session)
        actions = draw_links(data, system)
        change = Change("property test", links=actions,
                        parameters=draw_parameters(data, system, actions))
        change.store = data.draw(st.booleans(), label="store")
        policy = data.draw(st.sampled_from((None, True, False)), label="policy")
        if policy is not None:
            change.policy = Policy(autoconfigure=policy)

        before_present = [k for k, d in system.devices.items() if d.present]
        config_before = session.read_configuration()
        policy_before = session.read_policy()
        values_before = named_values(system)
        preview = preview_change(session, change)
        effect = preview.effect
        assert effect is not None
        result = session.transact(change)
        now = settled(session)
        values_after = named_values(now)
        config_after = session.read_configuration()
        policy_after = session.read_policy()

        if result.status is Status.NOTHING:
            assert effect.empty, result.summary()
        if not result.written:  # refused, rolled back or nothing: everything as it was
            assert result.status in (Status.NOTHING, Status.FAILED, Status.ROLLED_BACK), \
                result.summary()
            assert sorted(now.links) == sorted(system.links), result.summary()
            assert values_after == values_before, result.summary()
            assert config_after == config_before, result.summary()
            assert policy_after == policy_before, result.summary()
            return

        assert result.status is Status.APPLIED and result.verified
        assert result.history_id is not None, result.notes
        # The parts held still and the stored configuration's CRC, as shown.
        assert sorted(result.held) == effect.held
        assert result.config_crc_after == effect.crc_after
        assert result.config_crc_before == effect.crc_before
        # Links: made and removed, exactly as shown.
        before, after = set(system.links), set(now.links)
        assert sorted(after - before) == effect.links_added
        assert sorted(before - after) == effect.links_removed
        assert sorted(after) == effect.links_after
        # Parameters: every change shown happened, old → new as shown …
        changed = {w: (values_before.get(w), values_after.get(w))
                   for w in set(values_before) | set(values_after)
                   if values_before.get(w) != values_after.get(w)}
        shown = {(str(p.part), p.channel, p.name): (p.before, p.after)
                 for p in effect.parameters}
        for where, (old, new) in shown.items():
            assert changed.get(where) == (old, new), (where, old, new, changed.get(where))
        # … and what else changed is the links' own bookkeeping (data transfer on the ends of
        # the links made or removed), exactly as the effect's model of the written system says.
        ends = {(str(r.device), r.index) for lk in effect.links_added + effect.links_removed
                for r in (lk.output, lk.input)}
        for (part, channel, name) in set(changed) - set(shown):
            assert name == "data-transfer" and (part, channel) in ends, \
                ((part, channel, name), changed[(part, channel, name)])
        predicted = named_values(system_after(system, effect.links_after, change.parameters))
        assert values_after == predicted
        # The devices themselves hold the bytes written.
        for w in change.parameters:
            if (w.device, w.param, w.channel) in {(p.part, p.param, p.channel or 0)
                                                  for p in effect.parameters}:
                assert session.get_parameter(w.device, w.param, w.channel, timeout=5.0) \
                    == w.value, w
        # The stored configuration read back is the one the effect said.
        assert stored_links(now, config_after) == effect.stored_after
        if not change.store and change.configuration is None:
            assert config_after == config_before
        if effect.stored_changed:
            assert effect.stored_after is not None
            assert set(effect.stored_after) == after
        # The policy.
        assert policy_after.autoconfigure == effect.policy_after
        # The next power-on: the arbitrator reset on its memory (every device resets and binds
        # again, start-up runs) makes exactly the links the preview predicted.
        po = effect.next_power_on
        predicted_links = (after | set(po.links_added)) - set(po.links_removed)
        session.reset_arbitrator(keep_memory=True)
        assert session.arbitrator.wait_for(lambda: len(session.arbitrator.devices_present())
                                           == len(before_present), SETTLE_S)
        powered = settled(session)
        assert sorted(powered.links) == sorted(predicted_links), (
            f"predicted {sorted(map(str, predicted_links))}, "
            f"after power-on {sorted(map(str, powered.links))}")
        # The fitting history keeps what was read back, and restoring the entry afterwards
        # puts all of it back: links, parameter values, stored configuration, policy.
        archive = History.open()
        try:
            entry = archive.get(result.history_id)
        finally:
            archive.close()
        assert entry is not None
        assert {link_from_json(d) for d in entry["links_after"]} == after
        assert entry["effect"]["parameters"] == effect.to_json()["parameters"]
        assert entry["next_power_on"]["links_added"] == effect.power_on_json()["links_added"]
        assert entry["next_power_on"]["links_removed"] == \
            effect.power_on_json()["links_removed"]
        recorded = entry["parameters_after"]
        assert recorded == snapshot(d for d in now.devices.values() if d.present)
        try:
            restore = restore_change(entry, powered)
        except NotRestorable as err:  # a dead link to the part that left
            assert gone is not None and err.missing == [gone], err
            return
        back = session.transact(restore)
        assert back.ok, back.summary()
        restored = settled(session)
        assert set(restored.links) == after
        assert snapshot(d for d in restored.devices.values() if d.present) == recorded
        assert session.read_configuration() == config_after
        assert session.read_policy() == policy_after
