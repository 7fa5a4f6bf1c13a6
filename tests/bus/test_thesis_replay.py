"""Each thesis test (reference §4) replayed end to end on the virtual bus.

The scripts run on a ``sim:`` session: the arbitrator and the devices exchange real PDCP
frames over python-can's virtual interface, and the final links must be exactly the ones
the thesis reports.
"""

from __future__ import annotations

import pytest

from pdcp_studio.bus.session.opening import open_session
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link


def L(o: tuple[int, int], i: tuple[int, int]) -> Link:
    return Link(ChannelRef(2, 2, o[0], o[1]), ChannelRef(2, 2, i[0], i[1]))


TEST2 = [L((4, 1), (5, 2)), L((5, 3), (6, 1)), L((5, 5), (6, 2))]
CASES = [
    ("thesis-test1", "thesis", [L((4, 1), (6, 1))], "stored"),
    ("thesis-test1", "hot-swap", [L((4, 1), (6, 1))], None),
    ("thesis-test2", "thesis", TEST2, "retrieved"),
    ("thesis-test3", "thesis", TEST2, "stored"),
    ("thesis-test4", "thesis", [L((5, 2), (6, 2))], "stored"),
    ("thesis-test4", "hot-swap", [L((5, 2), (6, 2))], None),
    ("thesis-test5", "thesis", TEST2, "retrieved"),
]


@pytest.mark.parametrize("name, script, links, startup_source", CASES,
                         ids=[f"{c[0]}-{c[1]}" for c in CASES])
def test_thesis_script_ends_in_the_thesis_links(name, script, links, startup_source):
    with open_session(f"sim:{name}", frame_events=False) as session:
        result = session.run_script(script)
        assert result.final_links == sorted(links), result.mismatch()
        assert result.ok
        # The bus agrees with the arbitrator's model: a scan finds the same links.
        assert session.scan().links == sorted(links)
        plans = session.arbitrator.applied_plans
        if startup_source is not None:
            last_startup = [p for p in plans if p.mode == "startup"][-1]
            assert last_startup.configuration_source == startup_source


def test_test5_rebuilds_from_the_devices_not_from_memory():
    with open_session("sim:thesis-test5", frame_events=False) as session:
        result = session.run_script()
        assert result.ok
        assert not session.read_configuration().configurations  # the memory was erased
        startup = [p for p in session.arbitrator.applied_plans if p.mode == "startup"][-1]
        assert {a.rule.value for a in startup.added} == {"retrieved"}


def test_scripts_run_again_from_the_initial_state():
    with open_session("sim:thesis-test4", frame_events=False) as session:
        assert session.run_script("thesis").ok
        # The second run starts over: D1 plugged and D2 unplugged again, memory erased.
        trace = session.run_script("hot-swap")
        assert trace.ok
        assert trace.trace[0][1] == [L((4, 1), (6, 2))]
        plugged = {str(k): p for k, _, p in session.sim_devices()}
        assert plugged == {"2/2/4": False, "2/2/5": True, "2/2/6": True}
