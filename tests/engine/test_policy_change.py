"""What a policy switch changes (issue 26 item 5): one pure decision for the CLI and the app."""

from __future__ import annotations

from pdcp_studio.engine import check_system, plan_duty_cycle
from pdcp_studio.engine.policy_change import policy_switch
from pdcp_studio.storage import system_file


def _unlinked(full):
    bare = full.copy()
    for link in list(bare.links):
        bare.remove_link(link)
    return bare


def test_turning_autoconfigure_on_plans_the_links_the_duty_cycle_would_make(systems_dir):
    full = system_file.load_path(systems_dir / "appendix-d.json")
    bare = _unlinked(full)
    switch = policy_switch(bare, False, True)
    assert switch.switches and switch.action == "policy autoconfigure on"
    assert switch.kept == [] and switch.words == []
    added = {a.link for a in switch.plan.added}
    assert added and not switch.plan.removed
    # Exactly what the duty cycle makes with the policy on and nothing gone since.
    present = {ref for ref, _ in bare.channels() if bare.is_present(ref)}
    duty = plan_duty_cycle(bare, present, autoconfigure=True)
    assert added == {a.link for a in duty.added}
    after = bare.copy()
    for link in switch.plan.final_links:
        after.add_link(link)
    assert not any(f.code == "terminal-unconnected" for f in check_system(after))


def test_turning_it_off_removes_nothing_and_says_which_links_stay(systems_dir):
    full = system_file.load_path(systems_dir / "appendix-d.json")
    switch = policy_switch(full, True, False, name=lambda ref: f"<{ref}>")
    assert switch.action == "policy autoconfigure off"
    assert switch.plan.actions == []
    assert switch.kept == sorted(full.links)
    assert switch.words[0].startswith(f"Every link stays as it is ({len(full.links)} links)")
    for link in full.links:  # every link, named by the caller's part names
        assert f"  <{link.output}> → <{link.input}>" in switch.words


def test_turning_it_off_with_no_links_says_none_are_removed(systems_dir):
    bare = _unlinked(system_file.load_path(systems_dir / "appendix-d.json"))
    switch = policy_switch(bare, True, False)
    assert switch.kept == [] and switch.words[0].startswith("No link is removed")


def test_no_switch_changes_no_link(systems_dir):
    bare = _unlinked(system_file.load_path(systems_dir / "appendix-d.json"))
    for same in (True, False):
        switch = policy_switch(bare, same, same)
        assert not switch.switches and switch.plan.actions == [] and switch.words == []
