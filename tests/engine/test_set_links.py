"""``engine.set_links``: the one offline apply path (issue 8) — the same system as
``Plan.apply`` and the CLI's ``apply --system``, source fields and Data Transfer Enabled
included."""

from __future__ import annotations

import pytest

from pdcp_studio.engine import plan_autoconfigure, plan_clear, set_links
from pdcp_studio.errors import ModelError
from pdcp_studio.model.refs import ChannelRef
from pdcp_studio.model.system import Link
from pdcp_studio.storage import system_file


@pytest.fixture
def bare(systems_dir):
    system = system_file.load_path(systems_dir / "transradial.json")
    set_links(system, [])
    return system


def test_set_links_gives_the_system_plan_apply_gives(bare):
    plan = plan_autoconfigure(bare)
    by_plan, by_links = bare.copy(), bare.copy()
    plan.apply(by_plan)
    added, removed = set_links(by_links, plan.final_links)
    assert removed == [] and sorted(added) == plan.final_links
    assert system_file.dumps(by_links) == system_file.dumps(by_plan)
    for link in by_links.links:
        inp = by_links.channel(link.input)
        assert inp.source.ref == link.output and inp.data_enabled
        assert by_links.channel(link.output).data_enabled


def test_set_links_back_to_none_clears_the_source_fields(bare):
    linked = bare.copy()
    set_links(linked, plan_autoconfigure(bare).final_links)
    cleared = linked.copy()
    plan_clear(linked).apply(linked)
    set_links(cleared, [])
    assert system_file.dumps(cleared) == system_file.dumps(linked)
    assert not any(ch.data_enabled for _, ch in cleared.channels())


def test_a_refused_link_changes_nothing(bare):
    before = system_file.dumps(bare)
    ghost = Link(ChannelRef(1, 1, 1, 1), ChannelRef(2, 2, 2, 2))
    with pytest.raises(ModelError):
        set_links(bare, [ghost])
    assert system_file.dumps(bare) == before
