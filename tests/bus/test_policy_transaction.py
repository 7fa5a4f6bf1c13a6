"""A policy switch and its links in one transaction, and the arbitrator's own duty cycle
(issue 26 item 5): the duty cycle waits for the transaction, and a link it made meanwhile
does not fail the read-back."""

from __future__ import annotations

import threading
import time

import pytest

from pdcp_studio.bus.arbitrator.memory import MemoryStore
from pdcp_studio.bus.session.api import open_session
from pdcp_studio.bus.transaction import Change, Policy, Status
from pdcp_studio.engine.policy_change import policy_switch


@pytest.fixture
def off(tmp_path):
    """``sim:thesis-test2`` with autoconfigure off: its terminal channels unconnected."""
    memory = tmp_path / "memory.bin"
    MemoryStore(memory).write_policy({"autoconfigure": False})
    session = open_session("sim:thesis-test2", memory=str(memory))
    try:
        assert session.system().links == []
        yield session
    finally:
        session.close()


def _switch_on(session):
    system = session.system()
    switch = policy_switch(system, session.read_policy().autoconfigure, True)
    change = Change.from_plan(switch.plan, switch.action)
    change.policy = Policy(autoconfigure=True)
    return switch, change


def test_the_arbitrator_carries_out_the_policy_and_its_links_together(off):
    switch, change = _switch_on(off)
    assert len(change.links) == 3 and change.policy is not None
    result = off.carry_out(change)
    assert result.status is Status.APPLIED and result.verified, result.summary()
    assert result.policy_before == Policy(False) and result.policy_after == Policy(True)
    assert set(result.links_after) == set(switch.plan.final_links)
    assert result.held  # the control unit feeds the terminal board: held while written


def test_links_the_duty_cycle_made_meanwhile_do_not_fail_the_verify(off):
    """Between the preview and the write the arbitrator made one of the links itself."""
    switch, change = _switch_on(off)
    off.arbitrator.add_link(change.links[0].link)
    result = off.carry_out(change)
    assert result.status is Status.APPLIED and result.verified, result.summary()
    assert set(off.system().links) == set(switch.plan.final_links)


def test_a_duty_cycle_due_during_the_transaction_waits_and_finds_nothing_to_do(off):
    switch, change = _switch_on(off)
    arb = off.arbitrator
    inside = threading.Event()
    real = arb._do_link

    def slow(op, link):
        inside.set()
        time.sleep(0.05)
        real(op, link)

    arb._do_link = slow
    plans = []
    try:
        tx = threading.Thread(target=lambda: plans.append(off.carry_out(change)))
        tx.start()
        assert inside.wait(5)
        duty = threading.Thread(target=lambda: plans.append(arb.run_duty_cycle()))
        duty.start()
        tx.join(10)
        duty.join(10)
    finally:
        del arb._do_link
    result, plan = plans  # the transaction first, then the duty cycle
    assert result.status is Status.APPLIED and result.verified, result.summary()
    assert plan.actions == []  # policy on and every terminal linked: nothing left to do
    assert set(off.system().links) == set(switch.plan.final_links)
